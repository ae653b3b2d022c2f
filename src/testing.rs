//! crashtest in your own `cargo test`: your engine on the built-in fixtures and
//! a seeded random campaign, judged against the referee, failing with the
//! discrepancy table when it disagrees.
//!
//! ```
//! use crashtest::{Engine, Queries, Reply};
//! use crashtest::geom::Aabb;
//!
//! struct Boxes;
//! impl Queries for Boxes {
//!     fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
//!         Ok((0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]))
//!     }
//! }
//! // Panics with the table of every case it gets wrong.
//! crashtest::testing::assert_agrees(Engine::new("boxes", Some(53), Boxes));
//! ```
//!
//! What fails: a disagreement with the referee, a failure (panic or non-finite
//! number), and an answer that misses a fixture's `expect`. What does not: a
//! query the engine does not implement (`Unsupported`), a borderline case (the
//! referee's margin is inside the tolerance band) and a known divergence the
//! engine carries ([`crate::Engine::with_known`]).

use crate::{EngineSet, Query};
use harness::check::{CaseResult, EngineResult, check_case};
use harness::judge::Verdict;
use harness::load::LoadedCase;
use std::fmt::Write;
use std::path::PathBuf;

/// Random cases per query kind [`assert_agrees`] runs: 500. Reason: every
/// generator family (touching, degenerate, near-parallel, far) is drawn tens of
/// times at that count, and the whole run stays within a few seconds of a test
/// build.
pub const DEFAULT_TEST_CASES: u64 = 500;

/// Full-range cases per query kind [`assert_agrees`] runs: 100 (raw bit
/// patterns, huge, tiny and subnormal magnitudes, multi-scale scenes).
pub const DEFAULT_TEST_FULL_RANGE: u64 = 100;

/// Judges `engine` (alone, as the gate) on the built-in fixtures,
/// [`DEFAULT_TEST_CASES`] random and [`DEFAULT_TEST_FULL_RANGE`] full-range cases
/// per query kind of the default seed; panics with the discrepancy table when
/// it fails one.
#[track_caller]
pub fn assert_agrees(engine: crate::Engine) {
    let name = engine.name.clone();
    let set = match EngineSet::new(vec![engine], &name) {
        Ok(set) => set,
        Err(e) => panic!("crashtest: {e}"),
    };
    Judge::new(set).run().assert_agrees(&name);
}

/// A test run: which engines, which cases.
#[derive(Clone, Debug)]
pub struct Judge {
    engines: EngineSet,
    seed: u64,
    cases: u64,
    full_range: u64,
    only: Option<Query>,
    fixtures: Vec<PathBuf>,
}

impl Judge {
    /// `engines` on the built-in fixtures and the default seed's
    /// [`DEFAULT_TEST_CASES`] random and [`DEFAULT_TEST_FULL_RANGE`] full-range
    /// cases per query kind.
    pub fn new(engines: EngineSet) -> Self {
        Self {
            engines,
            seed: crate::DEFAULT_SEED,
            cases: DEFAULT_TEST_CASES,
            full_range: DEFAULT_TEST_FULL_RANGE,
            only: None,
            fixtures: vec![crate::builtin_fixtures()],
        }
    }

    /// Judges with a fixed allowance of `n` ulps of each field's magnitude in
    /// the engine's own precision (the CLI's `--ulps N`; the conditioning
    /// allowances stay): is the engine backward stable to `n` ulps?
    pub fn ulps(mut self, n: u32) -> Self {
        self.engines.ulps = Some(f64::from(n));
        self
    }

    /// The seed of the random cases.
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Random cases per query kind.
    pub fn cases(mut self, n: u64) -> Self {
        self.cases = n;
        self
    }

    /// Full-range cases per query kind.
    pub fn full_range(mut self, n: u64) -> Self {
        self.full_range = n;
        self
    }

    /// Only this query kind (fixtures included only for it).
    pub fn only(mut self, q: Query) -> Self {
        self.only = Some(q);
        self
    }

    /// These fixture files or folders instead of the built-in ones (none: an
    /// empty list).
    pub fn fixtures(mut self, paths: Vec<PathBuf>) -> Self {
        self.fixtures = paths;
        self
    }

    /// Runs every case through every engine of the set.
    pub fn run(&self) -> Judged {
        let config = harness::report::campaign::Config {
            seed: self.seed,
            cases_per_query: self.cases,
            full_range_per_query: self.full_range,
            only: self.only,
            fixtures: self.fixtures.clone(),
            ..Default::default()
        };
        let (cases, input_errors) = harness::report::campaign::cases(&config);
        let results = cases.iter().map(|lc| check_case(lc, &self.engines)).collect();
        Judged { cases, results, input_errors }
    }
}

/// What a [`Judge`] run found.
#[derive(Debug)]
pub struct Judged {
    /// The cases, in run order.
    pub cases: Vec<LoadedCase>,
    /// Their results, in the same order.
    pub results: Vec<CaseResult>,
    /// Fixture files or cases that could not be read.
    pub input_errors: Vec<String>,
}

/// Whether a result is a discrepancy: a disagreement, a failure, or a missed
/// `expect`.
fn is_discrepancy(r: &EngineResult) -> bool {
    matches!(r.verdict, Verdict::Disagree { .. } | Verdict::Failed { .. })
        || r.expect_mismatches.as_ref().is_some_and(|m| !m.is_empty())
}

impl Judged {
    /// `engine`'s results with the case each belongs to.
    fn of<'a>(&'a self, engine: &'a str) -> impl Iterator<Item = (&'a LoadedCase, &'a CaseResult, &'a EngineResult)> {
        self.cases
            .iter()
            .zip(&self.results)
            .filter_map(move |(lc, c)| c.engines.iter().find(|r| r.engine == engine).map(|r| (lc, c, r)))
    }

    /// How many cases `engine` disagrees on, fails, or misses the `expect` of.
    pub fn disagreements(&self, engine: &str) -> usize {
        self.of(engine).filter(|(_, _, r)| is_discrepancy(r)).count()
    }

    /// `engine`'s verdict counts: `(agree, disagree, borderline, unsupported,
    /// failed)` — a known divergence counts as agree.
    pub fn counts(&self, engine: &str) -> (usize, usize, usize, usize, usize) {
        let mut n = (0, 0, 0, 0, 0);
        for (_, _, r) in self.of(engine) {
            match r.verdict {
                Verdict::Agree | Verdict::KnownDivergence { .. } => n.0 += 1,
                Verdict::Disagree { .. } => n.1 += 1,
                Verdict::Borderline { .. } => n.2 += 1,
                Verdict::Unsupported { .. } => n.3 += 1,
                Verdict::Failed { .. } => n.4 += 1,
            }
        }
        n
    }

    /// The discrepancy table of `engine`: one row per case it gets wrong (its
    /// origin, query, verdict and reasons), at most [`TABLE_ROWS`] rows, and for
    /// the first the case as a fixture file to replay with `crashtest check`.
    pub fn table(&self, engine: &str) -> String {
        let wrong: Vec<_> = self.of(engine).filter(|(_, _, r)| is_discrepancy(r)).collect();
        let (agree, disagree, borderline, unsupported, failed) = self.counts(engine);
        let mut s = String::new();
        let _ = writeln!(
            s,
            "crashtest: {engine} on {} cases: {agree} agree, {disagree} disagree, {borderline} borderline, \
             {unsupported} unsupported, {failed} failed; {} discrepancies",
            self.results.len(),
            wrong.len()
        );
        for e in &self.input_errors {
            let _ = writeln!(s, "input error: {e}");
        }
        if wrong.is_empty() {
            return s;
        }
        let _ = writeln!(s, "| case | query | verdict | why |\n|---|---|---|---|");
        for (lc, c, r) in wrong.iter().take(TABLE_ROWS) {
            let mut why: Vec<String> = match &r.verdict {
                Verdict::Disagree { reasons } => reasons.clone(),
                Verdict::Failed { reason } => vec![reason.clone()],
                _ => Vec::new(),
            };
            for m in r.expect_mismatches.iter().flatten() {
                why.push(format!("expect.{}: want {}, got {}", m.field, m.expected, m.got));
            }
            let origin = if lc.case.source.starts_with("generated") { &lc.case.source } else { &c.file };
            let _ = writeln!(s, "| {} ({origin}) | {} | {} | {} |", c.name, c.query, r.verdict.label(), why.join("; "));
        }
        if wrong.len() > TABLE_ROWS {
            let _ = writeln!(s, "… and {} more", wrong.len() - TABLE_ROWS);
        }
        let (lc, _, _) = wrong[0];
        let replay = harness::case::FixtureFile { schema: harness::case::SCHEMA.into(), cases: vec![lc.case.clone()] };
        if let Ok(json) = serde_json::to_string(&replay) {
            let _ = writeln!(s, "replay the first (save it, then `crashtest check FILE`):\n{json}");
        }
        s
    }

    /// Panics with [`Judged::table`] when `engine` has a discrepancy or a
    /// fixture could not be read.
    #[track_caller]
    pub fn assert_agrees(&self, engine: &str) {
        if self.disagreements(engine) > 0 || !self.input_errors.is_empty() {
            panic!("{}", self.table(engine));
        }
        if self.of(engine).all(|(_, _, r)| matches!(r.verdict, Verdict::Unsupported { .. })) {
            panic!("crashtest: {engine} answered none of the {} cases", self.results.len());
        }
    }
}

/// Rows of a discrepancy table: 20. Reason: enough to see a pattern; the count
/// above the table says how many there are.
pub const TABLE_ROWS: usize = 20;
