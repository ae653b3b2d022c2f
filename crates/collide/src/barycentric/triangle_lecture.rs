//! The lecture's barycentric coordinates on a triangle: ratios of unsigned areas.

use super::coords::Barycentric;
use super::local::{is_flat_triangle, longest_edge_fallback, scaled_differences};
use crate::real::{Real, Vec3, stable_norm};
use crate::shapes::Triangle;

/// The lecture's barycentric coordinates of `p` in `tri = (v0, v1, v2)`: each
/// vertex's coordinate is the area of the sub-triangle opposite it (with `p` in
/// the vertex's place) over the triangle's area `S`,
///
/// ```text
/// α = t1 / S = area(p, v1, v2) / S
/// β = t2 / S = area(v0, p, v2) / S
/// γ = t3 / S = area(v0, v1, p) / S
/// area(x, y, z) = ½ ‖(y − x) × (z − x)‖,   S = area(v0, v1, v2)
/// ```
///
/// computed as `‖(v1 − p) × (v2 − p)‖ / ‖(v1 − v0) × (v2 − v0)‖` and likewise (the
/// ½ cancels). Derivation: for `p = α v0 + β v1 + γ v2` inside the triangle, the
/// sub-triangle `(p, v1, v2)` has the base `v1 v2` and `α` times the height of
/// `v0` above it, so its area is `α S`; likewise for `β`, `γ`.
///
/// Returned exactly as the lecture defines them, raw: the areas are unsigned,
/// so the coordinates are never negative and sum to 1 only for `p` inside the
/// triangle (or on its boundary) and in its plane. Outside they sum to more than
/// 1 (`p = v1 + v2 − v0`, the fourth corner of the parallelogram, gives
/// `[1, 1, 1]` where the signed coordinates are `[−1, 1, 1]`), and off the plane
/// each area includes the height, so the ratios describe no point of the plane.
/// They are not normalized: that is the method's limitation, shown as it is.
/// [`barycentric_triangle`](super::barycentric_triangle) is the signed, projected
/// counterpart.
///
/// Numerics: the differences are formed in one frame scaled by an exact power of
/// two (halved first if one overflows) and the norms use [`stable_norm`], so no
/// intermediate overflows or underflows.
///
/// Degenerate input: a zero-area triangle, by a scale-relative flatness test
/// on the computed normal (`‖n‖ ≤ 16 ε L²`, `L` the longest edge: below it the
/// computed area is rounding noise and the division by `S` meaningless; the
/// signed [`barycentric_triangle`](super::barycentric_triangle) decides zero
/// area exactly instead), sets `degenerate` with the fallback of the signed
/// coordinates: the closest point to `p` on the longest edge as coordinates
/// (`[1, 0, 0]` when the vertices coincide), non-negative and summing to 1.
/// When an area overflows the type (the cross product of two offsets from `p`
/// squares their length: `p` more than about `√(largest finite)` triangle sizes
/// away, 1e19 in `f32`, 1e154 in `f64`), the answer gets the same fallback and
/// flag. Never NaN for finite input.
pub fn barycentric_triangle_lecture<T: Real>(p: &Vec3<T>, tri: &Triangle<T>) -> Barycentric<T, 3> {
    let [v0, v1, v2] = &tri.vertices;
    let fallback = || Barycentric { coords: longest_edge_fallback(p, &tri.vertices), degenerate: true };
    let Some([e0, e1, w0, w1, w2]) = scaled_differences([(v1, v0), (v2, v0), (v0, p), (v1, p), (v2, p)], 2) else {
        return fallback();
    };
    let n = e0.cross(&e1);
    if is_flat_triangle(&e0, &e1, &n) {
        return fallback();
    }
    let s = stable_norm(&n);
    let coords = [stable_norm(&w1.cross(&w2)) / s, stable_norm(&w2.cross(&w0)) / s, stable_norm(&w0.cross(&w1)) / s];
    if !coords.iter().all(|x| x.finite()) {
        return fallback();
    }
    Barycentric { coords, degenerate: false }
}
