//! Sphere–box time of impact by the lecture's interval halving.

use super::halving::{horizon, toi_halving};
use super::time_of_impact::{Halving, Toi};
use crate::boxes::contact_sphere_box_lecture;
use crate::real::{Real, Vec3};
use crate::shapes::{OrientedBox, Sphere};

/// Time of impact of sphere `a` (velocity `va`) and oriented box `b`
/// (velocity `vb`, translating with its rotation fixed) over `[0, t_max]` by
/// **the lecture's interval halving**: [`toi_halving`] on the static test
/// [`contact_sphere_box_lecture`] at time `t`.
///
/// **Formula.** At time `t` the sphere is `Sphere(M + t·va, r)` and the box
/// `OrientedBox(c + t·vb, h, q)`; each test takes the centre into the box's
/// frame, `u = Rᵀ(M(t) − c(t))` (`R` the lecture's matrix of the normalized
/// quaternion), clamps it to `[−h, h]` and decides `‖u − clamp(u)‖ ≤ r`. The
/// answer is the upper end of the final bracket with the contact there,
/// within `t_max / 2^k` after `k` bisections.
///
/// **Misses.** Only the end of the interval is tested first: a sphere that
/// passes through the box, or past one of its edges or corners, within the
/// interval and is clear of it at `t_max` is missed — the tunneling case the
/// lecture's method is known for (a thin or flat box makes it common). See
/// [`toi_halving`].
///
/// **Degenerate input.** A centre inside the box at the reported time gets the
/// static test's nearest face, flagged on a tie; a zero half-extent is a flat
/// box; a quaternion whose plain norm under- or overflows is the identity (the
/// lecture's matrix failing); a static contact whose numbers are not finite is
/// none; a negative or NaN `t_max` is read as 0. A `t_max` so large that the
/// motion leaves the type's range is cut to the last time it stays
/// representable (`halving::horizon`, a documented deviation: the lecture
/// never meets such a step).
pub fn toi_sphere_box_halving<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &OrientedBox<T>,
    vb: &Vec3<T>,
    t_max: T,
    stop: Halving<T>,
) -> Option<Toi<T>> {
    toi_halving(
        |t| {
            let moved = OrientedBox { center: b.center + vb * t, ..*b };
            contact_sphere_box_lecture(&Sphere::new(a.center + va * t, a.radius), &moved)
        },
        horizon(t_max, &[va, vb]),
        stop,
    )
}
