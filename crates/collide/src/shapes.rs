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

/// A solid box that may be rotated: the points `center + R u` with
/// `|u_i| ≤ half_extents_i`, `R` the rotation of the unit quaternion
/// `rotation / ‖rotation‖` (`[w, x, y, z]`, any non-zero length). Axis `i` of
/// the box is column `i` of `R`; a zero half-extent is a flat box.
///
/// Two matrices are offered: [`OrientedBox::rotation_matrix_lecture`], the
/// textbook's (normalize the quaternion, then the usual formula), and
/// [`OrientedBox::rotation_matrix`], which scales the quaternion by a power of
/// two first, so that no square over- or underflows. The robust queries use the
/// latter: their box is the one of that rounded matrix (see
/// [`crate::boxes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrientedBox<T: Real> {
    /// Centre.
    pub center: Vec3<T>,
    /// Half-extents along the box's own axes, each ≥ 0.
    pub half_extents: Vec3<T>,
    /// The rotation as a quaternion `[w, x, y, z]` of any non-zero length.
    pub rotation: [T; 4],
}

/// The points within `radius` of the segment from `start` to `end` (a sphere
/// when the two are equal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule<T: Real> {
    /// One end of the axis.
    pub start: Vec3<T>,
    /// The other end.
    pub end: Vec3<T>,
    /// Radius, expected > 0.
    pub radius: T,
}

impl<T: Real> OrientedBox<T> {
    /// A box from its centre, half-extents and quaternion `[w, x, y, z]`.
    pub fn new(center: Vec3<T>, half_extents: Vec3<T>, rotation: [T; 4]) -> Self {
        Self { center, half_extents, rotation }
    }

    /// An unrotated box (quaternion `[1, 0, 0, 0]`).
    pub fn axis_aligned(center: Vec3<T>, half_extents: Vec3<T>) -> Self {
        Self::new(center, half_extents, [T::one(), T::zero(), T::zero(), T::zero()])
    }

    /// The rotation matrix, **the lecture's form**: `q̂ = q / ‖q‖` with the
    /// plain norm, then
    ///
    /// ```text
    /// R = [[1 − 2(y² + z²), 2(xy − wz),     2(xz + wy)],
    ///      [2(xy + wz),     1 − 2(x² + z²), 2(yz − wx)],
    ///      [2(xz − wy),     2(yz + wx),     1 − 2(x² + y²)]]
    /// ```
    ///
    /// The norm underflows for a quaternion below about `1e-154` (`f64`;
    /// `1e-19` in `f32`) and overflows above `1e154`: then (and for a zero
    /// quaternion) the answer is the identity, which is the lecture's form
    /// failing, not a fallback anyone defined.
    pub fn rotation_matrix_lecture(&self) -> nalgebra::Matrix3<T> {
        let [w, x, y, z] = self.rotation;
        let n = (w * w + x * x + y * y + z * z).sqrt();
        if !(n > T::zero()) || !n.finite() {
            return nalgebra::Matrix3::identity();
        }
        let (w, x, y, z) = (w / n, x / n, y / n, z / n);
        let two = T::one() + T::one();
        nalgebra::Matrix3::new(
            T::one() - two * (y * y + z * z),
            two * (x * y - w * z),
            two * (x * z + w * y),
            two * (x * y + w * z),
            T::one() - two * (x * x + z * z),
            two * (y * z - w * x),
            two * (x * z - w * y),
            two * (y * z + w * x),
            T::one() - two * (x * x + y * y),
        )
    }

    /// The rotation matrix, **robust form**: the quaternion scaled by a power
    /// of two so that its largest component lies in `[1, 2)` (exact), then
    /// `R = I + 2w[v]× + 2[v]×²` over `‖q‖²`, each entry
    /// `1 − s(y² + z²)`, `s(xy − wz)`, … with `s = 2/‖q‖²`. No square over- or
    /// underflows for any finite non-zero quaternion, and each entry is within
    /// a few ulps of the exact rotation's. A zero or non-finite quaternion
    /// gives the identity.
    pub fn rotation_matrix(&self) -> nalgebra::Matrix3<T> {
        let m = self.rotation.iter().fold(T::zero(), |m, q| m.max(q.abs()));
        if !(m > T::zero()) || !m.finite() {
            return nalgebra::Matrix3::identity();
        }
        let k = -(crate::exact::frexp(m.wide()).1 as i32) + 1;
        let [w, x, y, z] = self.rotation.map(|q| crate::real::scale2(q, k));
        let s = (T::one() + T::one()) / (w * w + x * x + y * y + z * z);
        nalgebra::Matrix3::new(
            T::one() - s * (y * y + z * z),
            s * (x * y - w * z),
            s * (x * z + w * y),
            s * (x * y + w * z),
            T::one() - s * (x * x + z * z),
            s * (y * z - w * x),
            s * (x * z - w * y),
            s * (y * z + w * x),
            T::one() - s * (x * x + y * y),
        )
    }
}

impl<T: Real> Capsule<T> {
    /// A capsule from its axis and radius.
    pub fn new(start: Vec3<T>, end: Vec3<T>, radius: T) -> Self {
        Self { start, end, radius }
    }
}
