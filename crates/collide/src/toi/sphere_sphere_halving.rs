//! Sphere–sphere time of impact by the lecture's interval halving.

use super::halving::{horizon, toi_halving};
use super::time_of_impact::{Halving, Toi};
use crate::contact::contact_sphere_sphere;
use crate::real::{Real, Vec3};
use crate::shapes::Sphere;

/// Time of impact of sphere `a` (velocity `va`) and sphere `b` (velocity `vb`)
/// over `[0, t_max]` by **the lecture's interval halving**: [`toi_halving`] on
/// the static test [`contact_sphere_sphere`] between the spheres moved to time
/// `t`, `Sphere(M + t·v, r)`.
///
/// **Formula.** Each test decides `‖(M1 + t v1) − (M2 + t v2)‖ ≤ r1 + r2`; the
/// bracket `[lo, hi]` keeps `hi` in contact and `lo` apart, and the answer is
/// `hi` with the contact there (normal from `b` toward `a`, point on `b`), within
/// `t_max / 2^k` of the first contact after `k` bisections.
///
/// **Misses.** Spheres that are apart at `t_max` give `None` even when they
/// touched on the way (a fast sphere passing through the other); see
/// [`toi_halving`]. [`super::toi_sphere_sphere`] finds those.
///
/// **Degenerate input.** Concentric spheres at the reported time get the static
/// test's fallback normal (flagged); a negative or NaN `t_max` is read as 0.
/// A `t_max` so large that the motion leaves the type's range is cut to the
/// last time it stays representable (`halving::horizon`, a documented
/// deviation: the lecture never meets such a step).
pub fn toi_sphere_sphere_halving<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Sphere<T>,
    vb: &Vec3<T>,
    t_max: T,
    stop: Halving<T>,
) -> Option<Toi<T>> {
    toi_halving(
        |t| contact_sphere_sphere(&Sphere::new(a.center + va * t, a.radius), &Sphere::new(b.center + vb * t, b.radius)),
        horizon(t_max, &[va, vb]),
        stop,
    )
}
