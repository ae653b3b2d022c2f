//! Bounding volumes of a box: its AABB and a bounding sphere.

use super::poly::{Ring, norm2, quaternion_axes, ratio};
use super::{all_finite, quaternion_of, wide3};
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
/// `center_i ± Σ_j |R_ij| h_j` of the quaternion's own rotation
/// `R = M/‖q‖²` (`M`'s entries quadratics in `q`), taken
/// as `(center_i ‖q‖² ± Σ_j |M_ij| h_j) / ‖q‖²`: numerator and denominator
/// exact, the quotient formed on their exponents to `2⁻⁴⁰` relative (so no
/// product of a huge half-extent and a tiny entry is lost, as it is with the
/// rounded matrix, whose entries underflow to 0 first; a face beyond the range
/// is `±∞`, a face below it 0). A non-finite input gives `[−∞, ∞]³`.
pub fn aabb_of_box<T: Real>(b: &OrientedBox<T>) -> Aabb<T> {
    let (c, h) = (wide3(&b.center), wide3(&b.half_extents).map(f64::abs));
    let q = quaternion_of(b);
    let Some(q) = q.filter(|_| all_finite(&[c[0], c[1], c[2], h[0], h[1], h[2]])) else {
        let inf = T::of(f64::INFINITY);
        return Aabb::new(Vec3::new(-inf, -inf, -inf), Vec3::new(inf, inf, inf));
    };
    let qb = q.map(BigFloat::from_f64);
    let qr = [&qb[0], &qb[1], &qb[2], &qb[3]];
    let (m, n) = (quaternion_axes(qr), norm2(qr));
    let den = n.estimate();
    let mut lo = Vec3::zeros();
    let mut hi = Vec3::zeros();
    for i in 0..3 {
        // Column j of M is axis j: its entry i is R_ij ‖q‖².
        let reach = (0..3).fold(BigFloat::ZERO, |s, j| s.add(&m[j][i].abs().mul(&BigFloat::from_f64(h[j]))));
        let cn = BigFloat::from_f64(c[i]).mul(&n);
        lo[i] = T::of(ratio(cn.sub(&reach).estimate(), den));
        hi[i] = T::of(ratio(cn.add(&reach).estimate(), den));
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The faces are quotients to `2⁻⁴⁰` relative: this many of it.
    const FACE_REL: f64 = 4.0 * crate::exact::ESTIMATE_REL_ERR;

    #[test]
    fn aabb_of_box_keeps_a_huge_extent_times_a_tiny_entry() {
        // q = [w, 0, 0, z] with w = 2⁶⁰⁰, z = 2⁻⁵⁰⁰: a turn of about 2⁻¹⁰⁹⁹ rad
        // about z. R_yx = 2wz/(w² + z²) = 2⁻⁹⁹/(2¹⁰⁰⁰ (1 + 2⁻²²⁰⁰)) ≈ 2⁻¹⁰⁹⁹,
        // below f64's range once q is scaled (the rounded matrix has 0 there),
        // and with h = (2¹⁰⁰⁰, 0, 0) the box reaches 2⁻⁹⁹ along y (to far below
        // an ulp); along x it reaches 2¹⁰⁰⁰ (R_xx = 1 to as far), along z 0.
        let (w, z) = (2f64.powi(600), 2f64.powi(-500));
        let h = 2f64.powi(1000);
        let b = OrientedBox::<f64>::new(Vec3::zeros(), Vec3::new(h, 0.0, 0.0), [w, 0.0, 0.0, z]);
        let bb = aabb_of_box(&b);
        let y = 2f64.powi(-99);
        assert!((bb.max.y - y).abs() <= FACE_REL * y && (bb.min.y + y).abs() <= FACE_REL * y, "{bb:?}");
        assert!((bb.max.x / h - 1.0).abs() <= FACE_REL && (bb.min.x / h + 1.0).abs() <= FACE_REL, "{bb:?}");
        assert!(bb.max.z == 0.0 && bb.min.z == 0.0, "{bb:?}");
    }
}
