//! The floating-point stage of contact between a sphere and a sphere, a
//! plane, a triangle or a mesh ([`super::fast`]): the exact stage's formulas,
//! each output kept only when its correct rounding is certain, each decision
//! (contact, a triangle's region, a mesh's nearest face) only on certain
//! signs.
//!
//! Every function is written over [`Num`] and runs in double-word numbers
//! first. There every output is `x = A + B/√S` for double-words `A`, `B` and a
//! sum of squares `S > 0` (or a quotient, for the sphere–plane point); its
//! rounding is certified by [`certify`]: for a midpoint `m` around a
//! candidate, the sign of `x − m` is that of `P + Q·√S` with `P`, `Q` exact or
//! bounded double-words ([`sign_affine_root`]); an output exactly 0 (a
//! touching depth) is proved so and is `+0.0`. What the double-word bounds
//! leave open (a sign, two mesh faces they cannot order, an output on or near
//! a midpoint, beyond `MAX`) runs again in exact dyadic numbers
//! ([`super::dyadic`]), where every sign is certain, each quotient is rounded
//! from exact integers, and each output with a square root is rounded by the
//! exact stage's own `Root` from those numbers' rationals. A function returns
//! `None` — the exact stage's rationals answer, with the same bits by
//! construction and by test (`tests/referee_stages.rs`) — for concentric
//! spheres, a centre exactly on a triangle and a zero-area triangle (the
//! exact stage's fallbacks), input that is not a finite number and input the
//! exact stage refuses.

use super::dyadic::{self as dy, Dy, Num};
use super::fast::{Dw, all_finite};
use crate::geom::{Contact, P3, Plane, Sphere, Triangle};

/// The two spheres' centre difference `Δ = Ma − Mb`, `S = Δ·Δ` and the radii's
/// sum, or `None` for input outside the stage (a radius that is not `≥ 0`,
/// a number that is not finite: [`all_finite`]).
fn spheres<T: Num>(a: &Sphere, b: &Sphere) -> Option<([T; 3], T, T)> {
    let numbers = a.center.iter().chain(&b.center).copied().chain([a.radius, b.radius]);
    if !(a.radius >= 0.0 && b.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let delta = dy::diff3::<T>(&a.center, &b.center);
    let s = dy::dot(&delta, &delta);
    Some((delta, s, T::diff(a.radius, -b.radius)))
}

fn sphere_sphere_in<T: Num>(a: &Sphere, b: &Sphere) -> Option<Option<Contact>> {
    let (delta, s, sum) = spheres::<T>(a, b)?;
    // contact ⇔ Δ·Δ ≤ (ra + rb)².
    if sum.times(&sum).minus(&s).sign_of()? < 0 {
        return Some(None);
    }
    if !s.positive() {
        return None;
    }
    let normal = T::unit(&delta, &s)?;
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = T::over_root(b.center[i], &T::of(b.radius).times(&delta[i]), &s)?;
    }
    Some(Some(Contact { point, normal, depth: T::minus_root(&sum, &s)? }))
}

/// Sphere–sphere contact: `Some(None)` certified apart, `Some(Some(c))`
/// certified in contact with every output certified, `None` for the exact
/// stage.
pub(super) fn sphere_sphere(a: &Sphere, b: &Sphere) -> Option<Option<Contact>> {
    sphere_sphere_in::<Dw>(a, b).or_else(|| sphere_sphere_in::<Dy>(a, b))
}

fn sphere_sphere_margin_in<T: Num>(a: &Sphere, b: &Sphere) -> Option<f64> {
    let (_, s, sum) = spheres::<T>(a, b)?;
    if s.exact_zero() {
        // ra + rb, rounded once by IEEE addition (+0 for 0 + 0); a sum beyond
        // MAX is the exact stage's.
        let sum = a.radius + b.radius;
        return sum.is_finite().then_some(sum + 0.0);
    }
    T::minus_root(&sum, &s)
}

/// `ra + rb − ‖Ma − Mb‖`, correctly rounded, or `None` for the exact stage.
pub(super) fn sphere_sphere_margin(a: &Sphere, b: &Sphere) -> Option<f64> {
    sphere_sphere_margin_in::<Dw>(a, b).or_else(|| sphere_sphere_margin_in::<Dy>(a, b))
}

/// A sphere and a plane: `e = n·c − d`, `S = n·n`, or `None` for input outside
/// the stage (including a zero normal, which the exact stage refuses).
fn sphere_plane_parts<T: Num>(s: &Sphere, p: &Plane) -> Option<([T; 3], T, T)> {
    let numbers = s.center.iter().chain(&p.normal).copied().chain([s.radius, p.offset]);
    if !(s.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let n = p.normal.map(T::of);
    let c = s.center.map(T::of);
    let nn = dy::dot(&n, &n);
    if !nn.positive() {
        return None;
    }
    let e = dy::dot(&n, &c).minus(&T::of(p.offset));
    Some((n, nn, e))
}

/// Whether the sphere reaches the plane's solid: `e ≤ 0`, or `e² ≤ r²·S`
/// (`None` when the bounds leave it open).
fn touches<T: Num>(r: f64, e: &T, nn: &T) -> Option<bool> {
    if e.sign_of()? <= 0 {
        return Some(true);
    }
    let r = T::of(r);
    Some(r.times(&r).times(nn).minus(&e.times(e)).sign_of()? >= 0)
}

fn sphere_plane_in<T: Num>(a: &Sphere, b: &Plane) -> Option<Option<Contact>> {
    let (n, nn, e) = sphere_plane_parts::<T>(a, b)?;
    if !touches(a.radius, &e, &nn)? {
        return Some(None);
    }
    // point = c − e·n/S = (c·S − e·n)/S, rational.
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = T::quotient(&T::of(a.center[i]).times(&nn).minus(&e.times(&n[i])), &nn)?;
    }
    Some(Some(Contact { point, normal: T::unit(&n, &nn)?, depth: T::minus_over_root(a.radius, &e, &nn)? }))
}

/// Sphere `a` against plane `b`, as [`sphere_sphere`] answers.
pub(super) fn sphere_plane(a: &Sphere, b: &Plane) -> Option<Option<Contact>> {
    sphere_plane_in::<Dw>(a, b).or_else(|| sphere_plane_in::<Dy>(a, b))
}

fn plane_sphere_in<T: Num>(a: &Plane, b: &Sphere) -> Option<Option<Contact>> {
    let (n, nn, e) = sphere_plane_parts::<T>(b, a)?;
    if !touches(b.radius, &e, &nn)? {
        return Some(None);
    }
    let neg = n.map(|x| x.neg());
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = T::over_root(b.center[i], &T::of(b.radius).times(&neg[i]), &nn)?;
    }
    Some(Some(Contact { point, normal: T::unit(&neg, &nn)?, depth: T::minus_over_root(b.radius, &e, &nn)? }))
}

/// Plane `a` against sphere `b`: the normal is `−n/‖n‖` and the point
/// `c − r·n/‖n‖`, on the sphere.
pub(super) fn plane_sphere(a: &Plane, b: &Sphere) -> Option<Option<Contact>> {
    plane_sphere_in::<Dw>(a, b).or_else(|| plane_sphere_in::<Dy>(a, b))
}

fn sphere_plane_margin_in<T: Num>(a: &Sphere, b: &Plane) -> Option<f64> {
    let (_, nn, e) = sphere_plane_parts::<T>(a, b)?;
    T::minus_over_root(a.radius, &e, &nn)
}

/// The sphere–plane margin `r − (n·c − d)/‖n‖`, correctly rounded, or `None`.
pub(super) fn sphere_plane_margin(a: &Sphere, b: &Plane) -> Option<f64> {
    sphere_plane_margin_in::<Dw>(a, b).or_else(|| sphere_plane_margin_in::<Dy>(a, b))
}

/// Where the centre's closest point on a triangle lies, with what the outputs
/// need, all exact or bounded.
pub(super) enum Near<T> {
    /// On a vertex or an edge: the closest point is `qn / l` (`l > 0`: 1 on a
    /// vertex, the edge's squared length on an edge), and `w = c − q = wv / l`
    /// with `ww = wv·wv`.
    Feature { qn: [T; 3], l: T, wv: [T; 3], ww: T },
    /// Inside the face: `e = N·(c − v0)` with `N = (v1 − v0) × (v2 − v0)`,
    /// `nn = N·N`. Then `c − q = (e/nn)·N`: its direction is `sign(e)·N`, its
    /// length `|e|/√nn`, and `q = (c·nn − e·N)/nn`.
    Face { n: [T; 3], nn: T, e: T },
}

/// The exact stage's region tests (Ericson §5.1.5, as `closest_on_triangle`)
/// decided on certain signs; `None` when a sign is open, for a zero-area
/// triangle, or for a centre exactly on the triangle (no direction).
fn near<T: Num>(p: &P3, v: &[P3; 3]) -> Option<Near<T>> {
    near_by(|x| dy::diff3::<T>(p, x), v)
}

/// [`near`] for a point known by its differences `rel(x) = p − x` from the
/// triangle's vertices (exact or bounded).
pub(super) fn near_by<T: Num>(rel: impl Fn(&P3) -> [T; 3], v: &[P3; 3]) -> Option<Near<T>> {
    let s = |x: &T| x.sign_of();
    let [a, b, c] = v;
    let (ab, ac) = (dy::diff3::<T>(b, a), dy::diff3::<T>(c, a));
    let n = dy::cross(&ab, &ac);
    let nn = dy::dot(&n, &n);
    if !nn.positive() {
        return None;
    }
    // On a vertex: q = V, w = c − V.
    let vertex = |x: &P3| {
        let wv = rel(x);
        let ww = dy::dot(&wv, &wv);
        Near::Feature { qn: x.map(T::of), l: T::of(1.0), wv, ww }
    };
    // On the edge from `x` along `e` at `t = d/l`: q = (x·l + d·e)/l, w = ((c − x)·l − d·e)/l.
    let edge = |x: &P3, e: [T; 3], d: &T| {
        let l = dy::dot(&e, &e);
        let xp = rel(x);
        let qn = [0, 1, 2].map(|i| T::of(x[i]).times(&l).plus(&d.times(&e[i])));
        let wv = [0, 1, 2].map(|i| xp[i].times(&l).minus(&d.times(&e[i])));
        let ww = dy::dot(&wv, &wv);
        Near::Feature { qn, l, wv, ww }
    };
    let ap = rel(a);
    let (d1, d2) = (dy::dot(&ab, &ap), dy::dot(&ac, &ap));
    if s(&d1)? <= 0 && s(&d2)? <= 0 {
        return Some(vertex(a));
    }
    let bp = rel(b);
    let (d3, d4) = (dy::dot(&ab, &bp), dy::dot(&ac, &bp));
    if s(&d3)? >= 0 && s(&d4.minus(&d3))? <= 0 {
        return Some(vertex(b));
    }
    let vc = d1.times(&d4).minus(&d3.times(&d2));
    if s(&vc)? <= 0 && s(&d1)? >= 0 && s(&d3)? <= 0 {
        return Some(edge(a, ab, &d1));
    }
    let cp = rel(c);
    let (d5, d6) = (dy::dot(&ab, &cp), dy::dot(&ac, &cp));
    if s(&d6)? >= 0 && s(&d5.minus(&d6))? <= 0 {
        return Some(vertex(c));
    }
    let vb = d5.times(&d2).minus(&d1.times(&d6));
    if s(&vb)? <= 0 && s(&d2)? >= 0 && s(&d6)? <= 0 {
        return Some(edge(a, ac, &d2));
    }
    let va = d3.times(&d6).minus(&d5.times(&d4));
    let (d43, d56) = (d4.minus(&d3), d5.minus(&d6));
    if s(&va)? <= 0 && s(&d43)? >= 0 && s(&d56)? >= 0 {
        // d4 − d3 = (c − b)·(p − b).
        return Some(edge(b, dy::diff3::<T>(c, b), &d43));
    }
    let e = dy::dot(&n, &ap);
    Some(Near::Face { n, nn, e })
}

/// The parts of a sphere–triangle answer: the triangle's closest point, the
/// unit direction `m = (c − q)/‖c − q‖` before rounding (a vector and its
/// squared length), and whether the sphere touches the triangle.
struct TriangleParts<T> {
    near: Near<T>,
    dir: ([T; 3], T),
    touches: bool,
}

fn sphere_triangle_parts<T: Num>(s: &Sphere, t: &Triangle) -> Option<TriangleParts<T>> {
    let numbers = s.center.iter().chain(t.vertices.iter().flatten()).copied().chain([s.radius]);
    if !(s.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    parts_of(s, &t.vertices)
}

/// [`sphere_triangle_parts`] for input already checked.
fn parts_of<T: Num>(s: &Sphere, v: &[P3; 3]) -> Option<TriangleParts<T>> {
    let near = near::<T>(&s.center, v)?;
    let r = T::of(s.radius);
    let (dir, touches) = match &near {
        Near::Feature { l, wv, ww, .. } => {
            if !ww.positive() {
                return None;
            }
            // ‖w‖² = ww/l² ≤ r².
            let rl = r.times(l);
            ((wv.clone(), ww.clone()), rl.times(&rl).minus(ww).sign_of()? >= 0)
        }
        Near::Face { n, nn, e } => {
            let sign = e.sign_of()?;
            if sign == 0 {
                return None;
            }
            let dir = if sign > 0 { n.clone() } else { n.clone().map(|x| x.neg()) };
            // (e/nn)²·nn = e²/nn ≤ r².
            ((dir, nn.clone()), r.times(&r).times(nn).minus(&e.times(e)).sign_of()? >= 0)
        }
    };
    Some(TriangleParts { near, dir, touches })
}

impl<T: Num> TriangleParts<T> {
    /// `‖c − q‖²` as a fraction `(num, den)` with `den > 0`.
    fn dist2(&self) -> (T, T) {
        match &self.near {
            Near::Feature { l, ww, .. } => (ww.clone(), l.times(l)),
            Near::Face { nn, e, .. } => (e.times(e), nn.clone()),
        }
    }

    /// Whether this face is certainly nearer than `other` (`Some(false)` for
    /// an exact tie too).
    fn nearer(&self, other: &TriangleParts<T>) -> Option<bool> {
        let ((a, da), (b, db)) = (self.dist2(), other.dist2());
        Some(a.times(&db).minus(&b.times(&da)).sign_of()? < 0)
    }

    /// `r − ‖c − q‖`, correctly rounded (`None`: open).
    fn depth(&self, r: f64) -> Option<f64> {
        match &self.near {
            Near::Feature { l, ww, .. } => T::minus_root_over(r, ww, l),
            // ‖c − q‖ = |e|/√nn.
            Near::Face { nn, e, .. } => {
                let abs_e = if e.sign_of()? < 0 { e.neg() } else { e.clone() };
                T::minus_over_root(r, &abs_e, nn)
            }
        }
    }

    /// The closest point `q`, each component correctly rounded.
    fn point(&self, c: &P3) -> Option<P3> {
        let mut out = [0.0; 3];
        for i in 0..3 {
            out[i] = match &self.near {
                Near::Feature { qn, l, .. } => T::quotient(&qn[i], l)?,
                Near::Face { n, nn, e } => T::quotient(&T::of(c[i]).times(nn).minus(&e.times(&n[i])), nn)?,
            };
        }
        Some(out)
    }
}

fn sphere_triangle_in<T: Num>(a: &Sphere, b: &Triangle) -> Option<Option<Contact>> {
    let parts = sphere_triangle_parts::<T>(a, b)?;
    if !parts.touches {
        return Some(None);
    }
    let (dir, dd) = &parts.dir;
    let normal = T::unit(dir, dd)?;
    Some(Some(Contact { point: parts.point(&a.center)?, normal, depth: parts.depth(a.radius)? }))
}

/// Sphere `a` against triangle `b`, as [`sphere_sphere`] answers.
pub(super) fn sphere_triangle(a: &Sphere, b: &Triangle) -> Option<Option<Contact>> {
    sphere_triangle_in::<Dw>(a, b).or_else(|| sphere_triangle_in::<Dy>(a, b))
}

fn triangle_sphere_in<T: Num>(a: &Triangle, b: &Sphere) -> Option<Option<Contact>> {
    let parts = sphere_triangle_parts::<T>(b, a)?;
    if !parts.touches {
        return Some(None);
    }
    let (dir, dd) = &parts.dir;
    let neg = dir.clone().map(|x| x.neg());
    let mut point = [0.0; 3];
    for i in 0..3 {
        point[i] = T::over_root(b.center[i], &T::of(b.radius).times(&neg[i]), dd)?;
    }
    Some(Some(Contact { point, normal: T::unit(&neg, dd)?, depth: parts.depth(b.radius)? }))
}

/// Triangle `a` against sphere `b`: normal `−m`, point `c − r·m` on the sphere.
pub(super) fn triangle_sphere(a: &Triangle, b: &Sphere) -> Option<Option<Contact>> {
    triangle_sphere_in::<Dw>(a, b).or_else(|| triangle_sphere_in::<Dy>(a, b))
}

/// The sphere–triangle margin `r − ‖c − q‖`, correctly rounded, or `None`.
pub(super) fn sphere_triangle_margin(a: &Sphere, b: &Triangle) -> Option<f64> {
    sphere_triangle_parts::<Dw>(a, b)
        .and_then(|p| p.depth(a.radius))
        .or_else(|| sphere_triangle_parts::<Dy>(a, b)?.depth(a.radius))
}

/// Whether sphere `a` touches the triangle `v` (its inputs already in the
/// stage's range), or `None` when left open (double-word numbers: the time
/// of impact's stage asks).
pub(super) fn touches_triangle(a: &Sphere, v: &[P3; 3]) -> Option<bool> {
    Some(parts_of::<Dw>(a, v)?.touches)
}

/// The nearest face of a mesh (smallest `‖c − q‖²`, certified against every
/// other face; an exact tie keeps the lowest index, as the exact stage does),
/// or `None` (an empty mesh, an index out of range, any face the stage cannot
/// answer, a comparison left open).
fn nearest<T: Num>(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<TriangleParts<T>> {
    let numbers = a.center.iter().chain(vertices.iter().flatten()).copied().chain([a.radius]);
    if !(a.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let mut best: Option<TriangleParts<T>> = None;
    for tri in triangles {
        let v = [*vertices.get(tri[0])?, *vertices.get(tri[1])?, *vertices.get(tri[2])?];
        let parts = parts_of::<T>(a, &v)?;
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

fn sphere_mesh_in<T: Num>(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<Option<Contact>> {
    let parts = nearest::<T>(a, vertices, triangles)?;
    if !parts.touches {
        return Some(None);
    }
    let (dir, dd) = &parts.dir;
    let normal = T::unit(dir, dd)?;
    Some(Some(Contact { point: parts.point(&a.center)?, normal, depth: parts.depth(a.radius)? }))
}

/// Sphere `a` against a mesh, as [`sphere_sphere`] answers.
pub(super) fn sphere_mesh(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<Option<Contact>> {
    sphere_mesh_in::<Dw>(a, vertices, triangles).or_else(|| sphere_mesh_in::<Dy>(a, vertices, triangles))
}

/// The sphere–mesh margin `r − min ‖c − q‖`, correctly rounded, or `None`.
pub(super) fn sphere_mesh_margin(a: &Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<f64> {
    nearest::<Dw>(a, vertices, triangles)
        .and_then(|p| p.depth(a.radius))
        .or_else(|| nearest::<Dy>(a, vertices, triangles)?.depth(a.radius))
}
