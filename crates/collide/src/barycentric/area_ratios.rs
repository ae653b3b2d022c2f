//! The signed barycentric coordinates of a point's projection onto a triangle's
//! plane as ratios of exactly known polynomials: a filtered `f64` evaluation
//! with a forward error bound first, an exact one when the bound is not good
//! enough.
//!
//! With `n = (v1 − v0) × (v2 − v0)`, the coordinates are `N_i / D`:
//!
//! ```text
//! N_α = n · ((v2 − v1) × (p − v1))
//! N_β = n · ((v0 − v2) × (p − v2))  = n · ((p − v0) × (v2 − v0))
//! N_γ = n · ((v1 − v0) × (p − v0))
//! D   = n · n                        = N_α + N_β + N_γ
//! ```
//!
//! polynomials of degree 4 in the input coordinates (each `(v_j − v_i) ×
//! (p − v_i)` equals `(v_i − p) × (v_j − p)`, the `p`-centred form, whatever
//! vertex it is written from). `D = 0` exactly when the vertices are collinear
//! or coincide.
//!
//! Everything here works on the `f64` values of the inputs (exact for `f32`).

use crate::exact::{BigFloat, Estimate, Sign};
use crate::real::{Real, Vec3, to_f64_3};
use crate::shapes::Triangle;

/// A point in `f64`.
pub(super) type P3 = [f64; 3];

/// Unit roundoff of `f64`, `u = 2^−53`.
const U: f64 = 1.1102230246251565e-16;

/// Shewchuk's `ccwerrboundA`, `(3 + 16u)u`: the exact 2×2 determinant
/// `a_x b_y − a_y b_x` of exact differences `a = a1 − a0`, `b = b1 − b0`
/// lies within `CROSS_BOUND · (|fl(â_x b̂_y)| + |fl(â_y b̂_x)|)` of the value
/// computed from the rounded differences `â`, `b̂` (Shewchuk, *Adaptive
/// Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates*,
/// 1997, §4.3; the differences' roundings are part of his analysis). Each
/// cross-product component below is such a determinant.
const CROSS_BOUND: f64 = (3.0 + 16.0 * U) * U;

/// `γ3 = 3u/(1 − 3u) < (3 + 16u)u`: the rounding of `(x0·y0 + x1·y1) + x2·y2`
/// relative to `Σ |x_k y_k|` (three roundings on the deepest term).
const DOT_ROUNDING: f64 = (3.0 + 16.0 * U) * U;

/// Factor applied to every computed error bound (and to the left side of the
/// acceptance test) so that its own roundings — fewer than 16 per quantity,
/// each at most `u`, all on non-negative terms — cannot make it an
/// underestimate: `1 + 32u`.
const BOUND_ROUNDING: f64 = 1.0 + 32.0 * U;

/// Absolute slack (2^−1000) added to every filter bound, in the scaled frame
/// where every factor is below 2: it covers products that underflow (each off
/// by at most 2^−1075, carried through at most two more factors below 2) and
/// differences that became subnormal when scaled down (each off by at most
/// 2^−1074), with a wide margin. A value this small in the scaled frame (a
/// triangle thinner than about 2^−500 of its size) goes to the exact path.
const UNDERFLOW_SLACK: f64 = 9.332636185032189e-302;

/// The filter's target, relative to the coordinates' size
/// `max(1, max_i |coordinate_i|)`: the `f64` answer is used only when the
/// error bounds of the two coordinates that are kept (the third becomes
/// `1 −` them) sum to at most this, so that each of the three is within it
/// (plus the final roundings, `3.5 ε` at most: see [`signed_area_ratios`]).
/// `12 ε = 3 · 2^−50 ≈ 2.7e-15`.
///
/// Reason: every answer is meant to be within `16 ε` of the size of the exact
/// coordinates whatever the triangle's shape (the unit of crashtest's
/// barycentric conditioning allowance); `12 ε + 3.5 ε` is. The computed bound
/// is pessimistic — it adds every rounding at its worst: for random triangles
/// and points in a box the actual error is a few `u` while the bound's median
/// is about `15 ε` for the two coordinates together — so the target trades
/// accuracy against how often the exact path runs. Measured on such inputs:
/// at `8 ε` 73% of queries need the exact path, at `12 ε` 50%, at `16 ε` 30%,
/// at `32 ε` 6%; the exact path on fixed-width integers costs about 1.6
/// times the filter.
pub(super) const FILTER_TOL: f64 = 2.6645352591003757e-15;

/// Coordinates from [`signed_area_ratios`]: `coords[free]` is only an
/// approximation (the filter does not certify it); the caller replaces it
/// with `1 −` the other two.
#[derive(Clone, Copy, Debug)]
pub(super) struct Ratios {
    /// `[N_α / D, N_β / D, N_γ / D]`, possibly `±∞` beyond `f64`'s range.
    pub coords: [f64; 3],
    /// The coordinate to recompute from the other two (the largest in
    /// magnitude).
    pub free: usize,
}

#[cfg(test)]
thread_local! {
    /// Exact-path evaluations on this thread, so tests can measure the filter.
    static EXACT_PATH: core::cell::Cell<u64> = const { core::cell::Cell::new(0) };
}

/// How many [`signed_area_ratios`] calls on this thread took the exact path.
#[cfg(test)]
pub(super) fn exact_path_count() -> u64 {
    EXACT_PATH.with(|c| c.get())
}

/// Which exact evaluation the inputs would get: `"narrow"`, `"wide"` (the
/// fixed-width grids) or `"big"` ([`BigFloat`]).
#[cfg(test)]
pub(super) fn exact_kind(p: &P3, v: &[P3; 3]) -> &'static str {
    grid::kind(p, v)
}

/// The coordinates `N_i / D` of `p`'s projection onto the plane of `v`, or
/// `None` when the triangle has exactly zero area (`D = 0`: collinear or
/// coincident vertices, the same decision as
/// [`exact::collinear`](crate::exact::collinear)). Inputs must be finite.
///
/// 1. **Filter.** The seven differences (`v1 − v0`, `v2 − v0`, `v2 − v1` and
///    `p − v_i`) are rounded once; the edges are scaled by one power of two
///    and the offsets `p − v_i` by another (exactly, up to subnormals) so the
///    largest component of each group lies in `[1, 2)`, and nothing can
///    overflow or underflow. Each component of `n` and of the three
///    `edge × offset` products gets Shewchuk's orient2d bound (`η_k`, `ζ_k`);
///    each dot product `N̂ = n̂·ĉ` the bound `A = Σ |n̂_k| ζ_k + |ĉ_k| η_k +
///    η_k ζ_k` plus its own rounding; `D̂ = Σ n̂_k²` the bound
///    `B = Σ 2 |n̂_k| η_k + η_k²` plus rounding (no cancellation in the sum).
///    A coordinate `N̂_i / D̂` is then within `(A_i + |N̂_i| B / D̂) / (D̂ − B)`
///    of the exact one; the filter answers when that, summed over the two kept
///    coordinates, is at most [`FILTER_TOL`] of the size. Each kept
///    coordinate is then off by at most its bound plus two roundings
///    (`N̂ · (1/D̂)`, within `ε` of its magnitude), and the recomputed one by
///    the sum of their errors plus two roundings of `1 − a − b` (`1.5 ε` of
///    the size): `FILTER_TOL + 3.5 ε` of the size in all.
/// 2. **Exact.** Otherwise `D`, `N_β`, `N_γ` are evaluated exactly and
///    `N_α = D − N_β − N_γ`; `D = 0` is the zero-area case. When the inputs'
///    significant bits lie within 61 binades of each other (all but contrived
///    scenes), the inputs are integers on a common grid and the evaluation
///    runs on fixed-width integers (`i128` and 256-bit), without allocation;
///    within 124 binades on 512-bit integers; beyond, in [`BigFloat`]. Each
///    value is rounded to an [`Estimate`] (relative error `≤ ε`), so each
///    coordinate is within `2.5 ε` of its own magnitude and the recomputed
///    one within `6.5 ε` of the size.
///
/// Takes the query in its own type and converts to `f64` here: the filter
/// then works on values in registers, and only the exact path (which takes
/// its inputs by reference) gives them a home in memory. Building `f64`
/// arrays in the caller instead made the filter reload them in wider loads
/// than they were stored with, which stalls.
#[inline(always)]
pub(super) fn signed_area_ratios<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Option<Ratios> {
    let v = [to_f64_3(&tri.vertices[0]), to_f64_3(&tri.vertices[1]), to_f64_3(&tri.vertices[2])];
    if let Some(r) = filtered(&to_f64_3(p), &v) {
        return Some(r);
    }
    exact_of(p, tri)
}

/// The exact path from the query's own type.
#[inline(never)]
fn exact_of<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Option<Ratios> {
    #[cfg(test)]
    EXACT_PATH.with(|c| c.set(c.get() + 1));
    let v = [to_f64_3(&tri.vertices[0]), to_f64_3(&tri.vertices[1]), to_f64_3(&tri.vertices[2])];
    exact(&to_f64_3(p), &v)
}

// ---------------------------------------------------------------- filter

#[inline(always)]
fn sub(a: &P3, b: &P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn max_abs3(v: &P3) -> f64 {
    v[0].abs().max(v[1].abs()).max(v[2].abs())
}

/// `2^e` for `e ∈ [−1022, 1023]`, from its bits.
#[inline(always)]
fn pow2(e: i64) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// `x · 2^e` for any `e`, in steps whose factors are normal powers of two:
/// exact unless the result (or, for `|e| > 1022`, an intermediate) is
/// subnormal — then within `2^−1074` — or overflows to `±∞`.
#[inline(always)]
fn ldexp(x: f64, e: i64) -> f64 {
    if (-1022..=1023).contains(&e) {
        return x * pow2(e);
    }
    let (mut x, mut e) = (x, e);
    while e > 1023 {
        x *= pow2(1023);
        e -= 1023;
    }
    while e < -1022 {
        x *= pow2(-1022);
        e += 1022;
    }
    x * pow2(e)
}

/// The `k` with `m · 2^k ∈ [1, 2)`, for a finite `m > 0`.
#[inline(always)]
fn unit_exponent(m: f64) -> i64 {
    if m >= f64::MIN_POSITIVE {
        1023 - ((m.to_bits() >> 52) & 0x7ff) as i64
    } else {
        // Subnormal: 2^64 m is normal.
        64 + 1023 - (((m * pow2(64)).to_bits() >> 52) & 0x7ff) as i64
    }
}

#[inline(always)]
fn scale3(v: &P3, k: i64) -> P3 {
    if (-1022..=1023).contains(&k) {
        let f = pow2(k);
        [v[0] * f, v[1] * f, v[2] * f]
    } else {
        [ldexp(v[0], k), ldexp(v[1], k), ldexp(v[2], k)]
    }
}

/// `a × b` from rounded differences, with Shewchuk's bound on each component
/// (plus [`UNDERFLOW_SLACK`]).
#[inline(always)]
fn cross_bounded(a: &P3, b: &P3) -> (P3, P3) {
    let det = |l: f64, r: f64| (l - r, CROSS_BOUND * (l.abs() + r.abs()) + UNDERFLOW_SLACK);
    let (x, ex) = det(a[1] * b[2], a[2] * b[1]);
    let (y, ey) = det(a[2] * b[0], a[0] * b[2]);
    let (z, ez) = det(a[0] * b[1], a[1] * b[0]);
    ([x, y, z], [ex, ey, ez])
}

/// `n̂ · ĉ` and a bound on its distance from the exact `n · c`, given bounds
/// `η`, `ζ` on the components: `n̂_k ĉ_k − n_k c_k = n̂_k χ_k + ĉ_k ν_k − ν_k χ_k`
/// with `|ν_k| ≤ η_k`, `|χ_k| ≤ ζ_k`, plus the dot product's own rounding.
#[inline(always)]
fn dot_bounded(n: &P3, eta: &P3, c: &P3, zeta: &P3) -> (f64, f64) {
    let t = [n[0] * c[0], n[1] * c[1], n[2] * c[2]];
    let value = (t[0] + t[1]) + t[2];
    let mut err = DOT_ROUNDING * ((t[0].abs() + t[1].abs()) + t[2].abs());
    for k in 0..3 {
        err += n[k].abs() * zeta[k] + c[k].abs() * eta[k] + eta[k] * zeta[k];
    }
    (value, err * BOUND_ROUNDING + UNDERFLOW_SLACK)
}

/// The filter (step 1 of [`signed_area_ratios`]); `None` when it cannot certify
/// the answer to [`FILTER_TOL`].
#[inline]
fn filtered(p: &P3, v: &[P3; 3]) -> Option<Ratios> {
    let [v0, v1, v2] = v;
    let (e0, e1, e12) = (sub(v1, v0), sub(v2, v0), sub(v2, v1));
    let (q0, q1, q2) = (sub(p, v0), sub(p, v1), sub(p, v2));
    let me = max_abs3(&e0).max(max_abs3(&e1)).max(max_abs3(&e12));
    let mq = max_abs3(&q0).max(max_abs3(&q1)).max(max_abs3(&q2));
    // An overflowed difference, or coincident vertices (a rounded difference
    // is zero only when its operands are equal), or p on all three of them:
    // for the exact path.
    if !(me.is_finite() && mq.is_finite()) || me == 0.0 || mq == 0.0 {
        return None;
    }
    let (ke, kq) = (unit_exponent(me), unit_exponent(mq));
    let (e0, e1, e12) = (scale3(&e0, ke), scale3(&e1, ke), scale3(&e12, ke));
    let (q0, q1, q2) = (scale3(&q0, kq), scale3(&q1, kq), scale3(&q2, kq));
    // v0 − v2 is −(v2 − v0) exactly (rounding is symmetric).
    let e20 = [-e1[0], -e1[1], -e1[2]];

    let (n, eta) = cross_bounded(&e0, &e1);
    let sq = [n[0] * n[0], n[1] * n[1], n[2] * n[2]];
    let d = (sq[0] + sq[1]) + sq[2];
    let mut b = DOT_ROUNDING * d;
    for k in 0..3 {
        b += (2.0 * n[k].abs() + eta[k]) * eta[k];
    }
    let b = b * BOUND_ROUNDING + UNDERFLOW_SLACK;
    // D̂'s relative error alone carries over to every coordinate: beyond the
    // target (a sliver, or zero area) the acceptance test below would fail
    // unless both kept coordinates were far below 1, so the numerators are
    // not worth computing. (Leaving early is always safe: the exact path
    // answers.) Every value here is finite: the factors are below 2.
    if b > FILTER_TOL * d {
        return None;
    }

    let numerator = |edge: &P3, offset: &P3| {
        let (c, zeta) = cross_bounded(edge, offset);
        dot_bounded(&n, &eta, &c, &zeta)
    };
    let num = [numerator(&e12, &q1), numerator(&e20, &q2), numerator(&e0, &q0)];

    // Scaled: N' = 2^(3ke + kq) N and D' = 2^(4ke) D, so N/D = (N'/D') 2^s.
    let s = ke - kq;
    let mut free = 0;
    for i in 1..3 {
        if num[i].0.abs() > num[free].0.abs() {
            free = i;
        }
    }
    let (i, j) = ((free + 1) % 3, (free + 2) % 3);
    // err_i + err_j ≤ FILTER_TOL · max(1, |c_i|, |c_j|), with
    // err_k = (A_k + |N̂_k| B/D̂)/(D̂ − B) and c_k = (N̂_k/D̂) 2^s, multiplied
    // through by D̂ (D̂ − B) > 0 (no division).
    let (ni, nj) = (num[i].0.abs(), num[j].0.abs());
    let lhs = ((num[i].1 + num[j].1) * d + (ni + nj) * b) * BOUND_ROUNDING;
    let size = ldexp(d, -s).max(ni).max(nj);
    let rhs = FILTER_TOL * ((d - b) * size);
    if lhs > rhs {
        return None;
    }
    let inv = 1.0 / d;
    Some(Ratios { coords: num.map(|(x, _)| ldexp(x * inv, s)), free })
}

// ---------------------------------------------------------------- exact

/// The exact path (step 2 of [`signed_area_ratios`]).
#[cold]
fn exact(p: &P3, v: &[P3; 3]) -> Option<Ratios> {
    let values = match grid::exact_values(p, v) {
        Some(values) => values,
        None => big::exact_values(p, v),
    };
    let [d, n_beta, n_gamma, n_alpha] = values?;
    let coords = [n_alpha, n_beta, n_gamma].map(|x| quotient(&x, &d));
    let mut free = 0;
    for i in 1..3 {
        if coords[i].abs() > coords[free].abs() {
            free = i;
        }
    }
    Some(Ratios { coords, free })
}

/// `num / den` from their estimates (`den > 0`), saturating to `±∞` and
/// flushing toward zero outside `f64`'s range: the mantissas' quotient (in
/// `(1/2, 2)`) rounded once, then scaled.
fn quotient(num: &Estimate, den: &Estimate) -> f64 {
    let q = num.mant / den.mant;
    let signed = match num.sign {
        Sign::Zero => return 0.0,
        Sign::Negative => -q,
        Sign::Positive => q,
    };
    // Beyond ±2200 the answer is ±∞ or ±0 whatever the mantissa.
    ldexp(signed, (num.exp - den.exp).clamp(-2200, 2200))
}

/// Exact evaluation in [`BigFloat`]: any finite input.
mod big {
    use super::{BigFloat, Estimate, P3};

    type Big3 = [BigFloat; 3];

    fn sub(a: &Big3, b: &Big3) -> Big3 {
        [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
    }

    fn cross(a: &Big3, b: &Big3) -> Big3 {
        [&(&a[1] * &b[2]) - &(&a[2] * &b[1]), &(&a[2] * &b[0]) - &(&a[0] * &b[2]), &(&a[0] * &b[1]) - &(&a[1] * &b[0])]
    }

    fn dot(a: &Big3, b: &Big3) -> BigFloat {
        &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
    }

    /// `[D, N_β, N_γ, N_α]` as estimates, or `None` when `D = 0`.
    pub(super) fn exact_values(p: &P3, v: &[P3; 3]) -> Option<[Estimate; 4]> {
        let big3 = |x: &P3| x.map(BigFloat::from_f64);
        let (v0, v1, v2, p) = (big3(&v[0]), big3(&v[1]), big3(&v[2]), big3(p));
        let (e0, e1, q0) = (sub(&v1, &v0), sub(&v2, &v0), sub(&p, &v0));
        let n = cross(&e0, &e1);
        let d = dot(&n, &n);
        if d.is_zero() {
            return None;
        }
        let n_gamma = dot(&n, &cross(&e0, &q0));
        let n_beta = dot(&n, &cross(&q0, &e1));
        let n_alpha = &(&d - &n_beta) - &n_gamma;
        Some([d, n_beta, n_gamma, n_alpha].map(|x| x.estimate()))
    }
}

/// Exact evaluation on fixed-width integers, without allocation. Every input
/// is `m · 2^e` with an integer `m` of at most 53 bits; with `lo` the smallest
/// such `e` among the non-zero inputs, every input is the integer
/// `m · 2^(e − lo)` times `2^lo`, and the common factor `2^(4 lo)` cancels in
/// the ratios. When those integers are below `2^61` (the narrow grid: the
/// inputs' significant bits span at most 61 binades) the differences fit in
/// `i64` (`< 2^62`), the cross products in native `i128` (`< 2^125`) and the
/// numerators and denominator in 256 bits (`< 2^254`); below `2^124` (the
/// wide grid) in 128, 256 and 512 bits. Both in two's complement; no value
/// comes near its type's limit.
mod grid {
    use super::{Estimate, P3};

    /// Bits of magnitude below which the inputs' integers take the narrow
    /// path.
    const NARROW_BITS: i64 = 61;
    /// Bits of magnitude below which the inputs' integers take the wide path
    /// (beyond: [`BigFloat`](super::BigFloat)).
    const WIDE_BITS: i64 = 124;

    type W2 = [u64; 2];
    type W4 = [u64; 4];
    type W8 = [u64; 8];

    /// `(m, e)` with `x = m · 2^e` exactly, `m` odd (or zero, with `e = 0`).
    #[inline(always)]
    fn decompose(x: f64) -> (i64, i64) {
        let bits = x.to_bits();
        let biased = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        let (m, e) = if biased == 0 { (fraction, -1074) } else { (fraction | (1u64 << 52), biased - 1075) };
        if m == 0 {
            return (0, 0);
        }
        let tz = m.trailing_zeros();
        let m = (m >> tz) as i64;
        (if x < 0.0 { -m } else { m }, e + i64::from(tz))
    }

    #[inline(always)]
    fn is_negative<const L: usize>(a: &[u64; L]) -> bool {
        a[L - 1] >> 63 == 1
    }

    #[inline(always)]
    fn add<const L: usize>(a: &[u64; L], b: &[u64; L]) -> [u64; L] {
        let mut out = [0u64; L];
        let mut carry = false;
        for i in 0..L {
            let (s1, c1) = a[i].overflowing_add(b[i]);
            let (s2, c2) = s1.overflowing_add(u64::from(carry));
            out[i] = s2;
            carry = c1 || c2;
        }
        out
    }

    #[inline(always)]
    fn negate<const L: usize>(a: &[u64; L]) -> [u64; L] {
        let mut out = [0u64; L];
        let mut carry = true;
        for i in 0..L {
            let (s, c) = (!a[i]).overflowing_add(u64::from(carry));
            out[i] = s;
            carry = c;
        }
        out
    }

    #[inline(always)]
    fn sub<const L: usize>(a: &[u64; L], b: &[u64; L]) -> [u64; L] {
        add(a, &negate(b))
    }

    #[inline(always)]
    fn magnitude<const L: usize>(a: &[u64; L]) -> [u64; L] {
        if is_negative(a) { negate(a) } else { *a }
    }

    /// The signed product in `C = A + B` limbs (the operands' magnitudes
    /// keep the result's top bit clear).
    fn mul<const A: usize, const B: usize, const C: usize>(a: &[u64; A], b: &[u64; B]) -> [u64; C] {
        let (ma, mb) = (magnitude(a), magnitude(b));
        let mut out = [0u64; C];
        for i in 0..A {
            let mut carry: u128 = 0;
            for j in 0..B {
                let cur = u128::from(out[i + j]) + u128::from(ma[i]) * u128::from(mb[j]) + carry;
                out[i + j] = cur as u64;
                carry = cur >> 64;
            }
            out[i + B] = carry as u64;
        }
        if is_negative(a) != is_negative(b) { negate(&out) } else { out }
    }

    /// `a · b` for `|a|, |b| < 2^126`, as a 256-bit two's complement value.
    #[inline(always)]
    fn mul_i128(a: i128, b: i128) -> W4 {
        let (x, y) = (a.unsigned_abs(), b.unsigned_abs());
        let (x0, x1) = (u128::from(x as u64), x >> 64);
        let (y0, y1) = (u128::from(y as u64), y >> 64);
        let (p00, p01, p10, p11) = (x0 * y0, x0 * y1, x1 * y0, x1 * y1);
        // The middle column p01 + p10 + ⌊p00 / 2^64⌋ may carry into bit 128.
        let (mid, c1) = p01.overflowing_add(p10);
        let (mid, c2) = mid.overflowing_add(p00 >> 64);
        let high = p11 + (mid >> 64) + (u128::from(u8::from(c1) + u8::from(c2)) << 64);
        let out = [p00 as u64, mid as u64, high as u64, (high >> 64) as u64];
        if (a < 0) != (b < 0) { negate(&out) } else { out }
    }

    /// The value as an [`Estimate`]: the top 64 bits of the magnitude,
    /// truncated (relative error `< 2^−63`, the top bit being set) and rounded
    /// to `f64` once: within `2^−53 + 2^−63 < ε` relative.
    #[inline]
    fn estimate<const L: usize>(a: &[u64; L]) -> Estimate {
        let negative = is_negative(a);
        let m = magnitude(a);
        let Some(top) = (0..L).rev().find(|&i| m[i] != 0) else {
            return Estimate::ZERO;
        };
        let lz = m[top].leading_zeros();
        let window = if lz == 0 {
            m[top]
        } else {
            let below = if top > 0 { m[top - 1] } else { 0 };
            (m[top] << lz) | (below >> (64 - lz))
        };
        let x = window as f64;
        let exp = 64 * top as i64 - i64::from(lz);
        Estimate::from_scaled(if negative { -x } else { x }, exp, f64::EPSILON)
    }

    /// `a × b` of `i64` vectors with components below `2^62`: below `2^125`.
    #[inline(always)]
    fn cross_i64(a: &[i64; 3], b: &[i64; 3]) -> [i128; 3] {
        let m = |x: i64, y: i64| i128::from(x) * i128::from(y);
        [m(a[1], b[2]) - m(a[2], b[1]), m(a[2], b[0]) - m(a[0], b[2]), m(a[0], b[1]) - m(a[1], b[0])]
    }

    /// `a · b` of `i128` vectors with components below `2^125`, in 256 bits.
    #[inline(always)]
    fn dot_i128(a: &[i128; 3], b: &[i128; 3]) -> W4 {
        let s = add(&mul_i128(a[0], b[0]), &mul_i128(a[1], b[1]));
        add(&s, &mul_i128(a[2], b[2]))
    }

    /// The narrow grid: integers below `2^61`.
    #[inline(always)]
    fn narrow(ints: &[i64; 12]) -> Option<[Estimate; 4]> {
        let mut e0 = [0i64; 3];
        let mut e1 = [0i64; 3];
        let mut q0 = [0i64; 3];
        for k in 0..3 {
            e0[k] = ints[3 + k] - ints[k];
            e1[k] = ints[6 + k] - ints[k];
            q0[k] = ints[9 + k] - ints[k];
        }
        let n = cross_i64(&e0, &e1);
        if (n[0] | n[1] | n[2]) == 0 {
            return None;
        }
        let d = dot_i128(&n, &n);
        let n_gamma = dot_i128(&n, &cross_i64(&e0, &q0));
        let n_beta = dot_i128(&n, &cross_i64(&q0, &e1));
        let n_alpha = sub(&sub(&d, &n_beta), &n_gamma);
        Some([estimate(&d), estimate(&n_beta), estimate(&n_gamma), estimate(&n_alpha)])
    }

    /// The wide grid: integers below `2^124`.
    fn wide(ints: &[i128; 12]) -> Option<[Estimate; 4]> {
        let d = |i: usize, j: usize| -> [W2; 3] {
            [0, 1, 2].map(|k| {
                let x = (ints[3 * i + k] - ints[3 * j + k]) as u128;
                [x as u64, (x >> 64) as u64]
            })
        };
        let (e0, e1, q0) = (d(1, 0), d(2, 0), d(3, 0));
        let cross = |a: &[W2; 3], b: &[W2; 3]| -> [W4; 3] {
            let m = |x: &W2, y: &W2| -> W4 { mul(x, y) };
            [
                sub(&m(&a[1], &b[2]), &m(&a[2], &b[1])),
                sub(&m(&a[2], &b[0]), &m(&a[0], &b[2])),
                sub(&m(&a[0], &b[1]), &m(&a[1], &b[0])),
            ]
        };
        let dot = |a: &[W4; 3], b: &[W4; 3]| -> W8 {
            let m = |x: &W4, y: &W4| -> W8 { mul(x, y) };
            add(&add(&m(&a[0], &b[0]), &m(&a[1], &b[1])), &m(&a[2], &b[2]))
        };
        let n = cross(&e0, &e1);
        if n.iter().flatten().all(|&x| x == 0) {
            return None;
        }
        let d = dot(&n, &n);
        let n_gamma = dot(&n, &cross(&e0, &q0));
        let n_beta = dot(&n, &cross(&q0, &e1));
        let n_alpha = sub(&sub(&d, &n_beta), &n_gamma);
        Some([d, n_beta, n_gamma, n_alpha].map(|x| estimate(&x)))
    }

    /// The inputs `v0, v1, v2, p` decomposed: mantissas, exponents, the
    /// smallest exponent and the largest top bit among the non-zero ones
    /// (`i64::MAX`, `i64::MIN` when all are zero).
    #[inline(always)]
    fn decomposed(p: &P3, v: &[P3; 3]) -> ([i64; 12], [i64; 12], i64, i64) {
        let mut m = [0i64; 12];
        let mut e = [0i64; 12];
        let (mut lo, mut hi) = (i64::MAX, i64::MIN);
        for (k, x) in v.iter().chain([p]).flatten().enumerate() {
            let (mk, ek) = decompose(*x);
            m[k] = mk;
            e[k] = ek;
            if mk != 0 {
                lo = lo.min(ek);
                hi = hi.max(ek + 64 - i64::from(mk.unsigned_abs().leading_zeros()));
            }
        }
        (m, e, lo, hi)
    }

    /// Which evaluation [`exact_values`] gives these inputs.
    #[cfg(test)]
    pub(super) fn kind(p: &P3, v: &[P3; 3]) -> &'static str {
        let (_, _, lo, hi) = decomposed(p, v);
        match hi.saturating_sub(lo) {
            span if span <= NARROW_BITS => "narrow",
            span if span <= WIDE_BITS => "wide",
            _ => "big",
        }
    }

    /// `[D, N_β, N_γ, N_α]` as estimates (`None` inside when `D = 0`), or
    /// `None` outside when the inputs do not fit a grid.
    pub(super) fn exact_values(p: &P3, v: &[P3; 3]) -> Option<Option<[Estimate; 4]>> {
        let (m, e, lo, hi) = decomposed(p, v);
        if lo == i64::MAX {
            // Every coordinate is zero: four coincident points.
            return Some(None);
        }
        let span = hi - lo;
        if span <= NARROW_BITS {
            let mut ints = [0i64; 12];
            for k in 0..12 {
                if m[k] != 0 {
                    ints[k] = m[k] << (e[k] - lo);
                }
            }
            Some(narrow(&ints))
        } else if span <= WIDE_BITS {
            let mut ints = [0i128; 12];
            for k in 0..12 {
                if m[k] != 0 {
                    ints[k] = i128::from(m[k]) << (e[k] - lo);
                }
            }
            Some(wide(&ints))
        } else {
            None
        }
    }
}
