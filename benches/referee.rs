//! The referee's two stages against its exact stage alone, one run:
//! `cargo bench --bench referee`.
//!
//! Per query kind, on the campaign's own mix ([`PER_KIND`] generated cases of
//! [`SEED`], a tenth of them full-range, as a report draws them), the work the
//! campaign asks of the referee for each case — its answer and its margin —
//! timed with the floating-point stages on (`referee`) and off
//! (`oracle::referee::exact_only`: `exact`). The answers are the same bits
//! either way (`tests/referee_stages.rs`); this measures what the stages save.
//! At the end a table of mean ns per query, the ratio exact / staged, and the
//! target (at least [`TARGET_RATIO`] for every kind) is printed and written to
//! `target/criterion/crashtest-referee-table.md`.

#[path = "shared/criterion.rs"]
#[allow(
    dead_code,
    reason = "shared with the other benches; this one uses the timing loop, the estimates and the cells, not the paired ratios"
)]
mod criterion_files;
use criterion_files::{cell, criterion_dir, ns_per, ratio, run};

use criterion::Criterion;
use harness::check::run_caught;
use harness::engines::{self, referee};
use harness::generate::{generate, try_generate_full_range};
use harness::load::LoadedCase;
use harness::report::campaign::CAMPAIGN_QUERIES;
use std::time::{Duration, SystemTime};

/// Seed of the cases: the campaign's default, so the mix is a report's.
const SEED: u64 = harness::defaults::DEFAULT_SEED;

/// Cases per query kind: enough to mix every family several times, few enough
/// that one pass of the exact stage over them (up to about a millisecond a
/// case) keeps the run to a minute or two.
const PER_KIND: u64 = 400;

/// The target: the staged referee's mean time per query at least this
/// many times lower than the exact stage's, for every query kind.
const TARGET_RATIO: f64 = 50.0;

fn cases(q: harness::case::Query) -> Vec<LoadedCase> {
    let full = PER_KIND / 10;
    let mut out: Vec<LoadedCase> = (0..PER_KIND - full).map(|i| generate(q, SEED, i)).collect();
    out.extend((0..full).filter_map(|i| try_generate_full_range(q, SEED, i)));
    out
}

fn main() {
    let since = SystemTime::now();
    let mut c = Criterion::default().configure_from_args().sample_size(10).measurement_time(Duration::from_secs(3));
    let r = engines::referee();
    let truth = |lc: &LoadedCase| (run_caught(&r, lc).is_ok(), referee::margin(lc));
    let mut rows = Vec::new();
    for q in CAMPAIGN_QUERIES {
        let inputs = cases(q);
        let group = format!("referee-{q}");
        let mut g = c.benchmark_group(&group);
        run(&mut g, "staged", &inputs, truth);
        run(&mut g, "exact", &inputs, |lc| oracle::referee::exact_only(|| truth(lc)));
        g.finish();
        let staged = ns_per(&group, "staged", inputs.len(), since);
        let exact = ns_per(&group, "exact", inputs.len(), since);
        rows.push((q, inputs.len(), staged, exact));
    }
    c.final_summary();
    let mut table = format!(
        "# The referee's stages\n\nMean ns per query (answer and margin) over the campaign's mix, {PER_KIND} cases \
         per kind (seed {SEED}, a tenth full-range); target: exact / staged ≥ {TARGET_RATIO} for every kind.\n\n\
         | query | cases | staged ns | exact ns | exact / staged | target |\n| --- | ---: | ---: | ---: | ---: | --- |\n"
    );
    for (q, n, staged, exact) in rows {
        let x = ratio(exact, staged);
        let verdict = match x {
            Some(x) if x >= TARGET_RATIO => "met",
            Some(_) => "not met",
            None => "not measured",
        };
        table.push_str(&format!("| {q} | {n} | {} | {} | {} | {verdict} |\n", cell(staged), cell(exact), cell(x)));
    }
    println!("\n{table}");
    let path = criterion_dir().join("crashtest-referee-table.md");
    if let Err(e) = std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, &table)) {
        eprintln!("cannot write {}: {e}", path.display());
    }
}
