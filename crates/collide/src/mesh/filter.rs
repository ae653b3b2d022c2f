//! A floating-point filter in front of the exact segment–triangle test: for each
//! face a BVH query visits it answers "certainly no hit", "certainly a hit, at a
//! segment parameter within these bounds", or "not certain" (then the exact test
//! decides), at a fraction of the exact test's cost.
//!
//! Every decision is a sign certified by a forward error bound: the volumes are
//! the exact test's ([`classify`](super::segment_mesh::classify),
//! Ericson §5.3.4), evaluated as
//! [`intersect_segment_triangle`](crate::intersect::intersect_segment_triangle)'s
//! own filter evaluates them (`crate::exact::filter`: rounded differences,
//! cross products with their permanents, triple products with
//! `TRIPLE_BOUND`), with the face's part — its vertices, its normal
//! `n̂ = fl((v1 − v0) × (v2 − v0))` and that normal's permanents — computed once
//! per face when the tree is built. With `w_i = q_i − v0`, `d_i = n̂ · w_i`
//! (`= −s_i`, the endpoints' volumes of the exact test, negated) and the edge
//! volumes `α'`, `β'`, `γ'` (apex `q0`, direction `r = q1 − q0`):
//!
//! - **no hit** when `d0`, `d1` are certainly non-zero and of one sign (both
//!   endpoints strictly on one side of the plane: the exact test answers a miss
//!   or parallel); or when two edge volumes are certainly of opposite signs
//!   (the segment's line passes outside the closed triangle: one of them has
//!   the sign opposite to `α' + β' + γ'`, or the sum is zero and the segment is
//!   parallel — no hit either way); or when the plane is decided and one edge
//!   volume certainly has the sign opposite to `σ = sign(s1 − s0)`;
//! - **a hit** when `d0`, `d1` are certainly non-zero and of opposite signs and
//!   all three edge volumes are certainly non-zero and none has the sign `−σ`:
//!   exactly the exact test's hit condition, with every sign certain. The hit's
//!   parameter `t = |d0| / (|d0| + |d1|)` is then bracketed from the bounds
//!   ([`FaceTest::Hit`]);
//! - otherwise (an endpoint within rounding of the plane, the line within
//!   rounding of an edge or a vertex — every tie at a shared edge): **not
//!   certain**.
//!
//! The bounds assume no overflow and only benign underflow, which
//! `crate::exact::filter` guarantees for coordinates up to `FAST_MAX` (2^63)
//! in magnitude; the queries use the filter only when every coordinate is
//! within [`FILTER_MAX_COORD`] (below that).

use crate::exact::P3;
use crate::exact::filter::{Filtered, cross, sub, triple};

/// Largest coordinate magnitude (of the mesh's vertices and the segment's
/// endpoints) for which the filter is used: 2^60. Reason: the error bounds of
/// `crate::exact::filter` hold for inputs up to 2^63 (no overflow, underflow
/// covered by its slack); 2^60 keeps the segment's point for the hit values
/// (`values.rs`, a convex combination of the endpoints) in range too, with
/// room.
pub(crate) const FILTER_MAX_COORD: f64 = 1_152_921_504_606_846_976.0; // 2^60

/// Unit roundoff of `f64`, 2^−53.
const U: f64 = f64::EPSILON / 2.0;

/// Relative widening of the bracket on `t` for its own roundings. Each end is
/// `a / (a + b)` with `a`, `b` a sum or difference of two exact values (one
/// rounding each), then the sum, the quotient and the widening product (one
/// each): `d ln(a / (a + b))` is at most `|d ln a| + max(|d ln a|, |d ln b|)`,
/// so five roundings of `u` at first order; `8u` covers them with their
/// second-order terms.
const T_BRACKET_ROUNDING: f64 = 8.0 * U;

/// A face's data for the filter, computed once: its vertices (exact), its
/// rounded normal `n̂ = fl((v1 − v0) × (v2 − v0))` and the normal's computed
/// permanents `|e1_j e2_k| + |e1_k e2_j|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FaceFilter {
    pub(crate) v: [P3; 3],
    pub(crate) n: P3,
    pub(crate) n_perm: P3,
}

/// A segment prepared for the filter: its endpoints and `r̂ = fl(q1 − q0)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentFilter {
    pub(crate) q0: P3,
    pub(crate) q1: P3,
    pub(crate) r: P3,
}

/// What the filter made of a face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum FaceTest {
    /// The exact test misses (or calls the segment parallel): no hit.
    Miss,
    /// The exact test hits, at a parameter `t` with `lo ≤ t ≤ hi`.
    Hit {
        /// Lower bound on the exact `t`.
        lo: f64,
        /// Upper bound on the exact `t`.
        hi: f64,
    },
    /// Not certain: the exact test decides.
    Undecided,
}

impl SegmentFilter {
    /// `None` when a coordinate exceeds [`FILTER_MAX_COORD`] or is not finite
    /// (the filter is then not used).
    pub(crate) fn new(q0: P3, q1: P3) -> Option<Self> {
        let ok = q0.iter().chain(&q1).all(|x| x.abs() <= FILTER_MAX_COORD);
        ok.then(|| Self { q0, q1, r: sub(q1, q0) })
    }
}

impl FaceFilter {
    /// The face's data (see the type). Its normal's components are within
    /// `CROSS_BOUND` of their permanents of the exact normal.
    pub(crate) fn new(v: [P3; 3]) -> Self {
        let (n, n_perm) = cross(sub(v[1], v[0]), sub(v[2], v[0]));
        Self { v, n, n_perm }
    }

    /// The endpoints against the face's plane: `d_i = n̂ · (q_i − v0)`
    /// (`= −orient3d(v0, v1, v2, q_i)`) with their bounds.
    #[inline(always)]
    pub(crate) fn plane(&self, s: &SegmentFilter) -> [Filtered; 2] {
        let w0 = sub(s.q0, self.v[0]);
        let w1 = sub(s.q1, self.v[0]);
        [triple(self.n, self.n_perm, w0), triple(self.n, self.n_perm, w1)]
    }

    /// The three-way test of the module documentation.
    #[inline(always)]
    pub(crate) fn test(&self, s: &SegmentFilter) -> FaceTest {
        let [a, b, c] = self.v;
        let w0 = sub(s.q0, a);
        let d0 = triple(self.n, self.n_perm, w0);
        let d1 = triple(self.n, self.n_perm, sub(s.q1, a));
        let plane = d0.decided() && d1.decided();
        // σ = sign(s1 − s0) = sign(d0 − d1); with the plane decided and the
        // signs opposite, sign(d0). An edge volume of sign −σ is a miss.
        let d0_positive = d0.value > 0.0;
        if plane && (d1.value > 0.0) == d0_positive {
            return FaceTest::Miss;
        }
        // The edges, the products shared as in the triangle query's filter:
        // m = r × (v2 − q0): α' = m · (v1 − q0), β' = m · (q0 − v0);
        // m2 = r × (v1 − q0): −γ' = m2 · (q0 − v0).
        let (pb, pc) = (sub(b, s.q0), sub(c, s.q0));
        let (m, m_perm) = cross(s.r, pc);
        let alpha = triple(m, m_perm, pb);
        // Whether a volume is certainly of sign −σ (`flip`: held negated).
        let against =
            |f: &Filtered, flip: bool| -> bool { plane && f.decided() && ((f.value > 0.0) != flip) != d0_positive };
        if against(&alpha, false) {
            return FaceTest::Miss;
        }
        let beta = triple(m, m_perm, w0);
        if against(&beta, false) || opposite(&alpha, &beta, false) {
            return FaceTest::Miss;
        }
        let (m2, m2_perm) = cross(s.r, pb);
        let gamma_neg = triple(m2, m2_perm, w0);
        if against(&gamma_neg, true) || opposite(&alpha, &gamma_neg, true) || opposite(&beta, &gamma_neg, true) {
            return FaceTest::Miss;
        }
        if !(plane && alpha.decided() && beta.decided() && gamma_neg.decided()) {
            return FaceTest::Undecided;
        }
        // A hit: every sign certain, none against σ. The exact |d_i| lie within
        // the bounds of the computed ones (and are non-zero), and
        // t = |d0| / (|d0| + |d1|) grows with |d0| and falls with |d1|.
        let (x0, x1) = (d0.value.abs(), d1.value.abs());
        let (lo0, hi0) = (x0 - d0.bound, x0 + d0.bound);
        let (lo1, hi1) = (x1 - d1.bound, x1 + d1.bound);
        FaceTest::Hit {
            lo: lo0 / (lo0 + hi1) * (1.0 - T_BRACKET_ROUNDING),
            hi: hi0 / (hi0 + lo1) * (1.0 + T_BRACKET_ROUNDING),
        }
    }
}

/// Whether two edge volumes are certainly of opposite signs (`flip`: the
/// second is held negated, as `−γ'`).
#[inline(always)]
fn opposite(x: &Filtered, y: &Filtered, flip: bool) -> bool {
    x.decided() && y.decided() && ((x.value > 0.0) != (y.value > 0.0)) != flip
}
