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
//!
//! **The ceiling.** The cases the stages cannot finish (the stage counters
//! show work of the exact stage for them, or no stage answered any of it) are
//! timed on their own, staged (`staged-left`): the staged referee spends at
//! least that on the mix, whatever its work on every other case costs. The
//! table gives `exact time of the mix / staged time of the cases left`, the
//! ratio the stages would reach if that other work cost nothing. A kind whose
//! ceiling is below the target cannot meet it without a faster exact stage (or
//! a finer fallback) for the cases it leaves; the table names their pairs.

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

/// Cases drawn per query kind for the box and capsule pairs' own rows: they
/// are a share of each kind's families, so more are drawn and those kept.
const BOX_DRAWN: u64 = 4000;

fn cases(q: harness::case::Query) -> Vec<LoadedCase> {
    drawn(q, PER_KIND)
}

fn drawn(q: harness::case::Query, n: u64) -> Vec<LoadedCase> {
    let full = n / 10;
    let mut out: Vec<LoadedCase> = (0..n - full).map(|i| generate(q, SEED, i)).collect();
    out.extend((0..full).filter_map(|i| try_generate_full_range(q, SEED, i)));
    out
}

/// Whether a case's shapes include a box or a capsule.
fn boxy(lc: &LoadedCase) -> bool {
    use harness::case::ShapeKind;
    let kinds = [Some(lc.case.a.shape_kind()), lc.case.b.as_ref().map(harness::case::Shape::shape_kind)];
    kinds.iter().flatten().any(|k| matches!(k, ShapeKind::Box | ShapeKind::Capsule))
}

/// Splits `inputs` into the cases the floating-point stages finish and those
/// left, wholly or in part, to the exact stage: a case is left when running it
/// staged counts any exact answer, or no stage answer at all (a kind with no
/// stage, like overlap, whose exact stage is already plain comparisons).
fn left_to_exact(inputs: &[LoadedCase], truth: impl Fn(&LoadedCase)) -> Vec<LoadedCase> {
    let counts = || {
        oracle::referee::stage_counts_on_this_thread()
            .iter()
            .fold((0, 0), |(f, e), &(_, fast, exact)| (f + fast, e + exact))
    };
    inputs
        .iter()
        .filter(|lc| {
            let (f0, e0) = counts();
            truth(lc);
            let (f1, e1) = counts();
            e1 > e0 || f1 == f0
        })
        .cloned()
        .collect()
}

fn main() {
    let since = SystemTime::now();
    let mut c = Criterion::default().configure_from_args().sample_size(10).measurement_time(Duration::from_secs(3));
    let r = engines::referee();
    let truth = |lc: &LoadedCase| (run_caught(&r, lc).is_ok(), referee::margin(lc));
    let mut rows = Vec::new();
    for q in CAMPAIGN_QUERIES {
        let inputs = cases(q);
        let left = left_to_exact(&inputs, |lc| {
            truth(lc);
        });
        let group = format!("referee-{q}");
        let mut g = c.benchmark_group(&group);
        run(&mut g, "staged", &inputs, truth);
        run(&mut g, "exact", &inputs, |lc| oracle::referee::exact_only(|| truth(lc)));
        if !left.is_empty() {
            run(&mut g, "staged-left", &left, truth);
        }
        g.finish();
        let staged = ns_per(&group, "staged", inputs.len(), since);
        let exact = ns_per(&group, "exact", inputs.len(), since);
        // The exact time of the whole mix over the staged time of the cases
        // left: with no case left, nothing bounds the ratio but the stages'
        // own cost.
        let ceiling = if left.is_empty() {
            Some(f64::INFINITY)
        } else {
            ratio(exact.map(|e| e * inputs.len() as f64), ns_per(&group, "staged-left", 1, since))
        };
        let mut by_pair = std::collections::BTreeMap::<String, usize>::new();
        for lc in &left {
            *by_pair.entry(lc.case.pair().map_or_else(|| "(no pair)".into(), |p| p.to_string())).or_default() += 1;
        }
        let by_pair: Vec<String> = by_pair.iter().map(|(p, n)| format!("{p} {n}")).collect();
        rows.push((q, inputs.len(), left.len(), by_pair.join(", "), staged, exact, ceiling));
    }
    // The box and capsule pairs alone: each pair's campaign cases, staged
    // against exact.
    let mut box_rows = Vec::new();
    for q in CAMPAIGN_QUERIES {
        let mut by_pair = std::collections::BTreeMap::<String, Vec<LoadedCase>>::new();
        for lc in drawn(q, BOX_DRAWN).into_iter().filter(boxy) {
            let pair = lc.case.pair().map_or_else(|| "(no pair)".into(), |p| p.to_string());
            by_pair.entry(pair).or_default().push(lc);
        }
        for (pair, inputs) in by_pair {
            let group = format!("referee-{q}-{}", pair.replace([' ', '–', '/'], "_"));
            let mut g = c.benchmark_group(&group);
            run(&mut g, "staged", &inputs, truth);
            run(&mut g, "exact", &inputs, |lc| oracle::referee::exact_only(|| truth(lc)));
            g.finish();
            let staged = ns_per(&group, "staged", inputs.len(), since);
            let exact = ns_per(&group, "exact", inputs.len(), since);
            box_rows.push((pair, inputs.len(), staged, exact));
        }
    }
    c.final_summary();
    let mut table = format!(
        "# The referee's stages\n\nMean ns per query (answer and margin) over the campaign's mix, {PER_KIND} cases \
         per kind (seed {SEED}, a tenth full-range); target: exact / staged ≥ {TARGET_RATIO} for every kind. \
         \"left\" counts the cases the floating-point stages leave, wholly or in part, to the exact stage; \
         \"ceiling\" is the exact time of the whole mix over the staged time of those cases alone: the ratio the \
         stages would reach if their work on every other case cost nothing.\n\n\
         | query | cases | left | staged ns | exact ns | exact / staged | ceiling | target | left, by pair |\n\
         | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |\n"
    );
    for (q, n, left, by_pair, staged, exact, ceiling) in rows {
        let x = ratio(exact, staged);
        let verdict = match x {
            Some(x) if x >= TARGET_RATIO => "met",
            Some(_) => "not met",
            None => "not measured",
        };
        let ceiling = match ceiling {
            Some(c) if c.is_infinite() => "none".to_string(),
            c => cell(c),
        };
        table.push_str(&format!(
            "| {q} | {n} | {left} | {} | {} | {} | {ceiling} | {verdict} | {by_pair} |\n",
            cell(staged),
            cell(exact),
            cell(x)
        ));
    }
    table.push_str(&format!(
        "\n## Box and capsule pairs\n\nEach pair's own cases among {BOX_DRAWN} drawn per query kind (seed {SEED}, a \
         tenth full-range), answer and margin, staged against exact.\n\n\
         | pair | cases | staged ns | exact ns | exact / staged |\n| --- | ---: | ---: | ---: | ---: |\n"
    ));
    for (pair, n, staged, exact) in box_rows {
        table.push_str(&format!(
            "| {pair} | {n} | {} | {} | {} |\n",
            cell(staged),
            cell(exact),
            cell(ratio(exact, staged))
        ));
    }
    println!("\n{table}");
    let path = criterion_dir().join("crashtest-referee-table.md");
    if let Err(e) = std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, &table)) {
        eprintln!("cannot write {}: {e}", path.display());
    }
}
