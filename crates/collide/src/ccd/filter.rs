//! The robust method's filter: decisions certified in floating point with
//! rigorous error bounds ([`Fe`]), or none.
//!
//! 1. **No root.** On an interval `[t_a, t_b]` the coplanarity cubic, as a
//!    function of `s = (t − t_a)/(t_b − t_a)`, is `det[U(s), V(s), W(s)]` with
//!    each vector linear in `s` between its values at `t_a` and `t_b`; by
//!    multilinearity its Bernstein coefficients (times `C(3, k)`) are
//!    `B0 = det[U0, V0, W0]`, `B1 = det[U1, V0, W0] + det[U0, V1, W0] +
//!    det[U0, V0, W1]`, `B2` likewise with two vectors at `t_b`, and
//!    `B3 = det[U1, V1, W1]`. The cubic is a convex combination of them with
//!    positive weights, so if all four are certainly of one strict sign it
//!    has no root on the closed interval. Over `[0, t_max]` this decides
//!    nearly every miss.
//! 2. **The first root.** Otherwise candidate roots come from the lecture's
//!    `f64` solver (their quality only matters for speed: each is checked).
//!    Walking from `0`, each candidate `r` is bracketed by doubles
//!    `t_l < r < t_h` a few ulps apart at which the cubic's signs are
//!    certainly opposite (so a root lies between), the stretch from the
//!    previous bracket to `t_l` is certified free of roots as in 1, and the
//!    contact test's margins (the exact stage's membership polynomials) are
//!    evaluated with bounds valid for every `t ∈ [t_l, t_h]`: all certainly
//!    positive — the contact holds at every root in the bracket, so the
//!    first root is there, and `t_l < r < t_h` is returned after bisection to
//!    within 2 ulps (where the bounds no longer decide the bisection — a
//!    root near `t = 0`, or a slow approach — the exact first root in the
//!    bracket, correctly rounded); one certainly negative — no contact at any root there,
//!    walk on. The stretch after the last bracket must be free of roots too.
//!    A stretch whose Bernstein coefficients straddle zero is certified on
//!    halves, a few times over.
//!
//! Anything not certified (a root at `0` or `t_max`, a tangency, a zero
//! margin, a degenerate triangle, overflow) returns `None`: the exact stage
//! answers.

use super::fe::{Fe, FeV, cross3, det3, dot3, positions, sub3};
use super::lecture::{cubic, cubic_roots};
use super::poly::next_up;
use super::{Ccd, Inputs, Query, exact_stage};
use crate::exact::Sign;

/// Brackets tried around a candidate root, in turn: 1 ulp on each side (the
/// answer's accuracy itself), then half-widths of [`BRACKET_GROWTH`]`^k`
/// times the root's estimated uncertainty (the cubic's error bound at the
/// root over its slope), `k = 0, 1, 2`: a root whose slope is small against
/// the rounding of the positions (a slow approach, a root near `t = 0`,
/// where ulps are tiny) is bracketed by a sign change all the same.
const BRACKET_TRIES: u32 = 3;

/// Growth of successive brackets' half-widths (see [`BRACKET_TRIES`]).
const BRACKET_GROWTH: f64 = 16.0;

/// Halvings allowed when certifying a stretch root-free ([`no_root_split`]):
/// 16 pieces at most, each as cheap as the first test; beyond that the
/// stretch most likely holds a root the `f64` solver missed (or a near
/// tangency), which is the exact stage's to decide.
const SPLIT_DEPTH: u32 = 4;

/// The three coplanarity vectors (see the exact stage's `coplanarity`).
fn vectors(q: Query, x: &[FeV; 4]) -> [FeV; 3] {
    match q {
        Query::VertexFace => [sub3(&x[2], &x[1]), sub3(&x[3], &x[1]), sub3(&x[0], &x[1])],
        Query::EdgeEdge => [sub3(&x[1], &x[0]), sub3(&x[2], &x[0]), sub3(&x[3], &x[0])],
    }
}

/// The cubic at the double `t`.
fn value_at(q: Query, x0: &Inputs, x1: &Inputs, t: f64) -> Fe {
    let [u, v, w] = vectors(q, &positions(x0, x1, t, t));
    det3(&u, &v, &w)
}

/// Whether the cubic certainly has no root on `[ta, tb]` (step 1).
fn no_root(q: Query, x0: &Inputs, x1: &Inputs, ta: f64, tb: f64) -> bool {
    let [u0, v0, w0] = vectors(q, &positions(x0, x1, ta, ta));
    let [u1, v1, w1] = vectors(q, &positions(x0, x1, tb, tb));
    let b0 = det3(&u0, &v0, &w0);
    let Some(s) = b0.sign() else { return false };
    let b3 = det3(&u1, &v1, &w1);
    if b3.sign() != Some(s) {
        return false;
    }
    let b1 = det3(&u1, &v0, &w0) + det3(&u0, &v1, &w0) + det3(&u0, &v0, &w1);
    if b1.sign() != Some(s) {
        return false;
    }
    let b2 = det3(&u1, &v1, &w0) + det3(&u1, &v0, &w1) + det3(&u0, &v1, &w1);
    b2.sign() == Some(s)
}

/// Whether the cubic certainly has no root on `[ta, tb]`, by step 1 on the
/// interval or, failing that, on its halves, down to `depth` halvings: the
/// Bernstein coefficients on an interval converge to the cubic's values as
/// it shrinks, so a cubic without a root there whose coefficients straddle
/// zero on the whole interval is certified on pieces.
fn no_root_split(q: Query, x0: &Inputs, x1: &Inputs, ta: f64, tb: f64, depth: u32) -> bool {
    if no_root(q, x0, x1, ta, tb) {
        return true;
    }
    let m = 0.5 * (ta + tb);
    depth > 0
        && m > ta
        && m < tb
        && no_root_split(q, x0, x1, ta, m, depth - 1)
        && no_root_split(q, x0, x1, m, tb, depth - 1)
}

/// The contact test's margins on `[tl, th]`: all certainly positive gives
/// `Some(true)`, one certainly negative `Some(false)`, else `None`.
fn margins(q: Query, x0: &Inputs, x1: &Inputs, tl: f64, th: f64) -> Option<bool> {
    let x = positions(x0, x1, tl, th);
    let m: [Fe; 4] = match q {
        Query::VertexFace => {
            let (p, a, b, c) = (&x[0], &x[1], &x[2], &x[3]);
            let n = cross3(&sub3(b, a), &sub3(c, a));
            let g = |vi: &FeV, vj: &FeV| dot3(&n, &cross3(&sub3(vj, vi), &sub3(p, vi)));
            let g0 = g(a, b);
            [g0, g(b, c), g(c, a), g0]
        }
        Query::EdgeEdge => {
            let (a0, a1, b0, b1) = (&x[0], &x[1], &x[2], &x[3]);
            let (da, db, w) = (sub3(a1, a0), sub3(b1, b0), sub3(b0, a0));
            let n = cross3(&da, &db);
            let nn = dot3(&n, &n);
            let s = dot3(&cross3(&w, &db), &n);
            let u = dot3(&cross3(&w, &da), &n);
            [s, nn - s, u, nn - u]
        }
    };
    let signs = m.map(Fe::sign);
    if signs.contains(&Some(Sign::Negative)) {
        Some(false)
    } else if signs.iter().all(|s| *s == Some(Sign::Positive)) {
        Some(true)
    } else {
        None
    }
}

/// `t` moved by `k` ulps (up for `k > 0`), for `t ≥ 0`; `None` below 0.
fn ulps(t: f64, k: i64) -> Option<f64> {
    let b = t.to_bits() as i64 + k;
    (b >= 0).then(|| f64::from_bits(b as u64))
}

/// The filter's answer, or `None` when the exact stage must decide.
pub(crate) fn solve(q: Query, x0: &Inputs, x1: &Inputs, t_max: f64) -> Option<Ccd> {
    if no_root(q, x0, x1, 0.0, t_max) {
        return Some(Ccd::MISS);
    }
    // Candidate roots from the f64 cubic, polished by Newton steps on the
    // determinant at positions (more accurate than the expanded cubic).
    let vel: Inputs = core::array::from_fn(|i| [0, 1, 2].map(|k| x1[i][k] - x0[i][k]));
    let rel = |i: usize, j: usize| ([0, 1, 2].map(|k| x0[i][k] - x0[j][k]), [0, 1, 2].map(|k| vel[i][k] - vel[j][k]));
    let ((u, du), (v, dv), (w, dw)) = match q {
        Query::VertexFace => (rel(2, 1), rel(3, 1), rel(0, 1)),
        Query::EdgeEdge => (rel(1, 0), rel(2, 0), rel(3, 0)),
    };
    let c = cubic(u, du, v, dv, w, dw);
    if c.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut cursor = 0.0;
    for r in cubic_roots(&c, t_max) {
        if r < cursor {
            continue;
        }
        let slope = (3.0 * c[3] * r + 2.0 * c[2]) * r + c[1];
        let (mut tl, mut th) = bracket(q, x0, x1, r, slope, cursor, t_max)?;
        if !no_root_split(q, x0, x1, cursor, tl, SPLIT_DEPTH) {
            return None;
        }
        match margins(q, x0, x1, tl, th)? {
            false => cursor = th,
            true => {
                // Narrow the bracket to within 2 ulps by certified bisection.
                let slo = value_at(q, x0, x1, tl).sign()?;
                while th.to_bits() - tl.to_bits() > 2 {
                    let m = f64::from_bits((tl.to_bits() + th.to_bits()) / 2);
                    // A sign change on [tl, m] keeps a root there; no sign
                    // change may still hide two, so the left part is
                    // certified root-free before it is dropped.
                    match value_at(q, x0, x1, m).sign() {
                        Some(s) if s != slo => th = m,
                        Some(_) if no_root(q, x0, x1, tl, m) => tl = m,
                        // Beyond the filter's accuracy: the contact is
                        // certain, the time is the exact first root here.
                        _ => return exact_stage::first_root_in(q, x0, x1, tl, th).map(Ccd::hit),
                    }
                }
                let t = if th.to_bits() - tl.to_bits() == 2 { next_up(tl) } else { tl };
                return Some(Ccd { t: Some(t), degenerate: false });
            }
        }
    }
    no_root_split(q, x0, x1, cursor, t_max, SPLIT_DEPTH).then_some(Ccd::MISS)
}

/// Doubles `cursor < tl < th ≤ t_max` around `r` at which the cubic's signs
/// are certainly opposite (`slope`: the `f64` cubic's derivative at `r`,
/// which sizes the wider brackets and needs no accuracy).
fn bracket(q: Query, x0: &Inputs, x1: &Inputs, r: f64, slope: f64, cursor: f64, t_max: f64) -> Option<(f64, f64)> {
    let at_r = value_at(q, x0, x1, r);
    let mut half = 4.0 * at_r.bound() / slope.abs();
    for i in 0..=BRACKET_TRIES {
        let (tl, th) = if i == 0 {
            (ulps(r, -1)?, ulps(r, 1)?.min(t_max))
        } else {
            let h = half.max(4.0 * (next_up(r) - r));
            half = h * BRACKET_GROWTH;
            (r - h, (r + h).min(t_max))
        };
        if !(tl > cursor) || !(th > tl) || !(th <= t_max) {
            return None;
        }
        let (sl, sh) = (value_at(q, x0, x1, tl).sign(), value_at(q, x0, x1, th).sign());
        if let (Some(a), Some(b)) = (sl, sh)
            && a == -b
        {
            return Some((tl, th));
        }
    }
    None
}
