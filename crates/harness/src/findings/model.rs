//! The findings' data: [`Finding`], [`FindingsFile`] (`findings.json`), and
//! the [`Collector`] that folds a campaign's results into them.

use super::signature::{self, Cause, Signature};
use crate::case::{Case, Expect, Query};
use crate::check::CaseResult;
use crate::judge::Verdict;
use crate::load::LoadedCase;
use crate::summary::Dist;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The format of `findings.json`.
pub const FORMAT: &str = "crashtest-findings/1";

/// Example cases kept per finding: the first few met, in case order (the
/// first is the one shrunk).
pub const MAX_EXAMPLES: usize = 3;

/// Fixture cases named per finding: fixtures are the same in every run, so
/// `diff` compares them case by case; a finding holding more than this many
/// is compared by its count alone.
pub const MAX_FIXTURE_NAMES: usize = 200;

/// A standalone reproduction: its language (for the code block) and program.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Reproduction {
    /// `rust`, `python`, …
    pub language: String,
    /// The program.
    pub code: String,
}

/// One example of a finding: its case, the verdict's reasons, its error and
/// every engine's answer.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Example {
    /// The case's name.
    pub case: String,
    /// Where it came from: its fixture file, or its generator.
    pub origin: String,
    /// The verdict's label (`DISAGREE`, `FAILED`, `known`).
    pub verdict: String,
    /// The verdict's reasons (one for a failure or a known divergence).
    pub reasons: Vec<String>,
    /// The case's headline error (1 for a misclassification or a failure); an
    /// infinite one (a distance off by an infinity) is written `null`, as JSON
    /// has no infinity, and read back as +∞.
    #[serde(deserialize_with = "infinite_when_null")]
    pub headline: f64,
    /// Every engine's answer and the referee's (`referee`), as written in
    /// `expect` (a non-finite number as `null`).
    pub answers: BTreeMap<String, serde_json::Value>,
    /// The case as a fixture, its `expect` the referee's answer, meshes inline.
    pub fixture: Case,
}

/// A number written by `serde_json`, which writes a non-finite one as `null`:
/// `null` is read as +∞ (an error is never negative, and never NaN here).
fn infinite_when_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::INFINITY))
}

/// A finding's shrunk case.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Shrunk {
    /// The fixture file, relative to the report (`findings/<name>.json`).
    pub file: String,
    /// The shrunk case, its `expect` the referee's answer.
    pub case: Case,
    /// The engine's answer to it (a non-finite number as `null`).
    pub answer: Option<serde_json::Value>,
    /// Its verdict's reasons.
    pub reasons: Vec<String>,
    /// Numbers in the case before and after.
    pub numbers: (usize, usize),
    /// The shrinker's measure of the case before and after (see
    /// [`shrink::cost`]): smaller is simpler.
    pub cost: (u64, u64),
    /// Candidates judged.
    pub evaluations: u32,
    /// Of [`crate::findings::shrink::REPLAYS`] judgements of the shrunk
    /// case, how many showed the finding's signature again: fewer than all
    /// means the engine answers the same case differently between calls.
    #[serde(default)]
    pub replayed: u32,
}

/// One root cause: the discrepancies of one signature.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Finding {
    /// Its file name in the report (`findings/<name>.json`, `.md`), unique.
    pub name: String,
    /// What it is, in words.
    pub title: String,
    /// Its root cause: engine (its source code), pair, class of what is wrong.
    pub cause: Cause,
    /// The engines that showed it and their cases (two when builds of one
    /// source code in two precisions show one cause).
    #[serde(default)]
    pub engines: BTreeMap<String, u64>,
    /// Its first case's signature: the one its shrunk case keeps.
    pub signature: Signature,
    /// Its signatures and how many cases each (the ways it shows), most first.
    pub variants: Vec<(Signature, u64)>,
    /// Its cases per case family.
    pub families: BTreeMap<String, u64>,
    /// The known divergence's documented reason, when it is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub known: Option<String>,
    /// Cases in it.
    pub count: u64,
    /// The engine's cases of this query kind in the run (ordinary and full range).
    pub of_cases: u64,
    /// The headline errors of its cases (1 for a misclassification or a failure).
    pub errors: Dist,
    /// Its first cases.
    pub examples: Vec<Example>,
    /// The fixture cases in it, `file#case` (at most [`MAX_FIXTURE_NAMES`]).
    #[serde(default)]
    pub fixture_cases: Vec<String>,
    /// Its first case shrunk, when it was.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shrunk: Option<Shrunk>,
    /// The engine's version, from the report's provenance.
    #[serde(default)]
    pub engine_version: String,
    /// A peer engine's standalone reproduction of the shrunk case, when it
    /// gives one for the pair.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reproduction: Option<Reproduction>,
    /// A peer engine's bug-report draft (Markdown; `findings/<name>.md`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub draft: Option<String>,
    /// The case to shrink (the first example, as loaded).
    #[serde(skip)]
    pub representative: Option<LoadedCase>,
    /// A process engine's fixture cases in it, as loaded, with the engine
    /// (judged again for stability; at most [`MAX_FIXTURE_NAMES`]).
    #[serde(skip)]
    pub fixture_loaded: Vec<(String, String, LoadedCase)>,
}

impl Finding {
    /// The engines that showed it, most cases first.
    pub fn engine_names(&self) -> Vec<&str> {
        let mut v: Vec<(&str, u64)> = self.engines.iter().map(|(e, n)| (e.as_str(), *n)).collect();
        if v.is_empty() {
            return vec![self.cause.engine.as_str()];
        }
        v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(b.0)));
        v.into_iter().map(|(e, _)| e).collect()
    }

    /// Its engines in words: `parry3d-f64, parry3d`.
    pub fn engines_label(&self) -> String {
        self.engine_names().join(", ")
    }

    /// The engine its shrunk case is judged by: its first case's.
    pub fn engine(&self) -> &str {
        &self.signature.engine
    }

    /// What it is, in words: `parry3d-f64, parry3d: contact sphere–plane:
    /// wrong answers`.
    fn make_title(&self) -> String {
        format!("{}: {}: {}", self.engines_label(), self.cause.pair, self.cause.class)
    }

    /// Its share of the engine's cases of this query kind.
    pub fn share(&self) -> f64 {
        if self.of_cases == 0 { 0.0 } else { self.count as f64 / self.of_cases as f64 }
    }

    /// Whether it is a discrepancy (not a known divergence).
    pub fn is_discrepancy(&self) -> bool {
        self.known.is_none()
    }

    /// Its draft's file in the report, when it has one.
    pub fn draft_file(&self) -> Option<String> {
        self.draft.as_ref().map(|_| format!("findings/{}.md", self.name))
    }

    /// The command that replays it, from the report folder `dir`.
    pub fn replay_command(&self, dir: &str) -> String {
        match &self.shrunk {
            Some(s) => format!("crashtest check {dir}/{} --engines {}", s.file, self.engine()),
            None => format!("crashtest check {dir}/findings/{}.json --engines {}", self.name, self.engine()),
        }
    }
}

/// `findings.json`: every finding of a report.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct FindingsFile {
    /// [`FORMAT`].
    pub format: String,
    /// Discrepancies in the run (disagreements and failures), all engines.
    pub discrepancies: u64,
    /// Cases per engine and query kind (what a finding's share divides by).
    pub cases: Vec<(String, Query, u64)>,
    /// The findings, discrepancies first (most cases first), then known divergences.
    pub findings: Vec<Finding>,
    /// Fixture cases a process engine answered differently when judged again
    /// in new processes ([`crate::findings::STABILITY_PROCESSES`]):
    /// `(engine, "file#case")`.
    /// Which finding such a case falls in can change from run to run with no
    /// change to the engine, so `crashtest diff` does not count its moves.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unstable: Vec<(String, String)>,
}

/// The findings of a campaign as it runs: fold each case's results in, in
/// case order.
#[derive(Debug, Default)]
pub struct Collector {
    by_cause: BTreeMap<Cause, Finding>,
    cases: BTreeMap<(String, Query), u64>,
    discrepancies: u64,
}

/// An answer as JSON (a non-finite number as `null`).
pub fn value(a: &Expect) -> serde_json::Value {
    serde_json::to_value(a).unwrap_or(serde_json::Value::Null)
}

/// A case's example for a finding.
fn example(c: &CaseResult, lc: &LoadedCase, ix: usize, headline: f64) -> Example {
    let r = &c.engines[ix];
    let mut answers = BTreeMap::new();
    for e in &c.engines {
        if let Some(a) = &e.answer {
            answers.insert(e.engine.clone(), value(a));
        }
    }
    if let Some(a) = &c.referee {
        answers.insert(crate::engines::REFEREE.into(), value(a));
    }
    let reasons = match &r.verdict {
        Verdict::Disagree { reasons } | Verdict::Borderline { reasons } => reasons.clone(),
        Verdict::Failed { reason } | Verdict::KnownDivergence { reason } | Verdict::Unsupported { reason } => {
            vec![reason.clone()]
        }
        Verdict::Agree => Vec::new(),
    };
    Example {
        case: c.name.clone(),
        origin: origin(c, lc),
        verdict: r.verdict.label().into(),
        reasons,
        headline,
        answers,
        fixture: as_fixture(lc, c.referee.clone()),
    }
}

/// Where a case came from: its generator (the source of a generated case),
/// or its fixture file.
pub fn origin(c: &CaseResult, lc: &LoadedCase) -> String {
    if lc.case.source.starts_with("generated") { lc.case.source.clone() } else { c.file.clone() }
}

/// The case as a fixture that reproduces wherever it is saved: meshes inline,
/// its `expect` the referee's answer (a bounding sphere checked by its radius
/// only in `bounds` cases).
pub fn as_fixture(lc: &LoadedCase, referee: Option<Expect>) -> Case {
    let mut case = lc.case.clone();
    case.expect = referee.map(|mut e| {
        if lc.case.query != Query::Bounds {
            e.min_radius = None;
        }
        e
    });
    inline_meshes(case, lc)
}

/// The case with every mesh that names a file written inline instead (from
/// the mesh as loaded): the file was named relative to the fixture it came from.
pub fn inline_meshes(mut case: Case, lc: &LoadedCase) -> Case {
    let shapes = [Some(&mut case.a), case.b.as_mut()];
    for (shape, mesh) in shapes.into_iter().zip(&lc.meshes) {
        if let (Some(crate::case::Shape::Mesh(spec)), Some(m)) = (shape, mesh)
            && spec.file.take().is_some()
        {
            spec.vertices = Some(m.vertices.clone());
            spec.triangles = Some(m.triangles.clone());
        }
    }
    case
}

impl Collector {
    /// Folds one case's results in; `judged` are the engines, in the
    /// results' order (their precision for the case decides whether its
    /// inputs are beyond it).
    pub fn add(&mut self, c: &CaseResult, lc: &LoadedCase, judged: &[crate::engine::Engine]) {
        for (ix, r) in c.engines.iter().enumerate() {
            *self.cases.entry((r.engine.clone(), c.query)).or_default() += 1;
            let misclassified = r.errors.misclass.is_some() || matches!(r.verdict, Verdict::Failed { .. });
            let headline = if misclassified { 1.0 } else { crate::judge::headline(&r.errors, c.scale) };
            let Some(sig) = signature::signature(lc, r, headline) else { continue };
            let known = match &r.verdict {
                Verdict::KnownDivergence { reason } => Some(reason.clone()),
                _ => {
                    self.discrepancies += 1;
                    None
                }
            };
            let cause = signature::cause_of(&sig, lc, judged.get(ix), r);
            let f = self.by_cause.entry(cause.clone()).or_insert_with(|| Finding {
                name: String::new(),
                title: String::new(),
                cause,
                engines: BTreeMap::new(),
                signature: sig.clone(),
                variants: Vec::new(),
                families: BTreeMap::new(),
                known,
                count: 0,
                of_cases: 0,
                errors: Dist::default(),
                examples: Vec::new(),
                fixture_cases: Vec::new(),
                shrunk: None,
                engine_version: String::new(),
                reproduction: None,
                draft: None,
                representative: None,
                fixture_loaded: Vec::new(),
            });
            f.count += 1;
            *f.engines.entry(r.engine.clone()).or_default() += 1;
            f.errors.add(headline);
            *f.families.entry(sig.family.clone()).or_default() += 1;
            match f.variants.iter_mut().find(|(s, _)| *s == sig) {
                Some((_, n)) => *n += 1,
                None => f.variants.push((sig, 1)),
            }
            if f.examples.len() < MAX_EXAMPLES {
                f.examples.push(example(c, lc, ix, headline));
            }
            if f.representative.is_none() {
                f.representative = Some(LoadedCase { case: inline_meshes(lc.case.clone(), lc), ..lc.clone() });
            }
            if !lc.case.source.starts_with("generated") && f.fixture_cases.len() < MAX_FIXTURE_NAMES {
                f.fixture_cases.push(format!("{}#{}", c.file, c.name));
                if judged.get(ix).is_some_and(|e| e.process().is_some()) {
                    f.fixture_loaded.push((r.engine.clone(), format!("{}#{}", c.file, c.name), lc.clone()));
                }
            }
        }
    }

    /// The findings, named and ordered: discrepancies by count (largest
    /// first), then known divergences by count. `versions` gives each
    /// engine's version.
    pub fn finish(self, versions: &BTreeMap<String, String>) -> FindingsFile {
        let cases = self.cases;
        let mut findings: Vec<Finding> = self.by_cause.into_values().collect();
        for f in &mut findings {
            f.of_cases = of_cases(&cases, f);
            f.engine_version = versions.get(f.engine()).cloned().unwrap_or_default();
            f.variants.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        }
        findings.sort_by(report_order);
        name_all(&mut findings);
        FindingsFile {
            format: FORMAT.into(),
            discrepancies: self.discrepancies,
            cases: cases.into_iter().map(|((e, q), n)| (e, q, n)).collect(),
            findings,
            unstable: Vec::new(),
        }
    }
}

/// The cases a finding's share divides by: its engines' cases of its query
/// kind, or of every kind for a cause over every pair.
pub fn of_cases(cases: &BTreeMap<(String, Query), u64>, f: &Finding) -> u64 {
    cases_of(cases, f.cause.query, &f.engine_names())
}

/// The cases of `engines` of query kind `query` (every kind for `None`).
pub fn cases_of(cases: &BTreeMap<(String, Query), u64>, query: Option<Query>, engines: &[&str]) -> u64 {
    cases
        .iter()
        .filter(|((e, q), _)| engines.contains(&e.as_str()) && query.is_none_or(|cq| cq == *q))
        .map(|(_, n)| n)
        .sum()
}

/// The report's order: discrepancies before known divergences, most cases first.
fn report_order(a: &Finding, b: &Finding) -> std::cmp::Ordering {
    (a.known.is_some(), std::cmp::Reverse(a.count), &a.cause).cmp(&(
        b.known.is_some(),
        std::cmp::Reverse(b.count),
        &b.cause,
    ))
}

/// Gives every finding its title and a unique file name from it (`-2`, `-3`,
/// … after a name already taken).
fn name_all(findings: &mut [Finding]) {
    let mut taken: BTreeMap<String, u32> = BTreeMap::new();
    for f in findings {
        f.title = f.make_title();
        let base = signature::slugify(&format!("{} {} {}", f.engines_label(), f.cause.pair, f.cause.class));
        let n = taken.entry(base.clone()).or_default();
        *n += 1;
        f.name = if *n == 1 { base } else { format!("{base}-{n}") };
    }
}

impl FindingsFile {
    /// The discrepancy findings (not known divergences).
    pub fn discrepancy_findings(&self) -> impl Iterator<Item = &Finding> {
        self.findings.iter().filter(|f| f.is_discrepancy())
    }

    /// Joins shards' findings: counts, cases and errors add; examples and
    /// fixture names are kept up to their caps, in shard order; a shrunk case
    /// is the first shard's that has one.
    pub fn merge(parts: &[FindingsFile]) -> FindingsFile {
        let mut by: BTreeMap<Cause, Finding> = BTreeMap::new();
        let mut cases: BTreeMap<(String, Query), u64> = BTreeMap::new();
        let mut discrepancies = 0;
        for p in parts {
            discrepancies += p.discrepancies;
            for (e, q, n) in &p.cases {
                *cases.entry((e.clone(), *q)).or_default() += n;
            }
            for f in &p.findings {
                match by.get_mut(&f.cause) {
                    None => {
                        by.insert(f.cause.clone(), f.clone());
                    }
                    Some(into) => {
                        into.count += f.count;
                        for (e, n) in &f.engines {
                            *into.engines.entry(e.clone()).or_default() += n;
                        }
                        into.errors.merge(&f.errors);
                        for (fam, n) in &f.families {
                            *into.families.entry(fam.clone()).or_default() += n;
                        }
                        for (sig, n) in &f.variants {
                            match into.variants.iter_mut().find(|(s, _)| s == sig) {
                                Some((_, m)) => *m += n,
                                None => into.variants.push((sig.clone(), *n)),
                            }
                        }
                        for e in &f.examples {
                            if into.examples.len() < MAX_EXAMPLES {
                                into.examples.push(e.clone());
                            }
                        }
                        for c in &f.fixture_cases {
                            if into.fixture_cases.len() < MAX_FIXTURE_NAMES {
                                into.fixture_cases.push(c.clone());
                            }
                        }
                        if into.shrunk.is_none() {
                            into.shrunk = f.shrunk.clone();
                        }
                    }
                }
            }
        }
        let mut findings: Vec<Finding> = by.into_values().collect();
        for f in &mut findings {
            f.of_cases = of_cases(&cases, f);
            f.variants.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        }
        findings.sort_by(report_order);
        // Named anew in the merged order (shards may have numbered two
        // findings' names differently); each shrunk case's file follows.
        name_all(&mut findings);
        for f in &mut findings {
            if let Some(s) = &mut f.shrunk {
                s.file = format!("findings/{}.json", f.name);
                s.case.name = f.name.clone();
            }
        }
        let mut unstable: Vec<(String, String)> = parts.iter().flat_map(|p| p.unstable.iter().cloned()).collect();
        unstable.sort();
        unstable.dedup();
        FindingsFile {
            format: FORMAT.into(),
            discrepancies,
            cases: cases.into_iter().map(|((e, q), n)| (e, q, n)).collect(),
            findings,
            unstable,
        }
    }
}

/// Reads a report's `findings.json`; the error names the file (and, for bad
/// JSON, the line and column).
pub fn read(dir: &std::path::Path) -> Result<FindingsFile, String> {
    let p = dir.join("findings.json");
    let text = std::fs::read_to_string(&p).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            format!("{}: no findings (a report written before findings were kept, or not a report folder)", p.display())
        } else {
            format!("{}: cannot read: {e}", p.display())
        }
    })?;
    let f: FindingsFile = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", p.display()))?;
    if f.format != FORMAT {
        return Err(format!("{}: field `format`: `{}`, expected `{FORMAT}`", p.display(), f.format));
    }
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_infinite_headline_is_written_null_and_read_back_infinite() {
        // A full-range distance off by an infinity gave a report whose
        // findings.json `crashtest findings` could not read.
        #[derive(Serialize, Deserialize)]
        struct H {
            #[serde(deserialize_with = "infinite_when_null")]
            headline: f64,
        }
        let text = serde_json::to_string(&H { headline: f64::INFINITY }).expect("written");
        assert_eq!(text, r#"{"headline":null}"#);
        let back: H = serde_json::from_str(&text).expect("read back");
        assert!(back.headline.is_infinite() && back.headline > 0.0, "{}", back.headline);
        let finite: H = serde_json::from_str(r#"{"headline":0.5}"#).expect("read");
        assert_eq!(finite.headline.to_bits(), 0.5f64.to_bits());
    }
}
