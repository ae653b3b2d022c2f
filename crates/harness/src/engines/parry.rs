//! parry3d-f64 and parry3d (f32) as engines. Their conventions are translated in
//! the oracle (`oracle::parry`), once per engine; this adapter only plugs them
//! into the seam.

use crate::engine::{Queries, Reply};
use crate::mesh::Mesh;
use oracle::geom::ToiAnswer;
use oracle::geom::{
    Aabb, BarycentricAnswer, BoundsAnswer, ContactAnswer, IntersectAnswer, P3, Plane, Segment, Sphere, Triangle,
};
use oracle::parry::{ParryCast, ParryEngine};

/// A parry engine behind the seam.
#[derive(Clone, Copy, Debug)]
pub struct ParryQueries<E>(pub E);

impl<E: ParryEngine + ParryCast + Send + Sync> Queries for ParryQueries<E> {
    fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
        Ok(self.0.contact_sphere_sphere(*a, *b))
    }
    fn contact_sphere_plane(&self, a: &Sphere, b: &Plane) -> Reply<ContactAnswer> {
        Ok(self.0.contact_sphere_plane(*a, *b))
    }
    fn contact_plane_sphere(&self, a: &Plane, b: &Sphere) -> Reply<ContactAnswer> {
        Ok(self.0.contact_plane_sphere(*a, *b))
    }
    fn contact_sphere_triangle(&self, a: &Sphere, b: &Triangle) -> Reply<ContactAnswer> {
        Ok(self.0.contact_sphere_triangle(*a, *b))
    }
    fn contact_triangle_sphere(&self, a: &Triangle, b: &Sphere) -> Reply<ContactAnswer> {
        Ok(self.0.contact_triangle_sphere(*a, *b))
    }
    fn intersect_segment_plane(&self, s: &Segment, p: &Plane) -> Reply<IntersectAnswer> {
        Ok(self.0.intersect_segment_plane(*s, *p))
    }
    fn intersect_segment_triangle(&self, s: &Segment, t: &Triangle) -> Reply<IntersectAnswer> {
        Ok(self.0.intersect_segment_triangle(*s, *t))
    }
    fn intersect_segment_mesh(&self, s: &Segment, m: &Mesh) -> Reply<IntersectAnswer> {
        Ok(self.0.intersect_segment_mesh(*s, &m.vertices, &m.triangles))
    }
    fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
        Ok(self.0.barycentric_triangle(*p, *t))
    }
    fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
        Ok(self.0.bounds_of_points(points))
    }
    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        Ok(self.0.overlap_aabb_aabb(*a, *b))
    }
    // Time of impact: parry's `cast_shapes` (`oracle::parry::ParryCast`), its
    // status kept in the oracle's answer; only the `toi` answer crosses the seam.
    fn toi_sphere_sphere(&self, a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        Ok(self.0.cast_sphere_sphere(*a, *va, *b, *vb, t_max).answer)
    }
    fn toi_sphere_plane(&self, a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        Ok(self.0.cast_sphere_plane(*a, *va, *b, *vb, t_max).answer)
    }
    fn toi_sphere_triangle(&self, a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        Ok(self.0.cast_sphere_triangle(*a, *va, *b, *vb, t_max).answer)
    }
}
