//! The referee's floating-point stages change nothing: on every fixture, every
//! stability-sweep point (its default poses), the campaign's random cases of
//! every query kind (ordinary and full-range), and families built to force the
//! exact stage (clouds with a point one ulp outside the floating-point ball,
//! meshes touched exactly), each answer and margin is the same bit for bit
//! with the stages on as with the exact stage alone
//! (`oracle::referee::exact_only`).
//!
//! `cargo test` runs [`DEFAULT_RANDOM`] random cases. The documented run of a
//! million (docs/tests.md):
//!
//! ```sh
//! CRASHTEST_STAGE_CASES=1000000 cargo test --release --test referee_stages
//! ```

use harness::case::{
    Case, MeshSpec, PlaneSpec, PointSpec, PointsSpec, Query, SegmentSpec, Shape, SphereSpec, TriangleSpec,
};
use harness::check::run_caught;
use harness::engines::{self, referee};
use harness::generate::{generate, loaded, try_generate_full_range};
use harness::load::{LoadedCase, load_paths};
use harness::report::campaign::CAMPAIGN_QUERIES;
use oracle::referee::{Stage, exact_only, stage_counts_on_this_thread};

/// Random cases in `cargo test`, over the campaign's query kinds (a tenth of
/// them full-range).
const DEFAULT_RANDOM: u64 = 100_000;

/// Poses per point of the standalone sweeps here: every probe and point,
/// in an exact and a rotated pose.
const STANDALONE_POSES: usize = 2;

/// Seed of the random cases (the campaign's default).
const SEED: u64 = harness::defaults::DEFAULT_SEED;

/// The referee's answer, margin and contact region as exact text: `{:?}`
/// prints every `f64` with the shortest digits that read back to the same
/// bits, and `-0.0` as such; the margin is compared by its bits. The region
/// (a box's or a capsule's touching set, which the judge measures a contact
/// point against) has its own apart stage.
fn verdict(r: &harness::engine::Engine, lc: &LoadedCase) -> (String, Option<u64>, String) {
    let answer = run_caught(r, lc);
    let region = match &answer {
        Ok(a) => format!("{:?}", harness::judge::sizes::local(lc, a).region),
        Err(_) => String::new(),
    };
    (format!("{answer:?}"), referee::margin(lc).map(f64::to_bits), region)
}

/// The cases that differ between the stages, named, on two threads (the
/// switch is per thread).
fn differences(cases: &[LoadedCase]) -> Vec<String> {
    let half = cases.len().div_ceil(2).max(1);
    std::thread::scope(|scope| {
        let handles: Vec<_> = cases
            .chunks(half)
            .map(|chunk| {
                scope.spawn(move || {
                    let r = engines::referee();
                    chunk
                        .iter()
                        .filter_map(|lc| {
                            let staged = verdict(&r, lc);
                            let exact = exact_only(|| verdict(&r, lc));
                            (staged != exact)
                                .then(|| format!("{}: staged {:?}, exact {:?}", lc.case.source, staged, exact))
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().expect("thread")).collect()
    })
}

fn assert_same(what: &str, cases: &[LoadedCase]) {
    let diffs = differences(cases);
    assert!(
        diffs.is_empty(),
        "{what}: {} of {} cases differ between the stages, first: {}",
        diffs.len(),
        cases.len(),
        diffs[0]
    );
}

/// The cases' answers and margins are the same with the stages as without
/// ([`assert_same`]), and each case's answer came from the stage it names:
/// `true`, the floating-point stage `stage` (once); `false`, the exact stage.
fn assert_staged(what: &str, stage: Stage, cases: &[(bool, LoadedCase)]) {
    let loaded: Vec<LoadedCase> = cases.iter().map(|(_, lc)| lc.clone()).collect();
    assert_same(what, &loaded);
    let r = engines::referee();
    for (fast, lc) in cases {
        let before = stage_counts_on_this_thread();
        run_caught(&r, lc).expect("the referee answers");
        let (exact, by_fast) = delta(&before, &stage_counts_on_this_thread(), stage);
        assert_eq!((by_fast, exact), (u64::from(*fast), u64::from(!*fast)), "{}", lc.case.source);
    }
}

fn case(query: Query, a: Shape, b: Option<Shape>, source: String) -> LoadedCase {
    loaded(Case {
        name: source.clone(),
        source,
        query,
        a,
        b,
        expect: None,
        tol: None,
        t_max: Some(1.0),
        restitution: None,
    })
}

#[test]
fn every_fixture_and_sweep_point_is_the_same_with_the_stages() {
    let fixtures = load_paths(&[std::path::PathBuf::from("fixtures")]);
    assert!(fixtures.errors.is_empty(), "{:?}", fixtures.errors);
    assert!(fixtures.cases.len() > 200, "the fixtures: {}", fixtures.cases.len());
    assert_same("fixtures", &fixtures.cases);
    // The sweeps the report runs, at their default poses; the standalone
    // ones (`sweep::STANDALONE`: too costly for the report) at two poses.
    let settings = harness::sweep::Settings::default();
    let few = harness::sweep::Settings { poses: STANDALONE_POSES, ..settings };
    let sweeps: Vec<LoadedCase> = harness::sweep::SWEEPS
        .iter()
        .flat_map(|s| harness::sweep::cases(s, if harness::sweep::standalone(s.name) { &few } else { &settings }))
        .map(|c| c.case)
        .collect();
    assert!(!sweeps.is_empty());
    assert_same("stability sweep points", &sweeps);
}

#[test]
fn random_cases_are_the_same_with_the_stages() {
    let total: u64 = std::env::var("CRASHTEST_STAGE_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(DEFAULT_RANDOM);
    let per_kind = total / CAMPAIGN_QUERIES.len() as u64;
    let full = per_kind / 10;
    for q in CAMPAIGN_QUERIES {
        let mut cases: Vec<LoadedCase> = (0..per_kind - full).map(|i| generate(q, SEED, i)).collect();
        cases.extend((0..full).filter_map(|i| try_generate_full_range(q, SEED, i)));
        assert_same(&format!("{q} ({} cases)", cases.len()), &cases);
    }
}

/// Clouds with a point a few ulps outside the ball of the others, which the
/// floating-point stage lets in: its candidate fails the certificate and the
/// exact stage answers, the same ball.
#[test]
fn clouds_that_force_the_exact_stage_are_the_same() {
    let mut cases = Vec::new();
    for k in 1..=200u32 {
        let s = 2f64.powi(k as i32 % 61 - 30);
        let bump = 1.0 + f64::from(k % 7 + 1) * f64::EPSILON;
        let points =
            vec![[s, 0.0, 0.0], [-s, 0.0, 0.0], [0.0, s * bump, 0.0], [0.0, 0.0, -s * 0.5], [0.25 * s, 0.5 * s, 0.0]];
        let a = Shape::Points(PointsSpec { points });
        cases.push(case(Query::Bounds, a, None, format!("cloud {k}: a point {} ulps out", k % 7 + 1)));
    }
    assert_same("clouds one ulp out", &cases);
    let r = engines::referee();
    for lc in &cases {
        let before = stage_counts_on_this_thread();
        run_caught(&r, lc).expect("the referee answers");
        let (exact, fast) = delta(&before, &stage_counts_on_this_thread(), Stage::MinBall);
        assert_eq!((exact, fast), (1, 0), "{}: the exact stage must answer", lc.case.source);
    }
}

/// Barycentric cases at the floating-point stage's edges: a coordinate exactly
/// on a midpoint between two `f64` (a tie: the double-word bounds leave it
/// open, the exact dyadic numbers round it, the same bits as the rationals), a
/// coordinate exactly 0 (a point on an edge: certified as `+0.0`), zero-area
/// triangles (the longest edge's fallback, on certified signs: collinear,
/// tied edges, clamped, coincident), a sliver, and products beyond `f64`'s
/// range.
#[test]
fn barycentric_ties_zeros_and_degenerate_triangles_are_the_same() {
    let tri = |v: [[f64; 3]; 3]| Shape::Triangle(TriangleSpec { vertices: v, velocity: None });
    let pt = |at: [f64; 3]| Shape::Point(PointSpec { at });
    // (expected stage: true = the floating-point stage answers, case)
    let mut cases: Vec<(bool, LoadedCase)> = Vec::new();
    let mut add = |fast: bool, p: [f64; 3], v: [[f64; 3]; 3], what: String| {
        cases.push((fast, case(Query::Barycentric, pt(p), Some(tri(v)), what)));
    };
    for k in 0..40i32 {
        let s = 2f64.powi(k - 20);
        // v0.x = −2^-53·s, v1.x = (1 − 2^-53)·s: e1 = (s, 0, 0), and w.x =
        // (1 + 2^-53)·s, so β = 1 + 2^-53: a tie between 1 and its successor.
        let v = [
            [-(2f64.powi(-53)) * s, 0.0, 0.0],
            [(1.0 - 2f64.powi(-53)) * s, 0.0, 0.0],
            [-(2f64.powi(-53)) * s, s, 0.0],
        ];
        // The double-word bounds leave the tie open; the exact dyadic
        // numbers round it, short of the rationals.
        add(true, [s, 0.25 * s, 0.0], v, format!("β on a midpoint, scale 2^{}", k - 20));
        // The same triangle, the point on its edge v0v1: γ = 0 exactly.
        add(true, [0.5 * s, 0.0, 0.0], v, format!("γ exactly 0, scale 2^{}", k - 20));
        // Off the plane and outside: β = 3 + 2^-53 (rounds to 3, no tie),
        // γ = −1.25, α = −0.75 − 2^-53 (an f64).
        add(true, [3.0 * s, -1.25 * s, 2.0 * s], v, format!("outside and off the plane, scale 2^{}", k - 20));
        // Zero area (N exactly 0): the longest edge's fallback, flagged —
        // three collinear vertices, a tie of two longest edges (the first
        // wins), a point clamped to an edge's end, three coincident vertices.
        let at = format!("scale 2^{}", k - 20);
        let line = [[0.0, 0.0, 0.0], [s, s, s], [2.0 * s, 2.0 * s, 2.0 * s]];
        add(true, [s, s, 0.0], line, format!("collinear, {at}"));
        let tied = [[0.0; 3], [s, 0.0, 0.0], [0.0; 3]];
        add(true, [0.25 * s, s, 0.0], tied, format!("two longest edges tied, {at}"));
        add(true, [-s, 0.0, 0.0], tied, format!("clamped to an edge's end, {at}"));
        add(true, [s, s, s], [[s, 0.0, 0.0]; 3], format!("coincident vertices, {at}"));
        // A sliver 2^-50 high: N·N keeps its precision.
        let sliver = [[0.0; 3], [s, 0.0, 0.0], [0.5 * s, 2f64.powi(-50) * s, 0.0]];
        add(true, [0.3 * s, 0.7 * s, 0.0], sliver, format!("sliver, {at}"));
    }
    // Products of these leave f64's range; the stage's exponent carries them.
    add(
        true,
        [2f64.powi(999), 2f64.powi(-1000), 0.0],
        [[0.0, 0.0, 0.0], [2f64.powi(1000), 0.0, 0.0], [0.0, 2f64.powi(-1000), 0.0]],
        "beyond f64's range".into(),
    );
    add(
        true,
        [1.0, 0.5, 0.0],
        [[0.0, 0.0, 0.0], [1.0, 2f64.powi(-101), 0.0], [0.0, 1.0, 0.0]],
        "a vertex 2^-101 off its axis".into(),
    );
    assert_staged("barycentric edges of the stage", Stage::Barycentric, &cases);
}

/// Contact of spheres with spheres and planes on the edges of the
/// floating-point stage, at scales 2^-20 … 2^19: touching exactly (the stage
/// proves the depth exactly 0: +0.0), concentric, a point exactly on a
/// midpoint (a tie: the double-word bounds leave it open, the exact dyadic
/// numbers round it), outputs that are exact or exactly zero
/// (the stage certifies them), clear contact and clear separation (certified), and
/// inputs outside its range. Each answer and margin is the same with the
/// stages as without, and each case is answered by the stage it should be.
#[test]
fn contact_touching_ties_and_exact_outputs_are_the_same() {
    let sphere =
        |center: [f64; 3], radius: f64| Shape::Sphere(SphereSpec { center, radius, velocity: None, mass: None });
    let plane = |normal: [f64; 3], offset: f64| Shape::Plane(PlaneSpec { normal, offset, velocity: None });
    // (the floating-point stage answers the contact, case)
    let mut cases: Vec<(bool, LoadedCase)> = Vec::new();
    let mut add = |fast: bool, a: Shape, b: Shape, what: String| {
        cases.push((fast, case(Query::Contact, a, Some(b), what)));
    };
    for k in 0..40i32 {
        let s = 2f64.powi(k - 20);
        let at = format!("scale 2^{}", k - 20);
        // Centres 5s apart (3, 4, 0)·s: radii 2s + 3s touch exactly.
        add(true, sphere([3.0 * s, 4.0 * s, 0.0], 2.0 * s), sphere([0.0; 3], 3.0 * s), format!("touching, {at}"));
        // Radii 3s + 3s: depth s, normal (0.6, 0.8, +0): exact or not a tie.
        add(true, sphere([3.0 * s, 4.0 * s, 0.0], 3.0 * s), sphere([0.0; 3], 3.0 * s), format!("3-4-5, {at}"));
        add(false, sphere([s, s, s], s), sphere([s, s, s], 0.5 * s), format!("concentric, {at}"));
        // Δ = (s, 0, 0), rb = 2^-53·s: the point's x is s(1 + 2^-53), a tie.
        let tiny = 2f64.powi(-53) * s;
        add(true, sphere([2.0 * s, 0.0, 0.0], s), sphere([s, 0.0, 0.0], tiny), format!("point on a midpoint, {at}"));
        add(true, sphere([9.0 * s, 0.0, -s], s), sphere([0.0; 3], s), format!("apart, {at}"));
        // Plane n = (0, 0, 2), d = 0 and a sphere resting on it.
        add(true, sphere([0.0, 0.0, s], s), plane([0.0, 0.0, 2.0], 0.0), format!("resting on a plane, {at}"));
        // n = (0, 3, 4), centre at height 2s/5·… : e = 2s, depth s − 2s/5.
        add(true, sphere([s, 0.0, 0.5 * s], s), plane([0.0, 3.0, 4.0], 0.0), format!("sphere–plane, {at}"));
        add(true, plane([0.0, 3.0, 4.0], 0.0), sphere([-0.0, 0.0, 0.5 * s], s), format!("plane–sphere, {at}"));
        add(true, sphere([s, 0.0, 3.0 * s], s), plane([0.0, 3.0, 4.0], 0.0), format!("above a plane, {at}"));
        // The triangle (0, 0, 0), (4s, 0, 0), (0, 4s, 0) in each of its regions.
        let tri = || {
            Shape::Triangle(TriangleSpec {
                vertices: [[0.0; 3], [4.0 * s, 0.0, 0.0], [0.0, 4.0 * s, 0.0]],
                velocity: None,
            })
        };
        add(true, sphere([s, s, 3.0 * s], 4.0 * s), tri(), format!("triangle face, {at}"));
        add(true, tri(), sphere([s, s, -3.0 * s], 4.0 * s), format!("triangle–sphere face, {at}"));
        add(true, sphere([s, s, 2.0 * s], 2.0 * s), tri(), format!("triangle face touched, {at}"));
        add(true, sphere([2.0 * s, -3.0 * s, 4.0 * s], 6.0 * s), tri(), format!("triangle edge, {at}"));
        add(true, sphere([3.0 * s, 3.0 * s, s], 2.0 * s), tri(), format!("triangle hypotenuse, {at}"));
        add(true, tri(), sphere([-3.0 * s, -4.0 * s, 0.0], 6.0 * s), format!("triangle vertex, {at}"));
        // d1 = 0 exactly: on the boundary of vertex a's region and edge ac's.
        add(true, sphere([0.0, -s, 0.0], 2.0 * s), tri(), format!("triangle region boundary, {at}"));
        add(false, sphere([s, s, 0.0], s), tri(), format!("centre on the triangle, {at}"));
        let flat = Shape::Triangle(TriangleSpec {
            vertices: [[0.0; 3], [s, s, s], [2.0 * s, 2.0 * s, 2.0 * s]],
            velocity: None,
        });
        add(false, sphere([s, 0.0, 0.0], s), flat, format!("zero-area triangle, {at}"));
        // A mesh: the triangle and a face far below it; the centre over the
        // triangle's face, then over its vertex (0, 0, 0) shared by both.
        let mesh = Shape::Mesh(MeshSpec {
            vertices: Some(vec![
                [0.0; 3],
                [4.0 * s, 0.0, 0.0],
                [0.0, 4.0 * s, 0.0],
                [0.0, 0.0, -8.0 * s],
                [4.0 * s, 0.0, -8.0 * s],
            ]),
            triangles: Some(vec![[3, 4, 2], [0, 1, 2]]),
            file: None,
            velocity: None,
        });
        add(true, sphere([s, s, 3.0 * s], 4.0 * s), mesh.clone(), format!("mesh face, {at}"));
        add(true, sphere([s, s, 30.0 * s], 4.0 * s), mesh, format!("apart from a mesh, {at}"));
    }
    // A product beyond f64's range (2^2000), carried by the stage's exponent;
    // subnormal inputs and outputs, rounded on the subnormal grid.
    add(true, sphere([0.0; 3], 2f64.powi(1000)), sphere([1.0, 0.0, 0.0], 1.0), "beyond f64's range".into());
    for bits in [1u64, 3, 8, 1 << 40] {
        let tiny = f64::from_bits(bits);
        let (a, b) = (sphere([0.0; 3], tiny), sphere([tiny, tiny, 0.0], tiny));
        add(true, a, b, format!("subnormal spheres of {tiny:e}"));
    }
    // A contact point exactly 0 whose proof, (1 − 2^-101)² − (1 − 2^-101)²,
    // needs more than two words: the exact dyadic numbers give it.
    let off = sphere([2f64.powi(-101), 0.0, 0.0], 1.0);
    add(true, off, sphere([1.0, 0.0, 0.0], 1.0), "a zero point beyond two words".into());
    assert_staged("contact edges of the stage", Stage::Contact, &cases);
}

/// Segments against planes and triangles on the edges of the floating-point
/// stage, at scales 2^-20 … 2^19: ending or starting exactly on the plane,
/// through an edge or a vertex exactly (certified: the signs are exactly
/// known), missing by one ulp (a certified miss), a point exactly on a
/// midpoint (a tie: rounded in exact dyadic numbers), parallel, zero-length
/// and zero-area (the rationals, with their flags). Answers and margins are the same with
/// the stages as without, each from the stage it should be.
#[test]
fn intersect_ends_edges_ties_and_flags_are_the_same() {
    let seg = |start: [f64; 3], end: [f64; 3]| Shape::Segment(SegmentSpec { start, end });
    let plane = |normal: [f64; 3], offset: f64| Shape::Plane(PlaneSpec { normal, offset, velocity: None });
    let tri = |vertices: [[f64; 3]; 3]| Shape::Triangle(TriangleSpec { vertices, velocity: None });
    let mut cases: Vec<(bool, LoadedCase)> = Vec::new();
    let mut add = |fast: bool, a: Shape, b: Shape, what: String| {
        cases.push((fast, case(Query::Intersect, a, Some(b), what)));
    };
    for k in 0..40i32 {
        let s = 2f64.powi(k - 20);
        let at = format!("scale 2^{}", k - 20);
        let ground = || plane([0.0, 0.0, 1.0], 0.0);
        add(true, seg([s, 0.0, -s], [s, 2.0 * s, 3.0 * s]), ground(), format!("through a plane, {at}"));
        add(true, seg([s, 0.0, s], [2.0 * s, s, 0.0]), ground(), format!("ending on a plane, {at}"));
        add(true, seg([s, 0.0, 0.0], [2.0 * s, s, s]), ground(), format!("starting on a plane, {at}"));
        let above = 2f64.powi(-60) * s;
        add(true, seg([s, 0.0, s], [s, 0.0, above]), ground(), format!("stopping short of a plane, {at}"));
        add(true, seg([s, s, -s], [-s, s, 4.0 * s]), plane([0.0, 3.0, 4.0], 2.0 * s), format!("tilted plane, {at}"));
        add(false, seg([s, 0.0, s], [2.0 * s, s, s]), ground(), format!("parallel to a plane, {at}"));
        add(false, seg([s, 0.0, s], [s, 0.0, s]), ground(), format!("zero-length, {at}"));
        // t = 1/2 and x = s(1 + 2^-53): a tie. The double-word stage leaves
        // it open; the exact dyadic numbers round it (to even), short of the
        // rationals.
        let tie = seg([s, 0.0, 0.0], [s * (1.0 + f64::EPSILON), 0.0, s]);
        add(true, tie, plane([0.0, 0.0, 1.0], 0.5 * s), format!("point on a midpoint, {at}"));
        let t = || tri([[0.0; 3], [4.0 * s, 0.0, 0.0], [0.0, 4.0 * s, 0.0]]);
        add(true, seg([s, s, s], [s, 2.0 * s, -3.0 * s]), t(), format!("through a triangle, {at}"));
        add(true, seg([2.0 * s, 0.0, s], [2.0 * s, 0.0, -s]), t(), format!("through an edge, {at}"));
        add(true, seg([4.0 * s, 0.0, s], [4.0 * s, 0.0, -s]), t(), format!("through a vertex, {at}"));
        add(true, seg([2.0 * s, 2.0 * s, s], [2.0 * s, 2.0 * s, -s]), t(), format!("through the hypotenuse, {at}"));
        let out = -(2f64.powi(-60)) * s;
        add(true, seg([2.0 * s, out, s], [2.0 * s, out, -s]), t(), format!("just outside an edge, {at}"));
        add(false, seg([s, s, s], [2.0 * s, s, s]), t(), format!("parallel to a triangle, {at}"));
        let flat = tri([[0.0; 3], [s, s, 0.0], [2.0 * s, 2.0 * s, 0.0]]);
        add(false, seg([s, 0.0, s], [s, 0.0, -s]), flat, format!("zero-area triangle, {at}"));
        // A square of two faces sharing the diagonal, and a face behind them:
        // through the diagonal both faces tie (the lowest index wins).
        let vertices = vec![
            [0.0, 0.0, 0.0],
            [2.0 * s, 0.0, 0.0],
            [2.0 * s, 2.0 * s, 0.0],
            [0.0, 2.0 * s, 0.0],
            [0.0, 0.0, -s],
            [4.0 * s, 0.0, -s],
            [0.0, 4.0 * s, -s],
        ];
        for faces in [vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]], vec![[4, 5, 6], [0, 2, 3], [0, 1, 2]]] {
            let mesh = Shape::Mesh(MeshSpec {
                vertices: Some(vertices.clone()),
                triangles: Some(faces.clone()),
                file: None,
                velocity: None,
            });
            add(true, seg([s, s, s], [s, s, -2.0 * s]), mesh, format!("mesh diagonal tie, faces {faces:?}, {at}"));
        }
        let mesh = Shape::Mesh(MeshSpec {
            vertices: Some(vertices.clone()),
            triangles: Some(vec![[0, 1, 2], [0, 1, 1]]),
            file: None,
            velocity: None,
        });
        add(false, seg([s, s, s], [s, s, -2.0 * s]), mesh, format!("mesh with a zero-area face, {at}"));
    }
    assert_staged("intersect edges of the stage", Stage::Intersect, &cases);
}

/// A sphere's time of impact with a sphere or a plane on the edges of the
/// floating-point stage, at scales 2^-20 … 2^19 (`t_max` 1): an impact at
/// t = 1/2, exactly at `t_max`, grazing (a zero discriminant), moving apart,
/// moving parallel to a plane (certified), and two points meeting (a zero
/// total radius: the exact stage's fallback normal).
#[test]
fn toi_at_the_horizon_grazing_and_points_are_the_same() {
    let moving = |center: [f64; 3], radius: f64, v: [f64; 3]| {
        Shape::Sphere(SphereSpec { center, radius, velocity: Some(v), mass: None })
    };
    let still =
        |center: [f64; 3], radius: f64| Shape::Sphere(SphereSpec { center, radius, velocity: None, mass: None });
    let ground = || Shape::Plane(PlaneSpec { normal: [0.0, 0.0, 1.0], offset: 0.0, velocity: None });
    let mut cases: Vec<(bool, LoadedCase)> = Vec::new();
    let mut add = |fast: bool, a: Shape, b: Shape, what: String| {
        cases.push((fast, case(Query::Toi, a, Some(b), what)));
    };
    for k in 0..40i32 {
        let s = 2f64.powi(k - 20);
        let at = format!("scale 2^{}", k - 20);
        let b = || still([0.0; 3], s);
        add(true, moving([-4.0 * s, 0.0, 0.0], s, [4.0 * s, 0.0, 0.0]), b(), format!("head-on at t = 1/2, {at}"));
        add(true, moving([-4.0 * s, 0.0, 0.0], s, [2.0 * s, 0.0, 0.0]), b(), format!("impact at t_max, {at}"));
        add(true, moving([-4.0 * s, s, 0.0], s, [3.0 * s, -s, s]), b(), format!("oblique, {at}"));
        add(true, moving([-4.0 * s, 2.0 * s, 0.0], s, [4.0 * s, 0.0, 0.0]), b(), format!("grazing, {at}"));
        add(true, moving([-4.0 * s, 0.0, 0.0], s, [-s, 0.0, 0.0]), b(), format!("moving apart, {at}"));
        let point = |c: [f64; 3], v| moving(c, 0.0, v);
        let target = still([0.0; 3], 0.0);
        add(false, point([-4.0 * s, 0.0, 0.0], [4.0 * s, 0.0, 0.0]), target, format!("two points meet, {at}"));
        add(true, moving([0.0, 0.0, 3.0 * s], s, [s, 0.0, -4.0 * s]), ground(), format!("onto a plane, {at}"));
        add(
            true,
            moving([0.0, 0.0, 3.0 * s], s, [0.0, 0.0, -2.0 * s]),
            ground(),
            format!("onto a plane at t_max, {at}"),
        );
        add(true, moving([0.0, 0.0, 3.0 * s], s, [s, s, 0.0]), ground(), format!("along a plane, {at}"));
        add(true, moving([0.0, 0.0, 3.0 * s], s, [0.0, s, s]), ground(), format!("away from a plane, {at}"));
    }
    assert_staged("toi edges of the stage", Stage::Toi, &cases);
}

/// A sphere's time of impact with a triangle or a mesh at 40 scales: a face
/// hit from either side, an edge hit at an irrational time, impact exactly at
/// `t_max`, and the exact ties of features meeting at one time — a vertex and
/// the edge whose foot ends there, a face and the edge its contact lies on,
/// the two faces and the diagonal of a square mesh, the three features of a
/// zero-area triangle — all certified by the floating-point stage, which
/// needs only that tied candidates round alike; grazing an edge or a vertex
/// (`D = 0`: both roots tied), motion in the triangle's plane, moving away. A
/// point-sized sphere (no normal) and a mesh already touched at `t = 0` are
/// the exact stage's. The margins, the path's distance from the triangle or
/// the mesh, are the floating-point stage's but for a zero-area triangle.
#[test]
fn toi_against_triangles_faces_edges_vertices_and_ties_are_the_same() {
    let moving = |center: [f64; 3], radius: f64, v: [f64; 3]| {
        Shape::Sphere(SphereSpec { center, radius, velocity: Some(v), mass: None })
    };
    let tri = |v: [[f64; 3]; 3]| Shape::Triangle(TriangleSpec { vertices: v, velocity: None });
    let mesh = |vertices: Vec<[f64; 3]>, triangles: Vec<[usize; 3]>| {
        Shape::Mesh(MeshSpec { vertices: Some(vertices), triangles: Some(triangles), file: None, velocity: None })
    };
    let mut cases: Vec<(bool, LoadedCase)> = Vec::new();
    let mut add = |fast: bool, a: Shape, b: Shape, what: String| {
        let lc = case(Query::Toi, a, Some(b), what);
        assert!(!matches!(lc.case.b, Some(Shape::Mesh(_))) || lc.meshes[1].is_some(), "the inline mesh loads");
        cases.push((fast, lc));
    };
    for k in 0..40i32 {
        let s = 2f64.powi(k - 20);
        let at = format!("scale 2^{}", k - 20);
        // Legs 2s on x and y in z = 0.
        let t = || tri([[0.0; 3], [2.0 * s, 0.0, 0.0], [0.0, 2.0 * s, 0.0]]);
        let c = |x: f64, y: f64, z: f64| [x * s, y * s, z * s];
        add(true, moving(c(0.5, 0.5, 3.0), s, c(0.0, 0.0, -4.0)), t(), format!("face from above at t = 1/2, {at}"));
        add(true, moving(c(0.5, 0.5, -3.0), s, c(0.1, 0.0, 4.0)), t(), format!("face from below, {at}"));
        add(true, moving(c(0.5, 0.5, 3.0), s, c(0.0, 0.0, -2.0)), t(), format!("face at t_max, {at}"));
        add(true, moving(c(2.0, 2.0, 0.2), 0.5 * s, c(-1.0, -1.5, 0.0)), t(), format!("hypotenuse, {at}"));
        let over = moving(c(2.0, 2.0, 0.5), 0.5 * s, c(-1.0, -1.5, 0.0));
        add(true, over, t(), format!("grazing the hypotenuse (a double root), {at}"));
        add(true, moving(c(-3.0, 0.0, 0.0), s, c(4.0, 0.0, 0.0)), t(), format!("vertex and edge end tied, {at}"));
        add(true, moving(c(1.0, 0.0, 3.0), s, c(0.0, 0.0, -4.0)), t(), format!("face and edge tied, {at}"));
        add(true, moving(c(-3.0, -1.0, 0.0), s, c(4.0, 0.0, 0.0)), t(), format!("grazing a vertex, {at}"));
        add(true, moving(c(-3.0, 0.5, 0.0), s, c(4.0, 0.0, 0.0)), t(), format!("in the plane onto an edge, {at}"));
        add(true, moving(c(0.5, 0.5, 3.0), s, c(0.0, 1.0, 4.0)), t(), format!("moving away, {at}"));
        let flat = tri([[0.0; 3], [s, 0.0, 0.0], [2.0 * s, 0.0, 0.0]]);
        add(true, moving(c(1.0, 0.0, 3.0), s, c(0.0, 0.0, -4.0)), flat, format!("zero-area triangle, {at}"));
        add(false, moving(c(0.5, 0.5, 3.0), 0.0, c(0.0, 0.0, -4.0)), t(), format!("point-sized sphere, {at}"));
        let square = || {
            mesh(
                vec![c(0.0, 0.0, 0.0), c(2.0, 0.0, 0.0), c(2.0, 2.0, 0.0), c(0.0, 2.0, 0.0)],
                vec![[0, 1, 2], [0, 2, 3]],
            )
        };
        add(true, moving(c(1.0, 1.0, 3.0), s, c(0.0, 0.0, -4.0)), square(), format!("mesh diagonal tied, {at}"));
        add(true, moving(c(0.5, 1.5, 3.0), s, c(0.5, 0.0, -4.0)), square(), format!("mesh second face, {at}"));
        add(false, moving(c(1.0, 1.0, 0.5), s, c(0.0, 0.0, -4.0)), square(), format!("mesh touched at 0, {at}"));
    }
    assert_staged("toi against triangles", Stage::Toi, &cases);
    // The margins (already the same bits, above) come from the floating-point
    // stage too — the path's distance from every feature, the crossing of a
    // face — except for the zero-area triangle, whose nearest feature the
    // stage leaves to the exact one.
    for (_, lc) in &cases {
        let before = stage_counts_on_this_thread();
        referee::margin(lc).expect("a toi case has a margin");
        let (exact, by_fast) = delta(&before, &stage_counts_on_this_thread(), Stage::Toi);
        let flat = lc.case.source.starts_with("zero-area");
        assert_eq!((by_fast, exact), (u64::from(!flat), u64::from(flat)), "margin of {}", lc.case.source);
    }
}

/// Collision response at 40 scales: head-on, glancing at a Pythagorean
/// normal, unequal masses, concentric centres (the flagged +z fallback),
/// separating and sliding (velocities kept as given, −0 included), a sphere
/// bouncing on a plane or leaving it — all the floating-point stage's; an
/// output exactly on a midpoint between two `f64` (a tie), which the
/// double-word bounds leave open, is rounded in exact dyadic numbers, short of
/// the rationals (and the same bits as theirs).
#[test]
fn response_heads_on_glances_ties_and_fallbacks_are_the_same() {
    let body = |center: [f64; 3], v: [f64; 3], mass: f64| {
        Shape::Sphere(SphereSpec { center, radius: 1.0, velocity: Some(v), mass: Some(mass) })
    };
    let plane = |normal: [f64; 3]| Shape::Plane(PlaneSpec { normal, offset: 0.0, velocity: None });
    let mut cases: Vec<(bool, LoadedCase)> = Vec::new();
    let mut add = |fast: bool, a: Shape, b: Shape, e: f64, what: String| {
        let mut lc = case(Query::Response, a, Some(b), what);
        lc.case.restitution = Some(e);
        cases.push((fast, lc));
    };
    for k in 0..40i32 {
        let s = 2f64.powi(k - 20);
        let at = format!("scale 2^{}", k - 20);
        let head_on = (body([-s, 0.0, 0.0], [s, 0.0, 0.0], 1.0), body([s, 0.0, 0.0], [-s, 0.0, 0.0], 1.0));
        add(true, head_on.0, head_on.1, 1.0, format!("head-on, {at}"));
        let glance = (body([0.0; 3], [s, 0.0, 0.0], 2.0), body([3.0 * s, 4.0 * s, 0.0], [0.0; 3], 3.0));
        add(true, glance.0, glance.1, 0.5, format!("glancing at (3,4,0)/5, {at}"));
        let uneven = (body([0.0; 3], [s, s, 0.0], 1e-3), body([s, 2.0 * s, 0.5 * s], [-s, 0.0, s], 7.0));
        add(true, uneven.0, uneven.1, 0.3, format!("unequal masses, {at}"));
        let same = (body([s, s, s], [0.0, 0.0, s], 1.0), body([s, s, s], [0.0; 3], 1.0));
        add(true, same.0, same.1, 1.0, format!("concentric, {at}"));
        let apart = (body([-s, 0.0, 0.0], [-s, -0.0, 0.0], 1.0), body([s, 0.0, 0.0], [0.0; 3], 1.0));
        add(true, apart.0, apart.1, 1.0, format!("separating, {at}"));
        let slide = (body([-s, 0.0, 0.0], [0.0, s, 0.0], 1.0), body([s, 0.0, 0.0], [0.0, -s, 0.0], 1.0));
        add(true, slide.0, slide.1, 1.0, format!("sliding, {at}"));
        let bounce = body([0.0, 0.0, s], [s, 0.0, -2.0 * s], 1.0);
        add(true, bounce, plane([0.0, 3.0, 4.0]), 0.7, format!("bouncing on a plane, {at}"));
        let leave = body([0.0, 0.0, s], [s, 0.0, 2.0 * s], 1.0);
        add(true, leave, plane([0.0, 0.0, 1.0]), 0.7, format!("leaving a plane, {at}"));
    }
    // −e·vz = 1 + 2^-26 + 2^-27 + 2^-53 exactly: half an ulp above an f64.
    let e = 1.0 + 2f64.powi(-26);
    let tie = body([0.0, 0.0, 1.0], [0.0, 0.0, -(1.0 + 2f64.powi(-27))], 1.0);
    add(true, tie, plane([0.0, 0.0, 1.0]), e, "a velocity on a midpoint".into());
    assert_staged("response", Stage::Response, &cases);
}

/// Spheres moving along x at height 1 exactly above a mesh's face (touching it
/// all along, the face's box exactly r below the path), or one ulp above: the
/// floating-point stage must not rule out a face the sphere touches.
#[test]
fn meshes_touched_exactly_are_the_same() {
    let mut cases = Vec::new();
    for k in 0..100u32 {
        let r = 1.0 + f64::from(k) / 64.0;
        let lift = if k % 2 == 0 { 0.0 } else { r * f64::EPSILON };
        let center = [-3.0, 0.0, r + lift];
        let a = Shape::Sphere(SphereSpec { center, radius: r, velocity: Some([6.0, 0.0, 0.0]), mass: None });
        let vertices = vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, -4.0], [6.0, 5.0, -4.0]];
        let triangles = vec![[0, 1, 2], [3, 4, 2], [0, 3, 4]];
        let b =
            Shape::Mesh(MeshSpec { vertices: Some(vertices), triangles: Some(triangles), file: None, velocity: None });
        let lc = case(Query::Toi, a, Some(b), format!("mesh {k}: touched at height r + {lift:e}"));
        assert!(lc.meshes[1].is_some(), "the inline mesh loads");
        cases.push(lc);
    }
    assert_same("meshes touched exactly", &cases);
    // A diagonal path whose box holds every face, and a zero-size face (one
    // point, three times) exactly r above the path, or one ulp farther: the
    // ball bound's edge, where only the rounding allowance keeps the face in.
    let mut points = Vec::new();
    for k in 0..100u32 {
        let r = 0.5 + f64::from(k) / 128.0;
        let at = f64::from(k % 9) / 4.0 - 1.0;
        let z = if k % 2 == 0 { r } else { r * (1.0 + f64::EPSILON) };
        let a = Shape::Sphere(SphereSpec {
            center: [-3.0, -3.0, 0.0],
            radius: r,
            velocity: Some([6.0, 6.0, 0.0]),
            mass: None,
        });
        let vertices =
            vec![[at, at, z], [at, at, z], [at, at, z], [2.5, -2.5, 0.0], [2.5, -2.0, 0.0], [2.0, -2.5, 0.0]];
        let b = Shape::Mesh(MeshSpec {
            vertices: Some(vertices),
            triangles: Some(vec![[3, 4, 5], [0, 1, 2]]),
            file: None,
            velocity: None,
        });
        let lc = case(Query::Toi, a, Some(b), format!("point face {k}: at height {z:e} over a diagonal path"));
        assert!(lc.meshes[1].is_some(), "the inline mesh loads");
        points.push(lc);
    }
    assert_same("point faces at distance r from a diagonal path", &points);
    // The touching ones are hits (the point face is what the sphere meets), the
    // others misses: the cases do reach the face.
    let r = engines::referee();
    for (k, lc) in points.iter().enumerate() {
        let hit = format!("{:?}", run_caught(&r, lc)).contains("toi: Some");
        assert_eq!(hit, k % 2 == 0, "{}: {:?}", lc.case.source, run_caught(&r, lc));
    }
}

/// How many `stage` answers came from each stage between two readings:
/// (exact, fast).
fn delta(before: &[(Stage, u64, u64)], now: &[(Stage, u64, u64)], stage: Stage) -> (u64, u64) {
    let get =
        |v: &[(Stage, u64, u64)]| v.iter().find(|(s, _, _)| *s == stage).map(|&(_, f, e)| (f, e)).unwrap_or((0, 0));
    let ((f0, e0), (f1, e1)) = (get(before), get(now));
    (e1 - e0, f1 - f0)
}

/// Every refusal is the same with the stages on as with the exact stage
/// alone, and no stage answers a question the exact stage refuses. (The
/// stages run after checks that make no rational; that the checks refuse as
/// the conversions do, field for field, is `toi`'s unit test.) Each number of
/// a valid question is set in turn to NaN, +∞ and −∞, every two of them to
/// NaN, a radius to −1, a plane's normal to zero and a mesh's index out of
/// range; the result, error or answer, must be the same text either way.
#[test]
fn refusals_name_the_same_field_with_the_stages() {
    use oracle::geom::{P3, Plane, Sphere, Triangle};
    use oracle::referee as r;
    // A valid question's numbers, flat: sphere a (centre, radius), its
    // velocity, sphere b, b's velocity, a plane (normal, offset), a
    // triangle, t_max, two masses and a restitution; a mesh's vertices are
    // the triangle's and a fourth point.
    const BASE: [f64; 34] = [
        0.0, 0.0, 3.0, 0.5, // a
        0.0, 0.0, -2.0, // va
        0.0, 0.25, 0.0, 1.0, // b
        0.0, 0.0, 1.0, // vb
        0.0, 0.0, 1.0, -1.0, // plane
        -1.0, -1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 2.0, 0.0, // triangle
        4.0, // t_max
        2.0, 3.0, 0.5, // masses, restitution
        0.5, 0.5, -1.0, // the mesh's fourth vertex
    ];
    type Call = fn(&[f64; 34], bool) -> String;
    fn p3(x: &[f64; 34], i: usize) -> P3 {
        [x[i], x[i + 1], x[i + 2]]
    }
    fn sphere(x: &[f64; 34], i: usize) -> Sphere {
        Sphere { center: p3(x, i), radius: x[i + 3] }
    }
    fn plane(x: &[f64; 34], zero: bool) -> Plane {
        Plane { normal: if zero { [0.0; 3] } else { p3(x, 14) }, offset: x[17] }
    }
    fn tri(x: &[f64; 34]) -> Triangle {
        Triangle { vertices: [p3(x, 18), p3(x, 21), p3(x, 24)] }
    }
    fn mesh(x: &[f64; 34], bad: bool) -> (Vec<P3>, Vec<[usize; 3]>) {
        let t = tri(x).vertices;
        (vec![t[0], t[1], t[2], p3(x, 31)], vec![[0, 1, 2], [0, 1, if bad { 4 } else { 3 }]])
    }
    let calls: [(&str, Call); 14] = [
        ("toi sphere–sphere", |x, _| {
            format!("{:?}", r::toi_sphere_sphere(&sphere(x, 0), &p3(x, 4), &sphere(x, 7), &p3(x, 11), x[27]))
        }),
        ("toi sphere–plane", |x, z| {
            format!("{:?}", r::toi_sphere_plane(&sphere(x, 0), &p3(x, 4), &plane(x, z), &p3(x, 11), x[27]))
        }),
        ("toi sphere–triangle", |x, _| {
            format!("{:?}", r::toi_sphere_triangle(&sphere(x, 0), &p3(x, 4), &tri(x), &p3(x, 11), x[27]))
        }),
        ("toi sphere–mesh", |x, bad| {
            let (v, t) = mesh(x, bad);
            format!("{:?}", r::toi_sphere_mesh(&sphere(x, 0), &p3(x, 4), &v, &t, &p3(x, 11), x[27]))
        }),
        ("toi margin sphere–sphere", |x, _| {
            format!(
                "{:?}",
                r::toi_margin_sphere_sphere(&sphere(x, 0), &p3(x, 4), &sphere(x, 7), &p3(x, 11), x[27])
                    .map(f64::to_bits)
            )
        }),
        ("toi margin sphere–plane", |x, z| {
            format!(
                "{:?}",
                r::toi_margin_sphere_plane(&sphere(x, 0), &p3(x, 4), &plane(x, z), &p3(x, 11), x[27]).map(f64::to_bits)
            )
        }),
        ("toi margin sphere–triangle", |x, _| {
            format!(
                "{:?}",
                r::toi_margin_sphere_triangle(&sphere(x, 0), &p3(x, 4), &tri(x), &p3(x, 11), x[27]).map(f64::to_bits)
            )
        }),
        ("toi margin sphere–mesh", |x, bad| {
            let (v, t) = mesh(x, bad);
            format!(
                "{:?}",
                r::toi_margin_sphere_mesh(&sphere(x, 0), &p3(x, 4), &v, &t, &p3(x, 11), x[27]).map(f64::to_bits)
            )
        }),
        ("response sphere–sphere", |x, _| {
            format!(
                "{:?}",
                r::response_sphere_sphere(&sphere(x, 0), &p3(x, 4), x[28], &sphere(x, 7), &p3(x, 11), x[29], x[30])
            )
        }),
        ("response sphere–plane", |x, z| format!("{:?}", r::response_sphere_plane(&p3(x, 4), &plane(x, z), x[30]))),
        ("contact sphere–sphere", |x, _| format!("{:?}", r::contact_sphere_sphere(&sphere(x, 0), &sphere(x, 7)))),
        ("contact sphere–plane", |x, z| format!("{:?}", r::contact_sphere_plane(&sphere(x, 0), &plane(x, z)))),
        ("contact sphere–triangle", |x, _| format!("{:?}", r::contact_sphere_triangle(&sphere(x, 0), &tri(x)))),
        ("contact sphere–mesh", |x, bad| {
            let (v, t) = mesh(x, bad);
            format!("{:?}", r::contact_sphere_mesh(&sphere(x, 0), &v, &t))
        }),
    ];
    let mut variants: Vec<(String, [f64; 34], bool)> = vec![("valid".into(), BASE, false), ("flag".into(), BASE, true)];
    for i in 0..BASE.len() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut x = BASE;
            x[i] = bad;
            variants.push((format!("number {i} = {bad}"), x, false));
        }
    }
    for i in 0..BASE.len() {
        for j in i + 1..BASE.len() {
            let mut x = BASE;
            (x[i], x[j]) = (f64::NAN, f64::NAN);
            variants.push((format!("numbers {i} and {j} = NaN"), x, false));
        }
    }
    for radius in [3, 10] {
        let mut x = BASE;
        x[radius] = -1.0;
        variants.push((format!("radius {radius} = -1"), x, false));
    }
    let mut refused = 0;
    let mut differ = Vec::new();
    for (name, call) in calls {
        for (what, x, flag) in &variants {
            let staged = call(x, *flag);
            let exact = exact_only(|| call(x, *flag));
            refused += usize::from(staged.starts_with("Err"));
            if staged != exact {
                differ.push(format!("{name}, {what}: staged {staged}, exact {exact}"));
            }
        }
    }
    assert!(differ.is_empty(), "{} differences:\n{}", differ.len(), differ.join("\n"));
    // The corruptions reach the checks: most variants are refusals.
    assert!(refused > calls.len() * 100, "only {refused} refusals");
}

/// Meeting polytopes at the separating-axes filter's edges: boxes given as
/// hulls of their corners under rotations a few ulps apart (edges nearly
/// parallel: cross products that cancel to almost nothing, and exact zeros),
/// the same box slightly moved (many pushes exactly equal: the ties the
/// filter must keep), boxes against those hulls and against capsules along
/// their edges, and small hulls meeting, at scales from 2⁻⁵⁰⁰ to 2⁵⁰⁰. Every
/// answer and witness set is the same with the filter as without, and the
/// filter set some pushes aside (it ran).
#[test]
fn distance_near_parallel_edges_and_tied_pushes_are_the_same() {
    use harness::case::BoxSpec;
    use oracle::geom::{Capsule, Convex, P3};
    // Corners of the box `center ± h` under the unit quaternion `q`.
    let corners = |center: P3, h: f64, q: [f64; 4]| -> Vec<P3> {
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        let [w, x, y, z] = q.map(|c| c / n);
        let r = [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
            [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
            [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
        ];
        (0..8)
            .map(|s| {
                let u = [0, 1, 2].map(|i| if s >> i & 1 == 1 { h } else { -h });
                [0, 1, 2].map(|i| center[i] + r[i][0] * u[0] + r[i][1] * u[1] + r[i][2] * u[2])
            })
            .collect()
    };
    let distance = |a: Shape, b: Shape, source: String| {
        loaded(Case {
            name: source.clone(),
            source,
            query: Query::Distance,
            a,
            b: Some(b),
            expect: None,
            tol: None,
            t_max: None,
            restitution: None,
        })
    };
    let mut cases = Vec::new();
    let mut rng = harness::rng::SplitMix64(SEED);
    for (k, scale) in [-500, -30, 0, 30, 500].into_iter().enumerate() {
        let s = 2f64.powi(scale);
        for ulps in [0u64, 1, 3, 1 << 20] {
            let q: [f64; 4] = [2.0, 1.0, 0.5, 0.25];
            let nudged = [q[0], f64::from_bits(q[1].to_bits() + ulps), q[2], q[3]];
            let a = corners([0.3 * s, 0.2 * s, 0.1 * s], s, q);
            let b = corners([0.0; 3], s, nudged);
            let what = format!("scale 2^{scale}, rotations {ulps} ulps apart");
            cases.push(distance(
                Shape::Convex(Convex { points: a.clone() }),
                Shape::Convex(Convex { points: b.clone() }),
                what.clone(),
            ));
            let boxed = BoxSpec { center: [0.0; 3], half_extents: [s; 3], rotation: Some(nudged), velocity: None };
            cases.push(distance(
                Shape::Convex(Convex { points: a.clone() }),
                Shape::Box(boxed),
                format!("{what}, box"),
            ));
            let capsule = Capsule { start: a[0], end: a[1], radius: 0.25 * s };
            cases.push(distance(
                Shape::Capsule(capsule),
                Shape::Convex(Convex { points: b }),
                format!("{what}, capsule along an edge"),
            ));
        }
        // The same box moved by a little: every face pair parallel.
        let q = [2.0, 0.0, 0.0, 1.0];
        for shift in [0.0, 0.5, 1.0, 2.0] {
            let a = corners([shift * s, 0.5 * s, 0.0], s, q);
            let b = corners([0.0; 3], s, q);
            cases.push(distance(
                Shape::Convex(Convex { points: a }),
                Shape::Convex(Convex { points: b }),
                format!("scale 2^{scale}: one box moved by {shift}"),
            ));
        }
        // Small random hulls meeting.
        for i in 0..20 {
            let hull = |rng: &mut harness::rng::SplitMix64, c: f64| -> Vec<P3> {
                (0..4 + i % 9).map(|_| [0, 1, 2].map(|_| (c + rng.range(-1.0, 1.0)) * s)).collect()
            };
            let (a, b) = (hull(&mut rng, 0.25), hull(&mut rng, 0.0));
            cases.push(distance(
                Shape::Convex(Convex { points: a }),
                Shape::Convex(Convex { points: b }),
                format!("scale 2^{scale}: random hulls {k}.{i}"),
            ));
        }
    }
    assert_same("distance at the separating-axes filter's edges", &cases);
    let r = engines::referee();
    let before = stage_counts_on_this_thread();
    for lc in &cases {
        run_caught(&r, lc).expect("the referee answers");
    }
    let (exact, set_aside) = delta(&before, &stage_counts_on_this_thread(), Stage::SeparatingAxes);
    assert!(set_aside > 0 && exact > 0, "the filter ran: {set_aside} pushes set aside, {exact} compared exactly");
}
