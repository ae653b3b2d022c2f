//! Stability sweeps as evidence: across every sweep (every point of every
//! degeneracy parameter, a reduced number of poses), no collide method panics or
//! returns NaN; the robust methods stay within their documented error bounds;
//! the lecture methods' breaking points are reported, not hidden; and
//! `crashtest sweep` refuses an unknown sweep with the list of names.

use harness::case::Query;
use harness::check::{check_case, run_caught};
use harness::engines::EngineSet;
use harness::engines::{self, judged, referee};
use harness::judge::tolerance::Tolerance;
use harness::judge::{Verdict, judge, scene_scale};
use harness::sweep::{self, BreakWhy, Settings, SweepResult};
use std::sync::OnceLock;

/// Poses per point here: 8 — four exact and four rotated where a sweep
/// alternates them, enough for both sides of an edge to be met at every point —
/// so every point of every sweep is visited in a few seconds; the report runs
/// [`sweep::REPORT_POSES`].
const TEST_POSES: usize = 8;

const SETTINGS: Settings = Settings { poses: TEST_POSES, seed: sweep::DEFAULT_SEED };

const COLLIDE: [&str; 4] = ["collide/robust", "collide/lecture", "collide-f32/robust", "collide-f32/lecture"];

/// Where a robust method's values are known to leave the campaign's tolerance
/// in a sweep (each entry with a comment saying why). Classification must still hold there, and each gap is
/// pinned by a test below that fails once it closes (so this list never goes
/// stale).
struct Gap {
    sweep: &'static str,
    query: &'static str,
    engines: &'static [&'static str],
}

/// Empty: every gap the sweeps found has been closed; each left a regression
/// test below and a fixture in `fixtures/regressions/`.
const KNOWN_GAPS: &[Gap] = &[];

fn gap(sweep: &str, query: &str, engine: &str) -> bool {
    KNOWN_GAPS.iter().any(|g| g.sweep == sweep && g.query == query && g.engines.contains(&engine))
}

fn results() -> &'static [SweepResult] {
    static R: OnceLock<Vec<SweepResult>> = OnceLock::new();
    R.get_or_init(|| sweep::run_all(&SETTINGS, &Default::default()))
}

fn result(name: &str) -> &'static SweepResult {
    results().iter().find(|r| r.name == name).unwrap_or_else(|| panic!("{}", sweep::unknown_name(name)))
}

#[test]
fn no_collide_method_panics_or_returns_nan_at_any_sweep_point() {
    let mut seen = 0;
    for r in results() {
        for p in &r.probes {
            for s in p.engines.iter().filter(|s| COLLIDE.contains(&s.engine.as_str())) {
                for (pt, stats) in r.points.iter().zip(&s.points) {
                    seen += stats.cases;
                    assert_eq!(stats.panics, 0, "{} › {} › {} panics at {}", r.name, p.name, s.engine, pt.label);
                    assert_eq!(
                        stats.non_finite, 0,
                        "{} › {} › {} returns NaN at {}",
                        r.name, p.name, s.engine, pt.label
                    );
                    // collide's continuous collision is written in f64 only:
                    // its f32 builds answer no ccd case.
                    let f64_only = p.query == Query::Ccd && s.engine.starts_with("collide-f32/");
                    if f64_only {
                        assert_eq!(stats.unsupported, stats.cases, "{} › {} › {}", r.name, p.name, s.engine);
                    } else {
                        assert_eq!(
                            stats.unsupported, 0,
                            "{} › {} › {} answers at {}",
                            r.name, p.name, s.engine, pt.label
                        );
                    }
                }
            }
        }
    }
    assert!(seen > 20_000, "every sweep point was visited: {seen} case runs");
}

#[test]
fn collide_robust_stays_within_the_campaign_tolerance_at_every_sweep_point() {
    // The documented bound is the campaign's: the tolerance table
    // (`tolerance::F64_REL`, `F64_NORMAL_RAD`, `F64_BARY`) with its conditioning
    // allowances for normals and barycentrics, and classifications as the
    // referee's except within the tolerance band of its decision boundary.
    for r in results() {
        for p in &r.probes {
            let s = p.engines.iter().find(|s| s.engine == "collide/robust").expect("collide/robust is judged");
            for (pt, stats) in r.points.iter().zip(&s.points) {
                let at = format!("{} › {} at {}", r.name, p.name, pt.label);
                assert_eq!(stats.misclassified_outside_band(), 0, "{at}: misclassified beyond the band");
                if !gap(&r.name, &p.name, &s.engine) {
                    assert_eq!(stats.beyond_tolerance(), 0, "{at}: an error beyond the tolerance ({:?})", stats.max);
                }
            }
        }
    }
}

#[test]
fn collide_f32_robust_stays_within_the_f32_tolerance_of_its_rounded_input() {
    // An f32 engine first rounds its input to f32 (the adapter does), and no
    // method can recover what that rounding loses: on a sliver or far from the
    // origin the rounded scene is another scene. So the bound of the f32 robust
    // method is the f32 entry of the tolerance table (`tolerance::F32_REL`,
    // `F32_NORMAL_RAD`, `F32_BARY`, conditioning in f32's epsilon) against the
    // referee's answer to the rounded case: it judges the method's arithmetic,
    // not its input format. (Against the f64 case it is charted in the report.)
    let engines = judged();
    let f32_robust = engines.iter().find(|e| e.name == "collide-f32/robust").expect("judged");
    let referee = referee();
    let tol = Tolerance::for_precision(f32_robust.precision);
    let mut judged_cases = 0;
    let mut outside = std::collections::BTreeMap::new();
    for s in sweep::SWEEPS {
        if s.probes.iter().all(|p| p.query == Query::Ccd) {
            // collide's continuous collision is f64 only: no f32 answer to judge.
            continue;
        }
        for c in sweep::cases(s, &SETTINGS) {
            let rounded = sweep::rounded_to_f32(&c.case);
            let probe = s.probes[c.probe].name;
            let truth = run_caught(&referee, &rounded).unwrap_or_else(|v| panic!("{}: {v:?}", c.case.case.name));
            let answer = run_caught(f32_robust, &c.case).unwrap_or_else(|v| panic!("{}: {v:?}", c.case.case.name));
            let scale = scene_scale(&rounded);
            let margin = engines::referee::margin(&rounded).map(|m| m / scale);
            let (verdict, errors) = judge(&rounded, &answer, &truth, &tol, margin);
            judged_cases += 1;
            match verdict {
                Verdict::Agree | Verdict::Borderline { .. } => {}
                Verdict::Disagree { .. } if errors.misclass.is_none() && gap(s.name, probe, &f32_robust.name) => {}
                other => {
                    outside.entry((s.name, probe)).or_insert_with(|| format!("{}: {other:?}", c.case.case.name));
                }
            }
        }
    }
    assert!(judged_cases > 3_000, "{judged_cases} cases");
    // collide's robust distance takes a box exactly (its quaternion's own
    // rotation, as the referee does): rounded to f32, box–box faces 1e-16
    // apart in a rotated pose (`distance-kissing`) and a flat box face down
    // over a box in a rotated pose (`distance-aspect`) are exactly parallel
    // for both, and flagged.
    let unexpected: Vec<&String> = outside.values().collect();
    assert!(unexpected.is_empty(), "outside the f32 bound (first case per sweep and query):\n{unexpected:#?}");
}

#[test]
fn the_lecture_methods_break_where_the_robust_ones_do_not_and_the_table_says_so() {
    // What the sweeps show (seed and poses above), asserted as it is:
    // - angle: the lecture's t = n·(v0 − p0) / n·(p1 − p0) loses digits as
    //   1/sin θ; its error passes 1e-6 of the scene near 1e-10 rad;
    // - edge and vertex: the lecture's s–t test rounds, so crossings within an
    //   ulp or so of an edge or a vertex are called on the wrong side;
    // - collide/robust (exact predicates) never breaks on these three.
    let table = sweep::breaking_table(results());
    let cell = |sweep: &str, query: &str, engine: &str| {
        let col = table.header.iter().position(|h| h == engine).expect("engine column");
        table
            .rows
            .iter()
            .find(|r| r[0] == sweep && r[1] == query)
            .map(|r| r[col].clone())
            .unwrap_or_else(|| panic!("no row {sweep} › {query}"))
    };
    let lecture_break = |sweep: &str, query: &str| {
        let r = result(sweep);
        let p = r.probes.iter().find(|p| p.name == query).expect("probe");
        let s = p.engines.iter().find(|s| s.engine == "collide/lecture").expect("lecture");
        s.walks[0].breaks_at.clone().unwrap_or_else(|| panic!("collide/lecture does not break on {sweep} › {query}"))
    };
    for query in ["segment–plane", "segment–triangle"] {
        let b = lecture_break("angle", query);
        assert!(b.value > 1e-13 && b.value < 1e-6, "angle › {query}: lecture breaks at {}", b.label);
        assert!(matches!(b.why, BreakWhy::Error { .. }), "by its error: {:?}", b.why);
        assert_eq!(cell("angle", query, "collide/lecture"), format!("{} (error)", b.label), "reported");
        assert_eq!(cell("angle", query, "collide/robust"), "none");
    }
    for sweep in ["edge", "vertex"] {
        let b = lecture_break(sweep, "segment–triangle");
        assert!(b.value < 1e-12, "{sweep}: lecture breaks at {}", b.label);
        assert!(matches!(b.why, BreakWhy::Misclassified { .. }), "{sweep}: by a misclassification: {:?}", b.why);
        assert_eq!(cell(sweep, "segment–triangle", "collide/lecture"), format!("{} (misclass)", b.label));
        assert_eq!(cell(sweep, "segment–triangle", "collide/robust"), "none");
    }
    let section = sweep::section_from(results(), &SETTINGS);
    assert!(section.html.starts_with("<div class=\"scroll\"><table>"), "the section opens with the table");
    let in_report = sweep::SWEEPS.iter().filter(|s| !sweep::standalone(s.name)).count();
    assert_eq!(section.charts.len(), in_report, "one chart per sweep of the report");
}

#[test]
fn the_lecture_ccd_breaks_at_its_tolerances_and_the_robust_ccd_never() {
    // What the ccd sweeps show (seed and poses above), asserted as it is:
    // - ccd-edge, outside: the lecture's inside test admits barycentrics down
    //   to −1e-6 (its LECTURE_INSIDE_TOL), so a point passing a few millionths
    //   outside an edge (the triangles' heights are 4–6) is a false impact;
    // - ccd-parallel: edges within 1e-6 rad of parallel (its
    //   LECTURE_PARALLEL_TOL, a squared sine of 1e-12) are treated as
    //   parallel, and the crossing is missed;
    // - collide/robust (exact polynomials in t) never breaks on either.
    let walk = |sweep: &str, query: &str, engine: &str| {
        let r = result(sweep);
        let p = r.probes.iter().find(|p| p.name == query).expect("probe");
        let s = p.engines.iter().find(|s| s.engine == engine).expect("engine");
        s.walks[0].breaks_at.clone()
    };
    for (sweep, query) in
        [("ccd-edge", "vertex–face outside"), ("ccd-edge", "vertex–face inside"), ("ccd-parallel", "edge–edge")]
    {
        assert_eq!(walk(sweep, query, "collide/robust"), None, "collide/robust breaks on {sweep} › {query}");
    }
    let b = walk("ccd-edge", "vertex–face outside", "collide/lecture").expect("the lecture breaks");
    assert!((1e-6..=1e-5).contains(&b.value), "ccd-edge: the lecture breaks at {}", b.label);
    assert!(matches!(b.why, BreakWhy::Misclassified { .. }), "by a false impact: {:?}", b.why);
    let b = walk("ccd-parallel", "edge–edge", "collide/lecture").expect("the lecture breaks");
    assert!((1e-7..=1e-6).contains(&b.value), "ccd-parallel: the lecture breaks at {}", b.label);
    assert!(matches!(b.why, BreakWhy::Misclassified { .. }), "by a missed impact: {:?}", b.why);
}

/// The cases of one sweep point, one query, one pose, with the report's poses.
fn pinned(sweep_name: &str, query: &str, label: &str, pose: usize) -> harness::load::LoadedCase {
    let s = sweep::find(sweep_name).expect("sweep");
    let point = s.points().iter().position(|p| p.label == label).expect("point");
    let probe = s.probes.iter().position(|p| p.name == query).expect("probe");
    sweep::cases(s, &Settings { poses: sweep::DEFAULT_POSES, seed: sweep::DEFAULT_SEED })
        .into_iter()
        .find(|c| c.point == point && c.probe == probe && c.pose == pose)
        .map(|c| c.case)
        .expect("case")
}

fn robust_verdict(lc: &harness::load::LoadedCase) -> Verdict {
    let r = check_case(lc, &EngineSet::default());
    r.engines.into_iter().find(|e| e.engine == "collide/robust").map(|e| e.verdict).expect("judged")
}

#[test]
fn sliver_sphere_triangle_contact_agrees_on_a_rotated_sliver_at_1e_15() {
    // Pose 17 (rotated) of the report's sliver sweep at 1e-15, once a known
    // gap: the book's region tests, on rounded values, called the centre's
    // projection inside the sliver, and the face answer M − n·d was 1.1e-2
    // off the triangle, its normal 2.4e-2 rad off. collide now certifies the
    // region (its edge tests against a rigorous bound, else the exact
    // barycentric signs). Fixture:
    // fixtures/regressions/contact_sphere_triangle_rotated_sliver_projection_outside.json.
    let lc = pinned("sliver", "sphere–triangle", "1e-15", 17);
    let v = robust_verdict(&lc);
    assert!(matches!(v, Verdict::Agree), "collide/robust on {}: {v:?}", lc.case.name);
}

#[test]
fn offset_toi_sphere_plane_agrees_1e12_from_the_origin() {
    // 1e12 from the origin the closed form's signed distance cancels values of
    // the scene's size: t is off by about ε · 1e12 / speed. That is the
    // problem's own conditioning (moving the inputs by their rounding moves the
    // impact as much), which the judge allows for a time of impact
    // (`judge::toi_allowance`); it was a sweep gap while the judge held t to a
    // fraction of t_max whatever the scene's scale.
    let lc = pinned("offset", "toi sphere–plane", "1e12", 0);
    let v = robust_verdict(&lc);
    assert!(matches!(v, Verdict::Agree), "{v:?}");
}

#[test]
fn f32_sphere_triangle_contact_agrees_under_a_sphere_1e4_times_the_triangle() {
    // Pose 0 (rotated) of the size-ratio sweep at 1e4, judged as the f32 test
    // above judges: against the referee's answer to the f32-rounded case. Once
    // a known gap: the f32 region tests cancelled and picked a wrong feature,
    // putting the point 1.1 off (1.1e-4 of the scene); collide-f32 now answers
    // in f64 on the widened inputs. Fixture:
    // fixtures/regressions/contact_sphere_triangle_f32_under_a_huge_sphere.json.
    let lc = pinned("size-ratio", "sphere–triangle", "1e4", 0);
    let rounded = sweep::rounded_to_f32(&lc);
    let engines = judged();
    let f32_robust = engines.iter().find(|e| e.name == "collide-f32/robust").expect("judged");
    let truth = run_caught(&referee(), &rounded).expect("referee answers");
    let answer = run_caught(f32_robust, &lc).expect("collide answers");
    let tol = Tolerance::for_precision(f32_robust.precision);
    let (v, _) = judge(&rounded, &answer, &truth, &tol, None);
    assert!(matches!(v, Verdict::Agree), "collide-f32/robust on {}: {v:?}", lc.case.name);
}
