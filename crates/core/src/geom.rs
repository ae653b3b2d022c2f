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

/// A solid box that may be rotated: the points `center + R·u` with
/// `|u_i| ≤ half_extents[i]`, `R` the rotation of the quaternion
/// `rotation / ‖rotation‖` (`[w, x, y, z]`, any non-zero length). `R`'s entries
/// are rational functions of the quaternion's, so an exact referee holds the box
/// exactly: `[2, 0, 0, 1]` is the 3-4-5 rotation about z.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct OrientedBox {
    /// Centre.
    pub center: P3,
    /// Half-extents along the box's own axes, each ≥ 0 (a zero one is a flat box).
    pub half_extents: P3,
    /// `[w, x, y, z]`, non-zero, need not be unit.
    pub rotation: [f64; 4],
}

impl OrientedBox {
    /// The rotation matrix `R` in `f64` (rows), from the quaternion scaled by a
    /// power of two first (exact), so that no square over- or underflows for
    /// any finite non-zero quaternion: `R = I + 2w·[v]× + 2[v]×²` over `‖q‖²`.
    /// The box's axis `i` is column `i` of `R`.
    pub fn rotation_matrix(&self) -> [[f64; 3]; 3] {
        rotation_matrix(self.rotation)
    }
}

/// The rotation matrix (rows) of the quaternion `q / ‖q‖`, `q = [w, x, y, z]`
/// non-zero, in `f64` (see [`OrientedBox::rotation_matrix`]). A zero
/// quaternion, which the format refuses, gives the identity.
pub fn rotation_matrix(q: [f64; 4]) -> [[f64; 3]; 3] {
    let m = q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m <= 0.0 || !m.is_finite() {
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    // 2^-e in two factors: one alone overflows for a subnormal `m`.
    let e = -(m.log2().floor() as i32);
    let (k1, k2) = (2f64.powi(e / 2), 2f64.powi(e - e / 2));
    let [w, x, y, z] = q.map(|c| c * k1 * k2);
    let n2 = w * w + x * x + y * y + z * z;
    let s = 2.0 / n2;
    [
        [1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)],
        [s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x)],
        [s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y)],
    ]
}

/// The points within `radius` of the segment from `start` to `end` (a sphere
/// when the two are equal).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Capsule {
    /// One end of the axis.
    pub start: P3,
    /// The other end of the axis.
    pub end: P3,
    /// Radius, > 0.
    pub radius: f64,
}

/// The convex hull of a non-empty set of points (flat, segment-like and
/// single-point hulls included).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize, Deserialize, JsonSchema), serde(deny_unknown_fields))]
pub struct Convex {
    /// The points, at least one; their order, repeats and interior points do
    /// not change the solid.
    pub points: Vec<P3>,
}

/// A solid of a `distance` query, borrowed from its case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solid<'a> {
    /// A ball.
    Sphere(&'a Sphere),
    /// A capsule.
    Capsule(&'a Capsule),
    /// A box that may be rotated.
    Box(&'a OrientedBox),
    /// A convex hull.
    Convex(&'a Convex),
    /// A triangle: a flat solid.
    Triangle(&'a Triangle),
    /// The solid half-space `normal · x ≤ offset`.
    Plane(&'a Plane),
}

impl Solid<'_> {
    /// Its shape kind.
    pub fn kind(&self) -> crate::pair::ShapeKind {
        use crate::pair::ShapeKind as K;
        match self {
            Solid::Sphere(_) => K::Sphere,
            Solid::Capsule(_) => K::Capsule,
            Solid::Box(_) => K::Box,
            Solid::Convex(_) => K::Convex,
            Solid::Triangle(_) => K::Triangle,
            Solid::Plane(_) => K::Plane,
        }
    }
}

/// The answer to a `distance` query: the signed distance of two solids and its
/// witnesses.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct DistanceAnswer {
    /// The separation (> 0), 0 touching, or minus the penetration depth (< 0).
    pub distance: f64,
    /// On `a`: its closest point, or for a penetration its deepest point, on
    /// its boundary.
    pub point_a: P3,
    /// On `b`, likewise; `point_a = point_b + distance · normal`.
    pub point_b: P3,
    /// Unit, from `b` toward `a`.
    pub normal: P3,
    /// The witnesses or the normal are not unique (parallel faces or edges;
    /// two least pushes), or the answer is a documented fallback.
    pub degenerate: bool,
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A rotation matrix in `f64` is orthonormal and matches its exact value
    /// to a few roundings: each entry is a handful of operations on numbers
    /// of size at most 1 (the quaternion scaled to about 1 first).
    const ENTRY_TOL: f64 = 8.0 * f64::EPSILON;

    fn close(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> bool {
        (0..3).all(|i| (0..3).all(|j| (a[i][j] - b[i][j]).abs() <= ENTRY_TOL))
    }

    #[test]
    fn the_3_4_5_rotation_at_every_scale() {
        let want = [[0.6, -0.8, 0.0], [0.8, 0.6, 0.0], [0.0, 0.0, 1.0]];
        // f64::from_bits(2) is the subnormal 2^-1073.
        for k in [1.0, 1e-300, f64::from_bits(2), 1e300, f64::MAX / 2.0] {
            let r = rotation_matrix([2.0 * k, 0.0, 0.0, k]);
            assert!(close(r, want), "scale {k}: {r:?}");
        }
        // The smallest subnormal quaternion: [0,0,0,tiny] is a half turn about z.
        let r = rotation_matrix([0.0, 0.0, 0.0, 5e-324]);
        assert!(close(r, [[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]), "{r:?}");
    }

    #[test]
    fn identity_for_the_unit_and_for_the_refused_zero_quaternion() {
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(close(rotation_matrix([1.0, 0.0, 0.0, 0.0]), id));
        assert!(close(rotation_matrix([0.0; 4]), id));
    }
}
