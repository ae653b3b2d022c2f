//! Convex polytopes against each other, exactly: contact of two boxes, of a box
//! and a triangle, and of a capsule with a box or a triangle.
//!
//! Every shape here is a convex polytope held exactly — its vertices, the
//! directions of its edges and its face normals, all rational (a box's are, by
//! its quaternion's rational rotation, `super::boxes`) — and a capsule is its
//! axis (a two-vertex polytope) grown by its radius. The definitions are the
//! format's (`docs/FORMAT.md`, "Boxes and capsules", box–box to
//! capsule–triangle).
//!
//! **The penetration depth by separating axes.** For convex polytopes `A` and
//! `B` that meet, the shortest translation separating them is the least
//! support of the Minkowski difference `A − B` over unit directions, and that
//! least is reached at a facet normal of the difference. Its facets come from
//! a face of one with a vertex of the other (the face normals) or from an edge
//! of each (the cross products of edge directions): the candidate axes hold
//! them all. Along axis `L`, `A` is pushed clear by `max_B L·x − min_A L·x`
//! (along `+L`) or `max_A L·x − min_B L·x` (along `−L`); each push over `‖L‖`
//! is at least the depth, and the least of them is the depth. Pushes are
//! compared exactly as `p₁/√n₁` against `p₂/√n₂` (by the signs, then
//! `p₁²n₂` against `p₂²n₁`); the depth is `p/√n`, rounded once. When no push
//! is negative the polytopes meet: the candidates hold every facet normal, and
//! for a flat difference (coplanar flat boxes, a triangle and a box lying in
//! its plane) the directions within its plane that could separate it are
//! spanned, for every generating edge direction `g`, by candidates
//! perpendicular to `g` (each box axis's two partners, each edge crossed with
//! the box's axes).
//!
//! **The region.** After the shortest separating translation `a` touches `b`,
//! and the touching set `(a + depth·normal) ∩ b` is the contact region: the
//! intersection, in the plane both touch, of `a`'s support feature in
//! `−normal` and `b`'s in `+normal` (each a face, an edge or a vertex). The
//! translation is `(p/n)·L`, rational, so the region's vertices are rational:
//! the two features' vertices inside the other and their edges' crossings,
//! taken in the plane dropped onto two coordinates and hulled exactly.
//!
//! **A capsule** meets `b` when its axis is within `r` of it. The axis's
//! distance to a box or a triangle is found exactly among a few closest pairs
//! (its ends against `b`, its segment against `b`'s edges; a pass through a
//! face is distance 0): when it is positive, the contact is the closest pair's;
//! when it is 0, the axis itself penetrates by `s` (the separating axes above,
//! the axis a two-vertex polytope) and the capsule by `r + s`.

use std::cmp::Ordering;

use super::boxes::{BOX_A, BOX_B, ExactBox, check_box, exact_box};
use super::capsule::{check_capsule_fields, closest_pairs};
use super::closest::closest_on_triangle;
use super::error::RefereeError;
use super::exact::{
    Q, Root, V3, add, check_v3, cross, dot, dot_relaxed, is_zero, lerp, radius, round_unit, round_v, scale, sub, v3,
};
use super::push_filter::{AxisOf, Polytope};
use super::stage::{Memo, apart, remembered};
use crate::geom::{Capsule, Contact, ContactAnswer, OrientedBox, P3, Triangle};

/// A convex polytope held exactly.
#[derive(Clone)]
pub(crate) struct Convex {
    pub(super) vertices: Vec<V3>,
    /// Edges as pairs of vertex indices (a closest pair's candidates).
    pub(super) edges: Vec<(usize, usize)>,
    /// The directions of the edges, once per direction (the cross products'
    /// factors).
    pub(super) directions: Vec<V3>,
    /// Face normals, any length and either sign (a zero one is no axis).
    pub(super) normals: Vec<V3>,
}

impl Convex {
    /// A box's eight corners `c + Σ ±hᵢ·Rᵢ` (corner `s` takes `+hᵢ` where bit
    /// `i` of `s` is set), its twelve edges, its axes as directions and normals.
    pub(super) fn of_box(b: &ExactBox) -> Self {
        let vertices = (0..8usize)
            .map(|s| {
                let u: V3 = std::array::from_fn(|i| if s >> i & 1 == 1 { b.h[i].clone() } else { -b.h[i].clone() });
                b.to_world(&u)
            })
            .collect();
        let edges =
            (0..8usize).flat_map(|s| (0..3).filter(move |i| s >> i & 1 == 0).map(move |i| (s, s | 1 << i))).collect();
        Self { vertices, edges, directions: b.axes.to_vec(), normals: b.axes.to_vec() }
    }

    /// A triangle: its edges `v1 − v0`, `v2 − v1`, `v0 − v2` and its face
    /// normal `(v1 − v0) × (v2 − v0)`.
    pub(super) fn of_triangle(v: &[V3; 3]) -> Self {
        let directions = vec![sub(&v[1], &v[0]), sub(&v[2], &v[1]), sub(&v[0], &v[2])];
        let normal = cross(&sub(&v[1], &v[0]), &sub(&v[2], &v[0]));
        Self { vertices: v.to_vec(), edges: vec![(0, 1), (1, 2), (2, 0)], directions, normals: vec![normal] }
    }

    /// A segment: two vertices, one edge, no face.
    pub(super) fn of_segment(p0: &V3, p1: &V3) -> Self {
        Self {
            vertices: vec![p0.clone(), p1.clone()],
            edges: vec![(0, 1)],
            directions: vec![sub(p1, p0)],
            normals: vec![],
        }
    }

    /// As the separating-axes filter reads it.
    fn polytope(&self) -> Polytope<'_> {
        Polytope { vertices: &self.vertices, normals: &self.normals, directions: &self.directions }
    }

    /// The least and greatest `l·x` over the vertices.
    fn project(&self, l: &V3) -> (Q, Q) {
        // Compared unreduced; the two ends alone are reduced.
        let mut it = self.vertices.iter().map(|v| dot_relaxed(l, v));
        let first = it.next().expect("a polytope has a vertex");
        let (lo, hi) = it.fold((first.clone(), first), |(lo, hi), x| {
            let lo = if x < lo { x.clone() } else { lo };
            let hi = if x > hi { x } else { hi };
            (lo, hi)
        });
        (lo.canonicalize(), hi.canonicalize())
    }
}

/// The candidate axes of `a` against `b`, in the format's order: `a`'s normals,
/// `b`'s normals, then `a`'s directions crossed with `b`'s, row by row; zero
/// vectors left out.
fn axes(a: &Convex, b: &Convex) -> Vec<V3> {
    super::push_filter::axis_order(&a.polytope(), &b.polytope())
        .map(|id| axis(a, b, id))
        .filter(|l| !is_zero(l))
        .collect()
}

/// One candidate axis, exactly.
fn axis(a: &Convex, b: &Convex, id: AxisOf) -> V3 {
    match id {
        AxisOf::NormalA(i) => a.normals[i].clone(),
        AxisOf::NormalB(j) => b.normals[j].clone(),
        AxisOf::Cross(i, j) => cross(&a.directions[i], &b.directions[j]),
    }
}

/// One way to push `a` clear of `b`: along `sign·l`, by `amount/√norm2`.
#[derive(Clone)]
pub(super) struct Push {
    pub(super) l: V3,
    pub(super) norm2: Q,
    /// `true`: along `+l`.
    pub(super) plus: bool,
    /// The push times `‖l‖`: `max_b l·x − min_a l·x` or `max_a l·x − min_b l·x`.
    pub(super) amount: Q,
}

impl Push {
    /// `sign·l`.
    pub(super) fn direction(&self) -> V3 {
        if self.plus { self.l.clone() } else { scale(&self.l, &Q::NEG_ONE) }
    }

    /// `amount/√norm2` against `other`'s, exactly.
    fn cmp(&self, other: &Push) -> Ordering {
        let (sa, sb) = (self.amount >= Q::ZERO, other.amount >= Q::ZERO);
        if sa != sb {
            return if sa { Ordering::Greater } else { Ordering::Less };
        }
        // Unreduced: only compared.
        let (a, b) = (self.amount.as_relaxed(), other.amount.as_relaxed());
        let lhs = a * a * other.norm2.as_relaxed();
        let rhs = b * b * self.norm2.as_relaxed();
        if sa { lhs.cmp(&rhs) } else { rhs.cmp(&lhs) }
    }

    /// Whether the two pushes go the same way (parallel axes, same sense).
    fn same_direction(&self, other: &Push) -> bool {
        let (u, v) = (self.direction(), other.direction());
        is_zero(&cross(&u, &v)) && dot(&u, &v) > Q::ZERO
    }

    /// `amount/√norm2 + base`, correctly rounded.
    pub(super) fn round_plus(&self, base: &Q) -> f64 {
        Root::new(self.norm2.clone()).round_over(base, &self.amount)
    }

    /// The translation `(amount/norm2)·(sign·l)` that makes `a` touch `b`.
    pub(super) fn translation(&self) -> V3 {
        scale(&self.direction(), &(&self.amount / &self.norm2))
    }
}

/// The least push of `a` clear of `b` over the candidate axes, first in the
/// format's order (`+L` before `−L`), and whether another push as short goes
/// another way (`degenerate`). `None` when there is no axis at all. The least
/// is negative exactly when some axis separates them (then it is minus the
/// widest gap, a lower bound of their distance).
#[derive(Clone)]
pub(super) struct Least {
    pub(super) push: Push,
    pub(super) tie: bool,
    /// The other least pushes, one per direction other than `push`'s, in the
    /// format's order (empty unless `tie`).
    pub(super) others: Vec<Push>,
}

///
/// A floating-point filter (`super::push_filter`) first sets aside the pushes
/// that are certainly longer than another; the exact search runs over the
/// rest in the same order, which gives the same answer.
pub(super) fn least_push(a: &Convex, b: &Convex) -> Option<Least> {
    let filtered =
        if super::stage::staged() { super::push_filter::may_be_least(&a.polytope(), &b.polytope()) } else { None };
    match filtered {
        Some(kept) => {
            let signs = kept.len() as u64 * 2;
            let exact = kept.iter().map(|(_, s)| u64::from(s[0]) + u64::from(s[1])).sum::<u64>();
            super::stage::count(super::stage::Stage::SeparatingAxes, true, signs - exact);
            super::stage::count(super::stage::Stage::SeparatingAxes, false, exact);
            let axes = kept.into_iter().filter(|(_, signs)| signs[0] || signs[1]).filter_map(|(id, signs)| {
                let l = axis(a, b, id);
                (!is_zero(&l)).then_some((l, signs))
            });
            least_signed(a, b, axes)
        }
        None => {
            let all = axes(a, b);
            super::stage::count(super::stage::Stage::SeparatingAxes, false, 2 * all.len() as u64);
            least_on(a, b, all.into_iter())
        }
    }
}

/// [`least_push`] over the given axes (none of them zero).
fn least_on(a: &Convex, b: &Convex, axes: impl Iterator<Item = V3>) -> Option<Least> {
    least_signed(a, b, axes.map(|l| (l, [true, true])))
}

/// [`least_on`], each axis with the senses (`[+L, −L]`) to try.
fn least_signed(a: &Convex, b: &Convex, axes: impl Iterator<Item = (V3, [bool; 2])>) -> Option<Least> {
    let mut best: Option<Least> = None;
    for (l, signs) in axes {
        let (lo_a, hi_a) = a.project(&l);
        let (lo_b, hi_b) = b.project(&l);
        let norm2 = dot(&l, &l);
        let both = [(true, signs[0]), (false, signs[1])];
        for (plus, amount) in both.into_iter().filter(|(_, keep)| *keep).map(|(plus, _)| {
            let amount = if plus { &hi_b - &lo_a } else { &hi_a - &lo_b };
            (plus, amount)
        }) {
            let push = Push { l: l.clone(), norm2: norm2.clone(), plus, amount };
            best = Some(match best {
                None => Least { push, tie: false, others: Vec::new() },
                Some(cur) => match push.cmp(&cur.push) {
                    Ordering::Less => Least { push, tie: false, others: Vec::new() },
                    Ordering::Equal => {
                        let Least { push: first, mut others, .. } = cur;
                        if !push.same_direction(&first) && !others.iter().any(|o| push.same_direction(o)) {
                            others.push(push);
                        }
                        Least { tie: !others.is_empty(), push: first, others }
                    }
                    Ordering::Greater => cur,
                },
            });
        }
    }
    best
}

/// The plane's two kept coordinates: those other than the normal's largest
/// in magnitude (dropping it is one to one on the plane).
pub(super) fn kept(n: &V3) -> (usize, usize) {
    let abs = |x: &Q| if *x < Q::ZERO { -x.clone() } else { x.clone() };
    let k = (0..3).fold(0, |k, i| if abs(&n[i]) > abs(&n[k]) { i } else { k });
    ((k + 1) % 3, (k + 2) % 3)
}

/// `(b − a) × (c − a)` in the kept coordinates.
fn orient(a: &V3, b: &V3, c: &V3, (i, j): (usize, usize)) -> Q {
    (&b[i] - &a[i]) * (&c[j] - &a[j]) - (&b[j] - &a[j]) * (&c[i] - &a[i])
}

/// The convex hull of coplanar points, exactly (Andrew's monotone chain in the
/// kept coordinates): one point, a segment's two ends, or a polygon's
/// vertices in counter-clockwise order without collinear ones.
pub(super) fn hull(points: &[V3], ij: (usize, usize)) -> Vec<V3> {
    let (i, j) = ij;
    let mut p: Vec<V3> = Vec::with_capacity(points.len());
    for x in points {
        if !p.iter().any(|y| y[i] == x[i] && y[j] == x[j]) {
            p.push(x.clone());
        }
    }
    p.sort_by(|a, b| a[i].cmp(&b[i]).then_with(|| a[j].cmp(&b[j])));
    if p.len() <= 2 {
        return p;
    }
    let chain = |pts: &mut dyn Iterator<Item = &V3>| {
        let mut h: Vec<V3> = Vec::new();
        for x in pts {
            while h.len() >= 2 && orient(&h[h.len() - 2], &h[h.len() - 1], x, ij) <= Q::ZERO {
                h.pop();
            }
            h.push(x.clone());
        }
        h.pop();
        h
    };
    let mut lower = chain(&mut p.iter());
    let upper = chain(&mut p.iter().rev());
    lower.extend(upper);
    lower
}

/// Whether `x` lies in the closed convex set of `hull`'s vertices (a point, a
/// segment or a counter-clockwise polygon), all in one plane.
fn holds(hull: &[V3], x: &V3, ij: (usize, usize)) -> bool {
    let (i, j) = ij;
    match hull.len() {
        0 => false,
        1 => hull[0][i] == x[i] && hull[0][j] == x[j],
        2 => {
            let (a, b) = (&hull[0], &hull[1]);
            let along = |p: &V3, q: &V3, r: &V3| (&q[i] - &p[i]) * (&r[i] - &p[i]) + (&q[j] - &p[j]) * (&r[j] - &p[j]);
            orient(a, b, x, ij).is_zero() && along(a, b, x) >= Q::ZERO && along(b, a, x) >= Q::ZERO
        }
        n => (0..n).all(|k| orient(&hull[k], &hull[(k + 1) % n], x, ij) >= Q::ZERO),
    }
}

/// The edges of a hull: none for a point, the segment itself, or the
/// polygon's sides.
fn hull_edges(hull: &[V3]) -> Vec<(&V3, &V3)> {
    match hull.len() {
        0 | 1 => vec![],
        2 => vec![(&hull[0], &hull[1])],
        n => (0..n).map(|k| (&hull[k], &hull[(k + 1) % n])).collect(),
    }
}

/// The point where segments `pq` and `rs` (coplanar) cross, when they are not
/// parallel and do cross (ends included). Parallel overlapping segments are
/// left to the ends' containment tests.
fn crossing(p: &V3, q: &V3, r: &V3, s: &V3, ij: (usize, usize)) -> Option<V3> {
    let (i, j) = ij;
    let (d1, d2) = ([&q[i] - &p[i], &q[j] - &p[j]], [&s[i] - &r[i], &s[j] - &r[j]]);
    let den = &d1[0] * &d2[1] - &d1[1] * &d2[0];
    if den.is_zero() {
        return None;
    }
    let w = [&r[i] - &p[i], &r[j] - &p[j]];
    let t = (&w[0] * &d2[1] - &w[1] * &d2[0]) / &den;
    let u = (&w[0] * &d1[1] - &w[1] * &d1[0]) / &den;
    let unit = |x: &Q| *x >= Q::ZERO && *x <= Q::ONE;
    (unit(&t) && unit(&u)).then(|| lerp(p, q, &t))
}

/// The touching set of `a` moved by `push`'s translation and `b`: the
/// intersection of `a`'s support feature in `−n` and `b`'s in `+n` (`n` the
/// push's direction), as a hull (one point, a segment, a polygon).
pub(super) fn touching_region(a: &Convex, b: &Convex, push: &Push) -> Vec<V3> {
    let n = push.direction();
    let t = push.translation();
    let moved: Vec<V3> = a.vertices.iter().map(|v| add(v, &t)).collect();
    let feature = |pts: &[V3], lowest: bool| -> Vec<V3> {
        let heights: Vec<Q> = pts.iter().map(|v| dot(&n, v)).collect();
        let pick = heights
            .iter()
            .fold(heights[0].clone(), |m, h| if (lowest && *h < m) || (!lowest && *h > m) { h.clone() } else { m });
        pts.iter().zip(&heights).filter(|(_, h)| **h == pick).map(|(v, _)| v.clone()).collect()
    };
    let ij = kept(&n);
    let fa = hull(&feature(&moved, true), ij);
    let fb = hull(&feature(&b.vertices, false), ij);
    let mut pts: Vec<V3> = fa.iter().filter(|x| holds(&fb, x, ij)).cloned().collect();
    pts.extend(fb.iter().filter(|x| holds(&fa, x, ij)).cloned());
    for (p, q) in hull_edges(&fa) {
        for (r, s) in hull_edges(&fb) {
            pts.extend(crossing(p, q, r, s, ij));
        }
    }
    let region = hull(&pts, ij);
    debug_assert!(!region.is_empty(), "a touching translation leaves a touching set");
    if region.is_empty() { fb } else { region }
}

/// The mean of a region's vertices: a point of it (the region is convex).
pub(super) fn middle(region: &[V3]) -> V3 {
    let k = Q::from(region.len() as u64);
    let sum = region.iter().skip(1).fold(region[0].clone(), |s, v| add(&s, v));
    scale(&sum, &(Q::ONE / k))
}

/// Two polytopes in contact by their least push (`None`: apart, or no axis).
struct Resting {
    least: Option<Least>,
}

impl Resting {
    fn of(a: &Convex, b: &Convex) -> Self {
        Self { least: least_push(a, b) }
    }

    fn touches(&self) -> bool {
        self.least.as_ref().is_some_and(|l| l.push.amount >= Q::ZERO)
    }

    /// The contact answer of touching polytopes, the radius `r` added to the
    /// depth (a capsule's axis: its own penetration plus `r`).
    fn answer(&self, a: &Convex, b: &Convex, r: &Q) -> Option<ContactAnswer> {
        let least = self.least.as_ref()?;
        let region = touching_region(a, b, &least.push);
        Some(ContactAnswer {
            contact: Some(Contact {
                point: round_v(&middle(&region)),
                normal: round_unit(&least.push.direction()),
                depth: least.push.round_plus(r),
            }),
            degenerate: least.tie,
        })
    }

    fn region(&self, a: &Convex, b: &Convex) -> Option<Vec<P3>> {
        let least = self.least.as_ref()?;
        Some(touching_region(a, b, &least.push).iter().map(round_v).collect())
    }
}

/// A contact answer of separated shapes.
const APART: ContactAnswer = ContactAnswer { contact: None, degenerate: false };

/// Two boxes as polytopes, and their least push: on the one axis the
/// floating-point stage certifies to be strictly the least (`boxes_fast`'s
/// `least_axis`, the same fifteen axes in the same order), else over all.
/// A certified axis has no rival: only its own two ways can tie.
#[derive(Clone)]
struct BoxPair {
    a: Convex,
    b: Convex,
    least: Option<Least>,
}

/// The bits of a box's numbers: a memory's key.
fn box_bits(b: &OrientedBox) -> [u64; 10] {
    let mut k = [0; 10];
    for (slot, x) in k.iter_mut().zip(b.center.iter().chain(&b.half_extents).chain(&b.rotation)) {
        *slot = x.to_bits();
    }
    k
}

/// The bits of a capsule's numbers: a memory's key.
fn capsule_bits(c: &Capsule) -> [u64; 7] {
    let mut k = [0; 7];
    for (slot, x) in k.iter_mut().zip(c.start.iter().chain(&c.end).chain(std::iter::once(&c.radius))) {
        *slot = x.to_bits();
    }
    k
}

thread_local! {
    static BOX_BOX: Memo<([u64; 10], [u64; 10]), Result<BoxPair, RefereeError>> = const { std::cell::RefCell::new(None) };
    static CAPSULE_BOX: Memo<([u64; 7], [u64; 10]), Result<AxisSolid, RefereeError>> =
        const { std::cell::RefCell::new(None) };
}

/// [`box_box_computed`], remembered for the last pair on this thread (a
/// case's answer, margin and region share it: `stage::remembered`).
fn box_box(a: &OrientedBox, b: &OrientedBox) -> Result<BoxPair, RefereeError> {
    remembered(&BOX_BOX, (box_bits(a), box_bits(b)), || box_box_computed(a, b))
}

fn box_box_computed(a: &OrientedBox, b: &OrientedBox) -> Result<BoxPair, RefereeError> {
    check_box(a, BOX_A)?;
    check_box(b, BOX_B)?;
    let certified = super::stage::fast_stage(super::stage::Stage::BoxOverlap, || {
        use super::boxes_fast::{FastBox, least_axis};
        least_axis(&FastBox::of(a), &FastBox::of(b))
    });
    let (ea, eb) = (exact_box(a, BOX_A)?, exact_box(b, BOX_B)?);
    let (ca, cb) = (Convex::of_box(&ea), Convex::of_box(&eb));
    let least = match certified {
        Some(k) => {
            let l = if k < 3 {
                ea.axes[k].clone()
            } else if k < 6 {
                eb.axes[k - 3].clone()
            } else {
                cross(&ea.axes[(k - 6) / 3], &eb.axes[(k - 6) % 3])
            };
            least_on(&ca, &cb, std::iter::once(l))
        }
        None => least_push(&ca, &cb),
    };
    Ok(BoxPair { a: ca, b: cb, least })
}

/// Whether the floating-point stage proves boxes `a` and `b` apart (some
/// separating axis, bounded).
fn boxes_apart(a: &OrientedBox, b: &OrientedBox) -> bool {
    use super::boxes_fast::{FastBox, overlap};
    overlap(&FastBox::of(a), &FastBox::of(b)) == Some(false)
}

/// Contact between oriented boxes `a` and `b`.
///
/// **Definition** (`docs/FORMAT.md`, box–box): the least push of `a` clear of
/// `b` over the separating axes — each box's axes, then the nine `aᵢ × bⱼ`
/// (the exact zero ones of parallel edges are no axis) — is the exact
/// penetration depth; the normal is its direction, the point the middle of the
/// touching set `(a + depth·normal) ∩ b` ([`contact_region_box_box`] gives
/// it whole). Source: Gottschalk, Lin and Manocha's separating axes (Ericson
/// §4.4.1) as a penetration depth, without their epsilon.
///
/// **Degenerate input.** The least push reached along two directions
/// (concentric boxes, a box centred on the other's face plane, a corner that
/// has two nearest faces…) has no unique normal: the first in the format's
/// order, `degenerate: true`. Flat boxes are valid.
pub fn contact_box_box(a: &OrientedBox, b: &OrientedBox) -> Result<ContactAnswer, RefereeError> {
    check_box(a, BOX_A)?;
    check_box(b, BOX_B)?;
    if apart(|| boxes_apart(a, b)) {
        return Ok(APART);
    }
    let pair = box_box(a, b)?;
    let rest = Resting { least: pair.least };
    if !rest.touches() {
        return Ok(APART);
    }
    Ok(rest.answer(&pair.a, &pair.b, &Q::ZERO).unwrap_or(APART))
}

/// The signed margin behind [`contact_box_box`]'s decision: the least push
/// over the axes, correctly rounded — the exact penetration depth when they
/// touch; when apart, minus the widest gap along an axis, a **lower bound**
/// of the distance (as [`super::overlap_margin_box_box`]'s). The sign bit is
/// the decision.
pub fn contact_margin_box_box(a: &OrientedBox, b: &OrientedBox) -> Result<f64, RefereeError> {
    Ok(box_box(a, b)?.least.map_or(0.0, |l| l.push.round_plus(&Q::ZERO)))
}

/// The contact region of [`contact_box_box`] on `b`'s surface, each vertex
/// correctly rounded: one point, a segment's two ends, or a convex polygon's
/// corners in order (up to eight); `None` when apart.
pub fn contact_region_box_box(a: &OrientedBox, b: &OrientedBox) -> Result<Option<Vec<P3>>, RefereeError> {
    check_box(a, BOX_A)?;
    check_box(b, BOX_B)?;
    if apart(|| boxes_apart(a, b)) {
        return Ok(None);
    }
    let pair = box_box(a, b)?;
    let rest = Resting { least: pair.least };
    Ok(if rest.touches() { rest.region(&pair.a, &pair.b) } else { None })
}

/// The refusals of a triangle `b`: a non-finite vertex.
fn check_triangle(t: &Triangle) -> Result<(), RefereeError> {
    t.vertices.iter().try_for_each(|v| check_v3(v, "b.vertices"))
}

fn exact_triangle(t: &Triangle) -> Result<[V3; 3], RefereeError> {
    Ok([v3(&t.vertices[0], "b.vertices")?, v3(&t.vertices[1], "b.vertices")?, v3(&t.vertices[2], "b.vertices")?])
}

fn box_triangle(a: &OrientedBox, b: &Triangle) -> Result<(Convex, Convex), RefereeError> {
    check_box(a, BOX_A)?;
    check_triangle(b)?;
    Ok((Convex::of_box(&exact_box(a, BOX_A)?), Convex::of_triangle(&exact_triangle(b)?)))
}

/// Contact between an oriented box `a` and a triangle `b` (two-sided).
///
/// **Definition** (`docs/FORMAT.md`, box–triangle): as [`contact_box_box`],
/// the axes being the box's three, the triangle's normal
/// `(v1 − v0) × (v2 − v0)`, and the box's axes crossed with the edges
/// `v1 − v0`, `v2 − v1`, `v0 − v2` (zero ones left out).
///
/// **Degenerate input.** As box–box; a zero-area triangle is the segment or
/// point it collapsed to (no normal axis), answered the same way.
pub fn contact_box_triangle(a: &OrientedBox, b: &Triangle) -> Result<ContactAnswer, RefereeError> {
    check_box(a, BOX_A)?;
    check_triangle(b)?;
    if apart(|| super::boxes_fast::box_triangle_apart(a, b)) {
        return Ok(APART);
    }
    let (ca, cb) = box_triangle(a, b)?;
    let rest = Resting::of(&ca, &cb);
    if !rest.touches() {
        return Ok(APART);
    }
    Ok(rest.answer(&ca, &cb, &Q::ZERO).unwrap_or(APART))
}

/// The signed margin behind [`contact_box_triangle`]'s decision, as
/// [`contact_margin_box_box`]'s (a lower bound of minus the distance when
/// apart).
pub fn contact_margin_box_triangle(a: &OrientedBox, b: &Triangle) -> Result<f64, RefereeError> {
    let (ca, cb) = box_triangle(a, b)?;
    Ok(least_push(&ca, &cb).map_or(0.0, |l| l.push.round_plus(&Q::ZERO)))
}

/// The contact region of [`contact_box_triangle`] on the triangle, as
/// [`contact_region_box_box`]'s.
pub fn contact_region_box_triangle(a: &OrientedBox, b: &Triangle) -> Result<Option<Vec<P3>>, RefereeError> {
    check_box(a, BOX_A)?;
    check_triangle(b)?;
    if apart(|| super::boxes_fast::box_triangle_apart(a, b)) {
        return Ok(None);
    }
    let (ca, cb) = box_triangle(a, b)?;
    let rest = Resting::of(&ca, &cb);
    Ok(if rest.touches() { rest.region(&ca, &cb) } else { None })
}

/// The solid a capsule meets: a box or a triangle.
enum Solid {
    Box(Box<ExactBox>),
    Triangle(Box<[V3; 3]>),
}

impl Solid {
    fn convex(&self) -> Convex {
        match self {
            Solid::Box(b) => Convex::of_box(b),
            Solid::Triangle(t) => Convex::of_triangle(t),
        }
    }

    /// The point of the solid nearest `x`.
    fn closest(&self, x: &V3) -> V3 {
        match self {
            Solid::Box(b) => {
                let u = b.to_local(x);
                b.to_world(&b.clamp(&u))
            }
            Solid::Triangle(t) => closest_on_triangle(x, t),
        }
    }

    /// A point where the segment `p0p1` passes through the solid's inside or
    /// its face (for a box: the first point of the segment in it, by the
    /// slabs; for a triangle: where it crosses the plane strictly between its
    /// ends, when that point is in the triangle). Other meetings — an end in
    /// the solid, the segment touching an edge — are found as closest pairs at
    /// distance 0.
    fn pierce(&self, p0: &V3, p1: &V3) -> Option<V3> {
        match self {
            Solid::Box(b) => b.entry(&b.to_local(p0), &b.to_local(p1)).map(|s| lerp(p0, p1, &s)),
            Solid::Triangle(t) => {
                let n = cross(&sub(&t[1], &t[0]), &sub(&t[2], &t[0]));
                let (s0, s1) = (dot(&n, &sub(p0, &t[0])), dot(&n, &sub(p1, &t[0])));
                let opposite = (s0 < Q::ZERO && s1 > Q::ZERO) || (s0 > Q::ZERO && s1 < Q::ZERO);
                if !opposite {
                    return None;
                }
                let x = lerp(p0, p1, &(&s0 / (&s0 - &s1)));
                (closest_on_triangle(&x, t) == x).then_some(x)
            }
        }
    }
}

/// A capsule's axis against a solid: the closest pairs found, or that they
/// meet.
#[derive(Clone)]
struct AxisSolid {
    axis: Convex,
    solid: Convex,
    r: Q,
    /// `Some` when the axis is apart from the solid: the squared distance, a
    /// closest pair's difference `p_a − p_b`, and the closest points on the
    /// solid (the region's ends, or its one point).
    apart: Option<(Q, V3, Vec<V3>)>,
    /// A point the axis shares with the solid, when they meet.
    common: Option<V3>,
}

fn axis_solid(a: &Capsule, solid: Solid) -> Result<AxisSolid, RefereeError> {
    let (p0, p1) = (v3(&a.start, "a.start")?, v3(&a.end, "a.end")?);
    let r = radius(a.radius, "a.radius")?;
    let axis = Convex::of_segment(&p0, &p1);
    let convex = solid.convex();
    if let Some(x) = solid.pierce(&p0, &p1) {
        return Ok(AxisSolid { axis, solid: convex, r, apart: None, common: Some(x) });
    }
    // Closest pairs (x on the axis, y on the solid): the ends against the
    // solid, the axis against each edge (both ends of a parallel run).
    let mut pairs: Vec<(V3, V3)> = [&p0, &p1].iter().map(|e| ((*e).clone(), solid.closest(e))).collect();
    for &(i, j) in &convex.edges {
        let (e0, e1) = (&convex.vertices[i], &convex.vertices[j]);
        let cp = closest_pairs(&p0, &p1, e0, e1);
        for (s, t) in [cp.lo, cp.hi] {
            pairs.push((lerp(&p0, &p1, &s), lerp(e0, e1, &t)));
        }
    }
    let dist2 = |(x, y): &(V3, V3)| {
        let d = sub(x, y);
        dot(&d, &d)
    };
    let least = pairs.iter().map(dist2).min().expect("two ends at least");
    if least.is_zero() {
        let common = pairs.iter().find(|p| dist2(p).is_zero()).map(|p| p.1.clone());
        return Ok(AxisSolid { axis, solid: convex, r, apart: None, common });
    }
    let closest: Vec<&(V3, V3)> = pairs.iter().filter(|p| dist2(p) == least).collect();
    let delta = sub(&closest[0].0, &closest[0].1);
    // The closest points on the solid lie on one segment parallel to the
    // axis: its ends are the least and greatest along the axis.
    let along = sub(&p1, &p0);
    let key = |y: &V3| dot(&along, y);
    let lo = closest.iter().map(|p| &p.1).min_by(|u, v| key(u).cmp(&key(v))).expect("a closest pair");
    let hi = closest.iter().map(|p| &p.1).max_by(|u, v| key(u).cmp(&key(v))).expect("a closest pair");
    let ends = if lo == hi { vec![lo.clone()] } else { vec![lo.clone(), hi.clone()] };
    Ok(AxisSolid { axis, solid: convex, r, apart: Some((least, delta, ends)), common: None })
}

impl AxisSolid {
    fn touches(&self) -> bool {
        self.apart.as_ref().is_none_or(|(d2, _, _)| *d2 <= &self.r * &self.r)
    }

    fn answer(&self) -> ContactAnswer {
        if !self.touches() {
            return APART;
        }
        if let Some((d2, delta, ends)) = &self.apart {
            return ContactAnswer {
                contact: Some(Contact {
                    point: round_v(&middle(ends)),
                    normal: round_unit(delta),
                    depth: Root::new(d2.clone()).round_affine(&self.r, &Q::NEG_ONE),
                }),
                degenerate: false,
            };
        }
        let rest = Resting::of(&self.axis, &self.solid);
        rest.answer(&self.axis, &self.solid, &self.r).unwrap_or_else(|| self.no_axis())
    }

    /// No candidate axis (the axis and the solid lie on one line, or are
    /// points): the fallback normal `+z`, depth `r`, a common point.
    fn no_axis(&self) -> ContactAnswer {
        let point = self.common.as_ref().map_or([0.0; 3], round_v);
        ContactAnswer {
            contact: Some(Contact { point, normal: [0.0, 0.0, 1.0], depth: super::exact::round(&self.r) }),
            degenerate: true,
        }
    }

    fn margin(&self) -> f64 {
        match &self.apart {
            Some((d2, _, _)) => Root::new(d2.clone()).round_affine(&self.r, &Q::NEG_ONE),
            None => least_push(&self.axis, &self.solid)
                .map_or_else(|| super::exact::round(&self.r), |l| l.push.round_plus(&self.r)),
        }
    }

    fn region(&self) -> Option<Vec<P3>> {
        if !self.touches() {
            return None;
        }
        match &self.apart {
            Some((_, _, ends)) => Some(ends.iter().map(round_v).collect()),
            None => match Resting::of(&self.axis, &self.solid).region(&self.axis, &self.solid) {
                Some(region) => Some(region),
                None => self.common.as_ref().map(|c| vec![round_v(c)]),
            },
        }
    }
}

/// [`capsule_box_computed`], remembered as [`box_box`] is.
fn capsule_box(a: &Capsule, b: &OrientedBox) -> Result<AxisSolid, RefereeError> {
    remembered(&CAPSULE_BOX, (capsule_bits(a), box_bits(b)), || capsule_box_computed(a, b))
}

fn capsule_box_computed(a: &Capsule, b: &OrientedBox) -> Result<AxisSolid, RefereeError> {
    check_capsule_fields(a)?;
    check_box(b, BOX_B)?;
    axis_solid(a, Solid::Box(Box::new(exact_box(b, BOX_B)?)))
}

fn capsule_triangle(a: &Capsule, b: &Triangle) -> Result<AxisSolid, RefereeError> {
    check_capsule_fields(a)?;
    check_triangle(b)?;
    axis_solid(a, Solid::Triangle(Box::new(exact_triangle(b)?)))
}

/// Contact between a capsule `a` and an oriented box `b`.
///
/// **Definition** (`docs/FORMAT.md`, capsule–box). With `d` the distance from
/// `a`'s axis to the solid box (exact: the axis's ends clamped into the box,
/// the axis against the box's twelve edges, a pass through the box by the
/// slabs): when `d > 0`, contact when `d ≤ r`, normal `(p_a − p_b)/d`, depth
/// `r − d`, point the middle of the closest points on the box. When `d = 0`
/// the axis penetrates the box by `s`, the least push as in
/// [`contact_box_box`] over the box's axes and the capsule's axis crossed
/// with them: depth `r + s`, normal that push's direction, point the middle of
/// `(axis + s·normal) ∩ b`. Source: Ericson §5.1.9 (closest points of
/// segments) and §4.4.1 (separating axes).
///
/// **Degenerate input.** As box–box when the axis meets the box: two
/// directions of least push (an axis through the box's centre, along a face…)
/// give the first in the format's order, `degenerate: true`. A zero-length
/// axis is a sphere.
pub fn contact_capsule_box(a: &Capsule, b: &OrientedBox) -> Result<ContactAnswer, RefereeError> {
    check_capsule_fields(a)?;
    check_box(b, BOX_B)?;
    if apart(|| super::boxes_fast::capsule_box_apart(a, b)) {
        return Ok(APART);
    }
    Ok(capsule_box(a, b)?.answer())
}

/// The signed depth behind [`contact_capsule_box`]'s decision, correctly
/// rounded: `r − d` when the axis is apart from the box (negative, minus the
/// gap, when the capsule is apart), `r + s` when it meets it.
pub fn contact_margin_capsule_box(a: &Capsule, b: &OrientedBox) -> Result<f64, RefereeError> {
    Ok(capsule_box(a, b)?.margin())
}

/// The contact region of [`contact_capsule_box`] on the box, each vertex
/// correctly rounded; `None` when apart.
pub fn contact_region_capsule_box(a: &Capsule, b: &OrientedBox) -> Result<Option<Vec<P3>>, RefereeError> {
    check_capsule_fields(a)?;
    check_box(b, BOX_B)?;
    if apart(|| super::boxes_fast::capsule_box_apart(a, b)) {
        return Ok(None);
    }
    Ok(capsule_box(a, b)?.region())
}

/// Contact between a capsule `a` and a triangle `b` (two-sided).
///
/// **Definition** (`docs/FORMAT.md`, capsule–triangle): as
/// [`contact_capsule_box`], the distance from the axis's ends to the triangle
/// (Ericson §5.1.5), from the axis to its three edges, and a pass through its
/// face; when the axis meets it, the least push over the triangle's normal and
/// the axis crossed with the edges.
///
/// **Degenerate input.** As capsule–box. An axis that meets a zero-area
/// triangle along its line, or a zero-length axis on one, has no axis to
/// push along: normal `(0, 0, 1)`, depth `r`, point a common point,
/// `degenerate: true`.
pub fn contact_capsule_triangle(a: &Capsule, b: &Triangle) -> Result<ContactAnswer, RefereeError> {
    check_capsule_fields(a)?;
    check_triangle(b)?;
    if apart(|| super::boxes_fast::capsule_triangle_apart(a, b)) {
        return Ok(APART);
    }
    Ok(capsule_triangle(a, b)?.answer())
}

/// The signed depth behind [`contact_capsule_triangle`]'s decision, as
/// [`contact_margin_capsule_box`]'s.
pub fn contact_margin_capsule_triangle(a: &Capsule, b: &Triangle) -> Result<f64, RefereeError> {
    Ok(capsule_triangle(a, b)?.margin())
}

/// The contact region of [`contact_capsule_triangle`] on the triangle.
pub fn contact_region_capsule_triangle(a: &Capsule, b: &Triangle) -> Result<Option<Vec<P3>>, RefereeError> {
    check_capsule_fields(a)?;
    check_triangle(b)?;
    if apart(|| super::boxes_fast::capsule_triangle_apart(a, b)) {
        return Ok(None);
    }
    Ok(capsule_triangle(a, b)?.region())
}

#[cfg(test)]
#[path = "convex_tests.rs"]
mod tests;
