//! The floating-point stage of contact between a sphere and a sphere, a
//! plane, a triangle or a mesh ([`super::fast`]): the exact stage's formulas
//! in double-word numbers that account for their error, each output kept only
//! when its correct rounding is certified, each decision (contact, a
//! triangle's region, a mesh's nearest face) only on certified signs.
//!
//! Every output is `x = A + B/√S` for double-words `A`, `B` and a sum of
//! squares `S > 0` (or a quotient, for the sphere–plane point). Its rounding is
//! certified by [`certify`]: for a midpoint `m` around a candidate, the sign of
//! `x − m` is that of `P + Q·√S` with `P`, `Q` exact or bounded double-words
//! ([`sign_affine_root`]); an output exactly 0 (a touching depth) is proved
//! so and is `+0.0`. A function here returns `None` whenever anything is left
//! open — concentric spheres or a centre exactly on a triangle, a zero-area
//! triangle, two mesh faces whose distances the bounds cannot order, an
//! output on a midpoint or beyond `MAX`, a sign the bounds leave open, an
//! input that is not a finite number, or input the exact stage refuses — and the exact stage then
//! answers, with the same bits by construction and by test
//! (`tests/referee_stages.rs`).

use super::fast::{Dw, all_finite, certify, cross, diff3, div_approx, dot, quotient, sign_affine_root, sqrt_approx};
use crate::geom::{Contact, P3, Plane, Sphere, Triangle};

/// `A + (u·Δ)/√S` correctly rounded, for an exact input `a`, `u` and an
/// exact or bounded `Δ`; `a + 0` (a `−0` input made `+0`, as the exact
/// stage's rounding of the rational zero) when `u·Δ` is exactly zero.
fn over_root(a: f64, u: f64, delta: Dw, s: Dw, root: Dw) -> Option<f64> {
    let p = Dw::of(u).mul(delta);
    if p.is_exact_zero() {
        return Some(a + 0.0);
    }
    // x − m = ((a − m)·√S + u·Δ)/√S.
    let candidate = Dw::of(a).add(div_approx(p, root)).approx();
    certify(candidate, |m| sign_affine_root(p, Dw::of(a).sub(m), s))
}

/// `c − √S` (the sphere–sphere depth and margin `ra + rb − ‖Δ‖`), correctly
/// rounded (`+0.0` when touching exactly); `None` when left open.
pub(super) fn minus_root(c: Dw, s: Dw, root: Dw) -> Option<f64> {
    // x − m = (c − m) − √S.
    certify(c.sub(root).approx(), |m| sign_affine_root(c.sub(m), Dw::of(-1.0), s))
}

/// The two spheres' centre difference `Δ = Ma − Mb`, `S = Δ·Δ` and the radii's
/// sum, or `None` for input outside the stage (a radius that is not `≥ 0`,
/// a number that is not finite: [`all_finite`]).
fn spheres(a: &Sphere, b: &Sphere) -> Option<([Dw; 3], Dw, Dw)> {
    let numbers = a.center.iter().chain(&b.center).copied().chain([a.radius, b.radius]);
    if !(a.radius >= 0.0 && b.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let delta = diff3(&a.center, &b.center);
    Some((delta, dot(&delta, &delta), Dw::diff(a.radius, -b.radius)))
}

/// Sphere–sphere contact: `Some(None)` certified apart, `Some(Some(c))`
/// certified in contact with every output certified, `None` for the exact
/// stage.
pub(super) fn sphere_sphere(a: &Sphere, b: &Sphere) -> Option<Option<Contact>> {
    let (delta, s, sum) = spheres(a, b)?;
    // contact ⇔ Δ·Δ ≤ (ra + rb)².
    if sum.mul(sum).sub(s).signum()? < 0 {
        return Some(None);
    }
    if !s.is_positive() {
        return None;
    }
    let root = sqrt_approx(s);
    let normal = unit(&delta, s, root)?;
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = over_root(b.center[i], b.radius, delta[i], s, root)?;
    }
    Some(Some(Contact { point, normal, depth: minus_root(sum, s, root)? }))
}

/// `ra + rb − ‖Ma − Mb‖`, correctly rounded, or `None` for the exact stage.
pub(super) fn sphere_sphere_margin(a: &Sphere, b: &Sphere) -> Option<f64> {
    let (_, s, sum) = spheres(a, b)?;
    if s.is_exact_zero() {
        // ra + rb, rounded once by IEEE addition (+0 for 0 + 0); a sum beyond
        // MAX is the exact stage's.
        let sum = a.radius + b.radius;
        return sum.is_finite().then_some(sum + 0.0);
    }
    minus_root(sum, s, sqrt_approx(s))
}

/// `v / ‖v‖` componentwise (`S = v·v > 0`), each correctly rounded; an exactly
/// zero component is `+0`.
pub(super) fn unit(v: &[Dw; 3], s: Dw, root: Dw) -> Option<P3> {
    let mut out = [0.0; 3];
    for (o, &x) in out.iter_mut().zip(v) {
        *o = if x.is_exact_zero() {
            0.0
        } else {
            // x − m = (v − m·√S)/√S.
            certify(div_approx(x, root).approx(), |m| sign_affine_root(x, m.neg(), s))?
        };
    }
    Some(out)
}

/// A sphere and a plane: `e = n·c − d`, `S = n·n`, or `None` for input outside
/// the stage (including a zero normal, which the exact stage refuses).
fn sphere_plane_parts(s: &Sphere, p: &Plane) -> Option<([Dw; 3], Dw, Dw)> {
    let numbers = s.center.iter().chain(&p.normal).copied().chain([s.radius, p.offset]);
    if !(s.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let n = p.normal.map(Dw::of);
    let c = s.center.map(Dw::of);
    let nn = dot(&n, &n);
    if !nn.is_positive() {
        return None;
    }
    Some((n, nn, dot(&n, &c).sub(Dw::of(p.offset))))
}

/// `r − e/√S` (the sphere–plane depth and margin), correctly rounded, or
/// `None` for the exact stage.
pub(super) fn plane_depth(r: f64, e: Dw, nn: Dw, root: Dw) -> Option<f64> {
    if e.is_exact_zero() {
        return Some(r + 0.0);
    }
    // x − m = ((r − m)·√S − e)/√S.
    certify(Dw::of(r).sub(div_approx(e, root)).approx(), |m| sign_affine_root(e.neg(), Dw::of(r).sub(m), nn))
}

/// Whether the sphere reaches the plane's solid: `e ≤ 0`, or `e² ≤ r²·S`
/// (`None` when the bounds leave it open).
fn touches(r: f64, e: Dw, nn: Dw) -> Option<bool> {
    if e.signum()? <= 0 {
        return Some(true);
    }
    let r = Dw::of(r);
    Some(r.mul(r).mul(nn).sub(e.mul(e)).signum()? >= 0)
}

/// Sphere `a` against plane `b`, as [`sphere_sphere`] answers.
pub(super) fn sphere_plane(a: &Sphere, b: &Plane) -> Option<Option<Contact>> {
    let (n, nn, e) = sphere_plane_parts(a, b)?;
    if !touches(a.radius, e, nn)? {
        return Some(None);
    }
    let root = sqrt_approx(nn);
    // point = c − e·n/S = (c·S − e·n)/S, rational.
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = quotient(Dw::of(a.center[i]).mul(nn).sub(e.mul(n[i])), nn)?;
    }
    Some(Some(Contact { point, normal: unit(&n, nn, root)?, depth: plane_depth(a.radius, e, nn, root)? }))
}

/// Plane `a` against sphere `b`: the normal is `−n/‖n‖` and the point
/// `c − r·n/‖n‖`, on the sphere.
pub(super) fn plane_sphere(a: &Plane, b: &Sphere) -> Option<Option<Contact>> {
    let (n, nn, e) = sphere_plane_parts(b, a)?;
    if !touches(b.radius, e, nn)? {
        return Some(None);
    }
    let root = sqrt_approx(nn);
    let neg = n.map(Dw::neg);
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = over_root(b.center[i], b.radius, neg[i], nn, root)?;
    }
    Some(Some(Contact { point, normal: unit(&neg, nn, root)?, depth: plane_depth(b.radius, e, nn, root)? }))
}

/// The sphere–plane margin `r − (n·c − d)/‖n‖`, correctly rounded, or `None`.
pub(super) fn sphere_plane_margin(a: &Sphere, b: &Plane) -> Option<f64> {
    let (_, nn, e) = sphere_plane_parts(a, b)?;
    plane_depth(a.radius, e, nn, sqrt_approx(nn))
}

/// Where the centre's closest point on a triangle lies, with what the outputs
/// need, all exact or bounded double-words.
pub(super) enum Near {
    /// On a vertex or an edge: the closest point is `qn / l` (`l > 0`: 1 on a
    /// vertex, the edge's squared length on an edge), and `w = c − q = wv / l`
    /// with `ww = wv·wv`.
    Feature { qn: [Dw; 3], l: Dw, wv: [Dw; 3], ww: Dw },
    /// Inside the face: `e = N·(c − v0)` with `N = (v1 − v0) × (v2 − v0)`,
    /// `nn = N·N`. Then `c − q = (e/nn)·N`: its direction is `sign(e)·N`, its
    /// length `|e|/√nn`, and `q = (c·nn − e·N)/nn`.
    Face { n: [Dw; 3], nn: Dw, e: Dw },
}

/// The exact stage's region tests (Ericson §5.1.5, as `closest_on_triangle`)
/// decided on certified signs; `None` when a sign is open, for a zero-area
/// triangle, or for a centre exactly on the triangle (no direction).
fn near(p: &P3, v: &[P3; 3]) -> Option<Near> {
    near_by(|x| diff3(p, x), v)
}

/// [`near`] for a point known by its differences `rel(x) = p − x` from the
/// triangle's vertices (exact or bounded double-words).
pub(super) fn near_by(rel: impl Fn(&P3) -> [Dw; 3], v: &[P3; 3]) -> Option<Near> {
    let s = |x: Dw| x.signum();
    let [a, b, c] = v;
    let (ab, ac) = (diff3(b, a), diff3(c, a));
    let n = cross(&ab, &ac);
    let nn = dot(&n, &n);
    if !nn.is_positive() {
        return None;
    }
    // On a vertex: q = V, w = c − V.
    let vertex = |x: &P3| {
        let wv = rel(x);
        let ww = dot(&wv, &wv);
        Near::Feature { qn: x.map(Dw::of), l: Dw::of(1.0), wv, ww }
    };
    // On the edge from `x` along `e` at `t = d/l`: q = (x·l + d·e)/l, w = ((c − x)·l − d·e)/l.
    let edge = |x: &P3, e: [Dw; 3], d: Dw| {
        let l = dot(&e, &e);
        let xp = rel(x);
        let qn = [0, 1, 2].map(|i| Dw::of(x[i]).mul(l).add(d.mul(e[i])));
        let wv = [0, 1, 2].map(|i| xp[i].mul(l).sub(d.mul(e[i])));
        let ww = dot(&wv, &wv);
        Near::Feature { qn, l, wv, ww }
    };
    let ap = rel(a);
    let (d1, d2) = (dot(&ab, &ap), dot(&ac, &ap));
    if s(d1)? <= 0 && s(d2)? <= 0 {
        return Some(vertex(a));
    }
    let bp = rel(b);
    let (d3, d4) = (dot(&ab, &bp), dot(&ac, &bp));
    if s(d3)? >= 0 && s(d4.sub(d3))? <= 0 {
        return Some(vertex(b));
    }
    let vc = d1.mul(d4).sub(d3.mul(d2));
    if s(vc)? <= 0 && s(d1)? >= 0 && s(d3)? <= 0 {
        return Some(edge(a, ab, d1));
    }
    let cp = rel(c);
    let (d5, d6) = (dot(&ab, &cp), dot(&ac, &cp));
    if s(d6)? >= 0 && s(d5.sub(d6))? <= 0 {
        return Some(vertex(c));
    }
    let vb = d5.mul(d2).sub(d1.mul(d6));
    if s(vb)? <= 0 && s(d2)? >= 0 && s(d6)? <= 0 {
        return Some(edge(a, ac, d2));
    }
    let va = d3.mul(d6).sub(d5.mul(d4));
    let (d43, d56) = (d4.sub(d3), d5.sub(d6));
    if s(va)? <= 0 && s(d43)? >= 0 && s(d56)? >= 0 {
        // d4 − d3 = (c − b)·(p − b).
        return Some(edge(b, diff3(c, b), d43));
    }
    Some(Near::Face { n, nn, e: dot(&n, &ap) })
}

/// The parts of a sphere–triangle answer: the triangle's closest point, the
/// unit direction `m = (c − q)/‖c − q‖` before rounding (a vector and its
/// squared length), the depth `r − ‖c − q‖`'s certified rounding, and whether
/// the sphere touches the triangle.
struct TriangleParts {
    near: Near,
    dir: ([Dw; 3], Dw),
    touches: bool,
}

fn sphere_triangle_parts(s: &Sphere, t: &Triangle) -> Option<TriangleParts> {
    let numbers = s.center.iter().chain(t.vertices.iter().flatten()).copied().chain([s.radius]);
    if !(s.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    parts_of(s, &t.vertices)
}

/// [`sphere_triangle_parts`] for input already checked.
fn parts_of(s: &Sphere, v: &[P3; 3]) -> Option<TriangleParts> {
    let near = near(&s.center, v)?;
    let r = Dw::of(s.radius);
    let (dir, touches) = match &near {
        Near::Feature { l, wv, ww, .. } => {
            if !ww.is_positive() {
                return None;
            }
            // ‖w‖² = ww/l² ≤ r².
            let rl = r.mul(*l);
            ((*wv, *ww), rl.mul(rl).sub(*ww).signum()? >= 0)
        }
        Near::Face { n, nn, e } => {
            let sign = e.signum()?;
            if sign == 0 {
                return None;
            }
            let dir = if sign > 0 { *n } else { n.map(Dw::neg) };
            // (e/nn)²·nn = e²/nn ≤ r².
            ((dir, *nn), r.mul(r).mul(*nn).sub(e.mul(*e)).signum()? >= 0)
        }
    };
    Some(TriangleParts { near, dir, touches })
}

impl TriangleParts {
    /// `‖c − q‖²` as a fraction `(num, den)` with `den > 0`.
    fn dist2(&self) -> (Dw, Dw) {
        match &self.near {
            Near::Feature { l, ww, .. } => (*ww, l.mul(*l)),
            Near::Face { nn, e, .. } => (e.mul(*e), *nn),
        }
    }

    /// Whether this face is certainly nearer than `other` (`Some(false)` for
    /// an exact tie too).
    fn nearer(&self, other: &TriangleParts) -> Option<bool> {
        let ((a, da), (b, db)) = (self.dist2(), other.dist2());
        Some(a.mul(db).sub(b.mul(da)).signum()? < 0)
    }

    /// `r − ‖c − q‖`, correctly rounded (`None`: open, or exactly 0).
    fn depth(&self, r: f64) -> Option<f64> {
        match &self.near {
            // x − m = ((r − m)·l − √ww)/l.
            Near::Feature { l, ww, .. } => {
                let candidate = Dw::of(r).sub(div_approx(sqrt_approx(*ww), *l)).approx();
                certify(candidate, |m| sign_affine_root(Dw::of(r).sub(m).mul(*l), Dw::of(-1.0), *ww))
            }
            // ‖c − q‖ = |e|/√nn.
            Near::Face { nn, e, .. } => {
                let abs_e = if e.signum()? < 0 { e.neg() } else { *e };
                plane_depth(r, abs_e, *nn, sqrt_approx(*nn))
            }
        }
    }

    /// The closest point `q`, each component correctly rounded.
    fn point(&self, c: &P3) -> Option<P3> {
        let mut out = [0.0; 3];
        for i in 0..3 {
            out[i] = match &self.near {
                Near::Feature { qn, l, .. } => quotient(qn[i], *l)?,
                Near::Face { n, nn, e } => quotient(Dw::of(c[i]).mul(*nn).sub(e.mul(n[i])), *nn)?,
            };
        }
        Some(out)
    }
}

/// Sphere `a` against triangle `b`, as [`sphere_sphere`] answers.
pub(super) fn sphere_triangle(a: &Sphere, b: &Triangle) -> Option<Option<Contact>> {
    let parts = sphere_triangle_parts(a, b)?;
    if !parts.touches {
        return Some(None);
    }
    let (dir, dd) = parts.dir;
    let normal = unit(&dir, dd, sqrt_approx(dd))?;
    Some(Some(Contact { point: parts.point(&a.center)?, normal, depth: parts.depth(a.radius)? }))
}

/// Triangle `a` against sphere `b`: normal `−m`, point `c − r·m` on the sphere.
pub(super) fn triangle_sphere(a: &Triangle, b: &Sphere) -> Option<Option<Contact>> {
    let parts = sphere_triangle_parts(b, a)?;
    if !parts.touches {
        return Some(None);
    }
    let (dir, dd) = parts.dir;
    let root = sqrt_approx(dd);
    let neg = dir.map(Dw::neg);
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = over_root(b.center[i], b.radius, neg[i], dd, root)?;
    }
    Some(Some(Contact { point, normal: unit(&neg, dd, root)?, depth: parts.depth(b.radius)? }))
}

/// The sphere–triangle margin `r − ‖c − q‖`, correctly rounded, or `None`.
pub(super) fn sphere_triangle_margin(a: &Sphere, b: &Triangle) -> Option<f64> {
    sphere_triangle_parts(a, b)?.depth(a.radius)
}

/// Whether sphere `a` touches the triangle `v` (its inputs already in the
/// stage's range), or `None` when left open.
pub(super) fn touches_triangle(a: &Sphere, v: &[P3; 3]) -> Option<bool> {
    Some(parts_of(a, v)?.touches)
}

/// The nearest face of a mesh (smallest `‖c − q‖²`, certified against every
/// other face; an exact tie keeps the lowest index, as the exact stage does),
/// or `None` (an empty mesh, an index out of range, any face the stage cannot
/// answer, a comparison left open).
fn nearest(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<TriangleParts> {
    let numbers = a.center.iter().chain(vertices.iter().flatten()).copied().chain([a.radius]);
    if !(a.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let mut best: Option<TriangleParts> = None;
    for tri in triangles {
        let v = [*vertices.get(tri[0])?, *vertices.get(tri[1])?, *vertices.get(tri[2])?];
        let parts = parts_of(a, &v)?;
        let nearer = match &best {
            None => true,
            Some(b) => parts.nearer(b)?,
        };
        if nearer {
            best = Some(parts);
        }
    }
    best
}

/// Sphere `a` against a mesh, as [`sphere_sphere`] answers.
pub(super) fn sphere_mesh(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<Option<Contact>> {
    let parts = nearest(a, vertices, triangles)?;
    if !parts.touches {
        return Some(None);
    }
    let (dir, dd) = parts.dir;
    let normal = unit(&dir, dd, sqrt_approx(dd))?;
    Some(Some(Contact { point: parts.point(&a.center)?, normal, depth: parts.depth(a.radius)? }))
}

/// The sphere–mesh margin `r − min ‖c − q‖`, correctly rounded, or `None`.
pub(super) fn sphere_mesh_margin(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<f64> {
    nearest(a, vertices, triangles)?.depth(a.radius)
}
