//! Tests of the predicates: hand-derived cases, agreement with the `robust`
//! crate where it is exact, agreement with a direct [`BigFloat`] evaluation for
//! every finite input, and the filter's hit rate.

use super::estimate::ldexp;
use super::*;
use proptest::prelude::*;

fn bf(x: f64) -> BigFloat {
    BigFloat::from_f64(x)
}

/// Reference: `det[a − d, b − d, c − d]` written out in BigFloat, independently
/// of the predicates' code (cofactor expansion along the first column).
fn det_reference(a: P3, b: P3, c: P3, d: P3) -> BigFloat {
    let r = |p: P3| [&bf(p[0]) - &bf(d[0]), &bf(p[1]) - &bf(d[1]), &bf(p[2]) - &bf(d[2])];
    let (a, b, c) = (r(a), r(b), r(c));
    let minor = |u: &[BigFloat; 3], v: &[BigFloat; 3], i: usize, j: usize| &(&u[i] * &v[j]) - &(&u[j] * &v[i]);
    // det = a0 (b1 c2 − c1 b2) − b0 (a1 c2 − c1 a2) + c0 (a1 b2 − b1 a2)
    let t0 = &a[0] * &minor(&b, &c, 1, 2);
    let t1 = &b[0] * &minor(&a, &c, 1, 2);
    let t2 = &c[0] * &minor(&a, &b, 1, 2);
    &(&t0 - &t1) + &t2
}

fn robust3(p: P3) -> robust::Coord3D<f64> {
    robust::Coord3D { x: p[0], y: p[1], z: p[2] }
}

fn robust_orient3d(a: P3, b: P3, c: P3, d: P3) -> Sign {
    Sign::of(robust::orient3d(robust3(a), robust3(b), robust3(c), robust3(d)))
}

/// Relative difference of two estimates of the same non-zero value.
fn rel_diff(x: Estimate, y: Estimate) -> f64 {
    let e = x.exp.max(y.exp);
    let (a, b) = (ldexp(x.mant, x.exp - e), ldexp(y.mant, y.exp - e));
    (a - b).abs() / b
}

/// The bound an estimate requested at [`ESTIMATE_REL_ERR`] must meet against the
/// exact value, as seen through the exact value's own estimate (which adds at
/// most 2^−53 relative, plus 2^−53 for the comparison's rounding).
const ESTIMATE_CHECK: f64 = ESTIMATE_REL_ERR + f64::EPSILON;

fn any_finite() -> impl Strategy<Value = f64> {
    use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO
}

fn any_point() -> impl Strategy<Value = P3> {
    [any_finite(), any_finite(), any_finite()]
}

/// Coordinates where `robust` (Shewchuk's expansions) is exact: no overflow and
/// no underflow in products of differences up to degree 3.
fn moderate_point() -> impl Strategy<Value = P3> {
    [-1e6..1e6f64, -1e6..1e6f64, -1e6..1e6f64]
}

/// Small integers: many exactly coplanar quadruples.
fn grid_point() -> impl Strategy<Value = P3> {
    [-3i32..=3, -3i32..=3, -3i32..=3].prop_map(|p| p.map(f64::from))
}

/// A point near the plane of `a b c`: `a + s (b − a) + t (c − a)` rounded,
/// which is coplanar only when the rounding happens to be exact.
fn near_plane(a: P3, b: P3, c: P3, s: f64, t: f64) -> P3 {
    [0, 1, 2].map(|i| a[i] + s * (b[i] - a[i]) + t * (c[i] - a[i]))
}

#[test]
fn orient3d_unit_tetrahedron() {
    // det[a − d, b − d, c − d] with d = (0,0,1): rows (0,0,−1), (1,0,−1),
    // (0,1,−1); expanding along the first row, det = −1·(1·1 − 0·0) = −1.
    // d is above the counterclockwise triangle a b c: negative, as Shewchuk.
    let (a, b, c, d) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    assert!(orient3d(a, b, c, d) == Sign::Negative, "d above: negative");
    assert!(orient3d(a, b, c, [0.0, 0.0, -1.0]) == Sign::Positive, "d below: positive");
    assert!(orient3d(a, b, c, [5.0, -7.0, 0.0]) == Sign::Zero, "d in the plane: zero");
    assert!(orient3d(b, a, c, d) == Sign::Positive, "swapping a and b flips the sign");
    // Scaled by 2^−1074·2^k: every coordinate a subnormal or zero, and by 2^1000.
    for s in [5e-324, 2.0f64.powi(-1060), 2.0f64.powi(1000), 1e300, 1e-300] {
        let m = |p: P3| p.map(|x| x * s);
        assert!(orient3d(m(a), m(b), m(c), m(d)) == Sign::Negative, "scale {s:e}");
        let e = orient3d_estimate(m(a), m(b), m(c), m(d), ESTIMATE_REL_ERR);
        let want = det_reference(m(a), m(b), m(c), m(d)).estimate();
        assert!(e.sign == Sign::Negative && rel_diff(e, want) <= ESTIMATE_CHECK, "scale {s:e}: {e:?}");
    }
}

#[test]
fn orient3d_decides_1e_300_off_the_plane() {
    // Plane z = x through the origin (a, b, c below); d = (−1e-300, 0, 0) has
    // z − x = 1e-300 > 0: the side n = (b − a) × (c − a) = (−6, 0, 6) points to,
    // so orient3d = −n·(d − a) < 0. Mirrored d = (1e-300, 0, 0): positive.
    let (a, b, c) = ([-1.0, -1.0, -1.0], [1.0, -1.0, 1.0], [0.0, 2.0, 0.0]);
    assert!(orient3d(a, b, c, [-1e-300, 0.0, 0.0]) == Sign::Negative, "1e-300 above");
    assert!(orient3d(a, b, c, [1e-300, 0.0, 0.0]) == Sign::Positive, "1e-300 below");
    assert!(orient3d(a, b, c, [0.0, 0.0, 0.0]) == Sign::Zero, "on the plane");
}

#[test]
fn plane_side_and_dot_diff_hand_cases() {
    // n = (0, 0, 2), d = 2: the plane z = 1. p = (3, 4, 1 + 2^−52) is above by
    // 2·2^−52; p = (3, 4, 1) is on it. A huge normal (1e300) with a tiny point
    // (1e-300) and d = 0.5: n·p − d = 1 − 0.5 > 0 only exactly (the products
    // are fine, but n·p in f64 is a rounding of 1e300·1e-300).
    let n = [0.0, 0.0, 2.0];
    assert!(plane_side(n, 2.0, [3.0, 4.0, 1.0 + f64::EPSILON]) == Sign::Positive, "just above");
    assert!(plane_side(n, 2.0, [3.0, 4.0, 1.0]) == Sign::Zero, "on");
    assert!(plane_side(n, 2.0, [3.0, 4.0, 1.0 - f64::EPSILON]) == Sign::Negative, "just below");
    let big = [1e300, 0.0, 0.0];
    let small = [1e-300, 0.0, 0.0];
    let exact = &(&bf(1e300) * &bf(1e-300)) - &bf(0.5);
    assert!(plane_side(big, 0.5, small) == exact.sign(), "1e300·1e-300 − 0.5");
    assert!(plane_side([0.0; 3], -3.0, [1.0, 2.0, 3.0]) == Sign::Positive, "zero normal: sign of −d");
    // n·(p1 − p0) with p1 − p0 = (1, 1, 0) and n = (1, −1, 5): 1 − 1 = 0.
    assert!(dot_diff([1.0, -1.0, 5.0], [2.0, 3.0, 7.0], [3.0, 4.0, 7.0]) == Sign::Zero, "parallel");
    assert!(dot_diff([1.0, -1.0, 5.0], [2.0, 3.0, 7.0], [3.0, 4.0, 7.0 + 1e-15]) == Sign::Positive, "up");
    let e = plane_side_estimate(big, 0.5, small, ESTIMATE_REL_ERR);
    assert!(rel_diff(e, exact.estimate()) <= ESTIMATE_CHECK, "{e:?}");
}

#[test]
fn collinear_and_equal_points() {
    // (1,2,3), (4,5,6), (7,8,9): second differences (3,3,3), (6,6,6) are
    // parallel; moving the last point by one ulp in z breaks that.
    let (a, b) = ([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]);
    assert!(collinear(a, b, [7.0, 8.0, 9.0]), "on a line");
    assert!(!collinear(a, b, [7.0, 8.0, 9.0 + 8.0 * f64::EPSILON]), "one ulp off");
    assert!(collinear(a, a, [7.0, -1.0, 0.5]), "two coincident points");
    let (t, u) = ([1e-300, 2e-300, 3e-300], [1e300, 2e300, 3e300]);
    assert!(collinear(t, [0.0; 3], u.map(|x| -x)) == (orient_all_zero(t, [0.0; 3], u.map(|x| -x))), "extreme");
    assert!(points_equal([0.0, -0.0, 1.0], [-0.0, 0.0, 1.0]), "±0 are equal");
    assert!(!points_equal([0.0, 0.0, 1.0], [0.0, 0.0, 1.0 + f64::EPSILON]), "one ulp apart");
}

/// Reference collinearity: every component of (b − a) × (c − a) is exactly 0.
fn orient_all_zero(a: P3, b: P3, c: P3) -> bool {
    let d = |p: P3, i: usize| &bf(p[i]) - &bf(a[i]);
    (0..3).all(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        (&(&d(b, j) * &d(c, k)) - &(&d(b, k) * &d(c, j))).is_zero()
    })
}

#[test]
fn filter_decides_random_cases_without_the_exact_path() {
    // Uniform points in a cube: the fast path should decide nearly all signs,
    // and give nearly all values. Deterministic LCG so the count is repeatable.
    const CASES: u64 = 20_000;
    /// At most 0.1% of random signs may need the exact path (in practice none).
    const MAX_SIGN_FALLBACK: u64 = CASES / 1000;
    /// At most 2% of random values may need it (a value is refined when it is
    /// within 2^−42 of its error bound's scale, ≈ 1/300 of the permanent).
    const MAX_VALUE_FALLBACK: u64 = CASES / 50;
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut points = Vec::new();
    for _ in 0..CASES {
        points.push([
            [next(), next(), next()],
            [next(), next(), next()],
            [next(), next(), next()],
            [next(), next(), next()],
        ]);
    }
    let before = exact_evaluations();
    for p in &points {
        let _ = orient3d(p[0], p[1], p[2], p[3]);
    }
    let signs = exact_evaluations() - before;
    assert!(signs <= MAX_SIGN_FALLBACK, "{signs} of {CASES} signs took the exact path");
    let before = exact_evaluations();
    for p in &points {
        let _ = orient3d_estimate(p[0], p[1], p[2], p[3], ESTIMATE_REL_ERR);
    }
    let values = exact_evaluations() - before;
    assert!(values <= MAX_VALUE_FALLBACK, "{values} of {CASES} values took the exact path");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn orient3d_agrees_with_robust(a in moderate_point(), b in moderate_point(), c in moderate_point(), d in moderate_point()) {
        prop_assert_eq!(orient3d(a, b, c, d), robust_orient3d(a, b, c, d));
    }

    #[test]
    fn orient3d_agrees_with_robust_near_the_plane(
        a in moderate_point(), b in moderate_point(), c in moderate_point(),
        s in -2.0..2.0f64, t in -2.0..2.0f64,
    ) {
        let d = near_plane(a, b, c, s, t);
        prop_assert_eq!(orient3d(a, b, c, d), robust_orient3d(a, b, c, d));
        prop_assert_eq!(orient3d(a, b, c, d), det_reference(a, b, c, d).sign());
    }

    #[test]
    fn orient3d_agrees_with_robust_on_a_grid(a in grid_point(), b in grid_point(), c in grid_point(), d in grid_point()) {
        prop_assert_eq!(orient3d(a, b, c, d), robust_orient3d(a, b, c, d));
    }

    #[test]
    fn orient3d_is_exact_for_any_finite_input(a in any_point(), b in any_point(), c in any_point(), d in any_point()) {
        let want = det_reference(a, b, c, d);
        prop_assert_eq!(orient3d(a, b, c, d), want.sign());
        let e = orient3d_estimate(a, b, c, d, ESTIMATE_REL_ERR);
        prop_assert_eq!(e.sign, want.sign());
        prop_assert!(e.rel_err <= ESTIMATE_REL_ERR, "stated error {:e}", e.rel_err);
        if !want.is_zero() {
            prop_assert!(rel_diff(e, want.estimate()) <= ESTIMATE_CHECK, "{:?} vs {:?}", e, want.estimate());
        }
        // Sign only: the stated error, however large, holds.
        let loose = orient3d_estimate(a, b, c, d, f64::INFINITY);
        prop_assert_eq!(loose.sign, want.sign());
        if !want.is_zero() {
            let bound = loose.rel_err + f64::EPSILON;
            prop_assert!(rel_diff(loose, want.estimate()) <= bound, "{:?} vs {:?}", loose, want.estimate());
        }
    }

    #[test]
    fn orient3d_is_exact_near_the_plane_at_any_scale(
        a in moderate_point(), b in moderate_point(), c in moderate_point(),
        s in -2.0..2.0f64, t in -2.0..2.0f64, k in -1100i64..1000,
    ) {
        // Scaling by 2^k (k < −1000 pushes coordinates into the subnormals and
        // loses bits, which is fine: the reference sees the same inputs).
        let m = |p: P3| p.map(|x| ldexp(x, k));
        let d = near_plane(a, b, c, s, t);
        let (a, b, c, d) = (m(a), m(b), m(c), m(d));
        prop_assert_eq!(orient3d(a, b, c, d), det_reference(a, b, c, d).sign());
    }

    #[test]
    fn triple_product_is_the_difference_of_two_orientations(
        v0 in any_point(), v1 in any_point(), v2 in any_point(), q0 in any_point(), q1 in any_point(),
    ) {
        // det[v1 − v0, v2 − v0, q1 − q0] = orient3d(v0, v1, v2, q0) − orient3d(v0, v1, v2, q1)
        // (orient3d(v0, v1, v2, q) = −n·(q − v0) with n = (v1 − v0) × (v2 − v0)).
        let want = &det_reference(v0, v1, v2, q0) - &det_reference(v0, v1, v2, q1);
        prop_assert_eq!(triple_product(v0, v1, v0, v2, q0, q1), want.sign());
    }

    #[test]
    fn triple_product_near_parallel(v0 in moderate_point(), v1 in moderate_point(), v2 in moderate_point(), q0 in moderate_point(), s in -2.0..2.0f64, t in -2.0..2.0f64) {
        let q1 = [0, 1, 2].map(|i| q0[i] + s * (v1[i] - v0[i]) + t * (v2[i] - v0[i]));
        let want = &det_reference(v0, v1, v2, q0) - &det_reference(v0, v1, v2, q1);
        prop_assert_eq!(triple_product(v0, v1, v0, v2, q0, q1), want.sign());
    }

    #[test]
    fn plane_side_is_exact_for_any_finite_input(n in any_point(), d in any_finite(), p in any_point()) {
        let want = &(&(&(&bf(n[0]) * &bf(p[0])) + &(&bf(n[1]) * &bf(p[1]))) + &(&bf(n[2]) * &bf(p[2]))) - &bf(d);
        prop_assert_eq!(plane_side(n, d, p), want.sign());
        let e = plane_side_estimate(n, d, p, ESTIMATE_REL_ERR);
        prop_assert_eq!(e.sign, want.sign());
        if !want.is_zero() {
            prop_assert!(rel_diff(e, want.estimate()) <= ESTIMATE_CHECK, "{:?} vs {:?}", e, want.estimate());
        }
    }

    #[test]
    fn plane_side_near_the_plane(n in moderate_point(), p in moderate_point(), ulps in -4i64..=4) {
        // d = fl(n·p) nudged by a few ulps: n·p − d is tiny and often exactly 0.
        let np = n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
        let d = f64::from_bits((np.to_bits() as i64 + ulps) as u64);
        let want = &(&(&(&bf(n[0]) * &bf(p[0])) + &(&bf(n[1]) * &bf(p[1]))) + &(&bf(n[2]) * &bf(p[2]))) - &bf(d);
        prop_assert_eq!(plane_side(n, d, p), want.sign());
    }

    #[test]
    fn dot_diff_is_exact_for_any_finite_input(n in any_point(), p0 in any_point(), p1 in any_point()) {
        let t = |i: usize| &bf(n[i]) * &(&bf(p1[i]) - &bf(p0[i]));
        let want = &(&t(0) + &t(1)) + &t(2);
        prop_assert_eq!(dot_diff(n, p0, p1), want.sign());
    }

    #[test]
    fn orient2d_agrees_with_robust(a in moderate_point(), b in moderate_point(), s in -2.0..2.0f64) {
        // c on (or next to, after rounding) the line a b.
        let (a, b) = ([a[0], a[1]], [b[0], b[1]]);
        let c = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
        let r = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
        prop_assert_eq!(orient2d(a, b, c), Sign::of(robust::orient2d(r(a), r(b), r(c))));
    }

    #[test]
    fn collinear_is_exact_for_any_finite_input(a in any_point(), b in any_point(), c in any_point()) {
        prop_assert_eq!(collinear(a, b, c), orient_all_zero(a, b, c));
    }

    #[test]
    fn collinear_on_exact_lines(a in grid_point(), d in grid_point(), j in -4i32..=4, k in -4i32..=4, ulp in 0u32..=1) {
        // a + j d and a + k d are exactly on the line through a along d; moving
        // one coordinate of the last point by an ulp leaves it collinear only if
        // d is zero or the move is along d's only non-zero axis (the reference
        // decides).
        let b = [0, 1, 2].map(|i| a[i] + f64::from(j) * d[i]);
        let mut c = [0, 1, 2].map(|i| a[i] + f64::from(k) * d[i]);
        if ulp == 1 {
            c[2] = c[2] + (c[2].abs() + 1.0) * f64::EPSILON;
        }
        prop_assert_eq!(collinear(a, b, c), orient_all_zero(a, b, c));
        if ulp == 0 {
            prop_assert!(collinear(a, b, c), "points on a line are collinear");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// `cross_estimate` (shared-difference filter first) agrees with each
    /// component's own `orient2d_estimate` at full accuracy: same exact sign,
    /// magnitude within the requested accuracy; and `collinear` agrees with the
    /// three signs. Near-collinear triples (a third point close to the line
    /// through two) make the filter's bounds matter.
    #[test]
    fn cross_estimate_and_collinear_agree_with_orient2d(a in moderate_point(), b in moderate_point(), s in -2.0..2.0f64, off in proptest::array::uniform3(-1e-12..1e-12f64)) {
        /// The accuracy asked of `cross_estimate` (2^−40, the queries' own).
        const ASKED: f64 = ESTIMATE_REL_ERR;
        let c = [0, 1, 2].map(|i| a[i] + s * (b[i] - a[i]) + off[i]);
        let (pa, pb, pc) = (
            [[a[1], a[2]], [a[2], a[0]], [a[0], a[1]]],
            [[b[1], b[2]], [b[2], b[0]], [b[0], b[1]]],
            [[c[1], c[2]], [c[2], c[0]], [c[0], c[1]]],
        );
        let got = cross_estimate(a, b, c, ASKED);
        for i in 0..3 {
            let want = orient2d_estimate(pa[i], pb[i], pc[i], 0.0);
            prop_assert_eq!(got[i].sign, want.sign, "component {}", i);
            prop_assert!(got[i].rel_err <= ASKED || got[i].rel_err <= 2.0 * f64::EPSILON, "rel_err {}", got[i].rel_err);
            if want.sign != Sign::Zero {
                // The estimate within ASKED of the exact value, seen through
                // `want` (itself within 2^−52).
                prop_assert!(rel_diff(got[i], want) <= ASKED + 4.0 * f64::EPSILON, "component {}: {:?} vs {:?}", i, got[i], want);
            }
        }
        let zero = got.iter().all(|e| e.sign == Sign::Zero);
        prop_assert_eq!(collinear(a, b, c), zero);
    }
}
