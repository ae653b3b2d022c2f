//! The messages of `crashtest-engine/1` (`docs/PROTOCOL.md`), as types: the
//! JSON Schema of every message is generated from them
//! ([`json_schema`]), and the conversions between a case or an answer and its
//! wire form live here and nowhere else.

use crate::case::{Case, CcdTime, Expect, MeshSpec, Query, Shape};
use crate::load::LoadedCase;
use crashtest_core::engine::Answer;
use crashtest_core::geom::{
    Aabb, Ball, BarycentricAnswer, BoundsAnswer, CcdAnswer, Contact, ContactAnswer, DistanceAnswer, IntersectAnswer,
    P3, ResponseAnswer, SegmentHit, Toi, ToiAnswer,
};
use crashtest_core::pair::{Pair, ShapeKind};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The protocol's name and version, as the handshake spells it.
pub const PROTOCOL: &str = "crashtest-engine/1";

/// A line crashtest writes to an engine.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum ToEngine {
    /// The first line: the protocol crashtest speaks.
    Hello {
        /// [`PROTOCOL`].
        protocol: String,
    },
    /// Cases to answer, one entry each in the reply.
    Batch {
        /// Counts batches from 1; the reply repeats it.
        id: u64,
        /// The cases, in the fixture format without `expect`, `tol` and `source`.
        cases: Vec<WireCase>,
    },
    /// A world to step (engines whose hello says `worlds`): one reply.
    World(World),
    /// The engine exits.
    Shutdown,
}

/// A rigid-body world to step (`docs/PROTOCOL.md`, "Worlds"): spheres moving
/// under gravity among fixed planes and boxes, frictionless, undamped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct World {
    /// Counts messages with the batches; the reply repeats it.
    pub id: u64,
    /// What it is, for messages (`bounce, e = 0.5`).
    pub name: String,
    /// The fixed time step (s).
    pub dt: f64,
    /// Steps to take.
    pub steps: u64,
    /// Gravity (m/s²).
    pub gravity: P3,
    /// Whether the spheres use the engine's continuous collision detection.
    pub ccd: bool,
    /// The bodies, in order; the reply lists the spheres in this order.
    pub bodies: Vec<Body>,
}

/// A body of a [`World`]: exactly one of `sphere` (dynamic, with `velocity`
/// and `mass`), `plane` (a fixed half-space `n · x ≤ d`) and `box` (fixed).
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// A dynamic ball.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sphere: Option<Ball>,
    /// A fixed half-space.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plane: Option<crashtest_core::geom::Plane>,
    /// A fixed axis-aligned box.
    #[serde(default, rename = "box", skip_serializing_if = "Option::is_none")]
    pub cuboid: Option<Cuboid>,
    /// A sphere's initial velocity (m/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<P3>,
    /// A sphere's mass (kg).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Coefficient of restitution (every body of a world has the same).
    pub restitution: f64,
}

/// A fixed axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Cuboid {
    /// Its centre.
    pub center: P3,
    /// Half its extent along each axis.
    pub half_extents: P3,
}

/// What an engine did with a [`World`]: the spheres' centres after every
/// step, and their final velocities; or its error.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WorldReply {
    /// The world's `id`.
    pub id: u64,
    /// `steps + 1` entries (the first is the start), each one centre per
    /// sphere in body order.
    #[serde(default)]
    pub positions: Vec<Vec<P3>>,
    /// Each sphere's velocity after the last step.
    #[serde(default)]
    pub velocities: Vec<P3>,
    /// Every setting that mattered for this world, as the report echoes it.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub settings: BTreeMap<String, String>,
    /// The engine's own time for the run, in nanoseconds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ns: Option<f64>,
    /// The engine failed on this world, and why.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// A line an engine writes to crashtest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum FromEngine {
    /// The engine's answer to crashtest's hello.
    Hello(EngineHello),
    /// The answers to one batch.
    Answers {
        /// The batch's `id`.
        id: u64,
        /// One entry per case, in the batch's order.
        answers: Vec<Entry>,
        /// The engine's own time for the whole batch, in nanoseconds.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        ns: Option<f64>,
    },
    /// What it did with a world.
    World(WorldReply),
}

/// An `answers` message without its `type`: what [`read_from_engine`] reads it
/// as, so that an error names the field's whole path.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AnswersBody {
    id: u64,
    answers: Vec<Entry>,
    #[serde(default)]
    ns: Option<f64>,
}

/// The tag of an `answers` line.
#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum AnswersTag {
    Answers,
}

/// An `answers` line, read without buffering.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AnswersLine {
    #[serde(rename = "type")]
    _tag: AnswersTag,
    id: u64,
    answers: Vec<Entry>,
    #[serde(default)]
    ns: Option<f64>,
}

/// The tag of a `batch` line.
#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum BatchTag {
    Batch,
}

/// A `batch` line, read without buffering.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BatchLine {
    #[serde(rename = "type")]
    _tag: BatchTag,
    id: u64,
    cases: Vec<WireCase>,
}

/// Reads one line crashtest wrote to an engine (a batch read straight into
/// its fields, the rest through [`ToEngine`]).
pub fn read_to_engine(line: &str) -> Result<ToEngine, serde_json::Error> {
    match serde_json::from_str::<BatchLine>(line) {
        Ok(b) => Ok(ToEngine::Batch { id: b.id, cases: b.cases }),
        Err(_) => serde_json::from_str(line),
    }
}

/// Reads one line of an engine's output as a message. The error says what is
/// wrong: the column, for JSON syntax; the field's path (`answers[3].answer.hit`)
/// otherwise.
///
/// ```
/// use harness::protocol::messages::{FromEngine, read_from_engine};
/// let m = read_from_engine(r#"{"type":"answers","id":1,"answers":[{"answer":{"overlap":true},"ns":12}]}"#).unwrap();
/// assert!(matches!(m, FromEngine::Answers { id: 1, .. }));
/// let e = read_from_engine(r#"{"type":"answers","id":1,"answers":[{"answer":{"overlapp":true}}]}"#).unwrap_err();
/// assert!(e.starts_with("field `answers[0].answer.overlapp`"), "{e}");
/// let e = read_from_engine(r#"{"type":"answers","#).unwrap_err();
/// assert!(e.starts_with("column 18: EOF while parsing"), "{e}");
/// ```
pub fn read_from_engine(line: &str) -> Result<FromEngine, String> {
    // The common case read straight into its fields (an internally tagged
    // enum buffers the whole line first, which costs more than the rest of
    // the exchange); any error is read again below, field by field.
    if let Ok(a) = serde_json::from_str::<AnswersLine>(line) {
        return Ok(FromEngine::Answers { id: a.id, answers: a.answers, ns: a.ns });
    }
    let mut v: serde_json::Value = serde_json::from_str(line).map_err(|e| {
        // serde's position counts lines within this one line: say the column.
        let text = e.to_string();
        let what = text.rsplit_once(" at line ").map_or(text.as_str(), |(w, _)| w).to_string();
        format!("column {}: {what}", e.column())
    })?;
    let obj = v.as_object_mut().ok_or("not a JSON object")?;
    let kind = match obj.remove("type") {
        Some(serde_json::Value::String(t)) => t,
        Some(other) => return Err(format!("field `type`: expected \"hello\" or \"answers\", got {other}")),
        None => return Err("field `type`: missing".into()),
    };
    fn body<T: serde::de::DeserializeOwned>(v: serde_json::Value) -> Result<T, String> {
        serde_path_to_error::deserialize(v).map_err(|e| {
            let path = e.path().to_string();
            let inner = e.into_inner();
            if path == "." { inner.to_string() } else { format!("field `{path}`: {inner}") }
        })
    }
    match kind.as_str() {
        "hello" => body(v).map(FromEngine::Hello),
        "answers" => body::<AnswersBody>(v).map(|b| FromEngine::Answers { id: b.id, answers: b.answers, ns: b.ns }),
        "world" => body(v).map(FromEngine::World),
        other => Err(format!("field `type`: `{other}` is not a message an engine sends (hello, answers, world)")),
    }
}

/// What an engine says of itself.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EngineHello {
    /// [`PROTOCOL`].
    pub protocol: String,
    /// Its name in reports.
    pub name: String,
    /// Its version, for the report's provenance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub version: Option<String>,
    /// Bits of mantissa of the arithmetic it uses (53 for f64, 24 for f32).
    pub precision: u32,
    /// The query pairs it answers.
    pub capabilities: Vec<Capability>,
    /// What the report's provenance should echo (library versions, settings).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub provenance: BTreeMap<String, String>,
    /// Whether it steps worlds (`world` messages: the report's dynamics).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub worlds: bool,
    /// Standalone reproductions in the engine's own API, one per pair at most:
    /// a finding's bug-report draft fills one with its shrunk case
    /// (`crashtest findings`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reproductions: Vec<Reproduction>,
}

/// A standalone program that asks the engine one case of a pair through the
/// engine's own API and prints its raw answer. `{{a.center}}`, `{{b.vertices}}`,
/// `{{t_max}}`, … (a shape's field, or the case's) stand for the case's values,
/// written as JSON literals (numbers as the shortest decimals that round-trip;
/// an absent velocity as `[0.0, 0.0, 0.0]`, an absent `t_max` as its default).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Reproduction {
    /// The query.
    pub query: Query,
    /// Shape `a`'s kind.
    pub a: ShapeKind,
    /// Shape `b`'s kind (absent for `bounds`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b: Option<ShapeKind>,
    /// The program's language, for the draft's code block (`python`).
    pub language: String,
    /// The program, with its placeholders.
    pub script: String,
}

/// One query pair of the pair table, by its kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Capability {
    /// The query.
    pub query: Query,
    /// Shape `a`'s kind.
    pub a: ShapeKind,
    /// Shape `b`'s kind (absent for `bounds`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b: Option<ShapeKind>,
    /// The precision this pair is answered in, in bits of mantissa, where it
    /// is not the engine's (an f64 engine that stores meshes in f32 says 24
    /// for its mesh pairs); its answers are judged at that precision.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<u32>,
}

impl Capability {
    /// The capability of answering `pair` (at the engine's precision).
    pub fn of(pair: Pair) -> Self {
        let row = pair.row();
        Capability { query: row.query, a: row.a, b: row.b, precision: None }
    }

    /// The pair it names, if the pair table has it.
    pub fn pair(&self) -> Option<Pair> {
        Pair::find(self.query, self.a, self.b)
    }
}

/// A case on the wire: the fixture format's case without `expect`, `tol` and
/// `source`, its meshes inline.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WireCase {
    /// The case's name.
    pub name: String,
    /// What is asked.
    pub query: Query,
    /// The first shape.
    pub a: Shape,
    /// The second shape (absent for `bounds`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub b: Option<Shape>,
    /// End of the time interval (`toi` and `ccd`: always written).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_max: Option<f64>,
    /// Coefficient of restitution (`response`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
}

impl WireCase {
    /// The wire form of a loaded case: mesh files replaced by their vertices
    /// and faces, `t_max` written out for `toi` and `ccd`.
    pub fn of(lc: &LoadedCase) -> Self {
        let c = &lc.case;
        let inline = |s: &Shape, m: &Option<crate::mesh::Mesh>| match (s, m) {
            (Shape::Mesh(spec), Some(mesh)) => Shape::Mesh(MeshSpec {
                vertices: Some(mesh.vertices.clone()),
                triangles: Some(mesh.triangles.clone()),
                file: None,
                velocity: spec.velocity,
            }),
            _ => s.clone(),
        };
        WireCase {
            name: c.name.clone(),
            query: c.query,
            a: inline(&c.a, &lc.meshes[0]),
            b: c.b.as_ref().map(|b| inline(b, &lc.meshes[1])),
            t_max: matches!(c.query, Query::Toi | Query::Ccd).then(|| c.t_max()),
            restitution: c.restitution,
        }
    }

    /// The case it carries (no `expect`), for an engine that reads the wire.
    pub fn into_case(self) -> Case {
        Case {
            name: self.name,
            source: String::new(),
            query: self.query,
            a: self.a,
            b: self.b,
            expect: None,
            tol: None,
            t_max: self.t_max,
            restitution: self.restitution,
        }
    }
}

/// One entry of an `answers` message: exactly one of `answer`, `unsupported`
/// and `error`, and the engine's own time for the case.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    /// The answer, in the `expect` vocabulary of the case's query.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub answer: Option<WireAnswer>,
    /// The engine does not answer this case, and why.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unsupported: Option<String>,
    /// The engine failed on this case, and how.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The engine's own time for this case, in nanoseconds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ns: Option<f64>,
}

/// What an entry says of its case.
#[derive(Clone, Debug, PartialEq)]
pub enum Said {
    /// An answer that fits the case's query.
    Answer(Answer),
    /// `unsupported`, with the reason.
    Unsupported(String),
    /// `error`, with the message; or an entry that breaks the protocol, with
    /// what is wrong.
    Error(String),
}

impl Entry {
    /// What the entry says about a case of `query`; an entry that does not fit
    /// (none or several of its fields, an answer that does not fit the query) is
    /// an error naming the field.
    pub fn said(&self, query: Query) -> Said {
        match (&self.answer, &self.unsupported, &self.error) {
            (Some(a), None, None) => match a.to_answer(query) {
                Ok(a) => Said::Answer(a),
                Err(e) => Said::Error(format!("protocol violation: answer.{e}")),
            },
            (None, Some(u), None) => Said::Unsupported(u.clone()),
            (None, None, Some(e)) => Said::Error(e.clone()),
            _ => Said::Error(
                "protocol violation: an entry holds exactly one of `answer`, `unsupported` and `error`".into(),
            ),
        }
    }

    /// The entry of an answer.
    pub fn answer(a: &Answer, ns: Option<f64>) -> Self {
        Entry { answer: Some(WireAnswer::of(a)), ns, ..Default::default() }
    }
}

/// An answer on the wire: the fixture format's `expect` vocabulary, with the
/// engine's bounding sphere (`sphere`) for `bounds` where a fixture's `expect`
/// has only the minimal radius — which is why it is a type of its own and not
/// [`crate::case::Expect`]. Only the fields of the case's query may be present.
#[derive(Clone, Debug, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WireAnswer {
    /// `contact`: the contact, or `null`.
    #[serde(default, deserialize_with = "crate::case::present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<Contact>")]
    pub contact: Option<Option<Contact>>,
    /// `intersect`: the first hit, or `null`.
    #[serde(default, deserialize_with = "crate::case::present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<SegmentHit>")]
    pub hit: Option<Option<SegmentHit>>,
    /// `intersect`: the segment is parallel to the surface.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parallel: Option<bool>,
    /// The answer is a documented fallback for input the rules do not define.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub degenerate: Option<bool>,
    /// `barycentric`: `[α, β, γ]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub barycentric: Option<[f64; 3]>,
    /// `bounds`: the AABB.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aabb: Option<Aabb>,
    /// `bounds`: the engine's bounding sphere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sphere: Option<Ball>,
    /// `overlap`: whether the boxes overlap.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overlap: Option<bool>,
    /// `toi`: the first contact, or `null`.
    #[serde(default, deserialize_with = "crate::case::present", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<Toi>")]
    pub toi: Option<Option<Toi>>,
    /// `response`: `a`'s velocity after the impulse.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_a: Option<P3>,
    /// `response`: `b`'s velocity after the impulse.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_b: Option<P3>,
    /// `ccd`: the first time of impact, or `null`.
    #[serde(default, deserialize_with = "crate::case::present", skip_serializing_if = "Option::is_none")]
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

impl WireAnswer {
    /// The wire form of an answer (every field it has, so that reading it back
    /// gives the same answer bit for bit).
    pub fn of(a: &Answer) -> Self {
        let mut w = WireAnswer::default();
        match a {
            Answer::Contact(c) => {
                w.contact = Some(c.contact);
                w.degenerate = Some(c.degenerate);
            }
            Answer::Intersect(i) => {
                w.hit = Some(i.hit);
                w.parallel = Some(i.parallel);
                w.degenerate = Some(i.degenerate);
            }
            Answer::Barycentric(b) => {
                w.barycentric = Some(b.coords);
                w.degenerate = Some(b.degenerate);
            }
            Answer::Bounds(b) => {
                w.aabb = b.aabb;
                w.sphere = b.sphere;
            }
            Answer::Overlap(o) => w.overlap = Some(*o),
            Answer::Toi(t) => {
                w.toi = Some(t.toi);
                w.degenerate = Some(t.degenerate);
            }
            Answer::Response(r) => {
                w.velocity_a = Some(r.velocity_a);
                w.velocity_b = Some(r.velocity_b);
                w.degenerate = Some(r.degenerate);
            }
            Answer::Ccd(c) => {
                w.ccd = Some(c.t.map(|t| CcdTime { t }));
                w.degenerate = Some(c.degenerate);
            }
            Answer::Distance(d) => {
                w.distance = Some(d.distance);
                w.point_a = Some(d.point_a);
                w.point_b = Some(d.point_b);
                w.normal = Some(d.normal);
                w.degenerate = Some(d.degenerate);
            }
        }
        w
    }

    /// The answer as a fixture's `expect` (the bounding sphere as its radius,
    /// which is what `expect` holds of it).
    pub fn into_expect(self) -> Expect {
        Expect {
            contact: self.contact,
            hit: self.hit,
            parallel: self.parallel,
            degenerate: self.degenerate,
            barycentric: self.barycentric,
            aabb: self.aabb,
            min_radius: self.sphere.map(|s| s.radius),
            overlap: self.overlap,
            toi: self.toi,
            velocity_a: self.velocity_a,
            velocity_b: self.velocity_b,
            impact: None,
            ccd: self.ccd,
            distance: self.distance,
            point_a: self.point_a,
            point_b: self.point_b,
            normal: self.normal,
        }
    }

    /// The fields present, by name.
    fn present(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        let mut has = |on: bool, name| {
            if on {
                out.push(name)
            }
        };
        has(self.contact.is_some(), "contact");
        has(self.hit.is_some(), "hit");
        has(self.parallel.is_some(), "parallel");
        has(self.degenerate.is_some(), "degenerate");
        has(self.barycentric.is_some(), "barycentric");
        has(self.aabb.is_some(), "aabb");
        has(self.sphere.is_some(), "sphere");
        has(self.overlap.is_some(), "overlap");
        has(self.toi.is_some(), "toi");
        has(self.velocity_a.is_some(), "velocity_a");
        has(self.velocity_b.is_some(), "velocity_b");
        has(self.ccd.is_some(), "ccd");
        has(self.distance.is_some(), "distance");
        has(self.point_a.is_some(), "point_a");
        has(self.point_b.is_some(), "point_b");
        has(self.normal.is_some(), "normal");
        out
    }

    /// The answer to a case of `query`; the error names the field that is
    /// missing or does not belong to the query.
    pub fn to_answer(&self, query: Query) -> Result<Answer, String> {
        let allowed: &[&str] = match query {
            Query::Contact => &["contact", "degenerate"],
            Query::Intersect => &["hit", "parallel", "degenerate"],
            Query::Barycentric => &["barycentric", "degenerate"],
            Query::Bounds => &["aabb", "sphere"],
            Query::Overlap => &["overlap"],
            Query::Toi => &["toi", "degenerate"],
            Query::Response => &["velocity_a", "velocity_b", "degenerate"],
            Query::Ccd => &["ccd", "degenerate"],
            Query::Distance => &["distance", "point_a", "point_b", "normal", "degenerate"],
        };
        if let Some(f) = self.present().into_iter().find(|f| !allowed.contains(f)) {
            return Err(format!("{f}: not a field of a {query} answer (its fields: {})", allowed.join(", ")));
        }
        let need = |name: &str| format!("{name}: missing (a {query} answer has it)");
        let degenerate = self.degenerate.unwrap_or(false);
        let answer = match query {
            Query::Contact => {
                Answer::Contact(ContactAnswer { contact: self.contact.ok_or_else(|| need("contact"))?, degenerate })
            }
            Query::Intersect => Answer::Intersect(IntersectAnswer {
                hit: self.hit.ok_or_else(|| need("hit"))?,
                parallel: self.parallel.unwrap_or(false),
                degenerate,
            }),
            Query::Barycentric => Answer::Barycentric(BarycentricAnswer {
                coords: self.barycentric.ok_or_else(|| need("barycentric"))?,
                degenerate,
            }),
            Query::Bounds => {
                if self.aabb.is_none() && self.sphere.is_none() {
                    return Err("aabb: missing (a bounds answer has `aabb`, `sphere` or both)".into());
                }
                Answer::Bounds(BoundsAnswer { aabb: self.aabb, sphere: self.sphere })
            }
            Query::Overlap => Answer::Overlap(self.overlap.ok_or_else(|| need("overlap"))?),
            Query::Toi => Answer::Toi(ToiAnswer { toi: self.toi.ok_or_else(|| need("toi"))?, degenerate }),
            Query::Response => Answer::Response(ResponseAnswer {
                velocity_a: self.velocity_a.ok_or_else(|| need("velocity_a"))?,
                velocity_b: self.velocity_b.ok_or_else(|| need("velocity_b"))?,
                degenerate,
            }),
            Query::Ccd => Answer::Ccd(CcdAnswer { t: self.ccd.ok_or_else(|| need("ccd"))?.map(|c| c.t), degenerate }),
            Query::Distance => Answer::Distance(DistanceAnswer {
                distance: self.distance.ok_or_else(|| need("distance"))?,
                point_a: self.point_a.ok_or_else(|| need("point_a"))?,
                point_b: self.point_b.ok_or_else(|| need("point_b"))?,
                normal: self.normal.ok_or_else(|| need("normal"))?,
                degenerate,
            }),
        };
        Ok(answer)
    }
}

/// Every message of the protocol, for the schema.
#[derive(JsonSchema)]
#[serde(untagged)]
#[allow(dead_code, reason = "a type for the schema generator only")]
enum Message {
    /// crashtest → engine.
    ToEngine(ToEngine),
    /// engine → crashtest.
    FromEngine(FromEngine),
}

/// The JSON Schema of every message of `crashtest-engine/1` (committed as
/// `schema/crashtest-engine-1.schema.json`; a test keeps it current).
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(Message);
    serde_json::to_string_pretty(&schema).unwrap_or_default() + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pair_is_a_capability_and_back() {
        for p in Pair::ALL {
            assert_eq!(Capability::of(p).pair(), Some(p), "{p:?}");
        }
        let not_a_pair =
            Capability { query: Query::Overlap, a: ShapeKind::Sphere, b: Some(ShapeKind::Sphere), precision: None };
        assert_eq!(not_a_pair.pair(), None);
    }

    #[test]
    fn an_answer_has_its_querys_fields_and_no_other() {
        let read = |json: &str, q: Query| serde_json::from_str::<WireAnswer>(json).expect("reads").to_answer(q);
        assert_eq!(read(r#"{"overlap": true}"#, Query::Overlap), Ok(Answer::Overlap(true)));
        assert!(matches!(read(r#"{"contact": null}"#, Query::Contact), Ok(Answer::Contact(c)) if c.contact.is_none()));
        let e = read(r#"{"overlap": true}"#, Query::Contact).expect_err("not a contact field");
        assert!(e.starts_with("overlap: not a field of a contact answer"), "{e}");
        let e = read(r#"{"degenerate": true}"#, Query::Contact).expect_err("no contact");
        assert!(e.starts_with("contact: missing"), "{e}");
        let e = read(r#"{}"#, Query::Bounds).expect_err("neither box nor sphere");
        assert!(e.starts_with("aabb: missing"), "{e}");
        assert!(serde_json::from_str::<WireAnswer>(r#"{"overlapp": true}"#).is_err(), "unknown keys are refused");
    }

    #[test]
    fn an_entry_holds_exactly_one_of_answer_unsupported_and_error() {
        let entry = |json: &str| serde_json::from_str::<Entry>(json).expect("reads").said(Query::Overlap);
        assert_eq!(entry(r#"{"unsupported": "no boxes here"}"#), Said::Unsupported("no boxes here".into()));
        assert_eq!(entry(r#"{"error": "boom", "ns": 3}"#), Said::Error("boom".into()));
        assert!(
            matches!(entry(r#"{"error": "boom", "unsupported": "no"}"#), Said::Error(m) if m.contains("exactly one"))
        );
        assert!(matches!(entry(r#"{"ns": 3}"#), Said::Error(m) if m.contains("exactly one")));
    }
}
