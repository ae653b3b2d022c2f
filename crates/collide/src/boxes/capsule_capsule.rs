//! Capsule–capsule contact.

use super::poly::{Ring, at, cross3, dot3, ratio, refs, scaled_f64, sign_of, sub3, value_of};
use super::sphere_capsule::{Foot, foot_of, foot_values, reach_test, touch_lecture};
use super::{all_finite, fallback_normal, finish, scene_scale, stage, up, up1, wide3};
use crate::contact::Contact;
use crate::exact::{Estimate, P3, Sign, triple_product};
use crate::real::{Real, Vec3};
use crate::shapes::Capsule;

/// Ericson's `EPSILON` in `ClosestPtSegmentSegment` (*Real-Time Collision
/// Detection*, §5.1.9): a segment whose **squared** length is at most this is
/// treated as a point. An absolute number, as in the book (1e-6, in the units
/// of the scene squared): so an axis shorter than `1e-3` is a point to the
/// lecture's form, which is where it goes wrong by design (a capsule of
/// length `5e-4` reaches `5e-4` less far than it does).
pub const SEGMENT_EPSILON: f64 = 1e-6;

/// Contact between capsules `a` and `b`, **the lecture's form**: the closest
/// points `p_a`, `p_b` of the two axes by Ericson's `ClosestPtSegmentSegment`
/// (§5.1.9) as written — [`SEGMENT_EPSILON`] for degenerate segments, the
/// parallel test `denom ≠ 0`, an arbitrary `s = 0` for parallel axes, then
/// `t` and the clamps — and the sphere–sphere formulas on them:
///
/// ```text
/// contact when ‖p_a − p_b‖ ≤ r_a + r_b;  n = (p_a − p_b)/‖p_a − p_b‖,
/// point = p_b + r_b n,  depth = r_a + r_b − ‖p_a − p_b‖
/// ```
///
/// Axes that meet as computed (a zero distance, or one that underflowed) take
/// the normal `+z`, flagged.
pub fn contact_capsule_capsule_lecture<T: Real>(a: &Capsule<T>, b: &Capsule<T>) -> Option<Contact<T>> {
    super::lecture_finite(contact_capsule_capsule_lecture_raw(a, b))
}

fn contact_capsule_capsule_lecture_raw<T: Real>(a: &Capsule<T>, b: &Capsule<T>) -> Option<Contact<T>> {
    let (pa, pb) = closest_pt_segment_segment_lecture(&a.start, &a.end, &b.start, &b.end);
    touch_lecture(&pa, a.radius, &pb, b.radius)
}

/// Ericson's `ClosestPtSegmentSegment` (§5.1.9) as written: the closest points
/// of `[p1, q1]` and `[p2, q2]` (a squared length at most [`SEGMENT_EPSILON`]
/// is a point; parallel segments take `s = 0`). Shared by the capsule
/// forms' lecture methods.
pub(crate) fn closest_pt_segment_segment_lecture<T: Real>(
    p1: &Vec3<T>,
    q1: &Vec3<T>,
    p2: &Vec3<T>,
    q2: &Vec3<T>,
) -> (Vec3<T>, Vec3<T>) {
    let eps = T::of(SEGMENT_EPSILON);
    let clamp01 = |x: T| x.max(T::zero()).min(T::one());
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let (s, t);
    if a <= eps && e <= eps {
        return (*p1, *p2);
    }
    if a <= eps {
        s = T::zero();
        t = clamp01(f / e);
    } else {
        let c = d1.dot(&r);
        if e <= eps {
            t = T::zero();
            s = clamp01(-c / a);
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let s0 = if denom != T::zero() { clamp01((b * f - c * e) / denom) } else { T::zero() };
            let t0 = (b * s0 + f) / e;
            if t0 < T::zero() {
                t = T::zero();
                s = clamp01(-c / a);
            } else if t0 > T::one() {
                t = T::one();
                s = clamp01((b - c) / a);
            } else {
                t = t0;
                s = s0;
            }
        }
    }
    (p1 + d1 * s, p2 + d2 * t)
}

/// Contact between capsules `a` and `b`, **robust form**: the format's
/// formulas with the decisions exact. The squared distance of two segments,
/// a convex function of their parameters `(s, t) ∈ [0, 1]²`, is least either
/// at the critical point of the two lines, when the axes are not parallel
/// and it lies in the square (decided from the signs of `s·denom`,
/// `t·denom` and `denom − s·denom`, `denom − t·denom`, `denom = ‖d_a × d_b‖²`),
/// or on the square's boundary, where it is an end of one axis against the
/// other axis (the point–segment tests of
/// [`super::contact_sphere_capsule`]). So: between the lines, contact when
/// `(n · (A0 − B0))² ≤ (r_a + r_b)² ‖n‖²` (`n = d_a × d_b`) and the axes meet
/// when `n · (A0 − B0) = 0`; otherwise contact when any end is within
/// `r_a + r_b` of the other axis, and the axes meet when one is on it. The
/// normal between the lines is `±n/‖n‖` (formed to `2^−40`, the sign exact);
/// at an end, as for a sphere. Parallel axes side by side are answered at
/// an end, one pair of the region's closest points.
///
/// **Degenerate input.** Axes that meet: normal `+z`, point
/// `p_b + r_b (0, 0, 1)`, depth `r_a + r_b`, flagged. A zero-length axis is a
/// sphere. A non-finite input is no contact.
pub fn contact_capsule_capsule<T: Real>(a: &Capsule<T>, b: &Capsule<T>) -> Option<Contact<T>> {
    let (a0, a1, b0, b1) = (wide3(&a.start), wide3(&a.end), wide3(&b.start), wide3(&b.end));
    let (ra, rb) = (a.radius.wide(), b.radius.wide());
    let l12 = [a0[0], a0[1], a0[2], a1[0], a1[1], a1[2], b0[0], b0[1], b0[2], b1[0], b1[1], b1[2]];
    let lengths = [a0[0], a0[1], a0[2], a1[0], a1[1], a1[2], b0[0], b0[1], b0[2], b1[0], b1[1], b1[2], ra, rb];
    if !all_finite(&lengths) {
        return None;
    }
    let k = scene_scale(&lengths);
    let (ras, rbs) = (up1(ra, k), up1(rb, k));
    // The floating-point stage certifies most signs; the exact code decides
    // the rest.
    let settled = stage::capsule_capsule(&lengths);
    let weights = [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [-1.0, 0.0, 1.0], [0.0, 1.0, 0.0], [0.0, -1.0, 1.0]];
    let crit = |i: usize| stage::or_exact(settled.critical[i], || sign_of!(critical, l12, weights[i]));
    let between = crit(0) == Sign::Positive && (1..5).all(|i| crit(i) != Sign::Negative);
    if between {
        if stage::or_exact(settled.skew, || sign_of!(skew_reach, lengths, [])) == Sign::Positive {
            return None;
        }
        let side = triple_product(a0, a1, b0, b1, b0, a0);
        let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let n: [Estimate; 3] = e.map(|e| value_of!(normal_component, 2, l12, e));
        let denom = value_of!(critical, 4, l12, [0.0, 0.0, 1.0]);
        let t = ratio(value_of!(critical, 4, l12, [0.0, 1.0, 0.0]), denom).clamp(0.0, 1.0);
        let (b0s, b1s) = (up(b0, k), up(b1, k));
        let pb = if t <= 0.5 { b0s + (b1s - b0s) * t } else { b1s + (b0s - b1s) * (1.0 - t) };
        if side == Sign::Zero {
            let z = fallback_normal();
            return Some(finish(pb + z * rbs, z, ras + rbs, k, true));
        }
        let nhat = Estimate::unit_vector(n).map(|d| Vec3::new(d[0], d[1], d[2])).unwrap_or_else(fallback_normal);
        let normal = if side == Sign::Negative { -nhat } else { nhat };
        let ns = Vec3::from(n.map(|x| scaled_f64(x, 2 * i64::from(k))));
        let nr = scaled_f64(value_of!(normal_offset, 3, l12, []), 3 * i64::from(k));
        let dist = nr.abs() / crate::real::stable_norm(&ns);
        return Some(finish(pb + normal * rbs, normal, (ras + rbs) - dist, k, false));
    }
    // The boundary of the square: each end against the other axis.
    let ends: [(P3, P3, P3, bool); 4] =
        [(a0, b0, b1, true), (a1, b0, b1, true), (b0, a0, a1, false), (b1, a0, a1, false)];
    // The nearest of the ends' distances, compared exactly: near-parallel
    // axes put them within far less than the values' 2^−40 of each other.
    let mut best: Option<(Feature, bool, Contact<T>)> = None;
    for (p, s0, s1, from_a) in ends {
        let foot: Foot = foot_of(p, s0, s1);
        let (contact, on) = reach_test(p, s0, s1, ra, rb, foot);
        if !contact {
            continue;
        }
        let near = foot_values(p, s0, s1, foot, k, on);
        let pb = if from_a { near.q } else { up(p, k) };
        let found = match near.dir {
            None => {
                let z = fallback_normal();
                finish(pb + z * rbs, z, ras + rbs, k, true)
            }
            Some(d) => {
                let n = if from_a { d } else { -d };
                finish(pb + n * rbs, n, (ras + rbs) - near.dist, k, false)
            }
        };
        let feature = Feature::of(p, s0, s1, foot);
        let better = match &best {
            None => true,
            Some((other, met, _)) => (on && !met) || (on == *met && feature.nearer_than(other)),
        };
        if better {
            best = Some((feature, on, found));
        }
    }
    best.map(|(_, _, k)| k)
}

/// A point `p` and the feature of a segment nearest it: an end (`a`), or the
/// segment `[a, b]` itself when the foot lies strictly between its ends.
#[derive(Clone, Copy)]
struct Feature {
    p: P3,
    a: P3,
    b: P3,
    line: bool,
}

impl Feature {
    fn of(p: P3, s0: P3, s1: P3, foot: Foot) -> Self {
        match foot {
            Foot::Start => Self { p, a: s0, b: s1, line: false },
            Foot::End => Self { p, a: s1, b: s0, line: false },
            Foot::Between => Self { p, a: s0, b: s1, line: true },
        }
    }

    /// Whether this squared distance is strictly below `o`'s, exactly.
    fn nearer_than(&self, o: &Self) -> bool {
        let (x, y) = (self, o);
        let l = [
            x.p[0], x.p[1], x.p[2], x.a[0], x.a[1], x.a[2], x.b[0], x.b[1], x.b[2], y.p[0], y.p[1], y.p[2], y.a[0],
            y.a[1], y.a[2], y.b[0], y.b[1], y.b[2],
        ];
        let flag = |line: bool| if line { [1.0, 0.0] } else { [0.0, 1.0] };
        let (fx, fy) = (flag(x.line), flag(y.line));
        stage::or_exact(stage::distance_order(&l, [x.line, y.line]), || {
            sign_of!(distance_order, l, [fx[0], fx[1], fy[0], fy[1]])
        }) == Sign::Negative
    }
}

/// `n_1 d_2 − n_2 d_1` for two squared distances `n_i/d_i` from a point `p` to
/// a feature: the end `a` (`n = ‖p − a‖²`, `d = 1`) or the line through
/// `a` and `b` (`n = ‖(p − a) × (b − a)‖²`, `d = ‖b − a‖²`), picked by the units
/// `[line, 1 − line]` of each. Homogeneous in the lengths whichever is picked
/// (each quotient has degree 2). Lengths `[p_1, a_1, b_1, p_2, a_2, b_2]`.
fn distance_order<N: Ring>(l: &[N; 18], u: &[N; 4]) -> N {
    let part = |o: usize, line: &N, end: &N| {
        let (v, d) = (sub3(at(l, o), at(l, o + 3)), sub3(at(l, o + 6), at(l, o + 3)));
        let x = cross3(refs(&v), refs(&d));
        let num = line.mul(&dot3(refs(&x), refs(&x))).add(&end.mul(&dot3(refs(&v), refs(&v))));
        let den = line.mul(&dot3(refs(&d), refs(&d))).add(end);
        (num, den)
    };
    let (n1, d1) = part(0, &u[0], &u[1]);
    let (n2, d2) = part(9, &u[2], &u[3]);
    n1.mul(&d2).sub(&n2.mul(&d1))
}

/// `w_s · s_num + w_t · t_num + w_d · denom`, Ericson's numerators and
/// denominator of the lines' critical parameters (`s = s_num/denom`,
/// `t = t_num/denom`, `denom = ‖d_a‖²‖d_b‖² − (d_a · d_b)²`): lengths
/// `[A0, A1, B0, B1]`, units `[w_s, w_t, w_d]`.
fn critical<N: Ring>(l: &[N; 12], u: &[N; 3]) -> N {
    let (da, db, r) = (sub3(at(l, 3), at(l, 0)), sub3(at(l, 9), at(l, 6)), sub3(at(l, 0), at(l, 6)));
    let a = dot3(refs(&da), refs(&da));
    let e = dot3(refs(&db), refs(&db));
    let b = dot3(refs(&da), refs(&db));
    let c = dot3(refs(&da), refs(&r));
    let f = dot3(refs(&db), refs(&r));
    let denom = a.mul(&e).sub(&b.mul(&b));
    let s = b.mul(&f).sub(&c.mul(&e));
    let t = a.mul(&f).sub(&b.mul(&c));
    u[0].mul(&s).add(&u[1].mul(&t)).add(&u[2].mul(&denom))
}

/// `(n · (A0 − B0))² − (ra + rb)² ‖n‖²`, `n = d_a × d_b`: lengths
/// `[A0, A1, B0, B1, ra, rb]`.
fn skew_reach<N: Ring>(l: &[N; 14], _: &[N; 0]) -> N {
    let (da, db, r) = (sub3(at(l, 3), at(l, 0)), sub3(at(l, 9), at(l, 6)), sub3(at(l, 0), at(l, 6)));
    let n = cross3(refs(&da), refs(&db));
    let nr = dot3(refs(&n), refs(&r));
    let reach = l[12].add(&l[13]);
    nr.mul(&nr).sub(&reach.mul(&reach).mul(&dot3(refs(&n), refs(&n))))
}

/// `e · (d_a × d_b)`: lengths `[A0, A1, B0, B1]`, units `[e]`.
fn normal_component<N: Ring>(l: &[N; 12], u: &[N; 3]) -> N {
    let (da, db) = (sub3(at(l, 3), at(l, 0)), sub3(at(l, 9), at(l, 6)));
    dot3(at(u, 0), refs(&cross3(refs(&da), refs(&db))))
}

/// `(d_a × d_b) · (A0 − B0)`: lengths `[A0, A1, B0, B1]`.
fn normal_offset<N: Ring>(l: &[N; 12], _: &[N; 0]) -> N {
    let (da, db, r) = (sub3(at(l, 3), at(l, 0)), sub3(at(l, 9), at(l, 6)), sub3(at(l, 0), at(l, 6)));
    dot3(refs(&cross3(refs(&da), refs(&db))), refs(&r))
}
