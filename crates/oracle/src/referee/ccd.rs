//! Continuous collision detection of a moving point against a moving
//! triangle (vertex–face) and of two moving segments (edge–edge), exactly.
//!
//! **Convention** (fixture format, `ccd`). Every position moves linearly,
//! `x(t) = (1 − t)·x_t0 + t·x_t1`, over `t ∈ [0, t_max]`, `t_max ∈ [0, 1]`.
//! The answer [`CcdAnswer::t`] is the *first* time in `[0, t_max]` at which the
//! point lies on the closed triangle (vertex–face), or the two closed segments
//! share a point (edge–edge), correctly rounded to `f64` (round to nearest,
//! ties to even) from the exact algebraic time; `None` when that never
//! happens. Touching at `t = 0` answers `0`; touching exactly at `t_max`
//! counts.
//!
//! **Degenerate** ([`CcdAnswer::degenerate`]) is `true` exactly when
//! - the motion is coplanar throughout: the coplanarity cubic `f(t)` (below)
//!   is the zero polynomial, so the problem is planar — whatever the answer;
//! - or there is an impact and at its time the triangle has zero area
//!   (vertex–face), or one segment has zero length or the two are parallel
//!   (edge–edge): the normal `n` below is the zero vector then.
//!
//! Otherwise it is `false`.
//!
//! **How it is exact.** With `a, b, c` the triangle's vertices and `p` the
//! point, `f(t) = det[b − a, c − a, p − a]` is a cubic in `t` with dyadic
//! coefficients; with `[a0, a1]`, `[b0, b1]` the segments,
//! `f(t) = det[a1 − a0, b0 − a0, b1 − a0]`. A contact needs `f = 0`. Whether
//! the point is on the triangle (the segments meet) at a time when they are
//! coplanar is a boolean formula in the signs of polynomials in `t`:
//! - vertex–face, `n = (b − a) × (c − a)`: if `n ≠ 0`, `n·((vᵢ₊₁ − vᵢ) × (p − vᵢ)) ≥ 0`
//!   for the three edges; if `n = 0` (the triangle is a segment or a point),
//!   `p` on one of its three closed edges;
//! - edge–edge, `n = (a1 − a0) × (b1 − b0)`, `w = b0 − a0`: if `n ≠ 0`,
//!   `0 ≤ (w × (b1 − b0))·n ≤ n·n` and `0 ≤ (w × (a1 − a0))·n ≤ n·n`; if `n = 0`
//!   (parallel, or a zero-length segment), one of the four ends on the other
//!   closed segment;
//! - a point `p` on the closed segment `[u, w]`: `p = u` if `u = w`, else
//!   `(w − u) × (p − u) = 0`, `(p − u)·(w − u) ≥ 0` and `(p − w)·(u − w) ≥ 0`.
//!
//! The times of contact form a closed set. When `f` is not the zero
//! polynomial they are among `f`'s real roots in `[0, t_max]` (at most three),
//! isolated exactly in increasing order (`ccd_poly`: square-free part, Sturm
//! sequence, bisection at dyadic points) and tested in that order, every sign
//! at an algebraic root decided exactly (zero by a gcd, else by refining the
//! root's interval). When `f ≡ 0` the first time is `0` or a root of one of
//! the formula's polynomials (between their roots every sign is constant),
//! and those candidates are sorted exactly and tested the same way. The first
//! time is then rounded by comparing it with the exact midpoints between
//! adjacent doubles (a root on one is a tie and goes to the even double).
//! Everything is integer arithmetic on dyadic numbers (`m·2^e`), so any
//! finite inputs — subnormal to `f64::MAX`, in one query — are exact.
//!
//! **Floating-point stage** (`ccd_fast`). First, in double-word numbers with a
//! rigorous error bound (the referee's `fast`): `f`'s Bernstein coefficients on
//! `[0, 1]`, subdivided a few times, certify that `f` has no root in
//! `[0, t_max]` (no contact, not planar); the swept boxes, compared exactly,
//! certify a miss when they are disjoint and `f` is certainly not the zero
//! polynomial. Only those two answers are given there — a proven
//! "no impact"; everything else goes to the exact stage. Both are counted as the
//! referee's other stages are ([`super::stage::Stage::Ccd`]).
//!
//! **Input.** Non-finite coordinates are refused naming the field (`p.t0`,
//! `tri.t1`, `a.t0`, `b.t1`, …), and so is a `t_max` that is not finite or
//! outside `[0, 1]` (field `t_max`; the referee's error type has no
//! out-of-range kind, so this is reported as [`RefereeError::NonFinite`]).

use std::cmp::Ordering;

use super::ccd_poly::{D, DPoly, IPoly, Root, integer, moving, padd, pmul, psub, roots};
use super::error::RefereeError;
use super::exact::check_v3;
use super::stage::{Stage, fast_stage};
use crate::geom::{CcdAnswer, MovingPoint, MovingSegment, MovingTriangle, P3};

fn check_t_max(t_max: f64) -> Result<(), RefereeError> {
    if !t_max.is_finite() {
        Err(RefereeError::NonFinite { field: "t_max" })
    } else if !(0.0..=1.0).contains(&t_max) {
        Err(RefereeError::TimeOutOfRange { field: "t_max" })
    } else {
        Ok(())
    }
}

/// The first time in `[0, t_max]` at which the moving point `p` lies on the
/// moving closed triangle `tri`, correctly rounded, and whether the question
/// is degenerate (see the [module docs](self)).
///
/// # Errors
/// A non-finite coordinate (`p.t0`, `p.t1`, `tri.t0`, `tri.t1`), or a
/// `t_max` that is not finite or outside `[0, 1]` (`t_max`).
pub fn ccd_point_triangle(p: &MovingPoint, tri: &MovingTriangle, t_max: f64) -> Result<CcdAnswer, RefereeError> {
    check_v3(&p.t0, "p.t0")?;
    check_v3(&p.t1, "p.t1")?;
    tri.t0.iter().try_for_each(|v| check_v3(v, "tri.t0"))?;
    tri.t1.iter().try_for_each(|v| check_v3(v, "tri.t1"))?;
    check_t_max(t_max)?;
    if let Some(answer) = fast_stage(Stage::Ccd, || super::ccd_fast::point_triangle(p, tri, t_max)) {
        return Ok(answer);
    }
    Ok(exact_point_triangle(p, tri, t_max))
}

/// The first time in `[0, t_max]` at which the moving closed segments `a` and
/// `b` share a point, correctly rounded, and whether the question is
/// degenerate (see the [module docs](self)).
///
/// # Errors
/// A non-finite coordinate (`a.t0`, `a.t1`, `b.t0`, `b.t1`), or a `t_max`
/// that is not finite or outside `[0, 1]` (`t_max`).
pub fn ccd_segment_segment(a: &MovingSegment, b: &MovingSegment, t_max: f64) -> Result<CcdAnswer, RefereeError> {
    a.t0.iter().try_for_each(|v| check_v3(v, "a.t0"))?;
    a.t1.iter().try_for_each(|v| check_v3(v, "a.t1"))?;
    b.t0.iter().try_for_each(|v| check_v3(v, "b.t0"))?;
    b.t1.iter().try_for_each(|v| check_v3(v, "b.t1"))?;
    check_t_max(t_max)?;
    if let Some(answer) = fast_stage(Stage::Ccd, || super::ccd_fast::segment_segment(a, b, t_max)) {
        return Ok(answer);
    }
    Ok(exact_segment_segment(a, b, t_max))
}

/// A moving point's coordinates, each a polynomial in `t`.
type PV = [DPoly; 3];

fn point(t0: &P3, t1: &P3) -> PV {
    [moving(t0[0], t1[0]), moving(t0[1], t1[1]), moving(t0[2], t1[2])]
}

fn vsub(a: &PV, b: &PV) -> PV {
    [psub(&a[0], &b[0]), psub(&a[1], &b[1]), psub(&a[2], &b[2])]
}

fn vdot(a: &PV, b: &PV) -> DPoly {
    padd(&padd(&pmul(&a[0], &b[0]), &pmul(&a[1], &b[1])), &pmul(&a[2], &b[2]))
}

fn vcross(a: &PV, b: &PV) -> PV {
    [
        psub(&pmul(&a[1], &b[2]), &pmul(&a[2], &b[1])),
        psub(&pmul(&a[2], &b[0]), &pmul(&a[0], &b[2])),
        psub(&pmul(&a[0], &b[1]), &pmul(&a[1], &b[0])),
    ]
}

/// What an atom's sign must be.
#[derive(Clone, Copy, Debug)]
enum Cond {
    Zero,
    NonZero,
    NonNegative,
}

/// A boolean formula in the signs of polynomials in `t` (atoms by index).
#[derive(Clone, Debug)]
enum Formula {
    Atom(usize, Cond),
    All(Vec<Formula>),
    Any(Vec<Formula>),
}

impl Formula {
    fn holds(&self, sign: &mut impl FnMut(usize) -> i8) -> bool {
        match self {
            Formula::Atom(i, c) => {
                let s = sign(*i);
                match c {
                    Cond::Zero => s == 0,
                    Cond::NonZero => s != 0,
                    Cond::NonNegative => s >= 0,
                }
            }
            Formula::All(fs) => fs.iter().all(|f| f.holds(sign)),
            Formula::Any(fs) => fs.iter().any(|f| f.holds(sign)),
        }
    }
}

/// The polynomials a formula is written in, as integer polynomials (each a
/// positive multiple of the exact one: the same signs).
#[derive(Default)]
struct Atoms(Vec<IPoly>);

impl Atoms {
    fn atom(&mut self, p: &DPoly, c: Cond) -> Formula {
        self.0.push(integer(p));
        Formula::Atom(self.0.len() - 1, c)
    }

    fn zero(&mut self, v: &PV) -> Formula {
        Formula::All(v.iter().map(|p| self.atom(p, Cond::Zero)).collect())
    }

    fn nonzero(&mut self, v: &PV) -> Formula {
        Formula::Any(v.iter().map(|p| self.atom(p, Cond::NonZero)).collect())
    }

    fn nonnegative(&mut self, p: &DPoly) -> Formula {
        self.atom(p, Cond::NonNegative)
    }

    /// `p` on the closed segment `[u, w]`.
    fn on_segment(&mut self, p: &PV, u: &PV, w: &PV) -> Formula {
        let d = vsub(w, u);
        let pu = vsub(p, u);
        let pw = vsub(p, w);
        let point = Formula::All(vec![self.zero(&d), self.zero(&pu)]);
        let segment = Formula::All(vec![
            self.nonzero(&d),
            self.zero(&vcross(&d, &pu)),
            self.nonnegative(&vdot(&pu, &d)),
            self.nonnegative(&vdot(&pw, &vsub(u, w))),
        ]);
        Formula::Any(vec![point, segment])
    }
}

/// A continuous collision question: the coplanarity polynomial `f` and the
/// contact formula (valid where `f = 0`): `face` (`n ≠ 0` and the point inside
/// the triangle, or the segments crossing), or `flat` (`n = 0`, also the
/// degenerate flag's test) and `edges` (the point on an edge, an end on the
/// other segment). `edges` is built when first needed: it is most of the
/// polynomials and rarely asked.
struct Problem {
    f: IPoly,
    atoms: Atoms,
    face: Formula,
    flat: Formula,
    edges: Lazy,
}

enum Lazy {
    Built(Formula),
    Later(Box<dyn FnOnce(&mut Atoms) -> Formula>),
}

impl Problem {
    fn edges(&mut self) -> &Formula {
        if let Lazy::Later(_) = self.edges {
            let Lazy::Later(build) = std::mem::replace(&mut self.edges, Lazy::Built(Formula::Any(Vec::new()))) else {
                unreachable!("just matched");
            };
            self.edges = Lazy::Built(build(&mut self.atoms));
        }
        match &self.edges {
            Lazy::Built(f) => f,
            Lazy::Later(_) => unreachable!("just built"),
        }
    }
}

fn point_triangle_problem(p: &MovingPoint, tri: &MovingTriangle) -> Problem {
    let x = point(&p.t0, &p.t1);
    let v: Vec<PV> = (0..3).map(|i| point(&tri.t0[i], &tri.t1[i])).collect();
    let n = vcross(&vsub(&v[1], &v[0]), &vsub(&v[2], &v[0]));
    let f = integer(&vdot(&n, &vsub(&x, &v[0])));
    let mut atoms = Atoms::default();
    let sides = (0..3)
        .map(|i| {
            let (u, w) = (&v[i], &v[(i + 1) % 3]);
            atoms.nonnegative(&vdot(&n, &vcross(&vsub(w, u), &vsub(&x, u))))
        })
        .collect::<Vec<_>>();
    let face = Formula::All([vec![atoms.nonzero(&n)], sides].concat());
    let flat = atoms.zero(&n);
    let edges = Lazy::Later(Box::new(move |atoms: &mut Atoms| {
        Formula::Any((0..3).map(|i| atoms.on_segment(&x, &v[i], &v[(i + 1) % 3])).collect())
    }));
    Problem { f, atoms, face, flat, edges }
}

fn segment_segment_problem(a: &MovingSegment, b: &MovingSegment) -> Problem {
    let (a0, a1) = (point(&a.t0[0], &a.t1[0]), point(&a.t0[1], &a.t1[1]));
    let (b0, b1) = (point(&b.t0[0], &b.t1[0]), point(&b.t0[1], &b.t1[1]));
    let (da, db, w) = (vsub(&a1, &a0), vsub(&b1, &b0), vsub(&b0, &a0));
    let f = integer(&vdot(&vcross(&da, &w), &vsub(&b1, &a0)));
    let n = vcross(&da, &db);
    let nn = vdot(&n, &n);
    let s = vdot(&vcross(&w, &db), &n);
    let u = vdot(&vcross(&w, &da), &n);
    let mut atoms = Atoms::default();
    let face = Formula::All(vec![
        atoms.nonzero(&n),
        atoms.nonnegative(&s),
        atoms.nonnegative(&psub(&nn, &s)),
        atoms.nonnegative(&u),
        atoms.nonnegative(&psub(&nn, &u)),
    ]);
    let flat = atoms.zero(&n);
    let edges = Lazy::Later(Box::new(move |atoms: &mut Atoms| {
        Formula::Any(vec![
            atoms.on_segment(&a0, &b0, &b1),
            atoms.on_segment(&a1, &b0, &b1),
            atoms.on_segment(&b0, &a0, &a1),
            atoms.on_segment(&b1, &a0, &a1),
        ])
    }));
    Problem { f, atoms, face, flat, edges }
}

fn exact_point_triangle(p: &MovingPoint, tri: &MovingTriangle, t_max: f64) -> CcdAnswer {
    solve(point_triangle_problem(p, tri), t_max)
}

fn exact_segment_segment(a: &MovingSegment, b: &MovingSegment, t_max: f64) -> CcdAnswer {
    solve(segment_segment_problem(a, b), t_max)
}

/// Whether `formula` holds at the root `r`, each atom's sign decided once.
fn holds_at(atoms: &Atoms, formula: &Formula, r: &mut Root, cache: &mut Vec<Option<i8>>) -> bool {
    cache.resize(atoms.0.len(), None);
    formula.holds(&mut |i| *cache[i].get_or_insert_with(|| r.sign_of(&atoms.0[i])))
}

/// Whether the contact formula holds at the root `r`.
fn contact_at(problem: &mut Problem, r: &mut Root, cache: &mut Vec<Option<i8>>) -> bool {
    if holds_at(&problem.atoms, &problem.face, r, cache) {
        return true;
    }
    if !holds_at(&problem.atoms, &problem.flat, r, cache) {
        return false;
    }
    problem.edges();
    let Lazy::Built(edges) = &problem.edges else { unreachable!("built") };
    holds_at(&problem.atoms, edges, r, cache)
}

/// The first contact in `[0, t_max]`, exactly.
fn solve(mut problem: Problem, t_max: f64) -> CcdAnswer {
    let (lo, hi) = (D::zero(), D::of(t_max));
    let planar = problem.f.is_empty();
    let mut candidates = if planar {
        // Planar throughout: the first contact is 0 or a root of an atom
        // (every atom, so the edges' too).
        problem.edges();
        let mut c = vec![Root::zero()];
        for p in problem.atoms.0.iter().filter(|p| !p.is_empty()) {
            c.extend(roots(p, &lo, &hi));
        }
        sort(&mut c);
        c
    } else {
        roots(&problem.f, &lo, &hi)
    };
    for r in &mut candidates {
        let mut cache = Vec::new();
        if contact_at(&mut problem, r, &mut cache) {
            let degenerate = planar || holds_at(&problem.atoms, &problem.flat, r, &mut cache);
            return CcdAnswer { t: Some(r.round()), degenerate };
        }
    }
    CcdAnswer { t: None, degenerate: planar }
}

/// Sorts roots in increasing order, comparing them exactly (insertion sort:
/// a comparison refines both roots).
fn sort(roots: &mut [Root]) {
    for i in 1..roots.len() {
        let mut j = i;
        while j > 0 {
            let (left, right) = roots.split_at_mut(j);
            if left[j - 1].cmp(&mut right[0]) != Ordering::Greater {
                break;
            }
            roots.swap(j - 1, j);
            j -= 1;
        }
    }
}

#[cfg(test)]
#[path = "ccd_tests.rs"]
mod tests;
