//! `crashtest diff OLD NEW`: what changed between two reports — new, fixed
//! and changed findings, and each engine's score per query kind.
//!
//! **Noise is told from change** two ways. Fixture cases are the same in
//! every run: a fixture case that enters or leaves a finding is a change,
//! whatever the seeds. Random cases differ between seeds: a finding's count
//! (and an engine's count of disagreements and failures) is compared as a
//! rate, `k₁/n₁` against `k₂/n₂`, with the two-proportion z score on the
//! pooled rate; it is a change only beyond [`Z_CHANGE`] standard errors. A
//! finding seen in one report only, with no fixture case, is new or fixed
//! only when its count alone is that far from 0; otherwise it is listed as
//! within noise.

use super::model::FindingsFile;
use super::signature::Cause as Signature;
use crate::case::Query;
use crate::summary::Summary;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// The z score beyond which a difference of rates is a change: 4 standard
/// errors. Reason: a diff compares a few hundred rates (findings and scores);
/// at 4σ the chance that one of 300 unchanged rates is called changed is
/// about 300 × 6.3e-5 ≈ 2 %, while a defect that doubles a rate of 1 % over
/// 10,000 cases (z ≈ 8) is still seen.
pub const Z_CHANGE: f64 = 4.0;

/// The two-proportion z score of `k2/n2` against `k1/n1` (positive when the
/// second rate is higher); 0 when both are empty or both rates are 0 or 1.
pub fn z_score(k1: u64, n1: u64, k2: u64, n2: u64) -> f64 {
    if n1 == 0 || n2 == 0 {
        return 0.0;
    }
    let (p1, p2) = (k1 as f64 / n1 as f64, k2 as f64 / n2 as f64);
    let p = (k1 + k2) as f64 / (n1 + n2) as f64;
    let se = (p * (1.0 - p) * (1.0 / n1 as f64 + 1.0 / n2 as f64)).sqrt();
    if se > 0.0 { (p2 - p1) / se } else { 0.0 }
}

/// How a finding or a score changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Change {
    /// Only in NEW, beyond noise.
    New,
    /// More cases in NEW, beyond noise (or fixture cases entered it).
    Worse,
    /// Only in OLD, beyond noise.
    Fixed,
    /// Fewer cases in NEW, beyond noise.
    Better,
    /// Fixture cases both entered and left it.
    Changed,
    /// In one report only, but within noise.
    Noise,
    /// The same within noise.
    Same,
}

impl Change {
    fn label(self) -> &'static str {
        match self {
            Change::New => "NEW",
            Change::Worse => "WORSE",
            Change::Fixed => "fixed",
            Change::Better => "better",
            Change::Changed => "CHANGED",
            Change::Noise => "within noise",
            Change::Same => "same",
        }
    }

    /// Whether it counts against the engine (`diff` exits 1 for a gated engine).
    pub fn is_worse(self) -> bool {
        matches!(self, Change::New | Change::Worse | Change::Changed)
    }
}

/// One finding compared.
#[derive(Clone, Debug, Serialize)]
pub struct FindingChange {
    /// Its root cause.
    pub signature: Signature,
    /// Its title.
    pub title: String,
    /// The engines that showed it, in either report (NEW's renamed): two
    /// builds of one code share a finding.
    pub engines: Vec<String>,
    /// Cases in OLD and the engine's cases of the query there.
    pub old: (u64, u64),
    /// In NEW.
    pub new: (u64, u64),
    /// Fixture cases that entered it, and that left it.
    pub fixtures: (Vec<String>, Vec<String>),
    /// The z score of the rates.
    pub z: f64,
    /// The verdict.
    pub change: Change,
}

/// One engine's score on one query kind compared: disagreements and failures
/// among its cases.
#[derive(Clone, Debug, Serialize)]
pub struct ScoreChange {
    /// The engine.
    pub engine: String,
    /// The query kind.
    pub query: Query,
    /// Disagreements and failures, and cases, in OLD.
    pub old: (u64, u64),
    /// In NEW.
    pub new: (u64, u64),
    /// The z score.
    pub z: f64,
    /// The verdict.
    pub change: Change,
}

/// What `diff` found.
#[derive(Clone, Debug, Serialize)]
pub struct Diff {
    /// Engines whose version differs: name, OLD's, NEW's.
    pub versions: Vec<(String, String, String)>,
    /// Engines in one report only: name and which (`OLD` or `NEW`).
    pub only_in: Vec<(String, String)>,
    /// Every finding of either report that is not the same.
    pub findings: Vec<FindingChange>,
    /// Every score of either report.
    pub scores: Vec<ScoreChange>,
}

fn classify(z: f64, entered: usize, left: usize) -> Change {
    match (entered > 0, left > 0) {
        (true, true) => Change::Changed,
        (true, false) => Change::Worse,
        (false, true) => Change::Better,
        _ if z > Z_CHANGE => Change::Worse,
        _ if z < -Z_CHANGE => Change::Better,
        _ => Change::Same,
    }
}

/// The engine names of NEW mapped to OLD's (`--as OLD=NEW` renames, to
/// compare two engines of one report or two names of one engine).
fn renamed(name: &str, renames: &[(String, String)]) -> String {
    match renames.iter().find(|(_, new)| new == name) {
        Some((old, _)) => old.clone(),
        // NEW's own engine of a name another engine now stands for is kept apart.
        None if renames.iter().any(|(old, _)| old == name) => format!("{name} (in NEW)"),
        None => name.to_string(),
    }
}

/// Compares two reports: their summaries and findings. `renames` maps
/// engine names of OLD to NEW's where they differ.
pub fn diff(old: (&Summary, &FindingsFile), new: (&Summary, &FindingsFile), renames: &[(String, String)]) -> Diff {
    let rename_sig = |s: &Signature| Signature { engine: renamed(&s.engine, renames), ..s.clone() };
    let old_cases: BTreeMap<(String, Query), u64> = old.1.cases.iter().map(|(e, q, n)| ((e.clone(), *q), *n)).collect();
    let new_cases: BTreeMap<(String, Query), u64> =
        new.1.cases.iter().map(|(e, q, n)| ((renamed(e, renames), *q), *n)).collect();
    let old_f: BTreeMap<Signature, &super::model::Finding> =
        old.1.findings.iter().filter(|f| f.is_discrepancy()).map(|f| (f.cause.clone(), f)).collect();
    let new_f: BTreeMap<Signature, &super::model::Finding> =
        new.1.findings.iter().filter(|f| f.is_discrepancy()).map(|f| (rename_sig(&f.cause), f)).collect();
    let keys: BTreeSet<&Signature> = old_f.keys().chain(new_f.keys()).collect();
    let mut findings = Vec::new();
    for sig in keys {
        let (fo, fnew) = (old_f.get(sig), new_f.get(sig));
        // The engines that showed it, in either report (NEW's renamed).
        let mut engines: BTreeSet<String> =
            fo.map(|f| f.engine_names().iter().map(|e| e.to_string()).collect()).unwrap_or_default();
        engines.extend(fnew.iter().flat_map(|f| f.engine_names()).map(|e| renamed(e, renames)));
        let engines: Vec<&str> = engines.iter().map(String::as_str).collect();
        let n_old = super::model::cases_of(&old_cases, sig.query, &engines);
        let n_new = super::model::cases_of(&new_cases, sig.query, &engines);
        if n_old == 0 || n_new == 0 {
            // The engine or the query kind ran in one report only: nothing to compare.
            continue;
        }
        let k_old = fo.map_or(0, |f| f.count);
        let k_new = fnew.map_or(0, |f| f.count);
        let set = |f: Option<&&super::model::Finding>| -> BTreeSet<String> {
            f.map(|f| f.fixture_cases.iter().cloned().collect()).unwrap_or_default()
        };
        // A fixture case its engine answered differently when judged again
        // (in either run) may move between findings with no change to the
        // engine: its moves are not counted.
        let steady = |names: BTreeSet<String>| -> BTreeSet<String> {
            names
                .into_iter()
                .filter(|n| {
                    !old.1.unstable.iter().any(|(e, c)| engines.contains(&e.as_str()) && c == n)
                        && !new
                            .1
                            .unstable
                            .iter()
                            .any(|(e, c)| engines.contains(&renamed(e, renames).as_str()) && c == n)
                })
                .collect()
        };
        let (so, sn) = (steady(set(fo)), steady(set(fnew)));
        let capped = |f: Option<&&super::model::Finding>| {
            f.is_some_and(|f| f.fixture_cases.len() >= super::model::MAX_FIXTURE_NAMES)
        };
        let (entered, left): (Vec<String>, Vec<String>) = if capped(fo) || capped(fnew) {
            (Vec::new(), Vec::new())
        } else {
            (sn.difference(&so).cloned().collect(), so.difference(&sn).cloned().collect())
        };
        let z = z_score(k_old, n_old, k_new, n_new);
        let change = match (fo, fnew) {
            (None, Some(_)) if !entered.is_empty() || z > Z_CHANGE => Change::New,
            (Some(_), None) if !left.is_empty() || z < -Z_CHANGE => Change::Fixed,
            (None, _) | (_, None) => Change::Noise,
            _ => classify(z, entered.len(), left.len()),
        };
        if change == Change::Same {
            continue;
        }
        let title = fnew.or(fo).map(|f| f.title.clone()).unwrap_or_default();
        findings.push(FindingChange {
            signature: sig.clone(),
            title,
            engines: engines.iter().map(|e| e.to_string()).collect(),
            old: (k_old, n_old),
            new: (k_new, n_new),
            fixtures: (entered, left),
            z,
            change,
        });
    }
    findings.sort_by(|a, b| (a.change, &a.signature).cmp(&(b.change, &b.signature)));

    let score = |s: &Summary, rename: bool| -> BTreeMap<(String, Query), (u64, u64)> {
        let mut m = BTreeMap::new();
        for st in s.stats.iter().chain(&s.full_range) {
            let Some(q) = st.query else { continue };
            let name = if rename { renamed(&st.engine, renames) } else { st.engine.clone() };
            let e: &mut (u64, u64) = m.entry((name, q)).or_default();
            e.0 += st.disagree + st.failed;
            e.1 += st.cases;
        }
        m
    };
    let (so, sn) = (score(old.0, false), score(new.0, true));
    let mut scores = Vec::new();
    for (key, &(k_new, n_new)) in &sn {
        let Some(&(k_old, n_old)) = so.get(key) else { continue };
        let z = z_score(k_old, n_old, k_new, n_new);
        scores.push(ScoreChange {
            engine: key.0.clone(),
            query: key.1,
            old: (k_old, n_old),
            new: (k_new, n_new),
            z,
            change: classify(z, 0, 0),
        });
    }
    let names = |s: &Summary, rename: bool| -> BTreeMap<String, String> {
        s.provenance
            .engines
            .iter()
            .map(|e| (if rename { renamed(&e.name, renames) } else { e.name.clone() }, e.version.clone()))
            .collect()
    };
    let (vo, vn) = (names(old.0, false), names(new.0, true));
    let mut versions = Vec::new();
    let mut only_in = Vec::new();
    for (name, v) in &vo {
        match vn.get(name) {
            Some(w) if w != v => versions.push((name.clone(), v.clone(), w.clone())),
            Some(_) => {}
            None => only_in.push((name.clone(), "OLD".into())),
        }
    }
    for name in vn.keys().filter(|n| !vo.contains_key(*n)) {
        only_in.push((name.clone(), "NEW".into()));
    }
    Diff { versions, only_in, findings, scores }
}

impl Diff {
    /// The engines among `gated` that got worse: a new or worse finding, or
    /// a worse score.
    pub fn worse(&self, gated: &[String]) -> Vec<String> {
        let mut out: BTreeSet<String> = BTreeSet::new();
        for f in self.findings.iter().filter(|f| f.change.is_worse()) {
            out.extend(f.engines.iter().cloned());
        }
        for s in self.scores.iter().filter(|s| s.change.is_worse()) {
            out.insert(s.engine.clone());
        }
        out.into_iter().filter(|e| gated.iter().any(|g| g == e)).collect()
    }

    /// The diff as text.
    pub fn text(&self) -> String {
        let mut out = String::new();
        for (name, a, b) in &self.versions {
            let _ = writeln!(out, "engine {name}: {a} → {b}");
        }
        for (name, which) in &self.only_in {
            let _ = writeln!(out, "engine {name}: only in {which}");
        }
        let real: Vec<&FindingChange> = self.findings.iter().filter(|f| f.change != Change::Noise).collect();
        let noise = self.findings.len() - real.len();
        let _ = writeln!(
            out,
            "\nFindings: {} changed beyond noise (two-proportion z score |z| > {Z_CHANGE}, or fixture cases moved); \
             {noise} seen in one report only within noise",
            real.len()
        );
        for f in &real {
            let _ = writeln!(
                out,
                "  {:<12} {}\n               {} of {} → {} of {} cases (z {:+.1}){}",
                f.change.label(),
                f.title,
                f.old.0,
                f.old.1,
                f.new.0,
                f.new.1,
                f.z,
                if f.fixtures.0.is_empty() && f.fixtures.1.is_empty() {
                    String::new()
                } else {
                    format!("; fixture cases in: {:?}, out: {:?}", f.fixtures.0, f.fixtures.1)
                }
            );
        }
        let _ = writeln!(out, "\nScores (disagreements and failures of cases):");
        for s in &self.scores {
            let _ = writeln!(
                out,
                "  {:<12} {} {}: {} of {} → {} of {} (z {:+.1})",
                s.change.label(),
                s.engine,
                s.query,
                s.old.0,
                s.old.1,
                s.new.0,
                s.new.1,
                s.z
            );
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fixture_case_marked_unstable_does_not_count_as_a_change() {
        // The repository's sample, against itself with one fixture case taken
        // out of a finding: a change (fixture cases are the same every run) —
        // unless either report lists that case as unstable for its engine.
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../reports/sample");
        let old = crate::findings::read(&dir).expect("the sample's findings");
        let summary = Summary::default();
        let ix = old
            .findings
            .iter()
            .position(|f| f.is_discrepancy() && !f.fixture_cases.is_empty())
            .expect("a finding with fixture cases");
        let mut new = old.clone();
        let moved = new.findings[ix].fixture_cases.remove(0);
        let engine = new.findings[ix].engine().to_string();
        let changed = |new: &FindingsFile| {
            diff((&summary, &old), (&summary, new), &[]).findings.iter().any(|c| c.fixtures.1.contains(&moved))
        };
        assert!(changed(&new), "a fixture case leaving a finding is a change");
        new.unstable.push((engine, moved.clone()));
        assert!(!changed(&new), "not when its engine answered it differently when judged again");
    }

    #[test]
    fn a_worse_finding_two_builds_share_gates_on_either_engine() {
        // The sample's parry ball–half-space finding holds parry3d-f64's and
        // parry3d's cases: three times as many in NEW is worse for both.
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../reports/sample");
        let old = crate::findings::read(&dir).expect("the sample's findings");
        let ix = old
            .findings
            .iter()
            .position(|f| f.is_discrepancy() && f.engines.len() == 2)
            .expect("a finding two builds share");
        let mut new = old.clone();
        new.findings[ix].count *= 3;
        let d = diff((&Summary::default(), &old), (&Summary::default(), &new), &[]);
        let names: Vec<String> = new.findings[ix].engines.keys().cloned().collect();
        for name in &names {
            assert_eq!(d.worse(std::slice::from_ref(name)), vec![name.clone()], "{name}");
        }
    }

    #[test]
    fn equal_rates_are_noise_and_a_doubled_rate_is_a_change() {
        assert!(z_score(100, 10_000, 104, 10_000).abs() < 1.0);
        assert!(z_score(100, 10_000, 200, 10_000) > Z_CHANGE);
        assert!(z_score(200, 10_000, 100, 10_000) < -Z_CHANGE);
        assert_eq!(z_score(0, 10_000, 0, 10_000).to_bits(), 0.0f64.to_bits(), "no cases either side: no change");
        assert_eq!(z_score(0, 0, 5, 10).to_bits(), 0.0f64.to_bits(), "an empty side: nothing to compare");
        // Three cases against none in 10,000 is within noise; thirty is not.
        assert!(z_score(0, 10_000, 3, 10_000) < Z_CHANGE);
        assert!(z_score(0, 10_000, 30, 10_000) > Z_CHANGE);
    }
}
