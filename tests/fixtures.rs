//! Every shipped fixture, through the same code path as `crashtest check`: the
//! default engine meets every expectation and agrees with the referee, and the
//! referee itself meets every expectation (the cases' hand derivations and the
//! exact evaluation are independent, so each checks the other).

use harness::check::{CaseResult, check, render_text};
use harness::engines::EngineSet;
use harness::load::load_paths;

#[test]
fn every_fixture_loads_without_error() {
    let loaded = load_paths(&["fixtures"]);
    assert!(loaded.errors.is_empty(), "input errors: {:#?}", loaded.errors);
    assert!(loaded.cases.len() >= 50, "only {} cases found", loaded.cases.len());
}

#[test]
fn the_default_engine_passes_every_fixture() {
    let loaded = load_paths(&["fixtures"]);
    let result = check(&loaded.cases, &loaded.errors, &EngineSet::default());
    let failed: Vec<&CaseResult> = result.cases.iter().filter(|c| !c.passed).collect();
    assert!(failed.is_empty(), "{} cases failed:\n{}", failed.len(), render_text(&result));
}

#[test]
fn the_referee_meets_every_fixture_expectation() {
    let loaded = load_paths(&["fixtures"]);
    let result = check(&loaded.cases, &loaded.errors, &EngineSet::default());
    let off: Vec<String> = result
        .cases
        .iter()
        .filter(|c| c.referee_meets_expect == Some(false))
        .map(|c| format!("{} › {}: referee answered {:?}", c.file, c.name, c.referee))
        .collect();
    assert!(off.is_empty(), "the referee disagrees with these expectations:\n{}", off.join("\n"));
}

#[test]
fn every_query_kind_has_at_least_ten_hand_derived_cases() {
    let loaded = load_paths(&["fixtures"]);
    for q in ["contact", "intersect", "barycentric", "bounds", "overlap"] {
        let n = loaded
            .cases
            .iter()
            .filter(|c| c.case.query.as_str() == q && c.case.source.starts_with("hand-derived"))
            .count();
        assert!(n >= 10, "{q}: {n} hand-derived cases");
    }
}
