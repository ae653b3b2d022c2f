//! The first hit's values — `t`, point, normal, barycentrics — computed once per
//! query, for the winning face, by a certified floating-point path; the exact
//! segment–triangle query answers whenever the certificate fails.
//!
//! **Why not the triangle query alone.** [`intersect_segment_triangle`] takes
//! its barycentrics from the edge volumes with apex `q0`,
//! `α' = det[r, v2 − q0, v1 − q0]` and cyclically. For a small face far from
//! `q0` (the bunny's faces are a few hundredths of the segments' length) those
//! volumes are differences of large nearly equal products, their filtered
//! values miss the required accuracy, and the triangle query refines them in
//! exact arithmetic — a fifth of a BVH query's time on the bunny. Here the
//! apex is moved to the hit point instead.
//!
//! **Apex at the hit.** For a point `y` on the segment's line,
//! `det[r, v2 − y, v1 − y] = det[r, v2 − q0, v1 − q0]` (`v − y` and `v − q0`
//! differ by a multiple of `r`; the determinant is multilinear and
//! alternating). The computed hit point `x̂` is not quite on the line: with
//! `y` the exact point `e ± λ r` it was computed from (`e` the nearer
//! endpoint, `λ` the computed `t` or `1 − t`, `r = q1 − q0` exact) and
//! `δ = x̂ − y`, expanding the determinant gives the exact identities
//!
//! ```text
//! α' = det[r, v2 − x̂, v1 − x̂] + (r × δ) · (v1 − v2)
//! β' = det[r, v0 − x̂, v2 − x̂] + (r × δ) · (v2 − v0)
//! γ' = det[r, v1 − x̂, v0 − x̂] + (r × δ) · (v0 − v1)
//! ```
//!
//! The first terms are products of the face's own size, evaluated with
//! `crate::exact::filter`'s bounds. `δ` is the rounding of `x̂` itself, known
//! almost exactly from error-free transformations (Dekker's `TwoProduct` with
//! Veltkamp's split, Knuth's `TwoSum`): `δ_k = −(σ_k + s (π_k + λ ρ_k))` with
//! `ρ_k` the rounding error of `r̂_k = fl(q1_k − q0_k)`, `π_k` that of
//! `fl(λ r̂_k)`, `σ_k` that of the sum, `s = ±1`; so the corrections (about
//! `u |x̂|` times the face's size) are computed to a few units of roundoff of
//! themselves ([`CORRECTION_BOUND`]). The set is accepted when its total error
//! is within [`ESTIMATE_REL_ERR`] of its sum, as the triangle query accepts its
//! own.
//!
//! **The rest** is the triangle query's filter, term for term:
//! `t = |d0| / (|d0| + |d1|)` from the plane volumes (both certainly non-zero
//! and jointly accurate to [`ESTIMATE_REL_ERR`]), the point from the nearer
//! endpoint, the normal `n̂ / ‖n̂‖` (its components jointly accurate). So `t`,
//! the point and the normal are bit for bit the triangle query's whenever its
//! own filter answers; the barycentrics agree to within their accuracy.

use super::filter::{FILTER_MAX_COORD, FaceFilter};
use crate::exact::filter::{UNDERFLOW_SLACK, cross, cross_bounds, jointly_accurate, sub, triple};
use crate::exact::{ESTIMATE_REL_ERR, P3};
use crate::intersect::{SegmentHit, intersect_segment_triangle};
use crate::real::{Real, Vec3};
use crate::shapes::{Segment, Triangle};

/// Unit roundoff of `f64`, 2^−53.
const U: f64 = f64::EPSILON / 2.0;

/// Error bound of a correction `(r × δ) · w` as computed (`fl(fl(r̂ × δ̃) ·
/// fl(w))`), relative to `‖r̂‖₁ D ‖ŵ‖₁` with `D = Σ_k (|σ_k| + |π_k| + |λ ρ_k|)`
/// (which bounds `‖δ‖₁`): `r̂`'s rounding (`u`), `δ̃`'s three roundings (`3u`),
/// the cross product's (`4u`), `ŵ`'s (`u`), the dot product's (`3u`) — about
/// `12u` — and the bound's own evaluation; `64u` is generous, and the term is
/// near `u² |x̂| / size` of the sum, far below what the check needs.
const CORRECTION_BOUND: f64 = 64.0 * U;

/// Veltkamp's splitting constant `2^27 + 1`: `a = hi + lo` with both halves
/// of 26 bits, so their products are exact.
const SPLITTER: f64 = 134_217_729.0;

/// `a + b = s + e` exactly (Knuth's `TwoSum`; no condition but no overflow).
#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a · b = p + e` exactly when nothing overflows or underflows (Dekker's
/// `TwoProduct`, without a fused multiply-add).
#[inline(always)]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let split = |x: f64| {
        let c = SPLITTER * x;
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// Smallest `‖n̂‖²` normalized here (2^−960), as in the triangle query: above
/// it the sum of squares keeps full relative precision; below it the triangle
/// query normalizes by scaling.
const NORMAL_MIN_SQUARED: f64 = 1.0261342003245941e-289;

/// The hit's values in `f64`.
pub(super) struct Values {
    pub(super) t: f64,
    pub(super) point: P3,
    pub(super) normal: P3,
    pub(super) barycentric: [f64; 3],
}

/// The values of a face the segment `q0 q1` is known (exactly) to hit, each
/// accurate to about [`ESTIMATE_REL_ERR`]: the certified path of the module
/// documentation, or, when it cannot certify them,
/// [`intersect_segment_triangle`]'s. `None` only if the triangle query finds
/// no hit (it decides exactly as the mesh queries do, so never).
pub(super) fn hit_values<T: Real>(seg: &Segment<T>, tri: &Triangle<T>, q: [P3; 2]) -> Option<SegmentHit<T>> {
    let v = tri.vertices.map(|p| [p.x.wide(), p.y.wide(), p.z.wide()]);
    match certified(v, q) {
        Some(h) => {
            let vec = |p: P3| Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]));
            Some(SegmentHit {
                t: T::of(h.t),
                point: vec(h.point),
                normal: vec(h.normal),
                barycentric: Some(h.barycentric.map(T::of)),
            })
        }
        None => intersect_segment_triangle(seg, tri).hit,
    }
}

#[inline]
pub(super) fn certified(v: [P3; 3], [q0, q1]: [P3; 2]) -> Option<Values> {
    if !v.iter().chain([&q0, &q1]).flatten().all(|x| x.abs() <= FILTER_MAX_COORD) {
        return None;
    }
    let face = FaceFilter::new(v);
    // t: both plane volumes certain (so 0 < t < 1) and jointly accurate.
    let r = sub(q1, q0);
    let [d0, d1] = face.plane(&super::filter::SegmentFilter { q0, q1, r });
    let (x0, x1) = (d0.value.abs(), d1.value.abs());
    let x_sum = x0 + x1;
    if !(d0.decided() && d1.decided() && jointly_accurate(d0.bound + d1.bound, x_sum, ESTIMATE_REL_ERR)) {
        return None;
    }
    let (t, one_minus_t) = (x0 / x_sum, x1 / x_sum);
    // The point, from the nearer endpoint (the triangle query's rule), and
    // its offset δ from the line, from the rounding errors.
    let (lambda, end, sign) = if t <= one_minus_t { (t, q0, 1.0) } else { (one_minus_t, q1, -1.0) };
    let mut point = [0.0; 3];
    let mut delta = [0.0; 3];
    let mut offset = UNDERFLOW_SLACK;
    for k in 0..3 {
        let rho = two_sum(q1[k], -q0[k]).1;
        let (step, pi) = two_product(lambda, r[k]);
        let (x, sigma) = two_sum(end[k], sign * step);
        let lr = lambda * rho;
        point[k] = x;
        delta[k] = -(sigma + sign * (pi + lr));
        offset += (sigma.abs() + pi.abs()) + lr.abs();
    }
    // The normal.
    let nb = cross_bounds(face.n_perm);
    let n = face.n;
    let n_sum = (n[0].abs() + n[1].abs()) + n[2].abs();
    let nn = (n[0] * n[0] + n[1] * n[1]) + n[2] * n[2];
    if !(jointly_accurate((nb[0] + nb[1]) + nb[2], n_sum, ESTIMATE_REL_ERR) && nn >= NORMAL_MIN_SQUARED) {
        return None;
    }
    let inv_len = 1.0 / nn.sqrt();
    // The barycentrics, apex at the point: α(x̂) = (r × pc) · pb,
    // β(x̂) = (r × pc) · (x̂ − v0), −γ(x̂) = (r × pb) · (x̂ − v0); then the
    // corrections g · (v1 − v2), g · (v2 − v0), g · (v0 − v1), g = r × δ.
    let [a, b, c] = v;
    let (pb, pc) = (sub(b, point), sub(c, point));
    let wa = sub(point, a);
    let (m, m_perm) = cross(r, pc);
    let alpha = triple(m, m_perm, pb);
    let beta = triple(m, m_perm, wa);
    let (m2, m2_perm) = cross(r, pb);
    let gamma_neg = triple(m2, m2_perm, wa);
    let g = cross(r, delta).0;
    let edges = [sub(b, c), sub(c, a), sub(a, b)];
    let dot = |x: P3, y: P3| (x[0] * y[0] + x[1] * y[1]) + x[2] * y[2];
    let norm1 = |p: P3| (p[0].abs() + p[1].abs()) + p[2].abs();
    let w = [alpha.value + dot(g, edges[0]), beta.value + dot(g, edges[1]), -gamma_neg.value + dot(g, edges[2])]
        .map(f64::abs);
    let w_sum = (w[0] + w[1]) + w[2];
    let corrections = CORRECTION_BOUND * norm1(r) * offset * ((norm1(edges[0]) + norm1(edges[1])) + norm1(edges[2]));
    // The sums `value + correction` round once each: `2u` of the sum covers them.
    let w_err = ((alpha.bound + beta.bound) + gamma_neg.bound) + corrections + UNDERFLOW_SLACK + 2.0 * U * w_sum;
    if !jointly_accurate(w_err, w_sum, ESTIMATE_REL_ERR) {
        return None;
    }
    Some(Values { t, point, normal: n.map(|x| x * inv_len), barycentric: w.map(|x| x / w_sum) })
}
