//! Sphere–triangle time of impact by the lecture's interval halving.

use super::halving::{horizon, toi_halving};
use super::time_of_impact::{Halving, Toi};
use crate::contact::contact_sphere_triangle;
use crate::real::{Real, Vec3};
use crate::shapes::{Sphere, Triangle};

/// Time of impact of sphere `a` (velocity `va`) and triangle `b` (velocity
/// `vb`, every vertex moving with it) over `[0, t_max]` by **the lecture's
/// interval halving**: [`toi_halving`] on the static test
/// [`contact_sphere_triangle`] at time `t`.
///
/// **Formula.** At time `t` the sphere is `Sphere(M + t·va, r)` and the triangle
/// `[v0 + t vb, v1 + t vb, v2 + t vb]`; each test decides `‖M(t) − q(t)‖ ≤ r` with
/// `q(t)` the triangle's closest point. The answer is the upper end of the final
/// bracket with the contact there, within `t_max / 2^k` after `k` bisections.
///
/// **Misses.** A triangle has no thickness: a sphere that passes through it
/// within the interval (and is clear of it at `t_max`) is missed — the
/// tunneling case the lecture's method is known for. See [`toi_halving`].
///
/// **Degenerate input.** A sphere centre on the triangle at the reported time
/// gets the static test's fallback normal (flagged); a zero-area triangle is the
/// segment or point it collapsed to; a negative or NaN `t_max` is read as 0.
/// A `t_max` so large that the motion leaves the type's range is cut to the
/// last time it stays representable (`halving::horizon`, a documented
/// deviation: the lecture never meets such a step).
pub fn toi_sphere_triangle_halving<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Triangle<T>,
    vb: &Vec3<T>,
    t_max: T,
    stop: Halving<T>,
) -> Option<Toi<T>> {
    toi_halving(
        |t| {
            let d = vb * t;
            let [v0, v1, v2] = b.vertices;
            contact_sphere_triangle(&Sphere::new(a.center + va * t, a.radius), &Triangle::new(v0 + d, v1 + d, v2 + d))
        },
        horizon(t_max, &[va, vb]),
        stop,
    )
}
