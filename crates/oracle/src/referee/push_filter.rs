//! A floating-point filter in front of the exact least push over separating
//! axes (`super::convex::least_push`): which of the candidate pushes can be
//! the least.
//!
//! The exact search projects both polytopes on every candidate axis in
//! rationals — for two hulls of `n` points about `9n²` axes, each against
//! `2n` vertices — and compares the pushes by cross-multiplication. Here every
//! push is first enclosed in an `f64` interval `[lo, hi]`; with `U` the least
//! `hi`, a push whose `lo` exceeds `U` is certainly longer than another and
//! cannot be the least, nor tie with it. The exact search then runs over the
//! rest, in the same order, so it finds the same least push, the same first
//! one among equals and the same tie: every push equal to the least is kept.
//!
//! **The enclosures.** Each exact coordinate `x` (a vertex's, an edge
//! direction's, a face normal's) is rounded once to `x̃` with
//! `|x − x̃| ≤ 2u|x̃| + η` (`u = 2⁻⁵³`, `η = 2⁻¹⁰⁷⁴` for what underflow loses).
//! A cross product `l̃ = ã × b̃` formed in `f64` errs by at most
//! `8u·(|ãⱼb̃ₖ| + |ãₖb̃ⱼ|) + 8η(1 + |ã|₁ + |b̃|₁)` per component (the inputs'
//! errors, `4u` to first order, and three roundings). A projection
//! `P̃ = l̃·ṽ` errs by at most `E_l·|ṽ| + 6u·|l̃|·|ṽ| + η(|l̃|₁ + 5)` (the
//! axis's error, the vertex's, and the three products and two sums). Every
//! such bound is taken **four times over**, which covers the second-order
//! terms and the roundings of the bounds' own arithmetic; each further step
//! (the extreme projections' difference, the axis's length, the quotient)
//! widens its result outward by `4u` of it and `η`. An axis whose length
//! cannot be bounded away from zero, or any value that is not finite, keeps
//! its pushes (or the whole search) exact.

use super::exact::{V3, round};

/// A polytope as the filter reads it: its vertices, its face normals and
/// its edge directions (`super::convex::Convex`'s).
pub(super) struct Polytope<'a> {
    pub(super) vertices: &'a [V3],
    pub(super) normals: &'a [V3],
    pub(super) directions: &'a [V3],
}

const U: f64 = f64::EPSILON / 2.0;
/// What one operation can lose to underflow, and the rounding's absolute floor.
const ETA: f64 = f64::MIN_POSITIVE * f64::EPSILON;
/// The margin every first-order bound is multiplied by (see the module docs).
const SAFETY: f64 = 4.0;

/// Where a candidate axis comes from, in the format's order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum AxisOf {
    NormalA(usize),
    NormalB(usize),
    /// `a`'s direction `i` crossed with `b`'s direction `j`.
    Cross(usize, usize),
}

/// The candidate axes of `a` against `b` in the format's order: `a`'s normals,
/// `b`'s normals, then `a`'s directions crossed with `b`'s, row by row.
pub(super) fn axis_order(a: &Polytope<'_>, b: &Polytope<'_>) -> impl Iterator<Item = AxisOf> + use<> {
    let (na, nb, da, db) = (a.normals.len(), b.normals.len(), a.directions.len(), b.directions.len());
    (0..na)
        .map(AxisOf::NormalA)
        .chain((0..nb).map(AxisOf::NormalB))
        .chain((0..da).flat_map(move |i| (0..db).map(move |j| AxisOf::Cross(i, j))))
}

/// A vector rounded to `f64` with its componentwise error bound.
#[derive(Clone, Copy)]
struct Approx {
    x: [f64; 3],
    e: [f64; 3],
}

fn rounded(v: &V3) -> Approx {
    let x = [round(&v[0]), round(&v[1]), round(&v[2])];
    Approx { x, e: x.map(|c| 2.0 * U * c.abs() + ETA) }
}

fn abs_dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0].abs() * b[0].abs() + a[1].abs() * b[1].abs() + a[2].abs() * b[2].abs()
}

fn cross(a: &Approx, b: &Approx) -> Approx {
    let (p, q) = (a.x, b.x);
    let x = [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]];
    let l1 = |v: &[f64; 3]| v[0].abs() + v[1].abs() + v[2].abs();
    let floor = 8.0 * ETA * (1.0 + l1(&p) + l1(&q));
    let m = [
        (p[1] * q[2]).abs() + (p[2] * q[1]).abs(),
        (p[2] * q[0]).abs() + (p[0] * q[2]).abs(),
        (p[0] * q[1]).abs() + (p[1] * q[0]).abs(),
    ];
    Approx { x, e: m.map(|m| SAFETY * (8.0 * U * m + floor)) }
}

/// `x` moved outward (down or up) past what rounding it may have lost.
fn down(x: f64) -> f64 {
    x - 4.0 * U * x.abs() - ETA
}
fn up(x: f64) -> f64 {
    x + 4.0 * U * x.abs() + ETA
}

/// The least and greatest projections of `vertices` on `l`, each enclosed.
fn extremes(l: &Approx, vertices: &[Approx]) -> ([f64; 2], [f64; 2]) {
    let l1 = l.x[0].abs() + l.x[1].abs() + l.x[2].abs();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for v in vertices {
        let p = l.x[0] * v.x[0] + l.x[1] * v.x[1] + l.x[2] * v.x[2];
        let e = SAFETY
            * (l.e[0] * v.x[0].abs()
                + l.e[1] * v.x[1].abs()
                + l.e[2] * v.x[2].abs()
                + 6.0 * U * abs_dot(&l.x, &v.x)
                + ETA * (l1 + 5.0));
        let (pl, ph) = (down(p - e), up(p + e));
        lo = [lo[0].min(pl), lo[1].min(ph)];
        hi = [hi[0].max(pl), hi[1].max(ph)];
    }
    (lo, hi)
}

/// `amount/‖l‖` enclosed, for `amount ∈ [a_lo, a_hi]`, `‖l‖ ∈ [n_lo, n_hi]`,
/// `n_lo > 0`.
fn quotient(a: [f64; 2], n: [f64; 2]) -> [f64; 2] {
    let lo = if a[0] >= 0.0 { a[0] / n[1] } else { a[0] / n[0] };
    let hi = if a[1] >= 0.0 { a[1] / n[0] } else { a[1] / n[1] };
    [down(lo), up(hi)]
}

/// For each candidate axis in [`axis_order`], whether its push along `+L` and
/// along `−L` may be the least (`[plus, minus]`). `None` when some value is
/// not finite: the whole search stays exact.
pub(super) fn may_be_least(a: &Polytope<'_>, b: &Polytope<'_>) -> Option<Vec<(AxisOf, [bool; 2])>> {
    let (va, vb): (Vec<Approx>, Vec<Approx>) =
        (a.vertices.iter().map(rounded).collect(), b.vertices.iter().map(rounded).collect());
    let (na, nb): (Vec<Approx>, Vec<Approx>) =
        (a.normals.iter().map(rounded).collect(), b.normals.iter().map(rounded).collect());
    let (da, db): (Vec<Approx>, Vec<Approx>) =
        (a.directions.iter().map(rounded).collect(), b.directions.iter().map(rounded).collect());
    let finite = |s: &[Approx]| s.iter().all(|v| v.x.iter().chain(&v.e).all(|c| c.is_finite()));
    if ![&va, &vb, &na, &nb, &da, &db].iter().all(|s| finite(s)) {
        return None;
    }
    // Each push's enclosure; `None` for an axis whose length may be zero.
    let mut pushes: Vec<(AxisOf, Option<[[f64; 2]; 2]>)> = Vec::new();
    let mut least_hi = f64::INFINITY;
    for id in axis_order(a, b) {
        let l = match id {
            AxisOf::NormalA(i) => na[i],
            AxisOf::NormalB(j) => nb[j],
            AxisOf::Cross(i, j) => cross(&da[i], &db[j]),
        };
        let norm = (l.x[0] * l.x[0] + l.x[1] * l.x[1] + l.x[2] * l.x[2]).sqrt();
        let el = l.e[0] + l.e[1] + l.e[2];
        let n = [down(norm) - up(el), up(norm) + up(el)];
        let (lo_a, hi_a) = extremes(&l, &va);
        let (lo_b, hi_b) = extremes(&l, &vb);
        let all = [norm, el, lo_a[0], lo_a[1], hi_a[0], hi_a[1], lo_b[0], lo_b[1], hi_b[0], hi_b[1]];
        if !all.iter().all(|x| x.is_finite()) {
            return None;
        }
        if n[0] <= 0.0 {
            pushes.push((id, None));
            continue;
        }
        // Along +L: max_b − min_a; along −L: max_a − min_b.
        let plus = quotient([down(hi_b[0] - lo_a[1]), up(hi_b[1] - lo_a[0])], n);
        let minus = quotient([down(hi_a[0] - lo_b[1]), up(hi_a[1] - lo_b[0])], n);
        if !(plus.iter().chain(&minus).all(|x| x.is_finite())) {
            return None;
        }
        least_hi = least_hi.min(plus[1]).min(minus[1]);
        pushes.push((id, Some([plus, minus])));
    }
    Some(
        pushes
            .into_iter()
            .map(|(id, p)| match p {
                None => (id, [true, true]),
                Some([plus, minus]) => (id, [plus[0] <= least_hi, minus[0] <= least_hi]),
            })
            .collect(),
    )
}
