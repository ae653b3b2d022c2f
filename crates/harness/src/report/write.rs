//! Writing a report folder atomically, and joining shards.
//!
//! A report is assembled in a hidden sibling folder and renamed into place in one
//! step, and `latest` is switched only after that, so a run killed at any point
//! leaves the previous report (and `latest`) intact. The hidden folder's name
//! ends in the writing machine's name and process id, so that the next run can
//! tell a folder abandoned by a killed run (its process is gone) from one a
//! concurrent run is still writing, and remove only the first
//! ([`remove_abandoned`]).

use crate::case::{FixtureFile, SCHEMA};
use crate::findings::FindingsFile;
use crate::render::section::Section;
use crate::report::campaign::{MAX_DISCREPANCIES_PER_GROUP, Outcome};
use crate::summary::{EngineQueryStats, Summary};
use serde_json::Value;
use std::collections::BTreeMap;
use std::io;
use std::path::{Path, PathBuf};

/// The files of a report, as (path relative to the report folder, contents):
/// the summary, the discrepancies, the pages and charts, and the extra
/// sections (dynamics, stability, scene, time of impact) with their data files
/// and `sections.json` ([`crate::render::section::add_sections`]).
pub fn render_files(
    summary: &Summary,
    discrepancies: &[Value],
    sections: &[Section],
    findings: Option<&FindingsFile>,
    dir: &str,
) -> Vec<(PathBuf, String)> {
    let mut files =
        vec![("summary.json".into(), pretty(summary)), ("discrepancies.json".into(), pretty(&discrepancies))];
    match findings {
        Some(f) => {
            files.push(("findings.json".into(), pretty(f)));
            for x in &f.findings {
                if let Some(s) = &x.shrunk {
                    let fixture = FixtureFile { schema: SCHEMA.into(), cases: vec![s.case.clone()] };
                    files.push((PathBuf::from(&s.file), pretty(&fixture)));
                }
                if let (Some(d), Some(file)) = (&x.draft, x.draft_file()) {
                    files.push((PathBuf::from(file), d.clone()));
                }
            }
            files.extend(crate::render::pages_with(summary, &crate::findings::render::opening(f, discrepancies, dir)));
            files.push((
                "discrepancies.html".into(),
                crate::render::html::page(
                    "crashtest report — discrepancies",
                    &crate::findings::render::discrepancies_html(discrepancies),
                    crate::findings::render::TABLE_STYLE,
                    crate::findings::render::TABLE_SCRIPT,
                ),
            ));
        }
        None => files.extend(crate::render::pages(summary)),
    }
    crate::render::section::add_sections(&mut files, sections);
    files
}

/// Pretty JSON, newline-terminated.
fn pretty<T: serde::Serialize + ?Sized>(v: &T) -> String {
    let mut s = serde_json::to_string_pretty(v).unwrap_or_else(|e| format!("\"unserializable: {e}\""));
    s.push('\n');
    s
}

/// How the name of a report folder being written begins; the name ends in
/// `-<host>-<process id>` of the run writing it ([`incomplete_suffix`]).
pub const INCOMPLETE_PREFIX: &str = ".incomplete-";

/// This machine's name, as it goes into the name of a folder being written:
/// shards of one campaign may write into one shared folder from several
/// machines, and a process id means something only on its own machine. Only
/// letters, digits, `.` and `_` are kept; `unknown-host` where the name
/// cannot be read.
fn host() -> String {
    let name = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    let name: String = name.trim().chars().filter(|c| c.is_ascii_alphanumeric() || *c == '.' || *c == '_').collect();
    if name.is_empty() { "unknown_host".into() } else { name }
}

/// The end of the name of the folder this process writes: `-<host>-<pid>`.
pub fn incomplete_suffix() -> String {
    format!("-{}-{}", host(), std::process::id())
}

/// Checks that reports (or a sweep's files) can be written under `dir`: creates
/// it, then creates, writes and removes a probe file in it. Run before the
/// campaign, so that a bad `--out` (a regular file, a read-only place) is told
/// at once, not after hours of work.
pub fn probe_writable(dir: &Path) -> io::Result<()> {
    if dir.exists() && !dir.is_dir() {
        return Err(io::Error::new(io::ErrorKind::AlreadyExists, "it exists and is not a folder"));
    }
    std::fs::create_dir_all(dir)?;
    let probe = dir.join(format!(".probe-{}", std::process::id()));
    let written = std::fs::File::create_new(&probe).and_then(|mut f| io::Write::write_all(&mut f, b"probe\n"));
    let removed = std::fs::remove_file(&probe);
    written?;
    removed
}

/// Removes the report folders under `root` that runs which ended before they
/// finished left behind: every `.incomplete-*-<host>-<pid>` folder of this
/// machine whose process is no longer running (on Linux, `/proc/<pid>` is
/// gone). A folder of a live process — a concurrent run — is left alone, and
/// so is one written from another machine (its process cannot be looked up
/// here) or whose name carries no host and process id. Elsewhere than Linux,
/// nothing is removed. Returns each folder removed or that could not be.
pub fn remove_abandoned(root: &Path) -> Vec<(PathBuf, io::Result<()>)> {
    let mut out = Vec::new();
    if !cfg!(target_os = "linux") {
        return out;
    }
    let Ok(entries) = std::fs::read_dir(root) else { return out };
    let host = format!("-{}", host());
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let Some(rest) = name.strip_prefix(INCOMPLETE_PREFIX) else { continue };
        let Some((before, pid)) = rest.rsplit_once('-') else { continue };
        let Ok(pid) = pid.parse::<u32>() else { continue };
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        if !is_dir || !before.ends_with(&host) || pid == std::process::id() {
            continue;
        }
        if Path::new(&format!("/proc/{pid}")).exists() {
            continue;
        }
        let path = entry.path();
        let result = std::fs::remove_dir_all(&path);
        out.push((path, result));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Writes `files` as the report `root/id` atomically and points `root/latest`
/// at it. Returns the report's folder.
pub fn write_report(root: &Path, id: &str, files: &[(PathBuf, String)]) -> io::Result<PathBuf> {
    std::fs::create_dir_all(root)?;
    let tmp = root.join(format!("{INCOMPLETE_PREFIX}{id}{}", incomplete_suffix()));
    if tmp.exists() {
        std::fs::remove_dir_all(&tmp)?;
    }
    for (rel, contents) in files {
        let path = tmp.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::write(&path, contents)?;
    }
    // A report never replaces another: a second run in the same second with the
    // same seed gets a numbered id.
    let mut name = id.to_string();
    let mut n = 1;
    while root.join(&name).exists() {
        n += 1;
        name = format!("{id}-{n}");
    }
    let dest = root.join(&name);
    std::fs::rename(&tmp, &dest)?;
    point_latest(root, &name)?;
    Ok(dest)
}

/// Makes `root/latest` name `id`: a symbolic link where the platform has them
/// (replaced by an atomic rename), a one-line file elsewhere.
fn point_latest(root: &Path, id: &str) -> io::Result<()> {
    let latest = root.join("latest");
    #[cfg(unix)]
    {
        let tmp = root.join(format!(".latest-{}", std::process::id()));
        let _ = std::fs::remove_file(&tmp);
        std::os::unix::fs::symlink(id, &tmp)?;
        if latest.is_dir() && !latest.is_symlink() {
            std::fs::remove_dir_all(&latest)?;
        }
        std::fs::rename(&tmp, &latest)
    }
    #[cfg(not(unix))]
    {
        std::fs::write(&latest, format!("{id}\n"))
    }
}

/// Writes a campaign's outcome as a report.
pub fn write_outcome(root: &Path, id: &str, outcome: &Outcome) -> io::Result<PathBuf> {
    let discrepancies: Vec<Value> = outcome.discrepancies.iter().filter_map(|d| serde_json::to_value(d).ok()).collect();
    let dir = format!("{}/{id}", root.display());
    let files = render_files(&outcome.summary, &discrepancies, &outcome.sections, Some(&outcome.findings), &dir);
    write_report(root, id, &files)
}

/// A report read back for merging.
#[derive(Debug)]
pub struct ReadReport {
    /// The folder it was read from (named in merge's errors; empty when the
    /// report was not read from a folder).
    pub dir: PathBuf,
    /// Its summary.
    pub summary: Summary,
    /// Its discrepancies, as written.
    pub discrepancies: Vec<Value>,
    /// Its extra sections (`sections.json`; none when the file is absent —
    /// a shard other than 0, or a run with `--only`).
    pub sections: Vec<Section>,
}

/// Reads `summary.json`, `discrepancies.json` and (when present)
/// `sections.json` of a report folder. The error names the file.
pub fn read_report(dir: &Path) -> Result<ReadReport, String> {
    let read = |name: &str| {
        let p = dir.join(name);
        std::fs::read_to_string(&p).map_err(|e| format!("{}: cannot read: {e}", p.display())).map(|t| (p, t))
    };
    let (p, text) = read("summary.json")?;
    let summary: Summary = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", p.display()))?;
    let (p, text) = read("discrepancies.json")?;
    let discrepancies: Vec<Value> = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", p.display()))?;
    let sections = match std::fs::read_to_string(dir.join("sections.json")) {
        Ok(text) => serde_json::from_str(&text).map_err(|e| format!("{}: {e}", dir.join("sections.json").display()))?,
        Err(e) if e.kind() == io::ErrorKind::NotFound => Vec::new(),
        Err(e) => return Err(format!("{}: cannot read: {e}", dir.join("sections.json").display())),
    };
    Ok(ReadReport { dir: dir.to_path_buf(), summary, discrepancies, sections })
}

/// The extra sections of merged shards: each section once, as the first shard
/// that has it wrote it (they run whole in one shard — shard 0 — not split).
pub fn merge_sections(reports: &[ReadReport]) -> Vec<Section> {
    let mut m = Merging::default();
    for r in reports {
        m.add_sections(r);
    }
    m.sections
}

fn merge_stats(into: &mut EngineQueryStats, s: &EngineQueryStats) {
    into.cases += s.cases;
    into.agree += s.agree;
    into.disagree += s.disagree;
    into.borderline += s.borderline;
    into.known += s.known;
    into.unsupported += s.unsupported;
    into.failed += s.failed;
    into.panics += s.panics;
    into.non_finite += s.non_finite;
    into.false_positives += s.false_positives;
    into.false_negatives += s.false_negatives;
    into.flag_mismatches += s.flag_mismatches;
    for (a, b) in [
        (&mut into.point_abs, &s.point_abs),
        (&mut into.point_rel, &s.point_rel),
        (&mut into.depth_abs, &s.depth_abs),
        (&mut into.depth_rel, &s.depth_rel),
        (&mut into.normal_rad, &s.normal_rad),
        (&mut into.t, &s.t),
        (&mut into.barycentric, &s.barycentric),
        (&mut into.headline, &s.headline),
        (&mut into.normal_length, &s.normal_length),
    ] {
        a.merge(b);
    }
    into.ulps.merge(&s.ulps);
    // Timings are not additive: keep the one measured over more queries (the
    // shards ran on their own machines; their medians are each a fair figure).
    match (&into.timing, &s.timing) {
        (None, Some(t)) => into.timing = Some(*t),
        (Some(a), Some(b)) if b.queries > a.queries => into.timing = Some(*b),
        _ => {}
    }
}

/// How a report is named in merge's errors: its folder, or its place in the
/// list when it was not read from one.
fn label(r: &ReadReport, i: usize) -> String {
    if r.dir.as_os_str().is_empty() { format!("report #{}", i + 1) } else { r.dir.display().to_string() }
}

/// Checks that `reports` are the shards of one campaign, each once, and all of
/// them, so that their counts add up to that campaign's and no case is counted
/// twice: the same folder named twice, a whole (unsharded) report with any
/// other, shards of different splits (`0/2` with `1/3`), a shard given twice,
/// different seeds, case counts, `--only` or `--ulps`, and a missing shard (a lone shard
/// included) are each refused with the reports named. A single whole report is
/// accepted as it is.
pub fn check_mergeable(reports: &[ReadReport]) -> Result<(), String> {
    let first = reports.first().ok_or("nothing to merge")?;
    let mut dirs: BTreeMap<PathBuf, usize> = BTreeMap::new();
    for (i, r) in reports.iter().enumerate() {
        if r.dir.as_os_str().is_empty() {
            continue;
        }
        let canonical = std::fs::canonicalize(&r.dir).unwrap_or_else(|_| r.dir.clone());
        if let Some(&j) = dirs.get(&canonical) {
            return Err(format!("{} and {} are the same report, given twice", label(&reports[j], j), label(r, i)));
        }
        dirs.insert(canonical, i);
    }
    let p0 = &first.summary.provenance;
    for (i, r) in reports.iter().enumerate() {
        let p = &r.summary.provenance;
        if p.shards.is_empty() && reports.len() > 1 {
            return Err(format!(
                "{} is a whole report (not a shard): merging it with other reports would count its cases twice",
                label(r, i)
            ));
        }
        if p.seed != p0.seed || p.cases_per_query != p0.cases_per_query {
            return Err(format!(
                "shards of different campaigns: {} has seed {} / {} cases, {} has seed {} / {} cases",
                label(first, 0),
                p0.seed,
                p0.cases_per_query,
                label(r, i),
                p.seed,
                p.cases_per_query
            ));
        }
        if p.full_range_per_query != p0.full_range_per_query {
            return Err(format!(
                "shards of different campaigns: {} has {} full-range cases per query kind, {} has {}",
                label(first, 0),
                p0.full_range_per_query,
                label(r, i),
                p.full_range_per_query
            ));
        }
        if p.only != p0.only {
            let only = |q: Option<crate::case::Query>| q.map_or("every query".to_string(), |q| format!("--only {q}"));
            return Err(format!(
                "shards of different campaigns: {} ran {}, {} ran {}",
                label(first, 0),
                only(p0.only),
                label(r, i),
                only(p.only)
            ));
        }
        if p.ulps != p0.ulps {
            let rule = |u: Option<f64>| u.map_or("the tolerance table".to_string(), |n| format!("--ulps {n}"));
            return Err(format!(
                "shards judged by different rules: {} by {}, {} by {}",
                label(first, 0),
                rule(p0.ulps),
                label(r, i),
                rule(p.ulps)
            ));
        }
    }
    let mut owner: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for (i, r) in reports.iter().enumerate() {
        for &(k, n) in &r.summary.provenance.shards {
            if let Some((&(k0, n0), &j)) = owner.iter().find(|((_, n0), _)| *n0 != n) {
                return Err(format!(
                    "shards of different splits: {} is shard {k0}/{n0}, {} is shard {k}/{n}",
                    label(&reports[j], j),
                    label(r, i)
                ));
            }
            if let Some(&j) = owner.get(&(k, n)) {
                return Err(format!("shard {k}/{n} given twice: {} and {}", label(&reports[j], j), label(r, i)));
            }
            owner.insert((k, n), i);
        }
    }
    let n = owner.keys().next().map_or(0, |&(_, n)| n);
    let missing: Vec<String> = (0..n).filter(|k| !owner.contains_key(&(*k, n))).map(|k| format!("{k}/{n}")).collect();
    if !missing.is_empty() {
        return Err(format!(
            "incomplete shard set: {} of {n} shards given, missing {}",
            owner.len(),
            missing.join(", ")
        ));
    }
    Ok(())
}

/// Joins shard reports into one: counts and histograms add, maxima take the
/// larger, provenance lists every shard; discrepancies are kept up to the same
/// cap per engine and query kind as a single run. The reports must pass
/// [`check_mergeable`].
pub fn merge(reports: &[ReadReport]) -> Result<(Summary, Vec<Value>), String> {
    check_mergeable(reports)?;
    let mut m = Merging::default();
    for r in reports {
        m.add(r);
    }
    m.finish().map(|(summary, discrepancies, _)| (summary, discrepancies))
}

/// A merge folded one report at a time, so that any number of shards merge in
/// the memory of one (plus the folded statistics and the capped
/// discrepancies): `crashtest merge` checks the set first
/// ([`check_mergeable`] on [`read_provenance`]'s light copies), then reads and
/// adds each report in turn.
#[derive(Default)]
pub struct Merging {
    out: Option<Summary>,
    order: Vec<(String, Option<crate::case::Query>)>,
    stats: BTreeMap<(String, Option<crate::case::Query>), EngineQueryStats>,
    full_order: Vec<(String, Option<crate::case::Query>)>,
    full: BTreeMap<(String, Option<crate::case::Query>), EngineQueryStats>,
    per_group: BTreeMap<(String, String), usize>,
    discrepancies: Vec<Value>,
    sections: Vec<Section>,
}

/// Folds `s` into the statistics keyed by engine and query kind, keeping the
/// order in which keys are first met.
fn fold_stats(
    order: &mut Vec<(String, Option<crate::case::Query>)>,
    into: &mut BTreeMap<(String, Option<crate::case::Query>), EngineQueryStats>,
    s: &EngineQueryStats,
) {
    let key = (s.engine.clone(), s.query);
    if !into.contains_key(&key) {
        order.push(key.clone());
    }
    merge_stats(
        into.entry(key).or_insert_with(|| EngineQueryStats {
            engine: s.engine.clone(),
            query: s.query,
            ..Default::default()
        }),
        s,
    );
}

impl Merging {
    /// Adds one report (of a set [`check_mergeable`] accepted).
    pub fn add(&mut self, r: &ReadReport) {
        let s = &r.summary;
        let out = self.out.get_or_insert_with(|| {
            let mut out = s.clone();
            out.stats.clear();
            out.full_range.clear();
            out.provenance.shards.clear();
            out.provenance.fixture_cases = 0;
            out.provenance.random_cases = 0;
            out.provenance.wall_seconds = 0.0;
            out.provenance.phases.clear();
            out.provenance.referee_stages.clear();
            for p in out.provenance.engines.iter_mut().filter_map(|e| e.process.as_mut()) {
                p.cases_sent = 0;
                p.seconds_sent = 0.0;
            }
            out.discrepancies = 0;
            out
        });
        // A process engine's exchanges are every shard's.
        for e in &s.provenance.engines {
            let into = out.provenance.engines.iter_mut().find(|x| x.name == e.name).and_then(|x| x.process.as_mut());
            if let (Some(p), Some(into)) = (&e.process, into) {
                into.cases_sent += p.cases_sent;
                into.seconds_sent += p.seconds_sent;
            }
        }
        for st in &s.full_range {
            fold_stats(&mut self.full_order, &mut self.full, st);
        }
        out.provenance.shards.extend(s.provenance.shards.iter().copied());
        out.provenance.fixture_cases += s.provenance.fixture_cases;
        out.provenance.random_cases += s.provenance.random_cases;
        out.provenance.wall_seconds += s.provenance.wall_seconds;
        for (name, seconds) in &s.provenance.phases {
            match out.provenance.phases.iter_mut().find(|(n, _)| n == name) {
                Some((_, total)) => *total += seconds,
                None => out.provenance.phases.push((name.clone(), *seconds)),
            }
        }
        for (label, fast, exact) in &s.provenance.referee_stages {
            match out.provenance.referee_stages.iter_mut().find(|(l, _, _)| l == label) {
                Some((_, f, e)) => {
                    *f += fast;
                    *e += exact;
                }
                None => out.provenance.referee_stages.push((label.clone(), *fast, *exact)),
            }
        }
        out.discrepancies += s.discrepancies;
        for st in &s.stats {
            fold_stats(&mut self.order, &mut self.stats, st);
        }
        for d in &r.discrepancies {
            let key = (d["engine"].to_string(), d["query"].to_string());
            let n = self.per_group.entry(key).or_default();
            if *n < MAX_DISCREPANCIES_PER_GROUP {
                *n += 1;
                self.discrepancies.push(d.clone());
            }
        }
        self.add_sections(r);
    }

    /// Each section once, as the first shard that has it wrote it (they run
    /// whole in one shard — shard 0 — not split).
    fn add_sections(&mut self, r: &ReadReport) {
        for sec in &r.sections {
            if !self.sections.iter().any(|o| o.id == sec.id) {
                self.sections.push(sec.clone());
            }
        }
    }

    /// The merged summary, discrepancies and sections.
    pub fn finish(mut self) -> Result<(Summary, Vec<Value>, Vec<Section>), String> {
        let mut out = self.out.ok_or("nothing to merge")?;
        out.provenance.shards.sort_unstable();
        out.stats = self.order.into_iter().filter_map(|k| self.stats.remove(&k)).collect();
        out.full_range = self.full_order.into_iter().filter_map(|k| self.full.remove(&k)).collect();
        Ok((out, self.discrepancies, self.sections))
    }
}

/// A report's summary alone, with its statistics dropped: what
/// [`check_mergeable`] reads, light enough to hold for every shard at once.
pub fn read_provenance(dir: &Path) -> Result<ReadReport, String> {
    let p = dir.join("summary.json");
    let text = std::fs::read_to_string(&p).map_err(|e| format!("{}: cannot read: {e}", p.display()))?;
    let mut summary: Summary = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", p.display()))?;
    summary.stats = Vec::new();
    summary.full_range = Vec::new();
    Ok(ReadReport { dir: dir.to_path_buf(), summary, discrepancies: Vec::new(), sections: Vec::new() })
}
