//! Findings: a campaign's discrepancies grouped into root causes.
//!
//! Every disagreement or failure gets a [`Signature`] (engine, query, pair in
//! argument order, what is wrong, the case family, the error's magnitude
//! class); discrepancies with one signature are one [`Finding`], with its
//! count, its share of the engine's cases of that query kind, its worst and
//! median error, and example cases. Known divergences are grouped the same
//! way and kept apart, each with its documented reason.
//!
//! Each finding's first case is then shrunk ([`shrink`]) while the referee
//! still gives the same signature, and written as a fixture
//! (`findings/<name>.json` in the report) that `crashtest check` replays; a
//! peer engine's finding gets a bug-report draft with a standalone
//! reproduction in the engine's own API ([`draft`]). Two reports' findings
//! are compared by [`diff`].

pub mod diff;
pub mod draft;
pub mod model;
pub mod render;
pub mod shrink;
pub mod signature;

pub use model::{
    Collector, Example, FORMAT, Finding, FindingsFile, MAX_EXAMPLES, MAX_FIXTURE_NAMES, Reproduction, Shrunk,
    as_fixture, inline_meshes, of_cases, read,
};

use crate::judge::Verdict;

/// How many new processes judge a process engine's fixture cases in findings
/// again, each case once per process: 3. An engine may answer an input the
/// same way all through one process and differently in the next (FCL's time
/// of impact on one fixture flipped between a failure and a wrong answer in 3
/// of 6 runs), so asking again in the same process would not show it. With the
/// report's own judgement, four processes: an input answered one way or the
/// other at random shows both with probability 7/8.
pub const STABILITY_PROCESSES: u32 = 3;

/// Shrinks each discrepancy finding's first case against the engine that
/// showed it (in parallel, one finding per task: each is deterministic), and
/// writes each peer engine's bug-report draft from the shrunk case. First, a
/// process engine's fixture cases in findings are judged again in new
/// processes; those that do not show their finding's cause every time are
/// listed as unstable.
pub fn shrink_and_draft(file: &mut FindingsFile, set: &crate::engines::EngineSet) {
    use rayon::prelude::*;
    let mut checks: std::collections::BTreeMap<String, Vec<(signature::Cause, String, crate::load::LoadedCase)>> =
        Default::default();
    for f in &mut file.findings {
        for (engine, name, lc) in std::mem::take(&mut f.fixture_loaded) {
            checks.entry(engine).or_default().push((f.cause.clone(), name, lc));
        }
    }
    let unstable: Vec<(String, String)> = checks
        .into_par_iter()
        .flat_map_iter(|(engine_name, cases)| {
            let mut out = Vec::new();
            let Some(engine) = set.judged.iter().find(|e| e.name == engine_name) else { return out };
            let mut steady = vec![true; cases.len()];
            for _ in 0..STABILITY_PROCESSES {
                if engine.fresh_process().is_err() {
                    break;
                }
                for ((cause, _, lc), steady) in cases.iter().zip(&mut steady) {
                    let (sig, result, _) = shrink::judge_one(engine, set, lc);
                    *steady &= sig.is_some_and(|s| signature::cause_of(&s, lc, Some(engine), &result) == *cause);
                }
            }
            for ((_, name, _), steady) in cases.into_iter().zip(steady) {
                if !steady {
                    out.push((engine_name.clone(), name));
                }
            }
            out
        })
        .collect();
    file.unstable.extend(unstable);
    file.unstable.sort();
    file.unstable.dedup();
    file.findings.par_iter_mut().filter(|f| f.is_discrepancy()).for_each(|f| {
        let Some(lc) = f.representative.take() else { return };
        let Some(engine) = set.judged.iter().find(|e| e.name == f.engine()) else { return };
        let mut out = shrink::shrink(&lc, &f.signature, &f.cause, engine, set);
        let mut replayed = shrink::replays(&out.case, &f.signature, &f.cause, engine, set);
        if replayed < shrink::REPLAYS {
            // The shrunk case shows the defect less reliably than it might:
            // the original, if it does better.
            let original = shrink::replays(&lc, &f.signature, &f.cause, engine, set);
            if original > replayed {
                out.case = lc.clone();
                out.numbers.1 = out.numbers.0;
                out.cost.1 = out.cost.0;
                replayed = original;
            }
        }
        let (_, result, truth) = shrink::judge_one(engine, set, &out.case);
        let mut case = as_fixture(&out.case, truth.answer.as_ref().map(crate::check::answer_as_expect));
        case.name = f.name.clone();
        let reasons = match &result.verdict {
            Verdict::Disagree { reasons } => reasons.clone(),
            Verdict::Failed { reason } => vec![reason.clone()],
            other => vec![other.label().to_string()],
        };
        f.shrunk = Some(Shrunk {
            file: format!("findings/{}.json", f.name),
            case,
            answer: result.answer.as_ref().map(model::value),
            reasons,
            numbers: out.numbers,
            cost: out.cost,
            evaluations: out.evaluations,
            replayed,
        });
        if draft::is_peer(engine) {
            // parry's programs assert the exact values; a finding of flags
            // only (a flag crashtest's adapter derives) has no value to show.
            let flags_only = f.cause.class == signature::WRONG_FLAGS;
            f.reproduction = draft::reproduction(engine, &out.case, &truth)
                .filter(|r| !(flags_only && draft::is_parry(engine) && r.language == "rust"));
            f.draft = Some(draft::markdown(f, f.reproduction.as_ref()));
        }
    });
}

/// Writes the sample a repository keeps of a report (`reports/sample`): its
/// findings (`findings.md`, and `findings.json` — on one line — without the examples'
/// cases), each finding's shrunk case and draft (`findings/`), and the
/// report's overview table (`summary.md`). The folder's other files are
/// left as they are; its old `findings/` is replaced. Returns the files
/// written.
pub fn write_sample(
    report: &std::path::Path,
    summary: &crate::summary::Summary,
    out: &std::path::Path,
) -> Result<Vec<std::path::PathBuf>, String> {
    let mut file = read(report)?;
    let drafts: Vec<(Option<String>, Option<String>)> =
        file.findings.iter().map(|f| (f.draft.clone(), f.draft_file())).collect();
    for f in &mut file.findings {
        // The examples' cases, and the drafts (their own files), stay in the report.
        f.examples.clear();
        f.draft = None;
        f.reproduction = None;
    }
    let dir_name = "reports/sample";
    let mut files: Vec<(std::path::PathBuf, String)> = Vec::new();
    files.push(("findings.md".into(), render::markdown(&file, dir_name)));
    // One line: the sample is kept in the repository, and its findings are
    // read by a test and by `crashtest findings`, not by eye (findings.md is
    // the readable copy).
    files.push(("findings.json".into(), serde_json::to_string(&file).unwrap_or_default() + "\n"));
    let overview = crate::render::markdown::table_md(&crate::render::markdown::overview_table(summary));
    let p = &summary.provenance;
    files.push((
        "summary.md".into(),
        format!(
            "# Each engine against the referee\n\nThe default report's overview (seed {}, {} random and {} fixture \
             cases): per query kind, agree · disagree · known divergence · unsupported (borderline and failed in \
             brackets).\n\n{overview}",
            p.seed, p.random_cases, p.fixture_cases
        ),
    ));
    for (f, (draft, name)) in file.findings.iter().zip(drafts) {
        if let Some(s) = &f.shrunk {
            let fixture = crate::case::FixtureFile { schema: crate::case::SCHEMA.into(), cases: vec![s.case.clone()] };
            files.push((s.file.clone().into(), pretty(&fixture)));
        }
        if let (Some(d), Some(name)) = (draft, name) {
            files.push((name.into(), d));
        }
    }
    let old = out.join("findings");
    if old.is_dir() {
        std::fs::remove_dir_all(&old).map_err(|e| format!("{}: cannot remove: {e}", old.display()))?;
    }
    let mut written = Vec::new();
    for (rel, text) in files {
        let path = out.join(&rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| format!("{}: cannot create: {e}", parent.display()))?;
        }
        std::fs::write(&path, text).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// Pretty JSON, newline-terminated.
fn pretty<T: serde::Serialize>(v: &T) -> String {
    let mut s = serde_json::to_string_pretty(v).unwrap_or_default();
    s.push('\n');
    s
}
