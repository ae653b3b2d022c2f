//! The first hit of a segment on a capsule.

use super::sphere_capsule::closest_on_segment_lecture;
use super::{all_finite, scene_scale, unit, up, up1, wide3};
use crate::exact::points_equal;
use crate::intersect::{Intersection, SegmentHit};
use crate::real::{Real, Vec3};
use crate::shapes::{Capsule, Sphere};

/// The first hit of segment `s` on the solid capsule `c`, **the lecture's
/// form**: a start within `r` of the axis is hit at `t = 0`; otherwise the
/// least `t ∈ [0, 1]` of three textbook tests (Ericson, *Real-Time Collision
/// Detection*, §5.3.2 `IntersectRaySphere` against each end's ball, §5.3.7's
/// infinite cylinder about the axis, kept when the hit's axial coordinate
/// lies between the ends), each the smaller root `(−b − √(b² − ac))/a` of
/// its quadratic in plain arithmetic. The normal is the hit's direction from
/// its nearest axis point. A zero-length axis is a ball; non-finite numbers
/// answer no hit.
pub fn intersect_segment_capsule_lecture<T: Real>(s: &crate::shapes::Segment<T>, c: &Capsule<T>) -> Intersection<T> {
    let d = s.end - s.start;
    let r = c.radius;
    let q0 = closest_on_segment_lecture(&s.start, &c.start, &c.end);
    let out = s.start - q0;
    if out.norm_squared() <= r * r {
        let n = out.norm();
        let (normal, degenerate) = if n > T::zero() && n.finite() { (out / n, false) } else { (Vec3::z(), true) };
        return Intersection {
            hit: Some(SegmentHit { t: T::zero(), point: s.start, normal, barycentric: None }),
            parallel: false,
            degenerate: degenerate || s.start == s.end,
        };
    }
    let mut best: Option<T> = None;
    let mut keep = |t: T| {
        if t >= T::zero() && t <= T::one() && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    };
    for center in [c.start, c.end] {
        let m = s.start - center;
        let (a, b, cc) = (d.dot(&d), m.dot(&d), m.dot(&m) - r * r);
        let disc = b * b - a * cc;
        if a > T::zero() && disc >= T::zero() {
            keep((-b - disc.sqrt()) / a);
        }
    }
    let u = c.end - c.start;
    let w = s.start - c.start;
    let (uu, du, wu) = (u.dot(&u), d.dot(&u), w.dot(&u));
    let a = d.dot(&d) * uu - du * du;
    let b = w.dot(&d) * uu - wu * du;
    let cc = w.dot(&w) * uu - wu * wu - r * r * uu;
    let disc = b * b - a * cc;
    if a > T::zero() && disc >= T::zero() {
        let t = (-b - disc.sqrt()) / a;
        let axial = wu + t * du;
        if axial >= T::zero() && axial <= uu {
            keep(t);
        }
    }
    let Some(t) = best else { return Intersection::MISS };
    let point = s.start + d * t;
    let away = point - closest_on_segment_lecture(&point, &c.start, &c.end);
    let n = away.norm();
    if !(n > T::zero() && n.finite() && crate::real::finite3(&point)) {
        return Intersection::MISS;
    }
    Intersection::hit(SegmentHit { t, point, normal: away / n, barycentric: None })
}

/// The first hit of segment `s` on the solid capsule `c`, **robust form**.
///
/// Every decision is exact, taken from the robust contact forms: whether the
/// start is in the capsule (a point's contact with it,
/// [`super::contact_sphere_capsule`] at radius 0, whose normal — the start's
/// outward direction, or `+z` flagged on the axis — is the answer's), and
/// whether the segment hits at all (the segment as a capsule of radius 0
/// against `c`, [`super::contact_capsule_capsule`]: the axes within `r`).
/// The time is then computed in `f64` on the scene scaled to unit size: the
/// squared distance to the axis is a quadratic between the breakpoints where
/// the nearest axis point leaves an end (the referee's pieces), and the hit is
/// the first piece's smaller root, taken as `C/(−B + √(B² − AC))` so that
/// nothing cancels; a grazing segment that rounding puts a hair short of the
/// surface is answered at its closest approach. The normal is the hit's
/// direction from its nearest axis point. A zero-length segment is flagged
/// (a point in the capsule is hit at `t = 0`); non-finite input is a flagged
/// miss.
pub fn intersect_segment_capsule<T: Real>(s: &crate::shapes::Segment<T>, c: &Capsule<T>) -> Intersection<T> {
    let (p, q, a0, a1) = (wide3(&s.start), wide3(&s.end), wide3(&c.start), wide3(&c.end));
    let r = c.radius.wide();
    let lengths = [p[0], p[1], p[2], q[0], q[1], q[2], a0[0], a0[1], a0[2], a1[0], a1[1], a1[2], r];
    if !all_finite(&lengths) {
        return Intersection::DEGENERATE;
    }
    let zero = points_equal(p, q);
    let wide_capsule = |start: P3w, end: P3w, radius: f64| Capsule::<f64> {
        start: Vec3::new(start[0], start[1], start[2]),
        end: Vec3::new(end[0], end[1], end[2]),
        radius,
    };
    let axis = wide_capsule(a0, a1, r);
    let point = Sphere::<f64> { center: Vec3::new(p[0], p[1], p[2]), radius: 0.0 };
    if let Some(k) = super::contact_sphere_capsule(&point, &axis) {
        let hit = SegmentHit { t: T::zero(), point: s.start, normal: k.normal.map(T::of), barycentric: None };
        return Intersection { hit: Some(hit), parallel: false, degenerate: k.degenerate || zero };
    }
    if zero {
        return Intersection::DEGENERATE;
    }
    if super::contact_capsule_capsule(&wide_capsule(p, q, 0.0), &axis).is_none() {
        return Intersection::MISS;
    }
    let k = scene_scale(&lengths);
    let (p, q, a0, a1, r) = (up(p, k), up(q, k), up(a0, k), up(a1, k), up1(r, k));
    let d = q - p;
    let (t, g) = first_root(&p, &d, &a0, &a1, r);
    let point = crate::real::scale2v(&(p + d * t), -k);
    let normal = unit(&g).unwrap_or_else(Vec3::z);
    let point = point.map(T::of);
    if !crate::real::finite3(&point) {
        return Intersection::DEGENERATE;
    }
    Intersection::hit(SegmentHit { t: T::of(t.clamp(0.0, 1.0)), point, normal: normal.map(T::of), barycentric: None })
}

type P3w = [f64; 3];

/// The first `t` at which `p + t·d` is within `r` of the axis `[a0, a1]`
/// (known to exist), and `s(t) − foot(t)` there, in `f64`.
fn first_root(p: &Vec3<f64>, d: &Vec3<f64>, a0: &Vec3<f64>, a1: &Vec3<f64>, r: f64) -> (f64, Vec3<f64>) {
    let u = a1 - a0;
    let uu = u.dot(&u);
    let w = p - a0;
    // Pieces (lo, hi, g0, g1) with s(t) − foot(t) = g0 + t g1 on [lo, hi].
    let end = |e: &Vec3<f64>, lo: f64, hi: f64| (lo, hi, p - e, *d);
    let mut pieces = Vec::with_capacity(3);
    if uu == 0.0 {
        pieces.push(end(a0, 0.0, 1.0));
    } else {
        let (wu, du) = (w.dot(&u), d.dot(&u));
        let side = |lo: f64, hi: f64| (lo, hi, w - u * (wu / uu), d - u * (du / uu));
        if du == 0.0 {
            pieces.push(if wu < 0.0 {
                end(a0, 0.0, 1.0)
            } else if wu > uu {
                end(a1, 0.0, 1.0)
            } else {
                side(0.0, 1.0)
            });
        } else {
            let (ta, tb) = (-wu / du, (uu - wu) / du);
            let (first, t1, t2, last) = if du > 0.0 { (a0, ta, tb, a1) } else { (a1, tb, ta, a0) };
            let (c1, c2) = (t1.clamp(0.0, 1.0), t2.clamp(0.0, 1.0));
            if c1 > 0.0 {
                pieces.push(end(first, 0.0, c1));
            }
            if c2 > c1 {
                pieces.push(side(c1, c2));
            }
            if c2 < 1.0 {
                pieces.push(end(last, c2, 1.0));
            }
        }
    }
    let mut closest: Option<(f64, f64, Vec3<f64>)> = None;
    for (lo, hi, g0, g1) in pieces {
        let (a, b, c) = (g1.dot(&g1), g0.dot(&g1), g0.dot(&g0) - r * r);
        let tv = if a > 0.0 { (-b / a).clamp(lo, hi) } else { lo };
        let at = |t: f64| g0 + g1 * t;
        let fv = at(tv).norm_squared() - r * r;
        if fv <= 0.0 && a > 0.0 {
            let disc = (b * b - a * c).max(0.0);
            let den = -b + disc.sqrt();
            let t = if den > 0.0 { (c / den).clamp(lo, tv) } else { tv };
            return (t, at(t));
        }
        if closest.as_ref().is_none_or(|(f, _, _)| fv < *f) {
            closest = Some((fv, tv, at(tv)));
        }
    }
    closest.map_or((0.0, Vec3::z()), |(_, t, g)| (t, g))
}
