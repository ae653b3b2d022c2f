//! The exact predicates of the robust signed distance: signs of small
//! homogeneous polynomials in the input coordinates, written once over
//! [`Ring`](crate::boxes::poly::Ring) and evaluated through filters
//! ([`decide`]): `f64` with a running error bound, which settles nearly every
//! sign of an ordinary scene; double-double with a bound of order `2^−100` of
//! the terms, which settles the values a rounding away from zero (a rotated
//! box's nearly coplanar corners, nearly parallel edges); then
//! `crate::boxes::poly`'s stages, exact at the last, for exact zeros and for
//! the whole range of `f64`.
//!
//! Each predicate is about a **direction** [`Dir`]: a polynomial vector `N`
//! of a few input points, so that a normal, a supporting set or a tie decided
//! with it is decided exactly, at every scale. The kinds:
//!
//! - a Minkowski point `w₀ = a₀ − b₀` (GJK's one-vertex simplex): `N = w₀`;
//! - a Minkowski segment `w₀ w₁` (`e = w₁ − w₀`): `N = e × (w₀ × e)`, the
//!   direction from the origin to its foot on the line;
//! - a Minkowski triangle: `N = (w₁ − w₀) × (w₂ − w₀)`;
//! - a cross product of two point differences, `N = (p₁ − p₀) × (q₁ − q₀)`: a
//!   hull's face normal (`q₀ = p₀`) or the cross product of an edge of each
//!   hull (the separating axes).
//!
//! The points are [`Xp`]s: plain `f64` points, or a box's corners as the
//! format defines them (`super::points`), which `f64` holds only to a bound.
//! On plain points (and corners `f64` holds exactly) the stages are the
//! above. A predicate on inexact corners runs [`Fl`] on the `f64` values
//! with each point's bound as its leaves' error, then [`Dd`] on the
//! corners' double-double values with theirs, then exactly on the exact
//! corners (`super::points::lift`: [`Filt`] first, whose exactness tracking
//! settles the exact zeros of small quaternions, then [`BigFloat`]). The
//! zeros a box's construction makes (its corners on one face level along
//! that face's normal, its edges along one axis parallel, a face normal
//! built twice) are answered from the corners' sign bits without
//! evaluating them ([`Dir::perpendicular`], [`Dir::known`]).

use super::points::{ExactBox, Xp, lift, same};
use crate::boxes::poly::{Fast, Filt, Poly, Ring, at, cross3, dot3, refs, sign_fast, sub3, value_fast};
use crate::exact::{BigFloat, Estimate, Sign};
use crate::real::Vec3;

/// The kind of a [`Dir`] (see the module's documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// `N = a₀ − b₀`.
    Point,
    /// `N = e × (w₀ × e)`, `w_k = a_k − b_k`, `e = w₁ − w₀`.
    Edge,
    /// `N = (w₁ − w₀) × (w₂ − w₀)`.
    Triangle,
    /// `N = (p₁ − p₀) × (q₁ − q₀)`.
    Cross,
}

const POINT: u8 = 0;
const EDGE: u8 = 1;
const TRIANGLE: u8 = 2;
const CROSS: u8 = 3;

/// A direction: its kind and its six points (`a₀, a₁, a₂, b₀, b₁, b₂` for the
/// Minkowski kinds, `p₀, p₁, q₀, q₁` and two unused for a cross product;
/// unused points are the origin).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dir<'a> {
    pub kind: Kind,
    pts: [Xp<'a>; 6],
}

/// A line known from a direction's construction ([`Dir::known`]).
#[derive(Clone, Copy, Debug)]
enum KnownLine<'a> {
    /// Along `M_k` of the box.
    Normal(&'a ExactBox, u32),
    /// Along `M_i × M_j` of an axis of each of two boxes.
    Cross((&'a ExactBox, u32), (&'a ExactBox, u32)),
}

impl KnownLine<'_> {
    /// Whether the two lines are one by construction.
    fn same(&self, o: &Self) -> bool {
        let eq = |a: &(&ExactBox, u32), b: &(&ExactBox, u32)| std::ptr::eq(a.0, b.0) && a.1 == b.1;
        match (self, o) {
            (KnownLine::Normal(x, k), KnownLine::Normal(y, l)) => std::ptr::eq(*x, *y) && k == l,
            (KnownLine::Cross(a, b), KnownLine::Cross(c, d)) => (eq(a, c) && eq(b, d)) || (eq(a, d) && eq(b, c)),
            _ => false,
        }
    }
}

/// The origin, for a direction's unused points.
const ORIGIN: Xp<'static> = Xp::plain([0.0; 3]);

impl<'a> Dir<'a> {
    /// The normal of a Minkowski simplex of one to three vertices
    /// `a[k] − b[k]`.
    pub(crate) fn simplex(a: &[Xp<'a>], b: &[Xp<'a>]) -> Self {
        let mut pts = [ORIGIN; 6];
        for (k, (x, y)) in a.iter().zip(b).take(3).enumerate() {
            pts[k] = *x;
            pts[3 + k] = *y;
        }
        let kind = match a.len().min(b.len()) {
            0 | 1 => Kind::Point,
            2 => Kind::Edge,
            _ => Kind::Triangle,
        };
        Self { kind, pts }
    }

    /// `(p1 − p0) × (q1 − q0)`.
    pub(crate) fn cross(p0: Xp<'a>, p1: Xp<'a>, q0: Xp<'a>, q1: Xp<'a>) -> Self {
        Self { kind: Kind::Cross, pts: [p0, p1, q0, q1, ORIGIN, ORIGIN] }
    }

    /// The 18 lengths of the direction's points.
    fn lengths(&self) -> [f64; 18] {
        flat(&self.pts)
    }

    /// The axes `i` of the box `b` (a bit mask) to which `N` is
    /// perpendicular by construction, whatever the coordinates. A difference
    /// of two corners of `b` lies in the span of the axes `M_i` their signs
    /// differ in, with coefficients `±2h_i` (only the axes with `h_i ≠ 0`
    /// count: `b.nonzero()`). `N` is perpendicular to each difference it is
    /// made of: a cross product's two factors `u`, `v` (and, `N = u × v`
    /// being zero when they are parallel, to the plane of two axes that
    /// hold both), a Minkowski triangle's edges (and every vector in their
    /// span: an edge `(a_k − a₀) − (b_k − b₀)` one of whose parts vanishes
    /// is a difference of the other solid's, and then the other edge's
    /// parts that match it are in the span too; two such differences of
    /// distinct non-empty axis sets within two axes are independent, and
    /// their plane is the span), a Minkowski segment's edge.
    pub(crate) fn perpendicular(&self, b: &ExactBox) -> u8 {
        let p = &self.pts;
        let nz = b.nonzero();
        let diff = |x: &Xp, y: &Xp| -> Option<u8> {
            if x.identical(y) {
                return Some(0);
            }
            x.box_diff(y).filter(|(c, _)| std::ptr::eq(*c, b)).map(|(_, s)| s & nz)
        };
        let one = |s: u8| if s.count_ones() == 1 { s } else { 0 };
        match self.kind {
            Kind::Point => 0,
            Kind::Cross => match (diff(&p[0], &p[1]), diff(&p[2], &p[3])) {
                (Some(s), Some(t)) if (s | t).count_ones() <= 2 => s | t,
                (u, v) => one(u.unwrap_or(0)) | one(v.unwrap_or(0)),
            },
            Kind::Edge | Kind::Triangle => {
                let edges = if self.kind == Kind::Edge { 1 } else { 2 };
                // The vectors known to lie in the edges' span, as axis sets
                // of `b`.
                let mut vecs: [u8; 4] = [0; 4];
                let mut n = 0;
                let mut push = |s: Option<u8>| {
                    if let Some(s) = s.filter(|s| *s != 0) {
                        vecs[n] = s;
                        n += 1;
                    }
                };
                for k in 1..=edges {
                    let (pure_a, pure_b) = (p[3 + k].identical(&p[3]), p[k].identical(&p[0]));
                    if pure_a {
                        push(diff(&p[0], &p[k]));
                    } else if pure_b {
                        push(diff(&p[3], &p[3 + k]));
                    } else if edges == 2 {
                        let j = 3 - k;
                        let other_b = p[j].identical(&p[0]) && p[3 + j].identical(&p[3 + k]);
                        let other_a = p[3 + j].identical(&p[3]) && p[j].identical(&p[k]);
                        if other_b || other_a {
                            push(diff(&p[0], &p[k]));
                            push(diff(&p[3], &p[3 + k]));
                        }
                    }
                }
                let mut mask = vecs[..n].iter().fold(0, |m, s| m | one(*s));
                if edges == 2 {
                    for x in 0..n {
                        for y in x + 1..n {
                            let (s, t) = (vecs[x], vecs[y]);
                            if s != t && (s | t).count_ones() <= 2 {
                                mask |= s | t;
                            }
                        }
                    }
                }
                mask
            }
        }
    }

    /// A cross-product direction's known line: normal to axis `k` of a box
    /// (both factors differences of its corners, of distinct axis sets
    /// within two axes), or the cross product of an axis of each of two
    /// boxes (both factors along one axis). `None` otherwise (and for a
    /// factor that vanishes).
    fn known(&self) -> Option<KnownLine<'a>> {
        if self.kind != Kind::Cross {
            return None;
        }
        let p = &self.pts;
        let (x, s) = p[0].box_diff(&p[1])?;
        let (y, t) = p[2].box_diff(&p[3])?;
        let (s, t) = (s & x.nonzero(), t & y.nonzero());
        if s == 0 || t == 0 {
            return None;
        }
        if std::ptr::eq(x, y) {
            return (s != t && (s | t).count_ones() == 2)
                .then(|| KnownLine::Normal(x, (!(s | t) & 7).trailing_zeros()));
        }
        (s.count_ones() == 1 && t.count_ones() == 1)
            .then(|| KnownLine::Cross((x, s.trailing_zeros()), (y, t.trailing_zeros())))
    }

    /// The degree of `N` in the coordinates.
    fn degree(&self) -> i64 {
        match self.kind {
            Kind::Point => 1,
            Kind::Edge => 3,
            Kind::Triangle | Kind::Cross => 2,
        }
    }
}

/// The Minkowski edge `w_k − w₀ = (a_k − a₀) − (b_k − b₀)` (`a_k` at length
/// `o`, `b_k` at `o + 9`), formed from each solid's own differences: points
/// on one level of each give exact zeros.
#[inline(always)]
fn edge_of<R: Ring, const K: usize>(l: &[R; K], o: usize) -> [R; 3] {
    sub3(refs(&sub3(at(l, o), at(l, 0))), refs(&sub3(at(l, o + 9), at(l, 9))))
}

/// `N` of the direction of kind `KIND` whose points are the first 18 lengths
/// of `l`.
#[inline(always)]
fn dir_of<R: Ring, const KIND: u8, const K: usize>(l: &[R; K]) -> [R; 3] {
    match KIND {
        POINT => sub3(at(l, 0), at(l, 9)),
        EDGE => {
            let w0 = sub3(at(l, 0), at(l, 9));
            let e = edge_of(l, 3);
            cross3(refs(&e), refs(&cross3(refs(&w0), refs(&e))))
        }
        TRIANGLE => cross3(refs(&edge_of(l, 3)), refs(&edge_of(l, 6))),
        _ => cross3(refs(&sub3(at(l, 3), at(l, 0))), refs(&sub3(at(l, 9), at(l, 6)))),
    }
}

/// `N · (x − r)`, `x` and `r` the lengths 18..24.
fn side_poly<R: Ring, const KIND: u8>(l: &[R; 24], _u: &[R; 0]) -> R {
    let n = dir_of::<R, KIND, 24>(l);
    dot3(refs(&n), refs(&sub3(at(l, 18), at(l, 21))))
}

/// `N · ((q − p) × (s − r))`, `p, q, r, s` the lengths 18..30: the
/// orientation of `p, q, s` (with `r = p`) seen along `N`, which is the same
/// for every point moved along `N`.
fn orient_poly<R: Ring, const KIND: u8>(l: &[R; 30], _u: &[R; 0]) -> R {
    let n = dir_of::<R, KIND, 30>(l);
    let c = cross3(refs(&sub3(at(l, 21), at(l, 18))), refs(&sub3(at(l, 27), at(l, 24))));
    dot3(refs(&n), refs(&c))
}

/// `N · ((x − y) − (r − t))`, `x, y, r, t` the lengths 18..30: the side of
/// the Minkowski point `x − y` against the level of `r − t`.
fn side_w_poly<R: Ring, const KIND: u8>(l: &[R; 30], _u: &[R; 0]) -> R {
    let n = dir_of::<R, KIND, 30>(l);
    let w = sub3(refs(&sub3(at(l, 18), at(l, 24))), refs(&sub3(at(l, 21), at(l, 27))));
    dot3(refs(&n), refs(&w))
}

/// Component `C` of `(x − r) × N`, `x` and `r` the lengths 18..24: all three
/// vanish exactly when `x` and `r` are one point seen along `N`.
fn apart_poly<R: Ring, const KIND: u8, const C: usize>(l: &[R; 24], _u: &[R; 0]) -> R {
    let n = dir_of::<R, KIND, 24>(l);
    let c = cross3(refs(&sub3(at(l, 18), at(l, 21))), refs(&n));
    c[C].clone()
}

/// Component `C` of `N`.
fn component_poly<R: Ring, const KIND: u8, const C: usize>(l: &[R; 18], _u: &[R; 0]) -> R {
    dir_of::<R, KIND, 18>(l)[C].clone()
}

/// `(x − y) · (r₁ − r₀)` of the points `x, y, r₀, r₁`.
fn along_poly<R: Ring>(l: &[R; 12], _u: &[R; 0]) -> R {
    dot3(refs(&sub3(at(l, 0), at(l, 3))), refs(&sub3(at(l, 9), at(l, 6))))
}

/// Component `C` of `(p₁ − p₀) × (q₁ − q₀)`, lengths `[p₀, p₁, q₀, q₁]`.
fn edge_cross_poly<R: Ring, const C: usize>(l: &[R; 12], _u: &[R; 0]) -> R {
    cross3(refs(&sub3(at(l, 3), at(l, 0))), refs(&sub3(at(l, 9), at(l, 6))))[C].clone()
}

/// `w₀ · e` (`k = 0`) or `w₁ · e` (`k = 1`) of a Minkowski segment, lengths
/// `[a₀, a₁, b₀, b₁]`: the origin's foot lies on the segment exactly when
/// the first is `≤ 0` and the second `≥ 0`.
fn foot_edge_poly<R: Ring, const K: usize>(l: &[R; 12], _u: &[R; 0]) -> R {
    let w0 = sub3(at(l, 0), at(l, 6));
    let w1 = sub3(at(l, 3), at(l, 9));
    let e = sub3(refs(&sub3(at(l, 3), at(l, 0))), refs(&sub3(at(l, 9), at(l, 6))));
    if K == 0 { dot3(refs(&w0), refs(&e)) } else { dot3(refs(&w1), refs(&e)) }
}

/// `N · (w_j × w_k)` of a Minkowski triangle (`N` its normal, `(j, k)` the
/// vertices other than `I`): the origin's projection onto its plane has
/// barycentric coordinate `I` of that sign (their sum is `N·N`).
fn foot_triangle_poly<R: Ring, const I: usize>(l: &[R; 18], _u: &[R; 0]) -> R {
    let n = dir_of::<R, TRIANGLE, 18>(l);
    let w = |k: usize| sub3(at(l, 3 * k), at(l, 9 + 3 * k));
    let (j, k) = ((I + 1) % 3, (I + 2) % 3);
    dot3(refs(&n), refs(&cross3(refs(&w(j)), refs(&w(k)))))
}

/// Two pushes `p_i / ‖L_i‖` with `L_i = (P₁ − P₀) × (P₃ − P₂)` and
/// `p_i = L_i · (P₄ − P₅)` (points 0..6 the first, 6..12 the second):
/// `p₁² ‖L₂‖² − p₂² ‖L₁‖²`, whose sign orders two pushes of the same sign.
fn push_cmp_poly<R: Ring>(l: &[R; 36], _u: &[R; 0]) -> R {
    let axis = |o: usize| cross3(refs(&sub3(at(l, o + 3), at(l, o))), refs(&sub3(at(l, o + 9), at(l, o + 6))));
    let (l1, l2) = (axis(0), axis(18));
    let p1 = dot3(refs(&l1), refs(&sub3(at(l, 12), at(l, 15))));
    let p2 = dot3(refs(&l2), refs(&sub3(at(l, 30), at(l, 33))));
    let n1 = dot3(refs(&l1), refs(&l1));
    let n2 = dot3(refs(&l2), refs(&l2));
    p1.mul(&p1).mul(&n2).sub(&p2.mul(&p2).mul(&n1))
}

/// `p = L · (P₄ − P₅)` (`C = 0`) or `‖L‖²` (`C = 1`) of a push,
/// `L = (P₁ − P₀) × (P₃ − P₂)`.
fn push_value_poly<R: Ring, const C: usize>(l: &[R; 18], _u: &[R; 0]) -> R {
    let axis = cross3(refs(&sub3(at(l, 3), at(l, 0))), refs(&sub3(at(l, 9), at(l, 6))));
    if C == 0 { dot3(refs(&axis), refs(&sub3(at(l, 12), at(l, 15)))) } else { dot3(refs(&axis), refs(&axis)) }
}

/// Component `C` of `L₁ × L₂` (`C < 3`) or `L₁ · L₂` (`C = 3`) of two cross
/// product axes (points 0..4 and 4..8).
fn pair_poly<R: Ring, const C: usize>(l: &[R; 24], _u: &[R; 0]) -> R {
    let axis = |o: usize| cross3(refs(&sub3(at(l, o + 3), at(l, o))), refs(&sub3(at(l, o + 9), at(l, o + 6))));
    let (l1, l2) = (axis(0), axis(12));
    if C == 3 { dot3(refs(&l1), refs(&l2)) } else { cross3(refs(&l1), refs(&l2))[C].clone() }
}

/// An `f64` value `v` whose exact counterpart lies within `e` of it, with
/// the running bound of `crate::boxes::poly`'s `Fast` (each operation adds
/// the propagated errors and its own rounding, twice; a product adds
/// `2^−1073` for what underflow may lose), evaluated on the inputs as they
/// are: [`decide`] uses it only where nothing can overflow, so the scaling
/// that the staged filters start with is not needed. It is `Fast` itself,
/// its leaves made here.
pub(crate) type Fl = Fast;

/// Unit roundoff of `f64`.
const U: f64 = f64::EPSILON / 2.0;

/// A double-double value `hi + lo` (`|lo|` at most half an ulp of `hi`)
/// and a bound `e` on its distance from the exact value: the second stage
/// of [`decide`], for values within a few ulps of zero relative to their
/// terms (near-parallel edges, points a rounding off a face), which it
/// settles at about `2^−100` of the terms.
///
/// Every sum and product is formed with error-free transformations (Knuth's
/// two-sum, Dekker's product with Veltkamp's split: exact for finite
/// operands below `2^996` whose product's error term does not underflow),
/// and what is dropped to keep two components — the residuals of a few
/// further two-sums, and the rounding of `lo·lo'` — is added to `e` as it
/// is (a computation that dropped nothing has `e = 0`). An operand's own
/// bound propagates as `|a|·e_b + |b|·e_a + e_a·e_b` (plus what those
/// products may lose to underflow). A product whose error
/// term may fall into the subnormals (a product below `2^−968`) adds
/// [`DD_UNDERFLOW`]. Each bound is the rounded sum of a few non-negative terms,
/// enlarged by `1 + 8u` for that rounding.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dd {
    hi: f64,
    lo: f64,
    e: f64,
}

#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let aa = s - bb;
    (s, (a - aa) + (b - bb))
}

#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

#[inline(always)]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// Products below this may have an error term in the subnormals (`2^−968`).
const DD_TINY: f64 = f64::from_bits((1023 - 968) << 52);
/// What one such product's error term may lose: the term is at most
/// `u·2^−968 = 2^−1021`, counted twice (for a wrong one), with room
/// (`2^−1018`).
const DD_UNDERFLOW: f64 = f64::from_bits((1023 - 1018) << 52);
/// What the three products of a propagated bound may lose to underflow,
/// with room (`8·2^−1074`).
const DD_CARRY_FLOOR: f64 = f64::from_bits(8);
/// Above this a value's split could overflow: [`Dd`] gives up (`2^900`).
const DD_HUGE: f64 = f64::from_bits((1023 + 900) << 52);

impl Dd {
    /// `hi + lo` within `e` of the exact value (`|lo|` at most half an ulp
    /// of `hi`).
    pub(crate) const fn new(hi: f64, lo: f64, e: f64) -> Self {
        Self { hi, lo, e }
    }

    /// `(hi, lo, e)`.
    pub(crate) fn parts(&self) -> (f64, f64, f64) {
        (self.hi, self.lo, self.e)
    }

    #[inline(always)]
    fn tiny(a: f64, b: f64, p: f64) -> bool {
        a != 0.0 && b != 0.0 && p.abs() < DD_TINY
    }

    /// The sign, when the bound settles it.
    fn sign(&self) -> Option<Sign> {
        if !(self.hi.is_finite() && self.lo.is_finite() && self.e.is_finite()) {
            return None;
        }
        if self.e == 0.0 {
            return Some(Sign::of(self.hi));
        }
        (self.hi.abs() - self.lo.abs() > self.e * (1.0 + 4.0 * U)).then(|| Sign::of(self.hi))
    }
}

impl Ring for Dd {
    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        let (s, t) = two_sum(self.hi, o.hi);
        let (u, v) = two_sum(self.lo, o.lo);
        let (t2, w) = two_sum(t, u);
        let (hi, l1) = two_sum(s, t2);
        let (l2, r1) = two_sum(l1, w);
        let (lo, r2) = two_sum(l2, v);
        let (hi, lo) = two_sum(hi, lo);
        let e = self.e + o.e + r1.abs() + r2.abs();
        Self { hi, lo, e: if e == 0.0 { 0.0 } else { e * (1.0 + 8.0 * U) } }
    }
    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        self.add(&Self { hi: -o.hi, lo: -o.lo, e: o.e })
    }
    #[inline(always)]
    fn mul(&self, o: &Self) -> Self {
        let (a, b) = (self, o);
        if a.hi.abs() > DD_HUGE || b.hi.abs() > DD_HUGE {
            return Self { hi: a.hi * b.hi, lo: 0.0, e: f64::INFINITY };
        }
        let (p, q) = two_prod(a.hi, b.hi);
        let (c1, d1) = two_prod(a.hi, b.lo);
        let (c2, d2) = two_prod(a.lo, b.hi);
        let m = a.lo * b.lo;
        let (x1, r1) = two_sum(q, c1);
        let (x2, r2) = two_sum(x1, c2);
        let (y1, r3) = two_sum(d1, d2);
        let (y2, r4) = two_sum(y1, m);
        let (x3, r5) = two_sum(x2, y2);
        let (hi, lo) = two_sum(p, x3);
        let mut dropped = r1.abs() + r2.abs() + r3.abs() + r4.abs() + r5.abs() + 2.0 * U * m.abs();
        let under = [(a.hi, b.hi, p), (a.hi, b.lo, c1), (a.lo, b.hi, c2), (a.lo, b.lo, m)];
        if under.iter().any(|&(x, y, z)| Self::tiny(x, y, z)) {
            dropped += 4.0 * DD_UNDERFLOW;
        }
        let (na, nb) = (a.hi.abs() + a.lo.abs(), b.hi.abs() + b.lo.abs());
        // The propagated bound's own products may underflow: each loses
        // less than `2^−1074`.
        let carried = if a.e == 0.0 && b.e == 0.0 { 0.0 } else { na * b.e + nb * a.e + a.e * b.e + DD_CARRY_FLOOR };
        let e = dropped + carried;
        Self { hi, lo, e: if e == 0.0 { 0.0 } else { e * (1.0 + 8.0 * U) } }
    }
    #[inline(always)]
    fn abs(&self) -> Self {
        if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            Self { hi: -self.hi, lo: -self.lo, e: self.e }
        } else {
            *self
        }
    }
}

/// The sign of the polynomial in [`Dd`] on the inputs scaled by the power
/// of two that brings the largest into `[0.5, 1)` (a homogeneous
/// polynomial's sign is unchanged); an input that falls into the subnormals
/// is within `2^−1074` of its scaled value.
fn dd_sign<const K: usize>(len: &[f64; K], dd: Poly<Dd, K, 0>) -> Option<Sign> {
    let m = len.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !m.is_finite() {
        return None;
    }
    let k = if m == 0.0 { 0 } else { -crate::exact::frexp(m).1 };
    let l = len.map(|x| {
        let v = crate::exact::ldexp(x, k);
        let e = if x != 0.0 && v.abs() < f64::MIN_POSITIVE { f64::from_bits(1) } else { 0.0 };
        Dd { hi: v, lo: 0.0, e }
    });
    dd(&l, &[]).sign()
}

/// The largest input magnitude [`decide`] evaluates unscaled: a polynomial of
/// degree at most 10 in such inputs (with at most a few hundred terms) stays
/// far below `f64::MAX`.
const PLAIN: f64 = 1.0e27;

/// The least input magnitude the filter on inexact points ([`fl_sign_err`])
/// evaluates unscaled: below it, products could fall toward the subnormals
/// and the bound's underflow terms would swamp the value.
const PLAIN_LOW: f64 = 1.0e-100;

/// The exact sign of a homogeneous polynomial of degree at most 10 in exact
/// inputs (`fl`, `dd`, `fast`, `filt`, `big` the same polynomial over
/// [`Fl`], [`Dd`] and the staged filters' rings): first in [`Fl`]
/// ([`fl_sign`]: the bound covers underflow, so tiny inputs cost accuracy,
/// not correctness), then in [`Dd`] ([`dd_sign`]), then through
/// `crate::boxes::poly`'s stages (scaled `f64`, exactness-tracking `f64`,
/// exact).
#[inline]
fn decide_exact<const K: usize>(
    len: [f64; K],
    fl: Poly<Fl, K, 0>,
    dd: Poly<Dd, K, 0>,
    fast: Poly<Fast, K, 0>,
    filt: Poly<Filt, K, 0>,
    big: Poly<BigFloat, K, 0>,
) -> Sign {
    fl_sign(&len, fl).or_else(|| dd_sign(&len, dd)).unwrap_or_else(|| sign_fast(len, [], fast, filt, big))
}

/// The points' coordinates, flattened (`K = 3·pts.len()`).
fn flat<const K: usize>(pts: &[Xp]) -> [f64; K] {
    let mut l = [0.0; K];
    for (k, p) in pts.iter().enumerate() {
        l[3 * k..3 * k + 3].copy_from_slice(&p.v);
    }
    l
}

/// The exact sign of the polynomial on the points `pts` (`K` their
/// coordinates): [`decide_exact`] when every point is exact in `f64`; else
/// [`Fl`] on the `f64` values with each point's bound as its leaves' error
/// ([`fl_sign_err`]), then the exact evaluation on the exact points
/// multiplied by a positive factor ([`lift`]; the polynomial is
/// homogeneous, its sign unchanged).
#[inline]
fn decide<const K: usize>(
    pts: &[Xp],
    fl: Poly<Fl, K, 0>,
    dd: Poly<Dd, K, 0>,
    fast: Poly<Fast, K, 0>,
    filt: Poly<Filt, K, 0>,
    big: Poly<BigFloat, K, 0>,
) -> Sign {
    let len: [f64; K] = flat(pts);
    if pts.iter().all(|p| p.e == 0.0) {
        return decide_exact(len, fl, dd, fast, filt, big);
    }
    fl_sign_err(pts, fl).or_else(|| dd_sign_err(pts, dd)).unwrap_or_else(|| exact_sign(pts, filt, big))
}

/// The sign of the polynomial in [`Dd`] on inexact points: each point's
/// double-double value `v + lo` and its bound `ed` as the leaves, scaled by
/// the power of two that brings the largest `|v|` into `[0.5, 1)` (a scaled
/// part that falls into the subnormals adds `2^−1074`), when the bound
/// settles it.
fn dd_sign_err<const K: usize>(pts: &[Xp], dd: Poly<Dd, K, 0>) -> Option<Sign> {
    let m = pts.iter().fold(0.0f64, |m, p| p.v.iter().fold(m, |m, x| m.max(x.abs())));
    if !m.is_finite() || pts.iter().any(|p| !p.ed().is_finite()) {
        return None;
    }
    let k = if m == 0.0 { 0 } else { -crate::exact::frexp(m).1 };
    let tiny = f64::from_bits(1);
    let sc = |x: f64| {
        let v = crate::exact::ldexp(x, k);
        (v, if x != 0.0 && v.abs() < f64::MIN_POSITIVE { tiny } else { 0.0 })
    };
    let mut l = [Dd { hi: 0.0, lo: 0.0, e: 0.0 }; K];
    for (j, p) in pts.iter().enumerate() {
        let (ped, plo) = (p.ed(), p.lo());
        let (ed, _) = sc(ped);
        let ed = if ped > 0.0 { ed + tiny } else { 0.0 };
        for i in 0..3 {
            let ((hi, e1), (lo, e2)) = (sc(p.v[i]), sc(plo[i]));
            l[3 * j + i] = Dd { hi, lo, e: ed + e1 + e2 };
        }
    }
    dd(&l, &[]).sign()
}

/// The exact sign on the lifted points: in [`Filt`] first (its bound is 0
/// when every operation was exact: the exact zeros of a box with a small
/// quaternion and binary coordinates, such as a face exactly parallel to
/// another), then in [`BigFloat`].
#[cold]
fn exact_sign<const K: usize>(pts: &[Xp], filt: Poly<Filt, K, 0>, big: Poly<BigFloat, K, 0>) -> Sign {
    let f: [Filt; K] = lift(pts);
    filt(&f, &[]).sign().unwrap_or_else(|| big(&lift(pts), &[]).sign())
}

/// The points' values and bounds as [`Fl`] leaves, scaled by a power of two
/// `2^k` that brings the largest `|v| + e` into `[0.5, 1)` when it lies
/// outside `[PLAIN_LOW, PLAIN]` (`k = 0` inside): a scaled value or bound
/// that falls into the subnormals gains `2^−1074`. `None` when a value is
/// not finite.
fn leaves<const K: usize>(pts: &[Xp]) -> Option<([Fl; K], i64)> {
    let m = pts.iter().fold(0.0f64, |m, p| p.v.iter().fold(m, |m, x| m.max(x.abs() + p.e)));
    if !m.is_finite() {
        return None;
    }
    let k = if m == 0.0 || (PLAIN_LOW..=PLAIN).contains(&m) { 0 } else { -crate::exact::frexp(m).1 };
    let tiny = f64::from_bits(1);
    let mut l = [Fl { v: 0.0, e: 0.0 }; K];
    for (j, p) in pts.iter().enumerate() {
        let e = if k == 0 || p.e == 0.0 { p.e } else { crate::exact::ldexp(p.e, k) + tiny };
        for (i, x) in p.v.iter().enumerate() {
            let v = if k == 0 { *x } else { crate::exact::ldexp(*x, k) };
            let lost = if *x != 0.0 && v.abs() < f64::MIN_POSITIVE { tiny } else { 0.0 };
            l[3 * j + i] = Fl { v, e: e + lost };
        }
    }
    Some((l, k))
}

/// The sign of the polynomial in [`Fl`] on inexact points ([`leaves`]),
/// when the bound settles it.
fn fl_sign_err<const K: usize>(pts: &[Xp], fl: Poly<Fl, K, 0>) -> Option<Sign> {
    let (l, _) = leaves::<K>(pts)?;
    let x = fl(&l, &[]);
    (x.v.is_finite() && x.e.is_finite() && (x.v.abs() > x.e || x.e == 0.0)).then(|| Sign::of(x.v))
}

/// The value of the polynomial (homogeneous of degree `deg`) on inexact
/// points, in [`Fl`] ([`leaves`]), when its bound gives it to
/// `crate::boxes::poly::VALUE_REL_ERR`.
fn fl_value_err<const K: usize>(pts: &[Xp], deg: i64, fl: Poly<Fl, K, 0>) -> Option<Estimate> {
    let (l, k) = leaves::<K>(pts)?;
    let x = fl(&l, &[]);
    if !(x.v.is_finite() && x.e.is_finite()) {
        return None;
    }
    if x.e == 0.0 {
        return Some(Estimate::from_scaled(x.v, -k * deg, 0.0));
    }
    if x.v.abs() > x.e {
        let rel = x.e / (x.v.abs() - x.e) * (1.0 + 4.0 * U);
        if rel <= crate::boxes::poly::VALUE_REL_ERR {
            return Some(Estimate::from_scaled(x.v, -k * deg, rel));
        }
    }
    None
}

/// The sign of the polynomial in [`Fl`], when the bound settles it: on the
/// inputs as they are when all lie within [`PLAIN`], else on the inputs
/// scaled by the power of two that brings the largest into `[0.5, 1)` (an
/// input that falls into the subnormals is within `2^−1074` of its scaled
/// value).
#[inline]
fn fl_sign<const K: usize>(len: &[f64; K], fl: Poly<Fl, K, 0>) -> Option<Sign> {
    let x = if len.iter().all(|x| x.abs() <= PLAIN) {
        fl(&len.map(|v| Fl { v, e: 0.0 }), &[])
    } else {
        let m = len.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if !m.is_finite() {
            return None;
        }
        let k = -crate::exact::frexp(m).1;
        let l = len.map(|x| {
            let v = crate::exact::ldexp(x, k);
            Fl { v, e: if x != 0.0 && v.abs() < f64::MIN_POSITIVE { f64::from_bits(1) } else { 0.0 } }
        });
        fl(&l, &[])
    };
    (x.v.is_finite() && x.e.is_finite() && (x.v.abs() > x.e || x.e == 0.0)).then(|| Sign::of(x.v))
}

/// [`decide`] for the generic polynomial `f` (with its const arguments) on
/// the points `pts`.
macro_rules! sig {
    ($f:ident, $pts:expr $(, $c:expr)*) => {
        decide($pts, $f::<Fl $(, { $c })*>, $f::<Dd $(, { $c })*>, $f::<Fast $(, { $c })*>, $f::<Filt $(, { $c })*>, $f::<BigFloat $(, { $c })*>)
    };
}

/// The sign of a polynomial of kind-dependent form.
macro_rules! by_kind {
    ($kind:expr, $f:ident, $pts:expr $(, $c:literal)?) => {
        match $kind {
            Kind::Point => sig!($f, $pts, POINT $(, $c)?),
            Kind::Edge => sig!($f, $pts, EDGE $(, $c)?),
            Kind::Triangle => sig!($f, $pts, TRIANGLE $(, $c)?),
            Kind::Cross => sig!($f, $pts, CROSS $(, $c)?),
        }
    };
}

/// The direction's points followed by the given ones.
fn with<'a, const N: usize>(d: &Dir<'a>, pts: &[Xp<'a>]) -> [Xp<'a>; N] {
    let mut l = [ORIGIN; N];
    l[..6].copy_from_slice(&d.pts);
    l[6..6 + pts.len()].copy_from_slice(pts);
    l
}

/// The exact sign of `N · (x − r)`. Two of the points a cross product is
/// made of lie on one level by construction (`N ⟂ p₁ − p₀` and
/// `N ⟂ q₁ − q₀`; a face's three points when `q₀ = p₀`): that zero is
/// answered without evaluating it (its rounding would defeat the filters).
pub(crate) fn side(d: &Dir, x: Xp, r: Xp) -> Sign {
    if let Some((b, bits)) = x.box_diff(&r)
        && bits & b.nonzero() & !d.perpendicular(b) == 0
    {
        return Sign::Zero;
    }
    if d.kind == Kind::Cross {
        let [p0, p1, q0, q1, _, _] = d.pts;
        let is = |set: &[Xp], y: &Xp| set.iter().any(|z| same(z, y));
        let face = same(&p0, &q0);
        let own = |set: &[Xp]| is(set, &x) && is(set, &r);
        if own(&[p0, p1]) || own(&[q0, q1]) || (face && own(&[p0, p1, q1])) {
            return Sign::Zero;
        }
        // `x − r` parallel to a factor of plain points (a hull's edge beside
        // its own, under an axis with a box's edge): zero, which the filters
        // on the box's inexact corners could not see; decided on the plain
        // points alone.
        let plain = |set: &[Xp]| set.iter().all(|z| z.e == 0.0);
        if !plain(&d.pts[..4])
            && plain(&[x, r])
            && ((plain(&[p0, p1]) && parallel(p0, p1, x, r)) || (plain(&[q0, q1]) && parallel(q0, q1, x, r)))
        {
            return Sign::Zero;
        }
    }
    let p: [Xp; 8] = with(d, &[x, r]);
    by_kind!(d.kind, side_poly, &p)
}

/// The exact sign of `N · ((x − y) − (r − t))`.
pub(crate) fn side_w(d: &Dir, x: Xp, y: Xp, r: Xp, t: Xp) -> Sign {
    let level = |u: &Xp, w: &Xp| {
        u.identical(w) || u.box_diff(w).is_some_and(|(b, bits)| bits & b.nonzero() & !d.perpendicular(b) == 0)
    };
    if level(&x, &r) && level(&y, &t) {
        return Sign::Zero;
    }
    let p: [Xp; 10] = with(d, &[x, y, r, t]);
    by_kind!(d.kind, side_w_poly, &p)
}

/// The exact sign of `N · ((q − p) × (s − r))`; `orient(d, p, q, p, s)` is the
/// orientation of the triangle `p q s` seen along `N` (positive:
/// counter-clockwise, seen from `N`'s tip).
pub(crate) fn orient(d: &Dir, p: Xp, q: Xp, r: Xp, s: Xp) -> Sign {
    let x: [Xp; 10] = with(d, &[p, q, r, s]);
    by_kind!(d.kind, orient_poly, &x)
}

/// Whether `x` and `r` are one point seen along `N` (`(x − r) × N = 0`).
pub(crate) fn same_along(d: &Dir, x: Xp, r: Xp) -> bool {
    let p: [Xp; 8] = with(d, &[x, r]);
    by_kind!(d.kind, apart_poly, &p, 0) == Sign::Zero
        && by_kind!(d.kind, apart_poly, &p, 1) == Sign::Zero
        && by_kind!(d.kind, apart_poly, &p, 2) == Sign::Zero
}

/// Whether `N` is exactly the zero vector.
pub(crate) fn is_zero(d: &Dir) -> bool {
    let p = &d.pts;
    by_kind!(d.kind, component_poly, p, 0) == Sign::Zero
        && by_kind!(d.kind, component_poly, p, 1) == Sign::Zero
        && by_kind!(d.kind, component_poly, p, 2) == Sign::Zero
}

/// `N`'s unit vector, each component within a few `2^−40` (`None` for a zero
/// `N`). On inexact points: from [`Fl`] when it gives every component to
/// that accuracy, else from the exact components of the lifted points (all
/// three multiplied by one positive factor: the same unit vector).
pub(crate) fn unit(d: &Dir) -> Option<Vec3<f64>> {
    let deg = d.degree();
    macro_rules! each {
        ($e:ident, $kind:ident, $c:literal) => {
            $e!(component_poly, $kind, $c)
        };
    }
    macro_rules! comps {
        ($e:ident) => {
            match d.kind {
                Kind::Point => [each!($e, POINT, 0), each!($e, POINT, 1), each!($e, POINT, 2)],
                Kind::Edge => [each!($e, EDGE, 0), each!($e, EDGE, 1), each!($e, EDGE, 2)],
                Kind::Triangle => [each!($e, TRIANGLE, 0), each!($e, TRIANGLE, 1), each!($e, TRIANGLE, 2)],
                Kind::Cross => [each!($e, CROSS, 0), each!($e, CROSS, 1), each!($e, CROSS, 2)],
            }
        };
    }
    let e: [Estimate; 3] = if d.pts.iter().all(|p| p.e == 0.0) {
        let l = d.lengths();
        macro_rules! plain {
            ($f:ident, $kind:ident, $c:literal) => {
                value_fast(l, [], deg, $f::<Fast, $kind, $c>, $f::<Filt, $kind, $c>, $f::<BigFloat, $kind, $c>)
            };
        }
        comps!(plain)
    } else {
        macro_rules! filtered {
            ($f:ident, $kind:ident, $c:literal) => {
                fl_value_err(&d.pts, deg, $f::<Fl, $kind, $c>)
            };
        }
        match comps!(filtered) {
            [Some(x), Some(y), Some(z)] => [x, y, z],
            _ => {
                let l: [BigFloat; 18] = lift(&d.pts);
                macro_rules! lifted {
                    ($f:ident, $kind:ident, $c:literal) => {
                        $f::<BigFloat, $kind, $c>(&l, &[]).estimate()
                    };
                }
                comps!(lifted)
            }
        }
    };
    Estimate::unit_vector(e).map(|u| Vec3::new(u[0], u[1], u[2]))
}

/// The exact sign of `(x − y) · (r₁ − r₀)`.
pub(crate) fn along(x: Xp, y: Xp, r0: Xp, r1: Xp) -> Sign {
    if x.identical(&y) {
        return Sign::Zero;
    }
    sig!(along_poly, &[x, y, r0, r1])
}

/// Whether `p₁ − p₀` and `q₁ − q₀` are parallel (their cross product is
/// exactly zero).
pub(crate) fn parallel(p0: Xp, p1: Xp, q0: Xp, q1: Xp) -> bool {
    // Two edges of one box along one axis.
    if let (Some((b, s)), Some((c, t))) = (p0.box_diff(&p1), q0.box_diff(&q1))
        && std::ptr::eq(b, c)
        && s == t
        && s.count_ones() == 1
    {
        return true;
    }
    let l = [p0, p1, q0, q1];
    sig!(edge_cross_poly, &l, 0) == Sign::Zero
        && sig!(edge_cross_poly, &l, 1) == Sign::Zero
        && sig!(edge_cross_poly, &l, 2) == Sign::Zero
}

/// Whether `a`, `b` and `c` lie on one line (`(b − a) × (c − a) = 0`).
pub(crate) fn collinear(a: Xp, b: Xp, c: Xp) -> bool {
    // Three corners of one box with positive half extents: the differences
    // of distinct corners from one corner are independent unless equal.
    if let (Some((x, _)), Some((y, _))) = (a.box_diff(&b), a.box_diff(&c))
        && std::ptr::eq(x, y)
        && x.solid()
    {
        return a.identical(&b) || a.identical(&c) || b.identical(&c);
    }
    if a.e == 0.0 && b.e == 0.0 && c.e == 0.0 {
        return crate::exact::collinear(a.v, b.v, c.v);
    }
    parallel(a, b, a, c)
}

/// `det[a − d, b − d, c − d]` of the points `a, b, c, d`: the convention of
/// `crate::exact::orient3d` (positive when `d` lies below the plane of `a`,
/// `b`, `c` seen counter-clockwise from above).
fn orient3d_poly<R: Ring>(l: &[R; 12], _u: &[R; 0]) -> R {
    let (a, b, c) = (sub3(at(l, 0), at(l, 9)), sub3(at(l, 3), at(l, 9)), sub3(at(l, 6), at(l, 9)));
    dot3(refs(&a), refs(&cross3(refs(&b), refs(&c))))
}

/// `crate::exact::orient3d` of the points, exactly.
pub(crate) fn orient3d(a: Xp, b: Xp, c: Xp, d: Xp) -> Sign {
    if [a, b, c, d].iter().all(|p| p.e == 0.0) {
        return crate::exact::orient3d(a.v, b.v, c.v, d.v);
    }
    sig!(orient3d_poly, &[a, b, c, d])
}

/// Whether the origin's foot on the line of the Minkowski segment
/// `(a₀ − b₀)(a₁ − b₁)` lies on the segment (ends included).
pub(crate) fn foot_on_edge(a: [Xp; 2], b: [Xp; 2]) -> bool {
    let l = [a[0], a[1], b[0], b[1]];
    sig!(foot_edge_poly, &l, 0) != Sign::Positive && sig!(foot_edge_poly, &l, 1) != Sign::Negative
}

/// Whether the origin's projection onto the plane of the Minkowski triangle
/// `a_k − b_k` lies in the triangle (its boundary included); the triangle's
/// normal must not be zero.
pub(crate) fn foot_in_triangle(a: [Xp; 3], b: [Xp; 3]) -> bool {
    let l = [a[0], a[1], a[2], b[0], b[1], b[2]];
    sig!(foot_triangle_poly, &l, 0) != Sign::Negative
        && sig!(foot_triangle_poly, &l, 1) != Sign::Negative
        && sig!(foot_triangle_poly, &l, 2) != Sign::Negative
}

/// A push of `a` clear of `b` along `σ·L`, `L` a cross-product axis:
/// `p = L · (y − x)` for the given points (`y` the push's support on `b`,
/// `x` on `a`, swapped for `σ = −1`), and its exact sign.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ExactPush<'a> {
    /// The axis (a [`Kind::Cross`] direction).
    pub axis: Dir<'a>,
    /// `+1` or `−1`: the push's sense along the axis.
    pub sense: i8,
    /// The points whose difference along `L` is `p`.
    pub p: [Xp<'a>; 2],
    /// `sign(p)`.
    pub sign: Sign,
}

impl<'a> ExactPush<'a> {
    /// The points `[p₀, p₁, q₀, q₁, y, x]` of the push.
    fn points(&self) -> [Xp<'a>; 6] {
        [self.axis.pts[0], self.axis.pts[1], self.axis.pts[2], self.axis.pts[3], self.p[0], self.p[1]]
    }

    /// `log₂ |p/‖L‖|` and a bound on its error (from [`Estimate`]s of `p` and
    /// `‖L‖²` to `2^−40`); `None` for a zero push, and for inexact points
    /// whose floating-point values do not reach that accuracy.
    pub(crate) fn log_size(&self) -> Option<(f64, f64)> {
        if self.sign == Sign::Zero {
            return None;
        }
        let pts = self.points();
        let (p, n) = if pts.iter().all(|x| x.e == 0.0) {
            let l: [f64; 18] = flat(&pts);
            let p = value_fast(
                l,
                [],
                3,
                push_value_poly::<Fast, 0>,
                push_value_poly::<Filt, 0>,
                push_value_poly::<BigFloat, 0>,
            );
            let n = value_fast(
                l,
                [],
                4,
                push_value_poly::<Fast, 1>,
                push_value_poly::<Filt, 1>,
                push_value_poly::<BigFloat, 1>,
            );
            (p, n)
        } else {
            match (fl_value_err(&pts, 3, push_value_poly::<Fl, 0>), fl_value_err(&pts, 4, push_value_poly::<Fl, 1>)) {
                (Some(p), Some(n)) => (p, n),
                _ => return lifted_log_size(&pts),
            }
        };
        if p.sign == Sign::Zero || n.sign == Sign::Zero {
            return None;
        }
        let size = p.mant.log2() + p.exp as f64 - 0.5 * (n.mant.log2() + n.exp as f64);
        // log₂(1 + r) ≤ 1.5 r for small r; the logarithms' own rounding (of
        // values up to a few thousand) is far below 2^−30.
        let err = 1.5 * (p.rel_err + 0.5 * n.rel_err) + LOG_ROUNDING;
        Some((size, err))
    }
}

/// [`ExactPush::log_size`] from the push's exact values on the lifted
/// points (`super::points::lift`: each coordinate multiplied by `D`, so `p`
/// by `D³` and `‖L‖²` by `D⁴`, and the size by `D`): `log₂ D` (the boxes'
/// `‖q‖²` in `f64` on their quaternions scaled by powers of two, each
/// within `4u` relative, `log₂` then within `8u` each, with room
/// [`LOG_ROUNDING`]) taken off. Cheaper than [`push_cmp`]'s exact degree-10
/// comparison where the filters fail (a scene of very different
/// magnitudes), and it orders pushes far apart.
#[cold]
fn lifted_log_size(pts: &[Xp; 6]) -> Option<(f64, f64)> {
    let l: [BigFloat; 18] = lift(pts);
    let p = push_value_poly::<BigFloat, 0>(&l, &[]).estimate();
    let n = push_value_poly::<BigFloat, 1>(&l, &[]).estimate();
    if p.sign == Sign::Zero || n.sign == Sign::Zero {
        return None;
    }
    let mut log_d = 0.0;
    let mut seen: Vec<&ExactBox> = Vec::with_capacity(2);
    for x in pts.iter().filter(|x| x.e > 0.0) {
        if let Some((b, _)) = x.corner()
            && !seen.iter().any(|y| std::ptr::eq(*y, b))
        {
            seen.push(b);
            log_d += b.log2_norm2();
        }
    }
    let size = p.mant.log2() + p.exp as f64 - 0.5 * (n.mant.log2() + n.exp as f64) - log_d;
    let err = 1.5 * (p.rel_err + 0.5 * n.rel_err) + LOG_ROUNDING * (1.0 + seen.len() as f64);
    Some((size, err))
}

/// The absolute error allowed for the rounding of a `log₂` of an
/// [`Estimate`] (`f64` logarithms of numbers below `2^13`, and the exponent
/// added): far above their few ulps.
const LOG_ROUNDING: f64 = 1.0 / (1u64 << 30) as f64;

/// `p₁/‖L₁‖` against `p₂/‖L₂‖`, exactly; `sizes` their
/// [`ExactPush::log_size`]s when known, which decide pushes far apart.
pub(crate) fn push_cmp(x: &ExactPush, y: &ExactPush, sizes: [Option<(f64, f64)>; 2]) -> std::cmp::Ordering {
    use std::cmp::Ordering;
    match x.sign.as_i8().cmp(&y.sign.as_i8()) {
        Ordering::Equal => {}
        other => return other,
    }
    if x.sign == Sign::Zero {
        return Ordering::Equal;
    }
    if let [Some((sx, ex)), Some((sy, ey))] = sizes
        && (sx - sy).abs() > ex + ey
    {
        let by_size = sx.total_cmp(&sy);
        return if x.sign == Sign::Positive { by_size } else { by_size.reverse() };
    }
    let mut l = [ORIGIN; 12];
    l[..6].copy_from_slice(&x.points());
    l[6..].copy_from_slice(&y.points());
    let s = sig!(push_cmp_poly, &l);
    // p₁²n₂ − p₂²n₁ orders |p₁|/‖L₁‖ against |p₂|/‖L₂‖.
    let by_size = s.as_i8().cmp(&0);
    if x.sign == Sign::Positive { by_size } else { by_size.reverse() }
}

/// Whether two pushes go the same way (`σ₁L₁` and `σ₂L₂` parallel and of one
/// sense).
pub(crate) fn same_direction(x: &ExactPush, y: &ExactPush) -> bool {
    let mut l = [ORIGIN; 8];
    l[..4].copy_from_slice(&x.axis.pts[..4]);
    l[4..].copy_from_slice(&y.axis.pts[..4]);
    let parallel = matches!((x.axis.known(), y.axis.known()), (Some(a), Some(b)) if a.same(&b));
    if !parallel
        && (sig!(pair_poly, &l, 0) != Sign::Zero
            || sig!(pair_poly, &l, 1) != Sign::Zero
            || sig!(pair_poly, &l, 2) != Sign::Zero)
    {
        return false;
    }
    sig!(pair_poly, &l, 3).as_i8() * x.sense * y.sense > 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::P3;
    use proptest::prelude::*;

    /// The exact sign, in [`BigFloat`] alone.
    fn exact<const K: usize>(len: &[f64; K], big: Poly<BigFloat, K, 0>) -> Sign {
        big(&len.map(BigFloat::from_f64), &[]).sign()
    }

    /// Each stage's answer, when it gives one, and the whole filter's are
    /// the exact sign.
    fn agree<const K: usize>(
        len: [f64; K],
        fl: Poly<Fl, K, 0>,
        dd: Poly<Dd, K, 0>,
        fast: Poly<Fast, K, 0>,
        filt: Poly<Filt, K, 0>,
        big: Poly<BigFloat, K, 0>,
    ) -> Result<(), TestCaseError> {
        let want = exact(&len, big);
        if let Some(s) = fl_sign(&len, fl) {
            prop_assert_eq!(s, want, "Fl on {:?}", len);
        }
        if let Some(s) = dd_sign(&len, dd) {
            prop_assert_eq!(s, want, "Dd on {:?}", len);
        }
        prop_assert_eq!(decide_exact(len, fl, dd, fast, filt, big), want, "decide on {:?}", len);
        Ok(())
    }

    macro_rules! check {
        ($f:ident, $len:expr $(, $c:expr)*) => {
            agree($len, $f::<Fl $(, { $c })*>, $f::<Dd $(, { $c })*>, $f::<Fast $(, { $c })*>, $f::<Filt $(, { $c })*>, $f::<BigFloat $(, { $c })*>)
        };
    }

    /// Twelve points of one of four kinds: random in a unit box; on one
    /// plane up to rounding (`u₀ + α(u₁ − u₀) + β(u₂ − u₀)`, rounded once
    /// per operation: the values the predicates take are then within a few
    /// ulps of zero); the same on a grid of eighths (exact zeros); and
    /// random magnitudes from `2^−1000` to `2^1000` with either sign.
    fn points() -> impl Strategy<Value = Vec<P3>> {
        let unit = || -1.0..1.0f64;
        let basis = prop::array::uniform3(prop::array::uniform3(unit()));
        let coef = prop::collection::vec((unit(), unit()), 12);
        let wide = prop::collection::vec(prop::array::uniform3((-1000i32..1000, 0.5..1.0f64, any::<bool>())), 12);
        (0..4usize, basis, coef, wide).prop_map(|(kind, u, c, w)| match kind {
            0 => c
                .iter()
                .zip(&u)
                .map(|((a, b), x)| [*a, *b, x[0]])
                .chain(c.iter().map(|(a, b)| [*b, *a, a * b]))
                .take(12)
                .collect(),
            3 => w.iter().map(|p| p.map(|(e, m, s)| if s { m * 2f64.powi(e) } else { -m * 2f64.powi(e) })).collect(),
            _ => {
                let grid = |x: f64| if kind == 2 { (x * 8.0).round() / 8.0 } else { x };
                let u = u.map(|p| p.map(grid));
                c.iter()
                    .map(|(a, b)| {
                        let (a, b) = (grid(*a), grid(*b));
                        [0, 1, 2].map(|k| u[0][k] + a * (u[1][k] - u[0][k]) + b * (u[2][k] - u[0][k]))
                    })
                    .collect()
            }
        })
    }

    fn flat<const K: usize>(p: &[P3]) -> [f64; K] {
        let mut l = [0.0; K];
        for (k, x) in l.iter_mut().enumerate() {
            *x = p[k / 3 % p.len()][k % 3];
        }
        l
    }

    /// A value of `−1e-325` relative to its terms in the scaled inputs: the
    /// double-double products that make it underflow, and the bounds they
    /// carry underflow with them; the bound must not vanish (it once did,
    /// and [`Dd`] called the value an exact zero).
    #[test]
    fn an_underflowing_bound_is_not_an_exact_zero() {
        let p: [P3; 10] = [
            [-0.5, -0.5, -0.5],
            [-0.5, -0.5, 0.5],
            [-0.5, -0.5, -0.5],
            [-0.5, -0.5, -0.8917688435906126],
            [-0.5, -0.5, -0.5],
            [-0.5, 0.5, -0.5],
            [-0.5, -0.5, -0.5],
            [-0.5, -0.5, 0.5],
            [-5.871356456934583e107, -1.7031839360032603e-108, -0.5],
            [-0.5, -8.515919680016301e-109, -0.5],
        ];
        let l: [f64; 30] = flat(&p);
        assert_eq!(exact(&l, orient_poly::<BigFloat, TRIANGLE>), Sign::Negative);
        assert!(dd_sign(&l, orient_poly::<Dd, TRIANGLE>).is_none_or(|s| s == Sign::Negative));
        check!(orient_poly, l, TRIANGLE).expect("the filters agree with the exact sign");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        #[test]
        fn every_stage_gives_the_exact_sign(p in points()) {
            let l24: [f64; 24] = flat(&p);
            check!(side_poly, l24, CROSS)?;
            check!(side_poly, l24, EDGE)?;
            check!(side_poly, l24, TRIANGLE)?;
            check!(side_poly, l24, POINT)?;
            check!(pair_poly, l24, 0)?;
            check!(pair_poly, l24, 3)?;
            let l30: [f64; 30] = flat(&p);
            check!(orient_poly, l30, CROSS)?;
            check!(orient_poly, l30, TRIANGLE)?;
            check!(side_w_poly, l30, EDGE)?;
            let l36: [f64; 36] = flat(&p);
            check!(push_cmp_poly, l36)?;
            let l12: [f64; 12] = flat(&p);
            check!(edge_cross_poly, l12, 1)?;
            check!(along_poly, l12)?;
            check!(foot_edge_poly, l12, 0)?;
            let l18: [f64; 18] = flat(&p);
            check!(foot_triangle_poly, l18, 2)?;
            check!(component_poly, l18, EDGE, 1)?;
        }
    }
}
