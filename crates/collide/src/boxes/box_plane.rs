//! Box–plane contact.

use super::poly::{
    Ring, at, dot3, norm2, over_norm, over_norm2, picked_axis, quaternion_axes, refs, sign_of, value_of,
};
use super::{all_finite, finish, quaternion_of, quaternion_units, scene_scale, up, wide3};
use crate::contact::{Contact, normal_parts};
use crate::exact::Sign;
use crate::real::{Real, Vec3};
use crate::shapes::{OrientedBox, Plane};

/// Contact between a box `a` and the solid half-space `n · x ≤ d` bounded by
/// the plane `b`, **the lecture's form** (Ericson, *Real-Time Collision
/// Detection*, §5.2.3, `TestOBBPlane`): with `R` from
/// [`OrientedBox::rotation_matrix_lecture`] and `n̂ = n/‖n‖`,
///
/// ```text
/// ρ = Σ h_i |n̂ · R_i|             (the box's reach along n̂)
/// s = n̂ · center − d/‖n‖           (the centre's signed distance)
/// contact when s ≤ ρ;  depth = ρ − s,  normal = n̂,
/// lowest vertex v = center − Σ sign(n̂ · R_i) h_i R_i,  point = v + depth n̂
/// ```
///
/// The plain norm of `n` (it underflows below about `1e-154` in `f64`, then no
/// contact is found: the lecture's form failing) and rounded comparisons. Never
/// flagged: the normal is always `n̂`.
pub fn contact_box_plane_lecture<T: Real>(a: &OrientedBox<T>, b: &Plane<T>) -> Option<Contact<T>> {
    super::lecture_finite(contact_box_plane_lecture_raw(a, b))
}

fn contact_box_plane_lecture_raw<T: Real>(a: &OrientedBox<T>, b: &Plane<T>) -> Option<Contact<T>> {
    let r = a.rotation_matrix_lecture();
    let len = b.normal.norm();
    if !(len > T::zero()) || !len.finite() {
        return None;
    }
    let n = b.normal / len;
    let h = a.half_extents;
    let mut reach = T::zero();
    let mut v = a.center;
    for i in 0..3 {
        let along = n.dot(&r.column(i));
        reach += h[i] * along.abs();
        if along > T::zero() {
            v -= r.column(i) * h[i];
        } else if along < T::zero() {
            v += r.column(i) * h[i];
        }
    }
    let s = n.dot(&a.center) - b.offset / len;
    if !(s <= reach) {
        return None;
    }
    let depth = reach - s;
    Some(Contact { point: v + n * depth, normal: n, depth, degenerate: false })
}

/// Contact between a box `a` and the solid half-space bounded by plane `b`,
/// **robust form**: the lecture's formulas with the decision exact for the box
/// of the quaternion's own rotation `R(q)` (see [`crate::boxes`]; its axes
/// taken as `M_i = ‖q‖² R(q) e_i`, quadratics in `q`): contact when
/// `‖q‖² (n · center − d) − Σ h_i |n · M_i| ≤ 0` (`‖q‖²` times the lowest
/// vertex's `n · v − d`), the sign of each `n · M_i` (which way the lowest
/// vertex lies) exact too. That value is formed to `2^−40`, divided by `‖q‖²`
/// and by `‖n‖` on its exponent, so the depth is accurate at every scale. The
/// vertex itself is placed with the rounded matrix
/// [`OrientedBox::rotation_matrix`]. A box with an axis exactly perpendicular
/// to `n` has a lowest edge or face: its point is the middle of that edge's or
/// face's projection, one point of the contact region (the format takes any).
///
/// **Degenerate input.** A zero or non-finite normal, or any non-finite
/// input, is no contact. Never flagged otherwise (the normal is unique),
/// except for a value beyond the type's range.
pub fn contact_box_plane<T: Real>(a: &OrientedBox<T>, b: &Plane<T>) -> Option<Contact<T>> {
    let qt = quaternion_of(a)?;
    let (c, n) = (wide3(&a.center), wide3(&b.normal));
    let h = wide3(&a.half_extents).map(f64::abs);
    let d = b.offset.wide();
    if !all_finite(&[c[0], c[1], c[2], h[0], h[1], h[2], d]) {
        return None;
    }
    let (m, l, nhat) = normal_parts(&Vec3::new(n[0], n[1], n[2]))?;
    let lengths = [c[0], c[1], c[2], h[0], h[1], h[2], d];
    let units = [n[0], n[1], n[2], qt[0], qt[1], qt[2], qt[3]];
    let g = value_of!(lowest_gap, 1, lengths, units);
    if g.sign == Sign::Positive {
        return None;
    }
    let k = scene_scale(&lengths);
    let rot = a.rotation_matrix().map(|x| x.wide());
    let (cs, hs) = (up(c, k), up(h, k));
    let mut v = cs;
    for i in 0..3 {
        match sign_of!(lean, n, quaternion_units(&qt, i)) {
            Sign::Positive => v -= rot.column(i) * hs[i],
            Sign::Negative => v += rot.column(i) * hs[i],
            Sign::Zero => {}
        }
    }
    let depth = -over_norm(over_norm2(g, &qt), m, l, i64::from(k));
    Some(finish(v + nhat * depth, nhat, depth, k, false))
}

/// `‖q‖² (n · c − d) − Σ h_i |n · M_i|` (`M_i` the columns of `‖q‖² R(q)`;
/// `‖q‖²` times the lowest vertex's `n · v − d`): lengths `[c, h, d]`, units
/// `[n, q]`.
fn lowest_gap<N: Ring>(l: &[N; 7], u: &[N; 7]) -> N {
    let n = at(u, 0);
    let q = [&u[3], &u[4], &u[5], &u[6]];
    let (ax, n2) = (quaternion_axes(q), norm2(q));
    let reach = |i: usize| l[3 + i].mul(&dot3(n, refs(&ax[i])).abs());
    n2.mul(&dot3(n, at(l, 0)).sub(&l[6])).sub(&reach(0)).sub(&reach(1)).sub(&reach(2))
}

/// `n · M` (`M` the picked axis of `‖q‖² R(q)`): which way the axis leans
/// against the plane's normal. Lengths `[n]`, units `[q, e_i]`.
fn lean<N: Ring>(l: &[N; 3], u: &[N; 7]) -> N {
    let (a, _) = picked_axis(u);
    dot3(refs(l), refs(&a))
}
