//! Tests of the distance referee: hand-derived cases (the derivation beside
//! each), the hull's degenerate forms, and a property against sampled
//! support functions.

use super::super::exact::within_ulps;
use super::{distance, distance_witnesses};
use crate::geom::{Capsule, Convex, DistanceAnswer, OrientedBox, P3, Plane, Solid, Sphere, Triangle};

/// Exactly representable answers are returned exactly (the referee rounds
/// once from the exact value); the rest are compared to a hand value within
/// this many of its own units, its derivation's own rounding (a square root
/// or a quotient of small integers evaluated in `f64`, within 2 ulps).
const HAND_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// The same exact answer rounds to the same double: 0 ulps apart.
const SAME_ANSWER_ULPS: u64 = 0;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= HAND_ROUNDING * a.abs().max(b.abs()).max(1.0)
}

fn close3(a: P3, b: P3) -> bool {
    (0..3).all(|i| close(a[i], b[i]))
}

fn cube(center: P3, h: f64) -> Convex {
    let mut points = Vec::new();
    for s in 0..8 {
        points.push([0, 1, 2].map(|i| center[i] + if s >> i & 1 == 1 { h } else { -h }));
    }
    Convex { points }
}

fn check(d: &DistanceAnswer, dist: f64, normal: P3, degenerate: bool) {
    assert!(close(d.distance, dist), "distance {} want {dist}: {d:?}", d.distance);
    assert!(close3(d.normal, normal), "normal {:?} want {normal:?}", d.normal);
    assert_eq!(d.degenerate, degenerate, "{d:?}");
    // point_a = point_b + distance·normal.
    let back = [0, 1, 2].map(|i| d.point_b[i] + d.distance * d.normal[i]);
    assert!(close3(back, d.point_a), "{d:?}");
}

#[test]
fn unit_cubes_apart_face_to_face_are_half_a_unit_apart_and_degenerate() {
    // Cubes of half-size 1 centred 2.5 apart along x: the faces x = 1 and
    // x = 1.5 are parallel, 0.5 apart; every pair of facing points is closest.
    let (a, b) = (cube([2.5, 0.0, 0.0], 1.0), cube([0.0, 0.0, 0.0], 1.0));
    let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
    check(&d, 0.5, [1.0, 0.0, 0.0], true);
    assert!(close(d.point_b[0], 1.0) && close(d.point_a[0], 1.5));
    let (on_a, on_b) = distance_witnesses(Solid::Convex(&a), Solid::Convex(&b)).unwrap().expect("a face");
    assert_eq!(on_a.len(), 4);
    assert_eq!(on_b.len(), 4);
    assert!(on_b.iter().all(|p| close(p[0], 1.0)) && on_a.iter().all(|p| close(p[0], 1.5)));
}

#[test]
fn overlapping_cubes_are_minus_their_overlap() {
    // Centres 1.75 apart along x with half-size 1: they overlap by 0.25 in x
    // and by 2 in y and z, so the least push is 0.25 along +x.
    let (a, b) = (cube([1.75, 0.0, 0.0], 1.0), cube([0.0, 0.0, 0.0], 1.0));
    let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
    check(&d, -0.25, [1.0, 0.0, 0.0], true);
    // a's deepest points are on its face x = 0.75, b's on its face x = 1.
    assert!(close(d.point_a[0], 0.75) && close(d.point_b[0], 1.0));
}

#[test]
fn a_corner_above_a_face_is_its_height_away_and_unique() {
    // A tetrahedron's apex (0, 0, 3) over the cube's top face z = 1: 2 apart.
    let tet = Convex { points: vec![[0.0, 0.0, 3.0], [-1.0, -1.0, 5.0], [1.0, -1.0, 5.0], [0.0, 1.0, 5.0]] };
    let c = cube([0.0; 3], 1.0);
    let d = distance(Solid::Convex(&tet), Solid::Convex(&c)).unwrap();
    check(&d, 2.0, [0.0, 0.0, 1.0], false);
    assert!(close3(d.point_a, [0.0, 0.0, 3.0]), "{d:?}");
    assert!(close3(d.point_b, [0.0, 0.0, 1.0]), "{d:?}");
}

#[test]
fn crossing_edges_meet_at_their_closest_points() {
    // Segment-like hulls: x-axis segment at z = 0 and y-axis segment at z = 3.
    let a = Convex { points: vec![[-1.0, 0.0, 3.0], [1.0, 0.0, 3.0]] };
    let b = Convex { points: vec![[0.0, -1.0, 0.0], [0.0, 1.0, 0.0]] };
    let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
    check(&d, 3.0, [0.0, 0.0, 1.0], false);
    assert!(close3(d.point_a, [0.0, 0.0, 3.0]), "{d:?}");
    assert!(close3(d.point_b, [0.0, 0.0, 0.0]), "{d:?}");
}

#[test]
fn spheres_capsules_and_boxes_are_grown_cores() {
    let s = Sphere { center: [0.0, 0.0, 5.0], radius: 1.0 };
    let t = Sphere { center: [0.0, 0.0, 0.0], radius: 2.0 };
    let d = distance(Solid::Sphere(&s), Solid::Sphere(&t)).unwrap();
    check(&d, 2.0, [0.0, 0.0, 1.0], false);
    assert!(close3(d.point_a, [0.0, 0.0, 4.0]), "{d:?}");
    assert!(close3(d.point_b, [0.0, 0.0, 2.0]), "{d:?}");
    // Overlapping: centres 2 apart, radii 1 and 2: −1.
    let s = Sphere { center: [2.0, 0.0, 0.0], radius: 1.0 };
    let d = distance(Solid::Sphere(&s), Solid::Sphere(&t)).unwrap();
    check(&d, -1.0, [1.0, 0.0, 0.0], false);
    assert!(close3(d.point_a, [1.0, 0.0, 0.0]), "{d:?}");
    assert!(close3(d.point_b, [2.0, 0.0, 0.0]), "{d:?}");
    // A capsule lying along x at height 3, radius 0.5, over a unit box: the
    // axis is 2 above the top face z = 1, parallel to it: 1.5, degenerate.
    let c = Capsule { start: [-3.0, 0.0, 3.0], end: [3.0, 0.0, 3.0], radius: 0.5 };
    let b = OrientedBox { center: [0.0; 3], half_extents: [1.0; 3], rotation: [1.0, 0.0, 0.0, 0.0] };
    let d = distance(Solid::Capsule(&c), Solid::Box(&b)).unwrap();
    check(&d, 1.5, [0.0, 0.0, 1.0], true);
    // The 3-4-5 rotation about z turns the box: a sphere on its rotated x
    // axis at distance 6 from the centre is 5 from the face, minus its radius.
    let b = OrientedBox { center: [0.0; 3], half_extents: [1.0; 3], rotation: [2.0, 0.0, 0.0, 1.0] };
    let s = Sphere { center: [6.0 * 0.6, 6.0 * 0.8, 0.0], radius: 1.0 };
    let d = distance(Solid::Sphere(&s), Solid::Box(&b)).unwrap();
    check(&d, 4.0, [0.6, 0.8, 0.0], false);
}

#[test]
fn a_plane_takes_the_lowest_core_points() {
    let p = Plane { normal: [0.0, 0.0, 2.0], offset: 2.0 };
    // The plane z = 1, solid below. A unit cube centred at z = 3 rests 1 above.
    let c = cube([0.0, 0.0, 3.0], 1.0);
    let d = distance(Solid::Convex(&c), Solid::Plane(&p)).unwrap();
    check(&d, 1.0, [0.0, 0.0, 1.0], true);
    // A sphere of radius 3 at z = 2 reaches 2 below it.
    let s = Sphere { center: [5.0, 0.0, 2.0], radius: 3.0 };
    let d = distance(Solid::Sphere(&s), Solid::Plane(&p)).unwrap();
    check(&d, -2.0, [0.0, 0.0, 1.0], false);
    assert!(close3(d.point_b, [5.0, 0.0, 1.0]), "{d:?}");
    assert!(close3(d.point_a, [5.0, 0.0, -1.0]), "{d:?}");
}

#[test]
fn degenerate_hulls_are_answered() {
    // One point repeated: a single-point hull 3 above a triangle's plane.
    let p = Convex { points: vec![[0.25, 0.25, 3.0]; 4] };
    let t = Triangle { vertices: [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] };
    let d = distance(Solid::Convex(&p), Solid::Triangle(&t)).unwrap();
    check(&d, 3.0, [0.0, 0.0, 1.0], false);
    // Collinear points with repeats and interior ones: the segment from x = -2
    // to x = 2 at height 1, over the triangle: distance 1 and a segment of
    // witnesses (the part over the triangle).
    let s = Convex { points: vec![[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [-2.0, 0.0, 1.0], [1.0, 0.0, 1.0]] };
    let d = distance(Solid::Convex(&s), Solid::Triangle(&t)).unwrap();
    check(&d, 1.0, [0.0, 0.0, 1.0], true);
    // A flat square through a cube's middle penetrates: pushed out along
    // its own normal by the cube's half-size 1 (or sideways by 1 + 0.5 more).
    let sq = Convex { points: vec![[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.5, 0.5, 0.0], [-0.5, 0.5, 0.0]] };
    let d = distance(Solid::Convex(&sq), Solid::Convex(&cube([0.0; 3], 1.0))).unwrap();
    assert!(close(d.distance, -1.0), "{d:?}");
    // Two coincident points: no direction at all, the fallback normal.
    let o = Convex { points: vec![[1.0, 2.0, 3.0]] };
    let d = distance(Solid::Convex(&o), Solid::Convex(&o)).unwrap();
    check(&d, 0.0, [0.0, 0.0, 1.0], true);
    // A turned box without extent is a point, and with extent along one axis
    // a segment: its axes are not directions of its own (a full-range case
    // gave the box's first axis as the normal of a box and a point on it).
    let turned = [-3.0, 3.0, 1.0, -3.0];
    let point_box = OrientedBox { center: [1.0, 2.0, 3.0], half_extents: [0.0; 3], rotation: turned };
    let d = distance(Solid::Box(&point_box), Solid::Convex(&o)).unwrap();
    check(&d, 0.0, [0.0, 0.0, 1.0], true);
    // Along z: the segment from z = 1 to 3 at (0, 0); a point at (0, 0, 2) on it.
    let z = OrientedBox { center: [0.0, 0.0, 2.0], half_extents: [0.0, 0.0, 1.0], rotation: [1.0, 0.0, 0.0, 0.0] };
    let on = Convex { points: vec![[0.0, 0.0, 2.0]] };
    let d = distance(Solid::Box(&z), Solid::Convex(&on)).unwrap();
    // u × x for a line along z, u = (0, 0, ±1): (0, ±1, 0).
    assert!(close(d.distance, 0.0) && d.degenerate && close(d.normal[1].abs(), 1.0), "{d:?}");
}

#[test]
fn the_order_of_the_points_does_not_change_the_answer() {
    let pts =
        vec![[0.3, 1.1, 2.0], [1.7, -0.4, 2.5], [-0.9, 0.2, 3.1], [0.1, 0.1, 4.0], [0.5, 0.6, 2.9], [1.2, 1.3, 2.2]];
    let b = cube([0.0; 3], 1.0);
    let want = distance(Solid::Convex(&Convex { points: pts.clone() }), Solid::Convex(&b)).unwrap();
    let mut rev = pts.clone();
    rev.reverse();
    rev.rotate_left(2);
    let got = distance(Solid::Convex(&Convex { points: rev }), Solid::Convex(&b)).unwrap();
    // The referee rounds once from the exact answer, which the order does not
    // change: the same doubles.
    let same = |x: f64, y: f64| within_ulps(x, y, SAME_ANSWER_ULPS);
    assert!(same(got.distance, want.distance), "{got:?} vs {want:?}");
    assert!((0..3).all(|i| same(got.point_a[i], want.point_a[i]) && same(got.point_b[i], want.point_b[i])));
}

#[test]
fn far_tiny_and_huge_scenes() {
    for k in [1e-200, 1e-5, 1.0, 1e8, 1e200] {
        let (a, b) = (cube([2.5 * k, 0.0, 0.0], k), cube([0.0; 3], k));
        let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
        assert!(close(d.distance / k, 0.5), "scale {k}: {d:?}");
        let off = 1e8;
        let (a, b) = (cube([off + 1.75, off, off], 1.0), cube([off, off, off], 1.0));
        let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
        assert!(close(d.distance, -0.25), "{d:?}");
    }
}

mod sampled {
    use super::*;
    use proptest::prelude::*;

    /// The support gap along a direction `u` is a lower bound of the signed
    /// distance of convex sets (`min_a u·x − max_b u·x ≤ sd`, equality along
    /// the normal when apart); sampled in `f64` over points of size ≤ 4 it
    /// carries at most a few ulps of 4 per term: this bound.
    const SAMPLE_ROUNDING: f64 = 64.0 * f64::EPSILON;

    fn pt() -> impl Strategy<Value = P3> {
        [-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn the_distance_bounds_every_support_gap_and_meets_it_along_its_normal(
            pa in prop::collection::vec(pt(), 1..9),
            pb in prop::collection::vec(pt(), 1..9),
            shift in pt(),
        ) {
            let pa: Vec<P3> = pa.iter().map(|p| [p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]]).collect();
            let (a, b) = (Convex { points: pa.clone() }, Convex { points: pb.clone() });
            let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
            let gap = |u: P3| {
                let dot = |x: &P3| u[0] * x[0] + u[1] * x[1] + u[2] * x[2];
                let lo = pa.iter().map(dot).fold(f64::INFINITY, f64::min);
                let hi = pb.iter().map(dot).fold(f64::NEG_INFINITY, f64::max);
                lo - hi
            };
            for k in 0..200 {
                let t = k as f64 * 0.7;
                let z = (k as f64 / 100.0) - 1.0;
                let s = (1.0 - z * z).sqrt();
                let u = [s * t.cos(), s * t.sin(), z];
                prop_assert!(gap(u) <= d.distance + SAMPLE_ROUNDING, "gap {} over {}", gap(u), d.distance);
            }
            // Along the answer's own normal the gap is the distance, apart or
            // not (the least push's direction reaches it too).
            prop_assert!((gap(d.normal) - d.distance).abs() <= SAMPLE_ROUNDING, "{} vs {}", gap(d.normal), d.distance);
        }
    }
}

#[test]
fn concentric_cubes_tie_in_six_directions_and_every_one_is_an_answer() {
    // Two cubes of half-size 1 on one centre: a must move 2 along any of
    // ±x, ±y, ±z to leave b. The first is +x in the referee's order
    // (a's facet normals first); the five others are its alternatives,
    // each −2 along its own direction with a face as its witness sets.
    let (a, b) = (cube([0.0; 3], 1.0), cube([0.0; 3], 1.0));
    let d = distance(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
    assert!(close(d.distance, -2.0) && d.degenerate, "{d:?}");
    let alts = super::distance_alternatives(Solid::Convex(&a), Solid::Convex(&b)).unwrap();
    assert_eq!(alts.len(), 5, "{alts:?}");
    let mut normals: Vec<P3> = alts.iter().map(|(x, _)| x.normal).collect();
    normals.push(d.normal);
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let want: P3 = std::array::from_fn(|i| if i == axis { sign } else { 0.0 });
            assert!(normals.iter().any(|n| close3(*n, want)), "{want:?} among {normals:?}");
        }
    }
    for (alt, witnesses) in &alts {
        check(alt, -2.0, alt.normal, true);
        let (on_a, on_b) = witnesses.as_ref().expect("a face");
        assert_eq!((on_a.len(), on_b.len()), (4, 4), "{alt:?}");
    }
    // A unique least push has none.
    let shifted = cube([0.5, 0.0, 0.0], 1.0);
    let alts = super::distance_alternatives(Solid::Convex(&shifted), Solid::Convex(&b)).unwrap();
    assert!(alts.is_empty(), "{alts:?}");
}
