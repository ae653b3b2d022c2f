//! Tests of the exact continuous collision referee: hand-derived cases (each
//! derivation beside it) and the floating-point stage against the exact one.
//!
//! Every expected time below is a double known exactly (a dyadic time such as
//! 0.5, IEEE 754's correctly rounded `2.0 / 3.0` or `0.5f64.sqrt()`), and the
//! referee's answer is correctly rounded, so they are compared bit for bit.

use super::*;
use crate::referee::exact::Q;
use crate::referee::stage::exact_only;

/// Random cases in the stage-agreement test, per kind of input.
const RANDOM_CASES: usize = 1500;

/// The triangle `(0,0,0), (1,0,0), (0,1,0)`, not moving.
const TRI: [P3; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

fn fixed(t: [P3; 3]) -> MovingTriangle {
    MovingTriangle { t0: t, t1: t }
}

fn pt(t0: P3, t1: P3) -> MovingPoint {
    MovingPoint { t0, t1 }
}

fn seg(a0: P3, a1: P3, b0: P3, b1: P3) -> MovingSegment {
    MovingSegment { t0: [a0, a1], t1: [b0, b1] }
}

/// An answer's bits: the time's exact bit pattern and the flag.
fn bits(a: CcdAnswer) -> (Option<u64>, bool) {
    (a.t.map(f64::to_bits), a.degenerate)
}

/// The staged answer, checked to be the exact stage's alone bit for bit.
fn vf(p: &MovingPoint, tri: &MovingTriangle, t_max: f64) -> (Option<u64>, bool) {
    let staged = bits(ccd_point_triangle(p, tri, t_max).unwrap());
    let exact = bits(exact_only(|| ccd_point_triangle(p, tri, t_max)).unwrap());
    assert_eq!(staged, exact, "stages disagree: {p:?} {tri:?} {t_max}");
    staged
}

fn ee(a: &MovingSegment, b: &MovingSegment, t_max: f64) -> (Option<u64>, bool) {
    let staged = bits(ccd_segment_segment(a, b, t_max).unwrap());
    let exact = bits(exact_only(|| ccd_segment_segment(a, b, t_max)).unwrap());
    assert_eq!(staged, exact, "stages disagree: {a:?} {b:?} {t_max}");
    staged
}

fn hit(t: f64, degenerate: bool) -> (Option<u64>, bool) {
    (Some(t.to_bits()), degenerate)
}

const MISS: (Option<u64>, bool) = (None, false);

#[test]
fn a_point_through_the_face_at_one_half() {
    // The triangle lies in z = 0; p = (1/4, 1/4, 1 − 2t) crosses it at t = 1/2,
    // inside (1/4 + 1/4 ≤ 1). f(t) = det[(1,0,0), (0,1,0), p] = 1 − 2t.
    let p = pt([0.25, 0.25, 1.0], [0.25, 0.25, -1.0]);
    assert_eq!(vf(&p, &fixed(TRI), 1.0), hit(0.5, false));
    // t_max = 1/2: the impact exactly at t_max counts; t_max = 1/4 cuts it off.
    assert_eq!(vf(&p, &fixed(TRI), 0.5), hit(0.5, false));
    assert_eq!(vf(&p, &fixed(TRI), 0.25), MISS);
    // The same path outside the triangle (x + y = 4 > 1): the plane is crossed, not the face.
    assert_eq!(vf(&pt([2.0, 2.0, 1.0], [2.0, 2.0, -1.0]), &fixed(TRI), 1.0), MISS);
    // Beside the triangle entirely (its swept box is apart): the fast stage's miss.
    assert_eq!(vf(&pt([5.0, 5.0, 1.0], [5.0, 5.0, 2.0]), &fixed(TRI), 1.0), MISS);
}

/// The irrational case: a = (0,0,0), b = (1,0,0) fixed, c = (0, 1, 2t), and
/// p = (1/8, t, 1). n = (b − a) × (c − a) = (0, −2t, 1), f = n·p = 1 − 2t²: the
/// root in [0, 1] is t = 1/√2. Then c = (0, 1, √2) and p = (1/8, 1/√2, 1) =
/// (1/8)·b + (1/√2)·c, with 1/8 + 1/√2 ≤ 1: inside. `scale` multiplies every
/// coordinate (a power of two: exact), which leaves f's roots alone.
fn irrational(scale: f64) -> (MovingPoint, MovingTriangle) {
    let s = |v: P3| v.map(|x| x * scale);
    let p = pt(s([0.125, 0.0, 1.0]), s([0.125, 1.0, 1.0]));
    let tri = MovingTriangle {
        t0: [s([0.0, 0.0, 0.0]), s([1.0, 0.0, 0.0]), s([0.0, 1.0, 0.0])],
        t1: [s([0.0, 0.0, 0.0]), s([1.0, 0.0, 0.0]), s([0.0, 1.0, 2.0])],
    };
    (p, tri)
}

#[test]
fn an_irrational_time_is_correctly_rounded() {
    let (p, tri) = irrational(1.0);
    let (t, degenerate) = vf(&p, &tri, 1.0);
    assert!(!degenerate);
    let t = f64::from_bits(t.expect("an impact at 1/√2"));
    // IEEE 754's square root is correctly rounded: RN(√(1/2)) = RN(1/√2).
    assert_eq!(t.to_bits(), 0.5f64.sqrt().to_bits());
    // And independently: 1 − 2x² changes sign between the midpoints around t
    // (exact rationals), so 1/√2 lies strictly inside t's rounding interval.
    let f = |x: Q| Q::ONE - Q::from(2) * &x * &x;
    let mid = |a: f64, b: f64| (Q::try_from(a).unwrap() + Q::try_from(b).unwrap()) / Q::from(2);
    assert!(f(mid(t.next_down(), t)) > Q::ZERO);
    assert!(f(mid(t, t.next_up())) < Q::ZERO);
}

/// A genuine cubic: a = (0,0,0) fixed, b = u(t) = (1, t, 0), c = v(t) = (0, 1, t),
/// p = w(t) = (u + v)/4 + e(t) with e = (t/16, 0, −1/32). u × v = (t², −t, 1), so
/// f = w·(u × v) = e·(u × v) = t³/16 − 1/32, whose only real root is t = 2^(−1/3)
/// ≈ 0.794 (f < 0 before it). There e(r) = (r/16)·u − (r²/16)·v (its z is
/// −r³/16 = −1/32), so p = (1/4 + r/16)·b + (1/4 − r²/16)·c: both weights
/// positive, sum ≈ 0.51 ≤ 1, inside.
fn cubic(scale: f64) -> (MovingPoint, MovingTriangle) {
    let s = |v: P3| v.map(|x| x * scale);
    let p = pt(s([0.25, 0.25, -0.03125]), s([0.3125, 0.5, 0.21875]));
    let tri = MovingTriangle {
        t0: [s([0.0, 0.0, 0.0]), s([1.0, 0.0, 0.0]), s([0.0, 1.0, 0.0])],
        t1: [s([0.0, 0.0, 0.0]), s([1.0, 1.0, 0.0]), s([0.0, 1.0, 1.0])],
    };
    (p, tri)
}

#[test]
fn an_irrational_root_of_a_cubic_is_correctly_rounded() {
    let (p, tri) = cubic(1.0);
    let (t, degenerate) = vf(&p, &tri, 1.0);
    assert!(!degenerate);
    let t = f64::from_bits(t.expect("an impact at 2^(-1/3)"));
    // x³ − 1/2 (f times 16) is negative at the midpoint below t and positive at
    // the one above (exact rationals): 2^(-1/3) is strictly inside t's rounding
    // interval, so t is its correct rounding. So too at the neighbouring doubles.
    let f = |x: Q| &x * &x * &x - Q::from_parts(1.into(), 2u8.into());
    let q = |x: f64| Q::try_from(x).unwrap();
    let mid = |a: f64, b: f64| (q(a) + q(b)) / Q::from(2);
    assert!(f(mid(t.next_down(), t)) < Q::ZERO);
    assert!(f(mid(t, t.next_up())) > Q::ZERO);
    assert!(f(q(t.next_down())) < Q::ZERO && f(q(t.next_up())) > Q::ZERO);
    // The same at 2^±997: the same time, bit for bit.
    for scale in [2f64.powi(997), 2f64.powi(-997)] {
        let (p, tri) = cubic(scale);
        assert_eq!(vf(&p, &tri, 1.0), hit(t, false), "scale {scale:e}");
    }
}

#[test]
fn the_first_root_outside_and_the_second_inside() {
    // a = (0,0,0), b = (1,0,0), c = (0, 1, u), u = 2t − 1: n = (0, −u, 1).
    // p = (1/4, u, 1/4): f = n·p = 1/4 − u², roots u = ∓1/2 (t = 1/4, 3/4).
    // At t = 1/4, p = (1/4, −1/2, 1/4) has y < 0: outside. At t = 3/4,
    // c = (0, 1, 1/2) and p = (1/4, 1/2, 1/4) = (1/4)·b + (1/2)·c: inside.
    let tri = MovingTriangle { t0: [TRI[0], TRI[1], [0.0, 1.0, -1.0]], t1: [TRI[0], TRI[1], [0.0, 1.0, 1.0]] };
    let p = pt([0.25, -1.0, 0.25], [0.25, 1.0, 0.25]);
    assert_eq!(vf(&p, &tri, 1.0), hit(0.75, false));
    assert_eq!(vf(&p, &tri, 0.5), MISS);
}

#[test]
fn huge_and_tiny_coordinates_give_the_scaled_time() {
    // Powers of two near 1e300 and 1e-300, and the extremes of f64 (2^1000: f's
    // coefficients near 2^3000; 2^-1070: the smallest coordinate 2^-1073 is subnormal).
    let want = 0.5f64.sqrt().to_bits();
    for scale in [2f64.powi(997), 2f64.powi(-997), 2f64.powi(1000), 2f64.powi(-1070)] {
        let (p, tri) = irrational(scale);
        assert_eq!(vf(&p, &tri, 1.0), (Some(want), false), "scale {scale:e}");
    }
    // The face crossing at 1/2, scaled the same way.
    for scale in [2f64.powi(997), 2f64.powi(-997), 2f64.powi(1020), 2f64.powi(-1072)] {
        let s = |v: P3| v.map(|x| x * scale);
        let p = pt(s([0.25, 0.25, 1.0]), s([0.25, 0.25, -1.0]));
        assert_eq!(vf(&p, &fixed(TRI.map(s)), 1.0), hit(0.5, false), "scale {scale:e}");
    }
}

#[test]
fn grazing_an_edge_and_a_vertex_exactly() {
    // p = (1/2, 0, 1 − 2t) meets the edge y = 0 at t = 1/2: on the closed triangle.
    assert_eq!(vf(&pt([0.5, 0.0, 1.0], [0.5, 0.0, -1.0]), &fixed(TRI), 1.0), hit(0.5, false));
    // p = (0, 0, 1 − 2t) meets the vertex (0,0,0).
    assert_eq!(vf(&pt([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]), &fixed(TRI), 1.0), hit(0.5, false));
    // One double below the edge (y = −2^-60): a miss, and the same beside the vertex.
    let y = -(2f64.powi(-60));
    assert_eq!(vf(&pt([0.5, y, 1.0], [0.5, y, -1.0]), &fixed(TRI), 1.0), MISS);
    assert_eq!(vf(&pt([y, y, 1.0], [y, y, -1.0]), &fixed(TRI), 1.0), MISS);
    // Beyond the hypotenuse x + y = 1 by 2^-53 at x = 1/2.
    let x = 0.5 + 2f64.powi(-53);
    assert_eq!(vf(&pt([x, 0.5, 1.0], [x, 0.5, -1.0]), &fixed(TRI), 1.0), MISS);
}

#[test]
fn touching_at_the_ends_of_the_interval() {
    // On the face at t = 0 and moving away: t = 0.
    assert_eq!(vf(&pt([0.25, 0.25, 0.0], [0.25, 0.25, 1.0]), &fixed(TRI), 1.0), hit(0.0, false));
    // Reaching the face exactly at t = 1 = t_max: counts.
    let p = pt([0.25, 0.25, 1.0], [0.25, 0.25, 0.0]);
    assert_eq!(vf(&p, &fixed(TRI), 1.0), hit(1.0, false));
    // t_max = 0: only t = 0, so that same motion misses; the first one still touches.
    assert_eq!(vf(&p, &fixed(TRI), 0.0), MISS);
    assert_eq!(vf(&pt([0.25, 0.25, 0.0], [0.25, 0.25, 1.0]), &fixed(TRI), 0.0), hit(0.0, false));
}

#[test]
fn coplanar_motion_is_degenerate() {
    // p = (−1 + 2t, 1/4, 0) slides in the triangle's plane (f ≡ 0) and enters the
    // triangle at x = 0, t = 1/2: degenerate, hit.
    assert_eq!(vf(&pt([-1.0, 0.25, 0.0], [1.0, 0.25, 0.0]), &fixed(TRI), 1.0), hit(0.5, true));
    // In the plane but past the triangle (y = 2): degenerate, no hit.
    assert_eq!(vf(&pt([-1.0, 2.0, 0.0], [1.0, 2.0, 0.0]), &fixed(TRI), 1.0), (None, true));
    // Planar and entering at x = 1/3 − ... : p = (−1 + 3t, 0, 0) reaches the
    // vertex a = (0,0,0) at t = 1/3: RN(1/3) = 1.0 / 3.0 (IEEE division of exact values).
    assert_eq!(vf(&pt([-1.0, 0.0, 0.0], [2.0, 0.0, 0.0]), &fixed(TRI), 1.0), hit(1.0 / 3.0, true));
}

#[test]
fn zero_area_triangles() {
    // A collinear triangle (0,0,0), (1,0,0), (2,0,0): n ≡ 0, so f ≡ 0 (planar,
    // degenerate); p = (1/2, 0, 1 − 2t) meets the segment at t = 1/2.
    let flat = fixed([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
    assert_eq!(vf(&pt([0.5, 0.0, 1.0], [0.5, 0.0, -1.0]), &flat, 1.0), hit(0.5, true));
    assert_eq!(vf(&pt([3.0, 0.0, 1.0], [3.0, 0.0, -1.0]), &flat, 1.0), (None, true));
    // A triangle that collapses at the impact: c = (0, 1 − 2t, 0), so n = (0, 0, 1 − 2t)
    // and, with p = (1/2, 0, 1 − 2t), f = (1 − 2t)²: a double root at 1/2, where
    // c = a and p = (1/2, 0, 0) lies on the edge ab. Not planar; zero area at the impact.
    let collapsing = MovingTriangle { t0: TRI, t1: [TRI[0], TRI[1], [0.0, -1.0, 0.0]] };
    assert_eq!(vf(&pt([0.5, 0.0, 1.0], [0.5, 0.0, -1.0]), &collapsing, 1.0), hit(0.5, true));
    // A point triangle (all three vertices equal) that p passes through.
    let dot = fixed([[1.0, 1.0, 1.0]; 3]);
    assert_eq!(vf(&pt([1.0, 1.0, 0.0], [1.0, 1.0, 4.0]), &dot, 1.0), hit(0.25, true));
}

#[test]
fn a_tangent_touch_is_a_double_root() {
    // a = (0,0,0), b = (1,0,0), c = (0, 1, u) with u = 2t − 1; p = (1/4, 1/2 − u/4, u/2).
    // n = (0, −u, 1), f = n·p = −u(1/2 − u/4) + u/2 = u²/4 ≥ 0: p touches the plane
    // at u = 0 (t = 1/2) without crossing it, at (1/4, 1/2, 0), inside (1/4 + 1/2 ≤ 1).
    let tri = MovingTriangle { t0: [TRI[0], TRI[1], [0.0, 1.0, -1.0]], t1: [TRI[0], TRI[1], [0.0, 1.0, 1.0]] };
    let p = pt([0.25, 0.75, -0.5], [0.25, 0.25, 0.5]);
    assert_eq!(vf(&p, &tri, 1.0), hit(0.5, false));
    // The same touch outside the triangle (x = 3/4: 3/4 + 1/2 > 1): no contact.
    let p = pt([0.75, 0.75, -0.5], [0.75, 0.25, 0.5]);
    assert_eq!(vf(&p, &tri, 1.0), MISS);
}

#[test]
fn edges_crossing_and_missing() {
    // a = [(−1,0,z), (1,0,z)], z = 1 − 2t, against b = [(0,−1,0), (0,1,0)]:
    // f = (da × w)·(b1 − a0) = 4z, they cross at (0,0,0) at t = 1/2; n = (0,0,4) ≠ 0.
    let a = seg([-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], [-1.0, 0.0, -1.0], [1.0, 0.0, -1.0]);
    let b = seg([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0]);
    assert_eq!(ee(&a, &b, 1.0), hit(0.5, false));
    assert_eq!(ee(&b, &a, 1.0), hit(0.5, false));
    assert_eq!(ee(&a, &b, 0.25), MISS);
    // Scaled by 2^±997 (near 1e300 and 1e-300, exact): the same time.
    for scale in [2f64.powi(997), 2f64.powi(-997)] {
        let s = |m: &MovingSegment| MovingSegment {
            t0: m.t0.map(|p| p.map(|x| x * scale)),
            t1: m.t1.map(|p| p.map(|x| x * scale)),
        };
        assert_eq!(ee(&s(&a), &s(&b), 1.0), hit(0.5, false), "scale {scale:e}");
    }
    // b moved to x = 3, beyond a's end at x = 1: the lines cross, the segments do not.
    let far = seg([3.0, -1.0, 0.0], [3.0, 1.0, 0.0], [3.0, -1.0, 0.0], [3.0, 1.0, 0.0]);
    assert_eq!(ee(&a, &far, 1.0), MISS);
    // b ending exactly at y = 0 (an end touching a's interior): a hit at 1/2.
    let end = seg([0.0, -1.0, 0.0], [0.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 0.0]);
    assert_eq!(ee(&a, &end, 1.0), hit(0.5, false));
    // ... and ending 2^-70 short of it.
    let y = -(2f64.powi(-70));
    let short = seg([0.0, -1.0, 0.0], [0.0, y, 0.0], [0.0, -1.0, 0.0], [0.0, y, 0.0]);
    assert_eq!(ee(&a, &short, 1.0), MISS);
}

#[test]
fn parallel_collinear_and_zero_length_edges() {
    // a = [(0,0,0), (1,0,0)] fixed; b0 = (1/2, 0, z), b1 = (2, z, z), z = 1 − 2t.
    // f = (da × w)·(b1 − a0) = (0, −z, 0)·(2, z, z) = −z²: a double root at 1/2,
    // where b = [(1/2,0,0), (2,0,0)] is collinear with a and overlaps it on
    // [1/2, 1]; before that b is above z = 0. Parallel at the impact: degenerate.
    let a = seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let b = seg([0.5, 0.0, 1.0], [2.0, 1.0, 1.0], [0.5, 0.0, -1.0], [2.0, -1.0, -1.0]);
    assert_eq!(ee(&a, &b, 1.0), hit(0.5, true));
    // Parallel throughout (a rising to meet b in the xz plane): planar, degenerate.
    // a = [(0,0,z), (1,0,z)], z = 1 − 2t, b = [(1/2,0,0), (2,0,0)]: they overlap at t = 1/2.
    let a = seg([0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 0.0, -1.0], [1.0, 0.0, -1.0]);
    let b = seg([0.5, 0.0, 0.0], [2.0, 0.0, 0.0], [0.5, 0.0, 0.0], [2.0, 0.0, 0.0]);
    assert_eq!(ee(&a, &b, 1.0), hit(0.5, true));
    // Parallel throughout, apart (b at y = 1): planar, no contact.
    let b = seg([0.5, 1.0, 0.0], [2.0, 1.0, 0.0], [0.5, 1.0, 0.0], [2.0, 1.0, 0.0]);
    assert_eq!(ee(&a, &b, 1.0), (None, true));
    // Collinear, sliding: b = [(2 − 3t/2, 0, 0), (3 − 3t/2, 0, 0)] reaches a's end
    // x = 1 when 2 − 3t/2 = 1, t = 2/3: RN(2/3) = 2.0 / 3.0 (IEEE division).
    let a = seg([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let b = seg([2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.5, 0.0, 0.0]);
    assert_eq!(ee(&a, &b, 1.0), hit(2.0 / 3.0, true));
    // A zero-length a (a point at (1/2, 0, 1 − 2t)) through b = [(0,0,0), (1,0,0)]:
    // da ≡ 0, f ≡ 0; it lands on b at t = 1/2.
    let dot = seg([0.5, 0.0, 1.0], [0.5, 0.0, 1.0], [0.5, 0.0, -1.0], [0.5, 0.0, -1.0]);
    assert_eq!(ee(&dot, &a, 1.0), hit(0.5, true));
    assert_eq!(ee(&a, &dot, 1.0), hit(0.5, true));
    // Both of zero length, meeting: p = (t, 0, 0) and q = (1 − t, 0, 0) at t = 1/2.
    let p = seg([0.0; 3], [0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let q = seg([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]);
    assert_eq!(ee(&p, &q, 1.0), hit(0.5, true));
}

#[test]
fn refused_input_names_the_field() {
    let p = pt([0.0; 3], [0.0; 3]);
    let mut tri = fixed(TRI);
    tri.t1[2][1] = f64::NAN;
    assert_eq!(ccd_point_triangle(&p, &tri, 1.0), Err(RefereeError::NonFinite { field: "tri.t1" }));
    let bad = pt([0.0, f64::INFINITY, 0.0], [0.0; 3]);
    assert_eq!(ccd_point_triangle(&bad, &fixed(TRI), 1.0), Err(RefereeError::NonFinite { field: "p.t0" }));
    for t_max in [f64::NAN, f64::INFINITY] {
        assert_eq!(ccd_point_triangle(&p, &fixed(TRI), t_max), Err(RefereeError::NonFinite { field: "t_max" }));
    }
    for t_max in [-0.5, 1.5, 1.0 + f64::EPSILON] {
        assert_eq!(ccd_point_triangle(&p, &fixed(TRI), t_max), Err(RefereeError::TimeOutOfRange { field: "t_max" }));
    }
    let s = seg([0.0; 3], [1.0, 0.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]);
    let mut b = s;
    b.t1[0][2] = f64::NEG_INFINITY;
    assert_eq!(ccd_segment_segment(&s, &b, 1.0), Err(RefereeError::NonFinite { field: "b.t1" }));
    assert_eq!(ccd_segment_segment(&b, &s, 1.0), Err(RefereeError::NonFinite { field: "a.t1" }));
}

/// SplitMix64: a small deterministic generator for the random cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [−1, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// On the grid of eighths in [−1, 1]: exact zeros and coplanarities happen.
    fn grid(&mut self) -> f64 {
        (self.next() % 17) as f64 / 8.0 - 1.0
    }

    fn point(&mut self, kind: usize) -> P3 {
        match kind {
            0 => [self.unit(), self.unit(), self.unit()],
            1 => [self.grid(), self.grid(), self.grid()],
            // Near the plane z = 0: near-coplanar motion.
            2 => [self.unit(), self.unit(), self.unit() * 2f64.powi(-40)],
            // Each coordinate at its own magnitude, anywhere in f64's range.
            _ => [self.wide(), self.wide(), self.wide()],
        }
    }

    /// `unit() · 2^k`, `k` uniform in `[−1074, 1023]` (subnormal to huge).
    fn wide(&mut self) -> f64 {
        let k = (self.next() % 2098) as i32 - 1074;
        let x = self.unit() * 2f64.powi(k.clamp(-1022, 1023));
        if k < -1022 { x * 2f64.powi(k + 1022) } else { x }
    }

    fn t_max(&mut self) -> f64 {
        if self.next().is_multiple_of(2) { 1.0 } else { (self.next() % 9) as f64 / 8.0 }
    }
}

#[test]
fn the_fast_stage_agrees_with_the_exact_stage_on_random_input() {
    let mut rng = Rng(0x5eed);
    let mut hits = 0;
    for kind in 0..4 {
        // Full-range input costs the exact stage milliseconds a case: fewer of them.
        let cases = if kind == 3 { RANDOM_CASES / 10 } else { RANDOM_CASES };
        for _ in 0..cases {
            let mut r = || rng.point(kind);
            let (p, tri) = (pt(r(), r()), MovingTriangle { t0: [r(), r(), r()], t1: [r(), r(), r()] });
            let (a0, a1, b0, b1) = (r(), r(), r(), r());
            let (c0, c1, d0, d1) = (r(), r(), r(), r());
            let t_max = rng.t_max();
            // `vf` and `ee` check the staged answer against the exact stage's.
            hits += usize::from(vf(&p, &tri, t_max).0.is_some());
            hits += usize::from(ee(&seg(a0, a1, c0, c1), &seg(b0, b1, d0, d1), t_max).0.is_some());
        }
    }
    // The random input is not all misses (the exact stage is exercised on hits).
    assert!(hits > 0);
}

/// How far (squared) the point may be from the triangle at the rounded
/// time of a hit on grid input: the exact time is within `2^-53` of it and
/// nothing moves faster than `2√3` per unit time, so the distance is below
/// `7·2^-53 < 2^-50`.
const HIT_DISTANCE_SQUARED: f64 = 1.0 / (1u128 << 100) as f64;

/// Sample times per unit of time in the independent check.
const SAMPLES: u32 = 64;

/// The exact squared distance from `p` to `tri` at the rational time `t`
/// (the referee's exact closest point: a method independent of this one).
fn distance_squared(p: &MovingPoint, tri: &MovingTriangle, t: &Q) -> Q {
    use crate::referee::exact::{dot, lerp, sub, v3};
    let at = |a: &P3, b: &P3| lerp(&v3(a, "").unwrap(), &v3(b, "").unwrap(), t);
    let x = at(&p.t0, &p.t1);
    let v = [at(&tri.t0[0], &tri.t1[0]), at(&tri.t0[1], &tri.t1[1]), at(&tri.t0[2], &tri.t1[2])];
    let d = sub(&x, &crate::referee::closest::closest_on_triangle(&x, &v));
    dot(&d, &d)
}

#[test]
fn answers_agree_with_exact_distances_at_sampled_times() {
    // Grid input: at every sampled time before the answer (or in [0, t_max] for
    // a miss) the point is apart from the triangle, exactly; at the answer's
    // rounded time it is within the rounding's reach of it.
    let mut rng = Rng(7);
    let mut hits = 0;
    for _ in 0..RANDOM_CASES / 3 {
        let mut r = || rng.point(1);
        let (p, tri) = (pt(r(), r()), MovingTriangle { t0: [r(), r(), r()], t1: [r(), r(), r()] });
        let t_max = rng.t_max();
        let answer = ccd_point_triangle(&p, &tri, t_max).unwrap();
        // Samples strictly before the exact first time (2^-40 below the rounded one).
        let end = answer.t.map_or(t_max, |t| t - 2f64.powi(-40));
        for k in 0..=SAMPLES {
            let s = f64::from(k) / f64::from(SAMPLES);
            if s < end || (answer.t.is_none() && s <= t_max) {
                let d = distance_squared(&p, &tri, &Q::try_from(s).unwrap());
                assert!(d > Q::ZERO, "contact at {s} before the answer {answer:?}: {p:?} {tri:?} {t_max}");
            }
        }
        if answer.t.is_none() {
            let d = distance_squared(&p, &tri, &Q::try_from(t_max).unwrap());
            assert!(d > Q::ZERO, "contact at t_max, answer {answer:?}: {p:?} {tri:?}");
        }
        if let Some(t) = answer.t {
            hits += 1;
            assert!((0.0..=t_max).contains(&t), "{t} outside [0, {t_max}]");
            let d = distance_squared(&p, &tri, &Q::try_from(t).unwrap());
            assert!(d <= Q::try_from(HIT_DISTANCE_SQUARED).unwrap(), "apart at the answer {t}: {p:?} {tri:?}");
        }
    }
    assert!(hits > 0);
}

#[test]
fn a_clear_miss_is_answered_by_the_fast_stage_and_counted() {
    // p = (1/4, 1/4, 1 + t) above the triangle in z = 0: f = 1 + t > 0 on [0, 1],
    // its Bernstein coefficients are all positive, a certified miss (counted on
    // this thread, so other tests running meanwhile do not change it).
    let ccd = || {
        crate::referee::stage_counts_on_this_thread()
            .into_iter()
            .find(|(s, _, _)| *s == crate::referee::Stage::Ccd)
            .map(|(_, fast, exact)| (fast, exact))
    };
    let before = ccd();
    assert_eq!(vf(&pt([0.25, 0.25, 1.0], [0.25, 0.25, 2.0]), &fixed(TRI), 1.0), MISS);
    let after = ccd();
    assert_eq!(after.map(|c| c.0), before.map(|c| c.0 + 1), "{before:?} → {after:?}");
    assert_eq!(after.map(|c| c.1), before.map(|c| c.1), "{before:?} → {after:?}");
}
