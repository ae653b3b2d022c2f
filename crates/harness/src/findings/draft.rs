//! Bug-report drafts for a peer engine's findings: the minimal inputs, the
//! engine's answer, the exact answer, the engine's version, and a standalone
//! reproduction in the engine's own API.
//!
//! The reproduction comes from where the engine's conventions are written:
//! parry's from its adapter ([`oracle::parry::reproduce`]), a process
//! engine's from its hello (`reproductions`, docs/PROTOCOL.md), filled with
//! the shrunk case by [`fill`]. collide is crashtest's own library: its
//! findings get no upstream draft.

use super::model::Finding;
use crate::case::{Case, Query, Shape};
use crate::check::Truth;
use crate::engine::{Answer, Engine};
use crate::judge::tolerance::Tolerance;
use crate::load::LoadedCase;
use oracle::parry::reproduce as parry;
use serde_json::Value;
use std::fmt::Write;

pub use super::model::Reproduction;

/// A number list or number as a JSON literal, numbers in their shortest
/// round-trip form, with spaces after commas.
fn literal(v: &Value) -> String {
    match v {
        Value::Array(a) => format!("[{}]", a.iter().map(literal).collect::<Vec<_>>().join(", ")),
        Value::Number(n) => match n.as_f64() {
            Some(x) if n.is_f64() => {
                let s = format!("{x:?}");
                if s.contains('.') || s.contains('e') { s } else { format!("{s}.0") }
            }
            _ => n.to_string(),
        },
        other => other.to_string(),
    }
}

/// Fills a reproduction template's placeholders (`{{a.center}}`,
/// `{{b.vertices}}`, `{{t_max}}`, …) with the case's values as JSON
/// literals: an absent velocity is `[0.0, 0.0, 0.0]`, a box's absent rotation
/// `[1.0, 0.0, 0.0, 0.0]`, an absent `t_max` its default; a placeholder the case has no value for is left as it is, so the
/// program fails to run rather than run another case.
pub fn fill(template: &str, case: &Case) -> String {
    let shape_fields = |s: Option<&Shape>| -> Value {
        s.and_then(|s| serde_json::to_value(s).ok())
            .and_then(|v| v.as_object().and_then(|o| o.values().next().cloned()))
            .unwrap_or(Value::Null)
    };
    let (a, b) = (shape_fields(Some(&case.a)), shape_fields(case.b.as_ref()));
    let value = |key: &str| -> Option<String> {
        let key = key.trim();
        if key == "t_max" {
            return Some(literal(&serde_json::json!(case.t_max())));
        }
        if key == "restitution" {
            return case.restitution.map(|r| literal(&serde_json::json!(r)));
        }
        let (shape, field) = key.split_once('.')?;
        let fields = match shape {
            "a" => &a,
            "b" => &b,
            _ => return None,
        };
        match fields.get(field) {
            Some(v) => Some(literal(v)),
            None if field == "velocity" && !fields.is_null() => Some("[0.0, 0.0, 0.0]".into()),
            None if field == "rotation" && fields.get("half_extents").is_some() => Some("[1.0, 0.0, 0.0, 0.0]".into()),
            None => None,
        }
    };
    let mut out = String::new();
    let mut rest = template;
    while let Some(i) = rest.find("{{") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        match after.find("}}") {
            Some(j) => {
                let key = &after[..j];
                match value(key) {
                    Some(v) => out.push_str(&v),
                    None => {
                        let _ = write!(out, "{{{{{key}}}}}");
                    }
                }
                rest = &after[j + 2..];
            }
            None => {
                out.push_str(&rest[i..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// The version in an engine's version string (`parry3d-f64 0.31.1 …` → `0.31.1`).
fn version_number(v: &str) -> String {
    v.split_whitespace()
        .find(|w| w.chars().next().is_some_and(|c| c.is_ascii_digit()))
        .unwrap_or("*")
        .trim_end_matches(',')
        .to_string()
}

/// A parry reproduction of `lc`, when its pair has one.
fn parry_program(engine: &Engine, lc: &LoadedCase, truth: &Answer, tol: &Tolerance) -> Option<String> {
    let krate = if engine.name == oracle::parry::Parry64::NAME { "parry3d-f64" } else { "parry3d" };
    let version = version_number(engine.version.as_deref().unwrap_or(""));
    let allowed = crate::judge::allowed(lc, truth, tol);
    let allow = parry::Allowed {
        point: allowed.point,
        depth: allowed.depth,
        normal: allowed.normal,
        t: allowed.t,
        barycentric: allowed.barycentric,
    };
    // A case's shape `k` (0: a, 1: b) as parry builds it; a mesh from the
    // case as loaded.
    let shape = |s: &Shape, k: usize| -> Option<parry::Shape> {
        Some(match s {
            Shape::Sphere(s) => {
                parry::Shape::Sphere(crashtest_core::geom::Sphere { center: s.center, radius: s.radius })
            }
            Shape::Plane(p) => parry::Shape::Plane(crashtest_core::geom::Plane { normal: p.normal, offset: p.offset }),
            Shape::Triangle(t) => parry::Shape::Triangle(crashtest_core::geom::Triangle { vertices: t.vertices }),
            Shape::Mesh(_) => {
                let m = lc.meshes[k].as_ref()?;
                parry::Shape::Mesh(m.vertices.clone(), m.triangles.clone())
            }
            _ => return None,
        })
    };
    if let (Query::Bounds, Answer::Bounds(_)) = (lc.case.query, truth) {
        return Some(parry::bounds(krate, &version, &crate::load::bounded_points(lc), &allow));
    }
    let b = lc.case.b.as_ref()?;
    match (lc.case.query, truth) {
        (Query::Contact, Answer::Contact(w)) => {
            Some(parry::contact(krate, &version, &shape(&lc.case.a, 0)?, &shape(b, 1)?, w.contact.as_ref(), &allow))
        }
        (Query::Intersect, Answer::Intersect(w)) => {
            let Shape::Segment(s) = &lc.case.a else { return None };
            let seg = crashtest_core::geom::Segment { start: s.start, end: s.end };
            Some(parry::intersect(krate, &version, &seg, &shape(b, 1)?, w.hit.as_ref(), &allow))
        }
        (Query::Toi, Answer::Toi(w)) => {
            let Shape::Sphere(a) = &lc.case.a else { return None };
            let ball = crashtest_core::geom::Sphere { center: a.center, radius: a.radius };
            let (va, vb) = (lc.case.a.velocity(), b.velocity());
            Some(parry::toi(krate, &version, &ball, &va, &shape(b, 1)?, &vb, lc.case.t_max(), w.toi.as_ref(), &allow))
        }
        (Query::Overlap, Answer::Overlap(w)) => {
            let (Shape::Aabb(x), Shape::Aabb(y)) = (&lc.case.a, b) else { return None };
            let bx = |s: &crate::case::AabbSpec| crashtest_core::geom::Aabb { min: s.min, max: s.max };
            Some(parry::overlap(krate, &version, &bx(x), &bx(y), *w))
        }
        (Query::Barycentric, Answer::Barycentric(w)) => {
            let (Shape::Point(p), Shape::Triangle(t)) = (&lc.case.a, b) else { return None };
            let tri = crashtest_core::geom::Triangle { vertices: t.vertices };
            Some(parry::barycentric(krate, &version, &p.at, &tri, &w.coords, &allow))
        }
        _ => None,
    }
}

/// The standalone reproduction of `lc` for `engine`: parry's from its
/// adapter, a process engine's from its hello; `None` for collide, and for a
/// pair the engine gives no program for.
pub fn reproduction(engine: &Engine, lc: &LoadedCase, truth: &Truth) -> Option<Reproduction> {
    if let Some(p) = engine.process() {
        let hello = p.hello()?;
        let pair = lc.case.pair()?.row();
        let r = hello.reproductions.iter().find(|r| r.query == pair.query && r.a == pair.a && r.b == pair.b)?;
        return Some(Reproduction { language: r.language.clone(), code: fill(&r.script, &lc.case) });
    }
    if is_parry(engine) {
        let tol = Tolerance::for_precision(engine.precision_for(lc));
        return parry_program(engine, lc, truth.answer.as_ref()?, &tol)
            .map(|code| Reproduction { language: "rust".into(), code });
    }
    None
}

/// Whether the engine is parry (either precision), whose programs come from
/// its adapter.
pub fn is_parry(engine: &Engine) -> bool {
    engine.name == oracle::parry::Parry64::NAME || engine.name == oracle::parry::Parry32::NAME
}

/// Whether a finding's engine is a peer's (its findings get drafts): every
/// engine but crashtest's own collide.
pub fn is_peer(engine: &Engine) -> bool {
    !crate::engines::is_collide(engine)
}

/// The Markdown draft of a bug report for finding `f`: what is wrong and how
/// often, the minimal inputs, the engine's answer beside the exact one, the
/// engine's version, the reproduction, and the command that replays it.
pub fn markdown(f: &Finding, repro: Option<&Reproduction>) -> String {
    let mut out = String::new();
    let s = &f.signature;
    let _ = writeln!(out, "# {}: {} — {}\n", f.engines_label(), f.cause.pair, f.cause.class);
    let ways: Vec<String> = super::render::ways(f).iter().map(|(w, n)| format!("{w} ({n} cases)")).collect();
    let _ = writeln!(
        out,
        "**Engine**: {} · **query**: {} · **found in** {} of {} generated and hand-written cases ({}), \
         in {} case families; worst error {:.1e}, median {}. It shows as: {}.\n",
        if f.engine_version.is_empty() { s.engine.as_str() } else { f.engine_version.as_str() },
        s.pair,
        f.count,
        f.of_cases,
        super::render::percent(f.share()),
        f.families.len(),
        f.errors.max,
        f.errors.median().map_or_else(|| "–".into(), |m| format!("{m:.1e}")),
        ways.join("; ")
    );
    let (case, answer, reasons) = match (&f.shrunk, f.examples.first()) {
        (Some(sh), _) => (Some(&sh.case), sh.answer.clone(), sh.reasons.clone()),
        (None, Some(e)) => (Some(&e.fixture), e.answers.get(&s.engine).cloned(), e.reasons.clone()),
        (None, None) => (None, None, Vec::new()),
    };
    if let Some(case) = case {
        let mut inputs = case.clone();
        let exact = inputs.expect.take();
        let _ = writeln!(out, "## Inputs\n");
        if let Some(sh) = f.shrunk.as_ref().filter(|sh| sh.replayed < super::shrink::REPLAYS) {
            let _ = writeln!(
                out,
                "{} answers this case differently between calls: it showed the defect in {} of {} replays.\n",
                s.engine,
                sh.replayed,
                super::shrink::REPLAYS
            );
        }
        match &f.shrunk {
            Some(sh) if sh.cost.1 < sh.cost.0 => {
                let _ = writeln!(
                    out,
                    "Shrunk while the defect stayed the same: {} numbers to {}, simpler by crashtest's measure \
                     ({} → {}: fewer significant bits, exponents nearer 0, fewer distinct values).\n",
                    sh.numbers.0, sh.numbers.1, sh.cost.0, sh.cost.1
                );
            }
            _ => {
                let _ = writeln!(out, "The case as found (nothing simpler kept the defect).\n");
            }
        }
        let _ = writeln!(out, "```json\n{}\n```\n", serde_json::to_string_pretty(&inputs).unwrap_or_default());
        let _ = writeln!(out, "## What {} answers\n", s.engine);
        let _ = writeln!(out, "```json\n{}\n```\n", answer.map_or("no answer".into(), |a| json(&a)));
        let _ = writeln!(out, "## The exact answer\n");
        let _ = writeln!(
            out,
            "Correctly rounded from exact rational arithmetic (crashtest's referee), in the case format's \
             convention (docs/FORMAT.md: the normal points from `b` toward `a`, depth > 0 is penetration):\n"
        );
        let _ = writeln!(out, "```json\n{}\n```\n", exact.map_or("none".into(), |e| json(&e)));
        let _ = writeln!(out, "## What differs\n");
        for r in &reasons {
            let _ = writeln!(out, "- {r}");
        }
        out.push('\n');
    }
    let _ = writeln!(out, "## Reproduction\n");
    match repro {
        Some(r) => {
            let _ = writeln!(out, "Standalone, against {} alone:\n", f.engine_version);
            let _ = writeln!(out, "```{}\n{}```\n", r.language, r.code);
        }
        None => {
            let _ =
                writeln!(out, "{} gives no standalone program for {}; the replay below runs it.\n", s.engine, s.pair);
        }
    }
    let _ = writeln!(out, "With crashtest, from the report's folder:\n\n```sh\n{}\n```", f.replay_command("."));
    out
}

fn json<T: serde::Serialize>(v: &T) -> String {
    serde_json::to_string_pretty(v).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(text: &str) -> Case {
        serde_json::from_str(text).unwrap()
    }

    #[test]
    fn fill_writes_the_case_values_as_literals() {
        let c = case(
            r#"{"name":"n","query":"toi","a":{"sphere":{"center":[1,2.5,-0.0],"radius":0.1}},
                "b":{"plane":{"normal":[0,0,1],"offset":1e300}}}"#,
        );
        let t = "c = {{a.center}}; r = {{a.radius}}; v = {{a.velocity}}; n = {{b.normal}}; d = {{b.offset}}; \
                 t = {{t_max}}; x = {{b.nothing}}";
        assert_eq!(
            fill(t, &c),
            "c = [1.0, 2.5, -0.0]; r = 0.1; v = [0.0, 0.0, 0.0]; n = [0.0, 0.0, 1.0]; d = 1e300; t = 1.0; \
             x = {{b.nothing}}"
        );
    }

    #[test]
    fn fill_gives_a_box_without_rotation_the_identity() {
        let c = case(
            r#"{"name":"n","query":"overlap","a":{"box":{"center":[0,0,0],"half_extents":[1,2,3]}},
                "b":{"box":{"center":[1,0,0],"half_extents":[1,1,1],"rotation":[2,0,0,1]}}}"#,
        );
        assert_eq!(
            fill("qa = {{a.rotation}}; qb = {{b.rotation}}; h = {{a.half_extents}}", &c),
            "qa = [1.0, 0.0, 0.0, 0.0]; qb = [2.0, 0.0, 0.0, 1.0]; h = [1.0, 2.0, 3.0]"
        );
    }

    #[test]
    fn versions_are_read_from_version_strings() {
        assert_eq!(version_number("parry3d-f64 0.31.1 (f64)"), "0.31.1");
        assert_eq!(version_number("no version"), "*");
    }
}
