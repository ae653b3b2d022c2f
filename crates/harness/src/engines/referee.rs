//! The referee as an engine: the exact answer every other engine is judged
//! against, and the margin of each case from its nearest decision boundary.

use crate::case::{Pair, Shape};
use crate::engine::{Queries, Reply, Unsupported};
use crate::load::LoadedCase;
use crate::mesh::Mesh;
use crashtest_core::vec3::{norm_sqrt_dot, sub};
use oracle::geom::{
    Aabb, BarycentricAnswer, BoundsAnswer, Capsule, CcdAnswer, ContactAnswer, DistanceAnswer, IntersectAnswer,
    MovingPoint, MovingSegment, MovingTriangle, OrientedBox, P3, Plane, ResponseAnswer, Segment, Solid, Sphere,
    ToiAnswer, Triangle,
};
use oracle::referee::{self, RefereeError};

/// The referee's queries.
#[derive(Clone, Copy, Debug, Default)]
pub struct RefereeQueries;

fn r<T>(x: Result<T, RefereeError>) -> Reply<T> {
    x.map_err(|e| Unsupported(format!("referee refused the input: {e:?}")))
}

impl Queries for RefereeQueries {
    fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
        r(referee::contact_sphere_sphere(a, b))
    }
    fn contact_sphere_plane(&self, a: &Sphere, b: &Plane) -> Reply<ContactAnswer> {
        r(referee::contact_sphere_plane(a, b))
    }
    fn contact_plane_sphere(&self, a: &Plane, b: &Sphere) -> Reply<ContactAnswer> {
        r(referee::contact_plane_sphere(a, b))
    }
    fn contact_sphere_triangle(&self, a: &Sphere, b: &Triangle) -> Reply<ContactAnswer> {
        r(referee::contact_sphere_triangle(a, b))
    }
    fn contact_triangle_sphere(&self, a: &Triangle, b: &Sphere) -> Reply<ContactAnswer> {
        r(referee::contact_triangle_sphere(a, b))
    }
    fn contact_sphere_mesh(&self, a: &Sphere, b: &Mesh) -> Reply<ContactAnswer> {
        r(referee::contact_sphere_mesh(a, &b.vertices, &b.triangles))
    }
    fn contact_sphere_box(&self, a: &Sphere, b: &OrientedBox) -> Reply<ContactAnswer> {
        r(referee::contact_sphere_box(a, b))
    }
    fn contact_box_plane(&self, a: &OrientedBox, b: &Plane) -> Reply<ContactAnswer> {
        r(referee::contact_box_plane(a, b))
    }
    fn contact_sphere_capsule(&self, a: &Sphere, b: &Capsule) -> Reply<ContactAnswer> {
        r(referee::contact_sphere_capsule(a, b))
    }
    fn contact_capsule_capsule(&self, a: &Capsule, b: &Capsule) -> Reply<ContactAnswer> {
        r(referee::contact_capsule_capsule(a, b))
    }
    fn contact_capsule_plane(&self, a: &Capsule, b: &Plane) -> Reply<ContactAnswer> {
        r(referee::contact_capsule_plane(a, b))
    }
    fn contact_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<ContactAnswer> {
        r(referee::contact_box_box(a, b))
    }
    fn contact_box_triangle(&self, a: &OrientedBox, b: &Triangle) -> Reply<ContactAnswer> {
        r(referee::contact_box_triangle(a, b))
    }
    fn contact_capsule_box(&self, a: &Capsule, b: &OrientedBox) -> Reply<ContactAnswer> {
        r(referee::contact_capsule_box(a, b))
    }
    fn contact_capsule_triangle(&self, a: &Capsule, b: &Triangle) -> Reply<ContactAnswer> {
        r(referee::contact_capsule_triangle(a, b))
    }
    fn intersect_segment_box(&self, s: &Segment, b: &OrientedBox) -> Reply<IntersectAnswer> {
        r(referee::intersect_segment_box(s, b))
    }
    fn intersect_segment_capsule(&self, s: &Segment, b: &Capsule) -> Reply<IntersectAnswer> {
        r(referee::intersect_segment_capsule(s, b))
    }
    fn bounds_box(&self, b: &OrientedBox) -> Reply<BoundsAnswer> {
        r(referee::bounds_box(b))
    }
    fn overlap_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<bool> {
        r(referee::overlap_box_box(a, b))
    }
    fn overlap_box_aabb(&self, a: &OrientedBox, b: &Aabb) -> Reply<bool> {
        r(referee::overlap_box_aabb(a, b))
    }
    fn intersect_segment_plane(&self, s: &Segment, p: &Plane) -> Reply<IntersectAnswer> {
        r(referee::intersect_segment_plane(s, p))
    }
    fn intersect_segment_triangle(&self, s: &Segment, t: &Triangle) -> Reply<IntersectAnswer> {
        r(referee::intersect_segment_triangle(s, t))
    }
    fn intersect_segment_mesh(&self, s: &Segment, m: &Mesh) -> Reply<IntersectAnswer> {
        r(referee::intersect_segment_mesh(s, &m.vertices, &m.triangles))
    }
    fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
        r(referee::barycentric_triangle(p, t))
    }
    fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
        Ok(BoundsAnswer {
            aabb: Some(r(referee::aabb_of_points(points))?),
            sphere: Some(r(referee::min_ball(points))?),
        })
    }
    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        r(referee::overlap_aabb_aabb(a, b))
    }
    fn toi_sphere_sphere(&self, a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        r(referee::toi_sphere_sphere(a, va, b, vb, t_max))
    }
    fn toi_sphere_plane(&self, a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        r(referee::toi_sphere_plane(a, va, b, vb, t_max))
    }
    fn toi_sphere_triangle(&self, a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        r(referee::toi_sphere_triangle(a, va, b, vb, t_max))
    }
    fn toi_sphere_mesh(&self, a: &Sphere, va: &P3, b: &Mesh, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        r(referee::toi_sphere_mesh(a, va, &b.vertices, &b.triangles, vb, t_max))
    }
    fn toi_sphere_box(&self, a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        r(referee::toi_sphere_box(a, va, b, vb, t_max))
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
        r(referee::response_sphere_sphere(a, va, ma, b, vb, mb, e))
    }
    fn response_sphere_plane(&self, _a: &Sphere, va: &P3, b: &Plane, e: f64) -> Reply<ResponseAnswer> {
        r(referee::response_sphere_plane(va, b, e))
    }
    fn ccd_point_triangle(&self, p: &MovingPoint, t: &MovingTriangle, t_max: f64) -> Reply<CcdAnswer> {
        r(referee::ccd_point_triangle(p, t, t_max))
    }
    fn ccd_segment_segment(&self, a: &MovingSegment, b: &MovingSegment, t_max: f64) -> Reply<CcdAnswer> {
        r(referee::ccd_segment_segment(a, b, t_max))
    }
    fn distance(&self, a: Solid<'_>, b: Solid<'_>) -> Reply<DistanceAnswer> {
        r(referee::distance(a, b))
    }
}

/// The referee's signed distance of a case from its nearest decision boundary
/// (touching, the segment's ends and the triangle's edges, the boxes' faces), as
/// a length; `None` where a case has no such boundary or the referee gives none.
/// A segment parameter margin is turned into a length by the segment's length.
pub fn margin(lc: &LoadedCase) -> Option<f64> {
    let case = &lc.case;
    use Shape as S;
    let (a, b) = (&case.a, case.b.as_ref());
    let (va, vb, t_max) = (case.a.velocity(), b.map(Shape::velocity).unwrap_or_default(), case.t_max());
    use Pair as P;
    match (case.pair()?, a, b) {
        (P::ContactSphereSphere, S::Sphere(a), Some(S::Sphere(b))) => {
            referee::contact_margin_sphere_sphere(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactSpherePlane, S::Sphere(a), Some(S::Plane(b)))
        | (P::ContactPlaneSphere, S::Plane(b), Some(S::Sphere(a))) => {
            referee::contact_margin_sphere_plane(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactSphereTriangle, S::Sphere(a), Some(S::Triangle(b)))
        | (P::ContactTriangleSphere, S::Triangle(b), Some(S::Sphere(a))) => {
            referee::contact_margin_sphere_triangle(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactSphereMesh, S::Sphere(a), _) => lc.meshes[1]
            .as_ref()
            .and_then(|m| referee::contact_margin_sphere_mesh(&a.to_geom(), &m.vertices, &m.triangles).ok()),
        (P::IntersectSegmentPlane, S::Segment(s), Some(S::Plane(p))) => {
            let s = s.to_geom();
            referee::intersect_margin_segment_plane(&s, &p.to_geom())
                .ok()
                .flatten()
                .map(|m| m * norm_sqrt_dot(sub(s.end, s.start)))
        }
        (P::IntersectSegmentTriangle, S::Segment(s), Some(S::Triangle(t))) => {
            let s = s.to_geom();
            referee::intersect_margin_segment_triangle(&s, &t.to_geom())
                .ok()
                .flatten()
                .map(|m| m * norm_sqrt_dot(sub(s.end, s.start)))
        }
        (P::OverlapAabbAabb, S::Aabb(a), Some(S::Aabb(b))) => {
            referee::overlap_margin_aabb_aabb(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::OverlapBoxBox, S::Box(a), Some(S::Box(b))) => {
            referee::overlap_margin_box_box(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::OverlapBoxAabb, S::Box(a), Some(S::Aabb(b))) => {
            referee::overlap_margin_box_aabb(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactSphereBox, S::Sphere(a), Some(S::Box(b))) => {
            referee::contact_margin_sphere_box(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactBoxPlane, S::Box(a), Some(S::Plane(b))) => {
            referee::contact_margin_box_plane(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactSphereCapsule, S::Sphere(a), Some(S::Capsule(b))) => {
            referee::contact_margin_sphere_capsule(&a.to_geom(), b).ok()
        }
        (P::ContactCapsuleCapsule, S::Capsule(a), Some(S::Capsule(b))) => {
            referee::contact_margin_capsule_capsule(a, b).ok()
        }
        (P::ContactCapsulePlane, S::Capsule(a), Some(S::Plane(b))) => {
            referee::contact_margin_capsule_plane(a, &b.to_geom()).ok()
        }
        // A segment against a box: minus its distance from the box when it
        // misses, how deep it passes when it hits (its least push out) — the
        // margin of a capsule of radius 0 on that axis.
        (P::IntersectSegmentBox, S::Segment(s), Some(S::Box(b))) => {
            let axis = oracle::geom::Capsule { start: s.start, end: s.end, radius: 0.0 };
            referee::contact_margin_capsule_box(&axis, &b.to_geom()).ok()
        }
        (P::IntersectSegmentCapsule, S::Segment(s), Some(S::Capsule(b))) => {
            referee::intersect_margin_segment_capsule(&s.to_geom(), b).ok()
        }
        (P::ContactBoxBox, S::Box(a), Some(S::Box(b))) => {
            referee::contact_margin_box_box(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactBoxTriangle, S::Box(a), Some(S::Triangle(b))) => {
            referee::contact_margin_box_triangle(&a.to_geom(), &b.to_geom()).ok()
        }
        (P::ContactCapsuleBox, S::Capsule(a), Some(S::Box(b))) => {
            referee::contact_margin_capsule_box(a, &b.to_geom()).ok()
        }
        (P::ContactCapsuleTriangle, S::Capsule(a), Some(S::Triangle(b))) => {
            referee::contact_margin_capsule_triangle(a, &b.to_geom()).ok()
        }
        (P::ToiSphereSphere, S::Sphere(a), Some(S::Sphere(b))) => {
            referee::toi_margin_sphere_sphere(&a.to_geom(), &va, &b.to_geom(), &vb, t_max).ok()
        }
        (P::ToiSpherePlane, S::Sphere(a), Some(S::Plane(b))) => {
            referee::toi_margin_sphere_plane(&a.to_geom(), &va, &b.to_geom(), &vb, t_max).ok()
        }
        (P::ToiSphereTriangle, S::Sphere(a), Some(S::Triangle(b))) => {
            referee::toi_margin_sphere_triangle(&a.to_geom(), &va, &b.to_geom(), &vb, t_max).ok()
        }
        (P::ToiSphereMesh, S::Sphere(a), _) => lc.meshes[1].as_ref().and_then(|m| {
            referee::toi_margin_sphere_mesh(&a.to_geom(), &va, &m.vertices, &m.triangles, &vb, t_max).ok()
        }),
        (P::ToiSphereBox, S::Sphere(a), Some(S::Box(b))) => {
            referee::toi_margin_sphere_box(&a.to_geom(), &va, &b.to_geom(), &vb, t_max).ok()
        }
        // No margin, with the reason: the segment–mesh hit is decided face by
        // face (each face's margin is its own); a barycentric, a bound and a
        // response have no yes/no predicate whose distance from flipping a
        // margin would measure.
        (
            P::IntersectSegmentMesh | P::BarycentricPointTriangle | P::BoundsPoints | P::BoundsMesh | P::BoundsBox,
            _,
            _,
        )
        | (P::ResponseSphereSphere | P::ResponseSpherePlane, _, _) => None,
        // Continuous collision is judged exactly, with no borderline band (the
        // CCD benchmark's terms: a method's false positives and negatives are
        // counted against the exact answer; docs/FORMAT.md).
        (P::CcdPointTriangle | P::CcdSegmentSegment, _, _) => None,
        // A distance is a number, not a yes/no answer: its error is measured
        // as it is (a touching pair is distance 0, judged like any other).
        (p, _, _) if p.query() == crate::case::Query::Distance => None,
        // The pair's shapes are not the kinds its row names: only a case built by
        // hand and never loaded.
        _ => None,
    }
}
