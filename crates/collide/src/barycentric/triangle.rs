//! Signed barycentric coordinates on a triangle, of the point's projection onto
//! the triangle's plane.

use super::area_ratios::signed_area_ratios;
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
/// flagged genuine triangles thinner than `16 ε`. So the coordinates are the
/// ratios of exactly known values, and zero area is decided exactly.
///
/// **Method** (details in the private `area_ratios` module):
///
/// 1. *Filter.* The `f64` evaluation of the formula above, in a frame where the
///    edges and the offsets `p − v_i` are each scaled by an exact power of two
///    (no overflow or underflow), with a forward error bound on every numerator
///    and the denominator (Shewchuk's orient2d bound for each cross-product
///    component, first-order propagation through the dot products). When the
///    bounds of the two kept coordinates sum to at most `FILTER_TOL` (12 ε) of
///    the coordinates' size, the floating-point answer stands: about half of
///    random well-shaped cases (the bound is pessimistic), at about the cost of
///    the plain formula.
/// 2. *Exact.* Otherwise `‖n‖²` and two numerators are evaluated exactly (the
///    third is `‖n‖²` minus them), each rounded to an
///    [`Estimate`](crate::exact::Estimate), and the coordinates are their
///    quotients. The inputs are integers on a common binary grid; when their
///    significant bits span at most 61 binades (any scene of sensible
///    proportions) the evaluation runs on `i128` and 256-bit integers without
///    allocation, at about 1.6 times the filter's cost; up to 124 binades on
///    512-bit integers; beyond that in [`BigFloat`](crate::exact::BigFloat)
///    (microseconds). Slivers and degenerate triangles always take this path.
///
/// **Accuracy.** For every finite input whose triangle does not have exactly zero
/// area, each returned `f64` coordinate is within `16 ε · max(1, max_i |coord_i|)`
/// of the exact coordinate of the projection, whatever the triangle's shape:
/// `FILTER_TOL + 3.5 ε` on the fast path; on the exact path each kept quotient
/// is within `2.5 ε` of itself and the recomputed one within the sum of their
/// errors plus two roundings, `6.5 ε`. (Typical errors are an ulp or two.) The
/// sum `α + β + γ` is 1 to within `1.5 ε · max(1, max_i |coord_i|)`.
///
/// **Precision.** The computation runs on the inputs' `f64` values (exact for
/// `f32`); the `f32` answer rounds the two kept `f64` coordinates to `f32`
/// (half an ulp each) and recomputes the third in `f32` as `1 −` them (their
/// errors plus two roundings), so every `f32` coordinate is within
/// `2.5 ε_f32` of the size of the exact answer *for the `f32` inputs*, and the
/// sum is 1 as in `f64`.
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
pub fn barycentric_triangle<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Barycentric<T, 3> {
    let fallback = || Barycentric { coords: longest_edge_fallback(p, &tri.vertices), degenerate: true };
    if !(finite3(p) && tri.vertices.iter().all(finite3)) {
        return fallback();
    }
    let Some(r) = signed_area_ratios(p, tri) else {
        return fallback();
    };
    // The free coordinate is 1 minus the other two (`1 − c_i − c_j` with
    // `i, j = k + 1, k + 2`), chosen by selects rather than written through
    // an index: an indexed store makes the array a memory object, reread in
    // wider loads than it was written with, which stalls.
    let c = r.coords.map(T::of);
    let k = r.free;
    let one_minus = [T::one() - c[1] - c[2], T::one() - c[2] - c[0], T::one() - c[0] - c[1]];
    let coords = [0, 1, 2].map(|m| if m == k { one_minus[m] } else { c[m] });
    if !coords.iter().all(|x| x.finite()) {
        return fallback();
    }
    Barycentric { coords, degenerate: false }
}
