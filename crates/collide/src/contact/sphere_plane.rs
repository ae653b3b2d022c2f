//! Sphere–plane contact.

use super::Contact;
use crate::exact::norm::safe_squared_range;
use crate::real::{Real, Vec3, c};
use crate::shapes::{Plane, Sphere};

/// Contact between a sphere `a` and the solid half-space `n · x ≤ d` bounded by the
/// plane `b`.
///
/// **Lecture's method.** With the unit normal `n̂ = n/‖n‖`, the signed distance of
/// the centre `M` from the plane is `s = n̂ · M − d/‖n‖`. The sphere reaches the
/// half-space when `s ≤ r`; the penetration is `x = r − s`, and the contact point
/// on the plane is the lecture's
///
/// ```text
/// p = M − (r − x) n̂        (r − x = s: M pushed back onto the plane)
/// ```
///
/// The normal is `n̂`, pointing out of the half-space toward the sphere (from `b`
/// toward `a`). Touching (`s = r`) is contact with depth 0. A centre below the
/// plane is still a contact: the half-space is solid, so `depth = r − s > r`.
///
/// The lecture has no other method beside this one: the formula is one dot product
/// and is already well conditioned (its error is a few ulps of `|M|` and `d`).
///
/// **Cost.** Where `n · n` lies in the range in which its plain square root
/// loses nothing (`[2^−918, 2^920]` in `f64`), `s = (n · M − d) · (1/√(n · n))`:
/// one root, one division; a centre clearly beyond `r` is answered from the
/// squares `(n · M − d)² > r² (n · n)` without the root, with the same
/// decision. Other normals, and scenes whose distance overflows, take the
/// scaled path described below.
///
/// **Degenerate input.** A zero (or non-finite) normal defines no plane: the answer
/// is `None`; crashtest's fixtures refuse such planes as malformed before they
/// reach here. A scene whose signed distance overflows (coordinates near the top of
/// the type's range) is recomputed at a quarter of its scale, an exact rescaling;
/// if the penetration still overflows it is saturated to the largest finite value
/// and the contact is flagged `degenerate`.
pub fn contact_sphere_plane<T: Real>(a: &Sphere<T>, b: &Plane<T>) -> Option<Contact<T>> {
    let nn = b.normal.norm_squared();
    let (lo, hi) = safe_squared_range::<T>();
    if nn >= lo && nn <= hi {
        // s' = n · M − d = s ‖n‖. A centre clearly farther than r from the
        // plane needs no root: s' > 0 and s'² > r² (n · n)(1 + 16u), with both
        // squares accurate (≥ lo), implies s' / ‖n‖ > r (1 + 6u), so the
        // computed s below would exceed r too.
        let sp = b.normal.dot(&a.center) - b.offset;
        // Products near the subnormals keep only a few bits: a scene of tiny
        // lengths (the centre, the radius and the offset in units of the
        // normal) is answered scaled up by a power of two, which is exact.
        if sp.abs() < lo
            && let Some(k) = tiny_scene_scale(a, b)
        {
            use crate::real::{scale2, scale2v};
            let up = Sphere::new(scale2v(&a.center, k), scale2(a.radius, k));
            let plane = Plane::new(b.normal, scale2(b.offset, k));
            return contact_sphere_plane(&up, &plane).map(|r| Contact {
                point: scale2v(&r.point, -k),
                depth: scale2(r.depth, -k),
                ..r
            });
        }
        if clearly_apart(sp, a.radius, nn) {
            return None;
        }
        let inv = T::one() / nn.sqrt();
        let s = sp * inv;
        if s.finite() {
            if s > a.radius {
                return None;
            }
            let n = b.normal * inv;
            let depth = a.radius - s;
            let point = a.center - n * s;
            if depth.finite() && crate::real::finite3(&point) {
                return Some(Contact { point, normal: n, depth, degenerate: false });
            }
        }
    }
    contact_sphere_plane_scaled(a, b)
}

/// The power of two (`> 0`) that brings a scene of tiny lengths to about 1
/// (the centre, the radius and the offset over the normal's largest
/// component), or `None` for a scene of ordinary or large lengths.
fn tiny_scene_scale<T: Real>(a: &Sphere<T>, b: &Plane<T>) -> Option<i32> {
    let amax = |p: &Vec3<T>| p.x.abs().max(p.y.abs()).max(p.z.abs());
    let size = amax(&a.center).max(a.radius.abs()).max(b.offset.abs() / amax(&b.normal));
    crate::real::unit_scale(size).filter(|k| *k > 0)
}

/// The root-free "apart" test of [`contact_sphere_plane`]'s plain path, for
/// `s' = n · M − d`, the radius `r` and `n · n` in the plain range: `s' > 0`
/// and `s'² > r² (n · n)(1 + 16u)` with both squares at least `lo` (so
/// neither underflowed). Shared with the time of impact, which asks the
/// static test whenever this does not hold, so the two agree on every start.
#[inline(always)]
pub(crate) fn clearly_apart<T: Real>(sp: T, r: T, nn: T) -> bool {
    let (lo, _) = safe_squared_range::<T>();
    let (sp2, r2) = (sp * sp, r * r);
    sp > T::zero() && sp2 >= lo && r2 >= lo && sp2 > r2 * nn * clear_miss_factor::<T>()
}

/// `1 + 16u` (`u` the unit roundoff of `T`): covers the four roundings of the
/// squared test (`s'²`, `r²`, `r² (n · n)`, the factor) and the three of the
/// computed `s = s' · (1/√(n · n))`, with `2u` to spare (see
/// [`contact_sphere_plane`]).
#[inline(always)]
fn clear_miss_factor<T: Real>() -> T {
    T::one() + c::<T>(8.0) * T::EPSILON
}

/// A plane's normal `n` in parts: the magnitude `m` of its largest
/// component, the length `l = ‖n/m‖ ∈ [1, √3]` and the unit normal
/// `(n/m)/l`. The length `‖n‖ = m l` itself is never formed: it overflows
/// for components near `MAX` (the normal `(−MAX, −7e62, −MAX)` has none, and
/// its sphere was never in contact) and rounds to a few bits in the
/// subnormals (`(−5e-324, 0, 5e-324)` has the length `5e-324`, and `n/‖n‖`
/// the length `√2`). `None` for a zero or non-finite normal.
#[inline]
pub(crate) fn normal_parts<T: Real>(n: &Vec3<T>) -> Option<(T, T, Vec3<T>)> {
    let m = n.x.abs().max(n.y.abs()).max(n.z.abs());
    if !(m > T::zero() && m.finite()) {
        return None;
    }
    let s = n / m;
    let l = s.norm();
    Some((m, l, s / l))
}

/// The scaled path of [`contact_sphere_plane`]: a normal whose squared length
/// would underflow or overflow, or a scene whose signed distance overflows.
#[inline(never)]
fn contact_sphere_plane_scaled<T: Real>(a: &Sphere<T>, b: &Plane<T>) -> Option<Contact<T>> {
    contact_sphere_plane_parts(a, b).map(|(k, _)| k)
}

/// [`contact_sphere_plane`]'s scaled path, and whether its point lies beyond
/// the type's range (saturated): the contact's `degenerate` flag also marks a
/// depth beyond the range, which a time of impact, reporting no depth, does
/// not share.
///
/// The plane's distance `d/‖n‖` is `((d/m)/l)` from the normal's parts
/// ([`normal_parts`]). A signed distance that overflows is formed at a
/// quarter scale (exact), and so is the point `M − n̂ s`, whose terms may
/// overflow where their sum does not (a centre at `−MAX` pushed back
/// `1.3e308` onto the plane).
pub(crate) fn contact_sphere_plane_parts<T: Real>(a: &Sphere<T>, b: &Plane<T>) -> Option<(Contact<T>, bool)> {
    let (m, l, n) = normal_parts(&b.normal)?;
    let q: T = c(0.25);
    let mut s = n.dot(&a.center) - (b.offset / m) / l;
    let mut quarter = s * q;
    if !s.finite() {
        // |n̂| ≤ 1, so the quarter-scale dot product cannot overflow.
        quarter = n.dot(&(a.center * q)) - ((b.offset * q) / m) / l;
        s = quarter / q;
        if s.is_nan() {
            return None;
        }
    }
    if s > a.radius {
        return None;
    }
    let depth = a.radius - s;
    let mut point = a.center - n * s;
    if !crate::real::finite3(&point) {
        point = (a.center * q - n * quarter) / q;
    }
    let beyond = !crate::real::finite3(&point);
    Some((
        Contact {
            point: if beyond { saturate(&point) } else { point },
            normal: n,
            depth: if depth.finite() { depth } else { T::max_value().unwrap_or(depth) },
            degenerate: beyond || !depth.finite(),
        },
        beyond,
    ))
}

/// Contact between the solid half-space bounded by plane `a` and a sphere `b`: the
/// reverse order of [`contact_sphere_plane`]. The normal is `−n̂` (from the sphere
/// toward the plane) and the point is the sphere's deepest point `M − r n̂`.
pub fn contact_plane_sphere<T: Real>(a: &Plane<T>, b: &Sphere<T>) -> Option<Contact<T>> {
    contact_sphere_plane(b, a).map(|k| k.swapped())
}

/// Clamps each component of `v` to the finite range (NaN becomes 0).
fn saturate<T: Real>(v: &Vec3<T>) -> Vec3<T> {
    let big = T::max_value().unwrap_or_else(|| c(f64::MAX));
    v.map(|x| if x.is_nan() { T::zero() } else { x.max(-big).min(big) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::Vec3;

    /// Hand-derived answers are exact in binary floating point (small dyadic
    /// values), but `n / ‖n‖` for a non-axis normal rounds: 4 ulps of 1.
    const TOL: f64 = 4.0 * f64::EPSILON;

    fn close<T: Real>(a: T, b: f64) -> bool {
        (a.wide() - b).abs() <= TOL.max(T::EPSILON.wide() * 4.0) * (1.0 + b.abs())
    }

    fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
        Vec3::new(c(x), c(y), c(z))
    }

    fn ball_half_sunk<T: Real>() {
        // Centre (0,0,0.5), r = 1, ground z = 0 (n = (0,0,1), d = 0):
        // s = 0.5, depth = r − s = 0.5, p = M − s n̂ = (0,0,0), normal (0,0,1).
        let k =
            contact_sphere_plane(&Sphere::new(v::<T>(0.0, 0.0, 0.5), c(1.0)), &Plane::new(v(0.0, 0.0, 1.0), c(0.0)))
                .expect("sunk ball touches");
        assert!(close(k.depth, 0.5), "depth {:?}", k.depth);
        assert!(close(k.point.z, 0.0) && close(k.normal.z, 1.0));
        assert!(!k.degenerate);
        // Reverse order: normal (0,0,−1), point on the sphere: M − r n̂ = (0,0,−0.5).
        let r =
            contact_plane_sphere(&Plane::new(v(0.0, 0.0, 1.0), c(0.0)), &Sphere::new(v::<T>(0.0, 0.0, 0.5), c(1.0)))
                .expect("same contact");
        assert!(close(r.normal.z, -1.0) && close(r.point.z, -0.5) && close(r.depth, 0.5));
    }

    #[test]
    fn ball_half_sunk_f64() {
        ball_half_sunk::<f64>();
    }

    #[test]
    fn ball_half_sunk_f32() {
        ball_half_sunk::<f32>();
    }

    #[test]
    fn touching_counts_and_a_hair_above_does_not() {
        // Plane 2z = 4 is z = 2 (‖n‖ = 2, d/‖n‖ = 2); centre z = 3, r = 1: s = 1 = r.
        let p = Plane::new(Vec3::new(0.0, 0.0, 2.0), 4.0);
        let k = contact_sphere_plane(&Sphere::new(Vec3::new(5.0, -1.0, 3.0), 1.0), &p).expect("touching is contact");
        assert!(close(k.depth, 0.0) && close(k.point.z, 2.0) && close(k.point.x, 5.0));
        let above = Sphere::new(Vec3::new(0.0, 0.0, 3.0_f64.next_up()), 1.0);
        assert!(contact_sphere_plane(&above, &p).is_none());
    }

    #[test]
    fn centre_below_the_plane_is_deep_contact() {
        // Centre z = −3, r = 1, plane z = 0: s = −3, depth = 4, point (0,0,0).
        let k = contact_sphere_plane(
            &Sphere::new(Vec3::new(0.0, 0.0, -3.0), 1.0),
            &Plane::new(Vec3::new(0.0, 0.0, 1.0), 0.0),
        )
        .expect("solid half-space");
        assert!(close(k.depth, 4.0) && close(k.point.z, 0.0));
    }

    #[test]
    fn zero_normal_is_no_plane() {
        let k = contact_sphere_plane(&Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0), &Plane::new(Vec3::zeros(), 0.0));
        assert!(k.is_none());
    }

    #[test]
    fn huge_scene_does_not_overflow_to_nan() {
        // Centre at 1.5e308 on every axis, plane x + y + z = 0 with the sphere far
        // below: the naive dot product overflows; the quarter-scale one does not.
        let k = contact_sphere_plane(
            &Sphere::new(Vec3::new(-1.5e308_f64, -1.5e308, -1.5e308), 1.0),
            &Plane::new(Vec3::new(1.0, 1.0, 1.0), 0.0),
        )
        .expect("deep below");
        assert!(k.depth.is_finite() && k.point.iter().all(|x| x.is_finite()));
        assert!(k.degenerate, "the penetration overflows f64 and is saturated");
    }
}
