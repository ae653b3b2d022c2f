//! The AABB of a segment.

use super::aabb_from_points::aabb_from_points;
use crate::real::Real;
use crate::shapes::{Aabb, Segment};

/// The smallest axis-aligned box containing the segment: the expansion of
/// [`aabb_from_points`] over its two endpoints (a segment is the convex hull of its
/// endpoints). Exact: every face is an endpoint coordinate.
///
/// Degenerate input: none; a zero-length segment gets the point box `[start, start]`.
pub fn aabb_of_segment<T: Real>(seg: &Segment<T>) -> Aabb<T> {
    aabb_from_points(&[seg.start, seg.end]).unwrap_or(Aabb::new(seg.start, seg.start))
}
