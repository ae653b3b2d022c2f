//! A floating-point filter in front of the exact segment–triangle test: it
//! answers "certainly no hit" for most faces a BVH query visits, at a fraction of
//! the exact test's cost, and says nothing otherwise (the exact test decides).
//!
//! It never calls a face missed that the exact test would hit: every decision
//! is a sign certified by a forward error bound, as in the fast paths of
//! [`crate::exact`]. Two certificates, each sufficient for "no hit":
//!
//! 1. **Both endpoints strictly on one side of the face's plane.** The exact
//!    test then answers a miss or parallel.
//! 2. **Two of the edge volumes `α'`, `β'`, `γ'` strictly of opposite signs**
//!    (the volumes of the exact test, Ericson §5.3.4: the segment's line passes
//!    outside the closed triangle). The exact test misses whenever one of them
//!    has the sign opposite to `α' + β' + γ'`, and with two opposite signs one
//!    of them does (or the sum is zero, and the segment is parallel: no hit
//!    either).
//!
//! The bounds assume no overflow and only benign underflow, which holds when
//! every coordinate is at most [`FILTER_MAX_COORD`] in magnitude; the queries
//! skip the filter otherwise.

use crate::exact::P3;

/// Largest coordinate magnitude (of the mesh's vertices and the segment's
/// endpoints) for which the filter is used: 2^60. Reason: differences are then
/// at most 2^61, the normal's components at most 2^123 and every product at
/// most 2^246 — no overflow — and a product that underflows (error at most
/// 2^−1075) is multiplied by at most a 2^61 factor afterwards, so
/// [`UNDERFLOW_SLACK`] covers every underflow error.
pub(crate) const FILTER_MAX_COORD: f64 = 1_152_921_504_606_846_976.0; // 2^60

/// Unit roundoff of `f64`, 2^−53.
const U: f64 = 1.1102230246251565e-16;

/// Bound on the plane test's error relative to `Σ_k P_k |ŵ_k|` (see
/// [`FaceFilter::new`]): the derivation gives `8u` (the precomputed normal
/// within `4u·P_k` per component, the difference `ŵ` within `u`, the dot
/// product's three roundings within `3u`); `16u` leaves room for the bound's own
/// roundings.
const PLANE_BOUND: f64 = 16.0 * U;

/// Absolute slack for underflow, 2^−1000. Reason: under [`FILTER_MAX_COORD`]
/// every difference is at most 2^61. In the plane test, an underflowing
/// product inside `n̂_k` (error ≤ 2^−1075 each, two per component) is scaled by
/// `|ŵ_k| ≤ 2^61`, and an underflowing `n̂_k·ŵ_k` errs by 2^−1075: in all below
/// 2^−1008. In an edge volume, each of the twelve products of two differences
/// that may underflow is scaled by a third difference (≤ 2^61): below 2^−1010.
/// 2^−1000 covers both with room.
const UNDERFLOW_SLACK: f64 = 9.332636185032189e-302;

#[inline(always)]
fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// A face's data for the filter: its vertices, its rounded normal
/// `n̂ = fl((v1 − v0) × (v2 − v0))`, and the permanents `P` bounding the
/// normal's rounding error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FaceFilter {
    v: [P3; 3],
    n: P3,
    p: P3,
}

/// A segment prepared for the filter.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentFilter {
    q0: P3,
    q1: P3,
    /// `fl(q1 − q0)`.
    r: P3,
}

impl SegmentFilter {
    /// `None` when a coordinate exceeds [`FILTER_MAX_COORD`] (the filter is then
    /// not used).
    pub(crate) fn new(q0: P3, q1: P3) -> Option<Self> {
        let ok = q0.iter().chain(&q1).all(|x| x.abs() <= FILTER_MAX_COORD);
        ok.then(|| Self { q0, q1, r: sub(q1, q0) })
    }
}

impl FaceFilter {
    /// The face's data. With `e1 = fl(v1 − v0)`, `e2 = fl(v2 − v0)`:
    /// `n̂_x = fl(e1y·e2z − e1z·e2y)` and `P_x = |e1y·e2z| + |e1z·e2y|` (and
    /// cyclically). Each `n̂_k` lies within `4u·P_k` (to first order) of the
    /// exact normal's component.
    pub(crate) fn new(v: [P3; 3]) -> Self {
        let (e1, e2) = (sub(v[1], v[0]), sub(v[2], v[0]));
        let mut n = [0.0; 3];
        let mut p = [0.0; 3];
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let (a, b) = (e1[i] * e2[j], e1[j] * e2[i]);
            n[k] = a - b;
            p[k] = a.abs() + b.abs();
        }
        Self { v, n, p }
    }

    /// Whether the segment certainly misses the face (see the module docs).
    /// `false` means "not certain", never "hit".
    #[inline(always)]
    pub(crate) fn certainly_misses(&self, s: &SegmentFilter) -> bool {
        // 1. The plane: s_i = n · (q_i − v0), with
        //    |ŝ_i − s_i| ≤ PLANE_BOUND · Σ_k P_k |ŵ_ik| + UNDERFLOW_SLACK.
        let (w0, w1) = (sub(s.q0, self.v[0]), sub(s.q1, self.v[0]));
        let s0 = self.n[0] * w0[0] + self.n[1] * w0[1] + self.n[2] * w0[2];
        let s1 = self.n[0] * w1[0] + self.n[1] * w1[1] + self.n[2] * w1[2];
        let b0 = PLANE_BOUND * (self.p[0] * w0[0].abs() + self.p[1] * w0[1].abs() + self.p[2] * w0[2].abs())
            + UNDERFLOW_SLACK;
        let b1 = PLANE_BOUND * (self.p[0] * w1[0].abs() + self.p[1] * w1[1].abs() + self.p[2] * w1[2].abs())
            + UNDERFLOW_SLACK;
        if (s0 > b0 && s1 > b1) || (s0 < -b0 && s1 < -b1) {
            return true;
        }
        // 2. The edges: α' = orient3d(q1, v2, v1, q0), β' = orient3d(q1, v0, v2, q0),
        //    γ' = orient3d(q1, v1, v0, q0), each by Shewchuk's expression on the
        //    rounded differences with his bound.
        let d = [sub(self.v[0], s.q0), sub(self.v[1], s.q0), sub(self.v[2], s.q0)];
        let alpha = volume(s.r, d[2], d[1]);
        let beta = volume(s.r, d[0], d[2]);
        if opposite(alpha, beta) {
            return true;
        }
        let gamma = volume(s.r, d[1], d[0]);
        opposite(alpha, gamma) || opposite(beta, gamma)
    }
}

/// Certified sign of a value with its bound: `1`, `−1`, or `0` for "unknown".
#[inline(always)]
fn sign((value, bound): (f64, f64)) -> i8 {
    if value > bound {
        1
    } else if value < -bound {
        -1
    } else {
        0
    }
}

#[inline(always)]
fn opposite(a: (f64, f64), b: (f64, f64)) -> bool {
    sign(a) * sign(b) < 0
}

/// `det[a, b, c]` of rounded difference rows, as [`crate::exact`]'s fast path
/// evaluates it (Shewchuk's expression and bound), with the bound.
#[inline(always)]
fn volume(a: P3, b: P3, c: P3) -> (f64, f64) {
    crate::exact::det3_with_bound(a, b, c)
}
