//! A discrepancy's signature: what makes two discrepancies the same finding.
//!
//! Engine, query, shape pair in argument order, what is wrong (a false or
//! missed contact, hit, impact or overlap; which flag differs; which fields
//! exceed their allowance; how the engine failed), the case family, and the
//! error's magnitude class. Numbers never enter a signature: a reason's sizes
//! and a failure message's numbers are dropped, so the same defect at another
//! input has the same signature.

use crate::case::{Query, Shape};
use crate::check::{EngineResult, PANIC_REASON_PREFIX};
use crate::engine::Engine;
use crate::judge::{NON_FINITE, Verdict};
use crate::load::LoadedCase;
use serde::{Deserialize, Serialize};

/// What makes discrepancies one finding.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Signature {
    /// The engine.
    pub engine: String,
    /// The query kind.
    pub query: Query,
    /// The shape pair in argument order (`contact sphere–plane`).
    pub pair: String,
    /// What is wrong: `missed contact`, `normal, point off`, `failed: panic
    /// at src/x.rs:12`, … (numbers dropped).
    pub wrong: String,
    /// The case family: a generator family's name, `full range`, or `fixture`.
    pub family: String,
    /// The error's magnitude class ([`MAGNITUDE_CLASSES`]); empty for a
    /// misclassification or a failure, whose size is not an error's.
    pub magnitude: String,
}

/// The magnitude classes of a value error, by the case's headline error
/// (`judge::headline`: the largest relative error, radians for a normal):
/// upper bounds and names. Three decades apart at most: a class says whether
/// an answer is a rounding away (a few ulps to a millionth), noticeably off,
/// or wrong outright; finer classes would split one defect by its inputs.
pub const MAGNITUDE_CLASSES: [(f64, &str); 3] =
    [(1e-6, "error ≤ 1e-6"), (1e-2, "error 1e-6 to 1e-2"), (f64::INFINITY, "error > 1e-2")];

/// The magnitude class of a headline error.
pub fn magnitude_class(headline: f64) -> &'static str {
    MAGNITUDE_CLASSES.iter().find(|(hi, _)| headline <= *hi).map_or(MAGNITUDE_CLASSES[2].1, |(_, name)| name)
}

/// The case's family: the generator family named in a generated case's
/// `source` (`full range` for the full-range family, whose sub-families
/// share one score), or `fixture` for a hand-written case. A shrunk case
/// keeps its original's source after its own words, so it keeps the family.
pub fn family_of(lc: &LoadedCase) -> String {
    let s = &lc.case.source;
    if s.contains(crate::generate::FULL_RANGE_SOURCE) {
        return "full range".into();
    }
    match (s.find("generated: "), s.rfind(", family ")) {
        (Some(_), Some(i)) => s[i + ", family ".len()..].trim_end_matches(')').trim().to_string(),
        _ => "fixture".into(),
    }
}

/// A reason with its numbers dropped: every word holding a digit goes, and
/// what a comparison says of the referee (`(referee: apart)`) stays only as
/// far as it names the flag.
fn words(reason: &str) -> String {
    let kept: Vec<&str> = reason
        .split_whitespace()
        .filter(|w| !w.chars().any(|c| c.is_ascii_digit()))
        .map(|w| w.trim_matches(|c: char| c == ',' || c == ';'))
        .filter(|w| !w.is_empty())
        .collect();
    kept.join(" ")
}

/// One reason of a disagreement, as a signature names it: the field over its
/// allowance (`depth`, `hit point`, `aabb coordinate`), or the
/// classification (`false contact`, `parallel: true`, `bounding sphere misses
/// a point`), or a normal that is not unit (`normal not unit`).
fn reason_key(reason: &str) -> String {
    if let Some((field, _)) = reason.split_once(" off by ") {
        return words(field);
    }
    if reason.starts_with("bounding sphere misses point") {
        return "bounding sphere misses a point".into();
    }
    if reason.starts_with("normal not unit") {
        return "normal not unit".into();
    }
    // `false contact (referee: apart)`, `parallel: true (referee false)`,
    // `overlap: false (referee true)`.
    let head = reason.split(" (").next().unwrap_or(reason);
    words(head)
}

/// What is wrong, from a verdict: its reasons' keys, sorted and joined (the
/// classification first, then the fields off), or the failure's kind.
pub fn wrong_of(verdict: &Verdict) -> Option<String> {
    match verdict {
        Verdict::Disagree { reasons } => {
            let mut class: Vec<String> = Vec::new();
            let mut fields: Vec<String> = Vec::new();
            for r in reasons {
                let k = reason_key(r);
                let into = if r.contains(" off by ") { &mut fields } else { &mut class };
                if !into.contains(&k) {
                    into.push(k);
                }
            }
            class.sort();
            fields.sort();
            let mut parts = class;
            if !fields.is_empty() {
                parts.push(format!("{} off", fields.join(", ")));
            }
            Some(parts.join("; "))
        }
        Verdict::Failed { reason } => Some(failure_kind(reason)),
        Verdict::KnownDivergence { reason } => Some(format!("known: {}", words(first_sentence(reason)))),
        _ => None,
    }
}

/// A failure's kind: `non-finite answer`, `panic at <file>:<line>` (the
/// column and message dropped), or the engine's own message without its
/// numbers, cut at its first sentence.
pub fn failure_kind(reason: &str) -> String {
    if reason == NON_FINITE {
        return "failed: non-finite answer".into();
    }
    if let Some(rest) = reason.strip_prefix(PANIC_REASON_PREFIX) {
        // `src/x.rs:12:5: message` → `src/x.rs:12`.
        let mut parts = rest.splitn(3, ':');
        let (file, line) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
        return format!("failed: panic at {}:{line}", crate::check::crate_relative(file));
    }
    let text = words(first_sentence(reason));
    let text: String = text.chars().take(MAX_FAILURE_CHARS).collect();
    format!("failed: {text}")
}

/// A failure message is cut to this many characters in a signature: enough
/// for an exception's type and its message's gist.
const MAX_FAILURE_CHARS: usize = 80;

/// The text up to the first `. ` (a sentence's end), or all of it.
fn first_sentence(s: &str) -> &str {
    s.split(". ").next().unwrap_or(s).trim_end_matches('.')
}

/// The signature of one engine's result on one case, or `None` when it is
/// not a discrepancy (agree, borderline, unsupported) nor a known divergence.
/// `headline` is the case's headline error for that engine.
pub fn signature(lc: &LoadedCase, r: &EngineResult, headline: f64) -> Option<Signature> {
    let wrong = wrong_of(&r.verdict)?;
    // Only an answer of the right class whose values are off has an error's
    // size; a misclassification (flags included) or a failure has none.
    let magnitude = if matches!(r.verdict, Verdict::Disagree { .. }) && r.errors.misclass.is_none() {
        magnitude_class(headline).to_string()
    } else {
        String::new()
    };
    let known = matches!(r.verdict, Verdict::KnownDivergence { .. });
    Some(Signature {
        engine: r.engine.clone(),
        query: lc.case.query,
        pair: lc.case.pair().map_or_else(|| lc.case.query.to_string(), |p| p.label()),
        wrong,
        // A known divergence is one finding per rule and pair: its reason is
        // the documented convention, whatever the family.
        family: if known { String::new() } else { family_of(lc) },
        magnitude,
    })
}

impl Signature {
    /// A title that says it: `fcl: contact sphere–triangle: normal, point off
    /// (error > 1e-2; family grazing)`.
    pub fn title(&self) -> String {
        let mut extra = Vec::new();
        if !self.magnitude.is_empty() {
            extra.push(self.magnitude.clone());
        }
        if !self.family.is_empty() {
            extra.push(format!("family {}", self.family));
        }
        let tail = if extra.is_empty() { String::new() } else { format!(" ({})", extra.join("; ")) };
        format!("{}: {}: {}{tail}", self.engine, self.pair, self.wrong)
    }

    /// A file name for it: lower-case letters, digits and `-`, from the
    /// engine, pair, what is wrong, the family and the magnitude class.
    pub fn slug(&self) -> String {
        slugify(&format!("{} {} {} {} {}", self.engine, self.pair, self.wrong, self.family, self.magnitude))
    }

    /// Whether two signatures are the same apart from the family (a shrunk
    /// case is judged by this: its family is its original's by construction).
    pub fn same_defect(&self, other: &Signature) -> bool {
        (&self.engine, self.query, &self.pair, &self.wrong, &self.magnitude)
            == (&other.engine, other.query, &other.pair, &other.wrong, &other.magnitude)
    }
}

/// A root cause: what makes discrepancies one finding. One defect shows in
/// several ways — parry's ball–half-space contact gives false contacts,
/// missed contacts and wrong depths, in every family — so a finding is the
/// engine's source code, the pair in argument order, and the class of what is
/// wrong:
///
/// - wrong answers (a false or missed contact, hit, impact or overlap, or
///   values off), or wrong flags only (`degenerate`, `parallel`): per pair;
/// - a non-finite answer: per pair;
/// - one named failure (a panic at one place, a crash, the engine's own
///   message): one cause wherever it occurs, every pair at once;
/// - inputs beyond the engine's precision ([`BEYOND_PRECISION`], every pair at
///   once, see [`beyond_precision`]), for that engine alone.
///
/// Engines that are builds of one source code in two precisions
/// ([`crate::engine::Engine::build_of`]) share every cause but their
/// precision's: the same defect seen through both is one finding. The finer
/// [`Signature`]s are its variants.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Cause {
    /// The engine's source code: the engine's name, or the engine it is a
    /// build of ([`crate::engine::Engine::source`]); the engine itself for
    /// [`BEYOND_PRECISION`].
    pub engine: String,
    /// The query kind (none for a cause over every pair).
    pub query: Option<Query>,
    /// The pair in argument order, or [`EVERY_PAIR`].
    pub pair: String,
    /// What is wrong: [`WRONG_ANSWERS`], [`WRONG_FLAGS`], [`BEYOND_PRECISION`],
    /// `failed: …`, or `known: …` for a known divergence.
    pub class: String,
}

/// The pair of a cause over every pair.
pub const EVERY_PAIR: &str = "every pair";
/// The class of false or missed contacts, hits, impacts and overlaps, and of
/// values off.
pub const WRONG_ANSWERS: &str = "wrong answers";
/// The class of answers whose only fault is a flag.
pub const WRONG_FLAGS: &str = "wrong flags";
/// The class of cases beyond the engine's precision ([`beyond_precision`]).
pub const BEYOND_PRECISION: &str = "inputs beyond its precision";
/// The failure kind that is no one failure's: an answer with a NaN or an
/// infinity, a cause per pair.
const NON_FINITE_KIND: &str = "failed: non-finite answer";

/// The degree of the products a pair's formulas form from its inputs: 4 for
/// a pair with a triangle or a mesh (a face's squared normal length
/// `|(b − a) × (c − a)|²`) and for a time of impact (the discriminant `b² −
/// a·c` of a quadratic whose `b` is already a dot product); 2 for every other
/// pair (squared lengths and dot products).
pub fn pair_degree(lc: &LoadedCase) -> i32 {
    let kinds = [Some(&lc.case.a), lc.case.b.as_ref()];
    let triangles = kinds.iter().flatten().any(|s| matches!(s, Shape::Triangle(_) | Shape::Mesh(_)));
    if triangles || lc.case.query == Query::Toi { 4 } else { 2 }
}

/// The factor by which the squared length of a difference of two input
/// points can exceed the square of the largest input magnitude `M`:
/// `|b − a|² ≤ 3 · (2M)² = 12 M²`.
const DIFFERENCE_SQUARED: f64 = 12.0;

/// Whether the case is beyond the precision of an engine of `bits` bits of
/// mantissa (53: `f64`, 24: `f32`; no other precision is judged so):
///
/// - its products of the pair's degree `d` ([`pair_degree`]) leave the
///   type's normal range: with `M` the largest input magnitude and `m` the
///   smallest non-zero one, `(12 M²)^(d/2)` (a difference's squared length,
///   to the degree) overflows, or `m^d` falls below the smallest normal
///   number. The pair's formulas cannot be evaluated in the type without
///   scaling; numbers the type cannot hold at all (`f32` rounding them to 0
///   or ∞) are among them;
/// - or, for `f32`, `rounding_explains`: the engine's answer agrees with the
///   exact answer to the inputs rounded to `f32`
///   ([`crate::check::EngineResult::rounding_explains`]).
pub fn beyond_precision(lc: &LoadedCase, bits: u32, rounding_explains: bool) -> bool {
    let (max, min) = match bits {
        53 => (f64::MAX, f64::MIN_POSITIVE),
        24 => (f64::from(f32::MAX), f64::from(f32::MIN_POSITIVE)),
        _ => return false,
    };
    if bits == 24 && rounding_explains {
        return true;
    }
    let Ok(v) = serde_json::to_value(&lc.case) else { return false };
    let (mut big, mut small) = (0.0f64, f64::INFINITY);
    let mut seen = |x: f64| {
        if x != 0.0 && x.is_finite() {
            big = big.max(x.abs());
            small = small.min(x.abs());
        }
    };
    crate::case::input_number_paths(&v)
        .iter()
        .filter_map(|p| v.pointer(p).and_then(serde_json::Value::as_f64))
        .for_each(&mut seen);
    lc.meshes.iter().flatten().flat_map(|m| m.vertices.iter().flatten()).for_each(|&x| seen(x));
    let d = f64::from(pair_degree(lc));
    // In logarithms, which neither overflow nor underflow.
    let (lmax, lmin) = (max.log2(), min.log2());
    big > 0.0 && ((d / 2.0) * (DIFFERENCE_SQUARED.log2() + 2.0 * big.log2()) > lmax || d * small.log2() < lmin)
}

/// A panic's place in a dependency without the crate's folder
/// (`failed: panic at parry3d-0.31.1/src/q.rs:100` → `failed: panic at
/// src/q.rs:100`): builds of one source code in two precisions are two crates
/// of one code, and the cause already names the source. Any other kind is
/// kept as it is.
fn without_crate_folder(kind: &str) -> String {
    let prefix = "failed: panic at ";
    if let Some(rest) = kind.strip_prefix(prefix)
        && let Some((folder, path)) = rest.split_once('/')
        && folder.rsplit_once('-').is_some_and(|(_, v)| v.starts_with(|c: char| c.is_ascii_digit()))
    {
        return format!("{prefix}{path}");
    }
    kind.to_string()
}

/// The cause of a discrepancy of signature `sig` on `lc`: `r` is the result
/// that showed it, `engine` the engine that gave it (its precision and source;
/// without it, an `f64` engine of its own code).
pub fn cause_of(sig: &Signature, lc: &LoadedCase, engine: Option<&Engine>, r: &EngineResult) -> Cause {
    let known = matches!(r.verdict, Verdict::KnownDivergence { .. });
    let source = engine.map_or(sig.engine.as_str(), |e| e.source()).to_string();
    let failed = sig.wrong.starts_with("failed: ");
    let named_failure = failed && sig.wrong != NON_FINITE_KIND;
    if known {
        return Cause { engine: source, query: Some(sig.query), pair: sig.pair.clone(), class: sig.wrong.clone() };
    }
    if named_failure {
        return Cause { engine: source, query: None, pair: EVERY_PAIR.into(), class: without_crate_folder(&sig.wrong) };
    }
    let precision = engine.and_then(|e| e.precision_for(lc)).unwrap_or(53);
    if beyond_precision(lc, precision, r.rounding_explains) {
        return Cause {
            engine: sig.engine.clone(),
            query: None,
            pair: EVERY_PAIR.into(),
            class: BEYOND_PRECISION.into(),
        };
    }
    let class = if failed {
        sig.wrong.clone()
    } else if sig.wrong.split("; ").all(|p| p.starts_with("degenerate:") || p.starts_with("parallel:")) {
        WRONG_FLAGS.into()
    } else {
        WRONG_ANSWERS.into()
    };
    Cause { engine: source, query: Some(sig.query), pair: sig.pair.clone(), class }
}

/// Text as a file name: lower-case letters, digits and single `-`, at most
/// [`MAX_SLUG_CHARS`] characters.
pub fn slugify(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        let c = match c {
            'a'..='z' | '0'..='9' => c,
            'A'..='Z' => c.to_ascii_lowercase(),
            '≤' => 'l',
            '>' => 'g',
            _ => '-',
        };
        if !(c == '-' && (out.is_empty() || out.ends_with('-'))) {
            out.push(c);
        }
    }
    let out = out.trim_end_matches('-');
    out.chars().take(MAX_SLUG_CHARS).collect::<String>().trim_end_matches('-').to_string()
}

/// A finding's file name is cut to this many characters (file systems take
/// 255; a report's path should stay readable).
const MAX_SLUG_CHARS: usize = 120;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_leave_the_signature() {
        let a = Verdict::Disagree { reasons: vec!["depth off by 1.2e-3 (allowed 1e-9)".into()] };
        let b = Verdict::Disagree { reasons: vec!["depth off by 4.0e+7 (allowed 2.5e-3)".into()] };
        assert_eq!(wrong_of(&a), wrong_of(&b));
        assert_eq!(wrong_of(&a).unwrap(), "depth off");
        let aabb = Verdict::Disagree { reasons: vec!["aabb coordinate 1.5e0 off by 1e-3 (allowed 1e-9)".into()] };
        assert_eq!(wrong_of(&aabb).unwrap(), "aabb coordinate off");
    }

    #[test]
    fn a_misclassification_comes_first_and_fields_are_sorted() {
        let v = Verdict::Disagree {
            reasons: vec![
                "parallel: true (referee false)".into(),
                "t off by 1e-3 (allowed 1e-9)".into(),
                "hit point off by 1e-3 (allowed 1e-9)".into(),
            ],
        };
        assert_eq!(wrong_of(&v).unwrap(), "parallel: true; hit point, t off");
        let missed = Verdict::Disagree { reasons: vec!["missed contact (referee: touching)".into()] };
        assert_eq!(wrong_of(&missed).unwrap(), "missed contact");
    }

    #[test]
    fn failures_keep_their_kind_not_their_numbers() {
        let p = Verdict::Failed { reason: format!("{PANIC_REASON_PREFIX}src/a.rs:12:5: index 7 out of range") };
        assert_eq!(wrong_of(&p).unwrap(), "failed: panic at src/a.rs:12");
        let dep = Verdict::Failed {
            reason: format!(
                "{PANIC_REASON_PREFIX}/root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/parry3d-0.31.1/src/q.rs:100:9: x"
            ),
        };
        assert_eq!(wrong_of(&dep).unwrap(), "failed: panic at parry3d-0.31.1/src/q.rs:100");
        let e = Verdict::Failed { reason: "ValueError: point 3 at 1e300 is outside. More text".into() };
        assert_eq!(wrong_of(&e).unwrap(), "failed: ValueError: point at is outside");
        assert_eq!(wrong_of(&Verdict::Failed { reason: NON_FINITE.into() }).unwrap(), "failed: non-finite answer");
        assert_eq!(wrong_of(&Verdict::Agree), None);
    }

    /// One case from its JSON.
    fn case(json: &str) -> LoadedCase {
        let text = format!(r#"{{"schema": "crashtest-fixture/1", "cases": [{json}]}}"#);
        let mut loaded = crate::load::Loaded::default();
        crate::load::load_str_into(std::path::Path::new("t.json"), &text, &mut loaded);
        assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
        loaded.cases.remove(0)
    }

    fn spheres(c: f64, r: f64) -> LoadedCase {
        case(&format!(
            r#"{{"name": "s", "query": "contact", "a": {{"sphere": {{"center": [{c:e}, 0, 0], "radius": {r:e}}}}},
                "b": {{"sphere": {{"center": [0, {c:e}, 0], "radius": {r:e}}}}}}}"#
        ))
    }

    #[test]
    fn the_range_rule_takes_the_pair_s_degree_and_the_type() {
        // Degree 2: squared lengths of differences reach 12·M².
        assert!(!beyond_precision(&spheres(1e150, 1.0), 53, false), "12e300 fits f64");
        assert!(beyond_precision(&spheres(1e154, 1.0), 53, false), "12e308 does not");
        assert!(beyond_precision(&spheres(1.0, 1e-160), 53, false), "1e-320 is below f64's normal range");
        assert!(!beyond_precision(&spheres(1.0, 1e-150), 53, false));
        // f32's range is far narrower; no other precision is judged so.
        assert!(beyond_precision(&spheres(1e19, 1.0), 24, false));
        assert!(!beyond_precision(&spheres(1e18, 1.0), 24, false), "12e36 fits f32");
        assert!(!beyond_precision(&spheres(1e18, 1.0), 53, false));
        assert!(!beyond_precision(&spheres(1e300, 1.0), 11, false));
        // Degree 4 for a triangle: 1e80 is beyond f64 there, not for two spheres.
        let tri = case(
            r#"{"name": "t", "query": "contact", "a": {"sphere": {"center": [0, 0, 1], "radius": 1}},
                "b": {"triangle": {"vertices": [[1e80, 0, 0], [0, 1, 0], [0, 0, 0]]}}}"#,
        );
        assert_eq!(pair_degree(&tri), 4);
        assert!(beyond_precision(&tri, 53, false));
        assert!(!beyond_precision(&spheres(1e80, 1.0), 53, false));
        // Rounding explains only an f32 engine's answer.
        assert!(beyond_precision(&spheres(1.0, 1.0), 24, true));
        assert!(!beyond_precision(&spheres(1.0, 1.0), 53, true));
    }

    #[test]
    fn an_f32_answer_the_rounding_of_its_inputs_explains_is_filed_under_its_precision() {
        // Centres 2^-30 apart at 1: exact, they are not concentric; rounded to
        // f32 they are, and an f32 engine answers the concentric fallback.
        let lc = case(
            r#"{"name": "near-concentric", "query": "contact",
                "a": {"sphere": {"center": [1, 0, 0], "radius": 1}},
                "b": {"sphere": {"center": [1.000000000931322574615478515625, 0, 0], "radius": 1}}}"#,
        );
        let set = crate::engines::EngineSet::default();
        let r = crate::check::check_case(&lc, &set);
        let of = |name: &str| r.engines.iter().find(|e| e.engine == name).expect(name);
        let f32_robust = of("collide-f32/robust");
        assert!(matches!(f32_robust.verdict, Verdict::Disagree { .. }), "{:?}", f32_robust.verdict);
        assert!(f32_robust.rounding_explains, "the rounded case is concentric, as the engine answered");
        let engine = set.judged.iter().find(|e| e.name == "collide-f32/robust").unwrap();
        let sig = signature(&lc, f32_robust, 1.0).unwrap();
        let cause = cause_of(&sig, &lc, Some(engine), f32_robust);
        assert_eq!(
            (cause.engine.as_str(), cause.pair.as_str(), cause.class.as_str()),
            ("collide-f32/robust", EVERY_PAIR, BEYOND_PRECISION)
        );
        // An f64 engine is never explained so.
        assert!(
            r.engines
                .iter()
                .filter(|e| e.engine.contains("f64") || e.engine.starts_with("collide/"))
                .all(|e| !e.rounding_explains)
        );
    }

    #[test]
    fn two_builds_of_one_code_share_a_pair_s_cause() {
        // parry's ball–half-space defect, seen through parry3d-f64 and parry3d.
        let lc = case(
            r#"{"name": "ball above a floor", "query": "contact",
                "a": {"sphere": {"center": [0, 0, 0.75], "radius": 1}},
                "b": {"plane": {"normal": [0, 0, 1], "offset": 0}}}"#,
        );
        let set = crate::engines::EngineSet::select("parry3d-f64,parry3d", Some("parry3d-f64")).unwrap();
        let r = crate::check::check_case(&lc, &set);
        let causes: Vec<Cause> = r
            .engines
            .iter()
            .zip(&set.judged)
            .map(|(res, e)| {
                assert!(!res.rounding_explains, "{}: the defect is not f32's rounding", res.engine);
                let sig = signature(&lc, res, 1.0).unwrap_or_else(|| panic!("{}: {:?}", res.engine, res.verdict));
                cause_of(&sig, &lc, Some(e), res)
            })
            .collect();
        assert_eq!(causes.len(), 2);
        assert_eq!(causes[0], causes[1]);
        assert_eq!((causes[0].engine.as_str(), causes[0].class.as_str()), ("parry3d-f64", WRONG_ANSWERS));
    }

    #[test]
    fn a_panic_s_cause_names_its_place_in_the_source_not_the_crate_s_folder() {
        assert_eq!(
            without_crate_folder("failed: panic at parry3d-0.31.1/src/query/epa/epa3.rs:100"),
            without_crate_folder("failed: panic at parry3d-f64-0.31.1/src/query/epa/epa3.rs:100")
        );
        assert_eq!(without_crate_folder("failed: panic at parry3d-0.31.1/src/q.rs:1"), "failed: panic at src/q.rs:1");
        // A panic in the workspace's own code, and any other failure, keep theirs.
        assert_eq!(
            without_crate_folder("failed: panic at crates/collide/src/a.rs:3"),
            "failed: panic at crates/collide/src/a.rs:3"
        );
        assert_eq!(without_crate_folder("failed: non-finite answer"), "failed: non-finite answer");
    }

    #[test]
    fn magnitude_classes_cover_every_error() {
        assert_eq!(magnitude_class(0.0), "error ≤ 1e-6");
        assert_eq!(magnitude_class(1e-3), "error 1e-6 to 1e-2");
        assert_eq!(magnitude_class(3.0), "error > 1e-2");
        assert_eq!(magnitude_class(f64::INFINITY), "error > 1e-2");
        assert_eq!(magnitude_class(f64::NAN), "error > 1e-2");
    }

    #[test]
    fn slugs_are_file_names() {
        let s = Signature {
            engine: "parry3d-f64".into(),
            query: Query::Contact,
            pair: "contact sphere–plane".into(),
            wrong: "normal, point off".into(),
            family: "fixture".into(),
            magnitude: "error > 1e-2".into(),
        };
        assert_eq!(s.slug(), "parry3d-f64-contact-sphere-plane-normal-point-off-fixture-error-g-1e-2");
    }
}
