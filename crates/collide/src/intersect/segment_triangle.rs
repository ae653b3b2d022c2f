//! Segment against triangle: where the segment `q0 q1` crosses the triangle
//! `v0 v1 v2`.

use super::hit::{Intersection, SegmentHit};
use super::segment_plane::point_on_segment;
use crate::exact::{self, ESTIMATE_REL_ERR, Estimate, P3, Sign};
use crate::real::{Real, Vec3, finite3, to_f64_3, try_normalize_stable};
use crate::shapes::{Segment, Triangle};

/// The lecture's segment–triangle intersection: the plane hit, then `s`, `t` by
/// the dot-product formula.
///
/// **Formula.** With `u = v1 − v0`, `v = v2 − v0` and the face normal
/// `n = u × v`:
///
/// 1. the plane hit, the lecture's segment–plane formula on the triangle's plane
///    (see [`intersect_segment_plane_lecture`](super::intersect_segment_plane_lecture)):
///    `r = n · (v0 − q0) / n · (q1 − q0)`; parallel when the denominator is
///    exactly `0`, a miss unless `0 ≤ r ≤ 1`; `P = q0 + r (q1 − q0)`;
/// 2. `P`'s parametric coordinates in the plane, `P = v0 + s u + t v`: with
///    `w = P − v0`, dotting `w = s u + t v` with `u` and with `v` gives the
///    2 × 2 system `(u·u) s + (u·v) t = w·u`, `(u·v) s + (v·v) t = w·v`, whose
///    Cramer solution is (Sunday's form, denominator negated)
///
///    ```text
///    D = (u·v)² − (u·u)(v·v)
///    s = ((u·v)(w·v) − (v·v)(w·u)) / D
///    t = ((u·v)(w·u) − (u·u)(w·v)) / D
///    ```
///
/// 3. inside iff `s ≥ 0`, `t ≥ 0`, `s + t ≤ 1` (the boundary counts); the
///    barycentric coordinates are `[1 − s − t, s, t]`.
///
/// The hit's `t` is the segment parameter `r`; `normal` is `n / ‖n‖`
/// ([`try_normalize_stable`]), never flipped toward the segment.
///
/// Source: the lecture's segment–triangle slides; D. Sunday, *Intersections of
/// Rays, Segments, Planes and Triangles in 3D* (geomalgorithms.com), whose
/// `intersect3D_RayTriangle` this is with a segment's `0 ≤ r ≤ 1`.
///
/// **Degenerate input** ([`Intersection::DEGENERATE`]: no hit, not parallel,
/// `degenerate` set): a non-finite input; `n` computing to the zero vector (a
/// zero-area triangle, or one whose cross product underflows, e.g. a `1e-300`
/// scene in `f64`); a zero-length segment (`q0 == q1`); any non-finite
/// intermediate (`n` overflowing in a `1e300` scene, `r` overflowing, `D`
/// zero or non-finite for a sliver). Never NaN, never a panic.
///
/// **Deviation from the book**: none in the arithmetic; the degenerate checks
/// are added.
pub fn intersect_segment_triangle_lecture<T: Real>(seg: &Segment<T>, tri: &Triangle<T>) -> Intersection<T> {
    let [v0, v1, v2] = tri.vertices;
    let (q0, q1) = (seg.start, seg.end);
    if !(finite3(&v0) && finite3(&v1) && finite3(&v2) && finite3(&q0) && finite3(&q1)) {
        return Intersection::DEGENERATE;
    }
    let u = v1 - v0;
    let v = v2 - v0;
    let n = u.cross(&v);
    if n == Vec3::zeros() || q0 == q1 || !finite3(&n) {
        return Intersection::DEGENERATE;
    }
    // 1. The plane hit.
    let dir = q1 - q0;
    let denom = n.dot(&dir);
    let num = n.dot(&(v0 - q0));
    if !denom.finite() || !num.finite() {
        return Intersection::DEGENERATE;
    }
    if denom == T::zero() {
        return Intersection::PARALLEL;
    }
    let r = num / denom;
    if !r.finite() {
        return Intersection::DEGENERATE;
    }
    if r < T::zero() || r > T::one() {
        return Intersection::MISS;
    }
    let p = q0 + dir * r;
    // 2. s, t by the dot-product formula.
    let w = p - v0;
    let (uu, uv, vv, wu, wv) = (u.dot(&u), u.dot(&v), v.dot(&v), w.dot(&u), w.dot(&v));
    let d = uv * uv - uu * vv;
    if !d.finite() || d == T::zero() {
        return Intersection::DEGENERATE;
    }
    let s = (uv * wv - vv * wu) / d;
    let t = (uv * wu - uu * wv) / d;
    if !s.finite() || !t.finite() || !finite3(&p) {
        return Intersection::DEGENERATE;
    }
    // 3. Inside?
    if s < T::zero() || t < T::zero() || s + t > T::one() {
        return Intersection::MISS;
    }
    let Some(normal) = try_normalize_stable(&n) else {
        return Intersection::DEGENERATE;
    };
    Intersection::hit(SegmentHit { t: r, point: p, normal, barycentric: Some([T::one() - s - t, s, t]) })
}

/// Robust segment–triangle intersection: hit, miss and parallel decided exactly
/// for every finite input.
///
/// **Classification** (exact signs from [`exact::orient3d`], Shewchuk's
/// convention `orient3d(a, b, c, d) = det[a − d, b − d, c − d]`):
///
/// 1. The endpoints against the triangle's plane:
///    `s_i = orient3d(v0, v1, v2, q_i) = −n · (q_i − v0)` with
///    `n = (v1 − v0) × (v2 − v0)`.
///    - `s0 = s1 = 0`: the segment lies in the plane — **parallel** (no hit,
///      even where it overlaps the triangle: the fixture format's convention),
///      unless the triangle has zero area (then **degenerate**);
///    - both positive or both negative: **parallel** if
///      `det[v1 − v0, v2 − v0, q1 − q0] = n · (q1 − q0) = 0` exactly
///      ([`exact::triple_product`]), else a **miss** (this is how a segment
///      stopping `1e-300` short of the face is told from one touching it);
///    - otherwise the segment reaches the plane (an endpoint on it counts).
/// 2. The segment's line against the edges (Ericson §5.3.4, the scalar triple
///    products with apex `q0`, `r = q1 − q0`):
///
///    ```text
///    α' = det[r, v2 − q0, v1 − q0] = orient3d(q1, v2, v1, q0)
///    β' = det[r, v0 − q0, v2 − q0] = orient3d(q1, v0, v2, q0)
///    γ' = det[r, v1 − q0, v0 − q0] = orient3d(q1, v1, v0, q0)
///    ```
///
///    By multilinearity `α' + β' + γ' = −r · n = s1 − s0`, which is non-zero
///    here and whose sign `σ` follows from step 1. The line passes through the
///    closed triangle iff none of `α'`, `β'`, `γ'` has sign `−σ`; a zero means
///    through an edge, two zeros through a vertex: both **hit**.
///
/// **Values.** `t = s0 / (s0 − s1) = |s0| / (|s0| + |s1|)` (no cancellation:
/// opposite signs), exactly `0` or `1` when an endpoint lies on the plane; the
/// barycentric coordinates are `[α', β', γ'] / (α' + β' + γ')`, computed as
/// magnitudes over their sum so that they are `≥ 0` and sum to 1 (within
/// rounding). Both use [`Estimate`]s of the volumes whose error relative to
/// their sum is at most [`ESTIMATE_REL_ERR`] (fast values where their error
/// bounds allow, exact ones otherwise), so they are accurate to about `2^−40`
/// at every scale (volumes of `1e300` scenes, `~1e900`, included). The point is computed from the nearer endpoint (see
/// [`intersect_segment_plane`](super::intersect_segment_plane)). The normal is
/// the face normal `(v1 − v0) × (v2 − v0)` ([`exact::cross_estimate`], exact
/// signs and relative accuracy per component, so neither overflow nor
/// underflow) normalized, never flipped.
///
/// **Precision.** Predicates and values are evaluated on the inputs' `f64`
/// values (exact for `f32`) and rounded to `T` once at the end: the `f32`
/// answer is the `f64` answer rounded.
///
/// **Degenerate input** ([`Intersection::DEGENERATE`]: no hit, not parallel,
/// `degenerate` set): a non-finite input; a zero-length segment (`q0 == q1`
/// exactly); a zero-area triangle (collinear vertices exactly, checked when
/// both endpoints are coplanar with it — otherwise the triangle has area). No
/// NaN and no panic for any input.
///
/// **Cost: a filter first.** Every volume above is first evaluated once in
/// plain `f64` with a static forward error bound (`exact::filter`, in the
/// manner of Shewchuk's stage-A filters), the differences and cross products
/// shared: `n = (v1 − v0) × (v2 − v0)` once for both `s_i = −n · (q_i − v0)`,
/// and `m = r × (v2 − q0)`, `m' = r × (v1 − q0)` for the edge volumes
/// (`α' = m · (v1 − q0)`, `β' = m · (q0 − v0)`, `γ' = −m' · (q0 − v0)`, the
/// triple products above rewritten cyclically). A volume whose magnitude
/// exceeds its bound has its exact sign; a miss by the plane is told from a
/// parallel segment when `|s1 − s0|` exceeds both bounds. For a hit the
/// filtered volumes are used as the values when their bounds make each set
/// (`s0, s1`; `α', β', γ'`; the normal's components) accurate to
/// [`ESTIMATE_REL_ERR`] of its sum, so `t`, the barycentrics and the normal
/// come straight from them (`t = |s0| / (|s0| + |s1|)`, the normal
/// `n / ‖n‖`). Where a volume is too close to zero to call or a set is not
/// accurate enough (a segment through or within ulps of an edge or a vertex,
/// an endpoint on the plane, a near-parallel segment, a sliver, a scene far
/// from the origin), stage B re-evaluates just those volumes in compensated
/// arithmetic (`exact::compensated`: differences held exactly,
/// error-free products and sums, a bound of order `u²` times the permanent
/// that is `0` when every operation was exact) and decides with exact signs,
/// zeros included: a line through an edge or a vertex, an endpoint on the
/// plane, a segment exactly parallel or coplanar, a zero-area triangle (its
/// compensated normal exactly zero). Only when an input exceeds `2^63` in
/// magnitude or has a non-zero coordinate below `2^−250`, or a value is an
/// exact zero whose roundings stage B cannot see cancel, is the query
/// answered by the general path below, unchanged: [`exact::orient3d_estimate`]
/// (its own scaled filter, then [`exact::BigFloat`], which allocates) with
/// [`Estimate::refine_jointly`]. For random input stage A decides almost
/// every query: about 36 multiplications and 50 additions for a hit, as many
/// for a segment through the plane that misses by an edge (the three edge
/// volumes are formed, then tested at once), half that for a miss by the
/// plane; stage B adds a few hundred operations where it runs; no
/// allocation.
///
/// Source: Ericson, *Real-Time Collision Detection*, §5.3.4
/// (`IntersectSegmentTriangle` via scalar triple products), with exact
/// predicates after Shewchuk. **Deviation from the lecture**: no `s`, `t`
/// solve; classification is by exact signs, values come from the same volumes.
pub fn intersect_segment_triangle<T: Real>(seg: &Segment<T>, tri: &Triangle<T>) -> Intersection<T> {
    match filtered(seg, tri) {
        // The fields themselves rather than the constant: a copy of
        // `Intersection::MISS` writes the whole (unused) hit payload too.
        Filtered::Miss => Intersection { hit: None, parallel: false, degenerate: false },
        Filtered::Parallel => Intersection::PARALLEL,
        Filtered::Degenerate => Intersection::DEGENERATE,
        Filtered::Hit(h) => {
            // Every input is within the filter's range, so q1 − q0 is finite.
            let point = point_in_range(to_f64_3(&seg.start), to_f64_3(&seg.end), h.t, h.one_minus_t);
            let vec = |p: [f64; 3]| Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]));
            let w = h.barycentric;
            Intersection::hit(SegmentHit {
                t: T::of(h.t),
                point: vec(point),
                normal: vec(h.normal),
                barycentric: Some([T::of(w[0]), T::of(w[1]), T::of(w[2])]),
            })
        }
        Filtered::Undecided => general(seg, tri),
    }
}

/// What the filter made of a query.
enum Filtered {
    /// A miss, decided.
    Miss,
    /// Parallel, decided: `n · (q1 − q0) = 0` exactly (coplanar included,
    /// for a triangle of non-zero area).
    Parallel,
    /// Coplanar with a triangle of exactly zero area, decided.
    Degenerate,
    /// A hit, decided, with values accurate to [`ESTIMATE_REL_ERR`].
    Hit(FilteredHit),
    /// Not decided (or not accurate enough): the general path answers.
    Undecided,
}

/// A hit's values from the filter, in `f64`.
struct FilteredHit {
    t: f64,
    one_minus_t: f64,
    barycentric: [f64; 3],
    normal: [f64; 3],
}

/// Smallest `‖n‖²` normalized by the filter (2^−960): above it the sum of
/// squares keeps full relative precision (its largest term is normal with 60
/// bits to spare); below it the general path normalizes by scaling.
const NORMAL_MIN_SQUARED: f64 = 1.0261342003245941e-289;

/// The filter of [`intersect_segment_triangle`] (see its **Cost** section):
/// stage A, `f64` volumes with their error bounds, deciding the
/// classification when every sign it needs is certain and the values when
/// they are accurate to [`ESTIMATE_REL_ERR`]; where it cannot, stage B
/// ([`stage_b`]) takes over with the volumes it has.
///
/// Stage B receives the query itself rather than the `f64` points: passing
/// fifteen values to a call gives them a home in memory, written and read
/// back in different widths, which stalls the common path.
#[inline(always)]
fn filtered<T: Real>(seg: &Segment<T>, tri: &Triangle<T>) -> Filtered {
    use crate::exact::filter::{cross, in_fast_range_points, sub, triple};
    let (a, b, c) = (to_f64_3(&tri.vertices[0]), to_f64_3(&tri.vertices[1]), to_f64_3(&tri.vertices[2]));
    let (q0, q1) = (to_f64_3(&seg.start), to_f64_3(&seg.end));
    let inputs = [a, b, c, q0, q1];
    if !in_fast_range_points(inputs) {
        return Filtered::Undecided;
    }
    // 1. The plane: d_i = n · (q_i − v0) = −s_i.
    let (e1, e2) = (sub(b, a), sub(c, a));
    let (n, n_perm) = cross(e1, e2);
    let w0 = sub(q0, a);
    let d0 = triple(n, n_perm, w0);
    let d1 = triple(n, n_perm, sub(q1, a));
    let stage_a = |edges| StageA { d: [d0, d1], n, n_perm, edges };
    if !(d0.decided() && d1.decided()) {
        return stage_b(seg, tri, stage_a([None; 3]));
    }
    let d1_positive = d1.value > 0.0;
    if (d0.value > 0.0) == d1_positive {
        // Both ends strictly on one side: a miss unless n · (q1 − q0) =
        // d1 − d0 is exactly 0 (parallel), impossible when the two certainly
        // differ.
        if d0.differs_from(&d1) {
            return Filtered::Miss;
        }
        return stage_b(seg, tri, stage_a([None; 3]));
    }
    // 2. The edges. σ = sign(s1) = −sign(d1); a weight of sign −σ = sign(d1)
    // is a miss. pa = v0 − q0 = −w0 exactly (rounding is symmetric).
    let r = sub(q1, q0);
    let (pb, pc) = (sub(b, q0), sub(c, q0));
    let (m, m_perm) = cross(r, pc);
    let alpha = triple(m, m_perm, pb); // α' = (r × pc) · pb
    let beta = triple(m, m_perm, w0); // β' = −(r × pc) · pa = m · w0
    let (m2, m2_perm) = cross(r, pb);
    let gamma_neg = triple(m2, m2_perm, w0); // −γ' = −(r × pb) · pa = m2 · w0
    // All three volumes, then one test: a miss when any of them is decided
    // with the miss sign (one branch rather than one per edge, each taken at
    // random on a mix of queries).
    let miss = (alpha.decided() & ((alpha.value > 0.0) == d1_positive))
        | (beta.decided() & ((beta.value > 0.0) == d1_positive))
        | (gamma_neg.decided() & ((gamma_neg.value > 0.0) != d1_positive));
    if miss {
        return Filtered::Miss;
    }
    let edges = [alpha, beta, gamma_neg];
    if !(alpha.decided() && beta.decided() && gamma_neg.decided()) {
        return stage_b(seg, tri, stage_a(edges.map(Some)));
    }
    // 3. A hit: the values, if the filtered volumes are accurate enough.
    let normal = stage_a_normal(n, n_perm);
    match hit_values(&[d0, d1], &edges, &normal) {
        Some(hit) => Filtered::Hit(hit),
        None => stage_b(seg, tri, stage_a(edges.map(Some))),
    }
}

/// Stage A's volumes as far as it computed them, for stage B to reuse.
#[derive(Clone, Copy)]
struct StageA {
    /// `d0`, `d1`.
    d: [crate::exact::filter::Filtered; 2],
    /// The face normal's components and their permanents.
    n: P3,
    n_perm: P3,
    /// `α'`, `β'`, `−γ'`, if stage A reached them.
    edges: [Option<crate::exact::filter::Filtered>; 3],
}

/// Stage A's face normal components with their bounds.
#[inline(always)]
fn stage_a_normal(n: P3, n_perm: P3) -> [crate::exact::filter::Filtered; 3] {
    let nb = crate::exact::filter::cross_bounds(n_perm);
    let f = |i: usize| crate::exact::filter::Filtered { value: n[i], bound: nb[i] };
    [f(0), f(1), f(2)]
}

/// The hit's values from volumes known to their bounds, or `None` when a set
/// is not accurate to [`ESTIMATE_REL_ERR`] of its sum (or the normal is too
/// small to normalize plainly). An exact zero (bound `0`, from stage B) is
/// an endpoint on the plane: `t` is then exactly `0` or `1`.
#[inline(always)]
fn hit_values(
    d: &[crate::exact::filter::Filtered; 2],
    w: &[crate::exact::filter::Filtered; 3],
    n: &[crate::exact::filter::Filtered; 3],
) -> Option<FilteredHit> {
    use crate::exact::filter::jointly_accurate;
    let (s0, s1) = (d[0].value.abs(), d[1].value.abs());
    let s_sum = s0 + s1;
    let (t, one_minus_t) = if s0 == 0.0 {
        (0.0, 1.0)
    } else if s1 == 0.0 {
        (1.0, 0.0)
    } else if jointly_accurate(d[0].bound + d[1].bound, s_sum, ESTIMATE_REL_ERR) {
        // One division: x · fl(1/sum) is within 2 roundings of x / sum
        // (clamped: it may round past 1 where the quotient cannot).
        let inv = 1.0 / s_sum;
        ((s0 * inv).min(1.0), (s1 * inv).min(1.0))
    } else {
        return None;
    };
    let wa = [w[0].value.abs(), w[1].value.abs(), w[2].value.abs()];
    let w_sum = (wa[0] + wa[1]) + wa[2];
    let w_err = (w[0].bound + w[1].bound) + w[2].bound;
    let na = [n[0].value.abs(), n[1].value.abs(), n[2].value.abs()];
    let n_sum = (na[0] + na[1]) + na[2];
    let n_err = (n[0].bound + n[1].bound) + n[2].bound;
    let nn = (n[0].value * n[0].value + n[1].value * n[1].value) + n[2].value * n[2].value;
    if !(jointly_accurate(w_err, w_sum, ESTIMATE_REL_ERR)
        && jointly_accurate(n_err, n_sum, ESTIMATE_REL_ERR)
        && nn >= NORMAL_MIN_SQUARED)
    {
        return None;
    }
    let (inv_len, inv_w) = (1.0 / nn.sqrt(), 1.0 / w_sum);
    Some(FilteredHit {
        t,
        one_minus_t,
        barycentric: [(wa[0] * inv_w).min(1.0), (wa[1] * inv_w).min(1.0), (wa[2] * inv_w).min(1.0)],
        normal: [n[0].value * inv_len, n[1].value * inv_len, n[2].value * inv_len],
    })
}

/// Stage B of the filter: the volumes stage A could not decide (or not
/// accurately enough) evaluated again in compensated arithmetic
/// ([`crate::exact::compensated`]: bounds of order `u²` times the permanent,
/// and `0` for a volume whose every operation was exact, so exact zeros —
/// an endpoint on the plane, a line through an edge or a vertex, a segment
/// exactly parallel — are certified too). The decisions are those of stage A
/// with exact signs, zeros included:
///
/// - `d0`, `d1` both exactly zero (coplanar): left to the general path, which
///   tells a parallel segment from a zero-area triangle;
/// - same non-zero sign: a miss if `d1 − d0 = n · (q1 − q0)` is certainly
///   non-zero, parallel if both are exact and equal;
/// - otherwise the segment reaches the plane, and with `σ = sign(s1 − s0)`
///   (`−sign(d1)`, or `sign(d0)` when `d1 = 0`) a weight of sign `−σ` is a
///   miss; zero weights are edges and vertices (hits).
///
/// A hit's values come from stage A's volumes where they are accurate to
/// [`ESTIMATE_REL_ERR`] and from the compensated ones (accurate to about
/// `u`) otherwise; when every value is recomputed, `−γ'` is derived from
/// the others ([`third_edge`]). Inputs outside stage B's domain (a coordinate non-zero and
/// below `2^−250`), a zero-length segment, and values still undecided go to
/// the general path.
#[inline(never)]
fn stage_b<T: Real>(seg: &Segment<T>, tri: &Triangle<T>, sa: StageA) -> Filtered {
    use crate::exact::compensated::{self as cb, Cross, diff, differ, dot, sign_known};
    use crate::exact::filter::Filtered as F;
    let (a, b, c) = (to_f64_3(&tri.vertices[0]), to_f64_3(&tri.vertices[1]), to_f64_3(&tri.vertices[2]));
    let (q0, q1) = (to_f64_3(&seg.start), to_f64_3(&seg.end));
    let inputs = [a, b, c, q0, q1];
    if !cb::in_range_points(inputs) || exact::points_equal(q0, q1) {
        return Filtered::Undecided;
    }
    let w0 = diff(q0, a);
    let mut n_dd: Option<Cross> = None;
    let face = |n_dd: &mut Option<Cross>| *n_dd.get_or_insert_with(|| cb::cross(&diff(b, a), &diff(c, a)));
    let plane_dd = |n: &Cross| [dot(n, &w0), dot(n, &diff(q1, a))];

    // 1. The plane.
    let classify = |d: &[F; 2], n: Option<&Cross>| -> Option<Option<Filtered>> {
        if !(sign_known(&d[0]) && sign_known(&d[1])) {
            return None;
        }
        let (g0, g1) = (Sign::of(d[0].value), Sign::of(d[1].value));
        if g0 == g1 {
            return match (g0, differ(&d[0], &d[1])) {
                // Coplanar (only compensated values are exact zeros, so `n`
                // is at hand): parallel, or degenerate for a zero-area
                // triangle (`n = 0` exactly); the general path decides what
                // the compensated normal cannot.
                (Sign::Zero, _) => Some(Some(n.map_or(Filtered::Undecided, |n| {
                    let c = n.components();
                    if c.iter().all(|x| x.bound == 0.0 && x.value == 0.0) {
                        Filtered::Degenerate
                    } else if c.iter().any(|x| x.value.abs() > x.bound) {
                        Filtered::Parallel
                    } else {
                        Filtered::Undecided
                    }
                }))),
                (_, Some(true)) => Some(Some(Filtered::Miss)),
                (_, Some(false)) => Some(Some(Filtered::Parallel)),
                // d1 − d0 = n · (q1 − q0) itself, compensated: exact for a
                // segment exactly parallel to an axis-aligned face.
                (_, None) => n.map(|n| {
                    let gap = dot(n, &diff(q1, q0));
                    Some(match (sign_known(&gap), Sign::of(gap.value)) {
                        (true, Sign::Zero) => Filtered::Parallel,
                        (true, _) => Filtered::Miss,
                        (false, _) => Filtered::Undecided,
                    })
                }),
            };
        }
        Some(None)
    };
    let (mut d, mut d_compensated) = (sa.d, false);
    match classify(&d, None) {
        Some(Some(answer)) => return answer,
        Some(None) => {}
        None => {
            let n = face(&mut n_dd);
            d = plane_dd(&n);
            d_compensated = true;
            match classify(&d, Some(&n)) {
                Some(Some(answer)) => return answer,
                Some(None) => {}
                None => return Filtered::Undecided,
            }
        }
    }

    // 2. The edges: stage A's volume where its sign is certain, else the
    // compensated one.
    let bad = match Sign::of(d[1].value) {
        Sign::Zero => -Sign::of(d[0].value),
        s => s,
    };
    let (r, pb) = (diff(q1, q0), diff(b, q0));
    let mut m_dd: Option<Cross> = None;
    let mut compensated_edge = |i: usize| -> F {
        match i {
            0 => dot(m_dd.get_or_insert_with(|| cb::cross(&r, &diff(c, q0))), &pb),
            1 => dot(m_dd.get_or_insert_with(|| cb::cross(&r, &diff(c, q0))), &w0),
            _ => dot(&cb::cross(&r, &pb), &w0),
        }
    };
    let mut w = [F { value: 0.0, bound: 0.0 }; 3];
    let mut w_compensated = [false; 3];
    for i in 0..3 {
        let x = match sa.edges[i].filter(sign_known) {
            Some(x) => x,
            None => {
                w_compensated[i] = true;
                compensated_edge(i)
            }
        };
        if !sign_known(&x) {
            return Filtered::Undecided;
        }
        // −γ' is stored negated: its miss sign is −bad.
        let miss_sign = if i == 2 { -bad } else { bad };
        if Sign::of(x.value) == miss_sign {
            return Filtered::Miss;
        }
        w[i] = x;
    }

    // 3. A hit: the values as they are if accurate enough, else every one
    // compensated.
    let normal = stage_a_normal(sa.n, sa.n_perm);
    if let Some(hit) = hit_values(&d, &w, &normal) {
        return Filtered::Hit(hit);
    }
    let n = face(&mut n_dd);
    if !d_compensated {
        d = plane_dd(&n);
    }
    for i in 0..2 {
        if !w_compensated[i] {
            w[i] = compensated_edge(i);
        }
    }
    if !w_compensated[2] {
        w[2] = third_edge(&w, &d);
    }
    match hit_values(&d, &w, &n.components()) {
        Some(hit) => Filtered::Hit(hit),
        None => Filtered::Undecided,
    }
}

/// `−γ'` from the other volumes, by `α' + β' + γ' = s1 − s0 = d0 − d1`:
/// `−γ' = ((α' + β') + d1) − d0`, with the bound the four values' bounds
/// plus the sum's own three roundings (at most `γ3` times the sum of the
/// magnitudes, within `4u`), raised for the bound's roundings. For a hit
/// the three edge volumes share one sign and the two plane values have
/// opposite signs, so every magnitude here is at most `|d0| + |d1|`, the
/// sum of the three volumes' magnitudes: from compensated values (bounds of
/// order `u²`) the result is accurate to a few `u` of that sum, which is all
/// [`hit_values`] asks, for one compensated cross product and one dot
/// product less than evaluating `−γ'` itself.
#[inline(always)]
fn third_edge(
    w: &[crate::exact::filter::Filtered; 3],
    d: &[crate::exact::filter::Filtered; 2],
) -> crate::exact::filter::Filtered {
    /// Unit roundoff (2^−53).
    const U: f64 = f64::EPSILON / 2.0;
    let value = ((w[0].value + w[1].value) + d[1].value) - d[0].value;
    let magnitudes = ((w[0].value.abs() + w[1].value.abs()) + d[1].value.abs()) + d[0].value.abs();
    let bounds = ((w[0].bound + w[1].bound) + d[1].bound) + d[0].bound;
    crate::exact::filter::Filtered { value, bound: (bounds + 4.0 * U * magnitudes) * (1.0 + 8.0 * U) }
}

/// The general path of [`intersect_segment_triangle`]: the predicates of
/// [`crate::exact`] (scaled filter, then the exact path) and
/// [`Estimate::refine_jointly`], for every input the filter leaves undecided.
#[inline(never)]
fn general<T: Real>(seg: &Segment<T>, tri: &Triangle<T>) -> Intersection<T> {
    let [v0, v1, v2] = tri.vertices;
    if !(finite3(&v0) && finite3(&v1) && finite3(&v2) && finite3(&seg.start) && finite3(&seg.end)) {
        return Intersection::DEGENERATE;
    }
    let (a, b, c) = (to_f64_3(&v0), to_f64_3(&v1), to_f64_3(&v2));
    let (q0, q1) = (to_f64_3(&seg.start), to_f64_3(&seg.end));
    if exact::points_equal(q0, q1) {
        return Intersection::DEGENERATE;
    }

    // Every value below has an exact sign; its magnitude is the fast path's,
    // refined only for hits and only as far as the hit's values need.
    const LOOSE: f64 = f64::INFINITY;
    let est = |p: [P3; 4], tol: f64| exact::orient3d_estimate(p[0], p[1], p[2], p[3], tol);

    // 1. Endpoints against the plane.
    let plane = [[a, b, c, q0], [a, b, c, q1]];
    let (e0, e1) = (est(plane[0], LOOSE), est(plane[1], LOOSE));
    let sigma = match (e0.sign, e1.sign) {
        (Sign::Zero, Sign::Zero) => {
            return if exact::collinear(a, b, c) { Intersection::DEGENERATE } else { Intersection::PARALLEL };
        }
        (x, y) if x == y => {
            return if exact::triple_product(a, b, a, c, q0, q1) == Sign::Zero {
                Intersection::PARALLEL
            } else {
                Intersection::MISS
            };
        }
        // sign(s1 − s0), the sign of α' + β' + γ'.
        (_, Sign::Zero) => -e0.sign,
        (_, s1) => s1,
    };

    // 2. The line against the edges.
    let edges = [[q1, c, b, q0], [q1, a, c, q0], [q1, b, a, q0]];
    let mut weights = [Estimate::ZERO; 3];
    for (w, edge) in weights.iter_mut().zip(&edges) {
        *w = est(*edge, LOOSE);
        if w.sign == -sigma {
            return Intersection::MISS;
        }
    }

    // A hit: the values, each set refined to ESTIMATE_REL_ERR of its sum.
    let (t, one_minus_t) = match (e0.sign, e1.sign) {
        (Sign::Zero, _) => (0.0, 1.0),
        (_, Sign::Zero) => (1.0, 0.0),
        _ => {
            let e = Estimate::refine_jointly([e0, e1], ESTIMATE_REL_ERR, |i| est(plane[i], ESTIMATE_REL_ERR));
            match Estimate::abs_fractions(e) {
                Some([t, u]) => (t, u),
                // Unreachable: s0 and s1 are non-zero here.
                None => return Intersection::DEGENERATE,
            }
        }
    };
    let weights = Estimate::refine_jointly(weights, ESTIMATE_REL_ERR, |i| est(edges[i], ESTIMATE_REL_ERR));
    let cross = Estimate::refine_jointly(exact::cross_estimate(a, b, c, LOOSE), ESTIMATE_REL_ERR, |i| {
        exact::cross_estimate(a, b, c, ESTIMATE_REL_ERR)[i]
    });
    // Both unreachable as `None`: α' + β' + γ' = s1 − s0 ≠ 0, and a triangle
    // with a point off its plane has a non-zero normal.
    let (Some(bary), Some(normal)) = (Estimate::abs_fractions(weights), Estimate::unit_vector(cross)) else {
        return Intersection::DEGENERATE;
    };
    let point = point_on_segment(q0, q1, t, one_minus_t);
    let vec = |p: [f64; 3]| Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]));
    Intersection::hit(SegmentHit {
        t: T::of(t),
        point: vec(point),
        normal: vec(normal),
        barycentric: Some(bary.map(T::of)),
    })
}

/// [`point_on_segment`] for points within the filter's range (every
/// coordinate at most `2^63` in magnitude), where `q1 − q0` cannot overflow:
/// the same arithmetic (`q0 + t (q1 − q0)` for `t ≤ u`, else
/// `q1 + (−u)(q1 − q0)`, equal to `q1 − u (q1 − q0)`), with the endpoint and
/// the factor selected rather than branched on.
#[inline(always)]
fn point_in_range(q0: P3, q1: P3, t: f64, u: f64) -> P3 {
    let near_start = t <= u;
    let f = if near_start { t } else { -u };
    let base = |i: usize| if near_start { q0[i] } else { q1[i] };
    [base(0) + f * (q1[0] - q0[0]), base(1) + f * (q1[1] - q0[1]), base(2) + f * (q1[2] - q0[2])]
}

#[cfg(test)]
mod tests;
