//! The first hit of a segment on a box.

use super::poly::{Ring, at, dot3, norm2, picked_axis, quaternion_axes, ratio, refs, select, sign_of, sub3, value_of};
use super::sphere_box::{classify, coord, nearest_face};
use super::{all_finite, quaternion_of, quaternion_units, scene_scale, unit, up, wide3};
use crate::exact::{Sign, points_equal};
use crate::intersect::{Intersection, SegmentHit};
use crate::real::{Real, Vec3};
use crate::shapes::{OrientedBox, Segment};

/// Ericson's `EPSILON` in `IntersectRayAABB` (*Real-Time Collision Detection*,
/// §5.3.3): a segment whose direction along a box axis is below this (in
/// absolute value, in the box's frame) is taken as parallel to that slab, and
/// misses the box when it starts outside the slab. An absolute number (1e-6):
/// a segment shorter than that along the axis it enters through is missed,
/// which is where the lecture's form goes wrong by design.
pub const SLAB_EPSILON: f64 = 1e-6;

/// The first hit of segment `s` on the solid box `b`, **the lecture's form**:
/// Ericson's slab test (§5.3.3) in the box's frame (`R` from
/// [`OrientedBox::rotation_matrix_lecture`], `p = Rᵀ(start − center)`,
/// `d = Rᵀ(end − start)`): for each axis, a direction below [`SLAB_EPSILON`] is
/// parallel (a start outside the slab misses), otherwise the slab's entry and
/// exit times `(∓h − p)/d` narrow `[t_min, t_max]` from `[0, 1]`, and the
/// slab whose entry raised `t_min` last gives the face. A start inside the box
/// (no entry above 0) is a hit at `t = 0` on the face nearest the start, as in
/// [`super::contact_sphere_box_lecture`].
///
/// `degenerate` when two slabs' entries are equal as computed (an edge or a
/// corner), two faces are nearest to an inside start, or the segment has zero
/// length. `parallel` is always false. A scene whose numbers overflow (no
/// finite hit) is answered as a degenerate miss.
pub fn intersect_segment_box_lecture<T: Real>(s: &Segment<T>, b: &OrientedBox<T>) -> Intersection<T> {
    let r = b.rotation_matrix_lecture();
    let h = b.half_extents;
    let p = r.transpose() * (s.start - b.center);
    let d = r.transpose() * (s.end - s.start);
    let zero = s.start == s.end;
    let miss = Intersection { hit: None, parallel: false, degenerate: zero };
    let eps = T::of(SLAB_EPSILON);
    let (mut tmin, mut tmax) = (T::zero(), T::one());
    let mut enter: Option<(usize, T)> = None;
    let mut tie = false;
    for i in 0..3 {
        if d[i].abs() < eps {
            if p[i] < -h[i] || p[i] > h[i] {
                return miss;
            }
            continue;
        }
        let ood = T::one() / d[i];
        let (mut t1, mut t2, mut face) = ((-h[i] - p[i]) * ood, (h[i] - p[i]) * ood, -T::one());
        if t1 > t2 {
            core::mem::swap(&mut t1, &mut t2);
            face = T::one();
        }
        if t1 > tmin {
            tmin = t1;
            enter = Some((i, face));
            tie = false;
        } else if t1 == tmin && enter.is_some() {
            tie = true;
        }
        if t2 < tmax {
            tmax = t2;
        }
        if tmin > tmax {
            return miss;
        }
    }
    let (t, point, normal) = match enter {
        Some((i, face)) => (tmin, s.start + (s.end - s.start) * tmin, r.column(i) * face),
        None => {
            let gaps = [h.x - p.x.abs(), h.y - p.y.abs(), h.z - p.z.abs()];
            let mut best = 0;
            for i in 1..3 {
                if gaps[i] < gaps[best] {
                    best = i;
                }
            }
            tie = (0..3).any(|i| i != best && gaps[i] == gaps[best]) || p[best] == T::zero();
            let face = if p[best] < T::zero() { -T::one() } else { T::one() };
            (T::zero(), s.start, r.column(best) * face)
        }
    };
    if !(t.finite() && crate::real::finite3(&point) && crate::real::finite3(&normal)) {
        return Intersection::DEGENERATE;
    }
    Intersection {
        hit: Some(SegmentHit { t, point, normal, barycentric: None }),
        parallel: false,
        degenerate: tie || zero,
    }
}

/// The first hit of segment `s` on the solid box `b`, **robust form**: the
/// format's definition with every decision exact for the box of the
/// quaternion's own rotation `R(q)` (see [`crate::boxes`]). With
/// `a_i = R_i · (start − c)` and `D_i = R_i · (end − start)` — all taken times
/// `n = ‖q‖²`, the axes as `M_i = n R_i` (quadratics in `q`) and `h_i` as
/// `n h_i` — where each end lies against each slab is decided exactly; a slab
/// the start is beyond face `σ` of is entered at `t_i = (σ h_i − a_i)/D_i` (no
/// hit if the end is beyond the same face), and left, where the end is beyond
/// face `σ'`, at `(σ' h_j − a_j)/D_j`. The hit is at the latest entry when it
/// is no later than every exit; entries and exits are compared exactly (the
/// signs of `N_i D_j − N_j D_i` and of each `D_i`), so an edge entered exactly
/// is found as a tie. `t` is `N/D` with both formed to `2^−40` (the factor `n`
/// cancels). The point is formed from `t`, the normal from the rounded matrix
/// [`OrientedBox::rotation_matrix`].
///
/// **Degenerate input.** Entering through an edge or a corner (two slabs
/// the start is outside of are entered at the same time — the format's rule;
/// a segment running along a face, or leaving a slab exactly where it enters
/// the box, is not flagged), a start inside with two nearest faces (as
/// [`super::contact_sphere_box`]), or a zero-length segment (a hit at `t = 0`
/// when its point is in the box, else none): flagged, the face the first in
/// the order `+x, −x, +y, −y, +z, −z`. `parallel` is always false. A
/// non-finite input is a degenerate miss.
pub fn intersect_segment_box<T: Real>(s: &Segment<T>, b: &OrientedBox<T>) -> Intersection<T> {
    let (p, q, c) = (wide3(&s.start), wide3(&s.end), wide3(&b.center));
    let h = wide3(&b.half_extents).map(f64::abs);
    let lengths = [p[0], p[1], p[2], q[0], q[1], q[2], c[0], c[1], c[2], h[0], h[1], h[2]];
    let Some(qt) = quaternion_of(b).filter(|_| all_finite(&lengths)) else {
        return Intersection::DEGENERATE;
    };
    let zero = points_equal(p, q);
    let rot = b.rotation_matrix().map(|x| x.wide());
    let start = classify(p, c, h, &qt);
    if start == [0; 3] {
        let (i, side, tie) = nearest_face(p, c, h, &qt);
        let normal = unit(&(rot.column(i) * f64::from(side))).unwrap_or_else(Vec3::z);
        return hit_at(T::zero(), s.start, normal, tie || zero);
    }
    if zero {
        return Intersection::DEGENERATE;
    }
    let end = classify(q, c, h, &qt);
    if (0..3).any(|i| start[i] != 0 && end[i] == start[i]) {
        return Intersection::MISS;
    }
    // The sign of `D_i = M_i · (q − p)`.
    let along = |i: usize| sign_of!(coord, [q[0], q[1], q[2], p[0], p[1], p[2]], quaternion_units(&qt, i));
    let order = |i: usize, si: i8, j: usize, sj: i8| {
        let l = [p[0], p[1], p[2], q[0], q[1], q[2], c[0], c[1], c[2], h[i], h[j]];
        let mut u = [qt[0], qt[1], qt[2], qt[3], 0.0, 0.0, 0.0, f64::from(si), 0.0, 0.0, 0.0, f64::from(sj)];
        u[4 + i] = 1.0;
        u[8 + j] = 1.0;
        sign_of!(time_order, l, u)
    };
    // Compare the crossing times of face `si` of slab `i` and face `sj` of
    // slab `j`: the sign of t_i − t_j.
    let cmp = |i: usize, si: i8, j: usize, sj: i8| order(i, si, j, sj) * along(i) * along(j);
    let entering: Vec<usize> = (0..3).filter(|&i| start[i] != 0).collect();
    let mut best = entering[0];
    for &j in &entering[1..] {
        if cmp(j, start[j], best, start[best]) == Sign::Positive {
            best = j;
        }
    }
    for (j, &side) in end.iter().enumerate() {
        if side != 0 && cmp(best, start[best], j, side) == Sign::Positive {
            return Intersection::MISS;
        }
    }
    // Entering through an edge or a corner: another slab the start is outside
    // of is entered at the same time, `N_best D_j − N_j D_best = 0` with `j`'s
    // entry face (the format's rule, as the referee's). A slab the segment
    // runs parallel to, or leaves exactly at the entry, is not a tie: the
    // format names the face by the entries alone.
    let tie = (0..3).any(|j| j != best && start[j] != 0 && order(best, start[best], j, start[j]) == Sign::Zero);
    let u = quaternion_units(&qt, best);
    let num = value_of!(
        entry_numerator,
        1,
        [p[0], p[1], p[2], c[0], c[1], c[2], h[best]],
        [u[0], u[1], u[2], u[3], u[4], u[5], u[6], f64::from(start[best])]
    );
    let den = value_of!(coord, 1, [q[0], q[1], q[2], p[0], p[1], p[2]], u);
    let t = ratio(num, den).clamp(0.0, 1.0);
    let k = scene_scale(&lengths);
    let (ps, qs) = (up(p, k), up(q, k));
    let point = if t <= 0.5 { ps + (qs - ps) * t } else { qs + (ps - qs) * (1.0 - t) };
    let normal = unit(&(rot.column(best) * f64::from(start[best]))).unwrap_or_else(Vec3::z);
    hit_at(T::of(t), crate::real::scale2v(&point, -k).map(T::of), normal, tie)
}

/// A hit with its normal rounded to `T`; a point beyond the type's range is a
/// degenerate miss.
fn hit_at<T: Real>(t: T, point: Vec3<T>, normal: Vec3<f64>, degenerate: bool) -> Intersection<T> {
    if !crate::real::finite3(&point) {
        return Intersection::DEGENERATE;
    }
    Intersection {
        hit: Some(SegmentHit { t, point, normal: normal.map(T::of), barycentric: None }),
        parallel: false,
        degenerate,
    }
}

/// `s n h − M · (p − c)` (`M` the picked axis of `‖q‖² R(q)`, `n = ‖q‖²`):
/// lengths `[p, c, h]`, units `[q, e_i, s]` — `n` times the numerator of the
/// time face `s` of axis `i` is crossed.
fn entry_numerator<N: Ring>(l: &[N; 7], u: &[N; 8]) -> N {
    let (a, n) = picked_axis(u);
    let d = sub3(at(l, 0), at(l, 3));
    u[7].mul(&n.mul(&l[6])).sub(&dot3(refs(&a), refs(&d)))
}

/// `N_i D_j − N_j D_i` with `N = s n h − M · (p − c)`, `D = M · (q − p)`:
/// lengths `[p, q, c, h_i, h_j]`, units `[q, e_i, s_i, e_j, s_j]`.
fn time_order<N: Ring>(l: &[N; 11], u: &[N; 12]) -> N {
    let qt = [&u[0], &u[1], &u[2], &u[3]];
    let (ax, n) = (quaternion_axes(qt), norm2(qt));
    let (ai, aj) = (select(&u[4..7], &ax), select(&u[8..11], &ax));
    let (pc, qp) = (sub3(at(l, 0), at(l, 6)), sub3(at(l, 3), at(l, 0)));
    let ni = u[7].mul(&n.mul(&l[9])).sub(&dot3(refs(&ai), refs(&pc)));
    let nj = u[11].mul(&n.mul(&l[10])).sub(&dot3(refs(&aj), refs(&pc)));
    let di = dot3(refs(&ai), refs(&qp));
    let dj = dot3(refs(&aj), refs(&qp));
    ni.mul(&dj).sub(&nj.mul(&di))
}
