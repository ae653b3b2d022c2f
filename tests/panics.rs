//! A caught engine panic: one line with its location in the `FAILED` verdict,
//! nothing printed (no message, no backtrace), while a panic outside a caught
//! call still prints. No shipped engine panics on any input the format allows
//! (their adapters refuse what would), so an engine that does is built here;
//! the test runs itself in a child process with backtraces turned on and reads
//! the child's standard error, since the panic hook is process-global.

use harness::check::{PANIC_REASON_PREFIX, check_case, is_caught_panic};
use harness::engine::{Engine, Queries, Reply};
use harness::engines::EngineSet;
use harness::judge::Verdict;
use harness::load::{Loaded, load_str_into};
use oracle::geom::Aabb;
use std::path::Path;
use std::process::Command;

/// Set in the child process: run the panicking cases instead of spawning.
const CHILD: &str = "CRASHTEST_PANICS_CHILD";

/// Cases run in the child: enough that threads overlap in the caught calls.
const CASES: usize = 400;

/// Threads judging them at once (the campaign's rayon pool does the same).
const THREADS: usize = 4;

/// What the engine's panic says.
const MESSAGE: &str = "this engine breaks on boxes left of the origin";

/// Overlap of two boxes, panicking when `a` lies left of the origin.
struct BreaksLeft;

impl Queries for BreaksLeft {
    fn overlap(&self, a: &Aabb, b: &Aabb) -> Reply<bool> {
        if a.max[0] < 0.0 {
            panic!("{MESSAGE}");
        }
        Ok((0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i]))
    }
}

fn cases() -> Loaded {
    let cases: Vec<String> = (0..CASES)
        .map(|i| {
            // Even cases left of the origin (the engine panics), odd ones right.
            let x = if i % 2 == 0 { -10.0 - i as f64 } else { 10.0 + i as f64 };
            format!(
                r#"{{"name": "box {i}", "query": "overlap", "a": {{"aabb": {{"min": [{x}, 0, 0], "max": [{}, 1, 1]}}}},
                   "b": {{"aabb": {{"min": [{}, 0, 0], "max": [{}, 1, 1]}}}}}}"#,
                x + 1.0,
                x + 0.5,
                x + 2.0
            )
        })
        .collect();
    let text = format!(r#"{{"schema": "crashtest-fixture/1", "cases": [{}]}}"#, cases.join(","));
    let mut loaded = Loaded::default();
    load_str_into(Path::new("panics.json"), &text, &mut loaded);
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    loaded
}

/// The child: judge every case on several threads, print each verdict's
/// reason on standard output, then panic once outside a caught call.
fn child() {
    let loaded = cases();
    let set = EngineSet::of(vec![Engine::new("breaks-left", Some(53), BreaksLeft)]);
    let chunk = CASES.div_ceil(THREADS);
    let verdicts: Vec<Verdict> = std::thread::scope(|s| {
        let handles: Vec<_> = loaded
            .cases
            .chunks(chunk)
            .map(|part| {
                let set = &set;
                s.spawn(move || {
                    part.iter().map(|lc| check_case(lc, set).engines[0].verdict.clone()).collect::<Vec<_>>()
                })
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().expect("no judging thread panics")).collect()
    });
    for (i, v) in verdicts.iter().enumerate() {
        match v {
            Verdict::Failed { reason } => println!("case {i} failed: {reason}"),
            other => println!("case {i} {}", other.label()),
        }
        assert_eq!(is_caught_panic(v), i % 2 == 0, "case {i}: {v:?}");
    }
    let genuine = std::thread::spawn(|| panic!("a genuine panic outside any engine call"));
    assert!(genuine.join().is_err());
}

#[test]
fn caught_panics_print_nothing_and_keep_their_location_and_others_still_print() {
    if std::env::var_os(CHILD).is_some() {
        child();
        return;
    }
    let me = std::env::current_exe().expect("the test binary");
    let out = Command::new(me)
        .args(["--exact", "caught_panics_print_nothing_and_keep_their_location_and_others_still_print"])
        .args(["--nocapture", "--test-threads", "1"])
        .env(CHILD, "1")
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the child runs");
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "child failed:\n{stdout}\n{stderr}");
    assert!(!stderr.contains(MESSAGE), "a caught panic printed:\n{stderr}");
    assert!(stderr.contains("a genuine panic outside any engine call"), "the genuine panic was silenced:\n{stderr}");
    assert_eq!(stderr.matches("panicked at").count(), 1, "only the genuine panic prints:\n{stderr}");
    let failed: Vec<&str> = stdout.lines().filter(|l| l.contains(" failed: ")).collect();
    assert_eq!(failed.len(), CASES / 2, "{stdout}");
    for line in failed {
        let reason = line.split(" failed: ").nth(1).unwrap();
        let rest = reason.strip_prefix(PANIC_REASON_PREFIX).unwrap_or_else(|| panic!("{reason}"));
        let (location, message) = rest.split_once(": ").unwrap_or_else(|| panic!("location: message in {reason}"));
        assert_eq!(message, MESSAGE);
        let mut parts = location.rsplitn(3, ':');
        let (column, line_no, file) = (parts.next(), parts.next(), parts.next());
        assert!(
            column.is_some_and(|c| c.parse::<u32>().is_ok())
                && line_no.is_some_and(|l| l.parse::<u32>().is_ok())
                && file.is_some_and(|f| f.ends_with("panics.rs")),
            "file:line:column of the engine's panic in {reason}"
        );
    }
}
