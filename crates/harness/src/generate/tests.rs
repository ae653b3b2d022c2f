//! The generators' own guarantees: valid input, determinism, the uniform/biased
//! split, every family reached, and the exact constructions really exact (the
//! referee's margin is 0 where a family promises touching).

use super::*;
use crate::check::run_caught;
use crate::engine::Answer;
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
fn generate_every_kind_has_uniform_and_biased_families() {
    for q in Query::ALL {
        assert!(GENERATED.contains(&q), "{q}");
        let (mut uniform, mut biased) = (0, 0);
        for f in families(q) {
            match is_biased(q, f) {
                Some(true) => biased += 1,
                Some(false) => uniform += 1,
                None => panic!("{q}: family {f:?} unknown"),
            }
        }
        assert!(uniform >= 1 && biased >= 1, "{q}: {uniform} uniform and {biased} biased families");
        assert!(try_generate(q, 1, 0).is_some() && family_for(q, 0).is_some(), "{q}");
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

/// The referee's `toi` answer to a generated case.
fn referee_toi(lc: &LoadedCase) -> oracle::geom::ToiAnswer {
    match run_caught(&crate::engines::referee(), lc) {
        Ok(Answer::Toi(t)) => t,
        other => panic!("{}: the referee gave {other:?}\n{}", lc.case.name, json(lc)),
    }
}

/// Cases drawn from one family by proptest's deterministic runner, loaded as
/// the campaign loads them.
fn draw(q: Query, name: &str, n: usize) -> Vec<LoadedCase> {
    let mut runner = TestRunner::deterministic();
    let s = family_strategy(q, name).unwrap_or_else(|| panic!("no family {name:?}"));
    (0..n).map(|_| loaded(s.new_tree(&mut runner).map(|t| t.current()).expect("no filters"))).collect()
}

#[test]
fn generate_toi_meshes_are_loaded_and_answered() {
    let mut meshes = 0;
    for i in 0..SWEEP {
        let lc = generate(Query::Toi, 5, i);
        if let Some(crate::case::Shape::Mesh(_)) = &lc.case.b {
            meshes += 1;
            assert!(lc.meshes[1].is_some(), "{}: mesh not loaded", lc.case.name);
            referee_toi(&lc);
        }
    }
    assert!(meshes >= 60, "only {meshes} mesh cases in {SWEEP}");
}

#[test]
fn generate_toi_exact_impacts_are_exact() {
    // The referee's time of every built impact is the construction's t*, a
    // multiple of 1/16 in (0, 2], exactly; the interval's end decides whether
    // it counts (no impact when it comes too late).
    for name in [
        "impact built exactly: spheres",
        "impact built exactly: sphere–plane",
        "impact built exactly: a triangle's face, edge or vertex",
        "impact built exactly: a box's face, edge or corner",
    ] {
        let (mut hits, mut at_end) = (0, 0);
        for lc in draw(Query::Toi, name, 150) {
            let answer = referee_toi(&lc);
            let Some(k) = answer.toi else { continue };
            hits += 1;
            let sixteenths = k.t * 16.0;
            assert!(
                sixteenths.fract() == 0.0 && (1.0..=32.0).contains(&sixteenths) && !answer.degenerate,
                "{name}: t = {:e}, not a built t*\n{}",
                k.t,
                json(&lc)
            );
            if lc.case.t_max().to_bits() == k.t.to_bits() {
                at_end += 1;
            }
        }
        assert!(hits >= 90 && at_end >= 20, "{name}: {hits} impacts, {at_end} exactly at t_max, of 150");
    }
}

/// The edge walker on `t_max` steps at most this many ULPs from the impact.
const T_MAX_WALK_ULPS: u64 = 8;

#[test]
fn generate_toi_t_max_walker_stays_within_a_few_ulps_of_the_impact() {
    let (mut hits, mut misses) = (0, 0);
    for lc in draw(Query::Toi, "edge walker: impact at t_max ± k ulps", 200) {
        match referee_toi(&lc).toi {
            Some(k) => {
                hits += 1;
                let tm = lc.case.t_max();
                let ulps = tm.to_bits().abs_diff(k.t.to_bits());
                assert!(k.t <= tm && ulps <= T_MAX_WALK_ULPS, "t = {:e}, t_max = {tm:e}\n{}", k.t, json(&lc));
            }
            None => misses += 1,
        }
    }
    // k ∈ [−8, 8]: about 9 in 17 reach the impact, 8 in 17 end too early.
    assert!(hits >= 60 && misses >= 50, "{hits} impacts, {misses} misses");
}

#[test]
fn generate_toi_tunneling_cases_are_over_by_the_end() {
    // Each is an impact the referee sees and the lecture's halving (which tests
    // the end of the interval) misses, nearly always.
    let lecture = crate::engines::judged().into_iter().find(|e| e.name == "collide/lecture").expect("engine");
    let (mut seen, mut missed) = (0, 0);
    for lc in draw(Query::Toi, "tunneling: small fast sphere through a thin target", 150) {
        if referee_toi(&lc).toi.is_some() {
            seen += 1;
            if matches!(run_caught(&lecture, &lc), Ok(Answer::Toi(t)) if t.toi.is_none()) {
                missed += 1;
            }
        }
    }
    assert!(seen >= 135 && missed * 10 >= seen * 9, "{seen} impacts, {missed} missed by halving, of 150");
}

#[test]
fn generate_toi_start_and_never_families_do_what_they_say() {
    let at_zero = draw(Query::Toi, "touching or overlapping at t = 0", 150)
        .iter()
        .filter(|lc| referee_toi(lc).toi.is_some_and(|k| k.t == 0.0))
        .count();
    // Exactly touching (one in four) may round a hair apart.
    assert!(at_zero >= 120, "{at_zero} of 150 in contact at t = 0");
    for lc in draw(Query::Toi, "no relative motion, receding or sliding", 150) {
        assert!(referee_toi(&lc).toi.is_none(), "an impact\n{}", json(&lc));
    }
}

#[test]
fn generate_response_cases_carry_masses_and_restitution() {
    for i in 0..SWEEP {
        let lc = generate(Query::Response, 3, i);
        let e = lc.case.restitution.unwrap_or(f64::NAN);
        assert!((0.0..=1.0).contains(&e), "{}: restitution {e}", lc.case.name);
        match run_caught(&crate::engines::referee(), &lc) {
            Ok(Answer::Response(r)) => {
                assert!(r.velocity_a.iter().chain(&r.velocity_b).all(|x| x.is_finite()), "{}", lc.case.name)
            }
            other => panic!("{}: the referee gave {other:?}", lc.case.name),
        }
    }
}

/// How far collide's answer to an exact head-on response may be from the
/// referee's, in ULPs of the largest velocity component involved: the impulse
/// is one division of short dyadics and the update two roundings more, so a
/// few ULPs; 8 leaves room for the cancellation `v·n` cannot have here (axis
/// normals: one product, exact).
const HEAD_ON_ULPS: f64 = 8.0;

#[test]
fn generate_response_exact_families_are_answered_by_collide_to_a_few_ulps() {
    let robust = crate::engines::judged().into_iter().find(|e| e.name == "collide/robust").expect("engine");
    let mut exact = 0;
    for lc in draw(Query::Response, "head-on along an axis, exact", 150) {
        let (Ok(Answer::Response(got)), Ok(Answer::Response(want))) =
            (run_caught(&robust, &lc), run_caught(&crate::engines::referee(), &lc))
        else {
            panic!("no answer\n{}", json(&lc));
        };
        let all = [lc.case.a.velocity(), lc.case.b.as_ref().map(crate::case::Shape::velocity).unwrap_or_default()];
        let speed =
            all.iter().chain([&want.velocity_a, &want.velocity_b]).flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let err = (0..3)
            .map(|k| (got.velocity_a[k] - want.velocity_a[k]).abs().max((got.velocity_b[k] - want.velocity_b[k]).abs()))
            .fold(0.0f64, f64::max);
        assert!(err <= HEAD_ON_ULPS * f64::EPSILON * speed, "error {err:e} at speed {speed}\n{}", json(&lc));
        exact += usize::from(err == 0.0);
    }
    // Masses whose inverse sum is a power of two (equal masses, say) make the
    // whole formula exact.
    assert!(exact >= 30, "only {exact} of 150 answered exactly");
}

/// The families of boxes and capsules, each drawn 400 times: every case is
/// valid input (finite numbers, positive radii, non-zero quaternions).
#[test]
fn generate_box_and_capsule_families_give_valid_input() {
    let families = [
        (Query::Contact, super::boxes::contact_families()),
        (Query::Intersect, super::boxes::intersect_families()),
        (Query::Bounds, super::boxes::bounds_families()),
        (Query::Overlap, super::boxes::overlap_families()),
    ];
    for (q, fams) in families {
        for f in fams {
            let s = family_strategy(q, f.name).unwrap_or_else(|| panic!("no family {:?}", f.name));
            let mut runner = TestRunner::deterministic();
            for _ in 0..400 {
                let case = s.new_tree(&mut runner).map(|t| t.current()).expect("no filters");
                assert!(validate(&case).is_ok(), "{}: {:?}", f.name, validate(&case));
            }
        }
    }
}
