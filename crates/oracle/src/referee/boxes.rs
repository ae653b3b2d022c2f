//! Oriented boxes, exactly: contact of a sphere with a box and of a box with a
//! plane, a segment's first hit on a box, a box's bounds, and the overlap of a
//! box with a box or an axis-aligned box.
//!
//! A box is the solid `center + R·u`, `|uᵢ| ≤ hᵢ` (`docs/FORMAT.md`, "Boxes and
//! capsules"). `R` is the rotation of the unit quaternion `q/‖q‖`; with
//! `q = [w, x, y, z]` exact and `n² = w² + x² + y² + z²`,
//!
//! ```text
//!     ⎡ n² − 2(y² + z²)   2(xy − wz)        2(xz + wy)      ⎤
//! R = ⎢ 2(xy + wz)        n² − 2(x² + z²)   2(yz − wx)      ⎥ / n²
//!     ⎣ 2(xz − wy)        2(yz + wx)        n² − 2(x² + y²) ⎦
//! ```
//!
//! Every entry is rational, and `RᵀR = I` holds exactly: each column (the box's
//! axis) is exactly unit, so a face normal `±Rᵢ` is an exact rational unit vector
//! and the box's frame `u = Rᵀ(x − center)` preserves distances exactly. Every
//! decision below is then a comparison of rationals; the only square roots are
//! the lengths of a sphere's centre from the box, of a plane's normal, of a
//! cross-product axis, and of the half-extent vector.
//!
//! The six faces are numbered in the format's tie order `+x, −x, +y, −y, +z, −z`
//! of the box's own axes: face `2i` is `uᵢ = +hᵢ` (outward normal `+Rᵢ`), face
//! `2i + 1` is `uᵢ = −hᵢ` (normal `−Rᵢ`).
//!
//! Refused input: a non-finite number, a negative half-extent
//! ([`RefereeError::NegativeHalfExtent`]), a zero quaternion
//! ([`RefereeError::ZeroRotation`]), a zero plane normal, a negative sphere
//! radius, an inverted axis-aligned box. A flat box (a zero half-extent, down to
//! a point) is valid everywhere.

use super::boxes_fast::FastBox;
use super::error::RefereeError;
use super::exact::{
    Q, Root, V3, add, check, check_radius, check_v3, dot, is_zero, q, radius, round, round_unit, round_v, scale, sub,
    v3,
};
use super::stage::apart;
use crate::geom::{
    Aabb, Ball, BoundsAnswer, Contact, ContactAnswer, IntersectAnswer, OrientedBox, P3, Plane, Segment, SegmentHit,
    Sphere,
};

/// A box's fields named for errors: `a.…` or `b.…`.
#[derive(Clone, Copy)]
pub(crate) struct BoxFields {
    center: &'static str,
    half_extents: &'static str,
    rotation: &'static str,
}

pub(crate) const BOX_A: BoxFields =
    BoxFields { center: "a.center", half_extents: "a.half_extents", rotation: "a.rotation" };
pub(crate) const BOX_B: BoxFields =
    BoxFields { center: "b.center", half_extents: "b.half_extents", rotation: "b.rotation" };

/// A box held exactly.
pub(crate) struct ExactBox {
    /// Centre.
    pub(crate) c: V3,
    /// Half-extents, each ≥ 0.
    pub(crate) h: V3,
    /// `axes[i]` is column `i` of `R`: exactly unit, pairwise exactly orthogonal.
    pub(crate) axes: [V3; 3],
}

/// The rotation's columns, exactly (see the module docs), from a non-zero
/// quaternion.
fn columns(qr: [Q; 4]) -> [V3; 3] {
    let [w, x, y, z] = qr;
    let n2 = &w * &w + &x * &x + &y * &y + &z * &z;
    let two = Q::from(2u8);
    let (xx, yy, zz) = (&x * &x, &y * &y, &z * &z);
    let (xy, xz, yz) = (&x * &y, &x * &z, &y * &z);
    let (wx, wy, wz) = (&w * &x, &w * &y, &w * &z);
    let e = |v: Q| v / &n2;
    [
        [e(&n2 - &two * (&yy + &zz)), e(&two * (&xy + &wz)), e(&two * (&xz - &wy))],
        [e(&two * (&xy - &wz)), e(&n2 - &two * (&xx + &zz)), e(&two * (&yz + &wx))],
        [e(&two * (&xz + &wy)), e(&two * (&yz - &wx)), e(&n2 - &two * (&xx + &yy))],
    ]
}

/// The refusals of a box, in `f64` before any rational is made: a non-finite
/// number, a negative half-extent (`−0.0` is 0, not negative), a zero
/// quaternion.
pub(crate) fn check_box(b: &OrientedBox, f: BoxFields) -> Result<(), RefereeError> {
    check_v3(&b.center, f.center)?;
    check_v3(&b.half_extents, f.half_extents)?;
    if b.rotation.iter().any(|x| !x.is_finite()) {
        return Err(RefereeError::NonFinite { field: f.rotation });
    }
    if b.half_extents.iter().any(|&x| x < 0.0) {
        return Err(RefereeError::NegativeHalfExtent { field: f.half_extents });
    }
    if b.rotation.iter().all(|&x| x == 0.0) {
        return Err(RefereeError::ZeroRotation { field: f.rotation });
    }
    Ok(())
}

/// The exact box, or the refusal naming the field ([`check_box`]).
pub(crate) fn exact_box(b: &OrientedBox, f: BoxFields) -> Result<ExactBox, RefereeError> {
    check_box(b, f)?;
    let qr = [
        q(b.rotation[0], f.rotation)?,
        q(b.rotation[1], f.rotation)?,
        q(b.rotation[2], f.rotation)?,
        q(b.rotation[3], f.rotation)?,
    ];
    Ok(ExactBox { c: v3(&b.center, f.center)?, h: v3(&b.half_extents, f.half_extents)?, axes: columns(qr) })
}

impl ExactBox {
    /// `Rᵀ(x − c)`: `x` in the box's frame.
    pub(crate) fn to_local(&self, x: &V3) -> V3 {
        let d = sub(x, &self.c);
        self.dir_to_local(&d)
    }

    /// `Rᵀ v`: a direction in the box's frame.
    pub(crate) fn dir_to_local(&self, v: &V3) -> V3 {
        [dot(&self.axes[0], v), dot(&self.axes[1], v), dot(&self.axes[2], v)]
    }

    /// `R u`: a direction of the box's frame in the world.
    pub(crate) fn dir_to_world(&self, u: &V3) -> V3 {
        let mut out = scale(&self.axes[0], &u[0]);
        out = add(&out, &scale(&self.axes[1], &u[1]));
        add(&out, &scale(&self.axes[2], &u[2]))
    }

    /// `c + R u`: a point of the box's frame in the world.
    pub(crate) fn to_world(&self, u: &V3) -> V3 {
        add(&self.c, &self.dir_to_world(u))
    }

    /// The first parameter `s ∈ [0, 1]` at which the segment `u0 → u1` (in
    /// the box's frame) is in the closed box, by the slabs (Ericson §5.3.3,
    /// exactly); `None` when it misses.
    pub(crate) fn entry(&self, u0: &V3, u1: &V3) -> Option<Q> {
        let (mut lo, mut hi) = (Q::ZERO, Q::ONE);
        for i in 0..3 {
            let d = &u1[i] - &u0[i];
            let (neg_h, h) = (-self.h[i].clone(), self.h[i].clone());
            if d.is_zero() {
                if u0[i] < neg_h || u0[i] > h {
                    return None;
                }
                continue;
            }
            let (ta, tb) = ((&neg_h - &u0[i]) / &d, (&h - &u0[i]) / &d);
            let (t0, t1) = if ta <= tb { (ta, tb) } else { (tb, ta) };
            if t0 > lo {
                lo = t0;
            }
            if t1 < hi {
                hi = t1;
            }
            if lo > hi {
                return None;
            }
        }
        Some(lo)
    }

    /// `u` (in the box's frame) clamped into the closed box: its nearest point.
    pub(crate) fn clamp(&self, u: &V3) -> V3 {
        std::array::from_fn(|i| {
            let h = &self.h[i];
            if u[i] > *h {
                h.clone()
            } else if u[i] < -h.clone() {
                -h.clone()
            } else {
                u[i].clone()
            }
        })
    }

    /// Whether `u` (in the box's frame) lies in the closed box.
    fn holds(&self, u: &V3) -> bool {
        (0..3).all(|i| abs(&u[i]) <= self.h[i])
    }

    /// The outward unit normal of face `face` (`2i`: `+Rᵢ`, `2i + 1`: `−Rᵢ`),
    /// exact.
    fn face_normal(&self, face: usize) -> V3 {
        let axis = &self.axes[face / 2];
        if face.is_multiple_of(2) { axis.clone() } else { neg(axis) }
    }

    /// `u` (in the box's frame) projected onto the plane of face `face`, in the
    /// world.
    fn onto_face(&self, u: &V3, face: usize) -> V3 {
        let mut p = u.clone();
        let i = face / 2;
        p[i] = if face.is_multiple_of(2) { self.h[i].clone() } else { -self.h[i].clone() };
        self.to_world(&p)
    }
}

fn abs(x: &Q) -> Q {
    if *x < Q::ZERO { -x.clone() } else { x.clone() }
}

fn neg(v: &V3) -> V3 {
    [-v[0].clone(), -v[1].clone(), -v[2].clone()]
}

/// The face of the box nearest a point `u` of the closed box (in its frame):
/// the least `hᵢ − uᵢ` (face `2i`) or `hᵢ + uᵢ` (face `2i + 1`), the first in
/// the order `+x, −x, +y, −y, +z, −z` on a tie; its distance; and whether
/// there was a tie (two faces nearest: `u` on an edge or a corner, equidistant
/// from two faces inside, or `uᵢ = 0` where axis `i` is nearest).
fn nearest_face(h: &V3, u: &V3) -> (usize, Q, bool) {
    let mut best: Option<(usize, Q)> = None;
    let mut tie = false;
    for face in 0..6usize {
        let i = face / 2;
        let dist = if face.is_multiple_of(2) { &h[i] - &u[i] } else { &h[i] + &u[i] };
        match &best {
            Some((_, d)) if dist > *d => {}
            Some((_, d)) if dist == *d => tie = true,
            _ => {
                best = Some((face, dist));
                tie = false;
            }
        }
    }
    let (face, dist) = best.expect("six faces");
    (face, dist, tie)
}

/// A sphere against a box, in the box's frame.
struct SphereBox {
    r: Q,
    bx: ExactBox,
    /// The sphere's centre in the box's frame.
    u: V3,
    /// Where the centre is.
    place: Place,
}

enum Place {
    /// Outside the closed box (boxed: the big variant).
    Outside(Box<Outside>),
    /// In the closed box: the nearest face, its distance `hᵢ − |uᵢ|`, and
    /// whether another face is as near.
    Inside { face: usize, dist: Q, tie: bool },
}

/// A centre outside the closed box: `p = clamp(u, −h, h)` its closest point,
/// `w = u − p ≠ 0`, and `√(w·w)` the distance.
struct Outside {
    p: V3,
    w: V3,
    root: Root,
}

fn sphere_box(a: &Sphere, b: &OrientedBox) -> Result<SphereBox, RefereeError> {
    let m = v3(&a.center, "a.center")?;
    let r = radius(a.radius, "a.radius")?;
    let bx = exact_box(b, BOX_B)?;
    let u = bx.to_local(&m);
    let place = if bx.holds(&u) {
        let (face, dist, tie) = nearest_face(&bx.h, &u);
        Place::Inside { face, dist, tie }
    } else {
        let p = bx.clamp(&u);
        let w = sub(&u, &p);
        let root = Root::new(dot(&w, &w));
        Place::Outside(Box::new(Outside { p, w, root }))
    };
    Ok(SphereBox { r, bx, u, place })
}

/// Contact between a sphere `a` (centre `M`, radius `r`) and an oriented box
/// `b`.
///
/// **Definition** (`docs/FORMAT.md`, sphere–box). With `u = Rᵀ(M − center)` the
/// centre in the box's frame and `p = clamp(u, −h, h)` its closest point in the
/// box:
///
/// ```text
/// centre outside (u ≠ p):   contact ⇔ ‖u − p‖² ≤ r²
///                           normal = R(u − p)/‖u − p‖,  point = center + R·p,
///                           depth  = r − ‖u − p‖
/// centre in the closed box: the nearest face (least hᵢ − |uᵢ|, outward normal
///                           ±Rᵢ by the sign of uᵢ), point = the centre's
///                           projection onto it, depth = r + hᵢ − |uᵢ|
/// ```
///
/// `R`'s columns are exactly unit, so `‖R(u − p)‖ = ‖u − p‖` and the distance
/// is the world's. Outside, every output is `x + y·√(w·w)` (`w = u − p`), rounded
/// once; inside, every output is rational. Source: Ericson §5.1.4 (closest point
/// on an OBB) and §4.4 for the frame.
///
/// **Degenerate input.** A centre in the closed box with two faces nearest (on
/// an edge or a corner, equidistant from two faces inside, `uᵢ = 0` on the
/// nearest axis — every centre in a flat box's plane) has no unique normal: the
/// first of the nearest faces in the order `+x, −x, +y, −y, +z, −z`, and
/// `degenerate: true`. A zero radius (a point) is valid; a negative radius, a
/// negative half-extent, a zero quaternion or a non-finite number is refused.
pub fn contact_sphere_box(a: &Sphere, b: &OrientedBox) -> Result<ContactAnswer, RefereeError> {
    check_v3(&a.center, "a.center")?;
    check_radius(a.radius, "a.radius")?;
    check_box(b, BOX_B)?;
    if apart(|| super::boxes_fast::sphere_box_apart(a, b)) {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    let sb = sphere_box(a, b)?;
    match &sb.place {
        Place::Outside(out) => {
            let Outside { p, w, root } = &**out;
            if *root.square() > &sb.r * &sb.r {
                return Ok(ContactAnswer { contact: None, degenerate: false });
            }
            let zero: V3 = [Q::ZERO, Q::ZERO, Q::ZERO];
            Ok(ContactAnswer {
                contact: Some(Contact {
                    point: round_v(&sb.bx.to_world(p)),
                    normal: root.round_over_v(&zero, &Q::ONE, &sb.bx.dir_to_world(w)),
                    depth: root.round_affine(&sb.r, &Q::NEG_ONE),
                }),
                degenerate: false,
            })
        }
        Place::Inside { face, dist, tie } => Ok(ContactAnswer {
            contact: Some(Contact {
                point: round_v(&sb.bx.onto_face(&sb.u, *face)),
                normal: round_v(&sb.bx.face_normal(*face)),
                depth: round(&(&sb.r + dist)),
            }),
            degenerate: *tie,
        }),
    }
}

/// The signed depth behind [`contact_sphere_box`]'s decision, correctly
/// rounded: `r − ‖u − p‖` with the centre outside the box (negative, minus the
/// gap, when apart), `r + hᵢ − |uᵢ|` (the nearest face's) with it inside. ≥ 0
/// exactly when in contact; the sign bit is the decision (see
/// [`super::contact_margin_sphere_sphere`]).
pub fn contact_margin_sphere_box(a: &Sphere, b: &OrientedBox) -> Result<f64, RefereeError> {
    let sb = sphere_box(a, b)?;
    Ok(match &sb.place {
        Place::Outside(out) => out.root.round_affine(&sb.r, &Q::NEG_ONE),
        Place::Inside { dist, .. } => round(&(&sb.r + dist)),
    })
}

/// A box against a plane: everything the answer, the margin and the region
/// take.
struct BoxPlane {
    bx: ExactBox,
    n: V3,
    d: Q,
    /// `sᵢ = n·Rᵢ`.
    s: V3,
    /// The box's lowest point in its frame: `uᵢ = −sign(sᵢ)·hᵢ` (0 where
    /// `sᵢ = 0`: the centre of the lowest face or edge).
    low: V3,
    /// `d − n·x` at the lowest point: `‖n‖` times the depth.
    e: Q,
    root: Root,
}

fn box_plane(a: &OrientedBox, b: &Plane) -> Result<BoxPlane, RefereeError> {
    let bx = exact_box(a, BOX_A)?;
    let n = v3(&b.normal, "b.normal")?;
    let d = q(b.offset, "b.offset")?;
    if is_zero(&n) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    let s = bx.dir_to_local(&n);
    let low: V3 = std::array::from_fn(|i| {
        if s[i] > Q::ZERO {
            -bx.h[i].clone()
        } else if s[i] < Q::ZERO {
            bx.h[i].clone()
        } else {
            Q::ZERO
        }
    });
    let e = &d - dot(&n, &bx.to_world(&low));
    let root = Root::new(dot(&n, &n));
    Ok(BoxPlane { bx, n, d, s, low, e, root })
}

impl BoxPlane {
    fn touches(&self) -> bool {
        self.e >= Q::ZERO
    }

    /// A point of the box (in its frame) projected onto the plane, in the world:
    /// `x + ((d − n·x)/‖n‖²)·n`.
    fn project(&self, u: &V3) -> V3 {
        let x = self.bx.to_world(u);
        let k = (&self.d - dot(&self.n, &x)) / self.root.square();
        add(&x, &scale(&self.n, &k))
    }
}

/// Contact between an oriented box `a` and a plane `b` (`n·x = d`, bounding the
/// solid `n·x ≤ d`).
///
/// **Definition** (`docs/FORMAT.md`, box–plane). With `sᵢ = n·Rᵢ`, the box's
/// lowest point (least `n·x`) is `x* = center + R·u*`, `u*ᵢ = −sign(sᵢ)·hᵢ`, at
/// `n·x* = n·center − Σ hᵢ|sᵢ|`:
///
/// ```text
/// contact ⇔ n·x* ≤ d,   normal = n/‖n‖,   depth = (d − n·x*)/‖n‖,
/// point   = x* + ((d − n·x*)/‖n‖²)·n      (x*'s projection onto the plane)
/// ```
///
/// The depth is the exact penetration depth: the shortest translation out of
/// a half-space is along its normal. The point is rational, the depth
/// `e/√(n·n)`, each rounded once. Where the lowest point is not unique (some
/// `sᵢ = 0` with `hᵢ > 0`: a lowest edge or face), the answer's point is the
/// projection of that edge's or face's centre (`u*ᵢ = 0` there); the whole
/// region is [`contact_region_box_plane`].
///
/// **Degenerate input.** None: the normal is always unique (`degenerate` is
/// false). A zero plane normal, a zero quaternion, a negative half-extent or a
/// non-finite number is refused.
pub fn contact_box_plane(a: &OrientedBox, b: &Plane) -> Result<ContactAnswer, RefereeError> {
    check_box(a, BOX_A)?;
    check_v3(&b.normal, "b.normal")?;
    check(b.offset, "b.offset")?;
    if b.normal.iter().all(|&x| x == 0.0) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    if apart(|| super::boxes_fast::box_plane_apart(a, b)) {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    let bp = box_plane(a, b)?;
    if !bp.touches() {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    Ok(ContactAnswer {
        contact: Some(Contact {
            point: round_v(&bp.project(&bp.low)),
            normal: round_unit(&bp.n),
            depth: bp.root.round_over(&Q::ZERO, &bp.e),
        }),
        degenerate: false,
    })
}

/// The signed depth `(d − n·x*)/‖n‖` behind [`contact_box_plane`]'s decision
/// (`x*` the box's lowest point), correctly rounded: ≥ 0 exactly when in
/// contact, minus the gap when apart.
pub fn contact_margin_box_plane(a: &OrientedBox, b: &Plane) -> Result<f64, RefereeError> {
    let bp = box_plane(a, b)?;
    Ok(bp.root.round_over(&Q::ZERO, &bp.e))
}

/// The contact region of [`contact_box_plane`] on the plane: the projection of
/// the box's lowest points, each vertex correctly rounded. `None` when apart.
///
/// The lowest points are `u*` with every free axis (`sᵢ = 0` and `hᵢ > 0`)
/// spanning `[−hᵢ, hᵢ]`: no free axis gives one point (exactly the answer's
/// point), one gives a segment (2 vertices: `uᵢ = −hᵢ`, then `+hᵢ`), two give a
/// rectangle (4 vertices in order around it: `(−,−), (+,−), (+,+), (−,+)` on the
/// free axes `j < k`). Three free axes cannot happen (`n ≠ 0`).
pub fn contact_region_box_plane(a: &OrientedBox, b: &Plane) -> Result<Option<Vec<P3>>, RefereeError> {
    let bp = box_plane(a, b)?;
    if !bp.touches() {
        return Ok(None);
    }
    let free: Vec<usize> = (0..3).filter(|&i| bp.s[i].is_zero() && !bp.bx.h[i].is_zero()).collect();
    let corner = |signs: &[bool]| {
        let mut u = bp.low.clone();
        for (&i, &plus) in free.iter().zip(signs) {
            u[i] = if plus { bp.bx.h[i].clone() } else { -bp.bx.h[i].clone() };
        }
        round_v(&bp.project(&u))
    };
    let region = match free.len() {
        0 => vec![corner(&[])],
        1 => vec![corner(&[false]), corner(&[true])],
        _ => vec![corner(&[false, false]), corner(&[true, false]), corner(&[true, true]), corner(&[false, true])],
    };
    Ok(Some(region))
}

/// A segment's first hit on a box, exactly: the hit's parameter, the entering
/// face, and whether another face ties with it. `None`: no hit.
struct BoxHit {
    t: Q,
    face: usize,
    tie: bool,
}

/// The first point of the segment `u0 + t·e`, `t ∈ [0, 1]` (in the box's
/// frame) in the closed box `|uᵢ| ≤ hᵢ`: a start in the box gives `t = 0` and
/// its nearest face; otherwise the slabs (Ericson §5.3.3), each entered at
/// `(∓hᵢ − u0ᵢ)/eᵢ` through face `−i` when `eᵢ > 0` and `+i` when `eᵢ < 0`.
fn first_hit(h: &V3, u0: &V3, e: &V3) -> Option<BoxHit> {
    if (0..3).all(|i| abs(&u0[i]) <= h[i]) {
        let (face, _, tie) = nearest_face(h, u0);
        return Some(BoxHit { t: Q::ZERO, face, tie });
    }
    let mut enter: Option<(Q, usize)> = None;
    let mut tie = false;
    let mut exit: Option<Q> = None;
    for i in 0..3 {
        if e[i].is_zero() {
            // Parallel to the slab: inside it for all t, or never.
            if abs(&u0[i]) > h[i] {
                return None;
            }
            continue;
        }
        let lo = (-h[i].clone() - &u0[i]) / &e[i];
        let hi = (&h[i] - &u0[i]) / &e[i];
        let (t_in, t_out, face) = if e[i] > Q::ZERO { (lo, hi, 2 * i + 1) } else { (hi, lo, 2 * i) };
        match &enter {
            Some((t, _)) if t_in < *t => {}
            Some((t, _)) if t_in == *t => tie = true,
            _ => {
                enter = Some((t_in, face));
                tie = false;
            }
        }
        if exit.as_ref().is_none_or(|x| t_out < *x) {
            exit = Some(t_out);
        }
    }
    // The start is outside, so some slab holds it out: it has eᵢ ≠ 0 (else the
    // loop returned), and `enter` and `exit` are set.
    let (t, face) = enter?;
    let exit = exit?;
    (t >= Q::ZERO && t <= Q::ONE && t <= exit).then_some(BoxHit { t, face, tie })
}

/// The first hit of segment `s` (`p0 + t(p1 − p0)`, `t ∈ [0, 1]`) on the solid
/// oriented box `b`.
///
/// **Definition** (`docs/FORMAT.md`, segment–box). In the box's frame
/// (`u0 = Rᵀ(p0 − center)`, `e = Rᵀ(p1 − p0)`, exact):
///
/// - a start in the closed box is hit at `t = 0`, point `p0`, with the normal
///   of the face nearest it (as [`contact_sphere_box`] inside);
/// - otherwise, slab by slab (Ericson §5.3.3): a slab the segment runs parallel
///   to (`eᵢ = 0`) either holds it throughout or rules the hit out; each other
///   slab is entered at `t_in,i` and left at `t_out,i`; `t_enter = maxᵢ t_in,i`,
///   `t_exit = minᵢ t_out,i`, and the segment hits when
///   `0 ≤ t_enter ≤ min(1, t_exit)` — touching an edge or a corner counts. The
///   entering face is the slab's giving `t_enter` (face `−i` when `eᵢ > 0`,
///   `+i` when `eᵢ < 0`); its outward normal `±Rᵢ` is exact.
///
/// `t` and the point `p0 + t(p1 − p0)` are rational, rounded once; the normal is
/// an exact unit vector, rounded componentwise. `barycentric` and `triangle`
/// are `None`; `parallel` is always false.
///
/// **Degenerate input.** `degenerate: true` when the face is not unique: two
/// slabs entered at the same `t_enter` (an edge or a corner), or a start in the
/// box with two faces nearest; the first face in the order
/// `+x, −x, +y, −y, +z, −z` is reported. A segment sliding within the plane of a
/// face (`eᵢ = 0`, `|u0ᵢ| = hᵢ`) enters through the face of the slab it crosses
/// — that slab is the only one with an entry time — and is not degenerate. A
/// zero-length segment is always `degenerate: true`: a point in the box is hit
/// at `t = 0` with its nearest face, a point outside is no hit.
pub fn intersect_segment_box(s: &Segment, b: &OrientedBox) -> Result<IntersectAnswer, RefereeError> {
    check_v3(&s.start, "a.start")?;
    check_v3(&s.end, "a.end")?;
    check_box(b, BOX_B)?;
    if apart(|| super::boxes_fast::segment_box_miss(s, b)) {
        // A zero-length segment is degenerate however it is answered: the
        // exact stage's `p1 − p0 = 0`, coordinate by coordinate (−0 = +0).
        let zero_length = (0..3).all(|i| s.start[i] - s.end[i] == 0.0);
        return Ok(IntersectAnswer { hit: None, parallel: false, degenerate: zero_length });
    }
    let p0 = v3(&s.start, "a.start")?;
    let p1 = v3(&s.end, "a.end")?;
    let bx = exact_box(b, BOX_B)?;
    let dir = sub(&p1, &p0);
    let zero_length = is_zero(&dir);
    let u0 = bx.to_local(&p0);
    let e = bx.dir_to_local(&dir);
    let Some(hit) = first_hit(&bx.h, &u0, &e) else {
        return Ok(IntersectAnswer { hit: None, parallel: false, degenerate: zero_length });
    };
    let point = add(&p0, &scale(&dir, &hit.t));
    Ok(IntersectAnswer {
        hit: Some(SegmentHit {
            t: round(&hit.t),
            point: round_v(&point),
            normal: round_v(&bx.face_normal(hit.face)),
            barycentric: None,
            triangle: None,
        }),
        parallel: false,
        degenerate: hit.tie || zero_length,
    })
}

/// The bounds of an oriented box `b`: its tight axis-aligned box and a
/// bounding sphere.
///
/// **Definition** (`docs/FORMAT.md`, `bounds`). The box's extent along world
/// axis `i` is `Σⱼ |Rᵢⱼ| hⱼ` (the support of the box, Ericson §4.2.6), so
///
/// ```text
/// aabb.min[i] = centerᵢ − Σⱼ |Rᵢⱼ| hⱼ,   aabb.max[i] = centerᵢ + Σⱼ |Rᵢⱼ| hⱼ
/// sphere      = Ball { center, radius ‖h‖ }
/// ```
///
/// each coordinate a rational rounded once, the radius `√(h·h)` correctly
/// rounded. The ball centred on the box's centre with radius `‖h‖` is the
/// minimal enclosing sphere (its corners are at `‖h‖` in opposite pairs).
/// A coordinate beyond `f64`'s range rounds to ±∞, as everywhere in the
/// referee.
///
/// **Degenerate input.** A flat box is valid (a zero extent along its axis).
/// A negative half-extent, a zero quaternion or a non-finite number is refused.
pub fn bounds_box(b: &OrientedBox) -> Result<BoundsAnswer, RefereeError> {
    let bx = exact_box(b, BOX_A)?;
    let reach: V3 = std::array::from_fn(|i| (0..3).fold(Q::ZERO, |acc, j| acc + abs(&bx.axes[j][i]) * &bx.h[j]));
    let min: V3 = std::array::from_fn(|i| &bx.c[i] - &reach[i]);
    let max: V3 = std::array::from_fn(|i| &bx.c[i] + &reach[i]);
    Ok(BoundsAnswer {
        aabb: Some(Aabb { min: round_v(&min), max: round_v(&max) }),
        sphere: Some(Ball { center: round_v(&bx.c), radius: Root::new(dot(&bx.h, &bx.h)).round_sqrt() }),
    })
}

/// One separating-axis candidate: the overlap of the two boxes' projections on
/// `L` times `‖L‖`, and `‖L‖²` (1 for a box axis).
struct AxisOverlap {
    overlap: Q,
    norm2: Q,
}

impl AxisOverlap {
    /// Whether `self.overlap/√self.norm2 < other.overlap/√other.norm2`, exactly:
    /// by the signs, then by the squares `o₁²·n₂` against `o₂²·n₁` (reversed for
    /// two negatives).
    fn less(&self, other: &Self) -> bool {
        let (sa, sb) = (self.overlap >= Q::ZERO, other.overlap >= Q::ZERO);
        if sa != sb {
            return !sa;
        }
        let lhs = &self.overlap * &self.overlap * &other.norm2;
        let rhs = &other.overlap * &other.overlap * &self.norm2;
        if sa { lhs < rhs } else { lhs > rhs }
    }
}

/// The separating-axis test of two boxes (Ericson §4.4.1, Gottschalk's 15
/// axes), exactly: for each of `A`'s axes, `B`'s axes and the nine
/// `Aᵢ × Bⱼ` (an exactly zero cross product — parallel edges — is skipped: it
/// separates nothing), the projections' overlap
/// `Σ hA,ᵢ|L·Aᵢ| + Σ hB,ⱼ|L·Bⱼ| − |L·(cB − cA)|` (times `‖L‖`).
///
/// The 15 axes hold every facet normal of the Minkowski difference `A − B` (a
/// zonotope generated by the axes with `h > 0`), so the boxes overlap exactly
/// when every overlap is ≥ 0, flat boxes included: a flat difference lying in a
/// plane through the origin is separated within the plane along `N × g` (`g` a
/// generator), and among each box's other axes, perpendicular to `g`, one
/// projects onto that direction.
fn sat(a: &ExactBox, b: &ExactBox) -> Vec<AxisOverlap> {
    let t = sub(&b.c, &a.c);
    (0..15).filter_map(|k| sat_axis(a, b, &t, k)).collect()
}

/// Axis `k` of [`sat`] (`0..3`: `a`'s, `3..6`: `b`'s, `6..15`: `aᵢ × bⱼ` row by
/// row), `None` for a zero cross product; `t = cB − cA`.
fn sat_axis(a: &ExactBox, b: &ExactBox, t: &V3, k: usize) -> Option<AxisOverlap> {
    let (l, norm2) = if k < 3 {
        (a.axes[k].clone(), Q::ONE)
    } else if k < 6 {
        (b.axes[k - 3].clone(), Q::ONE)
    } else {
        let l = super::exact::cross(&a.axes[(k - 6) / 3], &b.axes[(k - 6) % 3]);
        if is_zero(&l) {
            return None;
        }
        let n2 = dot(&l, &l);
        (l, n2)
    };
    let ra = (0..3).fold(Q::ZERO, |acc, i| acc + &a.h[i] * abs(&dot(&l, &a.axes[i])));
    let rb = (0..3).fold(Q::ZERO, |acc, j| acc + &b.h[j] * abs(&dot(&l, &b.axes[j])));
    Some(AxisOverlap { overlap: ra + rb - abs(&dot(&l, t)), norm2 })
}

/// `overlap/‖L‖` of one axis, correctly rounded.
fn axis_margin(axis: &AxisOverlap) -> f64 {
    if axis.norm2 == Q::ONE {
        round(&axis.overlap)
    } else {
        Root::new(axis.norm2.clone()).round_over(&Q::ZERO, &axis.overlap)
    }
}

/// The exact margin of axis `k` alone, the one the floating-point stage
/// certified to be the least (a certified axis is never a zero one).
fn margin_on_axis(a: &ExactBox, b: &ExactBox, k: usize) -> f64 {
    let t = sub(&b.c, &a.c);
    sat_axis(a, b, &t, k).map_or_else(|| sat_margin(&sat(a, b)), |axis| axis_margin(&axis))
}

/// The floating-point stage's answer ([`super::boxes_fast`]), counted.
fn staged<T>(fast: impl FnOnce() -> Option<T>) -> Option<T> {
    super::stage::fast_stage(super::stage::Stage::BoxOverlap, fast)
}

/// `min` over the axes of `overlap/‖L‖`, correctly rounded.
fn sat_margin(axes: &[AxisOverlap]) -> f64 {
    let mut best = &axes[0];
    for ax in &axes[1..] {
        if ax.less(best) {
            best = ax;
        }
    }
    axis_margin(best)
}

/// Whether the oriented boxes `a` and `b` overlap: the closed solids share a
/// point; touching boxes overlap.
///
/// **Definition.** The separating-axis theorem over the 15 axes (see `sat`):
/// overlap exactly when no axis has the projections strictly apart, every
/// comparison in rationals. Source: Gottschalk, Lin and Manocha (OBBTree);
/// Ericson §4.4.1, without its epsilon: the exactly zero cross products are
/// skipped instead.
///
/// **Degenerate input.** Flat boxes (down to points) are valid. A negative
/// half-extent, a zero quaternion or a non-finite number is refused.
pub fn overlap_box_box(a: &OrientedBox, b: &OrientedBox) -> Result<bool, RefereeError> {
    check_box(a, BOX_A)?;
    check_box(b, BOX_B)?;
    if let Some(answer) = staged(|| super::boxes_fast::overlap(&FastBox::of(a), &FastBox::of(b))) {
        return Ok(answer);
    }
    let (a, b) = (exact_box(a, BOX_A)?, exact_box(b, BOX_B)?);
    Ok(sat(&a, &b).iter().all(|ax| ax.overlap >= Q::ZERO))
}

/// The signed margin behind [`overlap_box_box`]'s decision: the least over the
/// separating axes `L` of `overlap_L/‖L‖`, the projections' signed overlap along
/// the unit axis, correctly rounded (the least is chosen by exact comparisons,
/// then rounded once).
///
/// When the boxes overlap this is ≥ 0 and is their exact penetration depth (the
/// least support of the Minkowski difference over its facet normals, all among
/// the axes; 0 for touching boxes). When some axis separates it is
/// `−max gap_L/‖L‖`, the widest separating gap: a **lower bound** of the
/// distance between the boxes, not the distance itself. The sign bit is the
/// decision.
pub fn overlap_margin_box_box(a: &OrientedBox, b: &OrientedBox) -> Result<f64, RefereeError> {
    check_box(a, BOX_A)?;
    check_box(b, BOX_B)?;
    let least = staged(|| super::boxes_fast::least_axis(&FastBox::of(a), &FastBox::of(b)));
    let (a, b) = (exact_box(a, BOX_A)?, exact_box(b, BOX_B)?);
    Ok(match least {
        Some(k) => margin_on_axis(&a, &b, k),
        None => sat_margin(&sat(&a, &b)),
    })
}

/// The refusals of an axis-aligned box `b`: a non-finite number, `min > max`.
fn check_aabb(b: &Aabb) -> Result<(), RefereeError> {
    check_v3(&b.min, "b.min")?;
    check_v3(&b.max, "b.max")?;
    if (0..3).any(|k| b.min[k] > b.max[k]) {
        return Err(RefereeError::InvertedAabb { field: "b.min" });
    }
    Ok(())
}

/// An axis-aligned box as an exact box: centre `(min + max)/2`, half-extents
/// `(max − min)/2`, the identity rotation. Refuses a non-finite number and an
/// inverted box as [`super::overlap_aabb_aabb`] does.
fn aabb_box(b: &Aabb) -> Result<ExactBox, RefereeError> {
    check_aabb(b)?;
    let (min, max) = (v3(&b.min, "b.min")?, v3(&b.max, "b.max")?);
    let half = Q::from_parts(1.into(), 2u8.into());
    let unit = |k: usize| -> V3 { std::array::from_fn(|i| if i == k { Q::ONE } else { Q::ZERO }) };
    Ok(ExactBox {
        c: std::array::from_fn(|i| (&min[i] + &max[i]) * &half),
        h: std::array::from_fn(|i| (&max[i] - &min[i]) * &half),
        axes: [unit(0), unit(1), unit(2)],
    })
}

/// Whether the oriented box `a` and the axis-aligned box `b` overlap (closed
/// solids; touching overlaps): [`overlap_box_box`] with `b` as the box of
/// centre `(min + max)/2`, half-extents `(max − min)/2` and no rotation, exactly.
///
/// **Degenerate input.** Flat boxes on either side are valid. An inverted
/// `b` (`min > max`) and the box refusals of [`overlap_box_box`] are refused.
pub fn overlap_box_aabb(a: &OrientedBox, b: &Aabb) -> Result<bool, RefereeError> {
    check_box(a, BOX_A)?;
    check_aabb(b)?;
    if let Some(answer) = staged(|| super::boxes_fast::overlap(&FastBox::of(a), &FastBox::of_aabb(b))) {
        return Ok(answer);
    }
    let (a, b) = (exact_box(a, BOX_A)?, aabb_box(b)?);
    Ok(sat(&a, &b).iter().all(|ax| ax.overlap >= Q::ZERO))
}

/// The signed margin behind [`overlap_box_aabb`]'s decision, as
/// [`overlap_margin_box_box`]: the exact penetration depth when they overlap, a
/// lower bound of minus the distance when apart; correctly rounded.
pub fn overlap_margin_box_aabb(a: &OrientedBox, b: &Aabb) -> Result<f64, RefereeError> {
    check_box(a, BOX_A)?;
    check_aabb(b)?;
    let least = staged(|| super::boxes_fast::least_axis(&FastBox::of(a), &FastBox::of_aabb(b)));
    let (a, b) = (exact_box(a, BOX_A)?, aabb_box(b)?);
    Ok(match least {
        Some(k) => margin_on_axis(&a, &b, k),
        None => sat_margin(&sat(&a, &b)),
    })
}

#[cfg(test)]
#[path = "boxes_tests.rs"]
pub(crate) mod tests;
