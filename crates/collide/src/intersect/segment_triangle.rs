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
pub fn intersect_segment_triangle_lecture<T: Real>(
    seg: &Segment<T>,
    tri: &Triangle<T>,
) -> Intersection<T> {
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
    Intersection::hit(SegmentHit {
        t: r,
        point: p,
        normal,
        barycentric: Some([T::one() - s - t, s, t]),
    })
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
/// **Cost.** Two orient3d evaluations for most misses, five plus three orient2d
/// (the normal) for hits: each a dozen `f64` operations with its error bound.
/// [`exact::BigFloat`] (and allocation) comes in only when a sign is too close
/// to call or a hit's values are not yet accurate to [`ESTIMATE_REL_ERR`]
/// jointly — near degeneracies, rarely for random input.
///
/// Source: Ericson, *Real-Time Collision Detection*, §5.3.4
/// (`IntersectSegmentTriangle` via scalar triple products), with exact
/// predicates after Shewchuk. **Deviation from the lecture**: no `s`, `t`
/// solve; classification is by exact signs, values come from the same volumes.
pub fn intersect_segment_triangle<T: Real>(seg: &Segment<T>, tri: &Triangle<T>) -> Intersection<T> {
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
            return if exact::collinear(a, b, c) {
                Intersection::DEGENERATE
            } else {
                Intersection::PARALLEL
            };
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
            let e = Estimate::refine_jointly([e0, e1], ESTIMATE_REL_ERR, |i| {
                est(plane[i], ESTIMATE_REL_ERR)
            });
            match Estimate::abs_fractions(e) {
                Some([t, u]) => (t, u),
                // Unreachable: s0 and s1 are non-zero here.
                None => return Intersection::DEGENERATE,
            }
        }
    };
    let weights = Estimate::refine_jointly(weights, ESTIMATE_REL_ERR, |i| {
        est(edges[i], ESTIMATE_REL_ERR)
    });
    let cross = Estimate::refine_jointly(
        exact::cross_estimate(a, b, c, LOOSE),
        ESTIMATE_REL_ERR,
        |i| exact::cross_estimate(a, b, c, ESTIMATE_REL_ERR)[i],
    );
    // Both unreachable as `None`: α' + β' + γ' = s1 − s0 ≠ 0, and a triangle
    // with a point off its plane has a non-zero normal.
    let (Some(bary), Some(normal)) = (
        Estimate::abs_fractions(weights),
        Estimate::unit_vector(cross),
    ) else {
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

#[cfg(test)]
mod tests;
