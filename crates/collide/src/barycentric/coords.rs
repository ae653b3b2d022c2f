//! The result of a barycentric query.

use crate::real::Real;

/// Barycentric coordinates of a point with respect to `N` vertices (2 for a
/// segment, 3 for a triangle), `point = Σ coords[i] · vertex[i]`.
///
/// The signed methods (`barycentric_segment`, `barycentric_triangle`) describe the
/// point's projection onto the simplex's line or plane: they sum to 1 (to within
/// a rounding of the largest coordinate) and are negative outside. The lecture's
/// unsigned ratios (`*_lecture`) are never negative and are returned raw, as the
/// lecture defines them: they sum to 1 only for a point inside the simplex.
///
/// `degenerate` is set when the reference simplex has no extent (a zero-length
/// segment, a zero-area triangle) or the coordinates exceed the type's range;
/// `coords` then holds the function's documented fallback, non-negative and
/// summing to 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Barycentric<T: Real, const N: usize> {
    /// The coordinates, one per vertex.
    pub coords: [T; N],
    /// The simplex is degenerate; `coords` is a fallback.
    pub degenerate: bool,
}
