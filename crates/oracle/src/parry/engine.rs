//! The adapter body, written once and compiled once per precision (from
//! `parry64.rs` and `parry32.rs`): the parent module supplies `backend` (the parry
//! crate), `Real` (its scalar), `Engine` (the unit struct implemented here),
//! `narrow` and `widen` (the edge conversions).
//!
//! The conventions table is in [`crate::parry`]; the translations it describes
//! live here, one function per kind of answer: [`translate_contact`],
//! [`translate_hit`] and [`translate_location`]. Everything else builds parry's
//! shapes from crashtest's and checks what comes back.

use super::backend::bounding_volume::details::point_cloud_bounding_sphere;
use super::backend::bounding_volume::{Aabb as EngineAabb, BoundingVolume};
use super::backend::math::Rotation;
use super::backend::math::{DEFAULT_EPSILON, Pose, Vector};
use super::backend::query::details::line_toi_with_halfspace;
use super::backend::query::{self, PointQuery, PointQueryWithLocation, Ray, RayCast, RayIntersection, Unsupported};
use super::backend::shape::{
    Ball as EngineBall, Capsule as EngineCapsule, ConvexPolyhedron, Cuboid, HalfSpace, Shape, TriMesh as EngineTriMesh,
    Triangle as EngineTriangle, TrianglePointLocation,
};
use super::{Engine, Real, narrow, widen};
use crate::geom::{
    Aabb, Ball, BarycentricAnswer, BoundsAnswer, Capsule, Contact, ContactAnswer, DistanceAnswer, IntersectAnswer,
    OrientedBox, P3, Plane, Segment, SegmentHit, Solid, Sphere, Triangle,
};
use crate::parry::api::ParryEngine;

/// Prediction distance handed to `query::contact`: 0, so parry reports only
/// touching or overlapping pairs (crashtest's definition of a contact). A positive
/// value would also report separated pairs and is not used, even though it would
/// make ball–ball report exact touching (see `TOUCHING_SPHERES`).
const PREDICTION: Real = 0.0;

/// Largest time of impact of a ray cast: the segment ends at `t = 1` (ray direction
/// `end − start`); parry's comparison `toi ≤ max` keeps a hit at the very end.
const MAX_TIME_OF_IMPACT: Real = 1.0;

/// Barycentric fallback when no coordinates can be given: the centroid's weights,
/// which sum to 1.
const CENTROID_WEIGHTS: [f64; 3] = [1.0 / 3.0; 3];

/// No contact, flagged: the fallback of every contact query.
const NO_CONTACT_DEGENERATE: ContactAnswer = ContactAnswer { contact: None, degenerate: true };

/// No hit, not parallel, flagged: the fallback of every intersect query.
const NO_HIT_DEGENERATE: IntersectAnswer = IntersectAnswer { hit: None, parallel: false, degenerate: true };

// ---------------------------------------------------------------------------
// The edge: crashtest's f64 in, the engine's scalar out, and back.

/// An input scalar in the engine's precision, or `None` when it is not finite there.
fn scalar(x: f64) -> Option<Real> {
    let r = narrow(x);
    r.is_finite().then_some(r)
}

/// An input point in the engine's precision, or `None` when not finite there.
pub(crate) fn vector(p: P3) -> Option<Vector> {
    Some(Vector::new(scalar(p[0])?, scalar(p[1])?, scalar(p[2])?))
}

/// An engine scalar as an answer, or `None` when parry returned a NaN or infinity.
fn answer_scalar(x: Real) -> Option<f64> {
    x.is_finite().then(|| widen(x))
}

/// An engine vector as an answer, or `None` when parry returned a NaN or infinity.
pub(crate) fn answer_point(v: Vector) -> Option<P3> {
    Some([answer_scalar(v.x)?, answer_scalar(v.y)?, answer_scalar(v.z)?])
}

/// A sphere as parry places it: a ball of radius `r` at the translation of its
/// centre. `None` for a radius that is not positive or a non-finite input.
pub(crate) fn ball(s: &Sphere) -> Option<(Pose, EngineBall)> {
    let center = vector(s.center)?;
    let radius = scalar(s.radius)?;
    (radius > 0.0).then(|| (Pose::from_translation(center), EngineBall::new(radius)))
}

/// The plane `n · x = d` as parry's half-space: unit normal `n̂ = n/‖n‖` placed at
/// the translation `(d/‖n‖) n̂`, so that its boundary `n̂ · (x − (d/‖n‖) n̂) = 0` is
/// `n · x = d` and its solid side `n · x ≤ d`. `None` when `n` cannot be normalized
/// (zero, or non-finite in the engine's scalar) or the placement overflows.
pub(crate) fn half_space(p: &Plane) -> Option<(Pose, HalfSpace)> {
    let n = vector(p.normal)?;
    let d = scalar(p.offset)?;
    let unit = n.try_normalize()?;
    let origin = unit * (d / n.length());
    origin.is_finite().then(|| (Pose::from_translation(origin), HalfSpace::new(unit)))
}

/// A box as parry places it: a `Cuboid` of the box's half-extents at the pose
/// (centre, `q/‖q‖`). The quaternion is scaled by a power of two in `f64` first
/// (exact), so that a huge or subnormal one normalizes in the engine's scalar.
/// `None` for a negative half-extent, a zero quaternion or a non-finite input.
pub(crate) fn cuboid(b: &OrientedBox) -> Option<(Pose, Cuboid)> {
    let center = vector(b.center)?;
    let half = vector(b.half_extents)?;
    if half.min_element() < 0.0 {
        return None;
    }
    let m = b.rotation.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let e = -(m.log2().floor() as i32);
    let k = 2f64.powi(e / 2) * 2f64.powi(e - e / 2);
    let [w, x, y, z] = b.rotation.map(|c| c * k);
    let q = Rotation::from_xyzw(scalar(x)?, scalar(y)?, scalar(z)?, scalar(w)?).normalize();
    q.is_finite().then(|| (Pose::from_parts(center, q), Cuboid::new(half)))
}

/// A capsule as parry's: its segment's two ends and its radius, at the
/// identity pose. `None` for a radius that is not positive or a non-finite input.
fn capsule(c: &Capsule) -> Option<EngineCapsule> {
    let radius = scalar(c.radius)?;
    (radius > 0.0).then_some(())?;
    Some(EngineCapsule::new(vector(c.start)?, vector(c.end)?, radius))
}

/// A distance query's solid as parry's shape at its pose (built once: a
/// hull's `ConvexPolyhedron` is the costly part).
pub type PreparedSolid = (Pose, Box<dyn Shape>);

/// A distance query's solid as parry's shape and pose, or why there is none.
pub fn solid(s: Solid<'_>) -> Result<PreparedSolid, String> {
    let bad = |what: &str| format!("parry: {what} not representable in the engine's scalar");
    Ok(match s {
        Solid::Sphere(x) => {
            let (p, b) = ball(x).ok_or_else(|| bad("sphere"))?;
            (p, Box::new(b))
        }
        Solid::Capsule(c) => (Pose::IDENTITY, Box::new(capsule(c).ok_or_else(|| bad("capsule"))?)),
        Solid::Box(b) => {
            let (p, c) = cuboid(b).ok_or_else(|| bad("box"))?;
            (p, Box::new(c))
        }
        Solid::Triangle(t) => (Pose::IDENTITY, Box::new(triangle(t).ok_or_else(|| bad("triangle"))?)),
        Solid::Plane(p) => {
            let (pose, h) = half_space(p).ok_or_else(|| bad("plane"))?;
            (pose, Box::new(h))
        }
        Solid::Convex(c) => {
            let points: Vec<Vector> =
                c.points.iter().map(|p| vector(*p)).collect::<Option<_>>().ok_or_else(|| bad("hull"))?;
            let hull = ConvexPolyhedron::from_convex_hull(&points)
                .ok_or_else(|| "parry: ConvexPolyhedron::from_convex_hull gave no hull for these points".to_string())?;
            (Pose::IDENTITY, Box::new(hull))
        }
    })
}

/// The distance of two prepared solids: `query::contact` at the largest
/// prediction, translated (`ParryEngine::distance`).
pub fn distance_prepared((pa, sa): &PreparedSolid, (pb, sb): &PreparedSolid) -> Result<DistanceAnswer, String> {
    let c = query::contact(pa, sa.as_ref(), pb, sb.as_ref(), Real::MAX)
        .map_err(|_| "parry: query::contact does not dispatch this pair".to_string())?
        .ok_or_else(|| "parry: query::contact returned no contact at the largest prediction".to_string())?;
    let answer = || {
        Some(DistanceAnswer {
            distance: answer_scalar(c.dist)?,
            point_a: answer_point(c.point1)?,
            point_b: answer_point(c.point2)?,
            normal: answer_point(-c.normal1)?,
            degenerate: false,
        })
    };
    answer().ok_or_else(|| "parry: a non-finite number in the contact".to_string())
}

/// An AABB as a `Cuboid` at its centre, in the engine's scalar.
fn aabb_cuboid(b: &Aabb) -> Option<(Pose, Cuboid)> {
    let (lo, hi) = (vector(b.min)?, vector(b.max)?);
    let center = (lo + hi) * 0.5;
    let half = (hi - lo) * 0.5;
    (center.is_finite() && half.is_finite()).then(|| (Pose::from_translation(center), Cuboid::new(half)))
}

/// A triangle as parry's, from its world vertices (placed at the identity pose).
/// `None` for a non-finite input.
fn triangle(t: &Triangle) -> Option<EngineTriangle> {
    let [a, b, c] = t.vertices;
    Some(EngineTriangle::new(vector(a)?, vector(b)?, vector(c)?))
}

/// A segment as parry's ray: origin `start`, direction `end − start` (computed in
/// the engine's scalar). `None` for a zero-length segment (the direction is exactly
/// zero in the engine's scalar) or a non-finite input or direction.
fn ray(s: &Segment) -> Option<Ray> {
    let start = vector(s.start)?;
    let dir = vector(s.end)? - start;
    (dir.is_finite() && dir != Vector::ZERO).then(|| Ray::new(start, dir))
}

/// Every point of a non-empty set in the engine's precision; `None` when the set
/// is empty (parry's point-cloud functions would panic) or a point is not finite.
fn points(ps: &[P3]) -> Option<Vec<Vector>> {
    if ps.is_empty() {
        return None;
    }
    ps.iter().map(|&p| vector(p)).collect()
}

/// A box in the engine's precision, bounds rounded as they are (infinities kept:
/// `overlap` needs no refusal).
fn engine_aabb(b: &Aabb) -> EngineAabb {
    let v = |p: P3| Vector::new(narrow(p[0]), narrow(p[1]), narrow(p[2]));
    EngineAabb::new(v(b.min), v(b.max))
}

// ---------------------------------------------------------------------------
// The translations: the only places where parry's conventions meet crashtest's.

/// parry's contact between shape 1 = `a` and shape 2 = `b` (world frame) in
/// crashtest's convention: point = `point2` (on `b`'s surface), normal =
/// `−normal1` (parry's points from `a` toward `b`; crashtest's from `b` toward
/// `a`), depth = `−dist` (parry's `dist < 0` is penetration), written `0 − dist`
/// so that an exact touch gives `+0`. `None` when parry returned a non-finite
/// number.
fn translate_contact(c: &query::Contact) -> Option<Contact> {
    Some(Contact {
        point: answer_point(c.point2)?,
        normal: answer_point(-c.normal1)?,
        depth: answer_scalar(0.0 - c.dist)?,
    })
}

/// parry's ray hit in crashtest's convention: `t` = parry's time of impact (the ray
/// direction is `end − start`), point = `ray.point_at(t)`, normal = parry's normal
/// re-oriented to the surface's own normal `own` (parry turns it toward the ray's
/// origin side). `None` when parry returned a non-finite number.
fn translate_hit(ray: &Ray, hit: &RayIntersection, own: Vector) -> Option<SegmentHit> {
    let normal = if hit.normal.dot(own) < 0.0 { -hit.normal } else { hit.normal };
    Some(SegmentHit {
        t: answer_scalar(hit.time_of_impact)?,
        point: answer_point(ray.point_at(hit.time_of_impact))?,
        normal: answer_point(normal)?,
        barycentric: None,
        triangle: None,
    })
}

/// parry's location of a projection on a triangle as `[α, β, γ]` for
/// `[v0, v1, v2]`: `TrianglePointLocation::barycentric_coordinates` (an edge's two
/// weights placed on its vertices, a vertex weighted 1). `None` for `OnSolid`
/// (never produced in 3-D) or non-finite coordinates.
fn translate_location(loc: &TrianglePointLocation) -> Option<[f64; 3]> {
    let [a, b, c] = loc.barycentric_coordinates()?;
    Some([answer_scalar(a)?, answer_scalar(b)?, answer_scalar(c)?])
}

/// A contact answer from parry's result, flagged `degenerate` as the caller found.
/// A non-finite answer, or parry refusing the pair (it dispatches every pair used
/// here, so this does not happen), gives no contact, flagged.
fn contact_answer(result: Result<Option<query::Contact>, Unsupported>, degenerate: bool) -> ContactAnswer {
    match result {
        Ok(None) => ContactAnswer { contact: None, degenerate },
        Ok(Some(c)) => match translate_contact(&c) {
            Some(contact) => ContactAnswer { contact: Some(contact), degenerate },
            None => NO_CONTACT_DEGENERATE,
        },
        Err(Unsupported) => NO_CONTACT_DEGENERATE,
    }
}

/// Whether parry answers a ball centred at `center` against `tri` with a fallback:
/// the triangle has no normal (parry's `Triangle::normal()` is `None`: zero area),
/// or the centre lies closer than `DEFAULT_EPSILON` to its projection on the
/// triangle — the branch condition of `contact_convex_polyhedron_ball`, evaluated
/// with the same projection (`project_local_point_and_get_feature`) on the same
/// local point (the triangle sits at the identity pose).
fn triangle_contact_fallback(tri: &EngineTriangle, center: Vector) -> bool {
    if tri.normal().is_none() {
        return true;
    }
    let (proj, _) = tri.project_local_point_and_get_feature(center);
    (proj.point - center).length() < DEFAULT_EPSILON
}

/// A mesh prepared for this engine: parry's `TriMesh` (built once, with its BVH)
/// or none for a mesh without faces, and whether some face has no normal in the
/// engine's scalar (parry's `Triangle::normal()` is `None`: zero area), which
/// flags every answer `degenerate` (the fixture format's mesh rule).
#[derive(Clone)]
pub struct PreparedMesh {
    trimesh: Option<EngineTriMesh>,
    degenerate: bool,
}

impl PreparedMesh {
    /// Number of faces.
    pub fn len(&self) -> usize {
        self.trimesh.as_ref().map_or(0, |t| t.num_triangles())
    }

    /// Whether the mesh has no face.
    pub fn is_empty(&self) -> bool {
        self.trimesh.is_none()
    }

    /// Whether some face has zero area in the engine's scalar.
    pub fn has_degenerate_face(&self) -> bool {
        self.degenerate
    }
}

impl core::fmt::Debug for PreparedMesh {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PreparedMesh").field("faces", &self.len()).field("degenerate", &self.degenerate).finish()
    }
}

/// The segment–triangle hit of a ray on `tri` in crashtest's convention, with the
/// barycentrics of the hit point (parry's location of its projection). `None`
/// when the triangle has no normal or parry returned a non-finite number.
fn triangle_hit(ray: &Ray, hit: &RayIntersection, tri: &EngineTriangle) -> Option<SegmentHit> {
    let mut answer = translate_hit(ray, hit, tri.normal()?)?;
    let (_, location) = tri.project_local_point_and_get_location(ray.point_at(hit.time_of_impact), false);
    answer.barycentric = Some(translate_location(&location)?);
    Some(answer)
}

impl ParryEngine for Engine {
    type Mesh = PreparedMesh;

    fn name(&self) -> &'static str {
        Engine::NAME
    }

    fn contact_sphere_sphere(&self, a: Sphere, b: Sphere) -> ContactAnswer {
        let (Some((pa, ba)), Some((pb, bb))) = (ball(&a), ball(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        // parry's own concentric branch: ‖Δ‖² = 0 (with identity rotations,
        // `pos1.inv_mul(pos2)` has the translation Δ exactly).
        let concentric = (pb.translation - pa.translation).length_squared() == 0.0;
        contact_answer(query::contact(&pa, &ba, &pb, &bb, PREDICTION), concentric)
    }

    fn contact_sphere_plane(&self, a: Sphere, b: Plane) -> ContactAnswer {
        let (Some((pa, ba)), Some((pb, hb))) = (ball(&a), half_space(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ba, &pb, &hb, PREDICTION), false)
    }

    fn contact_plane_sphere(&self, a: Plane, b: Sphere) -> ContactAnswer {
        let (Some((pa, ha)), Some((pb, bb))) = (half_space(&a), ball(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ha, &pb, &bb, PREDICTION), false)
    }

    fn contact_sphere_triangle(&self, a: Sphere, b: Triangle) -> ContactAnswer {
        let (Some((pa, ba)), Some(tb)) = (ball(&a), triangle(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        let degenerate = triangle_contact_fallback(&tb, pa.translation);
        let result = query::contact(&pa, &ba, &Pose::IDENTITY, &tb, PREDICTION);
        contact_answer(result, degenerate)
    }

    fn contact_triangle_sphere(&self, a: Triangle, b: Sphere) -> ContactAnswer {
        let (Some(ta), Some((pb, bb))) = (triangle(&a), ball(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        let degenerate = triangle_contact_fallback(&ta, pb.translation);
        let result = query::contact(&Pose::IDENTITY, &ta, &pb, &bb, PREDICTION);
        contact_answer(result, degenerate)
    }

    fn contact_sphere_mesh(&self, a: Sphere, vertices: &[P3], triangles: &[[usize; 3]]) -> ContactAnswer {
        let (Some((pa, ba)), Some(mesh)) = (ball(&a), self.mesh(vertices, triangles)) else {
            return NO_CONTACT_DEGENERATE;
        };
        let Some(trimesh) = &mesh.trimesh else {
            return ContactAnswer { contact: None, degenerate: mesh.degenerate };
        };
        let fallback = (0..trimesh.num_triangles() as u32)
            .any(|i| triangle_contact_fallback(&trimesh.triangle(i), pa.translation));
        let result = query::contact(&pa, &ba, &Pose::IDENTITY, trimesh, PREDICTION);
        contact_answer(result, fallback || mesh.degenerate)
    }

    fn contact_sphere_box(&self, a: Sphere, b: OrientedBox) -> ContactAnswer {
        let (Some((pa, ba)), Some((pb, cb))) = (ball(&a), cuboid(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ba, &pb, &cb, PREDICTION), false)
    }

    fn contact_box_plane(&self, a: OrientedBox, b: Plane) -> ContactAnswer {
        let (Some((pa, ca)), Some((pb, hb))) = (cuboid(&a), half_space(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ca, &pb, &hb, PREDICTION), false)
    }

    fn contact_sphere_capsule(&self, a: Sphere, b: Capsule) -> ContactAnswer {
        let (Some((pa, ba)), Some(cb)) = (ball(&a), capsule(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ba, &Pose::IDENTITY, &cb, PREDICTION), false)
    }

    fn contact_capsule_capsule(&self, a: Capsule, b: Capsule) -> ContactAnswer {
        let (Some(ca), Some(cb)) = (capsule(&a), capsule(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&Pose::IDENTITY, &ca, &Pose::IDENTITY, &cb, PREDICTION), false)
    }

    fn contact_capsule_plane(&self, a: Capsule, b: Plane) -> ContactAnswer {
        let (Some(ca), Some((pb, hb))) = (capsule(&a), half_space(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&Pose::IDENTITY, &ca, &pb, &hb, PREDICTION), false)
    }

    fn contact_box_box(&self, a: OrientedBox, b: OrientedBox) -> ContactAnswer {
        let (Some((pa, ca)), Some((pb, cb))) = (cuboid(&a), cuboid(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ca, &pb, &cb, PREDICTION), false)
    }

    fn contact_box_triangle(&self, a: OrientedBox, b: Triangle) -> ContactAnswer {
        let (Some((pa, ca)), Some(tb)) = (cuboid(&a), triangle(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&pa, &ca, &Pose::IDENTITY, &tb, PREDICTION), false)
    }

    fn contact_capsule_box(&self, a: Capsule, b: OrientedBox) -> ContactAnswer {
        let (Some(ca), Some((pb, cb))) = (capsule(&a), cuboid(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&Pose::IDENTITY, &ca, &pb, &cb, PREDICTION), false)
    }

    fn distance(&self, a: Solid<'_>, b: Solid<'_>) -> Result<DistanceAnswer, String> {
        distance_prepared(&solid(a)?, &solid(b)?)
    }

    fn contact_capsule_triangle(&self, a: Capsule, b: Triangle) -> ContactAnswer {
        let (Some(ca), Some(tb)) = (capsule(&a), triangle(&b)) else {
            return NO_CONTACT_DEGENERATE;
        };
        contact_answer(query::contact(&Pose::IDENTITY, &ca, &Pose::IDENTITY, &tb, PREDICTION), false)
    }

    fn intersect_segment_box(&self, s: Segment, b: OrientedBox) -> IntersectAnswer {
        let (Some(ray), Some((pose, cb))) = (ray(&s), cuboid(&b)) else {
            return NO_HIT_DEGENERATE;
        };
        match cb.cast_ray_and_get_normal(&pose, &ray, MAX_TIME_OF_IMPACT, true) {
            Some(hit) => match (answer_scalar(hit.time_of_impact), answer_point(ray.point_at(hit.time_of_impact))) {
                (Some(t), Some(point)) => match answer_point(hit.normal) {
                    Some(normal) => IntersectAnswer {
                        hit: Some(SegmentHit { t, point, normal, barycentric: None, triangle: None }),
                        parallel: false,
                        degenerate: false,
                    },
                    None => NO_HIT_DEGENERATE,
                },
                _ => NO_HIT_DEGENERATE,
            },
            None => IntersectAnswer::default(),
        }
    }

    fn intersect_segment_capsule(&self, s: Segment, b: Capsule) -> IntersectAnswer {
        let (Some(ray), Some((pose, cb))) = (ray(&s), capsule(&b).map(|c| (Pose::IDENTITY, c))) else {
            return NO_HIT_DEGENERATE;
        };
        match cb.cast_ray_and_get_normal(&pose, &ray, MAX_TIME_OF_IMPACT, true) {
            Some(hit) => match (answer_scalar(hit.time_of_impact), answer_point(ray.point_at(hit.time_of_impact))) {
                (Some(t), Some(point)) => match answer_point(hit.normal) {
                    Some(normal) => IntersectAnswer {
                        hit: Some(SegmentHit { t, point, normal, barycentric: None, triangle: None }),
                        parallel: false,
                        degenerate: false,
                    },
                    None => NO_HIT_DEGENERATE,
                },
                _ => NO_HIT_DEGENERATE,
            },
            None => IntersectAnswer::default(),
        }
    }

    fn bounds_box(&self, b: OrientedBox) -> BoundsAnswer {
        let Some((pose, cb)) = cuboid(&b) else {
            return BoundsAnswer::default();
        };
        let aabb = cb.aabb(&pose);
        let sphere = cb.bounding_sphere(&pose);
        BoundsAnswer {
            aabb: answer_point(aabb.mins).zip(answer_point(aabb.maxs)).map(|(min, max)| Aabb { min, max }),
            sphere: answer_point(sphere.center())
                .zip(answer_scalar(sphere.radius()))
                .map(|(center, radius)| Ball { center, radius }),
        }
    }

    fn overlap_box_box(&self, a: OrientedBox, b: OrientedBox) -> bool {
        let (Some((pa, ca)), Some((pb, cb))) = (cuboid(&a), cuboid(&b)) else {
            return false;
        };
        query::intersection_test(&pa, &ca, &pb, &cb).is_ok_and(|i| i.intersecting)
    }

    fn overlap_box_aabb(&self, a: OrientedBox, b: Aabb) -> bool {
        let (Some((pa, ca)), Some((pb, cb))) = (cuboid(&a), aabb_cuboid(&b)) else {
            return false;
        };
        query::intersection_test(&pa, &ca, &pb, &cb).is_ok_and(|i| i.intersecting)
    }

    fn intersect_segment_plane(&self, s: Segment, b: Plane) -> IntersectAnswer {
        let (Some(ray), Some((pose, hs))) = (ray(&s), half_space(&b)) else {
            return NO_HIT_DEGENERATE;
        };
        match hs.cast_ray_and_get_normal(&pose, &ray, MAX_TIME_OF_IMPACT, false) {
            Some(hit) => match translate_hit(&ray, &hit, hs.normal) {
                Some(hit) => IntersectAnswer { hit: Some(hit), parallel: false, degenerate: false },
                None => NO_HIT_DEGENERATE,
            },
            None => IntersectAnswer {
                hit: None,
                parallel: line_toi_with_halfspace(pose.translation, hs.normal, ray.origin, ray.dir).is_none(),
                degenerate: false,
            },
        }
    }

    fn intersect_segment_triangle(&self, s: Segment, b: Triangle) -> IntersectAnswer {
        let (Some(ray), Some(tri)) = (ray(&s), triangle(&b)) else {
            return NO_HIT_DEGENERATE;
        };
        let Some(face_normal) = tri.normal() else {
            return NO_HIT_DEGENERATE;
        };
        let Some(hit) = tri.cast_local_ray_and_get_normal(&ray, MAX_TIME_OF_IMPACT, false) else {
            // parry gives no parallel verdict for triangles (NO_TRIANGLE_PARALLEL).
            return IntersectAnswer::default();
        };
        let Some(mut answer) = translate_hit(&ray, &hit, face_normal) else {
            return NO_HIT_DEGENERATE;
        };
        let (_, location) = tri.project_local_point_and_get_location(ray.point_at(hit.time_of_impact), false);
        let Some(coords) = translate_location(&location) else {
            return NO_HIT_DEGENERATE;
        };
        answer.barycentric = Some(coords);
        IntersectAnswer { hit: Some(answer), parallel: false, degenerate: false }
    }

    fn barycentric_triangle(&self, p: P3, b: Triangle) -> BarycentricAnswer {
        const FALLBACK: BarycentricAnswer = BarycentricAnswer { coords: CENTROID_WEIGHTS, degenerate: true };
        let (Some(p), Some(tri)) = (vector(p), triangle(&b)) else {
            return FALLBACK;
        };
        let (_, location) = tri.project_local_point_and_get_location(p, false);
        match translate_location(&location) {
            Some(coords) => BarycentricAnswer { coords, degenerate: tri.normal().is_none() },
            None => FALLBACK,
        }
    }

    fn aabb_of_points(&self, ps: &[P3]) -> Option<Aabb> {
        let aabb = EngineAabb::from_points(points(ps)?);
        Some(Aabb { min: answer_point(aabb.mins)?, max: answer_point(aabb.maxs)? })
    }

    fn bounding_sphere_of_points(&self, ps: &[P3]) -> Option<Ball> {
        let sphere = point_cloud_bounding_sphere(&points(ps)?);
        Some(Ball { center: answer_point(sphere.center())?, radius: answer_scalar(sphere.radius())? })
    }

    fn overlap_aabb_aabb(&self, a: Aabb, b: Aabb) -> bool {
        engine_aabb(&a).intersects(&engine_aabb(&b))
    }

    fn mesh(&self, vertices: &[P3], triangles: &[[usize; 3]]) -> Option<PreparedMesh> {
        let vs: Vec<Vector> = vertices.iter().map(|&p| vector(p)).collect::<Option<_>>()?;
        let index = |i: usize| u32::try_from(i).ok().filter(|_| i < vs.len());
        let faces: Vec<[u32; 3]> =
            triangles.iter().map(|t| Some([index(t[0])?, index(t[1])?, index(t[2])?])).collect::<Option<_>>()?;
        if faces.is_empty() {
            return Some(PreparedMesh { trimesh: None, degenerate: false });
        }
        // Only an empty index buffer is refused by `TriMesh::new`.
        let trimesh = EngineTriMesh::new(vs, faces).ok()?;
        let degenerate = (0..trimesh.num_triangles() as u32).any(|i| trimesh.triangle(i).normal().is_none());
        Some(PreparedMesh { trimesh: Some(trimesh), degenerate })
    }

    fn intersect_segment_prepared_mesh(&self, s: Segment, mesh: &PreparedMesh) -> IntersectAnswer {
        let Some(ray) = ray(&s) else {
            return NO_HIT_DEGENERATE;
        };
        let miss = IntersectAnswer {
            hit: None,
            // parry gives no parallel verdict (MESH_NO_PARALLEL).
            parallel: false,
            degenerate: mesh.degenerate,
        };
        let Some(trimesh) = &mesh.trimesh else {
            return miss;
        };
        let Some(hit) = trimesh.cast_local_ray_and_get_normal(&ray, MAX_TIME_OF_IMPACT, false) else {
            return miss;
        };
        let face = hit.subshape;
        match triangle_hit(&ray, &hit, &trimesh.triangle(face)) {
            Some(mut h) => {
                h.triangle = Some(face as usize);
                IntersectAnswer { hit: Some(h), parallel: false, degenerate: mesh.degenerate }
            }
            None => NO_HIT_DEGENERATE,
        }
    }
}

#[cfg(test)]
mod tests {
    //! One body for both precisions: every test here runs once for parry3d-f64 and
    //! once for parry3d (f32). Cases use coordinates exact in `f32`, so the only
    //! differences between the two runs are parry's own roundings.

    use super::super::SMOKE_TOL;
    use super::*;
    use crate::parry::api::{
        BOX_RAY_FROM_INSIDE, BOX_TIE_NO_FLAG, CAPSULE_RAY_FROM_INSIDE, CENTRE_NEAR_TRIANGLE, CENTROID_SPHERE,
        CLAMPED_BARYCENTRICS, CONCENTRIC_SPHERES, DISTANCE_NO_FLAG, DIVERGENCES, Divergence, MESH_END_HIT,
        MESH_NO_PARALLEL, MESH_TIE_FACE, NO_TRIANGLE_PARALLEL, PLANE_PARALLEL_EPSILON, TOUCHING_SPHERES,
        known_divergences,
    };
    use proptest::prelude::*;

    fn engine() -> Engine {
        Engine::default()
    }

    fn sphere(center: P3, radius: f64) -> Sphere {
        Sphere { center, radius }
    }

    fn plane(normal: P3, offset: f64) -> Plane {
        Plane { normal, offset }
    }

    fn segment(start: P3, end: P3) -> Segment {
        Segment { start, end }
    }

    fn tri(v0: P3, v1: P3, v2: P3) -> Triangle {
        Triangle { vertices: [v0, v1, v2] }
    }

    /// The engine's machine epsilon (parry's `DEFAULT_EPSILON`) as an `f64`.
    fn eps() -> f64 {
        widen(DEFAULT_EPSILON)
    }

    fn close(got: f64, want: f64) -> bool {
        (got - want).abs() <= SMOKE_TOL
    }

    fn assert_close(what: &str, got: f64, want: f64) {
        assert!(close(got, want), "{}: {what} = {got}, want {want}", Engine::NAME);
    }

    fn assert_p3(what: &str, got: P3, want: P3) {
        assert!((0..3).all(|i| close(got[i], want[i])), "{}: {what} = {got:?}, want {want:?}", Engine::NAME);
    }

    fn assert_contact(answer: ContactAnswer, point: P3, normal: P3, depth: f64) {
        assert!(!answer.degenerate, "{}: not degenerate", Engine::NAME);
        let c = answer.contact.unwrap_or_else(|| panic!("{}: a contact is expected", Engine::NAME));
        assert_p3("point", c.point, point);
        assert_p3("normal", c.normal, normal);
        assert_close("depth", c.depth, depth);
    }

    fn assert_listed(d: &Divergence) {
        assert!(
            known_divergences().iter().any(|k| k.engine == Engine::NAME && k.query == d.query && k.what == d.what),
            "{}: `{}` is listed",
            Engine::NAME,
            d.what
        );
    }

    // --- translations --------------------------------------------------------

    #[test]
    fn parry_translate_contact_flips_normal1_and_takes_point2() {
        // parry: a on the left, b on the right, normal1 from a toward b (+x),
        // point2 on b, overlap 0.5 (dist −0.5).
        let raw = query::Contact::new(
            Vector::new(1.0, 0.0, 0.0),
            Vector::new(0.5, 0.0, 0.0),
            Vector::new(1.0, 0.0, 0.0),
            Vector::new(-1.0, 0.0, 0.0),
            -0.5,
        );
        let c = translate_contact(&raw).expect("finite contact");
        assert_p3("point", c.point, [0.5, 0.0, 0.0]);
        assert_p3("normal", c.normal, [-1.0, 0.0, 0.0]);
        assert_close("depth", c.depth, 0.5);
        let touching = query::Contact::new(Vector::ZERO, Vector::ZERO, Vector::X, -Vector::X, -0.0);
        let depth = translate_contact(&touching).expect("finite").depth;
        assert!(depth.is_sign_positive(), "an exact touch has depth +0, got {depth}");
    }

    #[test]
    fn parry_translations_refuse_non_finite_numbers() {
        let nan = Real::NAN;
        let raw = query::Contact::new(Vector::ZERO, Vector::ZERO, Vector::X, -Vector::X, nan);
        assert!(translate_contact(&raw).is_none(), "NaN depth caught");
        let raw = query::Contact::new(Vector::ZERO, Vector::new(nan, 0.0, 0.0), Vector::X, -Vector::X, 0.0);
        assert!(translate_contact(&raw).is_none(), "NaN point caught");
        let ray = Ray::new(Vector::ZERO, Vector::X);
        let hit = RayIntersection::new(nan, Vector::Z, Default::default());
        assert!(translate_hit(&ray, &hit, Vector::Z).is_none(), "NaN t caught");
        let hit = RayIntersection::new(0.5, Vector::new(0.0, 0.0, Real::INFINITY), Default::default());
        assert!(translate_hit(&ray, &hit, Vector::Z).is_none(), "infinite normal caught");
        let loc = TrianglePointLocation::OnFace(0, [nan, 0.5, 0.5]);
        assert!(translate_location(&loc).is_none(), "NaN coordinate caught");
    }

    #[test]
    fn parry_translate_hit_orients_normal_to_the_surface() {
        let ray = Ray::new(Vector::ZERO, Vector::new(0.0, 0.0, 2.0));
        let toward_origin = RayIntersection::new(0.25, -Vector::Z, Default::default());
        let h = translate_hit(&ray, &toward_origin, Vector::Z).expect("finite");
        assert_p3("normal", h.normal, [0.0, 0.0, 1.0]);
        assert_p3("point", h.point, [0.0, 0.0, 0.5]);
        assert_close("t", h.t, 0.25);
    }

    // --- contact ---------------------------------------------------------------

    #[test]
    fn parry_contact_sphere_sphere_smoke() {
        // M_a = 0, r_a = 1; M_b = (1.5, 0, 0), r_b = 1. n = (M_a − M_b)/‖·‖ = −x,
        // p = M_b + r_b n = (0.5, 0, 0), depth = 2 − 1.5 = 0.5.
        let answer = engine().contact_sphere_sphere(sphere([0.0; 3], 1.0), sphere([1.5, 0.0, 0.0], 1.0));
        assert_contact(answer, [0.5, 0.0, 0.0], [-1.0, 0.0, 0.0], 0.5);
        let apart = engine().contact_sphere_sphere(sphere([0.0; 3], 1.0), sphere([2.5, 0.0, 0.0], 1.0));
        assert_eq!(apart, ContactAnswer::default(), "apart: no contact");
    }

    #[test]
    fn parry_contact_sphere_plane_smoke() {
        // Plane 2z = 2, i.e. z = 1 with n̂ = +z, anchored at (0, 0, 1). Centre on the
        // anchor, r = 1: height 0, depth r = 1, point M − (r − x) n̂ = M, normal +z.
        // (The anchor is the one place parry's defect in this order, pinned below,
        // leaves the answer right.)
        let answer = engine().contact_sphere_plane(sphere([0.0, 0.0, 1.0], 1.0), plane([0.0, 0.0, 2.0], 2.0));
        assert_contact(answer, [0.0, 0.0, 1.0], [0.0, 0.0, 1.0], 1.0);
    }

    #[test]
    fn parry_contact_plane_sphere_smoke() {
        // Plane z = 1 as above; centre (1, 2, 1.5), r = 1, height 0.5 above: normal
        // from the sphere toward the plane, −z; point on the sphere, its deepest
        // point M − r n̂ = (1, 2, 0.5); depth 1 − 0.5 = 0.5.
        let p = plane([0.0, 0.0, 2.0], 2.0);
        let answer = engine().contact_plane_sphere(p, sphere([1.0, 2.0, 1.5], 1.0));
        assert_contact(answer, [1.0, 2.0, 0.5], [0.0, 0.0, -1.0], 0.5);
        // Touching (height exactly r) counts: depth 0 at (1, 2, 1).
        let touching = engine().contact_plane_sphere(p, sphere([1.0, 2.0, 2.0], 1.0));
        assert_contact(touching, [1.0, 2.0, 1.0], [0.0, 0.0, -1.0], 0.0);
        let apart = engine().contact_plane_sphere(p, sphere([1.0, 2.0, 2.5], 1.0));
        assert_eq!(apart, ContactAnswer::default(), "apart: no contact");
    }

    #[test]
    fn parry_defect_sphere_plane_mirrors_the_sphere_through_the_anchor() {
        // Plane z = 1 (anchor (0, 0, 1)), centre M = (1, 2, 1.5), r = 1. Right answer:
        // point (1, 2, 1), normal +z, depth 0.5. parry treats the ball as centred at
        // 2·(0, 0, 1) − M = (−1, −2, 0.5), half a unit *below* the plane: depth 1.5,
        // point (−1, −2, 1). A fixed parry fails this test; then the defect note
        // on `contact_sphere_plane` goes.
        let p = plane([0.0, 0.0, 2.0], 2.0);
        let answer = engine().contact_sphere_plane(sphere([1.0, 2.0, 1.5], 1.0), p);
        assert_contact(answer, [-1.0, -2.0, 1.0], [0.0, 0.0, 1.0], 1.5);
        // A ball sunk deep into the solid (M = (0, 0, −5)) is mirrored far above it:
        // no contact.
        let sunk = engine().contact_sphere_plane(sphere([0.0, 0.0, -5.0], 1.0), p);
        assert_eq!(sunk, ContactAnswer::default(), "parry misses the sunk ball");
    }

    #[test]
    fn parry_contact_sphere_triangle_smoke() {
        // Triangle in z = 0 with face normal +z. Centre (0.5, 0.5, 0.25), r = 1:
        // closest point q = (0.5, 0.5, 0), normal (M − q)/‖·‖ = +z, depth 0.75.
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let answer = engine().contact_sphere_triangle(sphere([0.5, 0.5, 0.25], 1.0), t);
        assert_contact(answer, [0.5, 0.5, 0.0], [0.0, 0.0, 1.0], 0.75);
        // Behind the face the normal points toward the centre: −z (two-sided).
        let behind = engine().contact_sphere_triangle(sphere([0.5, 0.5, -0.25], 1.0), t);
        assert_contact(behind, [0.5, 0.5, 0.0], [0.0, 0.0, -1.0], 0.75);
        // Beyond the edge x + y = 2: closest point (1, 1, 0), distance √2·0.5 ≈ 0.707
        // from (1.5, 1.5, 0), so r = 0.5 misses.
        let apart = engine().contact_sphere_triangle(sphere([1.5, 1.5, 0.0], 0.5), t);
        assert_eq!(apart, ContactAnswer::default(), "apart: no contact");
    }

    #[test]
    fn parry_contact_triangle_sphere_smoke() {
        // The same pair reversed: normal from the sphere toward the triangle, −z;
        // point on the sphere, M − r·(+z) = (0.5, 0.5, −0.75); depth 0.75.
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let answer = engine().contact_triangle_sphere(t, sphere([0.5, 0.5, 0.25], 1.0));
        assert_contact(answer, [0.5, 0.5, -0.75], [0.0, 0.0, -1.0], 0.75);
    }

    // --- intersect -------------------------------------------------------------

    #[test]
    fn parry_intersect_segment_plane_smoke() {
        // Plane 2z = 2 (z = 1). From (0, 0, 3) to (0, 0, −1): t = (3 − 1)/4 = 0.5,
        // point (0, 0, 1), normal +z.
        let p = plane([0.0, 0.0, 2.0], 2.0);
        let answer = engine().intersect_segment_plane(segment([0.0, 0.0, 3.0], [0.0, 0.0, -1.0]), p);
        let h = answer.hit.expect("a hit");
        assert!(!answer.parallel && !answer.degenerate, "plain hit");
        assert_close("t", h.t, 0.5);
        assert_p3("point", h.point, [0.0, 0.0, 1.0]);
        assert_p3("normal", h.normal, [0.0, 0.0, 1.0]);
        assert_eq!(h.barycentric, None, "no barycentrics for planes");
        // From below (inside the solid, where parry turns its normal to −z): the
        // plane's own normal +z all the same. (1, 1, 0) → (1, 1, 2): t = 0.5.
        let below = engine().intersect_segment_plane(segment([1.0, 1.0, 0.0], [1.0, 1.0, 2.0]), p);
        let h = below.hit.expect("a hit from below");
        assert_close("t", h.t, 0.5);
        assert_p3("point", h.point, [1.0, 1.0, 1.0]);
        assert_p3("normal", h.normal, [0.0, 0.0, 1.0]);
        // Parallel above the plane, and in it: no hit, parallel.
        for z in [0.0, 1.0] {
            let answer = engine().intersect_segment_plane(segment([0.0, 0.0, z], [1.0, 0.0, z]), p);
            assert_eq!(answer, IntersectAnswer { hit: None, parallel: true, degenerate: false }, "parallel at z = {z}");
        }
        // Short of the plane: no hit, not parallel.
        let short = engine().intersect_segment_plane(segment([0.0, 0.0, 3.0], [0.0, 0.0, 2.0]), p);
        assert_eq!(short, IntersectAnswer::default(), "short of the plane");
    }

    #[test]
    fn parry_intersect_segment_triangle_smoke() {
        // Triangle (0,0,0), (2,0,0), (0,2,0), face normal +z. From (0.5, 0.25, 1) to
        // (0.5, 0.25, −1): t = 0.5, point (0.5, 0.25, 0) = α v0 + β v1 + γ v2 with
        // β = x/2 = 0.25, γ = y/2 = 0.125, α = 1 − β − γ = 0.625.
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        for (start, end) in [([0.5, 0.25, 1.0], [0.5, 0.25, -1.0]), ([0.5, 0.25, -1.0], [0.5, 0.25, 1.0])] {
            // Both directions: the face normal is reported unflipped.
            let answer = engine().intersect_segment_triangle(segment(start, end), t);
            assert!(!answer.parallel && !answer.degenerate, "plain hit");
            let h = answer.hit.expect("a hit");
            assert_close("t", h.t, 0.5);
            assert_p3("point", h.point, [0.5, 0.25, 0.0]);
            assert_p3("normal", h.normal, [0.0, 0.0, 1.0]);
            assert_p3("barycentric", h.barycentric.expect("barycentrics"), [0.625, 0.25, 0.125]);
        }
        let beside = engine().intersect_segment_triangle(segment([3.0, 3.0, 1.0], [3.0, 3.0, -1.0]), t);
        assert_eq!(beside, IntersectAnswer::default(), "beside the triangle");
    }

    // --- barycentric, bounds, overlap -----------------------------------------

    #[test]
    fn parry_barycentric_triangle_smoke() {
        // (0.5, 0.25, 7) projects to (0.5, 0.25, 0): [0.625, 0.25, 0.125] as above;
        // the height above the plane does not matter.
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let answer = engine().barycentric_triangle([0.5, 0.25, 7.0], t);
        assert!(!answer.degenerate, "not degenerate");
        assert_p3("coords", answer.coords, [0.625, 0.25, 0.125]);
    }

    #[test]
    fn parry_aabb_of_points_smoke() {
        // Component-wise extremes of (1, −2, 3), (−1, 5, 0), (0, 0, −4).
        let pts = [[1.0, -2.0, 3.0], [-1.0, 5.0, 0.0], [0.0, 0.0, -4.0]];
        let b = engine().aabb_of_points(&pts).expect("a box");
        assert_p3("min", b.min, [-1.0, -2.0, -4.0]);
        assert_p3("max", b.max, [1.0, 5.0, 3.0]);
    }

    #[test]
    fn parry_bounding_sphere_of_points_smoke() {
        // (±1, 0, 0), (0, ±1, 0): centroid 0, farthest point at distance 1.
        let pts = [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]];
        let s = engine().bounding_sphere_of_points(&pts).expect("a sphere");
        assert_p3("center", s.center, [0.0; 3]);
        assert_close("radius", s.radius, 1.0);
        let both = engine().bounds_of_points(&pts);
        assert_eq!(both.sphere, Some(s), "bounds carries the sphere");
        assert!(both.aabb.is_some(), "bounds carries the box");
    }

    #[test]
    fn parry_overlap_aabb_aabb_smoke() {
        // [0,1]³ against boxes shifted along x: overlapping, touching (x = 1), apart.
        let unit = Aabb { min: [0.0; 3], max: [1.0; 3] };
        let shifted = |x: f64| Aabb { min: [x, 0.0, 0.0], max: [x + 1.0, 1.0, 1.0] };
        assert!(engine().overlap_aabb_aabb(unit, shifted(0.5)), "overlapping");
        assert!(engine().overlap_aabb_aabb(unit, shifted(1.0)), "touching faces overlap");
        assert!(!engine().overlap_aabb_aabb(unit, shifted(1.5)), "apart");
    }

    // --- degenerate input ------------------------------------------------------

    #[test]
    fn parry_concentric_spheres_are_flagged() {
        // Centres equal: parry's fallback normal1 = +x, so normal −x, point
        // M_b − r_b x̂ = (1 − 2, 2, 3), depth r_a + r_b = 3.
        let answer = engine().contact_sphere_sphere(sphere([1.0, 2.0, 3.0], 1.0), sphere([1.0, 2.0, 3.0], 2.0));
        assert!(answer.degenerate, "flagged");
        let c = answer.contact.expect("a contact");
        assert_p3("normal", c.normal, [-1.0, 0.0, 0.0]);
        assert_p3("point", c.point, [-1.0, 2.0, 3.0]);
        assert_close("depth", c.depth, 3.0);
    }

    #[test]
    fn parry_zero_plane_normal_is_degenerate() {
        let zero = plane([0.0; 3], 1.0);
        let s = sphere([0.0; 3], 1.0);
        assert_eq!(engine().contact_sphere_plane(s, zero), NO_CONTACT_DEGENERATE);
        assert_eq!(engine().contact_plane_sphere(zero, s), NO_CONTACT_DEGENERATE);
        let seg = segment([0.0, 0.0, -1.0], [0.0, 0.0, 1.0]);
        assert_eq!(engine().intersect_segment_plane(seg, zero), NO_HIT_DEGENERATE);
    }

    #[test]
    fn parry_zero_length_segment_is_degenerate() {
        let seg = segment([0.5, 0.25, 0.0], [0.5, 0.25, 0.0]);
        let p = plane([0.0, 0.0, 1.0], 0.0);
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        assert_eq!(engine().intersect_segment_plane(seg, p), NO_HIT_DEGENERATE);
        assert_eq!(engine().intersect_segment_triangle(seg, t), NO_HIT_DEGENERATE);
    }

    #[test]
    fn parry_zero_area_triangle_is_degenerate() {
        // Collinear vertices on the x axis.
        let t = tri([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        let seg = segment([0.5, 0.0, 1.0], [0.5, 0.0, -1.0]);
        assert_eq!(engine().intersect_segment_triangle(seg, t), NO_HIT_DEGENERATE);
        // Barycentric: parry projects onto the longest edge v0–v2: (0.5, 0, 0) is a
        // quarter of the way, so [0.75, 0, 0.25]; flagged.
        let b = engine().barycentric_triangle([0.5, 0.0, 0.0], t);
        assert!(b.degenerate, "flagged");
        assert_p3("coords", b.coords, [0.75, 0.0, 0.25]);
        // Contact: parry's answer against the segment the triangle collapses to,
        // flagged. Centre (0.5, 0, 0.5), r = 1: q = (0.5, 0, 0), depth 0.5, normal +z.
        let c = engine().contact_sphere_triangle(sphere([0.5, 0.0, 0.5], 1.0), t);
        assert!(c.degenerate, "flagged");
        let contact = c.contact.expect("a contact");
        assert_p3("point", contact.point, [0.5, 0.0, 0.0]);
        assert_p3("normal", contact.normal, [0.0, 0.0, 1.0]);
        assert_close("depth", contact.depth, 0.5);
    }

    #[test]
    fn parry_centre_on_triangle_is_flagged() {
        // Centre exactly on the face: parry's fallback, face normal +z, depth r.
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let answer = engine().contact_sphere_triangle(sphere([0.5, 0.5, 0.0], 1.0), t);
        assert!(answer.degenerate, "flagged");
        let c = answer.contact.expect("a contact");
        assert_p3("point", c.point, [0.5, 0.5, 0.0]);
        assert_p3("normal", c.normal, [0.0, 0.0, 1.0]);
        assert_close("depth", c.depth, 1.0);
        let reversed = engine().contact_triangle_sphere(t, sphere([0.5, 0.5, 0.0], 1.0));
        assert!(reversed.degenerate, "flagged in either order");
        assert_p3("normal", reversed.contact.expect("a contact").normal, [0.0, 0.0, -1.0]);
    }

    #[test]
    fn parry_bad_radius_and_empty_sets_are_refused() {
        let p = plane([0.0, 0.0, 1.0], 0.0);
        for r in [0.0, -1.0] {
            let s = sphere([0.0; 3], r);
            assert_eq!(engine().contact_sphere_plane(s, p), NO_CONTACT_DEGENERATE, "radius {r}");
            assert_eq!(engine().contact_sphere_sphere(s, s), NO_CONTACT_DEGENERATE, "radius {r}");
        }
        assert_eq!(engine().aabb_of_points(&[]), None, "empty set: no box");
        assert_eq!(engine().bounding_sphere_of_points(&[]), None, "empty set: no sphere");
    }

    #[test]
    fn parry_non_finite_input_is_degenerate() {
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY] {
            let s = sphere([bad, 0.0, 0.0], 1.0);
            assert_eq!(engine().contact_sphere_triangle(s, t), NO_CONTACT_DEGENERATE, "{bad}");
            let seg = segment([0.0, 0.0, bad], [0.0, 0.0, -1.0]);
            assert_eq!(engine().intersect_segment_triangle(seg, t), NO_HIT_DEGENERATE, "{bad}");
            let b = engine().barycentric_triangle([bad, 0.0, 0.0], t);
            assert!(b.degenerate && b.coords == CENTROID_WEIGHTS, "{bad}: centroid fallback");
            assert_eq!(engine().aabb_of_points(&[[0.0; 3], [bad; 3]]), None, "{bad}");
        }
    }

    // --- known divergences: each still happens --------------------------------

    #[test]
    fn parry_divergence_touching_spheres_give_no_contact() {
        assert_listed(&TOUCHING_SPHERES);
        // ‖M_a − M_b‖ = 2 = r_a + r_b exactly.
        let answer = engine().contact_sphere_sphere(sphere([0.0; 3], 1.0), sphere([2.0, 0.0, 0.0], 1.0));
        assert_eq!(answer, ContactAnswer::default(), "parry reports no contact at a touch");
    }

    #[test]
    fn parry_divergence_concentric_fallback_is_not_plus_z() {
        assert_listed(&CONCENTRIC_SPHERES);
        let answer = engine().contact_sphere_sphere(sphere([0.0; 3], 1.0), sphere([0.0; 3], 1.0));
        let n = answer.contact.expect("a contact").normal;
        assert!(!close(n[2], 1.0), "parry's fallback normal {n:?} is not +z");
        assert_p3("normal", n, [-1.0, 0.0, 0.0]);
    }

    #[test]
    fn parry_divergence_centre_near_triangle_takes_face_normal() {
        assert_listed(&CENTRE_NEAR_TRIANGLE);
        // Centre ε/2 *behind* the face (ε the scalar's machine epsilon): the exact
        // normal points from q = (0.25, 0.25, 0) toward the centre, −z, depth
        // 1 − ε/2. parry takes its fallback: the face normal +z, depth 1.
        let t = tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let answer = engine().contact_sphere_triangle(sphere([0.25, 0.25, -eps() / 2.0], 1.0), t);
        assert!(answer.degenerate, "flagged as parry's fallback");
        assert_p3("normal", answer.contact.expect("a contact").normal, [0.0, 0.0, 1.0]);
    }

    #[test]
    fn parry_divergence_triangle_gives_no_parallel_verdict() {
        assert_listed(&NO_TRIANGLE_PARALLEL);
        // In the triangle's plane, crossing it; and parallel one unit above.
        let t = tri([0.0; 3], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        for z in [0.0, 1.0] {
            let seg = segment([-1.0, 0.5, z], [3.0, 0.5, z]);
            let answer = engine().intersect_segment_triangle(seg, t);
            assert_eq!(answer, IntersectAnswer::default(), "z = {z}: a plain miss, parallel unset");
        }
    }

    #[test]
    fn parry_divergence_plane_parallel_within_machine_epsilon() {
        assert_listed(&PLANE_PARALLEL_EPSILON);
        // Plane z = 0; from (0, 0, 1) to (1, 0, 1 − ε/2): n̂ · (p1 − p0) = −ε/2 ≠ 0
        // (exactly: 1 − ε/2 is representable in both scalars), so not parallel —
        // parry calls it parallel. At −4ε it does not.
        let p = plane([0.0, 0.0, 1.0], 0.0);
        let tilted = |drop: f64| segment([0.0, 0.0, 1.0], [1.0, 0.0, 1.0 - drop]);
        assert_eq!(
            engine().intersect_segment_plane(tilted(eps() / 2.0), p),
            IntersectAnswer { hit: None, parallel: true, degenerate: false },
            "slope ε/2 called parallel"
        );
        assert_eq!(
            engine().intersect_segment_plane(tilted(4.0 * eps()), p),
            IntersectAnswer::default(),
            "slope 4ε not parallel"
        );
    }

    #[test]
    fn parry_divergence_barycentrics_are_clamped_outside() {
        assert_listed(&CLAMPED_BARYCENTRICS);
        // Triangle (0,0,0), (1,0,0), (0,1,0); p = (−1, 0.25, 0). Signed: β = x = −1,
        // γ = y = 0.25, α = 1.75. parry: p is in edge v0–v2's Voronoi region, its
        // closest point (0, 0.25, 0) = 0.75 v0 + 0.25 v2.
        let t = tri([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let answer = engine().barycentric_triangle([-1.0, 0.25, 0.0], t);
        assert!(!answer.degenerate, "not degenerate");
        assert_p3("parry's clamped coords", answer.coords, [0.75, 0.0, 0.25]);
        assert!(!close(answer.coords[1], -1.0), "not the signed β = −1");
    }

    #[test]
    fn parry_divergence_bounding_sphere_is_not_minimal() {
        assert_listed(&CENTROID_SPHERE);
        // (−1,0,0), (1,0,0) twice: the minimal sphere is the unit sphere at 0; parry
        // centres on the centroid (1/3, 0, 0), radius 4/3.
        let pts = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let s = engine().bounding_sphere_of_points(&pts).expect("a sphere");
        assert_p3("center", s.center, [1.0 / 3.0, 0.0, 0.0]);
        assert_close("radius", s.radius, 4.0 / 3.0);
        assert!(s.radius > 1.0 + SMOKE_TOL, "larger than the minimal radius 1");
    }

    // --- meshes ------------------------------------------------------------------

    /// The corner tetrahedron, faces oriented outward: 0 = z = 0 (normal −z),
    /// 1 = y = 0, 2 = x = 0, 3 = x + y + z = 1 (normal (1,1,1)/√3).
    const TETRA_V: [P3; 4] = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    const TETRA_F: [[usize; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

    /// An open unit square in z = 0 as two faces sharing the diagonal v0 v2.
    const QUAD_V: [P3; 4] = [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    const QUAD_F: [[usize; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

    #[test]
    fn parry_mesh_first_hit_with_face_index_and_own_normal() {
        let e = engine();
        let m = e.mesh(&TETRA_V, &TETRA_F).expect("prepared");
        assert_eq!(m.len(), 4);
        // Down x = y = 0.25 from z = 2 to z = −1: the slanted face at t = 1/2
        // first (z = 0.5), then the base.
        let a = e.intersect_segment_prepared_mesh(segment([0.25, 0.25, 2.0], [0.25, 0.25, -1.0]), &m);
        let h = a.hit.expect("hit");
        assert_eq!(h.triangle, Some(3), "{}: face index from subshape", Engine::NAME);
        assert_close("t", h.t, 0.5);
        assert_p3("point", h.point, [0.25, 0.25, 0.5]);
        let r3 = 1.0 / 3f64.sqrt();
        assert!((0..3).all(|i| (h.normal[i] - r3).abs() <= 4.0 * SMOKE_TOL), "normal {:?}", h.normal);
        assert_p3("barycentric", h.barycentric.expect("coords"), [0.25, 0.25, 0.5]);
        assert!(!a.parallel && !a.degenerate);
        // Upward: the base first, its own normal −z although the ray comes from
        // below (parry's normal faces the ray's origin).
        let h = e
            .intersect_segment_mesh(segment([0.25, 0.25, -1.0], [0.25, 0.25, 2.0]), &TETRA_V, &TETRA_F)
            .hit
            .expect("hit");
        assert_eq!(h.triangle, Some(0));
        assert_close("t", h.t, 1.0 / 3.0);
        assert_p3("normal", h.normal, [0.0, 0.0, -1.0]);
        // Through the box but outside the tetrahedron: a miss.
        let a = e.intersect_segment_prepared_mesh(segment([0.9, 0.9, -1.0], [0.9, 0.9, 2.0]), &m);
        assert_eq!(a, IntersectAnswer::default());
    }

    #[test]
    fn parry_mesh_degenerate_input_is_flagged() {
        let e = engine();
        // A zero-area face (collinear (0,0,0), (1,1,0), (2,2,0)) beside the quad.
        let mut verts = QUAD_V.to_vec();
        verts.push([2.0, 2.0, 0.0]);
        let faces = [[0, 2, 4], QUAD_F[0], QUAD_F[1]];
        let m = e.mesh(&verts, &faces).expect("prepared");
        assert!(m.has_degenerate_face());
        let a = e.intersect_segment_prepared_mesh(segment([0.75, 0.25, 1.0], [0.75, 0.25, -1.0]), &m);
        assert!(a.degenerate && a.hit.expect("hit").triangle == Some(1), "{a:?}");
        // Zero-length segment; an index out of range; a vertex beyond the scalar.
        let p = [0.5, 0.25, 0.0];
        assert_eq!(e.intersect_segment_prepared_mesh(segment(p, p), &m), NO_HIT_DEGENERATE);
        assert!(e.mesh(&QUAD_V, &[[0, 1, 4]]).is_none(), "index out of range");
        // 1e39 overflows f32 only.
        let far = [[1e39, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let s = segment([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
        let finite = narrow(1e39).is_finite();
        assert_eq!(
            e.intersect_segment_mesh(s, &far, &[[0, 1, 2]]).degenerate,
            !finite,
            "refused only where the scalar overflows"
        );
        // No faces: a plain miss.
        let empty = e.mesh(&QUAD_V, &[]).expect("prepared");
        assert!(empty.is_empty());
        assert_eq!(
            e.intersect_segment_prepared_mesh(segment([0.5, 0.5, 1.0], [0.5, 0.5, -1.0]), &empty),
            IntersectAnswer::default()
        );
    }

    #[test]
    fn parry_divergence_mesh_misses_a_hit_at_the_segment_end() {
        assert_listed(&MESH_END_HIT);
        // Ending exactly on the tetrahedron's base (t = 1): the face alone is
        // hit, the mesh is not.
        let e = engine();
        let s = segment([0.25, 0.25, -1.0], [0.25, 0.25, 0.0]);
        let alone = e.intersect_segment_triangle(s, tri(TETRA_V[0], TETRA_V[2], TETRA_V[1]));
        assert_close("t", alone.hit.expect("the face alone is hit").t, 1.0);
        let a = e.intersect_segment_mesh(s, &TETRA_V, &TETRA_F);
        assert!(a.hit.is_none(), "{}: t = 1 missed on the mesh: {a:?}", Engine::NAME);
        // A hair further and it is found.
        let s = segment([0.25, 0.25, -1.0], [0.25, 0.25, 0.5]);
        assert!(e.intersect_segment_mesh(s, &TETRA_V, &TETRA_F).hit.is_some());
    }

    /// A flat `n × n` grid of unit squares in z = 0, two faces each, listed in a
    /// scrambled (but fixed) order so that index order and spatial order differ.
    fn grid(n: usize) -> (Vec<P3>, Vec<[usize; 3]>) {
        let mut verts = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                verts.push([i as f64, j as f64, 0.0]);
            }
        }
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b) = (j * (n + 1) + i, j * (n + 1) + i + 1);
                let (c, d) = (a + n + 1, b + n + 1);
                faces.push([a, b, d]);
                faces.push([a, d, c]);
            }
        }
        // A fixed permutation: stride 7 through the faces (coprime with 2n²).
        let m = faces.len();
        let scrambled = (0..m).map(|k| faces[(k * 7) % m]).collect();
        (verts, scrambled)
    }

    #[test]
    fn parry_divergence_mesh_tie_is_not_the_lowest_index() {
        assert_listed(&MESH_TIE_FACE);
        // Straight down through every interior grid vertex: each is shared by
        // several faces, all hit at t = 1/2. The lowest index among them is
        // crashtest's answer (the referee's); parry answers another one for some
        // of these vertices.
        let e = engine();
        let (verts, faces) = grid(4);
        let m = e.mesh(&verts, &faces).expect("prepared");
        let mut differs = 0;
        for j in 1..4 {
            for i in 1..4 {
                let p = [i as f64, j as f64];
                let s = segment([p[0], p[1], 1.0], [p[0], p[1], -1.0]);
                let h = e.intersect_segment_prepared_mesh(s, &m).hit.expect("hit");
                assert_close("t", h.t, 0.5);
                let lowest = crate::referee::intersect_segment_mesh(&s, &verts, &faces)
                    .expect("referee")
                    .hit
                    .and_then(|h| h.triangle)
                    .expect("referee hit");
                if h.triangle != Some(lowest) {
                    differs += 1;
                }
            }
        }
        assert!(differs > 0, "{}: every vertex tie went to the lowest index", Engine::NAME);
    }

    #[test]
    fn parry_divergence_mesh_gives_no_parallel_verdict() {
        assert_listed(&MESH_NO_PARALLEL);
        // The flat quad and a segment in its plane, and one parallel above it.
        let e = engine();
        for z in [0.0, 1.0] {
            let a = e.intersect_segment_mesh(segment([-1.0, 0.5, z], [2.0, 0.5, z]), &QUAD_V, &QUAD_F);
            assert_eq!(a, IntersectAnswer::default(), "z = {z}: a plain miss, parallel unset");
        }
    }

    fn unit_box() -> OrientedBox {
        OrientedBox { center: [0.0; 3], half_extents: [1.0; 3], rotation: [1.0, 0.0, 0.0, 0.0] }
    }

    #[test]
    fn parry_divergence_box_ray_from_inside_has_a_zero_normal() {
        assert_listed(&BOX_RAY_FROM_INSIDE);
        // From the unit box's centre outward: the format's answer is t = 0 at
        // the start with a nearest face's normal (all six tie); parry's is t = 0
        // with the zero vector. From (0.5, 0, 0): +x is nearest, still zero.
        for start in [[0.0; 3], [0.5, 0.0, 0.0]] {
            let a = engine().intersect_segment_box(segment(start, [3.0, 0.2, 0.1]), unit_box());
            let h = a.hit.expect("a hit at the start");
            assert_close("t", h.t, 0.0);
            assert_p3("point", h.point, start);
            assert_p3("normal", h.normal, [0.0; 3]);
        }
    }

    #[test]
    fn parry_divergence_capsule_ray_from_inside_has_a_zero_normal() {
        assert_listed(&CAPSULE_RAY_FROM_INSIDE);
        // The rod from (−1,0,0) to (1,0,0) of radius 1, a start 0.5 off its
        // axis: the format's answer is t = 0 with the normal +y; parry's is
        // t = 0 with the zero vector.
        let rod = Capsule { start: [-1.0, 0.0, 0.0], end: [1.0, 0.0, 0.0], radius: 1.0 };
        let a = engine().intersect_segment_capsule(segment([0.5, 0.5, 0.0], [0.5, 5.0, 0.0]), rod);
        let h = a.hit.expect("a hit at the start");
        assert_close("t", h.t, 0.0);
        assert_p3("point", h.point, [0.5, 0.5, 0.0]);
        assert_p3("normal", h.normal, [0.0; 3]);
    }

    #[test]
    fn parry_divergence_box_tie_is_not_flagged() {
        assert_listed(&BOX_TIE_NO_FLAG);
        // A centre on the unit box's edge (1, 1, 0), radius 1/2: the faces +x
        // and +y tie; the format's answer is normal +x, point (1, 1, 0),
        // depth 1/2, degenerate. parry gives the same contact, unflagged; on
        // the corner (1, 1, 1) likewise.
        for center in [[1.0, 1.0, 0.0], [1.0, 1.0, 1.0]] {
            let a = engine().contact_sphere_box(sphere(center, 0.5), unit_box());
            assert_contact(a, center, [1.0, 0.0, 0.0], 0.5);
        }
    }

    #[test]
    fn parry_divergence_distance_witnesses_are_not_flagged() {
        assert_listed(&DISTANCE_NO_FLAG);
        // Boxes of half-size 1 whose faces x = 1.5 and x = 1 face each other:
        // 0.5 apart, every facing pair closest; parry answers one pair,
        // unflagged.
        let (a, b) = (
            OrientedBox { center: [2.5, 0.0, 0.0], half_extents: [1.0; 3], rotation: [1.0, 0.0, 0.0, 0.0] },
            unit_box(),
        );
        let d = engine().distance(Solid::Box(&a), Solid::Box(&b)).expect("an answer");
        assert!(!d.degenerate);
        assert_close("distance", d.distance, 0.5);
    }

    #[test]
    fn parry_every_divergence_is_pinned() {
        // The divergences the tests above pin; a new entry needs a pin here.
        let pinned = [
            TOUCHING_SPHERES,
            CONCENTRIC_SPHERES,
            CENTRE_NEAR_TRIANGLE,
            NO_TRIANGLE_PARALLEL,
            PLANE_PARALLEL_EPSILON,
            CLAMPED_BARYCENTRICS,
            CENTROID_SPHERE,
            MESH_END_HIT,
            MESH_TIE_FACE,
            MESH_NO_PARALLEL,
            BOX_RAY_FROM_INSIDE,
            BOX_TIE_NO_FLAG,
            CAPSULE_RAY_FROM_INSIDE,
            DISTANCE_NO_FLAG,
        ];
        for d in DIVERGENCES {
            assert!(pinned.iter().any(|p| p.what == d.what), "`{}` has a pin", d.what);
        }
        assert_eq!(pinned.len(), DIVERGENCES.len(), "no pin without an entry");
    }

    // --- never a panic, never a NaN ----------------------------------------------

    /// Coordinates across the whole range: small integers, zeros, and values from
    /// 1e-300 to 1e300 (beyond `f32`'s range, so the `f32` run meets its overflow).
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            (-3i32..=3).prop_map(f64::from),
            -2.0..2.0f64,
            (-1.0..1.0f64, -300i32..=300).prop_map(|(m, e)| m * 10f64.powi(e)),
        ]
    }

    fn point() -> impl Strategy<Value = P3> {
        [coordinate(), coordinate(), coordinate()]
    }

    fn finite(p: &P3) -> bool {
        p.iter().all(|x| x.is_finite())
    }

    fn check_contact(what: &str, answer: ContactAnswer) -> Result<(), TestCaseError> {
        if let Some(c) = answer.contact {
            prop_assert!(finite(&c.point) && finite(&c.normal), "{what}: finite {c:?}");
            prop_assert!(c.depth >= 0.0, "{what}: depth ≥ 0 in {c:?}");
        }
        Ok(())
    }

    fn check_intersect(what: &str, answer: IntersectAnswer) -> Result<(), TestCaseError> {
        if let Some(h) = answer.hit {
            prop_assert!(finite(&h.point) && finite(&h.normal), "{what}: finite {h:?}");
            prop_assert!((0.0..=1.0).contains(&h.t), "{what}: t in [0, 1] in {h:?}");
            prop_assert!(!answer.parallel, "{what}: a hit is not parallel");
            if let Some(b) = h.barycentric {
                prop_assert!(finite(&b), "{what}: finite barycentrics {b:?}");
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn parry_never_panics_nor_answers_nan(
            c in point(), r in coordinate(), n in point(), d in coordinate(),
            v0 in point(), v1 in point(), v2 in point(), p0 in point(), p1 in point(),
        ) {
            let e = engine();
            let s = sphere(c, r.abs());
            let s2 = sphere(p0, r.abs());
            let pl = plane(n, d);
            let t = tri(v0, v1, v2);
            let seg = segment(p0, p1);
            check_contact("sphere–sphere", e.contact_sphere_sphere(s, s2))?;
            check_contact("sphere–plane", e.contact_sphere_plane(s, pl))?;
            check_contact("plane–sphere", e.contact_plane_sphere(pl, s))?;
            check_contact("sphere–triangle", e.contact_sphere_triangle(s, t))?;
            check_contact("triangle–sphere", e.contact_triangle_sphere(t, s))?;
            check_intersect("segment–plane", e.intersect_segment_plane(seg, pl))?;
            check_intersect("segment–triangle", e.intersect_segment_triangle(seg, t))?;
            let b = e.barycentric_triangle(c, t);
            prop_assert!(finite(&b.coords), "finite barycentrics {b:?}");
            let pts = [c, n, v0, v1, v2];
            if let Some(aabb) = e.aabb_of_points(&pts) {
                prop_assert!(finite(&aabb.min) && finite(&aabb.max), "finite box {aabb:?}");
            }
            if let Some(ball) = e.bounding_sphere_of_points(&pts) {
                prop_assert!(finite(&ball.center) && ball.radius.is_finite(), "finite {ball:?}");
            }
            let _ = e.overlap_aabb_aabb(
                Aabb { min: v0, max: v1 },
                Aabb { min: v2, max: p0 },
            );
        }
    }
}
