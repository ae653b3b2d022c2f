//! A discrepancy's signature: what makes two discrepancies the same finding.
//!
//! Engine, query, shape pair in argument order, what is wrong (a false or
//! missed contact, hit, impact or overlap; which flag differs; which fields
//! exceed their allowance; how the engine failed), the case family, and the
//! error's magnitude class. Numbers never enter a signature: a reason's sizes
//! and a failure message's numbers are dropped, so the same defect at another
//! input has the same signature.

use crate::case::Query;
use crate::check::{EngineResult, PANIC_REASON_PREFIX};
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
/// a point`).
fn reason_key(reason: &str) -> String {
    if let Some((field, _)) = reason.split_once(" off by ") {
        return words(field);
    }
    if reason.starts_with("bounding sphere misses point") {
        return "bounding sphere misses a point".into();
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
        return format!("failed: panic at {}:{line}", crate_relative(file));
    }
    let text = words(first_sentence(reason));
    let text: String = text.chars().take(MAX_FAILURE_CHARS).collect();
    format!("failed: {text}")
}

/// A source path from a crate's root: a dependency's file under cargo's
/// registry (`…/registry/src/<index>/parry3d-f64-0.31.1/src/x.rs`) is named
/// from its crate's folder (`parry3d-f64-0.31.1/src/x.rs`), the same on every
/// machine.
fn crate_relative(file: &str) -> &str {
    match file.find("/registry/src/") {
        Some(i) => {
            let rest = &file[i + "/registry/src/".len()..];
            rest.split_once('/').map_or(rest, |(_, r)| r)
        }
        None => file,
    }
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
/// engine, the pair in argument order, and the class of what is wrong: wrong
/// answers (a false or missed contact, hit, impact or overlap, or values off),
/// wrong flags only (`degenerate`, `parallel`), one kind of failure, or —
/// for an engine of less precision than `f64` — inputs that its precision
/// cannot hold (every pair at once: one cause). The finer [`Signature`]s are
/// its variants.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct Cause {
    /// The engine.
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
/// The class of cases whose inputs the engine's precision cannot hold.
pub const BEYOND_PRECISION: &str = "inputs beyond its precision's range";

/// Whether some input number of the case does not survive rounding to a
/// precision of `bits` bits of mantissa (24: f32): a finite non-zero number
/// that becomes 0 or infinite.
pub fn beyond_precision(lc: &LoadedCase, bits: u32) -> bool {
    if bits != 24 {
        return false;
    }
    let Ok(v) = serde_json::to_value(&lc.case) else { return false };
    let mut beyond = false;
    fn walk(v: &serde_json::Value, beyond: &mut bool) {
        match v {
            serde_json::Value::Number(n) => {
                if let Some(x) = n.as_f64() {
                    let y = x as f32;
                    if x != 0.0 && x.is_finite() && (y == 0.0 || !y.is_finite()) {
                        *beyond = true;
                    }
                }
            }
            serde_json::Value::Array(a) => a.iter().for_each(|x| walk(x, beyond)),
            serde_json::Value::Object(o) => {
                for (k, x) in o {
                    if k != "expect" && k != "tol" {
                        walk(x, beyond);
                    }
                }
            }
            _ => {}
        }
    }
    walk(&v, &mut beyond);
    if let Some(m) = lc.meshes.iter().flatten().next() {
        beyond |= m.vertices.iter().flatten().any(|&x| x != 0.0 && ((x as f32) == 0.0 || !(x as f32).is_finite()));
    }
    beyond
}

/// The cause of a discrepancy of signature `sig` on `lc`, for an engine of
/// `precision` bits.
pub fn cause_of(sig: &Signature, lc: &LoadedCase, precision: u32, known: bool) -> Cause {
    if !known && beyond_precision(lc, precision) {
        return Cause {
            engine: sig.engine.clone(),
            query: None,
            pair: EVERY_PAIR.into(),
            class: BEYOND_PRECISION.into(),
        };
    }
    let class = if known || sig.wrong.starts_with("failed: ") {
        sig.wrong.clone()
    } else if sig.wrong.split("; ").all(|p| p.starts_with("degenerate:") || p.starts_with("parallel:")) {
        WRONG_FLAGS.into()
    } else {
        WRONG_ANSWERS.into()
    };
    Cause { engine: sig.engine.clone(), query: Some(sig.query), pair: sig.pair.clone(), class }
}

impl Cause {
    /// `parry3d-f64: contact sphere–plane: wrong answers`.
    pub fn title(&self) -> String {
        format!("{}: {}: {}", self.engine, self.pair, self.class)
    }

    /// A file name for it: lower-case letters, digits and `-`.
    pub fn slug(&self) -> String {
        slugify(&format!("{} {} {}", self.engine, self.pair, self.class))
    }
}

/// Text as a file name: lower-case letters, digits and single `-`, at most
/// [`MAX_SLUG_CHARS`] characters.
fn slugify(text: &str) -> String {
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
