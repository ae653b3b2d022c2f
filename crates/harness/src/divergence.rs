//! Known divergences as data: where an engine's documented definition differs from
//! the fixture format's, a disagreement it explains is recorded as a known
//! divergence with its reason, not as an error.
//!
//! Each rule says which engines it covers and when it explains a disagreement, from
//! the case, the engine's answer and the referee's. parry's entries come from
//! `oracle::parry::known_divergences()` (each pinned there by a test showing it
//! still happens); collide's lecture methods carry their own. A rule whose
//! divergence stops happening is caught by those pinning tests, and a rule that
//! names an entry parry no longer lists fails the tests here.
//!
//! A process engine's known divergences are data ([`DataRule`]): a file in the
//! engine's folder (`engines/<name>/known.json`, schema `crashtest-known/1`),
//! each rule naming the pair, the fields the verdict may name, conditions on the
//! engine's answer and the referee's, its reason, and the cases that pin it (a
//! test runs them and fails when the divergence stops happening).

use crate::case::{Query, Shape};
use crate::load::LoadedCase;
use crate::protocol::messages::WireAnswer;
use crashtest_core::engine::Answer;
use crashtest_core::pair::ShapeKind;
use oracle::parry::{KnownDivergence, cast_known_divergences, known_divergences};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// When a rule explains a disagreement: the case, the engine's answer, the
/// referee's, and the disagreement's reasons.
type Explains = fn(&LoadedCase, &Answer, &Answer, &[String]) -> bool;

/// One known divergence: when it explains a disagreement, and why.
pub struct Rule {
    /// For parry: the start of the `what` of its entry in `known_divergences()`
    /// (its reason is read from there); `None` for a rule that states its own.
    pub parry_what: Option<&'static str>,
    /// The reason, when `parry_what` is `None`.
    pub reason: &'static str,
    /// Whether it explains this disagreement.
    pub explains: Explains,
}

/// The known divergences an engine carries (each [`crate::engine::Engine`] has
/// its own set; most have none): rules in code, for the engines built in, or
/// rules read from data, for a process engine.
#[derive(Clone)]
pub struct Known {
    rules: &'static [Rule],
    data: Option<Arc<[DataRule]>>,
}

impl Known {
    /// No known divergence: every disagreement stands.
    pub const NONE: Known = Known::rules(&[]);

    /// Rules written in code.
    pub const fn rules(rules: &'static [Rule]) -> Known {
        Known { rules, data: None }
    }

    /// Rules read from data ([`load_known`]).
    pub fn data(rules: Vec<DataRule>) -> Known {
        Known { rules: &[], data: Some(rules.into()) }
    }

    /// The rules read from data (none for an engine built in).
    pub fn data_rules(&self) -> &[DataRule] {
        self.data.as_deref().unwrap_or(&[])
    }
}

impl std::fmt::Debug for Known {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Known({} rules, {} from data)", self.rules.len(), self.data_rules().len())
    }
}

/// A known divergence written as data: one entry of a `crashtest-known/1` file.
/// It explains a disagreement when the case is of its pair, every reason the
/// verdict gives starts with one of `reasons` (when it lists any), and every
/// condition on the engine's answer and on the referee's holds.
#[derive(Clone, Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DataRule {
    /// What happens, in a few words (shown in the verdict).
    pub what: String,
    /// Why it is a convention of the engine and not its error, and where the
    /// engine documents it (shown in the verdict).
    pub reason: String,
    /// The pair: the query and the kinds of `a` and `b`.
    pub query: Query,
    /// The kind of `a`.
    pub a: ShapeKind,
    /// The kind of `b` (absent for `bounds`).
    #[serde(default)]
    pub b: Option<ShapeKind>,
    /// The verdict's reasons it covers, by their start (`normal off`, `point
    /// off`, `missed contact`, …); empty: any.
    #[serde(default)]
    pub reasons: Vec<String>,
    /// Conditions on the engine's answer: a field's path in the answer's wire
    /// form (`contact.depth`, `hit`, `degenerate`) and a value it equals, or
    /// one comparison `{"<": x}` (`<`, `<=`, `>`, `>=`, `!=`). A missing
    /// field reads as `null`.
    #[serde(default)]
    pub engine: BTreeMap<String, serde_json::Value>,
    /// Conditions on the referee's answer, written the same way.
    #[serde(default)]
    pub referee: BTreeMap<String, serde_json::Value>,
    /// Facts about the case and the referee's answer that must hold, from a
    /// fixed vocabulary ([`Given`]).
    #[serde(default)]
    pub given: Vec<Given>,
    /// The cases (by name, in the engine's divergences file) that show it; a
    /// test runs them and fails when one stops diverging this way.
    pub pinned_by: Vec<String>,
}

/// Facts a data rule can require that are not a field of an answer.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Given {
    /// `intersect`: the segment runs along the surface's normal, `(end −
    /// start) · n > 0` in f64, with `n` the plane's normal or the triangle's
    /// face normal `(v1 − v0) × (v2 − v0)`: it crosses from the back.
    SegmentAlongNormal,
    /// `intersect`: the referee's hit lies on an edge or a vertex of its face
    /// (a barycentric coordinate is 0), a point that faces of a mesh share.
    HitOnAnEdge,
    /// `intersect`: the engine's hit normal faces the segment's start,
    /// `n · (end − start) < 0` in f64.
    EngineNormalFacesTheStart,
    /// `intersect` with a triangle: the engine's hit point lies outside the
    /// triangle by at most this fraction: each of its signed barycentric
    /// coordinates (in f64) is at least minus it.
    EngineHitOutsideByAtMost(f64),
    /// A mesh `b` that is not the surface of its convex hull — open (an edge
    /// not shared by exactly two faces), not convex (a vertex strictly on both
    /// sides of a face's plane), with a vertex no face uses, or with a
    /// zero-area face — or a sphere whose centre lies strictly inside it: an
    /// engine that takes a mesh as its convex hull answers another shape there.
    MeshNotItsConvexHull,
    /// `toi` or `ccd`: both found an impact, and the engine's time is early by
    /// at most this fraction of `t_max`: `t_referee − x · t_max ≤ t_engine ≤
    /// t_referee` (a conservative advancement or inclusion that stops within a
    /// tolerance of the contact, never past it).
    EngineTimeEarlyByAtMost(f64),
}

impl Given {
    fn holds(self, lc: &LoadedCase, answer: &Answer, truth: &Answer) -> bool {
        use crashtest_core::vec3::{cross, dot, sub};
        let segment = match &lc.case.a {
            Shape::Segment(s) => Some(sub(s.end, s.start)),
            _ => None,
        };
        let engine_hit = match answer {
            Answer::Intersect(a) => a.hit,
            _ => None,
        };
        match self {
            Given::SegmentAlongNormal => {
                let n = match &lc.case.b {
                    Some(Shape::Plane(p)) => p.normal,
                    Some(Shape::Triangle(t)) => {
                        let [v0, v1, v2] = t.vertices;
                        cross(sub(v1, v0), sub(v2, v0))
                    }
                    _ => return false,
                };
                segment.is_some_and(|d| dot(d, n) > 0.0)
            }
            Given::HitOnAnEdge => matches!(truth, Answer::Intersect(t)
                if t.hit.is_some_and(|h| h.barycentric.is_some_and(|b| b.contains(&0.0)))),
            Given::EngineNormalFacesTheStart => {
                matches!((segment, engine_hit), (Some(d), Some(h)) if dot(h.normal, d) < 0.0)
            }
            Given::MeshNotItsConvexHull => match (lc.meshes[1].as_ref(), &lc.case.a) {
                (Some(m), Shape::Sphere(s)) => !convex_closed(m) || strictly_inside(m, &s.center),
                (Some(m), _) => !convex_closed(m),
                _ => false,
            },
            Given::EngineTimeEarlyByAtMost(x) => {
                let early = |a: f64, t: f64| a <= t && t - a <= x * lc.case.t_max();
                match (answer, truth) {
                    (Answer::Toi(a), Answer::Toi(t)) => match (a.toi, t.toi) {
                        (Some(a), Some(t)) => early(a.t, t.t),
                        _ => false,
                    },
                    (Answer::Ccd(a), Answer::Ccd(t)) => match (a.t, t.t) {
                        (Some(a), Some(t)) => early(a, t),
                        _ => false,
                    },
                    _ => false,
                }
            }
            Given::EngineHitOutsideByAtMost(x) => {
                let (Some(Shape::Triangle(t)), Some(h)) = (&lc.case.b, engine_hit) else { return false };
                let [v0, v1, v2] = t.vertices;
                let n = cross(sub(v1, v0), sub(v2, v0));
                let nn = dot(n, n);
                // Signed barycentric of each vertex: the sub-triangle opposite it
                // against the whole, along the face normal.
                let coords = [
                    dot(cross(sub(v1, h.point), sub(v2, h.point)), n) / nn,
                    dot(cross(sub(v2, h.point), sub(v0, h.point)), n) / nn,
                    dot(cross(sub(v0, h.point), sub(v1, h.point)), n) / nn,
                ];
                nn > 0.0 && coords.iter().all(|c| *c >= -x)
            }
        }
    }
}

/// The signed side of `p` from face `f`'s plane, `((v1 − v0) × (v2 − v0)) ·
/// (p − v0)`, in f64.
fn side(m: &crate::mesh::Mesh, f: &[usize; 3], p: &crashtest_core::geom::P3) -> f64 {
    use crashtest_core::vec3::{cross, dot, sub};
    let [v0, v1, v2] = f.map(|i| m.vertices[i]);
    dot(cross(sub(v1, v0), sub(v2, v0)), sub(*p, v0))
}

/// Whether a mesh is the closed surface of a convex solid: every edge shared by
/// exactly two faces, every vertex used, no zero-area face, and no vertex
/// strictly on both sides of any face's plane.
fn convex_closed(m: &crate::mesh::Mesh) -> bool {
    use crashtest_core::vec3::{cross, dot, sub};
    let mut edges: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let mut used = vec![false; m.vertices.len()];
    for f in &m.triangles {
        let [v0, v1, v2] = f.map(|i| m.vertices[i]);
        let n = cross(sub(v1, v0), sub(v2, v0));
        if dot(n, n) == 0.0 {
            return false;
        }
        for k in 0..3 {
            used[f[k]] = true;
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    if m.triangles.is_empty() || used.contains(&false) || edges.values().any(|&n| n != 2) {
        return false;
    }
    m.triangles.iter().all(|f| {
        let sides: Vec<f64> = m.vertices.iter().map(|p| side(m, f, p)).collect();
        !(sides.iter().any(|s| *s > 0.0) && sides.iter().any(|s| *s < 0.0))
    })
}

/// Whether `p` lies strictly inside a closed convex mesh: strictly on the side
/// of every face's plane that the rest of the mesh is on.
fn strictly_inside(m: &crate::mesh::Mesh, p: &crashtest_core::geom::P3) -> bool {
    m.triangles.iter().all(|f| {
        let inner = m.vertices.iter().map(|v| side(m, f, v)).find(|s| *s != 0.0).unwrap_or(0.0);
        let s = side(m, f, p);
        inner != 0.0 && s != 0.0 && (s > 0.0) == (inner > 0.0)
    })
}

/// A `crashtest-known/1` file.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct KnownFile {
    /// Always `crashtest-known/1`.
    pub schema: String,
    /// The rules, in the order they are tried.
    pub known: Vec<DataRule>,
}

/// The schema name of a known-divergences file.
pub const KNOWN_SCHEMA: &str = "crashtest-known/1";

/// The comparisons a condition may make.
const COMPARISONS: [&str; 5] = ["<", "<=", ">", ">=", "!="];

/// Reads a `crashtest-known/1` file; the error names the file and the field
/// (line and column for JSON syntax).
pub fn load_known(path: &Path) -> Result<Vec<DataRule>, String> {
    let at = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{at}: cannot read: {e}"))?;
    let de = &mut serde_json::Deserializer::from_str(&text);
    let file: KnownFile = serde_path_to_error::deserialize(de).map_err(|e| {
        let field = e.path().to_string();
        let inner = e.into_inner();
        if inner.is_syntax() || inner.is_eof() {
            format!("{at}: line {} column {}: {inner}", inner.line(), inner.column())
        } else {
            format!("{at}: field `{field}`: {inner}")
        }
    })?;
    if file.schema != KNOWN_SCHEMA {
        return Err(format!("{at}: field `schema`: `{}`, expected `{KNOWN_SCHEMA}`", file.schema));
    }
    for (i, r) in file.known.iter().enumerate() {
        if crashtest_core::pair::Pair::find(r.query, r.a, r.b).is_none() {
            let b = r.b.map_or("nothing", ShapeKind::as_str);
            return Err(format!(
                "{at}: field `known[{i}]`: {} of {} and {b} is not a pair of the table",
                r.query.as_str(),
                r.a.as_str()
            ));
        }
        if r.pinned_by.is_empty() {
            return Err(format!("{at}: field `known[{i}].pinned_by`: a known divergence needs a case that shows it"));
        }
        for (side, conds) in [("engine", &r.engine), ("referee", &r.referee)] {
            for (path, cond) in conds {
                for (op, _) in comparisons(cond).unwrap_or_default() {
                    if !COMPARISONS.contains(&op) {
                        return Err(format!(
                            "{at}: field `known[{i}].{side}.{path}`: `{op}` is not a comparison ({})",
                            COMPARISONS.join(" ")
                        ));
                    }
                }
            }
        }
    }
    Ok(file.known)
}

/// A condition written as comparisons, every one of which must hold:
/// `{">=": -1e-12, "<": 0}` (an object whose keys are operators: no letter or
/// digit). `None` for a value to equal.
fn comparisons(cond: &serde_json::Value) -> Option<Vec<(&str, &serde_json::Value)>> {
    let m = cond.as_object()?;
    let ops: Vec<(&str, &serde_json::Value)> = m.iter().map(|(k, v)| (k.as_str(), v)).collect();
    (!ops.is_empty() && ops.iter().all(|(k, _)| !k.chars().any(char::is_alphanumeric))).then_some(ops)
}

/// Equality of JSON values, numbers compared as f64 (`0` equals `0.0`).
fn same(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    use serde_json::Value as V;
    match (a, b) {
        (V::Number(x), V::Number(y)) => x.as_f64() == y.as_f64(),
        (V::Array(x), V::Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(x, y)| same(x, y)),
        (V::Object(x), V::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

/// The value at a dotted path of an answer's wire form (`null` when absent).
fn at_path<'v>(v: &'v serde_json::Value, path: &str) -> &'v serde_json::Value {
    path.split('.')
        .try_fold(v, |v, k| match v {
            serde_json::Value::Object(m) => m.get(k),
            serde_json::Value::Array(a) => k.parse::<usize>().ok().and_then(|i| a.get(i)),
            _ => None,
        })
        .unwrap_or(&serde_json::Value::Null)
}

/// Whether `got` meets `cond`: equality (numbers compared as f64), or every
/// comparison written.
fn holds(got: &serde_json::Value, cond: &serde_json::Value) -> bool {
    match comparisons(cond) {
        None => same(got, cond),
        Some(ops) => ops.iter().all(|&(op, want)| match (op, got.as_f64(), want.as_f64()) {
            ("!=", _, _) => !same(got, want),
            ("<", Some(x), Some(y)) => x < y,
            ("<=", Some(x), Some(y)) => x <= y,
            (">", Some(x), Some(y)) => x > y,
            (">=", Some(x), Some(y)) => x >= y,
            _ => false,
        }),
    }
}

impl DataRule {
    /// Whether it explains this disagreement.
    pub fn explains(&self, lc: &LoadedCase, answer: &Answer, truth: &Answer, reasons: &[String]) -> bool {
        let pair = lc.case.pair();
        if pair.is_none() || pair != crashtest_core::pair::Pair::find(self.query, self.a, self.b) {
            return false;
        }
        if !self.reasons.is_empty() && !reasons.iter().all(|r| self.reasons.iter().any(|p| r.starts_with(p.as_str()))) {
            return false;
        }
        let wire = |a: &Answer| serde_json::to_value(WireAnswer::of(a)).unwrap_or(serde_json::Value::Null);
        let (got, want) = (wire(answer), wire(truth));
        self.engine.iter().all(|(p, c)| holds(at_path(&got, p), c))
            && self.referee.iter().all(|(p, c)| holds(at_path(&want, p), c))
            && self.given.iter().all(|g| g.holds(lc, answer, truth))
    }
}

fn shapes(lc: &LoadedCase) -> (&'static str, Option<&'static str>) {
    (lc.case.a.kind(), lc.case.b.as_ref().map(Shape::kind))
}

/// A segment starting inside `b` of kind `kind`, answered at `t = 0` with a
/// zero normal where the referee also hits at `t = 0`, and disagreeing only
/// in the normal and the flag.
fn starts_inside_with_no_normal(lc: &LoadedCase, a: &Answer, t: &Answer, reasons: &[String], kind: &str) -> bool {
    let zero = |n: &[f64; 3]| n.iter().all(|x| *x == 0.0);
    matches!((a, t), (Answer::Intersect(a), Answer::Intersect(t))
        if shapes(lc).1 == Some(kind)
            && a.hit.is_some_and(|h| h.t == 0.0 && zero(&h.normal))
            && t.hit.is_some_and(|h| h.t == 0.0))
        && !reasons.is_empty()
        && reasons.iter().all(|r| r.starts_with("normal") || r.starts_with("degenerate"))
}

/// parry3d-f64 and parry3d: the divergences `oracle::parry` documents.
pub const PARRY: Known = Known::rules(&[
    Rule {
        parry_what: Some("segment–box: a segment starting in the box"),
        reason: "",
        explains: |lc, a, t, reasons| starts_inside_with_no_normal(lc, a, t, reasons, "box"),
    },
    Rule {
        parry_what: Some("segment–capsule: a segment starting in the capsule"),
        reason: "",
        explains: |lc, a, t, reasons| starts_inside_with_no_normal(lc, a, t, reasons, "capsule"),
    },
    Rule {
        parry_what: Some("sphere–box: a centre tied between faces"),
        reason: "",
        explains: |lc, a, t, reasons| {
            matches!((a, t), (Answer::Contact(a), Answer::Contact(t))
                if shapes(lc) == ("sphere", Some("box")) && !a.degenerate && t.degenerate
                    && a.contact.is_some_and(|c| c.normal.iter().any(|x| *x != 0.0)))
                && !reasons.is_empty()
                && reasons.iter().all(|r| r.starts_with("degenerate"))
        },
    },
    Rule {
        parry_what: Some("distance: witnesses that are not unique"),
        reason: "",
        explains: |_, a, t, reasons| {
            matches!((a, t), (Answer::Distance(a), Answer::Distance(t)) if !a.degenerate && t.degenerate)
                && !reasons.is_empty()
                && reasons.iter().all(|r| r.starts_with("degenerate"))
        },
    },
    Rule {
        parry_what: Some("sphere–sphere: exactly touching"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Contact(a), Answer::Contact(t))
                if shapes(lc) == ("sphere", Some("sphere")) && a.contact.is_none()
                    && t.contact.is_some_and(|c| c.depth == 0.0))
        },
    },
    Rule {
        parry_what: Some("sphere–sphere, concentric"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Contact(a), Answer::Contact(t))
                if shapes(lc) == ("sphere", Some("sphere")) && a.degenerate && t.degenerate)
        },
    },
    Rule {
        parry_what: Some("sphere–triangle: a centre within"),
        reason: "",
        explains: |lc, a, t, _| {
            let pair = shapes(lc);
            matches!((a, t), (Answer::Contact(a), Answer::Contact(t))
                if (pair == ("sphere", Some("triangle")) || pair == ("triangle", Some("sphere")))
                    && a.degenerate && !t.degenerate)
        },
    },
    Rule {
        parry_what: Some("segment–triangle: a segment parallel"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Intersect(a), Answer::Intersect(t))
                if shapes(lc).1 == Some("triangle") && t.parallel && !a.parallel && a.hit.is_none())
        },
    },
    Rule {
        parry_what: Some("segment–plane: a missing segment"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Intersect(a), Answer::Intersect(t))
                if shapes(lc).1 == Some("plane") && a.parallel && !t.parallel
                    && t.hit.is_none() && a.hit.is_none())
        },
    },
    Rule {
        parry_what: Some("a point whose projection lies outside"),
        reason: "",
        explains: |_, _, t, _| matches!(t, Answer::Barycentric(t) if t.coords.iter().any(|x| *x < 0.0)),
    },
    Rule {
        parry_what: Some("bounding sphere: centroid"),
        reason: "",
        explains: |lc, _, _, reasons| lc.case.query == Query::Bounds && only_radius(reasons),
    },
    Rule {
        parry_what: Some("segment–mesh: a hit exactly at the segment's end"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Intersect(a), Answer::Intersect(t))
                if shapes(lc).1 == Some("mesh") && a.hit.is_none() && t.hit.is_some_and(|h| h.t >= 1.0))
        },
    },
    Rule {
        parry_what: Some("segment–mesh: a segment through an edge or vertex shared"),
        reason: "",
        explains: |lc, a, t, reasons| {
            let other_face = match (a, t) {
                (Answer::Intersect(a), Answer::Intersect(t)) => {
                    matches!((a.hit, t.hit), (Some(x), Some(y)) if x.triangle != y.triangle)
                }
                _ => false,
            };
            // Same t and point: only the face's own values (normal,
            // barycentrics) differ.
            shapes(lc).1 == Some("mesh")
                && other_face
                && !reasons.is_empty()
                && reasons.iter().all(|r| r.starts_with("normal off") || r.starts_with("barycentric off"))
        },
    },
    Rule {
        parry_what: Some("segment–mesh: a segment parallel to every face"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Intersect(a), Answer::Intersect(t))
                if shapes(lc).1 == Some("mesh") && t.parallel && !a.parallel && a.hit.is_none())
        },
    },
    Rule {
        parry_what: Some("sphere–sphere cast, overlapping at t = 0"),
        reason: "",
        explains: |lc, a, t, _| {
            matches!((a, t), (Answer::Toi(a), Answer::Toi(t))
                if shapes(lc) == ("sphere", Some("sphere"))
                    && a.toi.is_some_and(|x| x.t == 0.0) && t.toi.is_some_and(|x| x.t == 0.0))
        },
    },
    Rule {
        parry_what: Some("sphere–triangle cast hitting at 0 < t < 1e-4"),
        reason: "",
        explains: |lc, _, t, _| {
            matches!(t, Answer::Toi(t)
                if shapes(lc) == ("sphere", Some("triangle")) && t.toi.is_some_and(|x| x.t > 0.0 && x.t < 1e-4))
        },
    },
]);

/// collide's lecture methods (both precisions): where the lecture's definition is
/// not the format's.
pub const LECTURE: Known = Known::rules(&[
    Rule {
        parry_what: None,
        reason: "the lecture's bounding sphere (centroid and largest distance) encloses the points \
                 but is not the minimal sphere the format's bounds query reports",
        explains: |lc, _, _, reasons| lc.case.query == Query::Bounds && only_radius(reasons),
    },
    Rule {
        parry_what: None,
        reason: "the lecture's barycentrics are unsigned area ratios of the point itself: outside \
                 the triangle (or off its plane) they are not the signed coordinates of the \
                 projection that the format asks for",
        explains: |lc, _, t, _| {
            lc.case.query == Query::Barycentric
                && match (&lc.case.a, t) {
                    (Shape::Point(p), Answer::Barycentric(t)) => {
                        t.coords.iter().any(|x| *x < 0.0) || off_plane(&p.at, lc)
                    }
                    _ => false,
                }
        },
    },
]);

fn only_radius(reasons: &[String]) -> bool {
    !reasons.is_empty() && reasons.iter().all(|r| r.starts_with("bounding radius"))
}

/// Whether the point is off the plane of the case's triangle (exactly: any
/// non-zero distance; the rule only explains a disagreement that already exists).
fn off_plane(p: &[f64; 3], lc: &LoadedCase) -> bool {
    let Some(Shape::Triangle(t)) = &lc.case.b else { return false };
    let [v0, v1, v2] = t.vertices;
    let u = [v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]];
    let v = [v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]];
    let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    let w = [p[0] - v0[0], p[1] - v0[1], p[2] - v0[2]];
    n[0] * w[0] + n[1] * w[1] + n[2] * w[2] != 0.0
}

fn reason_of(rule: &Rule, engine: &str) -> Option<String> {
    match rule.parry_what {
        None => Some(rule.reason.to_string()),
        Some(prefix) => parry_entries()
            .find(|d| d.engine == engine && d.what.starts_with(prefix))
            .map(|d| format!("{} ({})", d.what, d.reason)),
    }
}

/// Every divergence parry's adapters document: queries and casts.
fn parry_entries() -> impl Iterator<Item = &'static KnownDivergence> {
    known_divergences().iter().chain(cast_known_divergences())
}

impl Known {
    /// The known divergence of these that explains the disagreement of the
    /// engine called `engine` on this case, if any: its documented reason.
    pub fn explain(
        &self,
        engine: &str,
        lc: &LoadedCase,
        answer: &Answer,
        truth: &Answer,
        reasons: &[String],
    ) -> Option<String> {
        if let Some(r) = self.data_rules().iter().find(|r| r.explains(lc, answer, truth, reasons)) {
            return Some(format!("{} ({})", r.what, r.reason));
        }
        self.rules.iter().find(|r| (r.explains)(lc, answer, truth, reasons)).and_then(|r| reason_of(r, engine))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oracle::parry::{Parry32, Parry64};

    const PARRY_NAMES: [&str; 2] = [Parry64::NAME, Parry32::NAME];

    #[test]
    fn every_parry_rule_names_an_entry_parry_still_lists_for_both_engines() {
        for rule in PARRY.rules.iter().filter(|r| r.parry_what.is_some()) {
            for engine in PARRY_NAMES {
                assert!(reason_of(rule, engine).is_some(), "{engine}: no known divergence {:?}", rule.parry_what);
            }
        }
    }

    #[test]
    fn every_parry_entry_has_a_rule() {
        for d in parry_entries() {
            let covered = PARRY_NAMES.contains(&d.engine)
                && PARRY.rules.iter().any(|r| r.parry_what.is_some_and(|w| d.what.starts_with(w)));
            assert!(covered, "{}: no rule for {:?}", d.engine, d.what);
        }
    }

    #[test]
    fn the_rules_go_with_the_engines_that_have_them() {
        for e in crate::engines::judged() {
            let want = if PARRY_NAMES.contains(&e.name.as_str()) {
                PARRY.rules.len()
            } else if e.name.ends_with("/lecture") {
                LECTURE.rules.len()
            } else {
                0
            };
            assert_eq!(e.known.rules.len(), want, "{}", e.name);
        }
    }

    fn case(json: &str) -> LoadedCase {
        let mut out = crate::load::Loaded::default();
        let text = format!(r#"{{"schema": "crashtest-fixture/1", "cases": [{json}]}}"#);
        crate::load::load_str_into(Path::new("test.json"), &text, &mut out);
        assert!(out.errors.is_empty(), "{:?}", out.errors);
        out.cases.remove(0)
    }

    fn contact(depth: Option<f64>, degenerate: bool) -> Answer {
        use crashtest_core::geom::{Contact, ContactAnswer};
        Answer::Contact(ContactAnswer {
            contact: depth.map(|depth| Contact { point: [0.0; 3], normal: [0.0, 0.0, 1.0], depth }),
            degenerate,
        })
    }

    fn rules(json: &str) -> Result<Vec<DataRule>, String> {
        let dir = std::env::temp_dir().join(format!("crashtest-known-{}", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        // One file per call: tests run side by side in one process, and two
        // texts of one length (a schema `/1` and `/2`) must not share a file.
        static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let n = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let path = dir.join(format!("known-{n}.json"));
        std::fs::write(&path, json).map_err(|e| e.to_string())?;
        load_known(&path)
    }

    const TOUCHING: &str = r#"{"schema": "crashtest-known/1", "known": [{
        "what": "touching spheres: no contact", "reason": "the engine reports penetration only",
        "query": "contact", "a": "sphere", "b": "sphere",
        "reasons": ["missed contact"], "engine": {"contact": null}, "referee": {"contact.depth": {"<=": 0}},
        "pinned_by": ["touching"]}]}"#;

    #[test]
    fn a_data_rule_explains_only_its_pair_reasons_and_conditions() {
        let known = Known::data(rules(TOUCHING).expect("reads"));
        let spheres = case(
            r#"{"name": "touching", "query": "contact", "a": {"sphere": {"center": [0,0,2], "radius": 1}}, "b": {"sphere": {"center": [0,0,0], "radius": 1}}}"#,
        );
        let missed = ["missed contact (referee: touching)".to_string()];
        let why = known.explain("x", &spheres, &contact(None, false), &contact(Some(0.0), false), &missed);
        assert_eq!(why.as_deref(), Some("touching spheres: no contact (the engine reports penetration only)"));
        // Another reason, a referee that is not touching, an engine that answered: not explained.
        let other = ["point off by 1 (allowed 1e-9)".to_string()];
        assert!(known.explain("x", &spheres, &contact(None, false), &contact(Some(0.0), false), &other).is_none());
        assert!(known.explain("x", &spheres, &contact(None, false), &contact(Some(0.5), false), &missed).is_none());
        assert!(
            known.explain("x", &spheres, &contact(Some(0.0), false), &contact(Some(0.0), false), &missed).is_none()
        );
        // Another pair: not explained.
        let plane = case(
            r#"{"name": "p", "query": "contact", "a": {"sphere": {"center": [0,0,1], "radius": 1}}, "b": {"plane": {"normal": [0,0,1], "offset": 0}}}"#,
        );
        assert!(known.explain("x", &plane, &contact(None, false), &contact(Some(0.0), false), &missed).is_none());
    }

    #[test]
    fn a_bad_known_file_is_refused_naming_the_field() {
        let err = rules(&TOUCHING.replace(r#""<=""#, r#""~""#)).expect_err("unknown comparison");
        assert!(err.contains("known[0].referee.contact.depth") && err.contains("`~` is not a comparison"), "{err}");
        let err = rules(&TOUCHING.replace(r#""b": "sphere""#, r#""b": "point""#)).expect_err("no such pair");
        assert!(err.contains("known[0]") && err.contains("not a pair of the table"), "{err}");
        let err = rules(&TOUCHING.replace(r#"["touching"]"#, "[]")).expect_err("unpinned");
        assert!(err.contains("known[0].pinned_by"), "{err}");
        let err = rules(&TOUCHING.replace(r#""reason""#, r#""reasn""#)).expect_err("unknown key");
        assert!(err.contains("known[0]") && err.contains("reasn"), "{err}");
        let err = rules(&TOUCHING.replace("crashtest-known/1", "crashtest-known/2")).expect_err("schema");
        assert!(err.contains("field `schema`"), "{err}");
        let err = rules("{\"schema\": ").expect_err("syntax");
        assert!(err.contains("line 1 column"), "{err}");
    }
}
