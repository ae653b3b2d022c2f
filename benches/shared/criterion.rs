//! Shared by the benchmarks (`queries`, `mesh`, `toi`): the timing loop every
//! one-at-a-time row uses, reading criterion's estimates back for the
//! tables, the paired ratios of the targets, and the tables' cells.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// A number with three significant digits or so; `—` when missing.
pub fn cell(x: Option<f64>) -> String {
    match x {
        Some(v) if v >= 100.0 => format!("{v:.0}"),
        Some(v) if v >= 10.0 => format!("{v:.1}"),
        Some(v) => format!("{v:.2}"),
        None => "—".into(),
    }
}

/// `x / y` when both are known.
pub fn ratio(x: Option<f64>, y: Option<f64>) -> Option<f64> {
    Some(x? / y?)
}

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
    g.bench_function(id, |b| b.iter(|| pass(inputs, &f)));
}

/// One pass of `f` over `inputs`, as [`run`] and [`Pairs::keep`] time it.
#[inline(always)]
fn pass<I, O>(inputs: &[I], f: &impl Fn(&I) -> O) {
    for x in inputs {
        let answer = f(std::hint::black_box(x));
        std::hint::black_box(&answer);
    }
}

/// Rounds of a paired ratio: each round times both engines back to back.
const PAIRED_ROUNDS: usize = 31;

/// Least time of one engine's slice in a round: long enough for the clock's
/// resolution and the loop's start to vanish, short enough that a change in
/// the machine's speed seldom falls inside a round.
const PAIRED_SLICE: std::time::Duration = std::time::Duration::from_millis(20);

/// Whether this run measures paired ratios (`cargo bench`, not the one-shot
/// test run of `cargo test --benches`). Set once by the bench's `main`.
pub static PAIRING: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// One paired ratio: the numerator's time over the denominator's, from
/// rounds in which both ran back to back on their inputs (in alternating
/// order), as the median of the rounds' ratios with the quartiles.
#[derive(Clone, Copy, Debug)]
pub struct PairedRatio {
    /// Median of the rounds' ratios.
    pub median: f64,
    /// Lower quartile.
    pub low: f64,
    /// Upper quartile.
    pub high: f64,
    /// Median over the rounds of the numerator's nanoseconds per query.
    pub ns_a: f64,
    /// Median over the rounds of the denominator's nanoseconds per query.
    pub ns_b: f64,
}

impl PairedRatio {
    /// The median with its quartiles, as the tables print it.
    pub fn quartiles(&self) -> String {
        format!("{:.3} ({:.3}–{:.3})", self.median, self.low, self.high)
    }
}

/// Every paired ratio measured in this run: group, numerator id, denominator
/// id, ratio.
static PAIRED: std::sync::Mutex<Vec<(String, String, String, PairedRatio)>> = std::sync::Mutex::new(Vec::new());

/// The paired ratio `a / b` of `group` measured in this run, if any.
pub fn paired_ratio(group: &str, a: &str, b: &str) -> Option<PairedRatio> {
    let all = PAIRED.lock().ok()?;
    all.iter().find(|(g, x, y, _)| g == group && x == a && y == b).map(|e| e.3)
}

/// The targets table's heading: how its ratios were measured, its columns
/// and their alignment.
pub fn targets_heading() -> String {
    format!(
        "## Targets\n\nEach ratio twice: from criterion's estimates (each engine timed for about a second, one after \
         the other) and paired: both engines timed back to back over the same cases for {} ms each, in alternating \
         order, {PAIRED_ROUNDS} times, the median of the {PAIRED_ROUNDS} ratios with its quartiles. A machine whose \
         speed changes for seconds at a time moves the first (one engine may be timed fast and the other slow) but \
         not the second; the verdict is the paired ratio's where it was measured. \"paired ns\" gives both \
         engines' median times per query in those rounds, numerator / denominator.\n\n\
         | target | criterion | paired (quartiles) | paired ns | verdict |\n| --- | ---: | ---: | ---: | --- |\n",
        PAIRED_SLICE.as_millis()
    )
}

/// A table's ratio cell: the paired median `paired` where measured, marked
/// `*`, else criterion's ratio (see [`PAIRED_MARK`]).
pub fn ratio_cell(criterion: Option<f64>, paired: Option<PairedRatio>) -> String {
    match paired {
        Some(p) => format!("{}*", cell(Some(p.median))),
        None => cell(criterion),
    }
}

/// The sentence that explains [`ratio_cell`]'s mark, for the tables'
/// introductions.
pub const PAIRED_MARK: &str = "A ratio marked * is the paired median of the targets below (both engines timed back \
     to back, many times over); unmarked ratios are from criterion's estimates, each engine timed after the other.";

/// The ratio a target is judged on: the paired median where it was
/// measured, else criterion's ratio.
pub fn judged(criterion: Option<f64>, paired: Option<PairedRatio>) -> Option<f64> {
    paired.map(|p| p.median).or(criterion)
}

/// The verdict on a ratio against its target.
pub fn verdict(r: Option<f64>, target: f64) -> &'static str {
    match r {
        Some(r) if r <= target => "met",
        Some(_) => "**missed**",
        None => "not measured",
    }
}

/// One row of the targets table: what is compared and its target, criterion's
/// ratio, the paired ratio (median and quartiles), both engines' paired
/// times, the verdict.
pub fn target_row(
    what: &str,
    target: f64,
    criterion: Option<f64>,
    paired: Option<PairedRatio>,
    verdict: &str,
) -> String {
    let ns = paired.map_or("—".into(), |p| format!("{} / {}", cell(Some(p.ns_a)), cell(Some(p.ns_b))));
    let paired = paired.map_or("—".into(), |p| p.quartiles());
    let criterion = criterion.map_or("—".into(), |x| format!("{x:.3}"));
    format!("| {what} ≤ {target} | {criterion} | {paired} | {ns} | {verdict} |\n")
}

/// An engine kept for a paired ratio: its id, the queries one pass answers,
/// and a timer running `passes` passes and giving nanoseconds per query.
struct Kept<'a> {
    id: &'static str,
    per_pass: usize,
    timer: Box<dyn FnMut(u32) -> f64 + 'a>,
}

/// The engines of one group kept for paired ratios.
///
/// Why pairs: criterion measures one engine after another, each for about a
/// second. On a shared machine whose speed changes for seconds at a time (on
/// the one these benches were written on, the same loop ran at 13 ns per case
/// for some seconds and 20 ns for the next, back and forth), two engines can
/// be measured at different speeds, and their ratio is off by as much. A
/// paired ratio times both within [`PAIRED_SLICE`] of each other, many times
/// over, and takes the median of the rounds' ratios: a change of speed
/// spoils the rounds it falls in, not the median.
pub struct Pairs<'a> {
    group: String,
    kept: Vec<Kept<'a>>,
}

impl<'a> Pairs<'a> {
    /// No engines yet, for `group`.
    pub fn new(group: impl Into<String>) -> Self {
        Self { group: group.into(), kept: Vec::new() }
    }

    /// Keeps engine `id`: `f` over every input, as [`run`] times it.
    pub fn keep<I, O>(&mut self, id: &'static str, inputs: &'a [I], f: impl Fn(&I) -> O + 'a) {
        self.keep_pass(id, inputs.len(), move || pass(inputs, &f));
    }

    /// Keeps engine `id` whose pass is one call of `f` answering `per_pass`
    /// queries (a batch call, or a loop that writes its answers itself).
    pub fn keep_pass(&mut self, id: &'static str, per_pass: usize, mut f: impl FnMut() + 'a) {
        let per_pass = per_pass.max(1);
        let timer = move |passes: u32| {
            let start = std::time::Instant::now();
            for _ in 0..passes {
                f();
            }
            start.elapsed().as_nanos() as f64 / (f64::from(passes) * per_pass as f64)
        };
        self.kept.push(Kept { id, per_pass, timer: Box::new(timer) });
    }

    /// Measures `a / b` for every pair of kept ids given (in a benchmarking
    /// run only) and records them for [`paired_ratio`].
    pub fn measure(mut self, pairs: &[(&str, &str)]) {
        if !PAIRING.load(std::sync::atomic::Ordering::Relaxed) {
            return;
        }
        for &(a, b) in pairs {
            let (Some(ia), Some(ib)) =
                (self.kept.iter().position(|k| k.id == a), self.kept.iter().position(|k| k.id == b))
            else {
                continue;
            };
            let r = self.pair(ia, ib);
            if let Ok(mut all) = PAIRED.lock() {
                all.push((self.group.clone(), a.into(), b.into(), r));
            }
        }
    }

    /// Times engines `ia` and `ib` in [`PAIRED_ROUNDS`] rounds.
    fn pair(&mut self, ia: usize, ib: usize) -> PairedRatio {
        let (pa, pb) = (self.passes(ia), self.passes(ib));
        let mut ratios = Vec::with_capacity(PAIRED_ROUNDS);
        let (mut times_a, mut times_b) = (Vec::with_capacity(PAIRED_ROUNDS), Vec::with_capacity(PAIRED_ROUNDS));
        for round in 0..PAIRED_ROUNDS {
            let (ta, tb) = if round % 2 == 0 {
                let ta = (self.kept[ia].timer)(pa);
                (ta, (self.kept[ib].timer)(pb))
            } else {
                let tb = (self.kept[ib].timer)(pb);
                ((self.kept[ia].timer)(pa), tb)
            };
            ratios.push(ta / tb);
            times_a.push(ta);
            times_b.push(tb);
        }
        let at = |xs: &mut Vec<f64>, q: f64| {
            xs.sort_by(f64::total_cmp);
            xs[((xs.len() - 1) as f64 * q).round() as usize]
        };
        PairedRatio {
            median: at(&mut ratios, 0.5),
            low: at(&mut ratios, 0.25),
            high: at(&mut ratios, 0.75),
            ns_a: at(&mut times_a, 0.5),
            ns_b: at(&mut times_b, 0.5),
        }
    }

    /// Passes of engine `i` that last at least [`PAIRED_SLICE`], from one
    /// pass (which also warms it).
    fn passes(&mut self, i: usize) -> u32 {
        let k = &mut self.kept[i];
        let once_s = (k.timer)(1) * k.per_pass as f64 * 1e-9;
        (PAIRED_SLICE.as_secs_f64() / once_s.max(1e-9)).ceil().clamp(1.0, 1e6) as u32
    }
}
