//! Signed barycentric coordinates on a triangle, of the point's projection onto
//! the triangle's plane.

use super::area_ratios::{ACCURACY, Fast, TIGHT_ACCURACY, fast_ratios, slow_ratios};
use super::coords::Barycentric;
use super::local::longest_edge_fallback;
use crate::real::{Real, Vec3, finite3};
use crate::shapes::Triangle;

/// Signed barycentric coordinates `[α, β, γ]` of the orthogonal projection `p'` of
/// `p` onto the plane of `tri = (v0, v1, v2)`: `p' = α v0 + β v1 + γ v2`,
/// `α + β + γ = 1`, negative outside the triangle. This is the answer the fixture
/// query `barycentric` expects.
///
/// Formula, with `n = (v1 − v0) × (v2 − v0)` (twice the signed area times the unit
/// normal):
///
/// ```text
/// α = n·((v2 − v1) × (p − v1)) / ‖n‖²
/// β = n·((v0 − v2) × (p − v2)) / ‖n‖²
/// γ = n·((v1 − v0) × (p − v0)) / ‖n‖²
/// ```
///
/// then the coordinate of largest magnitude is replaced by 1 minus the other two.
///
/// Derivation (Cramer's rule on the normal-projected areas): write
/// `p = v0 + β e0 + γ e1 + h n̂` with `e0 = v1 − v0`, `e1 = v2 − v0`, `h` the height
/// above the plane. Crossing with `e0` from the left removes the `β` term:
/// `e0 × (p − v0) = γ (e0 × e1) + h (e0 × n̂)`, and dotting with `n` removes the
/// height term (`e0 × n̂ ⊥ n`), so `γ = n·(e0 × (p − v0)) / n·n`. Each numerator
/// is `‖n‖` times twice the signed area of the sub-triangle opposite the vertex
/// (positive when it turns the same way as the triangle): the lecture's
/// `α = t1/S` with signs, of the projected point. The same steps from `v1` and
/// `v2` give `α` and `β`; the three numerators sum to `n·n` identically. Source:
/// the lecture's area ratios; signed form as in Ericson, *Real-Time Collision
/// Detection*, §3.4 (there with a 2-D projection and the normal equations
/// `d00 d11 − d01²`, equal to `‖n‖²` by Lagrange's identity).
///
/// **Why exact arithmetic.** Numerators and denominator are polynomials of degree
/// 4 in the input coordinates. Evaluated in floating point, `n` carries an
/// absolute error of a few `ε L²` (`L` the longest edge) in its length *and its
/// direction*; on a sliver of width `w` that tilts the computed plane by about
/// `ε L / w`, and the height `h` of `p` above the plane turns the tilt into an
/// in-plane error of `ε L h / w`, i.e. a coordinate error of `ε L h / w²` —
/// quadratic in the aspect ratio, far beyond the conditioning of the problem
/// (crashtest's sliver family met `[0.069, 1.145, −0.215]` for the exact
/// `[0.0228, 1.0907, −0.1135]`, and `O(1)` answers where the exact coordinates
/// are `~1e6`). Deciding "zero area" by a threshold on the computed `‖n‖` also
/// flagged genuine triangles thinner than `16 ε`. So the floating-point
/// answer is used only where a certified error bound shows it within the
/// promised accuracy, the coordinates are otherwise the ratios of exactly
/// known values, and zero area is decided exactly.
///
/// **Method** (details in the private `area_ratios` module):
///
/// 1. *Fast filter.* The formula above from `v0` in plain `f64`, in its Gram
///    form (Binet–Cauchy: `‖n‖² = A B − C²`, `β ‖n‖² = B P − C R`,
///    `γ ‖n‖² = A R − C P` with `A = e0·e0`, `B = e1·e1`, `C = e0·e1`,
///    `P = q·e0`, `R = q·e1`, `q = p − v0`; `α = 1 − β − γ`), with an error
///    bound from the squared lengths `A`, `B`, `‖q‖²` alone
///    (`26 u ‖q‖ ‖e0‖ ‖e1‖ max(‖e0‖, ‖e1‖)` on a numerator, `26 u A B` on
///    `‖n‖²`, `u = ε/2`; a dozen flops and one square root). When the
///    lengths are within `2^±100` and the bound meets the accuracy below, the
///    answer stands: the bound is about
///    `26 u (‖q‖ (1/‖e0‖ + 1/‖e1‖) + |β| + |γ|) / sin²θ0` (`θ0` the angle at
///    `v0`), so every triangle of ordinary proportions is answered here, at
///    about the cost of the plain formula.
/// 2. *Scaled filter.* For lengths out of that range, or a bound within a
///    factor 64 of the target, the same formula in a frame scaled by
///    exact powers of two (no overflow or underflow at any scale), with a
///    forward error bound on every component (Shewchuk's orient2d bound for
///    each cross-product component, first-order propagation through the dot
///    products), at several times the cost.
/// 3. *Exact.* Otherwise `n` and the numerators of `β` and `γ` are evaluated
///    exactly, each rounded to an [`Estimate`](crate::exact::Estimate)
///    (`‖n‖²`, without cancellation, summed in `f64` from the exact `n`), and
///    the coordinates are their quotients (`α = 1 − β − γ`). The inputs are integers on a common binary grid; when their
///    significant bits span at most 61 binades (any scene of sensible
///    proportions) the evaluation runs on `i128` and 256-bit integers without
///    allocation; up to 124 binades on 512-bit integers; beyond that in
///    [`BigFloat`](crate::exact::BigFloat) (microseconds). Slivers (the fast
///    bound, about `80 u / sin²θ0`, beyond `2^−40` times 64: an angle at `v0`
///    below about 0.7° or above 179.3°), near-degenerate and
///    zero-area triangles go straight to this path.
///
/// **Accuracy.** For every finite input whose triangle does not have exactly zero
/// area, each returned `f64` coordinate is within `2^−40 · max(1, max_i |coord_i|)`
/// (about `9.1e-13` of the size, the private constant `ACCURACY`) of the exact
/// coordinate of the projection, whatever the triangle's shape: each filter
/// answers only when its certified bounds on the two kept coordinates sum to
/// at most `2^−40 − 4 ε` of the size, and the final roundings add at most
/// `3.5 ε`; the exact path is within `10.5 ε`. (Typical errors are a few
/// ulps of the size; [`barycentric_triangle_tight`] promises `16 ε`.) The sum
/// `α + β + γ` is 1 to within `1.5 ε · max(1, max_i |coord_i|)`.
///
/// **Precision.** The computation runs on the inputs' `f64` values (exact for
/// `f32`); the `f32` answer rounds the two kept `f64` coordinates to `f32`
/// (half an ulp each) and recomputes the third in `f32` as `1 −` them (their
/// errors plus two roundings), so every `f32` coordinate is within
/// `2.5 ε_f32` (plus the `f64` answer's `2^−40`, below `1e-5 ε_f32`) of the
/// size of the exact answer *for the `f32` inputs*, and the sum is 1 as in
/// `f64`.
///
/// **Cost.** Well-shaped queries: the plain formula (about 45 flops, one
/// division, one square root) and its bound, inline. Slivers and zero-area
/// triangles: the exact path out of line, on 64- to 256-bit integers, about
/// five to ten times that; a zero-area triangle then pays for the fallback.
///
/// Degenerate input: a triangle of exactly zero area (collinear or coincident
/// vertices, `n = 0` exactly, the decision of
/// [`exact::collinear`](crate::exact::collinear)) has no plane. `degenerate` is
/// set and the fallback is the closest point to `p` on the longest edge, as
/// coordinates `1 − t`, `t` on that edge's endpoints and 0 on the third vertex
/// (`[1, 0, 0]` when all vertices coincide): non-negative, summing to 1, and
/// reconstructing that closest point. Any triangle of non-zero area, however
/// thin, is answered. Coordinates beyond the type's range (`p` more than about
/// the largest finite value times the triangle's width away) and non-finite input
/// get the same fallback and flag. Never NaN, never a panic.
///
/// **Deviation from the book**: Ericson evaluates the ratios in floating point
/// and calls the triangle degenerate when the computed denominator is (near)
/// zero; here the numerators and denominator are exact (or certified to the
/// target), and zero area is decided exactly — a triangle is degenerate only
/// when its area is exactly zero, as crashtest's referee decides it.
/// [`barycentric_triangle_lecture`](super::barycentric_triangle_lecture) keeps
/// the floating-point threshold `‖n‖ ≤ 16 ε L²`.
#[inline]
pub fn barycentric_triangle<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Barycentric<T, 3> {
    coordinates(p, tri, ACCURACY)
}

/// [`barycentric_triangle`] with the tighter accuracy `16 ε`: each returned
/// `f64` coordinate within `16 ε · max(1, max_i |coord_i|)` of the exact
/// coordinate of the projection (the private constant `TIGHT_ACCURACY`),
/// whatever the triangle's shape, for callers that certify the coordinates'
/// signs with a margin of a few ulps. Same formula, method, degenerate
/// behaviour, fallback and `f32` rounding (`2.5 ε_f32`); the filters must
/// meet `12 ε` instead of `2^−40 − 4 ε`, so their bounds (pessimistic by
/// about an order of magnitude) send about half of well-shaped random
/// queries to the exact path, at about twice the cost on average.
#[inline]
pub fn barycentric_triangle_tight<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Barycentric<T, 3> {
    coordinates(p, tri, TIGHT_ACCURACY)
}

/// The body of [`barycentric_triangle`] and [`barycentric_triangle_tight`],
/// for a promised `accuracy` relative to the size: the fast filter's answer
/// inline, every other case out of line ([`slow`]).
#[inline(always)]
fn coordinates<T: Real>(p: &Vec3<T>, tri: &Triangle<T>, accuracy: f64) -> Barycentric<T, 3> {
    match fast_ratios(p, tri, accuracy) {
        Fast::Answer(beta, gamma) => {
            let (beta, gamma) = (T::of(beta), T::of(gamma));
            let alpha = T::one() - beta - gamma;
            // Non-finite only when a coordinate overflows `T` (`f32`): then
            // the slow path decides it again, and falls back.
            if alpha.finite() {
                return Barycentric { coords: [alpha, beta, gamma], degenerate: false };
            }
            slow(p, tri, accuracy, true)
        }
        miss => slow(p, tri, accuracy, matches!(miss, Fast::Filter)),
    }
}

/// Every query the fast filter does not answer: non-finite input, the scaled
/// filter and the exact path, zero area and coordinates beyond `T`'s range
/// (the fallback). `scaled_filter`: whether the scaled filter runs before
/// the exact path (the fast filter's miss was [`Fast::Filter`]).
#[inline(never)]
fn slow<T: Real>(p: &Vec3<T>, tri: &Triangle<T>, accuracy: f64, scaled_filter: bool) -> Barycentric<T, 3> {
    let fallback = || Barycentric { coords: longest_edge_fallback(p, &tri.vertices), degenerate: true };
    if !(finite3(p) && tri.vertices.iter().all(finite3)) {
        return fallback();
    }
    let Some(r) = slow_ratios(p, tri, accuracy, scaled_filter) else {
        return fallback();
    };
    // The free coordinate is 1 minus the other two (`1 − c_i − c_j` with
    // `i, j = k + 1, k + 2`).
    let c = r.coords.map(T::of);
    let k = r.free;
    let one_minus = [T::one() - c[1] - c[2], T::one() - c[2] - c[0], T::one() - c[0] - c[1]];
    let coords = [0, 1, 2].map(|m| if m == k { one_minus[m] } else { c[m] });
    if !coords.iter().all(|x| x.finite()) {
        return fallback();
    }
    Barycentric { coords, degenerate: false }
}
