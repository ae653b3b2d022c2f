//! The AABB of a triangle.

use super::aabb_from_points::aabb_from_points;
use crate::real::Real;
use crate::shapes::{Aabb, Triangle};

/// The smallest axis-aligned box containing the triangle: the expansion of
/// [`aabb_from_points`] over its three vertices (a triangle is the convex hull of
/// its vertices, and a box is convex, so containing the vertices is containing
/// the triangle). Exact: every face is a vertex coordinate.
///
/// Degenerate input: none; a zero-area triangle gets the box of its vertices,
/// flat on some axes when they share coordinates.
pub fn aabb_of_triangle<T: Real>(tri: &Triangle<T>) -> Aabb<T> {
    let [v0, ..] = tri.vertices;
    aabb_from_points(&tri.vertices).unwrap_or(Aabb::new(v0, v0))
}
