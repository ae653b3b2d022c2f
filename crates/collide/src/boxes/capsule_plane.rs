//! Capsule–plane contact.

use super::poly::{Ring, at, dot3, over_norm, sign_of, value_of};
use super::{all_finite, finish, scene_scale, up, up1, wide3};
use crate::contact::{Contact, normal_parts};
use crate::exact::{Sign, dot_diff};
use crate::real::{Real, Vec3};
use crate::shapes::{Capsule, Plane};

/// Contact between a capsule `a` and the solid half-space `n · x ≤ d` bounded
/// by the plane `b`, **the lecture's form**: the sphere–plane formulas at the
/// axis end `e` with the smaller signed distance `s = n̂ · e − d/‖n‖`
/// (`n̂ = n/‖n‖`, the plain norm):
///
/// ```text
/// contact when s ≤ r;  depth = r − s,  normal = n̂,  point = e − s n̂
/// ```
///
/// Two ends at the same computed distance take the start. Never flagged.
pub fn contact_capsule_plane_lecture<T: Real>(a: &Capsule<T>, b: &Plane<T>) -> Option<Contact<T>> {
    super::lecture_finite(contact_capsule_plane_lecture_raw(a, b))
}

fn contact_capsule_plane_lecture_raw<T: Real>(a: &Capsule<T>, b: &Plane<T>) -> Option<Contact<T>> {
    let len = b.normal.norm();
    if !(len > T::zero()) || !len.finite() {
        return None;
    }
    let n = b.normal / len;
    let off = b.offset / len;
    let (s0, s1) = (n.dot(&a.start) - off, n.dot(&a.end) - off);
    let (e, s) = if s1 < s0 { (a.end, s1) } else { (a.start, s0) };
    if !(s <= a.radius) {
        return None;
    }
    Some(Contact { point: e - n * s, normal: n, depth: a.radius - s, degenerate: false })
}

/// Contact between a capsule `a` and the solid half-space bounded by plane
/// `b`, **robust form**: the lowest end `e` by the exact sign of
/// `n · (end − start)` (an axis parallel to the plane — a zero sign — answers at
/// the start's projection, one point of the region), and contact decided
/// exactly: `n · e − d ≤ 0`, or else `(n · e − d)² ≤ r² (n · n)`. The
/// distance `(n · e − d)/‖n‖` is formed to `2^−40` and divided on its
/// exponent: accurate at every scale.
///
/// **Degenerate input.** A zero or non-finite normal, or any non-finite
/// input, is no contact. Never flagged otherwise, except for a value beyond
/// the type's range.
pub fn contact_capsule_plane<T: Real>(a: &Capsule<T>, b: &Plane<T>) -> Option<Contact<T>> {
    let (p0, p1, n) = (wide3(&a.start), wide3(&a.end), wide3(&b.normal));
    let (r, d) = (a.radius.wide(), b.offset.wide());
    if !all_finite(&[p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], r, d]) {
        return None;
    }
    let (m, l, nhat) = normal_parts(&Vec3::new(n[0], n[1], n[2]))?;
    let e = if dot_diff(n, p0, p1) == Sign::Negative { p1 } else { p0 };
    let g = value_of!(plane_gap, 1, [e[0], e[1], e[2], d], n);
    if g.sign == Sign::Positive && sign_of!(plane_reach, [e[0], e[1], e[2], d, r], n) == Sign::Positive {
        return None;
    }
    let k = scene_scale(&[e[0], e[1], e[2], d, r]);
    let s = over_norm(g, m, l, i64::from(k));
    Some(finish(up(e, k) - nhat * s, nhat, up1(r, k) - s, k, false))
}

/// `n · e − d`: lengths `[e, d]`, units `[n]`.
fn plane_gap<N: Ring>(l: &[N; 4], u: &[N; 3]) -> N {
    dot3(at(u, 0), at(l, 0)).sub(&l[3])
}

/// `(n · e − d)² − r² (n · n)`: lengths `[e, d, r]`, units `[n]`.
fn plane_reach<N: Ring>(l: &[N; 5], u: &[N; 3]) -> N {
    let g = dot3(at(u, 0), at(l, 0)).sub(&l[3]);
    g.mul(&g).sub(&l[4].mul(&l[4]).mul(&dot3(at(u, 0), at(u, 0))))
}
