//! Bounding volumes of a box: its AABB and a bounding sphere.

use super::{all_finite, axes_of, wide3};
use crate::bounds::BoundingSphere;
use crate::exact::BigFloat;
use crate::real::{Real, Vec3};
use crate::shapes::{Aabb, OrientedBox};

/// The AABB of a box, **the lecture's form**: with `R` from
/// [`OrientedBox::rotation_matrix_lecture`], the box reaches
/// `e_i = Σ_j |R_ij| h_j` from its centre along world axis `i` (the support of
/// the box in direction `±x_i`), so `[center − e, center + e]`, in plain
/// arithmetic (each face within a few roundings; a face beyond the range is
/// `±∞`, which still bounds).
pub fn aabb_of_box_lecture<T: Real>(b: &OrientedBox<T>) -> Aabb<T> {
    let r = b.rotation_matrix_lecture();
    let h = b.half_extents.map(|x| x.abs());
    let e = r.abs() * h;
    Aabb::new(b.center - e, b.center + e)
}

/// The AABB of a box, **robust form**: each face
/// `center_i ± Σ_j |R̃_ij| h_j` computed exactly and rounded once (so it is
/// within an ulp of the exact face of the rounded rotation's box; a face beyond
/// the range is `±∞`). A non-finite input gives the box `[center, center]`
/// widened to `±∞`.
pub fn aabb_of_box<T: Real>(b: &OrientedBox<T>) -> Aabb<T> {
    let ax = axes_of(&b.rotation_matrix());
    let (c, h) = (wide3(&b.center), wide3(&b.half_extents).map(f64::abs));
    if !all_finite(&[c[0], c[1], c[2], h[0], h[1], h[2]]) || !all_finite(&ax) {
        let inf = T::of(f64::INFINITY);
        return Aabb::new(Vec3::new(-inf, -inf, -inf), Vec3::new(inf, inf, inf));
    }
    let reach = |i: usize| {
        (0..3).fold(BigFloat::ZERO, |s, j| &s + &(&BigFloat::from_f64(ax[3 * j + i].abs()) * &BigFloat::from_f64(h[j])))
    };
    let mut lo = Vec3::zeros();
    let mut hi = Vec3::zeros();
    for i in 0..3 {
        let (ci, e) = (BigFloat::from_f64(c[i]), reach(i));
        lo[i] = T::of((&ci - &e).to_f64());
        hi[i] = T::of((&ci + &e).to_f64());
    }
    Aabb::new(lo, hi)
}

/// A bounding sphere of a box, **the lecture's form**: its centre, and the
/// radius `‖h‖` with the plain norm (it overflows for half-extents above about
/// `1e154` in `f64`, flagged).
pub fn bounding_sphere_of_box_lecture<T: Real>(b: &OrientedBox<T>) -> BoundingSphere<T> {
    let radius = b.half_extents.norm();
    BoundingSphere { center: b.center, radius, degenerate: !radius.finite() }
}

/// A bounding sphere of a box, **robust form**: its centre and the radius
/// `‖h‖` (the smallest enclosing sphere's: every corner is at that distance),
/// with the scaled norm, which neither overflows nor underflows; flagged only
/// when `‖h‖` itself is beyond the range.
pub fn bounding_sphere_of_box<T: Real>(b: &OrientedBox<T>) -> BoundingSphere<T> {
    let radius = crate::real::stable_norm(&b.half_extents);
    BoundingSphere { center: b.center, radius, degenerate: !radius.finite() }
}
