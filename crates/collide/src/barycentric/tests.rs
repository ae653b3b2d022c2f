//! Tests of the barycentric queries: hand-derived cases (derivation beside each),
//! degenerate inputs, properties, and slivers against exact evaluations. Test
//! bodies are generic and run for `f32` and `f64` (the hand-derived sliver
//! cases have one exact answer per precision's inputs, so one test each).

use super::*;
use crate::exact::{BigFloat, Estimate, Sign};
use crate::real::{Real, Vec3};
use crate::shapes::{Segment, Triangle};
use crate::test_support::{both, eps, prop_both, v};
use proptest::prelude::*;

/// Hand-derived cases: small integer or dyadic inputs whose answers are short
/// ratios; a handful of roundings, each at most ε/2 of a value ≤ 8 in magnitude.
/// Units: ε of the type under test, absolute on each coordinate.
const HAND_TOL_EPS: f64 = 16.0;

/// Sum of the signed coordinates: the largest-magnitude one is `fl(fl(1 − a) − b)`
/// (or `fl(1 − t)` on a segment), whose two roundings are each at most `ε/2` of
/// a value `≤ 1 + 2M`, `M` the largest coordinate magnitude. Proven bound
/// `1.5 ε max(1, M)`; units: ε times `max(1, M)`.
const SUM_TOL_EPS: f64 = 2.0;

/// Reconstruction of the projected point from the coordinates, for triangles of
/// thinness `τ = ‖n‖/L² ≥ MIN_THINNESS`: each numerator carries rounding of about
/// `ε ‖p − v‖ L ‖n‖` and the coordinate error is that over `‖n‖²`, so the
/// reconstructed point is off by about `ε (‖p − v0‖ + L)/τ`; 32 covers the few
/// terms and the measured spread. Units: ε times `(‖p − v0‖ + L)/τ`.
const RECON_TOL_EPS: f64 = 32.0;

/// The shapes the reconstruction properties use are no thinner than this
/// (`‖n‖/L²`; an equilateral triangle has √3/2): thinner ones are the subject of
/// the degeneracy sweeps, not of identities with a fixed tolerance.
const MIN_THINNESS: f64 = 1e-2;

/// Translation on a dyadic grid is exact (see [`translation_invariant`]), so the
/// results must agree to the last bit; one ε of slack keeps this a tolerance.
/// Units: ε times `max(1, M)`.
const TRANSLATION_TOL_EPS: f64 = 1.0;

fn wide3<T: Real>(p: &Vec3<T>) -> Vec3<f64> {
    Vec3::new(p.x.wide(), p.y.wide(), p.z.wide())
}

fn assert_coords<T: Real, const N: usize>(got: &Barycentric<T, N>, want: [f64; N], degenerate: bool, what: &str) {
    let tol = HAND_TOL_EPS * eps::<T>();
    for (i, (g, w)) in got.coords.iter().zip(want).enumerate() {
        let g = g.wide();
        assert!((g - w).abs() <= tol, "{what}: coordinate {i} is {g}, want {w} (all: {:?})", got.coords);
    }
    assert_eq!(got.degenerate, degenerate, "{what}: degenerate flag");
}

fn max_abs_coord<T: Real, const N: usize>(b: &Barycentric<T, N>) -> f64 {
    b.coords.iter().map(|x| x.wide().abs()).fold(1.0, f64::max)
}

fn sum_error<T: Real, const N: usize>(b: &Barycentric<T, N>) -> f64 {
    (b.coords.iter().map(|x| x.wide()).sum::<f64>() - 1.0).abs()
}

// ---------------------------------------------------------------- segment

fn segment_hand<T: Real>() {
    let seg = Segment::new(v::<T>(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0));
    // t = (p − a)·(b − a)/‖b − a‖² = (1·4 + 2·0)/16 = 1/4, off the line by 2.
    assert_coords(&barycentric_segment(&v(1.0, 2.0, 0.0), &seg), [0.75, 0.25], false, "inside, off line");
    // Before a: t = (−2·4)/16 = −1/2 → [3/2, −1/2].
    assert_coords(&barycentric_segment(&v(-2.0, 1.0, 0.0), &seg), [1.5, -0.5], false, "before a");
    // Past b: t = (6·4)/16 = 3/2 → [−1/2, 3/2].
    assert_coords(&barycentric_segment(&v(6.0, 0.0, -3.0), &seg), [-0.5, 1.5], false, "past b");
    // Endpoints are exact.
    assert_coords(&barycentric_segment(&seg.end, &seg), [0.0, 1.0], false, "at b");
}
both!(segment_hand_derived, segment_hand);

fn segment_lecture_hand<T: Real>() {
    let seg = Segment::new(v::<T>(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0));
    // On the segment: ‖p − b‖/4 = 3/4, ‖p − a‖/4 = 1/4 (same as signed).
    assert_coords(&barycentric_segment_lecture(&v(1.0, 0.0, 0.0), &seg), [0.75, 0.25], false, "on segment");
    // Before a at −4: ‖p − b‖ = 8, ‖p − a‖ = 4 → [2, 1], sum 3 (signed: [2, −1]).
    assert_coords(&barycentric_segment_lecture(&v(-4.0, 0.0, 0.0), &seg), [2.0, 1.0], false, "before a");
    // Off the line at (0, 3, 0): ‖p − b‖ = 5 (3-4-5), ‖p − a‖ = 3 → [5/4, 3/4].
    assert_coords(&barycentric_segment_lecture(&v(0.0, 3.0, 0.0), &seg), [1.25, 0.75], false, "off line");
}
both!(segment_lecture_hand_derived, segment_lecture_hand);

fn segment_degenerate<T: Real>() {
    let a = v::<T>(1.0, -2.0, 3.0);
    let seg = Segment::new(a, a);
    let p = v(5.0, 5.0, 5.0);
    assert_coords(&barycentric_segment(&p, &seg), [1.0, 0.0], true, "signed, zero length");
    assert_coords(&barycentric_segment_lecture(&p, &seg), [1.0, 0.0], true, "lecture, zero length");
    // A segment 1/max long (subnormal) with the point max/2 away: t ≈ max²/2
    // overflows in either type.
    let max = T::max_value().unwrap_or(T::one());
    let (tiny, huge) = (T::one() / max, max * T::of(0.5));
    let seg = Segment::new(Vec3::zeros(), Vec3::new(tiny, T::zero(), T::zero()));
    let far = Vec3::new(huge, T::zero(), T::zero());
    assert_coords(&barycentric_segment(&far, &seg), [0.0, 1.0], true, "signed, t overflows toward b");
    assert_coords(&barycentric_segment(&-far, &seg), [1.0, 0.0], true, "signed, t overflows toward a");
    let lec = barycentric_segment_lecture(&far, &seg);
    assert!(lec.degenerate, "lecture, ratio overflows: flagged");
    assert!(sum_error(&lec) <= eps::<T>(), "lecture fallback sums to 1: {:?}", lec.coords);
}
both!(segment_degenerate_inputs, segment_degenerate);

/// A segment, a point, and an exact dyadic translation.
#[derive(Clone, Debug)]
struct SegScene {
    a: [f64; 3],
    b: [f64; 3],
    p: [f64; 3],
    shift: [f64; 3],
}

fn grid() -> impl Strategy<Value = f64> {
    // Multiples of 1/64 in [−16, 16]: 11 significant bits.
    (-1024i32..=1024).prop_map(|k| f64::from(k) / 64.0)
}

fn grid3() -> impl Strategy<Value = [f64; 3]> {
    [grid(), grid(), grid()]
}

fn shift3() -> impl Strategy<Value = [f64; 3]> {
    // Integers in [−1024, 1024]: with the grid above, sums need ≤ 17 bits, exact
    // in f32 (24) and f64 (53).
    [-1024i32..=1024, -1024i32..=1024, -1024i32..=1024].prop_map(|k| k.map(f64::from))
}

fn seg_scene() -> impl Strategy<Value = SegScene> {
    (grid3(), grid3(), grid3(), shift3()).prop_map(|(a, b, p, shift)| SegScene { a, b, p, shift })
}

fn of3<T: Real>(x: [f64; 3]) -> Vec3<T> {
    v(x[0], x[1], x[2])
}

fn check_segment_identities<T: Real>(s: &SegScene) -> Result<(), TestCaseError> {
    let (a, b, p) = (of3::<T>(s.a), of3::<T>(s.b), of3::<T>(s.p));
    prop_assume!(a != b);
    let seg = Segment::new(a, b);
    let got = barycentric_segment(&p, &seg);
    prop_assert!(!got.degenerate, "non-zero segment flagged degenerate");
    let m = max_abs_coord(&got);
    prop_assert!(sum_error(&got) <= SUM_TOL_EPS * eps::<T>() * m, "sum {:?}", got.coords);
    // Reconstruction: a + t (b − a) is the projection of p (in f64 from the same
    // inputs; exact enough here, the inputs having 11 bits).
    let (aw, bw, pw) = (wide3(&a), wide3(&b), wide3(&p));
    let d = bw - aw;
    let proj = aw + d * ((pw - aw).dot(&d) / d.norm_squared());
    let rec = aw * got.coords[0].wide() + bw * got.coords[1].wide();
    let scale = (pw - aw).norm() + d.norm();
    prop_assert!(
        (rec - proj).norm() <= RECON_TOL_EPS * eps::<T>() * scale,
        "reconstruction {rec:?} vs projection {proj:?}"
    );
    // Lecture: never negative; sums to ≥ 1 (triangle inequality
    // ‖p − a‖ + ‖p − b‖ ≥ ‖b − a‖), up to rounding.
    let lec = barycentric_segment_lecture(&p, &seg);
    prop_assert!(lec.coords.iter().all(|x| *x >= T::zero()), "lecture negative: {:?}", lec.coords);
    let lsum: f64 = lec.coords.iter().map(|x| x.wide()).sum();
    prop_assert!(lsum >= 1.0 - SUM_TOL_EPS * eps::<T>() * 4.0, "lecture sum {lsum} < 1");
    Ok(())
}

fn check_segment_translation<T: Real>(s: &SegScene) -> Result<(), TestCaseError> {
    let t = of3::<T>(s.shift);
    let (a, b, p) = (of3::<T>(s.a), of3::<T>(s.b), of3::<T>(s.p));
    let here = barycentric_segment(&p, &Segment::new(a, b));
    let there = barycentric_segment(&(p + t), &Segment::new(a + t, b + t));
    let tol = TRANSLATION_TOL_EPS * eps::<T>() * max_abs_coord(&here);
    for i in 0..2 {
        prop_assert!((here.coords[i].wide() - there.coords[i].wide()).abs() <= tol, "{here:?} vs {there:?}");
    }
    prop_assert_eq!(here.degenerate, there.degenerate);
    Ok(())
}

fn check_segment_on_segment<T: Real>(s: &SegScene) -> Result<(), TestCaseError> {
    // Points on the segment: the lecture's ratios equal the signed coordinates.
    let (a, b) = (of3::<T>(s.a), of3::<T>(s.b));
    prop_assume!(a != b);
    let t = (s.p[0] + 16.0) / 32.0; // in [0, 1]
    let p = a + (b - a) * T::of(t);
    let seg = Segment::new(a, b);
    let (lec, sig) = (barycentric_segment_lecture(&p, &seg), barycentric_segment(&p, &seg));
    for i in 0..2 {
        prop_assert!(
            (lec.coords[i].wide() - sig.coords[i].wide()).abs() <= HAND_TOL_EPS * eps::<T>(),
            "lecture {:?} vs signed {:?}",
            lec.coords,
            sig.coords
        );
    }
    Ok(())
}

// ---------------------------------------------------------------- triangle

fn right_triangle<T: Real>() -> Triangle<T> {
    Triangle::new(v(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0), v(0.0, 4.0, 0.0))
}

fn triangle_hand<T: Real>() {
    let tri = right_triangle::<T>();
    // Projection of (1, 2, 7) is (1, 2, 0) = α v0 + β (4,0,0) + γ (0,4,0):
    // β = 1/4, γ = 2/4, α = 1/4. The height 7 does not matter.
    assert_coords(&barycentric_triangle(&v(1.0, 2.0, 7.0), &tri), [0.25, 0.25, 0.5], false, "inside, above");
    // Fourth corner of the parallelogram, v1 + v2 − v0 = (4, 4, 0): [−1, 1, 1].
    assert_coords(&barycentric_triangle(&v(4.0, 4.0, 0.0), &tri), [-1.0, 1.0, 1.0], false, "outside");
    // The vertices themselves.
    assert_coords(&barycentric_triangle(&tri.vertices[2], &tri), [0.0, 0.0, 1.0], false, "at v2");
    // Reversed winding (v0, v2, v1): coordinates follow the vertices.
    let rev = Triangle::new(tri.vertices[0], tri.vertices[2], tri.vertices[1]);
    assert_coords(&barycentric_triangle(&v(1.0, 2.0, -3.0), &rev), [0.25, 0.5, 0.25], false, "reversed");
    // A thin but genuine triangle, height 1e-3 over base 1 (τ = 1e-3, far above
    // the flatness threshold): midpoint of the height's foot and apex is
    // γ = 1/2, α = β = 1/4. Error grows like ε/τ: allow that factor.
    let thin = Triangle::new(v::<T>(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.5, 1e-3, 0.0));
    let got = barycentric_triangle(&v(0.5, 0.5e-3, 0.0), &thin);
    assert!(!got.degenerate, "thin triangle is not degenerate");
    for (g, w) in got.coords.iter().zip([0.25, 0.25, 0.5]) {
        assert!((g.wide() - w).abs() <= HAND_TOL_EPS * eps::<T>() * 1e3, "thin: {:?}", got.coords);
    }
}
both!(triangle_hand_derived, triangle_hand);

fn triangle_lecture_hand<T: Real>() {
    let tri = right_triangle::<T>();
    // S = 8. p = (1, 2, 0): area(p, v1, v2) = 8 − area(v0,p,v2) − area(v0,v1,p)
    // = 8 − ½·4·1 − ½·4·2 = 2 → α = 1/4; β = 2/8, γ = 4/8.
    assert_coords(&barycentric_triangle_lecture(&v(1.0, 2.0, 0.0), &tri), [0.25, 0.25, 0.5], false, "inside");
    // p = (4, 4, 0): area(p, v1, v2) = ½·|(0,−4)×(−4,0)| = 8 → 1; area(v0, p, v2)
    // = ½·4·4 = 8 → 1; area(v0, v1, p) = 8 → 1. Raw: [1, 1, 1], sum 3.
    assert_coords(&barycentric_triangle_lecture(&v(4.0, 4.0, 0.0), &tri), [1.0, 1.0, 1.0], false, "outside");
    // p = (0, 0, 3), above v0: (v1 − p) × (v2 − p) = (4,0,−3) × (0,4,−3) =
    // (12, 12, 16), norm √544; (v2 − p) × (v0 − p) = (−12, 0, 0); (v0 − p) ×
    // (v1 − p) = (0, −12, 0); over ‖n‖ = 16: [√544/16, 3/4, 3/4] — the height
    // inflates every area (signed: [1, 0, 0]).
    let want = [544f64.sqrt() / 16.0, 0.75, 0.75];
    assert_coords(&barycentric_triangle_lecture(&v(0.0, 0.0, 3.0), &tri), want, false, "above v0");
    assert_coords(&barycentric_triangle(&v(0.0, 0.0, 3.0), &tri), [1.0, 0.0, 0.0], false, "above v0, signed");
}
both!(triangle_lecture_hand_derived, triangle_lecture_hand);

fn triangle_degenerate<T: Real>() {
    let p = v::<T>(2.0, 5.0, 0.0);
    // Collinear (0,0,0), (1,0,0), (3,0,0): edges 1, 2, 3; the longest is v2 → v0.
    // t = (p − v2)·(v0 − v2)/9 = ((−1,5,0)·(−3,0,0))/9 = 1/3 → v2 gets 2/3, v0 1/3:
    // reconstructs (2, 0, 0), the closest point of the line.
    let col = Triangle::new(v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(3.0, 0.0, 0.0));
    let want = [1.0 / 3.0, 0.0, 2.0 / 3.0];
    assert_coords(&barycentric_triangle(&p, &col), want, true, "collinear");
    assert_coords(&barycentric_triangle_lecture(&p, &col), want, true, "collinear, lecture");
    // Two coincident vertices (0,0,0), (0,0,0), (2,0,0), p = (1,1,0): edges 0, 2,
    // 2; the first longest is v1 → v2, t = (1·2)/4 = 1/2 → [0, 1/2, 1/2].
    let dup = Triangle::new(v::<T>(0.0, 0.0, 0.0), v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0));
    assert_coords(&barycentric_triangle(&v(1.0, 1.0, 0.0), &dup), [0.0, 0.5, 0.5], true, "duplicate vertex");
    // All coincident: [1, 0, 0].
    let pt = Triangle::new(p, p, p);
    assert_coords(&barycentric_triangle(&v(9.0, 9.0, 9.0), &pt), [1.0, 0.0, 0.0], true, "coincident");
    assert_coords(&barycentric_triangle_lecture(&v(9.0, 9.0, 9.0), &pt), [1.0, 0.0, 0.0], true, "coincident, lecture");
    // Collinear up to 1e-20 relative (far below 16 ε in either type): the
    // lecture's float test flags it; closest point of edge v2 → v0 to
    // (1, 1, 0) is t = 2/3 → [2/3, 0, 1/3].
    let delta = T::of(1e-20);
    let near = Triangle::new(v::<T>(0.0, 0.0, 0.0), v(1.0, delta.wide(), 0.0), v(3.0, 0.0, 0.0));
    assert_coords(
        &barycentric_triangle_lecture(&v(1.0, 1.0, 0.0), &near),
        [2.0 / 3.0, 0.0, 1.0 / 3.0],
        true,
        "near collinear, lecture",
    );
    // The signed coordinates decide zero area exactly: this triangle has area
    // δ = T(1e-20) > 0 and p = (1, 1, 0) lies in its plane. From
    // p = α v0 + β v1 + γ v2: y gives β δ = 1, x gives β + 3γ = 1, so
    // β = 1/δ, γ = (1 − 1/δ)/3, α = 1 − β − γ = 2(1 − 1/δ)/3 (≈ 1e20: the
    // tolerance is relative to that size; the f64 expressions below round a
    // few times, far inside it).
    let got = barycentric_triangle(&v(1.0, 1.0, 0.0), &near);
    let beta = 1.0 / delta.wide();
    let want = [2.0 * (1.0 - beta) / 3.0, beta, (1.0 - beta) / 3.0];
    assert!(!got.degenerate, "near collinear: a genuine triangle");
    let size = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for i in 0..3 {
        assert!(
            (got.coords[i].wide() - want[i]).abs() <= accuracy::<T>() * size,
            "near collinear, signed: {:?} vs {want:?}",
            got.coords
        );
    }
    // A point beyond the type's range relative to a tiny triangle: coordinates
    // overflow, answered by the fallback (non-negative, summing to 1).
    let max = T::max_value().unwrap_or(T::one());
    let (tiny, huge) = (T::one() / max, max * T::of(0.5));
    let small =
        Triangle::new(Vec3::zeros(), Vec3::new(tiny, T::zero(), T::zero()), Vec3::new(T::zero(), tiny, T::zero()));
    let far = Vec3::new(huge, huge, T::zero());
    for got in [barycentric_triangle(&far, &small), barycentric_triangle_lecture(&far, &small)] {
        assert!(got.degenerate, "overflowing coordinates flagged: {got:?}");
        assert!(got.coords.iter().all(|x| x.finite() && *x >= T::zero()), "fallback: {got:?}");
        assert!(sum_error(&got) <= eps::<T>(), "fallback sums to 1: {got:?}");
    }
}
both!(triangle_degenerate_inputs, triangle_degenerate);

fn triangle_extreme_scales<T: Real>() {
    // The right-angled triangle (−M,−M), (M,−M), (−M,M) and p = (0, 0, ·): β = γ = 1/2,
    // α = 0 at any scale M. At 0.75 × the largest finite value the differences
    // overflow (the halving path); at the reciprocal of the largest finite value
    // the inputs are subnormal in f32 (the scaling path).
    let max = T::max_value().unwrap_or(T::one());
    for m in [max * T::of(0.75), T::one() / max, T::of(1e-3)] {
        let z = T::zero();
        let tri = Triangle::new(Vec3::new(-m, -m, z), Vec3::new(m, -m, z), Vec3::new(-m, m, z));
        let p = Vec3::new(z, z, m);
        assert_coords(&barycentric_triangle(&p, &tri), [0.0, 0.5, 0.5], false, &format!("signed at scale {m:?}"));
        let q = Vec3::new(z, z, z);
        assert_coords(
            &barycentric_triangle_lecture(&q, &tri),
            [0.0, 0.5, 0.5],
            false,
            &format!("lecture at scale {m:?}"),
        );
        let seg = Segment::new(tri.vertices[0], tri.vertices[1]);
        assert_coords(&barycentric_segment(&p, &seg), [0.5, 0.5], false, &format!("segment at scale {m:?}"));
        let on = Vec3::new(z, -m, z);
        assert_coords(&barycentric_segment_lecture(&on, &seg), [0.5, 0.5], false, &format!("segment lecture at {m:?}"));
    }
}
both!(extreme_scales, triangle_extreme_scales);

/// A triangle, a point given by its coordinates and height, and a translation.
#[derive(Clone, Debug)]
struct TriScene {
    v: [[f64; 3]; 3],
    /// `[β, γ, h]`: p = v0 + β e0 + γ e1 + h L n̂.
    coords: [f64; 3],
    shift: [f64; 3],
}

fn tri_scene() -> impl Strategy<Value = TriScene> {
    ([grid3(), grid3(), grid3()], [-2.0f64..3.0, -2.0f64..3.0, -2.0f64..2.0], shift3())
        .prop_map(|(v, coords, shift)| TriScene { v, coords, shift })
}

struct Built<T: Real> {
    tri: Triangle<T>,
    p: Vec3<T>,
    /// ‖n‖/L².
    thinness: f64,
    /// Longest edge.
    l: f64,
}

fn build<T: Real>(s: &TriScene) -> Built<T> {
    let tri = Triangle::new(of3::<T>(s.v[0]), of3(s.v[1]), of3(s.v[2]));
    let [a, b, c] = tri.vertices.map(|x| wide3(&x));
    let n = (b - a).cross(&(c - a));
    let l = (b - a).norm().max((c - a).norm()).max((c - b).norm());
    let thinness = if l > 0.0 { n.norm() / (l * l) } else { 0.0 };
    let nhat = if n.norm() > 0.0 { n / n.norm() } else { Vec3::zeros() };
    let [be, ga, h] = s.coords;
    let pw = a + (b - a) * be + (c - a) * ga + nhat * (h * l);
    Built { tri, p: v(pw.x, pw.y, pw.z), thinness, l }
}

fn check_triangle_identities<T: Real>(s: &TriScene) -> Result<(), TestCaseError> {
    let Built { tri, p, thinness, l } = build::<T>(s);
    prop_assume!(thinness >= MIN_THINNESS);
    let got = barycentric_triangle(&p, &tri);
    prop_assert!(!got.degenerate, "well-shaped triangle flagged degenerate");
    let m = max_abs_coord(&got);
    prop_assert!(sum_error(&got) <= SUM_TOL_EPS * eps::<T>() * m, "sum {:?}", got.coords);
    // Reconstruction of the projection, both relative to v0, in f64.
    let [a, b, c] = tri.vertices.map(|x| wide3(&x));
    let n = (b - a).cross(&(c - a));
    let q = wide3(&p) - a;
    let proj = q - n * (q.dot(&n) / n.norm_squared());
    let rec = (b - a) * got.coords[1].wide() + (c - a) * got.coords[2].wide();
    let tol = RECON_TOL_EPS * eps::<T>() * (q.norm() + l) / thinness;
    prop_assert!((rec - proj).norm() <= tol, "reconstruction {rec:?} vs projection {proj:?}, tol {tol:e}");
    // Lecture: never negative, sum ≥ 1 (the three sub-areas cover the triangle),
    // and equal to the signed coordinates when p is inside and in the plane.
    let lec = barycentric_triangle_lecture(&p, &tri);
    prop_assert!(!lec.degenerate, "lecture flagged a well-shaped triangle");
    prop_assert!(lec.coords.iter().all(|x| *x >= T::zero()), "lecture negative: {:?}", lec.coords);
    let lsum: f64 = lec.coords.iter().map(|x| x.wide()).sum();
    prop_assert!(lsum >= 1.0 - RECON_TOL_EPS * eps::<T>() / thinness, "lecture sum {lsum} < 1");
    Ok(())
}

fn check_triangle_lecture_inside<T: Real>(s: &TriScene) -> Result<(), TestCaseError> {
    // p inside and in the plane: fold (β, γ) into the triangle, no height.
    let mut s = s.clone();
    let (mut be, mut ga) = ((s.coords[0] + 2.0) / 5.0, (s.coords[1] + 2.0) / 5.0);
    if be + ga > 1.0 {
        (be, ga) = (1.0 - be, 1.0 - ga);
    }
    s.coords = [be, ga, 0.0];
    let Built { tri, p, thinness, l } = build::<T>(&s);
    prop_assume!(thinness >= MIN_THINNESS);
    let (lec, sig) = (barycentric_triangle_lecture(&p, &tri), barycentric_triangle(&p, &tri));
    let q = (wide3(&p) - wide3(&tri.vertices[0])).norm();
    let tol = RECON_TOL_EPS * eps::<T>() * (q + l) / (l * thinness);
    for i in 0..3 {
        prop_assert!(
            (lec.coords[i].wide() - sig.coords[i].wide()).abs() <= tol,
            "lecture {:?} vs signed {:?}",
            lec.coords,
            sig.coords
        );
    }
    Ok(())
}

fn check_triangle_translation<T: Real>(s: &TriScene) -> Result<(), TestCaseError> {
    let Built { tri, p, .. } = build::<T>(s);
    // Round p to the grid so that p + shift is exact too.
    let p = p.map(|x| T::of((x.wide() * 64.0).round() / 64.0));
    let t = of3::<T>(s.shift);
    let moved = Triangle::new(tri.vertices[0] + t, tri.vertices[1] + t, tri.vertices[2] + t);
    for (here, there) in [
        (barycentric_triangle(&p, &tri), barycentric_triangle(&(p + t), &moved)),
        (barycentric_triangle_lecture(&p, &tri), barycentric_triangle_lecture(&(p + t), &moved)),
    ] {
        let tol = TRANSLATION_TOL_EPS * eps::<T>() * max_abs_coord(&here);
        for i in 0..3 {
            prop_assert!((here.coords[i].wide() - there.coords[i].wide()).abs() <= tol, "{here:?} vs {there:?}");
        }
        prop_assert_eq!(here.degenerate, there.degenerate);
    }
    Ok(())
}

fn check_triangle_recovers<T: Real>(s: &TriScene) -> Result<(), TestCaseError> {
    // p built from (β, γ) and a height: the signed coordinates recover them. The
    // rounding of p itself (ε/2 of its coordinates' magnitude) enters too.
    let Built { tri, p, thinness, l } = build::<T>(s);
    prop_assume!(thinness >= MIN_THINNESS);
    let got = barycentric_triangle(&p, &tri);
    let [be, ga, _] = s.coords;
    let mag = tri.vertices.iter().chain([&p]).map(|x| wide3(x).amax()).fold(0.0, f64::max);
    let q = (wide3(&p) - wide3(&tri.vertices[0])).norm();
    let tol = RECON_TOL_EPS * eps::<T>() * (q + l + mag) / (l * thinness);
    for (g, w) in got.coords.iter().zip([1.0 - be - ga, be, ga]) {
        prop_assert!((g.wide() - w).abs() <= tol, "got {:?}, built from [{}, {be}, {ga}]", got.coords, 1.0 - be - ga);
    }
    Ok(())
}

fn check_collinear_fallback<T: Real>(s: &TriScene) -> Result<(), TestCaseError> {
    // Exactly collinear vertices on the grid: v2 = v0 + k (v1 − v0), k an integer
    // in [−3, 3] (exact: grid values times small integers stay on the grid).
    // Both functions flag them and return the closest point of the longest edge.
    let k = (s.coords[0] * 1.2).round().clamp(-3.0, 3.0);
    let [a, b, _] = s.v;
    let c = [0, 1, 2].map(|i| a[i] + k * (b[i] - a[i]));
    let tri = Triangle::new(of3::<T>(a), of3(b), of3(c));
    let p = of3::<T>(s.shift).map(|x| x / T::of(64.0));
    let vw = tri.vertices.map(|x| wide3(&x));
    // Longest edge (first of equals), edge j joining vertex j to (j + 1) % 3.
    let lens = [0, 1, 2].map(|j| (vw[(j + 1) % 3] - vw[j]).norm());
    let j = (0..3).fold(0, |best, j| if lens[j] > lens[best] { j } else { best });
    let (u, w) = (vw[j], vw[(j + 1) % 3]);
    let d = w - u;
    let closest = if d.norm() > 0.0 { u + d * ((wide3(&p) - u).dot(&d) / d.norm_squared()).clamp(0.0, 1.0) } else { u };
    for got in [barycentric_triangle(&p, &tri), barycentric_triangle_lecture(&p, &tri)] {
        prop_assert!(got.degenerate, "collinear triangle not flagged: {got:?}");
        prop_assert!(got.coords.iter().all(|x| *x >= T::zero()), "fallback negative: {got:?}");
        prop_assert!(sum_error(&got) <= eps::<T>(), "fallback sum: {got:?}");
        let rec = vw[0] * got.coords[0].wide() + vw[1] * got.coords[1].wide() + vw[2] * got.coords[2].wide();
        let scale = lens[j] + (wide3(&p) - u).norm();
        prop_assert!(
            (rec - closest).norm() <= RECON_TOL_EPS * eps::<T>() * scale,
            "fallback reconstructs {rec:?}, closest point of the longest edge is {closest:?}"
        );
    }
    Ok(())
}

// ------------------------------------------------------- any finite input

/// A finite value of `T` from a mantissa in [−1, 1] and an exponent fraction,
/// spread over the type's whole range (subnormals to the largest finite value).
fn finite_of<T: Real>(m: f64, frac: f64) -> T {
    let max = T::max_value().unwrap_or(T::one()).wide();
    let top = max.log2();
    let bottom = -top - T::EPSILON.wide().log2().abs();
    let e = bottom + frac * (top - bottom);
    let x = T::of((m * e.exp2()).clamp(-max, max));
    if x.finite() { x } else { T::of(max.copysign(m)) }
}

fn any_point() -> impl Strategy<Value = [(f64, f64); 3]> {
    [(-1.0f64..=1.0, 0.0f64..=1.0), (-1.0f64..=1.0, 0.0f64..=1.0), (-1.0f64..=1.0, 0.0f64..=1.0)]
}

fn any_of3<T: Real>(x: &[(f64, f64); 3]) -> Vec3<T> {
    Vec3::new(finite_of(x[0].0, x[0].1), finite_of(x[1].0, x[1].1), finite_of(x[2].0, x[2].1))
}

fn check_any_finite<T: Real>(pts: &[[(f64, f64); 3]; 4]) -> Result<(), TestCaseError> {
    let [a, b, c, p] = [0, 1, 2, 3].map(|i| any_of3::<T>(&pts[i]));
    let tri = Triangle::new(a, b, c);
    let seg = Segment::new(a, b);
    for got in [barycentric_triangle(&p, &tri), barycentric_triangle_lecture(&p, &tri)] {
        prop_assert!(got.coords.iter().all(|x| x.finite()), "non-finite: {got:?}");
        if got.degenerate {
            prop_assert!(got.coords.iter().all(|x| *x >= T::zero()), "fallback negative: {got:?}");
            prop_assert!(sum_error(&got) <= eps::<T>(), "fallback sum: {got:?}");
        }
    }
    let signed = barycentric_triangle(&p, &tri);
    prop_assert!(sum_error(&signed) <= SUM_TOL_EPS * eps::<T>() * max_abs_coord(&signed), "sum {signed:?}");
    for got in [barycentric_segment(&p, &seg), barycentric_segment_lecture(&p, &seg)] {
        prop_assert!(got.coords.iter().all(|x| x.finite()), "non-finite: {got:?}");
    }
    let signed = barycentric_segment(&p, &seg);
    prop_assert!(sum_error(&signed) <= SUM_TOL_EPS * eps::<T>() * max_abs_coord(&signed), "sum {signed:?}");
    Ok(())
}

prop_both!(1000, segment_sums_to_one_and_reconstructs, seg_scene(), check_segment_identities);
prop_both!(500, segment_translation_invariant, seg_scene(), check_segment_translation);
prop_both!(500, segment_lecture_equals_signed_on_segment, seg_scene(), check_segment_on_segment);
prop_both!(1000, triangle_sums_to_one_and_reconstructs, tri_scene(), check_triangle_identities);
prop_both!(500, triangle_lecture_equals_signed_inside, tri_scene(), check_triangle_lecture_inside);
prop_both!(500, translation_invariant, tri_scene(), check_triangle_translation);
prop_both!(500, collinear_triangle_falls_back_to_longest_edge, tri_scene(), check_collinear_fallback);
prop_both!(1000, triangle_recovers_built_coordinates, tri_scene(), check_triangle_recovers);
prop_both!(2000, any_finite_input_is_finite, [any_point(), any_point(), any_point(), any_point()], check_any_finite);

// ------------------------------------------------ slivers, against exact values

/// The accuracy `barycentric_triangle_tight` promises for any triangle of
/// non-zero area, however thin: each coordinate within this many ε of the
/// type under test, times the size `max(1, max |coordinate|)` (`f64`: the
/// filters' 12 ε plus 3.5 ε of final roundings, or 6.5 ε from the exact
/// path; `f32`: 2.5 ε_f32 from rounding the `f64` answer). Units: ε of `T`
/// times the size.
const TIGHT_TOL_EPS: f64 = 16.0;

/// The accuracy `barycentric_triangle` promises, relative to the size: in
/// `f64` the named `ACCURACY` (`2^−40`, the filters' certified bounds plus
/// final roundings, or the exact path's 6.5 ε); in `f32` the rounding of the
/// `f64` answer, within [`TIGHT_TOL_EPS`] ε_f32 (2.5 ε_f32 plus `2^−40`).
/// Unitless (a fraction of the size).
fn accuracy<T: Real>() -> f64 {
    if eps::<T>() > f64::EPSILON { TIGHT_TOL_EPS * eps::<T>() } else { area_ratios::ACCURACY }
}

/// [`TIGHT_TOL_EPS`] as a fraction of the size. Unitless.
fn tight_accuracy<T: Real>() -> f64 {
    TIGHT_TOL_EPS * eps::<T>()
}

/// The references' own error, relative to the size: the hand values are
/// correctly rounded (½ ulp), the [`BigFloat`] ones quotients of two values
/// each rounded to within `2^−52`, rounded once more (2.5 ε of `f64`); 4 ε of
/// `f64` covers both. Units: relative to the size.
const REFERENCE_TOL: f64 = 4.0 * f64::EPSILON;

/// Reconstruction of the projection from the coordinates, measured in the
/// plane: `Σ c_i v_i − p` has an in-plane part of at most
/// `(|δβ| + |δγ|) L + |Σ δc_i| ‖v0‖ ≤ 2 · a · size · (L + ‖v0‖)` for
/// coordinate errors within the accuracy `a` ([`accuracy`] or
/// [`tight_accuracy`]; the sum's own error is smaller). Units: `a` times
/// `size · (L + max ‖v_i‖)`.
const RECON_EXACT_FACTOR: f64 = 2.0;

/// Largest share of well-shaped random queries (thinness `‖n‖/L² ≥ 0.1`)
/// the exact path may take in `barycentric_triangle`: its fast filter's bound
/// is a few hundred `u` over `sin²` of the angle at `v0` against a target of
/// `2^−40 ≈ 8192 u` (for thinness above 0.1, `sin²θ0` is above 0.01), and
/// the scaled filter answers most of what it misses by a small factor.
/// Above this, the filter has stopped doing its job (slower, though still
/// right). Unitless fraction.
const MAX_EXACT_SHARE: f64 = 0.02;

/// The same for `barycentric_triangle_tight`, whose filters must meet `12 ε`:
/// their bounds (pessimistic by about an order of magnitude) certify about
/// half of these queries. Unitless fraction.
const MAX_TIGHT_EXACT_SHARE: f64 = 0.7;

/// Smallest share of those queries that fit the allocation-free narrow grid
/// (measured 98% for coordinates in a box of half-width 4: the inputs' bits
/// span fewer than 61 binades unless a coordinate is within about 1e-9 of
/// zero). Unitless fraction.
const MIN_NARROW_SHARE: f64 = 0.9;

fn big3(p: &[f64; 3]) -> [BigFloat; 3] {
    p.map(BigFloat::from_f64)
}

fn big_sub(a: &[BigFloat; 3], b: &[BigFloat; 3]) -> [BigFloat; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

fn big_dot(a: &[BigFloat; 3], b: &[BigFloat; 3]) -> BigFloat {
    &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
}

fn big_cross(a: &[BigFloat; 3], b: &[BigFloat; 3]) -> [BigFloat; 3] {
    [&(&a[1] * &b[2]) - &(&a[2] * &b[1]), &(&a[2] * &b[0]) - &(&a[0] * &b[2]), &(&a[0] * &b[1]) - &(&a[1] * &b[0])]
}

/// `num / den` from estimates (`den ≠ 0`), for values within `f64`'s range.
fn ratio(num: &Estimate, den: &Estimate) -> f64 {
    let q = num.mant / den.mant * f64::from(num.sign.as_i8() * den.sign.as_i8());
    let e = (num.exp - den.exp).clamp(-2000, 2000) as i32;
    q * 2f64.powi(e / 2) * 2f64.powi(e - e / 2)
}

/// An evaluation of the coordinates independent of `barycentric_triangle`'s
/// formula: Ericson's normal equations (`d00 = e0·e0`, `d01 = e0·e1`,
/// `d11 = e1·e1`, `d20 = q·e0`, `d21 = q·e1`, `q = p − v0`; `β = (d11 d20 −
/// d01 d21)/det`, `γ = (d00 d21 − d01 d20)/det`, `det = d00 d11 − d01²`), in
/// exact [`BigFloat`] arithmetic on the inputs' `f64` values. `None` when
/// `det = 0` (zero area).
fn reference_coords(p: &[f64; 3], v: &[[f64; 3]; 3]) -> Option<[f64; 3]> {
    let [v0, v1, v2] = v.map(|x| big3(&x));
    let (e0, e1, q) = (big_sub(&v1, &v0), big_sub(&v2, &v0), big_sub(&big3(p), &v0));
    let (d00, d01, d11) = (big_dot(&e0, &e0), big_dot(&e0, &e1), big_dot(&e1, &e1));
    let (d20, d21) = (big_dot(&q, &e0), big_dot(&q, &e1));
    let det = &(&d00 * &d11) - &(&d01 * &d01);
    if det.sign() == Sign::Zero {
        return None;
    }
    let nb = &(&d11 * &d20) - &(&d01 * &d21);
    let ng = &(&d00 * &d21) - &(&d01 * &d20);
    let na = &(&det - &nb) - &ng;
    let den = det.estimate();
    Some([na, nb, ng].map(|x| ratio(&x.estimate(), &den)))
}

/// The in-plane part of `Σ c_i v_i − p`, evaluated exactly:
/// `‖(Σ c_i v_i − p) × n‖ / ‖n‖` with `n = (v1 − v0) × (v2 − v0)` (the normal
/// component of the residual is the height of `p`, not an error).
fn in_plane_residual(p: &[f64; 3], v: &[[f64; 3]; 3], c: [f64; 3]) -> f64 {
    let [v0, v1, v2] = v.map(|x| big3(&x));
    let n = big_cross(&big_sub(&v1, &v0), &big_sub(&v2, &v0));
    let w = [v0, v1, v2];
    let rec: [BigFloat; 3] = [0, 1, 2].map(|k| {
        let s = &(&(&BigFloat::from_f64(c[0]) * &w[0][k]) + &(&BigFloat::from_f64(c[1]) * &w[1][k]))
            + &(&BigFloat::from_f64(c[2]) * &w[2][k]);
        &s - &BigFloat::from_f64(p[k])
    });
    let x = big_cross(&rec, &n);
    let num = big_dot(&x, &x).to_f64();
    let den = big_dot(&n, &n).to_f64();
    (num / den).sqrt()
}

fn size_of(c: &[f64; 3]) -> f64 {
    c.iter().fold(1.0f64, |m, x| m.max(x.abs()))
}

/// Asserts `got` is within the accuracy `acc` (a fraction of the size, plus
/// the reference's error) of `want`.
fn assert_exact<T: Real>(got: &Barycentric<T, 3>, want: [f64; 3], acc: f64, what: &str) {
    assert!(!got.degenerate, "{what}: not degenerate");
    let size = size_of(&want);
    let tol = (acc + REFERENCE_TOL) * size;
    for i in 0..3 {
        let g = got.coords[i].wide();
        assert!(
            (g - want[i]).abs() <= tol,
            "{what}: coordinate {i} is {g:e}, exact {:e} (all: {:?} vs {want:?}, tol {tol:e})",
            want[i],
            got.coords
        );
    }
}

/// A hand-derived case: what it is, `p`, the vertices, the exact answer.
type HandCase<F> = (&'static str, [F; 3], [[F; 3]; 3], [f64; 3]);

fn tri64(v: [[f64; 3]; 3]) -> Triangle<f64> {
    Triangle::new(Vec3::from(v[0]), Vec3::from(v[1]), Vec3::from(v[2]))
}

fn tri32(v: [[f32; 3]; 3]) -> Triangle<f32> {
    Triangle::new(Vec3::from(v[0]), Vec3::from(v[1]), Vec3::from(v[2]))
}

/// Regression: sliver cases the earlier floating-point formula got wrong, with
/// their exact answers. Each expectation is the exact rational value of the
/// coordinates for these `f64` inputs, correctly rounded: derived in a
/// throwaway script with Python's `fractions` (Cramer's rule on the inputs'
/// exact values, checking that the three sum to exactly 1). The first three
/// are crashtest report cases (seed 20261122, family "point and sliver
/// triangle", indices 509, 33 and 61: height 3.9e-8, 1.4e-12 and 3.1e-13 of
/// the length), where the earlier formula answered `[0.069, 1.145, −0.215]`,
/// `[0.757, 0.306, −0.063]` and `[−0.517, 1.069, 0.447]` without flagging
/// anything. The last two are a sliver of height 3.2e-16 of its length (v2 is
/// `v0 + 1.1 e + 2^−50 f`, rounded): the centroid lifted 3 units along the
/// normal (coordinates of order 1), and a point 3 units off along a direction
/// with an in-plane part (coordinates of order 1e14).
#[test]
fn sliver_cases_match_exact_rationals() {
    let sliver = [[0.3, -0.7, 1.1], [1.5, 0.8, 2.7], [0.8280000000000007, -0.040000000000000244, 1.804]];
    let cases: [HandCase<f64>; 5] = [
        (
            "report #509, mild sliver, p 3.5 lengths off the plane",
            [-1.0540418519000019, 0.7038643948363407, 1.500554546196526],
            [
                [0.12807552244162454, 0.8473128872246762, -0.5190271572212751],
                [0.5189640036784201, 0.5672521306439173, -0.10488249935725946],
                [0.339964074852238, 0.6955005872603441, -0.29453214838550296],
            ],
            [0.022799192196262138, 1.090717818612432, -0.11351701080869407],
        ),
        (
            "report #33, strong sliver",
            [-1.4302701939518323, 0.6586903593346985, 0.45239076543683454],
            [
                [-1.2582908862967848, 0.7217862581431916, 0.41080672506978794],
                [-1.812880315894489, 0.7076661531397176, 0.7934928915447673],
                [-1.7756124492444814, 0.708615010369736, 0.7677767558605717],
            ],
            [-159066.35322770628, -2208037.1701210137, 2367104.52334872],
        ),
        (
            "report #61, strong sliver, p nearly in the plane",
            [2.342770550134559, 1.4352679677136628, 0.25948075412939126],
            [
                [-0.2609991661960118, -0.8130299538091448, 0.8658732408276817],
                [1.8197771955561615, 0.9836746942909109, 0.3812807949147306],
                [0.5867599247706702, -0.08100861446417695, 0.6684384472626743],
            ],
            [-0.170624666203216, 1.3068446457945784, -0.13621997959136245],
        ),
        (
            "aspect 3e-16, centroid lifted 3 along the normal",
            [1.3949433976479813, 1.971443401572095, -0.350685737209824],
            sliver,
            [0.38727842917694966, 0.37571876578188934, 0.237002805041161],
        ),
        (
            "aspect 3e-16, p off the plane with an in-plane part",
            [2.436, 1.64, 2.988],
            sliver,
            [-251208595897445.75, -197378182490848.47, 448586778388295.25],
        ),
    ];
    for (what, p, v, want) in cases {
        let got = barycentric_triangle(&Vec3::from(p), &tri64(v));
        assert_exact(&got, want, accuracy::<f64>(), what);
        let tight = barycentric_triangle_tight(&Vec3::from(p), &tri64(v));
        assert_exact(&tight, want, tight_accuracy::<f64>(), &format!("{what}, tight"));
    }
}

/// The report cases #509, #33 and #61 with every input rounded to `f32`, and
/// the exact answers for those `f32` inputs (derived as in
/// [`sliver_cases_match_exact_rationals`]; rounding the inputs changes the
/// problem, hence different values).
#[test]
fn sliver_cases_match_exact_rationals_f32() {
    // The inputs are exactly f32 values, written as the f64 literals that
    // hold them (so `as f32` below is exact).
    let cases: [HandCase<f64>; 3] = [
        (
            "report #509 in f32",
            [-1.054041862487793, 0.7038643956184387, 1.5005545616149902],
            [
                [0.1280755251646042, 0.847312867641449, -0.5190271735191345],
                [0.5189639925956726, 0.5672521591186523, -0.10488250106573105],
                [0.3399640619754791, 0.6955006122589111, -0.2945321500301361],
            ],
            [-54912634.14393999, -65002030.1260587, 119914665.26999868],
        ),
        (
            "report #33 in f32",
            [-1.4302701950073242, 0.658690333366394, 0.45239076018333435],
            [
                [-1.2582908868789673, 0.7217862606048584, 0.41080671548843384],
                [-1.812880277633667, 0.7076661586761475, 0.7934929132461548],
                [-1.775612473487854, 0.7086150050163269, 0.7677767276763916],
            ],
            [-64489.23935864905, -895196.7235734808, 959686.96293213],
        ),
        (
            "report #61 in f32",
            [2.342770576477051, 1.4352679252624512, 0.259480744600296],
            [
                [-0.2609991729259491, -0.813029944896698, 0.8658732175827026],
                [1.819777250289917, 0.9836747050285339, 0.3812808096408844],
                [0.5867599248886108, -0.08100861310958862, 0.6684384346008301],
            ],
            [-2.634202575862972, -0.3869844759076702, 4.021187051770642],
        ),
    ];
    for (what, p, v, want) in cases {
        let narrow = |x: [f64; 3]| x.map(|c| c as f32);
        let (p, tri) = (Vec3::from(narrow(p)), tri32(v.map(narrow)));
        assert_exact(&barycentric_triangle(&p, &tri), want, accuracy::<f32>(), what);
        assert_exact(&barycentric_triangle_tight(&p, &tri), want, tight_accuracy::<f32>(), &format!("{what}, tight"));
    }
}

/// A sliver in a random pose: base point, direction of the long edge, a
/// second direction, length, where along the edge the apex sits, the aspect
/// exponent (`aspect = 10^−k`), the point's barycentric position and lift.
#[derive(Clone, Debug)]
struct SliverScene {
    v0: [f64; 3],
    e: [f64; 3],
    w: [f64; 3],
    len: f64,
    along: f64,
    k: f64,
    st: [f64; 2],
    lift: f64,
}

fn unit3() -> impl Strategy<Value = [f64; 3]> {
    [-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0]
}

fn sliver_scene() -> impl Strategy<Value = SliverScene> {
    (
        (unit3(), unit3(), unit3()),
        (0.5f64..4.0, 0.05f64..0.95, 1.0f64..=15.0),
        ([-0.25f64..1.25, -0.25f64..1.25], prop_oneof![Just(0.0), -2.0f64..2.0]),
    )
        .prop_map(|((v0, e, w), (len, along, k), (st, lift))| SliverScene {
            v0: v0.map(|x| 2.0 * x),
            e,
            w,
            len,
            along,
            k,
            st,
            lift,
        })
}

/// The scene's inputs in `T` (rounded), as `f64` (exactly).
fn build_sliver<T: Real>(s: &SliverScene) -> Option<([f64; 3], [[f64; 3]; 3])> {
    let e = Vec3::from(s.e);
    let e = e.try_normalize(1e-3)?;
    let w = Vec3::from(s.w);
    let f = (w - e * e.dot(&w)).try_normalize(1e-3)?;
    let v0 = Vec3::from(s.v0);
    let v1 = v0 + e * s.len;
    let v2 = v0 + e * (s.along * s.len) + f * (10f64.powf(-s.k) * s.len);
    let [be, ga] = s.st;
    let p = v0 + (v1 - v0) * be + (v2 - v0) * ga + e.cross(&f) * s.lift;
    let r = |x: Vec3<f64>| [x.x, x.y, x.z].map(|c| T::of(c).wide());
    Some((r(p), [r(v0), r(v1), r(v2)]))
}

fn check_sliver_exact<T: Real>(s: &SliverScene) -> Result<(), TestCaseError> {
    let Some((p, v)) = build_sliver::<T>(s) else {
        return Ok(());
    };
    let of = |x: [f64; 3]| Vec3::new(T::of(x[0]), T::of(x[1]), T::of(x[2]));
    let tri = Triangle::new(of(v[0]), of(v[1]), of(v[2]));
    let want = reference_coords(&p, &v);
    for (name, got, acc) in [
        ("barycentric_triangle", barycentric_triangle(&of(p), &tri), accuracy::<T>()),
        ("barycentric_triangle_tight", barycentric_triangle_tight(&of(p), &tri), tight_accuracy::<T>()),
    ] {
        let Some(want) = want else {
            // Rounding to T made the triangle exactly flat: the fallback.
            prop_assert!(got.degenerate, "{name}: zero-area triangle not flagged: {got:?}");
            continue;
        };
        prop_assert!(!got.degenerate, "{name}: triangle of non-zero area flagged: {got:?}");
        let size = size_of(&want);
        let tol = (acc + REFERENCE_TOL) * size;
        let c = got.coords.map(|x| x.wide());
        for i in 0..3 {
            prop_assert!(
                (c[i] - want[i]).abs() <= tol,
                "{name}: coordinate {i}: {:e} vs exact {:e} (all {c:?} vs {want:?}, tol {tol:e})",
                c[i],
                want[i]
            );
        }
        // The coordinates reconstruct the projection: Σ c_i v_i − p is normal
        // to the plane, up to the coordinates' errors.
        let l = [(0, 1), (1, 2), (2, 0)]
            .iter()
            .map(|&(i, j)| (Vec3::from(v[j]) - Vec3::from(v[i])).norm())
            .fold(0.0, f64::max);
        let m = v.iter().map(|x| Vec3::from(*x).norm()).fold(0.0, f64::max);
        let residual = in_plane_residual(&p, &v, c);
        let recon_tol = RECON_EXACT_FACTOR * acc * size * (l + m);
        prop_assert!(residual <= recon_tol, "{name}: in-plane residual {residual:e} > {recon_tol:e} for {c:?}");
    }
    Ok(())
}

prop_both!(1000, sliver_coordinates_are_within_the_promised_accuracy, sliver_scene(), check_sliver_exact);

/// Each exact evaluation (narrow grid, wide grid, [`BigFloat`]) on a sliver
/// whose inputs force it, against the independent reference; and zero area
/// decided exactly on each.
#[test]
fn every_exact_path_agrees_with_the_reference() {
    use super::area_ratios::{exact_kind, exact_path_count};
    let v = [
        [0.12807552244162454, 0.8473128872246762, -0.5190271572212751],
        [0.5189640036784201, 0.5672521306439173, -0.10488249935725946],
        [0.339964074852238, 0.6955005872603441, -0.29453214838550296],
    ];
    // A coordinate with its last bit at 2^−100 spreads the inputs over ~100
    // binades; one near 1e-25 over ~137.
    for (p, kind) in [
        ([-1.0540418519000019, 0.7038643948363407, 1.500554546196526], "narrow"),
        ([-1.0540418519000019, 0.7038643948363407, 3.5e-15], "wide"),
        ([-1.0540418519000019, 0.7038643948363407, 1e-25], "big"),
    ] {
        assert!(exact_kind(&p, &v) == kind, "{p:?} should take the {kind} path");
        let want = reference_coords(&p, &v).expect("a genuine triangle");
        let before = exact_path_count();
        let got = barycentric_triangle(&Vec3::from(p), &tri64(v));
        assert!(exact_path_count() == before + 1, "{kind}: the filter answered a sliver");
        assert_exact(&got, want, accuracy::<f64>(), kind);
    }
    // Exactly collinear vertices k · (1, 2, 3) with k spread over the same
    // ranges: flagged on every path.
    let dir = [1.0, 2.0, 3.0];
    for (small, kind) in [(0.5, "narrow"), (2f64.powi(-100), "wide"), (2f64.powi(-200), "big")] {
        let v = [[0.0; 3], dir.map(|x| x * small), dir.map(|x| x * 1024.0)];
        let p = [0.0, 0.0, 5.0];
        assert!(exact_kind(&p, &v) == kind, "collinear: {kind} path");
        assert!(reference_coords(&p, &v).is_none(), "collinear: zero area");
        let got = barycentric_triangle(&Vec3::from(p), &tri64(v));
        assert!(got.degenerate, "collinear on the {kind} path: {got:?}");
    }
}

/// The filters answer well-shaped queries without the exact path (all but a
/// handful for `barycentric_triangle`, a good share for the tight variant),
/// and those that need it mostly fit the narrow grid.
#[test]
fn filter_answers_well_shaped_queries() {
    use super::area_ratios::{P3, exact_kind, exact_path_count};
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let point = || prop::array::uniform3(-4.0f64..4.0);
    let strategy = (point(), point(), point(), point());
    let (mut cases, mut narrow, mut exact, mut tight_exact) = (0u32, 0u32, 0u64, 0u64);
    while cases < 2000 {
        let (p, a, b, c): (P3, P3, P3, P3) = strategy.new_tree(&mut runner).expect("a case").current();
        let tri = tri64([a, b, c]);
        let [x, y, z] = tri.vertices;
        let n = (y - x).cross(&(z - x));
        let l = (y - x).norm().max((z - x).norm()).max((z - y).norm());
        if n.norm() < 0.1 * l * l {
            continue;
        }
        cases += 1;
        narrow += u32::from(exact_kind(&p, &[a, b, c]) == "narrow");
        let before = exact_path_count();
        let got = barycentric_triangle(&Vec3::from(p), &tri);
        assert!(!got.degenerate, "well-shaped triangle flagged");
        exact += exact_path_count() - before;
        let before = exact_path_count();
        let got = barycentric_triangle_tight(&Vec3::from(p), &tri);
        assert!(!got.degenerate, "well-shaped triangle flagged (tight)");
        tight_exact += exact_path_count() - before;
    }
    let share = exact as f64 / f64::from(cases);
    assert!(share <= MAX_EXACT_SHARE, "exact path taken by {share:.3} of queries");
    let share = tight_exact as f64 / f64::from(cases);
    assert!(share <= MAX_TIGHT_EXACT_SHARE, "tight: exact path taken by {share:.3} of queries");
    let narrow = f64::from(narrow) / f64::from(cases);
    assert!(narrow >= MIN_NARROW_SHARE, "narrow grid fits only {narrow:.3}");
}

/// Regression: triangles whose coordinates span the whole `f64` range (raw
/// bit patterns from crashtest's full-range barycentric family, seed
/// 20261122, cases #160, #945 and #835). In the scaled filter's frame the
/// denominator `D̂` is about `2^−940`, so its acceptance test — the bounds
/// multiplied through by `D̂ (D̂ − B)` — underflowed to `0 ≤ 0` and
/// certified numerators that were pure rounding (`β = γ = 0`, answered
/// `[1, 0, 0]` for the exact `[1.000001, −9.97e-7, −3.3e-220]` and
/// `[1.3e-35, 1, −5.2e-168]`). Against the independent exact reference.
#[test]
fn scaled_filter_does_not_certify_underflowed_bounds() {
    let cases: [([f64; 3], [[f64; 3]; 3]); 3] = [
        (
            [7.467278377768561e-165, -1.1361900441823032e-137, 2663.153470133173],
            [
                [-2.312704422947053e+151, -4.571121435426069e+79, -6.660857384276954e+30],
                [-2.3195055350094972e+157, 1.8533137813369009e-242, 1.722692135241105e-276],
                [-2.3425524651652588e+176, -1.3919361931443998e+299, -5.5901651846061356e+184],
            ],
        ),
        (
            [-2.261968041063866e+42, 1.61831888936319e-164, -1.2260496509428935e-90],
            [
                [-1.7188808943645088e+77, -1.1663328194914507e-53, 1.9867023559200062e-29],
                [-3.8515525051642e-221, 6.0207175956428776e+16, -1.7262088903562762e-155],
                [-3.475190621974285e+104, 1.1551129341997111e+184, 9.627050383457715e+141],
            ],
        ),
        (
            [3.440409197747224e-219, 1.2705172451686673e-35, 3.1180087455132664e+175],
            [
                [2.0888192723913104e+93, -1.0053608857532008e-55, 3.905521734296366e+49],
                [1.1716475096646746e+182, 74850199353052.55, 1.0379638236874816e+195],
                [-5.084167611985097e-72, -4.276569186960503e-245, -2.6212751643403288e+95],
            ],
        ),
    ];
    for (k, (p, v)) in cases.iter().enumerate() {
        let want = reference_coords(p, v).expect("a genuine triangle");
        let got = barycentric_triangle(&Vec3::from(*p), &tri64(*v));
        assert_exact(&got, want, accuracy::<f64>(), &format!("full-range case {k}"));
        let got = barycentric_triangle_tight(&Vec3::from(*p), &tri64(*v));
        assert_exact(&got, want, tight_accuracy::<f64>(), &format!("full-range case {k} (tight)"));
    }
}
