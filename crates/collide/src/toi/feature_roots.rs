//! The first contact of a moving point at distance `r` with a triangle's
//! features, from their equations with exactly computed coefficients: the
//! vertices and edges alone for grazing contacts, where advancement's
//! distance is flat ([`first_root_of_features`]), and the whole first
//! contact — face, edges and vertices, with exact decisions — for scenes
//! whose magnitudes range too widely for advancement ([`first_contact`]).

use crate::exact::bigfloat::{B3, cross3 as cross, dot3 as dot, sub3 as sub};
use crate::exact::{BigFloat, Estimate, Sign, frexp, ldexp};
use crate::real::{Real, Vec3};
use crate::shapes::{Sphere, Triangle};

fn big3<T: Real>(p: &Vec3<T>) -> B3 {
    [p.x, p.y, p.z].map(|x| BigFloat::from_f64(x.wide()))
}

/// A positive value as `(mant, exp)`, `mant ∈ [0.5, 1)`.
fn parts(e: &Estimate) -> (f64, i64) {
    (e.mant, e.exp)
}

/// The first root in `t ≥ 0` of `A t² + 2 B t + C = 0` for `C > 0` (clear at
/// `t = 0`): `C / (−B + √(B² − A C))`, cancellation-free, when `B < 0` and
/// the discriminant is non-negative (decided exactly); `None` otherwise.
fn first_root(a: &BigFloat, b: &BigFloat, c: &BigFloat) -> Option<f64> {
    if a.sign() != Sign::Positive || b.sign() != Sign::Negative || c.sign() != Sign::Positive {
        return None;
    }
    let disc = &(b * b) - &(a * c);
    if disc.sign() == Sign::Negative {
        return None;
    }
    let (mb, eb) = parts(&(-b.clone()).estimate());
    let (md, ed) = {
        let e = disc.estimate();
        if e.mant == 0.0 {
            (0.0, eb)
        } else {
            let (mut m, mut x) = parts(&e);
            if x.rem_euclid(2) != 0 {
                m *= 2.0;
                x -= 1;
            }
            (m.sqrt(), x / 2)
        }
    };
    // −B + √disc on B's exponent (√disc ≤ −B since A C > 0).
    let sum = mb + ldexp(md, ed - eb);
    let (mc, ec) = parts(&c.estimate());
    Some(ldexp(mc / sum, ec - eb))
}

/// The earliest first contact of the moving centre `M + t v` at distance
/// `r` with the vertices and edges of `tri` (see
/// `grazing_root` in the sphere–triangle advancement): an edge's root counts when
/// its foot parameter there lies in `[0, 1]`. `None` when no feature is met
/// or an input is not finite.
pub(crate) fn first_root_of_features<T: Real>(a: &Sphere<T>, v: &Vec3<T>, tri: &Triangle<T>) -> Option<f64> {
    let finite = |p: &Vec3<T>| p.x.finite() && p.y.finite() && p.z.finite();
    if !(finite(&a.center) && finite(v) && a.radius.finite() && tri.vertices.iter().all(finite)) {
        return None;
    }
    let m = big3(&a.center);
    let vb = big3(v);
    let r = BigFloat::from_f64(a.radius.wide());
    let rr = &r * &r;
    let verts = tri.vertices.each_ref().map(big3);
    let mut best: Option<f64> = None;
    let mut keep = |t: f64| {
        if t.is_finite() && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    };
    let vv = dot(&vb, &vb);
    for p in &verts {
        let w = sub(&m, p);
        if let Some(t) = first_root(&vv, &dot(&w, &vb), &(&dot(&w, &w) - &rr)) {
            keep(t);
        }
    }
    for (i, j) in [(0usize, 1usize), (1, 2), (2, 0)] {
        let u = sub(&verts[j], &verts[i]);
        let uu = dot(&u, &u);
        if uu.is_zero() {
            continue;
        }
        let w = sub(&m, &verts[i]);
        let (uw, uv) = (cross(&u, &w), cross(&u, &vb));
        let Some(t) = first_root(&dot(&uv, &uv), &dot(&uw, &uv), &(&dot(&uw, &uw) - &(&rr * &uu))) else {
            continue;
        };
        // The foot's parameter (w + t v)·u / u·u at the root, in f64 from
        // the exact dot products' estimates (on a common scale).
        let (wu, vu, uu) = (dot(&w, &u).estimate(), dot(&vb, &u).estimate(), uu.estimate());
        let val = |e: &Estimate| match e.sign {
            Sign::Negative => -ldexp(e.mant, e.exp - uu.exp),
            Sign::Zero => 0.0,
            Sign::Positive => ldexp(e.mant, e.exp - uu.exp),
        };
        let s = (val(&wu) + t * val(&vu)) / uu.mant;
        if (0.0..=1.0).contains(&s) {
            keep(t);
        }
    }
    best
}

/// The feature of a triangle a moving sphere meets first (see [`first_contact`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Feature {
    /// The face's interior (or its closed region, foot on the boundary).
    Face,
    /// The edge from vertex `i` to vertex `(i + 1) % 3`.
    Edge(usize),
    /// Vertex `i`.
    Vertex(usize),
}

/// The first contact of a moving sphere with a triangle, solved from the
/// features' equations (see [`first_contact`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FirstContact {
    /// The time, within a few roundings of the exact first contact and never
    /// above `t_max`.
    pub t: f64,
    /// The feature met then.
    pub feature: Feature,
    /// Touching already at `t = 0` (decided exactly).
    pub at_start: bool,
    /// The unit normal from the triangle toward the centre at `t`; `None`
    /// where there is no direction (a zero radius, or a centre on the
    /// triangle).
    pub normal: Option<[f64; 3]>,
    /// The contact point on the triangle at the exact time, in the world
    /// frame (the triangle moved to it), each coordinate within a few
    /// roundings of its exact value (an infinity beyond the range).
    pub point: [f64; 3],
}

/// A non-negative value `m · 2^e` (`m ∈ [0.25, 2)` after a few products and
/// sums, `0` for zero): the time's parts, which neither overflow nor
/// underflow whatever the scene's magnitudes.
#[derive(Clone, Copy, Debug)]
struct Pos {
    m: f64,
    e: i64,
}

impl Pos {
    fn of(x: &BigFloat) -> Self {
        let (m, e) = parts(&x.estimate());
        Self { m, e }
    }

    fn mul(self, o: Self) -> Self {
        Self { m: self.m * o.m, e: self.e + o.e }
    }

    fn add(self, o: Self) -> Self {
        if self.m == 0.0 {
            return o;
        }
        if o.m == 0.0 {
            return self;
        }
        let e = self.e.max(o.e);
        Self { m: ldexp(self.m, self.e - e) + ldexp(o.m, o.e - e), e }
    }

    fn sqrt(self) -> Self {
        if self.m == 0.0 {
            return self;
        }
        let (mut m, mut e) = (self.m, self.e);
        if e.rem_euclid(2) != 0 {
            m *= 2.0;
            e -= 1;
        }
        Self { m: m.sqrt(), e: e / 2 }
    }

    /// `self / o` as an `f64` (`o` non-zero).
    fn div(self, o: Self) -> f64 {
        ldexp(self.m / o.m, self.e - o.e)
    }
}

/// The exact sign of `x + y √z` for `z ≥ 0`: where the two terms' signs
/// differ, `x²` against `y² z`.
fn sign_plus_sqrt(x: &BigFloat, y: &BigFloat, z: &BigFloat) -> Sign {
    let sy = if z.is_zero() { Sign::Zero } else { y.sign() };
    let sx = x.sign();
    if sy == Sign::Zero || sx == sy {
        return sx;
    }
    if sx == Sign::Zero {
        return sy;
    }
    match (x * x).cmp_value(&(&(y * y) * z)) {
        core::cmp::Ordering::Greater => sx,
        core::cmp::Ordering::Less => sy,
        core::cmp::Ordering::Equal => Sign::Zero,
    }
}

/// Relative width, in units of ε, of the band around `t_max` in which a
/// candidate's rounded time does not decide `t ≤ t_max` and the exact test
/// does: 16. Reason: a time is a quotient of a dozen roundings of the exact
/// coefficients' estimates (each within 2^−52, products, one square root, one
/// sum, one division), so it is within ~12 ε of the exact time; 16 covers
/// that with room.
const T_MAX_BAND_EPS: f64 = 16.0;

/// The exact solve's inputs, widened to `f64` exactly and held exactly.
struct Scene {
    m: B3,
    v: B3,
    vb: B3,
    r: BigFloat,
    rr: BigFloat,
    r_pos: Pos,
    verts: [B3; 3],
    t_max: f64,
    t_max_big: BigFloat,
}

impl Scene {
    /// Whether a candidate's time `t` (rounded, from the exact root
    /// `(−b − √disc)/a` when the rounded one cannot tell) is at most `t_max`.
    fn by_t_max_quadratic(&self, t: f64, a: &BigFloat, b: &BigFloat, disc: &BigFloat) -> bool {
        if let Some(d) = self.t_max_rough(t) {
            return d;
        }
        // t − T = ((−b − a T) − √disc)/a, a > 0.
        let x = &(-b.clone()) - &(a * &self.t_max_big);
        sign_plus_sqrt(&x, &BigFloat::from_f64(-1.0), disc) != Sign::Positive
    }

    /// The decision by the rounded time alone, when it is clear of `t_max`.
    fn t_max_rough(&self, t: f64) -> Option<bool> {
        let band = T_MAX_BAND_EPS * f64::EPSILON;
        if t <= self.t_max * (1.0 - band) {
            Some(true)
        } else if t > self.t_max * (1.0 + band) {
            Some(false)
        } else {
            None
        }
    }
}

/// The smaller root `C / (−B + √(B² − A C))` of `A t² + 2 B t + C` for
/// `C > 0`, `B < 0` and a non-negative discriminant (decided exactly):
/// the time a point entering the quadratic's region (`≤ 0`) does so. With the
/// discriminant, for the exact tests at the root.
fn entering_root(a: &BigFloat, b: &BigFloat, c: &BigFloat) -> Option<(f64, BigFloat)> {
    if b.sign() != Sign::Negative || c.sign() != Sign::Positive {
        return None;
    }
    let disc = &(b * b) - &(a * c);
    if disc.sign() == Sign::Negative {
        return None;
    }
    let den = Pos::of(b).add(Pos::of(&disc).sqrt());
    Some((Pos::of(c).div(den), disc))
}

/// The first contact in `[0, t_max]` of sphere `a` (velocity `va`) with
/// triangle `tri` (velocity `vb`), from the equations of its features with
/// exact coefficients: the whole answer where the scene's magnitudes range
/// too widely for conservative advancement's `f64` distances (see
/// `EXACT_RANGE_RATIO` in the sphere–triangle advancement).
///
/// **Method.** In the triangle's frame the centre moves as `P(t) = M + t v`,
/// `v = va − vb` (formed exactly). The triangle is the union of its face,
/// edges and vertices; the first time `t*` at which `dist(P(t), tri) = r` is
/// a time at which the closest point lies on one of them, so it is the
/// earliest of:
///
/// - the **face**: `n · (P(t) − V0) = σ r ‖n‖` (`n = (V1 − V0) × (V2 − V0)`,
///   `σ` the side of the centre at `t = 0`), linear in `t`, when the centre
///   starts more than `r` off the plane and approaches it, counted when the
///   foot `P(t) − σ r n/‖n‖` is in the closed triangle (the three edge
///   functions `n · (e_i × (P(t) − V_i)) ≥ 0`);
/// - each **edge** `V_i + s u`: the first root of
///   `‖u × (w + t v)‖² = r² ‖u‖²` (`w = M − V_i`), counted when the foot's
///   parameter `s = (w + t v)·u / u·u` is in `[0, 1]` there;
/// - each **vertex**: the first root of `‖w + t v‖² = r²`.
///
/// Every counted root is a time at which the centre is within `r` of a point
/// of the triangle, so none is before `t*`; and `t*` is counted: at `t*` the
/// distance to the feature holding the closest point falls through `r` (the
/// smaller root of its convex quadratic, or for the face the root of its
/// linear distance on the centre's side). The first valid root is therefore
/// `t*`. A centre that starts more than `r` off the plane and does not
/// approach it never touches at all, and none touches before the face's own
/// root: both settle most queries with the face's few products.
///
/// **Exactness.** Every coefficient (`n`, the dot and cross products, `r²`,
/// the discriminants) is an exact [`BigFloat`]; whether a root exists, which
/// side, whether the foot is in the triangle or the edge (the sign of
/// `x + y √z`, decided by comparing `x²` with `y² z` where needed) and
/// `t ≤ t_max` near `t_max` are decided exactly at the exact root. Only the
/// time itself is rounded: a quotient of the coefficients' estimates,
/// formed without cancellation (`C / (−B + √D)`, and for the face
/// `((n·w)² − r² n·n) / ((|n·w| + r ‖n‖) |n·v|)`), within ~12 ε of the exact
/// time. The closest point at the first contact is unique (the triangle is
/// convex), and a feature met within that rounding of it touches inside the
/// shallow cap the sphere has entered by then, so when two times agree to
/// the rounding either feature answers to the contact's own conditioning.
///
/// **Answer.** The earliest time (the face before the edges before the
/// vertices on a tie), its feature, and the normal and point at the exact
/// time, each rounded from exact components (see `with_normal` and
/// `with_point`): the face's unit normal on the centre's side, or the
/// direction from the edge's foot or the vertex to the centre. A sphere
/// already touching at `t = 0` (which the static test, accurate to 2^−38 of
/// the distance, may call clear by a hair) gives `t = 0` with `at_start`.
/// `None`: no contact in `[0, t_max]`, or a non-finite input. A zero radius
/// gives no normal; a zero-area triangle has no face and is its edges and
/// vertices.
pub(crate) fn first_contact<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    tri: &Triangle<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<FirstContact> {
    let finite = |p: &Vec3<T>| p.x.finite() && p.y.finite() && p.z.finite();
    let t_max = t_max.wide();
    if !(finite(&a.center)
        && finite(va)
        && finite(vb)
        && a.radius.finite()
        && tri.vertices.iter().all(finite)
        && t_max.is_finite()
        && t_max >= 0.0)
    {
        return None;
    }
    let r = BigFloat::from_f64(a.radius.wide().abs());
    let s = Scene {
        m: big3(&a.center),
        v: sub(&big3(va), &big3(vb)),
        vb: big3(vb),
        rr: &r * &r,
        r_pos: Pos::of(&r),
        r,
        verts: tri.vertices.each_ref().map(big3),
        t_max,
        t_max_big: BigFloat::from_f64(t_max),
    };
    let mut best: Option<FirstContact> = None;
    let mut keep = |t: f64, feature: Feature, at_start: bool| {
        if t.is_finite() && best.is_none_or(|b| t < b.t) {
            best = Some(FirstContact { t: t.min(s.t_max), feature, at_start, normal: None, point: [0.0; 3] });
        }
    };
    let n = cross(&sub(&s.verts[1], &s.verts[0]), &sub(&s.verts[2], &s.verts[0]));
    let nn = dot(&n, &n);
    if !nn.is_zero() {
        match face(&s, &n, &nn) {
            FaceRoot::Never => return None,
            FaceRoot::Hit(t, at_start) => {
                keep(t, Feature::Face, at_start);
                return best.map(|b| with_point(&s, with_normal(&s, b, &n), &n));
            }
            FaceRoot::Outside => {}
        }
    }
    for i in 0..3 {
        if let Some((t, at_start)) = edge(&s, i) {
            keep(t, Feature::Edge(i), at_start);
        }
    }
    for i in 0..3 {
        if let Some((t, at_start)) = vertex(&s, i) {
            keep(t, Feature::Vertex(i), at_start);
        }
    }
    best.map(|b| with_point(&s, with_normal(&s, b, &n), &n))
}

/// What the face's equation says.
enum FaceRoot {
    /// The centre starts more than `r` off the plane and never comes within
    /// `r` of it in `[0, t_max]`: no feature is met either.
    Never,
    /// The face is met at this time (touching at the start when set): the
    /// first contact, since no point of the triangle is within `r` earlier.
    Hit(f64, bool),
    /// The face's own contact, if any, has its foot outside the triangle:
    /// the edges and vertices decide.
    Outside,
}

/// The face of the triangle (`n` its exact normal, `nn = n·n > 0`): see
/// [`first_contact`].
fn face(s: &Scene, n: &B3, nn: &BigFloat) -> FaceRoot {
    let w = sub(&s.m, &s.verts[0]);
    let nw = dot(n, &w);
    let nv = dot(n, &s.v);
    // The edge functions n·(e_i × (P(t) − V_i)) = α_i + t β_i.
    let edges = |i: usize| {
        let (p, q) = (&s.verts[i], &s.verts[(i + 1) % 3]);
        let e = sub(q, p);
        (dot(n, &cross(&e, &sub(&s.m, p))), dot(n, &cross(&e, &s.v)))
    };
    let off = &(&nw * &nw) - &(&s.rr * nn);
    if off.sign() != Sign::Positive {
        // Within r of the plane at t = 0: touching at the start when the
        // foot is in the triangle; otherwise only an edge or a vertex can be
        // met first (the plane distance only moves away from within r once).
        let inside = (0..3).all(|i| edges(i).0.sign() != Sign::Negative);
        return if inside { FaceRoot::Hit(0.0, true) } else { FaceRoot::Outside };
    }
    let sigma = nw.sign();
    let approaching = matches!((sigma, nv.sign()), (Sign::Positive, Sign::Negative) | (Sign::Negative, Sign::Positive));
    if !approaching {
        return FaceRoot::Never;
    }
    // t_f = ((n·w)² − r² n·n) / ((|n·w| + r ‖n‖) |n·v|).
    let den = Pos::of(&nw).add(s.r_pos.mul(Pos::of(nn).sqrt())).mul(Pos::of(&nv));
    let t = Pos::of(&off).div(den);
    let sig = BigFloat::from_f64(if sigma == Sign::Positive { 1.0 } else { -1.0 });
    // t_f − T = ((σ r‖n‖ − n·w) − T n·v) / n·v.
    let by_t_max = s.t_max_rough(t).unwrap_or_else(|| {
        let x = &(-nw.clone()) - &(&s.t_max_big * &nv);
        let side = sign_plus_sqrt(&x, &(&sig * &s.r), nn);
        side == Sign::Zero || side != nv.sign()
    });
    if !by_t_max {
        return FaceRoot::Never;
    }
    // g_i(t_f) · n·v = (α n·v − β n·w) + (σ r β) ‖n‖: of n·v's sign (or 0)
    // for a foot in the closed triangle.
    let inside = (0..3).all(|i| {
        let (alpha, beta) = edges(i);
        let x = &(&alpha * &nv) - &(&beta * &nw);
        let y = &(&sig * &s.r) * &beta;
        let g = sign_plus_sqrt(&x, &y, nn);
        g == Sign::Zero || g == nv.sign()
    });
    if inside { FaceRoot::Hit(t, false) } else { FaceRoot::Outside }
}

/// The edge from vertex `i` to `i + 1`: its first contact time (and whether
/// at the start), see [`first_contact`].
///
/// The edge is taken from its lexicographically smaller end, so that faces
/// sharing it compute the same coefficients and round its time alike (a
/// mesh's tie then goes to the lower face index, as the format asks).
fn edge(s: &Scene, i: usize) -> Option<(f64, bool)> {
    let (p0, p1) = edge_ends(s, i);
    let u = sub(p1, p0);
    let uu = dot(&u, &u);
    if uu.is_zero() {
        return None;
    }
    let w = sub(&s.m, p0);
    let (uw, uv) = (cross(&u, &w), cross(&u, &s.v));
    let c = &dot(&uw, &uw) - &(&s.rr * &uu);
    let (p, q) = (dot(&w, &u), dot(&s.v, &u));
    if c.sign() != Sign::Positive {
        // Within r of the edge's line at the start: touching when the foot
        // is on the edge; otherwise the line is only left.
        let on = p.sign() != Sign::Negative && (&uu - &p).sign() != Sign::Negative;
        return on.then_some((0.0, true));
    }
    let a = dot(&uv, &uv);
    let b = dot(&uw, &uv);
    let (t, disc) = entering_root(&a, &b, &c)?;
    // A (p + q t) = (A p − q B) − q √D and A (u·u − p − q t) = (A (u·u − p) + q B) + q √D.
    let lo = sign_plus_sqrt(&(&(&a * &p) - &(&q * &b)), &(-q.clone()), &disc);
    if lo == Sign::Negative {
        return None;
    }
    let hi = sign_plus_sqrt(&(&(&a * &(&uu - &p)) + &(&q * &b)), &q, &disc);
    if hi == Sign::Negative {
        return None;
    }
    s.by_t_max_quadratic(t, &a, &b, &disc).then_some((t, false))
}

/// The ends of the edge from vertex `i` to `i + 1`, the lexicographically
/// smaller (by the exact coordinates) first.
fn edge_ends(s: &Scene, i: usize) -> (&B3, &B3) {
    let (p, q) = (&s.verts[i], &s.verts[(i + 1) % 3]);
    let order = (0..3).map(|k| p[k].cmp_value(&q[k])).find(|o| o.is_ne()).unwrap_or(core::cmp::Ordering::Equal);
    if order.is_gt() { (q, p) } else { (p, q) }
}

/// Vertex `i`: its first contact time (and whether at the start).
fn vertex(s: &Scene, i: usize) -> Option<(f64, bool)> {
    let w = sub(&s.m, &s.verts[i]);
    let c = &dot(&w, &w) - &s.rr;
    if c.sign() != Sign::Positive {
        return Some((0.0, true));
    }
    let a = dot(&s.v, &s.v);
    let b = dot(&w, &s.v);
    let (t, disc) = entering_root(&a, &b, &c)?;
    s.by_t_max_quadratic(t, &a, &b, &disc).then_some((t, false))
}

/// The value `x + y √z` (`z ≥ 0`) as an [`Estimate`], within a few roundings
/// of it: its sign exactly, its magnitude `|x| + |y| √z` where the terms
/// agree in sign and `|x² − y² z| / (|x| + |y| √z)` where they cancel.
fn estimate_plus_sqrt(x: &BigFloat, y: &BigFloat, z: &BigFloat) -> Estimate {
    let sign = sign_plus_sqrt(x, y, z);
    if sign == Sign::Zero {
        return Estimate::ZERO;
    }
    let root = Pos::of(y).mul(Pos::of(z).sqrt());
    let sum = Pos::of(x).add(root);
    let mag = if x.sign() == y.sign() || x.is_zero() || y.is_zero() || z.is_zero() {
        sum
    } else {
        let diff = Pos::of(&(&(x * x) - &(&(y * y) * z)));
        let q = diff.m / sum.m;
        Pos { m: q, e: diff.e - sum.e }
    };
    let (mant, e) = frexp(mag.m);
    Estimate { sign, mant, exp: mag.e + e, rel_err: NORMAL_COMPONENT_REL_ERR }
}

/// Relative error of a normal's component from [`estimate_plus_sqrt`]:
/// 2^−48, a dozen roundings of 2^−53 with room (estimates of the exact
/// products, one square root, one sum, at most one quotient).
const NORMAL_COMPONENT_REL_ERR: f64 = 3.552713678800501e-15;

/// The contact's unit normal at the exact contact time, from exact
/// components: the face's normal `n` on the centre's side (its side at
/// `t = 0`, which a face contact keeps), or the direction from the edge's
/// foot or the vertex to the centre, `A d(t*) = (A d₀ − B d_v) − √D d_v` at
/// the exact root `t* = (−B − √D)/A` (`d₀ + t d_v` the centre's offset from
/// the edge's line, times `u·u`, or from the vertex), so that no rounding
/// of the time moves the centre across a sphere far smaller than the
/// distance travelled. None for a zero radius or a zero direction.
fn with_normal(s: &Scene, mut hit: FirstContact, n: &B3) -> FirstContact {
    if s.r_pos.m == 0.0 {
        return hit;
    }
    let zero = BigFloat::ZERO;
    // The offset d₀ at t = 0 and its rate d_v, and the quadratic's (A, B, C).
    let (d0, dv, abc) = match hit.feature {
        Feature::Face => {
            let side = dot(n, &sub(&s.m, &s.verts[0])).sign();
            let dir = match side {
                Sign::Positive => n.clone(),
                Sign::Negative => n.clone().map(|x| -x),
                Sign::Zero => return hit,
            };
            hit.normal = Estimate::unit_vector(dir.each_ref().map(|x| x.estimate()));
            return hit;
        }
        Feature::Edge(i) => {
            let (p0, p1) = edge_ends(s, i);
            let u = sub(p1, p0);
            let w = sub(&s.m, p0);
            let uu = dot(&u, &u);
            let perp = |x: &B3| {
                let xu = dot(x, &u);
                [0, 1, 2].map(|k| &(&x[k] * &uu) - &(&xu * &u[k]))
            };
            let (uw, uv) = (cross(&u, &w), cross(&u, &s.v));
            let abc = (dot(&uv, &uv), dot(&uw, &uv), &dot(&uw, &uw) - &(&s.rr * &uu));
            (perp(&w), perp(&s.v), abc)
        }
        Feature::Vertex(i) => {
            let w = sub(&s.m, &s.verts[i]);
            let abc = (dot(&s.v, &s.v), dot(&w, &s.v), &dot(&w, &w) - &s.rr);
            (w, s.v.clone(), abc)
        }
    };
    let comps = if hit.at_start {
        d0.each_ref().map(|x| estimate_plus_sqrt(x, &zero, &zero))
    } else {
        let (a, b, c) = abc;
        let disc = &(&b * &b) - &(&a * &c);
        [0, 1, 2].map(|k| estimate_plus_sqrt(&(&(&a * &d0[k]) - &(&b * &dv[k])), &(-dv[k].clone()), &disc))
    };
    hit.normal = Estimate::unit_vector(comps);
    hit
}

/// `num / den` as an `f64`, negated with `negate` (`den` non-zero).
fn quotient(num: &Estimate, den: Pos, negate: bool) -> f64 {
    let q = match num.sign {
        Sign::Zero => return 0.0,
        Sign::Negative => -ldexp(num.mant / den.m, num.exp - den.e),
        Sign::Positive => ldexp(num.mant / den.m, num.exp - den.e),
    };
    if negate { -q } else { q }
}

/// The contact point at the exact time `t*`, in the world frame, each
/// coordinate a quotient `(x + y √z) / d` of exact values formed without
/// cancellation ([`estimate_plus_sqrt`]), so that neither the rounding of
/// the time nor the cancellation of `M + t va` against the radius or the
/// triangle's motion costs digits:
///
/// - face: `M + t* va − σ r n/‖n‖` with `t* = (σ r ‖n‖ − n·w)/n·v`, times
///   `n·v ‖n‖`: `σ r (va n·n − n n·v) + (M n·v − va n·w) ‖n‖`;
/// - edge: `V + s(t*) u + vb t*` times `A u·u`:
///   `V A u·u + (A p − q B) u − vb B u·u − (q u + vb u·u) √D`
///   (`p = w·u`, `q = v·u`);
/// - vertex: `V + vb t*` times `A`: `V A − vb B − vb √D`;
///
/// and at `t = 0` the same without the motion.
fn with_point(s: &Scene, mut hit: FirstContact, n: &B3) -> FirstContact {
    let zero = BigFloat::ZERO;
    let sig = |x: &BigFloat| match x.sign() {
        Sign::Positive => s.r.clone(),
        Sign::Negative => -s.r.clone(),
        Sign::Zero => BigFloat::ZERO,
    };
    let point: [f64; 3] = match hit.feature {
        Feature::Face => {
            let nn = dot(n, n);
            let nw = dot(n, &sub(&s.m, &s.verts[0]));
            let sr = sig(&nw);
            let root = Pos::of(&nn).sqrt();
            if hit.at_start {
                // M − σ r n/‖n‖, times ‖n‖.
                [0, 1, 2].map(|k| quotient(&estimate_plus_sqrt(&-(&sr * &n[k]), &s.m[k], &nn), root, false))
            } else {
                let nv = dot(n, &s.v);
                let va = [0, 1, 2].map(|k| &s.v[k] + &s.vb[k]);
                let den = Pos::of(&nv).mul(root);
                let neg = nv.sign() == Sign::Negative;
                [0, 1, 2].map(|k| {
                    let x = &sr * &(&(&va[k] * &nn) - &(&n[k] * &nv));
                    let y = &(&s.m[k] * &nv) - &(&va[k] * &nw);
                    quotient(&estimate_plus_sqrt(&x, &y, &nn), den, neg)
                })
            }
        }
        Feature::Edge(i) => {
            let (p0, p1) = edge_ends(s, i);
            let u = sub(p1, p0);
            let w = sub(&s.m, p0);
            let uu = dot(&u, &u);
            let (p, q) = (dot(&w, &u), dot(&s.v, &u));
            if hit.at_start {
                [0, 1, 2].map(|k| {
                    let x = &(&p0[k] * &uu) + &(&p * &u[k]);
                    quotient(&estimate_plus_sqrt(&x, &zero, &zero), Pos::of(&uu), false)
                })
            } else {
                let (uw, uv) = (cross(&u, &w), cross(&u, &s.v));
                let (a, b) = (dot(&uv, &uv), dot(&uw, &uv));
                let c = &dot(&uw, &uw) - &(&s.rr * &uu);
                let disc = &(&b * &b) - &(&a * &c);
                let (auu, apqb) = (&a * &uu, &(&a * &p) - &(&q * &b));
                let buu = &b * &uu;
                [0, 1, 2].map(|k| {
                    let x = &(&(&p0[k] * &auu) + &(&apqb * &u[k])) - &(&s.vb[k] * &buu);
                    let y = -(&(&q * &u[k]) + &(&s.vb[k] * &uu));
                    quotient(&estimate_plus_sqrt(&x, &y, &disc), Pos::of(&auu), false)
                })
            }
        }
        Feature::Vertex(i) => {
            let vx = &s.verts[i];
            if hit.at_start {
                vx.each_ref().map(BigFloat::to_f64)
            } else {
                let w = sub(&s.m, vx);
                let (a, b) = (dot(&s.v, &s.v), dot(&w, &s.v));
                let c = &dot(&w, &w) - &s.rr;
                let disc = &(&b * &b) - &(&a * &c);
                [0, 1, 2].map(|k| {
                    let x = &(&vx[k] * &a) - &(&s.vb[k] * &b);
                    quotient(&estimate_plus_sqrt(&x, &-s.vb[k].clone(), &disc), Pos::of(&a), false)
                })
            }
        }
    };
    hit.point = point;
    hit
}
