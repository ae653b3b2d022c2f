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

use crate::case::{Query, Shape};
use crate::load::LoadedCase;
use crashtest_core::engine::Answer;
use oracle::parry::{KnownDivergence, cast_known_divergences, known_divergences};

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
/// its own set; most have none).
#[derive(Clone, Copy)]
pub struct Known(pub &'static [Rule]);

impl Known {
    /// No known divergence: every disagreement stands.
    pub const NONE: Known = Known(&[]);
}

impl std::fmt::Debug for Known {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Known({} rules)", self.0.len())
    }
}

fn shapes(lc: &LoadedCase) -> (&'static str, Option<&'static str>) {
    (lc.case.a.kind(), lc.case.b.as_ref().map(Shape::kind))
}

/// parry3d-f64 and parry3d: the divergences `oracle::parry` documents.
pub const PARRY: Known = Known(&[
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
pub const LECTURE: Known = Known(&[
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
        self.0.iter().find(|r| (r.explains)(lc, answer, truth, reasons)).and_then(|r| reason_of(r, engine))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oracle::parry::{Parry32, Parry64};

    const PARRY_NAMES: [&str; 2] = [Parry64::NAME, Parry32::NAME];

    #[test]
    fn every_parry_rule_names_an_entry_parry_still_lists_for_both_engines() {
        for rule in PARRY.0.iter().filter(|r| r.parry_what.is_some()) {
            for engine in PARRY_NAMES {
                assert!(reason_of(rule, engine).is_some(), "{engine}: no known divergence {:?}", rule.parry_what);
            }
        }
    }

    #[test]
    fn every_parry_entry_has_a_rule() {
        for d in parry_entries() {
            let covered = PARRY_NAMES.contains(&d.engine)
                && PARRY.0.iter().any(|r| r.parry_what.is_some_and(|w| d.what.starts_with(w)));
            assert!(covered, "{}: no rule for {:?}", d.engine, d.what);
        }
    }

    #[test]
    fn the_rules_go_with_the_engines_that_have_them() {
        for e in crate::engines::judged() {
            let want = if PARRY_NAMES.contains(&e.name.as_str()) {
                PARRY.0.len()
            } else if e.name.ends_with("/lecture") {
                LECTURE.0.len()
            } else {
                0
            };
            assert_eq!(e.known.0.len(), want, "{}", e.name);
        }
    }
}
