//! The impulse between a sphere and a static plane.

use super::impulse::Response;
use super::sphere_sphere::respond_sphere_sphere;
use crate::real::{Real, Vec3};

/// Velocity of a sphere (velocity `va`) after one frictionless impulse with
/// restitution `e` against a static plane whose outward normal is `normal` (from
/// the plane toward the sphere; any non-zero length — a [`crate::Plane`]'s
/// `normal` can be passed as it is).
///
/// **Formula.** The plane is a body of infinite mass at rest, so in
/// [`respond_sphere_sphere`] `1/mb = 0` and the sphere's mass cancels: with the
/// unit normal `n` and `v_n = va·n`,
///
/// ```text
/// j/ma = −(1 + e) v_n,    va' = va − (1 + e) (va·n) n
/// ```
///
/// the lecture's reflection with restitution: the normal component is reversed
/// and scaled by `e`, the tangential one kept. A sphere already leaving or
/// sliding (`v_n ≥ 0`) keeps its velocity. `velocity_b` is zero (the plane is
/// static) and `impulse` is `j/ma`, the impulse per unit of the sphere's mass.
///
/// **Degenerate input.** A zero or non-finite normal or a non-finite `e`:
/// velocity unchanged, `degenerate: true`.
pub fn respond_sphere_plane<T: Real>(va: &Vec3<T>, normal: &Vec3<T>, e: T) -> Response<T> {
    let inf = T::one() / T::zero();
    respond_sphere_sphere(va, T::one(), &Vec3::zeros(), inf, normal, e)
}
