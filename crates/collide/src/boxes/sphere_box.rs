//! Sphere–box contact.

use super::poly::{Ring, at, dot3, refs, sign_of, sub3, value_of};
use super::{all_finite, axes_of, axis, fallback_normal, finish, scene_scale, unit, up, up1, wide3};
use crate::contact::Contact;
use crate::exact::{Estimate, P3, Sign};
use crate::real::{Real, Vec3};
use crate::shapes::{OrientedBox, Sphere};

/// Contact between a sphere `a` and a box `b`, **the lecture's form**: with
/// `R` from [`OrientedBox::rotation_matrix_lecture`],
///
/// ```text
/// u = Rᵀ (M − center),   p = clamp(u, −h, h)
/// u ≠ p (outside):  contact when ‖u − p‖ ≤ r;  n = R (u − p) / ‖u − p‖,
///                   point = center + R p,  depth = r − ‖u − p‖
/// u = p (inside):   the face i with the least h_i − |u_i| (first of +x, −x,
///                   +y, −y, +z, −z), n = ±R_i, point = the centre projected
///                   onto it, depth = r + h_i − |u_i|
/// ```
///
/// The norm is the plain one and every comparison is on rounded values: a
/// centre within rounding of a face may be put on the wrong side of it; a
/// distance below about `1e-154` (`f64`) underflows to 0 (then the normal is
/// [`crate::contact::CONCENTRIC_FALLBACK_NORMAL`], flagged), one above `1e154`
/// overflows and the contact is missed. `degenerate` is set when two faces tie
/// as computed, or when the normal could not be formed.
pub fn contact_sphere_box_lecture<T: Real>(a: &Sphere<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    super::lecture_finite(contact_sphere_box_lecture_raw(a, b))
}

fn contact_sphere_box_lecture_raw<T: Real>(a: &Sphere<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    let r = b.rotation_matrix_lecture();
    let h = b.half_extents;
    let u = r.transpose() * (a.center - b.center);
    let p = Vec3::new(u.x.max(-h.x).min(h.x), u.y.max(-h.y).min(h.y), u.z.max(-h.z).min(h.z));
    if u != p {
        let e = u - p;
        let dist = e.norm();
        if dist.is_nan() || dist > a.radius {
            return None;
        }
        let (normal, degenerate) =
            if dist > T::zero() && dist.finite() { (r * (e / dist), false) } else { (fallback_normal(), true) };
        let point = b.center + r * p;
        return Some(Contact { point, normal, depth: a.radius - dist, degenerate });
    }
    if !crate::real::finite3(&u) {
        return None;
    }
    let gaps = [h.x - u.x.abs(), h.y - u.y.abs(), h.z - u.z.abs()];
    let mut best = 0;
    for i in 1..3 {
        if gaps[i] < gaps[best] {
            best = i;
        }
    }
    let tie = (0..3).any(|i| i != best && gaps[i] == gaps[best]) || u[best] == T::zero();
    let s = if u[best] < T::zero() { -T::one() } else { T::one() };
    let mut q = u;
    q[best] = s * h[best];
    Some(Contact { point: b.center + r * q, normal: r.column(best) * s, depth: a.radius + gaps[best], degenerate: tie })
}

/// Contact between a sphere `a` and a box `b`, **robust form**: the lecture's
/// formulas (see [`contact_sphere_box_lecture`] and `docs/FORMAT.md`) with
/// every decision exact for the box of the rounded rotation `R̃` (see
/// [`crate::boxes`]): whether the centre is beyond each face
/// (`±R̃_i · (M − c) − h_i`), whether `‖u − p‖ ≤ r` (its square against `r²`),
/// which face is nearest from inside and whether two tie. The distance to the
/// box is formed from the excesses `±u_i − h_i` to `2^−40` relative, so the
/// normal `R̃ (u − p)/‖u − p‖` is right however close the centre is to the
/// box, at every scale.
///
/// **Degenerate input.** A centre in the closed box with two nearest faces
/// (on an edge or a corner, equidistant from two faces inside, or `u_i = 0`,
/// which ties the faces `+i` and `−i`, as at the centre of a flat box): the
/// first face in the order `+x, −x, +y, −y, +z, −z`, flagged. A non-finite
/// input is no contact.
pub fn contact_sphere_box<T: Real>(a: &Sphere<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    let ax = axes_of(&b.rotation_matrix());
    let (m, c) = (wide3(&a.center), wide3(&b.center));
    let h = wide3(&b.half_extents).map(f64::abs);
    let r = a.radius.wide();
    if !all_finite(&[m[0], m[1], m[2], c[0], c[1], c[2], h[0], h[1], h[2], r]) || !all_finite(&ax) {
        return None;
    }
    let side = classify(m, c, h, &ax);
    let k = scene_scale(&[m[0], m[1], m[2], c[0], c[1], c[2], h[0], h[1], h[2], r]);
    let rot = nalgebra::Matrix3::from_column_slice(&ax);
    let (ms, cs, hs, rs) = (up(m, k), up(c, k), up(h, k), up1(r, k));
    let us = rot.transpose() * (ms - cs);
    if side == [0; 3] {
        let (i, s, tie) = nearest_face(m, c, h, &ax);
        let gap = super::poly::scaled_f64(face_gap(m, c, h, &ax, i), i64::from(k));
        let mut q = clamp(&us, &hs);
        q[i] = f64::from(s) * hs[i];
        let normal = unit(&(rot.column(i) * f64::from(s))).unwrap_or_else(fallback_normal);
        return Some(finish(cs + rot * q, normal, rs + gap, k, tie));
    }
    let lengths = [m[0], m[1], m[2], c[0], c[1], c[2], h[0], h[1], h[2], r];
    let s = side.map(f64::from);
    let mask = side.map(|x| f64::from(x.abs()));
    let units =
        [ax[0], ax[1], ax[2], ax[3], ax[4], ax[5], ax[6], ax[7], ax[8], s[0], s[1], s[2], mask[0], mask[1], mask[2]];
    if sign_of!(outside_reach, lengths, units) == Sign::Positive {
        return None;
    }
    // The excess beyond each face the centre is outside of, signed: u − p.
    let e: [Estimate; 3] = [0, 1, 2].map(|i| {
        if side[i] == 0 {
            Estimate::ZERO
        } else {
            let x = value_of!(face_excess, 1, [m[0], m[1], m[2], c[0], c[1], c[2], h[i]], {
                let a = axis(&ax, i);
                [a[0], a[1], a[2], s[i]]
            });
            if side[i] < 0 { Estimate { sign: -x.sign, ..x } } else { x }
        }
    });
    let dir = Estimate::unit_vector(e).map(|d| Vec3::new(d[0], d[1], d[2]));
    let es = Vec3::from(e.map(|x| super::poly::scaled_f64(x, i64::from(k))));
    let dist = crate::real::stable_norm(&es);
    let normal = dir.and_then(|d| unit(&(rot * d))).unwrap_or_else(fallback_normal);
    let mut q = clamp(&us, &hs);
    for i in 0..3 {
        if side[i] != 0 {
            q[i] = f64::from(side[i]) * hs[i];
        }
    }
    Some(finish(cs + rot * q, normal, rs - dist, k, false))
}

/// `u` clamped to the box `[−h, h]`.
fn clamp(u: &Vec3<f64>, h: &Vec3<f64>) -> Vec3<f64> {
    Vec3::new(u.x.max(-h.x).min(h.x), u.y.max(-h.y).min(h.y), u.z.max(-h.z).min(h.z))
}

/// `s · (a · (m − c)) − h`: lengths `[m, c, h]`, units `[a, s]`. Positive
/// when `m` lies beyond the face `s` of axis `a` at `h`.
pub(crate) fn face_excess<N: Ring>(l: &[N; 7], u: &[N; 4]) -> N {
    let d = sub3(at(l, 0), at(l, 3));
    u[3].mul(&dot3(at(u, 0), refs(&d))).sub(&l[6])
}

/// `Σ mask_i (s_i R̃_i · (m − c) − h_i)² − r²`: lengths `[m, c, h, r]`, units
/// `[R̃ (axes), s, mask]`.
fn outside_reach<N: Ring>(l: &[N; 10], u: &[N; 15]) -> N {
    let d = sub3(at(l, 0), at(l, 3));
    let term = |i: usize| {
        let x = u[9 + i].mul(&dot3(at(u, 3 * i), refs(&d))).sub(&l[6 + i]);
        u[12 + i].mul(&x.mul(&x))
    };
    term(0).add(&term(1)).add(&term(2)).sub(&l[9].mul(&l[9]))
}

/// `(h_i − |a_i · (m − c)|) − (h_j − |a_j · (m − c)|)`: lengths
/// `[m, c, h_i, h_j]`, units `[a_i, a_j]`.
fn gap_order<N: Ring>(l: &[N; 8], u: &[N; 6]) -> N {
    let d = sub3(at(l, 0), at(l, 3));
    let gi = l[6].sub(&dot3(at(u, 0), refs(&d)).abs());
    let gj = l[7].sub(&dot3(at(u, 3), refs(&d)).abs());
    gi.sub(&gj)
}

/// `h − |a · (m − c)|`: lengths `[m, c, h]`, units `[a]`.
fn gap<N: Ring>(l: &[N; 7], u: &[N; 3]) -> N {
    let d = sub3(at(l, 0), at(l, 3));
    l[6].sub(&dot3(at(u, 0), refs(&d)).abs())
}

/// `a · (m − c)`: lengths `[m, c]`, units `[a]`.
pub(crate) fn coord<N: Ring>(l: &[N; 6], u: &[N; 3]) -> N {
    let d = sub3(at(l, 0), at(l, 3));
    dot3(at(u, 0), refs(&d))
}

/// Where `m` lies against each slab of the box, exactly: `+1` beyond the face
/// `+i`, `−1` beyond `−i`, `0` within (faces included).
pub(crate) fn classify(m: P3, c: P3, h: P3, ax: &[f64; 9]) -> [i8; 3] {
    [0, 1, 2].map(|i| {
        let a = axis(ax, i);
        let l = [m[0], m[1], m[2], c[0], c[1], c[2], h[i]];
        if sign_of!(face_excess, l, [a[0], a[1], a[2], 1.0]) == Sign::Positive {
            1
        } else if sign_of!(face_excess, l, [a[0], a[1], a[2], -1.0]) == Sign::Positive {
            -1
        } else {
            0
        }
    })
}

/// The face nearest `m` from inside the closed box, exactly: its axis, its
/// side (`±1`) and whether another face is as near (the format's first face
/// in the order `+x, −x, +y, −y, +z, −z` is the one returned).
pub(crate) fn nearest_face(m: P3, c: P3, h: P3, ax: &[f64; 9]) -> (usize, i8, bool) {
    let order = |i: usize, j: usize| {
        let (a, b) = (axis(ax, i), axis(ax, j));
        sign_of!(gap_order, [m[0], m[1], m[2], c[0], c[1], c[2], h[i], h[j]], [a[0], a[1], a[2], b[0], b[1], b[2]])
    };
    let mut best = 0;
    for j in 1..3 {
        if order(j, best) == Sign::Negative {
            best = j;
        }
    }
    let mut tie = (0..3).any(|j| j != best && order(j, best) == Sign::Zero);
    let a = axis(ax, best);
    let side = match sign_of!(coord, [m[0], m[1], m[2], c[0], c[1], c[2]], a) {
        Sign::Negative => -1,
        Sign::Positive => 1,
        Sign::Zero => {
            tie = true;
            1
        }
    };
    (best, side, tie)
}

/// `h_i − |u_i|` of `m` (the distance to face `i` from inside) to `2^−40`.
pub(crate) fn face_gap(m: P3, c: P3, h: P3, ax: &[f64; 9], i: usize) -> Estimate {
    value_of!(gap, 1, [m[0], m[1], m[2], c[0], c[1], c[2], h[i]], axis(ax, i))
}
