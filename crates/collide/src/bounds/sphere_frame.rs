//! Private machinery shared by the bounding-sphere constructions: the local frame
//! they compute in, and the final enclosure step.

use super::aabb_from_points::aabb_from_points;
use super::bounding_sphere::BoundingSphere;
use crate::barycentric::local::{max_abs, mul_pow2, unit_exponent};
use crate::real::{Real, Vec3, c, finite3, stable_norm};

/// The input points moved into a local frame: translated by the first point and
/// scaled by an exact power of two so that the largest offset component lies in
/// `[1, 2)`. Every construction works here, where no sum, square or product of
/// two offsets can overflow or underflow, whatever the scene's position and size.
pub(super) struct LocalCloud<T: Real> {
    /// The first input point.
    origin: Vec3<T>,
    /// Offsets were formed as `p/2 − origin/2` because `p − origin` overflowed.
    halved: bool,
    /// `local = offset · 2^k`.
    k: i32,
    /// The points in the local frame, in input order.
    pub(super) points: Vec<Vec3<T>>,
}

/// The local frame of a non-empty point set; `None` when the set is empty or all
/// points coincide (every offset exactly zero: the answer is the first point with
/// radius 0, no frame needed).
pub(super) fn local_cloud<T: Real>(points: &[Vec3<T>]) -> Option<LocalCloud<T>> {
    let origin = *points.first()?;
    let halved = !points.iter().all(|p| finite3(&(p - origin)));
    let half = c::<T>(0.5);
    let offset = |p: &Vec3<T>| {
        if halved { p * half - origin * half } else { p - origin }
    };
    let m = points.iter().map(|p| max_abs(&offset(p))).fold(T::zero(), |a, b| a.max(b));
    if m == T::zero() {
        return None;
    }
    let k = unit_exponent(m);
    let points = points.iter().map(|p| mul_pow2(&offset(p), k)).collect();
    Some(LocalCloud { origin, halved, k, points })
}

impl<T: Real> LocalCloud<T> {
    /// A local point back in the input frame: `origin + local · 2^−k`, or
    /// `2 (origin/2 + local · 2^−k)` for a halved frame (no intermediate overflow
    /// for a point inside the cloud's box; a result beyond the type's range
    /// becomes ±∞ and is clamped by [`enclose`]).
    pub(super) fn to_world(&self, local: &Vec3<T>) -> Vec3<T> {
        let back = mul_pow2(local, -self.k);
        if self.halved {
            let half = c::<T>(0.5);
            (self.origin * half + back) * c::<T>(2.0)
        } else {
            self.origin + back
        }
    }
}

/// The distance `‖p − q‖` without spurious overflow: [`stable_norm`] of the
/// difference, or `2 ‖p/2 − q/2‖` when the difference overflows (`+∞` only when
/// the distance itself exceeds the type's range).
pub(super) fn distance<T: Real>(p: &Vec3<T>, q: &Vec3<T>) -> T {
    let d = p - q;
    if finite3(&d) {
        stable_norm(&d)
    } else {
        let half = c::<T>(0.5);
        stable_norm(&(p * half - q * half)) * c::<T>(2.0)
    }
}

/// The final step of every construction: the sphere about `center` that
/// encloses `points` (non-empty).
///
/// 1. `center` is clamped, per axis, into the points' AABB. The clamp is the
///    projection onto a convex set containing every point, which never increases
///    the distance to any of them, so it costs nothing; it also turns a centre
///    that left the type's range (±∞ after mapping back from the local frame) or
///    any non-finite value into a finite one (a NaN component goes to the box's
///    lower face; no construction produces one).
/// 2. `radius` is the largest [`distance`] from the clamped centre to a point:
///    each point's computed distance is then `≤ radius` exactly, whatever the
///    construction's rounding, and its exact distance within about `3 ε·radius`.
/// 3. `degenerate` is set when that radius overflowed to `+∞`.
pub(super) fn enclose<T: Real>(points: &[Vec3<T>], center: Vec3<T>) -> BoundingSphere<T> {
    let Some(bb) = aabb_from_points(points) else {
        return BoundingSphere { center, radius: T::zero(), degenerate: false };
    };
    let mut center = center;
    for i in 0..3 {
        // Written so that a NaN component fails both tests and takes the lower face.
        center[i] = if center[i] > bb.max[i] {
            bb.max[i]
        } else if center[i] >= bb.min[i] {
            center[i]
        } else {
            bb.min[i]
        };
    }
    let radius = points.iter().map(|p| distance(p, &center)).fold(T::zero(), |a, b| a.max(b));
    BoundingSphere { center, radius, degenerate: !radius.finite() }
}
