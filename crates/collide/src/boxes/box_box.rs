//! Overlap of two boxes, and of a box and an AABB.

use super::poly::{Ring, at, cross3, dot3, refs, sign_of, sub3};
use super::{all_finite, axes_of, axis, wide3};
use crate::exact::{P3, Sign, collinear};
use crate::real::{Real, Vec3};
use crate::shapes::{Aabb, OrientedBox};

/// Ericson's `EPSILON` in `TestOBBOBB` (*Real-Time Collision Detection*,
/// §4.4.1), added to every `|R_ij|` (the absolute entries of the rotation of
/// `b` in `a`'s frame) "to counteract arithmetic errors when two edges are
/// parallel and their cross product is (near) null". An absolute number
/// (1e-6): it widens every box's projection by up to `1e-6` times its
/// half-extents, so boxes apart by less than that along a face axis are
/// reported overlapping — the lecture's form wrong by design.
pub const OBB_EPSILON: f64 = 1e-6;

/// Whether two boxes overlap (touching counts), **the lecture's form**:
/// Ericson's `TestOBBOBB` (§4.4.1) as written, with `R` from
/// [`OrientedBox::rotation_matrix_lecture`]: `R_ij = A_i · B_j`, the centres'
/// offset `t` in `a`'s frame, `|R_ij| + OBB_EPSILON`, then the 15 axes — the
/// three of `a` (`|t_i| > h^a_i + Σ_j h^b_j |R_ij|` separates), the three of
/// `b`, and the nine `A_i × B_j`, each projection written with `R`'s
/// entries (which assumes both matrices orthonormal).
pub fn test_box_box_lecture<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> bool {
    let (ra, rb) = (a.rotation_matrix_lecture(), b.rotation_matrix_lecture());
    let (ea, eb) = (a.half_extents, b.half_extents);
    let r = ra.transpose() * rb;
    let d = b.center - a.center;
    let t = Vec3::new(d.dot(&ra.column(0)), d.dot(&ra.column(1)), d.dot(&ra.column(2)));
    let abs = r.map(|x| x.abs() + T::of(OBB_EPSILON));
    for i in 0..3 {
        let (sa, sb) = (ea[i], eb[0] * abs[(i, 0)] + eb[1] * abs[(i, 1)] + eb[2] * abs[(i, 2)]);
        if t[i].abs() > sa + sb {
            return false;
        }
    }
    for j in 0..3 {
        let sa = ea[0] * abs[(0, j)] + ea[1] * abs[(1, j)] + ea[2] * abs[(2, j)];
        let tj = t[0] * r[(0, j)] + t[1] * r[(1, j)] + t[2] * r[(2, j)];
        if tj.abs() > sa + eb[j] {
            return false;
        }
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let sa = ea[i1] * abs[(i2, j)] + ea[i2] * abs[(i1, j)];
            let sb = eb[j1] * abs[(i, j2)] + eb[j2] * abs[(i, j1)];
            if (t[i2] * r[(i1, j)] - t[i1] * r[(i2, j)]).abs() > sa + sb {
                return false;
            }
        }
    }
    true
}

/// Whether a box and an axis-aligned box overlap, **the lecture's form**: the
/// AABB as a box (centre `(min + max)/2`, half-extents `(max − min)/2`,
/// unrotated), then [`test_box_box_lecture`].
pub fn test_box_aabb_lecture<T: Real>(a: &OrientedBox<T>, b: &Aabb<T>) -> bool {
    let half = T::of(0.5);
    let bb = OrientedBox::axis_aligned((b.min + b.max) * half, (b.max - b.min) * half);
    test_box_box_lecture(a, &bb)
}

/// Whether two boxes overlap (touching counts), **robust form**: the
/// separating-axis test decided exactly for the boxes of the rounded
/// rotations, `c + R̃ u` with `|u_i| ≤ h_i` (see [`crate::boxes`]). As `R̃` is
/// orthonormal only to its rounding, the axes are the solids' own: the face
/// normals `A_j × A_k` and `B_j × B_k`, and the nine edge directions
/// `A_i × B_j` (a pair of exactly parallel edges, whose cross product is zero,
/// is skipped: it separates nothing). An axis `L` separates when
/// `|L · (c_b − c_a)| > Σ h^a_i |L · A_i| + Σ h^b_j |L · B_j|`, each sign
/// exact; no axis separating means the closed solids share a point.
///
/// Non-finite input: `false`.
pub fn test_box_box<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> bool {
    let (aa, ab) = (axes_of(&a.rotation_matrix()), axes_of(&b.rotation_matrix()));
    let (ca, cb) = (wide3(&a.center), wide3(&b.center));
    let (ha, hb) = (wide3(&a.half_extents).map(f64::abs), wide3(&b.half_extents).map(f64::abs));
    let lengths = [ca[0], ca[1], ca[2], cb[0], cb[1], cb[2], ha[0], ha[1], ha[2], hb[0], hb[1], hb[2]];
    if !all_finite(&lengths) || !all_finite(&aa) || !all_finite(&ab) {
        return false;
    }
    let separates = |x: P3, y: P3| {
        let mut u = [0.0; 24];
        u[..3].copy_from_slice(&x);
        u[3..6].copy_from_slice(&y);
        u[6..15].copy_from_slice(&aa);
        u[15..].copy_from_slice(&ab);
        sign_of!(separation, lengths, u) == Sign::Positive
    };
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        if separates(axis(&aa, j), axis(&aa, k)) || separates(axis(&ab, j), axis(&ab, k)) {
            return false;
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            let (x, y) = (axis(&aa, i), axis(&ab, j));
            if !collinear([0.0; 3], x, y) && separates(x, y) {
                return false;
            }
        }
    }
    true
}

/// Whether a box and an axis-aligned box overlap, **robust form**: as
/// [`test_box_box`], with the AABB's own faces (`min`, `max`, never a rounded
/// centre and half-extent): along `L` it spans `Σ_k min(L_k min_k, L_k max_k)`
/// to `Σ_k max(…)`, so `L` separates when
/// `|L · (min + max − 2c)| > 2 Σ h_i |L · A_i| + Σ_k (max_k − min_k)|L_k|`,
/// decided exactly. Axes: the box's face normals, the three coordinate axes
/// and the nine `A_i × e_k` (skipped when exactly zero).
///
/// Non-finite input: `false`. An AABB with `min > max` on an axis is
/// malformed; its answer is not meaningful.
pub fn test_box_aabb<T: Real>(a: &OrientedBox<T>, b: &Aabb<T>) -> bool {
    let aa = axes_of(&a.rotation_matrix());
    let (ca, ha) = (wide3(&a.center), wide3(&a.half_extents).map(f64::abs));
    let (lo, hi) = (wide3(&b.min), wide3(&b.max));
    let lengths = [ca[0], ca[1], ca[2], ha[0], ha[1], ha[2], lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]];
    if !all_finite(&lengths) || !all_finite(&aa) {
        return false;
    }
    let separates = |x: P3, y: P3| {
        let mut u = [0.0; 15];
        u[..3].copy_from_slice(&x);
        u[3..6].copy_from_slice(&y);
        u[6..].copy_from_slice(&aa);
        sign_of!(separation_aabb, lengths, u) == Sign::Positive
    };
    let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        if separates(axis(&aa, j), axis(&aa, k)) || separates(e[j], e[k]) {
            return false;
        }
    }
    for i in 0..3 {
        for ek in e {
            let x = axis(&aa, i);
            if !collinear([0.0; 3], x, ek) && separates(x, ek) {
                return false;
            }
        }
    }
    true
}

/// `|L · (c_b − c_a)| − Σ h^a_i |L · A_i| − Σ h^b_j |L · B_j|`, `L = X × Y`:
/// lengths `[c_a, c_b, h_a, h_b]`, units `[X, Y, A, B]`.
fn separation<N: Ring>(l: &[N; 12], u: &[N; 24]) -> N {
    let axis_l = cross3(at(u, 0), at(u, 3));
    let lv = refs(&axis_l);
    let mut sep = dot3(lv, refs(&sub3(at(l, 3), at(l, 0)))).abs();
    for i in 0..3 {
        sep = sep.sub(&l[6 + i].mul(&dot3(lv, at(u, 6 + 3 * i)).abs()));
        sep = sep.sub(&l[9 + i].mul(&dot3(lv, at(u, 15 + 3 * i)).abs()));
    }
    sep
}

/// `|L · (min + max − 2c)| − 2 Σ h_i |L · A_i| − Σ_k (max_k − min_k)|L_k|`,
/// `L = X × Y`: lengths `[c, h, min, max]`, units `[X, Y, A]`.
fn separation_aabb<N: Ring>(l: &[N; 12], u: &[N; 15]) -> N {
    let axis_l = cross3(at(u, 0), at(u, 3));
    let lv = refs(&axis_l);
    let mid = [0, 1, 2].map(|k| l[6 + k].add(&l[9 + k]).sub(&l[k]).sub(&l[k]));
    let mut sep = dot3(lv, refs(&mid)).abs();
    for i in 0..3 {
        let reach = l[3 + i].mul(&dot3(lv, at(u, 6 + 3 * i)).abs());
        sep = sep.sub(&reach).sub(&reach);
        sep = sep.sub(&l[9 + i].sub(&l[6 + i]).mul(&lv[i].abs()));
    }
    sep
}
