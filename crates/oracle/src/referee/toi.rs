//! Time of impact of a sphere moving linearly against a sphere, a plane, a
//! triangle or a triangle mesh, exactly.
//!
//! Convention (fixture format, `toi`): every shape moves as
//! `position(t) = position(0) + t·velocity`; the answer is the first time
//! `t ∈ [0, t_max]` at which the shapes touch, with the contact then — normal
//! from `b` toward `a`, unit length; point on `b`'s surface, `b` moved to time
//! `t`. Shapes already in contact at `t = 0` (touching counts) answer `t = 0`
//! with the static contact of [`super::contact`].
//!
//! **How it is exact.** In `b`'s frame the centre of `a` moves on the line
//! `p(t) = c + t v` (`v = va − vb`), and touching a feature of `b` — a point (a
//! sphere's centre, a triangle's vertex), a line (a triangle's edge) or a plane
//! (a face, a half-space) — at distance `r` is a quadratic or linear equation in
//! `t` with exact rational coefficients. Each candidate time is therefore
//! `α + β√D` with rationals `α`, `β`, `D`: the discriminant's sign is decided
//! exactly, candidates are compared exactly (signs of `a + b√p + c√q` by
//! squaring), and whether a candidate's contact lies on the feature (an edge's
//! foot inside the edge, a face's projection inside the triangle) is the sign of
//! an affine function of `t`, again exact. The contact point and normal at the
//! winning time are affine in the same `√D`, and every reported scalar is that
//! exact number correctly rounded by the referee's integer-square-root
//! enclosure (see [`super::error::PRECISION_BITS`]).
//!
//! **Margins.** Each `toi_margin_*` function returns the signed closest-approach
//! gap over the interval, `r − min_{t∈[0,t_max]} dist(p(t), b)` (with `r` the sum
//! of the radii for two spheres), correctly rounded: ≥ 0 exactly when there is
//! an impact, and in units of length, so the harness can call a case within
//! tolerance of grazing "borderline".
//!
//! **Input.** Non-finite numbers and negative radii are refused, naming the
//! field (`a.velocity`, `b.velocity` and `t_max` included); a zero plane normal
//! is refused as for contact. A negative `t_max` is read as 0 (the interval
//! `[0, 0]`: only a contact at `t = 0` counts); the fixture format refuses it
//! before it gets here.

use std::cmp::Ordering;

use super::closest::closest_on_triangle;
use super::contact::{contact_sphere_mesh, contact_sphere_plane, contact_sphere_sphere, contact_sphere_triangle};
use super::error::RefereeError;
use super::exact::{
    Q, Root, V3, add, check, check_radius, check_v3, cross, dot, is_zero, q, radius, round_unit, scale, sub, v3,
};
use crate::geom::{ContactAnswer, P3, Plane, Sphere, Toi, ToiAnswer, Triangle};

/// `a + b·√d`, exact (`d ≥ 0`).
#[derive(Clone, Debug)]
pub(super) struct Surd {
    pub(super) a: Q,
    pub(super) b: Q,
    pub(super) d: Q,
}

fn sign(x: &Q) -> Ordering {
    x.cmp(&Q::ZERO)
}

/// The sign of `a + b·√d` (`d ≥ 0`), exactly: when `a` and `b√d` have opposite
/// signs, the larger magnitude wins, decided on the squares `a²` and `b²d`.
fn sign_surd(a: &Q, b: &Q, d: &Q) -> Ordering {
    let sa = sign(a);
    let sb = if d.is_zero() { Ordering::Equal } else { sign(b) };
    if sb == Ordering::Equal || sa == sb {
        return sa;
    }
    if sa == Ordering::Equal {
        return sb;
    }
    match (a * a).cmp(&(b * b * d)) {
        Ordering::Greater => sa,
        Ordering::Less => sb,
        Ordering::Equal => Ordering::Equal,
    }
}

impl Surd {
    pub(super) fn rational(a: Q) -> Self {
        Self { a, b: Q::ZERO, d: Q::ZERO }
    }

    pub(super) fn sign(&self) -> Ordering {
        sign_surd(&self.a, &self.b, &self.d)
    }

    /// `k + m·self`, exactly (same `√d`).
    pub(super) fn affine(&self, k: &Q, m: &Q) -> Self {
        Self { a: k + m * &self.a, b: m * &self.b, d: self.d.clone() }
    }

    /// `self` against `o`, exactly, for any two radicands: with
    /// `X = (a₁ − a₂) + b₁√d₁` and `Y = b₂√d₂`, compare the signs of `X` and `Y`;
    /// if they agree, `X − Y` has the sign of `X² − Y²` (both positive) or its
    /// opposite (both negative), and `X² − Y² = A + B√d₁` with rational `A`, `B`.
    pub(super) fn cmp(&self, o: &Self) -> Ordering {
        let big_a = &self.a - &o.a;
        let sx = sign_surd(&big_a, &self.b, &self.d);
        let sy = if o.d.is_zero() { Ordering::Equal } else { sign(&o.b) };
        if sx != sy {
            return sx.cmp(&sy);
        }
        if sx == Ordering::Equal {
            return Ordering::Equal;
        }
        let rational = &big_a * &big_a + &self.b * &self.b * &self.d - &o.b * &o.b * &o.d;
        let ab = &big_a * &self.b;
        let s = sign_surd(&rational, &(&ab + &ab), &self.d);
        if sx == Ordering::Greater { s } else { s.reverse() }
    }

    pub(super) fn in_interval(&self, t_max: &Q) -> bool {
        self.sign() != Ordering::Less && self.cmp(&Surd::rational(t_max.clone())) != Ordering::Greater
    }
}

/// A candidate first contact, exact: time, world contact point on `b`, and the
/// unit normal — all in the same `√d` — or `None` for the normal when the
/// shapes meet with no radius between them.
pub(super) struct Hit {
    pub(super) t: Surd,
    pub(super) point: [Surd; 3],
    pub(super) normal: Option<[Surd; 3]>,
}

/// Every component of `k + m·t`.
pub(super) fn along(t: &Surd, k: &V3, m: &V3) -> [Surd; 3] {
    [t.affine(&k[0], &m[0]), t.affine(&k[1], &m[1]), t.affine(&k[2], &m[2])]
}

/// The contact at `t = 0` from the static query.
pub(super) fn at_zero(k: ContactAnswer) -> ToiAnswer {
    ToiAnswer { toi: k.contact.map(|k| Toi { t: 0.0, point: k.point, normal: k.normal }), degenerate: k.degenerate }
}

/// The winning hit, every component correctly rounded. A missing normal falls
/// back to the direction `a` came from, `−v/‖v‖` (flagged).
pub(super) fn finish(h: &Hit, v: &V3) -> ToiAnswer {
    let root = Root::new(h.t.d.clone());
    let r = |s: &Surd| root.round_affine(&s.a, &s.b);
    let (normal, degenerate) = match &h.normal {
        Some(n) => ([r(&n[0]), r(&n[1]), r(&n[2])], false),
        None => (round_unit(&[-v[0].clone(), -v[1].clone(), -v[2].clone()]), true),
    };
    ToiAnswer {
        toi: Some(Toi { t: r(&h.t), point: [r(&h.point[0]), r(&h.point[1]), r(&h.point[2])], normal }),
        degenerate,
    }
}

/// The floating-point stage's answer ([`super::toi_fast`]), counted.
pub(super) fn staged<T>(fast: impl FnOnce() -> Option<T>) -> Option<T> {
    super::stage::fast_stage(super::stage::Stage::Toi, fast)
}

fn time(t_max: f64) -> Result<Q, RefereeError> {
    let t = q(t_max, "t_max")?;
    Ok(if t < Q::ZERO { Q::ZERO } else { t })
}

/// The first time `‖w0 + t v‖ = r` for a point at `w0` (relative to a fixed
/// point) moving with `v`, when it starts outside (`‖w0‖ > r`): the smaller root
/// of `A t² + 2B t + C`, `A = v·v`, `B = w0·v`, `C = w0·w0 − r²`, i.e.
/// `t = −B/A − √(B² − AC)/A`. None without motion, when moving away (`B ≥ 0`:
/// both roots ≤ 0) or passing wide (`B² − AC < 0`).
pub(super) fn point_root(w0: &V3, v: &V3, r: &Q) -> Option<Surd> {
    let a = dot(v, v);
    let b = dot(w0, v);
    if a.is_zero() || b >= Q::ZERO {
        return None;
    }
    let c = dot(w0, w0) - r * r;
    let d = &b * &b - &a * &c;
    if d < Q::ZERO {
        return None;
    }
    Some(Surd { a: -(&b / &a), b: -(Q::ONE / &a), d })
}

/// Both times at which the distance of `c + t v` from the line `P0 + σu` is `r`
/// (`w0 = c − P0`): `‖u × (w0 + t v)‖² = r²‖u‖²`, a quadratic with
/// `A = ‖u × v‖²`, `B = (u × w0)·(u × v)`, `C = ‖u × w0‖² − r²‖u‖²`. None when the
/// motion is parallel to the line (`A = 0`: the distance is constant, and a first
/// contact with the edge is at an end, a vertex) or the line is missed.
fn line_roots(w0: &V3, u: &V3, v: &V3, r: &Q) -> Option<[Surd; 2]> {
    let cw = cross(u, w0);
    let cv = cross(u, v);
    let a = dot(&cv, &cv);
    if a.is_zero() {
        return None;
    }
    let b = dot(&cw, &cv);
    let c = dot(&cw, &cw) - r * r * dot(u, u);
    let d = &b * &b - &a * &c;
    if d < Q::ZERO {
        return None;
    }
    let mid = -(&b / &a);
    let half = Q::ONE / &a;
    Some([Surd { a: mid.clone(), b: -half.clone(), d: d.clone() }, Surd { a: mid, b: half, d }])
}

/// The earliest of the valid candidates of one triangle (static, `verts`) for
/// a sphere (centre `c`, radius `r`) moving with `v` relative to it; `vb` moves
/// the contact point to the world frame. The sphere is known to be apart at
/// `t = 0`.
///
/// Candidates: every vertex (the smaller root of the point equation), every edge
/// (both roots of the line equation, kept when the foot `σ(t)` lies in `[0, 1]`)
/// and the face (`N·(p(t) − v0) = ±r‖N‖`, kept when the projection lies in the
/// closed triangle). Each kept candidate is a time at which the distance to the
/// triangle is exactly `r`, and the first contact is one of them (its closest
/// point lies in some feature's region), so the first contact is their minimum.
fn first_contact(c: &V3, r: &Q, v: &V3, vb: &V3, verts: &[V3; 3], t_max: &Q) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    let mut consider = |h: Hit| {
        if h.t.in_interval(t_max) && best.as_ref().is_none_or(|b| h.t.cmp(&b.t) == Ordering::Less) {
            best = Some(h);
        }
    };
    let unit_r = (!r.is_zero()).then(|| Q::ONE / r);
    // Vertices: the normal is (w0 + t v)/r, the point the vertex (moved).
    for vx in verts {
        let w0 = sub(c, vx);
        if let Some(t) = point_root(&w0, v, r) {
            let normal = unit_r.as_ref().map(|k| along(&t, &scale(&w0, k), &scale(v, k)));
            consider(Hit { point: along(&t, vx, vb), normal, t });
        }
    }
    // Edges: foot σ(t)‖u‖² = w0·u + t v·u must lie in [0, ‖u‖²].
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let (p0, u) = (&verts[i], sub(&verts[j], &verts[i]));
        let uu = dot(&u, &u);
        if uu.is_zero() {
            continue;
        }
        let w0 = sub(c, p0);
        let (k, m) = (dot(&w0, &u), dot(v, &u));
        for t in line_roots(&w0, &u, v, r).into_iter().flatten() {
            let foot = t.affine(&k, &m);
            if foot.sign() == Ordering::Less || t.affine(&(&k - &uu), &m).sign() == Ordering::Greater {
                continue;
            }
            // foot point P0 + σu = (P0 + u k/uu) + (u m/uu) t; normal (w0 + t v − σu)/r.
            let foot0 = add(p0, &scale(&u, &(&k / &uu)));
            let foot1 = scale(&u, &(&m / &uu));
            let normal = unit_r
                .as_ref()
                .map(|kr| along(&t, &scale(&sub(&w0, &scale(&u, &(&k / &uu))), kr), &scale(&sub(v, &foot1), kr)));
            consider(Hit { point: along(&t, &foot0, &add(&foot1, vb)), normal, t });
        }
    }
    // Face: e(t) = N·(p(t) − v0) = e0 + t e1 reaches ±r‖N‖.
    let n = cross(&sub(&verts[1], &verts[0]), &sub(&verts[2], &verts[0]));
    let e1 = dot(&n, v);
    if !is_zero(&n) && !e1.is_zero() {
        let nn = dot(&n, &n);
        let e0 = dot(&n, &sub(c, &verts[0]));
        // Edge functions s_ij(t) = ((vj − vi) × (p(t) − vi))·N = s0 + t s1, all ≥ 0
        // inside the closed triangle (the out-of-plane part of p adds nothing).
        let edges: Vec<(Q, Q)> = [(0, 1), (1, 2), (2, 0)]
            .iter()
            .map(|&(i, j)| {
                let e = sub(&verts[j], &verts[i]);
                (dot(&cross(&e, &sub(c, &verts[i])), &n), dot(&cross(&e, v), &n))
            })
            .collect();
        let va = add(v, vb);
        for side in [Q::ONE, Q::NEG_ONE] {
            let t = Surd { a: -(&e0 / &e1), b: &side * r / &e1, d: nn.clone() };
            if edges.iter().any(|(s0, s1)| t.affine(s0, s1).sign() == Ordering::Less) {
                continue;
            }
            // normal = side·N/√NN = (side·N/NN)·√NN; point = c + va t − r·normal.
            let unit: [Surd; 3] = std::array::from_fn(|i| Surd { a: Q::ZERO, b: &side * &n[i] / &nn, d: nn.clone() });
            let point: [Surd; 3] = std::array::from_fn(|i| {
                let p = t.affine(&c[i], &va[i]);
                Surd { b: &p.b - r * &unit[i].b, ..p }
            });
            consider(Hit { t, point, normal: unit_r.is_some().then_some(unit) });
        }
    }
    best
}

pub(super) struct Moving {
    pub(super) c: V3,
    pub(super) r: Q,
    pub(super) va: V3,
    pub(super) vb: V3,
    pub(super) t_max: Q,
}

pub(super) fn moving(a: &Sphere, va: &P3, vb: &P3, t_max: f64) -> Result<Moving, RefereeError> {
    Ok(Moving {
        c: v3(&a.center, "a.center")?,
        r: radius(a.radius, "a.radius")?,
        va: v3(va, "a.velocity")?,
        vb: v3(vb, "b.velocity")?,
        t_max: time(t_max)?,
    })
}

fn triangle(t: &Triangle, field: &'static str) -> Result<[V3; 3], RefereeError> {
    Ok([v3(&t.vertices[0], field)?, v3(&t.vertices[1], field)?, v3(&t.vertices[2], field)?])
}

/// [`moving`]'s checks, in its order, without its rationals ([`check`]).
pub(super) fn check_moving(a: &Sphere, va: &P3, vb: &P3, t_max: f64) -> Result<(), RefereeError> {
    check_v3(&a.center, "a.center")?;
    check_radius(a.radius, "a.radius")?;
    check_v3(va, "a.velocity")?;
    check_v3(vb, "b.velocity")?;
    check(t_max, "t_max")
}

/// [`triangle`]'s checks without its rationals.
fn check_triangle(t: &Triangle, field: &'static str) -> Result<(), RefereeError> {
    t.vertices.iter().try_for_each(|p| check_v3(p, field))
}

/// Time of impact of sphere `a` (centre `M1`, radius `r1`, velocity `va`) and
/// sphere `b` (`M2`, `r2`, `vb`) over `[0, t_max]`.
///
/// **Definition.** With `w = M1 − M2`, `v = va − vb`, `R = r1 + r2`, the spheres
/// touch when `‖w + t v‖ = R`:
///
/// ```text
/// A t² + 2B t + C = 0,   A = v·v,  B = w·v,  C = w·w − R²
/// t = −B/A − √(B² − AC)/A          (the smaller root: the first contact)
/// normal = (w + t v)/R              (from b toward a; ‖w + t v‖ = R exactly)
/// point  = M2 + t vb + r2·normal    (on b, moved)
/// ```
///
/// Already in contact at `t = 0` (`C ≤ 0`): `t = 0` and
/// [`contact_sphere_sphere`]'s answer. No impact when `A = 0` (no relative
/// motion), `B ≥ 0` (moving apart: both roots ≤ 0), `B² − AC < 0` (passing wide;
/// `= 0` is grazing, one touch, and counts) or `t > t_max` (decided exactly).
/// Source: the lecture's sphere–sphere condition in relative motion; Ericson
/// §5.5.5 (`TestMovingSphereSphere`).
///
/// **Degenerate input.** Concentric spheres at `t = 0`: the static fallback
/// (flagged). Two zero radii meet at a point with no direction between them: the
/// normal is `−v/‖v‖` (where `a` came from), flagged.
pub fn toi_sphere_sphere(a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Result<ToiAnswer, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_v3(&b.center, "b.center")?;
    check_radius(b.radius, "b.radius")?;
    let at0 = contact_sphere_sphere(a, b)?;
    if at0.contact.is_some() {
        return Ok(at_zero(at0));
    }
    if let Some(answer) = staged(|| super::toi_fast::sphere_sphere(a, va, b, vb, t_max)) {
        return Ok(answer);
    }
    let s = moving(a, va, vb, t_max)?;
    let mb = v3(&b.center, "b.center")?;
    let rb = radius(b.radius, "b.radius")?;
    let w = sub(&s.c, &mb);
    let v = sub(&s.va, &s.vb);
    let reach = &s.r + &rb;
    let Some(t) = point_root(&w, &v, &reach) else {
        return Ok(ToiAnswer::default());
    };
    if !t.in_interval(&s.t_max) {
        return Ok(ToiAnswer::default());
    }
    let hit = if reach.is_zero() {
        Hit { point: along(&t, &mb, &s.vb), normal: None, t }
    } else {
        // normal = (w + t v)/R; point = M2 + t vb + r2 (w + t v)/R.
        let k = Q::ONE / &reach;
        let kb = &rb * &k;
        Hit {
            point: along(&t, &add(&mb, &scale(&w, &kb)), &add(&s.vb, &scale(&v, &kb))),
            normal: Some(along(&t, &scale(&w, &k), &scale(&v, &k))),
            t,
        }
    };
    Ok(finish(&hit, &v))
}

/// Time of impact of sphere `a` (centre `c`, radius `r`, velocity `va`) and the
/// solid half-space `n·x ≤ d` bounded by plane `b` (velocity `vb`) over
/// `[0, t_max]`.
///
/// **Definition.** The plane translated by `t vb` is `n·x = d + t n·vb`; the
/// centre's distance above it, times `‖n‖`, is `e(t) = e0 + t k` with
/// `e0 = n·c − d`, `k = n·(va − vb)`. Contact when `e(t) ≤ r‖n‖`:
///
/// ```text
/// t      = (r‖n‖ − e0)/k = −e0/k + (r/k)·√(n·n)
/// normal = n/‖n‖,   point = c + t va − r n/‖n‖   (the lowest point, on the plane)
/// ```
///
/// Already in contact at `t = 0`: `t = 0` and [`contact_sphere_plane`]'s answer
/// (a centre inside the solid included). No impact when `k ≥ 0` (parallel or
/// receding) or `t > t_max` (decided exactly). Source: the lecture's
/// sphere–plane condition; Ericson §5.5.3 (`IntersectMovingSpherePlane`).
///
/// **Degenerate input.** None for valid input; a zero normal is refused.
pub fn toi_sphere_plane(a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Result<ToiAnswer, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    let at0 = contact_sphere_plane(a, b)?;
    if at0.contact.is_some() {
        return Ok(at_zero(at0));
    }
    if let Some(answer) = staged(|| super::toi_fast::sphere_plane(a, va, b, vb, t_max)) {
        return Ok(answer);
    }
    let s = moving(a, va, vb, t_max)?;
    let n = v3(&b.normal, "b.normal")?;
    let d = q(b.offset, "b.offset")?;
    let v = sub(&s.va, &s.vb);
    let k = dot(&n, &v);
    if k >= Q::ZERO {
        return Ok(ToiAnswer::default());
    }
    let nn = dot(&n, &n);
    let e0 = dot(&n, &s.c) - d;
    let t = Surd { a: -(&e0 / &k), b: &s.r / &k, d: nn.clone() };
    if !t.in_interval(&s.t_max) {
        return Ok(ToiAnswer::default());
    }
    let normal: [Surd; 3] = std::array::from_fn(|i| Surd { a: Q::ZERO, b: &n[i] / &nn, d: nn.clone() });
    let point: [Surd; 3] = std::array::from_fn(|i| {
        let p = t.affine(&s.c[i], &s.va[i]);
        Surd { b: &p.b - &s.r * &normal[i].b, ..p }
    });
    Ok(finish(&Hit { t, point, normal: Some(normal) }, &v))
}

/// Time of impact of sphere `a` (centre `c`, radius `r`, velocity `va`) and
/// triangle `b` (a two-sided closed sheet, every vertex moving with `vb`) over
/// `[0, t_max]`.
///
/// **Definition.** The first `t` at which `dist(c + t va, b moved by t vb) = r`:
/// in `b`'s frame, the minimum over the candidates of the face interior, the
/// three edges and the three vertices (see the module docs and each feature's
/// equation):
///
/// ```text
/// vertex V:  ‖w + t v‖² = r²,                    w = c − V
/// edge P0P1: ‖u × (w + t v)‖² = r²‖u‖²,          w = c − P0, u = P1 − P0,
///            kept when the foot (w + t v)·u/‖u‖² ∈ [0, 1]
/// face:      N·(w + t v) = ±r‖N‖,                w = c − v0, N = (v1 − v0) × (v2 − v0),
///            kept when the projection lies in the closed triangle
/// ```
///
/// Then the contact: the feature's closest point moved by `t vb` (on `b`), and
/// the normal from it toward the centre, `(p(t) − q)/r` (for the face `±N/‖N‖`).
/// Already in contact at `t = 0`: `t = 0` and [`contact_sphere_triangle`]'s
/// answer. Source: Ericson §5.5.6 (moving sphere against a triangle by its
/// features), evaluated exactly.
///
/// **Degenerate input.** A zero-area triangle has no face but is still its
/// edges and vertices: answered exactly, not flagged. A centre on the triangle
/// at `t = 0`: the static fallback (flagged). A sphere of zero radius meets the
/// triangle at a point with no direction: normal `−v/‖v‖`, flagged.
pub fn toi_sphere_triangle(a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Result<ToiAnswer, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_triangle(b, "b.vertices")?;
    let at0 = contact_sphere_triangle(a, b)?;
    if at0.contact.is_some() {
        return Ok(at_zero(at0));
    }
    if let Some(answer) = staged(|| super::toi_fast::sphere_triangle(a, va, b, vb, t_max)) {
        return Ok(answer);
    }
    let s = moving(a, va, vb, t_max)?;
    let verts = triangle(b, "b.vertices")?;
    let v = sub(&s.va, &s.vb);
    Ok(match first_contact(&s.c, &s.r, &v, &s.vb, &verts, &s.t_max) {
        Some(h) => finish(&h, &v),
        None => ToiAnswer::default(),
    })
}

/// [`mesh`]'s checks, in its order, without its rationals.
fn check_mesh(vertices: &[P3], triangles: &[[usize; 3]]) -> Result<(), RefereeError> {
    vertices.iter().try_for_each(|p| check_v3(p, "b.vertices"))?;
    match triangles.iter().position(|tri| tri.iter().any(|&i| i >= vertices.len())) {
        Some(face) => Err(RefereeError::IndexOutOfRange { field: "b.triangles", face }),
        None => Ok(()),
    }
}

fn mesh(vertices: &[P3], triangles: &[[usize; 3]]) -> Result<Vec<[V3; 3]>, RefereeError> {
    let verts = vertices.iter().map(|p| v3(p, "b.vertices")).collect::<Result<Vec<_>, _>>()?;
    triangles
        .iter()
        .enumerate()
        .map(|(face, tri)| {
            if tri.iter().any(|&i| i >= verts.len()) {
                return Err(RefereeError::IndexOutOfRange { field: "b.triangles", face });
            }
            Ok([verts[tri[0]].clone(), verts[tri[1]].clone(), verts[tri[2]].clone()])
        })
        .collect()
}

/// An axis-aligned box, `[min, max]` per axis, in `f64`.
type Bounds = (P3, P3);

/// The path of `a`'s centre over `[0, t_max]` in `b`'s frame, `c + t (va − vb)`,
/// in `f64`: its ends (the far one computed, so rounded), a bound on that end's
/// error, and a box holding the exact path.
pub(super) struct Path {
    bounds: Bounds,
    start: P3,
    pub(super) end: P3,
    /// Bound on the far end's error, summed over the axes (≥ its length).
    pub(super) end_error: f64,
}

/// [`Path`] of `a`'s centre: the far end computed in `f64` and its error
/// bounded per axis (three roundings of at most 2⁻⁵³ relative each, taken as
/// 4·2⁻⁵³ of the magnitudes involved, plus an absolute floor for subnormal
/// results); the box is the two ends' widened by that bound. `None` when not
/// finite.
pub(super) fn path_bounds(c: &P3, va: &P3, vb: &P3, t_max: f64) -> Option<Path> {
    let t = t_max.max(0.0);
    let (mut lo, mut hi, mut end, mut end_error) = (*c, *c, *c, 0.0);
    for k in 0..3 {
        end[k] = c[k] + t * (va[k] - vb[k]);
        let err = 8.0 * f64::EPSILON / 2.0 * (c[k].abs() + t * (va[k].abs() + vb[k].abs())) + PATH_ERROR_FLOOR;
        lo[k] = lo[k].min(end[k] - err);
        hi[k] = hi[k].max(end[k] + err);
        end_error += err;
    }
    let finite = lo.iter().chain(&hi).all(|x| x.is_finite()) && end_error.is_finite();
    finite.then_some(Path { bounds: (lo, hi), start: *c, end, end_error })
}

/// A lower bound on the squared distance between the exact path and any
/// point of a face, safe under rounding: the larger of the boxes' gap
/// ([`box_gap2_below`]) and the gap between the path and the ball around the
/// face's box — the `f64` distance from the ball's centre to the `f64` path,
/// less a bound on that distance's rounding error (64·2⁻⁵³ of the magnitudes
/// involved, at least twice what its dozen roundings can add up to), less the
/// far end's error and the ball's radius (rounded up), then shrunk by 2⁻⁵⁰
/// before and after squaring. The ball test rules out faces near the path's box
/// but far from the path itself (a diagonal path's box holds many).
fn face_gap2_below(path: &Path, vertices: &[P3], tri: &[usize; 3]) -> f64 {
    let face = face_bounds(vertices, tri);
    let by_box = box_gap2_below(&path.bounds, &face);
    let norm1 = |v: &P3| v[0].abs() + v[1].abs() + v[2].abs();
    let dot = |a: &P3, b: &P3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let m: P3 = std::array::from_fn(|k| (face.0[k] + face.1[k]) * 0.5);
    let h: P3 = std::array::from_fn(|k| (face.1[k] - face.0[k]) * 0.5);
    // The exact box lies in the ball around the rounded centre with the
    // half-diagonal, rounded up, plus the centre's rounding.
    let radius = dot(&h, &h).sqrt() * (1.0 + 8.0 * f64::EPSILON) + f64::EPSILON * norm1(&m) + PATH_ERROR_FLOOR;
    let (c, e) = (&path.start, &path.end);
    let u: P3 = std::array::from_fn(|k| e[k] - c[k]);
    let w: P3 = std::array::from_fn(|k| m[k] - c[k]);
    let (uu, wu) = (dot(&u, &u), dot(&w, &u));
    // A path so long that `u·u` (or `w·u`) overflows has no foot here: the
    // foot would fall at the start, and the start's distance is no bound on
    // the path's (the boxes' gap alone stands).
    if !(uu.is_finite() && wu.is_finite()) {
        return by_box;
    }
    let t = if uu > 0.0 { (wu / uu).clamp(0.0, 1.0) } else { 0.0 };
    let off: P3 = std::array::from_fn(|k| m[k] - (c[k] + t * u[k]));
    let d = dot(&off, &off).sqrt();
    let error = 64.0 * f64::EPSILON * (norm1(c) + norm1(e) + norm1(&m)) + path.end_error + PATH_ERROR_FLOOR;
    let shrink = 1.0 - 8.0 * f64::EPSILON;
    let gap = (d - error - radius) * shrink;
    if gap.is_finite() && gap > 0.0 { by_box.max(gap * gap * shrink) } else { by_box }
}

/// The absolute part of [`path_bounds`]'s widening: far above the error of
/// any subnormal result (sums and differences of `f64` that land in the
/// subnormal range are exact; a product there errs by at most 2⁻¹⁰⁷⁵).
const PATH_ERROR_FLOOR: f64 = 1e-300;

/// The box of a face.
fn face_bounds(vertices: &[P3], tri: &[usize; 3]) -> Bounds {
    let (mut lo, mut hi) = (vertices[tri[0]], vertices[tri[0]]);
    for &i in &tri[1..] {
        for k in 0..3 {
            lo[k] = lo[k].min(vertices[i][k]);
            hi[k] = hi[k].max(vertices[i][k]);
        }
    }
    (lo, hi)
}

/// A lower bound on the squared distance between any point of box `a` and any
/// point of box `b`, safe under rounding: each axis's gap is a difference of two
/// `f64` (relative error at most 2⁻⁵³, exact when subnormal), shrunk by 2⁻⁵⁰
/// before squaring, and the sum of squares shrunk by 2⁻⁵⁰ again (three more
/// roundings). 0 when the boxes meet or the bound underflows.
fn box_gap2_below(a: &Bounds, b: &Bounds) -> f64 {
    let shrink = 1.0 - 8.0 * f64::EPSILON;
    let mut sum = 0.0;
    for k in 0..3 {
        let gap = (a.0[k] - b.1[k]).max(b.0[k] - a.1[k]).max(0.0) * shrink;
        sum += gap * gap;
    }
    sum * shrink
}

/// An upper bound on `r²` for an `f64` radius (one rounding, widened by 2⁻⁵⁰).
fn r2_above(r: f64) -> f64 {
    r * r * (1.0 + 8.0 * f64::EPSILON)
}

/// Whether `bound`, a lower bound on a squared distance, proves that distance
/// greater than the exact `d2`.
fn beyond(bound: f64, d2: &Q) -> bool {
    Q::try_from(bound).is_ok_and(|b| b > *d2)
}

/// Time of impact of sphere `a` (velocity `va`) and a triangle mesh `b`
/// (`vertices`, `triangles` as 0-based index triples; the whole mesh moving
/// with `vb`) over `[0, t_max]`.
///
/// **Definition.** The minimum over the faces of [`toi_sphere_triangle`]'s exact
/// first contact (each face a two-sided closed sheet); ties (a contact on a
/// shared edge or vertex) go to the lowest face index, whose contact is the same
/// point. Already in contact at `t = 0` with some face: `t = 0` and the static
/// contact with the face nearest the centre (smallest exact distance, lowest
/// index on ties).
///
/// **Degenerate input.** Zero-area faces are their edges and vertices, as for
/// one triangle. An empty mesh is never hit. A face naming a vertex out of range
/// is refused with [`RefereeError::IndexOutOfRange`].
pub fn toi_sphere_mesh(
    a: &Sphere,
    va: &P3,
    vertices: &[P3],
    triangles: &[[usize; 3]],
    vb: &P3,
    t_max: f64,
) -> Result<ToiAnswer, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_mesh(vertices, triangles)?;
    // Faces provably farther than r from the centre's whole path
    // are touched neither at t = 0 nor later: the exact tests skip them (a face
    // in contact at t = 0 is nearer than any skipped one, so the nearest face
    // is the same; a skipped face has no contact time to compare).
    let path = path_bounds(&a.center, va, vb, t_max).filter(|_| super::stage::staged());
    let r2_up = r2_above(a.radius);
    let near: Vec<bool> =
        triangles.iter().map(|tri| path.as_ref().is_none_or(|p| face_gap2_below(p, vertices, tri) <= r2_up)).collect();
    if let Some(answer) = staged(|| super::toi_fast::sphere_mesh(a, va, vertices, triangles, &near, vb, t_max)) {
        return Ok(answer);
    }
    // A contact at t = 0 (the stage above leaves every one to this function)
    // is the static contact with the nearest face, lowest index on a tie —
    // what the exact loop below finds — and contact has stages of its own,
    // exact dyadic numbers included.
    if super::stage::staged() {
        let at0 = contact_sphere_mesh(a, vertices, triangles)?;
        if at0.contact.is_some() {
            return Ok(at_zero(at0));
        }
    }
    let s = moving(a, va, vb, t_max)?;
    let faces = mesh(vertices, triangles)?;
    let tested = near.iter().filter(|n| **n).count() as u64;
    super::stage::count(super::stage::Stage::MeshFaces, true, near.len() as u64 - tested);
    super::stage::count(super::stage::Stage::MeshFaces, false, tested);
    let mut nearest: Option<(Q, usize)> = None;
    for (i, f) in faces.iter().enumerate() {
        if !near[i] {
            continue;
        }
        let w = sub(&s.c, &closest_on_triangle(&s.c, f));
        let d2 = dot(&w, &w);
        if nearest.as_ref().is_none_or(|(best, _)| d2 < *best) {
            nearest = Some((d2, i));
        }
    }
    if let Some((d2, i)) = nearest
        && d2 <= &s.r * &s.r
    {
        let tri = triangles[i];
        let face = Triangle { vertices: [vertices[tri[0]], vertices[tri[1]], vertices[tri[2]]] };
        return Ok(at_zero(contact_sphere_triangle(a, &face)?));
    }
    let v = sub(&s.va, &s.vb);
    let mut best: Option<Hit> = None;
    for (f, _) in faces.iter().zip(&near).filter(|(_, near)| **near) {
        if let Some(h) = first_contact(&s.c, &s.r, &v, &s.vb, f, &s.t_max)
            && best.as_ref().is_none_or(|b| h.t.cmp(&b.t) == Ordering::Less)
        {
            best = Some(h);
        }
    }
    Ok(match best {
        Some(h) => finish(&h, &v),
        None => ToiAnswer::default(),
    })
}

/// `r − √d2`, correctly rounded.
pub(super) fn gap_margin(r: &Q, d2: Q) -> f64 {
    Root::new(d2).round_affine(r, &Q::NEG_ONE)
}

/// The signed closest-approach gap behind [`toi_sphere_sphere`]'s decision,
/// `r1 + r2 − min_{t∈[0,t_max]} ‖w + t v‖`, correctly rounded: ≥ 0 exactly when
/// there is an impact. The minimum of the convex quadratic is at
/// `clamp(−w·v/v·v, 0, t_max)`, a rational.
pub fn toi_margin_sphere_sphere(a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Result<f64, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_v3(&b.center, "b.center")?;
    check_radius(b.radius, "b.radius")?;
    if let Some(margin) = staged(|| super::toi_fast::sphere_sphere_margin(a, va, b, vb, t_max)) {
        return Ok(margin);
    }
    let s = moving(a, va, vb, t_max)?;
    let mb = v3(&b.center, "b.center")?;
    let rb = radius(b.radius, "b.radius")?;
    let w = sub(&s.c, &mb);
    let v = sub(&s.va, &s.vb);
    let vv = dot(&v, &v);
    let tc = if vv.is_zero() { Q::ZERO } else { clamp(-(dot(&w, &v) / vv), &s.t_max) };
    let p = add(&w, &scale(&v, &tc));
    Ok(gap_margin(&(&s.r + &rb), dot(&p, &p)))
}

fn clamp(t: Q, hi: &Q) -> Q {
    if t < Q::ZERO {
        Q::ZERO
    } else if t > *hi {
        hi.clone()
    } else {
        t
    }
}

/// The signed closest-approach gap behind [`toi_sphere_plane`]'s decision,
/// `r − min(e(0), e(t_max))/‖n‖` (the distance above the plane is linear in
/// time), correctly rounded: ≥ 0 exactly when there is an impact.
pub fn toi_margin_sphere_plane(a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Result<f64, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_v3(&b.normal, "b.normal")?;
    check(b.offset, "b.offset")?;
    if b.normal.iter().all(|x| *x == 0.0) {
        return Err(RefereeError::ZeroNormal { field: "b.normal" });
    }
    if let Some(margin) = staged(|| super::toi_fast::sphere_plane_margin(a, va, b, vb, t_max)) {
        return Ok(margin);
    }
    let s = moving(a, va, vb, t_max)?;
    let n = v3(&b.normal, "b.normal")?;
    let d = q(b.offset, "b.offset")?;
    let e0 = dot(&n, &s.c) - d;
    let e1 = &e0 + &s.t_max * dot(&n, &sub(&s.va, &s.vb));
    let e = if e1 < e0 { e1 } else { e0 };
    Ok(Root::new(dot(&n, &n)).round_over(&s.r, &-e))
}

/// The squared distance between segments `[p1, q1]` and `[p2, q2]`, exactly
/// (Ericson §5.1.9, `ClosestPtSegmentSegment`, in rationals: every branch is
/// decided exactly, and parallel segments take `s = 0` then clamp, which the book
/// shows still yields a closest pair).
pub(super) fn dist2_segments(p1: &V3, q1: &V3, p2: &V3, q2: &V3) -> Q {
    let d1 = sub(q1, p1);
    let d2 = sub(q2, p2);
    let r = sub(p1, p2);
    let a = dot(&d1, &d1);
    let e = dot(&d2, &d2);
    let f = dot(&d2, &r);
    let one = Q::ONE;
    let (s, t) = if a.is_zero() && e.is_zero() {
        (Q::ZERO, Q::ZERO)
    } else if a.is_zero() {
        (Q::ZERO, clamp(&f / &e, &one))
    } else {
        let c = dot(&d1, &r);
        if e.is_zero() {
            (clamp(-(&c / &a), &one), Q::ZERO)
        } else {
            let b = dot(&d1, &d2);
            let denom = &a * &e - &b * &b;
            let s = if denom.is_zero() { Q::ZERO } else { clamp((&b * &f - &c * &e) / denom, &one) };
            let tn = &b * &s + &f;
            if tn < Q::ZERO {
                (clamp(-(&c / &a), &one), Q::ZERO)
            } else if tn > e {
                (clamp((&b - &c) / &a, &one), Q::ONE)
            } else {
                (s, tn / &e)
            }
        }
    };
    let x = add(p1, &scale(&d1, &s));
    let y = add(p2, &scale(&d2, &t));
    let w = sub(&x, &y);
    dot(&w, &w)
}

/// The squared distance between segment `[p0, p1]` and the closed triangle,
/// exactly: 0 when the segment crosses the face; otherwise the closest pair of
/// two disjoint convex sets has a vertex of one against the other or an edge
/// against an edge, so it is the least of the endpoints' distances to the
/// triangle and the segment's distances to the three edges (which also covers a
/// segment lying in the triangle's plane, and a zero-area triangle).
fn dist2_segment_triangle(p0: &V3, p1: &V3, verts: &[V3; 3]) -> Q {
    let n = cross(&sub(&verts[1], &verts[0]), &sub(&verts[2], &verts[0]));
    if !is_zero(&n) {
        let e0 = dot(&n, &sub(p0, &verts[0]));
        let e1 = dot(&n, &sub(p1, &verts[0]));
        let straddles = (e0 <= Q::ZERO && e1 >= Q::ZERO) || (e0 >= Q::ZERO && e1 <= Q::ZERO);
        if straddles && !(e0.is_zero() && e1.is_zero()) {
            let s = &e0 / (&e0 - &e1);
            let x = add(p0, &scale(&sub(p1, p0), &s));
            let inside = [(0, 1), (1, 2), (2, 0)]
                .iter()
                .all(|&(i, j)| dot(&cross(&sub(&verts[j], &verts[i]), &sub(&x, &verts[i])), &n) >= Q::ZERO);
            if inside {
                return Q::ZERO;
            }
        }
    }
    let to_tri = |p: &V3| {
        let w = sub(p, &closest_on_triangle(p, verts));
        dot(&w, &w)
    };
    let mut best = to_tri(p0);
    for cand in [
        to_tri(p1),
        dist2_segments(p0, p1, &verts[0], &verts[1]),
        dist2_segments(p0, p1, &verts[1], &verts[2]),
        dist2_segments(p0, p1, &verts[2], &verts[0]),
    ] {
        if cand < best {
            best = cand;
        }
    }
    best
}

/// The signed closest-approach gap behind [`toi_sphere_triangle`]'s decision,
/// `r − dist(path, b)` with the path the centre's segment `c → c + t_max v` in
/// `b`'s frame, correctly rounded: ≥ 0 exactly when there is an impact.
pub fn toi_margin_sphere_triangle(a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Result<f64, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_triangle(b, "b.vertices")?;
    if let Some(margin) = staged(|| super::toi_fast::sphere_triangle_margin(a, va, b, vb, t_max)) {
        return Ok(margin);
    }
    let s = moving(a, va, vb, t_max)?;
    let verts = triangle(b, "b.vertices")?;
    let end = add(&s.c, &scale(&sub(&s.va, &s.vb), &s.t_max));
    Ok(gap_margin(&s.r, dist2_segment_triangle(&s.c, &end, &verts)))
}

/// The signed closest-approach gap behind [`toi_sphere_mesh`]'s decision: the
/// largest face margin, `r − min_faces dist(path, face)`, correctly rounded. An
/// empty mesh is infinitely far: `−∞`.
pub fn toi_margin_sphere_mesh(
    a: &Sphere,
    va: &P3,
    vertices: &[P3],
    triangles: &[[usize; 3]],
    vb: &P3,
    t_max: f64,
) -> Result<f64, RefereeError> {
    check_moving(a, va, vb, t_max)?;
    check_mesh(vertices, triangles)?;
    // Faces in order of a lower bound on their distance from the path; once
    // that bound exceeds the nearest exact distance found, no later face can
    // be nearer, and the minimum is the same as over every face.
    let path = path_bounds(&a.center, va, vb, t_max).filter(|_| super::stage::staged());
    let mut order: Vec<(f64, usize)> = triangles
        .iter()
        .enumerate()
        .map(|(i, tri)| (path.as_ref().map_or(0.0, |p| face_gap2_below(p, vertices, tri)), i))
        .collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    if let Some(margin) = staged(|| super::toi_fast::sphere_mesh_margin(a, va, vertices, triangles, &order, vb, t_max))
    {
        return Ok(margin);
    }
    let s = moving(a, va, vb, t_max)?;
    let faces = mesh(vertices, triangles)?;
    let end = add(&s.c, &scale(&sub(&s.va, &s.vb), &s.t_max));
    let mut nearest: Option<Q> = None;
    let faces_count = order.len() as u64;
    let mut tested = 0;
    for (bound, i) in order {
        if nearest.as_ref().is_some_and(|d2| beyond(bound, d2)) {
            break;
        }
        tested += 1;
        let d2 = dist2_segment_triangle(&s.c, &end, &faces[i]);
        if nearest.as_ref().is_none_or(|best| d2 < *best) {
            nearest = Some(d2);
        }
    }
    super::stage::count(super::stage::Stage::MeshFaces, true, faces_count - tested);
    super::stage::count(super::stage::Stage::MeshFaces, false, tested);
    Ok(match nearest {
        Some(d2) => gap_margin(&s.r, d2),
        None => f64::NEG_INFINITY,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::referee::exact::within_ulps;

    /// The referee is correctly rounded and the expectations below are exact
    /// small dyadic numbers or correctly rounded literals derived independently
    /// (CPython `float(Decimal(...))` at 80 digits, which rounds correctly): no
    /// ulp of slack.
    const EXACT_ULPS: u64 = 0;

    /// `5 − √3`, correctly rounded (CPython Decimal, as above).
    const FIVE_MINUS_SQRT3: f64 = 3.267949192431123;
    /// `√3/2`, correctly rounded: IEEE `sqrt` is correctly rounded and halving is
    /// exact, so `3f64.sqrt() / 2.0` is it too (Decimal agrees).
    const HALF_SQRT3: f64 = 0.8660254037844386;
    /// `3 − √3/2`, correctly rounded (Decimal). The naive f64 evaluation gives the
    /// next float up, 2.1339745962155616.
    const THREE_MINUS_HALF_SQRT3: f64 = 2.133974596215561;
    /// `3 − 1/√2`, correctly rounded (Decimal).
    const THREE_MINUS_INV_SQRT2: f64 = 2.2928932188134525;
    const INV_SQRT2: f64 = std::f64::consts::FRAC_1_SQRT_2;

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

    /// The checks the stages run first refuse what the exact conversions
    /// refuse, naming the same field: every number (a sphere, two
    /// velocities, `t_max`, a triangle, a mesh's vertices) set to NaN or ∞,
    /// every two of them to NaN, the radius to −1, an index out of range.
    #[test]
    fn checks_refuse_as_the_conversions_do() {
        const N: usize = 23;
        let base: [f64; N] = [
            0.0, 0.0, 3.0, 0.5, 0.0, 0.0, -2.0, 0.0, 0.0, 1.0, 4.0, -1.0, -1.0, 0.0, 2.0, -1.0, 0.0, -1.0, 2.0, 0.0,
            0.5, 0.5, -1.0,
        ];
        let p = |x: &[f64; N], i: usize| [x[i], x[i + 1], x[i + 2]];
        let mut variants = vec![(base, 3)];
        for i in 0..N {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                let mut x = base;
                x[i] = bad;
                variants.push((x, 3));
            }
            for j in i + 1..N {
                let mut x = base;
                (x[i], x[j]) = (f64::NAN, f64::NAN);
                variants.push((x, 3));
            }
        }
        let mut x = base;
        x[3] = -1.0;
        variants.extend([(x, 3), (base, 4)]);
        let mut refused = 0;
        for (x, last) in variants {
            let a = sphere(p(&x, 0), x[3]);
            let (va, vb, t_max) = (p(&x, 4), p(&x, 7), x[10]);
            let tri = Triangle { vertices: [p(&x, 11), p(&x, 14), p(&x, 17)] };
            let vertices = vec![tri.vertices[0], tri.vertices[1], tri.vertices[2], p(&x, 20)];
            let triangles = [[0, 1, 2], [0, 1, last]];
            let what = format!("{x:?}, last index {last}");
            let moved = moving(&a, &va, &vb, t_max).err();
            assert_eq!(check_moving(&a, &va, &vb, t_max).err(), moved, "moving: {what}");
            assert_eq!(
                check_triangle(&tri, "b.vertices").err(),
                triangle(&tri, "b.vertices").err(),
                "triangle: {what}"
            );
            assert_eq!(check_mesh(&vertices, &triangles).err(), mesh(&vertices, &triangles).err(), "mesh: {what}");
            refused += usize::from(moved.is_some());
        }
        assert!(refused > 100, "only {refused} refusals");
    }

    fn hit(a: Result<ToiAnswer, RefereeError>, what: &str) -> (Toi, bool) {
        let a = a.unwrap_or_else(|e| panic!("{what}: refused: {e}"));
        (a.toi.unwrap_or_else(|| panic!("{what}: expected an impact")), a.degenerate)
    }

    fn miss(a: Result<ToiAnswer, RefereeError>, what: &str) {
        assert_eq!(a, Ok(ToiAnswer::default()), "{what}");
    }

    const STILL: P3 = [0.0; 3];

    fn ground() -> Plane {
        Plane { normal: [0.0, 0.0, 2.0], offset: 0.0 }
    }

    fn tri() -> Triangle {
        // Right triangle in z = 0, legs 2 on x and y; face normal +z.
        Triangle { vertices: [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]] }
    }

    #[test]
    fn referee_toi_sphere_sphere_head_on_and_t_max() {
        // w = (−10,0,0), v = (4,0,0), R = 2: A = 16, B = −40, C = 96, D = 1600 − 1536
        // = 64: t = (40 − 8)/16 = 2; normal (w + 2v)/2 = (−1,0,0); point
        // (5,0,0) + 2(−2,0,0) + (−1,0,0) = (0,0,0).
        let (a, b) = (sphere([-5.0, 0.0, 0.0], 1.0), sphere([5.0, 0.0, 0.0], 1.0));
        let (va, vb) = ([2.0, 0.0, 0.0], [-2.0, 0.0, 0.0]);
        for t_max in [3.0, 2.0] {
            let (k, deg) = hit(toi_sphere_sphere(&a, &va, &b, &vb, t_max), "head-on");
            assert!(!deg);
            close(k.t, 2.0, "t");
            close_v(k.point, [0.0; 3], "point");
            close_v(k.normal, [-1.0, 0.0, 0.0], "normal");
        }
        close(toi_margin_sphere_sphere(&a, &va, &b, &vb, 2.0).unwrap(), 0.0, "touching at t_max");
        // t_max one ulp below 2: no impact; the closest approach is then
        // ‖−10 + 4(2 − 2⁻⁵²)‖ = 2 + 2⁻⁵⁰, so the margin is −2⁻⁵⁰.
        let below = 2f64.next_down();
        miss(toi_sphere_sphere(&a, &va, &b, &vb, below), "one ulp short");
        close(toi_margin_sphere_sphere(&a, &va, &b, &vb, below).unwrap(), -(2f64.powi(-50)), "margin");
    }

    #[test]
    fn referee_toi_sphere_sphere_glancing() {
        // a at (−5,1,0) → +x past b at 0, radii 1: t = 5 − √3; the centre is then
        // (−√3, 1, 0), the normal and the point on b (−√3/2, 1/2, 0).
        let (k, _) = hit(
            toi_sphere_sphere(&sphere([-5.0, 1.0, 0.0], 1.0), &[1.0, 0.0, 0.0], &sphere([0.0; 3], 1.0), &STILL, 10.0),
            "glancing",
        );
        close(k.t, FIVE_MINUS_SQRT3, "t");
        close_v(k.normal, [-HALF_SQRT3, 0.5, 0.0], "normal");
        close_v(k.point, [-HALF_SQRT3, 0.5, 0.0], "point");
    }

    #[test]
    fn referee_toi_sphere_sphere_grazing_touches_exactly_once() {
        // a at (−5,2,0) → +x past b at 0, radii 1: closest approach 2 = R, D = 0:
        // t = −B/A = 5 exactly, point and normal (0,1,0); the margin is exactly +0.
        let b = sphere([0.0; 3], 1.0);
        let va = [1.0, 0.0, 0.0];
        let a = sphere([-5.0, 2.0, 0.0], 1.0);
        let (k, deg) = hit(toi_sphere_sphere(&a, &va, &b, &STILL, 10.0), "grazing");
        assert!(!deg);
        close(k.t, 5.0, "t");
        close_v(k.point, [0.0, 1.0, 0.0], "point");
        close_v(k.normal, [0.0, 1.0, 0.0], "normal");
        let m = toi_margin_sphere_sphere(&a, &va, &b, &STILL, 10.0).unwrap();
        assert!(m == 0.0 && m.is_sign_positive(), "margin {m:e}");
        // One ulp wider: a miss by exactly 2.next_up() − 2 = 2⁻⁵¹.
        let wide = sphere([-5.0, 2f64.next_up(), 0.0], 1.0);
        miss(toi_sphere_sphere(&wide, &va, &b, &STILL, 10.0), "one ulp wide");
        close(toi_margin_sphere_sphere(&wide, &va, &b, &STILL, 10.0).unwrap(), -(2f64.powi(-51)), "margin");
    }

    #[test]
    fn referee_toi_sphere_sphere_overlap_and_degenerate() {
        // Overlapping at 0 (centres 1.5 apart, radii 1): t = 0 and the static
        // contact (normal +x, point (1,0,0)), whatever the motion.
        let b = sphere([0.0; 3], 1.0);
        for va in [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]] {
            let (k, _) = hit(toi_sphere_sphere(&sphere([1.5, 0.0, 0.0], 1.0), &va, &b, &STILL, 1.0), "overlap");
            close(k.t, 0.0, "t");
            close_v(k.normal, [1.0, 0.0, 0.0], "normal");
            close_v(k.point, [1.0, 0.0, 0.0], "point");
        }
        // Concentric: the static fallback, flagged.
        let (k, deg) = hit(toi_sphere_sphere(&sphere([0.0; 3], 0.5), &STILL, &b, &STILL, 1.0), "concentric");
        assert!(deg);
        close_v(k.normal, [0.0, 0.0, 1.0], "fallback");
        // Two points meeting at the origin at t = 1: normal −v/‖v‖ = (−1,0,0), flagged.
        let (k, deg) = hit(
            toi_sphere_sphere(
                &sphere([-1.0, 0.0, 0.0], 0.0),
                &[1.0, 0.0, 0.0],
                &sphere([1.0, 0.0, 0.0], 0.0),
                &[-1.0, 0.0, 0.0],
                2.0,
            ),
            "points",
        );
        assert!(deg);
        close(k.t, 1.0, "t");
        close_v(k.point, [0.0; 3], "point");
        close_v(k.normal, [-1.0, 0.0, 0.0], "normal");
    }

    #[test]
    fn referee_toi_sphere_sphere_no_impact_and_refusals() {
        let (a, b) = (sphere([-5.0, 0.0, 0.0], 1.0), sphere([0.0; 3], 1.0));
        miss(toi_sphere_sphere(&a, &[-1.0, 0.0, 0.0], &b, &STILL, 10.0), "apart");
        miss(toi_sphere_sphere(&a, &[1.0, 1.0, 0.0], &b, &[1.0, 1.0, 0.0], 10.0), "together");
        miss(toi_sphere_sphere(&a, &[1.0, 0.0, 0.0], &b, &STILL, 2.0), "late");
        miss(toi_sphere_sphere(&a, &[1.0, 0.0, 0.0], &b, &STILL, -1.0), "negative t_max is [0, 0]");
        assert_eq!(
            toi_sphere_sphere(&a, &[f64::NAN, 0.0, 0.0], &b, &STILL, 1.0),
            Err(RefereeError::NonFinite { field: "a.velocity" })
        );
        assert_eq!(
            toi_sphere_sphere(&a, &STILL, &b, &[0.0, f64::INFINITY, 0.0], 1.0),
            Err(RefereeError::NonFinite { field: "b.velocity" })
        );
        assert_eq!(
            toi_sphere_sphere(&a, &STILL, &b, &STILL, f64::NAN),
            Err(RefereeError::NonFinite { field: "t_max" })
        );
    }

    #[test]
    fn referee_toi_sphere_plane() {
        // Centre (1,2,5), r 1, falling at 2 onto z = 0 (normal length 2): t = 2,
        // point (1,2,0), normal +z. The ground rising at 2: t = 1, point (1,2,2).
        let a = sphere([1.0, 2.0, 5.0], 1.0);
        let va = [0.0, 0.0, -2.0];
        let (k, deg) = hit(toi_sphere_plane(&a, &va, &ground(), &STILL, 3.0), "falling");
        assert!(!deg);
        close(k.t, 2.0, "t");
        close_v(k.point, [1.0, 2.0, 0.0], "point");
        close_v(k.normal, [0.0, 0.0, 1.0], "normal");
        let (k, _) = hit(toi_sphere_plane(&a, &va, &ground(), &[0.0, 0.0, 2.0], 3.0), "rising");
        close(k.t, 1.0, "t");
        close_v(k.point, [1.0, 2.0, 2.0], "point");
        // Tilted: plane x + y = 0, centre (3,3,0), r 1, velocity (−1,−1,0):
        // t = 3 − 1/√2, and the lowest point is then exactly the origin.
        let tilted = Plane { normal: [1.0, 1.0, 0.0], offset: 0.0 };
        let (k, _) =
            hit(toi_sphere_plane(&sphere([3.0, 3.0, 0.0], 1.0), &[-1.0, -1.0, 0.0], &tilted, &STILL, 5.0), "tilted");
        close(k.t, THREE_MINUS_INV_SQRT2, "t");
        close_v(k.point, [0.0; 3], "point");
        close_v(k.normal, [INV_SQRT2, INV_SQRT2, 0.0], "normal");
        // t exactly t_max, then one ulp short (margin −2·2⁻⁵²·… : the centre is
        // 2·2⁻⁵² above touching, s = 1 + 2⁻⁵¹).
        assert!(toi_sphere_plane(&a, &va, &ground(), &STILL, 2.0).unwrap().toi.is_some());
        miss(toi_sphere_plane(&a, &va, &ground(), &STILL, 2f64.next_down()), "one ulp short");
        close(
            toi_margin_sphere_plane(&a, &va, &ground(), &STILL, 2f64.next_down()).unwrap(),
            -(2f64.powi(-51)),
            "margin",
        );
        // Parallel, receding: none. Inside the solid: t = 0, depth-style contact.
        miss(toi_sphere_plane(&a, &[1.0, 0.0, 0.0], &ground(), &STILL, 9.0), "parallel");
        miss(toi_sphere_plane(&a, &[0.0, 0.0, 1.0], &ground(), &STILL, 9.0), "receding");
        let (k, _) = hit(toi_sphere_plane(&sphere([5.0, 6.0, -3.0], 1.0), &STILL, &ground(), &STILL, 1.0), "inside");
        close(k.t, 0.0, "t");
        close_v(k.point, [5.0, 6.0, 0.0], "point");
        let zero = Plane { normal: [0.0; 3], offset: 0.0 };
        assert_eq!(toi_sphere_plane(&a, &va, &zero, &STILL, 1.0), Err(RefereeError::ZeroNormal { field: "b.normal" }));
    }

    #[test]
    fn referee_toi_sphere_triangle_regions() {
        // (centre, velocity, point, normal) by hand, r 1, t = 2 each: face from
        // z = 3 down; edge v0v1 (y = 0) from y = −3; vertex v1 from x = 5.
        let cases = [
            ([0.5, 0.5, 3.0], [0.0, 0.0, -1.0], [0.5, 0.5, 0.0], [0.0, 0.0, 1.0], "face"),
            ([0.5, 0.5, -3.0], [0.0, 0.0, 1.0], [0.5, 0.5, 0.0], [0.0, 0.0, -1.0], "face from below"),
            ([1.0, -3.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], "edge"),
            ([1.0, -3.0, 0.5], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, -HALF_SQRT3, 0.5], "edge, off plane"),
            ([5.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0], "vertex"),
        ];
        for (c, va, point, normal, what) in cases {
            let (k, deg) = hit(toi_sphere_triangle(&sphere(c, 1.0), &va, &tri(), &STILL, 5.0), what);
            assert!(!deg, "{what}");
            // Off the plane by 0.5: the distance to the edge line y = 0 is
            // √(y² + 0.25) = 1 at y = −√3/2, so t = 3 − √3/2.
            let t = if what == "edge, off plane" { THREE_MINUS_HALF_SQRT3 } else { 2.0 };
            close(k.t, t, what);
            close_v(k.point, point, what);
            close_v(k.normal, normal, what);
        }
    }

    #[test]
    fn referee_toi_sphere_triangle_needs_the_feature_tests() {
        // Centre (5, −0.5, 0) → −x, r 1. The hypotenuse's line (x + y = 2) is
        // reached first, at x = 2.5 + √2, but its foot lies beyond v1: not the
        // triangle. The edge v0v1's line is parallel to the motion. The first
        // contact is vertex v1 = (2,0,0): (3 − t)² + 0.25 = 1, t = 3 − √3/2, with
        // the normal (√3/2, −1/2, 0).
        let (k, _) =
            hit(toi_sphere_triangle(&sphere([5.0, -0.5, 0.0], 1.0), &[-1.0, 0.0, 0.0], &tri(), &STILL, 5.0), "vertex");
        close(k.t, THREE_MINUS_HALF_SQRT3, "t (naive f64 is one ulp up)");
        close_v(k.point, [2.0, 0.0, 0.0], "point");
        close_v(k.normal, [HALF_SQRT3, -0.5, 0.0], "normal");
    }

    #[test]
    fn referee_toi_sphere_triangle_grazing_a_vertex() {
        // Centre (3, −4, 0) → +y, r 1: the distance to v1 = (2,0,0) is √(1 + y²),
        // exactly 1 once, at y = 0 (t = 4, D = 0); the edges' feet are outside.
        let va = [0.0, 1.0, 0.0];
        let a = sphere([3.0, -4.0, 0.0], 1.0);
        let (k, _) = hit(toi_sphere_triangle(&a, &va, &tri(), &STILL, 10.0), "grazing");
        close(k.t, 4.0, "t");
        close_v(k.point, [2.0, 0.0, 0.0], "point");
        close_v(k.normal, [1.0, 0.0, 0.0], "normal");
        let m = toi_margin_sphere_triangle(&a, &va, &tri(), &STILL, 10.0).unwrap();
        assert!(m == 0.0 && m.is_sign_positive(), "margin {m:e}");
        // One ulp farther out (x = 3 + 2⁻⁵¹): a miss by 2⁻⁵¹.
        let out = sphere([3f64.next_up(), -4.0, 0.0], 1.0);
        miss(toi_sphere_triangle(&out, &va, &tri(), &STILL, 10.0), "one ulp out");
        close(toi_margin_sphere_triangle(&out, &va, &tri(), &STILL, 10.0).unwrap(), -(2f64.powi(-51)), "margin");
    }

    #[test]
    fn referee_toi_sphere_triangle_tunneling_moving_and_degenerate() {
        // A small fast sphere through the face: t = (3 − 0.1)/10, whose correct
        // rounding is the literal 0.29 (Decimal); at t_max = 1 it is far below.
        let (k, _) =
            hit(toi_sphere_triangle(&sphere([0.5, 0.5, 3.0], 0.1), &[0.0, 0.0, -10.0], &tri(), &STILL, 1.0), "through");
        close(k.t, 0.29, "t");
        close_v(k.point, [0.5, 0.5, 0.0], "point");
        // The triangle rising at 1 toward a still sphere at z = 3: t = 2, point on
        // the moved triangle (0.5, 0.5, 2).
        let (k, _) =
            hit(toi_sphere_triangle(&sphere([0.5, 0.5, 3.0], 1.0), &STILL, &tri(), &[0.0, 0.0, 1.0], 5.0), "moving");
        close(k.t, 2.0, "t");
        close_v(k.point, [0.5, 0.5, 2.0], "point");
        // A zero-area triangle is its segment x ∈ [0, 2]: t = 2 at (1,0,0), defined.
        let flat = Triangle { vertices: [[0.0; 3], [2.0, 0.0, 0.0], [2.0, 0.0, 0.0]] };
        let (k, deg) =
            hit(toi_sphere_triangle(&sphere([1.0, 0.0, 3.0], 1.0), &[0.0, 0.0, -1.0], &flat, &STILL, 5.0), "flat");
        assert!(!deg);
        close(k.t, 2.0, "t");
        close_v(k.point, [1.0, 0.0, 0.0], "point");
        close_v(k.normal, [0.0, 0.0, 1.0], "normal");
        // A point (r 0) falling on the face: t = 3, normal −v/‖v‖ = +z, flagged.
        let (k, deg) =
            hit(toi_sphere_triangle(&sphere([0.5, 0.5, 3.0], 0.0), &[0.0, 0.0, -1.0], &tri(), &STILL, 5.0), "point");
        assert!(deg);
        close(k.t, 3.0, "t");
        close_v(k.normal, [0.0, 0.0, 1.0], "normal");
        // Already overlapping, and a centre on the face (static fallback, flagged).
        let (k, _) =
            hit(toi_sphere_triangle(&sphere([0.5, 0.5, 0.75], 1.0), &[0.0, 0.0, 1.0], &tri(), &STILL, 1.0), "overlap");
        close(k.t, 0.0, "t");
        close_v(k.point, [0.5, 0.5, 0.0], "point");
        let (_, deg) = hit(toi_sphere_triangle(&sphere([0.5, 0.5, 0.0], 1.0), &STILL, &tri(), &STILL, 1.0), "on face");
        assert!(deg);
        miss(toi_sphere_triangle(&sphere([0.5, 0.5, 3.0], 1.0), &[1.0, 0.0, 0.0], &tri(), &STILL, 10.0), "sideways");
    }

    /// A path whose length squared overflows (a sphere of radius 1.4e153
    /// moving 2.4e154 through a tetrahedron of size 1e153, both moving): the
    /// face skipping must not rule a face out from the path's start alone.
    /// Every face is hit (each one's own answer); the mesh's is the earliest,
    /// t = 0.145…, the same with the stages as without.
    #[test]
    fn referee_toi_sphere_mesh_long_path_skips_no_face_it_reaches() {
        let a = Sphere {
            center: [3.1310303430341712e153, 2.1108267093141695e153, 1.841260250693431e153],
            radius: 1.3725049409728446e153,
        };
        let va = [-1.7293686147459996e154, -1.5867995431728833e154, -1.5076426123701341e153];
        let vs = [
            [3.844358783706491e152, -1.3070426409782342e153, 1.36044295386168e153],
            [2.2379665178669997e152, 9.921716518281729e152, 5.580805066462855e152],
            [-1.62480679927288e153, -8.54099351118536e152, 9.752400938818175e152],
            [-7.385505558596373e152, -2.1601811846375226e150, -1.0495408493478584e153],
        ];
        let tris = [[0usize, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let vb = [-5.341508138680669e153, -5.640501147607259e153, 7.033993091736005e152];
        let staged = toi_sphere_mesh(&a, &va, &vs, &tris, &vb, 1.0).unwrap();
        let exact = crate::referee::exact_only(|| toi_sphere_mesh(&a, &va, &vs, &tris, &vb, 1.0).unwrap());
        assert_eq!(staged, exact, "the stages agree bit for bit");
        let first = tris
            .iter()
            .filter_map(|t| {
                let face = Triangle { vertices: [vs[t[0]], vs[t[1]], vs[t[2]]] };
                toi_sphere_triangle(&a, &va, &face, &vb, 1.0).unwrap().toi.map(|k| k.t)
            })
            .fold(f64::INFINITY, f64::min);
        let got = staged.toi.expect("the sphere reaches the mesh");
        close(got.t, first, "the earliest face's time");
    }

    #[test]
    fn referee_toi_sphere_mesh() {
        // A 2×2 square in z = 0 as two faces sharing the diagonal (0,0)–(2,2).
        let vertices = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, 1.0],
            [2.0, 0.0, 1.0],
            [0.0, 2.0, 1.0],
        ];
        let square = [[0, 1, 2], [0, 2, 3]];
        let fall = [0.0, 0.0, -1.0];
        // Onto the shared diagonal at (1,1): both faces at t = 2, the same point.
        let (k, _) =
            hit(toi_sphere_mesh(&sphere([1.0, 1.0, 3.0], 1.0), &fall, &vertices, &square, &STILL, 5.0), "diagonal");
        close(k.t, 2.0, "t");
        close_v(k.point, [1.0, 1.0, 0.0], "point");
        // Onto face 1 only.
        let (k, _) =
            hit(toi_sphere_mesh(&sphere([0.5, 1.5, 3.0], 1.0), &fall, &vertices, &square, &STILL, 5.0), "face 1");
        close(k.t, 2.0, "t");
        // A second face at z = 1 above the first: reached first, t = 5 − 1 − 1 = 3.
        let stacked = [[0, 1, 3], [4, 5, 6]];
        let (k, _) =
            hit(toi_sphere_mesh(&sphere([0.5, 0.5, 5.0], 1.0), &fall, &vertices, &stacked, &STILL, 9.0), "stacked");
        close(k.t, 3.0, "t");
        close_v(k.point, [0.5, 0.5, 1.0], "point");
        // Overlapping at 0: the static contact with the nearest face (z = 1).
        let (k, _) =
            hit(toi_sphere_mesh(&sphere([0.5, 0.5, 1.5], 1.0), &fall, &vertices, &stacked, &STILL, 9.0), "overlap");
        close(k.t, 0.0, "t");
        close_v(k.point, [0.5, 0.5, 1.0], "point");
        // Empty mesh; index out of range.
        miss(toi_sphere_mesh(&sphere([0.0; 3], 1.0), &fall, &vertices, &[], &STILL, 1.0), "empty");
        assert_eq!(
            toi_margin_sphere_mesh(&sphere([0.0; 3], 1.0), &fall, &vertices, &[], &STILL, 1.0),
            Ok(f64::NEG_INFINITY)
        );
        assert_eq!(
            toi_sphere_mesh(&sphere([0.0; 3], 1.0), &fall, &vertices, &[[0, 1, 7]], &STILL, 1.0),
            Err(RefereeError::IndexOutOfRange { field: "b.triangles", face: 0 })
        );
    }

    #[test]
    fn referee_toi_surd_comparison() {
        // Exact orderings, including an exact tie written two ways (√8 = 2√2) and
        // a near tie (√2 = 1.41421356237309504… against its f64 rounding).
        let s = |a: f64, b: f64, d: f64| Surd { a: q(a, "a").unwrap(), b: q(b, "b").unwrap(), d: q(d, "d").unwrap() };
        assert_eq!(s(0.0, 1.0, 8.0).cmp(&s(0.0, 2.0, 2.0)), Ordering::Equal);
        assert_eq!(
            s(0.0, 1.0, 2.0).cmp(&s(std::f64::consts::SQRT_2, 0.0, 0.0)),
            Ordering::Less,
            "f64 √2 = 1.4142135623730951 rounds up"
        );
        assert_eq!(s(1.0, 1.0, 2.0).cmp(&s(3.0, -1.0, 0.25)), Ordering::Less, "2.414 < 2.5");
        assert_eq!(s(-1.0, -1.0, 3.0).cmp(&s(-2.0, -1.0, 2.0)), Ordering::Greater, "−2.732 > −3.414");
        assert_eq!(sign_surd(&q(-3.0, "a").unwrap(), &q(1.0, "b").unwrap(), &q(9.0, "d").unwrap()), Ordering::Equal);
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::referee::exact::ulps;
    use proptest::prelude::*;

    fn coord() -> impl Strategy<Value = f64> {
        // Small integers make touching, grazing and tied features common.
        prop_oneof![(-3i8..=3).prop_map(f64::from), -4.0..4.0f64]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coord(), coord(), coord()]
    }

    fn radius() -> impl Strategy<Value = f64> {
        prop_oneof![(0u8..=2).prop_map(f64::from), 0.0..3.0f64]
    }

    fn t_max() -> impl Strategy<Value = f64> {
        prop_oneof![(0u8..=3).prop_map(f64::from), 0.0..3.0f64]
    }

    /// Exact squared distance from the centre at time `t` (a rational) to the
    /// triangle at time `t`, minus `r²`: > 0 exactly when apart.
    fn apart_at(a: &Sphere, va: &P3, b: &[V3; 3], vb: &P3, t: &Q) -> bool {
        let c = v3(&a.center, "c").unwrap();
        let v = sub(&v3(va, "va").unwrap(), &v3(vb, "vb").unwrap());
        let p = add(&c, &scale(&v, t));
        let w = sub(&p, &closest_on_triangle(&p, b));
        let r = q(a.radius, "r").unwrap();
        dot(&w, &w) > &r * &r
    }

    /// 32 exact sample times of `[0, end]`.
    fn samples(end: &Q) -> impl Iterator<Item = Q> + '_ {
        (0..=32u8).map(move |i| end * Q::from(i) / Q::from(32u8))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn referee_toi_margin_sign_is_the_decision(c in point(), r in radius(), va in point(), other in point(), r2 in radius(), vb in point(), v1 in point(), v2 in point(), tm in t_max()) {
            let a = Sphere { center: c, radius: r };
            let b = Sphere { center: other, radius: r2 };
            let m = toi_margin_sphere_sphere(&a, &va, &b, &vb, tm).unwrap();
            prop_assert_eq!(toi_sphere_sphere(&a, &va, &b, &vb, tm).unwrap().toi.is_some(), !m.is_sign_negative(), "spheres: margin {:e}", m);
            if other.iter().any(|x| x.abs() > 0.0) {
                let p = Plane { normal: other, offset: r2 };
                let m = toi_margin_sphere_plane(&a, &va, &p, &vb, tm).unwrap();
                prop_assert_eq!(toi_sphere_plane(&a, &va, &p, &vb, tm).unwrap().toi.is_some(), !m.is_sign_negative(), "plane: margin {:e}", m);
            }
            let t = Triangle { vertices: [other, v1, v2] };
            let m = toi_margin_sphere_triangle(&a, &va, &t, &vb, tm).unwrap();
            prop_assert_eq!(toi_sphere_triangle(&a, &va, &t, &vb, tm).unwrap().toi.is_some(), !m.is_sign_negative(), "triangle: margin {:e}", m);
        }

        #[test]
        fn referee_toi_sphere_triangle_no_contact_before_t(c in point(), r in radius(), va in point(), v0 in point(), v1 in point(), v2 in point(), vb in point(), tm in t_max()) {
            // Exactly, at 33 rational times: apart everywhere before the reported
            // time (up to the float below it), or everywhere on [0, t_max] when no
            // impact is reported.
            let a = Sphere { center: c, radius: r };
            let t = Triangle { vertices: [v0, v1, v2] };
            let verts = triangle(&t, "t").unwrap();
            let got = toi_sphere_triangle(&a, &va, &t, &vb, tm).unwrap();
            let end = match got.toi {
                None => q(tm, "t_max").unwrap(),
                Some(k) if k.t > 0.0 => q(k.t.next_down(), "t").unwrap(),
                Some(_) => return Ok(()),
            };
            for s in samples(&end) {
                prop_assert!(apart_at(&a, &va, &verts, &vb, &s), "contact at {} before {:?}", round_q(&s), got);
            }
            if let Some(k) = got.toi {
                prop_assert!(k.t <= tm && (k.normal.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-15, "{:?}", k);
            }
        }

        #[test]
        fn referee_toi_sphere_sphere_swap_flips_the_normal(c in point(), r in radius(), va in point(), other in point(), r2 in radius(), vb in point(), tm in t_max()) {
            // The same touching time (bitwise) from either side; the normal negated
            // unless it is a fallback.
            let (a, b) = (Sphere { center: c, radius: r }, Sphere { center: other, radius: r2 });
            let ab = toi_sphere_sphere(&a, &va, &b, &vb, tm).unwrap();
            let ba = toi_sphere_sphere(&b, &vb, &a, &va, tm).unwrap();
            prop_assert_eq!(ab.toi.is_some(), ba.toi.is_some());
            if let (Some(x), Some(y)) = (ab.toi, ba.toi) {
                prop_assert_eq!(x.t.to_bits(), y.t.to_bits(), "t");
                if !ab.degenerate && !ba.degenerate {
                    for k in 0..3 {
                        prop_assert_eq!(ulps(x.normal[k], -y.normal[k]), 0, "normal {:?} vs {:?}", x.normal, y.normal);
                    }
                }
            }
        }

        #[test]
        fn referee_toi_one_face_mesh_is_the_triangle(c in point(), r in radius(), va in point(), v0 in point(), v1 in point(), v2 in point(), vb in point(), tm in t_max()) {
            let a = Sphere { center: c, radius: r };
            let t = Triangle { vertices: [v0, v1, v2] };
            prop_assert_eq!(
                toi_sphere_mesh(&a, &va, &[v0, v1, v2], &[[0, 1, 2]], &vb, tm).unwrap(),
                toi_sphere_triangle(&a, &va, &t, &vb, tm).unwrap()
            );
        }
    }

    fn round_q(x: &Q) -> f64 {
        super::super::exact::round(x)
    }
}
