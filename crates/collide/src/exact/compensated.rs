//! Stage B of the queries' filters: the same volumes and plane values as
//! [`filter`](super::filter), evaluated again with error-free transformations
//! (compensated arithmetic, about twice the working precision), each with a
//! rigorous error bound that is **zero when every operation was exact**.
//!
//! Shewchuk's adaptive predicates go from a plain evaluation (stage A) to
//! ever more exact ones before the full expansion; this is the middle stage
//! for the queries. Where stage A's bound is a few `u` times the permanent
//! (`u = 2^−53`), this one is a few `u` times the *tails* — the rounding
//! errors of the differences, products and sums, themselves at most `u` times
//! what they came from — so it is of order `u²` times the permanent: it
//! decides every value that is not within about `1e-30` of its permanent, and
//! gives values accurate to about `u` relative. And because its bound is
//! built from the tails themselves, a value whose every operation was exact
//! (grid coordinates, a point exactly on an edge, an endpoint exactly on a
//! plane, a segment exactly parallel — the exact zeros of the edge walkers)
//! comes out with bound `0`: certified exactly, zero included, without the
//! expansion arithmetic. What is left (a zero with inexact tails, inputs out
//! of range) goes to the predicates of [`crate::exact`] as before.
//!
//! # The primitives
//!
//! `two_diff(a, b) = (x, y)`: `x = fl(a − b)`, `x + y = a − b` exactly
//! (Knuth). `two_prod(a, b) = (x, y)`: `x = fl(a b)`, `x + y = a b` exactly
//! (Dekker's product with Veltkamp's split; no fused multiply-add is assumed).
//! `two_sum` likewise. All hold when nothing overflows and no product's error
//! underflows; [`in_range`] makes that true (below).
//!
//! # Domain ([`in_range`])
//!
//! Every input is `0` or of magnitude in `[2^−250, 2^63]`. Then every input is
//! an integer multiple of `2^−302` (its last bit is at most 52 binades below
//! its first), so is every exact difference and every part of one; every
//! product of three such is a multiple of `2^−906`, and so is every exact sum
//! of them. A value that is a multiple of `2^−906` is either represented
//! exactly or rounded in the normal range (it is at least `2^−853` when it has
//! more than 53 significant bits), so every rounding below obeys
//! `fl(x ∘ y) = (x ∘ y)(1 + δ)`, `|δ| ≤ u`, and every error term is exact.
//! Nothing overflows: differences are at most `2^64`, volumes `2^195`, and
//! Veltkamp's split needs only `|x| < 2^996`.
//!
//! # Error bounds
//!
//! Standard results (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, §3–4): a sum of `n` terms evaluated in any order by `n − 1`
//! roundings is within `γ_{n−1} Σ|terms|` of the exact sum,
//! `γ_k = k u / (1 − k u)`; a rounded product is within `u` of itself. Each
//! bound below is stated in terms of `Σ|computed terms|` (computed as a sum
//! of non-negative terms, which rounds down by at most `(1 − u)^{n−1}`), and
//! every computed bound is multiplied by [`BOUND_ROUNDING`] `= 1 + 32u`, which
//! covers its own roundings (fewer than 30, each of a non-negative quantity).
//! The derivations are at [`cross`], [`dot`] and [`plane`].

use super::P3;
use super::expansion::{split, two_diff, two_sum};
use super::filter::{FAST_MAX, Filtered};

/// Unit roundoff of `f64` (2^−53).
const U: f64 = 1.1102230246251565e-16;

/// Smallest non-zero input magnitude of stage B (2^−250): see the module's
/// **Domain**.
pub(crate) const MIN_INPUT: f64 = 5.527147875260445e-76;

/// Factor on every computed bound for the bound's own roundings (fewer than
/// 30 roundings of non-negative terms, each at most `u`): `1 + 32u`.
const BOUND_ROUNDING: f64 = 1.0 + 32.0 * U;

/// Factor of a cross-product component's tail sum (see [`cross`]): `9u`.
const CROSS_TAIL: f64 = 9.0 * U;

/// Factor of a triple product's tail sum (see [`dot`]): `13u`.
const DOT_TAIL: f64 = 13.0 * U;

/// Factor of `n · (p1 − p0)`'s tail sum (see [`dot_diff`]): `9u`.
const DOT_DIFF_TAIL: f64 = 9.0 * U;

/// Factor of a plane value's tail sum (see [`plane`]): `6u`.
const PLANE_TAIL: f64 = 6.0 * U;

/// Whether every value is `0` or of magnitude in `[2^−250, 2^63]` (false for
/// infinities and NaN): the domain of every function here. Branch-free.
#[inline(always)]
pub(crate) fn in_range<const N: usize>(xs: [f64; N]) -> bool {
    xs.iter().fold(true, |ok, x| {
        let a = x.abs();
        ok & (a <= FAST_MAX) & ((a >= MIN_INPUT) | (a == 0.0))
    })
}

/// [`in_range`] over points (see `filter::in_fast_range_points`).
#[inline(always)]
pub(crate) fn in_range_points<const N: usize>(ps: [P3; N]) -> bool {
    let ok = |x: f64| {
        let a = x.abs();
        (a <= FAST_MAX) & ((a >= MIN_INPUT) | (a == 0.0))
    };
    ps.iter().fold(true, |acc, p| acc & ok(p[0]) & ok(p[1]) & ok(p[2]))
}

/// A value split for Dekker's product: `(x, hi, lo)` with `x = hi + lo`
/// exactly, each half of at most 26 significant bits.
#[derive(Clone, Copy, Debug)]
struct Split {
    x: f64,
    hi: f64,
    lo: f64,
}

#[inline(always)]
fn split_of(x: f64) -> Split {
    let (hi, lo) = split(x);
    Split { x, hi, lo }
}

/// Dekker's `two_product` of presplit factors: `(p, e)`, `p = fl(a b)`,
/// `p + e = a b` exactly.
#[inline(always)]
fn two_prod(a: Split, b: Split) -> (f64, f64) {
    let p = a.x * b.x;
    let err1 = p - a.hi * b.hi;
    let err2 = err1 - a.lo * b.hi;
    let err3 = err2 - a.hi * b.lo;
    (p, a.lo * b.lo - err3)
}

/// A difference of two points held exactly: `hi + lo`, `hi = fl(a − b)`,
/// `|lo| ≤ u |hi|` (per component), with `hi` split for products.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Diff3 {
    hi: [Split; 3],
    lo: P3,
}

/// `a − b`, exactly, as a [`Diff3`].
#[inline(always)]
pub(crate) fn diff(a: P3, b: P3) -> Diff3 {
    let d = [0, 1, 2].map(|i| two_diff(a[i], b[i]));
    Diff3 { hi: d.map(|(h, _)| split_of(h)), lo: d.map(|(_, l)| l) }
}

/// A cross product of two [`Diff3`]s: component `i` is `s_i + t_i + ε_i` with
/// `|ε_i| ≤ err_i` (`err_i = 0` when every operation behind it was exact).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cross {
    s: [Split; 3],
    t: P3,
    err: P3,
}

impl Cross {
    /// The components as `f64` values with their error bounds: component `i`
    /// lies within `bound_i` of `value_i` (`bound_i = 0`: exact).
    #[inline(always)]
    pub(crate) fn components(&self) -> [Filtered; 3] {
        [0, 1, 2].map(|i| component(self.s[i].x, self.t[i], self.err[i]))
    }
}

/// `p × q` of exact differences, compensated.
///
/// For component `i`, with `(j, k)` the next two axes and `p = p̂ + p̃`,
/// `q = q̂ + q̃` (rounded difference and its exact tail):
///
/// ```text
/// p_j q_k − p_k q_j = (a + a') − (b + b') + [p̂_j q̃_k + p̃_j q̂_k − p̂_k q̃_j − p̃_k q̂_j]
///                     + [p̃_j q̃_k − p̃_k q̃_j]
/// (a, a') = two_prod(p̂_j, q̂_k),  (b, b') = two_prod(p̂_k, q̂_j),  (s, s') = two_diff(a, b)
/// ```
///
/// so `c_i = s + T + R` with `T = s' + a' − b' + X1 + X2 − X3 − X4` (the `X`s
/// the four products in brackets) and `R` the second-order bracket. `t = fl(T)`
/// sums 7 terms (4 of them rounded products) by 6 roundings:
/// `|t − T| ≤ γ6 A + u(1 + γ6) Σ|X| ≤ 7.01 u A`, `A = Σ |computed terms|`.
/// `|p̃| ≤ u |p̂|` gives `|p̃_j q̃_k| ≤ u |p̂_j q̃_k| ≤ 1.01 u |x1|`, and likewise
/// for the other: `|R| ≤ 1.01 u A`. So `|c_i − (s + t)| ≤ 8.02 u A`, and the
/// computed `Â ≥ (1 − 6u) A`: `err_i = 9u Â` (rounded, times
/// [`BOUND_ROUNDING`]) covers it. All tails zero (exact differences and
/// products) give `err_i = 0` and `c_i = s` exactly.
#[inline(always)]
pub(crate) fn cross(p: &Diff3, q: &Diff3) -> Cross {
    let (c0, c1, c2) = (cross_parts(p, q, 0), cross_parts(p, q, 1), cross_parts(p, q, 2));
    Cross { s: [split_of(c0.0), split_of(c1.0), split_of(c2.0)], t: [c0.1, c1.1, c2.1], err: [c0.2, c1.2, c2.2] }
}

/// Component `i` of [`cross`] as `(s_i, t_i, err_i)`.
#[inline(always)]
fn cross_parts(p: &Diff3, q: &Diff3, i: usize) -> (f64, f64, f64) {
    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
    let (a, ae) = two_prod(p.hi[j], q.hi[k]);
    let (b, be) = two_prod(p.hi[k], q.hi[j]);
    let (s, se) = two_diff(a, b);
    let x1 = p.hi[j].x * q.lo[k];
    let x2 = p.lo[j] * q.hi[k].x;
    let x3 = p.hi[k].x * q.lo[j];
    let x4 = p.lo[k] * q.hi[j].x;
    let t = ((se + ae) - be) + ((x1 + x2) - (x3 + x4));
    let tails = ((se.abs() + ae.abs()) + be.abs()) + ((x1.abs() + x2.abs()) + (x3.abs() + x4.abs()));
    (s, t, CROSS_TAIL * tails * BOUND_ROUNDING)
}

/// Component `i` of `p × q` alone, as a value with its bound (see
/// [`Cross::components`]): a 2D orientation of the projection that drops
/// axis `i`.
#[inline(always)]
pub(crate) fn cross_component(p: &Diff3, q: &Diff3, i: usize) -> Filtered {
    let (s, t, err) = cross_parts(p, q, i);
    component(s, t, err)
}

/// `s + t` with error bound `err` as a value with its bound: `fl(s + t)` adds
/// `u |v|`; `err = 0` (every operation exact, `t = 0`) gives an exact value.
#[inline(always)]
fn component(s: f64, t: f64, err: f64) -> Filtered {
    let value = s + t;
    let bound = if err == 0.0 { 0.0 } else { (err + U * value.abs()) * BOUND_ROUNDING };
    Filtered { value, bound }
}

/// The triple product `c · w` of a compensated cross product and an exact
/// difference, with its bound (`0` when every operation was exact; then
/// `value` is the exact volume).
///
/// With `c_k = s_k + t_k + ε_k` (`|ε_k| ≤ err_k`, [`cross`]) and
/// `w = ŵ + w̃`:
///
/// ```text
/// c · w = Σ s_k ŵ_k + Σ (s_k w̃_k + t_k ŵ_k) + Σ (t_k w̃_k + ε_k w_k)
/// (P_k, F_k) = two_prod(s_k, ŵ_k),  (H1, σ1) = two_sum(P0, P1),  (H, σ2) = two_sum(H1, P2)
/// c · w = H + [σ1 + σ2 + Σ (F_k + s_k w̃_k + t_k ŵ_k)] + Σ (t_k w̃_k + ε_k w_k)
/// ```
///
/// `L = fl(bracket)` sums 11 terms (6 rounded products) by 10 roundings:
/// within `γ10 B + u(1 + γ10) Σ|products| ≤ 11.01 u B`, `B = Σ |computed
/// terms|`. `|t_k w̃_k| ≤ u |t_k ŵ_k| ≤ 1.01 u |z_k|` adds `1.01 u B` at most,
/// and `|ε_k w_k| ≤ (1 + u) err_k |ŵ_k|`. The value `v = fl(H + L)` adds
/// `u |v|`. With `B̂ ≥ (1 − 10u) B`:
/// `bound = (13u B̂ + (1 + u) Σ err_k |ŵ_k| + u |v|) · BOUND_ROUNDING`, and
/// `bound = 0` when the tail part is `0`: then every term above vanished
/// (no product underflows in the domain), `L = 0` and `v = H` is exact.
#[inline(always)]
pub(crate) fn dot(c: &Cross, w: &Diff3) -> Filtered {
    let (p0, f0) = two_prod(c.s[0], w.hi[0]);
    let (p1, f1) = two_prod(c.s[1], w.hi[1]);
    let (p2, f2) = two_prod(c.s[2], w.hi[2]);
    let (h1, sigma1) = two_sum(p0, p1);
    let (h, sigma2) = two_sum(h1, p2);
    let y = [0, 1, 2].map(|k| c.s[k].x * w.lo[k]);
    let z = [0, 1, 2].map(|k| c.t[k] * w.hi[k].x);
    let l = ((sigma1 + sigma2) + ((f0 + f1) + f2)) + ((y[0] + y[1]) + y[2]) + ((z[0] + z[1]) + z[2]);
    let b = ((sigma1.abs() + sigma2.abs()) + ((f0.abs() + f1.abs()) + f2.abs()))
        + ((y[0].abs() + y[1].abs()) + y[2].abs())
        + ((z[0].abs() + z[1].abs()) + z[2].abs());
    let e = (c.err[0] * w.hi[0].x.abs() + c.err[1] * w.hi[1].x.abs()) + c.err[2] * w.hi[2].x.abs();
    let tail = DOT_TAIL * b + (1.0 + U) * e;
    let value = h + l;
    let bound = if tail == 0.0 { 0.0 } else { (tail + U * value.abs()) * BOUND_ROUNDING };
    Filtered { value, bound }
}

/// A plane normal split once for [`plane`] (shared by a segment's two ends).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Normal([Split; 3]);

/// `n` split for [`plane`].
#[inline(always)]
pub(crate) fn normal(n: P3) -> Normal {
    Normal(n.map(split_of))
}

/// `n · p − d` of exact inputs, compensated, with its bound (`0` when every
/// operation was exact; then `value` is exact).
///
/// ```text
/// (P_k, F_k) = two_prod(n_k, p_k),  (H1, σ1) = two_sum(P0, P1),
/// (H2, σ2) = two_sum(H1, P2),       (H, σ3) = two_diff(H2, d)
/// n · p − d = H + σ1 + σ2 + σ3 + F0 + F1 + F2      (exactly)
/// ```
///
/// `L = fl(σ1 + σ2 + σ3 + F0 + F1 + F2)` errs by at most `γ5 B ≤ 5.01 u B`,
/// `B = Σ |terms|`, and `v = fl(H + L)` by `u |v|`: with `B̂ ≥ (1 − 5u) B`,
/// `bound = (6u B̂ + u |v|) · BOUND_ROUNDING`, or `0` when `B̂ = 0` (then
/// `v = H` exactly).
#[inline(always)]
pub(crate) fn plane(n: &Normal, d: f64, p: P3) -> Filtered {
    let (p0, f0) = two_prod(n.0[0], split_of(p[0]));
    let (p1, f1) = two_prod(n.0[1], split_of(p[1]));
    let (p2, f2) = two_prod(n.0[2], split_of(p[2]));
    let (h1, sigma1) = two_sum(p0, p1);
    let (h2, sigma2) = two_sum(h1, p2);
    let (h, sigma3) = two_diff(h2, d);
    let l = ((sigma1 + sigma2) + sigma3) + ((f0 + f1) + f2);
    let b = ((sigma1.abs() + sigma2.abs()) + sigma3.abs()) + ((f0.abs() + f1.abs()) + f2.abs());
    let value = h + l;
    let bound = if b == 0.0 { 0.0 } else { (PLANE_TAIL * b + U * value.abs()) * BOUND_ROUNDING };
    Filtered { value, bound }
}

/// `n · (p1 − p0)` of an exact `n` and an exact difference, compensated, with
/// its bound (`0` when every operation was exact; then `value` is exact).
///
/// ```text
/// (P_k, F_k) = two_prod(n_k, r̂_k),  (H1, σ1) = two_sum(P0, P1),  (H, σ2) = two_sum(H1, P2)
/// n · r = H + σ1 + σ2 + Σ F_k + Σ n_k r̃_k      (exactly)
/// ```
///
/// `L = fl(σ1 + σ2 + Σ F_k + Σ fl(n_k r̃_k))` sums 8 terms (3 rounded
/// products) by 7 roundings: within `γ7 B + u(1 + γ7) B ≤ 8.01 u B`,
/// `B = Σ |computed terms|`; `v = fl(H + L)` adds `u |v|`. With
/// `B̂ ≥ (1 − 7u) B`: `bound = (9u B̂ + u |v|) · BOUND_ROUNDING`, or `0` when
/// `B̂ = 0` (then `v = H` exactly).
#[inline(always)]
pub(crate) fn dot_diff(n: &Normal, r: &Diff3) -> Filtered {
    let (p0, f0) = two_prod(n.0[0], r.hi[0]);
    let (p1, f1) = two_prod(n.0[1], r.hi[1]);
    let (p2, f2) = two_prod(n.0[2], r.hi[2]);
    let (h1, sigma1) = two_sum(p0, p1);
    let (h, sigma2) = two_sum(h1, p2);
    let y = [0, 1, 2].map(|k| n.0[k].x * r.lo[k]);
    let l = ((sigma1 + sigma2) + ((f0 + f1) + f2)) + ((y[0] + y[1]) + y[2]);
    let b =
        ((sigma1.abs() + sigma2.abs()) + ((f0.abs() + f1.abs()) + f2.abs())) + ((y[0].abs() + y[1].abs()) + y[2].abs());
    let value = h + l;
    let bound = if b == 0.0 { 0.0 } else { (DOT_DIFF_TAIL * b + U * value.abs()) * BOUND_ROUNDING };
    Filtered { value, bound }
}

/// Smallest non-zero input magnitude of [`dot_cross`] (2^−200): a product of
/// two cross products is of degree 4, and the module's domain argument (every
/// value an integer multiple of the inputs' last bit to the degree) then
/// needs inputs of at least `2^−200`: every input is a multiple of `2^−252`,
/// every product of four a multiple of `2^−1008`, which is represented
/// exactly or rounded in the normal range (a multiple of `2^−1008` with more
/// than 53 significant bits is at least `2^−955`). Nothing overflows:
/// cross products are at most `2^129`, their products `2^260`.
pub(crate) const MIN_INPUT_DEGREE_4: f64 = 6.223015277861142e-61;

/// Whether every coordinate of the points is `0` or of magnitude in
/// `[2^−200, 2^63]`: the domain of [`dot_cross`] ([`MIN_INPUT_DEGREE_4`]).
#[inline(always)]
pub(crate) fn in_range_degree_4_points<const N: usize>(ps: [P3; N]) -> bool {
    let ok = |x: f64| {
        let a = x.abs();
        (a <= FAST_MAX) & ((a >= MIN_INPUT_DEGREE_4) | (a == 0.0))
    };
    ps.iter().fold(true, |acc, p| acc & ok(p[0]) & ok(p[1]) & ok(p[2]))
}

/// Factor of the tail sum of a product of two cross products (see
/// [`dot_cross`]): `16u`.
const DOT_CROSS_TAIL: f64 = 16.0 * U;

/// The dot product `c · d` of two compensated cross products, with its bound
/// (`0` when every operation was exact; then `value` is the exact value), on
/// inputs in the domain of [`in_range_degree_4_points`].
///
/// With `c_k = s_k + t_k + ε_k` (`|ε_k| ≤ e_k`) and `d_k = s'_k + t'_k + ε'_k`
/// (`|ε'_k| ≤ e'_k`, [`cross`]), and `c̃_k = s_k + t_k`, `d̃_k = s'_k + t'_k`:
///
/// ```text
/// c · d = Σ s_k s'_k + Σ (s_k t'_k + t_k s'_k + t_k t'_k) + Σ (ε_k d_k + c̃_k ε'_k)
/// (P_k, F_k) = two_prod(s_k, s'_k),  (H1, σ1) = two_sum(P0, P1),  (H, σ2) = two_sum(H1, P2)
/// c · d = H + [σ1 + σ2 + Σ (F_k + s_k t'_k + t_k s'_k + t_k t'_k)] + Σ (ε_k d_k + c̃_k ε'_k)
/// ```
///
/// `L = fl(bracket)` sums 14 terms (9 rounded products) by 13 roundings:
/// within `γ13 B + u(1 + γ13) Σ|products| ≤ 14.01 u B`, `B = Σ |computed
/// terms|` (no tail product is dropped: a cross product's tail `t` is not
/// small against its head `s`, which may cancel). The ε terms are at most
/// `E = Σ (e_k (|s'_k| + |t'_k| + e'_k) + e'_k (|s_k| + |t_k|))`, computed by
/// fewer than 12 roundings of non-negative terms. The value `v = fl(H + L)`
/// adds `u |v|`. With `B̂ ≥ (1 − 13u) B`:
/// `bound = (16u B̂ + (1 + 16u) Ê + u |v|) · BOUND_ROUNDING`, and `bound = 0`
/// when `B̂` and `Ê` are `0`: then every tail vanished (no product underflows
/// in the domain), `L = 0` and `v = H` is exact.
#[inline]
pub(crate) fn dot_cross(c: &Cross, d: &Cross) -> Filtered {
    let (p0, f0) = two_prod(c.s[0], d.s[0]);
    let (p1, f1) = two_prod(c.s[1], d.s[1]);
    let (p2, f2) = two_prod(c.s[2], d.s[2]);
    let (h1, sigma1) = two_sum(p0, p1);
    let (h, sigma2) = two_sum(h1, p2);
    let y = [0, 1, 2].map(|k| c.s[k].x * d.t[k]);
    let z = [0, 1, 2].map(|k| c.t[k] * d.s[k].x);
    let q = [0, 1, 2].map(|k| c.t[k] * d.t[k]);
    let l = ((sigma1 + sigma2) + ((f0 + f1) + f2))
        + ((y[0] + y[1]) + y[2])
        + ((z[0] + z[1]) + z[2])
        + ((q[0] + q[1]) + q[2]);
    let b = ((sigma1.abs() + sigma2.abs()) + ((f0.abs() + f1.abs()) + f2.abs()))
        + ((y[0].abs() + y[1].abs()) + y[2].abs())
        + ((z[0].abs() + z[1].abs()) + z[2].abs())
        + ((q[0].abs() + q[1].abs()) + q[2].abs());
    let e = [0, 1, 2]
        .map(|k| c.err[k] * ((d.s[k].x.abs() + d.t[k].abs()) + d.err[k]) + d.err[k] * (c.s[k].x.abs() + c.t[k].abs()))
        .iter()
        .fold(0.0, |acc, x| acc + x);
    let tail = DOT_CROSS_TAIL * b + (1.0 + DOT_CROSS_TAIL) * e;
    let value = h + l;
    let bound = if tail == 0.0 { 0.0 } else { (tail + U * value.abs()) * BOUND_ROUNDING };
    Filtered { value, bound }
}

/// Whether `x`'s sign is known: its bound is below its magnitude, or it is
/// exact (bound `0`, zero included).
#[inline(always)]
pub(crate) fn sign_known(x: &Filtered) -> bool {
    x.value.abs() > x.bound || x.bound == 0.0
}

/// Whether the exact values of `a` and `b` (each known to its bound) are
/// certainly different (`Some(true)`), certainly equal (`Some(false)`: both
/// exact and equal), or neither is certain (`None`).
///
/// Both exact: their values are the exact values. Otherwise
/// [`Filtered::differs_from`] decides "certainly different".
#[inline(always)]
pub(crate) fn differ(a: &Filtered, b: &Filtered) -> Option<bool> {
    if a.bound == 0.0 && b.bound == 0.0 {
        #[expect(clippy::float_cmp, reason = "both values are exact: equality is the question")]
        let equal = a.value == b.value;
        return Some(!equal);
    }
    if a.differs_from(b) { Some(true) } else { None }
}

#[cfg(test)]
mod tests {
    use super::super::{BigFloat, Sign};
    use super::*;
    use proptest::prelude::*;

    fn bf(x: f64) -> BigFloat {
        BigFloat::from_f64(x)
    }

    fn big_diff(a: P3, b: P3) -> [BigFloat; 3] {
        [0, 1, 2].map(|i| &bf(a[i]) - &bf(b[i]))
    }

    fn big_cross(p: &[BigFloat; 3], q: &[BigFloat; 3]) -> [BigFloat; 3] {
        [&(&p[1] * &q[2]) - &(&p[2] * &q[1]), &(&p[2] * &q[0]) - &(&p[0] * &q[2]), &(&p[0] * &q[1]) - &(&p[1] * &q[0])]
    }

    fn big_dot(a: &[BigFloat; 3], b: &[BigFloat; 3]) -> BigFloat {
        &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
    }

    /// Whether `|exact − value| ≤ bound`, decided exactly; with `bound = 0`,
    /// whether `value` is exact.
    fn within(exact: &BigFloat, f: &Filtered) -> bool {
        let err = exact - &bf(f.value);
        let lo = &err + &bf(f.bound);
        let hi = &bf(f.bound) - &err;
        lo.sign() != Sign::Negative && hi.sign() != Sign::Negative
    }

    /// Coordinates with heavy cancellation: grid values (exact differences,
    /// exact zeros), values far from the origin a few ulps apart, random
    /// binades down to the domain's floor, and near-coincident reals.
    fn coord() -> impl Strategy<Value = f64> {
        prop_oneof![
            (-64i32..64).prop_map(|k| f64::from(k) / 16.0),
            (-4i64..4).prop_map(|k| 1e15 + k as f64 * 0.125),
            (-1.0..1.0f64, -240i32..60).prop_map(|(m, e)| m * 2f64.powi(e)),
            (-1.0..1.0f64).prop_map(|x| 0.1 + x * 1e-15),
            Just(0.0),
        ]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// The product of two compensated cross products is within its
        /// bound of the exact value, and a zero bound means an exact value.
        #[test]
        fn dot_cross_bound_holds(a in point(), b in point(), c in point(), q in point()) {
            if !in_range_degree_4_points([a, b, c, q]) {
                // Outside the domain (a coordinate below 2^−200): not claimed.
                return Ok(());
            }
            let n = cross(&diff(b, a), &diff(c, a));
            let m = cross(&diff(b, q), &diff(c, q));
            let got = dot_cross(&n, &m);
            let exact = big_dot(
                &big_cross(&big_diff(b, a), &big_diff(c, a)),
                &big_cross(&big_diff(b, q), &big_diff(c, q)),
            );
            prop_assert!(within(&exact, &got), "{got:?}");
        }

        /// The compensated cross product, its components and the triple
        /// product are within their bounds of the exact values, and a zero
        /// bound means an exact value.
        #[test]
        fn cross_and_dot_bounds_hold(a in point(), b in point(), c in point(), q in point()) {
            prop_assume!(in_range([a, b, c, q].concat().try_into().unwrap_or([f64::NAN; 12])));
            let (p, r, w) = (diff(b, a), diff(c, a), diff(q, a));
            let x = cross(&p, &r);
            let exact_x = big_cross(&big_diff(b, a), &big_diff(c, a));
            let comps = x.components();
            for i in 0..3 {
                prop_assert!(within(&exact_x[i], &comps[i]), "cross component {i}: {:?}", comps[i]);
            }
            let f = dot(&x, &w);
            let exact = big_dot(&exact_x, &big_diff(q, a));
            prop_assert!(within(&exact, &f), "triple product {f:?}");
            if sign_known(&f) {
                prop_assert_eq!(Sign::of(f.value), exact.sign(), "sign of {:?}", f);
            }
        }

        /// `n · (p1 − p0)` is within its bound of the exact value.
        #[test]
        fn dot_diff_bound_holds(n in point(), p0 in point(), p1 in point()) {
            prop_assume!(in_range([n, p0, p1].concat().try_into().unwrap_or([f64::NAN; 9])));
            let f = dot_diff(&normal(n), &diff(p1, p0));
            let exact = big_dot(&n.map(bf), &big_diff(p1, p0));
            prop_assert!(within(&exact, &f), "n · (p1 − p0) {f:?}");
            if sign_known(&f) {
                prop_assert_eq!(Sign::of(f.value), exact.sign(), "sign of {:?}", f);
            }
        }

        /// `n · p − d` is within its bound of the exact value.
        #[test]
        fn plane_bound_holds(n in point(), p in point(), d in coord()) {
            prop_assume!(in_range([n[0], n[1], n[2], p[0], p[1], p[2], d]));
            let f = plane(&normal(n), d, p);
            let exact = &big_dot(&n.map(bf), &p.map(bf)) - &bf(d);
            prop_assert!(within(&exact, &f), "plane value {f:?}");
            if sign_known(&f) {
                prop_assert_eq!(Sign::of(f.value), exact.sign(), "sign of {:?}", f);
            }
        }
    }

    #[test]
    fn exact_zeros_are_certified() {
        // Grid points: q on the plane of a, b, c (q = a + (b − a) + (c − a)/2),
        // every operation exact: the volume is 0 with bound 0.
        let (a, b, c) = ([0.25, -1.0, 3.0], [2.0, 0.5, -1.0], [-1.5, 2.0, 0.75]);
        let q = [0, 1, 2].map(|i| b[i] + (c[i] - a[i]) / 2.0);
        let f = dot(&cross(&diff(b, a), &diff(c, a)), &diff(q, a));
        assert!(f.value == 0.0 && f.bound == 0.0, "{f:?}");
        // A point on the plane 3x + 4y = 10: (2, 1, 7).
        let g = plane(&normal([3.0, 4.0, 0.0]), 10.0, [2.0, 1.0, 7.0]);
        assert!(g.value == 0.0 && g.bound == 0.0, "{g:?}");
    }

    #[test]
    fn cancellation_far_from_the_origin_is_resolved() {
        // n · p − d with n · p ≈ 1e15 and the exact value 2^−3: stage A's
        // bound (about 1) cannot tell its sign; stage B's can.
        let n = [1.0, 1.0, 0.0];
        let p = [1e15 + 0.125, -0.25, 5.0];
        let f = plane(&normal(n), 1e15 - 0.25, p);
        assert!(sign_known(&f) && (f.value - 0.125).abs() <= f.bound, "{f:?}");
    }

    #[test]
    fn range_check() {
        assert!(in_range([0.0, 1.0, -9.2e18, 1e-75]));
        assert!(!in_range([1e-76]));
        assert!(!in_range([1e19]));
        assert!(!in_range([f64::NAN]));
        assert!(!in_range([f64::INFINITY]));
    }
}
