//! The robust method's exact stage: every decision on polynomials in `t`
//! with exact coefficients (see [`poly`](super::poly)).
//!
//! - **`f ≢ 0`**: the contact can only happen at a root of the coplanarity
//!   cubic `f`; the roots of its square-free part in `[0, t_max]` are taken
//!   in increasing order and the static test decided exactly at each
//!   ([`member_at`]): with `N = n · n` (`n` the triangle's normal, or the
//!   cross product of the edges' directions), if `N > 0` the sign tests of
//!   the module documentation, else (zero area, parallel or zero-length
//!   edges) the point on one of the triangle's edges, or an endpoint of one
//!   segment on the other.
//! - **`f ≡ 0`** (coplanar motion throughout): the contact holds at `t = 0`,
//!   or its first time is one at which a point reaches a segment (the
//!   vertex reaches an edge of the triangle, an endpoint of one segment
//!   reaches the other): a crossing of two non-parallel segments in their
//!   plane, or of a point through a triangle's interior, cannot begin at an
//!   interior point, since it persists under small changes of time. Each
//!   point–segment event is the first common root of `e × q` (`e` the
//!   segment's direction, `q` the point from its start) at which
//!   `0 ≤ e · q ≤ e · e` ([`first_on_segment`]).

use super::poly::{PVec, Poly, Root, moving, roots_in, round, sign_at, vcross, vdot, vsub};
use super::{Ccd, Inputs, Query};
use crate::exact::{BigFloat, Sign};

/// The four points as polynomial vectors.
fn points(x0: &Inputs, x1: &Inputs) -> [PVec; 4] {
    core::array::from_fn(|i| moving(x0[i], x1[i]))
}

fn det(u: &PVec, v: &PVec, w: &PVec) -> Poly {
    vdot(&vcross(u, v), w)
}

fn nonneg(s: Sign) -> bool {
    s != Sign::Negative
}

/// The coplanarity polynomial: `det[b − a, c − a, p − a]` (vertex–face,
/// points `[p, a, b, c]`) or `det[a1 − a0, b0 − a0, b1 − a0]` (edge–edge,
/// points `[a0, a1, b0, b1]`).
fn coplanarity(q: Query, x: &[PVec; 4]) -> Poly {
    match q {
        Query::VertexFace => det(&vsub(&x[2], &x[1]), &vsub(&x[3], &x[1]), &vsub(&x[0], &x[1])),
        Query::EdgeEdge => det(&vsub(&x[1], &x[0]), &vsub(&x[2], &x[0]), &vsub(&x[3], &x[0])),
    }
}

/// Whether point `p` lies on the closed segment `v w` at `root`:
/// with `e = w − v`, `q = p − v`, when `e ≠ 0` iff `e × q = 0` and
/// `0 ≤ e · q ≤ e · e`; when `e = 0` iff `q = 0`.
fn on_segment_at(root: &Root, p: &PVec, v: &PVec, w: &PVec) -> bool {
    let (e, q) = (vsub(w, v), vsub(p, v));
    let ee = vdot(&e, &e);
    if sign_at(root, &ee) == Sign::Positive {
        let c = vcross(&e, &q);
        let d1 = vdot(&e, &q);
        c.iter().all(|ci| sign_at(root, ci).is_zero())
            && nonneg(sign_at(root, &d1))
            && nonneg(sign_at(root, &ee.sub(&d1)))
    } else {
        q.iter().all(|qi| sign_at(root, qi).is_zero())
    }
}

/// Whether the query's contact holds at `root`, a time at which the four
/// points are coplanar: `Some(degenerate)` if it does, `degenerate` when the
/// triangle has zero area (the segments are parallel or one has zero length)
/// there; `None` if it does not.
fn member_at(q: Query, root: &Root, x: &[PVec; 4]) -> Option<bool> {
    match q {
        Query::VertexFace => {
            let (p, a, b, c) = (&x[0], &x[1], &x[2], &x[3]);
            let n = vcross(&vsub(b, a), &vsub(c, a));
            if sign_at(root, &vdot(&n, &n)) == Sign::Positive {
                // p ∈ T iff n · ((v_{i+1} − v_i) × (p − v_i)) ≥ 0 for each edge.
                let tri = [a, b, c];
                let inside = (0..3).all(|i| {
                    let (vi, vj) = (tri[i], tri[(i + 1) % 3]);
                    nonneg(sign_at(root, &vdot(&n, &vcross(&vsub(vj, vi), &vsub(p, vi)))))
                });
                inside.then_some(false)
            } else {
                // Zero area: the triangle is its edges.
                let on = (0..3).any(|i| on_segment_at(root, p, [a, b, c][i], [a, b, c][(i + 1) % 3]));
                on.then_some(true)
            }
        }
        Query::EdgeEdge => {
            let (a0, a1, b0, b1) = (&x[0], &x[1], &x[2], &x[3]);
            let (da, db, w) = (vsub(a1, a0), vsub(b1, b0), vsub(b0, a0));
            let n = vcross(&da, &db);
            let nn = vdot(&n, &n);
            if sign_at(root, &nn) == Sign::Positive {
                // s = ((b0 − a0) × db) · n / n·n and u = ((b0 − a0) × da) · n / n·n
                // in [0, 1].
                let s = vdot(&vcross(&w, &db), &n);
                let u = vdot(&vcross(&w, &da), &n);
                let inside = [&s, &u].iter().all(|k| nonneg(sign_at(root, k)) && nonneg(sign_at(root, &nn.sub(k))));
                inside.then_some(false)
            } else {
                // Parallel (or a zero-length edge): they meet iff an endpoint of
                // one lies on the other.
                let on = on_segment_at(root, a0, b0, b1)
                    || on_segment_at(root, a1, b0, b1)
                    || on_segment_at(root, b0, a0, a1)
                    || on_segment_at(root, b1, a0, a1);
                on.then_some(true)
            }
        }
    }
}

/// The first time in `[0, t_max]` at which `p` lies on the closed segment
/// `v w`, all four points moving in a common plane throughout (so that the
/// first time is `0`, or one at which `p` reaches the segment's line — a
/// common root of `e × q` — or, when `p` moves along the line throughout, one
/// at which `p` reaches an end: a root of `e · q`, `e · e − e · q`, or of
/// `q` itself where the segment has zero length).
fn first_on_segment(p: &PVec, v: &PVec, w: &PVec, t_max: f64) -> Option<f64> {
    let zero = Root::Exact(BigFloat::ZERO);
    if on_segment_at(&zero, p, v, w) {
        return Some(0.0);
    }
    let (e, q) = (vsub(w, v), vsub(p, v));
    let c = vcross(&e, &q);
    let candidates: Vec<Poly> = if c.iter().all(Poly::is_zero) {
        let d1 = vdot(&e, &q);
        let d2 = vdot(&e, &e).sub(&d1);
        vec![d1, d2, vdot(&q, &q)]
    } else {
        vec![c.iter().fold(Poly::default(), |g, ci| g.gcd(ci))]
    };
    candidates
        .iter()
        .filter(|g| !g.is_zero())
        .filter_map(|g| {
            roots_in(&g.square_free(), 0.0, t_max).into_iter().find(|r| on_segment_at(r, p, v, w)).map(|r| round(&r))
        })
        .min_by(f64::total_cmp)
}

/// The exact answer for any finite input.
pub(crate) fn solve(q: Query, x0: &Inputs, x1: &Inputs, t_max: f64) -> Ccd {
    let x = points(x0, x1);
    let f = coplanarity(q, &x);
    if f.is_zero() {
        // Coplanar throughout: contact at 0, or the first point–segment event.
        let zero = Root::Exact(BigFloat::ZERO);
        if member_at(q, &zero, &x).is_some() {
            return Ccd { t: Some(0.0), degenerate: true };
        }
        let pairs: &[(usize, usize, usize)] = match q {
            Query::VertexFace => &[(0, 1, 2), (0, 2, 3), (0, 3, 1)],
            Query::EdgeEdge => &[(0, 2, 3), (1, 2, 3), (2, 0, 1), (3, 0, 1)],
        };
        let t =
            pairs.iter().filter_map(|&(p, v, w)| first_on_segment(&x[p], &x[v], &x[w], t_max)).min_by(f64::total_cmp);
        return Ccd { t, degenerate: true };
    }
    for root in roots_in(&f.square_free(), 0.0, t_max) {
        if let Some(degenerate) = member_at(q, &root, &x) {
            return Ccd { t: Some(round(&root)), degenerate };
        }
    }
    Ccd::MISS
}

/// The first root of the coplanarity cubic in `[tl, th]`, correctly rounded
/// (the filter has certified the contact at every root there).
pub(crate) fn first_root_in(q: Query, x0: &Inputs, x1: &Inputs, tl: f64, th: f64) -> Option<f64> {
    let f = coplanarity(q, &points(x0, x1));
    if f.is_zero() {
        return None;
    }
    roots_in(&f.square_free(), tl, th).first().map(round)
}
