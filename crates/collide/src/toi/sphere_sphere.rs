//! Sphere–sphere time of impact in closed form.

use super::time_of_impact::{Toi, ToiStatus, approach_fallback, clamp_t_max};
use crate::contact::contact_sphere_sphere;
use crate::real::{Real, Vec3, stable_norm, try_normalize_stable};
use crate::shapes::Sphere;

/// Time of impact of sphere `a` (centre `M1`, radius `r1`, velocity `va`) and
/// sphere `b` (`M2`, `r2`, `vb`) over `[0, t_max]`, **in closed form**.
///
/// **Formula.** In the relative motion `Δp = M1 − M2`, `Δv = va − vb`, the spheres
/// touch when `‖Δp + t Δv‖ = R` with `R = r1 + r2`, i.e. at the roots of
///
/// ```text
/// a t² + 2 b' t + c = 0,   a = Δv·Δv,   b' = Δp·Δv,   c = Δp·Δp − R²
/// ```
///
/// and the first contact is the smaller root. Written as the textbook
/// `(−b' − √disc)/a` it cancels catastrophically when `c` is small against `b'²`
/// (spheres nearly touching at `t = 0`), so it is taken in the stable form
/// (Numerical Recipes §5.6, Goldberg): with `q = −(b' + sign(b')√disc)` the
/// roots are `q/a` and `c/q`; for approaching spheres `b' < 0`, so
/// `q = −b' + √disc` adds two positive numbers and the first contact is
/// `t = c/q`. The pieces are computed without forming `b'²` or `a·c` either:
///
/// ```text
/// s = ‖Δv‖,  u = Δv/s,  along = −Δp·u  (distance to the closest approach),
/// h = ‖Δp × u‖                         (the closest-approach distance),
/// disc = b'² − a c = s² (R² − h²)      (Lagrange's identity ‖Δp‖² = along² + h²),
/// √disc = s·w,   w = √((R − h)(R + h)),
/// q = s (along + w),   c = (‖Δp‖ − R)(‖Δp‖ + R),   t = c / q.
/// ```
///
/// So the hit-or-miss decision is `h ≤ R` (grazing, `h = R`, touches once and
/// counts), evaluated on well-conditioned quantities. The contact at `t` is the
/// sphere contact there: `n = (Δp + t Δv)/‖Δp + t Δv‖` (from `b` toward `a`),
/// point `M2 + t vb + r2 n` on `b`.
///
/// **Cases.** Already in contact at `t = 0` ([`contact_sphere_sphere`], touching
/// counts): `t = 0`, status [`ToiStatus::Penetrating`], the static contact. No
/// relative motion (`Δv = 0`), moving apart or sideways (`along ≤ 0`), passing
/// wide (`h > R`) or touching after `t_max`: `None`. Otherwise the status is
/// [`ToiStatus::Converged`] and `t` is accurate to a few ulps of the inputs'
/// scale over the closing speed — except near grazing, where `t` depends on the
/// data like `√(R − h)` and any method loses half the digits.
///
/// **Degenerate input.** Concentric spheres at `t = 0` get the static test's
/// fallback normal (flagged). Two spheres of zero total radius meet at a point
/// where `Δp + t Δv = 0` has no direction: the normal is the direction `a` came
/// from, `−Δv/‖Δv‖`, flagged. A scene whose intermediate values overflow is
/// answered `None`, never NaN. A negative or NaN `t_max` is read as 0.
pub fn toi_sphere_sphere<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Sphere<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<Toi<T>> {
    let t_max = clamp_t_max(t_max);
    if let Some(k) = contact_sphere_sphere(a, b) {
        return Some(Toi::penetrating(&k));
    }
    let dp = a.center - b.center;
    let dv = va - vb;
    let reach = a.radius + b.radius;
    let u = try_normalize_stable(&dv)?;
    let s = stable_norm(&dv);
    let along = -dp.dot(&u);
    if along.is_nan() || along <= T::zero() {
        return None;
    }
    let h = stable_norm(&dp.cross(&u));
    if h.is_nan() || h > reach {
        return None;
    }
    let w = ((reach - h) * (reach + h)).sqrt();
    let d = stable_norm(&dp);
    let c = (d - reach) * (d + reach);
    let t = c / (s * (along + w));
    if t.is_nan() || t > t_max {
        return None;
    }
    let t = t.max(T::zero());
    let delta = dp + dv * t;
    let (normal, degenerate) = match try_normalize_stable(&delta) {
        Some(n) if reach > T::zero() => (n, false),
        _ => (approach_fallback(&dv), true),
    };
    Some(Toi {
        t,
        point: b.center + vb * t + normal * b.radius,
        normal,
        status: ToiStatus::Converged,
        iterations: 0,
        degenerate,
    })
}
