//! The command line as a user meets it: exit codes, the closing line, and the
//! messages for bad input (file, case, field; line and column for JSON syntax),
//! with the rest of the run still checked.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs crashtest: its exit code, standard output and standard error.
fn crashtest(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest")).args(args).output().expect("crashtest runs");
    let text = |b: &[u8]| String::from_utf8_lossy(b).to_string();
    (out.status.code().unwrap_or(-1), text(&out.stdout), text(&out.stderr))
}

/// A scratch folder of this test binary, emptied first.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

const GOOD: &str = r#"{
  "schema": "crashtest-fixture/1",
  "cases": [
    {
      "name": "ball sunk half a unit into the ground",
      "source": "the format's example (docs/FORMAT.md): s = 0.5, depth = r − s = 0.5, p = M − s n = 0",
      "query": "contact",
      "a": { "sphere": { "center": [0, 0, 0.5], "radius": 1 } },
      "b": { "plane": { "normal": [0, 0, 1], "offset": 0 } },
      "expect": { "contact": { "point": [0, 0, 0], "normal": [0, 0, 1], "depth": 0.5 } },
      "tol": 1e-12
    }
  ]
}"#;

fn last_line(text: &str) -> &str {
    text.lines().last().unwrap_or("")
}

#[test]
fn the_shipped_fixtures_pass_with_exit_0() {
    let (code, out, err) = crashtest(&["check", "fixtures"]);
    assert_eq!(code, 0, "crashtest check fixtures:\n{out}{err}");
    assert!(last_line(&out).ends_with(" 0 failed (gate: collide/robust)"), "closing line: {}", last_line(&out));
}

#[test]
fn a_good_file_passes_and_the_closing_line_counts_it() {
    let dir = scratch("good");
    std::fs::write(dir.join("good.json"), GOOD).unwrap();
    let (code, out, err) = crashtest(&["check", dir.join("good.json").to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(last_line(&out), "1 passed, 0 failed (gate: collide/robust)");
}

#[test]
fn a_wrong_expectation_exits_1() {
    let dir = scratch("wrong");
    std::fs::write(dir.join("wrong.json"), GOOD.replace("\"depth\": 0.5", "\"depth\": 0.25")).unwrap();
    let (code, out, err) = crashtest(&["check", dir.to_str().unwrap()]);
    assert_eq!(code, 1, "{out}{err}");
    assert_eq!(last_line(&out), "0 passed, 1 failed (gate: collide/robust)");
    assert!(out.contains("expect.contact.depth"), "names the mismatching field:\n{out}");
}

#[test]
fn json_output_is_json_and_the_closing_line_follows() {
    let dir = scratch("json");
    std::fs::write(dir.join("good.json"), GOOD).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .args(["check", "--json", dir.to_str().unwrap()])
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("stdout is JSON");
    assert_eq!(v["passed"], 1);
    assert_eq!(v["cases"][0]["engines"][0]["engine"], "collide/robust");
    assert_eq!(String::from_utf8_lossy(&out.stderr).lines().last(), Some("1 passed, 0 failed (gate: collide/robust)"));
}

/// Each broken file gets one line naming it (and the case and field), on
/// standard error, exit 2, and the good file beside them is still checked.
#[test]
fn bad_input_is_named_and_the_rest_of_the_run_still_happens() {
    let dir = scratch("bad");
    std::fs::write(dir.join("a_good.json"), GOOD).unwrap();
    let case = |name: &str, body: &str| {
        format!(r#"{{"schema": "crashtest-fixture/1", "cases": [{{"name": "{name}", "query": "contact", {body}}}]}}"#)
    };
    let sphere = r#""a": {"sphere": {"center": [0, 0, 0], "radius": 1}}"#;
    let files: &[(&str, String, &[&str])] = &[
        ("syntax.json", "{\n  \"schema\": \"crashtest-fixture/1\",\n  \"cases\": [ {,] }".into(), &["syntax.json:3:", "JSON syntax"]),
        (
            "radius.json",
            case("negative radius", r#""a": {"sphere": {"center": [0,0,0], "radius": -1}}, "b": {"plane": {"normal": [0,0,1], "offset": 0}}"#),
            &["radius.json", "case \"negative radius\"", "a.sphere.radius", "> 0"],
        ),
        (
            "normal.json",
            case("zero normal", &format!(r#"{sphere}, "b": {{"plane": {{"normal": [0,0,0], "offset": 0}}}}"#)),
            &["normal.json", "case \"zero normal\"", "b.plane.normal", "zero normal"],
        ),
        (
            "length.json",
            case("short vector", &format!(r#"{sphere}, "b": {{"sphere": {{"center": [0,0], "radius": 1}}}}"#)),
            &["length.json", "case \"short vector\"", "b.sphere.center", "length"],
        ),
        (
            "missing.json",
            case("no radius", &format!(r#"{sphere}, "b": {{"sphere": {{"center": [0,0,0]}}}}"#)),
            &["missing.json", "case \"no radius\"", "b.sphere", "radius"],
        ),
        (
            "huge.json",
            case("beyond f64", &format!(r#"{sphere}, "b": {{"sphere": {{"center": [0,1e400,0], "radius": 1}}}}"#)),
            &["huge.json:1:", "case \"beyond f64\"", "b.sphere.center", "out of range"],
        ),
        (
            "typed.json",
            case("string radius", &format!(r#"{sphere}, "b": {{"sphere": {{"center": [0,0,0], "radius": "one"}}}}"#)),
            &["typed.json", "case \"string radius\"", "b.sphere.radius"],
        ),
        (
            "query.json",
            r#"{"schema": "crashtest-fixture/1", "cases": [{"name": "what", "query": "teleport", "a": {"point": {"at": [0,0,0]}}}]}"#.into(),
            &["query.json", "case \"what\"", "query", "teleport"],
        ),
        (
            "index.json",
            r#"{"schema": "crashtest-fixture/1", "cases": [{"name": "bad index", "query": "intersect",
               "a": {"segment": {"start": [0,0,1], "end": [0,0,-1]}},
               "b": {"mesh": {"vertices": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,3]]}}}]}"#
                .into(),
            &["index.json", "case \"bad index\"", "b.mesh.triangles[0][2]", "out of range"],
        ),
    ];
    for (name, text, _) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let missing = dir.join("no_such_file.json");
    let (code, out, err) = crashtest(&["check", dir.to_str().unwrap(), missing.to_str().unwrap()]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(!out.lines().any(|l| l.starts_with("error:")), "error lines on standard output:\n{out}");
    for (name, _, needles) in files {
        let line = err
            .lines()
            .find(|l| l.starts_with("error:") && l.contains(name))
            .unwrap_or_else(|| panic!("no error line for {name} on standard error:\n{err}"));
        for n in *needles {
            assert!(line.contains(n), "error line for {name} lacks {n:?}: {line}");
        }
    }
    assert!(
        err.lines().any(|l| l.starts_with("error:") && l.contains("no_such_file.json") && l.contains("cannot read")),
        "{err}"
    );
    assert!(out.contains("PASS") && out.contains("ball sunk half a unit"), "the good file was still checked:\n{out}");
    assert_eq!(last_line(&out), "1 passed, 0 failed (gate: collide/robust)");
}

#[test]
fn one_bad_case_does_not_sink_its_neighbours() {
    let dir = scratch("neighbours");
    let text = GOOD.replace(
        "  ]\n}",
        r#"  , {"name": "huge", "query": "contact", "a": {"sphere": {"center": [1e999, 0, 0], "radius": 1}},
       "b": {"sphere": {"center": [0, 0, 0], "radius": 1}}}
  ]
}"#,
    );
    std::fs::write(dir.join("mixed.json"), text).unwrap();
    let (code, out, err) = crashtest(&["check", dir.to_str().unwrap()]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.contains("case \"huge\"") && err.contains("a.sphere.center"), "{err}");
    assert_eq!(last_line(&out), "1 passed, 0 failed (gate: collide/robust)");
}

#[test]
fn cases_writes_a_fixture_file_that_check_replays() {
    let dir = scratch("cases");
    let (code, out, err) = crashtest(&["cases", "--full-range", "--only", "overlap", "--count", "5", "--start", "3"]);
    assert_eq!(code, 0, "{err}");
    let file: serde_json::Value = serde_json::from_str(&out).expect("a JSON fixture file");
    let cases = file["cases"].as_array().expect("cases");
    assert_eq!(cases.len(), 5);
    assert!(cases[0]["name"].as_str().unwrap_or("").starts_with("overlap full range #3 "), "{}", cases[0]["name"]);
    let path = dir.join("cases.json");
    std::fs::write(&path, &out).unwrap();
    let (code, out, err) = crashtest(&["check", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(last_line(&out), "5 passed, 0 failed (gate: collide/robust)");
    // A range past the last index is bad input, named.
    let (code, _, err) = crashtest(&["cases", "--start", "18446744073709551615", "--count", "2"]);
    assert_eq!(code, 2);
    assert!(err.contains("error: --start 18446744073709551615 + --count 2 overflows"), "{err}");
}

/// A reader that stops early (`crashtest cases | head`) ends the output, not
/// the run: no panic message, and the exit code is the run's own (0 here).
#[test]
fn a_reader_closing_the_pipe_early_is_not_a_panic() {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .args(["cases", "--count", "3000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("crashtest runs");
    let mut first = [0u8; 64];
    child.stdout.take().expect("piped").read_exact(&mut first).expect("the first bytes arrive");
    // The read end is dropped here: every later write hits a closed pipe.
    let out = child.wait_with_output().expect("crashtest ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "stderr: {stderr}");
    assert!(String::from_utf8_lossy(&first).contains("crashtest-fixture/1"));
}

#[test]
fn the_engines_and_the_gate_are_chosen_on_the_command_line() {
    // parry3d-f64 as the gate: the documented parry defects and conventions
    // (a known divergence is not a pass for the gate) fail it, exit 1.
    let (code, out, err) = crashtest(&[
        "check",
        "--engines",
        "collide/robust,parry3d-f64",
        "--gate",
        "parry3d-f64",
        "fixtures/contact.json",
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(last_line(&out).ends_with("(gate: parry3d-f64)"), "{}", last_line(&out));
    let tables: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("  collide") || l.starts_with("  parry") || l.starts_with("  referee"))
        .collect();
    assert!(tables.iter().all(|l| !l.contains("lecture") && !l.contains("f32")), "only the engines chosen: {tables:?}");
    // One engine chosen and no gate named: that engine is the gate.
    let (code, out, _) = crashtest(&["check", "--engines", "collide/robust", "fixtures/contact.json"]);
    assert_eq!(code, 0);
    assert!(last_line(&out).ends_with(" 0 failed (gate: collide/robust)"), "{}", last_line(&out));
}

#[test]
fn an_unknown_engine_or_a_gate_not_chosen_is_refused_before_anything_runs() {
    let (code, out, err) = crashtest(&["check", "--engines", "collide/robust,nope", "fixtures/contact.json"]);
    assert_eq!(code, 2);
    assert!(out.is_empty(), "nothing ran: {out}");
    assert!(err.contains("unknown engine `nope`") && err.contains("parry3d-f64"), "names the engines: {err}");
    let (code, _, err) =
        crashtest(&["check", "--engines", "collide/robust", "--gate", "parry3d", "fixtures/contact.json"]);
    assert_eq!(code, 2);
    assert!(err.contains("the gate `parry3d` is not among the engines judged"), "{err}");
    let out_dir = scratch("bad-engines-report");
    let (code, _, err) = crashtest(&["report", "--engines", "", "--out", out_dir.to_str().unwrap_or(".")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("empty engine name"), "{err}");
    assert!(std::fs::read_dir(&out_dir).map(|d| d.count()).unwrap_or(0) == 0, "no report folder was made");
}
