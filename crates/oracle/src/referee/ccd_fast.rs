//! The floating-point stage of continuous collision detection
//! ([`super::ccd`]): a certified miss, or nothing (the exact stage decides).
//!
//! A contact needs the coplanarity cubic `f(t)` to vanish. `f` is a
//! determinant of three vectors moving linearly, `det[u(t), v(t), w(t)]`, so
//! its Bernstein coefficients on `[0, 1]` are sums of determinants of the
//! vectors at `t = 0` and `t = 1` (the blossom of a trilinear form):
//! `3·β₀ = 3·det[u₀, v₀, w₀]`, `3·β₁ = det[u₁, v₀, w₀] + det[u₀, v₁, w₀] + det[u₀, v₀, w₁]`,
//! `3·β₂ = det[u₀, v₁, w₁] + det[u₁, v₀, w₁] + det[u₁, v₁, w₀]`, `3·β₃ = 3·det[u₁, v₁, w₁]`.
//! They are computed in double-word numbers that carry a rigorous bound on
//! their error (the referee's `fast`, valid at any magnitude), from exact
//! differences of the inputs. When every coefficient certainly has the same
//! strict sign, `f` has no root in `[0, 1]` (a Bernstein polynomial lies in
//! the convex hull of its coefficients); otherwise the coefficients are
//! subdivided by de Casteljau's rule (each step an exact combination, the
//! error carried) a few times and the pieces that meet `[0, t_max]` are
//! tested the same way. The swept boxes (each moving point's two positions;
//! compared exactly, no arithmetic) give a second proof: disjoint boxes never
//! touch. Either proof answers "no contact"; the flag is `false` only when
//! some coefficient is certainly not zero (`f` is not the zero polynomial, so
//! the motion is not planar). Nothing else is answered here.

use super::fast::{Dw, cross, diff3, dot};
use crate::geom::{CcdAnswer, MovingPoint, MovingSegment, MovingTriangle, P3};

/// How many times the Bernstein coefficients are halved (at most `2^DEPTH`
/// pieces): enough to separate a root-free cubic whose control polygon
/// crosses zero, cheap beside one exact query.
const DEPTH: u32 = 4;

fn det(u: &[Dw; 3], v: &[Dw; 3], w: &[Dw; 3]) -> Dw {
    dot(&cross(u, v), w)
}

/// `3·βᵢ` of `det[u(t), v(t), w(t)]`, `u(t) = (1 − t)·u[0] + t·u[1]`.
fn bernstein(u: &[[Dw; 3]; 2], v: &[[Dw; 3]; 2], w: &[[Dw; 3]; 2]) -> [Dw; 4] {
    let d = |i: usize, j: usize, k: usize| det(&u[i], &v[j], &w[k]);
    let three = |x: Dw| x.add(x).add(x);
    [
        three(d(0, 0, 0)),
        d(1, 0, 0).add(d(0, 1, 0)).add(d(0, 0, 1)),
        d(0, 1, 1).add(d(1, 0, 1)).add(d(1, 1, 0)),
        three(d(1, 1, 1)),
    ]
}

/// Whether `Σ cᵢ Bᵢ³` (on a piece of `[0, 1]` starting at `start` of length
/// `width`) certainly has no root in the piece's part of `[0, t_max]`.
fn root_free(c: [Dw; 4], start: f64, width: f64, t_max: f64, depth: u32) -> bool {
    if start > t_max {
        return true;
    }
    let signs = c.map(Dw::signum);
    if let Some(s @ (1 | -1)) = signs[0]
        && signs.iter().all(|&x| x == Some(s))
    {
        return true;
    }
    if depth == 0 {
        return false;
    }
    // de Casteljau at the middle, both halves scaled by 8 (a positive factor).
    let two = |x: Dw| x.add(x);
    let c01 = c[0].add(c[1]);
    let c12 = c[1].add(c[2]);
    let c23 = c[2].add(c[3]);
    let c012 = c01.add(c12);
    let c123 = c12.add(c23);
    let mid = c012.add(c123);
    let left = [two(two(two(c[0]))), two(two(c01)), two(c012), mid];
    let right = [mid, two(c123), two(two(c23)), two(two(two(c[3])))];
    let half = width / 2.0;
    root_free(left, start, half, t_max, depth - 1) && root_free(right, start + half, half, t_max, depth - 1)
}

/// Whether the boxes of two sets of points are disjoint (exact comparisons).
fn disjoint(a: &[P3], b: &[P3]) -> bool {
    (0..3).any(|k| {
        let lo = |s: &[P3]| s.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
        let hi = |s: &[P3]| s.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
        hi(a) < lo(b) || hi(b) < lo(a)
    })
}

/// A certified miss from `f`'s Bernstein coefficients and the swept boxes.
fn miss(c: [Dw; 4], boxes_disjoint: bool, t_max: f64) -> Option<CcdAnswer> {
    let not_planar = c.iter().any(|x| matches!(x.signum(), Some(1 | -1)));
    (not_planar && (boxes_disjoint || root_free(c, 0.0, 1.0, t_max, DEPTH)))
        .then_some(CcdAnswer { t: None, degenerate: false })
}

/// `u`, `v`, `w` at `t = 0` and `t = 1` for `det[b − a, c − a, p − a]`.
pub(super) fn point_triangle(p: &MovingPoint, tri: &MovingTriangle, t_max: f64) -> Option<CcdAnswer> {
    let at = |i: usize| if i == 0 { (&p.t0, &tri.t0) } else { (&p.t1, &tri.t1) };
    let vec = |f: &dyn Fn(usize) -> [Dw; 3]| [f(0), f(1)];
    let u = vec(&|i| {
        let (_, t) = at(i);
        diff3(&t[1], &t[0])
    });
    let v = vec(&|i| {
        let (_, t) = at(i);
        diff3(&t[2], &t[0])
    });
    let w = vec(&|i| {
        let (x, t) = at(i);
        diff3(x, &t[0])
    });
    let tri_points = [tri.t0[0], tri.t0[1], tri.t0[2], tri.t1[0], tri.t1[1], tri.t1[2]];
    let boxes_disjoint = disjoint(&[p.t0, p.t1], &tri_points);
    miss(bernstein(&u, &v, &w), boxes_disjoint, t_max)
}

/// `det[a1 − a0, b0 − a0, b1 − a0]`.
pub(super) fn segment_segment(a: &MovingSegment, b: &MovingSegment, t_max: f64) -> Option<CcdAnswer> {
    let at = |i: usize| if i == 0 { (&a.t0, &b.t0) } else { (&a.t1, &b.t1) };
    let pick = |j: usize, k: usize| -> [[Dw; 3]; 2] {
        [0, 1].map(|i| {
            let (sa, sb) = at(i);
            let x = if j < 2 { sa[j] } else { sb[j - 2] };
            diff3(&x, &sa[k])
        })
    };
    let (u, v, w) = (pick(1, 0), pick(2, 0), pick(3, 0));
    let points_a = [a.t0[0], a.t0[1], a.t1[0], a.t1[1]];
    let points_b = [b.t0[0], b.t0[1], b.t1[0], b.t1[1]];
    miss(bernstein(&u, &v, &w), disjoint(&points_a, &points_b), t_max)
}
