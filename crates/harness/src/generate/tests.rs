//! The generators' own guarantees: valid input, determinism, the uniform/biased
//! split, every family reached, and the exact constructions really exact (the
//! referee's margin is 0 where a family promises touching).

use super::*;
use crate::engines::referee::margin;
use crate::judge::scene_scale;
use crate::load::validate;
use proptest::test_runner::TestRunner;
use std::collections::BTreeMap;
use std::num::FpCategory;

/// Cases per kind in the sweeps below: enough to reach every family many times.
const SWEEP: u64 = 600;

fn json(lc: &LoadedCase) -> String {
    serde_json::to_string(&lc.case).unwrap_or_default()
}

#[test]
fn generate_every_case_is_valid_input_of_its_kind() {
    for q in GENERATED {
        for i in 0..SWEEP {
            let lc = generate(q, 7, i);
            assert_eq!(lc.case.query, q, "{}", lc.case.name);
            assert!(validate(&lc.case).is_ok(), "{}: {:?}\n{}", lc.case.name, validate(&lc.case), json(&lc));
        }
    }
}

#[test]
fn generate_is_a_function_of_seed_and_index() {
    for q in GENERATED {
        for i in 0..50 {
            let (x, y) = (generate(q, 99, i), generate(q, 99, i));
            assert_eq!(json(&x), json(&y), "{q} #{i}: two calls differ");
            assert_eq!(x.case.name, y.case.name);
            let other = generate(q, 100, i);
            assert_ne!(json(&x), json(&other), "{q} #{i}: seeds 99 and 100 give the same case");
        }
    }
}

#[test]
fn generate_names_cases_by_seed_index_and_family() {
    let lc = generate(Query::Contact, 42, 7);
    let family = family_for(Query::Contact, 7).unwrap_or_default();
    assert_eq!(lc.case.name, format!("contact #7 (seed 42, {family})"));
    assert_eq!(lc.case.source, format!("generated: seed 42, index 7, family {family}"));
    assert_eq!(lc.file, PathBuf::from(GENERATED_FILE));
    assert!(lc.case.expect.is_none(), "generated cases are judged against the referee only");
}

#[test]
fn generate_half_of_the_cases_are_biased_and_every_family_is_reached() {
    for q in GENERATED {
        let mut seen: BTreeMap<&str, u64> = BTreeMap::new();
        let mut biased = 0;
        for i in 0..SWEEP {
            let f = family_for(q, i).unwrap_or_default();
            *seen.entry(f).or_default() += 1;
            if is_biased(q, f) == Some(true) {
                biased += 1;
            }
        }
        assert_eq!(biased, SWEEP / 2, "{q}: biased cases");
        for f in families(q) {
            assert!(seen.get(f).copied().unwrap_or(0) >= 10, "{q}: family {f:?} reached {:?} times", seen.get(f));
        }
    }
}

#[test]
fn generate_kinds_without_generators_say_so() {
    for q in [Query::Toi, Query::Response] {
        assert!(families(q).is_empty(), "{q}");
        assert!(try_generate(q, 1, 0).is_none(), "{q}");
        assert!(family_for(q, 0).is_none(), "{q}");
    }
}

#[test]
fn generate_strategy_mixes_uniform_and_biased_families_evenly() {
    // The deterministic runner makes this count a fixed number, not a chance.
    let mut runner = TestRunner::deterministic();
    for q in GENERATED {
        let s = strategy(q);
        let n = 400;
        let mut biased = 0;
        for _ in 0..n {
            let case = s.new_tree(&mut runner).map(|t| t.current()).expect("no filters");
            let family = families(q).iter().find(|f| case.name == proptest_name(q, f)).copied().unwrap_or_default();
            if is_biased(q, family) == Some(true) {
                biased += 1;
            }
        }
        // Binomial(400, 1/2): a standard deviation of 10; ±60 is six of them.
        assert!((140..=260).contains(&biased), "{q}: {biased} of {n} biased");
    }
}

/// Families whose every case touches exactly (the referee's margin is exactly 0).
const EXACTLY_TOUCHING: [(Query, &str); 5] = [
    (Query::Contact, "exactly touching spheres"),
    (Query::Contact, "sphere exactly touching a plane"),
    (Query::Contact, "sphere exactly touching a triangle's face, edge or vertex"),
    (Query::Overlap, "boxes touching exactly on a face, edge or corner"),
    (Query::Intersect, "edge walker: segment through a triangle's edge ± k ulps"),
];

#[test]
fn generate_exact_families_touch_exactly() {
    for (q, name) in EXACTLY_TOUCHING {
        let mut runner = TestRunner::deterministic();
        let s = family_strategy(q, name).unwrap_or_else(|| panic!("no family {name:?}"));
        let mut zero = 0;
        for _ in 0..150 {
            let case = s.new_tree(&mut runner).map(|t| t.current()).expect("no filters");
            let lc = LoadedCase { file: GENERATED_FILE.into(), case, meshes: [None, None] };
            let m = margin(&lc);
            // The segment walker is exact only at k = 0 (one step in 17).
            if q == Query::Intersect {
                zero += usize::from(m.is_some_and(|m| m.classify() == FpCategory::Zero));
                continue;
            }
            assert!(
                m.is_some_and(|m| m.classify() == FpCategory::Zero),
                "{name}: margin {m:?}, not exactly 0\n{}",
                json(&lc)
            );
        }
        if q == Query::Intersect {
            assert!(zero >= 3, "{name}: only {zero} of 150 exactly on the edge");
        }
    }
}

/// An edge walker's case is `k ≤ 8` ULPs of its largest coordinate from exact
/// touching: its margin is within 8 ULPs of the scene's scale (`8 · 2ε · scale`
/// bounds the step of any coordinate up to `scale`), with a factor 2 to spare.
const WALKER_MARGIN_ULPS: f64 = 32.0;

#[test]
fn generate_edge_walkers_stay_within_a_few_ulps_of_touching() {
    let walkers = [
        (Query::Contact, "edge walker: touching spheres ± k ulps"),
        (Query::Contact, "edge walker: sphere touching a plane ± k ulps"),
        (Query::Overlap, "edge walker: box faces ± k ulps"),
    ];
    for (q, name) in walkers {
        let mut runner = TestRunner::deterministic();
        let s = family_strategy(q, name).unwrap_or_else(|| panic!("no family {name:?}"));
        for _ in 0..150 {
            let case = s.new_tree(&mut runner).map(|t| t.current()).expect("no filters");
            let lc = LoadedCase { file: GENERATED_FILE.into(), case, meshes: [None, None] };
            let bound = WALKER_MARGIN_ULPS * f64::EPSILON * scene_scale(&lc);
            let m = margin(&lc).unwrap_or(f64::INFINITY);
            assert!(m.abs() <= bound, "{name}: margin {m:e} beyond {bound:e}\n{}", json(&lc));
        }
    }
}
