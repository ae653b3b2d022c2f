//! The engine seam: every engine answers the same cases in the same neutral
//! values, or says `Unsupported`.
//!
//! An engine implements [`Queries`], one method per shape pair of the fixture
//! format, each defaulting to `Unsupported`; [`Engine::run`] turns a case into the
//! right call in one place for all engines. Adapters live in `engines/`, one per
//! engine, and translate conventions there and nowhere else.

use crate::case::{Query, Shape};
use crate::load::LoadedCase;
use crate::mesh::Mesh;
use oracle::geom::{
    Aabb, BarycentricAnswer, BoundsAnswer, ContactAnswer, IntersectAnswer, P3, Plane, ResponseAnswer, Segment, Sphere,
    ToiAnswer, Triangle,
};
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
    /// `barycentric`, point and triangle.
    fn barycentric_triangle(&self, p: &P3, t: &Triangle) -> Reply<BarycentricAnswer> {
        unsupported("barycentric coordinates")
    }
    /// `bounds` of a point cloud (a mesh's vertices for a mesh).
    fn bounds(&self, points: &[P3]) -> Reply<BoundsAnswer> {
        unsupported("bounding volumes")
    }
    /// `overlap`, two boxes.
    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        unsupported("AABB overlap")
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
}

/// The format's reverse-order contact: `contact(b, a)` from `contact(a, b)`.
pub fn swap(k: ContactAnswer) -> ContactAnswer {
    ContactAnswer {
        contact: k.contact.map(|c| oracle::geom::Contact {
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

/// A named engine.
pub struct Engine {
    /// `collide/robust`, `collide-f32/lecture`, `parry3d-f64`, `referee`, …
    pub name: String,
    /// Floating-point precision of its arithmetic, in bits of mantissa (53, 24),
    /// or `None` for the referee.
    pub precision: Option<u32>,
    queries: Box<dyn Queries>,
}

impl Engine {
    /// An engine from its name, precision and queries.
    pub fn new(name: impl Into<String>, precision: Option<u32>, queries: impl Queries + 'static) -> Self {
        Self { name: name.into(), precision, queries: Box::new(queries) }
    }

    /// Answers one case.
    pub fn run(&self, lc: &LoadedCase) -> Reply<Answer> {
        let q = self.queries.as_ref();
        let case = &lc.case;
        let b = case.b.as_ref();
        use Shape as S;
        match (case.query, &case.a, b) {
            (Query::Contact, S::Sphere(a), Some(S::Sphere(b))) => {
                q.contact_sphere_sphere(&a.to_geom(), &b.to_geom()).map(Answer::Contact)
            }
            (Query::Contact, S::Sphere(a), Some(S::Plane(b))) => {
                q.contact_sphere_plane(&a.to_geom(), &b.to_geom()).map(Answer::Contact)
            }
            (Query::Contact, S::Plane(a), Some(S::Sphere(b))) => {
                q.contact_plane_sphere(&a.to_geom(), &b.to_geom()).map(Answer::Contact)
            }
            (Query::Contact, S::Sphere(a), Some(S::Triangle(b))) => {
                q.contact_sphere_triangle(&a.to_geom(), &b.to_geom()).map(Answer::Contact)
            }
            (Query::Contact, S::Triangle(a), Some(S::Sphere(b))) => {
                q.contact_triangle_sphere(&a.to_geom(), &b.to_geom()).map(Answer::Contact)
            }
            (Query::Intersect, S::Segment(s), Some(S::Plane(p))) => {
                q.intersect_segment_plane(&s.to_geom(), &p.to_geom()).map(Answer::Intersect)
            }
            (Query::Intersect, S::Segment(s), Some(S::Triangle(t))) => {
                q.intersect_segment_triangle(&s.to_geom(), &t.to_geom()).map(Answer::Intersect)
            }
            (Query::Intersect, S::Segment(s), Some(S::Mesh(_))) => match &lc.meshes[1] {
                Some(m) => q.intersect_segment_mesh(&s.to_geom(), m).map(Answer::Intersect),
                None => Err(Unsupported("mesh not loaded".into())),
            },
            (Query::Barycentric, S::Point(p), Some(S::Triangle(t))) => {
                q.barycentric_triangle(&p.at, &t.to_geom()).map(Answer::Barycentric)
            }
            (Query::Bounds, S::Points(p), None) => q.bounds(&p.points).map(Answer::Bounds),
            (Query::Bounds, S::Mesh(_), None) => match &lc.meshes[0] {
                Some(m) => q.bounds(&m.vertices).map(Answer::Bounds),
                None => Err(Unsupported("mesh not loaded".into())),
            },
            (Query::Overlap, S::Aabb(a), Some(S::Aabb(b))) => {
                q.overlap(&a.to_geom(), &b.to_geom()).map(Answer::Overlap)
            }
            (Query::Toi, S::Sphere(a), Some(bs)) => {
                let (va, vb, t_max) = (case.a.velocity(), bs.velocity(), case.t_max());
                let a = a.to_geom();
                match bs {
                    S::Sphere(b) => q.toi_sphere_sphere(&a, &va, &b.to_geom(), &vb, t_max),
                    S::Plane(b) => q.toi_sphere_plane(&a, &va, &b.to_geom(), &vb, t_max),
                    S::Triangle(b) => q.toi_sphere_triangle(&a, &va, &b.to_geom(), &vb, t_max),
                    S::Mesh(_) => match &lc.meshes[1] {
                        Some(m) => q.toi_sphere_mesh(&a, &va, m, &vb, t_max),
                        None => Err(Unsupported("mesh not loaded".into())),
                    },
                    other => Err(Unsupported(format!("toi against {}", other.kind()))),
                }
                .map(Answer::Toi)
            }
            // Masses and restitution are required of response cases when they are
            // loaded; the defaults below only keep this function total.
            (Query::Response, S::Sphere(a), Some(S::Sphere(b))) => q
                .response_sphere_sphere(
                    &a.to_geom(),
                    &case.a.velocity(),
                    a.mass.unwrap_or(1.0),
                    &b.to_geom(),
                    &case.b.as_ref().map(Shape::velocity).unwrap_or_default(),
                    b.mass.unwrap_or(1.0),
                    case.restitution.unwrap_or(1.0),
                )
                .map(Answer::Response),
            (Query::Response, S::Sphere(a), Some(S::Plane(b))) => q
                .response_sphere_plane(&a.to_geom(), &case.a.velocity(), &b.to_geom(), case.restitution.unwrap_or(1.0))
                .map(Answer::Response),
            (query, a, b) => Err(Unsupported(format!(
                "{query} of {}{} is not implemented by the harness yet",
                a.kind(),
                b.map(|b| format!(" and {}", b.kind())).unwrap_or_default()
            ))),
        }
    }
}

impl fmt::Debug for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Engine").field("name", &self.name).finish()
    }
}
