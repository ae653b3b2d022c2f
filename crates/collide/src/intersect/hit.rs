//! The result of a segment intersection query.

use crate::real::{Real, Vec3};

/// Where a segment first meets a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentHit<T: Real> {
    /// Segment parameter of the hit, in `[0, 1]`: `point = start + t (end − start)`.
    pub t: T,
    /// The hit point.
    pub point: Vec3<T>,
    /// The surface's own unit normal (a plane's `normal / ‖normal‖`, a triangle's
    /// face normal), never flipped toward the segment.
    pub normal: Vec3<T>,
    /// For triangles: `[α, β, γ]` with `point = α v0 + β v1 + γ v2`, summing to 1.
    pub barycentric: Option<[T; 3]>,
}

/// The answer of a segment–surface query.
///
/// - `hit`: the first hit (smallest `t`), or `None`;
/// - `parallel`: the segment is parallel to the surface (coplanar included); a
///   parallel segment reports no hit, as the format (docs/FORMAT.md) asks, even when coplanar and
///   overlapping;
/// - `degenerate`: the question was not well posed (a zero-length segment, a zero
///   normal, a zero-area triangle, a scene beyond the type's range); the other
///   fields then hold the function's documented fallback.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intersection<T: Real> {
    /// First hit, if any.
    pub hit: Option<SegmentHit<T>>,
    /// Segment parallel to the surface.
    pub parallel: bool,
    /// Input degenerate; see the function's documentation for its fallback.
    pub degenerate: bool,
}

impl<T: Real> Intersection<T> {
    /// No hit, not parallel, not degenerate.
    pub const MISS: Self = Self { hit: None, parallel: false, degenerate: false };
    /// Parallel (or coplanar): no hit.
    pub const PARALLEL: Self = Self { hit: None, parallel: true, degenerate: false };
    /// Degenerate input answered with no hit.
    pub const DEGENERATE: Self = Self { hit: None, parallel: false, degenerate: true };

    /// A plain hit.
    pub fn hit(hit: SegmentHit<T>) -> Self {
        Self { hit: Some(hit), parallel: false, degenerate: false }
    }
}
