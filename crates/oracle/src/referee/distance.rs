//! Signed distance of two solids, exactly: the `distance` query
//! (`docs/FORMAT.md`, "Distance").
//!
//! **Every solid is a polytope grown by a ball.** A sphere is its centre grown
//! by its radius, a capsule its axis grown by its radius, a box its eight
//! corners (exact under its quaternion's rational rotation), a triangle its
//! three vertices, a `convex` shape the exact hull of its points
//! (`super::hull`). For cores `A`, `B` (polytopes) and radii `r_a`, `r_b`, the
//! support function of a grown solid is the core's plus its radius, so the
//! solids' signed distance is the cores' minus `r = r_a + r_b`, along the same
//! direction — apart, touching or overlapping alike:
//!
//! - **Cores apart.** The point `v = p_a − p_b` of the Minkowski difference
//!   `A − B` nearest the origin is found by GJK in exact rational arithmetic:
//!   each step takes the support point `w` of `A − B` in `−v` (exact dot
//!   products) and stops when `v·w = v·v`, which proves `v` nearest (every
//!   point `m` of `A − B` has `v·m ≥ v·w = v·v`). The simplex's nearest point
//!   is the least-norm projection onto the affine hulls of its subsets with
//!   non-negative barycentric coordinates (Cramer's rule, exact). In exact
//!   arithmetic `‖v‖` falls strictly at each step, so the loop ends.
//!   The distance is `√(v·v) − r`, rounded once; the normal `v/‖v‖`.
//! - **Cores meeting** (`v = 0`). Their penetration depth `s` is the least
//!   push over the separating axes (`super::convex`: the faces' normals of
//!   each and the cross products of their edge directions, which hold every
//!   facet normal of `A − B`), and the distance is `−(s + r)` along that push.
//!
//! In both, `a` moved by the translation that makes the cores touch
//! (`−v`, or the least push) touches `b` in the touching set of their support
//! features: the set of `b`'s core witnesses. `point_b` is its centre moved
//! out by `r_b` along the normal and `point_a = point_b + distance·normal`
//! (each rounded once). The witnesses are unique exactly when that set is one
//! point; otherwise any pair of it is right, and `degenerate` is set — as it
//! is when two least pushes go different ways (the normal is not unique).
//!
//! **A plane** (`b` only) is the half-space `n·x ≤ d`: the distance is
//! `(min_a n·x − d)/‖n‖ − r_a`, the witnesses `a`'s lowest core points (several
//! when a face or an edge lies parallel to the plane: `degenerate`).
//!
//! **No direction.** Cores that meet with no separating axis at all (two
//! points, or points and segments along one line) penetrate by 0 in every
//! direction across their line: the normal is `(0, 0, 1)` for points (as for
//! concentric spheres), else the unit vector of `u × z` (or `u × x` when the
//! line is along `z`) for the line's direction `u`; `degenerate`.

use super::boxes::{BOX_A, BOX_B, exact_box};
use super::convex::{Convex, Push, least_push, middle, touching_region};
use super::error::RefereeError;
use super::exact::{Q, Root, V3, add, check_v3, dot, dot_relaxed, is_zero, q, radius, round_unit, scale, sub, v3};
use super::hull::{convex_hull, distinct_points};
use super::stage::{Memo, remembered};
use crate::geom::{DistanceAnswer, P3, Solid};

/// The field names of one side's shapes, for errors.
struct Fields {
    center: &'static str,
    radius: &'static str,
    start: &'static str,
    end: &'static str,
    vertices: &'static str,
    points: &'static str,
    normal: &'static str,
    offset: &'static str,
}

const A: Fields = Fields {
    center: "a.center",
    radius: "a.radius",
    start: "a.start",
    end: "a.end",
    vertices: "a.vertices",
    points: "a.points",
    normal: "a.normal",
    offset: "a.offset",
};
const B: Fields = Fields {
    center: "b.center",
    radius: "b.radius",
    start: "b.start",
    end: "b.end",
    vertices: "b.vertices",
    points: "b.points",
    normal: "b.normal",
    offset: "b.offset",
};

/// A solid as the referee holds it.
enum Held<'a> {
    /// A polytope grown by `r` (0 for a box, a triangle or a hull). A
    /// `convex` shape's core holds its distinct points until the separating
    /// axes need its faces and edges (`hull`: its points, to build them):
    /// GJK and the touching set need only points.
    Grown { core: Convex, r: Q, hull: Option<&'a [P3]> },
    /// The half-space `n·x ≤ d`.
    HalfSpace { n: V3, d: Q },
}

fn held<'a>(s: Solid<'a>, f: &Fields, is_a: bool) -> Result<Held<'a>, RefereeError> {
    Ok(match s {
        Solid::Sphere(s) => {
            let c = v3(&s.center, f.center)?;
            Held::Grown {
                core: Convex { vertices: vec![c], edges: vec![], directions: vec![], normals: vec![] },
                r: radius(s.radius, f.radius)?,
                hull: None,
            }
        }
        Solid::Capsule(c) => {
            let (p0, p1) = (v3(&c.start, f.start)?, v3(&c.end, f.end)?);
            let r = radius(c.radius, f.radius)?;
            let core = if p0 == p1 {
                Convex { vertices: vec![p0], edges: vec![], directions: vec![], normals: vec![] }
            } else {
                Convex::of_segment(&p0, &p1)
            };
            Held::Grown { core, r, hull: None }
        }
        Solid::Box(b) => {
            let e = exact_box(b, if is_a { BOX_A } else { BOX_B })?;
            // A box without extent along two or three of its axes is a segment
            // or a point: its core has no face, so its axes are no directions
            // of its own (the format's rule for cores that meet with no
            // direction at all gives the normal, as for a capsule or a sphere).
            let spread: Vec<usize> = (0..3).filter(|&i| !e.h[i].is_zero()).collect();
            let core = match spread.as_slice() {
                [] => Convex {
                    vertices: vec![e.to_world(&[Q::ZERO, Q::ZERO, Q::ZERO])],
                    edges: vec![],
                    directions: vec![],
                    normals: vec![],
                },
                &[i] => {
                    let end = |sign: bool| {
                        let u: V3 = std::array::from_fn(|k| match (k == i, sign) {
                            (false, _) => Q::ZERO,
                            (true, true) => e.h[i].clone(),
                            (true, false) => -e.h[i].clone(),
                        });
                        e.to_world(&u)
                    };
                    Convex::of_segment(&end(false), &end(true))
                }
                _ => Convex::of_box(&e),
            };
            Held::Grown { core, r: Q::ZERO, hull: None }
        }
        Solid::Triangle(t) => {
            let v = [v3(&t.vertices[0], f.vertices)?, v3(&t.vertices[1], f.vertices)?, v3(&t.vertices[2], f.vertices)?];
            Held::Grown { core: Convex::of_triangle(&v), r: Q::ZERO, hull: None }
        }
        Solid::Convex(c) => {
            let vertices =
                distinct_points(&c.points, f.points)?.iter().map(|p| v3(p, f.points)).collect::<Result<_, _>>()?;
            let core = Convex { vertices, edges: vec![], directions: vec![], normals: vec![] };
            Held::Grown { core, r: Q::ZERO, hull: Some(&c.points) }
        }
        Solid::Plane(p) => {
            check_v3(&p.normal, f.normal)?;
            if p.normal.iter().all(|&x| x == 0.0) {
                return Err(RefereeError::ZeroNormal { field: f.normal });
            }
            Held::HalfSpace { n: v3(&p.normal, f.normal)?, d: q(p.offset, f.offset)? }
        }
    })
}

/// The answer before rounding: `a` moved by `push`'s translation touches `b`
/// (cores, or `a`'s core and the plane) in `region`.
struct Solved {
    push: Push,
    /// Two least pushes go different ways, or the direction is a fallback.
    tie: bool,
    /// The touching set on `b`'s core (or the plane), as a hull.
    region: Vec<V3>,
    /// The other least pushes, one per direction (a tie), each with its
    /// touching set: answers as right as the first.
    others: Vec<(Push, Vec<V3>)>,
    ra: Q,
    rb: Q,
}

impl Solved {
    fn answer(&self) -> DistanceAnswer {
        self.answer_along(&self.push, &self.region)
    }

    /// The answer `push` and its touching set `region` give.
    fn answer_along(&self, push: &Push, region: &[V3]) -> DistanceAnswer {
        let r = &self.ra + &self.rb;
        let dir = push.direction();
        let root = Root::new(push.norm2.clone());
        let x = middle(region);
        let x_a = sub(&x, &push.translation());
        DistanceAnswer {
            // amount/√norm2 + r is the cores' push plus the radii: minus the
            // signed distance. `0 − x` keeps a zero positive.
            distance: 0.0 - push.round_plus(&r),
            point_a: root.round_over_v(&x_a, &-self.ra.clone(), &dir),
            point_b: root.round_over_v(&x, &self.rb, &dir),
            normal: round_unit(&dir),
            degenerate: self.tie || region.len() > 1,
        }
    }

    /// The witness sets when they are more than one point: `a`'s and `b`'s,
    /// each the touching set moved onto its solid's boundary.
    fn regions(&self) -> Option<Witnesses> {
        self.regions_along(&self.push, &self.region)
    }

    fn regions_along(&self, push: &Push, region: &[V3]) -> Option<Witnesses> {
        if region.len() <= 1 {
            return None;
        }
        let dir = push.direction();
        let root = Root::new(push.norm2.clone());
        let t = push.translation();
        let on_b = region.iter().map(|x| root.round_over_v(x, &self.rb, &dir)).collect();
        let on_a = region.iter().map(|x| root.round_over_v(&sub(x, &t), &-self.ra.clone(), &dir)).collect();
        Some((on_a, on_b))
    }

    /// The other least pushes' answers and witness sets.
    fn alternatives(&self) -> Vec<(DistanceAnswer, Option<Witnesses>)> {
        self.others.iter().map(|(p, r)| (self.answer_along(p, r), self.regions_along(p, r))).collect()
    }
}

fn solve(a: Solid<'_>, b: Solid<'_>) -> Result<Solved, RefereeError> {
    let (ha, hb) = (held(a, &A, true)?, held(b, &B, false)?);
    let Held::Grown { core: ca, r: ra, hull: hull_a } = ha else {
        // The table has a plane only as `b`.
        return Err(RefereeError::ZeroNormal { field: A.normal });
    };
    match hb {
        Held::HalfSpace { n, d } => Ok(against_plane(&ca, ra, &n, &d)),
        Held::Grown { core: cb, r: rb, hull: hull_b } => {
            let faces = |core: Convex, hull: Option<&[P3]>, field| match hull {
                Some(points) => convex_hull(points, field),
                None => Ok(core),
            };
            let v = nearest(&ca.vertices, &cb.vertices);
            if is_zero(&v) {
                let (ca, cb) = (faces(ca, hull_a, A.points)?, faces(cb, hull_b, B.points)?);
                Ok(meeting(&ca, &cb, ra, rb))
            } else {
                Ok(apart(&ca, &cb, v, ra, rb))
            }
        }
    }
}

/// A grown polytope against the half-space `n·x ≤ d`.
fn against_plane(a: &Convex, ra: Q, n: &V3, d: &Q) -> Solved {
    let heights: Vec<Q> = a.vertices.iter().map(|v| dot(n, v)).collect();
    let low = heights.iter().min().expect("a polytope has a vertex").clone();
    let norm2 = dot(n, n);
    let push = Push { l: n.clone(), norm2, plus: true, amount: d - &low };
    let t = push.translation();
    let lowest: Vec<V3> =
        a.vertices.iter().zip(&heights).filter(|(_, h)| **h == low).map(|(v, _)| add(v, &t)).collect();
    let region = super::convex::hull(&lowest, super::convex::kept(n));
    Solved { push, tie: false, region, others: Vec::new(), ra, rb: Q::ZERO }
}

/// Two grown polytopes whose cores are apart, `v = p_a − p_b` nearest.
fn apart(a: &Convex, b: &Convex, v: V3, ra: Q, rb: Q) -> Solved {
    // a moved by −v touches b. As a push along +v: amount −v·v.
    let norm2 = dot(&v, &v);
    let push = Push { l: v, amount: -norm2.clone(), norm2, plus: true };
    let region = touching_region(a, b, &push);
    Solved { push, tie: false, region, others: Vec::new(), ra, rb }
}

/// Two grown polytopes whose cores meet.
fn meeting(a: &Convex, b: &Convex, ra: Q, rb: Q) -> Solved {
    match least_push(a, b) {
        Some(least) => {
            let region = touching_region(a, b, &least.push);
            let others = least
                .others
                .into_iter()
                .map(|p| {
                    let r = touching_region(a, b, &p);
                    (p, r)
                })
                .collect();
            Solved { push: least.push, tie: least.tie, region, others, ra, rb }
        }
        None => {
            // No separating axis: points, or points and segments on one line.
            let line = a.directions.iter().chain(&b.directions).find(|d| !is_zero(d));
            let l = match line {
                None => [Q::ZERO, Q::ZERO, Q::ONE],
                Some(u) => {
                    let z = [u[1].clone(), -u[0].clone(), Q::ZERO];
                    if is_zero(&z) { [Q::ZERO, u[2].clone(), -u[1].clone()] } else { z }
                }
            };
            let norm2 = dot(&l, &l);
            let push = Push { l, norm2, plus: true, amount: Q::ZERO };
            let region = touching_region(a, b, &push);
            Solved { push, tie: true, region, others: Vec::new(), ra, rb }
        }
    }
}

/// The point `p_a − p_b` of `A − B` nearest the origin, by exact GJK (see the
/// module docs). Zero when the polytopes meet.
///
/// **The warm start.** With the floating-point stages on, a GJK in `f64` on
/// the rounded points runs first, and the exact one starts from its last
/// simplex (pairs of the same points) instead of one pair: any simplex of
/// points of `A − B` is a valid start, and the exact loop still proves its
/// answer (`v·w = v·v`), so the answer is the same; it only takes fewer
/// exact steps when the `f64` one found the closest features.
fn nearest(a: &[V3], b: &[V3]) -> V3 {
    let w = |(i, j): (usize, usize)| sub(&a[i], &b[j]);
    let mut simplex: Vec<(usize, usize)> = if super::stage::staged() { float_simplex(a, b) } else { vec![(0, 0)] };
    let mut v = if simplex.len() == 1 {
        w(simplex[0])
    } else {
        let points: Vec<V3> = simplex.iter().map(|&k| w(k)).collect();
        let (kept, start) = nearest_on_simplex(&points);
        simplex = kept.iter().map(|&k| simplex[k]).collect();
        start
    };
    loop {
        if is_zero(&v) {
            return v;
        }
        let ia = argmin(a, &v);
        let neg = scale(&v, &Q::NEG_ONE);
        let ib = argmin(b, &neg);
        let wk = w((ia, ib));
        let vv = dot(&v, &v);
        if dot(&v, &wk) >= vv || simplex.contains(&(ia, ib)) {
            return v;
        }
        simplex.push((ia, ib));
        let points: Vec<V3> = simplex.iter().map(|&k| w(k)).collect();
        let (kept, next) = nearest_on_simplex(&points);
        simplex = kept.iter().map(|&k| simplex[k]).collect();
        v = next;
    }
}

/// Most steps of the floating-point GJK of the warm start.
const FLOAT_GJK_STEPS: usize = 64;

/// The last simplex of a GJK in `f64` on the rounded points (one to four
/// distinct pairs of indices): where it stops, or after
/// [`FLOAT_GJK_STEPS`]. `[(0, 0)]` where a rounded point is not finite.
fn float_simplex(a: &[V3], b: &[V3]) -> Vec<(usize, usize)> {
    let (fa, fb): (Vec<P3>, Vec<P3>) = (a.iter().map(round_v3).collect(), b.iter().map(round_v3).collect());
    if !fa.iter().chain(&fb).flatten().all(|x| x.is_finite()) {
        return vec![(0, 0)];
    }
    let w = |(i, j): (usize, usize)| -> P3 { std::array::from_fn(|k| fa[i][k] - fb[j][k]) };
    let fdot = |x: &P3, y: &P3| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let least = |pts: &[P3], d: &P3| {
        (0..pts.len()).fold((0, f64::INFINITY), |(bi, bh), i| {
            let h = fdot(&pts[i], d);
            if h < bh { (i, h) } else { (bi, bh) }
        })
    };
    let mut simplex = vec![(0, 0)];
    let mut v = w((0, 0));
    for _ in 0..FLOAT_GJK_STEPS {
        let vv = fdot(&v, &v);
        if !(vv > 0.0 && vv.is_finite()) {
            break;
        }
        let (ia, _) = least(&fa, &v);
        let (ib, _) = least(&fb, &v.map(|x| -x));
        if fdot(&v, &w((ia, ib))) >= vv || simplex.contains(&(ia, ib)) {
            break;
        }
        simplex.push((ia, ib));
        let points: Vec<P3> = simplex.iter().map(|&k| w(k)).collect();
        match float_nearest_on_simplex(&points) {
            Some((kept, next)) => {
                simplex = kept.iter().map(|&k| simplex[k]).collect();
                v = next;
            }
            None => break,
        }
    }
    simplex.truncate(4);
    simplex
}

/// [`nearest_on_simplex`] in `f64`; `None` when no subset gives a finite
/// projection with non-negative coordinates.
fn float_nearest_on_simplex(points: &[P3]) -> Option<(Vec<usize>, P3)> {
    let fdot = |x: &P3, y: &P3| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let n = points.len();
    let mut best: Option<(Vec<usize>, P3, f64)> = None;
    for mask in 1u32..(1 << n) {
        let idx: Vec<usize> = (0..n).filter(|i| mask >> i & 1 == 1).collect();
        let w: Vec<&P3> = idx.iter().map(|&i| &points[i]).collect();
        let k = w.len() - 1;
        let lambda: Vec<f64> = if k == 0 {
            vec![1.0]
        } else {
            let e: Vec<P3> = w[1..].iter().map(|x| std::array::from_fn(|c| x[c] - w[0][c])).collect();
            let g: Vec<Vec<f64>> = (0..k).map(|i| (0..k).map(|j| fdot(&e[i], &e[j])).collect()).collect();
            let rhs: Vec<f64> = (0..k).map(|i| -fdot(&e[i], w[0])).collect();
            let det = float_determinant(&g);
            if !(det.abs() > 0.0 && det.is_finite()) {
                continue;
            }
            let mu: Vec<f64> = (0..k)
                .map(|c| {
                    let m: Vec<Vec<f64>> =
                        (0..k).map(|i| (0..k).map(|j| if j == c { rhs[i] } else { g[i][j] }).collect()).collect();
                    float_determinant(&m) / det
                })
                .collect();
            std::iter::once(1.0 - mu.iter().sum::<f64>()).chain(mu).collect()
        };
        if lambda.iter().any(|l| !l.is_finite() || *l < 0.0) {
            continue;
        }
        let p: P3 = std::array::from_fn(|c| idx.iter().zip(&lambda).map(|(&i, l)| points[i][c] * l).sum());
        let norm = fdot(&p, &p);
        if !norm.is_finite() {
            continue;
        }
        // A warm start needs no tie rule: the first least.
        if best.as_ref().is_none_or(|(_, _, bn)| norm < *bn) {
            best = Some((idx, p, norm));
        }
    }
    best.map(|(idx, p, _)| (idx, p))
}

fn float_determinant(m: &[Vec<f64>]) -> f64 {
    match m.len() {
        1 => m[0][0],
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        _ => {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        }
    }
}

/// Below this many points the support is found in rationals alone.
const FILTERED_SUPPORT: usize = 16;

/// The index of the point with the least `d·x` (the first of the least).
///
/// **The filter.** For many points, `d·x` is first computed in `f64` on the
/// rounded `d̃` and `x̃` (`x̃ = x` for every input point), with the bound
/// `e = 8u·Σ|d̃ⱼ x̃ⱼ| + 8·2^−1022`: the rounding of the three products and two
/// sums (`3u` of the sum of magnitudes, to first order), `d̃`'s and `x̃`'s own
/// rounding (`u` each, relative), their second-order terms, and what underflow
/// can lose (`2^−1075` per operation). Only points whose interval reaches the
/// least upper end can be least; they are compared exactly. A non-finite
/// value (overflow) sends the whole set to the exact comparison.
fn argmin(points: &[V3], d: &V3) -> usize {
    if points.len() < FILTERED_SUPPORT {
        return argmin_exact(points, d, 0..points.len());
    }
    const U: f64 = f64::EPSILON / 2.0;
    let dd = round_v3(d);
    let mut approx = Vec::with_capacity(points.len());
    let mut upper = f64::INFINITY;
    for p in points {
        let x = round_v3(p);
        let a = dd[0] * x[0] + dd[1] * x[1] + dd[2] * x[2];
        let m = (dd[0] * x[0]).abs() + (dd[1] * x[1]).abs() + (dd[2] * x[2]).abs();
        let e = 8.0 * U * m + 8.0 * f64::MIN_POSITIVE;
        if !(a.is_finite() && e.is_finite()) {
            return argmin_exact(points, d, 0..points.len());
        }
        upper = upper.min(a + e);
        approx.push((a, e));
    }
    // `upper` and each `a − e` are rounded: an ulp of each, relative to the
    // magnitudes that formed them, keeps them on the safe side.
    let upper = upper + upper.abs() * f64::EPSILON + f64::MIN_POSITIVE;
    let candidates =
        approx.iter().enumerate().filter(|(_, (a, e))| a - e - f64::EPSILON * (a.abs() + e) <= upper).map(|(i, _)| i);
    argmin_exact(points, d, candidates)
}

fn round_v3(v: &V3) -> P3 {
    v.each_ref().map(super::exact::round)
}

/// [`argmin`] among the given indices, exactly.
fn argmin_exact(points: &[V3], d: &V3, mut among: impl Iterator<Item = usize>) -> usize {
    let first = among.next().expect("a candidate");
    let mut best = first;
    let mut low = dot_relaxed(d, &points[first]);
    for i in among {
        let p = &points[i];
        let h = dot_relaxed(d, p);
        if h < low {
            low = h;
            best = i;
        }
    }
    best
}

/// The point of the hull of `points` (one to four) nearest the origin, and
/// the fewest of the points whose hull holds it: over the subsets, the
/// projection of the origin onto the subset's affine hull when its
/// barycentric coordinates are all ≥ 0 (affinely dependent subsets skipped:
/// a smaller one holds their nearest point), the least in norm, the smaller
/// subset on a tie.
fn nearest_on_simplex(points: &[V3]) -> (Vec<usize>, V3) {
    let n = points.len();
    let mut best: Option<(Vec<usize>, V3, Q)> = None;
    for mask in 1u32..(1 << n) {
        let idx: Vec<usize> = (0..n).filter(|i| mask >> i & 1 == 1).collect();
        let Some(lambda) = barycentric_of_projection(&idx.iter().map(|&i| &points[i]).collect::<Vec<_>>()) else {
            continue;
        };
        if lambda.iter().any(|l| *l < Q::ZERO) {
            continue;
        }
        let p =
            idx.iter().zip(&lambda).fold([Q::ZERO, Q::ZERO, Q::ZERO], |acc, (&i, l)| add(&acc, &scale(&points[i], l)));
        let norm = dot(&p, &p);
        let better = match &best {
            None => true,
            Some((bi, _, bn)) => norm < *bn || (norm == *bn && idx.len() < bi.len()),
        };
        if better {
            best = Some((idx, p, norm));
        }
    }
    let (idx, p, _) = best.expect("a single point is its own projection");
    (idx, p)
}

/// The barycentric coordinates of the origin's projection onto the affine
/// hull of `w` (one to four points), or `None` when they are affinely
/// dependent. With `e_i = w_i − w_0`, the projection `w_0 + Σ μ_i e_i` solves
/// `G μ = −E^T w_0`, `G = E^T E`, by Cramer's rule.
fn barycentric_of_projection(w: &[&V3]) -> Option<Vec<Q>> {
    let k = w.len() - 1;
    if k == 0 {
        return Some(vec![Q::ONE]);
    }
    let e: Vec<V3> = w[1..].iter().map(|x| sub(x, w[0])).collect();
    let g: Vec<Vec<Q>> = (0..k).map(|i| (0..k).map(|j| dot(&e[i], &e[j])).collect()).collect();
    let rhs: Vec<Q> = (0..k).map(|i| -dot(&e[i], w[0])).collect();
    let det = determinant(&g);
    if det.is_zero() {
        return None;
    }
    let mut mu = Vec::with_capacity(k);
    for c in 0..k {
        let m: Vec<Vec<Q>> =
            (0..k).map(|i| (0..k).map(|j| if j == c { rhs[i].clone() } else { g[i][j].clone() }).collect()).collect();
        mu.push(determinant(&m) / &det);
    }
    let first = mu.iter().fold(Q::ONE, |s, m| s - m);
    Some(std::iter::once(first).chain(mu).collect())
}

/// The determinant of a 1×1 to 3×3 matrix.
fn determinant(m: &[Vec<Q>]) -> Q {
    // Formed unreduced, reduced once.
    let e = |i: usize, j: usize| m[i][j].as_relaxed();
    match m.len() {
        1 => e(0, 0).clone().canonicalize(),
        2 => (e(0, 0) * e(1, 1) - e(0, 1) * e(1, 0)).canonicalize(),
        _ => (e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1)) - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
            + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0)))
        .canonicalize(),
    }
}

/// The signed distance of solids `a` and `b`, correctly rounded, with its
/// witnesses and normal (see the module docs).
///
/// # Errors
/// A field that is not finite, a negative radius or half-extent, a zero
/// quaternion, a convex shape without points or a plane's zero normal.
pub fn distance(a: Solid<'_>, b: Solid<'_>) -> Result<DistanceAnswer, RefereeError> {
    Ok(remembered_solve(a, b)?.answer())
}

/// The bits of a solid's numbers, with its kind: a memory's key.
fn solid_bits(s: Solid<'_>, out: &mut Vec<u64>) {
    let mut p = |x: &P3| out.extend(x.map(f64::to_bits));
    match s {
        Solid::Sphere(x) => {
            p(&x.center);
            out.extend([1, x.radius.to_bits()]);
        }
        Solid::Capsule(c) => {
            p(&c.start);
            p(&c.end);
            out.extend([2, c.radius.to_bits()]);
        }
        Solid::Box(b) => {
            p(&b.center);
            p(&b.half_extents);
            out.extend(b.rotation.map(f64::to_bits));
            out.push(3);
        }
        Solid::Triangle(t) => {
            t.vertices.iter().for_each(&mut p);
            out.push(4);
        }
        Solid::Convex(c) => {
            c.points.iter().for_each(&mut p);
            out.extend([5, c.points.len() as u64]);
        }
        Solid::Plane(x) => {
            p(&x.normal);
            out.extend([6, x.offset.to_bits()]);
        }
    }
}

thread_local! {
    /// The last pair solved on this thread: a case's answer and its witness
    /// sets (asked for by the judge's sizes) are one computation.
    static LAST: Memo<Vec<u64>, Result<std::rc::Rc<Solved>, RefereeError>> = const { std::cell::RefCell::new(None) };
}

fn remembered_solve(a: Solid<'_>, b: Solid<'_>) -> Result<std::rc::Rc<Solved>, RefereeError> {
    let mut key = Vec::new();
    solid_bits(a, &mut key);
    key.push(u64::MAX);
    solid_bits(b, &mut key);
    remembered(&LAST, key, || solve(a, b).map(std::rc::Rc::new))
}

/// `a`'s and `b`'s witness sets, each as its hull's vertices.
pub type Witnesses = (Vec<P3>, Vec<P3>);

/// The witness sets of `a` and `b` (each as its hull's vertices, correctly
/// rounded) when the witnesses are not unique; `None` when they are.
///
/// # Errors
/// As [`distance`].
pub fn distance_witnesses(a: Solid<'_>, b: Solid<'_>) -> Result<Option<Witnesses>, RefereeError> {
    Ok(remembered_solve(a, b)?.regions())
}

/// Where two least pushes go different ways (`degenerate` for a tie of
/// directions), the answers along the others, each with its witness sets
/// (as [`distance_witnesses`]): every one is as right as [`distance`]'s,
/// which is the first in the referee's order. Empty otherwise.
///
/// # Errors
/// As [`distance`].
pub fn distance_alternatives(
    a: Solid<'_>,
    b: Solid<'_>,
) -> Result<Vec<(DistanceAnswer, Option<Witnesses>)>, RefereeError> {
    Ok(remembered_solve(a, b)?.alternatives())
}

#[cfg(test)]
#[path = "distance_tests.rs"]
mod tests;
