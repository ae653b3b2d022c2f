//! The neutral vocabulary every reference speaks: plain `f64` data, no engine
//! types. Field names and conventions are those of the fixture format
//! (`docs/FORMAT.md`), so the harness reads and writes these structs directly:
//!
//! - a contact normal points from `b` toward `a` and is unit length; the contact
//!   point lies on `b`'s surface; depth ≥ 0 is the penetration; touching counts;
//! - a plane is the surface `normal · x = offset` bounding the solid `normal · x ≤ offset`;
//! - a triangle's face normal is `(v1 − v0) × (v2 − v0)`, normalized;
//! - a segment hit's `normal` is the surface's own normal, never flipped.

#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::{Deserialize, Serialize};

/// A point or vector.
pub type P3 = [f64; 3];

/// A solid ball.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Sphere {
    /// Centre.
    pub center: P3,
    /// Radius, > 0.
    pub radius: f64,
}

/// The surface `normal · x = offset` (normal need not be unit).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Plane {
    /// Normal, non-zero.
    pub normal: P3,
    /// Offset.
    pub offset: f64,
}

/// The points `start + t (end − start)`, `t ∈ [0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Segment {
    /// `t = 0`.
    pub start: P3,
    /// `t = 1`.
    pub end: P3,
}

/// A triangle `[v0, v1, v2]`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Triangle {
    /// The vertices.
    pub vertices: [P3; 3],
}

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Aabb {
    /// Lower corner.
    pub min: P3,
    /// Upper corner.
    pub max: P3,
}

/// A contact (see the module docs for the convention).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Contact {
    /// On `b`'s surface.
    pub point: P3,
    /// Unit, from `b` toward `a`.
    pub normal: P3,
    /// Penetration, ≥ 0.
    pub depth: f64,
}

/// The answer to a `contact` query.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ContactAnswer {
    /// The contact, or `None` when the shapes are apart.
    pub contact: Option<Contact>,
    /// The answer is a documented fallback (concentric spheres, centre on a triangle).
    pub degenerate: bool,
}

/// The first hit of a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct SegmentHit {
    /// Segment parameter in `[0, 1]`.
    pub t: f64,
    /// The hit point.
    pub point: P3,
    /// The surface's own unit normal.
    pub normal: P3,
    /// `[α, β, γ]` for triangles and meshes.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub barycentric: Option<[f64; 3]>,
    /// The face index, for meshes.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub triangle: Option<usize>,
}

/// The answer to an `intersect` query.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct IntersectAnswer {
    /// The first hit, if any.
    pub hit: Option<SegmentHit>,
    /// The segment is parallel to the surface (coplanar included).
    pub parallel: bool,
    /// The input is degenerate (zero-length segment, zero-area triangle).
    pub degenerate: bool,
}

/// The answer to a `barycentric` query.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BarycentricAnswer {
    /// `[α, β, γ]`, summing to 1, signed.
    pub coords: [f64; 3],
    /// The triangle has zero area; `coords` is a fallback.
    pub degenerate: bool,
}

/// A bounding sphere as an engine reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Ball {
    /// Centre.
    pub center: P3,
    /// Radius, ≥ 0.
    pub radius: f64,
}

/// The answer to a `bounds` query.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BoundsAnswer {
    /// The tight AABB, if the engine computes one.
    pub aabb: Option<Aabb>,
    /// The engine's bounding sphere, if it computes one.
    pub sphere: Option<Ball>,
}

/// A time of impact: the first touching time and the contact then.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Toi {
    /// First time in `[0, t_max]` at which the shapes touch.
    pub t: f64,
    /// Contact point at that time, on `b`'s surface (`b` moved by its velocity).
    pub point: P3,
    /// Unit normal at that time, from `b` toward `a`.
    pub normal: P3,
}

/// The answer to a `toi` query.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ToiAnswer {
    /// The first contact in `[0, t_max]`, or `None` when the shapes never touch.
    pub toi: Option<Toi>,
    /// The normal is a documented fallback (concentric spheres or a centre on a
    /// triangle at `t = 0`, shapes of zero total radius meeting at a point).
    pub degenerate: bool,
}

/// The answer to a `response` query: velocities after one frictionless impulse.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ResponseAnswer {
    /// `a`'s velocity after the impulse.
    pub velocity_a: P3,
    /// `b`'s velocity after the impulse (zero for a static plane).
    pub velocity_b: P3,
    /// The normal or the impulse is a documented fallback (concentric spheres,
    /// a mass that is not positive).
    pub degenerate: bool,
}

/// A point moving linearly from `t0` (its position at time 0) to `t1` (at time
/// 1): `p(t) = (1 − t)·t0 + t·t1`. Both ends are given, never a velocity: their
/// difference need not be a double.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct MovingPoint {
    /// Position at time 0.
    pub t0: P3,
    /// Position at time 1.
    pub t1: P3,
}

/// A closed segment whose two ends move linearly from `t0` to `t1`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct MovingSegment {
    /// The two ends at time 0.
    pub t0: [P3; 2],
    /// The two ends at time 1.
    pub t1: [P3; 2],
}

/// A closed triangle whose three vertices move linearly from `t0` to `t1`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct MovingTriangle {
    /// The three vertices at time 0.
    pub t0: [P3; 3],
    /// The three vertices at time 1.
    pub t1: [P3; 3],
}

/// The answer to a `ccd` query (vertex–face or edge–edge continuous collision).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct CcdAnswer {
    /// The first time in `[0, t_max]` at which the point lies on the closed
    /// triangle (the two closed segments share a point), or `None`.
    pub t: Option<f64>,
    /// The motion is coplanar throughout `[0, t_max]` (the problem is planar),
    /// or at the first time the triangle has zero area (a segment has zero
    /// length, or the two segments are parallel).
    pub degenerate: bool,
}
