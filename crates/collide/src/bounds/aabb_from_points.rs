//! The lecture's AABB: expansion over the vertices.

use crate::real::{Real, Vec3};
use crate::shapes::Aabb;

/// The smallest axis-aligned box containing every point, by the lecture's
/// expansion: start with the box `[p0, p0]` of the first point, then for each
/// further point and each axis, lower `min` to the point's coordinate if it is
/// below, raise `max` if it is above.
///
/// ```text
/// min_i = min over points of p_i,   max_i = max over points of p_i   (i = x, y, z)
/// ```
///
/// Derivation: a box is the product of three intervals, so it contains every
/// point exactly when each interval contains every point's coordinate on its
/// axis; the smallest such interval runs from the least to the greatest
/// coordinate. One pass, `O(n)`.
///
/// The result is exact: every face is one of the input coordinates, unrounded,
/// so every point is inside (`min ≤ p ≤ max` per axis, with equality on each face
/// for at least one point). Ericson, *Real-Time Collision Detection*, §4.2.
///
/// Degenerate input: no points gives `None` (there is no empty box to return);
/// a single point, or points sharing a coordinate, give a box of zero extent on
/// those axes, which is a valid answer. Coordinates must not be NaN (crashtest's
/// fixture reader refuses them): a NaN in the first point would propagate, a
/// later one is ignored.
pub fn aabb_from_points<T: Real>(points: &[Vec3<T>]) -> Option<Aabb<T>> {
    let (first, rest) = points.split_first()?;
    let mut bb = Aabb::new(*first, *first);
    for p in rest {
        for i in 0..3 {
            if p[i] < bb.min[i] {
                bb.min[i] = p[i];
            }
            if p[i] > bb.max[i] {
                bb.max[i] = p[i];
            }
        }
    }
    Some(bb)
}
