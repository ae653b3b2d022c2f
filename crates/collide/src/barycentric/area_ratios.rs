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

/// The accuracy [`barycentric_triangle`](super::barycentric_triangle)
/// promises, relative to the coordinates' size `max(1, max_i |coordinate_i|)`:
/// `2^−40 ≈ 9.1e-13`, for any triangle of non-zero area.
///
/// Reason: crashtest's judge allows `1e-9` absolute on a barycentric
/// coordinate plus a conditioning allowance; `2^−40` of the size is three
/// orders of magnitude inside that and leaves the plain `f64` formula (whose
/// error bound is a few hundred `u` over the triangle's squared shape factor)
/// enough room to answer every triangle that is not a sliver, so that only
/// slivers, near-degenerate and zero-area triangles pay for exact arithmetic.
/// The loosest the project accepts is `2^−40`.
pub(super) const ACCURACY: f64 = 9.094947017729282e-13;

/// The tighter accuracy of [`barycentric_triangle_tight`](super::barycentric_triangle_tight):
/// `16 ε = 2^−48` of the size, for callers that certify the coordinates'
/// signs with a margin of a few ulps. (The filters below meet it only for
/// well-conditioned queries, so more of these queries take the exact path.)
pub(super) const TIGHT_ACCURACY: f64 = 3.552713678800501e-15;

/// What the filters' certified error bounds must meet, for a promised
/// accuracy `a` (relative to the size): the bounds of the two coordinates
/// that are kept (the third becomes `1 −` them) sum to at most `a − 4 ε`.
/// Each kept coordinate then carries its bound plus one rounding of the
/// quotient (`ε` of the size) and the recomputed one the sum of the kept
/// ones' errors plus the two roundings of `1 − a − b` (`1.5 ε`): `3.5 ε`
/// beyond the bounds; the last `0.5 ε` covers the difference between the
/// computed size the filters test against and the exact one (a factor
/// `1 + a`).
#[inline(always)]
fn filter_target(accuracy: f64) -> f64 {
    accuracy - 4.0 * f64::EPSILON
}

/// Coordinates from [`slow_ratios`]: `coords[free]` is only an
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

/// How many queries on this thread took the exact path.
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

/// Step 1 of the signed area ratios: the coordinates `N_i / D` of `p`'s
/// projection onto the plane of `tri`, each within `accuracy` ([`ACCURACY`]
/// or [`TIGHT_ACCURACY`]) of the size `max(1, max_i |N_i / D|)` once the
/// caller has recomputed `α` as `1 − β − γ`, or which step must answer
/// instead ([`slow_ratios`]: it returns `None` when the triangle has exactly
/// zero area, `D = 0`: collinear or coincident vertices, the same decision as
/// [`exact::collinear`](crate::exact::collinear), and needs finite inputs).
///
/// The steps:
///
/// 1. **Fast filter** ([`fast`]). The formula in plain `f64` on the rounded
///    differences `e0 = v1 − v0`, `e1 = v2 − v0`, `q = p − v0`, in its Gram
///    form: `D̂ = A B − C²`, `N̂_β = B P − C R`, `N̂_γ = A R − C P` from the
///    dot products `A = e0·e0`, `B = e1·e1`, `C = e0·e1`, `P = q·e0`,
///    `R = q·e1`; `β = N̂_β / D̂`, `γ = N̂_γ / D̂` (`α` is recomputed by the
///    caller). The bound comes from the squared lengths `A`, `B`,
///    `S = ‖q‖²` only: `|N̂ − N| ≤ 26 u ‖q‖ ‖e0‖ ‖e1‖ max(‖e0‖, ‖e1‖)` and
///    `|D̂ − D| ≤ 26 u A B` ([`FAST_BOUND`]). It answers when the lengths lie
///    in a range where nothing overflows or underflows ([`FAST_RANGE`]) and
///    the bound meets the target ([`filter_target`]); for triangles of
///    ordinary proportions that is almost always (the bound is about
///    `26 u (‖q‖/‖e‖ + |c|) / sin²θ0`, `θ0` the angle at `v0`). A bound far
///    beyond the target (a sliver) or an area not certainly non-zero sends
///    the query straight to step 3; one within [`RETRY_FACTOR`] of it, or
///    lengths out of range, to step 2.
/// 2. **Scaled filter** ([`filtered`]). The seven differences (`v1 − v0`,
///    `v2 − v0`, `v2 − v1` and `p − v_i`) are rounded once; the edges are
///    scaled by one power of two and the offsets `p − v_i` by another
///    (exactly, up to subnormals) so the largest component of each group
///    lies in `[1, 2)`, and nothing can overflow or underflow. Each
///    component of `n` and of the three `edge × offset` products gets
///    Shewchuk's orient2d bound (`η_k`, `ζ_k`); each dot product `N̂ = n̂·ĉ`
///    the bound `A = Σ |n̂_k| ζ_k + |ĉ_k| η_k + η_k ζ_k` plus its own
///    rounding; `D̂ = Σ n̂_k²` the bound `B = Σ 2 |n̂_k| η_k + η_k²` plus
///    rounding (no cancellation in the sum). A coordinate `N̂_i / D̂` is then
///    within `(A_i + |N̂_i| B / D̂) / (D̂ − B)` of the exact one; the filter
///    answers when that, summed over the two kept coordinates, meets the
///    target. Tighter than the fast bound and valid at any scale (tiny and
///    huge scenes, points far from the triangle), at several times its cost.
/// 3. **Exact.** Otherwise `n`, `N_β`, `N_γ` are evaluated exactly; `n = 0`
///    is the zero-area case. When the inputs' significant bits lie within 61
///    binades of each other (all but contrived scenes), the inputs are
///    integers on a common grid and the evaluation runs on fixed-width
///    integers (`i128` and 256-bit), without allocation; within 124 binades
///    on 512-bit integers; beyond, in [`BigFloat`]. Each value is rounded to
///    an [`Estimate`] (relative error `≤ ε`), except the narrow grid's
///    `D = Σ n_k²`, summed in `f64` from the exact `n` (no cancellation,
///    within `3 ε`). So `β` and `γ` are within `4.5 ε` of their own magnitude
///    and `α = 1 − β − γ`, recomputed by the caller, within `10.5 ε` of the
///    size (below either accuracy).
///
/// In both filters the answer stands only when `D̂` exceeds its own error
/// bound, i.e. the area is certainly non-zero: zero area is decided by the
/// exact path alone.
///
/// Takes the query in its own type and converts to `f64` here: the filter
/// then works on values in registers, and only the exact path (which takes
/// its inputs by reference) gives them a home in memory. Building `f64`
/// arrays in the caller instead made the filter reload them in wider loads
/// than they were stored with, which stalls.
#[inline(always)]
pub(super) fn fast_ratios<T: Real>(p: &Vec3<T>, tri: &Triangle<T>, accuracy: f64) -> Fast {
    let v = [to_f64_3(&tri.vertices[0]), to_f64_3(&tri.vertices[1]), to_f64_3(&tri.vertices[2])];
    fast(&to_f64_3(p), &v, filter_target(accuracy))
}

/// Steps 2 and 3 of [`fast_ratios`] after the fast filter's miss: the
/// scaled filter, then the exact path, when `scaled_filter` (the miss was
/// [`Fast::Filter`]), or the exact path at once ([`Fast::Exact`]). Inputs
/// must be finite.
///
/// The miss comes as a flag rather than as the [`Fast`] value: passing the
/// enum (with its answer's payload) to an out-of-line call gave it a home in
/// memory on the fast filter's own path, about 1 ns a query.
pub(super) fn slow_ratios<T: Real>(
    p: &Vec3<T>,
    tri: &Triangle<T>,
    accuracy: f64,
    scaled_filter: bool,
) -> Option<Ratios> {
    // Two coincident vertices: zero area, certainly, with no arithmetic (the
    // exact path would find `D = 0` too, after an exact evaluation).
    let [v0, v1, v2] = tri.vertices;
    if v0 == v1 || v1 == v2 || v2 == v0 {
        return None;
    }
    if scaled_filter {
        let v = [to_f64_3(&tri.vertices[0]), to_f64_3(&tri.vertices[1]), to_f64_3(&tri.vertices[2])];
        if let Some(r) = filtered(&to_f64_3(p), &v, filter_target(accuracy)) {
            return Some(r);
        }
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

/// The fast filter's error constant: `26 u`. With `A = ‖e0‖²`, `B = ‖e1‖²`,
/// `S = ‖q‖²` (`e0 = v1 − v0`, `e1 = v2 − v0`, `q = p − v0`, exact), the
/// numerators and denominator computed by [`fast`] from the rounded
/// differences satisfy `|N̂_β − N_β| ≤ FAST_BOUND · ‖q‖ ‖e0‖ ‖e1‖²`,
/// `|N̂_γ − N_γ| ≤ FAST_BOUND · ‖q‖ ‖e0‖² ‖e1‖` and
/// `|D̂ − D| ≤ FAST_BOUND · A B`.
///
/// Derivation (`γ_k = k u / (1 − k u)`): [`fast`] evaluates the Gram form
/// of the formula (Binet–Cauchy: `(a × b)·(c × d) = (a·c)(b·d) − (a·d)(b·c)`),
/// `D = A B − C²`, `N_β = B P − C R`, `N_γ = A R − C P` with `C = e0·e1`,
/// `P = q·e0`, `R = q·e1`. Each dot product of rounded differences (each
/// component within `u` of the exact difference, relatively) is within
/// `(1 + u)² (1 + γ3) − 1 ≤ γ5` of `Σ |x_k y_k| ≤ ‖x‖ ‖y‖` of the exact one.
/// So `Â B̂` is within `(2 γ5 + γ5²) A B` of `A B`, and `Ĉ²` within
/// `|Ĉ − C| (|Ĉ| + |C|) ≤ (2 γ5 + γ5²) A B` of `C²`; the two products and
/// the difference (of two non-negative values below `A B (1 + γ5)²`) round
/// by at most `3 u A B`: `23 u A B` to first order. Likewise
/// `|B̂ P̂ − B P| ≤ |B̂ − B| |P̂| + B |P̂ − P| ≤ 2 γ5 (1 + γ5) M` and
/// `|Ĉ R̂ − C R| ≤ 2 γ5 (1 + γ5) M` with `M = ‖q‖ ‖e0‖ ‖e1‖²`, and the
/// roundings of the two products and of their difference (of terms up to
/// `M` each, of either sign) add `4 u M`: `24 u M`; the same for `N_γ`
/// with `M = ‖q‖ ‖e0‖² ‖e1‖`. The bound itself is evaluated from the
/// computed `Â`, `B̂`, `Ŝ`, within `γ5` of the exact squared norms. The
/// constant's margin (`2 u`, 8 %) covers those factors, the second-order
/// terms, the roundings of the bound's own evaluation, and products that
/// underflow (each off by at most `2^−1075`, while [`FAST_RANGE`] keeps
/// every bound above `2^−450`).
const FAST_BOUND: f64 = 26.0 * U;

/// The range of the computed squared lengths `Â`, `B̂` and `Ŝ` (see
/// [`FAST_BOUND`]) in which [`fast`] answers: `[2^−200, 2^200]`, lengths
/// within `2^±100` (`Ŝ` may also be exactly zero, `p = v0`). Within it no
/// product in the formula or its bound overflows (`< 2^810`) and the error
/// bounds stay far above the underflow threshold (`> 2^−450`); tinier or
/// huger scenes take the scaled filter, which works at any scale.
const FAST_RANGE: (f64, f64) = (6.223015277861142e-61, 1.6069380442589903e60);

/// The larger of two values that are not NaN (one `maxsd`, without the
/// NaN handling of `f64::max`).
#[inline(always)]
fn max2(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// `a · b` in plain `f64`, as `(a0 b0 + a1 b1) + a2 b2`.
#[inline(always)]
fn dot(a: &P3, b: &P3) -> f64 {
    (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]
}

/// How far beyond the target the fast bound may be for the scaled filter to
/// be worth trying (unitless ratio, 64): the scaled filter's per-component
/// bound is tighter than the fast norm bound by a small factor for triangles
/// of ordinary proportions (the fast one bounds every term by products of
/// whole lengths), so a query the fast bound misses by more is a sliver or a
/// degenerate one, whose answer the scaled filter would not certify either;
/// it goes straight to the exact path.
const RETRY_FACTOR: f64 = 64.0;

/// What the fast filter concluded.
pub(super) enum Fast {
    /// The certified answer `β`, `γ` (`α` is `1 −` them).
    Answer(f64, f64),
    /// Outside [`FAST_RANGE`], or a bound within [`RETRY_FACTOR`] of the
    /// target: for the scaled filter.
    Filter,
    /// The bound is far beyond the target, or the area is not certainly
    /// non-zero: for the exact path.
    Exact,
}

/// The fast filter (step 1 of [`fast_ratios`]): the formula in its Gram
/// form (see [`FAST_BOUND`]: five dot products, six products) with the norm
/// bound of [`FAST_BOUND`].
///
/// With `K` = [`FAST_BOUND`], the numerators' bounds sum to
/// `K ‖q‖ ‖e0‖ ‖e1‖ (‖e0‖ + ‖e1‖) ≤ K √(2 S A B (A + B))` (one square root)
/// and the denominator's is `errD = K A B`. Each coordinate `N̂/D̂` is within
/// `(errN + |N̂/D̂| errD)/(D̂ − errD)` of `N/D` (when `D̂ > errD`, which also
/// certifies `D > 0`); the answer stands when the two coordinates' bounds sum
/// to at most `target` times the computed size `max(1, |α̂|, |β̂|, |γ̂|)`,
/// tested multiplied through by `D̂ − errD`, with the left side raised by
/// [`BOUND_ROUNDING`] for both sides' own roundings (and by `1 + 2u` inside
/// it for the rounding of `β̂`, `γ̂`). Since `D = A B sin²θ0` (`θ0` the angle
/// at `v0`), the bound is about `26 u (‖q‖ (1/‖e0‖ + 1/‖e1‖) + |β| + |γ|) /
/// sin²θ0`: a few hundred `u` for triangles of ordinary proportions.
///
/// Non-finite inputs need no test of their own: every input enters one of
/// the differences, which is then infinite or NaN and fails the range test.
#[inline(always)]
fn fast(p: &P3, v: &[P3; 3], target: f64) -> Fast {
    let [v0, v1, v2] = v;
    let (e0, e1, q) = (sub(v1, v0), sub(v2, v0), sub(p, v0));
    let (a, b, s) = (dot(&e0, &e0), dot(&e1, &e1), dot(&q, &q));
    let (lo, hi) = FAST_RANGE;
    // Refuses NaN and ∞ (an overflowed difference or a non-finite input);
    // an edge of zero length has zero area, for the exact path to decide.
    if !(a >= lo && a <= hi && b >= lo && b <= hi && s <= hi && (s >= lo || s == 0.0)) {
        return if a == 0.0 || b == 0.0 { Fast::Exact } else { Fast::Filter };
    }
    // The Gram form: D = ‖e0 × e1‖², N_β = (e0 × e1)·(q × e1),
    // N_γ = (e0 × e1)·(e0 × q) by Binet–Cauchy.
    let (c, pe0, pe1) = (dot(&e0, &e1), dot(&q, &e0), dot(&q, &e1));
    let d = a * b - c * c;
    let n_beta = b * pe0 - c * pe1;
    let n_gamma = a * pe1 - c * pe0;
    let inv = 1.0 / d;
    let (beta, gamma) = (n_beta * inv, n_gamma * inv);
    let alpha = (1.0 - beta) - gamma;
    let ab = a * b;
    let err_d = FAST_BOUND * ab;
    let err_n = FAST_BOUND * (2.0 * s * ab * (a + b)).sqrt();
    let lhs = (err_n + (beta.abs() + gamma.abs()) * ((1.0 + 2.0 * U) * err_d)) * BOUND_ROUNDING;
    let size = max2(max2(alpha.abs(), beta.abs()), max2(gamma.abs(), 1.0));
    let rhs = target * (size * (d - err_d));
    // `D̂ > errD` certifies `D > 0` (the zero-area decision stays exact).
    // NaN-safe: `d = 0` makes the quotients NaN or infinite, and `lhs` with
    // them; coordinates beyond `f64`'s range (an infinite size) are left to
    // the other steps, which decide them.
    if d > err_d && lhs <= rhs && size < f64::INFINITY {
        return Fast::Answer(beta, gamma);
    }
    if d > err_d && lhs <= RETRY_FACTOR * rhs { Fast::Filter } else { Fast::Exact }
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

/// The scaled filter (step 2 of [`fast_ratios`]); `None` when it
/// cannot certify the answer to `target` (see [`filter_target`]).
#[inline]
fn filtered(p: &P3, v: &[P3; 3], target: f64) -> Option<Ratios> {
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
    if b > target * d {
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
    // err_i + err_j ≤ target · max(1, |c_i|, |c_j|), with
    // err_k = (A_k + |N̂_k| B/D̂)/(D̂ − B) and c_k = (N̂_k/D̂) 2^s, multiplied
    // through by D̂ (D̂ − B) > 0 (no division). D̂ may be as small as about
    // 2^−1000 here (a triangle far thinner than its size, or the edges'
    // small components), so the products of bounds and D̂ would underflow to
    // zero and the test pass whatever the bounds; first every value of the
    // test is brought to D̂'s scale by one power of two, `D̂ ∈ [1, 2)`
    // (exact: D̂, B and the bounds exceed 2^−1000, and scaling up loses
    // nothing). A numerator may then overflow (coordinates beyond about
    // 2^1000 of 2^−s): the test fails and the exact path decides.
    let kd = unit_exponent(d);
    let (d, b) = (ldexp(d, kd), ldexp(b, kd));
    let num = num.map(|(x, err)| (ldexp(x, kd), ldexp(err, kd)));
    let (ni, nj) = (num[i].0.abs(), num[j].0.abs());
    let lhs = ((num[i].1 + num[j].1) * d + (ni + nj) * b) * BOUND_ROUNDING;
    // `D̂ 2^−s` is capped at 2^1001 (lowering the right side only makes the
    // test stricter), so the right side is finite unless a numerator is.
    let size = ldexp(d, (-s).min(1000)).max(ni).max(nj);
    let rhs = target * ((d - b) * size);
    if !(lhs <= rhs && lhs < f64::INFINITY) {
        return None;
    }
    let inv = 1.0 / d;
    Some(Ratios { coords: num.map(|(x, _)| ldexp(x * inv, s)), free })
}

// ---------------------------------------------------------------- exact

/// The exact path (step 3 of [`fast_ratios`]).
#[cold]
fn exact(p: &P3, v: &[P3; 3]) -> Option<Ratios> {
    let values = match grid::exact_values(p, v) {
        Some(values) => values,
        None => big::exact_values(p, v),
    };
    let [d, n_beta, n_gamma] = values?;
    let (beta, gamma) = (quotient(&n_beta, &d), quotient(&n_gamma, &d));
    // `α` is `1 −` the others (by the caller, in its type).
    Some(Ratios { coords: [(1.0 - beta) - gamma, beta, gamma], free: 0 })
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

    /// `[D, N_β, N_γ]` as estimates, or `None` when `D = 0`.
    pub(super) fn exact_values(p: &P3, v: &[P3; 3]) -> Option<[Estimate; 3]> {
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
        Some([d, n_beta, n_gamma].map(|x| x.estimate()))
    }
}

/// Exact evaluation on fixed-width integers, without allocation. Every input
/// is `m · 2^e` with an odd integer `m` of at most 53 bits; with `lo` the
/// smallest such `e` among the non-zero inputs, every input is the integer
/// `x · 2^−lo` (an exact scaling) times `2^lo`, and the common factor
/// `2^(4 lo)` cancels in the ratios. When those integers are below `2^61` (the narrow grid: the
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
    /// Relative error of the narrow grid's `D` (unitless): each `n_k`
    /// rounded to `f64` (`u`), squared (`2u` more) and summed (`γ2`): at most
    /// `(1 + u)² (1 + u)(1 + γ2) − 1 < 5.1 u`, so `3 ε`.
    const D_REL_ERR: f64 = 3.0 * f64::EPSILON;

    /// Bits of magnitude below which the inputs' integers take the wide path
    /// (beyond: [`BigFloat`](super::BigFloat)).
    const WIDE_BITS: i64 = 124;

    type W2 = [u64; 2];
    type W4 = [u64; 4];
    type W8 = [u64; 8];

    /// `(lo, hi)` for a non-zero finite `x`: its lowest set bit is worth
    /// `2^lo` and `|x| < 2^hi`; `(i64::MAX, i64::MIN)` for zero, so that it
    /// drops out of a minimum and a maximum. Branch-free.
    #[inline(always)]
    fn bit_range(x: f64) -> (i64, i64) {
        let bits = x.to_bits();
        let biased = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        let m = if biased == 0 { fraction } else { fraction | (1u64 << 52) };
        let e = biased.max(1) - 1075;
        let lo = e + i64::from(m.trailing_zeros());
        let hi = e + 64 - i64::from(m.leading_zeros());
        if m == 0 { (i64::MAX, i64::MIN) } else { (lo, hi) }
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
    fn narrow(ints: &[i64; 12]) -> Option<[Estimate; 3]> {
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
        // D = Σ n_k² has no cancellation: from the rounded n_k, three
        // roundings more, within D_REL_ERR.
        let nf = n.map(|x| x as f64);
        let d = Estimate::from_scaled((nf[0] * nf[0] + nf[1] * nf[1]) + nf[2] * nf[2], 0, D_REL_ERR);
        let n_gamma = dot_i128(&n, &cross_i64(&e0, &q0));
        let n_beta = dot_i128(&n, &cross_i64(&q0, &e1));
        Some([d, estimate(&n_beta), estimate(&n_gamma)])
    }

    /// The wide grid: integers below `2^124`.
    fn wide(ints: &[i128; 12]) -> Option<[Estimate; 3]> {
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
        Some([d, n_beta, n_gamma].map(|x| estimate(&x)))
    }

    /// The inputs `v0, v1, v2, p` in one array, with the smallest `lo` and
    /// the largest `hi` of [`bit_range`] among them (`i64::MAX`, `i64::MIN`
    /// when all are zero) — or, when that already fits the narrow grid, a
    /// cheaper `lo` from the smallest non-zero magnitude alone: the ulp of a
    /// normal `f64` is at most its lowest set bit, and grows with the
    /// magnitude, so every input is a multiple of the smallest magnitude's
    /// ulp.
    #[inline(always)]
    fn decomposed(p: &P3, v: &[P3; 3]) -> ([f64; 12], i64, i64) {
        let xs = [v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2], v[2][0], v[2][1], v[2][2], p[0], p[1], p[2]];
        let (mut small, mut large) = (f64::INFINITY, 0.0f64);
        for x in xs {
            let a = x.abs();
            small = if a != 0.0 && a < small { a } else { small };
            large = if a > large { a } else { large };
        }
        if (f64::MIN_POSITIVE..f64::INFINITY).contains(&small) {
            let exponent = |x: f64| ((x.to_bits() >> 52) & 0x7ff) as i64 - 1023;
            let (lo, hi) = (exponent(small) - 52, exponent(large) + 1);
            if hi - lo <= NARROW_BITS {
                return (xs, lo, hi);
            }
        }
        let (mut lo, mut hi) = (i64::MAX, i64::MIN);
        for x in xs {
            let (l, h) = bit_range(x);
            lo = lo.min(l);
            hi = hi.max(h);
        }
        (xs, lo, hi)
    }

    /// Which evaluation [`exact_values`] gives these inputs.
    #[cfg(test)]
    pub(super) fn kind(p: &P3, v: &[P3; 3]) -> &'static str {
        let (_, lo, hi) = decomposed(p, v);
        match hi.saturating_sub(lo) {
            span if span <= NARROW_BITS => "narrow",
            span if span <= WIDE_BITS => "wide",
            _ => "big",
        }
    }

    /// `[D, N_β, N_γ]` as estimates (`None` inside when `D = 0`), or
    /// `None` outside when the inputs do not fit a grid.
    pub(super) fn exact_values(p: &P3, v: &[P3; 3]) -> Option<Option<[Estimate; 3]>> {
        let (xs, lo, hi) = decomposed(p, v);
        if lo == i64::MAX {
            // Every coordinate is zero: four coincident points.
            return Some(None);
        }
        // Each input times 2^−lo is an integer below 2^span, and the scaling
        // by a power of two is exact (the result is an integer of at most 124
        // bits, far from under- and overflow), as is its conversion.
        let span = hi - lo;
        if span <= NARROW_BITS {
            let mut ints = [0i64; 12];
            if (-1022..=1023).contains(&-lo) {
                let f = super::pow2(-lo);
                for k in 0..12 {
                    ints[k] = (xs[k] * f) as i64;
                }
            } else {
                for k in 0..12 {
                    ints[k] = super::ldexp(xs[k], -lo) as i64;
                }
            }
            Some(narrow(&ints))
        } else if span <= WIDE_BITS {
            Some(wide(&xs.map(|x| super::ldexp(x, -lo) as i128)))
        } else {
            None
        }
    }
}
