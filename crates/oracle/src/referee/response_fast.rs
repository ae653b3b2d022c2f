//! The floating-point stage of collision response ([`super::fast`]): the
//! exact stage's rationals in double-word numbers, every output a certified
//! quotient.
//!
//! With `n` the line of centres (or the plane's normal), `nn = n·n`,
//! `vn = (va − vb)·n` and `k = 1 + e`, the velocities after the impulse are
//!
//! ```text
//! va' = (va·(ma + mb)·nn − k·vn·mb·n) / ((ma + mb)·nn)
//! vb' = (vb·(ma + mb)·nn + k·vn·ma·n) / ((ma + mb)·nn)
//! va' = (va·nn − k·vn·n) / nn                          (against a plane)
//! ```
//!
//! — the exact stage's `va + j'·wa·n` with `wa = 1/ma`, `wb = 1/mb`, the
//! masses cleared from the denominators. The switch "already separating" is
//! the certified sign of `vn`. `None` — the exact stage answers — for a sign
//! the bounds leave open, an output on a midpoint or beyond `MAX`, input that
//! is not finite, and input the exact stage refuses or flags in its own way
//! (a negative radius, a zero plane normal); the bits are the same
//! (`tests/referee_stages.rs`).

use super::fast::{Dw, all_finite, diff3, dot, quotient};
use crate::geom::{P3, Plane, ResponseAnswer, Sphere};

/// Both spheres after the impulse, as `response_sphere_sphere` answers.
pub(super) fn sphere_sphere(
    a: &Sphere,
    va: &P3,
    ma: f64,
    b: &Sphere,
    vb: &P3,
    mb: f64,
    e: f64,
) -> Option<ResponseAnswer> {
    let numbers = [&a.center, &b.center, va, vb].into_iter().flatten().copied().chain([a.radius, b.radius, ma, mb, e]);
    if !(a.radius >= 0.0 && b.radius >= 0.0 && all_finite(numbers)) {
        return None;
    }
    // A mass that is not positive: unchanged and flagged (compared as the
    // exact stage compares the rationals: f64 order is theirs).
    if ma <= 0.0 || mb <= 0.0 {
        return Some(ResponseAnswer { velocity_a: *va, velocity_b: *vb, degenerate: true });
    }
    // Concentric centres (a difference exactly 0): the +z fallback, flagged.
    let delta = diff3(&a.center, &b.center);
    let concentric = delta.iter().all(|x| x.is_exact_zero());
    let n = if concentric { [0.0, 0.0, 1.0].map(Dw::of) } else { delta };
    let vn = dot(&diff3(va, vb), &n);
    if vn.signum()? >= 0 {
        return Some(ResponseAnswer { velocity_a: *va, velocity_b: *vb, degenerate: concentric });
    }
    let total = Dw::diff(ma, -mb);
    let den = total.mul(dot(&n, &n));
    let kvn = Dw::diff(1.0, -e).mul(vn);
    let (ka, kb) = (kvn.mul(Dw::of(mb)), kvn.mul(Dw::of(ma)));
    let mut velocity_a = [0.0; 3];
    let mut velocity_b = [0.0; 3];
    for i in 0..3 {
        velocity_a[i] = quotient(Dw::of(va[i]).mul(den).sub(ka.mul(n[i])), den)?;
        velocity_b[i] = quotient(Dw::of(vb[i]).mul(den).add(kb.mul(n[i])), den)?;
    }
    Some(ResponseAnswer { velocity_a, velocity_b, degenerate: concentric })
}

/// The sphere after the impulse against a static plane, as
/// `response_sphere_plane` answers.
pub(super) fn sphere_plane(va: &P3, b: &Plane, e: f64) -> Option<ResponseAnswer> {
    let numbers = va.iter().chain(&b.normal).copied().chain([b.offset, e]);
    if !all_finite(numbers) || b.normal.iter().all(|x| *x == 0.0) {
        return None;
    }
    let n = b.normal.map(Dw::of);
    let vn = dot(&va.map(Dw::of), &n);
    if vn.signum()? >= 0 {
        return Some(ResponseAnswer { velocity_a: *va, velocity_b: [0.0; 3], degenerate: false });
    }
    let nn = dot(&n, &n);
    let kvn = Dw::diff(1.0, -e).mul(vn);
    let mut velocity_a = [0.0; 3];
    for i in 0..3 {
        velocity_a[i] = quotient(Dw::of(va[i]).mul(nn).sub(kvn.mul(n[i])), nn)?;
    }
    Some(ResponseAnswer { velocity_a, velocity_b: [0.0; 3], degenerate: false })
}
