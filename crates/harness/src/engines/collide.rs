//! collide as engines: each method and precision is its own engine
//! (`collide/lecture`, `collide/robust`, `collide-f32/lecture`, `collide-f32/robust`).
//!
//! collide already speaks the fixture format's conventions, so this adapter only
//! converts numbers: inputs are rounded to the engine's precision here (for `f32`
//! that rounding is part of what the engine is judged on) and answers widened
//! back to `f64`.

use crate::engine::{Queries, Reply, Unsupported};
use crate::mesh::Mesh;
use collide::Real;
use oracle::geom::{
    Aabb, Ball, BarycentricAnswer, BoundsAnswer, Capsule, CcdAnswer, Contact, ContactAnswer, DistanceAnswer,
    IntersectAnswer, MovingPoint, MovingSegment, MovingTriangle, OrientedBox, P3, Plane, ResponseAnswer, Segment,
    SegmentHit, Solid, Sphere, Toi, ToiAnswer, Triangle,
};

/// Bisection steps of the lecture's interval halving as an engine: 40, so its
/// time is within `t_max / 2^40 ≈ 9.1e-13 · t_max` of the first time the static
/// test sees (the accuracy the campaign asks of time, with a margin), when the
/// end of the interval intersects at all.
pub const HALVING_STEPS: u32 = 40;
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

impl<T: Real> CollideQueries<T> {
    /// A time of impact by this engine's method: `lecture`, the interval
    /// halving, given its stopping rule ([`HALVING_STEPS`] bisections), or
    /// `robust`.
    fn toi_by<R>(&self, lecture: impl FnOnce(collide::toi::Halving<T>) -> R, robust: impl FnOnce() -> R) -> R {
        match self.method {
            Method::Lecture => lecture(collide::toi::Halving::Steps(HALVING_STEPS)),
            Method::Robust => robust(),
        }
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

fn oriented_box<T: Real>(b: &OrientedBox) -> collide::OrientedBox<T> {
    collide::OrientedBox::new(v(&b.center), v(&b.half_extents), b.rotation.map(T::of))
}

fn capsule<T: Real>(c: &Capsule) -> collide::Capsule<T> {
    collide::Capsule::new(v(&c.start), v(&c.end), T::of(c.radius))
}

fn aabb<T: Real>(b: &Aabb) -> collide::Aabb<T> {
    collide::Aabb::new(v(&b.min), v(&b.max))
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

/// `t_max` in the engine's precision. An `f64` bound beyond the type's range (a
/// finite `t_max` that rounds to infinity in `f32`, such as parry's "no limit"
/// `f64::MAX`) is the largest finite value of the type: the interval is then
/// as long as the type can express, and the lecture's halving still has a
/// finite end to test (where it cuts the step further, to the last time the
/// motion stays representable, see `collide::toi`). The closed forms and
/// advancement answer the same either way: no impact they find lies beyond
/// the type's largest time.
fn time<T: Real>(t_max: f64) -> T {
    let t = T::of(t_max);
    if t_max.is_finite() && !t.finite() { T::max_value().unwrap_or(t) } else { t }
}

fn toi<T: Real>(t: Option<collide::toi::Toi<T>>) -> ToiAnswer {
    ToiAnswer {
        toi: t.map(|t| Toi { t: t.t.wide(), point: w(&t.point), normal: w(&t.normal) }),
        degenerate: t.is_some_and(|t| t.degenerate),
    }
}

fn response<T: Real>(r: collide::response::Response<T>) -> ResponseAnswer {
    ResponseAnswer { velocity_a: w(&r.velocity_a), velocity_b: w(&r.velocity_b), degenerate: r.degenerate }
}

/// collide's continuous collision is written in `f64` only: an `f32` engine
/// says so rather than widen its inputs and run another precision's method.
fn ccd_in_f64<T: Real>() -> Reply<()> {
    if T::EPSILON.wide().to_bits() == f64::EPSILON.to_bits() {
        Ok(())
    } else {
        Err(Unsupported("collide's continuous collision (ccd) is written in f64 only".into()))
    }
}

fn ccd_answer(c: collide::ccd::Ccd) -> CcdAnswer {
    CcdAnswer { t: c.t, degenerate: c.degenerate }
}

fn f64v(p: &P3) -> collide::Vec3<f64> {
    collide::Vec3::new(p[0], p[1], p[2])
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

    fn contact_sphere_mesh(&self, a: &Sphere, b: &Mesh) -> Reply<ContactAnswer> {
        // The format's mesh rule for contact: the nearest face's contact, ties
        // to the lowest face index. The lecture tests every face and keeps the
        // deepest by its plain closest point; the robust method ranks the faces
        // by their certified distances, through the mesh's BVH.
        let vertices = b.vertices.iter().map(v::<T>).collect();
        let mesh = collide::mesh::TriMesh::new(vertices, b.triangles.clone())
            .map_err(|e| Unsupported(format!("mesh refused by collide: {e}")))?;
        let a = sphere::<T>(a);
        let k = match self.method {
            Method::Lecture => collide::mesh::contact_sphere_mesh_brute(&a, &mesh),
            Method::Robust => collide::mesh::contact_sphere_mesh_nearest_bvh(&a, &collide::mesh::MeshBvh::new(mesh)),
        };
        Ok(contact(k.map(|m| m.contact)))
    }

    fn contact_sphere_box(&self, a: &Sphere, b: &OrientedBox) -> Reply<ContactAnswer> {
        let (a, b) = (sphere::<T>(a), oriented_box(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_sphere_box_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_sphere_box(&a, &b),
        }))
    }

    fn contact_box_plane(&self, a: &OrientedBox, b: &Plane) -> Reply<ContactAnswer> {
        let (a, b) = (oriented_box::<T>(a), plane(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_box_plane_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_box_plane(&a, &b),
        }))
    }

    fn contact_sphere_capsule(&self, a: &Sphere, b: &Capsule) -> Reply<ContactAnswer> {
        let (a, b) = (sphere::<T>(a), capsule(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_sphere_capsule_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_sphere_capsule(&a, &b),
        }))
    }

    fn contact_capsule_capsule(&self, a: &Capsule, b: &Capsule) -> Reply<ContactAnswer> {
        let (a, b) = (capsule::<T>(a), capsule(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_capsule_capsule_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_capsule_capsule(&a, &b),
        }))
    }

    fn contact_capsule_plane(&self, a: &Capsule, b: &Plane) -> Reply<ContactAnswer> {
        let (a, b) = (capsule::<T>(a), plane(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_capsule_plane_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_capsule_plane(&a, &b),
        }))
    }

    fn contact_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<ContactAnswer> {
        let (a, b) = (oriented_box::<T>(a), oriented_box(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_box_box_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_box_box(&a, &b),
        }))
    }

    fn contact_box_triangle(&self, a: &OrientedBox, b: &Triangle) -> Reply<ContactAnswer> {
        let (a, b) = (oriented_box::<T>(a), triangle(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_box_triangle_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_box_triangle(&a, &b),
        }))
    }

    fn contact_capsule_box(&self, a: &Capsule, b: &OrientedBox) -> Reply<ContactAnswer> {
        let (a, b) = (capsule::<T>(a), oriented_box(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_capsule_box_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_capsule_box(&a, &b),
        }))
    }

    fn contact_capsule_triangle(&self, a: &Capsule, b: &Triangle) -> Reply<ContactAnswer> {
        let (a, b) = (capsule::<T>(a), triangle(b));
        Ok(contact(match self.method {
            Method::Lecture => collide::boxes::contact_capsule_triangle_lecture(&a, &b),
            Method::Robust => collide::boxes::contact_capsule_triangle(&a, &b),
        }))
    }

    fn intersect_segment_box(&self, s: &Segment, b: &OrientedBox) -> Reply<IntersectAnswer> {
        let (s, b) = (segment::<T>(s), oriented_box(b));
        Ok(intersection(match self.method {
            Method::Lecture => collide::boxes::intersect_segment_box_lecture(&s, &b),
            Method::Robust => collide::boxes::intersect_segment_box(&s, &b),
        }))
    }

    fn intersect_segment_capsule(&self, s: &Segment, b: &Capsule) -> Reply<IntersectAnswer> {
        let (s, b) = (segment::<T>(s), capsule(b));
        Ok(intersection(match self.method {
            Method::Lecture => collide::boxes::intersect_segment_capsule_lecture(&s, &b),
            Method::Robust => collide::boxes::intersect_segment_capsule(&s, &b),
        }))
    }

    fn bounds_box(&self, b: &OrientedBox) -> Reply<BoundsAnswer> {
        let b = oriented_box::<T>(b);
        let (aabb, sphere) = match self.method {
            Method::Lecture => {
                (collide::boxes::aabb_of_box_lecture(&b), collide::boxes::bounding_sphere_of_box_lecture(&b))
            }
            Method::Robust => (collide::boxes::aabb_of_box(&b), collide::boxes::bounding_sphere_of_box(&b)),
        };
        Ok(BoundsAnswer {
            aabb: Some(Aabb { min: w(&aabb.min), max: w(&aabb.max) }),
            sphere: Some(Ball { center: w(&sphere.center), radius: sphere.radius.wide() }),
        })
    }

    fn overlap_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<bool> {
        let (a, b) = (oriented_box::<T>(a), oriented_box(b));
        Ok(match self.method {
            Method::Lecture => collide::boxes::test_box_box_lecture(&a, &b),
            Method::Robust => collide::boxes::test_box_box(&a, &b),
        })
    }

    fn overlap_box_aabb(&self, a: &OrientedBox, b: &Aabb) -> Reply<bool> {
        let (a, b) = (oriented_box::<T>(a), aabb(b));
        Ok(match self.method {
            Method::Lecture => collide::boxes::test_box_aabb_lecture(&a, &b),
            Method::Robust => collide::boxes::test_box_aabb(&a, &b),
        })
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
        // collide answers with the format's mesh rule (first hit, ties to the
        // lowest face index; a zero-area face skipped and flagged; parallel when
        // every face with area is): the robust method through its BVH (exact,
        // equal to brute force), the lecture's by testing every face.
        let vertices = m.vertices.iter().map(v::<T>).collect();
        let mesh = collide::mesh::TriMesh::new(vertices, m.triangles.clone())
            .map_err(|e| Unsupported(format!("mesh refused by collide: {e}")))?;
        let seg = segment::<T>(s);
        let r = match self.method {
            Method::Lecture => collide::mesh::intersect_segment_mesh_lecture(&seg, &mesh),
            Method::Robust => collide::mesh::intersect_segment_mesh_bvh(&seg, &collide::mesh::MeshBvh::new(mesh)),
        };
        Ok(IntersectAnswer {
            hit: r.hit.map(|h| SegmentHit {
                t: h.t.wide(),
                point: w(&h.point),
                normal: w(&h.normal),
                barycentric: Some(h.barycentric.map(|b| b.wide())),
                triangle: Some(h.triangle),
            }),
            parallel: r.parallel,
            degenerate: r.degenerate,
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

    fn toi_sphere_sphere(&self, a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        let (a, va, b, vb, t_max) = (sphere::<T>(a), v::<T>(va), sphere::<T>(b), v::<T>(vb), time::<T>(t_max));
        Ok(toi(self.toi_by(
            |stop| collide::toi::toi_sphere_sphere_halving(&a, &va, &b, &vb, t_max, stop),
            || collide::toi::toi_sphere_sphere(&a, &va, &b, &vb, t_max),
        )))
    }

    fn toi_sphere_plane(&self, a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        let (a, va, b, vb, t_max) = (sphere::<T>(a), v::<T>(va), plane::<T>(b), v::<T>(vb), time::<T>(t_max));
        Ok(toi(self.toi_by(
            |stop| collide::toi::toi_sphere_plane_halving(&a, &va, &b, &vb, t_max, stop),
            || collide::toi::toi_sphere_plane(&a, &va, &b, &vb, t_max),
        )))
    }

    fn toi_sphere_triangle(&self, a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        let (a, va, b, vb, t_max) = (sphere::<T>(a), v::<T>(va), triangle::<T>(b), v::<T>(vb), time::<T>(t_max));
        Ok(toi(self.toi_by(
            |stop| collide::toi::toi_sphere_triangle_halving(&a, &va, &b, &vb, t_max, stop),
            || collide::toi::toi_sphere_triangle(&a, &va, &b, &vb, t_max, &collide::toi::Advancement::default()),
        )))
    }

    fn toi_sphere_box(&self, a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        let (a, va, b, vb, t_max) = (sphere::<T>(a), v::<T>(va), oriented_box::<T>(b), v::<T>(vb), time::<T>(t_max));
        Ok(toi(self.toi_by(
            |stop| collide::toi::toi_sphere_box_halving(&a, &va, &b, &vb, t_max, stop),
            || collide::toi::toi_sphere_box(&a, &va, &b, &vb, t_max),
        )))
    }

    fn toi_sphere_mesh(&self, a: &Sphere, va: &P3, b: &Mesh, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        // The format's mesh rule for toi: the earliest touch over the faces, each
        // a two-sided triangle; ties to the lowest face index. The robust method
        // is conservative advancement over the mesh's BVH, the lecture's interval
        // halving on the static sphere–mesh test (also through the BVH, which
        // answers exactly as testing every face does).
        let vertices = b.vertices.iter().map(v::<T>).collect();
        let mesh = collide::mesh::TriMesh::new(vertices, b.triangles.clone())
            .map_err(|e| Unsupported(format!("mesh refused by collide: {e}")))?;
        let bvh = collide::mesh::MeshBvh::new(mesh);
        let (a, va, vb, t_max) = (sphere::<T>(a), v::<T>(va), v::<T>(vb), time::<T>(t_max));
        let r = self.toi_by(
            |stop| collide::toi::toi_sphere_mesh_halving(&a, &va, &bvh, &vb, t_max, stop),
            || collide::toi::toi_sphere_mesh(&a, &va, &bvh, &vb, t_max, &collide::toi::Advancement::default()),
        );
        Ok(toi(r.map(|m| m.toi)))
    }

    fn response_sphere_sphere(
        &self,
        a: &Sphere,
        va: &P3,
        ma: f64,
        b: &Sphere,
        vb: &P3,
        mb: f64,
        e: f64,
    ) -> Reply<ResponseAnswer> {
        Ok(response(collide::response::respond_sphere_sphere_contact(
            &sphere::<T>(a),
            &v(va),
            T::of(ma),
            &sphere(b),
            &v(vb),
            T::of(mb),
            T::of(e),
        )))
    }

    fn response_sphere_plane(&self, _a: &Sphere, va: &P3, b: &Plane, e: f64) -> Reply<ResponseAnswer> {
        Ok(response(collide::response::respond_sphere_plane(&v::<T>(va), &v(&b.normal), T::of(e))))
    }

    fn ccd_point_triangle(&self, p: &MovingPoint, t: &MovingTriangle, t_max: f64) -> Reply<CcdAnswer> {
        ccd_in_f64::<T>()?;
        let x0 = [p.t0, t.t0[0], t.t0[1], t.t0[2]].map(|q| f64v(&q));
        let x1 = [p.t1, t.t1[0], t.t1[1], t.t1[2]].map(|q| f64v(&q));
        Ok(ccd_answer(match self.method {
            Method::Lecture => collide::ccd::ccd_vertex_face_lecture(&x0, &x1, t_max),
            Method::Robust => collide::ccd::ccd_vertex_face(&x0, &x1, t_max),
        }))
    }

    fn ccd_segment_segment(&self, a: &MovingSegment, b: &MovingSegment, t_max: f64) -> Reply<CcdAnswer> {
        ccd_in_f64::<T>()?;
        let x0 = [a.t0[0], a.t0[1], b.t0[0], b.t0[1]].map(|q| f64v(&q));
        let x1 = [a.t1[0], a.t1[1], b.t1[0], b.t1[1]].map(|q| f64v(&q));
        Ok(ccd_answer(match self.method {
            Method::Lecture => collide::ccd::ccd_edge_edge_lecture(&x0, &x1, t_max),
            Method::Robust => collide::ccd::ccd_edge_edge(&x0, &x1, t_max),
        }))
    }
    fn distance(&self, a: Solid<'_>, b: Solid<'_>) -> Reply<DistanceAnswer> {
        use collide::convex::{Rounded, distance_lecture, distance_plane, distance_plane_lecture, distance_solids};
        let (pa, ra) = rounded::<T>(a).ok_or_else(|| Unsupported("a plane is a distance's `b` only".into()))?;
        let ra = Rounded { points: &pa, radius: ra };
        let d = match b {
            Solid::Plane(p) => match self.method {
                Method::Lecture => distance_plane_lecture(&ra, &plane::<T>(p)),
                Method::Robust => distance_plane(&ra, &plane::<T>(p)),
            },
            _ => {
                let (pb, rb) = rounded::<T>(b).ok_or_else(|| Unsupported("no solid".into()))?;
                let rb = Rounded { points: &pb, radius: rb };
                match self.method {
                    Method::Lecture => distance_lecture(&ra, &rb),
                    Method::Robust => {
                        // The robust distance takes a box as the format
                        // defines it (its quaternion's exact rotation).
                        let (ba, bb) = (exact_box::<T>(a), exact_box::<T>(b));
                        let sa = ba.as_ref().map_or(collide::convex::Solid::Hull(ra), collide::convex::Solid::Box);
                        let sb = bb.as_ref().map_or(collide::convex::Solid::Hull(rb), collide::convex::Solid::Box);
                        distance_solids(&sa, &sb)
                    }
                }
            }
        };
        Ok(DistanceAnswer {
            distance: d.distance.wide(),
            point_a: w(&d.point_a),
            point_b: w(&d.point_b),
            normal: w(&d.normal),
            degenerate: d.degenerate,
        })
    }
}

/// A distance's box for collide's robust distance, which decides about it
/// exactly; `None` for another solid.
fn exact_box<T: Real>(s: Solid<'_>) -> Option<collide::OrientedBox<T>> {
    match s {
        Solid::Box(b) => Some(oriented_box::<T>(b)),
        _ => None,
    }
}

/// A distance's solid as collide's GJK takes it: the points of its core and
/// its radius (a box's eight corners from its rotation matrix, a triangle's
/// vertices); `None` for a plane.
fn rounded<T: Real>(s: Solid<'_>) -> Option<(Vec<collide::Vec3<T>>, T)> {
    Some(match s {
        Solid::Sphere(x) => (vec![v(&x.center)], T::of(x.radius)),
        Solid::Capsule(c) => (vec![v(&c.start), v(&c.end)], T::of(c.radius)),
        Solid::Box(b) => (collide::convex::box_corners(&oriented_box::<T>(b)).to_vec(), T::of(0.0)),
        Solid::Triangle(t) => (t.vertices.iter().map(v).collect(), T::of(0.0)),
        Solid::Convex(c) => (c.points.iter().map(v).collect(), T::of(0.0)),
        Solid::Plane(_) => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// parry's issue 35 scene (`fixtures/toi.json`): radius 0.5 at the origin
    /// moving (0, 10, 0) toward a resting ball at (0, 10, 0), `t_max = f64::MAX`.
    fn issue_35<T: Real + Send + Sync>(method: Method) -> ToiAnswer {
        let a = Sphere { center: [0.0; 3], radius: 0.5 };
        let b = Sphere { center: [0.0, 10.0, 0.0], radius: 0.5 };
        CollideQueries::<T>::new(method)
            .toi_sphere_sphere(&a, &[0.0, 10.0, 0.0], &b, &[0.0; 3], f64::MAX)
            .unwrap_or_else(|e| panic!("unsupported: {e}"))
    }

    #[test]
    fn a_t_max_beyond_f32_is_its_largest_value() {
        assert_eq!(time::<f32>(f64::MAX).to_bits(), f32::MAX.to_bits());
        assert_eq!(time::<f32>(1e39).to_bits(), f32::MAX.to_bits());
        assert_eq!(time::<f32>(0.5).to_bits(), 0.5f32.to_bits());
        assert_eq!(time::<f64>(f64::MAX).to_bits(), f64::MAX.to_bits());
    }

    #[test]
    fn issue_35_is_answered_in_both_precisions_without_a_non_finite_number() {
        // The closed form finds t = 9/10 in both precisions (f32 rounds it).
        for (what, answer, tol) in
            [("f64", issue_35::<f64>(Method::Robust), 1e-15), ("f32", issue_35::<f32>(Method::Robust), 1e-7)]
        {
            let k = answer.toi.unwrap_or_else(|| panic!("{what}: no impact"));
            assert!((k.t - 0.9).abs() <= tol, "{what}: t {}", k.t);
        }
        // The lecture's halving tests the end of its step, cut where the motion
        // leaves the type's range: far past the ball, clear: no impact (the
        // tunneling it is known for), and no NaN or infinity anywhere.
        for answer in [issue_35::<f64>(Method::Lecture), issue_35::<f32>(Method::Lecture)] {
            assert_eq!(answer, ToiAnswer { toi: None, degenerate: false });
        }
    }
}
