//! The floating-point stage of a sphere's time of impact with a sphere, a
//! plane, a triangle or a mesh ([`super::fast`]), after the contact at
//! `t = 0` has been ruled out.
//!
//! Every output is `(P + Q·√D)/K` with double-words `P`, `Q`, `K` (`K`'s sign
//! certain) and the quadratic's discriminant or the plane normal's squared
//! length `D ≥ 0`, certified correctly rounded by [`certify`] on the sign of
//! `P − m·K + Q·√D` at the midpoints `m` around a candidate. Every decision
//! (moving apart, passing wide, the impact within `[0, t_max]`) is a certified
//! sign. A triangle's candidates (a root per vertex, two per edge, one per
//! side of the face, as `first_contact` in `toi.rs` lists them) are ordered by
//! their certified roundings: the exact time lies strictly inside its
//! rounding's midpoints. A margin against a triangle or a mesh is the largest
//! of its candidates' (the path's ends and its closest points to each edge,
//! each face), each certified; rounding is monotone, so the largest rounding
//! is the rounding of the largest. `None` — the exact stage answers — whenever anything
//! is left open, for a zero total radius (its normal is a fallback), for a
//! mesh touched at `t = 0`, and for inputs that are not finite; the bits
//! are the same (`tests/referee_stages.rs`).

use super::fast::{Dw, all_finite, certify, cross, diff3, div_approx, dot, sign_affine_root, sqrt_approx};
use super::root_fast::{plane_depth, unit};
use crate::geom::{P3, Plane, Sphere, Toi, ToiAnswer, Triangle};

/// The sign of `P + Q·√S` for an exact `S ≥ 0` (`S` may be exactly 0).
fn sign_surd(p: Dw, q: Dw, s: Dw) -> Option<i8> {
    if s.is_exact_zero() { p.signum() } else { sign_affine_root(p, q, s) }
}

/// `(P + Q·√S)/K` correctly rounded: the value minus `m` has the sign of
/// `P − m·K + Q·√S` times `sk`, `K`'s sign.
fn over_k(p: Dw, q: Dw, s: Dw, root: Dw, k: Dw, sk: i8) -> Option<f64> {
    let candidate = div_approx(p.add(q.mul(root)), k).approx();
    certify(candidate, |m| sign_surd(p.sub(m.mul(k)), q, s).map(|x| x * sk))
}

/// `t_max` as the exact stage reads it: a negative one is 0.
fn horizon(t_max: f64) -> f64 {
    if t_max < 0.0 { 0.0 } else { t_max }
}

/// Two moving spheres: the horizon, `w = M1 − M2`, `v = va − vb`,
/// `R = r1 + r2`, `A = v·v` and `B = w·v`.
struct Spheres {
    tm: Dw,
    w: [Dw; 3],
    v: [Dw; 3],
    big_r: Dw,
    aa: Dw,
    bb: Dw,
}

/// [`Spheres`], or `None` for input outside the stage.
fn spheres(a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Option<Spheres> {
    let numbers = [&a.center, &b.center, va, vb].into_iter().flatten().copied().chain([a.radius, b.radius, t_max]);
    if !(a.radius >= 0.0 && b.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let (w, v) = (diff3(&a.center, &b.center), diff3(va, vb));
    let (aa, bb) = (dot(&v, &v), dot(&w, &v));
    Some(Spheres { tm: Dw::of(horizon(t_max)), w, v, big_r: Dw::diff(a.radius, -b.radius), aa, bb })
}

/// Sphere `a` (velocity `va`) against sphere `b` (velocity `vb`), not in
/// contact at `t = 0`, as `toi_sphere_sphere` answers: the smaller root
/// `t = (−B − √D)/A` of `A t² + 2B t + C` (`A = v·v`, `B = w·v`,
/// `C = w·w − R²`, `D = B² − AC`), normal `(w + t v)/R`, point
/// `M2 + t vb + r2·normal`.
pub(super) fn sphere_sphere(a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Option<ToiAnswer> {
    let Spheres { tm, w, v, big_r, aa, bb } = spheres(a, va, b, vb, t_max)?;
    let none = Some(ToiAnswer::default());
    if aa.signum()? == 0 || bb.signum()? >= 0 {
        return none;
    }
    let cc = dot(&w, &w).sub(big_r.mul(big_r));
    let d = bb.mul(bb).sub(aa.mul(cc));
    if d.signum()? < 0 {
        return none;
    }
    let minus_one = Dw::of(-1.0);
    // 0 ≤ t ≤ t_max, with A > 0.
    if sign_surd(bb.neg(), minus_one, d)? < 0 || sign_surd(bb.neg().sub(tm.mul(aa)), minus_one, d)? > 0 {
        return none;
    }
    if big_r.signum()? <= 0 {
        return None;
    }
    let root = sqrt_approx(d);
    let k = aa.mul(big_r);
    let t = over_k(bb.neg(), minus_one, d, root, aa, 1)?;
    let mut normal = [0.0; 3];
    let mut point = [0.0; 3];
    for i in 0..3 {
        // w_i·A − v_i·B: the normal's numerator's rational part.
        let rational = w[i].mul(aa).sub(v[i].mul(bb));
        normal[i] = over_k(rational, v[i].neg(), d, root, k, 1)?;
        let vb_i = Dw::of(vb[i]);
        let rb = Dw::of(b.radius);
        let p = Dw::of(b.center[i]).mul(k).sub(vb_i.mul(big_r).mul(bb)).add(rb.mul(rational));
        let q = vb_i.mul(big_r).add(rb.mul(v[i])).neg();
        point[i] = over_k(p, q, d, root, k, 1)?;
    }
    Some(ToiAnswer { toi: Some(Toi { t, point, normal }), degenerate: false })
}

/// `R − min_{t ∈ [0, t_max]} ‖w + t v‖`, as `toi_margin_sphere_sphere`
/// answers, or `None`.
pub(super) fn sphere_sphere_margin(a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Option<f64> {
    let Spheres { tm, w, v, big_r, aa, bb } = spheres(a, va, b, vb, t_max)?;
    // The closest approach at tc = clamp(−B/A, 0, t_max) (0 without motion):
    // p = w + tc·v, over a positive denominator l.
    let (p, l) = if aa.signum()? == 0 || bb.neg().signum()? <= 0 {
        (w, Dw::of(1.0))
    } else if bb.neg().sub(tm.mul(aa)).signum()? >= 0 {
        ([0, 1, 2].map(|i| w[i].add(tm.mul(v[i]))), Dw::of(1.0))
    } else {
        ([0, 1, 2].map(|i| w[i].mul(aa).sub(v[i].mul(bb))), aa)
    };
    let pp = dot(&p, &p);
    if pp.is_exact_zero() {
        // R = r1 + r2, rounded once by IEEE addition; beyond MAX, exact.
        let sum = a.radius + b.radius;
        return sum.is_finite().then_some(sum + 0.0);
    }
    // x − m = ((R − m)·l − √pp)/l.
    let candidate = big_r.sub(div_approx(sqrt_approx(pp), l)).approx();
    certify(candidate, |m| sign_affine_root(big_r.sub(m).mul(l), Dw::of(-1.0), pp))
}

/// The parts of sphere `a` against plane `b`: `n`, `n·n`, `e0 = n·c − d`,
/// `k = n·(va − vb)`, or `None` outside the stage.
fn plane_parts(a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Option<([Dw; 3], Dw, Dw, Dw)> {
    let numbers = [&a.center, &b.normal, va, vb].into_iter().flatten().copied().chain([a.radius, b.offset, t_max]);
    if !(a.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let n = b.normal.map(Dw::of);
    let nn = dot(&n, &n);
    if !nn.is_positive() {
        return None;
    }
    let e0 = dot(&n, &a.center.map(Dw::of)).sub(Dw::of(b.offset));
    let k = dot(&n, &diff3(va, vb));
    Some((n, nn, e0, k))
}

/// Sphere `a` against plane `b`, not in contact at `t = 0`, as
/// `toi_sphere_plane` answers: `t = (−e0 + r√nn)/k`, normal `n/‖n‖`, point
/// `c + t va − r·n/‖n‖`.
pub(super) fn sphere_plane(a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Option<ToiAnswer> {
    let (n, nn, e0, k) = plane_parts(a, va, b, vb, t_max)?;
    let none = Some(ToiAnswer::default());
    if k.signum()? >= 0 {
        return none;
    }
    let (tm, r) = (Dw::of(horizon(t_max)), Dw::of(a.radius));
    // With k < 0: t ≥ 0 ⇔ −e0 + r√nn ≤ 0; t ≤ t_max ⇔ −e0 − t_max·k + r√nn ≥ 0.
    if sign_surd(e0.neg(), r, nn)? > 0 || sign_surd(e0.neg().sub(tm.mul(k)), r, nn)? < 0 {
        return none;
    }
    let root = sqrt_approx(nn);
    let t = over_k(e0.neg(), r, nn, root, k, -1)?;
    let normal = unit(&n, nn, root)?;
    // point_i = (c_i·k·nn − e0·va_i·nn + (r·va_i·nn − r·n_i·k)·√nn)/(k·nn).
    let knn = k.mul(nn);
    let mut point = [0.0; 3];
    for i in 0..3 {
        let va_i = Dw::of(va[i]);
        let p = Dw::of(a.center[i]).mul(knn).sub(e0.mul(va_i).mul(nn));
        let q = r.mul(va_i).mul(nn).sub(r.mul(n[i]).mul(k));
        point[i] = over_k(p, q, nn, root, knn, -1)?;
    }
    Some(ToiAnswer { toi: Some(Toi { t, point, normal }), degenerate: false })
}

/// `r − min(e(0), e(t_max))/‖n‖`, as `toi_margin_sphere_plane` answers, or
/// `None`.
pub(super) fn sphere_plane_margin(a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Option<f64> {
    let (_, nn, e0, k) = plane_parts(a, va, b, vb, t_max)?;
    let e1 = e0.add(Dw::of(horizon(t_max)).mul(k));
    let e = if e1.sub(e0).signum()? < 0 { e1 } else { e0 };
    plane_depth(a.radius, e, nn, sqrt_approx(nn))
}

/// `(P + Q·√S)/K` with `K > 0` certified: a candidate's time, or one
/// component of its point or normal, sharing the candidate's `S`.
#[derive(Clone, Copy)]
struct Frac {
    p: Dw,
    q: Dw,
    k: Dw,
}

impl Frac {
    /// Its correct rounding, or `None`.
    fn round(self, s: Dw, root: Dw) -> Option<f64> {
        over_k(self.p, self.q, s, root, self.k, 1)
    }

    /// The sign of `k + m·self`, that is of `k·K + m·P + m·Q·√S`.
    fn affine_sign(self, k: Dw, m: Dw, s: Dw) -> Option<i8> {
        sign_surd(k.mul(self.k).add(m.mul(self.p)), m.mul(self.q), s)
    }
}

/// A valid candidate of a triangle's first contact: its time certified
/// within `[0, t_max]` and correctly rounded (`t`), and the exact point and
/// normal of that time, all in one `√S`.
struct Candidate {
    t: f64,
    s: Dw,
    root: Dw,
    point: [Frac; 3],
    normal: [Frac; 3],
}

/// The moving sphere against a triangle, in the triangle's frame: the centre
/// `c`, the radius, `v = va − vb`, the velocities and the horizon, all inputs
/// finite and the radius positive.
struct Sweep {
    c: P3,
    r: Dw,
    v: [Dw; 3],
    va: P3,
    vb: P3,
    tm: Dw,
}

impl Sweep {
    fn new(a: &Sphere, va: &P3, vb: &P3, t_max: f64, shape: impl IntoIterator<Item = f64>) -> Option<Sweep> {
        let numbers = [&a.center, va, vb].into_iter().flatten().copied().chain([a.radius, t_max]).chain(shape);
        // A zero radius meets the triangle with no normal (the exact stage's
        // fallback direction, flagged): left to it, as is any input outside.
        if !(a.radius > 0.0 && all_finite(numbers)) {
            return None;
        }
        Some(Sweep { c: a.center, r: Dw::of(a.radius), v: diff3(va, vb), va: *va, vb: *vb, tm: Dw::of(horizon(t_max)) })
    }

    /// Pushes `t` onto `out` when it is certified within `[0, t_max]`, with
    /// its point and normal; `None` when a sign or the rounding is left open.
    fn consider(&self, t: Frac, s: Dw, point: [Frac; 3], normal: [Frac; 3], out: &mut Vec<Candidate>) -> Option<()> {
        if sign_surd(t.p, t.q, s)? < 0 || sign_surd(t.p.sub(self.tm.mul(t.k)), t.q, s)? > 0 {
            return Some(());
        }
        let root = sqrt_approx(s);
        out.push(Candidate { t: t.round(s, root)?, s, root, point, normal });
        Some(())
    }

    /// Every valid candidate of one triangle (vertices, edges, the face's two
    /// sides), as `first_contact` in `toi.rs` lists them; the sphere is known
    /// to be apart from it at `t = 0`.
    fn candidates(&self, verts: &[P3; 3], out: &mut Vec<Candidate>) -> Option<()> {
        let (c, r, v) = (&self.c, self.r, &self.v);
        let aa = dot(v, v);
        // Vertices: A t² + 2B t + C with A = v·v, B = w·v, C = w·w − r²; the
        // smaller root (−B − √D)/A when A > 0, B < 0 and D ≥ 0. Point V + t·vb,
        // normal (w + t v)/r.
        if aa.signum()? > 0 {
            for vx in verts {
                let w = diff3(c, vx);
                let bb = dot(&w, v);
                if bb.signum()? >= 0 {
                    continue;
                }
                let d = bb.mul(bb).sub(aa.mul(dot(&w, &w).sub(r.mul(r))));
                if d.signum()? < 0 {
                    continue;
                }
                let t = Frac { p: bb.neg(), q: Dw::of(-1.0), k: aa };
                let point = [0, 1, 2].map(|i| {
                    let vb = Dw::of(self.vb[i]);
                    Frac { p: Dw::of(vx[i]).mul(aa).sub(vb.mul(bb)), q: vb.neg(), k: aa }
                });
                let ar = aa.mul(r);
                let normal = [0, 1, 2].map(|i| Frac { p: w[i].mul(aa).sub(v[i].mul(bb)), q: v[i].neg(), k: ar });
                self.consider(t, d, point, normal, out)?;
            }
        }
        // Edges P0 + σu: ‖u × (w + t v)‖² = r²‖u‖², A = ‖u × v‖², B = (u × w)·(u × v),
        // C = ‖u × w‖² − r²‖u‖², both roots (−B ± √D)/A, kept when the foot
        // k + m·t (k = w·u, m = v·u) lies in [0, ‖u‖²].
        for (i, j) in [(0, 1), (1, 2), (2, 0)] {
            let p0 = &verts[i];
            let u = diff3(&verts[j], p0);
            let uu = dot(&u, &u);
            if uu.signum()? == 0 {
                continue;
            }
            let w = diff3(c, p0);
            let (cw, cv) = (cross(&u, &w), cross(&u, v));
            let a = dot(&cv, &cv);
            if a.signum()? == 0 {
                continue;
            }
            let b = dot(&cw, &cv);
            let d = b.mul(b).sub(a.mul(dot(&cw, &cw).sub(r.mul(r).mul(uu))));
            if d.signum()? < 0 {
                continue;
            }
            let (k, m) = (dot(&w, &u), dot(v, &u));
            // k·A − m·B: the foot's rational part over A.
            let foot = k.mul(a).sub(m.mul(b));
            for sigma in [Dw::of(-1.0), Dw::of(1.0)] {
                let t = Frac { p: b.neg(), q: sigma, k: a };
                if t.affine_sign(k, m, d)? < 0 || t.affine_sign(k.sub(uu), m, d)? > 0 {
                    continue;
                }
                let (ua, uar) = (uu.mul(a), uu.mul(a).mul(r));
                let point = [0, 1, 2].map(|x| {
                    let vb = Dw::of(self.vb[x]);
                    Frac {
                        p: Dw::of(p0[x]).mul(ua).add(u[x].mul(foot)).sub(vb.mul(uu).mul(b)),
                        q: sigma.mul(u[x].mul(m).add(vb.mul(uu))),
                        k: ua,
                    }
                });
                let normal = [0, 1, 2].map(|x| Frac {
                    p: w[x].mul(ua).sub(v[x].mul(uu).mul(b)).sub(u[x].mul(foot)),
                    q: sigma.mul(v[x].mul(uu).sub(u[x].mul(m))),
                    k: uar,
                });
                self.consider(t, d, point, normal, out)?;
            }
        }
        // Face: N·(w + t v) = ±r‖N‖ (w = c − v0), t = (−e0 ± r√nn)/e1, kept when
        // every edge function s0 + t·s1 is ≥ 0. Point c + t va ∓ r N/‖N‖, normal
        // ±N/‖N‖.
        let n = cross(&diff3(&verts[1], &verts[0]), &diff3(&verts[2], &verts[0]));
        let e1 = dot(&n, v);
        let n_zero = n.iter().try_fold(true, |z, x| Some(z && x.signum()? == 0))?;
        let e1_sign = e1.signum()?;
        if n_zero || e1_sign == 0 {
            return Some(());
        }
        let sign1 = Dw::of(f64::from(e1_sign));
        let nn = dot(&n, &n);
        let e0 = dot(&n, &diff3(c, &verts[0]));
        let edges = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| {
            let e = diff3(&verts[j], &verts[i]);
            (dot(&cross(&e, &diff3(c, &verts[i])), &n), dot(&cross(&e, v), &n))
        });
        let kt = e1.mul(sign1);
        let knn = kt.mul(nn);
        for side in [Dw::of(1.0), Dw::of(-1.0)] {
            let t = Frac { p: e0.neg().mul(sign1), q: side.mul(r).mul(sign1), k: kt };
            let mut inside = true;
            for (s0, s1) in edges {
                if t.affine_sign(s0, s1, nn)? < 0 {
                    inside = false;
                    break;
                }
            }
            if !inside {
                continue;
            }
            let point = [0, 1, 2].map(|i| {
                let va = Dw::of(self.va[i]);
                Frac {
                    p: Dw::of(c[i]).mul(knn).add(va.mul(t.p).mul(nn)),
                    q: va.mul(t.q).mul(nn).sub(r.mul(side).mul(n[i]).mul(kt)),
                    k: knn,
                }
            });
            let normal = [0, 1, 2].map(|i| Frac { p: Dw::of(0.0), q: side.mul(n[i]), k: nn });
            self.consider(t, nn, point, normal, out)?;
        }
        Some(())
    }
}

/// The first contact among valid candidates, or `None` when the bounds cannot
/// tell it. Candidates whose times round differently are ordered by their
/// roundings (the exact times lie strictly between the midpoints around
/// them). Those tied at the least rounding must all round to the same point
/// and normal: the first contact is one of them, whichever it is. Exactly
/// simultaneous candidates do (each is the triangle's unique nearest point at
/// that time), so the exact stage's choice among ties changes nothing.
fn first(cands: &[Candidate]) -> Option<ToiAnswer> {
    let Some(t) = cands.iter().map(|c| c.t).min_by(f64::total_cmp) else {
        return Some(ToiAnswer::default());
    };
    let mut answer: Option<Toi> = None;
    for c in cands.iter().filter(|c| c.t.to_bits() == t.to_bits()) {
        let mut point = [0.0; 3];
        let mut normal = [0.0; 3];
        for i in 0..3 {
            point[i] = c.point[i].round(c.s, c.root)?;
            normal[i] = c.normal[i].round(c.s, c.root)?;
        }
        let this = Toi { t, point, normal };
        match &answer {
            None => answer = Some(this),
            Some(a) if same_bits(a, &this) => {}
            Some(_) => return None,
        }
    }
    Some(ToiAnswer { toi: answer, degenerate: false })
}

fn same_bits(a: &Toi, b: &Toi) -> bool {
    let bits =
        |x: &Toi| [x.t, x.point[0], x.point[1], x.point[2], x.normal[0], x.normal[1], x.normal[2]].map(f64::to_bits);
    bits(a) == bits(b)
}

/// Sphere `a` (velocity `va`) against triangle `b` (velocity `vb`), apart at
/// `t = 0`, as `toi_sphere_triangle` answers, or `None`.
pub(super) fn sphere_triangle(a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Option<ToiAnswer> {
    let sweep = Sweep::new(a, va, vb, t_max, b.vertices.iter().flatten().copied())?;
    let mut cands = Vec::new();
    sweep.candidates(&b.vertices, &mut cands)?;
    first(&cands)
}

/// Sphere `a` against a mesh's faces marked `near` (the others are proved out
/// of reach of the whole path), as `toi_sphere_mesh` answers, or `None`: every
/// near face must be certified apart from the sphere at `t = 0` (a contact
/// then is the exact stage's), and the least time is taken over every near
/// face's candidates as over one triangle's.
pub(super) fn sphere_mesh(
    a: &Sphere,
    va: &P3,
    vertices: &[P3],
    triangles: &[[usize; 3]],
    near: &[bool],
    vb: &P3,
    t_max: f64,
) -> Option<ToiAnswer> {
    let sweep = Sweep::new(a, va, vb, t_max, vertices.iter().flatten().copied())?;
    let mut cands = Vec::new();
    for (tri, _) in triangles.iter().zip(near).filter(|(_, n)| **n) {
        let verts = [*vertices.get(tri[0])?, *vertices.get(tri[1])?, *vertices.get(tri[2])?];
        if super::contact_fast::touches_triangle(a, &verts)? {
            return None;
        }
        sweep.candidates(&verts, &mut cands)?;
    }
    first(&cands)
}

/// `r − √ww/l` (`l > 0`) correctly rounded: a margin from a squared distance
/// `ww/l²`; `r` itself (`+0.0` for a zero radius) when `ww` is exactly 0.
fn gap_margin(r: f64, ww: Dw, l: Dw) -> Option<f64> {
    if ww.is_exact_zero() {
        return Some(r + 0.0);
    }
    let rr = Dw::of(r);
    // x − m = ((r − m)·l − √ww)/l.
    let candidate = rr.sub(div_approx(sqrt_approx(ww), l)).approx();
    certify(candidate, |m| sign_affine_root(rr.sub(m).mul(l), Dw::of(-1.0), ww))
}

/// `N/D` clamped to `[0, 1]`, as a fraction with a positive denominator
/// (`D > 0` certified by the caller), decided on certified signs.
fn clamp01(n: Dw, d: Dw) -> Option<(Dw, Dw)> {
    Some(if n.signum()? < 0 {
        (Dw::ZERO, Dw::of(1.0))
    } else if n.sub(d).signum()? > 0 {
        (Dw::of(1.0), Dw::of(1.0))
    } else {
        (n, d)
    })
}

/// The squared distance between segments `p1 + s·d1` and `p2 + t·d2` as
/// `(W·W, L)` with `L > 0` (the distance is `√(W·W)/L`), by `dist2_segments`'
/// branches in `toi.rs` (Ericson's closest points of two segments), each
/// decided on a certified sign. `r12 = p1 − p2`.
fn segments(d1: &[Dw; 3], d2: &[Dw; 3], r12: &[Dw; 3]) -> Option<(Dw, Dw)> {
    let one = Dw::of(1.0);
    let a = dot(d1, d1);
    let e = dot(d2, d2);
    let f = dot(d2, r12);
    let (za, ze) = (a.signum()? == 0, e.signum()? == 0);
    // s = sn/sd, t = tn/td, both denominators positive.
    let ((sn, sd), (tn, td)) = if za && ze {
        ((Dw::ZERO, one), (Dw::ZERO, one))
    } else if za {
        ((Dw::ZERO, one), clamp01(f, e)?)
    } else {
        let c = dot(d1, r12);
        if ze {
            (clamp01(c.neg(), a)?, (Dw::ZERO, one))
        } else {
            let b = dot(d1, d2);
            let denom = a.mul(e).sub(b.mul(b));
            let (sn, sd) = if denom.signum()? == 0 { (Dw::ZERO, one) } else { clamp01(b.mul(f).sub(c.mul(e)), denom)? };
            // tn = b·s + f over sd.
            let tnum = b.mul(sn).add(f.mul(sd));
            if tnum.signum()? < 0 {
                (clamp01(c.neg(), a)?, (Dw::ZERO, one))
            } else if tnum.sub(e.mul(sd)).signum()? > 0 {
                (clamp01(b.sub(c), a)?, (one, one))
            } else {
                ((sn, sd), (tnum, sd.mul(e)))
            }
        }
    };
    // W = r12·sd·td + d1·sn·td − d2·tn·sd over L = sd·td.
    let w = [0, 1, 2].map(|i| r12[i].mul(sd).mul(td).add(d1[i].mul(sn).mul(td)).sub(d2[i].mul(tn).mul(sd)));
    Some((dot(&w, &w), sd.mul(td)))
}

/// The squared distance from a point (known by `rel(x) = p − x`) to a
/// triangle as `(ww, l)`, the distance being `√ww/l`.
fn to_triangle(rel: impl Fn(&P3) -> [Dw; 3], verts: &[P3; 3]) -> Option<(Dw, Dw)> {
    Some(match super::contact_fast::near_by(rel, verts)? {
        super::contact_fast::Near::Feature { l, ww, .. } => (ww, l),
        // |e|/√nn = √(e²·nn)/nn.
        super::contact_fast::Near::Face { nn, e, .. } => (e.mul(e).mul(nn), nn),
    })
}

/// The margin `r − dist(path, triangle)` of one face, correctly rounded, as
/// `toi_margin_sphere_triangle` answers, or `None`. The path runs from `c` by
/// `d = t_max·v`. Every candidate distance of `dist2_segment_triangle` in
/// `toi.rs` gets its own margin; the answer is the largest (rounding is
/// monotone, `−0.0` below `+0.0`, so the largest rounding is the largest
/// margin's).
fn face_margin(r: f64, c: &P3, d: &[Dw; 3], verts: &[P3; 3]) -> Option<f64> {
    let end_rel = |x: &P3| [0, 1, 2].map(|i| Dw::diff(c[i], x[i]).add(d[i]));
    // Crossing the face: the distance is 0.
    let n = cross(&diff3(&verts[1], &verts[0]), &diff3(&verts[2], &verts[0]));
    if n.iter().try_fold(false, |any, x| Some(any || x.signum()? != 0))? {
        let (e0, e1) = (dot(&n, &diff3(c, &verts[0])), dot(&n, &end_rel(&verts[0])));
        let (s0, s1) = (e0.signum()?, e1.signum()?);
        if s0 * s1 <= 0 && !(s0 == 0 && s1 == 0) {
            // x·(e0 − e1) = (c − vi)·(e0 − e1) + d·e0, and e0 − e1 has the
            // sign of s0 − s1 (not both zero).
            let (den, sd) = (e0.sub(e1), (s0 - s1).signum());
            let mut inside = true;
            for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                let ci = diff3(c, &verts[i]);
                let x = [0, 1, 2].map(|k| ci[k].mul(den).add(d[k].mul(e0)));
                if dot(&cross(&diff3(&verts[j], &verts[i]), &x), &n).signum()? * sd < 0 {
                    inside = false;
                    break;
                }
            }
            if inside {
                return Some(r + 0.0);
            }
        }
    }
    let mut cands = vec![to_triangle(|x| diff3(c, x), verts)?, to_triangle(end_rel, verts)?];
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        cands.push(segments(d, &diff3(&verts[j], &verts[i]), &diff3(c, &verts[i]))?);
    }
    let mut best: Option<f64> = None;
    for (ww, l) in cands {
        let m = gap_margin(r, ww, l)?;
        best = Some(best.map_or(m, |b| if m.total_cmp(&b).is_gt() { m } else { b }));
    }
    best
}

/// The path's parts for a margin: `d = t_max·(va − vb)`, or `None` outside
/// the stage.
fn path(a: &Sphere, va: &P3, vb: &P3, t_max: f64, shape: impl IntoIterator<Item = f64>) -> Option<[Dw; 3]> {
    let numbers = [&a.center, va, vb].into_iter().flatten().copied().chain([a.radius, t_max]).chain(shape);
    if !(a.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    let tm = Dw::of(horizon(t_max));
    Some(diff3(va, vb).map(|x| tm.mul(x)))
}

/// `r − dist(path, b)`, as `toi_margin_sphere_triangle` answers, or `None`.
pub(super) fn sphere_triangle_margin(a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Option<f64> {
    let d = path(a, va, vb, t_max, b.vertices.iter().flatten().copied())?;
    face_margin(a.radius, &a.center, &d, &b.vertices)
}

/// `r − min_faces dist(path, face)`, as `toi_margin_sphere_mesh` answers, or
/// `None`. Faces come in `order` (a lower bound on each one's squared
/// distance from the path, ascending); once a bound exceeds the squared
/// distance behind the best margin so far, no later face is nearer. An empty
/// mesh is the exact stage's.
pub(super) fn sphere_mesh_margin(
    a: &Sphere,
    va: &P3,
    vertices: &[P3],
    triangles: &[[usize; 3]],
    order: &[(f64, usize)],
    vb: &P3,
    t_max: f64,
) -> Option<f64> {
    let d = path(a, va, vb, t_max, vertices.iter().flatten().copied())?;
    let mut best: Option<(f64, f64)> = None;
    for &(bound, i) in order {
        if let Some((_, bound_best)) = best
            && bound > bound_best
        {
            break;
        }
        let tri = triangles.get(i)?;
        let verts = [*vertices.get(tri[0])?, *vertices.get(tri[1])?, *vertices.get(tri[2])?];
        let m = face_margin(a.radius, &a.center, &d, &verts)?;
        if best.is_none_or(|(b, _)| m.total_cmp(&b).is_gt()) {
            best = Some((m, below_of(a.radius, m)));
        }
    }
    best.map(|(m, _)| m)
}

/// A number at or above every squared distance `δ²` whose margin `r − δ`
/// rounds to `m`: `δ ≤ r − m + ulp(m)/2`, so `δ² ≤ (r − m + ulp)²`, raised
/// for the `f64` arithmetic; a face whose lower bound exceeds it is farther
/// than the best face. `+∞` keeps every face when the margin is not finite.
fn below_of(r: f64, m: f64) -> f64 {
    let slack = (m.abs().max(f64::MIN_POSITIVE)).next_up() - m.abs();
    let delta = (r - m).abs() * (1.0 + 4.0 * f64::EPSILON) + 2.0 * slack;
    let up = delta * delta * (1.0 + 8.0 * f64::EPSILON) + f64::MIN_POSITIVE;
    if up.is_finite() { up } else { f64::INFINITY }
}
