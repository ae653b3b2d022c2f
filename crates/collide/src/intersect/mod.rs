//! Segment intersection queries.

mod hit;

pub use hit::{Intersection, SegmentHit};
