//! Overlap of two boxes, and of a box and an AABB.

use super::poly::{Ring, at, cross3, dot3, norm2, quaternion_axes, refs, select, sign_of, sub3};
use super::{all_finite, stage, wide3};
use crate::exact::Sign;
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
/// separating-axis test decided exactly for the boxes the quaternions define,
/// `c + R(q) u` with `|u_i| ≤ h_i` and `R(q)` the exact rotation of `q/‖q‖`
/// (rational in `q`; never the rounded matrix, so a 3-4-5 box touching
/// another touches here too). The axes are taken unnormalized,
/// `M_i = ‖q‖² R(q) e_i` (quadratic in `q`, see `poly::quaternion_axes`): the
/// face normals `A_j × A_k` and `B_j × B_k`, and the nine edge directions
/// `A_i × B_j`. An axis `L` separates when
/// `|L · (c_b − c_a)| > Σ h^a_i |L · A_i| + Σ h^b_j |L · B_j|`, decided exactly
/// after multiplying through by `‖q_a‖²‖q_b‖² > 0`; an exactly zero `L` (a pair
/// of parallel edges) gives `0 > 0` and separates nothing. No axis separating
/// means the closed solids share a point.
///
/// Non-finite input or a zero quaternion: `false`.
///
/// A floating-point stage answers first when it is certain
/// (`crate::boxes::stage`), which is the exact answer; otherwise only the
/// axes it left undecided are decided by the exact code (the others
/// certainly do not separate).
pub fn test_box_box<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> bool {
    box_box(a, b, true)
}

/// [`test_box_box`] without its floating-point stage: the exact decisions
/// alone, which the stage must agree with bit for bit.
#[cfg(test)]
pub(super) fn test_box_box_unstaged<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>) -> bool {
    box_box(a, b, false)
}

fn box_box<T: Real>(a: &OrientedBox<T>, b: &OrientedBox<T>, staged: bool) -> bool {
    let (qa, qb) = (a.rotation.map(|x| x.wide()), b.rotation.map(|x| x.wide()));
    let (ca, cb) = (wide3(&a.center), wide3(&b.center));
    let (ha, hb) = (wide3(&a.half_extents).map(f64::abs), wide3(&b.half_extents).map(f64::abs));
    let lengths = [ca[0], ca[1], ca[2], cb[0], cb[1], cb[2], ha[0], ha[1], ha[2], hb[0], hb[1], hb[2]];
    if !all_finite(&lengths) || !all_finite(&qa) || !all_finite(&qb) || zero_quaternion(&qa) || zero_quaternion(&qb) {
        return false;
    }
    let undecided = if staged {
        match stage::box_box_axes(&qa, &qb, &lengths) {
            Ok(overlap) => return overlap,
            Err(mask) => mask,
        }
    } else {
        stage::ALL_AXES
    };
    let separates = |x: usize, y: usize| {
        let mut u = [0.0; 20];
        u[..4].copy_from_slice(&qa);
        u[4..8].copy_from_slice(&qb);
        u[8 + x] = 1.0;
        u[14 + y] = 1.0;
        sign_of!(separation, lengths, u) == Sign::Positive
    };
    !undecided_axes(undecided).any(|(x, y)| separates(x, y))
}

/// The exact code's selectors `(X, Y)` (`L = X × Y` among `[A_0..2, B_0..2]`)
/// of the axes in a mask of [`stage::box_box_axes`]' (bit `i`: `A_i`, that is
/// `A_{i+1} × A_{i+2}`; `3 + j`: `B_j`; `6 + 3i + j`: `A_i × B_j`), in the
/// exact code's order: the face axes, then the edge pairs.
fn undecided_axes(mask: u16) -> impl Iterator<Item = (usize, usize)> {
    let faces = (0..3).flat_map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        [(i, (j, k)), (3 + i, (3 + j, 3 + k))]
    });
    let edges = (0..3).flat_map(|i| (0..3).map(move |j| (6 + 3 * i + j, (i, 3 + j))));
    faces.chain(edges).filter(move |(bit, _)| mask & (1 << bit) != 0).map(|(_, xy)| xy)
}

/// Whether a box and an axis-aligned box overlap, **robust form**: as
/// [`test_box_box`] (the quaternion's exact rotation), with the AABB's own
/// faces (`min`, `max`, never a rounded centre and half-extent): along `L` it
/// spans `Σ_k min(L_k min_k, L_k max_k)` to `Σ_k max(…)`, so `L` separates when
/// `|L · (min + max − 2c)| > 2 Σ h_i |L · A_i| + Σ_k (max_k − min_k)|L_k|`,
/// decided exactly after multiplying through by `‖q‖²`. Axes: the box's face
/// normals, the three coordinate axes and the nine `A_i × e_k` (an exactly
/// zero one separates nothing).
///
/// Non-finite input or a zero quaternion: `false`. An AABB with `min > max`
/// on an axis is malformed; its answer is not meaningful.
///
/// A floating-point stage answers first when it is certain, as in
/// [`test_box_box`].
pub fn test_box_aabb<T: Real>(a: &OrientedBox<T>, b: &Aabb<T>) -> bool {
    box_aabb(a, b, true)
}

/// [`test_box_aabb`] without its floating-point stage.
#[cfg(test)]
pub(super) fn test_box_aabb_unstaged<T: Real>(a: &OrientedBox<T>, b: &Aabb<T>) -> bool {
    box_aabb(a, b, false)
}

fn box_aabb<T: Real>(a: &OrientedBox<T>, b: &Aabb<T>, staged: bool) -> bool {
    let q = a.rotation.map(|x| x.wide());
    let (ca, ha) = (wide3(&a.center), wide3(&a.half_extents).map(f64::abs));
    let (lo, hi) = (wide3(&b.min), wide3(&b.max));
    let lengths = [ca[0], ca[1], ca[2], ha[0], ha[1], ha[2], lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]];
    if !all_finite(&lengths) || !all_finite(&q) || zero_quaternion(&q) {
        return false;
    }
    let undecided = if staged {
        match stage::box_aabb_axes(&q, &lengths) {
            Ok(overlap) => return overlap,
            Err(mask) => mask,
        }
    } else {
        stage::ALL_AXES
    };
    let separates = |x: usize, y: usize| {
        let mut u = [0.0; 17];
        u[..4].copy_from_slice(&q);
        u[16] = 1.0;
        u[4 + x] = 1.0;
        u[10 + y] = 1.0;
        sign_of!(separation_aabb, lengths, u) == Sign::Positive
    };
    !undecided_axes(undecided).any(|(x, y)| separates(x, y))
}

fn zero_quaternion(q: &[f64; 4]) -> bool {
    q.iter().all(|x| *x == 0.0)
}

/// `n_a n_b |L · (c_b − c_a)| − n_b Σ h^a_i |L · M^a_i| − n_a Σ h^b_j |L · M^b_j|`
/// (`n = ‖q‖²`, `M` the [`quaternion_axes`]): `n_a n_b` times the separation
/// along `L = X × Y`, `X` and `Y` picked among `[M^a_0..2, M^b_0..2]` by
/// one-hot selectors. Lengths `[c_a, c_b, h_a, h_b]`, units
/// `[q_a, q_b, select X (6), select Y (6)]`.
fn separation<N: Ring>(l: &[N; 12], u: &[N; 20]) -> N {
    let (qa, qb) = ([&u[0], &u[1], &u[2], &u[3]], [&u[4], &u[5], &u[6], &u[7]]);
    let (ma, mb) = (quaternion_axes(qa), quaternion_axes(qb));
    let (na, nb) = (norm2(qa), norm2(qb));
    let v = [ma[0].clone(), ma[1].clone(), ma[2].clone(), mb[0].clone(), mb[1].clone(), mb[2].clone()];
    let axis_l = cross3(refs(&select(&u[8..14], &v)), refs(&select(&u[14..20], &v)));
    let lv = refs(&axis_l);
    let mut sep = na.mul(&nb).mul(&dot3(lv, refs(&sub3(at(l, 3), at(l, 0)))).abs());
    for i in 0..3 {
        sep = sep.sub(&nb.mul(&l[6 + i].mul(&dot3(lv, refs(&ma[i])).abs())));
        sep = sep.sub(&na.mul(&l[9 + i].mul(&dot3(lv, refs(&mb[i])).abs())));
    }
    sep
}

/// `n |L · (min + max − 2c)| − 2 Σ h_i |L · M_i| − n Σ_k (max_k − min_k)|L_k|`
/// (`n = ‖q‖²`): `n` times the separation along `L = X × Y`, `X` and `Y` picked
/// among `[M_0..2, e_0..2]` by one-hot selectors. Lengths `[c, h, min, max]`,
/// units `[q, select X (6), select Y (6), 1]`.
fn separation_aabb<N: Ring>(l: &[N; 12], u: &[N; 17]) -> N {
    let q = [&u[0], &u[1], &u[2], &u[3]];
    let (m, n) = (quaternion_axes(q), norm2(q));
    let (zero, one) = (u[16].sub(&u[16]), u[16].clone());
    let e = |k: usize| std::array::from_fn(|i| if i == k { one.clone() } else { zero.clone() });
    let v = [m[0].clone(), m[1].clone(), m[2].clone(), e(0), e(1), e(2)];
    let axis_l = cross3(refs(&select(&u[4..10], &v)), refs(&select(&u[10..16], &v)));
    let lv = refs(&axis_l);
    let mid = [0, 1, 2].map(|k| l[6 + k].add(&l[9 + k]).sub(&l[k]).sub(&l[k]));
    let mut sep = n.mul(&dot3(lv, refs(&mid)).abs());
    for i in 0..3 {
        let reach = l[3 + i].mul(&dot3(lv, refs(&m[i])).abs());
        sep = sep.sub(&reach).sub(&reach);
        sep = sep.sub(&n.mul(&l[9 + i].sub(&l[6 + i]).mul(&lv[i].abs())));
    }
    sep
}
