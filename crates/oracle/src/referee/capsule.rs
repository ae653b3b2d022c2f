//! Capsules, exactly: contact of a sphere with a capsule, of two capsules, and
//! of a capsule with a plane.
//!
//! A capsule is the set of points within `r` of its axis, the segment from
//! `start` to `end` (`docs/FORMAT.md`, "Boxes and capsules"); equal ends make it
//! a sphere, and every function here takes that case. Every closest point of
//! the axes is found in rationals, so contact and apart are decided exactly;
//! the only square root is the distance between the closest points (or the
//! plane normal's length), and every output is `x + y·√q`, rounded once.
//!
//! Refused input: a non-finite number, a negative radius (the check spheres
//! use: a zero radius is valid, the capsule is then its axis), a zero plane
//! normal.

use super::closest::closest_on_segment;
use super::error::RefereeError;
use super::exact::{
    Q, Root, V3, add, check, check_radius, check_v3, dot, is_zero, lerp, q, radius, round_unit, round_v, scale, sub, v3,
};
use super::stage::apart;
use crate::geom::{Capsule, Contact, ContactAnswer, IntersectAnswer, P3, Plane, Segment, SegmentHit, Sphere};

/// The normal when the direction is undefined (a sphere's centre on a capsule's
/// axis, axes that meet): `+z`, as for concentric spheres
/// ([`super::CONCENTRIC_FALLBACK_NORMAL`]).
fn fallback_normal() -> V3 {
    [Q::ZERO, Q::ZERO, Q::ONE]
}

/// A capsule held exactly: its axis ends and radius.
struct ExactCapsule {
    p0: V3,
    p1: V3,
    r: Q,
}

/// [`exact_capsule`]'s refusals without the rationals, in its order.
fn check_capsule(c: &Capsule, fields: [&'static str; 3]) -> Result<(), RefereeError> {
    check_v3(&c.start, fields[0])?;
    check_v3(&c.end, fields[1])?;
    check_radius(c.radius, fields[2])
}

/// [`capsule_plane`]'s refusals without the rationals, in its order.
fn check_capsule_plane(a: &Capsule, b: &Plane) -> Result<(), RefereeError> {
    check_capsule(a, CAPSULE_A)?;
    check_v3(&b.normal, "b.normal")?;
    check(b.offset, "b.offset")?;
    if b.normal.iter().all(|&x| x == 0.0) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    Ok(())
}

/// A contact answer of separated shapes.
const APART: ContactAnswer = ContactAnswer { contact: None, degenerate: false };

fn exact_capsule(c: &Capsule, fields: [&'static str; 3]) -> Result<ExactCapsule, RefereeError> {
    Ok(ExactCapsule { p0: v3(&c.start, fields[0])?, p1: v3(&c.end, fields[1])?, r: radius(c.radius, fields[2])? })
}

const CAPSULE_A: [&str; 3] = ["a.start", "a.end", "a.radius"];

/// The refusals of a capsule `a` (its ends, its radius), in order.
pub(crate) fn check_capsule_fields(a: &Capsule) -> Result<(), RefereeError> {
    check_capsule(a, CAPSULE_A)
}
const CAPSULE_B: [&str; 3] = ["b.start", "b.end", "b.radius"];

/// A contact between two round shapes shrunk to their cores: `pa` on `a`'s
/// core (kept as `pa − pb`), `pb` on `b`'s, the summed radius `sum`, `b`'s
/// radius `rb`.
struct Cores {
    pb: V3,
    /// `pa − pb`.
    delta: V3,
    sum: Q,
    rb: Q,
    root: Root,
}

impl Cores {
    fn new(pa: V3, pb: V3, ra: &Q, rb: &Q) -> Self {
        let delta = sub(&pa, &pb);
        let root = Root::new(dot(&delta, &delta));
        Self { pb, delta, sum: ra + rb, rb: rb.clone(), root }
    }

    fn touches(&self) -> bool {
        *self.root.square() <= &self.sum * &self.sum
    }

    /// The normal's direction (exact, not unit) and whether it is the fallback.
    fn direction(&self) -> (V3, bool) {
        if is_zero(&self.delta) { (fallback_normal(), true) } else { (self.delta.clone(), false) }
    }

    /// `sum − ‖pa − pb‖`, correctly rounded.
    fn depth(&self) -> f64 {
        self.root.round_affine(&self.sum, &Q::NEG_ONE)
    }

    /// `pb' + rb·n̂` for a point `pb'` of `b`'s core, with `n̂` the (fallback)
    /// unit normal, correctly rounded.
    fn surface_point(&self, pb: &V3) -> P3 {
        let (dir, _) = self.direction();
        Root::new(dot(&dir, &dir)).round_over_v(pb, &self.rb, &dir)
    }

    /// The contact when touching: normal `(pa − pb)/‖pa − pb‖` (the fallback
    /// `+z` when `pa = pb`, flagged degenerate), point `pb + rb·normal`, depth
    /// `sum − ‖pa − pb‖`.
    fn answer(&self) -> ContactAnswer {
        if !self.touches() {
            return ContactAnswer { contact: None, degenerate: false };
        }
        let (dir, degenerate) = self.direction();
        ContactAnswer {
            contact: Some(Contact {
                point: self.surface_point(&self.pb),
                normal: round_unit(&dir),
                depth: self.depth(),
            }),
            degenerate,
        }
    }
}

fn sphere_capsule(a: &Sphere, b: &Capsule) -> Result<Cores, RefereeError> {
    let m = v3(&a.center, "a.center")?;
    let ra = radius(a.radius, "a.radius")?;
    let cb = exact_capsule(b, CAPSULE_B)?;
    let qb = closest_on_segment(&m, &cb.p0, &cb.p1);
    Ok(Cores::new(m, qb, &ra, &cb.r))
}

/// Contact between a sphere `a` (centre `M`, radius `r_a`) and a capsule `b`.
///
/// **Definition** (`docs/FORMAT.md`, sphere–capsule). With `q` the point of
/// `b`'s axis nearest `M` (exact: Ericson §5.1.2, the parameter clamped to
/// `[0, 1]`):
///
/// ```text
/// contact ⇔ ‖M − q‖² ≤ (r_a + r_b)²,   normal = (M − q)/‖M − q‖,
/// point   = q + r_b·normal,             depth  = r_a + r_b − ‖M − q‖
/// ```
///
/// which is the contact of two spheres, `b`'s centred at `q` — the exact
/// penetration depth, since the nearest point of the axis moves the least.
///
/// **Degenerate input.** A centre on the axis (`M = q`) has no direction:
/// normal `(0, 0, 1)` ([`super::CONCENTRIC_FALLBACK_NORMAL`]), point
/// `q + r_b·(0, 0, 1)`, depth `r_a + r_b`, `degenerate: true`. A capsule with
/// `start = end` is a sphere and is answered as one.
pub fn contact_sphere_capsule(a: &Sphere, b: &Capsule) -> Result<ContactAnswer, RefereeError> {
    check_v3(&a.center, "a.center")?;
    check_radius(a.radius, "a.radius")?;
    check_capsule(b, CAPSULE_B)?;
    if apart(|| super::boxes_fast::sphere_capsule_apart(a, b)) {
        return Ok(APART);
    }
    Ok(sphere_capsule(a, b)?.answer())
}

/// The signed depth `r_a + r_b − ‖M − q‖` behind [`contact_sphere_capsule`]'s
/// decision, correctly rounded: ≥ 0 exactly when in contact, minus the gap
/// when apart.
pub fn contact_margin_sphere_capsule(a: &Sphere, b: &Capsule) -> Result<f64, RefereeError> {
    Ok(sphere_capsule(a, b)?.depth())
}

/// The closest pairs of two segments `a(s) = a0 + s·da`, `b(t) = b0 + t·db`
/// (`s, t ∈ [0, 1]`), exactly: the pairs `(s, t)` at the least distance form
/// one pair, or — parallel segments side by side — a line of pairs from
/// `lo` to `hi` (`lo` with the smaller `s`), all at the same distance.
pub(crate) struct ClosestPairs {
    pub(crate) lo: (Q, Q),
    pub(crate) hi: (Q, Q),
}

fn clamp01(x: Q) -> Q {
    if x < Q::ZERO {
        Q::ZERO
    } else if x > Q::ONE {
        Q::ONE
    } else {
        x
    }
}

/// Ericson's `ClosestPtSegmentSegment` (§5.1.9) in rationals, with the
/// parallel case taken apart: the book picks `s = 0` there, which is a
/// closest pair only when `a`'s start faces `b`; here the whole set is found.
///
/// With `r = a0 − b0`, `A = da·da`, `E = db·db`, `B = da·db`, `C = da·r`,
/// `F = db·r`:
///
/// - `A = E = 0`: two points, `(0, 0)`;
/// - `A = 0`: `s = 0`, `t = clamp(F/E)`; `E = 0`: `t = 0`, `s = clamp(−C/A)`;
/// - `AE − B² ≠ 0` (not parallel): the distance is strictly convex in `(s, t)`
///   and the book's clamp-and-recompute finds its unique minimum;
/// - parallel: along `da`, `a` covers `[0, A]` and `b` covers `−C + t·B`; where
///   the two ranges meet, every `s` in the common range `[lo, hi]` pairs with
///   `t = (s·A + C)/B` at the lines' distance; where they do not, the nearest
///   ends are the one pair.
pub(crate) fn closest_pairs(a0: &V3, a1: &V3, b0: &V3, b1: &V3) -> ClosestPairs {
    let one = |s: Q, t: Q| ClosestPairs { lo: (s.clone(), t.clone()), hi: (s, t) };
    let da = sub(a1, a0);
    let db = sub(b1, b0);
    let r = sub(a0, b0);
    let aa = dot(&da, &da);
    let ee = dot(&db, &db);
    let ff = dot(&db, &r);
    if aa.is_zero() && ee.is_zero() {
        return one(Q::ZERO, Q::ZERO);
    }
    if aa.is_zero() {
        return one(Q::ZERO, clamp01(ff / ee));
    }
    let cc = dot(&da, &r);
    if ee.is_zero() {
        return one(clamp01(-cc / aa), Q::ZERO);
    }
    let bb = dot(&da, &db);
    let denom = &aa * &ee - &bb * &bb;
    if !denom.is_zero() {
        let mut s = clamp01((&bb * &ff - &cc * &ee) / denom);
        let mut t = (&bb * &s + &ff) / &ee;
        if t < Q::ZERO {
            t = Q::ZERO;
            s = clamp01(-cc / &aa);
        } else if t > Q::ONE {
            t = Q::ONE;
            s = clamp01((&bb - &cc) / &aa);
        }
        return one(s, t);
    }
    // Parallel (B ≠ 0, as B² = AE > 0). Axial coordinates along da, from a0.
    let (e0, e1) = (-cc.clone(), &bb - &cc);
    let (b_lo, b_hi) = if e0 <= e1 { (e0, e1) } else { (e1, e0) };
    let lo = if b_lo > Q::ZERO { b_lo.clone() } else { Q::ZERO };
    let hi = if b_hi < aa { b_hi.clone() } else { aa.clone() };
    if lo <= hi {
        let t_of = |x: &Q| (x + &cc) / &bb;
        return ClosestPairs { lo: (&lo / &aa, t_of(&lo)), hi: (&hi / &aa, t_of(&hi)) };
    }
    let positive = bb > Q::ZERO;
    if b_hi < Q::ZERO {
        // b lies behind a's start: a's start and b's forward-most end.
        one(Q::ZERO, if positive { Q::ONE } else { Q::ZERO })
    } else {
        // b lies beyond a's end: a's end and b's rearmost end.
        one(Q::ONE, if positive { Q::ZERO } else { Q::ONE })
    }
}

/// Two capsules: their exact cores, the closest pairs of their axes, and the
/// contact of the chosen pair (the smallest parameter on `a`).
struct CapsulePair {
    a: ExactCapsule,
    b: ExactCapsule,
    pairs: ClosestPairs,
    cores: Cores,
}

fn capsule_capsule(a: &Capsule, b: &Capsule) -> Result<CapsulePair, RefereeError> {
    let a = exact_capsule(a, CAPSULE_A)?;
    let b = exact_capsule(b, CAPSULE_B)?;
    let pairs = closest_pairs(&a.p0, &a.p1, &b.p0, &b.p1);
    let (s, t) = &pairs.lo;
    let cores = Cores::new(lerp(&a.p0, &a.p1, s), lerp(&b.p0, &b.p1, t), &a.r, &b.r);
    Ok(CapsulePair { a, b, pairs, cores })
}

/// Contact between capsules `a` and `b`.
///
/// **Definition** (`docs/FORMAT.md`, capsule–capsule). With `p_a`, `p_b` a
/// closest pair of points of the two axes (exact, see `closest_pairs`):
///
/// ```text
/// contact ⇔ ‖p_a − p_b‖² ≤ (r_a + r_b)²,   normal = (p_a − p_b)/‖p_a − p_b‖,
/// point   = p_b + r_b·normal,               depth  = r_a + r_b − ‖p_a − p_b‖
/// ```
///
/// Parallel axes side by side have a line of closest pairs, all with the same
/// `p_a − p_b` (the lines' perpendicular offset), so the normal and depth are
/// the same for each; the answer's point is that of the pair with the
/// **smallest parameter on `a`** (nearest `a.start`), and
/// [`contact_region_capsule_capsule`] gives the whole set. Source: Ericson
/// §5.1.9 and §4.5.1.
///
/// **Degenerate input.** Axes that meet (`p_a = p_b`: crossing, touching or
/// collinear and overlapping) have no unique normal: normal `(0, 0, 1)`, point
/// `p_b + r_b·(0, 0, 1)`, depth `r_a + r_b`, `degenerate: true`. A capsule with
/// `start = end` is a sphere: its axis is one point.
pub fn contact_capsule_capsule(a: &Capsule, b: &Capsule) -> Result<ContactAnswer, RefereeError> {
    check_capsule(a, CAPSULE_A)?;
    check_capsule(b, CAPSULE_B)?;
    if apart(|| super::boxes_fast::capsule_capsule_apart(a, b)) {
        return Ok(APART);
    }
    Ok(capsule_capsule(a, b)?.cores.answer())
}

/// The signed depth `r_a + r_b − ‖p_a − p_b‖` behind
/// [`contact_capsule_capsule`]'s decision, correctly rounded: ≥ 0 exactly when
/// in contact, minus the gap when apart. Symmetric in `a` and `b`.
pub fn contact_margin_capsule_capsule(a: &Capsule, b: &Capsule) -> Result<f64, RefereeError> {
    Ok(capsule_capsule(a, b)?.cores.depth())
}

/// The contact region of [`contact_capsule_capsule`] on `b`'s surface: the
/// points `p_b + r_b·normal` over every closest pair, each vertex correctly
/// rounded. One vertex (exactly the answer's point) when the closest pair is
/// unique; two — the ends of a segment, the answer's point first — for
/// parallel axes side by side (collinear overlapping axes included, with the
/// fallback normal); `None` when apart.
pub fn contact_region_capsule_capsule(a: &Capsule, b: &Capsule) -> Result<Option<Vec<P3>>, RefereeError> {
    check_capsule(a, CAPSULE_A)?;
    check_capsule(b, CAPSULE_B)?;
    if apart(|| super::boxes_fast::capsule_capsule_apart(a, b)) {
        return Ok(None);
    }
    let cp = capsule_capsule(a, b)?;
    if !cp.cores.touches() {
        return Ok(None);
    }
    let first = cp.cores.surface_point(&cp.cores.pb);
    if cp.pairs.lo == cp.pairs.hi {
        return Ok(Some(vec![first]));
    }
    let pb_hi = lerp(&cp.b.p0, &cp.b.p1, &cp.pairs.hi.1);
    debug_assert_eq!(
        sub(&lerp(&cp.a.p0, &cp.a.p1, &cp.pairs.hi.0), &pb_hi),
        cp.cores.delta,
        "parallel closest pairs share one offset"
    );
    Ok(Some(vec![first, cp.cores.surface_point(&pb_hi)]))
}

/// A capsule against a plane: its axis ends' heights and the lowest end.
struct CapsulePlane {
    c: ExactCapsule,
    n: V3,
    d: Q,
    /// `n·start`, `n·end`.
    heights: [Q; 2],
    /// `d − n·e` for the lowest end `e` (`start` on a tie).
    e: Q,
    root: Root,
}

fn capsule_plane(a: &Capsule, b: &Plane) -> Result<CapsulePlane, RefereeError> {
    let c = exact_capsule(a, CAPSULE_A)?;
    let n = v3(&b.normal, "b.normal")?;
    let d = q(b.offset, "b.offset")?;
    if is_zero(&n) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    let heights = [dot(&n, &c.p0), dot(&n, &c.p1)];
    let low = if heights[1] < heights[0] { &heights[1] } else { &heights[0] };
    let e = &d - low;
    let root = Root::new(dot(&n, &n));
    Ok(CapsulePlane { c, n, d, heights, e, root })
}

impl CapsulePlane {
    /// `r + (d − n·e)/‖n‖ ≥ 0`: true when `d − n·e ≥ 0`, else
    /// `(n·e − d)² ≤ r²‖n‖²`.
    fn touches(&self) -> bool {
        self.e >= Q::ZERO || &self.e * &self.e <= &self.c.r * &self.c.r * self.root.square()
    }

    fn depth(&self) -> f64 {
        self.root.round_over(&self.c.r, &self.e)
    }

    /// `x`'s projection onto the plane, `x + ((d − n·x)/‖n‖²)·n`, given
    /// `n·x`.
    fn project(&self, x: &V3, height: &Q) -> V3 {
        let k = (&self.d - height) / self.root.square();
        add(x, &scale(&self.n, &k))
    }

    /// The lowest end (`start` on a tie) and its height.
    fn lowest(&self) -> (&V3, &Q) {
        if self.heights[1] < self.heights[0] { (&self.c.p1, &self.heights[1]) } else { (&self.c.p0, &self.heights[0]) }
    }
}

/// Contact between a capsule `a` and a plane `b` (`n·x = d`, bounding the
/// solid `n·x ≤ d`).
///
/// **Definition** (`docs/FORMAT.md`, capsule–plane). With `e` the axis end
/// with the least `n·x` (`start` on a tie):
///
/// ```text
/// contact ⇔ (d − n·e)/‖n‖ + r ≥ 0   (decided as d − n·e ≥ 0, or (n·e − d)² ≤ r²‖n‖²)
/// normal  = n/‖n‖,   depth = r + (d − n·e)/‖n‖,
/// point   = e + ((d − n·e)/‖n‖²)·n    (e's projection onto the plane)
/// ```
///
/// The depth is the exact penetration depth (the shortest way out of a
/// half-space is along its normal). An axis parallel to the plane
/// (`n·start = n·end`) has a line of lowest points: the answer's point is
/// `start`'s projection, and [`contact_region_capsule_plane`] gives the whole
/// segment.
///
/// **Degenerate input.** None: the normal is always unique. A zero normal is
/// refused with [`RefereeError::ZeroNormal`].
pub fn contact_capsule_plane(a: &Capsule, b: &Plane) -> Result<ContactAnswer, RefereeError> {
    check_capsule_plane(a, b)?;
    if apart(|| super::boxes_fast::capsule_plane_apart(a, b)) {
        return Ok(APART);
    }
    let cp = capsule_plane(a, b)?;
    if !cp.touches() {
        return Ok(APART);
    }
    let (x, height) = cp.lowest();
    Ok(ContactAnswer {
        contact: Some(Contact { point: round_v(&cp.project(x, height)), normal: round_unit(&cp.n), depth: cp.depth() }),
        degenerate: false,
    })
}

/// The signed depth `r + (d − n·e)/‖n‖` behind [`contact_capsule_plane`]'s
/// decision, correctly rounded: ≥ 0 exactly when in contact, minus the gap
/// when apart.
pub fn contact_margin_capsule_plane(a: &Capsule, b: &Plane) -> Result<f64, RefereeError> {
    Ok(capsule_plane(a, b)?.depth())
}

/// The contact region of [`contact_capsule_plane`] on the plane, each vertex
/// correctly rounded: the lowest end's projection (exactly the answer's
/// point), or — an axis of non-zero length parallel to the plane — the
/// projections of `start` then `end`. `None` when apart.
pub fn contact_region_capsule_plane(a: &Capsule, b: &Plane) -> Result<Option<Vec<P3>>, RefereeError> {
    check_capsule_plane(a, b)?;
    if apart(|| super::boxes_fast::capsule_plane_apart(a, b)) {
        return Ok(None);
    }
    let cp = capsule_plane(a, b)?;
    if !cp.touches() {
        return Ok(None);
    }
    let start = round_v(&cp.project(&cp.c.p0, &cp.heights[0]));
    if cp.heights[0] == cp.heights[1] && cp.c.p0 != cp.c.p1 {
        let end = round_v(&cp.project(&cp.c.p1, &cp.heights[1]));
        return Ok(Some(vec![start, end]));
    }
    let (x, height) = cp.lowest();
    Ok(Some(vec![round_v(&cp.project(x, height))]))
}

#[cfg(test)]
#[path = "capsule_tests.rs"]
mod tests;

/// One piece of a segment's path past a capsule: over `t ∈ [lo, hi]` the
/// point of the axis nearest `s(t)` is `foot0 + t·foot1` (an end, or the
/// foot of the perpendicular), so `s(t) − foot(t) = g0 + t·g1`.
struct Piece {
    lo: Q,
    hi: Q,
    g0: V3,
    g1: V3,
}

impl Piece {
    /// `A`, `B`, `C` of `‖g0 + t·g1‖² − r² = A t² + 2B t + C`.
    fn quadratic(&self, r: &Q) -> (Q, Q, Q) {
        (dot(&self.g1, &self.g1), dot(&self.g0, &self.g1), dot(&self.g0, &self.g0) - r * r)
    }
}

/// The pieces of `s(t) = s0 + t·d`, `t ∈ [0, 1]`, against the axis
/// `p0 + x·u`, `x ∈ [0, 1]`, in the order of `t`: where the axial coordinate
/// `(s(t) − p0)·u` is below 0 the nearest point is `p0`, above `u·u` it is
/// `p1`, between them the foot of the perpendicular. The breakpoints are
/// rational.
fn pieces(s0: &V3, d: &V3, p0: &V3, p1: &V3) -> Vec<Piece> {
    let u = sub(p1, p0);
    let uu = dot(&u, &u);
    let w = sub(s0, p0);
    let end = |p: &V3, lo: Q, hi: Q| Piece { lo, hi, g0: sub(s0, p), g1: d.clone() };
    if uu.is_zero() {
        return vec![end(p0, Q::ZERO, Q::ONE)];
    }
    let (wu, du) = (dot(&w, &u), dot(d, &u));
    // The foot of the perpendicular: p0 + (axial(t)/uu)·u.
    let side =
        Piece { lo: Q::ZERO, hi: Q::ONE, g0: sub(&w, &scale(&u, &(&wu / &uu))), g1: sub(d, &scale(&u, &(&du / &uu))) };
    if du.is_zero() {
        return vec![if wu < Q::ZERO {
            end(p0, Q::ZERO, Q::ONE)
        } else if wu > uu {
            end(p1, Q::ZERO, Q::ONE)
        } else {
            side
        }];
    }
    // axial(t) = wu + t·du reaches 0 at ta and uu at tb.
    let ta = -&wu / &du;
    let tb = (&uu - &wu) / &du;
    let (first, t1, t2, last) = if du > Q::ZERO { (p0, ta, tb, p1) } else { (p1, tb, ta, p0) };
    let clip = |x: &Q| {
        if *x < Q::ZERO {
            Q::ZERO
        } else if *x > Q::ONE {
            Q::ONE
        } else {
            x.clone()
        }
    };
    let (c1, c2) = (clip(&t1), clip(&t2));
    let mut out = Vec::new();
    if c1 > Q::ZERO {
        out.push(end(first, Q::ZERO, c1.clone()));
    }
    if c2 > c1 {
        out.push(Piece { lo: c1.clone(), hi: c2.clone(), ..side });
    }
    if c2 < Q::ONE {
        out.push(end(last, c2, Q::ONE));
    }
    out
}

/// The first hit of segment `s` on the solid capsule `b`: the least
/// `t ∈ [0, 1]` at which `s(t)` is within `r` of the axis.
///
/// **Definition** (`docs/FORMAT.md`, segment–capsule). The squared distance
/// from `s(t)` to the axis is convex in `t` and, between rational
/// breakpoints (where the nearest axis point leaves an end), a quadratic.
/// A start within `r` is hit at `t = 0`. Otherwise the first piece whose
/// quadratic reaches `r²` in its range holds the hit, at its smaller root
/// `t = (−B − √(B² − AC))/A` (`A t² + 2B t + C = ‖s(t) − foot(t)‖² − r²`);
/// the point is `s(t)`, the normal the capsule's outward normal there,
/// `(s(t) − foot(t))/r`. Each output is `x + y·√(B² − AC)`, rounded once; a
/// grazing segment (`B² = AC`) touches at `t = −B/A`.
///
/// **Degenerate input.** A start inside on the axis has no unique normal:
/// `(0, 0, 1)`, flagged. A zero-length segment is flagged, as for a box: a
/// point in the capsule is hit at `t = 0` with its outward direction.
/// `barycentric` and `triangle` are `None`; `parallel` is always false.
pub fn intersect_segment_capsule(s: &Segment, b: &Capsule) -> Result<IntersectAnswer, RefereeError> {
    check_v3(&s.start, "a.start")?;
    check_v3(&s.end, "a.end")?;
    check_capsule(b, CAPSULE_B)?;
    let (s0, s1) = (v3(&s.start, "a.start")?, v3(&s.end, "a.end")?);
    let cb = exact_capsule(b, CAPSULE_B)?;
    let d = sub(&s1, &s0);
    let zero_length = is_zero(&d);
    let pieces = pieces(&s0, &d, &cb.p0, &cb.p1);
    let first = &pieces[0];
    let (_, _, c0) = first.quadratic(&cb.r);
    if c0 <= Q::ZERO {
        let (normal, on_axis) =
            if is_zero(&first.g0) { ([0.0, 0.0, 1.0], true) } else { (round_unit(&first.g0), false) };
        return Ok(IntersectAnswer {
            hit: Some(SegmentHit { t: 0.0, point: s.start, normal, barycentric: None, triangle: None }),
            parallel: false,
            degenerate: on_axis || zero_length,
        });
    }
    for piece in &pieces {
        let (a, bq, c) = piece.quadratic(&cb.r);
        if a.is_zero() {
            continue;
        }
        let vertex = -&bq / &a;
        let tv = if vertex < piece.lo {
            piece.lo.clone()
        } else if vertex > piece.hi {
            piece.hi.clone()
        } else {
            vertex
        };
        if &a * &tv * &tv + Q::from(2u8) * &bq * &tv + &c > Q::ZERO {
            continue;
        }
        let root = Root::new(&bq * &bq - &a * &c);
        let k = -&bq / &a;
        let m = Q::NEG_ONE / &a;
        let at = |x0: &V3, x1: &V3| -> P3 {
            std::array::from_fn(|i| root.round_affine(&(&x0[i] + &k * &x1[i]), &(&m * &x1[i])))
        };
        let normal_num = at(&scale(&piece.g0, &(Q::ONE / &cb.r)), &scale(&piece.g1, &(Q::ONE / &cb.r)));
        return Ok(IntersectAnswer {
            hit: Some(SegmentHit {
                t: root.round_affine(&k, &m),
                point: at(&s0, &d),
                normal: normal_num,
                barycentric: None,
                triangle: None,
            }),
            parallel: false,
            degenerate: zero_length,
        });
    }
    Ok(IntersectAnswer { hit: None, parallel: false, degenerate: zero_length })
}

/// The signed margin behind [`intersect_segment_capsule`]'s decision: `r`
/// less the distance between the segment and the axis (exact closest pairs),
/// correctly rounded; ≥ 0 exactly when the segment hits.
pub fn intersect_margin_segment_capsule(s: &Segment, b: &Capsule) -> Result<f64, RefereeError> {
    let (s0, s1) = (v3(&s.start, "a.start")?, v3(&s.end, "a.end")?);
    let cb = exact_capsule(b, CAPSULE_B)?;
    let pairs = closest_pairs(&s0, &s1, &cb.p0, &cb.p1);
    let (x, y) = &pairs.lo;
    let gap = sub(&lerp(&s0, &s1, x), &lerp(&cb.p0, &cb.p1, y));
    Ok(Root::new(dot(&gap, &gap)).round_affine(&cb.r, &Q::NEG_ONE))
}
