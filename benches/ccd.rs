//! Continuous collision (ccd), collide's robust method against its lecture
//! method, one run: `cargo bench --bench ccd`.
//!
//! Vertex–face (`collide::ccd::ccd_vertex_face` against
//! `ccd_vertex_face_lecture`) and edge–edge (`ccd_edge_edge` against
//! `ccd_edge_edge_lecture`) apart, on two sets of queries:
//!
//! - the campaign's ccd mix: [`PER_KIND`] cases of the default seed as a
//!   report draws them (`harness::generate::generate`, a tenth from
//!   `try_generate_full_range`), split by kind;
//! - the CCD benchmark's committed sample queries (`fixtures/ccd-benchmark.json`,
//!   loaded through `harness::load`), split by kind.
//!
//! Inputs are converted to collide's `[Vec3<f64>; 4]` at `t = 0` and `t = 1`
//! before timing, as the harness's engine converts them; a timed iteration
//! runs the query on every case of a set (`shared/criterion.rs`). Each pair is
//! also measured paired (both methods back to back, alternating, many rounds),
//! and the table gives mean ns per query of each method (criterion's estimate
//! and the paired rounds' median), the paired ratio robust / lecture with its
//! quartiles, the fractions of cases each method finds an impact in, and how
//! many cases the two disagree on (impact or not). It is printed and written to
//! `target/criterion/crashtest-ccd-table.md`.
//!
//! collide exposes no counter of the cases its robust method's floating-point
//! filter leaves to the exact stage (`collide::ccd`'s filter is private), so
//! the table cannot give that fraction; it says so.

#[path = "shared/criterion.rs"]
#[allow(
    dead_code,
    reason = "shared with the other benches; this one uses the loop, the estimates and the paired ratios"
)]
mod criterion_files;
use criterion_files::{PAIRING, Pairs, cell, criterion_dir, ns_per, paired_ratio, run};

use collide::Vec3;
use collide::ccd::{Ccd, ccd_edge_edge, ccd_edge_edge_lecture, ccd_vertex_face, ccd_vertex_face_lecture};
use criterion::{Criterion, Throughput};
use harness::case::{Query, Shape};
use harness::generate::{generate, try_generate_full_range};
use harness::load::LoadedCase;
use std::path::Path;
use std::time::{Duration, SystemTime};

/// Seed of the campaign's cases: its default, so the mix is a report's.
const SEED: u64 = harness::defaults::DEFAULT_SEED;

/// Campaign cases drawn (both kinds together), a tenth of them full-range.
const PER_KIND: u64 = 400;

/// The committed benchmark queries.
const BENCHMARK_FILE: &str = "fixtures/ccd-benchmark.json";

/// Warm-up per benchmark.
const WARM_UP: Duration = Duration::from_millis(300);
/// Measurement per benchmark.
const MEASUREMENT: Duration = Duration::from_millis(1500);
/// Samples per benchmark (criterion's minimum is 10).
const SAMPLES: usize = 20;
/// Bootstrap resamples.
const RESAMPLES: usize = 10_000;

/// One query in collide's types: the four points at `t = 0` and `t = 1`,
/// `t_max`.
type Input = ([Vec3<f64>; 4], [Vec3<f64>; 4], f64);

/// A ccd method of collide.
type Method = fn(&[Vec3<f64>; 4], &[Vec3<f64>; 4], f64) -> Ccd;

fn v(p: &[f64; 3]) -> Vec3<f64> {
    Vec3::new(p[0], p[1], p[2])
}

/// A ccd case's kind and inputs, in the harness engine's order (`[p, a, b, c]`
/// or `[a0, a1, b0, b1]`); `None` for anything else.
fn input(lc: &LoadedCase) -> Option<(Kind, Input)> {
    let case = &lc.case;
    let t_max = case.t_max();
    match (&case.a, case.b.as_ref()?) {
        (Shape::MovingPoint(p), Shape::MovingTriangle(t)) => Some((
            Kind::VertexFace,
            ([p.t0, t.t0[0], t.t0[1], t.t0[2]].map(|q| v(&q)), [p.t1, t.t1[0], t.t1[1], t.t1[2]].map(|q| v(&q)), t_max),
        )),
        (Shape::MovingSegment(a), Shape::MovingSegment(b)) => Some((
            Kind::EdgeEdge,
            (
                [a.t0[0], a.t0[1], b.t0[0], b.t0[1]].map(|q| v(&q)),
                [a.t1[0], a.t1[1], b.t1[0], b.t1[1]].map(|q| v(&q)),
                t_max,
            ),
        )),
        _ => None,
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    VertexFace,
    EdgeEdge,
}

impl Kind {
    fn robust(self) -> Method {
        match self {
            Kind::VertexFace => ccd_vertex_face,
            Kind::EdgeEdge => ccd_edge_edge,
        }
    }
    fn lecture(self) -> Method {
        match self {
            Kind::VertexFace => ccd_vertex_face_lecture,
            Kind::EdgeEdge => ccd_edge_edge_lecture,
        }
    }
    fn label(self) -> &'static str {
        match self {
            Kind::VertexFace => "vertex–face",
            Kind::EdgeEdge => "edge–edge",
        }
    }
    fn slug(self) -> &'static str {
        match self {
            Kind::VertexFace => "vertex_face",
            Kind::EdgeEdge => "edge_edge",
        }
    }
}

/// The inputs of `cases` of kind `k`.
fn of_kind(cases: &[LoadedCase], k: Kind) -> Vec<Input> {
    cases.iter().filter_map(input).filter(|(kind, _)| *kind == k).map(|(_, x)| x).collect()
}

/// The campaign's ccd mix, as the referee bench and a report draw it.
fn campaign() -> Vec<LoadedCase> {
    let full = PER_KIND / 10;
    let mut out: Vec<LoadedCase> = (0..PER_KIND - full).map(|i| generate(Query::Ccd, SEED, i)).collect();
    out.extend((0..full).filter_map(|i| try_generate_full_range(Query::Ccd, SEED, i)));
    out
}

/// The committed benchmark queries; a load error stops the bench.
fn benchmark() -> Vec<LoadedCase> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(BENCHMARK_FILE);
    let loaded = harness::load::load_paths(&[&path]);
    assert!(loaded.errors.is_empty(), "{BENCHMARK_FILE}: {:?}", loaded.errors);
    loaded.cases
}

/// One row of the table.
struct Row {
    set: &'static str,
    kind: Kind,
    group: String,
    n: usize,
    robust_hits: usize,
    lecture_hits: usize,
    disagree: usize,
    /// The robust method's time on each case alone, in ns, sorted.
    per_case: Vec<f64>,
}

/// Per-case times above this are counted as slow in the table.
const SLOW_NS: f64 = 5_000.0;

/// The robust method's time on each case alone (the least of three calls, in
/// ns), sorted: where its mean comes from.
fn per_case(inputs: &[Input], f: Method) -> Vec<f64> {
    let mut out: Vec<f64> = inputs
        .iter()
        .map(|x| {
            (0..3)
                .map(|_| {
                    let start = std::time::Instant::now();
                    std::hint::black_box(f(std::hint::black_box(&x.0), &x.1, x.2));
                    start.elapsed().as_nanos() as f64
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    out.sort_by(f64::total_cmp);
    out
}

/// Times both methods of `kind` on `inputs` as group `ccd_{set}_{kind}`, and
/// their paired ratio robust / lecture.
fn bench(c: &mut Criterion, set: &'static str, kind: Kind, inputs: &[Input]) -> Row {
    let group = format!("ccd_{set}_{}", kind.slug());
    let (robust, lecture) = (kind.robust(), kind.lecture());
    let mut g = c.benchmark_group(&group);
    g.throughput(Throughput::Elements(inputs.len() as u64));
    run(&mut g, "robust", inputs, |(x0, x1, t)| robust(x0, x1, *t));
    run(&mut g, "lecture", inputs, |(x0, x1, t)| lecture(x0, x1, *t));
    g.finish();
    let mut pairs = Pairs::new(group.clone());
    pairs.keep("robust", inputs, move |(x0, x1, t)| robust(x0, x1, *t));
    pairs.keep("lecture", inputs, move |(x0, x1, t)| lecture(x0, x1, *t));
    pairs.measure(&[("robust", "lecture")]);
    let (mut robust_hits, mut lecture_hits, mut disagree) = (0, 0, 0);
    for (x0, x1, t) in inputs {
        let (r, l) = (robust(x0, x1, *t).t.is_some(), lecture(x0, x1, *t).t.is_some());
        robust_hits += usize::from(r);
        lecture_hits += usize::from(l);
        disagree += usize::from(r != l);
    }
    let per_case =
        if PAIRING.load(std::sync::atomic::Ordering::Relaxed) { per_case(inputs, robust) } else { Vec::new() };
    Row { set, kind, group, n: inputs.len(), robust_hits, lecture_hits, disagree, per_case }
}

fn table(rows: &[Row], since: SystemTime) -> String {
    let mut s = format!(
        "# crashtest speed: continuous collision (ccd), robust against lecture, one run\n\n\
         collide's robust method (a floating-point filter with rigorous bounds, then exact polynomials) against \
         its lecture method (the coplanarity cubic in f64 with tolerances), both f64. \"campaign\": the campaign's \
         ccd mix, {PER_KIND} cases of seed {SEED} (a tenth full-range) split by kind; \"benchmark\": the CCD \
         benchmark's sample queries of `{BENCHMARK_FILE}`. ns per query: criterion's estimate (slope, else mean, \
         over the cases per iteration), then the median of the paired rounds (both methods back to back over the \
         same cases, alternating, 31 rounds). The ratio robust / lecture is the paired median with its quartiles. \
         \"hits\" are the cases each method finds an impact in; \"differ\": cases where one finds an impact and \
         the other not.\n\n\
         | set | kind | cases | robust ns | lecture ns | paired ns robust / lecture | robust / lecture (quartiles) | \
         hits robust / lecture | differ |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
    );
    for r in rows {
        let robust = ns_per(&r.group, "robust", r.n, since);
        let lecture = ns_per(&r.group, "lecture", r.n, since);
        let p = paired_ratio(&r.group, "robust", "lecture");
        let ns = p.map_or("—".into(), |p| format!("{} / {}", cell(Some(p.ns_a)), cell(Some(p.ns_b))));
        let q = p.map_or("—".into(), |p| p.quartiles());
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {ns} | {q} | {} / {} | {} |\n",
            r.set,
            r.kind.label(),
            r.n,
            cell(robust),
            cell(lecture),
            r.robust_hits,
            r.lecture_hits,
            r.disagree
        ));
    }
    s.push_str(&format!(
        "\nWhere the robust method's mean comes from: its time on each case alone (the least of three calls, \
         timer overhead included), the median, the 90th percentile and the largest, and the cases over {} µs \
         with their share of the sum of the per-case times.\n\n\
         | set | kind | median ns | p90 ns | max ns | cases over {} µs | their share of the time |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: |\n",
        SLOW_NS / 1000.0,
        SLOW_NS / 1000.0
    ));
    for r in rows.iter().filter(|r| !r.per_case.is_empty()) {
        let at = |q: f64| r.per_case[((r.per_case.len() - 1) as f64 * q).round() as usize];
        let total: f64 = r.per_case.iter().sum();
        let slow: Vec<f64> = r.per_case.iter().copied().filter(|&t| t > SLOW_NS).collect();
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {:.1} % |\n",
            r.set,
            r.kind.label(),
            cell(Some(at(0.5))),
            cell(Some(at(0.9))),
            cell(Some(at(1.0))),
            slow.len(),
            100.0 * slow.iter().sum::<f64>() / total.max(1.0)
        ));
    }
    s.push_str(
        "\nThe fraction of cases the robust method's filter leaves to its exact stage is not measured: \
         collide exposes no counter for it (`collide::ccd`'s filter is private).\n",
    );
    s
}

fn main() {
    let since = SystemTime::now();
    // `cargo bench` passes `--bench`; `cargo test --benches` does not: then
    // each benchmark runs once as a test, with no pairs and no table.
    let benching = std::env::args().any(|a| a == "--bench");
    PAIRING.store(benching, std::sync::atomic::Ordering::Relaxed);
    let (campaign, benchmark) = (campaign(), benchmark());
    let mut c = Criterion::default()
        .output_directory(&criterion_dir())
        .warm_up_time(WARM_UP)
        .measurement_time(MEASUREMENT)
        .sample_size(SAMPLES)
        .nresamples(RESAMPLES)
        .configure_from_args();
    let mut rows = Vec::new();
    for (set, cases) in [("campaign", &campaign), ("benchmark", &benchmark)] {
        for kind in [Kind::VertexFace, Kind::EdgeEdge] {
            let inputs = of_kind(cases, kind);
            if !inputs.is_empty() {
                rows.push(bench(&mut c, set, kind, &inputs));
            }
        }
    }
    c.final_summary();
    if benching {
        let report = table(&rows, since);
        println!("\n{report}");
        let path = criterion_dir().join("crashtest-ccd-table.md");
        match std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, &report)) {
            Ok(()) => println!("(written to {})", path.display()),
            Err(e) => eprintln!("could not write {}: {e}", path.display()),
        }
    }
}
