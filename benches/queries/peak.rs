//! This machine's peak floating-point throughput, measured with the bench's own
//! build (same target features: `x86-64` baseline, SSE2, unless `RUSTFLAGS`
//! says otherwise), so the lower bound is what this binary could reach.
//!
//! - **ops**: independent multiply-add chains `x ← x·m + c` (2 ops per step),
//!   many at once so the loop is throughput-bound, not latency-bound; the
//!   compiler packs them into SIMD registers, so this is the packed peak. The
//!   best of several chain counts is kept (too few chains wait on latency, too
//!   many spill registers).
//! - **sqrt**, **div**: a square root or a division of each element of an
//!   array (independent; packed by the compiler).
//! - **read**: the bytes per nanosecond at which the timed loops' own shape —
//!   one record after another from an array in L1/L2, each through
//!   `black_box` — can read records of [`RECORD`] `f64`s (an AABB pair, 96
//!   bytes) and fold them into one value with bitwise ors (packed, so the
//!   loads, not the folding, are the limit). A query cannot take less than
//!   its input's bytes at this rate.
//!
//! Each figure is the best of [`REPEATS`] timed runs of [`WORK`] operations,
//! and the run measures twice (at its start and at its end) and keeps the
//! better of each rate ([`Peak::best`]).

use std::hint::black_box;
use std::time::Instant;

/// Timed runs per figure; the best is kept (the least disturbed by the other
/// work on the machine).
const REPEATS: usize = 9;
/// Operations per timed run: about 5–20 ms each at this machine's rates.
const WORK: usize = 1 << 24;
/// Array length of the sqrt and div loops: 2 × 8 KiB in `f64`, in L1.
const LANES: usize = 1024;
/// `f64`s per record of the read-rate loop: 12, an AABB pair (96 bytes), the
/// query whose floor this term sets.
const RECORD: usize = 12;
/// Records of the read-rate loop: 1024 × 96 bytes = 96 KiB, like the
/// benchmarks' case arrays (1024 cases).
const RECORDS: usize = 1024;

/// Measured peak rates, operations per nanosecond.
#[derive(Clone, Copy, Debug)]
pub struct Peak {
    /// `f64` add/sub/mul/compare ops per ns.
    pub ops_f64: f64,
    /// `f32` ops per ns.
    pub ops_f32: f64,
    /// `f64` square roots per ns.
    pub sqrt_f64: f64,
    /// `f64` divisions per ns.
    pub div_f64: f64,
    /// Input bytes read per ns (records of [`RECORD`] `f64`s, one at a time).
    pub read_bytes: f64,
}

impl Peak {
    /// Nanoseconds that `cost` takes at least at these rates: the FP pipes,
    /// the divider and the loads work in parallel, so the largest of their
    /// three times.
    pub fn bound_ns(&self, cost: super::cost::Cost) -> f64 {
        let pipes = cost.ops / self.ops_f64;
        let divider = cost.sqrt / self.sqrt_f64 + cost.div / self.div_f64;
        let loads = cost.bytes / self.read_bytes;
        pipes.max(divider).max(loads)
    }
}

fn best_rate(ops: usize, mut run: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..REPEATS {
        let t = Instant::now();
        run();
        best = best.min(t.elapsed().as_secs_f64());
    }
    ops as f64 / (best * 1e9)
}

macro_rules! mul_add_rate {
    ($t:ty, $chains:expr) => {{
        const N: usize = $chains;
        let steps = WORK / (2 * N);
        best_rate(2 * N * steps, || {
            let m: $t = black_box(0.999_999);
            let c: $t = black_box(1e-7);
            let mut acc: [$t; N] = black_box([1.0; N]);
            for _ in 0..steps {
                for a in acc.iter_mut() {
                    *a = *a * m + c;
                }
            }
            black_box(acc);
        })
    }};
}

fn ops_f64() -> f64 {
    [mul_add_rate!(f64, 8), mul_add_rate!(f64, 12), mul_add_rate!(f64, 16), mul_add_rate!(f64, 24)]
        .into_iter()
        .fold(0.0, f64::max)
}

fn ops_f32() -> f64 {
    [mul_add_rate!(f32, 16), mul_add_rate!(f32, 24), mul_add_rate!(f32, 32), mul_add_rate!(f32, 48)]
        .into_iter()
        .fold(0.0, f64::max)
}

fn elementwise(op: impl Fn(f64, f64) -> f64) -> f64 {
    let x: Vec<f64> = (0..LANES).map(|i| 1.5 + i as f64 * 1e-3).collect();
    let y: Vec<f64> = (0..LANES).map(|i| 3.25 - i as f64 * 1e-4).collect();
    let mut out = vec![0.0f64; LANES];
    let rounds = WORK / LANES / 4;
    best_rate(rounds * LANES, || {
        for _ in 0..rounds {
            let (x, y) = (black_box(&x), black_box(&y));
            for ((o, a), b) in out.iter_mut().zip(x).zip(y) {
                *o = op(*a, *b);
            }
            black_box(&mut out);
        }
    })
}

/// Bytes per ns reading [`RECORDS`] records of [`RECORD`] `f64`s, each
/// through `black_box` as the benchmarks pass their cases, folded into one
/// value by bitwise ors.
fn read_rate() -> f64 {
    let records: Vec<[f64; RECORD]> =
        (0..RECORDS).map(|i| std::array::from_fn(|k| (i * RECORD + k) as f64 * 0.25 - 3.0)).collect();
    let rounds = WORK / RECORDS / 4;
    let bytes = RECORDS * std::mem::size_of::<[f64; RECORD]>();
    best_rate(rounds * bytes, || {
        for _ in 0..rounds {
            for r in black_box(&records) {
                let r = black_box(r);
                black_box(r.iter().fold(0u64, |acc, x| acc | x.to_bits()));
            }
        }
    })
}

impl Peak {
    /// The faster of two measurements, rate by rate: on a shared machine a
    /// measurement taken in a slow spell would make the bound too high (even
    /// above the measured times), so the run measures at its start and at its
    /// end and keeps the best of each.
    pub fn best(self, other: Peak) -> Peak {
        Peak {
            ops_f64: self.ops_f64.max(other.ops_f64),
            ops_f32: self.ops_f32.max(other.ops_f32),
            sqrt_f64: self.sqrt_f64.max(other.sqrt_f64),
            div_f64: self.div_f64.max(other.div_f64),
            read_bytes: self.read_bytes.max(other.read_bytes),
        }
    }
}

/// Measures the peak rates (about half a second).
pub fn measure() -> Peak {
    Peak {
        ops_f64: ops_f64(),
        ops_f32: ops_f32(),
        sqrt_f64: elementwise(|a, _| a.sqrt()),
        div_f64: elementwise(|a, b| a / b),
        read_bytes: read_rate(),
    }
}
