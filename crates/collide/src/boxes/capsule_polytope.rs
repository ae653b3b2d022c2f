//! Capsule–box and capsule–triangle contact.

use super::box_contact::{
    Cand, Least, add3, at3, box_feature, cand, cat, comb3, e3, extent, max2x2, max3x4, over_sqrt, rotation_f64,
    sat_polys, scale3, side, times2, touching_point, tri_edges, triangle_top,
};
use super::capsule_capsule::closest_pt_segment_segment_lecture;
use super::poly::{self, Fast, Filt, Ring, cross3, dot3, over_norm2, quaternion_axes, refs, scaled_f64, select, sub3};
use super::{
    OBB_EPSILON, all_finite, contact_capsule_capsule, contact_sphere_box, fallback_normal, finish, lecture_finite,
    quaternion_of, scene_scale, stage, up, up1, wide3,
};
use crate::contact::{Contact, closest_pt_point_triangle, contact_sphere_triangle};
use crate::exact::{BigFloat, P3, Sign, collinear, orient2d, points_equal};
use crate::real::{Real, Vec3};
use crate::shapes::{Capsule, OrientedBox, Sphere, Triangle};

// ---------------------------------------------------------------------------
// The lecture's forms
// ---------------------------------------------------------------------------

/// Contact between a capsule `a` and a box `b`, **the lecture's form**: in the
/// box's frame (`R` from [`OrientedBox::rotation_matrix_lecture`]), whether the
/// axis meets the box by Ericson's `TestSegmentAABB` (*Real-Time Collision
/// Detection*, §5.3.3, with [`OBB_EPSILON`] added to the half-length
/// vector's absolute components, as the book does). If it does, the axis's
/// penetration `s` is the least push over the box's axes and `d × e_j`
/// (`d` the axis direction; a cross product shorter than [`OBB_EPSILON`]
/// times `‖d‖` skipped), plain projections; depth `r + s`, normal that push's
/// direction, point the axis's deepest end moved out by `s` and clamped to
/// the box. If not (or if a push comes out negative: the epsilon let an
/// axis that misses through), the closest points of the axis and the box among its
/// ends clamped to the box and the axis against the box's twelve edges
/// (Ericson's closest points of two segments, §5.1.9), and the
/// sphere formulas: contact when `d ≤ r`, normal `(p_a − p_b)/d`, depth
/// `r − d`, point `p_b`.
///
/// Known wrong: the epsilon makes an axis that passes within about `1e-6`
/// (relative) of an edge meet the box; a distance that underflows to 0 takes
/// the normal `+z`, flagged; ties are `==` on rounded values.
pub fn contact_capsule_box_lecture<T: Real>(a: &Capsule<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    lecture_finite(contact_capsule_box_lecture_raw(a, b))
}

fn contact_capsule_box_lecture_raw<T: Real>(a: &Capsule<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    let rot = b.rotation_matrix_lecture();
    let h = b.half_extents.map(|x| x.abs());
    let (p0, p1) = (rot.transpose() * (a.start - b.center), rot.transpose() * (a.end - b.center));
    if segment_meets_box_lecture(&p0, &p1, &h) {
        let d = p1 - p0;
        let mut axes: Vec<(Vec3<T>, T)> = (0..3).map(|j| (Vec3::ith(j, T::one()), T::zero())).collect();
        axes.extend((0..3).map(|j| (d.cross(&Vec3::ith(j, T::one())), T::of(OBB_EPSILON) * d.norm())));
        let mut best: Option<(T, Vec3<T>, bool)> = None;
        let mut tie = false;
        for (l, skip) in axes {
            let len = l.norm();
            if !(len > skip) {
                continue;
            }
            let rad = h.x * l.x.abs() + h.y * l.y.abs() + h.z * l.z.abs();
            let (s0, s1) = (l.dot(&p0), l.dot(&p1));
            let (plus, minus) = (rad - s0.min(s1), s0.max(s1) + rad);
            let (push, n) = if plus <= minus { (plus / len, l / len) } else { (minus / len, -l / len) };
            match best {
                Some((p, bn, _)) if push == p && n.dot(&bn) < T::one() - T::of(1e-9) => tie = true,
                Some((p, _, _)) if push >= p => {}
                _ => {
                    best = Some((push, n, plus == minus));
                    tie = false;
                }
            }
        }
        if let Some((s, nl, both)) = best.filter(|b| b.0 >= T::zero()) {
            let deepest = deepest_end_lecture(&p0, &p1, &nl);
            let q = deepest + nl * s;
            let q = Vec3::new(q.x.max(-h.x).min(h.x), q.y.max(-h.y).min(h.y), q.z.max(-h.z).min(h.z));
            let normal = rot * nl;
            return Some(Contact { point: b.center + rot * q, normal, depth: a.radius + s, degenerate: tie || both });
        }
    }
    let clamp = |p: &Vec3<T>| Vec3::new(p.x.max(-h.x).min(h.x), p.y.max(-h.y).min(h.y), p.z.max(-h.z).min(h.z));
    let mut pairs = vec![(p0, clamp(&p0)), (p1, clamp(&p1))];
    for (e0, e1) in box_edges_lecture(&h) {
        pairs.push(closest_pt_segment_segment_lecture(&p0, &p1, &e0, &e1));
    }
    let (pa, pb) = nearest_pair(&pairs)?;
    sphere_touch(&(rot * (pa - pb)), &(b.center + rot * pb), a.radius)
}

/// The axis's end deepest against `n` (least `n · x`; their midpoint when
/// level, as computed).
fn deepest_end_lecture<T: Real>(p0: &Vec3<T>, p1: &Vec3<T>, n: &Vec3<T>) -> Vec3<T> {
    let (s0, s1) = (n.dot(p0), n.dot(p1));
    if s0 < s1 {
        *p0
    } else if s1 < s0 {
        *p1
    } else {
        (p0 + p1) * T::of(0.5)
    }
}

/// A pair of points, `(on a, on b)`.
type Pair<T> = (Vec3<T>, Vec3<T>);

/// The nearest pair of points among `pairs` (`(on a, on b)`).
fn nearest_pair<T: Real>(pairs: &[(Vec3<T>, Vec3<T>)]) -> Option<(Vec3<T>, Vec3<T>)> {
    let mut best: Option<(T, Pair<T>)> = None;
    for (pa, pb) in pairs {
        let d2 = (pa - pb).norm_squared();
        if best.is_none_or(|(b, _)| d2 < b) {
            best = Some((d2, (*pa, *pb)));
        }
    }
    best.map(|(_, p)| p)
}

/// The sphere formulas at a closest pair `p_a`, `p_b` (given as
/// `offset = p_a − p_b` and `p_b`): no contact beyond `r`; a zero distance
/// takes `+z`, flagged.
fn sphere_touch<T: Real>(offset: &Vec3<T>, pb: &Vec3<T>, r: T) -> Option<Contact<T>> {
    let dist = offset.norm();
    if dist.is_nan() || dist > r {
        return None;
    }
    if dist > T::zero() && dist.finite() {
        Some(Contact { point: *pb, normal: offset / dist, depth: r - dist, degenerate: false })
    } else {
        Some(Contact { point: *pb, normal: fallback_normal(), depth: r - dist, degenerate: true })
    }
}

/// Ericson's `TestSegmentAABB` (§5.3.3) against the box `[−h, h]`, with the
/// book's epsilon.
fn segment_meets_box_lecture<T: Real>(p0: &Vec3<T>, p1: &Vec3<T>, h: &Vec3<T>) -> bool {
    let half = T::of(0.5);
    let m = (p0 + p1) * half;
    let d = p1 - m;
    let mut ad = d.map(|x| x.abs());
    for i in 0..3 {
        if m[i].abs() > h[i] + ad[i] {
            return false;
        }
    }
    ad = ad.map(|x| x + T::of(OBB_EPSILON));
    if (m.y * d.z - m.z * d.y).abs() > h.y * ad.z + h.z * ad.y {
        return false;
    }
    if (m.z * d.x - m.x * d.z).abs() > h.x * ad.z + h.z * ad.x {
        return false;
    }
    if (m.x * d.y - m.y * d.x).abs() > h.x * ad.y + h.y * ad.x {
        return false;
    }
    true
}

/// The twelve edges of the box `[−h, h]`.
fn box_edges_lecture<T: Real>(h: &Vec3<T>) -> Vec<(Vec3<T>, Vec3<T>)> {
    let mut out = Vec::with_capacity(12);
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        for (sj, sk) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let mut p = Vec3::zeros();
            p[j] = T::of(sj) * h[j];
            p[k] = T::of(sk) * h[k];
            let (mut a, mut b) = (p, p);
            a[i] = -h[i];
            b[i] = h[i];
            out.push((a, b));
        }
    }
    out
}

/// Contact between a capsule `a` and a triangle `b`, **the lecture's form**:
/// whether the axis meets the triangle as textbooks test it — the ends'
/// signed distances to the plane of `n = (v1 − v0) × (v2 − v0)` of opposite
/// signs (or one zero), the crossing point inside by the signs of
/// `n · (E_k × (x − v_k))` (a segment lying in the plane, or a zero-area
/// triangle, is taken as not meeting it) — and if so the least push over `n`
/// and `d × E_k` (a cross product shorter than [`OBB_EPSILON`] times its
/// factors' lengths skipped), depth `r + s`, point the axis's deepest end
/// moved out by `s`. If not (or if a push comes out negative), the closest
/// points of the axis and the triangle
/// among its ends against the triangle (Ericson's `ClosestPtPointTriangle`,
/// §5.1.5) and the axis against the three edges (§5.1.9), then the sphere
/// formulas.
///
/// Known wrong: an axis lying in the triangle's plane across it has distance
/// 0 as computed: normal `+z`, depth `r`, flagged (the format pushes it out
/// along the normal, degenerate too, but by the least push); the point of an
/// axis meeting the triangle is its end moved out, off the triangle where
/// the push is along a cross product.
pub fn contact_capsule_triangle_lecture<T: Real>(a: &Capsule<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    lecture_finite(contact_capsule_triangle_lecture_raw(a, b))
}

fn contact_capsule_triangle_lecture_raw<T: Real>(a: &Capsule<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    let [v0, v1, v2] = b.vertices;
    let e = tri_edges(b);
    let n = e[0].cross(&(v2 - v0));
    let (p0, p1) = (a.start, a.end);
    let (dp, dq) = (n.dot(&(p0 - v0)), n.dot(&(p1 - v0)));
    let crosses = !((dp > T::zero() && dq > T::zero()) || (dp < T::zero() && dq < T::zero()) || dp == dq);
    let meets = crosses && {
        let x = p0 + (p1 - p0) * (dp / (dp - dq));
        (0..3).all(|k| n.dot(&e[k].cross(&(x - b.vertices[k]))) >= T::zero())
    };
    if meets {
        let d = p1 - p0;
        let mut axes = vec![(n, T::of(OBB_EPSILON) * e[0].norm() * e[2].norm())];
        axes.extend(e.iter().map(|ek| (d.cross(ek), T::of(OBB_EPSILON) * d.norm() * ek.norm())));
        let mut best: Option<(T, Vec3<T>, bool)> = None;
        let mut tie = false;
        for (l, skip) in axes {
            let len = l.norm();
            if !(len > skip) || !(len > T::zero()) {
                continue;
            }
            let t = [v0, v1, v2].map(|v| l.dot(&v));
            let (tlo, thi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
            let (s0, s1) = (l.dot(&p0), l.dot(&p1));
            let (plus, minus) = (thi - s0.min(s1), s0.max(s1) - tlo);
            let (push, nn) = if plus <= minus { (plus / len, l / len) } else { (minus / len, -l / len) };
            match best {
                Some((p, bn, _)) if push == p && nn.dot(&bn) < T::one() - T::of(1e-9) => tie = true,
                Some((p, _, _)) if push >= p => {}
                _ => {
                    best = Some((push, nn, plus == minus));
                    tie = false;
                }
            }
        }
        if let Some((s, nn, both)) = best.filter(|b| b.0 >= T::zero()) {
            let point = deepest_end_lecture(&p0, &p1, &nn) + nn * s;
            return Some(Contact { point, normal: nn, depth: a.radius + s, degenerate: tie || both });
        }
    }
    let mut pairs = vec![(p0, closest_pt_point_triangle(&p0, b)), (p1, closest_pt_point_triangle(&p1, b))];
    for k in 0..3 {
        pairs.push(closest_pt_segment_segment_lecture(&p0, &p1, &b.vertices[k], &b.vertices[(k + 1) % 3]));
    }
    let (pa, pb) = nearest_pair(&pairs)?;
    sphere_touch(&(pa - pb), &pb, a.radius)
}

// ---------------------------------------------------------------------------
// The robust forms
// ---------------------------------------------------------------------------

/// Contact between a capsule `a` and a box `b`, **robust form**
/// (`docs/FORMAT.md`, "capsule–box"), for the box of the quaternion's own
/// rotation `R(q)` (see [`crate::boxes`]).
///
/// - *Whether the axis meets the box* (`d = 0`) is decided exactly: the
///   separating-axis test of the segment and the solid box over the box's
///   axes `M_j` (`‖q‖² R(q) e_j`) and `D × M_j` (`D` the axis direction),
///   which is complete for a segment (or a point) against a box, flat boxes
///   included.
/// - *`d = 0`*: the axis's penetration `s` is the least push over the same
///   axes, chosen exactly with its ties (`degenerate`; the first of `+M_x,
///   −M_x, …, +D × M_x, …` answering), the push along `±L` being
///   `(2Σ h_j |L · M_j| + ‖q‖² · 2 max_k (±L · (c − p_k))) / (2‖q‖² ‖L‖)`;
///   depth `r + s` and the normal to `2^−40`; the point the average of the
///   corners of `(axis + s·n) ∩ b` (the axis's end or ends deepest against
///   `n`, by the exact sign of `L · D`, against the box's face, edge or
///   vertex in `+n`), computed in `f64`.
/// - *`d > 0`*: the closest pair is an end of the axis against the box, or
///   the axis against one of the twelve edges. The ends are answered by
///   [`super::contact_sphere_box`] (exact decisions for `R(q)`), the edges by
///   edge, and the deepest of their contacts is the answer (the difference
///   of closest points of two convex sets is unique, so any nearest pair
///   gives the normal). "Contact or not" is exact: the ends by the
///   sphere–box query's exact decisions, the edges by an exact
///   segment–segment reach test on the edge's ends as polynomials of the
///   quaternion (times `‖q‖²`), never the rounded corners. **Not exact:**
///   the values of an edge contact come from the corners rounded to `f64`
///   (`c + R̃ (±h)`, computed about the box's centre: a few ulps of the box's
///   size), and which of two nearly equidistant features answers is decided
///   on their rounded depths (both give the same normal and depth to
///   rounding).
///
/// Non-finite input: no contact. A zero quaternion is the identity.
pub fn contact_capsule_box<T: Real>(a: &Capsule<T>, b: &OrientedBox<T>) -> Option<Contact<T>> {
    let q = quaternion_of(b)?;
    let (p0, p1, c) = (wide3(&a.start), wide3(&a.end), wide3(&b.center));
    let h = wide3(&b.half_extents).map(f64::abs);
    let r = a.radius.wide();
    let l: [f64; 12] = cat(&[&p0, &p1, &c, &h]);
    if !all_finite(&l) || !r.is_finite() {
        return None;
    }
    let z = [0.0; 3];
    let mut axes: Vec<Cand> = (0..3).map(|j| cand(e3(j), z, [1.0, 0.0, 0.0])).collect();
    axes.extend((0..3).map(|j| cand(e3(j), z, [0.0, 0.0, 1.0])));
    // The floating-point stage settles what it is certain of (the same
    // exact decisions, `stage::capsule_box_contact`); the exact code decides
    // the rest.
    let settled = stage::capsule_box_contact(&q, &cat(&[&l, &[r]]));
    if settled.as_ref().is_some_and(|s| s.far()) {
        return None;
    }
    let least = match &settled {
        None => cb::least(l, q, &axes),
        Some(s) if s.apart() => Least::Apart,
        Some(s) => s.least(&axes).unwrap_or_else(|| cb::least_by(l, q, &axes, s)),
    };
    match least {
        Least::Touch { best, tie } => {
            let k = scene_scale(&[l.as_slice(), &[r]].concat());
            let deg = if best[6] != 0.0 { 0 } else { 1 };
            let normal = cb::normal(l, q, &best, deg).unwrap_or_else(fallback_normal);
            let (o, n2) = cb::depth(l, q, &best, deg);
            let s = scaled_f64(over_norm2(times2(over_sqrt(o, n2), -1), &q), i64::from(k));
            let known = settled.map_or([None; 6], |s| s.along(&best));
            let along = |w: [f64; 4]| {
                let x = (0..4).find(|&x| w[x] != 0.0).unwrap_or(0);
                known[x].unwrap_or_else(|| {
                    let u: [f64; 18] = cat(&[&q, &best, &w]);
                    poly::sign_fast(l, u, cb::along::<Fast>, cb::along::<Filt>, cb::along::<BigFloat>)
                })
            };
            let sb = [0, 1, 2].map(|j| side(along([e3(j)[0], e3(j)[1], e3(j)[2], 0.0])));
            let (p0s, p1s, cs, hs) = (up(p0, k), up(p1, k), up(c, k), up(h, k));
            let fa: Vec<Vec3<f64>> =
                axis_feature(along([0.0, 0.0, 0.0, 1.0]), p0s, p1s).into_iter().map(|p| p + normal * s).collect();
            let fb = box_feature(&cs, &rotation_f64(&q), &hs, sb);
            let point = touching_point(&fa, &fb, &normal, extent(&[p0s, p1s, cs, hs]));
            Some(finish(point, normal, up1(r, k) + s, k, tie))
        }
        Least::NoAxis => None,
        Least::Apart => {
            let cap = Capsule::new(Vec3::from(p0), Vec3::from(p1), r);
            let bx = OrientedBox::new(Vec3::from(c), Vec3::from(h), q);
            let mut found: Vec<Contact<f64>> = Vec::with_capacity(14);
            for p in [p0, p1] {
                found.extend(contact_sphere_box(&Sphere::new(Vec3::from(p), r), &bx));
            }
            // The edges in the box's frame translated to its centre (the axis's
            // ends moved there, exactly where they are near it), so that the
            // corners are not rounded to the scale of the centre's
            // coordinates; back in the original frame if that overflows.
            let (rot, cv) = (rotation_f64(&q), Vec3::from(c));
            let near = Capsule::new(cap.start - cv, cap.end - cv, r);
            let (origin, cap) = if crate::real::finite3(&near.start) && crate::real::finite3(&near.end) {
                (cv, near)
            } else {
                (Vec3::zeros(), cap)
            };
            // Whether the axis reaches an edge is decided exactly (`edge_reach`);
            // the values come from the capsule–capsule query on the rounded
            // corners, or, where it rounds a touching pair apart, from the
            // closest points of the two segments.
            // The floating-point stage settles the edges certainly out of
            // reach first (`stage::capsule_box_edges_apart`: the same answer
            // as `edge_reach`'s); the exact test decides the rest.
            let apart = stage::capsule_box_edges_apart(&q, &cat(&[&l, &[r]]));
            for (e, (e0, e1)) in box_edges(&(cv - origin), &rot, &Vec3::from(h)).into_iter().enumerate() {
                if apart & (1 << e) != 0 || !edge_reach(l, r, &q, e) {
                    continue;
                }
                let k = contact_capsule_capsule(&cap, &Capsule::new(e0, e1, 0.0))
                    .filter(|k| !k.degenerate)
                    .unwrap_or_else(|| segment_touch(&cap, &e0, &e1));
                found.push(Contact { point: k.point + origin, ..k });
            }
            deepest(found)
        }
    }
}

/// The contact of a capsule with a segment `[e0, e1]` (radius 0) from the
/// closest points of the two segments in `f64`, on the scene scaled by a
/// power of two to unit size: values for a pair the exact test put within
/// reach where the capsule–capsule query, on rounded corners, did not (or
/// saw the segments meet; they are exactly apart). Depth at least 0.
fn segment_touch(cap: &Capsule<f64>, e0: &Vec3<f64>, e1: &Vec3<f64>) -> Contact<f64> {
    let k = crate::real::unit_scale::<f64>(extent(&[cap.start, cap.end, *e0, *e1]).max(cap.radius)).unwrap_or(0);
    let sc = |p: &Vec3<f64>| crate::real::scale2v(p, k);
    let (pa, pb) = closest_segments_exactly(&sc(&cap.start), &sc(&cap.end), &sc(e0), &sc(e1));
    let normal = super::unit(&(pa - pb)).unwrap_or_else(fallback_normal);
    let depth = (up1(cap.radius, k) - crate::real::stable_norm(&(pa - pb))).max(0.0);
    finish(pb, normal, depth, k, false)
}

/// The closest points of two segments in `f64` (Ericson's, §5.1.9, with no
/// epsilon).
fn closest_segments_exactly(p1: &Vec3<f64>, q1: &Vec3<f64>, p2: &Vec3<f64>, q2: &Vec3<f64>) -> (Vec3<f64>, Vec3<f64>) {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let clamp01 = |x: f64| if x.is_finite() { x.clamp(0.0, 1.0) } else { 0.0 };
    let (s, t) = if a <= 0.0 && e <= 0.0 {
        (0.0, 0.0)
    } else if a <= 0.0 {
        (0.0, clamp01(f / e))
    } else {
        let c = d1.dot(&r);
        if e <= 0.0 {
            (clamp01(-c / a), 0.0)
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let s0 = if denom > 0.0 { clamp01((b * f - c * e) / denom) } else { 0.0 };
            let t0 = (b * s0 + f) / e;
            if t0 < 0.0 {
                (clamp01(-c / a), 0.0)
            } else if t0 > 1.0 {
                (clamp01((b - c) / a), 1.0)
            } else {
                (s0, t0)
            }
        }
    };
    (p1 + d1 * s, p2 + d2 * t)
}

/// Whether the axis `[p0, p1]` (lengths `l = [p0, p1, c, h]`) comes within
/// `r` of edge `e` of the box (in [`box_edges`]' order), exactly for the box
/// of `R(q)`: every point multiplied by `n = ‖q‖²` (the edge's ends
/// `n c + Σ_j s_j h_j M_j ∓ h_i M_i`, polynomials in the inputs), the
/// distance of two segments is least at the lines' critical point when it
/// lies in both (then the skew distance), else at an end against the other
/// segment (its end points, or its line where the foot falls inside): each
/// a sign of a polynomial.
fn edge_reach(l: [f64; 12], r: f64, q: &[f64; 4], e: usize) -> bool {
    let (i, corner) = (e / 4, e % 4);
    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
    let [sj, sk] = [[1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]][corner];
    let mut sv = [0.0; 3];
    sv[j] = sj;
    sv[k] = sk;
    let lr: [f64; 13] = cat(&[&l, &[r]]);
    let g: [f64; 10] = cat(&[q, &sv, &e3(i)]);
    let crit = |w: [f64; 3]| {
        poly::sign_fast(lr, cat::<13>(&[&g, &w]), er::critical::<Fast>, er::critical::<Filt>, er::critical::<BigFloat>)
    };
    let between = crit([0.0, 0.0, 1.0]) == Sign::Positive
        && crit([1.0, 0.0, 0.0]) != Sign::Negative
        && crit([-1.0, 0.0, 1.0]) != Sign::Negative
        && crit([0.0, 1.0, 0.0]) != Sign::Negative
        && crit([0.0, -1.0, 1.0]) != Sign::Negative;
    if between {
        return poly::sign_fast(lr, g, er::skew::<Fast>, er::skew::<Filt>, er::skew::<BigFloat>) != Sign::Positive;
    }
    // An end X against the segment [Y0, Y1] (points 0, 1: the axis; 2, 3:
    // the edge).
    let end_near = |x: usize, y0: usize, y1: usize| {
        let pick = |a: usize| e4(a);
        let near = |y: usize| {
            let u: [f64; 18] = cat(&[&g, &pick(x), &pick(y)]);
            poly::sign_fast(lr, u, er::apart::<Fast>, er::apart::<Filt>, er::apart::<BigFloat>) != Sign::Positive
        };
        let foot = |w: [f64; 3]| {
            let u: [f64; 25] = cat(&[&g, &pick(x), &pick(y0), &pick(y1), &w]);
            poly::sign_fast(lr, u, er::foot::<Fast>, er::foot::<Filt>, er::foot::<BigFloat>)
        };
        near(y0)
            || near(y1)
            || (foot([1.0, 0.0, 0.0]) == Sign::Positive
                && foot([0.0, 1.0, 0.0]) == Sign::Positive
                && foot([0.0, 0.0, 1.0]) != Sign::Positive)
    };
    end_near(0, 2, 3) || end_near(1, 2, 3) || end_near(2, 0, 1) || end_near(3, 0, 1)
}

/// The one-hot selector of one of four points.
fn e4(a: usize) -> [f64; 4] {
    let mut x = [0.0; 4];
    x[a] = 1.0;
    x
}

/// The polynomials of [`edge_reach`]: lengths `[p0, p1, c, h, r]`, units
/// `[q, s (the edge's fixed corner signs, 0 on its axis), w (its axis)]`
/// then each one's own.
mod er {
    use super::*;

    /// `n p0, n p1, E0, E1` and `n r` (`n = ‖q‖²`).
    fn points<N: Ring>(l: &[N; 13], u: &[N]) -> ([[N; 3]; 4], N) {
        let q = [&u[0], &u[1], &u[2], &u[3]];
        let (m, n) = (quaternion_axes(q), poly::norm2(q));
        let corner = comb3(&[u[4].mul(&l[9]), u[5].mul(&l[10]), u[6].mul(&l[11])], [&m[0], &m[1], &m[2]]);
        let half = comb3(&[u[7].mul(&l[9]), u[8].mul(&l[10]), u[9].mul(&l[11])], [&m[0], &m[1], &m[2]]);
        let mid = add3(&scale3(&[l[6].clone(), l[7].clone(), l[8].clone()], &n), &corner);
        let p0 = scale3(&[l[0].clone(), l[1].clone(), l[2].clone()], &n);
        let p1 = scale3(&[l[3].clone(), l[4].clone(), l[5].clone()], &n);
        let e0 = sub3(refs(&mid), refs(&half));
        let e1 = add3(&mid, &half);
        ([p0, p1, e0, e1], n.mul(&l[12]))
    }

    /// `w_s s_num + w_t t_num + w_d denom` of the axis against the edge
    /// (Ericson's critical parameters of the two lines).
    pub(super) fn critical<N: Ring>(l: &[N; 13], u: &[N; 13]) -> N {
        let ([a0, a1, b0, b1], _) = points(l, u);
        let (da, db, r) = (sub3(refs(&a1), refs(&a0)), sub3(refs(&b1), refs(&b0)), sub3(refs(&a0), refs(&b0)));
        let a = dot3(refs(&da), refs(&da));
        let e = dot3(refs(&db), refs(&db));
        let b = dot3(refs(&da), refs(&db));
        let c = dot3(refs(&da), refs(&r));
        let f = dot3(refs(&db), refs(&r));
        let denom = a.mul(&e).sub(&b.mul(&b));
        let s = b.mul(&f).sub(&c.mul(&e));
        let t = a.mul(&f).sub(&b.mul(&c));
        u[10].mul(&s).add(&u[11].mul(&t)).add(&u[12].mul(&denom))
    }

    /// `(N · (A0 − B0))² − R² ‖N‖²`, `N = d_a × d_b`.
    pub(super) fn skew<N: Ring>(l: &[N; 13], u: &[N; 10]) -> N {
        let ([a0, a1, b0, b1], rr) = points(l, u);
        let (da, db, r) = (sub3(refs(&a1), refs(&a0)), sub3(refs(&b1), refs(&b0)), sub3(refs(&a0), refs(&b0)));
        let n = cross3(refs(&da), refs(&db));
        let nr = dot3(refs(&n), refs(&r));
        nr.mul(&nr).sub(&rr.mul(&rr).mul(&dot3(refs(&n), refs(&n))))
    }

    /// `‖X − Y‖² − R²` of two picked points.
    pub(super) fn apart<N: Ring>(l: &[N; 13], u: &[N; 18]) -> N {
        let (p, rr) = points(l, u);
        let pick =
            |s: &[N]| std::array::from_fn(|k| (1..4).fold(s[0].mul(&p[0][k]), |a, i| a.add(&s[i].mul(&p[i][k]))));
        let (x, y): ([N; 3], [N; 3]) = (pick(&u[10..14]), pick(&u[14..18]));
        let d = sub3(refs(&x), refs(&y));
        dot3(refs(&d), refs(&d)).sub(&rr.mul(&rr))
    }

    /// With `D = Y1 − Y0` and `v = X − Y0`: the sum of `w_1 (v · D)`,
    /// `w_2 (D · D − v · D)` and `w_3 (‖v × D‖² − R² ‖D‖²)` (the foot inside,
    /// and the line within reach).
    pub(super) fn foot<N: Ring>(l: &[N; 13], u: &[N; 25]) -> N {
        let (p, rr) = points(l, u);
        let pick =
            |s: &[N]| std::array::from_fn(|k| (1..4).fold(s[0].mul(&p[0][k]), |a, i| a.add(&s[i].mul(&p[i][k]))));
        let (x, y0, y1): ([N; 3], [N; 3], [N; 3]) = (pick(&u[10..14]), pick(&u[14..18]), pick(&u[18..22]));
        let (d, v) = (sub3(refs(&y1), refs(&y0)), sub3(refs(&x), refs(&y0)));
        let (vd, dd) = (dot3(refs(&v), refs(&d)), dot3(refs(&d), refs(&d)));
        let c = cross3(refs(&v), refs(&d));
        let line = dot3(refs(&c), refs(&c)).sub(&rr.mul(&rr).mul(&dd));
        u[22].mul(&vd).add(&u[23].mul(&dd.sub(&vd))).add(&u[24].mul(&line))
    }
}

/// The twelve edges of a box (centre `c`, rotation `r`, half-extents `h`).
fn box_edges(c: &Vec3<f64>, r: &nalgebra::Matrix3<f64>, h: &Vec3<f64>) -> Vec<(Vec3<f64>, Vec3<f64>)> {
    let mut out = Vec::with_capacity(12);
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        for (sj, sk) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let m = c + r.column(j) * (sj * h[j]) + r.column(k) * (sk * h[k]);
            let d = r.column(i) * h[i];
            out.push((m - d, m + d));
        }
    }
    out
}

/// The deepest of the contacts found at a positive distance, preferring one
/// with a defined normal (a sub-query that sees its features meet has been
/// misled by rounding: the distance is exactly positive), rounded to `T`.
fn deepest<T: Real>(found: Vec<Contact<f64>>) -> Option<Contact<T>> {
    let better = |x: &Contact<f64>, y: &Contact<f64>| {
        (!x.degenerate && y.degenerate) || (x.degenerate == y.degenerate && x.depth > y.depth)
    };
    let mut best: Option<Contact<f64>> = None;
    for k in found {
        if best.as_ref().is_none_or(|b| better(&k, b)) {
            best = Some(k);
        }
    }
    best.map(|k| finish(k.point, k.normal, k.depth, 0, k.degenerate))
}

/// The axis's end or ends deepest against the normal, from the exact sign of
/// `n · D`: `p0` when positive, `p1` when negative, both when zero.
fn axis_feature(s: Sign, p0: Vec3<f64>, p1: Vec3<f64>) -> Vec<Vec3<f64>> {
    match s {
        Sign::Positive => vec![p0],
        Sign::Negative => vec![p1],
        Sign::Zero => vec![p0, p1],
    }
}

mod cb {
    use super::*;

    /// Lengths `[p0, p1, c, h]`, global units `[q]`, candidate
    /// `[s (box axis), _, (face, _, cross), dir]`: `L = M_s` or `D × M_s`, and
    /// `o = 2‖q‖²` times the push along `dir · L`.
    pub(super) fn frame<N: Ring>(l: &[N; 12], g: &[N], c: &[N]) -> ([N; 3], N) {
        let q = [&g[0], &g[1], &g[2], &g[3]];
        let (m, n) = (quaternion_axes(q), poly::norm2(q));
        let d = sub3(at3(l, 3), at3(l, 0));
        let y = select(&c[0..3], &m);
        let axis = add3(&scale3(&y, &c[6]), &scale3(&cross3(refs(&d), refs(&y)), &c[8]));
        let lv = refs(&axis);
        let x0 = c[9].mul(&dot3(lv, refs(&sub3(at3(l, 6), at3(l, 0)))));
        let x1 = c[9].mul(&dot3(lv, refs(&sub3(at3(l, 6), at3(l, 3)))));
        let mut o = n.mul(&max2x2(&x0, &x1));
        for j in 0..3 {
            let r = l[9 + j].mul(&dot3(lv, refs(&m[j])).abs());
            o = o.add(&r.add(&r));
        }
        (axis, o)
    }
    sat_polys!(frame, 12, 4);

    /// `dir · L · (M_w + w' D)`: units `[q, candidate, w (3), w']`.
    pub(super) fn along<N: Ring>(l: &[N; 12], u: &[N; 18]) -> N {
        let (axis, _) = frame(l, &u[..4], &u[4..14]);
        let q = [&u[0], &u[1], &u[2], &u[3]];
        let d = sub3(at3(l, 3), at3(l, 0));
        let w = add3(&select(&u[14..17], &quaternion_axes(q)), &scale3(&d, &u[17]));
        u[13].mul(&dot3(refs(&axis), refs(&w)))
    }
}

/// Contact between a capsule `a` and a triangle `b`, **robust form**
/// (`docs/FORMAT.md`, "capsule–triangle").
///
/// - *Whether the axis meets the triangle* (`d = 0`) is decided exactly: the
///   separating-axis test of the segment and the triangle over `N`, `D × E_k`
///   (`N = (v1 − v0) × (v2 − v0)`, `D` the axis direction, `E_k` the edges),
///   and, for the flat cases (an axis in the triangle's plane, a zero-area
///   triangle), `N × E_k`, `N × D`, `(D × E_k) × D` and `(D × E_k) × E_k`;
///   where all of these vanish (a zero-area triangle and an axis along its
///   line, or points) the five points are tested for exact collinearity and
///   their order along the line compared exactly.
/// - *`d = 0`*: the axis's penetration `s` is the least push over `N` and
///   `D × E_k`, chosen exactly with its ties (`degenerate`; `+N, −N`, then
///   `±D × E_k` in the edges' order), the push along `±L` being
///   `(4 max_k (±L · (v_k − p0)) + 2(|L · D| ∓ L · D)) / (4 ‖L‖)`; depth
///   `r + s`, the normal to `2^−40`, the point the average of the corners of
///   `(axis + s·n) ∩ b` in `f64`. Where no axis exists: normal `(0, 0, 1)`,
///   a common point, depth `r`, flagged.
/// - *`d > 0`*: the nearest pair is an end over the face or the axis against
///   an edge. Contact is decided exactly: against the edges by
///   [`super::contact_capsule_capsule`] with zero-radius capsules (its reach
///   test is exact), over the face by the exact signs of
///   `N · (E_k × (p − v_k))` (the end's projection in the closed triangle)
///   and of `(N · (p − v0))² − r² ‖N‖²`. The values are the deepest of those
///   sub-queries' and [`crate::contact::contact_sphere_triangle`]'s at the
///   ends (the difference of closest points of two convex sets is unique, so
///   any nearest pair gives the normal). **Not exact:** which of two nearly
///   equidistant features answers is decided on their rounded depths (both
///   give the same normal and depth to rounding).
///
/// Non-finite input: no contact.
pub fn contact_capsule_triangle<T: Real>(a: &Capsule<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    let (p0, p1) = (wide3(&a.start), wide3(&a.end));
    let v = b.vertices.map(|x| wide3(&x));
    let r = a.radius.wide();
    let l: [f64; 15] = cat(&[&p0, &p1, &v[0], &v[1], &v[2]]);
    if !all_finite(&l) || !r.is_finite() {
        return None;
    }
    let k = scene_scale(&[l.as_slice(), &[r]].concat());
    let z = [0.0; 3];
    let mut depth_axes = vec![cand(z, z, [1.0, 0.0, 0.0])];
    depth_axes.extend((0..3).map(|e| cand(z, e3(e), [0.0, 1.0, 0.0])));
    let mut meet_axes = depth_axes.clone();
    for e in 0..3 {
        meet_axes.push(cand(z, e3(e), [0.0, 0.0, 1.0]));
        meet_axes.push(cand([0.0, 1.0, 0.0], e3(e), [0.0; 3]));
        meet_axes.push(cand([0.0, 0.0, 1.0], e3(e), [0.0; 3]));
    }
    meet_axes.push(cand([1.0, 0.0, 0.0], z, [0.0; 3]));
    let fallback = |common: P3| {
        let zn = fallback_normal::<f64>();
        Some(finish(up(common, k), zn, up1(r, k), k, true))
    };
    match ct::least(l, [], &meet_axes) {
        Least::Apart => {}
        Least::NoAxis => {
            if let Some(common) = collinear_common([p0, p1], v) {
                return fallback(common);
            }
        }
        Least::Touch { .. } => {
            let Least::Touch { best, tie } = ct::least(l, [], &depth_axes) else { return fallback(p0) };
            let normal = ct::normal(l, [], &best, 2).unwrap_or_else(fallback_normal);
            let (o, n2) = ct::depth(l, [], &best, 2);
            let s = scaled_f64(times2(over_sqrt(o, n2), -2), i64::from(k));
            let along = |w: [f64; 4]| {
                let u: [f64; 14] = cat(&[&best, &w]);
                poly::sign_fast(l, u, ct::along::<Fast>, ct::along::<Filt>, ct::along::<BigFloat>)
            };
            let (p0s, p1s) = (up(p0, k), up(p1, k));
            let vs = v.map(|x| up(x, k));
            let fa: Vec<Vec3<f64>> =
                axis_feature(along([0.0, 0.0, 0.0, 1.0]), p0s, p1s).into_iter().map(|p| p + normal * s).collect();
            let top = triangle_top(|i, j| {
                let mut w = [0.0; 4];
                w[i] = 1.0;
                w[j] = -1.0;
                along(w)
            });
            let fb: Vec<Vec3<f64>> = top.iter().map(|&i| vs[i]).collect();
            // Touching as given (the axis in the plane): the region decided
            // exactly from the inputs; else the translated features in f64.
            let exact = if s == 0.0 { touching_point_exact(&fa, &fb, &normal) } else { None };
            let point =
                exact.unwrap_or_else(|| touching_point(&fa, &fb, &normal, extent(&[p0s, p1s, vs[0], vs[1], vs[2]])));
            return Some(finish(point, normal, up1(r, k) + s, k, tie));
        }
    }
    // d > 0: the nearest pair is an end over the face, or the axis against
    // an edge. Contact is decided exactly: an edge by the capsule–capsule
    // test (exact), an end by the exact face test below; the values come
    // from the sub-queries.
    let cap = Capsule::new(Vec3::from(p0), Vec3::from(p1), r);
    let tri = Triangle::new(Vec3::from(v[0]), Vec3::from(v[1]), Vec3::from(v[2]));
    let mut found: Vec<Contact<f64>> = Vec::with_capacity(5);
    let mut reach = false;
    for e in 0..3 {
        let k = contact_capsule_capsule(&cap, &Capsule::new(tri.vertices[e], tri.vertices[(e + 1) % 3], 0.0));
        reach |= k.is_some();
        found.extend(k);
    }
    for p in [p0, p1] {
        let over = over_face(p, v, r);
        reach |= over;
        let k = contact_sphere_triangle(&Sphere::new(Vec3::from(p), r), &tri);
        match k {
            Some(k) => found.push(k),
            None if over => found.push(face_contact(p, v, r)),
            None => {}
        }
    }
    if !reach {
        return None;
    }
    deepest(found)
}

/// Whether the point `p`, off the triangle, lies over its closed face (its
/// projection inside) within `r` of its plane, exactly: the signs of
/// `N · (E_k × (p − v_k))` and of `(N · (p − v0))² − r² ‖N‖²`. A zero-area
/// triangle has no face (its edges answer).
fn over_face(p: P3, v: [P3; 3], r: f64) -> bool {
    let l: [f64; 13] = cat(&[&p, &v[0], &v[1], &v[2], &[r]]);
    let inside = (0..3).all(|k| {
        poly::sign_fast(l, e3(k), edge_side::<Fast>, edge_side::<Filt>, edge_side::<BigFloat>) != Sign::Negative
    });
    let flat = poly::sign_fast(l, [], face_area::<Fast>, face_area::<Filt>, face_area::<BigFloat>) == Sign::Zero;
    !flat
        && inside
        && poly::sign_fast(l, [], face_reach::<Fast>, face_reach::<Filt>, face_reach::<BigFloat>) != Sign::Positive
}

/// A face contact computed from the plane (for an end that the exact test
/// puts within `r` of the face where the sphere–triangle query, rounding
/// near touching, did not): normal `±N/‖N‖` toward `p`, depth `r − dist`
/// (at least 0), point `p`'s projection.
/// Computed on the scene scaled by a power of two to unit size, so that the
/// cross product neither over- nor underflows.
fn face_contact(p: P3, v: [P3; 3], r: f64) -> Contact<f64> {
    let k = crate::real::unit_scale::<f64>(
        extent(&[Vec3::from(p), Vec3::from(v[0]), Vec3::from(v[1]), Vec3::from(v[2])]).max(r),
    )
    .unwrap_or(0);
    let (pv, vv, rs) = (up(p, k), v.map(|x| up(x, k)), up1(r, k));
    let n = (vv[1] - vv[0]).cross(&(vv[2] - vv[0]));
    let n = super::unit(&n).unwrap_or_else(fallback_normal);
    let h = n.dot(&(pv - vv[0]));
    let normal = if h < 0.0 { -n } else { n };
    finish(pv - n * h, normal, (rs - h.abs()).max(0.0), k, false)
}

/// `N · (E_k × (p − v_k))` for the edge picked by the one-hot `u`: lengths
/// `[p, v0, v1, v2, r]`.
fn edge_side<N: Ring>(l: &[N; 13], u: &[N; 3]) -> N {
    let v = [at3(l, 3), at3(l, 6), at3(l, 9)];
    let e = [sub3(v[1], v[0]), sub3(v[2], v[1]), sub3(v[0], v[2])];
    let normal = cross3(refs(&e[0]), refs(&sub3(v[2], v[0])));
    let vv: [[N; 3]; 3] = std::array::from_fn(|k| std::array::from_fn(|i| v[k][i].clone()));
    let (ek, vk) = (comb3(u, [&e[0], &e[1], &e[2]]), comb3(u, [&vv[0], &vv[1], &vv[2]]));
    let x = cross3(refs(&ek), refs(&sub3(at3(l, 0), refs(&vk))));
    dot3(refs(&normal), refs(&x))
}

/// `‖N‖²`: lengths `[p, v0, v1, v2, r]`.
fn face_area<N: Ring>(l: &[N; 13], _: &[N; 0]) -> N {
    let v = [at3(l, 3), at3(l, 6), at3(l, 9)];
    let normal = cross3(refs(&sub3(v[1], v[0])), refs(&sub3(v[2], v[0])));
    dot3(refs(&normal), refs(&normal))
}

/// `(N · (p − v0))² − r² ‖N‖²`: lengths `[p, v0, v1, v2, r]`.
fn face_reach<N: Ring>(l: &[N; 13], _: &[N; 0]) -> N {
    let v = [at3(l, 3), at3(l, 6), at3(l, 9)];
    let normal = cross3(refs(&sub3(v[1], v[0])), refs(&sub3(v[2], v[0])));
    let h = dot3(refs(&normal), refs(&sub3(at3(l, 0), v[0])));
    let rr = l[12].mul(&l[12]);
    h.mul(&h).sub(&rr.mul(&dot3(refs(&normal), refs(&normal))))
}

/// Where the axis `[p0, p1]` and the triangle's vertices all lie on one line
/// (or are one point), a point they share, exactly: `p0` or else `p1` when on
/// the triangle, else the triangle's end nearest `p0`; `None` when they are
/// not all on one line or do not overlap along it.
fn collinear_common(a: [P3; 2], t: [P3; 3]) -> Option<P3> {
    let all = [a[0], a[1], t[0], t[1], t[2]];
    let Some(far) = all.iter().find(|p| !points_equal(all[0], **p)) else { return Some(all[0]) };
    if !all.iter().all(|p| collinear(all[0], *far, *p)) {
        return None;
    }
    // Along the line every coordinate that varies orders the points as the
    // line does: compare on one that varies, exactly.
    let i = (0..3).find(|&i| all.iter().any(|p| p[i].partial_cmp(&all[0][i]) != Some(std::cmp::Ordering::Equal)))?;
    let lo = |ps: &[P3]| *ps.iter().min_by(|x, y| x[i].total_cmp(&y[i])).unwrap_or(&ps[0]);
    let hi = |ps: &[P3]| *ps.iter().max_by(|x, y| x[i].total_cmp(&y[i])).unwrap_or(&ps[0]);
    let (alo, ahi, tlo, thi) = (lo(&a), hi(&a), lo(&t), hi(&t));
    if alo[i] > thi[i] || tlo[i] > ahi[i] {
        return None;
    }
    // The referee's choice: an end of the axis on the triangle (`p0` first),
    // else the triangle's end nearest `p0` (the triangle lies within the
    // axis then).
    let on = |p: &P3| p[i] >= tlo[i] && p[i] <= thi[i];
    Some(if on(&a[0]) {
        a[0]
    } else if on(&a[1]) {
        a[1]
    } else if a[0][i] < tlo[i] {
        tlo
    } else {
        thi
    })
}

mod ct {
    use super::*;

    /// Lengths `[p0, p1, v0, v1, v2]`, no global units, candidate
    /// `[x1, x2, x3, t (edge), (normal, cross, x0), dir]`:
    /// `L = N`, `D × E_t`, and for the meeting test only `N × E_t` (x0),
    /// `N × D` (x1), `(D × E_t) × D` (x2), `(D × E_t) × E_t` (x3); `o = 4`
    /// times the push along `dir · L`.
    pub(super) fn frame<N: Ring>(l: &[N; 15], _: &[N], c: &[N]) -> ([N; 3], N) {
        let d = sub3(at3(l, 3), at3(l, 0));
        let v = [at3(l, 6), at3(l, 9), at3(l, 12)];
        let e = [sub3(v[1], v[0]), sub3(v[2], v[1]), sub3(v[0], v[2])];
        let y = comb3(&c[3..6], [&e[0], &e[1], &e[2]]);
        let normal = cross3(refs(&e[0]), refs(&sub3(v[2], v[0])));
        let de = cross3(refs(&d), refs(&y));
        let parts = [
            scale3(&normal, &c[6]),
            scale3(&de, &c[7]),
            scale3(&cross3(refs(&normal), refs(&y)), &c[8]),
            scale3(&cross3(refs(&normal), refs(&d)), &c[0]),
            scale3(&cross3(refs(&de), refs(&d)), &c[1]),
            scale3(&cross3(refs(&de), refs(&y)), &c[2]),
        ];
        let axis = parts[1..].iter().fold(parts[0].clone(), |s, p| add3(&s, p));
        let lv = refs(&axis);
        let reach = v.map(|vk| c[9].mul(&dot3(lv, refs(&sub3(vk, at3(l, 0))))));
        let w = c[9].mul(&dot3(lv, refs(&d)));
        let back = w.abs().sub(&w);
        (axis.clone(), max3x4(&reach[0], &reach[1], &reach[2]).add(&back.add(&back)))
    }
    sat_polys!(frame, 15, 0);

    /// `dir · L · (Σ_k w_k v_k + w' D)`: units `[candidate, w (3), w']`.
    pub(super) fn along<N: Ring>(l: &[N; 15], u: &[N; 14]) -> N {
        let (axis, _) = frame(l, &[], &u[..10]);
        let v: [[N; 3]; 3] = std::array::from_fn(|k| std::array::from_fn(|i| l[6 + 3 * k + i].clone()));
        let d = sub3(at3(l, 3), at3(l, 0));
        let w = add3(&comb3(&u[10..13], [&v[0], &v[1], &v[2]]), &scale3(&d, &u[13]));
        u[9].mul(&dot3(refs(&axis), refs(&w)))
    }
}

/// The middle of the touching set of two features that touch as given (no
/// translation: the capsule's axis in the triangle's plane), their points the
/// inputs themselves, so every decision is exact: the points are dropped onto
/// the two coordinates other than the normal's largest (exact), and which of
/// each feature's corners lie in the other and which edges cross are
/// [`orient2d`] signs — no tolerance, so an axis a hair outside the
/// triangle's edge touches it at one corner, not along the edge. The corners
/// found are averaged (a point of the convex set); `None` when none is found.
fn touching_point_exact(pa: &[Vec3<f64>], pb: &[Vec3<f64>], n: &Vec3<f64>) -> Option<Vec3<f64>> {
    let k = (0..3).fold(0, |k, i| if n[i].abs() > n[k].abs() { i } else { k });
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let flat = |p: &Vec3<f64>| [p[i], p[j]];
    let holds = |x: &Vec3<f64>, poly: &[Vec3<f64>]| -> bool {
        let fx = flat(x);
        match poly.len() {
            0 => false,
            1 => points_equal([fx[0], fx[1], 0.0], {
                let f = flat(&poly[0]);
                [f[0], f[1], 0.0]
            }),
            2 => {
                let (f0, f1) = (flat(&poly[0]), flat(&poly[1]));
                orient2d(f0, f1, fx) == Sign::Zero
                    && (0..2).all(|c| f0[c].min(f1[c]) <= fx[c] && fx[c] <= f0[c].max(f1[c]))
            }
            m => {
                let signs: Vec<Sign> = (0..m).map(|e| orient2d(flat(&poly[e]), flat(&poly[(e + 1) % m]), fx)).collect();
                !(signs.contains(&Sign::Positive) && signs.contains(&Sign::Negative))
            }
        }
    };
    let edges = |poly: &[Vec3<f64>]| -> Vec<(Vec3<f64>, Vec3<f64>)> {
        match poly.len() {
            0 | 1 => vec![],
            2 => vec![(poly[0], poly[1])],
            m => (0..m).map(|e| (poly[e], poly[(e + 1) % m])).collect(),
        }
    };
    let mut found: Vec<Vec3<f64>> = pa.iter().filter(|p| holds(p, pb)).copied().collect();
    found.extend(pb.iter().filter(|q| holds(q, pa)));
    let opposite =
        |x: Sign, y: Sign| (x == Sign::Positive && y == Sign::Negative) || (x == Sign::Negative && y == Sign::Positive);
    for (a0, a1) in edges(pa) {
        for (b0, b1) in edges(pb) {
            let (fa0, fa1, fb0, fb1) = (flat(&a0), flat(&a1), flat(&b0), flat(&b1));
            if opposite(orient2d(fa0, fa1, fb0), orient2d(fa0, fa1, fb1))
                && opposite(orient2d(fb0, fb1, fa0), orient2d(fb0, fb1, fa1))
            {
                // A proper crossing: its place along b's edge in f64.
                let (da, db) = ([fa1[0] - fa0[0], fa1[1] - fa0[1]], [fb1[0] - fb0[0], fb1[1] - fb0[1]]);
                let den = da[0] * db[1] - da[1] * db[0];
                let r = [fb0[0] - fa0[0], fb0[1] - fa0[1]];
                let t = ((r[0] * da[1] - r[1] * da[0]) / den).clamp(0.0, 1.0);
                found.push(b0 + (b1 - b0) * t);
            }
        }
    }
    if found.is_empty() {
        return None;
    }
    let sum = found.iter().fold(Vec3::zeros(), |s, p| s + p);
    Some(sum / found.len() as f64)
}
