//! Sphere–triangle contact.

use super::Contact;
use super::closest_pt_triangle::closest_pt_point_triangle;
use super::sphere_sphere::CONCENTRIC_FALLBACK_NORMAL;
use crate::real::{Real, Vec3, c, stable_norm, try_normalize_stable};
use crate::shapes::{Sphere, Triangle};

/// Contact between a sphere `a` (centre `M`, radius `r`) and a triangle `b`.
///
/// **Method.** The triangle's point closest to the centre, `q`
/// ([`closest_pt_point_triangle`]), is where the sphere meets the triangle first;
/// then, as for two spheres with `b` shrunk to the point `q`:
///
/// ```text
/// contact when ‖M − q‖ ≤ r,   n = (M − q) / ‖M − q‖,   p = q,   depth = r − ‖M − q‖
/// ```
///
/// The triangle is two-sided and has no thickness: a centre behind the face is
/// pushed out through the face it is behind, as for one in front.
///
/// **Degenerate input.** A centre exactly on the triangle (`q = M`) has no
/// direction: the normal falls back to the face normal `(v1 − v0) × (v2 − v0)`,
/// normalized, depth `r`, flagged; if the triangle has zero area as well, to
/// [`CONCENTRIC_FALLBACK_NORMAL`]. A zero-area triangle otherwise is answered
/// exactly as the segment or point it collapsed to.
pub fn contact_sphere_triangle<T: Real>(a: &Sphere<T>, b: &Triangle<T>) -> Option<Contact<T>> {
    let q = closest_pt_point_triangle(&a.center, b);
    let delta = a.center - q;
    let dist = stable_norm(&delta);
    if !(dist <= a.radius) {
        return None;
    }
    let (normal, degenerate) = match try_normalize_stable(&delta) {
        Some(n) => (n, false),
        None => {
            let [v0, v1, v2] = b.vertices;
            let face = try_normalize_stable(&(v1 - v0).cross(&(v2 - v0))).unwrap_or_else(|| {
                let [x, y, z] = CONCENTRIC_FALLBACK_NORMAL;
                Vec3::new(c(x), c(y), c(z))
            });
            (face, true)
        }
    };
    Some(Contact { point: q, normal, depth: a.radius - dist, degenerate })
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
        let k = contact_sphere_triangle(&Sphere::new(v::<T>(0.5, 0.5, 0.75), c(1.0)), &tri())
            .expect("overlap");
        assert!(close(k.depth, 0.25) && close(k.normal.z, 1.0) && close(k.point.x, 0.5));
        // Below the face: normal −z, same depth (two-sided).
        let k = contact_sphere_triangle(&Sphere::new(v::<T>(0.5, 0.5, -0.75), c(1.0)), &tri())
            .expect("overlap");
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
        let k = contact_sphere_triangle(&Sphere::new(v(3.0, 0.0, 0.0), 1.5), &tri::<f64>())
            .expect("vertex");
        assert!(close(k.point.x, 2.0) && close(k.depth, 0.5) && close(k.normal.x, 1.0));
        // Beyond the hypotenuse x + y = 2: centre (2,2,0), q = (1,1,0),
        // ‖M − q‖ = √2, r = 2: depth 2 − √2, normal (1,1,0)/√2.
        let k = contact_sphere_triangle(&Sphere::new(v(2.0, 2.0, 0.0), 2.0), &tri::<f64>())
            .expect("edge");
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
        let k = contact_sphere_triangle(&Sphere::new(v(0.5, 0.5, 0.0), 1.0), &tri::<f64>())
            .expect("centre on the face");
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
        let k = contact_triangle_sphere(&tri::<f64>(), &Sphere::new(v(0.5, 0.5, 0.75), 1.0))
            .expect("overlap");
        assert!(close(k.normal.z, -1.0) && close(k.point.z, -0.25) && close(k.depth, 0.25));
    }
}
