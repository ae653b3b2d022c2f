//! The report's CCD benchmark section (`report --ccd-benchmark DIR`): the
//! published benchmark's sample queries ([`crate::ccd_benchmark`]) through
//! every engine of the run that answers `ccd` and through the referee, counted
//! in the benchmark paper's terms.
//!
//! Per engine, per scene folder and kind (vertex–face, edge–edge), and in
//! total: the queries, the false positives and false negatives against the
//! benchmark's ground-truth bit, the queries the engine does not answer
//! (unsupported) or fails on (a panic, a non-finite number, a process fault) —
//! each its own column, never a negative — and the mean time per query: for an
//! engine in crashtest's process, loops of calls through the engine seam timed
//! as the campaign times them ([`crate::timing::time_each`]: the median of a
//! few passes, each pass's wall time over its queries); for a process engine,
//! the mean of the `ns` it reports for each query (docs/PROTOCOL.md, "Speed"),
//! so neither the process nor JSON is charged to it. Each answer is also
//! judged against the referee ([`crate::check::judge_engine`]: agreement
//! within the verdict's allowance, borderline, a known divergence, or a
//! disagreement), and the referee's answers are checked against the ground
//! truth: the two must agree on every query, and any query where they do not
//! is listed by file and index.
//!
//! Decisions: queries are asked of the process engines in batches first, then
//! judged in parallel (each query's referee answer once, shared by every
//! engine), then timed one engine at a time on one thread. An engine that
//! answers no query of the benchmark (parry, the peers without `ccd`) has no
//! row: the section names it and why. A folder that cannot be read, or a
//! file with a bad query, is named among the section's errors (its good
//! queries still run), and the command's exit code says so.

use crate::ccd_benchmark::{self, BenchmarkQuery};
use crate::check::{self, Truth};
use crate::engine::{Answer, Engine};
use crate::engines::EngineSet;
use crate::judge::{self, Misclass, Verdict};
use crate::load::LoadedCase;
use crate::render::markdown::{Table, table_md};
use crate::render::section::Section;
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The section's id: its anchor in `index.html` and its data file,
/// `ccd-benchmark.json`.
pub const ID: &str = "ccd-benchmark";

/// Repetitions of each in-process timing loop by default: 3 (the median is
/// reported). Reason: a pass over a scene's queries is milliseconds for
/// collide's methods, so three passes settle the figure to a few percent
/// while the referee's passes (exact arithmetic) keep the section's cost to
/// seconds.
pub const DEFAULT_REPS: u32 = 3;

/// Misclassified queries kept per engine in the data file (the counts are
/// always whole).
pub const MISCLASSIFIED_KEPT: usize = 100;

/// Queries the referee gave no answer to, kept in the data file as examples.
pub const UNANSWERED_KEPT: usize = 20;

/// What the section runs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Repetitions of each in-process timing loop (the median is reported).
    pub reps: u32,
    /// Whether to time the engines (`report --no-timing` turns it off).
    pub timing: bool,
}

impl Default for Settings {
    /// [`DEFAULT_REPS`], timed.
    fn default() -> Self {
        Self { reps: DEFAULT_REPS, timing: true }
    }
}

/// How an engine's times were taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Clock {
    /// In crashtest's process, around the calls through the engine seam:
    /// loops over the queries, the median of the passes.
    InProcess,
    /// The process engine's own `ns` per query, measured inside it.
    EngineReported,
}

impl Clock {
    fn label(self) -> &'static str {
        match self {
            Clock::InProcess => "in process",
            Clock::EngineReported => "engine's own ns",
        }
    }
}

/// Answers judged against the referee's.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct AgainstReferee {
    /// Within the verdict's allowance (the same impact or none, the time
    /// within its allowance).
    pub agree: usize,
    /// A classification that differs inside the referee's margin band.
    pub borderline: usize,
    /// A disagreement the engine's documented divergences explain.
    pub known: usize,
    /// Beyond the allowance: a false or missed impact, or a time too far.
    pub disagree: usize,
    /// Of `disagree`: an impact the referee does not have.
    pub false_impacts: usize,
    /// Of `disagree`: an impact the referee has, missed.
    pub missed_impacts: usize,
    /// Answered, but the referee gave no answer to judge against.
    pub unjudged: usize,
    /// The largest `|t − t*| / t_max` where both found an impact.
    pub max_t_error: Option<f64>,
}

/// One engine's counts on a set of queries.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Counts {
    /// Queries.
    pub queries: usize,
    /// Of them, with an impact in the benchmark's ground truth.
    pub positives: usize,
    /// Answered (an impact or none, every number finite).
    pub answered: usize,
    /// Answered with an impact where the ground truth has none.
    pub false_positives: usize,
    /// Answered with none where the ground truth has an impact.
    pub false_negatives: usize,
    /// Not answered: the engine does not answer this query.
    pub unsupported: usize,
    /// Failed: a panic, a non-finite number, a process fault or time-out.
    pub failed: usize,
    /// Judged against the referee; `None` for the referee itself.
    pub vs_referee: Option<AgainstReferee>,
    /// Mean time per query in nanoseconds, over the queries answered ([`Clock`]);
    /// `None` when not timed or none answered.
    pub mean_ns: Option<f64>,
    /// The queries the time is the mean of.
    pub timed: usize,
}

/// One row: an engine on one scene's queries of one kind.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// The scene folder.
    pub scene: String,
    /// `vertex-face` or `edge-edge`.
    pub kind: String,
    /// The counts.
    #[serde(flatten)]
    pub counts: Counts,
}

/// A query an engine classified against the ground truth.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Misclassified {
    /// The file, relative to the benchmark folder.
    pub file: String,
    /// The query's index in it, from 0.
    pub index: usize,
    /// The ground truth.
    pub truth: bool,
    /// The engine's time of impact, if it gave one.
    pub t: Option<f64>,
}

/// One engine's results.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EngineReport {
    /// Its name (`referee` for the referee).
    pub engine: String,
    /// How it was timed.
    pub clock: Clock,
    /// Per scene and kind, in the benchmark's order.
    pub rows: Vec<Row>,
    /// Over every query.
    pub total: Counts,
    /// Its false positives and negatives, the first [`MISCLASSIFIED_KEPT`].
    pub misclassified: Vec<Misclassified>,
    /// The first reason it gave for a query it did not answer or failed.
    pub first_reason: Option<String>,
}

/// An engine given to the section that answered none of its queries.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NotAnswering {
    /// The engine.
    pub engine: String,
    /// Its reason on the first query.
    pub reason: String,
}

/// A query where the referee's answer and the ground truth differ, or where
/// the referee gave none.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RefereeQuery {
    /// The file, relative to the benchmark folder.
    pub file: String,
    /// The query's index in it, from 0.
    pub index: usize,
    /// The ground truth.
    pub truth: bool,
    /// The referee's time of impact (`None`: no impact, or no answer).
    pub t: Option<f64>,
    /// Why the referee gave no answer (absent when it gave one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The referee against the benchmark's ground truth.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RefereeCheck {
    /// Queries.
    pub queries: usize,
    /// Answered and agreeing with the ground truth.
    pub agree: usize,
    /// Answered and disagreeing: every one.
    pub disagreements: Vec<RefereeQuery>,
    /// Not answered (refused, failed, out of range).
    pub unanswered: usize,
    /// The first [`UNANSWERED_KEPT`] of them.
    pub unanswered_examples: Vec<RefereeQuery>,
}

/// One scene's queries of one kind.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Group {
    /// The scene folder.
    pub scene: String,
    /// `vertex-face` or `edge-edge`.
    pub kind: String,
    /// CSV files.
    pub files: usize,
    /// Queries.
    pub queries: usize,
    /// Of them, with an impact in the ground truth.
    pub positives: usize,
}

/// Everything the section measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CcdReport {
    /// What was run.
    pub settings: Settings,
    /// The benchmark folder as it was named (a folder inside the current one
    /// relative to it).
    pub source: String,
    /// Queries read.
    pub queries: usize,
    /// Of them, with an impact in the ground truth.
    pub positives: usize,
    /// The scene folders and kinds, in order.
    pub groups: Vec<Group>,
    /// The engines that answered, in the run's order, then the referee.
    pub engines: Vec<EngineReport>,
    /// The engines that answered none of the queries.
    pub not_answering: Vec<NotAnswering>,
    /// The referee against the ground truth.
    pub referee: RefereeCheck,
    /// Files and queries that could not be read (`file: what`).
    pub errors: Vec<String>,
    /// The section's wall time, in seconds (reading, asking, judging, timing).
    pub seconds: f64,
}

// ---------------------------------------------------------------- the run

/// One engine's outcome on one query, kept small.
#[derive(Clone, Debug)]
enum Outcome {
    Unsupported(String),
    Failed(String),
    Answered { t: Option<f64>, judged: Judged },
}

#[derive(Clone, Copy, Debug)]
enum Judged {
    Agree,
    Borderline,
    Known,
    Disagree(Option<Misclass>),
    Unjudged,
}

/// One query's outcomes: the referee's, then each judged engine's with its
/// time's error against the referee (`|t − t*| / t_max`, where both found one).
type QueryOutcomes = (Outcome, Vec<(Outcome, Option<f64>)>);

fn truth_of(referee: &Result<Answer, Verdict>, lc: &LoadedCase) -> Truth {
    let (answer, missing) = match referee {
        Ok(a) if judge::all_finite(a) => (Some(a.clone()), String::new()),
        Ok(_) => (None, check::OUT_OF_RANGE.to_string()),
        Err(Verdict::Unsupported { reason }) | Err(Verdict::Failed { reason }) => (None, reason.clone()),
        Err(_) => (None, "the referee gave no answer".to_string()),
    };
    Truth::new(lc, answer, missing)
}

fn ccd_time(a: &Answer) -> Option<f64> {
    match a {
        Answer::Ccd(c) => c.t,
        _ => None,
    }
}

/// One engine's answer to one query, judged against the referee's.
fn outcome(e: &Engine, set: &EngineSet, lc: &LoadedCase, truth: &Truth) -> (Outcome, Option<f64>) {
    let r = check::judge_engine(e, set, lc, truth);
    let t = r.answer.as_ref().and_then(|a| a.ccd.as_ref()).and_then(|c| c.as_ref()).map(|c| c.t);
    let o = match (&r.answer, r.verdict) {
        (_, Verdict::Failed { reason }) => Outcome::Failed(reason),
        (None, Verdict::Unsupported { reason }) => Outcome::Unsupported(reason),
        (None, v) => Outcome::Failed(format!("no answer ({})", v.label())),
        (Some(_), v) => Outcome::Answered {
            t,
            judged: match v {
                Verdict::Agree => Judged::Agree,
                Verdict::Borderline { .. } => Judged::Borderline,
                Verdict::KnownDivergence { .. } => Judged::Known,
                Verdict::Disagree { .. } => Judged::Disagree(r.errors.misclass),
                Verdict::Unsupported { .. } | Verdict::Failed { .. } => Judged::Unjudged,
            },
        },
    };
    (o, r.errors.t)
}

/// The referee's own outcome on one query.
fn referee_outcome(r: &Result<Answer, Verdict>) -> Outcome {
    match r {
        Ok(a) if judge::all_finite(a) => Outcome::Answered { t: ccd_time(a), judged: Judged::Agree },
        Ok(_) => Outcome::Failed(check::OUT_OF_RANGE.into()),
        Err(Verdict::Unsupported { reason }) => Outcome::Unsupported(reason.clone()),
        Err(Verdict::Failed { reason }) => Outcome::Failed(reason.clone()),
        Err(v) => Outcome::Failed(format!("no answer ({})", v.label())),
    }
}

/// The query as a loaded case (its file named relative to the benchmark).
fn loaded(q: &BenchmarkQuery) -> LoadedCase {
    LoadedCase { file: PathBuf::from(&q.file), case: q.case.clone(), meshes: [None, None] }
}

/// Runs the section on the benchmark folder `dir`.
pub fn run(dir: &Path, settings: &Settings, set: &EngineSet) -> CcdReport {
    let started = Instant::now();
    let (queries, errors) = ccd_benchmark::read_dir(dir);
    let source = crate::protocol::client::shown_path(&dir.to_string_lossy());
    let mut r = run_queries(&source, &queries, settings, set);
    r.errors = errors.iter().map(ToString::to_string).collect();
    r.seconds = started.elapsed().as_secs_f64();
    r
}

/// Runs the section on queries already read.
pub fn run_queries(source: &str, queries: &[BenchmarkQuery], settings: &Settings, set: &EngineSet) -> CcdReport {
    let started = Instant::now();
    let cases: Vec<LoadedCase> = queries.iter().map(loaded).collect();
    set.prefetch(&cases);
    // Per query: the referee's outcome, then each judged engine's with its
    // time error against the referee.
    let per_query: Vec<QueryOutcomes> = cases
        .par_iter()
        .map(|lc| {
            let referee = check::run_caught(&set.referee, lc);
            let truth = truth_of(&referee, lc);
            let engines = set.judged.iter().map(|e| outcome(e, set, lc, &truth)).collect();
            (referee_outcome(&referee), engines)
        })
        .collect();

    // The groups: runs of one scene and kind (the queries come sorted).
    let mut bounds: Vec<(usize, usize)> = Vec::new();
    for (i, q) in queries.iter().enumerate() {
        match bounds.last_mut() {
            Some((start, end)) if queries[*start].scene == q.scene && queries[*start].kind == q.kind => *end = i + 1,
            _ => bounds.push((i, i + 1)),
        }
    }
    let groups: Vec<Group> = bounds
        .iter()
        .map(|&(s, e)| {
            let qs = &queries[s..e];
            let mut files: Vec<&str> = qs.iter().map(|q| q.file.as_str()).collect();
            files.dedup();
            Group {
                scene: qs[0].scene.clone(),
                kind: qs[0].kind.as_str().into(),
                files: files.len(),
                queries: qs.len(),
                positives: qs.iter().filter(|q| q.truth).count(),
            }
        })
        .collect();

    let mut reports = Vec::new();
    let mut not_answering = Vec::new();
    let outcomes_of = |ix: Option<usize>| -> Vec<(&Outcome, Option<f64>)> {
        per_query
            .iter()
            .map(|(r, es)| match ix {
                Some(i) => (&es[i].0, es[i].1),
                None => (r, None),
            })
            .collect()
    };
    for (ix, e) in set.judged.iter().enumerate().map(|(i, e)| (Some(i), e)).chain([(None, &set.referee)]) {
        let outs = outcomes_of(ix);
        if outs.iter().all(|(o, _)| matches!(o, Outcome::Unsupported(_))) {
            let reason = outs.iter().find_map(|(o, _)| match o {
                Outcome::Unsupported(r) => Some(r.clone()),
                _ => None,
            });
            not_answering.push(NotAnswering {
                engine: e.name.clone(),
                reason: reason.unwrap_or_else(|| "no query to answer".into()),
            });
            continue;
        }
        reports.push(engine_report(e, ix.is_none(), queries, &cases, &outs, &bounds, settings));
    }

    let referee = referee_check(queries, &outcomes_of(None));
    // The process engines' answers are counted: let them go.
    set.forget();
    CcdReport {
        settings: *settings,
        source: source.into(),
        queries: queries.len(),
        positives: queries.iter().filter(|q| q.truth).count(),
        groups,
        engines: reports,
        not_answering,
        referee,
        errors: Vec::new(),
        seconds: started.elapsed().as_secs_f64(),
    }
}

fn count(queries: &[BenchmarkQuery], outs: &[(&Outcome, Option<f64>)], is_referee: bool) -> Counts {
    let mut c = Counts {
        queries: queries.len(),
        positives: queries.iter().filter(|q| q.truth).count(),
        vs_referee: (!is_referee).then(AgainstReferee::default),
        ..Counts::default()
    };
    for (q, (o, t_err)) in queries.iter().zip(outs) {
        match o {
            Outcome::Unsupported(_) => c.unsupported += 1,
            Outcome::Failed(_) => c.failed += 1,
            Outcome::Answered { t, judged } => {
                c.answered += 1;
                match (t.is_some(), q.truth) {
                    (true, false) => c.false_positives += 1,
                    (false, true) => c.false_negatives += 1,
                    _ => {}
                }
                if let Some(v) = &mut c.vs_referee {
                    match judged {
                        Judged::Agree => v.agree += 1,
                        Judged::Borderline => v.borderline += 1,
                        Judged::Known => v.known += 1,
                        Judged::Disagree(m) => {
                            v.disagree += 1;
                            match m {
                                Some(Misclass::FalsePositive) => v.false_impacts += 1,
                                Some(Misclass::FalseNegative) => v.missed_impacts += 1,
                                _ => {}
                            }
                        }
                        Judged::Unjudged => v.unjudged += 1,
                    }
                    if let Some(e) = t_err {
                        v.max_t_error = Some(v.max_t_error.map_or(*e, |m: f64| m.max(*e)));
                    }
                }
            }
        }
    }
    c
}

/// An engine's mean time per query on the `answered` cases: its own `ns` for
/// a process engine, loops through the seam otherwise.
fn time(e: &Engine, answered: &[&LoadedCase], settings: &Settings) -> Option<f64> {
    if !settings.timing || answered.is_empty() {
        return None;
    }
    match e.process() {
        Some(p) => p.mean_ns(answered.iter().copied()).map(|(ns, _)| ns),
        None => crate::timing::time_each(settings.reps, answered, |lc| e.run(lc)).map(|t| t.median_ns),
    }
}

fn engine_report(
    e: &Engine,
    is_referee: bool,
    queries: &[BenchmarkQuery],
    cases: &[LoadedCase],
    outs: &[(&Outcome, Option<f64>)],
    bounds: &[(usize, usize)],
    settings: &Settings,
) -> EngineReport {
    let mut rows = Vec::new();
    let (mut ns_sum, mut timed) = (0.0, 0);
    for &(s, end) in bounds {
        let mut counts = count(&queries[s..end], &outs[s..end], is_referee);
        let answered: Vec<&LoadedCase> =
            (s..end).filter(|&i| matches!(outs[i].0, Outcome::Answered { .. })).map(|i| &cases[i]).collect();
        counts.mean_ns = time(e, &answered, settings);
        if let Some(ns) = counts.mean_ns {
            counts.timed = answered.len();
            ns_sum += ns * answered.len() as f64;
            timed += answered.len();
        }
        rows.push(Row { scene: queries[s].scene.clone(), kind: queries[s].kind.as_str().into(), counts });
    }
    let mut total = count(queries, outs, is_referee);
    total.mean_ns = (timed > 0).then(|| ns_sum / timed as f64);
    total.timed = timed;
    let misclassified = queries
        .iter()
        .zip(outs)
        .filter_map(|(q, (o, _))| match o {
            Outcome::Answered { t, .. } if t.is_some() != q.truth => {
                Some(Misclassified { file: q.file.clone(), index: q.index, truth: q.truth, t: *t })
            }
            _ => None,
        })
        .take(MISCLASSIFIED_KEPT)
        .collect();
    let first_reason = outs.iter().find_map(|(o, _)| match o {
        Outcome::Unsupported(r) | Outcome::Failed(r) => Some(r.clone()),
        Outcome::Answered { .. } => None,
    });
    let clock = if e.process().is_some() { Clock::EngineReported } else { Clock::InProcess };
    EngineReport { engine: e.name.clone(), clock, rows, total, misclassified, first_reason }
}

fn referee_check(queries: &[BenchmarkQuery], outs: &[(&Outcome, Option<f64>)]) -> RefereeCheck {
    let mut c = RefereeCheck { queries: queries.len(), ..RefereeCheck::default() };
    for (q, (o, _)) in queries.iter().zip(outs) {
        let at = |t: Option<f64>, reason: Option<String>| RefereeQuery {
            file: q.file.clone(),
            index: q.index,
            truth: q.truth,
            t,
            reason,
        };
        match o {
            Outcome::Answered { t, .. } if t.is_some() == q.truth => c.agree += 1,
            Outcome::Answered { t, .. } => c.disagreements.push(at(*t, None)),
            Outcome::Unsupported(r) | Outcome::Failed(r) => {
                c.unanswered += 1;
                if c.unanswered_examples.len() < UNANSWERED_KEPT {
                    c.unanswered_examples.push(at(None, Some(r.clone())));
                }
            }
        }
    }
    c
}

// ------------------------------------------------------------ the rendering

/// A time per query as a table cell: `—` where nothing was timed.
fn ns_cell(ns: Option<f64>) -> String {
    ns.map_or("—".into(), crate::render::markdown::sig3)
}

/// The referee's columns as cells (`—` for the referee itself).
fn vs_cells(v: Option<&AgainstReferee>) -> [String; 6] {
    match v {
        None => ["—", "—", "—", "—", "—", "—"].map(String::from),
        Some(v) => [
            v.agree.to_string(),
            v.borderline.to_string(),
            v.known.to_string(),
            if v.false_impacts + v.missed_impacts == 0 {
                v.disagree.to_string()
            } else {
                format!("{} ({} false, {} missed)", v.disagree, v.false_impacts, v.missed_impacts)
            },
            v.unjudged.to_string(),
            v.max_t_error.map_or("—".into(), crate::render::markdown::sci),
        ],
    }
}

const COLUMNS: [(&str, bool); 13] = [
    ("queries", true),
    ("false positives", true),
    ("false negatives", true),
    ("unsupported", true),
    ("failed", true),
    ("vs referee: agree", true),
    ("borderline", true),
    ("known", true),
    ("disagree", true),
    ("unjudged", true),
    ("max |t − t*| / t_max", true),
    ("ns / query", true),
    ("clock", false),
];

fn cells(c: &Counts, clock: Clock) -> Vec<String> {
    let mut out = vec![
        c.queries.to_string(),
        c.false_positives.to_string(),
        c.false_negatives.to_string(),
        c.unsupported.to_string(),
        c.failed.to_string(),
    ];
    out.extend(vs_cells(c.vs_referee.as_ref()));
    out.push(ns_cell(c.mean_ns));
    out.push(clock.label().into());
    out
}

/// The totals per engine.
pub fn totals_table(r: &CcdReport) -> Table {
    let mut t = Table {
        header: std::iter::once("engine").chain(COLUMNS[..13].iter().map(|c| c.0)).map(String::from).collect(),
        numeric: std::iter::once(false).chain(COLUMNS[..13].iter().map(|c| c.1)).collect(),
        rows: Vec::new(),
    };
    for e in &r.engines {
        t.rows.push(std::iter::once(e.engine.clone()).chain(cells(&e.total, e.clock)).collect());
    }
    t
}

/// Per scene and kind, every engine (the referee last).
pub fn scenes_table(r: &CcdReport) -> Table {
    let cols = [("scene", false), ("kind", false), ("positives", true), ("engine", false)];
    let mut t = Table {
        header: cols.iter().map(|c| c.0).chain(COLUMNS[..12].iter().map(|c| c.0)).map(String::from).collect(),
        numeric: cols.iter().map(|c| c.1).chain(COLUMNS[..12].iter().map(|c| c.1)).collect(),
        rows: Vec::new(),
    };
    for (g_ix, g) in r.groups.iter().enumerate() {
        for e in &r.engines {
            let Some(row) = e.rows.get(g_ix) else { continue };
            let mut cells = cells(&row.counts, e.clock);
            cells.pop();
            let mut line = vec![g.scene.clone(), g.kind.clone(), g.positives.to_string(), e.engine.clone()];
            line.extend(cells);
            t.rows.push(line);
        }
    }
    t
}

/// The referee against the ground truth, in words.
pub fn referee_words(r: &CcdReport) -> String {
    let c = &r.referee;
    let mut s = String::new();
    if c.disagreements.is_empty() && c.unanswered == 0 {
        let _ = write!(s, "The referee agrees with the ground truth on all {} queries.", c.queries);
        return s;
    }
    if c.disagreements.is_empty() {
        let _ = write!(s, "The referee agrees with the ground truth on all {} queries it answered.", c.agree);
    } else {
        let _ = write!(
            s,
            "The referee and the ground truth DISAGREE on {} of {} queries (listed below); they agree on {}.",
            c.disagreements.len(),
            c.queries,
            c.agree
        );
    }
    if c.unanswered > 0 {
        let why = c.unanswered_examples.first().and_then(|q| q.reason.as_deref()).unwrap_or("");
        let _ = write!(s, " The referee gave no answer on {} queries (first: {why}).", c.unanswered);
    }
    s
}

fn disagreements_table(r: &CcdReport) -> Table {
    let mut t = Table {
        header: ["file", "query", "ground truth", "referee"].map(String::from).to_vec(),
        numeric: vec![false, true, false, false],
        rows: Vec::new(),
    };
    for q in &r.referee.disagreements {
        t.rows.push(vec![
            q.file.clone(),
            q.index.to_string(),
            if q.truth { "impact" } else { "none" }.into(),
            q.t.map_or("none".into(), |t| format!("impact at {t:e}")),
        ]);
    }
    t
}

/// What the section says of its times.
fn timing_words(r: &CcdReport) -> String {
    if !r.settings.timing {
        return "Nothing was timed (the report was run with --no-timing).".into();
    }
    format!(
        "Times are the mean per query over the queries an engine answered: for an engine in crashtest's process \
         (clock \"in process\") measured around its calls through the engine seam, as the campaign times them (the \
         median of {} passes over each scene's queries, one thread); for a process engine (clock \"engine's own \
         ns\") the mean of the ns it reports for each query, measured inside it, so neither the process nor JSON \
         is charged to it.",
        r.settings.reps
    )
}

fn intro(r: &CcdReport) -> String {
    format!(
        "The CCD benchmark's sample queries (Wang et al., \"A Large-scale Benchmark and an Inclusion-based \
         Algorithm for Continuous Collision Detection\", ACM TOG 2021) from {}: {} queries ({} with an impact in \
         the ground truth) in {} scene folders and kinds, t_max 1. False positives and negatives are against the \
         benchmark's ground-truth bit; a query an engine does not answer or fails on is counted in its own column, \
         never as a negative. Each answer is also judged against the referee's exact answer: agree (the same \
         classification, the time within the verdict's allowance), borderline, a known divergence of the engine, \
         or a disagreement (of which false and missed impacts); unjudged where the referee gave no answer. The \
         section took {:.1} s.",
        r.source,
        r.queries,
        r.positives,
        r.groups.len(),
        r.seconds
    )
}

fn not_answering_words(r: &CcdReport) -> Vec<String> {
    r.not_answering.iter().map(|n| format!("Answers no ccd query: {} ({}).", n.engine, n.reason)).collect()
}

fn error_words(r: &CcdReport) -> Vec<String> {
    r.errors.iter().map(|e| format!("Not read: {e}")).collect()
}

/// The section's Markdown.
pub fn markdown(r: &CcdReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## CCD benchmark\n");
    let _ = writeln!(s, "{}\n", intro(r));
    let _ = writeln!(s, "{}\n", timing_words(r));
    for e in error_words(r) {
        let _ = writeln!(s, "{e}\n");
    }
    let _ = writeln!(s, "{}\n", referee_words(r));
    if !r.referee.disagreements.is_empty() {
        s.push_str(&table_md(&disagreements_table(r)));
        s.push('\n');
    }
    if !r.engines.is_empty() {
        let _ = writeln!(s, "### Totals per engine\n");
        s.push_str(&table_md(&totals_table(r)));
        let _ = writeln!(s, "\n### Per scene and kind\n");
        s.push_str(&table_md(&scenes_table(r)));
    }
    for l in not_answering_words(r) {
        let _ = writeln!(s, "\n{l}");
    }
    s
}

/// The section of measurements already made (id [`ID`]); its data is the
/// whole [`CcdReport`].
pub fn section_of(r: &CcdReport) -> Section {
    use crate::render::html::{escape, table_html};
    let p = |text: &str| format!("<p>{}</p>\n", escape(text));
    let mut html = p(&intro(r));
    html.push_str(&p(&timing_words(r)));
    for e in error_words(r) {
        html.push_str(&format!("<p class=\"not-run\">{}</p>\n", escape(&e)));
    }
    html.push_str(&p(&referee_words(r)));
    if !r.referee.disagreements.is_empty() {
        html.push_str(&table_html(&disagreements_table(r)));
    }
    if !r.engines.is_empty() {
        html.push_str("<h3>Totals per engine</h3>\n");
        html.push_str(&table_html(&totals_table(r)));
        html.push_str("<h3>Per scene and kind</h3>\n");
        html.push_str(&table_html(&scenes_table(r)));
    }
    for l in not_answering_words(r) {
        html.push_str(&format!("<p class=\"not-run\">{}</p>\n", escape(&l)));
    }
    Section {
        id: ID.into(),
        title: "CCD benchmark".into(),
        html,
        markdown: markdown(r),
        charts: Vec::new(),
        data: serde_json::to_value(r).unwrap_or_else(|e| serde_json::Value::String(format!("unserializable: {e}"))),
    }
}

/// The section, measured now on the benchmark folder `dir`, with the errors
/// met reading it (each `file: what`, naming the query where there is one).
pub fn section(dir: &Path, settings: &Settings, set: &EngineSet) -> (Section, Vec<String>) {
    let r = run(dir, settings, set);
    (section_of(&r), r.errors.clone())
}
