//! Filtered exact predicates on `f64` points.
//!
//! Each predicate is the sign of a small polynomial in its inputs. It is
//! evaluated twice at most:
//!
//! 1. **Fast path** — plain `f64` arithmetic with a static forward error bound
//!    in the manner of Shewchuk (*Adaptive Precision Floating-Point Arithmetic
//!    and Fast Robust Geometric Predicates*, 1997): if `|value| > bound` the sign
//!    of the computed value is the exact sign. The bound is a constant times the
//!    *permanent* (the same polynomial with every term made non-negative), plus
//!    an absolute slack for underflow. Shewchuk's bounds assume that no
//!    operation overflows or underflows; here that is made true instead of
//!    assumed: the polynomial's arguments (the differences, for orient3d and
//!    orient2d; the vectors themselves for the dot products) are used as they
//!    are when their largest magnitude lies in `[2^−64, 2^64]`, where nothing
//!    can overflow; otherwise they (or, if a difference overflowed, the inputs)
//!    are first scaled by a power of two into `[0.5, 1)` — exactly, which is
//!    checked, or the exact path is taken. The error of every product that
//!    underflows (at most `2^−1075` each, propagated through at most one more
//!    factor of magnitude `≤ 2^65`) is covered by [`UNDERFLOW_SLACK`]. A
//!    predicate of degree `k` is homogeneous in each group of inputs, so
//!    scaling a group by `2^s` scales the value by a power of two and keeps
//!    its sign.
//! 2. **Exact path** — when the fast path cannot decide (or the inputs cannot be
//!    scaled exactly), the polynomial is evaluated in [`BigFloat`], exactly, for
//!    every finite input. Only this path allocates.
//!
//! The `_estimate` variants also return the value, as an [`Estimate`] with an
//! exact sign and a relative error at most the caller's `max_rel_err`: the fast
//! value is used when its bound allows (its error relative to the value is
//! `bound / (|value| − bound)`), otherwise the exact value is rounded (relative
//! error `≤ 2^−52`, so a `max_rel_err` below that is met as `2^−52`). Pass
//! `f64::INFINITY` to ask for the sign only, with whatever magnitude the fast
//! path gives; [`Estimate::refine_jointly`] then refines only what a sum of
//! several values needs.
//!
//! Non-finite input (never meant to reach a predicate: the queries check first)
//! gives [`Sign::Zero`] / [`Estimate::ZERO`], without panicking.

use super::bigfloat::BigFloat;
use super::estimate::{Estimate, frexp, ldexp};
use super::expansion::{self, Expansion, in_expansion_range};
use super::filter;
use super::sign::Sign;

/// A point (or vector) in the predicates' coordinates.
pub type P3 = [f64; 3];

/// Unit roundoff of `f64` (2^−53), Shewchuk's ε.
const EPS: f64 = 1.1102230246251565e-16;
/// Shewchuk's `o3derrboundA`: bound on the error of his orient3d expression,
/// relative to its permanent.
const O3D_BOUND: f64 = (7.0 + 56.0 * EPS) * EPS;
/// Shewchuk's `ccwerrboundA`: the same for orient2d.
const O2D_BOUND: f64 = (3.0 + 16.0 * EPS) * EPS;
/// Bound for `((x1·y1 + x2·y2) + x3·y3) − d` and for `Σ n_i·fl(q_i − p_i)`: every
/// term passes through at most 4 roundings, so the error is at most
/// `γ4 = 4ε/(1 − 4ε)` times the exact permanent, which is at most the computed
/// permanent over `(1 − ε)^4`; the bound's own product rounds once more.
/// `4ε(1 + 10ε)` suffices; `(4 + 64ε)ε` is used.
const DOT_BOUND: f64 = (4.0 + 64.0 * EPS) * EPS;
/// Absolute slack for underflow (2^−1000). In every fast path the polynomial's
/// arguments have magnitude `≤ 2^65` (differences of inputs `≤ 2^64`, or
/// `< 2` after scaling); a product that underflows errs by at most `2^−1075`,
/// that error is multiplied by at most one more argument (orient3d: `≤ 2^65`),
/// and at most 12 such errors occur:
/// `12 · 2^65 · 2^−1075 · (1 + small) < 2^−1006`. `2^−1000` covers that with
/// room.
const UNDERFLOW_SLACK: f64 = 9.332636185032189e-302;
/// Arguments with largest magnitude in `[SAFE_MIN, SAFE_MAX]` are used as they
/// are; others are scaled by a power of two into `[0.5, 1)` first (2^−64 and
/// 2^64).
const SAFE_MIN: f64 = 5.421010862427522e-20;
/// See [`SAFE_MIN`].
const SAFE_MAX: f64 = 18446744073709551616.0;

/// A fast-path evaluation: the exact value lies in
/// `[(value − bound)·2^exp, (value + bound)·2^exp]`; `bound == 0` means the
/// value is exact.
#[derive(Clone, Copy, Debug)]
struct Fast {
    value: f64,
    bound: f64,
    exp: i64,
}

impl Fast {
    const ZERO: Self = Self { value: 0.0, bound: 0.0, exp: 0 };
}

#[cfg(test)]
thread_local! {
    /// Exact-path evaluations on this thread, so tests can measure the filter.
    static EXACT_EVALUATIONS: core::cell::Cell<u64> = const { core::cell::Cell::new(0) };
}

/// How many predicates on this thread have taken the exact path so far.
#[cfg(test)]
pub(crate) fn exact_evaluations() -> u64 {
    EXACT_EVALUATIONS.with(|c| c.get())
}

#[inline]
fn note_exact() {
    #[cfg(test)]
    EXACT_EVALUATIONS.with(|c| c.set(c.get() + 1));
}

#[inline(always)]
fn decide_sign(fast: Option<Fast>, exact: impl FnOnce() -> Estimate) -> Sign {
    if let Some(f) = fast
        && (f.value.abs() > f.bound || f.bound == 0.0)
    {
        return Sign::of(f.value);
    }
    note_exact();
    exact().sign
}

#[inline(always)]
fn decide_estimate(fast: Option<Fast>, max_rel_err: f64, exact: impl FnOnce() -> Estimate) -> Estimate {
    if let Some(f) = fast {
        let magnitude = f.value.abs();
        if f.bound == 0.0 {
            return Estimate::from_scaled(f.value, f.exp, 0.0);
        }
        if magnitude > f.bound {
            // |exact| ≥ |value| − bound, so the relative error is at most
            // bound / (|value| − bound); 4 ulps cover this quotient's rounding.
            let rel_err = f.bound / (magnitude - f.bound) * (1.0 + 4.0 * f64::EPSILON);
            if rel_err <= max_rel_err {
                return Estimate::from_scaled(f.value, f.exp, rel_err);
            }
        }
    }
    note_exact();
    exact()
}

/// The power-of-two exponent that brings a largest magnitude `m > 0` into
/// `[0.5, 1)`, or 0 when `m` is already in the safe range.
#[inline]
fn scale_exponent(m: f64) -> i64 {
    if (SAFE_MIN..=SAFE_MAX).contains(&m) { 0 } else { -frexp(m).1 }
}

/// `x · 2^k` when that is exact and finite.
#[inline]
fn scale_exact(x: f64, k: i64) -> Option<f64> {
    if k == 0 || x == 0.0 {
        return Some(x);
    }
    let r = ldexp(x, k);
    if !r.is_finite() {
        return None;
    }
    // Scaling down rounds only if the result is subnormal; then check by
    // scaling back up (exact, as nothing overflows).
    #[expect(clippy::float_cmp, reason = "an exactness test: equality is the point")]
    let lost = k < 0 && r.abs() < f64::MIN_POSITIVE && ldexp(r, -k) != x;
    if lost { None } else { Some(r) }
}

#[inline]
fn scale3(p: P3, k: i64) -> Option<P3> {
    Some([scale_exact(p[0], k)?, scale_exact(p[1], k)?, scale_exact(p[2], k)?])
}

/// Largest magnitude, or `None` if any value is not finite.
#[inline]
fn max_abs<'a>(values: impl IntoIterator<Item = &'a f64>) -> Option<f64> {
    let mut m = 0.0f64;
    for &x in values {
        if !x.is_finite() {
            return None;
        }
        m = m.max(x.abs());
    }
    Some(m)
}

#[inline]
fn either_zero(u: f64, v: f64) -> bool {
    u == 0.0 || v == 0.0
}

fn big3(p: &P3) -> Option<[BigFloat; 3]> {
    Some([BigFloat::try_from_f64(p[0])?, BigFloat::try_from_f64(p[1])?, BigFloat::try_from_f64(p[2])?])
}

fn diff3(p0: &P3, p1: &P3) -> Option<[BigFloat; 3]> {
    let (a, b) = (big3(p0)?, big3(p1)?);
    Some([&b[0] - &a[0], &b[1] - &a[1], &b[2] - &a[2]])
}

fn dot_big(u: &[BigFloat; 3], v: &[BigFloat; 3]) -> BigFloat {
    &(&(&u[0] * &v[0]) + &(&u[1] * &v[1])) + &(&u[2] * &v[2])
}

// ---------------------------------------------------------------------------
// det[u1 − u0, v1 − v0, w1 − w0] (orient3d and the parallel test)
// ---------------------------------------------------------------------------

#[inline(always)]
fn sub3(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Largest magnitude of the values (a NaN is skipped: callers catch it through
/// the NaN it makes of their result).
#[inline(always)]
fn max_magnitude<const N: usize>(values: [f64; N]) -> f64 {
    let mut m = 0.0f64;
    for x in values {
        let a = x.abs();
        if a > m {
            m = a;
        }
    }
    m
}

/// `det[a, b, c]` of rows that are already (rounded) differences, in Shewchuk's
/// orient3d expression, with his static bound: the exact determinant of the
/// exact differences lies within `bound` of `det` (rows at most `2^65` in
/// magnitude, see [`UNDERFLOW_SLACK`]). The fast path of every volume filter.
#[inline(always)]
pub(crate) fn det3_with_bound(a: P3, b: P3, c: P3) -> (f64, f64) {
    let [adx, ady, adz] = a;
    let [bdx, bdy, bdz] = b;
    let [cdx, cdy, cdz] = c;
    let bdxcdy = bdx * cdy;
    let cdxbdy = cdx * bdy;
    let cdxady = cdx * ady;
    let adxcdy = adx * cdy;
    let adxbdy = adx * bdy;
    let bdxady = bdx * ady;
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    (det, O3D_BOUND * permanent + UNDERFLOW_SLACK)
}

/// Shewchuk's orient3d arithmetic on rows `a`, `b`, `c` that are already
/// (rounded) differences, with his bound, so that the exact determinant of the
/// *exact* differences lies within `bound` of `value`. Requires every row
/// component to be at most `2^65` in magnitude (see [`UNDERFLOW_SLACK`]).
#[inline(always)]
fn det3_rows(a: P3, b: P3, c: P3, exp: i64) -> Fast {
    let [adx, ady, adz] = a;
    let [bdx, bdy, bdz] = b;
    let [cdx, cdy, cdz] = c;
    let (det, bound) = det3_with_bound(a, b, c);
    // Undecided: each term is provably zero when every product in it has a zero
    // factor (a computed difference is zero exactly when its operands are
    // equal) — the common axis-aligned case, decided without the exact path.
    let decided = det.abs() > bound;
    if !decided
        && (adz == 0.0 || (either_zero(bdx, cdy) && either_zero(cdx, bdy)))
        && (bdz == 0.0 || (either_zero(cdx, ady) && either_zero(adx, cdy)))
        && (cdz == 0.0 || (either_zero(adx, bdy) && either_zero(bdx, ady)))
    {
        return Fast::ZERO;
    }
    Fast { value: det, bound, exp }
}

/// Fast path of `det[p1 − p0; p3 − p2; p5 − p4]`: the differences as they
/// are when their largest magnitude lies in `[2^−64, 2^64]` (overflow
/// impossible; anything that underflows covered by the slack); otherwise the
/// differences scaled by a power of two into `[0.5, 1)` (exactly, or not at
/// all), or, if a difference overflowed, the inputs scaled first. Scaling the
/// rounded differences is sound: Shewchuk's bound is about rounded
/// differences, and an exact scaling by `2^k` scales both the computed and the
/// exact determinant by `2^3k`.
#[inline(always)]
fn det3_fast(p: &[P3; 6]) -> Option<Fast> {
    let (a, b, c) = (sub3(p[1], p[0]), sub3(p[3], p[2]), sub3(p[5], p[4]));
    let m = max_magnitude([a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]);
    if (SAFE_MIN..=SAFE_MAX).contains(&m) {
        return Some(det3_rows(a, b, c, 0));
    }
    if m == 0.0 {
        // Every difference is zero (or NaN, which the exact path reports as 0).
        return Some(Fast::ZERO);
    }
    if m.is_finite() {
        // Scale the rounded differences themselves (exactly, or give up).
        let k = -frexp(m).1;
        if let (Some(a), Some(b), Some(c)) = (scale3(a, k), scale3(b, k), scale3(c, k)) {
            return Some(det3_rows(a, b, c, -3 * k));
        }
    }
    det3_fast_scaled(p)
}

#[cold]
fn det3_fast_scaled(p: &[P3; 6]) -> Option<Fast> {
    let m = max_abs(p.iter().flatten())?;
    let k = -frexp(m).1;
    let q =
        [scale3(p[0], k)?, scale3(p[1], k)?, scale3(p[2], k)?, scale3(p[3], k)?, scale3(p[4], k)?, scale3(p[5], k)?];
    let (a, b, c) = (sub3(q[1], q[0]), sub3(q[3], q[2]), sub3(q[5], q[4]));
    Some(det3_rows(a, b, c, -3 * k))
}

#[cold]
fn det3_exact(p: &[P3; 6]) -> Estimate {
    if in_expansion_range(p.iter().flatten()) {
        let d = |i: usize| [0, 1, 2].map(|k| Expansion::diff(p[i + 1][k], p[i][k]));
        return expansion::det3(d(0), d(2), d(4)).estimate();
    }
    let (Some(a), Some(b), Some(c)) = (diff3(&p[0], &p[1]), diff3(&p[2], &p[3]), diff3(&p[4], &p[5])) else {
        return Estimate::ZERO;
    };
    // a · (b × c)
    let bxc =
        [&(&b[1] * &c[2]) - &(&b[2] * &c[1]), &(&b[2] * &c[0]) - &(&b[0] * &c[2]), &(&b[0] * &c[1]) - &(&b[1] * &c[0])];
    dot_big(&a, &bxc).estimate()
}

/// Sign of `det[a − d, b − d, c − d] = (a − d) · ((b − d) × (c − d))`, exactly.
///
/// Shewchuk's convention (and the `robust` crate's): **positive when `d` lies
/// below the plane through `a`, `b`, `c`**, "below" meaning that `a`, `b`, `c`
/// appear counterclockwise seen from above; negative above; zero when the four
/// points are coplanar. Equivalently `orient3d(a, b, c, d) = −n · (d − a)` with
/// `n = (b − a) × (c − a)`: positive when `d` is on the side `n` points away
/// from.
#[inline]
pub fn orient3d(a: P3, b: P3, c: P3, d: P3) -> Sign {
    let p = [d, a, d, b, d, c];
    decide_sign(det3_fast(&p), || det3_exact(&p))
}

/// [`orient3d`]'s value `det[a − d, b − d, c − d]` as an [`Estimate`]: exact
/// sign, relative error at most `max_rel_err` (or `2^−52`, whichever is larger).
#[inline]
pub fn orient3d_estimate(a: P3, b: P3, c: P3, d: P3, max_rel_err: f64) -> Estimate {
    let p = [d, a, d, b, d, c];
    decide_estimate(det3_fast(&p), max_rel_err, || det3_exact(&p))
}

/// Sign of the triple product `det[u1 − u0, v1 − v0, w1 − w0] =
/// ((u1 − u0) × (v1 − v0)) · (w1 − w0)`, exactly, the three vectors given as
/// differences of points so that no rounded difference enters.
///
/// The parallel test of a segment `q0 q1` against a triangle `v0 v1 v2` is
/// `triple_product(v0, v1, v0, v2, q0, q1) == Sign::Zero`
/// (`((v1 − v0) × (v2 − v0)) · (q1 − q0) = 0`).
#[inline]
pub fn triple_product(u0: P3, u1: P3, v0: P3, v1: P3, w0: P3, w1: P3) -> Sign {
    let p = [u0, u1, v0, v1, w0, w1];
    decide_sign(det3_fast(&p), || det3_exact(&p))
}

// ---------------------------------------------------------------------------
// n · p − d and n · (p1 − p0)
// ---------------------------------------------------------------------------

#[inline]
fn plane_fast(n: P3, d: f64, p: P3) -> Option<Fast> {
    let mn = max_abs(&n)?;
    let mp = max_abs(&p)?;
    if !d.is_finite() {
        return None;
    }
    if mn == 0.0 || mp == 0.0 {
        return Some(Fast { value: -d, bound: 0.0, exp: 0 });
    }
    let (kn, kp) = (scale_exponent(mn), scale_exponent(mp));
    let (n, p, d) =
        if kn == 0 && kp == 0 { (n, p, d) } else { (scale3(n, kn)?, scale3(p, kp)?, scale_exact(d, kn + kp)?) };
    let (x, y, z) = (n[0] * p[0], n[1] * p[1], n[2] * p[2]);
    let exp = -(kn + kp);
    if either_zero(n[0], p[0]) && either_zero(n[1], p[1]) && either_zero(n[2], p[2]) {
        return Some(Fast { value: -d, bound: 0.0, exp });
    }
    let value = ((x + y) + z) - d;
    let permanent = ((x.abs() + y.abs()) + z.abs()) + d.abs();
    Some(Fast { value, bound: DOT_BOUND * permanent + UNDERFLOW_SLACK, exp })
}

#[cold]
fn plane_exact(n: P3, d: f64, p: P3) -> Estimate {
    if in_expansion_range(n.iter().chain(&p).chain([&d])) {
        let dot = expansion::dot3(n.map(Expansion::single), p.map(Expansion::single));
        let value: Expansion<32> = dot.sub(&Expansion::single(d));
        return value.estimate();
    }
    let (Some(n), Some(p), Some(d)) = (big3(&n), big3(&p), BigFloat::try_from_f64(d)) else {
        return Estimate::ZERO;
    };
    (&dot_big(&n, &p) - &d).estimate()
}

/// Sign of `n · p − d`, exactly: which side of the plane `n · x = d` the point
/// `p` is on (positive: the side `n` points to; zero: on the plane). A zero `n`
/// gives the sign of `−d`.
#[inline]
pub fn plane_side(n: P3, d: f64, p: P3) -> Sign {
    decide_sign(plane_fast(n, d, p), || plane_exact(n, d, p))
}

/// [`plane_side`]'s value `n · p − d` as an [`Estimate`] (exact sign, relative
/// error at most `max_rel_err` or `2^−52`).
#[inline]
pub fn plane_side_estimate(n: P3, d: f64, p: P3, max_rel_err: f64) -> Estimate {
    decide_estimate(plane_fast(n, d, p), max_rel_err, || plane_exact(n, d, p))
}

#[inline]
fn dot_diff_fast(n: P3, p0: P3, p1: P3) -> Option<Fast> {
    let mn = max_abs(&n)?;
    let mp = max_abs(p0.iter().chain(&p1))?;
    if mn == 0.0 || mp == 0.0 {
        return Some(Fast::ZERO);
    }
    let (kn, kp) = (scale_exponent(mn), scale_exponent(mp));
    let (n, p0, p1) = if kn == 0 && kp == 0 { (n, p0, p1) } else { (scale3(n, kn)?, scale3(p0, kp)?, scale3(p1, kp)?) };
    let (dx, dy, dz) = (p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
    if either_zero(n[0], dx) && either_zero(n[1], dy) && either_zero(n[2], dz) {
        return Some(Fast::ZERO);
    }
    let (x, y, z) = (n[0] * dx, n[1] * dy, n[2] * dz);
    let value = (x + y) + z;
    let permanent = (x.abs() + y.abs()) + z.abs();
    Some(Fast { value, bound: DOT_BOUND * permanent + UNDERFLOW_SLACK, exp: -(kn + kp) })
}

#[cold]
fn dot_diff_exact(n: P3, p0: P3, p1: P3) -> Estimate {
    if in_expansion_range(n.iter().chain(&p0).chain(&p1)) {
        let d = [0, 1, 2].map(|k| Expansion::diff(p1[k], p0[k]));
        return expansion::dot3(n.map(Expansion::single), d).estimate();
    }
    let (Some(n), Some(d)) = (big3(&n), diff3(&p0, &p1)) else {
        return Estimate::ZERO;
    };
    dot_big(&n, &d).estimate()
}

/// Sign of `n · (p1 − p0)`, exactly: whether a segment runs along a plane's
/// normal (positive), against it (negative) or parallel to the plane (zero).
#[inline]
pub fn dot_diff(n: P3, p0: P3, p1: P3) -> Sign {
    decide_sign(dot_diff_fast(n, p0, p1), || dot_diff_exact(n, p0, p1))
}

// ---------------------------------------------------------------------------
// orient2d, cross products, collinearity
// ---------------------------------------------------------------------------

/// Shewchuk's orient2d arithmetic on `a − c` and `b − c` (given), with his
/// bound; components at most `2^65`.
#[inline(always)]
fn orient2d_rows(ac: [f64; 2], bc: [f64; 2], exp: i64) -> Fast {
    let left = ac[0] * bc[1];
    let right = ac[1] * bc[0];
    let det = left - right;
    let bound = O2D_BOUND * (left.abs() + right.abs()) + UNDERFLOW_SLACK;
    let decided = det.abs() > bound;
    if !decided && either_zero(ac[0], bc[1]) && either_zero(ac[1], bc[0]) {
        return Fast::ZERO;
    }
    Fast { value: det, bound, exp }
}

/// Fast path of Shewchuk's orient2d `(a − c) × (b − c)`, arranged as
/// [`det3_fast`].
#[inline(always)]
fn orient2d_fast(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<Fast> {
    let ac = [a[0] - c[0], a[1] - c[1]];
    let bc = [b[0] - c[0], b[1] - c[1]];
    let m = max_magnitude([ac[0], ac[1], bc[0], bc[1]]);
    if (SAFE_MIN..=SAFE_MAX).contains(&m) {
        return Some(orient2d_rows(ac, bc, 0));
    }
    if m == 0.0 {
        return Some(Fast::ZERO);
    }
    if m.is_finite() {
        let k = -frexp(m).1;
        let s = |p: [f64; 2]| -> Option<[f64; 2]> { Some([scale_exact(p[0], k)?, scale_exact(p[1], k)?]) };
        if let (Some(ac), Some(bc)) = (s(ac), s(bc)) {
            return Some(orient2d_rows(ac, bc, -2 * k));
        }
    }
    orient2d_fast_scaled(a, b, c)
}

#[cold]
fn orient2d_fast_scaled(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<Fast> {
    let m = max_abs(a.iter().chain(&b).chain(&c))?;
    let k = -frexp(m).1;
    let s = |p: [f64; 2]| -> Option<[f64; 2]> { Some([scale_exact(p[0], k)?, scale_exact(p[1], k)?]) };
    let (a, b, c) = (s(a)?, s(b)?, s(c)?);
    Some(orient2d_rows([a[0] - c[0], a[1] - c[1]], [b[0] - c[0], b[1] - c[1]], -2 * k))
}

#[cold]
fn orient2d_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Estimate {
    if in_expansion_range(a.iter().chain(&b).chain(&c)) {
        let d = |p: [f64; 2]| [0, 1].map(|k| Expansion::diff(p[k], c[k]));
        return expansion::det2(d(a), d(b)).estimate();
    }
    let big = |x: f64| BigFloat::try_from_f64(x);
    let (Some(ax), Some(ay), Some(bx), Some(by), Some(cx), Some(cy)) =
        (big(a[0]), big(a[1]), big(b[0]), big(b[1]), big(c[0]), big(c[1]))
    else {
        return Estimate::ZERO;
    };
    (&(&(&ax - &cx) * &(&by - &cy)) - &(&(&ay - &cy) * &(&bx - &cx))).estimate()
}

/// Sign of `(a − c) × (b − c) = (b − a) × (c − a)` (2D), exactly: positive when
/// `a`, `b`, `c` turn counterclockwise, zero when collinear (Shewchuk's and the
/// `robust` crate's convention).
#[inline]
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Sign {
    decide_sign(orient2d_fast(a, b, c), || orient2d_exact(a, b, c))
}

/// [`orient2d`]'s value as an [`Estimate`] (exact sign, relative error at most
/// `max_rel_err` or `2^−52`).
#[inline]
pub fn orient2d_estimate(a: [f64; 2], b: [f64; 2], c: [f64; 2], max_rel_err: f64) -> Estimate {
    decide_estimate(orient2d_fast(a, b, c), max_rel_err, || orient2d_exact(a, b, c))
}

/// The three coordinate-plane projections of a triangle, in the order of the
/// cross product's components: `(y, z)`, `(z, x)`, `(x, y)`.
#[inline]
fn projections(p: P3) -> [[f64; 2]; 3] {
    [[p[1], p[2]], [p[2], p[0]], [p[0], p[1]]]
}

/// The cross product `(b − a) × (c − a)` (a triangle's unnormalized face
/// normal), each component an [`Estimate`]: component `i` is the orient2d of
/// the triangle projected onto the coordinate plane orthogonal to axis `i`, so
/// each has an exact sign and a relative error at most `max_rel_err` (or
/// `2^−52`), for every finite input — overflow (`1e300` scenes) and underflow
/// (`1e-300` ones) included.
///
/// The three components are first computed together in plain `f64` from the
/// shared differences `b − a`, `c − a`, each with its static error bound
/// (`filter::cross`); a component is taken from there when its bound makes it
/// accurate to `max_rel_err`, and evaluated alone by [`orient2d_estimate`]
/// (its own filter, then the exact path) otherwise.
pub fn cross_estimate(a: P3, b: P3, c: P3, max_rel_err: f64) -> [Estimate; 3] {
    let (pa, pb, pc) = (projections(a), projections(b), projections(c));
    let slow = |i: usize| orient2d_estimate(pa[i], pb[i], pc[i], max_rel_err);
    if !filter::in_fast_range([a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]) {
        return [0, 1, 2].map(slow);
    }
    let (n, perm) = filter::cross(filter::sub(b, a), filter::sub(c, a));
    let bounds = filter::cross_bounds(perm);
    [0, 1, 2].map(|i| {
        let magnitude = n[i].abs();
        if magnitude > bounds[i] {
            // As `decide_estimate`: relative error bound / (|value| − bound),
            // with 4 ulps for this quotient's rounding.
            let rel_err = bounds[i] / (magnitude - bounds[i]) * (1.0 + 4.0 * f64::EPSILON);
            if rel_err <= max_rel_err {
                return Estimate::from_scaled(n[i], 0, rel_err);
            }
        }
        slow(i)
    })
}

/// Whether `a`, `b`, `c` are collinear (coincident points included), exactly:
/// whether `(b − a) × (c − a)` is exactly the zero vector, i.e. the triangle
/// `a b c` has zero area.
///
/// A component of the cross product that its filter (`filter::cross`, on the
/// shared differences) shows to be non-zero answers `false` at once; only
/// otherwise are the three components decided one by one by [`orient2d`].
pub fn collinear(a: P3, b: P3, c: P3) -> bool {
    if filter::in_fast_range([a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]) {
        let (n, perm) = filter::cross(filter::sub(b, a), filter::sub(c, a));
        let bounds = filter::cross_bounds(perm);
        if (n[0].abs() > bounds[0]) | (n[1].abs() > bounds[1]) | (n[2].abs() > bounds[2]) {
            return false;
        }
    }
    let (pa, pb, pc) = (projections(a), projections(b), projections(c));
    (0..3).all(|i| orient2d(pa[i], pb[i], pc[i]) == Sign::Zero)
}

/// Whether two points are exactly equal (`−0.0` equals `0.0`; a NaN equals
/// nothing).
#[inline]
pub fn points_equal(a: P3, b: P3) -> bool {
    #[expect(clippy::float_cmp, reason = "exact equality is this predicate's meaning")]
    let eq = a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    eq
}
