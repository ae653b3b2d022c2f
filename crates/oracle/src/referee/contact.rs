//! Contact of a sphere with a sphere, a plane or a triangle, exactly.
//!
//! Convention (fixture format): the normal points from `b` toward `a` and has
//! unit length, the point lies on `b`'s surface, depth ≥ 0 is the penetration,
//! and touching (depth exactly 0) is contact. Each margin function returns the
//! signed depth behind the decision (negative when apart), correctly rounded.

use super::closest::closest_on_triangle;
use super::error::RefereeError;
use super::exact::{Q, Root, V3, cross, dot, is_zero, q, radius, round, round_unit, round_v, sub, v3};
use crate::geom::{Contact, ContactAnswer, P3, Plane, Sphere, Triangle};

/// The normal reported when the direction between the shapes is undefined:
/// concentric spheres, or a sphere centre exactly on a zero-area triangle. It is
/// `+z`, the same fallback `collide` documents, so engines that follow it agree
/// with the referee on degenerate cases too.
pub const CONCENTRIC_FALLBACK_NORMAL: P3 = [0.0, 0.0, 1.0];

/// The floating-point stage's answer ([`super::contact_fast`]), counted.
fn staged<T>(fast: impl FnOnce() -> Option<T>) -> Option<T> {
    super::stage::fast_stage(super::stage::Stage::Contact, fast)
}

fn fallback_normal() -> V3 {
    [Q::ZERO, Q::ZERO, Q::ONE]
}

struct Spheres {
    delta: V3,
    mb: V3,
    rb: Q,
    sum: Q,
}

fn spheres(a: &Sphere, b: &Sphere) -> Result<Spheres, RefereeError> {
    let ma = v3(&a.center, "a.center")?;
    let ra = radius(a.radius, "a.radius")?;
    let mb = v3(&b.center, "b.center")?;
    let rb = radius(b.radius, "b.radius")?;
    Ok(Spheres { delta: sub(&ma, &mb), mb, sum: &ra + &rb, rb })
}

/// Contact between spheres `a` (centre `Ma`, radius `ra`) and `b` (`Mb`, `rb`).
///
/// **Definition** (the lecture's, as in the fixture format): with `D = Ma − Mb`,
///
/// ```text
/// contact  ⇔  ‖D‖ ≤ ra + rb          (decided as D·D ≤ (ra + rb)², in rationals)
/// normal   =  D / ‖D‖                 (from b toward a)
/// point    =  Mb + rb · normal        (on b's surface)
/// depth    =  ra + rb − ‖D‖
/// ```
///
/// Every output is `x + y·√(D·D)` for exact rationals `x`, `y`, rounded correctly.
/// Source: the lecture's sphere–sphere formulas; Ericson §4.3.1 for the squared
/// comparison.
///
/// **Degenerate input.** Concentric spheres (`D = 0` exactly) have no direction:
/// the answer is contact with normal [`CONCENTRIC_FALLBACK_NORMAL`], point
/// `Mb + rb·(0, 0, 1)`, depth `ra + rb`, and `degenerate: true`. Zero radii are
/// allowed (points); a negative radius or a non-finite number is refused.
pub fn contact_sphere_sphere(a: &Sphere, b: &Sphere) -> Result<ContactAnswer, RefereeError> {
    if let Some(contact) = staged(|| super::contact_fast::sphere_sphere(a, b)) {
        return Ok(ContactAnswer { contact, degenerate: false });
    }
    let s = spheres(a, b)?;
    let dd = dot(&s.delta, &s.delta);
    if dd > &s.sum * &s.sum {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    if dd.is_zero() {
        let n = fallback_normal();
        let point = [s.mb[0].clone(), s.mb[1].clone(), &s.mb[2] + &s.rb];
        return Ok(ContactAnswer {
            contact: Some(Contact { point: round_v(&point), normal: round_v(&n), depth: round(&s.sum) }),
            degenerate: true,
        });
    }
    let root = Root::new(dd);
    let zero: V3 = [Q::ZERO, Q::ZERO, Q::ZERO];
    Ok(ContactAnswer {
        contact: Some(Contact {
            point: root.round_over_v(&s.mb, &s.rb, &s.delta),
            normal: root.round_over_v(&zero, &Q::ONE, &s.delta),
            depth: root.round_affine(&s.sum, &Q::NEG_ONE),
        }),
        degenerate: false,
    })
}

/// The signed depth `ra + rb − ‖Ma − Mb‖` behind [`contact_sphere_sphere`]'s
/// decision, correctly rounded: ≥ 0 exactly when the spheres are in contact,
/// negative (minus the gap) when apart. Symmetric in `a` and `b`.
///
/// The sign bit alone carries the decision: touching gives `+0.0`, and a gap
/// smaller than the least subnormal rounds to `−0.0`. This holds for every
/// margin function of the referee.
pub fn contact_margin_sphere_sphere(a: &Sphere, b: &Sphere) -> Result<f64, RefereeError> {
    if let Some(margin) = staged(|| super::contact_fast::sphere_sphere_margin(a, b)) {
        return Ok(margin);
    }
    let s = spheres(a, b)?;
    Ok(Root::new(dot(&s.delta, &s.delta)).round_affine(&s.sum, &Q::NEG_ONE))
}

struct SpherePlane {
    c: V3,
    r: Q,
    n: V3,
    /// `n·c − d`: the centre's signed distance times `‖n‖`.
    e: Q,
    root: Root,
}

fn sphere_plane(
    s: &Sphere,
    p: &Plane,
    sf: [&'static str; 2],
    pf: [&'static str; 2],
) -> Result<SpherePlane, RefereeError> {
    let c = v3(&s.center, sf[0])?;
    let r = radius(s.radius, sf[1])?;
    let n = v3(&p.normal, pf[0])?;
    let d = q(p.offset, pf[1])?;
    if is_zero(&n) {
        return Err(RefereeError::ZeroNormal { field: pf[0] });
    }
    let e = dot(&n, &c) - d;
    let root = Root::new(dot(&n, &n));
    Ok(SpherePlane { c, r, n, e, root })
}

impl SpherePlane {
    /// `s ≤ r` with `s = e/‖n‖`: true when `e ≤ 0` (`r ≥ 0`), else `e² ≤ r²‖n‖²`.
    fn touches(&self) -> bool {
        self.e <= Q::ZERO || &self.e * &self.e <= &self.r * &self.r * self.root.square()
    }

    /// `r − e/‖n‖`.
    fn depth(&self) -> f64 {
        self.root.round_over(&self.r, &-self.e.clone())
    }
}

/// Contact between a sphere `a` (centre `c`, radius `r`) and a plane `b`
/// (`n·x = d`, bounding the solid `n·x ≤ d`).
///
/// **Definition.** The centre's signed distance to the plane is
/// `s = (n·c − d)/‖n‖` (positive on the side `n` points to, outside the solid).
/// The sphere reaches the solid iff `s ≤ r` — decided exactly as `n·c − d ≤ 0` or
/// `(n·c − d)² ≤ r²‖n‖²`. Then
///
/// ```text
/// normal = n / ‖n‖                          (from the plane toward the sphere)
/// point  = c − s·n/‖n‖ = c − (n·c − d)·n/‖n‖²   (the centre's projection: rational)
/// depth  = r − s
/// ```
///
/// This is the lecture's `p = M − (r − x)·n` read with `p` on `b`'s surface (the
/// plane), as the fixture convention asks. A centre inside the solid gives
/// `depth > r`: the half-space is solid, not a thin sheet. Source: the lecture;
/// Ericson §5.2.2 (sphere against plane, with `n` not assumed unit here).
///
/// **Degenerate input.** None for valid input (`n ≠ 0`); a zero normal is refused
/// with [`RefereeError::ZeroNormal`], as the fixture format refuses it.
pub fn contact_sphere_plane(a: &Sphere, b: &Plane) -> Result<ContactAnswer, RefereeError> {
    if let Some(contact) = staged(|| super::contact_fast::sphere_plane(a, b)) {
        return Ok(ContactAnswer { contact, degenerate: false });
    }
    let sp = sphere_plane(a, b, ["a.center", "a.radius"], ["b.normal", "b.offset"])?;
    if !sp.touches() {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    let nn = sp.root.square();
    let k = &sp.e / nn;
    let point: V3 = [&sp.c[0] - &k * &sp.n[0], &sp.c[1] - &k * &sp.n[1], &sp.c[2] - &k * &sp.n[2]];
    Ok(ContactAnswer {
        contact: Some(Contact { point: round_v(&point), normal: round_unit(&sp.n), depth: sp.depth() }),
        degenerate: false,
    })
}

/// Contact between a plane `a` (`n·x = d`, solid `n·x ≤ d`) and a sphere `b`: the
/// reverse order of [`contact_sphere_plane`].
///
/// **Definition.** Same decision and depth `r − s`; the normal now points from
/// the sphere toward the plane's solid, `−n/‖n‖`, and the point lies on the
/// sphere's surface: its deepest point into the solid,
/// `c + r·(−n/‖n‖) = c − r·n/‖n‖`.
///
/// **Degenerate input.** As [`contact_sphere_plane`].
pub fn contact_plane_sphere(a: &Plane, b: &Sphere) -> Result<ContactAnswer, RefereeError> {
    if let Some(contact) = staged(|| super::contact_fast::plane_sphere(a, b)) {
        return Ok(ContactAnswer { contact, degenerate: false });
    }
    let sp = sphere_plane(b, a, ["b.center", "b.radius"], ["a.normal", "a.offset"])?;
    if !sp.touches() {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    let neg: V3 = [-sp.n[0].clone(), -sp.n[1].clone(), -sp.n[2].clone()];
    Ok(ContactAnswer {
        contact: Some(Contact {
            point: sp.root.round_over_v(&sp.c, &sp.r, &neg),
            normal: round_unit(&neg),
            depth: sp.depth(),
        }),
        degenerate: false,
    })
}

/// The signed depth `r − (n·c − d)/‖n‖` behind the sphere–plane decision (either
/// order), correctly rounded: ≥ 0 exactly when in contact, negative when apart.
pub fn contact_margin_sphere_plane(a: &Sphere, b: &Plane) -> Result<f64, RefereeError> {
    if let Some(margin) = staged(|| super::contact_fast::sphere_plane_margin(a, b)) {
        return Ok(margin);
    }
    Ok(sphere_plane(a, b, ["a.center", "a.radius"], ["b.normal", "b.offset"])?.depth())
}

struct SphereTriangle {
    c: V3,
    r: Q,
    verts: [V3; 3],
    /// The triangle's point closest to `c`.
    q: V3,
    /// `c − q`.
    w: V3,
    root: Root,
}

fn sphere_triangle(
    s: &Sphere,
    t: &Triangle,
    sf: [&'static str; 2],
    tf: &'static str,
) -> Result<SphereTriangle, RefereeError> {
    let c = v3(&s.center, sf[0])?;
    let r = radius(s.radius, sf[1])?;
    let verts = [v3(&t.vertices[0], tf)?, v3(&t.vertices[1], tf)?, v3(&t.vertices[2], tf)?];
    let q = closest_on_triangle(&c, &verts);
    let w = sub(&c, &q);
    let root = Root::new(dot(&w, &w));
    Ok(SphereTriangle { c, r, verts, q, w, root })
}

impl SphereTriangle {
    fn touches(&self) -> bool {
        self.root.square() <= &(&self.r * &self.r)
    }

    /// The unit normal from the triangle toward the centre, exact before
    /// normalization, and whether it is a fallback.
    fn direction(&self) -> (V3, bool) {
        if !self.root.square().is_zero() {
            return (self.w.clone(), false);
        }
        let [v0, v1, v2] = &self.verts;
        let face = cross(&sub(v1, v0), &sub(v2, v0));
        if is_zero(&face) { (fallback_normal(), true) } else { (face, true) }
    }

    fn depth(&self) -> f64 {
        self.root.round_affine(&self.r, &Q::NEG_ONE)
    }

    /// The forward-order answer: the contact at `q` when touching, else none.
    fn answer(&self) -> ContactAnswer {
        if !self.touches() {
            return ContactAnswer { contact: None, degenerate: false };
        }
        let (dir, degenerate) = self.direction();
        ContactAnswer {
            contact: Some(Contact { point: round_v(&self.q), normal: round_unit(&dir), depth: self.depth() }),
            degenerate,
        }
    }
}

/// Contact between a sphere `a` (centre `c`, radius `r`) and a triangle `b`.
///
/// **Definition.** The triangle is a solid two-sided sheet. Its point closest to
/// the centre, `q`, is found exactly (Ericson's closest-point-on-triangle, §5.1.5,
/// every region test in rationals). Then, as for two spheres with `b` shrunk to
/// `q`:
///
/// ```text
/// contact ⇔ ‖c − q‖² ≤ r²,  normal = (c − q)/‖c − q‖,  point = q,  depth = r − ‖c − q‖
/// ```
///
/// **Degenerate input.** A centre exactly on the triangle (`q = c`) has no
/// direction: normal = the face normal `(v1 − v0) × (v2 − v0)` normalized,
/// point `c`, depth `r`, `degenerate: true`; when the triangle has zero area as
/// well, the normal is [`CONCENTRIC_FALLBACK_NORMAL`]. A zero-area triangle whose
/// segment or point does not contain the centre is answered exactly as that
/// segment or point (its closest point), with `degenerate: false`: the answer is
/// fully defined.
pub fn contact_sphere_triangle(a: &Sphere, b: &Triangle) -> Result<ContactAnswer, RefereeError> {
    if let Some(contact) = staged(|| super::contact_fast::sphere_triangle(a, b)) {
        return Ok(ContactAnswer { contact, degenerate: false });
    }
    Ok(sphere_triangle(a, b, ["a.center", "a.radius"], "b.vertices")?.answer())
}

/// Contact between a triangle `a` and a sphere `b` (centre `c`, radius `r`): the
/// reverse order of [`contact_sphere_triangle`].
///
/// **Definition.** With `m = (c − q)/‖c − q‖` the forward normal, the normal now
/// points from the sphere toward the triangle, `−m`, and the point lies on the
/// sphere's surface: its deepest point, `c + r·(−m) = c − r·m`. The decision and
/// depth are those of the forward order.
///
/// **Degenerate input.** As [`contact_sphere_triangle`], with `m` the fallback:
/// normal `−m` (minus the face normal, or `(0, 0, −1)` for a zero-area triangle),
/// point `c − r·m`, depth `r`, `degenerate: true`.
pub fn contact_triangle_sphere(a: &Triangle, b: &Sphere) -> Result<ContactAnswer, RefereeError> {
    if let Some(contact) = staged(|| super::contact_fast::triangle_sphere(a, b)) {
        return Ok(ContactAnswer { contact, degenerate: false });
    }
    let st = sphere_triangle(b, a, ["b.center", "b.radius"], "a.vertices")?;
    if !st.touches() {
        return Ok(ContactAnswer { contact: None, degenerate: false });
    }
    let (dir, degenerate) = st.direction();
    let neg: V3 = [-dir[0].clone(), -dir[1].clone(), -dir[2].clone()];
    let unit = Root::new(dot(&neg, &neg));
    Ok(ContactAnswer {
        contact: Some(Contact {
            point: unit.round_over_v(&st.c, &st.r, &neg),
            normal: round_unit(&neg),
            depth: st.depth(),
        }),
        degenerate,
    })
}

/// The signed depth `r − ‖c − q‖` behind the sphere–triangle decision (either
/// order), correctly rounded: ≥ 0 exactly when in contact, negative when apart.
pub fn contact_margin_sphere_triangle(a: &Sphere, b: &Triangle) -> Result<f64, RefereeError> {
    if let Some(margin) = staged(|| super::contact_fast::sphere_triangle_margin(a, b)) {
        return Ok(margin);
    }
    Ok(sphere_triangle(a, b, ["a.center", "a.radius"], "b.vertices")?.depth())
}

/// The face of a mesh nearest the sphere's centre (smallest exact squared
/// distance, the lowest index on ties), as a [`SphereTriangle`], and its index.
/// `None` for an empty mesh. A face naming a vertex out of range is refused.
fn nearest_face(
    a: &Sphere,
    vertices: &[P3],
    triangles: &[[usize; 3]],
) -> Result<Option<(usize, SphereTriangle)>, RefereeError> {
    let mut best: Option<(usize, SphereTriangle)> = None;
    for (face, tri) in triangles.iter().enumerate() {
        if tri.iter().any(|&i| i >= vertices.len()) {
            return Err(RefereeError::IndexOutOfRange { field: "b.triangles", face });
        }
        let t = Triangle { vertices: [vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]] };
        let st = sphere_triangle(a, &t, ["a.center", "a.radius"], "b.vertices")?;
        if best.as_ref().is_none_or(|(_, b)| st.root.square() < b.root.square()) {
            best = Some((face, st));
        }
    }
    Ok(best)
}

/// Contact between a sphere `a` and a triangle mesh `b` (`vertices`,
/// `triangles` as 0-based index triples).
///
/// **Definition.** Each face is a two-sided sheet, as in
/// [`contact_sphere_triangle`]. The mesh's contact is the contact with the face
/// nearest the centre — the smallest exact distance `‖c − q‖`, which is the
/// deepest contact — and on a tie (a closest point on an edge or vertex that
/// faces share) the lowest face index. Apart from every face: no contact.
///
/// **Degenerate input.** As [`contact_sphere_triangle`] for the nearest face (a
/// centre exactly on the mesh: that face's normal as fallback, depth `r`,
/// `degenerate: true`). An empty mesh touches nothing. A face naming a vertex
/// out of range is refused with [`RefereeError::IndexOutOfRange`].
pub fn contact_sphere_mesh(
    a: &Sphere,
    vertices: &[P3],
    triangles: &[[usize; 3]],
) -> Result<ContactAnswer, RefereeError> {
    if let Some(contact) = staged(|| super::contact_fast::sphere_mesh(a, vertices, triangles)) {
        return Ok(ContactAnswer { contact, degenerate: false });
    }
    Ok(match nearest_face(a, vertices, triangles)? {
        Some((_, st)) => st.answer(),
        None => ContactAnswer { contact: None, degenerate: false },
    })
}

/// The signed depth `r − min ‖c − q‖` over the faces behind the sphere–mesh
/// decision, correctly rounded: ≥ 0 exactly when in contact. An empty mesh has
/// no margin (an error: nothing to decide).
pub fn contact_margin_sphere_mesh(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Result<f64, RefereeError> {
    if let Some(margin) = staged(|| super::contact_fast::sphere_mesh_margin(a, vertices, triangles)) {
        return Ok(margin);
    }
    match nearest_face(a, vertices, triangles)? {
        Some((_, st)) => Ok(st.depth()),
        None => Err(RefereeError::IndexOutOfRange { field: "b.triangles", face: 0 }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    #[test]
    fn referee_contact_sphere_mesh_is_the_nearest_face() {
        // Two faces: the unit square at z = 0 (two triangles sharing the
        // diagonal) and a face at z = 3 far above.
        let vertices = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 3.0],
            [2.0, 0.0, 3.0],
            [0.0, 2.0, 3.0],
        ];
        let faces = [[4, 5, 6], [0, 1, 2], [0, 2, 3]];
        let s = |c: P3, r: f64| Sphere { center: c, radius: r };
        // Above face 2 at height 0.5, radius 1: contact at (0.5, 1.5, 0), depth 0.5, normal +z.
        let k = contact_sphere_mesh(&s([0.5, 1.5, 0.5], 1.0), &vertices, &faces).unwrap();
        let c = k.contact.unwrap();
        close_v(c.point, [0.5, 1.5, 0.0], "point");
        close_v(c.normal, [0.0, 0.0, 1.0], "normal");
        close(c.depth, 0.5, "depth");
        assert!(!k.degenerate);
        // Nearer the top face (distance 0.5 from z = 3): that one, normal −z.
        let k = contact_sphere_mesh(&s([0.25, 0.25, 2.5], 1.0), &vertices, &faces).unwrap();
        close_v(k.contact.unwrap().normal, [0.0, 0.0, -1.0], "top face's normal");
        // Apart from every face; an empty mesh.
        assert!(contact_sphere_mesh(&s([5.0, 5.0, 5.0], 1.0), &vertices, &faces).unwrap().contact.is_none());
        assert!(contact_sphere_mesh(&s([0.0; 3], 1.0), &vertices, &[]).unwrap().contact.is_none());
        // A centre on the shared diagonal: degenerate, the lower face's (1) normal.
        let k = contact_sphere_mesh(&s([1.0, 1.0, 0.0], 0.5), &vertices, &faces).unwrap();
        assert!(k.degenerate);
        close_v(k.contact.unwrap().normal, [0.0, 0.0, 1.0], "face 1's normal");
        // The margin: 0.5 deep above face 2.
        close(contact_margin_sphere_mesh(&s([0.5, 1.5, 0.5], 1.0), &vertices, &faces).unwrap(), 0.5, "margin");
        assert!(contact_sphere_mesh(&s([0.0; 3], 1.0), &vertices, &[[0, 1, 9]]).is_err());
    }

    /// The referee is correctly rounded and the expectations below are either exact
    /// (small dyadic numbers, exact f64 operations) or correctly rounded literals
    /// derived independently: no ulp of slack.
    const EXACT_ULPS: u64 = 0;

    /// Slack for the in-test double-double cross-checks of the literals: a
    /// double-double value is within ~1e-32 of the exact one, so its single final
    /// rounding can differ from the correct rounding by at most 1 ulp.
    const DOUBLE_DOUBLE_ULPS: u64 = 1;

    /// `√2` as an unevaluated sum `hi + lo` (error ~2⁻¹⁰⁶): `hi` is IEEE's correctly
    /// rounded sqrt, and `lo = (2 − hi²)/(2 hi)` with the residual `2 − hi²`
    /// computed exactly by a fused multiply–add (Newton's correction).
    fn sqrt2_dd() -> (f64, f64) {
        let hi = 2f64.sqrt();
        let lo = (-hi).mul_add(hi, 2.0) / (2.0 * hi);
        (hi, lo)
    }

    /// `a − √2` from the double-double; `a − hi` is exact by Sterbenz's lemma for
    /// the values used (`hi/2 ≤ a ≤ 2 hi`).
    fn minus_sqrt2(a: f64) -> f64 {
        let (hi, lo) = sqrt2_dd();
        assert!(hi / 2.0 <= a && a <= 2.0 * hi, "Sterbenz precondition");
        (a - hi) - lo
    }

    /// `1/√2`, correctly rounded: `std::f64::consts::FRAC_1_SQRT_2`, which equals
    /// `float(Decimal(2).sqrt() / 2)` at 60 digits in CPython (its Decimal → float
    /// conversion is correctly rounded), and is cross-checked below.
    const INV_SQRT2: f64 = std::f64::consts::FRAC_1_SQRT_2;
    /// `1.5 − √2`, correctly rounded (same derivation).
    const ONE_HALF_MINUS_SQRT2: f64 = 0.08578643762690495;
    /// `2 − √2`, correctly rounded (same derivation).
    const TWO_MINUS_SQRT2: f64 = 0.585786437626905;
    /// `1 − √2`, correctly rounded (same derivation).
    const ONE_MINUS_SQRT2: f64 = -0.41421356237309503;

    fn close(got: f64, want: f64, what: &str) {
        assert!(within_ulps(got, want, EXACT_ULPS), "{what}: got {got:e}, want {want:e}");
    }

    fn close_v(got: P3, want: P3, what: &str) {
        for k in 0..3 {
            assert!(within_ulps(got[k], want[k], EXACT_ULPS), "{what}[{k}]: got {got:?}, want {want:?}");
        }
    }

    fn sphere(center: P3, radius: f64) -> Sphere {
        Sphere { center, radius }
    }

    fn contact(answer: Result<ContactAnswer, RefereeError>, what: &str) -> (Contact, bool) {
        let a = answer.unwrap_or_else(|e| panic!("{what}: refused: {e}"));
        (a.contact.unwrap_or_else(|| panic!("{what}: expected contact")), a.degenerate)
    }

    #[test]
    fn referee_literals_agree_with_double_double() {
        for (lit, dd, what) in [
            (ONE_HALF_MINUS_SQRT2, minus_sqrt2(1.5), "1.5 − √2"),
            (TWO_MINUS_SQRT2, minus_sqrt2(2.0), "2 − √2"),
            (ONE_MINUS_SQRT2, minus_sqrt2(1.0), "1 − √2"),
            (INV_SQRT2, sqrt2_dd().0 / 2.0 + sqrt2_dd().1 / 2.0, "1/√2 = √2/2"),
        ] {
            assert!(within_ulps(lit, dd, DOUBLE_DOUBLE_ULPS), "{what}: {lit} vs {dd}");
        }
    }

    #[test]
    fn referee_sphere_sphere_overlap() {
        // D = (0, 0, 1.5), ‖D‖ = 1.5: normal +z, point Mb + 1·z, depth 2 − 1.5.
        let (k, deg) = contact(contact_sphere_sphere(&sphere([0.0, 0.0, 1.5], 1.0), &sphere([0.0; 3], 1.0)), "overlap");
        assert!(!deg);
        close_v(k.normal, [0.0, 0.0, 1.0], "normal");
        close_v(k.point, [0.0, 0.0, 1.0], "point");
        close(k.depth, 0.5, "depth");
    }

    #[test]
    fn referee_sphere_sphere_needs_correct_rounding() {
        // a at (1, 1, 0), r 1; b at the origin, r 0.5: ‖D‖ = √2, so
        // normal = (1/√2, 1/√2, 0), point = 0.5·normal = (√2/4, √2/4, 0) (an exact
        // halving of 1/√2), depth = 1.5 − √2.
        let (k, _) = contact(contact_sphere_sphere(&sphere([1.0, 1.0, 0.0], 1.0), &sphere([0.0; 3], 0.5)), "diag");
        close_v(k.normal, [INV_SQRT2, INV_SQRT2, 0.0], "normal");
        close_v(k.point, [INV_SQRT2 / 2.0, INV_SQRT2 / 2.0, 0.0], "point");
        close(k.depth, ONE_HALF_MINUS_SQRT2, "depth");
        // Swapping a and b flips the normal and moves the point to a's surface:
        // (1,1,0) − 1·normal = (1 − 1/√2, 1 − 1/√2, 0); 1 − 1/√2 = (2 − √2)/2.
        let (k, _) = contact(contact_sphere_sphere(&sphere([0.0; 3], 0.5), &sphere([1.0, 1.0, 0.0], 1.0)), "swapped");
        close_v(k.normal, [-INV_SQRT2, -INV_SQRT2, 0.0], "normal");
        close_v(k.point, [TWO_MINUS_SQRT2 / 2.0, TWO_MINUS_SQRT2 / 2.0, 0.0], "point");
        close(k.depth, ONE_HALF_MINUS_SQRT2, "depth");
    }

    #[test]
    fn referee_sphere_sphere_touching_is_contact_one_ulp_apart_is_not() {
        // Centres 2 apart, radii 1 + 1: depth exactly 0, contact.
        let b = sphere([0.0; 3], 1.0);
        let (k, _) = contact(contact_sphere_sphere(&sphere([0.0, 0.0, 2.0], 1.0), &b), "touching");
        close(k.depth, 0.0, "depth");
        close_v(k.point, [0.0, 0.0, 1.0], "point");
        // One ulp further (2 + 2⁻⁵¹): apart, and the margin is minus that gap.
        let far = f64::from_bits(2f64.to_bits() + 1);
        let a = sphere([0.0, 0.0, far], 1.0);
        assert_eq!(contact_sphere_sphere(&a, &b).unwrap().contact, None);
        close(contact_margin_sphere_sphere(&a, &b).unwrap(), -(far - 2.0), "margin");
    }

    #[test]
    fn referee_sphere_sphere_concentric_is_degenerate() {
        // D = 0: fallback normal +z, point Mb + rb·z = (1, 2, 3 + 0.5), depth 1 + 0.5.
        let (k, deg) =
            contact(contact_sphere_sphere(&sphere([1.0, 2.0, 3.0], 1.0), &sphere([1.0, 2.0, 3.0], 0.5)), "concentric");
        assert!(deg);
        close_v(k.normal, CONCENTRIC_FALLBACK_NORMAL, "normal");
        close_v(k.point, [1.0, 2.0, 3.5], "point");
        close(k.depth, 1.5, "depth");
    }

    #[test]
    fn referee_sphere_sphere_huge_and_tiny_scales() {
        // Centres 3s apart, radii 2s each: depth 4s − 3s, normal +z, point (0,0,2s).
        // For s = 1e300 the naive ‖D‖² overflows; for 1e-300 it underflows. The
        // expected depth 2·(2s) − 3s is exact in f64 (doubling, then Sterbenz).
        for s in [1e300, 1e-300] {
            let (r, d) = (2.0 * s, 3.0 * s);
            let (k, _) = contact(contact_sphere_sphere(&sphere([0.0, 0.0, d], r), &sphere([0.0; 3], r)), "scaled");
            close_v(k.normal, [0.0, 0.0, 1.0], "normal");
            close_v(k.point, [0.0, 0.0, r], "point");
            close(k.depth, 2.0 * r - d, "depth");
        }
    }

    #[test]
    fn referee_sphere_plane_sunk_ball() {
        // The fixture format's example: centre (0,0,0.5), r 1, ground z = 0:
        // s = 0.5, point (0,0,0), normal +z, depth 0.5. A normal of length 2 is the
        // same plane (s = (2·0.5 − 0)/2).
        for n in [[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]] {
            let p = Plane { normal: n, offset: 0.0 };
            let (k, deg) = contact(contact_sphere_plane(&sphere([0.0, 0.0, 0.5], 1.0), &p), "sunk");
            assert!(!deg);
            close_v(k.point, [0.0; 3], "point");
            close_v(k.normal, [0.0, 0.0, 1.0], "normal");
            close(k.depth, 0.5, "depth");
        }
    }

    #[test]
    fn referee_sphere_plane_touching_apart_and_inside() {
        let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
        // s = r = 1: depth exactly 0 is contact.
        let (k, _) = contact(contact_sphere_plane(&sphere([0.0, 0.0, 1.0], 1.0), &ground), "touching");
        close(k.depth, 0.0, "depth");
        // One ulp higher: apart by 2⁻⁵², which is the margin's magnitude.
        let up = f64::from_bits(1f64.to_bits() + 1);
        let a = sphere([0.0, 0.0, up], 1.0);
        assert_eq!(contact_sphere_plane(&a, &ground).unwrap().contact, None);
        close(contact_margin_sphere_plane(&a, &ground).unwrap(), -f64::EPSILON, "margin");
        // Centre 3 deep in the solid: s = −3, depth r − s = 4, point above it.
        let (k, _) = contact(contact_sphere_plane(&sphere([5.0, 6.0, -3.0], 1.0), &ground), "inside");
        close(k.depth, 4.0, "depth");
        close_v(k.point, [5.0, 6.0, 0.0], "point");
    }

    #[test]
    fn referee_sphere_plane_tilted_both_orders() {
        // Plane x + y = 0 (n = (1,1,0)), centre (1,1,0), r 2: s = 2/√2 = √2,
        // depth 2 − √2, normal (1/√2, 1/√2, 0), point c − (n·c)n/‖n‖² = (0,0,0).
        let p = Plane { normal: [1.0, 1.0, 0.0], offset: 0.0 };
        let s = sphere([1.0, 1.0, 0.0], 2.0);
        let (k, _) = contact(contact_sphere_plane(&s, &p), "sphere-plane");
        close_v(k.point, [0.0; 3], "point");
        close_v(k.normal, [INV_SQRT2, INV_SQRT2, 0.0], "normal");
        close(k.depth, TWO_MINUS_SQRT2, "depth");
        // Reverse: normal −n̂, point c − r n̂ = (1 − √2, 1 − √2, 0), same depth.
        let (k, _) = contact(contact_plane_sphere(&p, &s), "plane-sphere");
        close_v(k.normal, [-INV_SQRT2, -INV_SQRT2, 0.0], "normal");
        close_v(k.point, [ONE_MINUS_SQRT2, ONE_MINUS_SQRT2, 0.0], "point");
        close(k.depth, TWO_MINUS_SQRT2, "depth");
    }

    #[test]
    fn referee_sphere_plane_refuses_zero_normal_and_nan() {
        let zero = Plane { normal: [0.0; 3], offset: 1.0 };
        assert_eq!(
            contact_sphere_plane(&sphere([0.0; 3], 1.0), &zero),
            Err(RefereeError::ZeroNormal { field: "b.normal" })
        );
        assert_eq!(
            contact_plane_sphere(&zero, &sphere([0.0; 3], 1.0)),
            Err(RefereeError::ZeroNormal { field: "a.normal" })
        );
        let ground = Plane { normal: [0.0, 0.0, 1.0], offset: 0.0 };
        assert_eq!(
            contact_sphere_plane(&sphere([0.0, f64::NAN, 0.0], 1.0), &ground),
            Err(RefereeError::NonFinite { field: "a.center" })
        );
        assert_eq!(
            contact_sphere_sphere(&sphere([0.0; 3], 1.0), &sphere([0.0; 3], -1.0)),
            Err(RefereeError::NegativeRadius { field: "b.radius" })
        );
    }

    fn tri() -> Triangle {
        // Right triangle in z = 0, legs 2 on x and y; face normal +z.
        Triangle { vertices: [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]] }
    }

    #[test]
    fn referee_sphere_triangle_regions() {
        // (centre, r, point q, normal, depth) by hand: face, edge, vertex, below.
        let cases = [
            ([0.5, 0.5, 0.75], 1.0, [0.5, 0.5, 0.0], [0.0, 0.0, 1.0], 0.25, "face"),
            ([1.0, -1.0, 0.0], 2.0, [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], 1.0, "edge v0v1"),
            ([0.5, 0.5, -0.75], 1.0, [0.5, 0.5, 0.0], [0.0, 0.0, -1.0], 0.25, "below: two-sided"),
            ([3.0, 0.0, 0.0], 1.0, [2.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.0, "touching vertex v1"),
            // Centre (−1,−1,0), q = v0, ‖c − q‖ = √2: depth 2 − √2.
            ([-1.0, -1.0, 0.0], 2.0, [0.0; 3], [-INV_SQRT2, -INV_SQRT2, 0.0], TWO_MINUS_SQRT2, "vertex v0"),
        ];
        for (c, r, q, n, depth, what) in cases {
            let (k, deg) = contact(contact_sphere_triangle(&sphere(c, r), &tri()), what);
            assert!(!deg, "{what}");
            close_v(k.point, q, what);
            close_v(k.normal, n, what);
            close(k.depth, depth, what);
        }
        // One ulp past touching: apart.
        let past = f64::from_bits(3f64.to_bits() + 1);
        let a = sphere([past, 0.0, 0.0], 1.0);
        assert_eq!(contact_sphere_triangle(&a, &tri()).unwrap().contact, None);
        close(contact_margin_sphere_triangle(&a, &tri()).unwrap(), -(past - 3.0), "margin");
    }

    #[test]
    fn referee_sphere_triangle_centre_on_face_is_degenerate() {
        // q = c: normal = face normal (+z; −z for the reversed winding), depth r.
        let (k, deg) = contact(contact_sphere_triangle(&sphere([0.5, 0.5, 0.0], 1.0), &tri()), "on face");
        assert!(deg);
        close_v(k.normal, [0.0, 0.0, 1.0], "normal");
        close_v(k.point, [0.5, 0.5, 0.0], "point");
        close(k.depth, 1.0, "depth");
        let cw = Triangle { vertices: [[0.0, 0.0, 0.0], [0.0, 2.0, 0.0], [2.0, 0.0, 0.0]] };
        let (k, _) = contact(contact_sphere_triangle(&sphere([0.5, 0.5, 0.0], 1.0), &cw), "on cw face");
        close_v(k.normal, [0.0, 0.0, -1.0], "normal");
    }

    #[test]
    fn referee_sphere_triangle_zero_area() {
        // Collinear vertices spanning x ∈ [0, 4]. Centre (1,3,0), r 5: q = (1,0,0),
        // normal +y, depth 2, fully defined (not degenerate).
        let flat = Triangle { vertices: [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [2.0, 0.0, 0.0]] };
        let (k, deg) = contact(contact_sphere_triangle(&sphere([1.0, 3.0, 0.0], 5.0), &flat), "off");
        assert!(!deg);
        close_v(k.point, [1.0, 0.0, 0.0], "point");
        close_v(k.normal, [0.0, 1.0, 0.0], "normal");
        close(k.depth, 2.0, "depth");
        // Centre on the segment: no face normal either, fallback +z, depth r.
        let (k, deg) = contact(contact_sphere_triangle(&sphere([1.0, 0.0, 0.0], 1.0), &flat), "on");
        assert!(deg);
        close_v(k.normal, CONCENTRIC_FALLBACK_NORMAL, "normal");
        close(k.depth, 1.0, "depth");
    }

    #[test]
    fn referee_triangle_sphere_reverse_order() {
        // Face case seen from the triangle: normal −z, point c − r·(+z) =
        // (0.5, 0.5, 0.75 − 1), depth 0.25.
        let (k, deg) = contact(contact_triangle_sphere(&tri(), &sphere([0.5, 0.5, 0.75], 1.0)), "face");
        assert!(!deg);
        close_v(k.normal, [0.0, 0.0, -1.0], "normal");
        close_v(k.point, [0.5, 0.5, -0.25], "point");
        close(k.depth, 0.25, "depth");
        // Vertex case: normal (1/√2, 1/√2, 0), point c + 2·normal = (−1 + √2, …).
        let (k, _) = contact(contact_triangle_sphere(&tri(), &sphere([-1.0, -1.0, 0.0], 2.0)), "vertex");
        close_v(k.normal, [INV_SQRT2, INV_SQRT2, 0.0], "normal");
        close_v(k.point, [-ONE_MINUS_SQRT2, -ONE_MINUS_SQRT2, 0.0], "point");
        close(k.depth, TWO_MINUS_SQRT2, "depth");
        // Degenerate: centre on the face, normal −face normal, point c − r·(+z).
        let (k, deg) = contact(contact_triangle_sphere(&tri(), &sphere([0.5, 0.5, 0.0], 1.0)), "on face");
        assert!(deg);
        close_v(k.normal, [0.0, 0.0, -1.0], "normal");
        close_v(k.point, [0.5, 0.5, -1.0], "point");
        close(k.depth, 1.0, "depth");
    }

    #[test]
    fn referee_sphere_triangle_huge_and_tiny() {
        // The face case scaled by s = 2^±1000 (exact scalings): q = (s/2, s/2, 0),
        // depth s/4, normal +z.
        for s in [2f64.powi(1000), 2f64.powi(-1000)] {
            let t = Triangle { vertices: [[0.0; 3], [2.0 * s, 0.0, 0.0], [0.0, 2.0 * s, 0.0]] };
            let (k, _) = contact(contact_sphere_triangle(&sphere([0.5 * s, 0.5 * s, 0.75 * s], s), &t), "scaled");
            close_v(k.point, [0.5 * s, 0.5 * s, 0.0], "point");
            close_v(k.normal, [0.0, 0.0, 1.0], "normal");
            close(k.depth, 0.25 * s, "depth");
        }
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::referee::exact::ulps;
    use crashtest_core::vec3::neg;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        // Small integers make touching, concentric and on-the-face cases common.
        prop_oneof![(-3i8..=3).prop_map(f64::from), -4.0..4.0f64]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    fn radius() -> impl Strategy<Value = f64> {
        prop_oneof![(0u8..=3).prop_map(f64::from), 0.0..4.0f64]
    }

    /// Component-wise ulp distances (`+0` and `−0` are 0 apart: an exact zero
    /// rounds to `+0`, and negating it gives `−0`).
    fn apart(x: P3, y: P3) -> [u64; 3] {
        [ulps(x[0], y[0]), ulps(x[1], y[1]), ulps(x[2], y[2])]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn referee_sphere_sphere_swap_flips_the_normal_exactly(ca in point(), ra in radius(), cb in point(), rb in radius()) {
            // Rounding is symmetric (round(−x) = −round(x)), so the swapped answer's
            // normal is bitwise the negation, and the depth is bitwise the same.
            let (a, b) = (Sphere { center: ca, radius: ra }, Sphere { center: cb, radius: rb });
            let ab = contact_sphere_sphere(&a, &b).unwrap();
            let ba = contact_sphere_sphere(&b, &a).unwrap();
            prop_assert_eq!(ab.contact.is_some(), ba.contact.is_some(), "same decision");
            if let (Some(x), Some(y), false) = (ab.contact, ba.contact, ab.degenerate) {
                prop_assert_eq!(apart(x.normal, neg(y.normal)), [0; 3], "normals opposite");
                prop_assert_eq!(x.depth.to_bits(), y.depth.to_bits(), "same depth");
            }
        }

        #[test]
        fn referee_contact_margin_sign_is_the_decision(c in point(), r in radius(), other in point(), r2 in radius(), n in point(), d in coord(), v1 in point(), v2 in point()) {
            // A zero margin is +0.0 (touching); an apart pair closer than the least
            // subnormal rounds to −0.0. So the sign bit carries the decision.
            let a = Sphere { center: c, radius: r };
            let b = Sphere { center: other, radius: r2 };
            let m = contact_margin_sphere_sphere(&a, &b).unwrap();
            prop_assert_eq!(contact_sphere_sphere(&a, &b).unwrap().contact.is_some(), !m.is_sign_negative(), "sphere margin {}", m);
            if n.iter().any(|x| x.abs() > 0.0) {
                let p = Plane { normal: n, offset: d };
                let m = contact_margin_sphere_plane(&a, &p).unwrap();
                prop_assert_eq!(contact_sphere_plane(&a, &p).unwrap().contact.is_some(), !m.is_sign_negative(), "plane margin {}", m);
                prop_assert_eq!(contact_plane_sphere(&p, &a).unwrap().contact.is_some(), !m.is_sign_negative(), "plane margin, reversed");
            }
            let t = Triangle { vertices: [other, v1, v2] };
            let m = contact_margin_sphere_triangle(&a, &t).unwrap();
            prop_assert_eq!(contact_sphere_triangle(&a, &t).unwrap().contact.is_some(), !m.is_sign_negative(), "triangle margin {}", m);
        }

        #[test]
        fn referee_sphere_triangle_ignores_which_vertex_comes_first(c in point(), r in radius(), v0 in point(), v1 in point(), v2 in point()) {
            // The closest point is unique and a cyclic relabelling keeps the face
            // normal: the answers must be bitwise equal.
            let a = Sphere { center: c, radius: r };
            let x = contact_sphere_triangle(&a, &Triangle { vertices: [v0, v1, v2] }).unwrap();
            let y = contact_sphere_triangle(&a, &Triangle { vertices: [v1, v2, v0] }).unwrap();
            prop_assert_eq!(x, y);
        }

        #[test]
        fn referee_triangle_sphere_is_the_swapped_contact(c in point(), r in radius(), v0 in point(), v1 in point(), v2 in point()) {
            // Reverse order: the same decision and flag, the normal negated (bitwise,
            // up to the sign of zero), and the same depth.
            let a = Sphere { center: c, radius: r };
            let t = Triangle { vertices: [v0, v1, v2] };
            let x = contact_sphere_triangle(&a, &t).unwrap();
            let y = contact_triangle_sphere(&t, &a).unwrap();
            prop_assert_eq!(x.degenerate, y.degenerate);
            prop_assert_eq!(x.contact.is_some(), y.contact.is_some());
            if let (Some(x), Some(y)) = (x.contact, y.contact) {
                prop_assert_eq!(apart(x.normal, neg(y.normal)), [0; 3], "normals opposite");
                prop_assert_eq!(x.depth.to_bits(), y.depth.to_bits(), "same depth");
            }
        }
    }
}
