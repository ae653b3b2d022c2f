//! Segment–triangle tests: hand-derived cases for both methods in both
//! precisions, and properties of the robust method.

use super::*;
use crate::exact::ESTIMATE_REL_ERR;
use proptest::prelude::*;

type P3 = [f64; 3];

fn v<T: Real>(p: P3) -> Vec3<T> {
    Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
}

fn seg<T: Real>(a: P3, b: P3) -> Segment<T> {
    Segment::new(v(a), v(b))
}

fn tri<T: Real>(a: P3, b: P3, c: P3) -> Triangle<T> {
    Triangle::new(v(a), v(b), v(c))
}

/// Tolerance on hand-case values (`t`, barycentrics, normal components, point
/// coordinates over the scene's scale), relative: a few roundings in `T` plus
/// the volumes' estimate error.
fn tol<T: Real>() -> f64 {
    16.0 * T::EPSILON.wide() + 4.0 * ESTIMATE_REL_ERR
}

/// Tolerance for the random properties (point on both shapes, barycentrics
/// reconstructing the point), relative to the scene's largest coordinate:
/// the point and the reconstruction each carry a handful of roundings in `T`
/// and up to 3 barycentric errors of `2ρ + 4ε`.
fn on_shape_tol<T: Real>() -> f64 {
    64.0 * T::EPSILON.wide() + 16.0 * ESTIMATE_REL_ERR
}

fn close<T: Real>(got: T, want: f64, scale: f64, what: &str) {
    let err = (got.wide() - want).abs();
    assert!(err <= tol::<T>() * scale, "{what}: got {:e}, want {want:e} (error {err:e})", got.wide());
}

fn close3<T: Real>(got: &Vec3<T>, want: P3, scale: f64, what: &str) {
    for i in 0..3 {
        close(got[i], want[i], scale, what);
    }
}

type Query<T> = fn(&Segment<T>, &Triangle<T>) -> Intersection<T>;

fn both<T: Real>() -> [(Query<T>, &'static str); 2] {
    [(intersect_segment_triangle_lecture::<T>, "lecture"), (intersect_segment_triangle::<T>, "robust")]
}

/// The reference triangle of the hand cases: `a = (0,0,0)`, `b = (4,0,0)`,
/// `c = (0,4,0)`; `n = (4,0,0) × (0,4,0) = (0,0,16)`, unit normal `(0,0,1)`.
/// A point `(x, y, 0)` has barycentrics `[1 − x/4 − y/4, x/4, y/4]`.
const A: P3 = [0.0, 0.0, 0.0];
const B: P3 = [4.0, 0.0, 0.0];
const C: P3 = [0.0, 4.0, 0.0];

/// Checks a hit against hand-derived values, for the triangle as given, for its
/// two cyclic rotations (barycentrics rotate with it) and for the reversed
/// segment (`t → 1 − t`, same point): the robust method is exactly invariant in
/// its classification, and both methods are in these cases.
fn expect_hit<T: Real>(f: Query<T>, name: &str, q: [P3; 2], tri_: [P3; 3], t: f64, point: P3, bary: [f64; 3]) {
    let scale = q.iter().chain(&tri_).flatten().fold(1.0f64, |m, x| m.max(x.abs()));
    for rot in 0..3 {
        let vs = [tri_[rot], tri_[(rot + 1) % 3], tri_[(rot + 2) % 3]];
        let want_bary = [bary[rot], bary[(rot + 1) % 3], bary[(rot + 2) % 3]];
        for (reverse, (q0, q1)) in [(false, (q[0], q[1])), (true, (q[1], q[0]))] {
            let r = f(&seg(q0, q1), &tri(vs[0], vs[1], vs[2]));
            let what = format!("{name}, rotation {rot}, reversed {reverse}");
            let h = r.hit.unwrap_or_else(|| panic!("{what}: expected a hit, got {r:?}"));
            assert!(!r.parallel && !r.degenerate, "{what}: flags {r:?}");
            close(h.t, if reverse { 1.0 - t } else { t }, 1.0, &what);
            close3(&h.point, point, scale, &what);
            let b = h.barycentric.expect("triangles report barycentrics");
            for i in 0..3 {
                close(b[i], want_bary[i], 1.0, &what);
            }
        }
    }
}

/// Checks "no hit" (a miss, or parallel) for the triangle and segment as given
/// and, when `reorder`, for the triangle's rotations and the reversed segment.
fn expect_no_hit<T: Real>(f: Query<T>, name: &str, q: [P3; 2], t: [P3; 3], parallel: bool, reorder: bool) {
    let n = if reorder { 3 } else { 1 };
    for rot in 0..n {
        for (q0, q1) in [(q[0], q[1]), (q[1], q[0])].into_iter().take(if reorder { 2 } else { 1 }) {
            let r = f(&seg(q0, q1), &tri(t[rot], t[(rot + 1) % 3], t[(rot + 2) % 3]));
            assert!(
                r.hit.is_none() && r.parallel == parallel && !r.degenerate,
                "{name}: expected {} for {q:?}, got {r:?}",
                if parallel { "parallel" } else { "a miss" }
            );
        }
    }
}

/// Hand cases common to both methods, one body for f32 and f64.
fn hand_cases<T: Real>() {
    let abc = [A, B, C];
    for (f, name) in both::<T>() {
        // Interior: (1,1,−1) → (1,1,3) crosses z = 0 at t = 1/4, at (1,1,0):
        // barycentrics [1 − 1/4 − 1/4, 1/4, 1/4]. The lecture: u·v = 0,
        // u·u = v·v = 16, w = (1,1,0), w·u = w·v = 4, D = −256,
        // s = (0 − 16·4)/(−256) = 1/4, t = 1/4.
        expect_hit(f, name, [[1.0, 1.0, -1.0], [1.0, 1.0, 3.0]], abc, 0.25, [1.0, 1.0, 0.0], [0.5, 0.25, 0.25]);
        let h = f(&seg([1.0, 1.0, -1.0], [1.0, 1.0, 3.0]), &tri(A, B, C)).hit.expect("interior hit");
        close3(&h.normal, [0.0, 0.0, 1.0], 1.0, "normal (0,0,16)/16, not flipped");
        let h = f(&seg([1.0, 1.0, 3.0], [1.0, 1.0, -1.0]), &tri(A, B, C)).hit.expect("interior hit");
        close3(&h.normal, [0.0, 0.0, 1.0], 1.0, "normal not flipped toward the segment");
        let h = f(&seg([1.0, 1.0, 3.0], [1.0, 1.0, -1.0]), &tri(A, C, B)).hit.expect("interior hit");
        close3(&h.normal, [0.0, 0.0, -1.0], 1.0, "the reversed triangle's normal");

        // Through edge ab at (2,0,0), t = 1/2: barycentrics [1/2, 1/2, 0].
        expect_hit(f, name, [[2.0, 0.0, -1.0], [2.0, 0.0, 1.0]], abc, 0.5, [2.0, 0.0, 0.0], [0.5, 0.5, 0.0]);
        // Through the diagonal edge bc at (2,2,0): [0, 1/2, 1/2].
        expect_hit(f, name, [[2.0, 2.0, -1.0], [2.0, 2.0, 1.0]], abc, 0.5, [2.0, 2.0, 0.0], [0.0, 0.5, 0.5]);
        // Through vertex b: [0, 1, 0].
        expect_hit(f, name, [[4.0, 0.0, -1.0], [4.0, 0.0, 1.0]], abc, 0.5, [4.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        // Endpoint exactly on the face: q0 = (1,1,0), t = 0, the point q0.
        expect_hit(f, name, [[1.0, 1.0, 0.0], [1.0, 1.0, 5.0]], abc, 0.0, [1.0, 1.0, 0.0], [0.5, 0.25, 0.25]);
        // Endpoint on an edge and on the face: (2,2,0), t = 0.
        expect_hit(f, name, [[2.0, 2.0, 0.0], [3.0, 7.0, 5.0]], abc, 0.0, [2.0, 2.0, 0.0], [0.0, 0.5, 0.5]);

        // Just outside edge ab: y = −2^−60 (the lecture, in this vertex order:
        // u·v = 0, w·v = −4·2^−60, t = −16·(−4·2^−60)/(−256) = −2^−62 < 0), and
        // just past vertex b: x = 4 + ulp(4) (s = (4 + 4ε)/4 = 1 + ε > 1). The
        // robust method misses in every vertex order and direction; the
        // lecture's rounding depends on the order (in the rotation (c, a, b)
        // its s computes to −0 and it reports a hit), so it is held to the
        // order derived here only.
        let reorder = name == "robust";
        let off = 2f64.powi(-60);
        expect_no_hit(f, name, [[2.0, -off, -1.0], [2.0, -off, 1.0]], abc, false, reorder);
        let past_b = 4.0 + 4.0 * T::EPSILON.wide();
        expect_no_hit(f, name, [[past_b, 0.0, -1.0], [past_b, 0.0, 1.0]], abc, false, reorder);
        // Beside the triangle, and short of it (both ends above).
        expect_no_hit(f, name, [[5.0, 5.0, -1.0], [5.0, 5.0, 1.0]], abc, false, true);
        expect_no_hit(f, name, [[1.0, 1.0, 1.0], [1.0, 1.0, 3.0]], abc, false, true);
        // Coplanar (crossing the triangle in its plane) and parallel above it:
        // n·(q1 − q0) = 16·0 = 0; parallel, no hit.
        expect_no_hit(f, name, [[-1.0, 1.0, 0.0], [5.0, 1.0, 0.0]], abc, true, true);
        expect_no_hit(f, name, [[-1.0, 1.0, 1.0], [5.0, 1.0, 1.0]], abc, true, true);

        // Degenerate: zero-area triangle (a, b, (8,0,0) collinear), zero-length
        // segment.
        for t in [tri(A, B, [8.0, 0.0, 0.0]), tri(A, A, C), tri(B, B, B)] {
            let r = f(&seg([1.0, 0.0, -1.0], [1.0, 0.0, 1.0]), &t);
            assert!(r.degenerate && r.hit.is_none(), "{name}: zero-area triangle {r:?}");
        }
        let r = f(&seg([1.0, 1.0, 0.0], [1.0, 1.0, 0.0]), &tri(A, B, C));
        assert!(r.degenerate && r.hit.is_none(), "{name}: zero-length segment {r:?}");
    }

    // Just outside the diagonal edge: (2, 2 + ulp(2), ·) has x + y > 4, so the
    // robust method misses. The lecture, as it is: t = (2 + 2ε)/4 = 1/2 + ε/2
    // exactly, s = 1/2, and s + t = 1 + ε/2 rounds (ties to even) to 1, so
    // it reports a hit. Known limitation, asserted as is.
    let y = 2.0 + 2.0 * T::EPSILON.wide();
    let q = [[2.0, y, -1.0], [2.0, y, 1.0]];
    expect_no_hit(intersect_segment_triangle::<T>, "robust", q, abc, false, true);
    let r = intersect_segment_triangle_lecture::<T>(&seg(q[0], q[1]), &tri(A, B, C));
    assert!(r.hit.is_some(), "lecture: s + t rounds to 1 and counts as inside: {r:?}");
}

#[test]
fn hand_cases_f32_and_f64() {
    hand_cases::<f32>();
    hand_cases::<f64>();
}

/// A segment stopping `tiny` short of a tilted triangle, touching it, and
/// reaching `tiny` past it; `tiny` = 1e-300 in f64, 1e-44 (subnormal) in f32.
fn stopping_short<T: Real>(tiny: f64) {
    // v0 = (−1,−1,−1), v1 = (1,−1,1), v2 = (0,2,0): the plane z = x, with
    // n = (2,0,2) × (1,3,1) = (−6, 0, 6). The origin is inside, at
    // barycentrics [1/3, 1/3, 1/3] (x: −α + β = 0, y: −α − β + 2γ = 0).
    // q0 = (−1, 0, 1): n·(q0 − v0) = (−6,0,6)·(0,1,2) = 12 > 0.
    // q1 = (−tiny, 0, 0): n·(q1 − v0) = −6(1 − tiny) + 6 = 6 tiny > 0: the
    // same side, a miss. q1 = 0: touching at t = 1. q1 = (tiny, 0, 0):
    // n·(q1 − v0) = −6 tiny, a hit at t = 12/(12 + 6 tiny) ≈ 1.
    let t = tri::<T>([-1.0, -1.0, -1.0], [1.0, -1.0, 1.0], [0.0, 2.0, 0.0]);
    let q0 = [-1.0, 0.0, 1.0];
    let r = intersect_segment_triangle(&seg::<T>(q0, [-tiny, 0.0, 0.0]), &t);
    assert!(r.hit.is_none() && !r.parallel && !r.degenerate, "short by {tiny:e}: {r:?}");
    let third = 1.0 / 3.0;
    for end in [[0.0, 0.0, 0.0], [tiny, 0.0, 0.0]] {
        let h = intersect_segment_triangle(&seg::<T>(q0, end), &t).hit.expect("touching or through: a hit");
        close(h.t, 1.0, 1.0, "t");
        close3(&h.point, [0.0; 3], 1.0, "point");
        let b = h.barycentric.expect("barycentrics");
        for x in b {
            close(x, third, 1.0, "barycentric");
        }
        let s = 0.5f64.sqrt();
        close3(&h.normal, [-s, 0.0, s], 1.0, "normal (−6,0,6)/‖·‖");
    }
    // The lecture, as it is: n·(q1 − q0) = −6(1 − tiny) − 6 rounds to −12 =
    // n·(v0 − q0), so r = 1 and P = q0 + (q1 − q0) lands inside: a hit.
    let l = intersect_segment_triangle_lecture(&seg::<T>(q0, [-tiny, 0.0, 0.0]), &t);
    assert!(l.hit.is_some(), "the lecture's rounded r = 1 counts as a hit: {l:?}");
}

#[test]
fn stopping_short_f32_and_f64() {
    stopping_short::<f32>(1e-44);
    stopping_short::<f64>(1e-300);
}

/// The interior case scaled by `s`; `lecture_fails`: the lecture's
/// intermediates leave `T`'s range at this scale (it must then say
/// degenerate).
fn scaled_scene<T: Real>(s: f64, lecture_fails: bool) {
    let m = |p: P3| p.map(|x| x * s);
    let (q0, q1) = (m([1.0, 1.0, -1.0]), m([1.0, 1.0, 3.0]));
    let t = tri::<T>(m(A), m(B), m(C));
    let r = intersect_segment_triangle(&seg::<T>(q0, q1), &t);
    let h = r.hit.unwrap_or_else(|| panic!("scale {s:e}: expected a hit, got {r:?}"));
    close(h.t, 0.25, 1.0, "t");
    close3(&h.point, m([1.0, 1.0, 0.0]), 4.0 * s, "point");
    close3(&h.normal, [0.0, 0.0, 1.0], 1.0, "normal");
    let b = h.barycentric.expect("barycentrics");
    for (x, want) in b.into_iter().zip([0.5, 0.25, 0.25]) {
        close(x, want, 1.0, "barycentric");
    }
    let l = intersect_segment_triangle_lecture(&seg::<T>(q0, q1), &t);
    if lecture_fails {
        // Known limitation of the lecture's method, asserted as is: its
        // intermediates overflow or underflow, so the answer is flagged
        // degenerate (never NaN).
        assert!(l.degenerate && l.hit.is_none(), "lecture at scale {s:e}: {l:?}");
    } else {
        assert!(l.hit.is_some(), "lecture at scale {s:e}: {l:?}");
    }
}

#[test]
fn huge_and_tiny_scenes_f32_and_f64() {
    // The lecture's n = u × v = (0, 0, 16 s²) is of degree 2 and
    // D = (u·v)² − (u·u)(v·v) = −256 s⁴ of degree 4. In f32, D overflows above
    // s ≈ 1.1e9 and n underflows to 0 below s ≈ 2.6e-23 (1e-30, 2^−120, 2^−140:
    // the last puts coordinates among the f32 subnormals).
    for (s, fails) in [
        (1.0, false),
        (1e4, false),
        (1e30, true),
        (1e-30, true),
        (2f64.powi(100), true),
        (2f64.powi(-120), true),
        (2f64.powi(-140), true),
    ] {
        scaled_scene::<f32>(s, fails);
    }
    // In f64, D overflows above s ≈ 1.6e76 and n underflows below s ≈ 5.5e-163;
    // 2^−1070 puts every coordinate among the f64 subnormals.
    for (s, fails) in [
        (1.0, false),
        (1e50, false),
        (1e-50, false),
        (1e100, true),
        (1e300, true),
        (1e-300, true),
        (2f64.powi(1000), true),
        (2f64.powi(-1000), true),
        (2f64.powi(-1070), true),
    ] {
        scaled_scene::<f64>(s, fails);
    }
}

// ---------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------

fn any_finite() -> impl Strategy<Value = f64> {
    use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO
}

fn any_finite_f32() -> impl Strategy<Value = f32> {
    use proptest::num::f32::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO
}

fn moderate() -> impl Strategy<Value = P3> {
    [-100.0..100.0f64, -100.0..100.0f64, -100.0..100.0f64]
}

fn grid() -> impl Strategy<Value = P3> {
    [-2i32..=2, -2i32..=2, -2i32..=2].prop_map(|p| p.map(f64::from))
}

/// A segment aimed at a point near the triangle (barycentrics `w`, possibly a
/// little outside), so that a good share of cases hit, graze or barely miss.
fn aimed() -> impl Strategy<Value = ([P3; 3], [P3; 2])> {
    (moderate(), moderate(), moderate(), [-0.2..1.2f64, -0.2..1.2f64], moderate(), -1.5..1.5f64).prop_map(
        |(a, b, c, [s, t], d, lambda)| {
            let p = [0, 1, 2].map(|i| a[i] + s * (b[i] - a[i]) + t * (c[i] - a[i]));
            let q0 = [0, 1, 2].map(|i| p[i] + lambda * d[i]);
            let q1 = [0, 1, 2].map(|i| p[i] - (1.0 - lambda.abs()) * d[i]);
            ([a, b, c], [q0, q1])
        },
    )
}

/// The answer's invariants for any input: no NaN, `t ∈ [0, 1]`, flags
/// consistent; for the robust method also unit normal and barycentrics in
/// `[0, 1]` summing to 1.
fn sane<T: Real>(r: &Intersection<T>, robust: bool) -> Result<(), TestCaseError> {
    // Unit length and the barycentric sum, within a few roundings of T.
    let unit_tol = 8.0 * T::EPSILON.wide();
    if let Some(h) = r.hit {
        prop_assert!(h.t.finite() && h.t >= T::zero() && h.t <= T::one(), "t = {:?}", h.t);
        prop_assert!(finite3(&h.point), "point {:?}", h.point);
        prop_assert!(finite3(&h.normal), "normal {:?}", h.normal);
        prop_assert!((h.normal.norm().wide() - 1.0).abs() <= unit_tol, "normal {:?} not unit", h.normal);
        let b = h.barycentric.expect("triangles report barycentrics");
        prop_assert!(b.iter().all(|x| x.finite()), "barycentrics {b:?}");
        prop_assert!(!r.parallel && !r.degenerate, "a hit is neither parallel nor degenerate");
        if robust {
            prop_assert!(b.iter().all(|&x| x >= T::zero() && x <= T::one()), "barycentrics {b:?}");
            let sum = b[0].wide() + b[1].wide() + b[2].wide();
            prop_assert!((sum - 1.0).abs() <= unit_tol, "barycentrics sum to {sum}");
        }
    }
    Ok(())
}

fn both_sane<T: Real>(p: [T; 15]) -> Result<(), TestCaseError> {
    let pt = |i: usize| Vec3::new(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    let s = Segment::new(pt(0), pt(1));
    let t = Triangle::new(pt(2), pt(3), pt(4));
    sane(&intersect_segment_triangle(&s, &t), true)?;
    sane(&intersect_segment_triangle_lecture(&s, &t), false)
}

/// Point on the segment and on the triangle's plane, barycentrics
/// reconstructing it; all relative to the scene's largest coordinate.
fn on_both_shapes<T: Real>(tri_: [P3; 3], q: [P3; 2]) -> Result<(), TestCaseError> {
    let s = seg::<T>(q[0], q[1]);
    let t = tri::<T>(tri_[0], tri_[1], tri_[2]);
    let r = intersect_segment_triangle(&s, &t);
    sane(&r, true)?;
    let Some(h) = r.hit else { return Ok(()) };
    let w = |x: &Vec3<T>| to_f64_3(x);
    let (q0, q1, p) = (w(&s.start), w(&s.end), w(&h.point));
    let [a, b, c] = t.vertices.map(|x| w(&x));
    let scale = [q0, q1, a, b, c].iter().flatten().fold(f64::MIN_POSITIVE, |m, x| m.max(x.abs()));
    let tol = on_shape_tol::<T>() * scale;
    let tt = h.t.wide();
    let on_seg = [0, 1, 2].map(|i| q0[i] + tt * (q1[i] - q0[i]));
    let d = (0..3).map(|i| (p[i] - on_seg[i]).abs()).fold(0.0, f64::max);
    prop_assert!(d <= tol, "{d:e} off the segment (tolerance {tol:e}): {h:?}");
    let n = w(&h.normal);
    let plane_dist = (0..3).map(|i| n[i] * (p[i] - a[i])).sum::<f64>().abs();
    prop_assert!(plane_dist <= tol, "{plane_dist:e} off the plane: {h:?}");
    let bary = h.barycentric.expect("barycentrics").map(|x| x.wide());
    let rebuilt = [0, 1, 2].map(|i| bary[0] * a[i] + bary[1] * b[i] + bary[2] * c[i]);
    let e = (0..3).map(|i| (rebuilt[i] - p[i]).abs()).fold(0.0, f64::max);
    prop_assert!(e <= tol, "barycentrics rebuild the point {e:e} away: {h:?}");
    Ok(())
}

/// The robust answer's invariance under cyclic rotation of the vertices
/// (barycentrics rotate) and under swapping the segment's ends (`t → 1 − t`).
fn invariant_under_reordering(tri_: [P3; 3], q: [P3; 2]) -> Result<(), TestCaseError> {
    /// Absolute, on t and barycentrics in [0, 1]: both answers within about
    /// 2^−40 of the exact value.
    const VALUE_TOL: f64 = 8.0 * ESTIMATE_REL_ERR + 8.0 * f64::EPSILON;
    let base = intersect_segment_triangle::<f64>(&seg(q[0], q[1]), &tri(tri_[0], tri_[1], tri_[2]));
    for rot in 0..3 {
        for reverse in [false, true] {
            let (q0, q1) = if reverse { (q[1], q[0]) } else { (q[0], q[1]) };
            let t = tri(tri_[rot], tri_[(rot + 1) % 3], tri_[(rot + 2) % 3]);
            let r = intersect_segment_triangle::<f64>(&seg(q0, q1), &t);
            prop_assert_eq!(r.parallel, base.parallel, "rotation {}, reversed {}", rot, reverse);
            prop_assert_eq!(r.degenerate, base.degenerate, "rotation {}, reversed {}", rot, reverse);
            prop_assert_eq!(r.hit.is_some(), base.hit.is_some(), "rotation {}, reversed {}", rot, reverse);
            if let (Some(h), Some(g)) = (r.hit, base.hit) {
                let want_t = if reverse { 1.0 - g.t } else { g.t };
                prop_assert!((h.t - want_t).abs() <= VALUE_TOL, "t {} vs {}", h.t, want_t);
                let (hb, gb) = (h.barycentric.expect("bary"), g.barycentric.expect("bary"));
                for i in 0..3 {
                    prop_assert!((hb[i] - gb[(i + rot) % 3]).abs() <= VALUE_TOL, "barycentrics {hb:?} vs {gb:?}");
                }
                prop_assert!((h.normal - g.normal).norm() <= VALUE_TOL, "normal {} vs {}", h.normal, g.normal);
            }
        }
    }
    Ok(())
}

/// Independent classification for small-integer inputs with the `robust`
/// crate (exact there), through the Plücker-style edge volumes
/// `orient3d(q0, q1, a, b)`, `(q0, q1, b, c)`, `(q0, q1, c, a)`: the line
/// passes through the closed triangle iff they do not have both strict signs.
#[derive(Debug, PartialEq)]
enum Kind {
    Degenerate,
    Parallel,
    Miss,
    Hit,
}

fn reference_kind(t: [P3; 3], q: [P3; 2]) -> Kind {
    let c3 = |p: P3| robust::Coord3D { x: p[0], y: p[1], z: p[2] };
    let o = |a: P3, b: P3, c: P3, d: P3| exact::Sign::of(robust::orient3d(c3(a), c3(b), c3(c), c3(d)));
    let [a, b, c] = t;
    if exact::points_equal(q[0], q[1]) {
        return Kind::Degenerate;
    }
    let (o0, o1) = (o(a, b, c, q[0]), o(a, b, c, q[1]));
    if o0 == exact::Sign::Zero && o1 == exact::Sign::Zero {
        let c2 = |p: P3, i: usize, j: usize| robust::Coord { x: p[i], y: p[j] };
        let flat = [(0, 1), (1, 2), (2, 0)]
            .iter()
            .all(|&(i, j)| robust::orient2d(c2(a, i, j), c2(b, i, j), c2(c, i, j)) == 0.0);
        return if flat { Kind::Degenerate } else { Kind::Parallel };
    }
    // n·(q1 − q0) = 0 iff a + (q1 − q0) is coplanar with a b c (exact on a grid).
    let shifted = [0, 1, 2].map(|i| a[i] + q[1][i] - q[0][i]);
    if o(a, b, c, shifted) == exact::Sign::Zero {
        return Kind::Parallel;
    }
    if o0 == o1 {
        return Kind::Miss;
    }
    let e = [o(q[0], q[1], a, b), o(q[0], q[1], b, c), o(q[0], q[1], c, a)];
    if e.contains(&exact::Sign::Positive) && e.contains(&exact::Sign::Negative) { Kind::Miss } else { Kind::Hit }
}

fn kind<T: Real>(r: &Intersection<T>) -> Kind {
    match (r.hit.is_some(), r.parallel, r.degenerate) {
        (_, _, true) => Kind::Degenerate,
        (_, true, _) => Kind::Parallel,
        (true, _, _) => Kind::Hit,
        _ => Kind::Miss,
    }
}

#[test]
fn filter_decides_random_queries_without_the_exact_path() {
    // Random segments and triangles in [−1, 1]³ (a deterministic LCG), about
    // a third of them aimed at the triangle so hits are common.
    const QUERIES: u64 = 5000;
    /// At most 0.2% of queries may take the exact path at all (none did when
    /// this was written).
    const MAX_EXACT: u64 = QUERIES / 500;
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut hits = 0;
    let before = exact::exact_evaluations();
    for i in 0..QUERIES {
        let mut p = || [next(), next(), next()];
        let (a, b, c) = (p(), p(), p());
        let (q0, mut q1) = (p(), p());
        if i % 3 == 0 {
            // Aim through the centroid.
            q1 = [0, 1, 2].map(|k| 2.0 * (a[k] + b[k] + c[k]) / 3.0 - q0[k]);
        }
        hits += usize::from(intersect_segment_triangle::<f64>(&seg(q0, q1), &tri(a, b, c)).hit.is_some());
    }
    let exact_calls = exact::exact_evaluations() - before;
    assert!(hits as u64 >= QUERIES / 4, "only {hits} hits: the test does not exercise the value path");
    assert!(exact_calls <= MAX_EXACT, "{exact_calls} exact evaluations in {QUERIES} queries");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn no_nan_and_no_panic_f64(p in proptest::array::uniform15(any_finite())) {
        both_sane::<f64>(p)?;
    }

    #[test]
    fn no_nan_and_no_panic_f32(p in proptest::array::uniform15(any_finite_f32())) {
        both_sane::<f32>(p)?;
    }

    #[test]
    fn no_nan_and_no_panic_in_moderate_scenes(a in moderate(), b in moderate(), c in moderate(), d in moderate(), e in moderate()) {
        let p = [a, b, c, d, e].concat();
        both_sane::<f64>(p.clone().try_into().expect("15 values"))?;
        both_sane::<f32>(p.iter().map(|&x| x as f32).collect::<Vec<_>>().try_into().expect("15 values"))?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn hit_point_is_on_both_shapes_f64((t, q) in aimed()) {
        on_both_shapes::<f64>(t, q)?;
    }

    #[test]
    fn hit_point_is_on_both_shapes_f32((t, q) in aimed()) {
        on_both_shapes::<f32>(t, q)?;
    }

    #[test]
    fn hit_point_is_on_both_shapes_at_extreme_scales((t, q) in aimed(), k in prop_oneof![900i32..1000, -1000i32..-900]) {
        let s = 2f64.powi(k);
        let m = |p: P3| p.map(|x| x * s);
        on_both_shapes::<f64>(t.map(m), q.map(m))?;
    }

    #[test]
    fn invariant_under_reordering_random((t, q) in aimed()) {
        invariant_under_reordering(t, q)?;
    }

    #[test]
    fn invariant_under_reordering_on_a_grid(a in grid(), b in grid(), c in grid(), q0 in grid(), q1 in grid()) {
        invariant_under_reordering([a, b, c], [q0, q1])?;
    }

    #[test]
    fn classification_matches_robust_on_a_grid(a in grid(), b in grid(), c in grid(), q0 in grid(), q1 in grid()) {
        let r = intersect_segment_triangle::<f64>(&seg(q0, q1), &tri(a, b, c));
        prop_assert_eq!(kind(&r), reference_kind([a, b, c], [q0, q1]));
        on_both_shapes::<f64>([a, b, c], [q0, q1])?;
    }

    #[test]
    fn classification_is_scale_invariant((t, q) in aimed(), k in -1000i32..1000) {
        // Scaling every coordinate by 2^k (exactly: prop_assume drops inputs
        // that would become subnormal) scales every volume by 2^3k: same
        // classification, same t and barycentrics.
        const VALUE_TOL: f64 = 8.0 * ESTIMATE_REL_ERR + 8.0 * f64::EPSILON;
        let s = 2f64.powi(k);
        prop_assume!(t.iter().chain(&q).flatten().all(|&x| x == 0.0 || (x * s).abs() >= f64::MIN_POSITIVE));
        let m = |p: P3| p.map(|x| x * s);
        let r = intersect_segment_triangle::<f64>(&seg(q[0], q[1]), &tri(t[0], t[1], t[2]));
        let rs = intersect_segment_triangle::<f64>(&seg(m(q[0]), m(q[1])), &tri(m(t[0]), m(t[1]), m(t[2])));
        prop_assert_eq!(kind(&r), kind(&rs));
        if let (Some(h), Some(g)) = (r.hit, rs.hit) {
            prop_assert!((h.t - g.t).abs() <= VALUE_TOL, "t {} vs {}", h.t, g.t);
            let (hb, gb) = (h.barycentric.expect("bary"), g.barycentric.expect("bary"));
            for i in 0..3 {
                prop_assert!((hb[i] - gb[i]).abs() <= VALUE_TOL, "barycentrics {hb:?} vs {gb:?}");
            }
        }
    }
}

// ---------------------------------------------------------------------------
// The inline filter against the general path
// ---------------------------------------------------------------------------

/// The filter's answer, where it gives one, is the general path's: the same
/// classification, and values within both answers' accuracy.
fn filter_agrees_with_general(t: [P3; 3], q: [P3; 2]) -> Result<(), TestCaseError> {
    /// Absolute, on t, barycentrics and normal components (all in [−1, 1]):
    /// each answer within about 2·2^−40 + a few roundings of the exact value.
    const VALUE_TOL: f64 = 8.0 * ESTIMATE_REL_ERR + 8.0 * f64::EPSILON;
    let g = general::<f64>(&seg(q[0], q[1]), &tri(t[0], t[1], t[2]));
    match filtered(&seg::<f64>(q[0], q[1]), &tri::<f64>(t[0], t[1], t[2])) {
        Filtered::Undecided => {}
        Filtered::Miss => prop_assert_eq!(kind(&g), Kind::Miss, "filter says miss: {:?}", g),
        Filtered::Parallel => prop_assert_eq!(kind(&g), Kind::Parallel, "filter says parallel: {:?}", g),
        Filtered::Degenerate => prop_assert_eq!(kind(&g), Kind::Degenerate, "filter says degenerate: {:?}", g),
        Filtered::Hit(h) => {
            let gh = g.hit.ok_or_else(|| TestCaseError::fail(format!("filter says hit: {g:?}")))?;
            prop_assert!((h.t - gh.t).abs() <= VALUE_TOL, "t {} vs {}", h.t, gh.t);
            prop_assert!((h.one_minus_t - (1.0 - gh.t)).abs() <= VALUE_TOL, "1 − t");
            let gb = gh.barycentric.expect("barycentrics");
            for i in 0..3 {
                prop_assert!((h.barycentric[i] - gb[i]).abs() <= VALUE_TOL, "{:?} vs {gb:?}", h.barycentric);
                prop_assert!((h.normal[i] - gh.normal[i]).abs() <= VALUE_TOL, "{:?} vs {}", h.normal, gh.normal);
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn filter_agrees_with_general_aimed((t, q) in aimed()) {
        filter_agrees_with_general(t, q)?;
    }

    #[test]
    fn filter_agrees_with_general_on_a_grid(a in grid(), b in grid(), c in grid(), q0 in grid(), q1 in grid()) {
        filter_agrees_with_general([a, b, c], [q0, q1])?;
    }

    #[test]
    fn filter_agrees_with_general_at_any_scale(p in proptest::array::uniform15(any_finite())) {
        let pt = |i: usize| [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
        filter_agrees_with_general([pt(0), pt(1), pt(2)], [pt(3), pt(4)])?;
    }
}

#[test]
fn filter_decides_random_queries_itself() {
    // The same random queries as `filter_decides_random_queries_without_the_exact_path`,
    // asked of the inline filter alone.
    const QUERIES: u64 = 5000;
    /// At most 0.2% may be left to the general path (none were when this was
    /// written).
    const MAX_UNDECIDED: u64 = QUERIES / 500;
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (mut hits, mut undecided) = (0u64, 0u64);
    for i in 0..QUERIES {
        let mut p = || [next(), next(), next()];
        let (a, b, c) = (p(), p(), p());
        let (q0, mut q1) = (p(), p());
        if i % 3 == 0 {
            q1 = [0, 1, 2].map(|k| 2.0 * (a[k] + b[k] + c[k]) / 3.0 - q0[k]);
        }
        match filtered(&seg::<f64>(q0, q1), &tri::<f64>(a, b, c)) {
            Filtered::Hit(_) => hits += 1,
            Filtered::Undecided => undecided += 1,
            Filtered::Miss | Filtered::Parallel | Filtered::Degenerate => {}
        }
    }
    assert!(hits >= QUERIES / 4, "only {hits} hits: the value path is not exercised");
    assert!(undecided <= MAX_UNDECIDED, "{undecided} of {QUERIES} left to the general path");
}

// ---------------------------------------------------------------------------
// Stage B: near-degenerate queries, decided without the general path
// ---------------------------------------------------------------------------

/// A scene built exactly on the grid of sixteenths (a triangle, a segment
/// through one of its edges or vertices, or lying in its plane, or parallel
/// to it), then, one way or another, nudged: endpoints moved `k` ulps
/// (`k ∈ [−4, 4]`, often 0), or the whole scene shifted far from the origin
/// (so exact relations hold only to rounding). These are the cases stage A
/// cannot decide and stage B exists for.
fn nudged() -> impl Strategy<Value = ([P3; 3], [P3; 2])> {
    let g = || (-32i32..=32).prop_map(|k| f64::from(k) / 16.0);
    let gp = move || [g(), g(), g()];
    (gp(), gp(), gp(), 0..4u8, (0..=16i32, 1..=8i32, 1..=8i32), gp(), (-4i32..=4, -4i32..=4), (0..3u8, 30..50i32))
        .prop_map(|(a, b, c, kind, (j, up, down), dir, (k0, k1), (far, e))| {
            let lerp = |x: P3, y: P3, f: f64| [0, 1, 2].map(|i| x[i] + (y[i] - x[i]) * f);
            // A point of edge a b (a vertex when j is 0 or 16).
            let x = lerp(a, b, f64::from(j) / 16.0);
            let (q0, q1) = match kind {
                // Through the edge point, along `dir`.
                0 => (
                    [0, 1, 2].map(|i| x[i] + dir[i] * f64::from(up)),
                    [0, 1, 2].map(|i| x[i] - dir[i] * f64::from(down)),
                ),
                // In the plane: from the edge point towards c and beyond.
                1 => (x, lerp(x, c, f64::from(up) / 4.0)),
                // Parallel: the in-plane segment lifted by a grid offset.
                2 => {
                    let lift = [0, 1, 2].map(|i| dir[i] / 4.0);
                    let (p, q) = (x, lerp(x, c, f64::from(up) / 4.0));
                    ([0, 1, 2].map(|i| p[i] + lift[i]), [0, 1, 2].map(|i| q[i] + lift[i]))
                }
                // One endpoint exactly on the plane (at the edge point).
                _ => (x, [0, 1, 2].map(|i| x[i] + dir[i])),
            };
            let step = |v: f64, k: i32| {
                let mut v = v;
                for _ in 0..k.unsigned_abs() {
                    v = if k > 0 { v.next_up() } else { v.next_down() };
                }
                v
            };
            let (q0, q1) = (q0.map(|v| step(v, k0)), q1.map(|v| step(v, k1)));
            let shift = if far == 0 { 2f64.powi(e) + 0.375 } else { 0.0 };
            let s = |p: P3| p.map(|v| v + shift);
            ([s(a), s(b), s(c)], [s(q0), s(q1)])
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Stage B's answers on near-degenerate scenes are the general path's.
    #[test]
    fn stage_b_agrees_with_general_on_nudged_scenes((t, q) in nudged()) {
        filter_agrees_with_general(t, q)?;
    }
}

#[test]
fn stage_b_decides_nudged_scenes_itself() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    /// Cases drawn.
    const CASES: u32 = 2000;
    /// At most 5% may be left to the general path (3.4% were when this was
    /// written): only exact zeros with inexact roundings behind them, such as
    /// a segment ending exactly on a vertex while its other end is off the
    /// grid (two edge volumes are exactly zero, but their compensated
    /// evaluation cannot see its roundings cancel).
    const MAX_UNDECIDED: u32 = CASES / 20;
    let mut runner = TestRunner::deterministic();
    let strategy = nudged();
    let mut undecided = 0;
    for _ in 0..CASES {
        let (t, q) = strategy.new_tree(&mut runner).expect("a case").current();
        if matches!(filtered(&seg::<f64>(q[0], q[1]), &tri::<f64>(t[0], t[1], t[2])), Filtered::Undecided) {
            undecided += 1;
        }
    }
    assert!(undecided <= MAX_UNDECIDED, "{undecided} of {CASES} nudged scenes left to the general path");
}
