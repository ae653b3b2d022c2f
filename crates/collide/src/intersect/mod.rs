//! Segment intersection queries: where a segment first meets a plane or a
//! triangle.
//!
//! Each query comes twice: the lecture's method (`_lecture`), written as the
//! lecture gives it, and a robust method whose hit / miss / parallel decision is
//! exact for every finite input (see [`crate::exact`]). Both answer an
//! [`Intersection`] in the fixture format's conventions: the normal is the
//! surface's own (not flipped), touching counts as a hit, a parallel or coplanar
//! segment reports no hit, and degenerate input is flagged, never NaN.

mod hit;
mod segment_plane;
mod segment_triangle;

pub use hit::{Intersection, SegmentHit};
pub use segment_plane::{intersect_segment_plane, intersect_segment_plane_lecture};
pub use segment_triangle::{intersect_segment_triangle, intersect_segment_triangle_lecture};
