//! One smoke test per engine on a hand-computed case: the seam works and each
//! adapter's conventions are translated the right way round.

use harness::case::{Case, Expect, PointSpec, Query, SegmentSpec, Shape, SphereSpec, TriangleSpec};
use harness::check::run_caught;
use harness::engine::Answer;
use harness::engines::{judged, referee};
use harness::load::LoadedCase;

/// The hand-computed answers below are exact small dyadic values; an f32 engine
/// rounds them once or twice: 1e-6 covers both precisions.
const SMOKE_TOL: f64 = 1e-6;

fn loaded(query: Query, a: Shape, b: Shape) -> LoadedCase {
    LoadedCase {
        file: "smoke".into(),
        case: Case {
            name: "smoke".into(),
            source: "hand-derived".into(),
            query,
            a,
            b: Some(b),
            expect: Some(Expect::default()),
            tol: None,
            t_max: None,
            restitution: None,
        },
        meshes: [None, None],
    }
}

fn ball(center: [f64; 3], radius: f64) -> Shape {
    Shape::Sphere(SphereSpec { center, radius, velocity: None, mass: None })
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= SMOKE_TOL)
}

#[test]
fn every_engine_answers_a_three_four_five_sphere_contact() {
    // a at (3,4,0) r 3, b at the origin r 3: ‖Δ‖ = 5, n = (0.6, 0.8, 0) from b to a,
    // point on b: 3n = (1.8, 2.4, 0), depth 6 − 5 = 1.
    let case = loaded(Query::Contact, ball([3.0, 4.0, 0.0], 3.0), ball([0.0; 3], 3.0));
    for engine in judged().iter().chain([&referee()]) {
        let Ok(Answer::Contact(k)) = run_caught(engine, &case) else { panic!("{}: no contact answer", engine.name) };
        let k = k.contact.unwrap_or_else(|| panic!("{}: no contact", engine.name));
        assert!(close(&k.normal, &[0.6, 0.8, 0.0]), "{}: normal {:?}", engine.name, k.normal);
        assert!(close(&k.point, &[1.8, 2.4, 0.0]), "{}: point {:?}", engine.name, k.point);
        assert!(close(&[k.depth], &[1.0]), "{}: depth {}", engine.name, k.depth);
    }
}

#[test]
fn every_engine_answers_a_segment_through_a_triangle() {
    // Triangle (0,0,0), (4,0,0), (0,4,0), face normal +z; segment from (1,1,2) to
    // (1,1,−2) crosses z = 0 at t = 0.5, point (1,1,0), barycentric
    // (1 − 1/4 − 1/4, 1/4, 1/4) = (0.5, 0.25, 0.25).
    let tri = Shape::Triangle(TriangleSpec { vertices: [[0.0; 3], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]], velocity: None });
    let seg = Shape::Segment(SegmentSpec { start: [1.0, 1.0, 2.0], end: [1.0, 1.0, -2.0] });
    let case = loaded(Query::Intersect, seg, tri);
    for engine in judged().iter().chain([&referee()]) {
        let Ok(Answer::Intersect(i)) = run_caught(engine, &case) else { panic!("{}: no answer", engine.name) };
        let h = i.hit.unwrap_or_else(|| panic!("{}: no hit", engine.name));
        assert!(close(&[h.t], &[0.5]), "{}: t {}", engine.name, h.t);
        assert!(close(&h.point, &[1.0, 1.0, 0.0]), "{}: point {:?}", engine.name, h.point);
        assert!(close(&h.normal, &[0.0, 0.0, 1.0]), "{}: normal {:?}", engine.name, h.normal);
        let b = h.barycentric.unwrap_or_else(|| panic!("{}: no barycentrics", engine.name));
        assert!(close(&b, &[0.5, 0.25, 0.25]), "{}: barycentric {:?}", engine.name, b);
    }
}

#[test]
fn every_engine_answers_barycentrics_inside_a_triangle() {
    // Point (1,1,0) in the triangle above: (0.5, 0.25, 0.25) (in the plane, so the
    // lecture's unsigned area ratios give the same answer as the signed ones).
    let tri = Shape::Triangle(TriangleSpec { vertices: [[0.0; 3], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]], velocity: None });
    let case = loaded(Query::Barycentric, Shape::Point(PointSpec { at: [1.0, 1.0, 0.0] }), tri);
    for engine in judged().iter().chain([&referee()]) {
        let Ok(Answer::Barycentric(b)) = run_caught(engine, &case) else { panic!("{}: no answer", engine.name) };
        assert!(close(&b.coords, &[0.5, 0.25, 0.25]), "{}: {:?}", engine.name, b.coords);
    }
}
