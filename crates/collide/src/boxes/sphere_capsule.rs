//! Sphere–capsule contact, and the exact point–segment tests capsules share.

use super::poly::{Ring, at, cross3, dot3, refs, scaled_f64, sign_of, sub3, value_of};
use super::{all_finite, fallback_normal, finish, scene_scale, stage, unit, up, up1, wide3};
use crate::contact::Contact;
use crate::exact::{Estimate, P3, Sign, collinear, points_equal};
use crate::real::{Real, Vec3};
use crate::shapes::{Capsule, Sphere};

/// Contact between a sphere `a` and a capsule `b`, **the lecture's form**: `q`
/// the point of `b`'s axis nearest the centre `M` (Ericson, *Real-Time
/// Collision Detection*, §5.1.2, the form without a division until it is
/// needed: `t = (M − A) · (B − A)`, clamped against 0 and `‖B − A‖²`), then
/// the sphere–sphere formulas against a ball of radius `r_b` at `q`:
///
/// ```text
/// contact when ‖M − q‖ ≤ r_a + r_b;  n = (M − q)/‖M − q‖,
/// point = q + r_b n,  depth = r_a + r_b − ‖M − q‖
/// ```
///
/// Plain norms: a distance below about `1e-154` (`f64`) underflows to 0 and
/// takes the fallback normal `+z` (flagged, as a centre on the axis), one above
/// `1e154` overflows and the contact is missed.
pub fn contact_sphere_capsule_lecture<T: Real>(a: &Sphere<T>, b: &Capsule<T>) -> Option<Contact<T>> {
    super::lecture_finite(contact_sphere_capsule_lecture_raw(a, b))
}

fn contact_sphere_capsule_lecture_raw<T: Real>(a: &Sphere<T>, b: &Capsule<T>) -> Option<Contact<T>> {
    let q = closest_on_segment_lecture(&a.center, &b.start, &b.end);
    touch_lecture(&a.center, a.radius, &q, b.radius)
}

/// Ericson's `ClosestPtPointSegment` (§5.1.2), as written.
pub(crate) fn closest_on_segment_lecture<T: Real>(m: &Vec3<T>, a: &Vec3<T>, b: &Vec3<T>) -> Vec3<T> {
    let ab = b - a;
    let t = (m - a).dot(&ab);
    if t <= T::zero() {
        return *a;
    }
    let denom = ab.dot(&ab);
    if t >= denom { *b } else { a + ab * (t / denom) }
}

/// The lecture's contact of a ball `(p, ra)` with a ball `(q, rb)` on `b`'s
/// side: the sphere–sphere formulas.
pub(crate) fn touch_lecture<T: Real>(p: &Vec3<T>, ra: T, q: &Vec3<T>, rb: T) -> Option<Contact<T>> {
    let v = p - q;
    let dist = v.norm();
    let reach = ra + rb;
    if dist.is_nan() || dist > reach {
        return None;
    }
    let (normal, degenerate) =
        if dist > T::zero() && dist.finite() { (v / dist, false) } else { (fallback_normal(), true) };
    Some(Contact { point: q + normal * rb, normal, depth: reach - dist, degenerate })
}

/// Contact between a sphere `a` and a capsule `b`, **robust form**: the
/// format's formulas with every decision exact — where the foot of `M` falls
/// (before the start, after the end or between, from the signs of
/// `(M − A)·(B − A)` and `(M − B)·(A − B)`), whether it is within
/// `r_a + r_b` (`‖M − E‖²` against `(r_a + r_b)²` at an end,
/// `‖(M − A) × (B − A)‖²` against `(r_a + r_b)² ‖B − A‖²` between), and whether
/// `M` is on the axis. Between the ends the normal is the direction of
/// `(B − A) × ((M − A) × (B − A))` formed to `2^−40`, so it is right however
/// near the axis the centre is; values are computed as described in
/// [`crate::boxes`].
///
/// **Degenerate input.** A centre on the axis: normal `+z`
/// ([`crate::contact::CONCENTRIC_FALLBACK_NORMAL`]), point `q + r_b (0, 0, 1)`,
/// depth `r_a + r_b`, flagged. A zero-length axis is a sphere. A non-finite
/// input is no contact.
pub fn contact_sphere_capsule<T: Real>(a: &Sphere<T>, b: &Capsule<T>) -> Option<Contact<T>> {
    let (m, p0, p1) = (wide3(&a.center), wide3(&b.start), wide3(&b.end));
    let (ra, rb) = (a.radius.wide(), b.radius.wide());
    let lengths = [m[0], m[1], m[2], p0[0], p0[1], p0[2], p1[0], p1[1], p1[2], ra, rb];
    if !all_finite(&lengths) {
        return None;
    }
    let foot = foot_of(m, p0, p1);
    let (contact, on_axis) = reach_test(m, p0, p1, ra, rb, foot);
    if !contact {
        return None;
    }
    let k = scene_scale(&lengths);
    let near = foot_values(m, p0, p1, foot, k, on_axis);
    let (ras, rbs) = (up1(ra, k), up1(rb, k));
    Some(match near.dir {
        Some(n) => finish(near.q + n * rbs, n, (ras + rbs) - near.dist, k, false),
        None => {
            let n = fallback_normal();
            finish(near.q + n * rbs, n, ras + rbs, k, true)
        }
    })
}

/// Where the foot of a point on a segment `[a, b]` lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Foot {
    /// At `a` (`(m − a) · (b − a) ≤ 0`; every point of a zero-length segment).
    Start,
    /// At `b`.
    End,
    /// Strictly between.
    Between,
}

/// `(m − a) · (b − a)`: lengths `[m, a, b]`.
fn along<N: Ring>(l: &[N; 9], _: &[N; 0]) -> N {
    dot3(refs(&sub3(at(l, 0), at(l, 3))), refs(&sub3(at(l, 6), at(l, 3))))
}

/// `‖m − e‖² − (ra + rb)²`: lengths `[m, e, ra, rb]`.
fn point_reach<N: Ring>(l: &[N; 8], _: &[N; 0]) -> N {
    let v = sub3(at(l, 0), at(l, 3));
    let r = l[6].add(&l[7]);
    dot3(refs(&v), refs(&v)).sub(&r.mul(&r))
}

/// `‖(m − a) × (b − a)‖² − (ra + rb)² ‖b − a‖²`: lengths `[m, a, b, ra, rb]`.
fn line_reach<N: Ring>(l: &[N; 11], _: &[N; 0]) -> N {
    let (v, d) = (sub3(at(l, 0), at(l, 3)), sub3(at(l, 6), at(l, 3)));
    let x = cross3(refs(&v), refs(&d));
    let r = l[9].add(&l[10]);
    dot3(refs(&x), refs(&x)).sub(&r.mul(&r).mul(&dot3(refs(&d), refs(&d))))
}

/// Component `e · (d × ((m − a) × d))` (`d = b − a`, `e` a unit axis): the
/// perpendicular from the axis toward `m`, times `‖d‖²`. Lengths `[m, a, b]`,
/// units `[e]`.
fn perpendicular<N: Ring>(l: &[N; 9], u: &[N; 3]) -> N {
    let (v, d) = (sub3(at(l, 0), at(l, 3)), sub3(at(l, 6), at(l, 3)));
    let x = cross3(refs(&v), refs(&d));
    dot3(at(u, 0), refs(&cross3(refs(&d), refs(&x))))
}

/// Component `e · ((m − a) × (b − a))`: lengths `[m, a, b]`, units `[e]`.
fn moment<N: Ring>(l: &[N; 9], u: &[N; 3]) -> N {
    let (v, d) = (sub3(at(l, 0), at(l, 3)), sub3(at(l, 6), at(l, 3)));
    dot3(at(u, 0), refs(&cross3(refs(&v), refs(&d))))
}

/// Where the foot of `m` on `[a, b]` lies, exactly.
pub(crate) fn foot_of(m: P3, a: P3, b: P3) -> Foot {
    let cat = |x: P3, y: P3, z: P3| [x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]];
    let along_sign = |l: [f64; 9]| stage::or_exact(stage::along(&l), || sign_of!(along, l, []));
    if along_sign(cat(m, a, b)) != Sign::Positive {
        Foot::Start
    } else if along_sign(cat(m, b, a)) != Sign::Positive {
        Foot::End
    } else {
        Foot::Between
    }
}

/// Whether `m` is within `ra + rb` of `[a, b]` (its foot given), and whether it
/// is on the segment, exactly.
pub(crate) fn reach_test(m: P3, a: P3, b: P3, ra: f64, rb: f64, foot: Foot) -> (bool, bool) {
    let end = |e: P3| {
        let l = [m[0], m[1], m[2], e[0], e[1], e[2], ra, rb];
        let reach = stage::or_exact(stage::point_reach(&l), || sign_of!(point_reach, l, []));
        (reach != Sign::Positive, points_equal(m, e))
    };
    match foot {
        Foot::Start => end(a),
        Foot::End => end(b),
        Foot::Between => {
            let l = [m[0], m[1], m[2], a[0], a[1], a[2], b[0], b[1], b[2], ra, rb];
            let reach = stage::or_exact(stage::line_reach(&l), || sign_of!(line_reach, l, []));
            (reach != Sign::Positive, collinear(a, b, m))
        }
    }
}

/// The nearest point of a segment to a point, in a scene scaled by `2^k`.
pub(crate) struct Near {
    /// The nearest point of the segment (scaled).
    pub q: Vec3<f64>,
    /// The unit direction from `q` toward the point; `None` when on the segment.
    pub dir: Option<Vec3<f64>>,
    /// The distance (scaled).
    pub dist: f64,
}

/// [`Near`] for `m` and `[a, b]` with the foot found by [`foot_of`] and
/// whether `m` is on the segment. The foot between the ends is formed from
/// the nearer end; the direction there is the perpendicular's, to `2^−40`.
pub(crate) fn foot_values(m: P3, a: P3, b: P3, foot: Foot, k: i32, on: bool) -> Near {
    let (ms, as_, bs) = (up(m, k), up(a, k), up(b, k));
    let q = match foot {
        Foot::Start => as_,
        Foot::End => bs,
        Foot::Between => {
            let ab = bs - as_;
            let len2 = ab.norm_squared();
            let t = (ms - as_).dot(&ab) / len2;
            if t <= 0.5 {
                as_ + ab * t.max(0.0)
            } else {
                let tb = (ms - bs).dot(&-ab) / len2;
                bs - ab * tb.max(0.0)
            }
        }
    };
    if on {
        return Near { q, dir: None, dist: 0.0 };
    }
    if foot != Foot::Between {
        let v = ms - q;
        return Near { q, dir: unit(&v), dist: crate::real::stable_norm(&v) };
    }
    let l = [m[0], m[1], m[2], a[0], a[1], a[2], b[0], b[1], b[2]];
    let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let perp: [Estimate; 3] = e.map(|e| value_of!(perpendicular, 3, l, e));
    let dir = Estimate::unit_vector(perp).map(|d| Vec3::new(d[0], d[1], d[2]));
    let mom = Vec3::from(e.map(|e| scaled_f64(value_of!(moment, 2, l, e), 2 * i64::from(k))));
    let dist = crate::real::stable_norm(&mom) / crate::real::stable_norm(&(bs - as_));
    Near { q, dir, dist }
}
