//! The campaign behind `crashtest report`: every fixture plus seeded random cases
//! per query kind, through every engine, judged against the referee, with
//! timings; folded into a [`Summary`] and a list of [`Discrepancy`].
//!
//! Cases stream: a chunk ([`CHUNK`]) at a time they are made, asked of the
//! process engines, judged in parallel (rayon) and folded in case order, so
//! the same seed gives the same summary whatever the thread count or chunk
//! size, and a run's memory does not grow with its case count. Timing runs afterwards, one
//! engine at a time on one thread, over the same cases.

use crate::case::{Expect, FixtureFile, Query, SCHEMA};
use crate::check::{CaseResult, check_case, run_caught};
use crate::engine::Engine;
use crate::engines::{self, EngineSet};
use crate::judge::tolerance::Tolerance;
use crate::judge::{Errors, Misclass, Verdict};
use crate::load::{LoadedCase, load_paths};
use crate::summary::{Dist, EngineInfo, EngineQueryStats, Provenance, Summary, Timing};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

pub use crate::defaults::{
    DEFAULT_CASES, DEFAULT_FULL_RANGE_CASES, DEFAULT_SEED, REFEREE_TIMING_CASES, TIMING_CASES, TIMING_REPS,
};
pub use crate::judge::headline;

/// The query kinds the random campaign generates: every kind, in the
/// format's order.
pub const CAMPAIGN_QUERIES: [Query; Query::ALL.len()] = Query::ALL;

/// At most this many discrepancies per engine and query kind are written out in
/// full (the summary counts all of them): enough to study every failure family,
/// few enough to keep `discrepancies.json` readable.
pub const MAX_DISCREPANCIES_PER_GROUP: usize = 25;

/// What to run.
#[derive(Clone, Debug)]
pub struct Config {
    /// Seed of the random cases.
    pub seed: u64,
    /// Random cases per query kind, before sharding.
    pub cases_per_query: u64,
    /// Full-range cases per query kind, before sharding (scored apart: the
    /// summary's `full_range`).
    pub full_range_per_query: u64,
    /// Only this query kind (fixtures included only for it).
    pub only: Option<Query>,
    /// This shard `(i, n)`, 0 ≤ i < n: the cases with index in
    /// `[i·N/n, (i+1)·N/n)` of each query kind, and the fixtures for shard 0 only.
    pub shard: Option<(u32, u32)>,
    /// Fixture files or folders.
    pub fixtures: Vec<PathBuf>,
    /// Whether to time the engines.
    pub timing: bool,
    /// Whether to draw a progress bar (only on a terminal).
    pub progress: bool,
    /// The criterion benchmark's figures (`crashtest-bench.json`), read when
    /// the file exists: the accuracy–speed charts then use them.
    pub bench: Option<PathBuf>,
    /// The engines judged, the referee and the gate ([`EngineSet::default`]:
    /// every built-in engine, gated by `collide/robust`).
    pub engines: EngineSet,
    /// Whether to run the extra sections (dynamics, stability sweeps, the
    /// scene's needs, time of impact) — with the whole campaign only.
    pub sections: bool,
    /// Cases made and judged at a time ([`CHUNK`]; at least 1). The results
    /// do not depend on it.
    pub chunk: u64,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            seed: DEFAULT_SEED,
            cases_per_query: DEFAULT_CASES,
            full_range_per_query: DEFAULT_FULL_RANGE_CASES,
            only: None,
            shard: None,
            fixtures: vec![PathBuf::from(crate::builtin::NAME)],
            timing: true,
            progress: true,
            sections: true,
            bench: None,
            engines: EngineSet::default(),
            chunk: CHUNK,
        }
    }
}

/// One disagreement or failure, with everything needed to reproduce it: its case
/// as a fixture (`crashtest check` on `fixture` shows the same verdict), every
/// engine's answer, the errors and the tolerance.
#[derive(Clone, Debug, Serialize)]
pub struct Discrepancy {
    /// The engine that disagreed or failed.
    pub engine: String,
    /// The query kind.
    pub query: Query,
    /// Where the case came from (its fixture file, or its generator).
    pub origin: String,
    /// Its verdict and reasons.
    pub verdict: Verdict,
    /// Its errors against the referee (absolute lengths).
    pub errors: Errors,
    /// The answer's length scale (relative errors divide by it).
    pub scale: f64,
    /// The tolerances the engine was held to.
    pub tolerance: ToleranceJson,
    /// Every engine's answer, and the referee's, as a fixture's `expect`.
    pub answers: BTreeMap<String, Expect>,
    /// The case as a fixture file whose `expect` is the referee's answer.
    pub fixture: FixtureFile,
}

/// A [`Tolerance`] as written in a report.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ToleranceJson {
    /// Relative to the field's local magnitude.
    pub rel: f64,
    /// Normals, radians.
    pub normal_rad: f64,
    /// Segment parameters and barycentrics.
    pub unitless: f64,
}

/// The campaign's outcome.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The summary (`summary.json`).
    pub summary: Summary,
    /// The discrepancies written out (`discrepancies.json`), capped per group.
    pub discrepancies: Vec<Discrepancy>,
    /// Input errors met reading the fixtures (the run went on without them).
    pub input_errors: Vec<String>,
    /// The extra sections (dynamics: bounces, tunneling, two balls; …), run
    /// with the whole campaign (not with `--only`, and in shard 0 only).
    pub sections: Vec<crate::render::section::Section>,
    /// The discrepancies grouped into findings, each shrunk, with drafts for
    /// peer engines (`findings.json`, `findings/`).
    pub findings: crate::findings::FindingsFile,
}

/// The slice `[lo, hi)` of `0..n` that shard `i` of `count` takes.
pub fn shard_range(n: u64, shard: Option<(u32, u32)>) -> (u64, u64) {
    match shard {
        None => (0, n),
        Some((i, count)) => {
            let (i, count) = (u128::from(i), u128::from(count.max(1)));
            let n = u128::from(n);
            ((n * i / count) as u64, (n * (i + 1) / count) as u64)
        }
    }
}

/// The engines and their versions, for the provenance.
pub fn engine_infos(judged: &[Engine]) -> Vec<EngineInfo> {
    let mut v: Vec<EngineInfo> = judged
        .iter()
        .map(|e| EngineInfo {
            name: e.name.clone(),
            version: format!(
                "{} ({})",
                e.version.clone().unwrap_or_else(|| format!("{}, version not given", e.name)),
                precision_name(e.precision)
            ),
            process: e.process().map(|p| p.info()),
        })
        .collect();
    v.push(EngineInfo {
        name: engines::REFEREE.into(),
        version: format!(
            "exact rationals, {}-bit floats for square roots (dashu 0.6)",
            oracle::referee::PRECISION_BITS
        ),
        process: None,
    });
    v
}

fn precision_name(p: Option<u32>) -> &'static str {
    match p {
        Some(53) => "f64",
        Some(24) => "f32",
        _ => "exact",
    }
}

/// Whether a case is one of the full-range family's (scored apart).
pub fn is_full_range(lc: &LoadedCase) -> bool {
    lc.case.source.starts_with(crate::generate::FULL_RANGE_SOURCE)
}

/// The statistics' key: engine index, query kind, and whether the case is of
/// the full-range family.
type StatsKey = (usize, Query, bool);

fn stats_for<'a>(
    map: &'a mut BTreeMap<StatsKey, EngineQueryStats>,
    ix: usize,
    name: &str,
    q: Query,
) -> &'a mut EngineQueryStats {
    stats_in(map, (ix, q, false), name)
}

fn stats_in<'a>(
    map: &'a mut BTreeMap<StatsKey, EngineQueryStats>,
    key: StatsKey,
    name: &str,
) -> &'a mut EngineQueryStats {
    let q = key.1;
    map.entry(key).or_insert_with(|| EngineQueryStats {
        engine: name.to_string(),
        query: Some(q),
        ..Default::default()
    })
}

/// Folds one case's results into the statistics.
fn fold(map: &mut BTreeMap<StatsKey, EngineQueryStats>, c: &CaseResult, full_range: bool) {
    for (ix, r) in c.engines.iter().enumerate() {
        let s = stats_in(map, (ix, c.query, full_range), &r.engine);
        s.cases += 1;
        let e = &r.errors;
        let record_values = |s: &mut EngineQueryStats| {
            let add = |d: &mut Dist, x: Option<f64>| {
                if let Some(x) = x {
                    d.add(x)
                }
            };
            add(&mut s.point_abs, e.point);
            add(&mut s.point_rel, e.point.map(|x| x / c.scale));
            add(&mut s.depth_abs, e.depth.map(f64::abs));
            add(&mut s.depth_rel, e.depth.map(|x| x.abs() / c.scale));
            add(&mut s.normal_rad, e.normal);
            add(&mut s.t, e.t);
            add(&mut s.barycentric, e.barycentric);
            add(&mut s.normal_length, e.normal_length);
            if let Some(u) = e.ulps {
                s.ulps.add(u);
            }
        };
        match &r.verdict {
            Verdict::Agree => {
                s.agree += 1;
                record_values(s);
                s.headline.add(headline(e, c.scale));
            }
            Verdict::Borderline { .. } => {
                s.borderline += 1;
                record_values(s);
                s.headline.add(headline(e, c.scale));
            }
            Verdict::Disagree { .. } => {
                s.disagree += 1;
                record_values(s);
                match e.misclass {
                    Some(Misclass::FalsePositive) => s.false_positives += 1,
                    Some(Misclass::FalseNegative) => s.false_negatives += 1,
                    Some(Misclass::Flag) => s.flag_mismatches += 1,
                    None => {}
                }
                s.headline.add(if e.misclass.is_some() { 1.0 } else { headline(e, c.scale) });
            }
            Verdict::KnownDivergence { .. } => s.known += 1,
            Verdict::Unsupported { .. } => s.unsupported += 1,
            Verdict::Failed { reason } => {
                s.failed += 1;
                if reason == crate::judge::NON_FINITE {
                    s.non_finite += 1;
                }
                s.panics += u64::from(crate::check::is_caught_panic(&r.verdict));
                s.headline.add(1.0);
            }
        }
    }
}

fn discrepancy(c: &CaseResult, lc: &LoadedCase, ix: usize, tol: Tolerance) -> Discrepancy {
    let r = &c.engines[ix];
    let mut answers = BTreeMap::new();
    for e in &c.engines {
        if let Some(a) = &e.answer {
            answers.insert(e.engine.clone(), a.clone());
        }
    }
    if let Some(a) = &c.referee {
        answers.insert(engines::REFEREE.into(), a.clone());
    }
    let case = crate::findings::as_fixture(lc, c.referee.clone());
    Discrepancy {
        engine: r.engine.clone(),
        query: c.query,
        origin: crate::findings::model::origin(c, lc),
        verdict: r.verdict.clone(),
        errors: r.errors,
        scale: c.scale,
        tolerance: ToleranceJson { rel: tol.rel, normal_rad: tol.normal_rad, unitless: tol.unitless },
        answers,
        fixture: FixtureFile { schema: SCHEMA.into(), cases: vec![case] },
    }
}

/// A process engine's own times for the cases it answered (measured inside the
/// engine, so the process and JSON costs are not charged to it): their mean,
/// as one pass; `None` when it gave no time.
fn engine_side(p: &crate::protocol::ProcessEngine, cases: &[&LoadedCase]) -> Option<Timing> {
    let (mean, n) = p.mean_ns(cases.iter().copied())?;
    Some(Timing { median_ns: mean, min_ns: mean, max_ns: mean, reps: 1, queries: n as u64 })
}

/// Times `engine` on `cases`: [`TIMING_REPS`] repetitions of a loop over them;
/// `None` when it answers none of them.
pub fn time_engine(engine: &Engine, cases: &[&LoadedCase]) -> Option<Timing> {
    if let Some(p) = engine.process() {
        return engine_side(p, cases);
    }
    let answered: Vec<&LoadedCase> =
        cases.iter().copied().filter(|lc| run_caught(engine, lc).is_ok()).take(TIMING_CASES).collect();
    crate::timing::time_each(TIMING_REPS, &answered, |lc| engine.run(lc))
}

/// Cases generated, asked of the process engines and judged at a time. A run
/// holds one chunk's cases and results, never the campaign's: its memory is
/// what the folded statistics, the capped discrepancies and the findings take,
/// whatever `--cases` is. Large enough that the parallel judging and the
/// process engines' batches ([`crate::protocol::client::DEFAULT_BATCH`]) run
/// full.
pub const CHUNK: u64 = 8192;

/// Generated cases of each query kind kept for the timing loops and the
/// referee's estimated share: twice [`TIMING_CASES`], so that the loops still
/// find that many an engine answers.
const TIMING_SAMPLE: usize = 2 * TIMING_CASES;

/// What a run keeps while its cases stream past.
struct Folded<'a> {
    judged: &'a [Engine],
    /// The judging rule `--ulps N` ([`EngineSet::ulps`]).
    ulps: Option<f64>,
    map: BTreeMap<StatsKey, EngineQueryStats>,
    discrepancies: Vec<Discrepancy>,
    per_group: BTreeMap<StatsKey, usize>,
    total_discrepancies: u64,
    collector: crate::findings::Collector,
    /// Per query kind: the first generated ordinary cases (for timing), and how
    /// many there were in all.
    timing: BTreeMap<Query, (Vec<LoadedCase>, u64)>,
    /// The benchmark groups' mix over the generated cases.
    mix: crate::report::bench::Mix,
    fixture_cases: u64,
    random_cases: u64,
    /// The fixtures' results (the peers section reads them).
    fixture_results: Vec<CaseResult>,
}

impl Folded<'_> {
    fn add(&mut self, c: CaseResult, lc: &LoadedCase) {
        let full = is_full_range(lc);
        fold(&mut self.map, &c, full);
        self.collector.add(&c, lc, self.judged);
        for (ix, r) in c.engines.iter().enumerate() {
            if matches!(r.verdict, Verdict::Disagree { .. } | Verdict::Failed { .. }) {
                self.total_discrepancies += 1;
                let n = self.per_group.entry((ix, c.query, full)).or_default();
                if *n < MAX_DISCREPANCIES_PER_GROUP {
                    *n += 1;
                    self.discrepancies.push(discrepancy(
                        &c,
                        lc,
                        ix,
                        Tolerance::for_engine(self.judged[ix].precision_for(lc), self.ulps),
                    ));
                }
            }
        }
        let generated = lc.case.source.starts_with("generated");
        if generated {
            self.random_cases += 1;
            self.mix.add(lc);
            if !full {
                let (sample, n) = self.timing.entry(lc.case.query).or_default();
                *n += 1;
                if sample.len() < TIMING_SAMPLE {
                    sample.push(lc.clone());
                }
            }
        } else {
            self.fixture_cases += 1;
            self.fixture_results.push(c);
        }
    }
}

/// The campaign's cases in chunks of at most [`CHUNK`], in case order: the
/// fixtures, then each query kind's random cases, then its full-range ones.
/// Each chunk is generated when it is asked for.
fn chunks(config: &Config) -> impl Iterator<Item = Vec<LoadedCase>> + '_ {
    let kinds: Vec<Query> = CAMPAIGN_QUERIES.into_iter().filter(|q| config.only.is_none_or(|o| o == *q)).collect();
    let chunk = config.chunk.max(1);
    let slices = |n: u64, full: bool| {
        let (lo, hi) = shard_range(n, config.shard);
        let kinds = kinds.clone();
        kinds.into_iter().flat_map(move |q| {
            (lo..hi).step_by(chunk as usize).map(move |from| (q, from, (from + chunk).min(hi), full))
        })
    };
    slices(config.cases_per_query, false).chain(slices(config.full_range_per_query, true)).map(
        move |(q, from, to, full)| {
            if full {
                (from..to)
                    .into_par_iter()
                    .filter_map(|i| crate::generate::try_generate_full_range(q, config.seed, i))
                    .collect()
            } else {
                (from..to).into_par_iter().map(|i| crate::generate::generate(q, config.seed, i)).collect()
            }
        },
    )
}

/// Every case the campaign runs, in its order, held at once — for a caller
/// that wants them all (a user's test of a few thousand cases); [`run`]
/// streams them instead.
pub fn cases(config: &Config) -> (Vec<LoadedCase>, Vec<String>) {
    let (mut out, errors) = fixtures(config);
    out.extend(chunks(config).flatten());
    (out, errors)
}

/// The fixtures a run reads (shard 0 only), and the errors met reading them.
fn fixtures(config: &Config) -> (Vec<LoadedCase>, Vec<String>) {
    if config.shard.is_some_and(|(i, _)| i != 0) {
        return (Vec::new(), Vec::new());
    }
    let loaded = load_paths(&config.fixtures);
    let errors = loaded.errors.iter().map(|e| e.to_string()).collect();
    (loaded.cases.into_iter().filter(|c| config.only.is_none_or(|q| c.case.query == q)).collect(), errors)
}

/// Runs the campaign, streaming: chunk by chunk, its cases are made, asked of
/// the process engines, judged in parallel and folded in case order (so the
/// same seed gives the same summary whatever the thread count or chunk size),
/// then dropped.
pub fn run(config: &Config, provenance: Provenance) -> Outcome {
    let wall = Instant::now();
    let mut phases = Phases::default();
    let set = &config.engines;
    let (judged, referee) = (&set.judged, &set.referee);
    let (fixture_list, input_errors) = fixtures(config);
    phases.end(PHASE_CASES);
    let expected = fixture_list.len() as u64
        + config.only.map_or(CAMPAIGN_QUERIES.len() as u64, |_| 1)
            * [config.cases_per_query, config.full_range_per_query]
                .iter()
                .map(|&n| {
                    let (lo, hi) = shard_range(n, config.shard);
                    hi - lo
                })
                .sum::<u64>();
    let bar = progress_bar(config.progress, expected);
    let stages_before = oracle::referee::stage_counts();
    let mut folded = Folded {
        judged,
        ulps: set.ulps,
        map: BTreeMap::new(),
        discrepancies: Vec::new(),
        per_group: BTreeMap::new(),
        total_discrepancies: 0,
        collector: crate::findings::Collector::default(),
        timing: BTreeMap::new(),
        mix: Default::default(),
        fixture_cases: 0,
        random_cases: 0,
        fixture_results: Vec::new(),
    };
    let mut next = Some(fixture_list);
    let mut rest = chunks(config);
    loop {
        let chunk = match next.take() {
            Some(c) => c,
            None => match rest.next() {
                Some(c) => c,
                None => break,
            },
        };
        phases.end(PHASE_CASES);
        set.prefetch(&chunk);
        phases.end(PHASE_PROCESS);
        let sampled: BTreeMap<Query, usize> = folded.timing.iter().map(|(q, (s, _))| (*q, s.len())).collect();
        let results: Vec<CaseResult> = chunk
            .par_iter()
            .map(|lc| {
                let r = check_case(lc, set);
                bar.inc(1);
                r
            })
            .collect();
        for (c, lc) in results.into_iter().zip(&chunk) {
            folded.add(c, lc);
        }
        // The process engines' answers to this chunk are folded: forget them,
        // but for the timing sample's (the timing loops read them).
        set.keep(folded.timing.iter().flat_map(|(q, (s, _))| &s[sampled.get(q).copied().unwrap_or(0)..]));
        set.forget();
        phases.end(PHASE_JUDGE);
    }
    bar.finish_and_clear();
    let judge_seconds = wall.elapsed().as_secs_f64();
    // Other work in this process (another run, a test) may count too: the
    // figures are at least this run's, and exactly them in a lone run.
    let referee_stages: Vec<(String, u64, u64)> = oracle::referee::stage_counts()
        .into_iter()
        .zip(stages_before)
        .map(|((stage, f1, e1), (_, f0, e0))| (stage.label().to_string(), f1 - f0, e1 - e0))
        .filter(|(_, f, e)| f + e > 0)
        .collect();
    let Folded {
        mut map,
        discrepancies,
        total_discrepancies,
        collector,
        timing: samples,
        mix,
        fixture_cases,
        random_cases,
        fixture_results,
        ..
    } = folded;
    let versions = engine_infos(judged).into_iter().map(|e| (e.name, e.version)).collect();
    let mut findings = collector.finish(&versions);
    crate::findings::shrink_and_draft(&mut findings, set);
    phases.end(PHASE_SHRINK);

    let mut throughput = Vec::new();
    let mut growth = Vec::new();
    let mut referee_seconds = 0.0;
    if config.timing {
        // The process engines' answers to the sample, in batches (kept while
        // the chunks streamed past; asked again here if anything forgot them).
        set.prefetch(samples.values().flat_map(|(sample, _)| sample));
        for q in CAMPAIGN_QUERIES {
            // Timed on the generated cases only: the fixtures mix in meshes (whose
            // structures the adapters build per call), which would swamp a
            // per-query figure.
            let Some((sample, all)) = samples.get(&q) else { continue };
            let qcases: Vec<&LoadedCase> = sample.iter().collect();
            if qcases.is_empty() {
                continue;
            }
            for (ix, engine) in judged.iter().enumerate() {
                if let Some(t) = time_engine(engine, &qcases) {
                    stats_for(&mut map, ix, &engine.name, q).timing = Some(t);
                }
            }
            if let Some(t) = time_engine(referee, &qcases[..qcases.len().min(REFEREE_TIMING_CASES)]) {
                referee_seconds += t.median_ns * 1e-9 * *all as f64;
                let ix = judged.len();
                stats_for(&mut map, ix, &referee.name, q).timing = Some(t);
            }
        }
        for engine in judged.iter().chain([referee]) {
            let ns: Vec<f64> = map
                .values()
                .filter(|s| s.engine == engine.name)
                .filter_map(|s| s.timing.map(|t| t.median_ns))
                .collect();
            if !ns.is_empty() {
                throughput.push((engine.name.clone(), 1e9 * ns.len() as f64 / ns.iter().sum::<f64>()));
            }
        }
        if config.only.is_none_or(|q| q == Query::Distance) && config.cases_per_query > 0 {
            growth = crate::report::growth::measure(set, config.seed, time_engine);
        }
        let n = (fixture_cases + random_cases) as f64;
        throughput.push(("campaign (referee included)".into(), n / judge_seconds.max(1e-9)));
        let without = (judge_seconds - referee_seconds / rayon::current_num_threads() as f64).max(1e-9);
        throughput.push(("campaign (referee excluded, estimated)".into(), n / without));
        phases.end(PHASE_TIMING);
    }

    let (full, ordinary): (Vec<_>, Vec<_>) = map.into_iter().partition(|((_, _, full), _)| *full);
    let mut stats: Vec<EngineQueryStats> = ordinary.into_iter().map(|(_, s)| s).collect();
    // The full-range family in query order, then engine order (its table is
    // read query by query).
    let mut full: Vec<(StatsKey, EngineQueryStats)> = full;
    full.sort_by_key(|((ix, q, _), _)| (*q, *ix));
    let full_range: Vec<EngineQueryStats> = full.into_iter().map(|(_, s)| s).collect();
    let mut input_errors = input_errors;
    let mut speed_source = None;
    if let Some(path) = &config.bench {
        match crate::report::bench::load(path) {
            Ok(Some(bench)) => {
                crate::report::bench::apply_mix(&mut stats, &mix, &bench);
                speed_source =
                    Some(format!("criterion benchmark of {} on {} ({})", bench.written, bench.machine, path.display()));
            }
            Ok(None) => {}
            Err(e) => input_errors.push(e),
        }
    }
    let mut provenance = provenance;
    provenance.missing_engines = set.missing.clone();
    provenance.seed = config.seed;
    provenance.ulps = set.ulps;
    provenance.cases_per_query = config.cases_per_query;
    provenance.full_range_per_query = config.full_range_per_query;
    provenance.only = config.only;
    provenance.shards = config.shard.into_iter().collect();
    provenance.fixture_cases = fixture_cases;
    provenance.random_cases = random_cases;
    let sections = if config.sections && config.only.is_none() && config.shard.is_none_or(|(i, _)| i == 0) {
        sections(config, &fixture_results, &mut phases)
    } else {
        Vec::new()
    };
    // After the sections: a process engine's counts cover the whole run.
    provenance.engines = engine_infos(judged);
    provenance.wall_seconds = wall.elapsed().as_secs_f64();
    provenance.phases = phases.0;
    provenance.referee_stages = referee_stages;
    provenance.speed_source = speed_source;
    Outcome {
        summary: Summary {
            format: "crashtest-summary/1".into(),
            provenance,
            stats,
            full_range,
            discrepancies: total_discrepancies,
            throughput,
            growth,
        },
        discrepancies,
        input_errors,
        findings,
        sections,
    }
}

/// The phases of a run, as [`Provenance::phases`] names them.
pub const PHASE_CASES: &str = "making the cases";
/// Asking the process engines (their answers are fetched in batches first).
pub const PHASE_PROCESS: &str = "asking the process engines";
/// Judging every engine's answers against the referee's (the referee runs here).
pub const PHASE_JUDGE: &str = "judging";
/// Shrinking the findings and drafting their reports.
pub const PHASE_SHRINK: &str = "shrinking the findings";
/// The timing loops.
pub const PHASE_TIMING: &str = "timing";
/// The extra sections: each is its own phase, `sections: <id>` (stability,
/// scene, toi, peers, dynamics).
pub const PHASE_SECTIONS: &str = "sections";

/// Phase timings: each phase ends where the previous one ended.
struct Phases(Vec<(String, f64)>, Instant);

impl Default for Phases {
    fn default() -> Self {
        Self(Vec::new(), Instant::now())
    }
}

impl Phases {
    /// Ends a stretch of `name` (a phase met again, chunk after chunk, adds up;
    /// a phase that never took any time is not listed).
    fn end(&mut self, name: &str) {
        let now = Instant::now();
        let s = (now - self.1).as_secs_f64();
        match self.0.iter_mut().find(|(n, _)| n == name) {
            Some((_, total)) => *total += s,
            None if s > 0.0005 => self.0.push((name.to_string(), s)),
            None => {}
        }
        self.1 = now;
    }
}

/// The extra sections of a whole campaign, in report order.
fn sections(config: &Config, results: &[CaseResult], phases: &mut Phases) -> Vec<crate::render::section::Section> {
    let set = &config.engines;
    // The engines of the set a section does not run: all but collide's, and
    // those it names.
    let others = |also: &[&str]| -> Vec<&str> {
        set.judged
            .iter()
            .filter(|e| !engines::is_collide(e) && !also.contains(&e.name.as_str()))
            .map(|e| e.name.as_str())
            .collect()
    };
    let mut out = Vec::new();
    let done = |out: &Vec<crate::render::section::Section>, phases: &mut Phases| {
        if let Some(s) = out.last() {
            phases.end(&format!("{PHASE_SECTIONS}: {}", s.id));
        }
    };
    out.push(crate::sweep::section(
        &crate::sweep::Settings { poses: crate::sweep::REPORT_POSES, seed: config.seed },
        set,
    ));
    done(&out, phases);
    out.push(
        crate::scene::section(&crate::scene::SceneSettings {
            seed: config.seed,
            timing: config.timing,
            ..Default::default()
        })
        .with_not_run(
            &others(&[oracle::parry::Parry64::NAME]),
            "this section measures collide's scene structures (bounding-volume hierarchy, batched contacts, \
             bounding spheres) and parry3d-f64's through their own functions, not one query at a time through \
             the engine trait",
        ),
    );
    done(&out, phases);
    out.push(crate::toi_report::section(
        &crate::toi_report::Settings { seed: config.seed, timing: config.timing, ..Default::default() },
        set,
    ));
    done(&out, phases);
    let before = out.len();
    out.extend(crate::report::peers::section(results));
    if out.len() > before {
        done(&out, phases);
    }
    out.push(dynamics_section(set));
    done(&out, phases);
    out
}

/// The dynamics section: stepped worlds of collide and rapier3d-f64, and of
/// the process engines that step worlds; the other engines are not run there,
/// and it says why.
#[cfg(feature = "dynamics")]
fn dynamics_section(set: &EngineSet) -> crate::render::section::Section {
    let others: Vec<&str> = set
        .judged
        .iter()
        .filter(|e| !engines::is_collide(e) && !crate::dynamics::steps_worlds(e))
        .map(|e| e.name.as_str())
        .collect();
    crate::dynamics::section(&crate::dynamics::run_with(&set.judged)).with_not_run(
        &others,
        "the dynamics experiments step worlds with collide's integrators, with rapier3d-f64 and with the \
         process engines whose hello says `worlds`; this engine answers single queries and has no world to step",
    )
}

/// Without the `dynamics` feature there is no rapier to step: the section says
/// so, and how to get it.
#[cfg(not(feature = "dynamics"))]
fn dynamics_section(_set: &EngineSet) -> crate::render::section::Section {
    let why = "this build of crashtest has no dynamics: rapier3d-f64 is behind the `dynamics` feature of the \
               `crashtest` library (the `crashtest` command line enables it)";
    crate::render::section::Section {
        id: "dynamics".into(),
        title: "Dynamics: bounces, tunneling, two balls".into(),
        html: format!("<p class=\"not-run\">Not run: {}</p>\n", crate::render::xml::escape(why)),
        markdown: format!("## Dynamics\n\nNot run: {why}.\n"),
        charts: Vec::new(),
        data: serde_json::json!({ "not_run": why }),
    }
}

fn progress_bar(wanted: bool, len: u64) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !(wanted && std::io::stderr().is_terminal()) {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{spinner} judging {pos}/{len} cases [{bar:40}] {per_sec} ETA {eta}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::{EngineResult, PANIC_REASON_PREFIX};

    #[test]
    fn caught_panics_are_counted_per_engine_apart_from_other_failures() {
        let failed = |engine: &str, reason: String| EngineResult {
            engine: engine.into(),
            answer: None,
            verdict: Verdict::Failed { reason },
            errors: Errors::default(),
            expect_mismatches: None,
            rounding_explains: false,
        };
        let case = CaseResult {
            file: "f.json".into(),
            name: "c".into(),
            query: Query::Overlap,
            scale: 1.0,
            margin: None,
            referee: None,
            referee_meets_expect: None,
            engines: vec![
                failed("panics", format!("{PANIC_REASON_PREFIX}src/x.rs:1:2: broke")),
                failed("nan", "non-finite depth".into()),
            ],
            passed: false,
            unanswered: false,
        };
        let mut map = BTreeMap::new();
        fold(&mut map, &case, false);
        fold(&mut map, &case, false);
        let by_engine: Vec<(String, u64, u64)> = map.values().map(|s| (s.engine.clone(), s.failed, s.panics)).collect();
        assert_eq!(by_engine, vec![("panics".into(), 2, 2), ("nan".into(), 2, 0)]);
    }
}
