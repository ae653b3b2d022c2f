//! The textbook closed form of sphere–sphere time of impact, for the toi
//! bench's reference column: how fast this formula runs with nothing around
//! it, so the table shows what collide's checks cost and how close the
//! formula itself comes to the target.
//!
//! Not an engine: it has no range checks (extreme scales overflow or
//! underflow), no scaled path, no screen before the root, nothing that bounds
//! the normal's length, and concentric spheres get a NaN normal. Only the
//! answer's shape is collide's ([`Toi`]), so both write the same bytes.

use collide::toi::{Toi, ToiStatus};
use collide::{Sphere, Vec3};

/// Sphere `a` moving at `va` against sphere `b` moving at `vb` over
/// `[0, t_max]`: with `Δp = M1 − M2`, `Δv = va − vb`, `R = r1 + r2`,
/// `c = Δp·Δp − R²`, `b' = Δp·Δv`, `disc = b'² − (Δv·Δv) c`, the first root
/// `t = c/(√disc − b')` (the stable form); `t = 0` and the centres' direction
/// when `c ≤ 0`; `None` when moving apart, passing wide or after `t_max`.
#[inline]
pub fn toi_sphere_sphere(
    a: &Sphere<f64>,
    va: &Vec3<f64>,
    b: &Sphere<f64>,
    vb: &Vec3<f64>,
    t_max: f64,
) -> Option<Toi<f64>> {
    let dp = a.center - b.center;
    let dv = va - vb;
    let reach = a.radius + b.radius;
    let dd = dp.norm_squared();
    let c = dd - reach * reach;
    if c <= 0.0 {
        let normal = dp * (1.0 / dd.sqrt());
        let point = b.center + normal * b.radius;
        return Some(Toi { t: 0.0, point, normal, status: ToiStatus::Penetrating, iterations: 0, degenerate: false });
    }
    let bp = dp.dot(&dv);
    let disc = bp * bp - dv.norm_squared() * c;
    if bp >= 0.0 || disc < 0.0 {
        return None;
    }
    let t = c / (disc.sqrt() - bp);
    if t > t_max {
        return None;
    }
    let normal = (dp + dv * t) * (1.0 / reach);
    let point = b.center + vb * t + normal * b.radius;
    Some(Toi { t, point, normal, status: ToiStatus::Converged, iterations: 0, degenerate: false })
}
