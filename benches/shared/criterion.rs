//! Shared by the benchmarks (`queries`, `mesh`, `toi`): the timing loop every
//! one-at-a-time row uses, and reading criterion's estimates back for the
//! tables.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// Where criterion writes: `$CARGO_TARGET_DIR/criterion`, else the
/// workspace's `target/criterion`.
pub fn criterion_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("criterion")
}

/// Nanoseconds per query (or element) of benchmark `group/id`, from
/// criterion's estimate written during this run (`since`): its slope (time per
/// iteration, by regression over the samples) or, failing that, its mean,
/// divided by the queries per iteration. `None` when the benchmark did not run
/// this time.
pub fn ns_per(group: &str, id: &str, per_iter: usize, since: SystemTime) -> Option<f64> {
    let path = criterion_dir().join(group).join(id).join("new").join("estimates.json");
    let written = std::fs::metadata(&path).and_then(|m| m.modified()).ok()?;
    if written < since {
        return None;
    }
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).ok()?).ok()?;
    let pick = |k: &str| json.get(k)?.get("point_estimate")?.as_f64();
    let ns = pick("slope").or_else(|| pick("mean"))?;
    Some(ns / per_iter as f64)
}

/// Times `f` over every input of `inputs` as benchmark `id` of `g`: each
/// input through `black_box`, each answer left in place and handed to
/// `black_box` by reference, so that nothing is hoisted or dropped.
///
/// By reference, not by value: `black_box(f(x))` moves the answer from where
/// `f` built it into `black_box`'s own slot, a copy in 16-byte loads of
/// fields just written as 8-byte stores, which the processor cannot forward
/// from its store buffer — a stall that belongs to the harness, not to the
/// query. Measured on this machine (AMD EPYC, one run each way, sphere–sphere
/// time of impact over the toi bench's 1024 cases): by value collide 19.4 µs
/// and parry3d-f64 58.8 µs per iteration, by reference 15.6 and 52.6 µs. The
/// stall costs an engine more the larger its answer and the sooner the
/// answer is written before the copy, so it distorted the ratios too.
pub fn run<I, O>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    inputs: &[I],
    f: impl Fn(&I) -> O,
) {
    g.bench_function(id, |b| {
        b.iter(|| {
            for x in inputs {
                let answer = f(std::hint::black_box(x));
                std::hint::black_box(&answer);
            }
        })
    });
}
