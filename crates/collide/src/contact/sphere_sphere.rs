//! Sphere–sphere contact: the lecture's form and the robust form.

use super::Contact;
use crate::exact::norm::{clear_miss_factor, safe_squared_range};
use crate::real::{Real, Vec3, c, try_normalize_stable};
use crate::shapes::Sphere;

/// The normal reported for concentric spheres, where no direction is defined:
/// `+z`. The referee and the fixtures use the same fallback, so a concentric case
/// is compared on its point and depth and checked for its `degenerate` flag.
pub const CONCENTRIC_FALLBACK_NORMAL: [f64; 3] = [0.0, 0.0, 1.0];

fn fallback_normal<T: Real>() -> Vec3<T> {
    let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
    Vec3::new(c(x), c(y), c(z))
}

/// Contact between spheres `a` (centre `M1`, radius `r1`) and `b` (`M2`, `r2`),
/// **the lecture's form**:
///
/// ```text
/// n = (M1 − M2) / ‖M1 − M2‖      (from b toward a)
/// p = M2 + r2 n                  (on b's surface)
/// depth = r1 + r2 − ‖M1 − M2‖    (contact when ≥ 0)
/// ```
///
/// The distance is the naive `sqrt(Δx² + Δy² + Δz²)`, as written in the lecture:
/// it underflows to 0 for centre distances below about 1e-154 (f64; 1e-19 for f32)
/// and overflows above about 1e154 (1e19), which is where this form breaks and
/// what crashtest's sweeps show.
///
/// **Degenerate input.** When the computed distance is 0 (concentric, or a
/// distance that underflowed) the normal is undefined: the answer uses
/// [`CONCENTRIC_FALLBACK_NORMAL`], depth `r1 + r2`, and is flagged. When the
/// distance overflows, the normal would be 0/∞: the same fallback is used and the
/// contact (if the radii say there is one) is flagged.
pub fn contact_sphere_sphere_lecture<T: Real>(a: &Sphere<T>, b: &Sphere<T>) -> Option<Contact<T>> {
    let delta = a.center - b.center;
    let dist = delta.norm();
    let reach = a.radius + b.radius;
    if dist.is_nan() || dist > reach {
        return None;
    }
    let (normal, degenerate) =
        if dist == T::zero() || !dist.finite() { (fallback_normal(), true) } else { (delta / dist, false) };
    Some(Contact { point: b.center + normal * b.radius, normal, depth: reach - dist, degenerate })
}

/// Contact between spheres `a` and `b`, **robust form**: the lecture's formulas
/// (see [`contact_sphere_sphere_lecture`]) with the distance computed without
/// spurious underflow or overflow (scaled by the largest component, as
/// [`crate::real::stable_norm`] does), so only exactly concentric spheres lack a
/// normal.
///
/// **Cost.** Where `‖M1 − M2‖²` lies in the range in which the plain sum of
/// squares loses nothing (`[2^−918, 2^920]` in `f64`), the distance is its
/// plain square root and the normal `Δ · (1/‖Δ‖)`: one root and one division;
/// a pair apart by more than the roundings (`‖Δ‖² > (r1 + r2)² (1 + 8u)`) is
/// answered from the squares alone, with the same decision. Outside that
/// range the components are scaled first, as above.
///
/// **Degenerate input.** Concentric centres (`M1 = M2` exactly): normal
/// [`CONCENTRIC_FALLBACK_NORMAL`], point `M2 + r2 n`, depth `r1 + r2`, flagged.
/// Centres so far apart that `M1 − M2` overflows are compared at half scale
/// (exact); they are never in contact with finite radii below the overflow
/// threshold, and a contact whose depth overflows is flagged. Radii whose
/// sum overflows (two of `1e308`) are summed at half scale: the depth is
/// finite whenever its exact value is representable.
#[inline]
pub fn contact_sphere_sphere<T: Real>(a: &Sphere<T>, b: &Sphere<T>) -> Option<Contact<T>> {
    let delta = a.center - b.center;
    let dd = delta.norm_squared();
    let (lo, hi) = safe_squared_range::<T>();
    if dd >= lo && dd <= hi {
        // The plain distance is as accurate as the scaled one here (see
        // `safe_squared_range`), and a clear miss needs no root at all. A
        // sum of radii that overflows here overflows the exact depth too
        // (`‖Δ‖ ≤ 2^460` is far below an ulp of it): `∞`, flagged.
        let reach = a.radius + b.radius;
        if dd > reach * reach * clear_miss_factor::<T>() {
            return None;
        }
        let dist = dd.sqrt();
        if dist > reach {
            return None;
        }
        let normal = delta * (T::one() / dist);
        let depth = reach - dist;
        return Some(Contact { point: b.center + normal * b.radius, normal, depth, degenerate: !depth.finite() });
    }
    contact_sphere_sphere_scaled(a, b, delta)
}

/// The robust form's scaled path: centres whose squared distance would
/// underflow or overflow (see [`contact_sphere_sphere`]).
#[inline(never)]
fn contact_sphere_sphere_scaled<T: Real>(a: &Sphere<T>, b: &Sphere<T>, delta: Vec3<T>) -> Option<Contact<T>> {
    let h: T = c(0.5);
    if !crate::real::finite3(&delta) {
        // Centres whose difference overflows: distance and reach compared at
        // half scale (exact for the radii that can reach that far, which are
        // normal), the depth formed there too. Never concentric.
        let half = a.center * h - b.center * h;
        let normal = try_normalize_stable(&half)?;
        let (dist, reach) = (crate::real::stable_norm(&half), a.radius * h + b.radius * h);
        if !(dist <= reach) {
            return None;
        }
        let depth = (reach - dist) * c::<T>(2.0);
        return Some(Contact { point: b.center + normal * b.radius, normal, depth, degenerate: !depth.finite() });
    }
    // A scene of tiny or subnormal lengths: answered scaled up by a power of
    // two (exact), where the distance is formed to its own precision. On the
    // subnormal grid it rounds to a few ulps: centres √10 ulps apart measured
    // 3 ulps, equal to the radii's sum, a contact where they are apart.
    let amax = |p: &Vec3<T>| p.x.abs().max(p.y.abs()).max(p.z.abs());
    let size = amax(&a.center).max(amax(&b.center)).max(a.radius.abs()).max(b.radius.abs());
    if let Some(k) = crate::real::unit_scale(size).filter(|k| *k > 0) {
        use crate::real::{scale2, scale2v};
        let up = |s: &Sphere<T>| Sphere::new(scale2v(&s.center, k), scale2(s.radius, k));
        return contact_sphere_sphere(&up(a), &up(b)).map(|r| Contact {
            point: scale2v(&r.point, -k),
            depth: scale2(r.depth, -k),
            ..r
        });
    }
    let reach = a.radius + b.radius;
    let Some(normal) = try_normalize_stable(&delta) else {
        // Exactly concentric.
        return Some(Contact {
            point: b.center + fallback_normal::<T>() * b.radius,
            normal: fallback_normal(),
            depth: depth_of(a.radius, b.radius, reach, T::zero()),
            degenerate: true,
        });
    };
    // A reach that overflowed exceeds every finite distance: `dist > ∞` is
    // false, as the exact comparison.
    let dist = crate::real::stable_norm(&delta);
    if dist > reach {
        return None;
    }
    let depth = depth_of(a.radius, b.radius, reach, dist);
    Some(Contact { point: b.center + normal * b.radius, normal, depth, degenerate: !depth.finite() })
}

/// `r1 + r2 − dist` (with `reach = fl(r1 + r2)`), without the spurious
/// overflow of `reach`: two finite radii whose sum overflows (each near the
/// top of the range, so both normal and their halves exact) give the depth
/// at half scale, `((r1/2 + r2/2) − dist/2) · 2`, two roundings as in the
/// plain form (halving `dist` loses at most `2^−1075`, nothing against a
/// depth that large). It is infinite only when the exact depth overflows
/// (or a radius is infinite).
#[inline]
pub(crate) fn depth_of<T: Real>(r1: T, r2: T, reach: T, dist: T) -> T {
    if reach.finite() {
        return reach - dist;
    }
    let h: T = c(0.5);
    ((r1 * h + r2 * h) - dist * h) * c::<T>(2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-derived answers below are small dyadic numbers, exact in both
    /// precisions, or one rounded division: 4 ulps of the answer's size.
    const ULPS4: f64 = 4.0;

    fn close<T: Real>(a: T, b: f64) -> bool {
        (a.wide() - b).abs() <= ULPS4 * T::EPSILON.wide() * (1.0 + b.abs())
    }

    fn ball<T: Real>(x: f64, y: f64, z: f64, r: f64) -> Sphere<T> {
        Sphere::new(Vec3::new(c(x), c(y), c(z)), c(r))
    }

    type Method<T> = fn(&Sphere<T>, &Sphere<T>) -> Option<Contact<T>>;

    fn both<T: Real>() -> [(&'static str, Method<T>); 2] {
        [("lecture", contact_sphere_sphere_lecture), ("robust", contact_sphere_sphere)]
    }

    fn overlap_three_four_five<T: Real>() {
        // M1 = (3,4,0), M2 = 0, r1 = r2 = 3: ‖Δ‖ = 5, n = (0.6, 0.8, 0),
        // p = M2 + 3n = (1.8, 2.4, 0), depth = 6 − 5 = 1.
        for (name, f) in both::<T>() {
            let k = f(&ball(3.0, 4.0, 0.0, 3.0), &ball(0.0, 0.0, 0.0, 3.0)).expect(name);
            assert!(close(k.depth, 1.0), "{name}: depth {:?}", k.depth);
            assert!(close(k.normal.x, 0.6) && close(k.normal.y, 0.8), "{name}: normal");
            assert!(close(k.point.x, 1.8) && close(k.point.y, 2.4), "{name}: point");
            assert!(!k.degenerate, "{name}");
        }
    }

    #[test]
    fn overlap_three_four_five_f64() {
        overlap_three_four_five::<f64>();
    }

    #[test]
    fn overlap_three_four_five_f32() {
        overlap_three_four_five::<f32>();
    }

    #[test]
    fn touching_is_contact_with_zero_depth() {
        // Centres 2 apart on x, radii 1 + 1: depth exactly 0, point (1,0,0).
        for (name, f) in both::<f64>() {
            let k = f(&ball(2.0, 0.0, 0.0, 1.0), &ball(0.0, 0.0, 0.0, 1.0)).expect(name);
            assert!(close(k.depth, 0.0) && close(k.point.x, 1.0), "{name}");
            assert!(f(&ball(2.0_f64.next_up(), 0.0, 0.0, 1.0), &ball(0.0, 0.0, 0.0, 1.0)).is_none());
        }
    }

    #[test]
    fn concentric_is_flagged_with_the_fallback_normal() {
        // Same centre (1,1,1), radii 1 and 2: depth 3, normal +z, p = M2 + 2·(+z).
        for (name, f) in both::<f64>() {
            let k = f(&ball(1.0, 1.0, 1.0, 1.0), &ball(1.0, 1.0, 1.0, 2.0)).expect(name);
            assert!(k.degenerate, "{name}");
            assert!(close(k.depth, 3.0) && close(k.normal.z, 1.0) && close(k.point.z, 3.0));
        }
    }

    #[test]
    fn tiny_offset_breaks_the_lecture_form_but_not_the_robust_one() {
        // Centres 1e-200 apart on y: the lecture's Δy² underflows to 0 and it falls
        // back to +z (flagged); the robust form finds n = (0,1,0). This is the
        // known weakness the stability sweeps chart, asserted as it is.
        let a = ball::<f64>(0.0, 1e-200, 0.0, 1.0);
        let b = ball::<f64>(0.0, 0.0, 0.0, 1.0);
        let lecture = contact_sphere_sphere_lecture(&a, &b).expect("overlap");
        assert!(lecture.degenerate && close(lecture.normal.z, 1.0));
        let robust = contact_sphere_sphere(&a, &b).expect("overlap");
        assert!(!robust.degenerate && close(robust.normal.y, 1.0));
    }

    #[test]
    fn far_apart_centres_overflowing_the_difference_are_apart() {
        let a = ball::<f64>(1.5e308, 0.0, 0.0, 1.0);
        let b = ball::<f64>(-1.5e308, 0.0, 0.0, 1.0);
        assert!(contact_sphere_sphere(&a, &b).is_none());
        assert!(contact_sphere_sphere_lecture(&a, &b).is_none());
        // Radii 1e308 at ∓1.7e308: the difference 3.4e308 and the reach
        // 2e308 both overflow; compared at half scale they are apart (before,
        // ∞ > ∞ was false: a contact of depth ∞). At ∓0.9e308 they overlap
        // by 2e308 − 1.8e308 = 2e307.
        let (a, b) = (ball::<f64>(-1.7e308, 0.0, 0.0, 1e308), ball::<f64>(1.7e308, 0.0, 0.0, 1e308));
        assert!(contact_sphere_sphere(&a, &b).is_none());
        let (a, b) = (ball::<f64>(-0.9e308, 0.0, 0.0, 1e308), ball::<f64>(0.9e308, 0.0, 0.0, 1e308));
        let k = contact_sphere_sphere(&a, &b).expect("overlap");
        assert!((k.depth - 2e307).abs() <= HUGE_DEPTH_REL * 1e308 && !k.degenerate, "{k:?}");
    }

    /// The depth of the huge pairs below: two roundings of a value near
    /// `1e308`, so 4 ulps of it, relative.
    const HUGE_DEPTH_REL: f64 = 4.0 * f64::EPSILON;

    #[test]
    fn radii_whose_sum_overflows_give_a_finite_depth() {
        // r1 = r2 = 1e308, centres 1e308 apart on x: r1 + r2 = 2e308
        // overflows, the exact depth 2e308 − 1e308 = 1e308 does not. The
        // normal from b toward a is −x, the point M2 + r2 n = 0. Before the
        // half-scale sum the depth was ∞ (flagged).
        let a = ball::<f64>(0.0, 0.0, 0.0, 1e308);
        let b = ball::<f64>(1e308, 0.0, 0.0, 1e308);
        let k = contact_sphere_sphere(&a, &b).expect("overlap");
        assert!((k.depth - 1e308).abs() <= HUGE_DEPTH_REL * 1e308 && !k.degenerate, "{k:?}");
        assert!(close(k.normal.x, -1.0) && k.point.x.abs() <= HUGE_DEPTH_REL * 1e308, "{k:?}");
        // The same radii 1 apart (the plain range of ‖Δ‖²): depth 2e308 − 1
        // is beyond the range, so ∞ and flagged; 1.7e308 apart it is 3e307.
        let k = contact_sphere_sphere(&a, &ball(1.0, 0.0, 0.0, 1e308)).expect("overlap");
        assert!(k.depth.is_infinite() && k.degenerate, "{k:?}");
        let (a, b) = (ball::<f64>(-0.85e308, 0.0, 0.0, 1e308), ball::<f64>(0.85e308, 0.0, 0.0, 1e308));
        let k = contact_sphere_sphere(&a, &b).expect("overlap");
        assert!((k.depth - 3e307).abs() <= HUGE_DEPTH_REL * 1e308 && !k.degenerate, "{k:?}");
    }
}
