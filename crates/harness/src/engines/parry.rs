//! parry3d-f64 and parry3d (f32) as engines. Their conventions are translated in
//! the oracle (`oracle::parry`), once per engine; this adapter only plugs them
//! into the seam.

use crate::engine::{Queries, Reply};
use oracle::geom::{Aabb, BarycentricAnswer, BoundsAnswer, ContactAnswer, IntersectAnswer, P3, Plane, Segment, Sphere, Triangle};
use oracle::parry::ParryEngine;

/// A parry engine behind the seam.
#[derive(Clone, Copy, Debug)]
pub struct ParryQueries<E>(pub E);

impl<E: ParryEngine + Send + Sync> Queries for ParryQueries<E> {
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
    fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
        Ok(self.0.barycentric_triangle(*p, *t))
    }
    fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
        Ok(self.0.bounds_of_points(points))
    }
    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        Ok(self.0.overlap_aabb_aabb(*a, *b))
    }
}
