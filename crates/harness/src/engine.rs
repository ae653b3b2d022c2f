//! The engine seam: every engine answers the same cases in the same neutral
//! values, or says `Unsupported`.
//!
//! An engine implements [`Queries`], one method per shape pair of the fixture
//! format, each defaulting to `Unsupported`; [`Engine::run`] turns a case into the
//! right call in one place for all engines. Adapters live in `engines/`, one per
//! engine, and translate conventions there and nowhere else.

use crate::case::{Pair, Shape};
use crate::divergence::Known;
use crate::load::LoadedCase;
use crate::mesh::Mesh;
use crate::protocol::client::{Outcome, ProcessEngine};
use oracle::geom::{
    Aabb, Capsule, Convex, MovingPoint, MovingSegment, MovingTriangle, OrientedBox, P3, Plane, Segment, Solid, Sphere,
    Triangle,
};
use std::fmt;
use std::sync::Arc;

pub use crashtest_core::engine::{Answer, Queries, Reply, Unsupported, swap};

/// A named engine (cloning shares its queries).
#[derive(Clone)]
pub struct Engine {
    /// `collide/robust`, `collide-f32/lecture`, `parry3d-f64`, `referee`, …
    pub name: String,
    /// Floating-point precision of its arithmetic, in bits of mantissa (53, 24),
    /// or `None` for the referee.
    pub precision: Option<u32>,
    /// The known divergences this engine carries ([`crate::divergence`]).
    pub known: Known,
    /// What the report's provenance says it is (`collide 0.1.0`, `parry3d-f64
    /// 0.31.1`); `None` for an engine that does not say.
    pub version: Option<String>,
    /// The engine whose source code this one is another build of (the same
    /// code in another precision: `collide-f32/robust` of `collide/robust`,
    /// `parry3d` of `parry3d-f64`): their findings of one cause are one root
    /// cause ([`crate::findings`]). `None` for an engine of its own code.
    pub build_of: Option<String>,
    queries: Arc<dyn Queries>,
    /// A process engine answers through the protocol instead of `queries`.
    process: Option<Arc<ProcessEngine>>,
}

/// The queries of a process engine's [`Engine`]: it answers through the
/// protocol, never through these.
struct ThroughTheProtocol;
impl Queries for ThroughTheProtocol {}

impl Engine {
    /// An engine from its name, precision (bits of mantissa: 53 for f64, 24
    /// for f32; `None` for exact arithmetic) and queries.
    ///
    /// ```
    /// use harness::engine::{Engine, Queries, Reply};
    /// use crashtest_core::geom::Aabb;
    /// struct Boxes;
    /// impl Queries for Boxes {
    ///     fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
    ///         Ok((0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]))
    ///     }
    /// }
    /// let e = Engine::new("boxes", Some(53), Boxes).with_version("boxes 1.0");
    /// assert_eq!((e.name.as_str(), e.version.as_deref()), ("boxes", Some("boxes 1.0")));
    /// ```
    pub fn new(name: impl Into<String>, precision: Option<u32>, queries: impl Queries + 'static) -> Self {
        Self {
            name: name.into(),
            precision,
            known: Known::NONE,
            version: None,
            build_of: None,
            queries: Arc::new(queries),
            process: None,
        }
    }

    /// A process engine ([`crate::protocol`]) under its spec's name, with the
    /// precision and version its hello gave (an engine that never shook hands
    /// is judged as f64, and fails every case with the reason).
    pub fn from_process(engine: ProcessEngine) -> Self {
        let hello = engine.hello();
        let precision = hello.as_ref().map_or(53, |h| h.precision);
        let version = hello.as_ref().map(|h| match &h.version {
            Some(v) => format!("{} {v} (process: {})", h.name, engine.spec().command_line()),
            None => format!("{} (process: {})", h.name, engine.spec().command_line()),
        });
        Self {
            name: engine.spec().name.clone(),
            precision: Some(precision),
            known: Known::NONE,
            version: version.or_else(|| Some(format!("down (process: {})", engine.spec().command_line()))),
            build_of: None,
            queries: Arc::new(ThroughTheProtocol),
            process: Some(Arc::new(engine)),
        }
    }

    /// The precision this engine answers `lc` in: its own, or, for a process
    /// engine, the one its hello gives for the case's pair when it gives one.
    pub fn precision_for(&self, lc: &LoadedCase) -> Option<u32> {
        let pair = lc.case.pair();
        self.process.as_ref().zip(pair).and_then(|(p, pair)| p.precision_for(pair)).or(self.precision)
    }

    /// The process behind a process engine.
    pub fn process(&self) -> Option<&ProcessEngine> {
        self.process.as_deref()
    }

    /// A process engine's new process (see
    /// [`crate::protocol::ProcessEngine::fresh_process`]); nothing for an
    /// in-process engine.
    pub fn fresh_process(&self) -> Result<(), String> {
        self.process.as_ref().map_or(Ok(()), |p| p.fresh_process())
    }

    /// Lets a process engine forget its answer to `lc` (nothing for an
    /// in-process engine, which answers anew each time).
    pub fn forget_case(&self, lc: &LoadedCase) {
        if let Some(p) = &self.process {
            p.forget_case(lc);
        }
    }

    /// Marks `cases` as answers a process engine keeps when it forgets the
    /// others (nothing for an in-process engine).
    pub fn keep<'a>(&self, cases: impl IntoIterator<Item = &'a LoadedCase>) {
        if let Some(p) = &self.process {
            p.keep(cases);
        }
    }

    /// Lets a process engine forget its answers but the kept ones (nothing for
    /// an in-process engine).
    pub fn forget(&self) {
        if let Some(p) = &self.process {
            p.forget();
        }
    }

    /// Lets a process engine answer `cases` in batches before they are judged
    /// one by one (nothing for an in-process engine).
    pub fn prefetch<'a>(&self, cases: impl IntoIterator<Item = &'a LoadedCase>) {
        if let Some(p) = &self.process {
            p.prefetch(cases);
        }
    }

    /// The same engine with its version, as the report's provenance shows it.
    pub fn with_version(self, version: impl Into<String>) -> Self {
        Self { version: Some(version.into()), ..self }
    }

    /// The same engine, declared another build of `engine`'s source code.
    pub fn build_of(self, engine: impl Into<String>) -> Self {
        Self { build_of: Some(engine.into()), ..self }
    }

    /// The name of the source code it is a build of: [`Engine::build_of`],
    /// or its own name.
    pub fn source(&self) -> &str {
        self.build_of.as_deref().unwrap_or(&self.name)
    }

    /// The same engine carrying these known divergences.
    pub fn with_known(self, known: Known) -> Self {
        Self { known, ..self }
    }

    /// Answers one case: its row of the pair table ([`crashtest_core::pair`])
    /// decides the call.
    pub fn run(&self, lc: &LoadedCase) -> Reply<Answer> {
        if let Some(p) = &self.process {
            return match p.answer(lc).outcome {
                Outcome::Answer(a) => Ok(a),
                Outcome::Unsupported(why) | Outcome::Failed(why) => Err(Unsupported(why)),
            };
        }
        let case = &lc.case;
        match case.pair() {
            Some(pair) => dispatch(self.queries.as_ref(), pair, lc),
            None => Err(Unsupported(format!(
                "{} of {}{} is not in the pair table",
                case.query,
                case.a.kind(),
                case.b.as_ref().map(|b| format!(" and {}", b.kind())).unwrap_or_default()
            ))),
        }
    }
}

/// The call for each pair. Loading checked the shapes against the table, so the
/// kind errors below happen only for a case built by hand and never loaded.
fn dispatch(q: &dyn Queries, pair: Pair, lc: &LoadedCase) -> Reply<Answer> {
    let case = &lc.case;
    let (a, b) = (Some(&case.a), case.b.as_ref());
    let (va, vb) = (case.a.velocity(), b.map(Shape::velocity).unwrap_or_default());
    let t_max = case.t_max();
    // Masses and restitution are required of response cases when they are
    // loaded; the defaults below only keep this function total.
    let e = case.restitution.unwrap_or(1.0);
    let mass = |s: Option<&Shape>| match s {
        Some(Shape::Sphere(s)) => s.mass.unwrap_or(1.0),
        _ => 1.0,
    };
    use Pair as P;
    Ok(match pair {
        P::ContactSphereSphere => Answer::Contact(q.contact_sphere_sphere(&sphere(a)?, &sphere(b)?)?),
        P::ContactSpherePlane => Answer::Contact(q.contact_sphere_plane(&sphere(a)?, &plane(b)?)?),
        P::ContactPlaneSphere => Answer::Contact(q.contact_plane_sphere(&plane(a)?, &sphere(b)?)?),
        P::ContactSphereTriangle => Answer::Contact(q.contact_sphere_triangle(&sphere(a)?, &triangle(b)?)?),
        P::ContactSphereMesh => Answer::Contact(q.contact_sphere_mesh(&sphere(a)?, mesh(lc, 1)?)?),
        P::ContactTriangleSphere => Answer::Contact(q.contact_triangle_sphere(&triangle(a)?, &sphere(b)?)?),
        P::ContactSphereBox => Answer::Contact(q.contact_sphere_box(&sphere(a)?, &oriented_box(b)?)?),
        P::ContactBoxPlane => Answer::Contact(q.contact_box_plane(&oriented_box(a)?, &plane(b)?)?),
        P::ContactSphereCapsule => Answer::Contact(q.contact_sphere_capsule(&sphere(a)?, &capsule(b)?)?),
        P::ContactCapsuleCapsule => Answer::Contact(q.contact_capsule_capsule(&capsule(a)?, &capsule(b)?)?),
        P::ContactCapsulePlane => Answer::Contact(q.contact_capsule_plane(&capsule(a)?, &plane(b)?)?),
        P::ContactBoxBox => Answer::Contact(q.contact_box_box(&oriented_box(a)?, &oriented_box(b)?)?),
        P::ContactBoxTriangle => Answer::Contact(q.contact_box_triangle(&oriented_box(a)?, &triangle(b)?)?),
        P::ContactCapsuleBox => Answer::Contact(q.contact_capsule_box(&capsule(a)?, &oriented_box(b)?)?),
        P::ContactCapsuleTriangle => Answer::Contact(q.contact_capsule_triangle(&capsule(a)?, &triangle(b)?)?),
        P::IntersectSegmentPlane => Answer::Intersect(q.intersect_segment_plane(&segment(a)?, &plane(b)?)?),
        P::IntersectSegmentTriangle => Answer::Intersect(q.intersect_segment_triangle(&segment(a)?, &triangle(b)?)?),
        P::IntersectSegmentMesh => Answer::Intersect(q.intersect_segment_mesh(&segment(a)?, mesh(lc, 1)?)?),
        P::IntersectSegmentBox => Answer::Intersect(q.intersect_segment_box(&segment(a)?, &oriented_box(b)?)?),
        P::IntersectSegmentCapsule => Answer::Intersect(q.intersect_segment_capsule(&segment(a)?, &capsule(b)?)?),
        P::BarycentricPointTriangle => Answer::Barycentric(q.barycentric_triangle(&point(a)?, &triangle(b)?)?),
        P::BoundsPoints => match &case.a {
            Shape::Points(p) => Answer::Bounds(q.bounds(&p.points)?),
            other => return Err(kind_error("points", other.kind())),
        },
        P::BoundsMesh => Answer::Bounds(q.bounds(&mesh(lc, 0)?.vertices)?),
        P::BoundsBox => Answer::Bounds(q.bounds_box(&oriented_box(a)?)?),
        P::OverlapAabbAabb => Answer::Overlap(q.overlap(&aabb(a)?, &aabb(b)?)?),
        P::OverlapBoxBox => Answer::Overlap(q.overlap_box_box(&oriented_box(a)?, &oriented_box(b)?)?),
        P::OverlapBoxAabb => Answer::Overlap(q.overlap_box_aabb(&oriented_box(a)?, &aabb(b)?)?),
        P::ToiSphereSphere => Answer::Toi(q.toi_sphere_sphere(&sphere(a)?, &va, &sphere(b)?, &vb, t_max)?),
        P::ToiSpherePlane => Answer::Toi(q.toi_sphere_plane(&sphere(a)?, &va, &plane(b)?, &vb, t_max)?),
        P::ToiSphereTriangle => Answer::Toi(q.toi_sphere_triangle(&sphere(a)?, &va, &triangle(b)?, &vb, t_max)?),
        P::ToiSphereMesh => Answer::Toi(q.toi_sphere_mesh(&sphere(a)?, &va, mesh(lc, 1)?, &vb, t_max)?),
        P::ToiSphereBox => Answer::Toi(q.toi_sphere_box(&sphere(a)?, &va, &oriented_box(b)?, &vb, t_max)?),
        P::ResponseSphereSphere => {
            Answer::Response(q.response_sphere_sphere(&sphere(a)?, &va, mass(a), &sphere(b)?, &vb, mass(b), e)?)
        }
        P::ResponseSpherePlane => Answer::Response(q.response_sphere_plane(&sphere(a)?, &va, &plane(b)?, e)?),
        P::CcdPointTriangle => Answer::Ccd(q.ccd_point_triangle(&moving_point(a)?, &moving_triangle(b)?, t_max)?),
        P::CcdSegmentSegment => Answer::Ccd(q.ccd_segment_segment(&moving_segment(a)?, &moving_segment(b)?, t_max)?),
        P::DistanceSphereSphere
        | P::DistanceSpherePlane
        | P::DistanceSphereTriangle
        | P::DistanceSphereBox
        | P::DistanceSphereCapsule
        | P::DistanceSphereConvex
        | P::DistanceBoxPlane
        | P::DistanceBoxBox
        | P::DistanceBoxTriangle
        | P::DistanceCapsuleCapsule
        | P::DistanceCapsulePlane
        | P::DistanceCapsuleBox
        | P::DistanceCapsuleTriangle
        | P::DistanceCapsuleConvex
        | P::DistanceConvexConvex
        | P::DistanceConvexPlane
        | P::DistanceConvexBox
        | P::DistanceConvexTriangle => {
            let (a, b) = (SolidValue::of(&case.a)?, SolidValue::of(b.ok_or_else(|| missing("solid"))?)?);
            Answer::Distance(q.distance(a.solid(), b.solid())?)
        }
    })
}

/// A `distance` query's shape as the geometry engines receive it: the case's
/// spec turned into its value, a convex hull borrowed.
#[derive(Clone, Debug)]
pub enum SolidValue<'a> {
    /// A ball.
    Sphere(Sphere),
    /// A capsule.
    Capsule(Capsule),
    /// A box that may be rotated.
    Box(OrientedBox),
    /// A convex hull.
    Convex(&'a Convex),
    /// A triangle.
    Triangle(Triangle),
    /// The solid half-space.
    Plane(Plane),
}

impl<'a> SolidValue<'a> {
    /// The solid of a shape, or why it is none.
    pub fn of(s: &'a Shape) -> Reply<Self> {
        Ok(match s {
            Shape::Sphere(s) => SolidValue::Sphere(s.to_geom()),
            Shape::Capsule(c) => SolidValue::Capsule(*c),
            Shape::Box(b) => SolidValue::Box(b.to_geom()),
            Shape::Convex(c) => SolidValue::Convex(c),
            Shape::Triangle(t) => SolidValue::Triangle(t.to_geom()),
            Shape::Plane(p) => SolidValue::Plane(p.to_geom()),
            other => return Err(kind_error("solid", other.kind())),
        })
    }

    /// Borrowed as the engines' [`Solid`].
    pub fn solid(&self) -> Solid<'_> {
        match self {
            SolidValue::Sphere(s) => Solid::Sphere(s),
            SolidValue::Capsule(c) => Solid::Capsule(c),
            SolidValue::Box(b) => Solid::Box(b),
            SolidValue::Convex(c) => Solid::Convex(c),
            SolidValue::Triangle(t) => Solid::Triangle(t),
            SolidValue::Plane(p) => Solid::Plane(p),
        }
    }
}

fn kind_error(want: &str, got: &str) -> Unsupported {
    Unsupported(format!("expected a {want}, got a {got}"))
}

fn missing(want: &str) -> Unsupported {
    Unsupported(format!("expected a {want}, got no shape"))
}

macro_rules! shape_of {
    ($name:ident, $variant:ident, $want:literal, $out:ty, |$spec:ident| $conv:expr) => {
        fn $name(s: Option<&Shape>) -> Reply<$out> {
            match s {
                Some(Shape::$variant($spec)) => Ok($conv),
                Some(other) => Err(kind_error($want, other.kind())),
                None => Err(missing($want)),
            }
        }
    };
}
shape_of!(sphere, Sphere, "sphere", Sphere, |s| s.to_geom());
shape_of!(plane, Plane, "plane", Plane, |s| s.to_geom());
shape_of!(oriented_box, Box, "box", OrientedBox, |s| s.to_geom());
shape_of!(capsule, Capsule, "capsule", Capsule, |s| *s);
shape_of!(triangle, Triangle, "triangle", Triangle, |s| s.to_geom());
shape_of!(segment, Segment, "segment", Segment, |s| s.to_geom());
shape_of!(aabb, Aabb, "aabb", Aabb, |s| s.to_geom());
shape_of!(point, Point, "point", P3, |s| s.at);
shape_of!(moving_point, MovingPoint, "moving_point", MovingPoint, |s| *s);
shape_of!(moving_segment, MovingSegment, "moving_segment", MovingSegment, |s| *s);
shape_of!(moving_triangle, MovingTriangle, "moving_triangle", MovingTriangle, |s| *s);

/// Mesh `i` (0 for `a`, 1 for `b`) as loaded.
fn mesh(lc: &LoadedCase, i: usize) -> Reply<&Mesh> {
    lc.meshes[i].as_ref().ok_or_else(|| Unsupported("mesh not loaded".into()))
}

impl fmt::Debug for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Engine").field("name", &self.name).finish()
    }
}
