//! Barycentric coordinates on a segment (1D) and a triangle (2D): the lecture's
//! unsigned length and area ratios, and signed coordinates of the projected point
//! beside them.

mod area_ratios;
mod coords;
pub(crate) mod local;
mod segment;
mod segment_lecture;
mod triangle;
mod triangle_lecture;

pub use coords::Barycentric;
pub use segment::barycentric_segment;
pub use segment_lecture::barycentric_segment_lecture;
pub use triangle::{barycentric_triangle, barycentric_triangle_tight};
pub use triangle_lecture::barycentric_triangle_lecture;
#[cfg(test)]
mod tests;
