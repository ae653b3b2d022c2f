//! Overlap of two AABBs.

use crate::real::Real;
use crate::shapes::Aabb;

/// Whether two axis-aligned boxes overlap; touching faces, edges or corners count
/// as overlap.
///
/// ```text
/// overlap ⇔ for every axis i:  a.min_i ≤ b.max_i  and  b.min_i ≤ a.max_i
/// ```
///
/// Derivation (the lecture's separating axes): two convex sets are disjoint
/// exactly when some axis separates their projections. For two boxes with
/// parallel faces the candidate axes are the three face normals (the edge cross
/// products are the same three axes), and a box's projection onto axis `i` is its
/// interval `[min_i, max_i]`; two intervals are disjoint exactly when one ends
/// before the other begins. Ericson, *Real-Time Collision Detection*, §4.2.1.
/// `≤` rather than `<` so that touching counts, as crashtest's fixtures ask.
///
/// Exact: only comparisons of the inputs, no arithmetic. Symmetric in `a`, `b`.
///
/// Cost: the six comparisons are all made and combined with `&` rather than
/// `&&`: no branch, so a random mix of overlapping and separated pairs costs
/// no mispredictions (measured by `cargo bench --bench queries`).
///
/// Degenerate input: boxes of zero extent (points, flat boxes) are answered by
/// the same rule. A box with `min > max` on some axis is malformed (empty); it
/// overlaps nothing on that axis unless the other box spans the gap, so the
/// answer for it is not meaningful.
#[inline]
pub fn test_aabb_aabb<T: Real>(a: &Aabb<T>, b: &Aabb<T>) -> bool {
    // Grouped by the pairs of adjacent numbers (x and y of a corner), which
    // the compiler compares two at a time in one packed instruction.
    let low = (a.min.x <= b.max.x) & (a.min.y <= b.max.y);
    let high = (b.min.x <= a.max.x) & (b.min.y <= a.max.y);
    let z = (a.min.z <= b.max.z) & (b.min.z <= a.max.z);
    low & high & z
}
