//! The command line as a user meets it: exit codes, the closing line, and the
//! messages for bad input (file, case, field; line and column for JSON syntax),
//! with the rest of the run still checked.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root: the runs read `fixtures/` as a user at the root does.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Runs crashtest: its exit code, standard output and standard error.
fn crashtest(args: &[&str]) -> (i32, String, String) {
    let out =
        Command::new(env!("CARGO_BIN_EXE_crashtest")).current_dir(ROOT).args(args).output().expect("crashtest runs");
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
        .current_dir(ROOT)
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
        .current_dir(ROOT)
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

// --- report, sweep and malformed mesh files through the binary ---------------

fn report_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn a_report_folder_has_every_file_and_latest_names_it() {
    let out = report_dir("report-files");
    let status = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .current_dir(ROOT)
        .args(["report", "--cases", "40", "--full-range", "10", "--no-timing", "--no-sections", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let latest = out.join("latest");
    // The sections (sweeps, scene, dynamics, …) take most of a report's time
    // and have their own tests; `render::section`'s tests check how they land
    // in a report's files.
    for f in ["index.html", "summary.md", "summary.json", "discrepancies.json", "sections.json"] {
        assert!(latest.join(f).is_file(), "{f} missing");
    }
    let charts = std::fs::read_dir(latest.join("charts")).map(|d| d.count()).unwrap_or(0);
    assert!(charts > 0, "no charts");
}

#[test]
fn killing_a_run_leaves_the_previous_report_intact() {
    let out = report_dir("report-killed");
    let first = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .current_dir(ROOT)
        .args(["report", "--cases", "20", "--full-range", "10", "--no-timing", "--no-sections", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(first.success());
    let before = std::fs::read_link(out.join("latest")).expect("latest is a link");
    let index = std::fs::read_to_string(out.join("latest/index.html")).unwrap();
    // A run large enough to be killed mid-way (it judges 500,000 cases).
    let mut child = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .current_dir(ROOT)
        .args(["report", "--cases", "100000", "--no-sections", "--out"])
        .arg(&out)
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    child.kill().unwrap();
    let _ = child.wait();
    assert_eq!(std::fs::read_link(out.join("latest")).unwrap(), before, "latest moved");
    assert_eq!(std::fs::read_to_string(out.join("latest/index.html")).unwrap(), index, "previous report changed");
}

#[test]
fn an_unknown_sweep_exits_2_and_lists_the_sweeps() {
    let (code, _, err) = crashtest(&["sweep", "tilt"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("unknown sweep `tilt`"), "{err}");
    for name in harness::sweep::names() {
        assert!(err.contains(name), "the message names {name}: {err}");
    }
    let (code, out, _) = crashtest(&["sweep", "--list"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), harness::sweep::SWEEPS.len(), "{out}");
}

#[test]
fn a_sweep_writes_its_chart_and_data_and_prints_its_breaking_points() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("sweep-cli");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, out, err) = crashtest(&["sweep", "concentric", "--poses", "1", "--out", dir.to_str().expect("utf-8")]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.starts_with("sweep") && out.contains("concentric  sphere–sphere"), "the table: {out}");
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("concentric.json")).expect("data written"))
            .expect("data parses");
    assert_eq!(data["sweeps"][0]["points"].as_array().map(Vec::len), Some(162), "161 grid points and concentric");
    let svg = std::fs::read_to_string(dir.join("concentric.svg")).expect("chart written");
    assert!(svg.starts_with("<svg") && svg.contains("collide/lecture"));
}

/// Malformed mesh files: name, contents (empty: the file is missing), and what
/// the message says.
const BAD_MESHES: [(&str, &str, &str); 4] = [
    ("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "only triangles"),
    ("out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "index out of bounds"),
    ("empty.obj", "# no faces\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "empty mesh"),
    ("missing.obj", "", "cannot read mesh"),
];

#[test]
fn malformed_mesh_files_are_refused_naming_the_file() {
    let dir = scratch("mesh-load");
    for (name, text, what) in BAD_MESHES {
        let path = dir.join(name);
        if !text.is_empty() {
            std::fs::write(&path, text).expect("write");
        }
        let err = harness::mesh::load_mesh_file(&path).expect_err(name);
        assert!(err.contains(&path.display().to_string()), "{name}: the message names the file: {err}");
        assert!(err.contains(what), "{name}: the message says `{what}`: {err}");
    }
}

#[test]
fn crashtest_check_reports_a_malformed_mesh_file_with_exit_2() {
    let dir = scratch("mesh-check");
    let mut cases = Vec::new();
    for (name, text, _) in BAD_MESHES {
        if !text.is_empty() {
            std::fs::write(dir.join(name), text).expect("write");
        }
        cases.push(format!(
            r#"{{"name": "segment against {name}", "source": "a malformed mesh file", "query": "intersect",
               "a": {{"segment": {{"start": [0.25, 0.25, 1], "end": [0.25, 0.25, -1]}}}},
               "b": {{"mesh": {{"file": "{name}"}}}}}}"#
        ));
    }
    // One good case beside them: it is still run and passes.
    cases.push(
        r#"{"name": "segment against the tetrahedron", "source": "hand-derived: from below, the base z=0 at t=1/2",
            "query": "intersect",
            "a": {"segment": {"start": [0.25, 0.25, -1], "end": [0.25, 0.25, 1]}},
            "b": {"mesh": {"vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "triangles": [[0,2,1],[0,1,3],[0,3,2],[1,2,3]]}},
            "expect": {"hit": {"t": 0.5, "point": [0.25, 0.25, 0], "normal": [0, 0, -1], "triangle": 0}}}"#
            .to_string(),
    );
    let fixture = dir.join("bad_meshes.json");
    std::fs::write(&fixture, format!(r#"{{"schema": "crashtest-fixture/1", "cases": [{}]}}"#, cases.join(",\n")))
        .expect("write");
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .current_dir(ROOT)
        .args(["check", fixture.to_str().expect("utf-8 path")])
        .output()
        .expect("crashtest runs");
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "bad input exits 2:\n{text}");
    for (name, _, what) in BAD_MESHES {
        let line = text
            .lines()
            .find(|l| l.contains(&format!("segment against {name}")))
            .unwrap_or_else(|| panic!("an error for {name}:\n{text}"));
        assert!(line.contains("b.mesh.file"), "{name}: the field is named: {line}");
        assert!(line.contains(&dir.join(name).display().to_string()), "{name}: the mesh file is named: {line}");
        assert!(line.contains(what), "{name}: says `{what}`: {line}");
        assert!(line.contains("bad_meshes.json"), "{name}: the fixture file is named: {line}");
    }
    assert!(text.lines().any(|l| l.contains("segment against the tetrahedron") && l.starts_with("PASS")), "{text}");
}
