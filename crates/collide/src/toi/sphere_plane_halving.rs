//! Sphere–plane time of impact by the lecture's interval halving.

use super::halving::{horizon, toi_halving};
use super::time_of_impact::{Halving, Toi};
use crate::contact::contact_sphere_plane;
use crate::real::{Real, Vec3};
use crate::shapes::{Plane, Sphere};

/// Time of impact of sphere `a` (velocity `va`) and the solid half-space
/// `n·x ≤ d` bounded by plane `b` (velocity `vb`) over `[0, t_max]`, by **the
/// lecture's interval halving**: [`toi_halving`] on the static test
/// [`contact_sphere_plane`] at time `t`.
///
/// **Formula.** At time `t` the sphere is `Sphere(M + t·va, r)` and the plane,
/// translated by `t·vb`, is `n·(x − t·vb) = d`, i.e. `n·x = d + t (n·vb)`; each
/// test decides `(n·(M + t va) − d − t n·vb)/‖n‖ ≤ r`. The answer is the upper
/// end of the final bracket with the contact there, within `t_max / 2^k` after
/// `k` bisections.
///
/// **Misses.** The half-space is solid and unbounded, so a sphere that reaches
/// it stays in it: halving only misses here when the plane moves away again
/// within the interval. See [`toi_halving`].
///
/// **Degenerate input.** A zero or non-finite normal defines no plane: no
/// contact is ever found and the answer is `None`, as for
/// [`contact_sphere_plane`]. A negative or NaN `t_max` is read as 0.
/// A `t_max` so large that the motion leaves the type's range is cut to the
/// last time it stays representable (`halving::horizon`, a documented
/// deviation: the lecture never meets such a step).
pub fn toi_sphere_plane_halving<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Plane<T>,
    vb: &Vec3<T>,
    t_max: T,
    stop: Halving<T>,
) -> Option<Toi<T>> {
    toi_halving(
        |t| {
            contact_sphere_plane(
                &Sphere::new(a.center + va * t, a.radius),
                &Plane::new(b.normal, b.offset + b.normal.dot(vb) * t),
            )
        },
        horizon(t_max, &[va, vb]),
        stop,
    )
}
