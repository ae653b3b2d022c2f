//! Randomized differential tests: for each query kind, cases drawn from the
//! generators (`harness::generate`, the same strategies the report's campaigns
//! use: half uniform, half biased toward where methods fail) go through
//! `collide/robust`, `parry3d-f64` and the referee, and each answer is judged
//! against the referee's with the harness's own tolerances
//! (`harness::check::check_case`, the code path of `crashtest check`).
//!
//! - `collide/robust` must agree with the referee: `agree`, `borderline` (a
//!   classification inside the tolerance band of its boundary) and a documented
//!   known divergence pass; anything else fails the test, which prints the
//!   shrunk case as a fixture (its expectation the referee's answer) and writes
//!   it to `$CARGO_TARGET_TMPDIR/differential/<query>.json`, so that
//!   `crashtest check` on that file replays it.
//! - `parry3d-f64` is adjudicated by the referee and recorded, never failed: its
//!   verdicts are counted, and its disagreements listed, on standard output
//!   (`cargo test --test differential -- --nocapture` shows them).
//!
//! Failures are persisted by proptest in `tests/differential.proptest-regressions`
//! and replayed first on every run; each one also becomes a fixture under
//! `fixtures/regressions/`.

use harness::case::{Case, FixtureFile, Query, SCHEMA};
use harness::check::{CaseResult, check_case};
use harness::engine::Engine;
use harness::engines::EngineSet;
use harness::engines::{DEFAULT_ENGINE, judged};
use harness::generate::{GENERATED, generate, strategy};
use harness::judge::tolerance::F64_REL;
use harness::judge::{Verdict, scene_scale};
use harness::load::LoadedCase;
use oracle::parry::Parry64;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError, TestError, TestRunner};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Mutex;

/// Cases per query kind. Measured in the test profile on two shared cores: the
/// whole file runs in about 4 s once built (bounds, whose referee finds minimal
/// spheres of up to 64 points in exact rationals, takes 2.5 s of it; the other
/// kinds well under a second each).
const CASES: u32 = 2000;

/// How many of parry's disagreements are listed (all are counted).
const LISTED: usize = 8;

/// The engines these tests run: collide's default and parry in f64.
fn engines() -> Vec<Engine> {
    judged().into_iter().filter(|e| e.name == DEFAULT_ENGINE || e.name == Parry64::NAME).collect()
}

/// The case count: [`CASES`], or proptest's own `PROPTEST_CASES` when set (for a
/// longer campaign from the command line).
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(CASES)
}

fn config() -> Config {
    Config {
        cases: cases(),
        source_file: Some(file!()),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
        ..Config::default()
    }
}

/// The case as the campaign loads it (inline meshes, as time-of-impact
/// cases against meshes carry them, built into meshes).
fn loaded(case: Case) -> LoadedCase {
    harness::generate::loaded(case)
}

/// The case as a one-case fixture file expecting the referee's answer. The
/// format's `tol` is absolute, so for answers made of lengths the harness's
/// relative tolerance is turned absolute at the scene's scale when the scene is
/// larger than 1 (barycentric coordinates are unitless and keep the default).
fn as_fixture(case: &Case, result: &CaseResult) -> String {
    let mut case = case.clone();
    case.expect = result.referee.clone();
    let scale = scene_scale(&loaded(case.clone()));
    if scale > 1.0 && case.query != Query::Barycentric {
        case.tol = Some(F64_REL * scale);
    }
    case.source = format!("{} (shrunk by tests/differential.rs)", case.source);
    let file = FixtureFile { schema: SCHEMA.into(), cases: vec![case] };
    serde_json::to_string_pretty(&file).unwrap_or_default()
}

/// Whether `collide/robust`'s verdict passes.
fn acceptable(v: &Verdict) -> bool {
    matches!(v, Verdict::Agree | Verdict::Borderline { .. } | Verdict::KnownDivergence { .. })
}

/// What parry did over a run.
#[derive(Default)]
struct ParryTally {
    /// Cases judged (shrinking steps after a failure included).
    cases: usize,
    verdicts: BTreeMap<&'static str, usize>,
    listed: Vec<String>,
}

fn verdict_detail(v: &Verdict) -> String {
    match v {
        Verdict::Disagree { reasons } | Verdict::Borderline { reasons } => reasons.join("; "),
        Verdict::KnownDivergence { reason } | Verdict::Unsupported { reason } | Verdict::Failed { reason } => {
            reason.clone()
        }
        Verdict::Agree => String::new(),
    }
}

/// Runs the proptest of one query kind.
fn differential(query: Query) {
    let set = EngineSet::of(engines());
    let tally = Mutex::new(ParryTally::default());
    let mut runner = TestRunner::new(config());
    let outcome = runner.run(&strategy(query), |case| {
        let lc = loaded(case);
        let result = check_case(&lc, &set);
        for r in &result.engines {
            if r.engine == DEFAULT_ENGINE {
                if !acceptable(&r.verdict) {
                    return Err(TestCaseError::fail(format!(
                        "{} {}: {}",
                        r.engine,
                        r.verdict.label(),
                        verdict_detail(&r.verdict)
                    )));
                }
            } else if let Ok(mut t) = tally.lock() {
                t.cases += 1;
                *t.verdicts.entry(r.verdict.label()).or_default() += 1;
                if matches!(r.verdict, Verdict::Disagree { .. } | Verdict::Failed { .. }) && t.listed.len() < LISTED {
                    t.listed.push(format!("{}: {}", lc.case.name, verdict_detail(&r.verdict)));
                }
            }
        }
        Ok(())
    });
    if let Ok(t) = tally.lock() {
        println!("{query}: {} against the referee over {} cases: {:?}", Parry64::NAME, t.cases, t.verdicts);
        for line in &t.listed {
            println!("  {line}");
        }
    }
    match outcome {
        Ok(()) => {}
        Err(TestError::Fail(why, case)) => {
            let result = check_case(&loaded(case.clone()), &set);
            let fixture = as_fixture(&case, &result);
            let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("differential");
            let path = dir.join(format!("{query}.json"));
            let written = std::fs::create_dir_all(&dir).and_then(|_| std::fs::write(&path, &fixture));
            panic!(
                "{query}: {why}\nreplay with `crashtest check {}`{}:\n{fixture}",
                path.display(),
                written.err().map(|e| format!(" (not written: {e})")).unwrap_or_default()
            );
        }
        Err(TestError::Abort(why)) => panic!("{query}: proptest aborted: {why}"),
    }
}

#[test]
fn differential_contact() {
    differential(Query::Contact);
}

#[test]
fn differential_intersect() {
    differential(Query::Intersect);
}

#[test]
fn differential_barycentric() {
    differential(Query::Barycentric);
}

#[test]
fn differential_bounds() {
    differential(Query::Bounds);
}

#[test]
fn differential_overlap() {
    differential(Query::Overlap);
}

#[test]
fn differential_toi() {
    differential(Query::Toi);
}

#[test]
fn differential_response() {
    differential(Query::Response);
}

#[test]
fn generated_cases_are_reproducible_from_seed_and_index() {
    for q in GENERATED {
        for i in 0..100 {
            let (x, y) = (generate(q, 2024, i), generate(q, 2024, i));
            let text = |lc: &LoadedCase| serde_json::to_string(&lc.case).unwrap_or_default();
            assert_eq!(text(&x), text(&y), "{q} #{i}: the same seed and index gave different cases");
            let z = generate(q, 2025, i);
            assert_ne!(text(&x), text(&z), "{q} #{i}: seeds 2024 and 2025 gave the same case");
        }
    }
}
