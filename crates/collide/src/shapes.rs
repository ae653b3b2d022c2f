//! The shapes collide answers queries about. Plain data: every field is public and
//! no constructor validates (a query receiving degenerate input answers it and sets
//! its `degenerate` flag instead).

use crate::real::{Real, Vec3};

/// A solid ball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<T: Real> {
    /// Centre.
    pub center: Vec3<T>,
    /// Radius, expected > 0 (a zero radius is answered as a point).
    pub radius: T,
}

/// The surface `normal · x = offset`. For contact it bounds the solid half-space
/// `normal · x ≤ offset`, whose outward normal is `normal / ‖normal‖`. The normal
/// need not be unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<T: Real> {
    /// Normal; any non-zero length.
    pub normal: Vec3<T>,
    /// Offset `d` in `normal · x = d` (in units of ‖normal‖).
    pub offset: T,
}

/// The points `start + t (end − start)`, `t ∈ [0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment<T: Real> {
    /// `t = 0`.
    pub start: Vec3<T>,
    /// `t = 1`.
    pub end: Vec3<T>,
}

/// A triangle; its face normal is `(v1 − v0) × (v2 − v0)`, normalized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle<T: Real> {
    /// `[v0, v1, v2]`.
    pub vertices: [Vec3<T>; 3],
}

/// An axis-aligned box; `min ≤ max` per axis for a non-empty box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<T: Real> {
    /// Lower corner.
    pub min: Vec3<T>,
    /// Upper corner.
    pub max: Vec3<T>,
}

impl<T: Real> Sphere<T> {
    /// A sphere from its centre and radius.
    pub fn new(center: Vec3<T>, radius: T) -> Self {
        Self { center, radius }
    }
}

impl<T: Real> Plane<T> {
    /// A plane from its (not necessarily unit) normal and offset.
    pub fn new(normal: Vec3<T>, offset: T) -> Self {
        Self { normal, offset }
    }
}

impl<T: Real> Segment<T> {
    /// A segment from `start` to `end`.
    pub fn new(start: Vec3<T>, end: Vec3<T>) -> Self {
        Self { start, end }
    }
}

impl<T: Real> Triangle<T> {
    /// A triangle from its three vertices.
    pub fn new(v0: Vec3<T>, v1: Vec3<T>, v2: Vec3<T>) -> Self {
        Self { vertices: [v0, v1, v2] }
    }
}

impl<T: Real> Aabb<T> {
    /// A box from its corners.
    pub fn new(min: Vec3<T>, max: Vec3<T>) -> Self {
        Self { min, max }
    }
}
