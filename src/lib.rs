//! # crashtest — judge your collision code against an exact referee
//!
//! Write an engine (implement [`Queries`] for the pairs you answer; the rest say
//! [`Unsupported`]), name it with [`Engine::new`], and get:
//!
//! - verdicts on fixture files with your engine as the gate ([`check`]);
//! - the full report — per-query accuracy and speed beside collide and parry,
//!   the full-range family, the stability sweeps and every section that applies
//!   ([`Campaign`]);
//! - a test for your own `cargo test` that fails with the discrepancy table
//!   when your engine disagrees with the referee ([`testing::assert_agrees`]).
//!
//! ```
//! use crashtest::{Engine, EngineSet, Queries, Reply};
//! use crashtest::geom::{Aabb, Query};
//!
//! /// Boxes overlap when they overlap on every axis (touching counts).
//! struct Boxes;
//! impl Queries for Boxes {
//!     fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
//!         Ok((0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]))
//!     }
//! }
//!
//! let mine = Engine::new("boxes", Some(53), Boxes);
//! let set = EngineSet::with_builtins(mine, &["collide/robust"]).unwrap();
//! let result = crashtest::testing::Judge::new(set).only(Query::Overlap).cases(200).run();
//! assert_eq!(result.disagreements("boxes"), 0, "{}", result.table("boxes"));
//! ```
//!
//! Everything an engine needs to be written is in the light crate
//! `crashtest-core`, re-exported here; an engine crate can depend on that alone.
#![deny(missing_docs)]

pub mod testing;

pub use crashtest_core::engine::{Answer, Queries, Reply, Unsupported};
pub use crashtest_core::mesh::Mesh;
pub use crashtest_core::pair::{Pair, Query, ShapeKind};
pub use harness::check::{CheckResult, check_case};
pub use harness::engine::Engine;
pub use harness::engines::{DEFAULT_ENGINE, EngineSet};
pub use harness::report::campaign::{DEFAULT_CASES, DEFAULT_FULL_RANGE_CASES, DEFAULT_SEED};

/// The geometry values every engine speaks (plain `f64`, the fixture format's
/// conventions), their vector operations, and the query kinds.
pub mod geom {
    pub use crashtest_core::geom::*;
    pub use crashtest_core::pair::{Pair, Query, ShapeKind};
    pub use crashtest_core::vec3;
}

/// The lower-level machinery (loading, judging, generators, report parts), for
/// what the entry points here do not cover.
pub use harness;

use std::path::{Path, PathBuf};

pub use harness::engines::listed::Listed;
pub use harness::protocol::ProcessSpec;

/// The process engines of the command line: `NAME=COMMAND` specs and an engines
/// file ([`harness::engines::listed`]: `{"engines": {"NAME": ["program", "arg",
/// …]}}`, or an entry `{"command": […], "known": "file"}` that carries known
/// divergences), each with the time limit `timeout_seconds` per batch. The
/// error names the spec, or the file and the field.
///
/// ```
/// let listed = crashtest::process_engines(&["mine=python3 engine.py".into()], None, 30.0).unwrap();
/// let spec = &listed[0].spec;
/// assert_eq!((spec.name.as_str(), spec.args.as_slice()), ("mine", &["engine.py".to_string()][..]));
/// assert!(crashtest::process_engines(&["no command".into()], None, 30.0).is_err());
/// ```
pub fn process_engines(specs: &[String], file: Option<&Path>, timeout_seconds: f64) -> Result<Vec<Listed>, String> {
    if !(timeout_seconds.is_finite() && timeout_seconds > 0.0 && timeout_seconds <= 1e6) {
        return Err(format!("--engine-timeout {timeout_seconds}: a number of seconds above 0 and at most 1e6"));
    }
    let mut out = Vec::new();
    for s in specs {
        let spec = ProcessSpec::parse(s).map_err(|e| format!("--engine {e}"))?;
        out.push(Listed { spec, known: Vec::new(), missing: None, known_file: None });
    }
    if let Some(path) = file {
        out.extend(harness::engines::listed::read(path)?);
    }
    for l in &mut out {
        l.spec.timeout = std::time::Duration::from_secs_f64(timeout_seconds);
    }
    Ok(out)
}

/// The environment variable that names the peer engines' list
/// ([`peer_engines_file`]).
pub const PEERS_VARIABLE: &str = "CRASHTEST_PEERS";

/// The list of the peer engines crashtest ships adapters for
/// (`engines/engines.json`: FCL, Coal, MuJoCo and Bullet through their Python
/// packages, installed by `engines/install`), found by this rule: the file
/// [`PEERS_VARIABLE`] names, when it is set; else the list of the repository
/// this crashtest was built from, when that is still there (so an installed
/// binary finds the peers its repository installed). Returns the file and
/// which rule found it, for the provenance; or why there is none.
pub fn peer_engines_file() -> Result<(PathBuf, String), String> {
    if let Some(p) = std::env::var_os(PEERS_VARIABLE).filter(|p| !p.is_empty()) {
        return Ok((PathBuf::from(p), format!("named by {PEERS_VARIABLE}")));
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR")).join("engines").join("engines.json");
    if built.is_file() {
        Ok((built, "the repository crashtest was built from".into()))
    } else {
        Err(format!(
            "no peer engines' list: {PEERS_VARIABLE} is not set and the repository crashtest was built from is gone \
             ({} is missing)",
            built.display()
        ))
    }
}

/// Starts a process engine and shakes hands; an engine that cannot start is
/// still returned, marked down, so that the run shows its failure on every
/// case instead of stopping.
///
/// ```
/// let spec = crashtest::ProcessSpec::parse("gone=/nonexistent/engine").unwrap();
/// let engine = crashtest::start_process(spec);
/// let why = engine.process().and_then(|p| p.down()).unwrap();
/// assert!(why.contains("cannot start `/nonexistent/engine`"), "{why}");
/// ```
pub fn start_process(spec: ProcessSpec) -> Engine {
    Engine::from_process(harness::protocol::ProcessEngine::start(spec))
}

/// The fixtures shipped with crashtest (the built-in cases), embedded in
/// the binary: give this path where a list of fixture files or folders is
/// asked for ([`harness::builtin::NAME`]).
pub fn builtin_fixtures() -> PathBuf {
    PathBuf::from(harness::builtin::NAME)
}

/// Runs every case of the fixture files and folders `paths` through `engines`,
/// judged against the referee and each case's `expect`. Its
/// [`CheckResult::exit_code`] is 2 for bad input, 1 when the gate engine fails
/// a case, 0 otherwise; [`harness::check::render_text`] prints it as `crashtest
/// check` does.
///
/// ```
/// let set = crashtest::EngineSet::default();
/// let r = crashtest::check(&[crashtest::builtin_fixtures().join("contact.json")], &set);
/// assert_eq!(r.exit_code(), 0, "{}", crashtest::harness::check::render_text(&r));
/// ```
pub fn check(paths: &[PathBuf], engines: &EngineSet) -> CheckResult {
    let loaded = harness::load::load_paths(paths);
    harness::check::check(&loaded.cases, &loaded.errors, engines)
}

/// A campaign: seeded random cases per query kind (and the full-range family),
/// the fixtures, every engine of the set, and the extra sections; it writes
/// the same report `crashtest report` writes.
///
/// ```no_run
/// let written = crashtest::Campaign::new().cases(1000).out("reports").run().expect("report written");
/// println!("{}", written.index.display());
/// ```
#[derive(Clone, Debug)]
pub struct Campaign {
    config: harness::report::campaign::Config,
    out: PathBuf,
}

/// What [`Campaign::run`] wrote.
#[derive(Debug)]
pub struct Written {
    /// The report's folder.
    pub dir: PathBuf,
    /// Its `index.html`.
    pub index: PathBuf,
    /// Everything it measured.
    pub outcome: harness::report::campaign::Outcome,
}

impl Default for Campaign {
    fn default() -> Self {
        Self::new()
    }
}

impl Campaign {
    /// The CLI's defaults: every built-in engine gated by `collide/robust`,
    /// [`DEFAULT_SEED`], [`DEFAULT_CASES`] cases and [`DEFAULT_FULL_RANGE_CASES`]
    /// full-range cases per query kind, the built-in fixtures, timed, with the
    /// extra sections, written under `reports/`.
    pub fn new() -> Self {
        let config = harness::report::campaign::Config {
            fixtures: vec![builtin_fixtures()],
            progress: false,
            ..Default::default()
        };
        Self { config, out: PathBuf::from("reports") }
    }

    /// The engines (and gate) to judge (a [`Campaign::ulps`] given before
    /// stays in force).
    pub fn engines(mut self, engines: EngineSet) -> Self {
        let ulps = engines.ulps.or(self.config.engines.ulps);
        self.config.engines = EngineSet { ulps, ..engines };
        self
    }

    /// Judges with a fixed allowance of `n` ulps of each field's magnitude in
    /// each engine's own precision (the CLI's `--ulps N`; the conditioning
    /// allowances stay): the engines' backward stability to `n` ulps.
    pub fn ulps(mut self, n: u32) -> Self {
        self.config.engines.ulps = Some(f64::from(n));
        self
    }

    /// The seed of the random cases.
    pub fn seed(mut self, seed: u64) -> Self {
        self.config.seed = seed;
        self
    }

    /// Random cases per query kind.
    pub fn cases(mut self, n: u64) -> Self {
        self.config.cases_per_query = n;
        self
    }

    /// Full-range cases per query kind.
    pub fn full_range(mut self, n: u64) -> Self {
        self.config.full_range_per_query = n;
        self
    }

    /// Only this query kind.
    pub fn only(mut self, q: Query) -> Self {
        self.config.only = Some(q);
        self
    }

    /// The fixture files or folders (instead of the built-in ones).
    pub fn fixtures(mut self, paths: Vec<PathBuf>) -> Self {
        self.config.fixtures = paths;
        self
    }

    /// Whether to run the extra sections (sweeps, scene, time of impact,
    /// dynamics).
    pub fn sections(mut self, on: bool) -> Self {
        self.config.sections = on;
        self
    }

    /// Whether to time the engines.
    pub fn timing(mut self, on: bool) -> Self {
        self.config.timing = on;
        self
    }

    /// The folder the report folder goes in.
    pub fn out(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out = dir.into();
        self
    }

    /// The configuration as it stands.
    pub fn config(&self) -> &harness::report::campaign::Config {
        &self.config
    }

    /// Runs it and writes the report. Refused before anything runs: an output
    /// folder that cannot be written.
    pub fn run(&self) -> Result<Written, String> {
        let c = &self.config;
        prepare_out(&self.out)?;
        let started = std::time::SystemTime::now();
        let outcome = harness::report::campaign::run(c, harness::report::provenance::here());
        let mut id = format!("{}-seed{}", harness::report::provenance::stamp(started), c.seed);
        if let Some((i, n)) = c.shard {
            id.push_str(&format!("-shard{i}of{n}"));
        }
        let dir = harness::report::write::write_outcome(&self.out, &id, &outcome)
            .map_err(|e| format!("cannot write the report under {}: {e}", self.out.display()))?;
        Ok(Written { index: dir.join("index.html"), dir, outcome })
    }
}

/// Checks, before any work, that reports can be written under `out` (the
/// folder is created and a file written and removed in it), and removes the
/// folders that killed runs left there (saying so on standard error).
pub fn prepare_out(out: &Path) -> Result<(), String> {
    harness::report::write::probe_writable(out)
        .map_err(|e| format!("cannot write the report under {}: {e}", out.display()))?;
    for (dir, result) in harness::report::write::remove_abandoned(out) {
        match result {
            Ok(()) => eprintln!("removed {}, left by a run that ended before it finished", dir.display()),
            Err(e) => eprintln!("warning: cannot remove {}, left by a run that ended: {e}", dir.display()),
        }
    }
    Ok(())
}
