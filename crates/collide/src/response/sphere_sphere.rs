//! The impulse between two spheres along a given normal.

use super::impulse::Response;
use crate::real::{Real, Vec3, try_normalize_stable};

/// Velocities of spheres `a` (velocity `va`, mass `ma`) and `b` (`vb`, `mb`) after
/// one frictionless impulse with restitution `e` along the contact `normal`
/// (from `b` toward `a`; any non-zero length, it is normalized).
///
/// **Formula** (the lecture's rigid collision; Hecker, *Physics, Part 3:
/// Collision Response*, 1997, without the angular terms, which vanish for
/// spheres hit along the line of centres). With `n` the unit normal and the
/// relative velocity `v_rel = va − vb`, the normal approach speed is
/// `v_n = v_rel·n` (negative when approaching). Newton's restitution law asks
/// `v_n' = −e v_n` after the impulse `j n` on `a` and `−j n` on `b`:
///
/// ```text
/// v_n' = v_n + j (1/ma + 1/mb) = −e v_n
///   ⇒  j = −(1 + e) v_n / (1/ma + 1/mb)
/// va' = va + (j/ma) n,    vb' = vb − (j/mb) n
/// ```
///
/// Momentum `ma va + mb vb` is conserved (the impulses are opposite), the
/// tangential velocities are untouched (frictionless), and with `e = 1` the
/// kinetic energy is conserved; with `e = 0` the bodies leave with equal normal
/// velocities. Inverse masses are used throughout (not the reduced mass
/// `ma mb/(ma + mb)`, which overflows for large masses), so an infinite mass is
/// a static body: `1/mb = 0` and `b` keeps its velocity.
///
/// **Separating bodies.** When `v_n ≥ 0` (moving apart or sliding) there is
/// nothing to resolve: the velocities are returned unchanged, impulse 0.
///
/// **Degenerate input.** A zero or non-finite normal, a mass that is not
/// positive (or NaN), both masses infinite (`1/ma + 1/mb = 0`), or a non-finite
/// `e`: no impulse can be defined; velocities unchanged, `degenerate: true`.
/// `e` outside `[0, 1]` is applied as given (`e > 1` adds energy).
pub fn respond_sphere_sphere<T: Real>(va: &Vec3<T>, ma: T, vb: &Vec3<T>, mb: T, normal: &Vec3<T>, e: T) -> Response<T> {
    let Some(n) = try_normalize_stable(normal) else {
        return Response::unchanged(va, vb, true);
    };
    if !(ma > T::zero() && mb > T::zero() && e.finite()) {
        return Response::unchanged(va, vb, true);
    }
    let (wa, wb) = (T::one() / ma, T::one() / mb);
    let w = wa + wb;
    if !(w > T::zero() && w.finite()) {
        return Response::unchanged(va, vb, true);
    }
    let vn = (va - vb).dot(&n);
    if vn.is_nan() || vn >= T::zero() {
        return Response::unchanged(va, vb, !vn.finite());
    }
    let j = -(T::one() + e) * vn / w;
    Response { velocity_a: va + n * (j * wa), velocity_b: vb - n * (j * wb), impulse: j, degenerate: false }
}
