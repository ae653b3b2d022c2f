//! parry called directly on inputs already in its own types.
//!
//! `oracle::parry::ParryEngine` converts crashtest's `f64` vocabulary into
//! parry's shapes inside every call (rounding to `f32`, normalizing the plane,
//! building poses) and translates the answer back; timing it times that
//! adapter too. So beside it the bench times this path: the inputs are built as
//! the adapter builds them, once, before timing, and each query is the same
//! parry call the adapter makes, with nothing around it:
//!
//! | query | parry call |
//! | --- | --- |
//! | sphere–sphere, –plane, –triangle contact | `query::contact(pose_a, shape_a, pose_b, shape_b, 0)` |
//! | the same, by pair function (`*_pair`) | what `query::contact` does without its dynamic dispatch: `pos12 = pose_a⁻¹ pose_b`, the pair's `query::details` function (`contact_ball_ball`, `contact_support_map_halfspace`, `contact_ball_convex_polyhedron`, the ones its dispatcher picks), the contact moved back to world space |
//! | segment–plane | `HalfSpace::cast_ray_and_get_normal(pose, ray, 1, false)`, keeping the parameter; like for like (`*_like`), also the hit point `ray.point_at(t)` and the normal, which collide's answer holds |
//! | segment–triangle | `Triangle::cast_local_ray_and_get_normal(ray, 1, false)`, and on a hit `project_local_point_and_get_location` of the hit point, for the barycentrics collide's answer carries |
//! | barycentric | `Triangle::project_local_point_and_get_location(p, false)` |
//! | AABB overlap | `Aabb::intersects` |
//! | bounding sphere | `point_cloud_bounding_sphere` |
//!
//! Written once, instantiated for parry3d-f64 and parry3d (`f32`).

use oracle::geom;

macro_rules! parry_direct {
    ($name:ident, $krate:ident) => {
        /// parry called directly; see the module documentation.
        pub mod $name {
            use super::geom;
            use $krate::bounding_volume::details::point_cloud_bounding_sphere;
            use $krate::bounding_volume::{Aabb, BoundingSphere, BoundingVolume};
            use $krate::math::{Pose, Real, Vector};
            use $krate::query::{self, Contact, PointQueryWithLocation, Ray, RayCast};
            use $krate::shape::{Ball, HalfSpace, Triangle, TrianglePointLocation};

            /// A point in parry's scalar (rounded once for `f32`).
            pub fn v(p: geom::P3) -> Vector {
                Vector::new(p[0] as Real, p[1] as Real, p[2] as Real)
            }
            /// A sphere as the adapter places it.
            pub fn ball(s: &geom::Sphere) -> (Pose, Ball) {
                (Pose::from_translation(v(s.center)), Ball::new(s.radius as Real))
            }
            /// A plane as the adapter places it (unit normal, anchored at
            /// `(d/‖n‖) n̂`).
            pub fn half_space(p: &geom::Plane) -> (Pose, HalfSpace) {
                let n = v(p.normal);
                let unit = n.normalize();
                let origin = unit * (p.offset as Real / n.length());
                (Pose::from_translation(origin), HalfSpace::new(unit))
            }
            /// A triangle at the identity pose.
            pub fn triangle(t: &geom::Triangle) -> Triangle {
                let [a, b, c] = t.vertices;
                Triangle::new(v(a), v(b), v(c))
            }
            /// A segment as a ray with direction `end − start`.
            pub fn ray(s: &geom::Segment) -> Ray {
                let start = v(s.start);
                Ray::new(start, v(s.end) - start)
            }
            /// A box.
            pub fn aabb(b: &geom::Aabb) -> Aabb {
                Aabb::new(v(b.min), v(b.max))
            }
            /// A point cloud.
            pub fn cloud(ps: &[geom::P3]) -> Vec<Vector> {
                ps.iter().map(|&p| v(p)).collect()
            }

            /// Contact of two placed balls.
            #[inline]
            pub fn contact_sphere_sphere(a: &(Pose, Ball), b: &(Pose, Ball)) -> Option<Contact> {
                query::contact(&a.0, &a.1, &b.0, &b.1, 0.0).ok().flatten()
            }
            /// Contact of a ball and a half-space.
            #[inline]
            pub fn contact_sphere_plane(a: &(Pose, Ball), b: &(Pose, HalfSpace)) -> Option<Contact> {
                query::contact(&a.0, &a.1, &b.0, &b.1, 0.0).ok().flatten()
            }
            /// Contact of a ball and a triangle.
            #[inline]
            pub fn contact_sphere_triangle(a: &(Pose, Ball), b: &Triangle) -> Option<Contact> {
                query::contact(&a.0, &a.1, &Pose::IDENTITY, b, 0.0).ok().flatten()
            }
            /// [`contact_sphere_sphere`] through the pair function, without
            /// the dispatch.
            #[inline]
            #[allow(dead_code, reason = "timed for parry3d-f64 only")]
            pub fn contact_sphere_sphere_pair(a: &(Pose, Ball), b: &(Pose, Ball)) -> Option<Contact> {
                let pos12 = a.0.inv_mul(&b.0);
                let mut c = query::details::contact_ball_ball(&pos12, &a.1, &b.1, 0.0)?;
                c.transform_by_mut(&a.0, &b.0);
                Some(c)
            }
            /// [`contact_sphere_plane`] through the pair function.
            #[inline]
            #[allow(dead_code, reason = "timed for parry3d-f64 only")]
            pub fn contact_sphere_plane_pair(a: &(Pose, Ball), b: &(Pose, HalfSpace)) -> Option<Contact> {
                let pos12 = a.0.inv_mul(&b.0);
                let mut c = query::details::contact_support_map_halfspace(&pos12, &a.1, &b.1, 0.0)?;
                c.transform_by_mut(&a.0, &b.0);
                Some(c)
            }
            /// [`contact_sphere_triangle`] through the pair function.
            #[inline]
            #[allow(dead_code, reason = "timed for parry3d-f64 only")]
            pub fn contact_sphere_triangle_pair(a: &(Pose, Ball), b: &Triangle) -> Option<Contact> {
                let pos12 = a.0.inv_mul(&Pose::IDENTITY);
                let mut c = query::details::contact_ball_convex_polyhedron(&pos12, &a.1, b, 0.0)?;
                c.transform_by_mut(&a.0, &Pose::IDENTITY);
                Some(c)
            }
            /// A segment's ray against a half-space's surface.
            #[inline]
            pub fn intersect_segment_plane(r: &Ray, b: &(Pose, HalfSpace)) -> Option<Real> {
                b.1.cast_ray_and_get_normal(&b.0, r, 1.0, false).map(|h| h.time_of_impact)
            }
            /// [`intersect_segment_plane`] answering what collide's answer
            /// holds: the parameter, the hit point and the normal.
            #[inline]
            #[allow(dead_code, reason = "timed for parry3d-f64 only")]
            pub fn intersect_segment_plane_like(r: &Ray, b: &(Pose, HalfSpace)) -> Option<(Real, Vector, Vector)> {
                b.1.cast_ray_and_get_normal(&b.0, r, 1.0, false)
                    .map(|h| (h.time_of_impact, r.point_at(h.time_of_impact), h.normal))
            }
            /// A segment's ray against a triangle, with the hit's barycentrics.
            #[inline]
            pub fn intersect_segment_triangle(r: &Ray, t: &Triangle) -> Option<(Real, TrianglePointLocation)> {
                let hit = t.cast_local_ray_and_get_normal(r, 1.0, false)?;
                let (_, loc) = t.project_local_point_and_get_location(r.point_at(hit.time_of_impact), false);
                Some((hit.time_of_impact, loc))
            }
            /// The location (barycentrics) of a point's projection on a triangle.
            #[inline]
            pub fn barycentric(p: &Vector, t: &Triangle) -> TrianglePointLocation {
                t.project_local_point_and_get_location(*p, false).1
            }
            /// Box overlap.
            #[inline]
            pub fn overlap(a: &Aabb, b: &Aabb) -> bool {
                a.intersects(b)
            }
            /// parry's bounding sphere of a cloud.
            #[inline]
            pub fn bounding_sphere(ps: &[Vector]) -> BoundingSphere {
                point_cloud_bounding_sphere(ps)
            }
        }
    };
}

parry_direct!(p64, parry3d_f64);
parry_direct!(p32, parry3d);
