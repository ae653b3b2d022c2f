//! The impulse between two spheres, with the normal found from the spheres.

use super::impulse::Response;
use super::sphere_sphere::respond_sphere_sphere;
use crate::contact::CONCENTRIC_FALLBACK_NORMAL;
use crate::real::{Real, Vec3, c};
use crate::shapes::Sphere;

/// Velocities of spheres `a` (velocity `va`, mass `ma`) and `b` (`vb`, `mb`) after
/// one frictionless impulse with restitution `e` along their contact normal, the
/// fixture format's `response` query.
///
/// **Formula.** The contact normal of two spheres is the line of centres,
/// `n = (M1 − M2)/‖M1 − M2‖` (from `b` toward `a`), whether they touch, overlap
/// or are a little apart (a stepped simulation resolves the contact it found a
/// step late); then [`respond_sphere_sphere`]:
/// `j = −(1 + e)(v_rel·n)/(1/ma + 1/mb)`, `va' = va + (j/ma) n`,
/// `vb' = vb − (j/mb) n`, and separating bodies (`v_rel·n ≥ 0`) keep their
/// velocities.
///
/// **Degenerate input.** Concentric spheres have no line of centres: the normal
/// is [`CONCENTRIC_FALLBACK_NORMAL`] (as for their contact), the impulse is
/// applied along it, and `degenerate` is set. Masses and `e` as in
/// [`respond_sphere_sphere`].
pub fn respond_sphere_sphere_contact<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    ma: T,
    b: &Sphere<T>,
    vb: &Vec3<T>,
    mb: T,
    e: T,
) -> Response<T> {
    let mut delta = a.center - b.center;
    if !crate::real::finite3(&delta) {
        // Centres so far apart that the difference overflows: the same direction
        // at half scale (exact).
        let h: T = c(0.5);
        delta = a.center * h - b.center * h;
    }
    if crate::real::try_normalize_stable(&delta).is_some() {
        return respond_sphere_sphere(va, ma, vb, mb, &delta, e);
    }
    let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
    let mut r = respond_sphere_sphere(va, ma, vb, mb, &Vec3::new(c(x), c(y), c(z)), e);
    r.degenerate = true;
    r
}
