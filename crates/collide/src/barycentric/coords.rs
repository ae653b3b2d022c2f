//! The result of a barycentric query.

use crate::real::Real;

/// Barycentric coordinates of a point with respect to `N` vertices (2 for a
/// segment, 3 for a triangle). They sum to 1; signed methods give negative
/// coordinates outside, the lecture's unsigned area ratios never do.
///
/// `degenerate` is set when the reference simplex has no extent (a zero-length
/// segment, a zero-area triangle); `coords` then holds the function's documented
/// fallback, still summing to 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Barycentric<T: Real, const N: usize> {
    /// The coordinates, one per vertex.
    pub coords: [T; N],
    /// The simplex is degenerate; `coords` is a fallback.
    pub degenerate: bool,
}
