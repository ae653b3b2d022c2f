//! The engine trait: every engine answers the same cases in the same neutral
//! values ([`crate::geom`]), or says [`Unsupported`].
//!
//! An engine implements [`Queries`], one method per entry of the pair table
//! ([`crate::pair::PAIRS`]), each defaulting to `Unsupported`. The harness turns a
//! case into the right call in one place for all engines; an engine translates
//! its own conventions inside its methods and nowhere else.

use crate::geom::{
    Aabb, BarycentricAnswer, BoundsAnswer, Capsule, CcdAnswer, ContactAnswer, DistanceAnswer, IntersectAnswer,
    MovingPoint, MovingSegment, MovingTriangle, OrientedBox, P3, Plane, ResponseAnswer, Segment, Solid, Sphere,
    ToiAnswer, Triangle,
};
use crate::mesh::Mesh;
use std::fmt;

/// An engine's answer to one case.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer {
    /// `contact`.
    Contact(ContactAnswer),
    /// `intersect`.
    Intersect(IntersectAnswer),
    /// `barycentric`.
    Barycentric(BarycentricAnswer),
    /// `bounds`.
    Bounds(BoundsAnswer),
    /// `overlap`.
    Overlap(bool),
    /// `toi`.
    Toi(ToiAnswer),
    /// `response`.
    Response(ResponseAnswer),
    /// `ccd`.
    Ccd(CcdAnswer),
    /// `distance`.
    Distance(DistanceAnswer),
}

/// The engine does not answer this kind of case, with the reason.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub String);

impl fmt::Display for Unsupported {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// What a query method returns.
pub type Reply<T> = Result<T, Unsupported>;

fn unsupported<T>(what: &str) -> Reply<T> {
    Err(Unsupported(format!("{what} is not implemented by this engine")))
}

/// One method per shape pair of the fixture format. Each defaults to
/// `Unsupported`, except the reverse orders of contact, which default to the
/// format's own swap (normal negated, point moved to the deepest point of the
/// other shape); an engine whose reverse order is a separate code path overrides
/// them.
#[allow(unused_variables)]
pub trait Queries: Send + Sync {
    /// `contact`, sphere `a`, sphere `b`.
    fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
        unsupported("sphere–sphere contact")
    }
    /// `contact`, sphere `a`, plane `b`.
    fn contact_sphere_plane(&self, a: &Sphere, b: &Plane) -> Reply<ContactAnswer> {
        unsupported("sphere–plane contact")
    }
    /// `contact`, plane `a`, sphere `b`.
    fn contact_plane_sphere(&self, a: &Plane, b: &Sphere) -> Reply<ContactAnswer> {
        self.contact_sphere_plane(b, a).map(swap)
    }
    /// `contact`, sphere `a`, triangle `b`.
    fn contact_sphere_triangle(&self, a: &Sphere, b: &Triangle) -> Reply<ContactAnswer> {
        unsupported("sphere–triangle contact")
    }
    /// `contact`, triangle `a`, sphere `b`.
    fn contact_triangle_sphere(&self, a: &Triangle, b: &Sphere) -> Reply<ContactAnswer> {
        self.contact_sphere_triangle(b, a).map(swap)
    }
    /// `contact`, sphere `a`, mesh `b`: the contact with the nearest face.
    fn contact_sphere_mesh(&self, a: &Sphere, b: &Mesh) -> Reply<ContactAnswer> {
        unsupported("sphere–mesh contact")
    }
    /// `contact`, sphere `a`, box `b`.
    fn contact_sphere_box(&self, a: &Sphere, b: &OrientedBox) -> Reply<ContactAnswer> {
        unsupported("sphere–box contact")
    }
    /// `contact`, box `a`, plane `b` (the solid half-space).
    fn contact_box_plane(&self, a: &OrientedBox, b: &Plane) -> Reply<ContactAnswer> {
        unsupported("box–plane contact")
    }
    /// `contact`, sphere `a`, capsule `b`.
    fn contact_sphere_capsule(&self, a: &Sphere, b: &Capsule) -> Reply<ContactAnswer> {
        unsupported("sphere–capsule contact")
    }
    /// `contact`, capsule `a`, capsule `b`.
    fn contact_capsule_capsule(&self, a: &Capsule, b: &Capsule) -> Reply<ContactAnswer> {
        unsupported("capsule–capsule contact")
    }
    /// `contact`, capsule `a`, plane `b` (the solid half-space).
    fn contact_capsule_plane(&self, a: &Capsule, b: &Plane) -> Reply<ContactAnswer> {
        unsupported("capsule–plane contact")
    }
    /// `contact`, box `a`, box `b`.
    fn contact_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<ContactAnswer> {
        unsupported("box–box contact")
    }
    /// `contact`, box `a`, triangle `b` (two-sided).
    fn contact_box_triangle(&self, a: &OrientedBox, b: &Triangle) -> Reply<ContactAnswer> {
        unsupported("box–triangle contact")
    }
    /// `contact`, capsule `a`, box `b`.
    fn contact_capsule_box(&self, a: &Capsule, b: &OrientedBox) -> Reply<ContactAnswer> {
        unsupported("capsule–box contact")
    }
    /// `contact`, capsule `a`, triangle `b` (two-sided).
    fn contact_capsule_triangle(&self, a: &Capsule, b: &Triangle) -> Reply<ContactAnswer> {
        unsupported("capsule–triangle contact")
    }
    /// `intersect`, segment and plane.
    fn intersect_segment_plane(&self, s: &Segment, p: &Plane) -> Reply<IntersectAnswer> {
        unsupported("segment–plane intersection")
    }
    /// `intersect`, segment and triangle.
    fn intersect_segment_triangle(&self, s: &Segment, t: &Triangle) -> Reply<IntersectAnswer> {
        unsupported("segment–triangle intersection")
    }
    /// `intersect`, segment and mesh.
    fn intersect_segment_mesh(&self, s: &Segment, m: &Mesh) -> Reply<IntersectAnswer> {
        unsupported("segment–mesh intersection")
    }
    /// `intersect`, segment and solid box: the first point of the segment in the box.
    fn intersect_segment_box(&self, s: &Segment, b: &OrientedBox) -> Reply<IntersectAnswer> {
        unsupported("segment–box intersection")
    }
    /// `intersect`, segment and solid capsule: the first hit.
    fn intersect_segment_capsule(&self, s: &Segment, b: &Capsule) -> Reply<IntersectAnswer> {
        unsupported("segment–capsule intersection")
    }
    /// `barycentric`, point and triangle.
    fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
        unsupported("barycentric coordinates")
    }
    /// `bounds` of a point cloud (a mesh's vertices for a mesh).
    fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
        unsupported("bounding volumes")
    }
    /// `bounds` of a box: its AABB and bounding sphere.
    fn bounds_box(&self, b: &OrientedBox) -> Reply<BoundsAnswer> {
        unsupported("bounding volumes of a box")
    }
    /// `overlap`, two boxes.
    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        unsupported("AABB overlap")
    }
    /// `overlap`, two boxes that may be rotated (touching overlaps).
    fn overlap_box_box(&self, a: &OrientedBox, b: &OrientedBox) -> Reply<bool> {
        unsupported("box–box overlap")
    }
    /// `overlap`, a box that may be rotated and an axis-aligned box.
    fn overlap_box_aabb(&self, a: &OrientedBox, b: &Aabb) -> Reply<bool> {
        unsupported("box–AABB overlap")
    }
    /// `toi`, sphere `a` moving at `va` against sphere `b` moving at `vb`.
    fn toi_sphere_sphere(&self, a: &Sphere, va: &P3, b: &Sphere, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        unsupported("sphere–sphere time of impact")
    }
    /// `toi`, sphere against plane.
    fn toi_sphere_plane(&self, a: &Sphere, va: &P3, b: &Plane, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        unsupported("sphere–plane time of impact")
    }
    /// `toi`, sphere against triangle.
    fn toi_sphere_triangle(&self, a: &Sphere, va: &P3, b: &Triangle, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        unsupported("sphere–triangle time of impact")
    }
    /// `toi`, sphere against mesh.
    fn toi_sphere_mesh(&self, a: &Sphere, va: &P3, b: &Mesh, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        unsupported("sphere–mesh time of impact")
    }
    /// `toi`, sphere against a box that may be rotated (its rotation fixed,
    /// moving at `vb`).
    fn toi_sphere_box(&self, a: &Sphere, va: &P3, b: &OrientedBox, vb: &P3, t_max: f64) -> Reply<ToiAnswer> {
        unsupported("sphere–box time of impact")
    }
    /// `response`, two spheres with velocities and masses, restitution `e`.
    #[allow(clippy::too_many_arguments)]
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
        unsupported("sphere–sphere response")
    }
    /// `response`, a sphere with velocity against a static plane, restitution `e`.
    fn response_sphere_plane(&self, a: &Sphere, va: &P3, b: &Plane, e: f64) -> Reply<ResponseAnswer> {
        unsupported("sphere–plane response")
    }
    /// `ccd`, a moving point against a moving triangle (vertex–face), over
    /// `[0, t_max]`.
    fn ccd_point_triangle(&self, p: &MovingPoint, t: &MovingTriangle, t_max: f64) -> Reply<CcdAnswer> {
        unsupported("vertex–face continuous collision")
    }
    /// `ccd`, a moving segment against a moving segment (edge–edge), over
    /// `[0, t_max]`.
    fn ccd_segment_segment(&self, a: &MovingSegment, b: &MovingSegment, t_max: f64) -> Reply<CcdAnswer> {
        unsupported("edge–edge continuous collision")
    }
    /// `distance`, solid `a` and solid `b`: every distance pair of the table
    /// comes here, its shapes' kinds in `a` and `b` (an engine that answers
    /// only some kinds says `Unsupported` for the others).
    fn distance(&self, a: Solid<'_>, b: Solid<'_>) -> Reply<DistanceAnswer> {
        Err(Unsupported(format!("{}–{} distance is not implemented by this engine", a.kind(), b.kind())))
    }
}

/// The format's reverse-order contact: `contact(b, a)` from `contact(a, b)`.
pub fn swap(k: ContactAnswer) -> ContactAnswer {
    ContactAnswer {
        contact: k.contact.map(|c| crate::geom::Contact {
            point: [
                c.point[0] - c.normal[0] * c.depth,
                c.point[1] - c.normal[1] * c.depth,
                c.point[2] - c.normal[2] * c.depth,
            ],
            normal: [-c.normal[0], -c.normal[1], -c.normal[2]],
            depth: c.depth,
        }),
        degenerate: k.degenerate,
    }
}
