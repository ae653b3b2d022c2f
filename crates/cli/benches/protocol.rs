//! The engine protocol's own cost per case (docs/PROTOCOL.md, "Speed"):
//! `crashtest-engine-collide` answering AABB overlaps — a trivial query (a few
//! nanoseconds inside the engine) — in batches of 1 to 4096 cases. Per case,
//! the wall time of a batch exchange (crashtest writing the cases, the engine
//! reading them, answering and writing the answers, crashtest reading them)
//! minus the engine's own time for the query is the protocol's overhead.
//!
//! criterion times each batch size; the table at the end takes, per batch
//! size, the median of `ROUNDS` passes over the same cases, and marks the
//! target (at most `TARGET_NS` of overhead per case at batch size 1024).

use criterion::{Criterion, Throughput};
use harness::load::LoadedCase;
use harness::protocol::client::{ProcessEngine, ProcessSpec};
use std::hint::black_box;
use std::time::Instant;

/// Batch sizes timed.
const BATCHES: [usize; 7] = [1, 4, 16, 64, 256, 1024, 4096];
/// Cases per pass: every batch size sends the same 4096 cases.
const CASES: u64 = 4096;
/// Passes per batch size for the table's median.
const ROUNDS: usize = 9;
/// The target: protocol overhead per case at batch size 1024, ns.
const TARGET_NS: f64 = 2000.0;
const TARGET_BATCH: usize = 1024;

fn engine(batch: usize) -> ProcessEngine {
    let mut spec =
        ProcessSpec::new("collide over the protocol", vec![env!("CARGO_BIN_EXE_crashtest-engine-collide").into()])
            .expect("spec");
    spec.batch = batch;
    let e = ProcessEngine::start(spec);
    assert_eq!(e.down(), None, "the engine starts");
    e
}

fn main() {
    let q = harness::case::Query::Overlap;
    let cases: Vec<LoadedCase> = (0..CASES)
        .filter_map(|i| harness::generate::try_generate(q, harness::report::campaign::DEFAULT_SEED, i))
        .collect();
    let refs: Vec<&LoadedCase> = cases.iter().collect();
    let mut c = Criterion::default().configure_from_args();
    let mut group = c.benchmark_group("protocol");
    group.throughput(Throughput::Elements(refs.len() as u64));
    group.sample_size(10);
    for batch in BATCHES {
        let e = engine(batch);
        group.bench_function(format!("overlap, batch {batch}"), |b| {
            b.iter(|| black_box(e.run_batches(black_box(&refs))))
        });
    }
    group.finish();
    c.final_summary();

    // The table: wall per case, the engine's own time per case, the overhead.
    let mut rows = Vec::new();
    for batch in BATCHES {
        let e = engine(batch);
        let mut walls = Vec::new();
        let mut inside = Vec::new();
        for _ in 0..ROUNDS {
            let start = Instant::now();
            let replies = e.run_batches(&refs);
            walls.push(start.elapsed().as_nanos() as f64 / refs.len() as f64);
            inside.push(replies.iter().filter_map(|r| r.ns).sum::<f64>() / refs.len() as f64);
        }
        walls.sort_by(f64::total_cmp);
        inside.sort_by(f64::total_cmp);
        let (wall, engine_ns) = (walls[ROUNDS / 2], inside[ROUNDS / 2]);
        rows.push((batch, wall, engine_ns, wall - engine_ns));
    }
    println!(
        "\nprotocol cost per case, collide's overlap over crashtest-engine/1, {CASES} cases a pass, median of {ROUNDS}:"
    );
    println!("| batch | wall ns/case | inside the engine ns/case | protocol overhead ns/case |");
    println!("|---:|---:|---:|---:|");
    for (batch, wall, engine_ns, over) in &rows {
        println!("| {batch} | {wall:.0} | {engine_ns:.0} | {over:.0} |");
    }
    if let Some((_, _, _, over)) = rows.iter().find(|r| r.0 == TARGET_BATCH) {
        let verdict = if *over <= TARGET_NS { "met" } else { "missed" };
        println!("target: overhead ≤ {TARGET_NS:.0} ns per case at batch {TARGET_BATCH}: {over:.0} ns — {verdict}");
    }
}
