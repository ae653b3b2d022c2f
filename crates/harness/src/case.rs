//! The fixture format `crashtest-fixture/1` (docs/FORMAT.md): the contract
//! between whoever writes cases and every engine the harness runs.
//!
//! These types read and write the format exactly. Optional fields the project adds
//! are marked as such and never change the meaning of the format's own fields.
//! Every level rejects unknown fields — the file, the case, its shapes and its
//! expectation — because a misspelt key is never harmless: `raduis` would
//! become a default, `tmax` would run with `t_max` = 1, and `expected` for
//! `expect` would make a wrong expectation pass unchecked. Free text goes in
//! `source`.

use oracle::geom::{
    Aabb, Capsule, Contact, Convex, MovingPoint, MovingSegment, MovingTriangle, OrientedBox, P3, SegmentHit, Toi,
};
use schemars::JsonSchema;
use serde::{Deserialize, Deserializer, Serialize};

/// The schema tag every fixture file carries.
pub const SCHEMA: &str = "crashtest-fixture/1";

/// The default absolute tolerance on every scalar of an expected answer, from the
/// format: `1e-9`.
pub const DEFAULT_TOL: f64 = 1e-9;

/// The default end of the time interval of a `toi` or `ccd` case, from the format: 1.
pub const DEFAULT_T_MAX: f64 = 1.0;

/// One fixture file.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FixtureFile {
    /// Always [`SCHEMA`].
    pub schema: String,
    /// The cases; names are unique within a file.
    pub cases: Vec<Case>,
}

/// One case: a query about two shapes (one for `bounds`), with an optional
/// expected answer.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Unique within its file.
    pub name: String,
    /// Where the case comes from (free text; hand derivations go here).
    #[serde(default)]
    pub source: String,
    /// What is asked.
    pub query: Query,
    /// The first shape.
    pub a: Shape,
    /// The second shape (absent for `bounds`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b: Option<Shape>,
    /// The expected answer; only what it names is checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expect: Option<Expect>,
    /// Absolute tolerance on every scalar of the answer (default [`DEFAULT_TOL`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tol: Option<f64>,
    /// End of the time interval for `toi` and `ccd` (default [`DEFAULT_T_MAX`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_max: Option<f64>,
    /// Coefficient of restitution for `response`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
}

impl Case {
    /// The case's row of the pair table, if the format has its kinds.
    pub fn pair(&self) -> Option<Pair> {
        Pair::find(self.query, self.a.shape_kind(), self.b.as_ref().map(Shape::shape_kind))
    }

    /// The tolerance in force for this case.
    pub fn tol(&self) -> f64 {
        self.tol.unwrap_or(DEFAULT_TOL)
    }
}

pub use crashtest_core::pair::{Pair, Query, ShapeKind};

/// A shape, written `{"<kind>": {fields}}`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    /// Solid ball.
    Sphere(SphereSpec),
    /// The surface `normal · x = offset` (solid below for contact and toi).
    Plane(PlaneSpec),
    /// `start + t (end − start)`, `t ∈ [0, 1]`.
    Segment(SegmentSpec),
    /// Three vertices.
    Triangle(TriangleSpec),
    /// One point.
    Point(PointSpec),
    /// A point cloud (at least one point).
    Points(PointsSpec),
    /// A triangle soup, inline or from a file.
    Mesh(MeshSpec),
    /// Axis-aligned box.
    Aabb(AabbSpec),
    /// A point moving linearly from `t0` (time 0) to `t1` (time 1).
    MovingPoint(MovingPoint),
    /// A closed segment whose ends move linearly from `t0` to `t1`.
    MovingSegment(MovingSegment),
    /// A closed triangle whose vertices move linearly from `t0` to `t1`.
    MovingTriangle(MovingTriangle),
    /// A solid box that may be rotated.
    Box(BoxSpec),
    /// The points within a radius of a segment.
    Capsule(Capsule),
    /// The convex hull of points (at least one).
    Convex(Convex),
}

impl Shape {
    /// The shape's key in the format.
    pub fn kind(&self) -> &'static str {
        self.shape_kind().as_str()
    }

    /// The shape's kind.
    pub fn shape_kind(&self) -> ShapeKind {
        match self {
            Shape::Sphere(_) => ShapeKind::Sphere,
            Shape::Plane(_) => ShapeKind::Plane,
            Shape::Segment(_) => ShapeKind::Segment,
            Shape::Triangle(_) => ShapeKind::Triangle,
            Shape::Point(_) => ShapeKind::Point,
            Shape::Points(_) => ShapeKind::Points,
            Shape::Mesh(_) => ShapeKind::Mesh,
            Shape::Aabb(_) => ShapeKind::Aabb,
            Shape::MovingPoint(_) => ShapeKind::MovingPoint,
            Shape::MovingSegment(_) => ShapeKind::MovingSegment,
            Shape::MovingTriangle(_) => ShapeKind::MovingTriangle,
            Shape::Box(_) => ShapeKind::Box,
            Shape::Capsule(_) => ShapeKind::Capsule,
            Shape::Convex(_) => ShapeKind::Convex,
        }
    }
}

/// `sphere`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    /// Centre.
    pub center: P3,
    /// Radius, > 0.
    pub radius: f64,
    /// Linear velocity for `toi` and `response` (default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<P3>,
    /// Mass for `response`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
}

/// `plane`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// Non-zero, need not be unit.
    pub normal: P3,
    /// `d` in `normal · x = d`.
    pub offset: f64,
    /// Linear velocity for `toi` (default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<P3>,
}

/// `segment`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// `t = 0`.
    pub start: P3,
    /// `t = 1`.
    pub end: P3,
}

/// `triangle`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TriangleSpec {
    /// `[v0, v1, v2]`.
    pub vertices: [P3; 3],
    /// Linear velocity for `toi` (default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<P3>,
}

/// `point`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointSpec {
    /// The point.
    pub at: P3,
}

/// `points`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointsSpec {
    /// At least one point.
    pub points: Vec<P3>,
}

/// `mesh`: `vertices` + `triangles`, or `file`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Inline vertices.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vertices: Option<Vec<P3>>,
    /// Inline faces, 0-based vertex indices.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub triangles: Option<Vec<[usize; 3]>>,
    /// A mesh file, relative to the fixture file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Linear velocity for `toi` (default zero).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<P3>,
}

/// `aabb`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AabbSpec {
    /// Lower corner.
    pub min: P3,
    /// Upper corner (≥ `min` per axis).
    pub max: P3,
}

/// `box`: the solid `center + R·u`, `|u_i| ≤ half_extents[i]`, `R` the rotation
/// of `rotation / ‖rotation‖`.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    /// Centre.
    pub center: P3,
    /// Half-extents along the box's own axes, each ≥ 0.
    pub half_extents: P3,
    /// The quaternion `[w, x, y, z]`, non-zero, any length (default `[1, 0, 0, 0]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<[f64; 4]>,
    /// Linear velocity for `toi` (default zero; the rotation stays fixed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<P3>,
}

/// The rotation of a box without one: the identity.
pub const IDENTITY_ROTATION: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

/// An expected answer. Every field is optional; a check compares only what is
/// named. For `contact`, `hit` and `toi`, `null` means "nothing is found" and is
/// distinct from the field's absence.
#[derive(Clone, Debug, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Expect {
    /// `contact`: the contact, or `null`.
    #[serde(default, deserialize_with = "present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<Contact>")]
    pub contact: Option<Option<Contact>>,
    /// `intersect`: the first hit, or `null`.
    #[serde(default, deserialize_with = "present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<SegmentHit>")]
    pub hit: Option<Option<SegmentHit>>,
    /// `intersect`: the segment is parallel to the surface.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parallel: Option<bool>,
    /// Any query: the answer is not defined by the rules (fallback in use).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub degenerate: Option<bool>,
    /// `barycentric`: `[α, β, γ]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub barycentric: Option<[f64; 3]>,
    /// `bounds`: the exact AABB.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aabb: Option<Aabb>,
    /// `bounds`: the radius of the smallest enclosing sphere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_radius: Option<f64>,
    /// `overlap`: whether the boxes overlap (touching overlaps).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overlap: Option<bool>,
    /// `toi`: the first touching time and contact, or `null`.
    #[serde(default, deserialize_with = "present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<Toi>")]
    pub toi: Option<Option<Toi>>,
    /// `response`: `a`'s velocity after the impulse.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_a: Option<P3>,
    /// `response`: `b`'s velocity after the impulse.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_b: Option<P3>,
    /// `ccd`: whether there is an impact in `[0, t_max]` (a benchmark's boolean
    /// ground truth), checked against the answer's classification only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact: Option<bool>,
    /// `ccd`: the first time of impact, or `null`.
    #[serde(default, deserialize_with = "present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<CcdTime>")]
    pub ccd: Option<Option<CcdTime>>,
    /// `distance`: the signed distance (< 0: minus the penetration depth).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance: Option<f64>,
    /// `distance`: the witness on `a`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub point_a: Option<P3>,
    /// `distance`: the witness on `b`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub point_b: Option<P3>,
    /// `distance`: the unit normal from `b` toward `a`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<P3>,
}

/// A `ccd` impact as the format writes it: `{"t": T}`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CcdTime {
    /// The first time in `[0, t_max]` at which the point lies on the closed
    /// triangle, or the two closed segments share a point.
    pub t: f64,
}

/// A field that is present, with `null` kept apart from absence: absent →
/// `None` (through `#[serde(default)]`), `null` → `Some(None)`.
pub(crate) fn present<'de, D, T>(d: D) -> Result<Option<Option<T>>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<T>::deserialize(d).map(Some)
}

impl SphereSpec {
    /// The sphere at time 0.
    pub fn to_geom(&self) -> oracle::geom::Sphere {
        oracle::geom::Sphere { center: self.center, radius: self.radius }
    }
}

impl PlaneSpec {
    /// The plane at time 0.
    pub fn to_geom(&self) -> oracle::geom::Plane {
        oracle::geom::Plane { normal: self.normal, offset: self.offset }
    }
}

impl SegmentSpec {
    /// The segment.
    pub fn to_geom(&self) -> oracle::geom::Segment {
        oracle::geom::Segment { start: self.start, end: self.end }
    }
}

impl TriangleSpec {
    /// The triangle at time 0.
    pub fn to_geom(&self) -> oracle::geom::Triangle {
        oracle::geom::Triangle { vertices: self.vertices }
    }
}

impl AabbSpec {
    /// The box.
    pub fn to_geom(&self) -> Aabb {
        Aabb { min: self.min, max: self.max }
    }
}

impl BoxSpec {
    /// The box, its rotation defaulted.
    pub fn to_geom(&self) -> OrientedBox {
        OrientedBox {
            center: self.center,
            half_extents: self.half_extents,
            rotation: self.rotation.unwrap_or(IDENTITY_ROTATION),
        }
    }
}

/// A case's input numbers, as JSON pointers into the case written as JSON
/// (`serde_json::to_value`): every number of its shapes (`/a/…`, `/b/…`; a
/// mesh's face indices are not inputs) and its `t_max` and `restitution`.
/// Never `expect` or `tol`.
pub fn input_number_paths(case: &serde_json::Value) -> Vec<String> {
    let mut out = Vec::new();
    fn walk(v: &serde_json::Value, path: String, out: &mut Vec<String>) {
        match v {
            serde_json::Value::Number(_) => out.push(path),
            serde_json::Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| walk(x, format!("{path}/{i}"), out)),
            serde_json::Value::Object(o) => {
                for (k, x) in o {
                    if k != "triangles" {
                        walk(x, format!("{path}/{k}"), out);
                    }
                }
            }
            _ => {}
        }
    }
    for key in ["a", "b"] {
        if let Some(s) = case.get(key) {
            walk(s, format!("/{key}"), &mut out);
        }
    }
    for key in ["t_max", "restitution"] {
        if case.get(key).is_some_and(serde_json::Value::is_number) {
            out.push(format!("/{key}"));
        }
    }
    out
}

/// The JSON Schema of a fixture file, generated from these types (committed as
/// `schema/crashtest-fixture-1.schema.json`; a test keeps the copy current).
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(FixtureFile);
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}

impl Case {
    /// `t_max` in force (default [`DEFAULT_T_MAX`]).
    pub fn t_max(&self) -> f64 {
        self.t_max.unwrap_or(DEFAULT_T_MAX)
    }
}

impl Shape {
    /// The shape's velocity (zero when not given or not movable).
    pub fn velocity(&self) -> P3 {
        match self {
            Shape::Sphere(s) => s.velocity,
            Shape::Plane(p) => p.velocity,
            Shape::Triangle(t) => t.velocity,
            Shape::Mesh(m) => m.velocity,
            Shape::Box(b) => b.velocity,
            _ => None,
        }
        .unwrap_or([0.0; 3])
    }
}
