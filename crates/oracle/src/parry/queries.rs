//! parry3d-f64 and parry3d (f32) behind crashtest's engine trait: each
//! method is the oracle's translation of parry's answer ([`ParryEngine`],
//! [`ParryCast`]), where the conventions are translated once per engine.

use super::api::{Parry32, Parry64, ParryEngine};
use super::cast::ParryCast;
use crashtest_core::engine::{Queries, Reply};
use crashtest_core::geom::{
    Aabb, BarycentricAnswer, BoundsAnswer, Capsule, ContactAnswer, DistanceAnswer, IntersectAnswer, OrientedBox, P3,
    Plane, Segment, Solid, Sphere, ToiAnswer, Triangle,
};
use crashtest_core::mesh::Mesh;

/// The trait's methods for one parry engine (the two differ only in precision).
macro_rules! parry_queries {
    ($engine:ty) => {
        impl Queries for $engine {
            fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_sphere_sphere(self, *a, *b))
            }
            fn contact_sphere_plane(&self, a: &Sphere, b: &Plane) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_sphere_plane(self, *a, *b))
            }
            fn contact_plane_sphere(&self, a: &Plane, b: &Sphere) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_plane_sphere(self, *a, *b))
            }
            fn contact_sphere_triangle(&self, a: &Sphere, b: &Triangle) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_sphere_triangle(self, *a, *b))
            }
            fn contact_triangle_sphere(&self, a: &Triangle, b: &Sphere) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_triangle_sphere(self, *a, *b))
            }
            fn contact_sphere_mesh(&self, a: &Sphere, m: &Mesh) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_sphere_mesh(self, *a, &m.vertices, &m.triangles))
            }
            fn contact_sphere_box(&self, a: &Sphere, b: &OrientedBox) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_sphere_box(self, *a, *b))
            }
            fn contact_box_plane(&self, a: &OrientedBox, b: &Plane) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_box_plane(self, *a, *b))
            }
            fn contact_sphere_capsule(&self, a: &Sphere, b: &Capsule) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_sphere_capsule(self, *a, *b))
            }
            fn contact_capsule_capsule(&self, a: &Capsule, b: &Capsule) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_capsule_capsule(self, *a, *b))
            }
            fn contact_capsule_plane(&self, a: &Capsule, b: &Plane) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_capsule_plane(self, *a, *b))
            }
            fn contact_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_box_box(self, *a, *b))
            }
            fn contact_box_triangle(&self, a: &OrientedBox, b: &Triangle) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_box_triangle(self, *a, *b))
            }
            fn contact_capsule_box(&self, a: &Capsule, b: &OrientedBox) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_capsule_box(self, *a, *b))
            }
            fn contact_capsule_triangle(&self, a: &Capsule, b: &Triangle) -> Reply<ContactAnswer> {
                Ok(ParryEngine::contact_capsule_triangle(self, *a, *b))
            }
            fn intersect_segment_box(&self, s: &Segment, b: &OrientedBox) -> Reply<IntersectAnswer> {
                Ok(ParryEngine::intersect_segment_box(self, *s, *b))
            }
            fn intersect_segment_capsule(&self, s: &Segment, b: &Capsule) -> Reply<IntersectAnswer> {
                Ok(ParryEngine::intersect_segment_capsule(self, *s, *b))
            }
            fn bounds_box(&self, b: &OrientedBox) -> Reply<BoundsAnswer> {
                Ok(ParryEngine::bounds_box(self, *b))
            }
            fn overlap_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<bool> {
                Ok(ParryEngine::overlap_box_box(self, *a, *b))
            }
            fn overlap_box_aabb(&self, a: &OrientedBox, b: &Aabb) -> Reply<bool> {
                Ok(ParryEngine::overlap_box_aabb(self, *a, *b))
            }
            fn intersect_segment_plane(&self, s: &Segment, p: &Plane) -> Reply<IntersectAnswer> {
                Ok(ParryEngine::intersect_segment_plane(self, *s, *p))
            }
            fn intersect_segment_triangle(&self, s: &Segment, t: &Triangle) -> Reply<IntersectAnswer> {
                Ok(ParryEngine::intersect_segment_triangle(self, *s, *t))
            }
            fn intersect_segment_mesh(&self, s: &Segment, m: &Mesh) -> Reply<IntersectAnswer> {
                Ok(ParryEngine::intersect_segment_mesh(self, *s, &m.vertices, &m.triangles))
            }
            fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
                Ok(ParryEngine::barycentric_triangle(self, *p, *t))
            }
            fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
                Ok(ParryEngine::bounds_of_points(self, points))
            }
            fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
                Ok(ParryEngine::overlap_aabb_aabb(self, *a, *b))
            }
            // Time of impact: parry's `cast_shapes` (`oracle::parry::ParryCast`), its
            // status kept in the oracle's answer; only the `toi` answer crosses the seam.
            fn toi_sphere_sphere(&self, a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
                Ok(ParryCast::cast_sphere_sphere(self, *a, *va, *b, *vb, t_max).answer)
            }
            fn toi_sphere_plane(&self, a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
                Ok(ParryCast::cast_sphere_plane(self, *a, *va, *b, *vb, t_max).answer)
            }
            fn toi_sphere_triangle(&self, a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
                Ok(ParryCast::cast_sphere_triangle(self, *a, *va, *b, *vb, t_max).answer)
            }
            fn toi_sphere_box(&self, a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
                Ok(ParryCast::cast_sphere_box(self, *a, *va, *b, *vb, t_max).answer)
            }
            fn distance(&self, a: Solid<'_>, b: Solid<'_>) -> Reply<DistanceAnswer> {
                ParryEngine::distance(self, a, b).map_err(crashtest_core::engine::Unsupported)
            }
        }
    };
}

parry_queries!(Parry64);
parry_queries!(Parry32);
