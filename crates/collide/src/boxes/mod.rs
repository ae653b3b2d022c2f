//! Oriented boxes and capsules: contact (sphere–box, box–plane,
//! sphere–capsule, capsule–capsule, capsule–plane, box–box, box–triangle,
//! capsule–box, capsule–triangle), the first hit of a segment on a box or a
//! capsule, a box's bounds, and the overlap of two boxes (or a box and an
//! AABB). The definitions are the fixture format's (`docs/FORMAT.md`, "Boxes and
//! capsules"); each query comes twice, as everywhere in collide.
//!
//! **The lecture's forms** are the textbook's: the box's rotation matrix from
//! the normalized quaternion ([`OrientedBox::rotation_matrix_lecture`]), the
//! point in the box's frame and a clamp, Ericson's slabs for a segment, the
//! 15 separating axes of Ericson's `TestOBBOBB` (*Real-Time Collision
//! Detection*, §4.4.1) with [`OBB_EPSILON`] added to the rotation's entries,
//! and capsules through Ericson's closest points of two segments (§5.1.9) with
//! [`SEGMENT_EPSILON`]. Plain norms, plain comparisons. A lecture's contact
//! whose numbers are not all finite (a scene beyond its plain arithmetic's
//! range) is reported as none: it fails there, and never answers NaN.
//!
//! **The robust forms** decide with exact predicates and compute with
//! scaled norms:
//!
//! - *The box they decide about* is the one the format defines, turned by the
//!   quaternion's own rotation `R(q)`, the rotation of `q/‖q‖` (rational in
//!   `q`; never the rounded matrix [`OrientedBox::rotation_matrix`], whose
//!   `3/5` for the 3-4-5 box is not a binary number): every decision — inside
//!   or outside a face, contact or not, which face is nearest and whether two
//!   tie, which face a segment enters first and whether it enters through an
//!   edge, which way a plane's normal leans against an axis, whether an axis
//!   separates two boxes — is the exact sign of the format's formula, for
//!   every finite input, at every scale (`crate::boxes::poly`: a filtered
//!   `f64` evaluation, exact arithmetic when the filter cannot decide). The
//!   axes enter as `M_i = ‖q‖² R(q) e_i` (quadratics in the quaternion's raw
//!   components, `poly::quaternion_axes`, picked by one-hot selectors), and
//!   each comparison `R_i · x` against `h_i` as `M_i · x` against `‖q‖² h_i`
//!   (multiplied through by `‖q‖² > 0`, signs unchanged); a length formed so
//!   (a depth, a distance) is divided by `‖q‖²` after. So a sphere exactly
//!   touching the 3-4-5 box touches, and a segment through its exact corner
//!   hits it. A zero quaternion is the identity.
//! - *A floating-point stage* answers first where it is certain
//!   (`crate::boxes::stage`): each box's rotation is computed once per call in
//!   plain `f64` within a derived bound per entry of the exact `R(q)`
//!   (`2^−48`), the scene is scaled by a power of two to unit size, and each
//!   decision's quantity is evaluated with a running forward error bound. A
//!   sign beyond its bound is the exact sign; anything closer declines to the
//!   exact evaluation, and only the declined decisions are evaluated
//!   exactly. Box–box and box–AABB overlap are answered whole when some axis
//!   certainly separates or every axis certainly does not, else only the
//!   undecided axes go to the exact code; sphere–box settles "no contact",
//!   each slab, the reach test, and each order of the faces from inside;
//!   box–box and capsule–box contact settle the least push (every axis's
//!   push in the box's frame with its bound: "apart", or the least certainly
//!   below every other; the other pushes' signs and comparisons are hints to
//!   the exact loop) and the features' sides, and capsule–box settles "out
//!   of reach" along an axis and the edges certainly out of reach;
//!   capsule–capsule (and the point–segment tests it shares with
//!   sphere–capsule) settles the lines' critical signs, the reach tests and
//!   the order of the ends' distances. The values are computed as before.
//!   The answers are therefore bit for bit those of the exact decisions
//!   alone (tested against them). Every filtered polynomial is evaluated
//!   first without exactness tracking (`poly::Fast`), then with it, then
//!   exactly.
//! - *Values* (points, normals, depths, times) are computed in `f64` from the
//!   inputs (every `f32` is an `f64`, exactly) and rounded to the type once: on
//!   the scene scaled by a power of two when it lies outside the plain range,
//!   and with the quantities that cancel (a distance to a face, a
//!   perpendicular direction, a segment's entry time) taken from the same
//!   exact kit to `2^−40` relative. Points and normals turn with the rounded
//!   matrix [`OrientedBox::rotation_matrix`] (within a few ulps of `R(q)` per
//!   entry): values, never decisions. An `f32` robust answer is therefore
//!   more accurate than `f32` arithmetic would give.
//! - *Flags* are set exactly where the format puts them; nothing returns NaN.
//!   A non-finite input answers "no contact" (or a degenerate miss).

mod bounds;
mod box_box;
mod box_contact;
mod box_plane;
mod capsule_capsule;
mod capsule_plane;
mod capsule_polytope;
pub(crate) mod poly;
mod segment_box;
mod segment_capsule;
mod sphere_box;
mod sphere_capsule;
pub(crate) mod stage;
#[cfg(test)]
mod tests;

pub use crate::shapes::{Capsule, OrientedBox};
pub use bounds::{aabb_of_box, aabb_of_box_lecture, bounding_sphere_of_box, bounding_sphere_of_box_lecture};
pub use box_box::{OBB_EPSILON, test_box_aabb, test_box_aabb_lecture, test_box_box, test_box_box_lecture};
pub use box_contact::{
    TOUCH_TOL, TOUCH_TOL_ABS, contact_box_box, contact_box_box_lecture, contact_box_triangle,
    contact_box_triangle_lecture,
};
pub use box_plane::{contact_box_plane, contact_box_plane_lecture};
pub use capsule_capsule::{SEGMENT_EPSILON, contact_capsule_capsule, contact_capsule_capsule_lecture};
pub use capsule_plane::{contact_capsule_plane, contact_capsule_plane_lecture};
pub use capsule_polytope::{
    contact_capsule_box, contact_capsule_box_lecture, contact_capsule_triangle, contact_capsule_triangle_lecture,
};
pub use segment_box::{SLAB_EPSILON, intersect_segment_box, intersect_segment_box_lecture};
pub use segment_capsule::{intersect_segment_capsule, intersect_segment_capsule_lecture};
pub use sphere_box::{contact_sphere_box, contact_sphere_box_lecture};
pub use sphere_capsule::{contact_sphere_capsule, contact_sphere_capsule_lecture};

use crate::contact::{CONCENTRIC_FALLBACK_NORMAL, Contact};
use crate::exact::P3;
use crate::real::{Real, Vec3};

/// The normal of a contact whose normal is not unique (axes that meet, a
/// sphere's centre on a capsule's axis): `+z`, as for concentric spheres.
pub(crate) fn fallback_normal<T: Real>() -> Vec3<T> {
    let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
    Vec3::new(T::of(x), T::of(y), T::of(z))
}

/// A vector's components as `f64`.
#[inline(always)]
pub(crate) fn wide3<T: Real>(v: &Vec3<T>) -> P3 {
    [v.x.wide(), v.y.wide(), v.z.wide()]
}

/// A box's quaternion as `f64`, the rotation every robust decision is exact
/// for (its axes taken as `‖q‖² R(q)`, [`poly::quaternion_axes`]): `None` when
/// a component is not finite; a zero quaternion is the identity `[1, 0, 0, 0]`
/// (as in [`OrientedBox::rotation_matrix`]).
pub(crate) fn quaternion_of<T: Real>(b: &OrientedBox<T>) -> Option<[f64; 4]> {
    let q = b.rotation.map(|x| x.wide());
    if !all_finite(&q) {
        None
    } else if q.iter().all(|x| *x == 0.0) {
        Some([1.0, 0.0, 0.0, 0.0])
    } else {
        Some(q)
    }
}

/// The units `[q, e_i]` of a polynomial over one of the box's axes: the
/// quaternion and the one-hot selector of axis `i` ([`poly::picked_axis`]).
#[inline(always)]
pub(crate) fn quaternion_units(q: &[f64; 4], i: usize) -> [f64; 7] {
    let mut u = [q[0], q[1], q[2], q[3], 0.0, 0.0, 0.0];
    u[4 + i] = 1.0;
    u
}

/// Whether every number is finite.
#[inline(always)]
pub(crate) fn all_finite(xs: &[f64]) -> bool {
    xs.iter().all(|x| x.is_finite())
}

/// The power of two that brings a scene whose largest length is `m` near 1
/// when it lies outside `f64`'s plain range (0 inside it).
#[inline(always)]
pub(crate) fn scene_scale(lengths: &[f64]) -> i32 {
    let m = lengths.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    crate::real::unit_scale::<f64>(m).unwrap_or(0)
}

/// `p · 2^k` as a vector.
#[inline(always)]
pub(crate) fn up(p: P3, k: i32) -> Vec3<f64> {
    crate::real::scale2v(&Vec3::new(p[0], p[1], p[2]), k)
}

/// `x · 2^k`.
#[inline(always)]
pub(crate) fn up1(x: f64, k: i32) -> f64 {
    crate::real::scale2(x, k)
}

/// Clamps to the finite range (NaN to 0): the last guard of an answer whose
/// value lies beyond the type's range.
fn saturate<T: Real>(x: T) -> T {
    let big = T::max_value().unwrap_or_else(|| T::of(f64::MAX));
    if x.is_nan() { T::zero() } else { x.max(-big).min(big) }
}

/// A robust contact computed in `f64` on a scene scaled by `2^k`: the point
/// and depth scaled back, everything rounded to `T`. A value beyond the type's
/// range is saturated and the contact flagged.
pub(crate) fn finish<T: Real>(point: Vec3<f64>, normal: Vec3<f64>, depth: f64, k: i32, degenerate: bool) -> Contact<T> {
    let point = crate::real::scale2v(&point, -k).map(T::of);
    let depth = T::of(crate::real::scale2(depth.max(0.0), -k));
    let normal = normal.map(T::of);
    let beyond = !(crate::real::finite3(&point) && depth.finite() && crate::real::finite3(&normal));
    Contact {
        point: point.map(saturate),
        normal: if crate::real::finite3(&normal) { normal } else { fallback_normal() },
        depth: saturate(depth),
        degenerate: degenerate || beyond,
    }
}

/// A lecture's contact whose numbers are not all finite (a scene beyond the
/// range of its plain arithmetic, or a non-finite input) is reported as none:
/// the lecture's form fails there, and it never answers NaN.
pub(crate) fn lecture_finite<T: Real>(k: Option<Contact<T>>) -> Option<Contact<T>> {
    k.filter(|k| crate::real::finite3(&k.point) && crate::real::finite3(&k.normal) && k.depth.finite())
}

/// `v / ‖v‖` (scaled first); `None` for a zero or non-finite `v`.
#[inline(always)]
pub(crate) fn unit(v: &Vec3<f64>) -> Option<Vec3<f64>> {
    crate::real::try_normalize_stable(v)
}
