//! Every input path of the command line, hardened: unknown keys at every level
//! of a fixture, a file that is not an object, folders with links back up the
//! tree, paths that are not regular files or are too large, empty selections,
//! sweep counts beyond memory, an unwritable `--out`, merges that would double-count,
//! folders left by killed runs, and `--no-timing` (caught panics: tests/panics.rs). Each test runs
//! the built binary under a time limit (a regression that hangs fails the test
//! instead of hanging it) and checks the exit code and the message.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The workspace root: the runs read `fixtures/` as a user at the root does.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Every run is killed, and its test failed, past this: far more than any of
/// these runs takes (most a second or two; a report with its sections runs
/// every installed peer engine too, a Python process each, about a minute on
/// a loaded 2-core machine), far less than a hang.
const TIME_LIMIT: Duration = Duration::from_secs(300);

/// What one run of crashtest gave.
struct Run {
    code: i32,
    stdout: String,
    stderr: String,
}

impl Run {
    fn both(&self) -> String {
        format!("--- stdout\n{}--- stderr\n{}", self.stdout, self.stderr)
    }

    /// The one `error:` line on standard error that contains every needle.
    fn error_line(&self, needles: &[&str]) -> &str {
        self.stderr
            .lines()
            .find(|l| l.starts_with("error:") && needles.iter().all(|n| l.contains(n)))
            .unwrap_or_else(|| panic!("no error line with {needles:?} on standard error:\n{}", self.both()))
    }

    fn last_stdout_line(&self) -> &str {
        self.stdout.lines().last().unwrap_or("")
    }
}

/// Runs crashtest with `args` (and `envs`), killing it and failing past
/// [`TIME_LIMIT`]. Output is read on threads, so a chatty run cannot block on a
/// full pipe.
fn crashtest_env(args: &[&str], envs: &[(&str, &str)]) -> Run {
    let mut command = Command::new(env!("CARGO_BIN_EXE_crashtest"));
    command.current_dir(ROOT).args(args).envs(envs.iter().copied());
    run_limited(command, &format!("crashtest {args:?}"))
}

/// Runs `command` with its output piped, killing it and failing past
/// [`TIME_LIMIT`]; `what` names it in that failure.
fn run_limited(mut command: Command, what: &str) -> Run {
    let mut child =
        command.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("the command starts");
    let reader = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = r.read_to_end(&mut bytes);
            String::from_utf8_lossy(&bytes).to_string()
        })
    };
    let out = reader(Box::new(child.stdout.take().expect("piped")));
    let err = reader(Box::new(child.stderr.take().expect("piped")));
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what} still running after {TIME_LIMIT:?}: killed");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Run {
        code: status.code().unwrap_or(-1),
        stdout: out.join().expect("stdout read"),
        stderr: err.join().expect("stderr read"),
    }
}

fn crashtest(args: &[&str]) -> Run {
    crashtest_env(args, &[])
}

/// A folder of its own in the system's temporary folder, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("crashtest-inputs-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch folder");
        Scratch(dir)
    }

    fn path(&self, rel: &str) -> PathBuf {
        self.0.join(rel)
    }

    fn write(&self, rel: &str, text: &str) -> PathBuf {
        let p = self.path(rel);
        std::fs::create_dir_all(p.parent().expect("inside")).expect("folder");
        std::fs::write(&p, text).expect("write");
        p
    }

    fn s(&self, rel: &str) -> String {
        self.path(rel).to_str().expect("UTF-8 path").to_string()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// One case that collide/robust passes: a ball sunk half a unit into the ground.
const GOOD_CASE: &str = r#"{
      "name": "ball sunk half a unit into the ground",
      "source": "the format's example (docs/FORMAT.md): s = 0.5, depth = r − s = 0.5, p = M − s n = 0",
      "query": "contact",
      "a": { "sphere": { "center": [0, 0, 0.5], "radius": 1 } },
      "b": { "plane": { "normal": [0, 0, 1], "offset": 0 } },
      "expect": { "contact": { "point": [0, 0, 0], "normal": [0, 0, 1], "depth": 0.5 } },
      "tol": 1e-12
    }"#;

fn file_of(cases: &[&str]) -> String {
    format!("{{\n  \"schema\": \"crashtest-fixture/1\",\n  \"cases\": [\n    {}\n  ]\n}}\n", cases.join(",\n    "))
}

fn good_file() -> String {
    file_of(&[GOOD_CASE])
}

/// `text` with the first `from` replaced by `to`, which must be there.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} not in the text");
    text.replacen(from, to, 1)
}

/// The line and column of the first `needle` in `text`, 1-based.
fn line_col_of(text: &str, needle: &str) -> (usize, usize) {
    let at = text.find(needle).expect("needle in text");
    let before = &text[..at];
    (before.matches('\n').count() + 1, at - before.rfind('\n').map_or(0, |i| i + 1) + 1)
}

/// The line and column of an error line, `file:LINE:COL: …`.
fn position(line: &str, file: &str) -> (usize, usize) {
    let rest = &line[line.find(file).expect("file named") + file.len()..];
    let mut parts = rest.trim_start_matches(':').split(':');
    let n = |p: Option<&str>| p.and_then(|x| x.trim().parse().ok()).unwrap_or_else(|| panic!("no position: {line}"));
    (n(parts.next()), n(parts.next()))
}

#[test]
fn unknown_keys_are_refused_at_every_level_with_file_case_field_and_position() {
    let dir = Scratch::new("unknown");
    dir.write("a_good.json", &good_file());
    // A wrong expectation under a misspelt key: before, it was ignored and the
    // case passed.
    let expected = edit(GOOD_CASE, "\"expect\"", "\"expected\"").replace("\"depth\": 0.5", "\"depth\": 7");
    let tmax = r#"{"name": "tmax typo", "query": "toi",
      "a": {"sphere": {"center": [0, 0, 0], "radius": 1, "velocity": [1, 0, 0]}},
      "b": {"sphere": {"center": [10, 0, 0], "radius": 1}}, "tmax": 20}"#;
    let files: Vec<(&str, String, &str, Vec<&str>)> = vec![
        (
            "top.json",
            edit(&good_file(), "\"cases\"", "\"comment\": \"mine\",\n  \"cases\""),
            "\"comment\"",
            vec!["field `comment`", "unknown field `comment`"],
        ),
        (
            "expected.json",
            file_of(&[&expected]),
            "\"expected\"",
            vec!["case \"ball sunk half a unit into the ground\"", "field `expected`", "unknown field"],
        ),
        ("tmax.json", file_of(&[tmax]), "\"tmax\"", vec!["case \"tmax typo\"", "field `tmax`", "unknown field"]),
        (
            "shape.json",
            file_of(&[&edit(GOOD_CASE, "\"radius\": 1", "\"raduis\": 1")]),
            "\"raduis\"",
            vec!["case \"ball sunk", "field `a.sphere.raduis`", "unknown field"],
        ),
        (
            "beside.json",
            file_of(&[&edit(GOOD_CASE, "\"radius\": 1 } }", "\"radius\": 1 }, \"radius\": 2 }")]),
            "{ \"sphere\"",
            vec!["case \"ball sunk", "field `a`", "exactly one key", "`radius`"],
        ),
        (
            "expect.json",
            file_of(&[&edit(GOOD_CASE, "\"depth\": 0.5", "\"dpeth\": 0.5")]),
            "\"dpeth\"",
            vec!["case \"ball sunk", "field `expect.contact.dpeth`", "unknown field"],
        ),
    ];
    for (name, text, _, _) in &files {
        dir.write(name, text);
    }
    let run = crashtest(&["check", &dir.s("")]);
    assert_eq!(run.code, 2, "{}", run.both());
    for (name, text, at, needles) in &files {
        let mut all = needles.clone();
        all.push(name);
        let line = run.error_line(&all);
        let (l, c) = position(line, name);
        let (want_l, want_c) = line_col_of(text, at);
        // serde reports where it stopped: within the key (or, for a second
        // shape key, at the shape's start).
        assert!(l == want_l && c >= want_c && c <= want_c + at.len(), "{name}: {line} (key at {want_l}:{want_c})");
    }
    assert_eq!(
        run.last_stdout_line(),
        "1 passed, 0 failed (gate: collide/robust)",
        "only the good file's case ran:\n{}",
        run.both()
    );
}

#[test]
fn a_top_level_array_is_refused() {
    let dir = Scratch::new("array");
    let file = dir.write("array.json", &format!("[{GOOD_CASE}]"));
    let pair = dir.write("pair.json", &format!("[\"crashtest-fixture/1\", [{GOOD_CASE}]]"));
    dir.write("good.json", &good_file());
    let run = crashtest(&["check", &dir.s("")]);
    assert_eq!(run.code, 2, "{}", run.both());
    for f in [&file, &pair] {
        let name = f.file_name().unwrap().to_str().unwrap();
        run.error_line(&[name, ":1:1:", "expected an object with `schema` and `cases`"]);
    }
    assert_eq!(run.last_stdout_line(), "1 passed, 0 failed (gate: collide/robust)", "{}", run.both());
}

#[cfg(unix)]
#[test]
fn links_back_up_the_tree_end_the_walk_and_each_file_counts_once() {
    use std::os::unix::fs::symlink;
    let dir = Scratch::new("links");
    let good = dir.write("tree/good.json", &good_file());
    symlink(".", dir.path("tree/a")).unwrap();
    symlink(".", dir.path("tree/b")).unwrap();
    symlink("..", dir.path("tree/up")).unwrap();
    symlink("good.json", dir.path("tree/alias.json")).unwrap();
    let run = crashtest(&["check", &dir.s("tree")]);
    assert_eq!(run.code, 0, "{}", run.both());
    assert_eq!(run.last_stdout_line(), "1 passed, 0 failed (gate: collide/robust)", "{}", run.both());
    // The same file named twice, and through its folder and a link.
    let g = good.to_str().unwrap();
    let run = crashtest(&["check", g, g, &dir.s("tree"), &dir.s("tree/alias.json")]);
    assert_eq!(run.code, 0, "{}", run.both());
    assert_eq!(run.last_stdout_line(), "1 passed, 0 failed (gate: collide/robust)", "{}", run.both());
}

#[cfg(unix)]
#[test]
fn a_fifo_or_a_device_is_refused_at_once_and_the_rest_is_checked() {
    let dir = Scratch::new("fifo");
    dir.write("good.json", &good_file());
    let fifo = dir.path("p.json");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo runs");
    assert!(made.success(), "mkfifo {}", fifo.display());
    let run = crashtest(&["check", &dir.s(""), "/dev/zero"]);
    assert_eq!(run.code, 2, "{}", run.both());
    run.error_line(&["p.json", "not a regular file (a FIFO)"]);
    run.error_line(&["/dev/zero", "not a regular file (a character device)"]);
    assert_eq!(run.last_stdout_line(), "1 passed, 0 failed (gate: collide/robust)", "{}", run.both());
}

#[test]
fn a_file_over_the_size_limit_is_refused_without_reading_it() {
    let dir = Scratch::new("size");
    dir.write("good.json", &good_file());
    // Sparse: the size is there, the disk space is not used.
    let big = std::fs::File::create(dir.path("big.json")).unwrap();
    big.set_len(harness::load::MAX_INPUT_BYTES + 1).unwrap();
    let run = crashtest(&["check", &dir.s("")]);
    assert_eq!(run.code, 2, "{}", run.both());
    run.error_line(&["big.json", &format!("{} bytes", harness::load::MAX_INPUT_BYTES + 1), "limit of 64 MiB"]);
    assert_eq!(run.last_stdout_line(), "1 passed, 0 failed (gate: collide/robust)", "{}", run.both());
}

#[test]
fn a_mesh_file_that_is_not_a_regular_file_is_refused() {
    let dir = Scratch::new("meshdev");
    let case = r#"{"name": "mesh from a device", "query": "intersect",
      "a": {"segment": {"start": [0, 0, 1], "end": [0, 0, -1]}},
      "b": {"mesh": {"file": "/dev/zero.obj"}}}"#;
    dir.write("mesh.json", &file_of(&[case]));
    let run = crashtest(&["check", &dir.s("mesh.json")]);
    assert_eq!(run.code, 2, "{}", run.both());
    run.error_line(&["mesh.json", "case \"mesh from a device\"", "b.mesh.file", "/dev/zero.obj"]);
}

#[test]
fn an_empty_selection_is_bad_input() {
    let dir = Scratch::new("empty");
    std::fs::create_dir_all(dir.path("nothing")).unwrap();
    dir.write("text/readme.txt", "not a case\n");
    dir.write("none/empty.json", "{\"schema\": \"crashtest-fixture/1\", \"cases\": []}");
    for (sel, words) in [
        ("nothing", "no cases found in this folder"),
        ("text", "no cases found in this folder"),
        ("none", "no cases found in the files named"),
    ] {
        let run = crashtest(&["check", &dir.s(sel)]);
        assert_eq!(run.code, 2, "{sel}: {}", run.both());
        run.error_line(&[sel, words]);
        assert_eq!(run.last_stdout_line(), "0 passed, 0 failed (gate: collide/robust)", "{}", run.both());
    }
}

#[test]
fn sweep_counts_beyond_memory_are_refused_before_anything_runs() {
    // (A report streams its cases, a chunk at a time: its counts have no such
    // limit. A sweep still holds its cases.)
    let dir = Scratch::new("counts");
    let out = dir.s("reports");
    let sweep = harness::sweep::find("angle").expect("the angle sweep");
    let max = harness::sweep::max_poses(sweep);
    for n in ["18446744073709551615", &(max + 1).to_string()] {
        let run = crashtest(&["sweep", "angle", "--poses", n, "--out", &out]);
        assert_eq!(run.code, 2, "--poses {n}: {}", run.both());
        run.error_line(&[&format!("--poses {n}"), &format!("largest allowed for sweep angle, {max} poses")]);
    }
    assert!(!dir.path("reports").exists(), "nothing was written");
}

#[test]
fn an_unwritable_out_is_refused_before_the_run() {
    let dir = Scratch::new("out");
    let file = dir.write("a_file", "not a folder\n");
    let file = file.to_str().unwrap();
    for out in [file, "/proc/crashtest-cannot-be-here"] {
        // The default campaign takes minutes; the refusal must come first.
        let run = crashtest(&["report", "--out", out]);
        assert_eq!(run.code, 2, "report --out {out}: {}", run.both());
        run.error_line(&["cannot write the report under", out]);
        let run = crashtest(&["merge", &dir.s("no-report"), "--out", out]);
        assert_eq!(run.code, 2, "merge --out {out}: {}", run.both());
        run.error_line(&["cannot write the report under", out]);
        let run = crashtest(&["sweep", "angle", "--out", out]);
        assert_eq!(run.code, 2, "sweep --out {out}: {}", run.both());
        run.error_line(&["cannot write under", out]);
    }
    let run = crashtest(&["report", "--out", file]);
    run.error_line(&["it exists and is not a folder"]);
}

/// A tiny report (overlap only: the cheapest query) of `cases` per query, into
/// its own root; returns the report's folder.
fn tiny_report(dir: &Scratch, root: &str, extra: &[&str]) -> PathBuf {
    let out = dir.s(root);
    let mut args = vec!["report", "--cases", "10", "--full-range", "2", "--no-sections", "--no-timing", "--out", &out];
    if !extra.contains(&"--only") {
        args.extend(["--only", "overlap"]);
    }
    args.extend(extra);
    let run = crashtest(&args);
    assert_eq!(run.code, 0, "report {extra:?}: {}", run.both());
    let latest = Path::new(&out).join("latest");
    Path::new(&out).join(std::fs::read_link(&latest).expect("latest names the report"))
}

#[test]
fn merge_refuses_what_would_double_count_or_leave_shards_out() {
    let dir = Scratch::new("merge");
    let whole = tiny_report(&dir, "whole", &[]);
    let s02 = tiny_report(&dir, "s02", &["--shard", "0/2"]);
    let s12 = tiny_report(&dir, "s12", &["--shard", "1/2"]);
    let s03 = tiny_report(&dir, "s03", &["--shard", "0/3"]);
    let s13 = tiny_report(&dir, "s13", &["--shard", "1/3"]);
    let s12_seed = tiny_report(&dir, "s12seed", &["--shard", "1/2", "--seed", "99"]);
    let s12_only = tiny_report(&dir, "s12only", &["--shard", "1/2", "--only", "bounds"]);
    let s12_ulps = tiny_report(&dir, "s12ulps", &["--shard", "1/2", "--ulps", "4"]);
    let copy = dir.path("s02copy");
    std::fs::create_dir_all(&copy).unwrap();
    for f in ["summary.json", "discrepancies.json"] {
        std::fs::copy(s02.join(f), copy.join(f)).unwrap();
    }
    let out = dir.s("merged");
    let p = |d: &PathBuf| d.to_str().unwrap().to_string();
    let cases: Vec<(Vec<String>, Vec<String>)> = vec![
        (vec![p(&whole), p(&whole)], vec![p(&whole), "given twice".into()]),
        (vec![p(&whole), p(&s02)], vec![p(&whole), "is a whole report".into()]),
        (vec![p(&s02), p(&s13)], vec!["different splits".into(), "0/2".into(), "1/3".into()]),
        (vec![p(&s02), p(&copy)], vec!["shard 0/2 given twice".into(), p(&copy)]),
        (vec![p(&s03), p(&s13)], vec!["incomplete shard set".into(), "missing 2/3".into()]),
        (vec![p(&s13)], vec!["incomplete shard set".into(), "missing 0/3, 2/3".into()]),
        (vec![p(&s02), p(&s12_seed)], vec!["different campaigns".into(), "seed 99".into()]),
        (vec![p(&s02), p(&s12_only)], vec!["different campaigns".into(), "--only bounds".into()]),
        (vec![p(&s02), p(&s12_ulps)], vec!["different rules".into(), "--ulps 4".into()]),
    ];
    for (reports, needles) in &cases {
        let mut args = vec!["merge", "--out", &out];
        args.extend(reports.iter().map(String::as_str));
        let run = crashtest(&args);
        assert_eq!(run.code, 2, "merge {reports:?}: {}", run.both());
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        run.error_line(&needles);
    }
    assert!(!Path::new(&out).join("latest").exists(), "no refused merge wrote a report");
    let run = crashtest(&["merge", "--out", &out, &p(&s12), &p(&s02)]);
    assert_eq!(run.code, 0, "{}", run.both());
    assert!(run.stdout.contains("merged 2 shards"), "{}", run.both());
    let run = crashtest(&["merge", "--out", &out, &p(&whole)]);
    assert_eq!(run.code, 0, "one whole report is merged as it is: {}", run.both());
}

#[cfg(target_os = "linux")]
#[test]
fn a_killed_runs_folder_is_removed_and_a_live_ones_kept() {
    use harness::report::write::{INCOMPLETE_PREFIX, incomplete_suffix};
    let dir = Scratch::new("abandoned");
    // This process's suffix with its id replaced: by one that has ended, and
    // kept (this process is alive).
    let mut gone = Command::new("true").spawn().expect("true runs");
    let gone_pid = gone.id();
    gone.wait().unwrap();
    let ours = incomplete_suffix();
    let host_part = ours.rsplit_once('-').unwrap().0;
    let folder = |id: &str, suffix: &str| {
        let f = dir.write(&format!("reports/{INCOMPLETE_PREFIX}{id}{suffix}/summary.json"), "{}\n");
        f.parent().unwrap().to_path_buf()
    };
    let dead = folder("20250101T000000Z-seed1", &format!("{host_part}-{gone_pid}"));
    let live = folder("20250101T000000Z-seed2", &ours);
    // The same dead id written from another machine: its process cannot be
    // looked up here.
    let elsewhere = folder("20250101T000000Z-seed3", &format!("-another_machine-{gone_pid}"));
    let run = crashtest(&[
        "report",
        "--cases",
        "2",
        "--full-range",
        "2",
        "--only",
        "overlap",
        "--no-sections",
        "--no-timing",
        "--out",
        &dir.s("reports"),
    ]);
    assert_eq!(run.code, 0, "{}", run.both());
    assert!(run.stderr.contains(&format!("removed {}", dead.display())), "{}", run.both());
    assert!(!dead.exists(), "the killed run's folder is still there");
    assert!(live.exists(), "a live process's folder was removed");
    assert!(elsewhere.exists(), "another machine's folder was removed");
}

#[test]
fn no_timing_times_nothing_in_the_time_of_impact_section() {
    let dir = Scratch::new("notiming");
    let out = dir.s("reports");
    // The built-in engines only: the peers' sections are tested with them
    // (crates/cli/tests/peers.rs), and the toi section's rule is the same.
    let engines = "collide/robust,collide/lecture,parry3d-f64";
    let run =
        crashtest(&["report", "--engines", engines, "--cases", "1", "--full-range", "1", "--no-timing", "--out", &out]);
    assert_eq!(run.code, 0, "{}", run.both());
    let toi: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path("reports/latest/toi.json")).unwrap()).unwrap();
    let methods = toi["methods"].as_array().expect("methods");
    assert!(!methods.is_empty() && methods.iter().all(|m| m["ns_per_query"].is_null()), "{methods:?}");
    let md = std::fs::read_to_string(dir.path("reports/latest/summary.md")).unwrap();
    assert!(md.contains("nothing was timed (the report was run with --no-timing)"), "the section says so");
}

/// `findings` prints a report's findings; `diff` compares two reports, exits
/// 1 when a gated engine got worse and 2 for bad input; `merge` adds the
/// shards' findings up.
#[test]
fn findings_diff_and_merge_from_the_command_line() {
    let s = Scratch::new("findings");
    let out = |name: &str| s.path(name).display().to_string();
    let report = |seed: &str, dir: &str, extra: &[&str]| {
        let mut args = vec![
            "report",
            "--only",
            "toi",
            "--cases",
            "400",
            "--full-range",
            "0",
            "--no-sections",
            "--no-timing",
            "--engines",
            "collide/robust,collide/lecture",
            "--seed",
            seed,
        ];
        args.extend_from_slice(extra);
        let d = out(dir);
        args.extend_from_slice(&["--out", &d]);
        let r = crashtest(&args);
        assert_eq!(r.code, 0, "{}", r.both());
        format!("{d}/latest")
    };
    let (a, b) = (report("1", "a", &[]), report("2", "b", &[]));
    let f = crashtest(&["findings", &a]);
    assert_eq!(f.code, 0, "{}", f.both());
    assert!(f.stdout.contains("collide/lecture: toi") && f.stdout.contains("replay: crashtest check"), "{}", f.both());
    let none = crashtest(&["findings", &out("a")]);
    assert_eq!(none.code, 2, "{}", none.both());
    assert!(none.stderr.contains("findings.json"), "{}", none.both());

    let same = crashtest(&["diff", &a, &b, "--engine", "collide/robust", "--engine", "collide/lecture"]);
    assert_eq!(same.code, 0, "two seeds of unchanged engines: {}", same.both());
    let worse = crashtest(&["diff", &a, &b, "--engine", "collide/robust", "--as", "collide/robust=collide/lecture"]);
    assert_eq!(worse.code, 1, "the lecture's methods in place of the robust ones: {}", worse.both());
    assert!(worse.stderr.contains("worse: collide/robust"), "{}", worse.both());
    let unknown = crashtest(&["diff", &a, &b, "--engine", "collide/robustt"]);
    assert_eq!(unknown.code, 2, "{}", unknown.both());
    assert!(unknown.stderr.contains("--engine collide/robustt"), "{}", unknown.both());
    let bad = crashtest(&["diff", &a, &b, "--as", "collide/robust"]);
    assert_eq!(bad.code, 2, "{}", bad.both());

    let (s0, s1) = (report("1", "s", &["--shard", "0/2"]), report("1", "s", &["--shard", "1/2"]));
    let _ = (s0, s1);
    let shards: Vec<String> = std::fs::read_dir(s.path("s"))
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().contains("-shard")))
        .map(|p| p.display().to_string())
        .collect();
    assert_eq!(shards.len(), 2, "{shards:?}");
    let m = crashtest(&["merge", &shards[0], &shards[1], "--out", &out("m")]);
    assert_eq!(m.code, 0, "{}", m.both());
    let read = |dir: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(format!("{dir}/findings.json")).unwrap()).unwrap()
    };
    let (merged, whole) = (read(&format!("{}/latest", out("m"))), read(&a));
    assert_eq!(merged["discrepancies"], whole["discrepancies"], "the shards' findings add up to the whole run's");
    let count = |v: &serde_json::Value| v["findings"].as_array().map_or(0, Vec::len);
    assert_eq!(count(&merged), count(&whole));
}

/// Four shards started as a scheduler starts them — four processes at once,
/// each told its shard only by a Slurm job array's variables — and merged, give
/// the summary and findings of one unsharded run of the same campaign.
#[test]
fn four_scheduled_shards_merge_into_the_unsharded_run() {
    let s = Scratch::new("scheduled-shards");
    let args = |dir: &str| -> Vec<String> {
        [
            "report",
            "--cases",
            "300",
            "--full-range",
            "30",
            "--no-sections",
            "--no-timing",
            "--engines",
            "collide/robust,collide/lecture,collide-f32/robust,parry3d-f64",
            "--seed",
            "5",
            "--out",
            &s.s(dir),
        ]
        .map(String::from)
        .to_vec()
    };
    let run = |dir: &str, env: Vec<(String, String)>| {
        let a = args(dir);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        let e: Vec<(&str, &str)> = env.iter().map(|(k, v)| (k.as_str(), v.as_str())).collect();
        crashtest_env(&a, &e)
    };
    let whole = run("whole", Vec::new());
    assert_eq!(whole.code, 0, "{}", whole.both());
    // Task ids 1..=4, as `sbatch --array=1-4` numbers them.
    let shards: Vec<Run> = std::thread::scope(|scope| {
        let handles: Vec<_> = (1..=4)
            .map(|id| {
                let env = [
                    ("SLURM_ARRAY_TASK_ID", id.to_string()),
                    ("SLURM_ARRAY_TASK_MIN", "1".into()),
                    ("SLURM_ARRAY_TASK_MAX", "4".into()),
                    ("SLURM_ARRAY_TASK_COUNT", "4".into()),
                ];
                let env: Vec<(String, String)> = env.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
                scope.spawn(move || run("shards", env))
            })
            .collect();
        handles.into_iter().map(|h| h.join().expect("shard thread")).collect()
    });
    for (i, r) in shards.iter().enumerate() {
        assert_eq!(r.code, 0, "shard {i}: {}", r.both());
        assert!(r.stdout.contains(&format!("shard {i}/4 (from SLURM_ARRAY_TASK_ID={}", i + 1)), "{}", r.both());
    }
    let dirs: Vec<String> = std::fs::read_dir(s.path("shards"))
        .expect("shard reports")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().contains("-shard")))
        .map(|p| p.display().to_string())
        .collect();
    assert_eq!(dirs.len(), 4, "{dirs:?}");
    let mut merge = vec!["merge".to_string()];
    merge.extend(dirs);
    merge.extend(["--out".to_string(), s.s("merged")]);
    let m = crashtest(&merge.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(m.code, 0, "{}", m.both());
    let read = |dir: PathBuf, file: &str| -> serde_json::Value {
        let text = std::fs::read_to_string(dir.join("latest").join(file)).expect("report file");
        serde_json::from_str(&text).expect("JSON")
    };
    let (merged, one) = (read(s.path("merged"), "summary.json"), read(s.path("whole"), "summary.json"));
    // Counts and histograms are integers and exact sums; the timings (off here)
    // and the provenance (times, shards) are the run's own.
    for field in ["stats", "full_range", "discrepancies"] {
        assert!(merged[field] == one[field], "{field}: the merged shards differ from the unsharded run");
    }
    assert_eq!(merged["provenance"]["random_cases"], one["provenance"]["random_cases"]);
    assert_eq!(merged["provenance"]["fixture_cases"], one["provenance"]["fixture_cases"]);
    let causes = |v: &serde_json::Value| -> Vec<(String, u64)> {
        let mut c: Vec<(String, u64)> = v["findings"]
            .as_array()
            .expect("findings")
            .iter()
            .map(|f| (f["title"].as_str().unwrap_or_default().to_string(), f["count"].as_u64().unwrap_or(0)))
            .collect();
        c.sort();
        c
    };
    let (mf, wf) = (read(s.path("merged"), "findings.json"), read(s.path("whole"), "findings.json"));
    assert!(!causes(&wf).is_empty(), "the lecture's engines give findings at 300 cases");
    assert_eq!(causes(&mf), causes(&wf), "the merged shards' findings differ from the unsharded run's");
}

/// The Slurm scripts of docs/scale, run by hand as Slurm runs them: two array
/// tasks of crashtest.sbatch (no SLURM_ARRAY_JOB_ID, so nothing is queued),
/// then merge.sbatch on their folder, which writes the merged report; with no
/// shards there, merge.sbatch exits 2 and says so.
#[test]
fn the_slurm_scripts_run_and_merge_their_shards() {
    let s = Scratch::new("slurm-scripts");
    let script = |name: &str, env: &[(&str, &str)]| -> Run {
        let mut command = Command::new("bash");
        command
            .current_dir(ROOT)
            .arg(format!("docs/scale/{name}"))
            .env("CRASHTEST", env!("CARGO_BIN_EXE_crashtest"))
            .envs(env.iter().copied());
        run_limited(command, name)
    };
    let out = s.s("campaign");
    for id in ["0", "1"] {
        let r = script(
            "crashtest.sbatch",
            &[
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_MIN", "0"),
                ("SLURM_ARRAY_TASK_COUNT", "2"),
                ("CASES", "100"),
                ("OUT", &out),
                ("ARGS", "--full-range 10 --no-sections --engines collide/robust,collide/lecture"),
            ],
        );
        assert_eq!(r.code, 0, "task {id}: {}", r.both());
        assert!(r.stdout.contains(&format!("shard {id}/2 (from SLURM_ARRAY_TASK_ID={id}")), "{}", r.both());
    }
    let m = script("merge.sbatch", &[("OUT", &out)]);
    assert_eq!(m.code, 0, "{}", m.both());
    assert!(m.stdout.contains("merged 2 shards"), "{}", m.both());
    let summary = std::fs::read_to_string(s.path("campaign/latest/summary.json")).expect("the merged report");
    let summary: serde_json::Value = serde_json::from_str(&summary).expect("JSON");
    assert_eq!(summary["provenance"]["shards"], serde_json::json!([[0, 2], [1, 2]]));
    let none = script("merge.sbatch", &[("OUT", &s.s("empty"))]);
    assert_eq!(none.code, 2, "{}", none.both());
    assert!(none.stderr.contains("no shard reports"), "{}", none.both());
}

/// Run from a folder that is not the repository, `crashtest report` reads the
/// same built-in fixtures (embedded in the binary) and finds the same peer
/// engines' list (by its documented rule, named in the provenance) as from
/// the repository's root: the same cases, the same counts.
#[test]
fn a_report_from_another_folder_runs_the_same_cases() {
    let dir = Scratch::new("elsewhere");
    let away = dir.path("away");
    std::fs::create_dir_all(&away).unwrap();
    let args = |out: &str| {
        ["report", "--cases", "5", "--full-range", "1", "--no-sections", "--no-timing", "--engines", "collide/robust"]
            .into_iter()
            .map(String::from)
            .chain(["--out".to_string(), out.to_string()])
            .collect::<Vec<_>>()
    };
    let summary = |out: &str| -> serde_json::Value {
        let latest = Path::new(out).join("latest");
        let text = std::fs::read_to_string(latest.join("summary.json")).expect("a summary");
        serde_json::from_str(&text).expect("JSON")
    };
    let at_root = crashtest(&args(&dir.s("root")).iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(at_root.code, 0, "{}", at_root.both());
    let mut command = Command::new(env!("CARGO_BIN_EXE_crashtest"));
    command.current_dir(&away).args(args(&dir.s("away/reports"))).env_remove("CRASHTEST_PEERS");
    let elsewhere = run_limited(command, "crashtest report from another folder");
    assert_eq!(elsewhere.code, 0, "{}", elsewhere.both());
    assert!(!elsewhere.stderr.contains("cannot read"), "{}", elsewhere.both());
    let (mut a, mut b) = (summary(&dir.s("root")), summary(&dir.s("away/reports")));
    // The bench's figures are read from the folder a run starts in (its
    // `--bench-figures`): not a case, left out of the comparison.
    for s in [&mut a, &mut b] {
        for row in s["stats"].as_array_mut().expect("stats") {
            row.as_object_mut().expect("a row").remove("bench_ns");
        }
    }
    let fixtures = a["provenance"]["fixture_cases"].as_u64().expect("a count");
    assert!(fixtures >= 250, "{fixtures} fixture cases");
    assert_eq!(a["provenance"]["fixture_cases"], b["provenance"]["fixture_cases"]);
    assert_eq!(a["stats"], b["stats"], "the same cases give the same counts and errors");
    let peers = b["provenance"]["peers"].as_str().expect("the peers' list is named");
    assert!(peers.contains("engines.json (the repository crashtest was built from)"), "{peers}");
}
