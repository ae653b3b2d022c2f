//! Sphere–sphere time of impact in closed form.

use super::time_of_impact::{Toi, ToiStatus, approach_fallback, clamp_t_max};
use crate::contact::contact_sphere_sphere;
use crate::exact::norm::{clear_miss_factor, normalize, safe_squared_range};
use crate::real::{Real, Vec3, c, stable_norm, try_normalize_stable};
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
/// `(−b' − √disc)/a`, `disc = b'² − a c`, it cancels twice: the root when `c` is
/// small against `b'²` (spheres nearly touching at `t = 0`), the discriminant
/// near grazing. Both are avoided:
///
/// ```text
/// disc = a R² − ‖Δp × Δv‖²        (Lagrange's identity: ‖Δp‖²‖Δv‖² = b'² + ‖Δp × Δv‖²)
/// t    = c / (−b' + √disc)        (Numerical Recipes §5.6; Goldberg)
/// ```
///
/// For approaching spheres `b' < 0`, so the denominator adds two non-negative
/// numbers, and `disc` is a difference of two squares of the data's own size,
/// never of `b'²`. The hit-or-miss decision is `‖Δp × Δv‖² ≤ a R²`: the closest
/// approach `‖Δp × Δv‖ / ‖Δv‖` is at most `R` (grazing, equality, touches once
/// and counts). The contact at `t` is the sphere contact there:
/// `n = (Δp + t Δv)/‖Δp + t Δv‖` (from `b` toward `a`), point `M2 + t vb + r2 n`
/// on `b`. The normal is computed from the split of `Δp + t Δv` into its parts
/// across and along the motion, with `w = Δp × Δv` (the same `w` as in `disc`):
///
/// ```text
/// Δp + t Δv = (Δv × w − √disc Δv) / a,      ‖Δv × w‖² = a ‖w‖²,  ‖√disc Δv‖² = a disc
/// n         = (Δv × w − √disc Δv) / (a R)
/// ```
///
/// (`Δv × (Δp × Δv) = a Δp − b' Δv`, and `t + b'/a = −√disc/a` at the first
/// root.) The two parts are orthogonal and their squared lengths sum to
/// `a (‖w‖² + disc) = a² R²` by the definition of `disc`, so `n` is unit to
/// within `16u` in length for spheres starting up to `2^24` radii apart (see
/// `far_apart`): the roundings of `w` move its direction, as they move every
/// method's, but barely its length. Written as
/// `(Δp + t Δv)/R`, the vector carries the rounding of `Δp`'s scale into its
/// length, and a small sphere coming from afar needs a second root.
///
/// **Cost.** Where `‖Δp‖² + ‖Δv‖² + R² ≤ 2^460` (in `f64`; `2^41` in `f32`),
/// so that every product of two squares lies in the range in which plain sums
/// of squares lose nothing (`[2^−918, 2^920]`), and `‖Δv‖²` and `‖Δp‖² + R²`
/// are at least `2^−459` (so that `a R²` and `‖Δp × Δv‖²`, products of two
/// squares, are not flushed to 0 beside each other: at `2^−400` a head-on
/// pair's `disc` underflowed and `t` came out `8/3` for 2): the dot products, one root and one division for `t`, whose
/// comparison with `t_max` decides, and the normal as above — one more
/// division, by `a R` — for spheres starting up to `2^24` radii apart in `f64`
/// (`2^9.5` in `f32`) with `a R² ≥ 2^−918`, where it is unit to within `16u`
/// in length without normalizing (else one more root and division); the
/// static contact test only for spheres that
/// already overlap or touch within the roundings (`‖Δp‖² ≤ R²(1 + 8u)`, its
/// own clear-miss threshold). Every rare case (out of range, touching, a
/// normal to renormalize) runs out of line from the inputs alone, so the
/// common path keeps nothing alive for it. Outside that range a scaled path
/// computes the same root from lengths divided by the scene's own scale and
/// the unit direction of the motion (see `toi_sphere_sphere_scaled`), which
/// never overflows or underflows spuriously. Measured against parry's
/// `cast_shapes` in `benches/toi.rs`, beside the textbook formula with no
/// checks at all.
///
/// **Cases.** Already in contact at `t = 0` ([`contact_sphere_sphere`], touching
/// counts): `t = 0`, status [`ToiStatus::Penetrating`], the static contact. No
/// relative motion (`Δv = 0`), moving apart or sideways (`b' ≥ 0`), passing
/// wide (`disc < 0`) or touching after `t_max`: `None`. Otherwise the status is
/// [`ToiStatus::Converged`] and `t` is accurate to a few ulps of the inputs'
/// scale over the closing speed — except near grazing, where `t` depends on the
/// data like `√disc` and any method loses half the digits. Spheres the static
/// test calls apart while `‖Δp‖² ≤ R²(1 + 8u)` start within the roundings of
/// touching: `c` is read as `max(c, 0)`, so such a touch may be reported at
/// `t = 0`, converged.
///
/// **Degenerate input.** Concentric spheres at `t = 0` get the static test's
/// fallback normal (flagged). Two spheres of zero total radius meet at a point
/// where `Δp + t Δv = 0` has no direction: the normal is the direction `a` came
/// from, `−Δv/‖Δv‖`, flagged. A scene whose intermediate values overflow is
/// answered `None`, never NaN. A negative or NaN `t_max` is read as 0.
#[inline]
pub fn toi_sphere_sphere<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Sphere<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<Toi<T>> {
    let t_max = clamp_t_max(t_max);
    let m = Relative::new(a, va, b, vb);
    // Within the roundings of touching or closer (`‖Δp‖² ≤ R²(1 + 8u)`), the
    // static test decides whether the spheres are in contact at `t = 0`;
    // beyond, they are certainly apart (its own clear-miss test).
    let near = m.dd <= m.rr * clear_miss_factor::<T>();
    // The range and "apart" tested together (`&`, not `&&`): one branch
    // that is rarely taken, to the rarer cases.
    if !(m.plain() & !near) {
        return rare(a, va, b, vb, t_max);
    }
    m.first_touch(a, va, b, vb, m.dd - m.rr, t_max)
}

/// The relative motion of two spheres and its squares, as the closed form
/// reads them: `Δp = M1 − M2`, `Δv = va − vb`, `R = r1 + r2`, `‖Δp‖²`,
/// `a = ‖Δv‖²`, `R²`.
struct Relative<T: Real> {
    dp: Vec3<T>,
    dv: Vec3<T>,
    reach: T,
    dd: T,
    vv: T,
    rr: T,
}

impl<T: Real> Relative<T> {
    #[inline(always)]
    fn new(a: &Sphere<T>, va: &Vec3<T>, b: &Sphere<T>, vb: &Vec3<T>) -> Self {
        let (dp, dv, reach) = (a.center - b.center, va - vb, a.radius + b.radius);
        Self { dp, dv, reach, dd: dp.norm_squared(), vv: dv.norm_squared(), rr: reach * reach }
    }

    /// Whether the closed form runs on plain squares. The three squares sum
    /// to at most √hi, so every product of two of them (the terms of `disc`,
    /// ‖Δp × Δv‖² ≤ ‖Δp‖²‖Δv‖², a R² for the normal) stays in the plain range,
    /// and `disc`'s root is as accurate as the type allows; ‖Δv‖² and
    /// ‖Δp‖² + R² are at least `√lo`, so `c` is not a difference of
    /// underflowed squares and the products of two squares in `disc` (`a R²`
    /// and `‖Δp × Δv‖²`, of the scales `‖Δv‖²` times `‖Δp‖² + R²`) do not
    /// fall below `lo`, where they would be flushed toward 0 beside each
    /// other. One sum and three comparisons (√lo and √hi are constants). A
    /// NaN fails every test: the scaled path.
    #[inline(always)]
    fn plain(&self) -> bool {
        let (lo, hi) = safe_squared_range::<T>();
        let span = self.dd + self.rr;
        let lo = lo.sqrt();
        (self.vv >= lo) & (span >= lo) & (span + self.vv <= hi.sqrt())
    }

    /// The first touch within `[0, t_max]` of spheres apart at `t = 0`, in the
    /// plain range, with `c = ‖Δp‖² − R²` (see [`toi_sphere_sphere`]).
    #[inline(always)]
    fn first_touch(&self, a: &Sphere<T>, va: &Vec3<T>, b: &Sphere<T>, vb: &Vec3<T>, c: T, t_max: T) -> Option<Toi<T>> {
        let Self { dp, dv, reach, dd, vv, rr } = *self;
        let bp = dp.dot(&dv);
        // Moving apart or sideways. The plain range leaves no NaN here.
        if bp >= T::zero() {
            return None;
        }
        let w = dp.cross(&dv);
        let disc = vv * rr - w.norm_squared();
        // Passing wide.
        if disc < T::zero() {
            return None;
        }
        let root = disc.sqrt();
        let t = c / (root - bp);
        if !(t <= t_max) {
            return None;
        }
        // At the touch ‖Δp + t Δv‖ = R, and a (Δp + t Δv) = Δv × w − √disc Δv,
        // two orthogonal parts whose squares sum to a² R² (see above):
        // dividing by a R keeps a second root off the path, and the division
        // for `t` too. The quotient is unit to within `16 u` in length (see
        // `far_apart`) where a R² ≥ `lo` (then a R ≥ `lo` too, so 1/(a R) is
        // finite and exact to an ulp) and ‖Δp‖² ≤ R² · `far_apart` (spheres
        // starting up to 2^24 radii apart in f64); this depends on the data
        // alone, so the branch is decided early, not after the normal.
        // Otherwise (no radius between the centres, a R out of the normal
        // range, spheres farther apart) `contact_at` normalizes Δp + t Δv by
        // its own norm or falls back.
        let (lo, _) = safe_squared_range::<T>();
        if !((vv * rr >= lo) & (dd <= rr * far_apart::<T>())) {
            return Some(contact_at(a, va, b, vb, t));
        }
        let normal = (dv.cross(&w) - dv * root) * (T::one() / (vv * reach));
        Some(Toi {
            t,
            point: b.center + vb * t + normal * b.radius,
            normal,
            status: ToiStatus::Converged,
            iterations: 0,
            degenerate: false,
        })
    }
}

/// `1/(32u)` (`u` the unit roundoff: `2^48` in `f64`, `2^19` in `f32`): the
/// largest `‖Δp‖²/R²` for which [`toi_sphere_sphere`] reports
/// `(Δv × w − √disc Δv)/(a R)` as the normal without normalizing it, so
/// spheres starting up to `2^24` radii apart in `f64` (`2^9.5` in `f32`).
///
/// **Why the quotient is unit there** (`u` the unit roundoff; `Δp`, `Δv`, `R`
/// as computed, `W` the computed `w`, `a` the computed `‖Δv‖²`; first order
/// in `u`):
/// - `W = w + e`, `‖e‖ ≤ 2√2 u ‖Δp‖‖Δv‖`, and `Δv·w = 0`, so
///   `‖Δv × W‖² = ‖Δv‖²‖W‖² − (Δv·e)²` with `(Δv·e)² ≤ 8u²‖Δv‖⁴‖Δp‖²`: at most
///   `u/4` of `‖Δv‖² a R²` while `‖Δp‖² ≤ R²/(32u)`. This is the only term that
///   grows with the distance.
/// - `disc ≥ 0` was tested, so `‖W‖² ≤ a R²(1 + 4u)`, and
///   `‖W‖² + (√disc)² = a R²(1 + η)` with `|η| ≤ 11u` (the roundings of the
///   squares, `R²`, the difference and the root; `‖W‖²` enters both with
///   opposite signs), which moves the length by `5.5u`.
/// - The cross product, the product by `√disc`, the difference, `a R`, its
///   reciprocal and the scaling add at most `7u` to the length, and
///   `‖Δv‖/√a` is within `1.5u` of 1.
///
/// So `|‖n‖ − 1| ≤ 14.2u < 16u`. On the bench's 1024 campaign cases
/// `|‖n‖² − 1|` reaches `6u` (spheres up to `2^20` radii apart). Units: a ratio of squared
/// lengths.
fn far_apart<T: Real>() -> T {
    T::one() / (c::<T>(16.0) * T::EPSILON)
}

/// The rare cases of [`toi_sphere_sphere`], out of line: squares out of the
/// plain range, and spheres overlapping or within the roundings of touching
/// (`‖Δp‖² ≤ R²(1 + 8u)`), where the static test decides. No relative motion
/// (exactly: a square can underflow) is in contact at 0 and for good, or
/// never. Spheres in contact by the static test get
/// [`ToiStatus::Penetrating`] and the static contact. Spheres it calls
/// apart (within the roundings of touching) take the closed form with
/// `c = max(‖Δp‖² − R², 0)` in the plain range, the scaled path, which
/// decides from lengths, outside it.
#[cold]
#[inline(never)]
fn rare<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Sphere<T>, vb: &Vec3<T>, t_max: T) -> Option<Toi<T>> {
    if let Some(k) = contact_sphere_sphere(a, b) {
        // Flagged for concentric centres (the fallback normal) or a point
        // beyond the range, not for a depth beyond it (see
        // `Toi::penetrating_flagged`).
        let concentric = (a.center - b.center).iter().all(|x| *x == T::zero());
        return Some(Toi::penetrating_flagged(&k, concentric || !crate::real::finite3(&k.point)));
    }
    // A tiny scene (subnormal coordinates, whose differences, norms and
    // quotients lose their few bits) is answered scaled up by a power of two
    // to about 1, exactly, and its point scaled back; times and directions
    // do not scale. The static test has decided the start at the original
    // scale (so the time of impact and the contact agree on it): a contact
    // of the scaled scene at `t = 0` is a touch at 0, within the roundings
    // of the original one, not a penetration.
    if let Some(k) = tiny_scene(a, va, b, vb) {
        use crate::real::{scale2, scale2v};
        let a2 = Sphere::new(scale2v(&a.center, k), scale2(a.radius, k));
        let b2 = Sphere::new(scale2v(&b.center, k), scale2(b.radius, k));
        return toi_sphere_sphere(&a2, &scale2v(va, k), &b2, &scale2v(vb, k), t_max).map(|mut r| {
            r.point = scale2v(&r.point, -k);
            r.status = ToiStatus::Converged;
            r
        });
    }
    let m = Relative::new(a, va, b, vb);
    if m.dv.iter().all(|x| *x == T::zero()) {
        return None;
    }
    if m.plain() {
        // Apart by the static test, within the roundings of touching:
        // ‖Δp‖² − R² may have rounded to 0 or below, and the touch, if any,
        // is a few ulps of R over the closing speed away. From 0.
        return m.first_touch(a, va, b, vb, (m.dd - m.rr).max(T::zero()), t_max);
    }
    toi_sphere_sphere_scaled(a, va, b, vb, t_max)
}

/// The power of two `2^k` (`k > 0`) that brings a scene whose lengths (centres,
/// radii, velocities) all lie below the plain range (see
/// [`unit_scale`](crate::real::unit_scale)) to about 1; `None` otherwise.
/// Scaling up is exact, and every length of the answer scales with it.
fn tiny_scene<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Sphere<T>, vb: &Vec3<T>) -> Option<i32> {
    let amax = |p: &Vec3<T>| p.x.abs().max(p.y.abs()).max(p.z.abs());
    let size = amax(&a.center).max(amax(&b.center)).max(a.radius.abs()).max(b.radius.abs()).max(amax(va)).max(amax(vb));
    crate::real::unit_scale(size).filter(|k| *k > 0)
}

/// The contact of a touch at `t`: the normal from `b` toward `a` (or the
/// approach direction, flagged, when the radii sum to 0), the point on `b`.
/// Recomputes `Δp`, `Δv` and `R` from the inputs (the same roundings as the
/// caller's), so the caller keeps nothing alive for this rare case.
#[cold]
#[inline(never)]
fn contact_at<T: Real>(a: &Sphere<T>, va: &Vec3<T>, b: &Sphere<T>, vb: &Vec3<T>, t: T) -> Toi<T> {
    let (dp, dv) = (a.center - b.center, va - vb);
    let delta = dp + dv * t;
    let (normal, degenerate) = match normalize(&delta) {
        Some(n) if a.radius + b.radius > T::zero() => (n, false),
        _ => (approach_fallback(&dv), true),
    };
    Toi {
        t,
        point: b.center + vb * t + normal * b.radius,
        normal,
        status: ToiStatus::Converged,
        iterations: 0,
        degenerate,
    }
}

/// The scaled path of [`toi_sphere_sphere`]: squares out of the plain range,
/// for spheres its caller (`rare`) found apart at `t = 0` by the static test.
///
/// Lengths are divided by `m = max(‖Δp‖∞, R)` first (so `‖Δp/m‖∞ ≤ 1` and
/// `R/m ≤ 1`), and the motion is its unit direction `u` and its speed `s`
/// (scaled norms): with `p = Δp/m`, `r = R/m`, `along = −p·u`,
/// `h = ‖p × u‖` (the closest approach, in units of `m`),
/// `τ = (‖p‖² − r²)/(along + √((r − h)(r + h)))` is the distance travelled to
/// the touch in units of `m`, and `t = τ · (m / s)`; the normal is `p + τ u`
/// normalized. Nothing here overflows or underflows spuriously whatever the
/// scale of the scene (a centre difference, a sum of radii or a relative
/// velocity that overflows is taken at half scale, exactly).
#[inline(never)]
fn toi_sphere_sphere_scaled<T: Real>(
    a: &Sphere<T>,
    va: &Vec3<T>,
    b: &Sphere<T>,
    vb: &Vec3<T>,
    t_max: T,
) -> Option<Toi<T>> {
    // A relative velocity that overflows (`±1e308`) is taken at half scale,
    // exactly: its direction is the same, and the time divides by half the
    // speed (`speed_unit`).
    let mut dv = va - vb;
    let mut speed_unit = T::one();
    if !crate::real::finite3(&dv) {
        let h: T = c(0.5);
        dv = va * h - vb * h;
        speed_unit = h;
    }
    let u = try_normalize_stable(&dv)?;
    let speed = stable_norm(&dv);
    let mut dp = a.center - b.center;
    let mut reach = a.radius + b.radius;
    let mut unit = T::one();
    if !crate::real::finite3(&dp) || !reach.finite() {
        // Half scale, exactly: lengths in units of 2.
        let h: T = c(0.5);
        dp = a.center * h - b.center * h;
        reach = a.radius * h + b.radius * h;
        unit = c(2.0);
    }
    let m = dp.x.abs().max(dp.y.abs()).max(dp.z.abs()).max(reach);
    if !(m > T::zero() && m.finite()) {
        return None;
    }
    let (p, r) = (dp / m, reach / m);
    let along = -p.dot(&u);
    if !(along > T::zero()) {
        return None;
    }
    let h = stable_norm(&p.cross(&u));
    if !(h <= r) {
        return None;
    }
    let w = ((r - h) * (r + h)).sqrt();
    let d = stable_norm(&p);
    let tau = ((d - r) * (d + r) / (along + w)).max(T::zero());
    let t = tau * (m / speed) * unit * speed_unit;
    if !(t <= t_max) {
        return None;
    }
    let (normal, degenerate) = match try_normalize_stable(&(p + u * tau)) {
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
