//! The sweeps' construction: grids, walks, poses, determinism, and that each
//! sweep's exact poses really sit at the nominal parameter (checked with the
//! referee, which takes the case's numbers as exact).

use super::*;
use crate::case::Query;
use crate::engine::Answer;
use crate::engines;
use crate::judge::scene_scale;
use crate::sweep::grid::PoseKind;

fn sweep(name: &str) -> &'static Sweep {
    find(name).unwrap_or_else(|| panic!("{}", unknown_name(name)))
}

/// The referee's answer to every exact-pose case of `probe` at the point
/// labelled `label`.
fn referee_at(name: &str, probe: usize, label: &str, poses: usize) -> Vec<Answer> {
    let s = sweep(name);
    let point = s.points().iter().position(|p| p.label == label).unwrap_or_else(|| panic!("{name}: no point {label}"));
    let referee = engines::referee();
    cases(s, &Settings { poses, seed: 3 })
        .into_iter()
        .filter(|c| c.probe == probe && c.point == point && c.kind == PoseKind::Exact)
        .map(|c| referee.run(&c.case).unwrap_or_else(|e| panic!("{}: referee refused: {e}", c.case.case.name)))
        .collect()
}

#[test]
fn every_sweep_has_ten_points_per_decade_over_its_whole_range() {
    for s in SWEEPS {
        let pts = s.points();
        let grid: Vec<&SweepPoint> = pts.iter().filter(|p| !p.exact).collect();
        assert_eq!(grid.len(), 10 * (s.hi - s.lo) as usize + 1, "{}", s.name);
        let decade = |k: i32| if k == 0 { "1".to_string() } else { format!("1e{k}") };
        assert_eq!(grid[0].label, decade(s.lo), "{} starts at its lowest decade", s.name);
        assert_eq!(grid[grid.len() - 1].label, decade(s.hi), "{} ends at its highest decade", s.name);
        assert!(pts.windows(2).all(|w| w[0].value < w[1].value), "{}: ascending", s.name);
        assert_eq!(pts.iter().filter(|p| p.exact).count(), usize::from(s.exact.is_some()), "{}", s.name);
    }
}

#[test]
fn the_sweeps_the_issue_asks_for_cover_its_ranges() {
    let range = |n: &str| (sweep(n).lo, sweep(n).hi, sweep(n).exact.is_some());
    assert_eq!(range("angle"), (-16, 0, true), "angle: 1 → 1e-16 rad, and exactly parallel");
    assert_eq!(range("edge"), (-17, 0, true), "edge: 1 → 1e-17, and exactly on");
    assert_eq!(range("vertex"), (-17, 0, true), "vertex: 1 → 1e-17, and exactly on");
    assert_eq!(range("sliver"), (-15, 0, true), "sliver: 1 → 1e-15");
    assert_eq!(range("offset"), (0, 15, false), "offset: 1 → 1e15");
    assert_eq!(range("concentric"), (-16, 0, true), "concentric: → 0");
    assert_eq!(range("grazing"), (-16, 0, true), "grazing: 1 → 1e-16");
    assert_eq!(range("size-ratio"), (-8, 8, false), "size ratio: 1e-8 → 1e8");
    assert_eq!(range("ccd-edge"), (-30, 0, true), "ccd edge: 1 → 1e-30, and exactly through the edge");
    assert_eq!(range("ccd-parallel"), (-30, 0, true), "ccd parallel: 1 → 1e-30 rad, and exactly parallel");
    let offset_queries: std::collections::BTreeSet<Query> = sweep("offset").probes.iter().map(|p| p.query).collect();
    for q in [Query::Contact, Query::Intersect, Query::Barycentric, Query::Bounds, Query::Overlap, Query::Toi] {
        assert!(offset_queries.contains(&q), "offset asks {q}");
    }
}

#[test]
fn walks_run_from_the_benign_point_to_each_degenerate_end() {
    let angle = sweep("angle");
    let w = angle.walks();
    assert_eq!(w.len(), 1);
    assert_eq!(angle.points()[w[0][0]].label, "1", "starts at 1 rad");
    assert!(angle.points()[*w[0].last().expect("non-empty")].exact, "ends exactly parallel");
    let offset = sweep("offset").walks();
    assert_eq!((offset.len(), offset[0][0]), (1, 0), "offset walks up from 1");
    let ratio = sweep("size-ratio");
    let w = ratio.walks();
    assert_eq!(w.len(), 2, "size ratio degenerates both ways");
    let pts = ratio.points();
    assert_eq!((pts[w[0][0]].label.as_str(), pts[*w[0].last().expect("non-empty")].label.as_str()), ("1", "1e-8"));
    assert_eq!((pts[w[1][0]].label.as_str(), pts[*w[1].last().expect("non-empty")].label.as_str()), ("1", "1e8"));
}

#[test]
fn poses_alternate_and_exact_points_take_exact_poses_only() {
    let s = sweep("edge");
    let all = cases(s, &Settings { poses: 4, seed: 1 });
    assert_eq!(all.len(), s.points().len() * 4);
    for c in &all {
        let want = if s.points()[c.point].exact || c.pose % 2 == 0 { PoseKind::Exact } else { PoseKind::Rotated };
        assert_eq!(c.kind, want, "{}", c.case.case.name);
    }
    assert!(cases(sweep("offset"), &Settings { poses: 2, seed: 1 }).iter().all(|c| c.kind == PoseKind::Rotated));
}

#[test]
fn the_same_seed_gives_the_same_cases_and_another_seed_others() {
    for s in SWEEPS {
        let json = |seed| {
            let cs: Vec<crate::case::Case> =
                cases(s, &Settings { poses: 2, seed }).into_iter().map(|c| c.case.case).collect();
            serde_json::to_string(&cs).expect("serializes")
        };
        assert_eq!(json(9), json(9), "{}: deterministic", s.name);
        assert_ne!(json(9), json(10), "{}: the seed matters", s.name);
    }
}

#[test]
fn a_pose_is_the_same_scene_family_at_every_point() {
    // Common random numbers: the triangle of the edge sweep's pose 0 does not
    // depend on the distance.
    let s = sweep("edge");
    let all = cases(s, &Settings { poses: 2, seed: 5 });
    let tri = |point: usize| {
        all.iter()
            .find(|c| c.point == point && c.pose == 0)
            .map(|c| serde_json::to_string(&c.case.case.b).expect("serializes"))
    };
    assert_eq!(tri(1), tri(100), "same triangle at 1e-17 and at 1e-7");
}

#[test]
fn every_case_is_valid_input_for_the_referee() {
    let referee = engines::referee();
    for s in SWEEPS {
        for c in cases(s, &Settings { poses: 2, seed: 11 }).iter().step_by(7) {
            assert!(referee.run(&c.case).is_ok(), "{}: refused", c.case.case.name);
        }
    }
}

#[test]
fn exact_poses_tell_inside_from_outside_even_1e_17_from_an_edge() {
    // Rounded away, every crossing would sit exactly on the edge and hit
    // (touching counts): misses prove δ = 1e-17 survives.
    let answers = referee_at("edge", 0, "1e-17", 16);
    let hits = answers.iter().filter(|a| matches!(a, Answer::Intersect(i) if i.hit.is_some())).count();
    assert!(hits > 0 && hits < answers.len(), "{hits} hits of {}", answers.len());
    let on = referee_at("edge", 0, "exactly on the edge", 8);
    assert!(on.iter().all(|a| matches!(a, Answer::Intersect(i) if i.hit.is_some())), "exactly on hits");
}

#[test]
fn exact_poses_tell_inside_from_outside_even_1e_17_from_a_vertex() {
    let answers = referee_at("vertex", 0, "1e-17", 16);
    let hits = answers.iter().filter(|a| matches!(a, Answer::Intersect(i) if i.hit.is_some())).count();
    assert!(hits > 0 && hits < answers.len(), "{hits} hits of {}", answers.len());
    let on = referee_at("vertex", 0, "exactly on the vertex", 8);
    assert!(on.iter().all(|a| matches!(a, Answer::Intersect(i) if i.hit.is_some())), "exactly on hits");
}

#[test]
fn exact_poses_keep_a_1e_16_angle_crossing_and_exactly_parallel_parallel() {
    for probe in 0..2 {
        for a in referee_at("angle", probe, "1e-16", 8) {
            assert!(matches!(&a, Answer::Intersect(i) if !i.parallel && i.hit.is_some()), "{a:?}");
        }
        for a in referee_at("angle", probe, "exactly parallel", 8) {
            assert!(matches!(&a, Answer::Intersect(i) if i.parallel && i.hit.is_none()), "{a:?}");
        }
    }
}

#[test]
fn exact_poses_keep_a_1e_15_sliver_a_triangle_and_exactly_flat_degenerate() {
    for a in referee_at("sliver", 0, "1e-15", 8) {
        assert!(matches!(&a, Answer::Barycentric(b) if !b.degenerate && b.coords.iter().all(|x| *x > 0.0)), "{a:?}");
    }
    for a in referee_at("sliver", 0, "exactly flat", 8) {
        assert!(matches!(&a, Answer::Barycentric(b) if b.degenerate), "{a:?}");
    }
    for a in referee_at("sliver", 1, "1e-15", 8) {
        assert!(matches!(&a, Answer::Intersect(i) if i.hit.is_some()), "the segment crosses inside: {a:?}");
    }
}

#[test]
fn exact_poses_keep_spheres_1e_16_apart_non_concentric_and_0_concentric() {
    for a in referee_at("concentric", 0, "1e-16", 8) {
        assert!(matches!(&a, Answer::Contact(c) if !c.degenerate && c.contact.is_some()), "{a:?}");
    }
    for a in referee_at("concentric", 0, "exactly concentric", 8) {
        assert!(matches!(&a, Answer::Contact(c) if c.degenerate), "{a:?}");
    }
}

#[test]
fn grazing_gaps_are_the_nominal_ones_in_exact_poses() {
    /// A gap of 1e-6 in coordinates of about 3 rounds by at most half an ulp of
    /// 4 (4.4e-16), so the depth is 1e-6 to within 1e-9 of itself.
    const GAP_REL_TOL: f64 = 1e-9;
    for a in referee_at("grazing", 0, "1e-6", 8) {
        assert!(matches!(&a, Answer::Contact(c) if c.contact.is_none()), "apart: {a:?}");
    }
    for a in referee_at("grazing", 1, "1e-6", 8) {
        let depth = match &a {
            Answer::Contact(c) => c.contact.map(|k| k.depth),
            _ => None,
        };
        let d = depth.unwrap_or_else(|| panic!("overlapping: {a:?}"));
        assert!((d - 1e-6).abs() <= GAP_REL_TOL * 1e-6, "depth {d:e}");
    }
    for probe in 0..2 {
        for a in referee_at("grazing", probe, "exactly touching", 8) {
            assert!(matches!(&a, Answer::Contact(c) if c.contact.is_some_and(|k| k.depth == 0.0)), "{a:?}");
        }
    }
}

/// The referee's ccd answers of the exact poses at a point: (time, degenerate).
fn ccd_at(name: &str, probe: usize, label: &str) -> Vec<(Option<f64>, bool)> {
    referee_at(name, probe, label, 16)
        .into_iter()
        .map(|a| match a {
            Answer::Ccd(c) => (c.t, c.degenerate),
            other => panic!("not a ccd answer: {other:?}"),
        })
        .collect()
}

/// Where the sweeps put the crossing time: `t*` in `[1/4, 3/4]`, to within the
/// rounding of the positions (a few ulps).
fn at_crossing_time(t: Option<f64>) -> bool {
    t.is_some_and(|t| (0.25 - 1e-12..=0.75 + 1e-12).contains(&t))
}

#[test]
fn exact_poses_pass_a_point_1e_30_outside_or_inside_an_edge_and_exactly_through_it() {
    // Outside: no impact even 1e-30 from the edge; inside: the impact at t*;
    // exactly through: the closed triangle's edge is hit at t*.
    for (label, outside_hits) in [("1", false), ("1e-17", false), ("1e-30", false), ("exactly through the edge", true)]
    {
        for (t, degenerate) in ccd_at("ccd-edge", 0, label) {
            assert_eq!(t.is_some(), outside_hits, "outside at {label}: {t:?}");
            assert!(!degenerate, "outside at {label}");
            assert!(t.is_none() || at_crossing_time(t), "outside at {label}: {t:?}");
        }
        for (t, degenerate) in ccd_at("ccd-edge", 1, label) {
            assert!(at_crossing_time(t) && !degenerate, "inside at {label}: {t:?}");
        }
    }
}

#[test]
fn exact_poses_cross_edges_1e_30_rad_apart_and_exactly_parallel_ones_degenerately() {
    for label in ["1", "1e-8", "1e-30"] {
        for (t, degenerate) in ccd_at("ccd-parallel", 0, label) {
            assert!(at_crossing_time(t) && !degenerate, "at {label}: {t:?}, degenerate {degenerate}");
        }
    }
    for (t, degenerate) in ccd_at("ccd-parallel", 0, "exactly parallel") {
        assert!(at_crossing_time(t) && degenerate, "exactly parallel: {t:?}, degenerate {degenerate}");
    }
}

#[test]
fn offset_and_size_ratio_set_the_scene_scale() {
    let s = sweep("offset");
    let at = |label: &str| s.points().iter().position(|p| p.label == label).expect("point");
    for c in cases(s, &Settings { poses: 4, seed: 2 }) {
        let scale = scene_scale(&c.case);
        if c.point == at("1e15") {
            assert!((2e14..=1e15 + 1e3).contains(&scale), "{}: scale {scale:e}", c.case.case.name);
        }
    }
    let r = sweep("size-ratio");
    let big = r.points().iter().position(|p| p.label == "1e8").expect("point");
    for c in cases(r, &Settings { poses: 2, seed: 2 }).iter().filter(|c| c.point == big && c.probe != 1) {
        assert!(scene_scale(&c.case) >= 1e7, "{}", c.case.case.name);
    }
}

#[test]
fn rounding_to_f32_rounds_every_number() {
    let c = &cases(sweep("offset"), &Settings { poses: 1, seed: 4 })[0];
    let r = rounded_to_f32(&c.case);
    let text = serde_json::to_string(&r.case).expect("serializes");
    let v: serde_json::Value = serde_json::from_str(&text).expect("parses");
    fn check(v: &serde_json::Value) {
        match v {
            serde_json::Value::Number(n) => {
                let x = n.as_f64().expect("a number");
                assert_eq!((x as f32 as f64).to_bits(), x.to_bits(), "{x} is an f32");
            }
            serde_json::Value::Array(a) => a.iter().for_each(check),
            serde_json::Value::Object(o) => o.values().for_each(check),
            _ => {}
        }
    }
    check(&v["a"]);
    check(&v["b"]);
}

#[test]
fn an_unknown_name_is_refused_with_every_name() {
    let msg = unknown_name("tilt");
    assert!(msg.contains("`tilt`"));
    for n in names() {
        assert!(msg.contains(n), "{msg} names {n}");
    }
    assert!(find("tilt").is_none());
    assert_eq!(list_text().lines().count(), SWEEPS.len());
}

#[test]
fn the_section_opens_with_the_breaking_point_table_and_has_a_chart_per_sweep() {
    let settings = Settings { poses: 1, seed: 6 };
    let results: Vec<SweepResult> =
        ["grazing", "concentric"].iter().map(|n| run(sweep(n), &settings, &Default::default())).collect();
    let s = section_from(&results, &settings);
    assert_eq!(s.id, SECTION_ID);
    assert!(s.html.starts_with("<div class=\"scroll\"><table>"), "opens with the table: {}", &s.html[..80]);
    for engine in ["collide/robust", "collide/lecture", "collide-f32/robust", "collide-f32/lecture", "parry3d-f64"] {
        assert!(s.html.contains(&format!("<th>{engine}</th>")), "column for {engine}");
    }
    assert!(s.markdown.starts_with(&format!("## {}\n", s.title)));
    assert_eq!(s.charts.len(), 2, "one chart per sweep");
    assert!(s.charts.iter().all(|c| c.file.starts_with("stability-") && c.svg.starts_with("<svg")));
    assert_eq!(s.data["sweeps"].as_array().map(Vec::len), Some(2), "the data holds both sweeps");
    assert_eq!(s, section_from(&results, &settings), "pure");
}

#[test]
fn a_failure_is_drawn_as_its_own_mark() {
    let settings = Settings { poses: 1, seed: 6 };
    let mut r = run(sweep("grazing"), &settings, &Default::default());
    for s in r.probes.iter_mut().flat_map(|p| p.engines.iter_mut()).flat_map(|e| e.points.iter_mut()) {
        (s.panics, s.non_finite, s.false_positives, s.false_negatives, s.flags) = (0, 0, 0, 0, 0);
    }
    assert!(!chart(&r, None).svg.contains("× above the plot"), "no failure, no mark");
    r.probes[0].engines[1].points[3].false_negatives = 1;
    assert!(chart(&r, None).svg.contains("× above the plot"), "one failure, its mark");
}

#[test]
fn the_table_cell_names_the_value_and_the_reason() {
    let settings = Settings { poses: 1, seed: 6 };
    let mut r = run(sweep("concentric"), &settings, &Default::default());
    let lecture = &mut r.probes[0].engines[1];
    lecture.walks[0].breaks_at = Some(Break {
        point: 5,
        value: 2.5e-9,
        label: "2.5e-9".into(),
        why: BreakWhy::Misclassified { count: 1, of: 1 },
    });
    let t = breaking_table(std::slice::from_ref(&r));
    assert_eq!(t.rows[0][3], "2.5e-9 (misclass)");
    let text = table_text(std::slice::from_ref(&r));
    assert!(text.contains("2.5e-9 (misclass)") && text.starts_with("sweep"));
}
