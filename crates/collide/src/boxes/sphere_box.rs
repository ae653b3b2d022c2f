//! Sphere–box contact.

use super::poly::{
    Ring, at, dot3, norm2, over_norm2, picked_axis, quaternion_axes, refs, scaled_f64, select, sign_of, sub3, value_of,
};
use super::{
    all_finite, fallback_normal, finish, quaternion_of, quaternion_units, scene_scale, stage, unit, up, up1, wide3,
};
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
/// every decision exact for the box of the quaternion's own rotation `R(q)`
/// (see [`crate::boxes`]; its axes taken as `M_i = ‖q‖² R(q) e_i`, quadratics
/// in `q`, and every comparison multiplied through by `n = ‖q‖² > 0`): whether
/// the centre is beyond each face (`±M_i · (m − c) − n h_i`), whether
/// `‖u − p‖ ≤ r` (its square against `r²`, times `n²`), which face is nearest
/// from inside and whether two tie. The distance to the box is formed from the
/// excesses `±u_i − h_i` (times `n`, divided by it after) to `2^−40`
/// relative, so the normal `R (u − p)/‖u − p‖` is right however close the
/// centre is to the box, at every scale. Points are computed with the rounded
/// matrix [`OrientedBox::rotation_matrix`].
///
/// **Degenerate input.** A centre in the closed box with two nearest faces
/// (on an edge or a corner, equidistant from two faces inside, or `u_i = 0`,
/// which ties the faces `+i` and `−i`, as at the centre of a flat box): the
/// first face in the order `+x, −x, +y, −y, +z, −z`, flagged. A non-finite
/// input is no contact.
///
/// A floating-point stage settles first what it is certain of
/// (`crate::boxes::stage`): no contact, the slab classification, the reach
/// test, the nearest face — each the exact decision; the values are computed
/// as without it.
pub fn contact_sphere_box<T: Real>(a: &Sphere<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    sphere_box(a, b, true)
}

/// [`contact_sphere_box`] without its floating-point stage: the exact
/// decisions alone, which the stage must agree with bit for bit.
#[cfg(test)]
pub(super) fn contact_sphere_box_unstaged<T: Real>(a: &Sphere<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    sphere_box(a, b, false)
}

fn sphere_box<T: Real>(a: &Sphere<T>, b: &OrientedBox<T>, staged: bool) -> Option<Contact<T>> {
    let qt = quaternion_of(b)?;
    let (m, c) = (wide3(&a.center), wide3(&b.center));
    let h = wide3(&b.half_extents).map(f64::abs);
    let r = a.radius.wide();
    let lengths = [m[0], m[1], m[2], c[0], c[1], c[2], h[0], h[1], h[2], r];
    if !all_finite(&lengths) {
        return None;
    }
    let settled = if staged { stage::sphere_box(&qt, &lengths) } else { stage::SphereBox::default() };
    if settled.apart {
        return None;
    }
    let side = settled.side.unwrap_or_else(|| classify_with(m, c, h, &qt, settled.sides));
    let k = scene_scale(&lengths);
    let rot = b.rotation_matrix().map(|x| x.wide());
    let (ms, cs, hs, rs) = (up(m, k), up(c, k), up(h, k), up1(r, k));
    let us = rot.transpose() * (ms - cs);
    if side == [0; 3] {
        let (i, s, tie) = settled.nearest.unwrap_or_else(|| nearest_face_with(m, c, h, &qt, &settled));
        let gap = scaled_f64(over_norm2(face_gap(m, c, h, &qt, i), &qt), i64::from(k));
        let mut q = clamp(&us, &hs);
        q[i] = f64::from(s) * hs[i];
        let normal = unit(&(rot.column(i) * f64::from(s))).unwrap_or_else(fallback_normal);
        return Some(finish(cs + rot * q, normal, rs + gap, k, tie));
    }
    let s = side.map(f64::from);
    let mask = side.map(|x| f64::from(x.abs()));
    let units = [qt[0], qt[1], qt[2], qt[3], s[0], s[1], s[2], mask[0], mask[1], mask[2]];
    if !settled.within && sign_of!(outside_reach, lengths, units) == Sign::Positive {
        return None;
    }
    // The excess beyond each face the centre is outside of, signed: u − p
    // (times n).
    let e: [Estimate; 3] = [0, 1, 2].map(|i| {
        if side[i] == 0 {
            Estimate::ZERO
        } else {
            let u = quaternion_units(&qt, i);
            let x = value_of!(face_excess, 1, [m[0], m[1], m[2], c[0], c[1], c[2], h[i]], {
                [u[0], u[1], u[2], u[3], u[4], u[5], u[6], s[i]]
            });
            if side[i] < 0 { Estimate { sign: -x.sign, ..x } } else { x }
        }
    });
    let dir = Estimate::unit_vector(e).map(|d| Vec3::new(d[0], d[1], d[2]));
    let es = Vec3::from(e.map(|x| scaled_f64(over_norm2(x, &qt), i64::from(k))));
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

/// `s · (M · (m − c)) − n h` (`M` the picked axis of `‖q‖² R(q)`,
/// `n = ‖q‖²`): lengths `[m, c, h]`, units `[q, e_i, s]`. Positive when `m`
/// lies beyond the face `s` of axis `i` at `h`.
fn face_excess<N: Ring>(l: &[N; 7], u: &[N; 8]) -> N {
    let (a, n) = picked_axis(u);
    let d = sub3(at(l, 0), at(l, 3));
    u[7].mul(&dot3(refs(&a), refs(&d))).sub(&n.mul(&l[6]))
}

/// `Σ mask_i (s_i M_i · (m − c) − n h_i)² − n² r²` (`M_i` the columns of
/// `‖q‖² R(q)`, `n = ‖q‖²`): lengths `[m, c, h, r]`, units `[q, s, mask]`.
fn outside_reach<N: Ring>(l: &[N; 10], u: &[N; 10]) -> N {
    let q = [&u[0], &u[1], &u[2], &u[3]];
    let (ax, n) = (quaternion_axes(q), norm2(q));
    let d = sub3(at(l, 0), at(l, 3));
    let term = |i: usize| {
        let x = u[4 + i].mul(&dot3(refs(&ax[i]), refs(&d))).sub(&n.mul(&l[6 + i]));
        u[7 + i].mul(&x.mul(&x))
    };
    let nr = n.mul(&l[9]);
    term(0).add(&term(1)).add(&term(2)).sub(&nr.mul(&nr))
}

/// `(n h_i − |M_i · (m − c)|) − (n h_j − |M_j · (m − c)|)`: lengths
/// `[m, c, h_i, h_j]`, units `[q, e_i, e_j]`.
fn gap_order<N: Ring>(l: &[N; 8], u: &[N; 10]) -> N {
    let q = [&u[0], &u[1], &u[2], &u[3]];
    let (ax, n) = (quaternion_axes(q), norm2(q));
    let (ai, aj) = (select(&u[4..7], &ax), select(&u[7..10], &ax));
    let d = sub3(at(l, 0), at(l, 3));
    let gi = n.mul(&l[6]).sub(&dot3(refs(&ai), refs(&d)).abs());
    let gj = n.mul(&l[7]).sub(&dot3(refs(&aj), refs(&d)).abs());
    gi.sub(&gj)
}

/// `n h − |M · (m − c)|`: lengths `[m, c, h]`, units `[q, e_i]`.
fn gap<N: Ring>(l: &[N; 7], u: &[N; 7]) -> N {
    let (a, n) = picked_axis(u);
    let d = sub3(at(l, 0), at(l, 3));
    n.mul(&l[6]).sub(&dot3(refs(&a), refs(&d)).abs())
}

/// `M · (m − c)` (`‖q‖²` times the coordinate along axis `i`): lengths
/// `[m, c]`, units `[q, e_i]`.
pub(crate) fn coord<N: Ring>(l: &[N; 6], u: &[N; 7]) -> N {
    let (a, _) = picked_axis(u);
    let d = sub3(at(l, 0), at(l, 3));
    dot3(refs(&a), refs(&d))
}

/// Where `m` lies against each slab of the box of quaternion `q`, exactly:
/// `+1` beyond the face `+i`, `−1` beyond `−i`, `0` within (faces included).
pub(crate) fn classify(m: P3, c: P3, h: P3, q: &[f64; 4]) -> [i8; 3] {
    classify_with(m, c, h, q, [None; 3])
}

/// [`classify`], with the axes already settled (by the floating-point stage,
/// exactly) taken as given.
fn classify_with(m: P3, c: P3, h: P3, q: &[f64; 4], known: [Option<i8>; 3]) -> [i8; 3] {
    [0, 1, 2].map(|i| {
        if let Some(s) = known[i] {
            return s;
        }
        let l = [m[0], m[1], m[2], c[0], c[1], c[2], h[i]];
        let u = quaternion_units(q, i);
        let beyond = |s: f64| sign_of!(face_excess, l, [u[0], u[1], u[2], u[3], u[4], u[5], u[6], s]) == Sign::Positive;
        if beyond(1.0) {
            1
        } else if beyond(-1.0) {
            -1
        } else {
            0
        }
    })
}

/// The face nearest `m` from inside the closed box of quaternion `q`, exactly:
/// its axis, its side (`±1`) and whether another face is as near (the
/// format's first face in the order `+x, −x, +y, −y, +z, −z` is the one
/// returned).
pub(crate) fn nearest_face(m: P3, c: P3, h: P3, q: &[f64; 4]) -> (usize, i8, bool) {
    nearest_face_with(m, c, h, q, &stage::SphereBox::default())
}

/// The exact sign as the stage states it (`Equal` is never certified).
fn sign_of_order(o: std::cmp::Ordering) -> Sign {
    match o {
        std::cmp::Ordering::Greater => Sign::Positive,
        std::cmp::Ordering::Less => Sign::Negative,
        std::cmp::Ordering::Equal => Sign::Zero,
    }
}

/// [`nearest_face`], with the orders of the gaps and the signs of the
/// coordinates the floating-point stage settled (exactly) taken as given.
fn nearest_face_with(m: P3, c: P3, h: P3, q: &[f64; 4], settled: &stage::SphereBox) -> (usize, i8, bool) {
    let order = |i: usize, j: usize| {
        if let Some(o) = settled.orders[i][j] {
            return sign_of_order(o);
        }
        let mut u = [q[0], q[1], q[2], q[3], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        u[4 + i] = 1.0;
        u[7 + j] = 1.0;
        sign_of!(gap_order, [m[0], m[1], m[2], c[0], c[1], c[2], h[i], h[j]], u)
    };
    let mut best = 0;
    for j in 1..3 {
        if order(j, best) == Sign::Negative {
            best = j;
        }
    }
    let mut tie = (0..3).any(|j| j != best && order(j, best) == Sign::Zero);
    let coord_sign = settled.coords[best].map_or_else(
        || sign_of!(coord, [m[0], m[1], m[2], c[0], c[1], c[2]], quaternion_units(q, best)),
        sign_of_order,
    );
    let side = match coord_sign {
        Sign::Negative => -1,
        Sign::Positive => 1,
        Sign::Zero => {
            tie = true;
            1
        }
    };
    (best, side, tie)
}

/// `‖q‖² (h_i − |u_i|)` of `m` (the distance to face `i` from inside, times
/// `‖q‖²`) to `2^−40`.
fn face_gap(m: P3, c: P3, h: P3, q: &[f64; 4], i: usize) -> Estimate {
    value_of!(gap, 1, [m[0], m[1], m[2], c[0], c[1], c[2], h[i]], quaternion_units(q, i))
}
