//! Outputs with a square root, in double-word numbers ([`super::fast`]):
//! `A + P/√S`, `c − √S`, `r − √W/l`, `v/‖v‖` and `r − e/√S`, each correctly
//! rounded when its rounding is certain ([`certify`], by the sign of an
//! affine form in `√S`), or `None` when the bounds leave it open. The stages
//! written over `super::dyadic::Num` take them for their double-word
//! numbers; they depend on nothing but the double words, so the stages and
//! the dyadic numbers that use them import no one another's module.

use super::fast::{Dw, certify, div_approx, sign_affine_root, sqrt_approx};
use crate::geom::P3;

/// `A + P/√S` correctly rounded, for an exact input `a` and an exact or
/// bounded `P`; `a + 0` (a `−0` input made `+0`, as the exact stage's rounding
/// of the rational zero) when `P` is exactly zero.
pub(super) fn over_root(a: f64, p: Dw, s: Dw, root: Dw) -> Option<f64> {
    if p.is_exact_zero() {
        return Some(a + 0.0);
    }
    // x − m = ((a − m)·√S + P)/√S.
    let candidate = Dw::of(a).add(div_approx(p, root)).approx();
    certify(candidate, |m| sign_affine_root(p, Dw::of(a).sub(m), s))
}

/// `c − √S` (the sphere–sphere depth and margin `ra + rb − ‖Δ‖`), correctly
/// rounded (`+0.0` when touching exactly); `None` when left open.
pub(super) fn minus_root(c: Dw, s: Dw, root: Dw) -> Option<f64> {
    // x − m = (c − m) − √S.
    certify(c.sub(root).approx(), |m| sign_affine_root(c.sub(m), Dw::of(-1.0), s))
}

/// `r − √W/l` (`l > 0`, `W > 0`): a depth from a squared distance `W/l²`,
/// correctly rounded, or `None` when left open.
pub(super) fn root_over_depth(r: f64, w: Dw, l: Dw) -> Option<f64> {
    // x − m = ((r − m)·l − √W)/l.
    let candidate = Dw::of(r).sub(div_approx(sqrt_approx(w), l)).approx();
    certify(candidate, |m| sign_affine_root(Dw::of(r).sub(m).mul(l), Dw::of(-1.0), w))
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

/// `r − e/√S` (the sphere–plane depth and margin), correctly rounded, or
/// `None` for the exact stage.
pub(super) fn plane_depth(r: f64, e: Dw, nn: Dw, root: Dw) -> Option<f64> {
    if e.is_exact_zero() {
        return Some(r + 0.0);
    }
    // x − m = ((r − m)·√S − e)/√S.
    certify(Dw::of(r).sub(div_approx(e, root)).approx(), |m| sign_affine_root(e.neg(), Dw::of(r).sub(m), nn))
}
