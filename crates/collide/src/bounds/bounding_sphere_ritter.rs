//! Ritter's bounding sphere: a far pair, then one growth pass.

use super::bounding_sphere::BoundingSphere;
use super::sphere_frame::{enclose, local_cloud};
use crate::real::{Real, Vec3, c};

/// Ritter's bounding sphere (J. Ritter, "An Efficient Bounding Sphere",
/// *Graphics Gems*, 1990): an initial sphere on a far-apart pair of points, then
/// one pass that grows it just enough to take in each point left outside.
///
/// 1. Far pair (farthest-point heuristic): from the first point `x`, find the
///    point `y` farthest from it, then the point `z` farthest from `y`. Initial
///    sphere: `center = (y + z)/2`, `r = ‖z − y‖/2`.
/// 2. Growth pass: for each point `p` with `d = ‖p − center‖ > r`, replace the
///    sphere by the smallest one containing both it and `p`:
///
///    ```text
///    r' = (r + d)/2,   center' = center + ((d − r)/2) (p − center)/d
///    ```
///
///    Derivation: the new sphere's diameter runs from `p` through the old centre
///    to the far side of the old sphere, length `d + r`; its centre sits `r'` back
///    from `p` along that line, i.e. `(d − r)/2` forward from the old centre. It
///    contains the old sphere (internally tangent), so points already inside stay
///    inside and one pass suffices.
///
/// Deviation from the Gem: Ritter seeds with the most separated pair among the
/// six axis-extreme points (min and max `x`, `y`, `z`); this uses the
/// farthest-point pair above, which is never less separated than half the
/// diameter and costs two passes instead of one. Both are heuristics. Measured
/// against [`bounding_sphere_minimal`](fn@super::bounding_sphere_minimal) on
/// 200-point random clouds (300 each): 3.6% larger on average in a cube (at most
/// 12%), 6.2% in a ball (at most 16%), within 1% for an elongated ellipsoid or a
/// cluster with one outlier.
///
/// Numerics: computed in a local frame (offsets from the first point, scaled by
/// an exact power of two), so nothing overflows. The reported radius is the
/// largest computed distance from the final centre (clamped into the points'
/// AABB, where it lies up to rounding): it is Ritter's radius up to rounding, and
/// every point's computed distance is `≤ radius`, its exact distance within about
/// `3 ε·radius` of it (see [`BoundingSphere`]).
///
/// Degenerate input: no points gives `None`. A single point, or coincident points,
/// give that point with radius 0; duplicates, collinear and coplanar points need
/// nothing special (`d > r ≥ 0` guards the division). A scene spread over more
/// than the type's range gets radius `+∞` with `degenerate` set. Never NaN for
/// finite input.
pub fn bounding_sphere_ritter<T: Real>(points: &[Vec3<T>]) -> Option<BoundingSphere<T>> {
    let first = *points.first()?;
    let Some(cloud) = local_cloud(points) else {
        return Some(enclose(points, first));
    };
    let pts = &cloud.points;
    let farthest_from = |q: &Vec3<T>| {
        let mut best = pts[0];
        let mut best_d2 = (best - q).norm_squared();
        for p in pts {
            let d2 = (p - q).norm_squared();
            if d2 > best_d2 {
                best = *p;
                best_d2 = d2;
            }
        }
        best
    };
    let y = farthest_from(&pts[0]);
    let z = farthest_from(&y);
    let half = c::<T>(0.5);
    let mut center = (y + z) * half;
    let mut r = (z - y).norm() * half;
    for p in pts {
        let d = (p - center).norm();
        if d > r {
            let grow = (d - r) * half;
            center += (p - center) * (grow / d);
            r += grow;
        }
    }
    Some(enclose(points, cloud.to_world(&center)))
}
