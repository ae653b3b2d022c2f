//! The floating-point stage of a sphere's time of impact with a sphere or a
//! plane ([`super::fast`]), after the contact at `t = 0` has been ruled out.
//!
//! Every output is `(P + Q·√D)/K` with double-words `P`, `Q`, `K` (`K`'s sign
//! certain) and the quadratic's discriminant or the plane normal's squared
//! length `D ≥ 0`, certified correctly rounded by [`certify`] on the sign of
//! `P − m·K + Q·√D` at the midpoints `m` around a candidate. Every decision
//! (moving apart, passing wide, the impact within `[0, t_max]`) is a certified
//! sign. `None` — the exact stage answers — whenever anything is left open,
//! for a zero total radius (its normal is a fallback), and for inputs outside
//! the stage's range; the bits are the same (`tests/referee_stages.rs`).

use super::contact_fast::{plane_depth, unit};
use super::fast::{Dw, certify, diff3, div_approx, dot, in_range, sign_affine_root, sqrt_approx};
use crate::geom::{P3, Plane, Sphere, Toi, ToiAnswer};

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
    if !(a.radius >= 0.0 && b.radius >= 0.0 && in_range(numbers)) {
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
        return Some(big_r.approx() + 0.0);
    }
    // x − m = ((R − m)·l − √pp)/l.
    let candidate = big_r.sub(div_approx(sqrt_approx(pp), l)).approx();
    certify(candidate, |m| sign_affine_root(big_r.sub(m).mul(l), Dw::of(-1.0), pp))
}

/// The parts of sphere `a` against plane `b`: `n`, `n·n`, `e0 = n·c − d`,
/// `k = n·(va − vb)`, or `None` outside the stage.
fn plane_parts(a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Option<([Dw; 3], Dw, Dw, Dw)> {
    let numbers = [&a.center, &b.normal, va, vb].into_iter().flatten().copied().chain([a.radius, b.offset, t_max]);
    if !(a.radius >= 0.0 && in_range(numbers)) {
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
