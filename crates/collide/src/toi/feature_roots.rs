//! The first contact of a moving point at distance `r` with a triangle's
//! vertices and edges, from their quadratics with exactly computed
//! coefficients (for grazing contacts, where the distance is flat).

use crate::exact::bigfloat::{B3, cross3 as cross, dot3 as dot, sub3 as sub};
use crate::exact::{BigFloat, Estimate, Sign, ldexp};
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
