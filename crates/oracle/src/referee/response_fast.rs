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
//! the certified sign of `vn`. What the double-word bounds leave open (a sign,
//! an output on or near a midpoint, beyond `MAX`) is computed again in exact
//! dyadic numbers ([`super::dyadic`]), where every sign is certain and each
//! output is rounded once from exact integers. `None` — the exact stage
//! answers — for input that is not finite and input the exact stage refuses
//! or flags in its own way (a negative radius, a zero plane normal); the bits
//! are the same (`tests/referee_stages.rs`).

use super::dyadic::{self as dy, Dy, Num};
use super::fast::{Dw, all_finite};
use crate::geom::{P3, Plane, ResponseAnswer, Sphere};

/// Both spheres after the impulse, as `response_sphere_sphere` answers: in
/// double-word numbers, else in exact dyadic ones ([`super::dyadic`]).
pub(super) fn sphere_sphere(
    a: &Sphere,
    va: &P3,
    ma: f64,
    b: &Sphere,
    vb: &P3,
    mb: f64,
    e: f64,
) -> Option<ResponseAnswer> {
    sphere_sphere_in::<Dw>(a, va, ma, b, vb, mb, e).or_else(|| sphere_sphere_in::<Dy>(a, va, ma, b, vb, mb, e))
}

fn sphere_sphere_in<T: Num>(
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
    let delta = dy::diff3::<T>(&a.center, &b.center);
    let concentric = delta.iter().all(T::exact_zero);
    let n = if concentric { [0.0, 0.0, 1.0].map(T::of) } else { delta };
    let vn = dy::dot(&dy::diff3::<T>(va, vb), &n);
    if vn.sign_of()? >= 0 {
        return Some(ResponseAnswer { velocity_a: *va, velocity_b: *vb, degenerate: concentric });
    }
    let total = T::diff(ma, -mb);
    let den = total.times(&dy::dot(&n, &n));
    let kvn = T::diff(1.0, -e).times(&vn);
    let (ka, kb) = (kvn.times(&T::of(mb)), kvn.times(&T::of(ma)));
    let mut velocity_a = [0.0; 3];
    let mut velocity_b = [0.0; 3];
    for i in 0..3 {
        velocity_a[i] = T::quotient(&T::of(va[i]).times(&den).minus(&ka.times(&n[i])), &den)?;
        velocity_b[i] = T::quotient(&T::of(vb[i]).times(&den).plus(&kb.times(&n[i])), &den)?;
    }
    Some(ResponseAnswer { velocity_a, velocity_b, degenerate: concentric })
}

/// The sphere after the impulse against a static plane, as
/// `response_sphere_plane` answers: in double-word numbers, else in exact
/// dyadic ones.
pub(super) fn sphere_plane(va: &P3, b: &Plane, e: f64) -> Option<ResponseAnswer> {
    sphere_plane_in::<Dw>(va, b, e).or_else(|| sphere_plane_in::<Dy>(va, b, e))
}

fn sphere_plane_in<T: Num>(va: &P3, b: &Plane, e: f64) -> Option<ResponseAnswer> {
    let numbers = va.iter().chain(&b.normal).copied().chain([b.offset, e]);
    if !all_finite(numbers) || b.normal.iter().all(|x| *x == 0.0) {
        return None;
    }
    let n = b.normal.map(T::of);
    let vn = dy::dot(&va.map(T::of), &n);
    if vn.sign_of()? >= 0 {
        return Some(ResponseAnswer { velocity_a: *va, velocity_b: [0.0; 3], degenerate: false });
    }
    let nn = dy::dot(&n, &n);
    let kvn = T::diff(1.0, -e).times(&vn);
    let mut velocity_a = [0.0; 3];
    for i in 0..3 {
        velocity_a[i] = T::quotient(&T::of(va[i]).times(&nn).minus(&kvn.times(&n[i])), &nn)?;
    }
    Some(ResponseAnswer { velocity_a, velocity_b: [0.0; 3], degenerate: false })
}
