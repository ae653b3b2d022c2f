//! `crashtest`: the command line. Thin: it parses arguments and calls the harness.

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "crashtest",
    version,
    about = "Is your collision code right, how right, how fast, and where does it break?"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run fixture cases through every engine; compare with each case's `expect`
    /// and with the exact referee. Exit 0 when the gate engine (collide/robust
    /// unless --gate names another) passes every case, 1 when it fails one, 2
    /// for bad input.
    Check {
        #[command(flatten)]
        engines: EngineArgs,
        /// Fixture files, or folders searched recursively for *.json.
        #[arg(required = true)]
        paths: Vec<PathBuf>,
        /// Print the results as JSON on standard output (the closing
        /// `N passed, M failed` line then goes to standard error).
        #[arg(long)]
        json: bool,
    },
    /// Run the campaign (every fixture, seeded random cases per query kind, every
    /// engine, timings) and write a report: reports/<id>/index.html, summary.md,
    /// summary.json, discrepancies.json, charts/*.svg; reports/latest names it.
    Report {
        #[command(flatten)]
        engines: EngineArgs,
        /// Random cases per query kind. A run streams them (a chunk at a time:
        /// its memory does not grow with the count); split a large campaign
        /// across machines with --shard (docs/SCALE.md).
        #[arg(long, default_value_t = harness::report::campaign::DEFAULT_CASES)]
        cases: u64,
        /// Full-range cases per query kind (raw bit patterns, huge, tiny and
        /// subnormal magnitudes, signed zeros, multi-scale scenes), scored
        /// apart in the report's "Full range" table.
        #[arg(long, default_value_t = harness::report::campaign::DEFAULT_FULL_RANGE_CASES)]
        full_range: u64,
        /// Seed of the random cases.
        #[arg(long, default_value_t = harness::report::campaign::DEFAULT_SEED)]
        seed: u64,
        /// Folder the report folders go in.
        #[arg(long, default_value = "reports")]
        out: PathBuf,
        /// Only this query kind (contact, intersect, barycentric, bounds, overlap, toi, response, ccd).
        #[arg(long, value_parser = parse_query)]
        only: Option<harness::case::Query>,
        /// Run one deterministic slice of the cases, `i/n` (0-based): shard i of n.
        /// Without it, a task of a Slurm job array (SLURM_ARRAY_TASK_ID, _MIN,
        /// _COUNT) or a pod of a Kubernetes Indexed Job (JOB_COMPLETION_INDEX,
        /// JOB_COMPLETIONS) runs its own shard (docs/SCALE.md). Join shard
        /// reports with `crashtest merge`.
        #[arg(long, value_parser = parse_shard)]
        shard: Option<(u32, u32)>,
        /// Fixture files or folders to include; `built-in:fixtures`, the
        /// default, names the repository's fixtures embedded in the binary (the
        /// same cases from any folder).
        #[arg(long, default_value = harness::builtin::NAME)]
        fixtures: Vec<PathBuf>,
        /// Skip the timing loops.
        #[arg(long)]
        no_timing: bool,
        /// Skip the extra sections (dynamics, stability sweeps, the scene's
        /// needs, time of impact): only the per-query campaign.
        #[arg(long)]
        no_sections: bool,
        /// The criterion benchmark's figures, written by `cargo bench --bench
        /// queries`; when the file exists, the accuracy–speed charts use them.
        #[arg(long, default_value = "target/criterion/crashtest-bench.json")]
        bench_figures: PathBuf,
        /// Add the CCD benchmark section: the benchmark's sample queries in
        /// DIR (`<scene>/vertex-face/*.csv`, `<scene>/edge-edge/*.csv`)
        /// through every engine that answers ccd and the referee, false
        /// positives, false negatives and time per query (ccd-benchmark.json).
        /// Runs with --no-sections too; a DIR or query that cannot be read is
        /// named and the exit code is 2, the rest of the report still written.
        #[arg(long, value_name = "DIR")]
        ccd_benchmark: Option<PathBuf>,
    },
    /// Join shard reports (folders written by `report --shard`) into one report.
    Merge {
        /// The shard report folders.
        #[arg(required = true)]
        reports: Vec<PathBuf>,
        /// Folder the merged report folder goes in.
        #[arg(long, default_value = "reports")]
        out: PathBuf,
    },
    /// Print a report's findings: each root cause with its engine, pair,
    /// what is wrong, how often, how badly, and the command that replays it.
    Findings {
        /// The report folder (`reports/latest` is the newest).
        #[arg(default_value = "reports/latest")]
        report: PathBuf,
        /// Print findings.json instead.
        #[arg(long)]
        json: bool,
        /// Write the sample a repository keeps instead (`reports/sample`):
        /// findings.md, findings.json without the examples, each finding's
        /// shrunk case and draft, and the overview table.
        #[arg(long, value_name = "DIR")]
        sample: Option<PathBuf>,
    },
    /// Compare two reports: new, fixed and changed findings, and each
    /// engine's score per query kind, telling noise from change. Exit 1 when
    /// an engine named with --engine got worse, 2 for bad input, else 0.
    Diff {
        /// The older report folder.
        old: PathBuf,
        /// The newer report folder.
        new: PathBuf,
        /// An engine whose getting worse fails the diff (exit 1). Repeatable.
        #[arg(long = "engine", value_name = "NAME")]
        gate: Vec<String>,
        /// Compare engine OLD of the older report with engine NEW of the
        /// newer (two versions of one engine under two names). Repeatable.
        #[arg(long = "as", value_name = "OLD=NEW")]
        renames: Vec<String>,
        /// Print the comparison as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Process engines (docs/PROTOCOL.md).
    Engine {
        #[command(subcommand)]
        action: EngineCommand,
    },
    /// Print the JSON Schema of the fixture format (crashtest-fixture/1), or
    /// with --protocol of the engine protocol's messages (crashtest-engine/1).
    Schema {
        /// The engine protocol's messages instead of the fixture format.
        #[arg(long)]
        protocol: bool,
    },
    /// Read a published benchmark's queries into a fixture file.
    Import {
        #[command(subcommand)]
        what: ImportCommand,
    },
    /// Write generated cases as a fixture file on standard output (no
    /// `expect`: `crashtest check` judges them against the referee), to replay
    /// a slice of a campaign or to run it through another build.
    Cases {
        /// The query kind (every kind when absent).
        #[arg(long, value_parser = parse_query)]
        only: Option<harness::case::Query>,
        /// Cases per query kind, from index --start on.
        #[arg(long, default_value_t = 100)]
        count: u64,
        /// The first index.
        #[arg(long, default_value_t = 0)]
        start: u64,
        /// The full-range family's cases instead of the ordinary mix.
        #[arg(long)]
        full_range: bool,
        /// Seed of the cases.
        #[arg(long, default_value_t = harness::report::campaign::DEFAULT_SEED)]
        seed: u64,
    },
    /// Run one stability sweep (a degeneracy parameter over many decades, every
    /// engine against the referee), write its charts (SVG) and data (JSON) into
    /// --out, and print where each engine breaks. Exit 2 for an unknown name.
    Sweep {
        #[command(flatten)]
        engines: EngineArgs,
        /// The sweep (see --list).
        #[arg(required_unless_present = "list")]
        name: Option<String>,
        /// List the sweeps and exit.
        #[arg(long)]
        list: bool,
        /// Folder the charts and data go in.
        #[arg(long, default_value = "reports/sweeps")]
        out: PathBuf,
        /// Random rigid poses per point (at most what the sweep's cases allow
        /// in memory; the message of a larger count names it).
        #[arg(long, default_value_t = harness::sweep::DEFAULT_POSES as u64, value_parser = clap::value_parser!(u64).range(1..))]
        poses: u64,
        /// Seed of the poses.
        #[arg(long, default_value_t = harness::sweep::DEFAULT_SEED)]
        seed: u64,
        /// Also write the cases of the point with this label (`2.5e-9`, or an
        /// exact point's label) as a fixture file for `crashtest check`.
        #[arg(long, value_name = "LABEL")]
        cases_at: Option<String>,
    },
}

/// What `crashtest import` reads.
#[derive(Subcommand)]
enum ImportCommand {
    /// The CCD benchmark's sample queries: a folder of
    /// `<scene>/vertex-face/*.csv` and `<scene>/edge-edge/*.csv` (8 rows of 7
    /// integers per query) written as `ccd` cases whose `expect.impact` is the
    /// benchmark's ground truth. A coordinate that is not exactly a double is
    /// refused with its file, query, row and column; the other queries are
    /// still written, and the exit code is 2.
    CcdBenchmark {
        /// The benchmark folder.
        dir: PathBuf,
        /// The fixture file to write.
        #[arg(short, long)]
        out: PathBuf,
        /// Take this many queries of each file: half (rounded up) with an
        /// impact and half without where the file has them, each evenly
        /// spaced through the file (every query when absent).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        per_file: Option<u64>,
    },
}

/// What `crashtest engine` does.
#[derive(Subcommand)]
enum EngineCommand {
    /// The conformance run of a command speaking crashtest-engine/1: the
    /// handshake, the fixture corpus judged against the referee, malformed-case
    /// probes. Prints what it supports, its scores and every protocol violation;
    /// exit 1 when there was one.
    Test {
        /// Fixture files or folders to send (`built-in:fixtures`, the default:
        /// the ones embedded in the binary).
        #[arg(long, default_value = harness::builtin::NAME)]
        fixtures: Vec<PathBuf>,
        /// The time limit for one batch, in seconds.
        #[arg(long, value_name = "SECONDS", default_value_t = harness::protocol::client::DEFAULT_TIMEOUT.as_secs_f64())]
        engine_timeout: f64,
        /// Print the result as JSON.
        #[arg(long)]
        json: bool,
        /// The engine's command and its arguments.
        #[arg(required = true, trailing_var_arg = true, allow_hyphen_values = true)]
        command: Vec<String>,
    },
}

/// Which engines a command judges.
#[derive(clap::Args)]
struct EngineArgs {
    /// The engines to judge, comma-separated, in report order, or `all`:
    /// collide/robust, collide/lecture, collide-f32/robust, collide-f32/lecture,
    /// parry3d-f64, parry3d, and the process engines of --engine and
    /// --engines-file.
    #[arg(long, default_value = "all")]
    engines: String,
    /// The gate engine, whose answers decide the exit code of `check`
    /// (default collide/robust; with one engine selected, that engine).
    #[arg(long)]
    gate: Option<String>,
    /// A process engine speaking crashtest-engine/1 (docs/PROTOCOL.md):
    /// NAME=COMMAND, the command split on white space. Repeatable.
    #[arg(long = "engine", value_name = "NAME=COMMAND")]
    process: Vec<String>,
    /// A JSON file of named process engines: {"engines": {"NAME": ["program", "arg", ...]}}.
    #[arg(long, value_name = "FILE")]
    engines_file: Option<PathBuf>,
    /// The time limit for one batch of a process engine, in seconds.
    #[arg(long, value_name = "SECONDS", default_value_t = harness::protocol::client::DEFAULT_TIMEOUT.as_secs_f64())]
    engine_timeout: f64,
    /// Cases per batch sent to a process engine.
    #[arg(long, value_name = "N", default_value_t = harness::protocol::client::DEFAULT_BATCH as u64, value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    engine_batch: u64,
    /// Judge with a fixed allowance of N ulps of each field's magnitude in
    /// the engine's own precision instead of the tolerance table's (the
    /// conditioning allowances stay): does the engine agree when held to
    /// backward stability within N ulps? The default verdicts use the table.
    #[arg(long, value_name = "N")]
    ulps: Option<u32>,
}

impl EngineArgs {
    /// The engine set, or the error (printed) and exit code 2.
    fn set(&self) -> Result<crashtest::EngineSet, ExitCode> {
        let fail = |e: String| {
            eprintln!("error: {e}");
            ExitCode::from(2)
        };
        // The peer engines crashtest ships adapters for first, then the user's.
        // A shipped list that does not read leaves the peers out, with the reason,
        // and the run goes on.
        let mut listed = match crashtest::peer_engines_file()
            .and_then(|(file, _)| crashtest::process_engines(&[], Some(&file), self.engine_timeout))
        {
            Ok(l) => l,
            Err(e) => {
                eprintln!("warning: the peer engines are not run: {e}");
                Vec::new()
            }
        };
        listed.extend(
            crashtest::process_engines(&self.process, self.engines_file.as_deref(), self.engine_timeout)
                .map_err(fail)?,
        );
        for l in &mut listed {
            l.spec.batch = self.engine_batch as usize;
        }
        let set = crashtest::EngineSet::select_with(&self.engines, self.gate.as_deref(), listed).map_err(|e| {
            fail(format!("--engines {} --gate {}: {e}", self.engines, self.gate.as_deref().unwrap_or("(default)")))
        })?;
        Ok(crashtest::EngineSet { ulps: self.ulps.map(f64::from), ..set })
    }
}

fn parse_query(s: &str) -> Result<harness::case::Query, String> {
    harness::case::Query::parse(s)
        .ok_or_else(|| format!("unknown query `{s}` (contact, intersect, barycentric, bounds, overlap, toi, response)"))
}

fn parse_shard(s: &str) -> Result<(u32, u32), String> {
    let (i, n) = s.split_once('/').ok_or("expected i/n, for example 0/4")?;
    let i: u32 = i.trim().parse().map_err(|e| format!("shard index: {e}"))?;
    let n: u32 = n.trim().parse().map_err(|e| format!("shard count: {e}"))?;
    if n == 0 || i >= n {
        return Err(format!("shard {i}/{n}: need 0 ≤ i < n"));
    }
    Ok((i, n))
}

/// Writes to standard output. A reader that closed the pipe early
/// (`crashtest cases | head`) is not a failure of the run: the rest of the
/// output is dropped and the exit code stays the run's. Any other write error
/// is reported once, on standard error.
fn emit(text: &str) {
    use std::io::Write;
    use std::sync::atomic::{AtomicBool, Ordering};
    static FAILED: AtomicBool = AtomicBool::new(false);
    if FAILED.load(Ordering::Relaxed) {
        return;
    }
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        FAILED.store(true, Ordering::Relaxed);
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            eprintln!("error: cannot write to standard output: {e}");
        }
    }
}

/// [`emit`] with `format!` arguments.
macro_rules! out {
    ($($arg:tt)*) => { emit(&format!($($arg)*)) };
}

/// [`out!`] and a newline.
macro_rules! outln {
    ($($arg:tt)*) => { emit(&format!("{}\n", format_args!($($arg)*))) };
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { engines, paths, json } => {
            let set = match engines.set() {
                Ok(set) => set,
                Err(code) => return code,
            };
            let result = crashtest::check(&paths, &set);
            for (name, why) in &set.missing {
                eprintln!("note: engine `{name}` not run: {why}");
            }
            if json {
                match serde_json::to_string_pretty(&result) {
                    Ok(s) => outln!("{s}"),
                    Err(e) => eprintln!("error: cannot write JSON: {e}"),
                }
                eprint!("{}", harness::check::render_errors(&result));
                eprint!("{}", harness::check::closing_line(&result));
            } else {
                // The tables, then the errors (standard error), then the closing
                // line: on a terminal it stays the last line.
                let text = harness::check::render_text(&result);
                let closing = harness::check::closing_line(&result);
                out!("{}", text.strip_suffix(&closing).unwrap_or(&text));
                eprint!("{}", harness::check::render_errors(&result));
                out!("{closing}");
            }
            ExitCode::from(result.exit_code() as u8)
        }
        Command::Report {
            engines,
            cases,
            full_range,
            seed,
            out,
            only,
            shard,
            fixtures,
            no_timing,
            no_sections,
            bench_figures,
            ccd_benchmark,
        } => {
            let set = match engines.set() {
                Ok(set) => set,
                Err(code) => return code,
            };
            let shard = match harness::report::shard::resolve(shard, |k| std::env::var(k).ok()) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: the shard: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Some(s) = &shard {
                outln!("shard {}/{} (from {})", s.shard.0, s.shard.1, s.from);
            }
            let shard = shard.map(|s| s.shard);
            if let Err(code) = prepare_out(&out) {
                return code;
            }
            let config = harness::report::campaign::Config {
                seed,
                cases_per_query: cases,
                full_range_per_query: full_range,
                only,
                shard,
                fixtures,
                timing: !no_timing,
                progress: true,
                sections: !no_sections,
                bench: Some(bench_figures),
                engines: set,
                chunk: harness::report::campaign::CHUNK,
            };
            let started = std::time::SystemTime::now();
            let mut provenance = harness::report::provenance::here();
            provenance.peers = Some(match crashtest::peer_engines_file() {
                Ok((file, rule)) => {
                    format!("{} ({rule})", harness::protocol::client::shown_path(&file.to_string_lossy()))
                }
                Err(why) => why,
            });
            let mut outcome = harness::report::campaign::run(&config, provenance);
            // The CCD benchmark's section, as the campaign's own sections: in
            // shard 0 only (a merge carries it).
            if let (Some(_), Some((i, n))) = (&ccd_benchmark, shard)
                && i > 0
            {
                eprintln!(
                    "note: --ccd-benchmark runs in shard 0 of {n} only (merge carries its section); not in shard {i}"
                );
            }
            if let Some(dir) = ccd_benchmark.filter(|_| shard.is_none_or(|(i, _)| i == 0)) {
                let settings = harness::ccd_report::Settings { timing: !no_timing, ..Default::default() };
                let (section, errors) = harness::ccd_report::section(&dir, &settings, &config.engines);
                let seconds = section.data["seconds"].as_f64().unwrap_or(0.0);
                let p = &mut outcome.summary.provenance;
                p.phases.push((format!("sections: {}", section.id), seconds));
                p.wall_seconds += seconds;
                outcome.sections.push(section);
                outcome.input_errors.extend(errors.into_iter().map(|e| format!("--ccd-benchmark: {e}")));
            }
            let mut id = format!("{}-seed{seed}", harness::report::provenance::stamp(started));
            if let Some((i, n)) = shard {
                id.push_str(&format!("-shard{i}of{n}"));
            }
            for e in &outcome.input_errors {
                eprintln!("error: {e}");
            }
            match harness::report::write::write_outcome(&out, &id, &outcome) {
                Ok(dir) => {
                    let p = &outcome.summary.provenance;
                    outln!(
                        "{} cases ({} fixtures, {} random) in {:.1} s; {} discrepancies",
                        p.fixture_cases + p.random_cases,
                        p.fixture_cases,
                        p.random_cases,
                        p.wall_seconds,
                        outcome.summary.discrepancies
                    );
                    if !p.phases.is_empty() {
                        let parts: Vec<String> = p.phases.iter().map(|(name, s)| format!("{name} {s:.1} s")).collect();
                        outln!("  {}", parts.join(" · "));
                    }
                    for (name, rate) in &outcome.summary.throughput {
                        outln!("  {name}: {rate:.0} cases/s");
                    }
                    outln!("report: {}", dir.join("index.html").display());
                }
                Err(e) => {
                    eprintln!("error: cannot write the report under {}: {e}", out.display());
                    return ExitCode::from(1);
                }
            }
            ExitCode::from(if outcome.input_errors.is_empty() { 0 } else { 2 })
        }
        Command::Merge { reports, out } => {
            if let Err(code) = prepare_out(&out) {
                return code;
            }
            // First the set is checked on each shard's provenance alone, then
            // the shards are read and added one at a time: any number of them
            // merge in the memory of one.
            let mut light = Vec::new();
            for dir in &reports {
                match harness::report::write::read_provenance(dir) {
                    Ok(r) => light.push(r),
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::from(2);
                    }
                }
            }
            if let Err(e) = harness::report::write::check_mergeable(&light) {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            drop(light);
            let mut merging = harness::report::write::Merging::default();
            // Shards' findings add up (a shard written before findings were
            // kept has none: the merged report then has none either).
            let mut findings: Option<harness::findings::FindingsFile> = None;
            let mut all_findings = true;
            for dir in &reports {
                match harness::report::write::read_report(dir) {
                    Ok(r) => merging.add(&r),
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::from(2);
                    }
                }
                if all_findings {
                    match harness::findings::read(dir) {
                        Ok(f) => {
                            findings = Some(match findings.take() {
                                None => harness::findings::FindingsFile::merge(&[f]),
                                Some(acc) => harness::findings::FindingsFile::merge(&[acc, f]),
                            });
                        }
                        Err(e) => {
                            eprintln!("note: {e}; the merged report has no findings");
                            all_findings = false;
                            findings = None;
                        }
                    }
                }
            }
            let (summary, discrepancies, sections) = match merging.finish() {
                Ok(m) => m,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            let id = format!(
                "{}-seed{}-merged",
                harness::report::provenance::stamp(std::time::SystemTime::now()),
                summary.provenance.seed
            );
            let dir = format!("{}/{id}", out.display());
            let files =
                harness::report::write::render_files(&summary, &discrepancies, &sections, findings.as_ref(), &dir);
            match harness::report::write::write_report(&out, &id, &files) {
                Ok(dir) => {
                    outln!("merged {} shards: {}", reports.len(), dir.join("index.html").display());
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: cannot write the report under {}: {e}", out.display());
                    ExitCode::from(1)
                }
            }
        }
        Command::Sweep { engines, name, list, out, poses, seed, cases_at } => {
            if list {
                out!("{}", harness::sweep::list_text());
                return ExitCode::SUCCESS;
            }
            let name = name.unwrap_or_default();
            let Some(sweep) = harness::sweep::find(&name) else {
                eprintln!("error: {}", harness::sweep::unknown_name(&name));
                return ExitCode::from(2);
            };
            if let Err(e) = harness::sweep::check_poses(sweep, poses) {
                eprintln!("error: --poses {poses}: {e}");
                return ExitCode::from(2);
            }
            if let Err(e) = harness::report::write::probe_writable(&out) {
                eprintln!("error: cannot write under {}: {e}", out.display());
                return ExitCode::from(2);
            }
            let settings = harness::sweep::Settings { poses: poses as usize, seed };
            let fixture = match cases_at.as_deref().map(|l| (l, harness::sweep::fixture_at(sweep, &settings, l))) {
                Some((label, None)) => {
                    eprintln!("error: sweep {} has no point labelled `{label}`", sweep.name);
                    return ExitCode::from(2);
                }
                Some((label, Some(f))) => Some((label.to_string(), f)),
                None => None,
            };
            let set = match engines.set() {
                Ok(set) => set,
                Err(code) => return code,
            };
            let started = std::time::Instant::now();
            let result = harness::sweep::run(sweep, &settings, &set);
            out!("{}", harness::sweep::table_text(std::slice::from_ref(&result)));
            match harness::sweep::write(&result, &out) {
                Ok(mut files) => {
                    if let Some((label, f)) = fixture {
                        let path = out.join(format!("{}-cases-{label}.json", sweep.name));
                        let text = serde_json::to_string_pretty(&f).unwrap_or_default() + "\n";
                        if let Err(e) = std::fs::write(&path, text) {
                            eprintln!("error: cannot write {}: {e}", path.display());
                            return ExitCode::from(1);
                        }
                        files.push(path);
                    }
                    outln!(
                        "{} in {:.1} s ({poses} poses per point, seed {seed}):",
                        sweep.name,
                        started.elapsed().as_secs_f64()
                    );
                    for f in files {
                        outln!("  {}", f.display());
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: cannot write under {}: {e}", out.display());
                    ExitCode::from(1)
                }
            }
        }
        Command::Engine { action: EngineCommand::Test { fixtures, engine_timeout, json, command } } => {
            // One argument is a whole command line (`engine test "python3 e.py"`).
            let command: Vec<String> = match command.as_slice() {
                [one] => one.split_whitespace().map(String::from).collect(),
                _ => command,
            };
            let name = command.first().map(|p| p.rsplit('/').next().unwrap_or(p).to_string()).unwrap_or_default();
            let mut spec = match crashtest::ProcessSpec::new(&name, command) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if !(engine_timeout.is_finite() && engine_timeout > 0.0 && engine_timeout <= 1e6) {
                eprintln!("error: --engine-timeout {engine_timeout}: a number of seconds above 0 and at most 1e6");
                return ExitCode::from(2);
            }
            spec.timeout = std::time::Duration::from_secs_f64(engine_timeout);
            let loaded = harness::load::load_paths(&fixtures);
            for e in &loaded.errors {
                eprintln!("error: {e}");
            }
            let result = harness::conformance::run(spec, &loaded);
            if json {
                match serde_json::to_string_pretty(&result) {
                    Ok(s) => outln!("{s}"),
                    Err(e) => eprintln!("error: cannot write JSON: {e}"),
                }
            } else {
                out!("{}", harness::conformance::render(&result));
            }
            ExitCode::from(if loaded.errors.is_empty() { result.exit_code() as u8 } else { 2 })
        }
        Command::Findings { report, json, sample } => {
            let file = match harness::findings::read(&report) {
                Ok(f) => f,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Some(dir) = sample {
                let written = harness::report::write::read_report(&report)
                    .and_then(|r| harness::findings::write_sample(&report, &r.summary, &dir));
                return match written {
                    Ok(files) => {
                        outln!("{} files under {}", files.len(), dir.display());
                        ExitCode::SUCCESS
                    }
                    Err(e) => {
                        eprintln!("error: {e}");
                        ExitCode::from(2)
                    }
                };
            }
            if json {
                match serde_json::to_string_pretty(&file) {
                    Ok(s) => outln!("{s}"),
                    Err(e) => eprintln!("error: cannot write JSON: {e}"),
                }
            } else {
                out!("{}", harness::findings::render::text(&file, &report.display().to_string()));
            }
            ExitCode::SUCCESS
        }
        Command::Diff { old, new, gate, renames, json } => {
            let mut pairs = Vec::new();
            for r in &renames {
                match r.split_once('=') {
                    Some((a, b)) if !a.trim().is_empty() && !b.trim().is_empty() => {
                        pairs.push((a.trim().to_string(), b.trim().to_string()))
                    }
                    _ => {
                        eprintln!("error: --as {r}: expected OLD=NEW, two engine names");
                        return ExitCode::from(2);
                    }
                }
            }
            let read = |dir: &std::path::Path| -> Result<(harness::summary::Summary, harness::findings::FindingsFile), String> {
                let r = harness::report::write::read_report(dir)?;
                Ok((r.summary, harness::findings::read(dir)?))
            };
            let (o, n) = match (read(&old), read(&new)) {
                (Ok(o), Ok(n)) => (o, n),
                (Err(e), _) | (_, Err(e)) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            // A gated engine that is not in both reports would pass unseen.
            for g in &gate {
                let old_name = pairs.iter().find(|(_, b)| b == g).map_or(g.as_str(), |(a, _)| a.as_str());
                let has =
                    |s: &harness::summary::Summary, name: &str| s.provenance.engines.iter().any(|e| e.name == name);
                if !has(&o.0, old_name) || !has(&n.0, g) {
                    eprintln!(
                        "error: --engine {g}: not judged in both reports ({} and {})",
                        old.display(),
                        new.display()
                    );
                    return ExitCode::from(2);
                }
            }
            let d = harness::findings::diff::diff((&o.0, &o.1), (&n.0, &n.1), &pairs);
            if json {
                match serde_json::to_string_pretty(&d) {
                    Ok(s) => outln!("{s}"),
                    Err(e) => eprintln!("error: cannot write JSON: {e}"),
                }
            } else {
                out!("{}", d.text());
            }
            let worse = d.worse(&gate);
            if worse.is_empty() {
                ExitCode::SUCCESS
            } else {
                eprintln!("worse: {}", worse.join(", "));
                ExitCode::from(1)
            }
        }
        Command::Schema { protocol } => {
            if protocol {
                out!("{}", harness::protocol::messages::json_schema());
            } else {
                out!("{}", harness::case::json_schema());
            }
            ExitCode::SUCCESS
        }
        Command::Import { what: ImportCommand::CcdBenchmark { dir, out, per_file } } => {
            let (queries, errors) = harness::ccd_benchmark::read_dir(&dir);
            for e in &errors {
                eprintln!("error: {e}");
            }
            let picked = match per_file {
                Some(n) => harness::ccd_benchmark::evenly_per_file(&queries, usize::try_from(n).unwrap_or(usize::MAX)),
                None => queries.iter().collect(),
            };
            let positives = picked.iter().filter(|q| q.truth).count();
            let cases = picked.into_iter().map(|q| q.case.clone()).collect();
            let file = harness::case::FixtureFile { schema: harness::case::SCHEMA.into(), cases };
            let written = serde_json::to_string_pretty(&file)
                .map_err(|e| e.to_string())
                .and_then(|s| std::fs::write(&out, s + "\n").map_err(|e| e.to_string()));
            match written {
                Ok(()) => {
                    eprintln!(
                        "{} queries ({positives} with an impact) of {} read, written to {}",
                        file.cases.len(),
                        queries.len(),
                        out.display()
                    );
                    if errors.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(2) }
                }
                Err(e) => {
                    eprintln!("error: cannot write {}: {e}", out.display());
                    ExitCode::from(2)
                }
            }
        }
        Command::Cases { only, count, start, full_range, seed } => {
            let Some(end) = start.checked_add(count) else {
                eprintln!("error: --start {start} + --count {count} overflows");
                return ExitCode::from(2);
            };
            let mut cases = Vec::new();
            for q in harness::report::campaign::CAMPAIGN_QUERIES {
                if only.is_some_and(|o| o != q) {
                    continue;
                }
                for i in start..end {
                    let lc = if full_range {
                        harness::generate::try_generate_full_range(q, seed, i)
                    } else {
                        harness::generate::try_generate(q, seed, i)
                    };
                    cases.extend(lc.map(|lc| lc.case));
                }
            }
            let file = harness::case::FixtureFile { schema: harness::case::SCHEMA.into(), cases };
            match serde_json::to_string_pretty(&file) {
                Ok(s) => {
                    outln!("{s}");
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: cannot write the cases as JSON: {e}");
                    ExitCode::from(2)
                }
            }
        }
    }
}

/// [`crashtest::prepare_out`], its error printed with exit code 2.
fn prepare_out(out: &std::path::Path) -> Result<(), ExitCode> {
    crashtest::prepare_out(out).map_err(|e| {
        eprintln!("error: {e}");
        ExitCode::from(2)
    })
}
