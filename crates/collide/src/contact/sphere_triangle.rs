//! Sphere–triangle contact.

use super::Contact;
use super::closest_pt_triangle::{Region, closest_pt_point_triangle_region, nearest_on_edges};
use super::sphere_sphere::CONCENTRIC_FALLBACK_NORMAL;
use crate::real::{Real, Vec3, c, stable_norm, try_normalize_stable};
use crate::shapes::{Sphere, Triangle};

/// Contact between a sphere `a` (centre `M`, radius `r`) and a triangle `b`.
///
/// **Method.** The triangle's point closest to the centre, `q`
/// ([`closest_pt_point_triangle`], computed in the frame of the centre — see the
/// comment in the body), is where the sphere meets the triangle first;
/// then, as for two spheres with `b` shrunk to the point `q`:
///
/// ```text
/// contact when ‖M − q‖ ≤ r,   n = (M − q) / ‖M − q‖,   p = q,   depth = r − ‖M − q‖
/// ```
///
/// The triangle is two-sided and has no thickness: a centre behind the face is
/// pushed out through the face it is behind, as for one in front.
///
/// **Degenerate input.** A centre exactly on the triangle (decided exactly, with
/// `orient3d` and `orient2d`) has no direction: the normal falls back to the face
/// normal `(v1 − v0) × (v2 − v0)`, normalized, depth `r`, point `M`, flagged. A
/// centre off the triangle but nearer than the rounding of `q` can resolve gets
/// the face normal on the centre's (exactly known) side, not flagged. A zero-area
/// triangle is answered as the segment or point it collapsed to; if even its
/// direction is lost, the normal is [`CONCENTRIC_FALLBACK_NORMAL`], flagged.
pub fn contact_sphere_triangle<T: Real>(a: &Sphere<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    // Work in the frame of the centre: `M − q` is then computed as `−q'`, the
    // closest point of the translated triangle to the origin, whose rounding is
    // relative to the triangle's distance and size, not to the coordinates' size.
    // A scene far from the origin (1e14, say) otherwise loses every digit of a
    // small `M − q` to the rounding of `q`. The translation overflows only for
    // coordinates of opposite signs near the top of the range: then the global
    // frame is used.
    let [v0, v1, v2] = b.vertices;
    let wide = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let flat = crate::exact::collinear(wide(&v0), wide(&v1), wide(&v2));
    let local = Triangle::new(v0 - a.center, v1 - a.center, v2 - a.center);
    let (q, delta, region) = if local.vertices.iter().all(crate::real::finite3) {
        let (q_local, region) = if flat {
            (nearest_on_edges(&Vec3::zeros(), &local), Region::Boundary)
        } else {
            closest_pt_point_triangle_region(&Vec3::zeros(), &local)
        };
        (a.center + q_local, -q_local, region)
    } else {
        let (q, region) = closest_pt_point_triangle_region(&a.center, b);
        (q, a.center - q, region)
    };
    // In the face region the direction is the face normal and the distance the
    // plane distance; both come accurately from exact-filtered volumes, where
    // the closest point's own rounding would tilt the normal of a thin triangle
    // by (its rounding) / (the distance).
    if region == Region::Face {
        if let Some((n, d)) = face_normal_and_distance(wide(&a.center), [wide(&v0), wide(&v1), wide(&v2)]) {
            let (normal, dist) = (Vec3::new(c(n[0]), c(n[1]), c(n[2])), c::<T>(d));
            if !(dist <= a.radius) {
                return None;
            }
            return Some(Contact {
                point: a.center - normal * dist,
                normal,
                depth: a.radius - dist,
                degenerate: false,
            });
        }
    }
    let dist = stable_norm(&delta);
    if !(dist <= a.radius) {
        return None;
    }
    let on = centre_on_triangle(&a.center, b);
    let face = || {
        let [v0, v1, v2] = b.vertices;
        try_normalize_stable(&(v1 - v0).cross(&(v2 - v0)))
    };
    if on == OnTriangle::Exactly {
        // Exactly on the triangle: no direction is defined.
        let normal = face().unwrap_or_else(|| {
            let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
            Vec3::new(c(x), c(y), c(z))
        });
        return Some(Contact { point: a.center, normal, depth: a.radius, degenerate: true });
    }
    let normal = match try_normalize_stable(&delta) {
        Some(n) => n,
        // Off the triangle, but closer than the rounding of `q` can resolve: the
        // direction is the face normal toward the side the centre is on, which the
        // exact test knows.
        None => match (on, face()) {
            (OnTriangle::Side(s), Some(n)) if s != 0.0 => n * c::<T>(s),
            _ => {
                let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
                return Some(Contact {
                    point: q,
                    normal: Vec3::new(c(x), c(y), c(z)),
                    depth: a.radius - dist,
                    degenerate: true,
                });
            }
        },
    };
    Some(Contact { point: q, normal, depth: a.radius - dist, degenerate: false })
}

/// The unit face normal on `p`'s side and `p`'s distance from the triangle's
/// plane, from the triangle's cross product and the volume `orient3d`, each
/// refined to a relative error of 2^-40 by the exact filters: accurate however
/// thin the triangle. `None` for `p` in the plane, a zero-area triangle, or a
/// distance beyond `f64`'s range.
fn face_normal_and_distance(p: [f64; 3], v: [[f64; 3]; 3]) -> Option<([f64; 3], f64)> {
    use crate::exact::{Estimate, Sign, cross_estimate, orient3d_estimate};
    const REL: f64 = 1.0 / (1u64 << 40) as f64;
    let vol = orient3d_estimate(v[0], v[1], v[2], p, REL);
    let n = cross_estimate(v[0], v[1], v[2], REL);
    let unit = Estimate::unit_vector(n)?;
    let emax = n.iter().filter(|e| e.sign != Sign::Zero).map(|e| e.exp).max()?;
    let norm = n
        .iter()
        .filter(|e| e.sign != Sign::Zero)
        .map(|e| {
            let m = e.mant * pow2(e.exp - emax);
            m * m
        })
        .sum::<f64>()
        .sqrt();
    // orient3d is −n · (p − v0): positive when p is on the side n points away from.
    let side = match vol.sign {
        Sign::Zero => return None,
        Sign::Positive => -1.0,
        Sign::Negative => 1.0,
    };
    let d = vol.mant / norm * pow2(vol.exp - emax);
    d.is_finite().then_some((unit.map(|x| x * side), d))
}

/// `2^k` as an `f64` (0 below the subnormal range, infinity above the top).
fn pow2(k: i64) -> f64 {
    if k < -1074 {
        0.0
    } else if k > 1023 {
        f64::INFINITY
    } else if k < -1022 {
        f64::from_bits(1u64 << (k + 1074))
    } else {
        f64::from_bits(((k + 1023) as u64) << 52)
    }
}

/// Where a point is with respect to a triangle, decided exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
enum OnTriangle {
    /// On the triangle (its plane, within or on its edges).
    Exactly,
    /// Not on it; the sign of the side of its plane (+1 the face normal's side,
    /// −1 the other, 0 in the plane but outside the triangle).
    Side(f64),
}

/// Decides exactly whether `p` lies on the triangle: coplanar (`orient3d = 0`)
/// and inside or on the boundary, tested by `orient2d` in a coordinate plane onto
/// which the triangle projects with non-zero area (projection preserves
/// inside-ness for coplanar points). A zero-area triangle is never "exactly on":
/// its contacts are those of the segment or point it collapsed to.
fn centre_on_triangle<T: Real>(p: &Vec3<T>, t: &Triangle<T>) -> OnTriangle {
    use crate::exact::{Sign, orient2d, orient3d};
    let w = |v: &Vec3<T>| [v.x.wide(), v.y.wide(), v.z.wide()];
    let [a, b, cc] = t.vertices.map(|v| w(&v));
    let q = w(p);
    match orient3d(a, b, cc, q) {
        // Shewchuk's sign: positive below, i.e. against the face normal.
        Sign::Positive => return OnTriangle::Side(-1.0),
        Sign::Negative => return OnTriangle::Side(1.0),
        Sign::Zero => {}
    }
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let pr = |v: [f64; 3]| [v[i], v[j]];
        let area = orient2d(pr(a), pr(b), pr(cc));
        if area == Sign::Zero {
            continue;
        }
        let inside = [(a, b), (b, cc), (cc, a)].iter().all(|&(u, v)| {
            let s = orient2d(pr(u), pr(v), pr(q));
            s == area || s == Sign::Zero
        });
        return if inside { OnTriangle::Exactly } else { OnTriangle::Side(0.0) };
    }
    OnTriangle::Side(0.0)
}

/// Contact between a triangle `a` and a sphere `b`: the reverse order of
/// [`contact_sphere_triangle`] (normal from the sphere toward the triangle, point
/// the sphere's deepest point).
pub fn contact_triangle_sphere<T: Real>(a: &Triangle<T>, b: &Sphere<T>) -> Option<Contact<T>> {
    contact_sphere_triangle(b, a).map(|k| k.swapped())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The answers below are exact small dyadic values or one rounded square
    /// root: 8 ulps of the answer's size covers the closest-point arithmetic.
    const ULPS: f64 = 8.0;

    fn close<T: Real>(a: T, b: f64) -> bool {
        (a.wide() - b).abs() <= ULPS * T::EPSILON.wide() * (1.0 + b.abs())
    }

    fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
        Vec3::new(c(x), c(y), c(z))
    }

    fn tri<T: Real>() -> Triangle<T> {
        // Right triangle in z = 0 with legs 2 on x and y; face normal +z.
        Triangle::new(v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(0.0, 2.0, 0.0))
    }

    fn face_region<T: Real>() {
        // Centre (0.5, 0.5, 0.75), r = 1: q = (0.5, 0.5, 0) (above the face),
        // ‖M − q‖ = 0.75, depth 0.25, normal +z.
        let k = contact_sphere_triangle(&Sphere::new(v::<T>(0.5, 0.5, 0.75), c(1.0)), &tri()).expect("overlap");
        assert!(close(k.depth, 0.25) && close(k.normal.z, 1.0) && close(k.point.x, 0.5));
        // Below the face: normal −z, same depth (two-sided).
        let k = contact_sphere_triangle(&Sphere::new(v::<T>(0.5, 0.5, -0.75), c(1.0)), &tri()).expect("overlap");
        assert!(close(k.depth, 0.25) && close(k.normal.z, -1.0));
    }

    #[test]
    fn face_region_f64() {
        face_region::<f64>();
    }

    #[test]
    fn face_region_f32() {
        face_region::<f32>();
    }

    #[test]
    fn vertex_and_edge_regions() {
        // Beyond vertex v1 = (2,0,0): centre (3,0,0), r = 1.5: q = v1, depth 0.5,
        // normal (1,0,0).
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 0.0, 0.0), 1.5), &tri::<f64>()).expect("vertex");
        assert!(close(k.point.x, 2.0) && close(k.depth, 0.5) && close(k.normal.x, 1.0));
        // Beyond the hypotenuse x + y = 2: centre (2,2,0), q = (1,1,0),
        // ‖M − q‖ = √2, r = 2: depth 2 − √2, normal (1,1,0)/√2.
        let k = contact_sphere_triangle(&Sphere::new(v(2.0, 2.0, 0.0), 2.0), &tri::<f64>()).expect("edge");
        assert!(close(k.point.x, 1.0) && close(k.point.y, 1.0));
        assert!(close(k.depth, 2.0 - 2f64.sqrt()) && close(k.normal.x, 0.5f64.sqrt()));
    }

    #[test]
    fn touching_vertex_is_contact() {
        // Centre (3,0,0), r = 1: ‖M − v1‖ = 1 = r.
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 0.0, 0.0), 1.0), &tri::<f64>());
        assert!(k.is_some_and(|k| close(k.depth, 0.0)));
        let apart = Sphere::new(v(3.0_f64.next_up(), 0.0, 0.0), 1.0);
        assert!(contact_sphere_triangle(&apart, &tri::<f64>()).is_none());
    }

    #[test]
    fn centre_on_the_face_falls_back_to_the_face_normal() {
        let k =
            contact_sphere_triangle(&Sphere::new(v(0.5, 0.5, 0.0), 1.0), &tri::<f64>()).expect("centre on the face");
        assert!(k.degenerate && close(k.normal.z, 1.0) && close(k.depth, 1.0));
    }

    #[test]
    fn zero_area_triangle_is_its_segment() {
        // Vertices on the x axis from 0 to 2 (v2 repeats v1): centre (1, 0.5, 0),
        // r = 1: q = (1,0,0), depth 0.5, normal +y.
        let flat = Triangle::new(v(0.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(2.0, 0.0, 0.0));
        let k = contact_sphere_triangle(&Sphere::new(v(1.0, 0.5, 0.0), 1.0), &flat).expect("hit");
        assert!(close(k.point.x, 1.0) && close(k.depth, 0.5) && close(k.normal.y, 1.0));
        assert!(!k.degenerate);
    }

    #[test]
    fn reverse_order_flips_the_normal_and_moves_the_point() {
        // From face_region: normal +z, q = (0.5,0.5,0), depth 0.25. Reversed:
        // normal −z, point M − r·(+z) = (0.5, 0.5, −0.25).
        let k = contact_triangle_sphere(&tri::<f64>(), &Sphere::new(v(0.5, 0.5, 0.75), 1.0)).expect("overlap");
        assert!(close(k.normal.z, -1.0) && close(k.point.z, -0.25) && close(k.depth, 0.25));
    }

    #[test]
    fn far_from_the_origin_the_normal_keeps_its_digits() {
        // The triangle of `tri` and a centre 0.75 above (0.5, 0.5), all shifted by
        // 2^46 (about 7e13) on x and y: the shift is exact, so the answer is the
        // unshifted one, normal +z, depth 0.25. Without the centre's frame, `q`
        // rounds to 2^-6 at that size and the normal tilts.
        let s = 2f64.powi(46);
        let t = Triangle::new(v(s, s, 0.0), v(s + 2.0, s, 0.0), v(s, s + 2.0, 0.0));
        let k = contact_sphere_triangle(&Sphere::new(v(s + 0.5, s + 0.5, 0.75), 1.0), &t).expect("overlap");
        assert!(close(k.normal.z, 1.0) && close(k.depth, 0.25), "{k:?}");
    }

    #[test]
    fn a_centre_a_hair_off_the_face_gets_the_side_it_is_on() {
        // Centre 1e-300 below the face z = 0 (inside it in x, y): the closest point
        // rounds onto the centre, but the exact side test says below, so the
        // normal is −z and the contact is not degenerate.
        let k = contact_sphere_triangle(&Sphere::new(v(0.5, 0.5, -1e-300), 1.0), &tri::<f64>()).expect("overlap");
        assert!(!k.degenerate && close(k.normal.z, -1.0), "{k:?}");
    }

    #[test]
    fn a_centre_in_the_plane_but_outside_the_triangle_is_not_degenerate() {
        // Centre (3, 3, 0), r = 2: in the plane, beyond the hypotenuse; q = (1,1,0),
        // ‖M − q‖ = 2√2 > 2: no contact. With r = 3: normal (1,1,0)/√2.
        assert!(contact_sphere_triangle(&Sphere::new(v(3.0, 3.0, 0.0), 2.0), &tri::<f64>()).is_none());
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 3.0, 0.0), 3.0), &tri::<f64>()).expect("overlap");
        assert!(!k.degenerate && close(k.normal.x, 0.5f64.sqrt()), "{k:?}");
    }
}
