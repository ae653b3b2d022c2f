//! Time of impact of a sphere moving linearly against an oriented box,
//! exactly, and its margin.
//!
//! **How it is exact.** The box's rotation is exact (its quaternion's matrix
//! has rational entries, [`super::boxes`]), so in the box's frame the
//! sphere's centre moves on the line `u(t) = u0 + t w` with rational `u0` and
//! `w`, and the box is the axis-aligned `|uᵢ| ≤ hᵢ`. Touching a face is a
//! linear equation in `t`, an edge a quadratic (the distance across the edge's
//! direction) and a corner a quadratic: each candidate time is `α + β√D` with
//! rationals, compared exactly as [`super::toi`] compares them, and the
//! contact point and normal at the winning time are affine in the same `√D`,
//! rotated back by the exact `R` and correctly rounded once.

use std::cmp::Ordering;

use super::boxes::{BOX_B, ExactBox, check_box, contact_sphere_box, exact_box};
use super::error::RefereeError;
use super::exact::{Q, V3, dot, sub};
use super::toi::{
    Hit, Moving, Surd, along, at_zero, check_moving, dist2_segments, finish, gap_margin, moving, path_bounds,
    point_root, staged,
};
use crate::geom::{Capsule, OrientedBox, P3, Sphere, ToiAnswer};
use dashu::base::Abs;

/// `x` with component `i` replaced by `y`.
fn with(x: &V3, i: usize, y: Q) -> V3 {
    let mut out = x.clone();
    out[i] = y;
    out
}

/// The box's corner or edge offset `sᵢ hᵢ` per axis (`signs[i]` true for
/// `+`), component `skip` zero when given.
fn offset(h: &V3, signs: [bool; 3], skip: Option<usize>) -> V3 {
    std::array::from_fn(|i| match (Some(i) == skip, signs[i]) {
        (true, _) => Q::ZERO,
        (false, true) => h[i].clone(),
        (false, false) => -h[i].clone(),
    })
}

/// The eight sign patterns of a box's corners, in the order `−−−, +−−, −+−, …`.
fn corners() -> impl Iterator<Item = [bool; 3]> {
    (0..8u8).map(|k| [k & 1 != 0, k & 2 != 0, k & 4 != 0])
}

/// Whether `lo ≤ k + m·t ≤ hi` at the candidate time `t`, exactly.
fn within(t: &Surd, k: &Q, m: &Q, h: &Q) -> bool {
    t.affine(&(k - h), m).sign() != Ordering::Greater && t.affine(&(k + h), m).sign() != Ordering::Less
}

/// The earliest candidate of the box `bx` for the moving sphere `s`
/// (relative velocity `v`), known to be apart from it at `t = 0`.
///
/// Candidates, in the box's frame (`u0`, `w` the centre and its velocity
/// there): each face `uᵢ = ±(hᵢ + r)` (linear), kept when the other two
/// coordinates lie in the face; each edge along axis `i` at `(±hⱼ, ±hₖ)`, the
/// smaller root of `‖(u(t) − e)⊥ᵢ‖ = r`, kept when `|uᵢ(t)| ≤ hᵢ`; each corner
/// `e`, the smaller root of `‖u(t) − e‖ = r`. At every kept candidate the
/// distance to the box is at most `r` (it is `r` to that feature), and the
/// first contact is a candidate (its closest point lies on some feature), so
/// the first contact is their minimum; at that time the closest point is
/// unique, so candidates that tie there agree on the point and the normal.
fn first_contact(bx: &ExactBox, s: &Moving, v: &V3) -> Option<Hit> {
    let u0 = bx.to_local(&s.c);
    let w = bx.dir_to_local(v);
    let (h, r) = (&bx.h, &s.r);
    let unit_r = (!r.is_zero()).then(|| Q::ONE / r);
    let mut best: Option<Hit> = None;
    // A candidate at time `t` with the point `pk + t pm` and the normal
    // `nk + t nm` in the box's frame (no normal for a zero radius), moved to
    // the world: `c + R p + t vb` and `R n`.
    let mut consider = |t: Surd, pk: &V3, pm: &V3, normal: Option<(V3, V3)>| {
        if !t.in_interval(&s.t_max) || best.as_ref().is_some_and(|b| t.cmp(&b.t) != Ordering::Less) {
            return;
        }
        let point = along(&t, &bx.to_world(pk), &super::exact::add(&bx.dir_to_world(pm), &s.vb));
        let normal = normal.map(|(nk, nm)| along(&t, &bx.dir_to_world(&nk), &bx.dir_to_world(&nm)));
        best = Some(Hit { t, point, normal });
    };
    let zero: V3 = [Q::ZERO, Q::ZERO, Q::ZERO];
    // Faces: uᵢ(t) = ±(hᵢ + r), the point u(t) with uᵢ = ±hᵢ, the normal ±eᵢ.
    for i in 0..3 {
        if w[i].is_zero() {
            continue;
        }
        for plus in [true, false] {
            let sign = if plus { Q::ONE } else { Q::NEG_ONE };
            let t = (&sign * (&h[i] + r) - &u0[i]) / &w[i];
            let inside = (0..3).filter(|&j| j != i).all(|j| (&u0[j] + &t * &w[j]).abs() <= h[j]);
            if !inside {
                continue;
            }
            let t = Surd::rational(t);
            let normal = unit_r.as_ref().map(|_| (with(&zero, i, sign.clone()), zero.clone()));
            consider(t, &with(&u0, i, &sign * &h[i]), &with(&w, i, Q::ZERO), normal);
        }
    }
    // Edges along axis i: the distance across axis i from (±hⱼ, ±hₖ).
    for i in 0..3 {
        for signs in corners().filter(|s| !s[i]) {
            let e = offset(h, signs, Some(i));
            let w0 = with(&sub(&u0, &e), i, Q::ZERO);
            let wi = with(&w, i, Q::ZERO);
            let Some(t) = point_root(&w0, &wi, r) else { continue };
            if !within(&t, &u0[i], &w[i], &h[i]) {
                continue;
            }
            let mut pm = zero.clone();
            pm[i] = w[i].clone();
            let normal =
                unit_r.as_ref().map(|k| (std::array::from_fn(|j| &w0[j] * k), std::array::from_fn(|j| &wi[j] * k)));
            consider(t, &with(&e, i, u0[i].clone()), &pm, normal);
        }
    }
    // Corners: ‖u(t) − e‖ = r, the point e.
    for signs in corners() {
        let e = offset(h, signs, None);
        let w0 = sub(&u0, &e);
        let Some(t) = point_root(&w0, &w, r) else { continue };
        let normal = unit_r.as_ref().map(|k| (std::array::from_fn(|j| &w0[j] * k), std::array::from_fn(|j| &w[j] * k)));
        consider(t, &e, &zero, normal);
    }
    best
}

/// Whether the floating-point stage certifies that the centre's whole path
/// stays further than `r` from the box: the capsule from the centre to its
/// place at `t_max` (in `b`'s frame, [`super::toi::path_bounds`]'s far end),
/// its radius grown by that end's error bound and rounded up by a relative
/// `2ε`, certainly apart from the box ([`super::boxes_fast::capsule_box_apart`]).
fn path_apart(a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> bool {
    let Some(path) = path_bounds(&a.center, va, vb, t_max) else { return false };
    let radius = (a.radius + path.end_error) * (1.0 + 2.0 * f64::EPSILON);
    radius.is_finite() && super::boxes_fast::capsule_box_apart(&Capsule { start: a.center, end: path.end, radius }, b)
}

/// Time of impact of sphere `a` (centre `c`, radius `r`, velocity `va`) and
/// the solid oriented box `b` (moving with `vb`, its rotation fixed) over
/// `[0, t_max]`.
///
/// **Definition** (`docs/FORMAT.md`, toi): the first `t` at which
/// `dist(c + t va, b moved by t vb) = r`; in the box's frame, the least of the
/// candidates of its six faces (linear), twelve edges and eight corners
/// (quadratics), each kept when its contact lies on the feature (see
/// `first_contact`). The contact: the feature's point moved by `t vb`, on
/// `b`'s surface, and the normal from it toward the centre (a face's own
/// normal). Already in contact at `t = 0` (touching counts, a centre inside
/// included): `t = 0` and [`contact_sphere_box`]'s answer. Source: Ericson
/// §5.5.7 (a moving sphere against a box by the features of the rounded box),
/// evaluated exactly.
///
/// **Degenerate input.** A flat box (a zero half-extent) is its rectangle,
/// segment or point, answered exactly and not flagged. At `t = 0`, the static
/// answer's flags. A sphere of zero radius meets the box at a point with no
/// direction: normal `−v/‖v‖`, flagged.
pub fn toi_sphere_box(a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> Result<ToiAnswer, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_box(b, BOX_B)?;
    let at0 = contact_sphere_box(a, b)?;
    if at0.contact.is_some() {
        return Ok(at_zero(at0));
    }
    if staged(|| path_apart(a, va, b, vb, t_max).then_some(())).is_some() {
        return Ok(ToiAnswer::default());
    }
    let s = moving(a, va, vb, t_max)?;
    let bx = exact_box(b, BOX_B)?;
    let v = sub(&s.va, &s.vb);
    Ok(match first_contact(&bx, &s, &v) {
        Some(h) => finish(&h, &v),
        None => ToiAnswer::default(),
    })
}

/// The squared distance from the segment `p0 → p1` to the axis-aligned box
/// `|uᵢ| ≤ hᵢ`, exactly: 0 when they meet; otherwise the closest pair of two
/// disjoint convex polytopes has a vertex of one or an edge against an edge,
/// so it is the least of the ends' distances to the box (their clamps) and the
/// segment's distances to the box's twelve edges.
fn dist2_segment_box(bx: &ExactBox, p0: &V3, p1: &V3) -> Q {
    if bx.entry(p0, p1).is_some() {
        return Q::ZERO;
    }
    let to_box = |p: &V3| {
        let d = sub(p, &bx.clamp(p));
        dot(&d, &d)
    };
    let mut best = to_box(p0);
    let mut keep = |x: Q| {
        if x < best {
            best = x;
        }
    };
    keep(to_box(p1));
    for i in 0..3 {
        for signs in corners().filter(|s| !s[i]) {
            let e = offset(&bx.h, signs, Some(i));
            keep(dist2_segments(p0, p1, &with(&e, i, -&bx.h[i]), &with(&e, i, bx.h[i].clone())));
        }
    }
    best
}

/// The signed closest-approach gap behind [`toi_sphere_box`]'s decision,
/// `r − dist(path, b)` with the path the centre's segment `c → c + t_max v` in
/// `b`'s frame, correctly rounded: ≥ 0 exactly when there is an impact.
pub fn toi_margin_sphere_box(a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> Result<f64, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_box(b, BOX_B)?;
    let s = moving(a, va, vb, t_max)?;
    let bx = exact_box(b, BOX_B)?;
    let v = sub(&s.va, &s.vb);
    let p0 = bx.to_local(&s.c);
    let w = bx.dir_to_local(&v);
    let p1: V3 = std::array::from_fn(|i| &p0[i] + &s.t_max * &w[i]);
    Ok(gap_margin(&s.r, dist2_segment_box(&bx, &p0, &p1)))
}

#[cfg(test)]
#[path = "toi_box_tests.rs"]
mod tests;
