//! collide as engines: each method and precision is its own engine
//! (`collide/lecture`, `collide/robust`, `collide-f32/lecture`, `collide-f32/robust`).
//!
//! collide already speaks the fixture format's conventions, so this adapter only
//! converts numbers: inputs are rounded to the engine's precision here (for `f32`
//! that rounding is part of what the engine is judged on) and answers widened
//! back to `f64`.

use crate::engine::{Queries, Reply};
use crate::mesh::Mesh;
use collide::Real;
use oracle::geom::{
    Aabb, Ball, BarycentricAnswer, BoundsAnswer, Contact, ContactAnswer, IntersectAnswer, P3, Plane, Segment,
    SegmentHit, Sphere, Triangle,
};
use std::marker::PhantomData;

/// Which of collide's methods an engine runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The lecture's formulas as written: naive norms, `== 0` parallel tests,
    /// Sunday's s–t test, unsigned area ratios, the centroid bounding sphere.
    Lecture,
    /// The robust methods beside them: scaled norms, exact predicates, signed
    /// barycentrics, the minimal (Welzl) bounding sphere.
    Robust,
}

/// collide in precision `T` with one method.
#[derive(Clone, Copy, Debug)]
pub struct CollideQueries<T> {
    method: Method,
    _t: PhantomData<fn() -> T>,
}

impl<T> CollideQueries<T> {
    /// The engine running `method`.
    pub fn new(method: Method) -> Self {
        Self { method, _t: PhantomData }
    }
}

fn v<T: Real>(p: &P3) -> collide::Vec3<T> {
    collide::Vec3::new(T::of(p[0]), T::of(p[1]), T::of(p[2]))
}

fn w<T: Real>(p: &collide::Vec3<T>) -> P3 {
    [p.x.wide(), p.y.wide(), p.z.wide()]
}

fn sphere<T: Real>(s: &Sphere) -> collide::Sphere<T> {
    collide::Sphere::new(v(&s.center), T::of(s.radius))
}

fn plane<T: Real>(p: &Plane) -> collide::Plane<T> {
    collide::Plane::new(v(&p.normal), T::of(p.offset))
}

fn triangle<T: Real>(t: &Triangle) -> collide::Triangle<T> {
    collide::Triangle::new(v(&t.vertices[0]), v(&t.vertices[1]), v(&t.vertices[2]))
}

fn segment<T: Real>(s: &Segment) -> collide::Segment<T> {
    collide::Segment::new(v(&s.start), v(&s.end))
}

fn contact<T: Real>(k: Option<collide::contact::Contact<T>>) -> ContactAnswer {
    ContactAnswer {
        contact: k.map(|k| Contact { point: w(&k.point), normal: w(&k.normal), depth: k.depth.wide() }),
        degenerate: k.is_some_and(|k| k.degenerate),
    }
}

fn intersection<T: Real>(i: collide::intersect::Intersection<T>) -> IntersectAnswer {
    IntersectAnswer {
        hit: i.hit.map(|h| SegmentHit {
            t: h.t.wide(),
            point: w(&h.point),
            normal: w(&h.normal),
            barycentric: h.barycentric.map(|b| [b[0].wide(), b[1].wide(), b[2].wide()]),
            triangle: None,
        }),
        parallel: i.parallel,
        degenerate: i.degenerate,
    }
}

impl<T: Real + Send + Sync> Queries for CollideQueries<T> {
    fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
        let (a, b) = (sphere::<T>(a), sphere::<T>(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::contact::contact_sphere_sphere_lecture(&a, &b),
            Method::Robust => collide::contact::contact_sphere_sphere(&a, &b),
        }))
    }

    fn contact_sphere_plane(&self, a: &Sphere, b: &Plane) -> Reply<ContactAnswer> {
        Ok(contact(collide::contact::contact_sphere_plane(&sphere::<T>(a), &plane(b))))
    }

    fn contact_plane_sphere(&self, a: &Plane, b: &Sphere) -> Reply<ContactAnswer> {
        Ok(contact(collide::contact::contact_plane_sphere(&plane::<T>(a), &sphere(b))))
    }

    fn contact_sphere_triangle(&self, a: &Sphere, b: &Triangle) -> Reply<ContactAnswer> {
        Ok(contact(collide::contact::contact_sphere_triangle(&sphere::<T>(a), &triangle(b))))
    }

    fn contact_triangle_sphere(&self, a: &Triangle, b: &Sphere) -> Reply<ContactAnswer> {
        Ok(contact(collide::contact::contact_triangle_sphere(&triangle::<T>(a), &sphere(b))))
    }

    fn intersect_segment_plane(&self, s: &Segment, p: &Plane) -> Reply<IntersectAnswer> {
        let (s, p) = (segment::<T>(s), plane::<T>(p));
        Ok(intersection(match self.method {
            Method::Lecture => collide::intersect::intersect_segment_plane_lecture(&s, &p),
            Method::Robust => collide::intersect::intersect_segment_plane(&s, &p),
        }))
    }

    fn intersect_segment_triangle(&self, s: &Segment, t: &Triangle) -> Reply<IntersectAnswer> {
        let (s, t) = (segment::<T>(s), triangle::<T>(t));
        Ok(intersection(match self.method {
            Method::Lecture => collide::intersect::intersect_segment_triangle_lecture(&s, &t),
            Method::Robust => collide::intersect::intersect_segment_triangle(&s, &t),
        }))
    }

    fn intersect_segment_mesh(&self, s: &Segment, m: &Mesh) -> Reply<IntersectAnswer> {
        // Every triangle, first hit by smallest t, ties to the lowest face index
        // (the lecture's brute force). As the format's definition for meshes: a
        // zero-area face is skipped and flags the answer degenerate; with no hit,
        // the answer is parallel when every face with area is parallel.
        let seg = segment::<T>(s);
        let mut best: Option<IntersectAnswer> = None;
        let mut all_parallel = true;
        let mut any_area = false;
        let mut any_degenerate = false;
        for (i, face) in m.faces().enumerate() {
            let t = triangle::<T>(&face);
            let r = intersection(match self.method {
                Method::Lecture => collide::intersect::intersect_segment_triangle_lecture(&seg, &t),
                Method::Robust => collide::intersect::intersect_segment_triangle(&seg, &t),
            });
            if r.degenerate {
                any_degenerate = true;
                continue;
            }
            any_area = true;
            all_parallel &= r.parallel;
            if let Some(mut h) = r.hit {
                h.triangle = Some(i);
                if best.as_ref().and_then(|b| b.hit).is_none_or(|b| h.t < b.t) {
                    best = Some(IntersectAnswer { hit: Some(h), parallel: false, degenerate: false });
                }
            }
        }
        Ok(match best {
            Some(b) => IntersectAnswer { degenerate: any_degenerate, ..b },
            None => IntersectAnswer { hit: None, parallel: any_area && all_parallel, degenerate: any_degenerate },
        })
    }

    fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
        let (p, t) = (v::<T>(p), triangle::<T>(t));
        let b = match self.method {
            Method::Lecture => collide::barycentric::barycentric_triangle_lecture(&p, &t),
            Method::Robust => collide::barycentric::barycentric_triangle(&p, &t),
        };
        Ok(BarycentricAnswer { coords: b.coords.map(|x| x.wide()), degenerate: b.degenerate })
    }

    fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
        let pts: Vec<collide::Vec3<T>> = points.iter().map(v).collect();
        let aabb = collide::bounds::aabb_from_points(&pts).map(|b| Aabb { min: w(&b.min), max: w(&b.max) });
        let sphere = match self.method {
            Method::Lecture => collide::bounds::bounding_sphere_centroid(&pts),
            Method::Robust => collide::bounds::bounding_sphere_minimal(&pts),
        };
        Ok(BoundsAnswer { aabb, sphere: sphere.map(|s| Ball { center: w(&s.center), radius: s.radius.wide() }) })
    }

    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        let a = collide::Aabb::new(v::<T>(&a.min), v(&a.max));
        let b = collide::Aabb::new(v::<T>(&b.min), v(&b.max));
        Ok(collide::bounds::test_aabb_aabb(&a, &b))
    }
}
