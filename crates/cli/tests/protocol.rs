//! The engine protocol `crashtest-engine/1` (docs/PROTOCOL.md) as a user meets
//! it: collide served over it is bit-identical to collide in process; every
//! fault of a process engine (scripted misbehaving engines in
//! `tests/engines/`) fails the cases concerned with the reason and changes
//! nothing else in the run; the stdlib-only Python reference engine is judged
//! beside collide; and the conformance run reports what it should.

use harness::check::run_caught;
use harness::engines::judged;
use harness::judge::Verdict;
use harness::load::LoadedCase;
use harness::protocol::client::{Outcome, ProcessEngine, ProcessSpec};
use harness::protocol::messages::WireAnswer;
use serde_json::Value;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// The workspace root: the runs read `fixtures/` as a user at the root does.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Random cases per query kind for the bit-identity test: 7 kinds × 1,430 ≥ 10⁴.
const RANDOM_PER_KIND: u64 = 1_430;

/// Every run here is killed, and its test failed, past this: far more than any
/// of them takes (the slowest waits out a 2 s time limit a few times).
const TIME_LIMIT: Duration = Duration::from_secs(120);

/// A scripted engine's command.
fn script(name: &str) -> String {
    format!("python3 {}/tests/engines/{name}.py", env!("CARGO_MANIFEST_DIR"))
}

/// Runs crashtest (from the workspace root) under [`TIME_LIMIT`]: exit code,
/// standard output, standard error.
fn crashtest(args: &[&str]) -> (i32, String, String) {
    let start = Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_crashtest"))
        .current_dir(ROOT)
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("crashtest starts");
    let out = child.wait_with_output().expect("crashtest ends");
    assert!(start.elapsed() < TIME_LIMIT, "crashtest {args:?} took {:?}", start.elapsed());
    let text = |b: &[u8]| String::from_utf8_lossy(b).to_string();
    (out.status.code().unwrap_or(-1), text(&out.stdout), text(&out.stderr))
}

/// `check --json` with collide/robust and the process engine `x`, gated by `x`:
/// the exit code and the parsed result.
fn check_with(command: &str, extra: &[&str], files: &[&str]) -> (i32, Value) {
    let spec = format!("x={command}");
    let mut args = vec!["check", "--json", "--engines", "collide/robust,x", "--gate", "x", "--engine", &spec];
    args.extend_from_slice(extra);
    args.extend_from_slice(files);
    let (code, out, err) = crashtest(&args);
    let v: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("not JSON ({e}):\n{out}\n{err}"));
    (code, v)
}

/// Each case's (verdict, reason) for `engine`.
fn verdicts(v: &Value, engine: &str) -> Vec<(String, String)> {
    v["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .map(|c| {
            let r = c["engines"].as_array().expect("engines").iter().find(|r| r["engine"] == engine).expect("engine");
            (r["verdict"].as_str().unwrap_or("").to_string(), r["reason"].as_str().unwrap_or("").to_string())
        })
        .collect()
}

/// collide/robust's verdicts are all `agree`: the process engine's faults
/// changed nothing else in the run.
fn collide_unaffected(v: &Value) {
    let all = verdicts(v, "collide/robust");
    assert!(!all.is_empty());
    assert!(all.iter().all(|(k, _)| k == "agree"), "collide/robust: {all:?}");
}

fn count(all: &[(String, String)], verdict: &str, needle: &str) -> usize {
    all.iter().filter(|(k, r)| k == verdict && r.contains(needle)).count()
}

#[test]
fn collide_through_the_protocol_is_bit_identical_on_every_fixture_and_10k_random_cases() {
    let loaded = harness::load::load_paths(&[Path::new(ROOT).join("fixtures")]);
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    let mut cases: Vec<LoadedCase> = loaded.cases;
    let fixtures = cases.len();
    for q in harness::report::campaign::CAMPAIGN_QUERIES {
        for i in 0..RANDOM_PER_KIND {
            cases.extend(harness::generate::try_generate(q, harness::report::campaign::DEFAULT_SEED, i));
        }
    }
    assert!(cases.len() - fixtures >= 10_000, "{} random cases", cases.len() - fixtures);
    let wire = ProcessEngine::start(
        ProcessSpec::new("collide over the protocol", vec![env!("CARGO_BIN_EXE_crashtest-engine-collide").into()])
            .expect("spec"),
    );
    assert_eq!(wire.down(), None);
    wire.prefetch(&cases);
    let here = judged().into_iter().find(|e| e.name == "collide/robust").expect("collide/robust");
    // Shortest round-trip JSON of the answer: equal text is equal bits (−0 is
    // written `-0.0`).
    let bits = |a: &harness::engine::Answer| serde_json::to_string(&WireAnswer::of(a)).expect("JSON");
    let mut differ = Vec::new();
    for lc in &cases {
        let (mine, theirs) = (run_caught(&here, lc), wire.answer(lc).outcome);
        let same = match (&mine, &theirs) {
            (Ok(a), Outcome::Answer(b)) => bits(a) == bits(b),
            (Err(Verdict::Unsupported { reason: a }), Outcome::Unsupported(b)) => a == b,
            _ => false,
        };
        if !same {
            differ.push(format!("{}: in process {mine:?}, over the protocol {theirs:?}", lc.case.name));
        }
    }
    assert_eq!(wire.info().faults, Vec::<String>::new());
    assert!(
        differ.is_empty(),
        "{} of {} cases differ:\n{}",
        differ.len(),
        cases.len(),
        differ[..differ.len().min(10)].join("\n")
    );
}

#[test]
fn an_engine_that_exits_mid_batch_fails_that_batch_and_is_restarted() {
    // Two cases a batch, nine batches: the script answers its first batch and
    // exits on its second, so each process answers one batch of two; after
    // three restarts the engine is marked down for the ninth.
    let (code, v) = check_with(&script("exits_mid_batch"), &["--engine-batch", "2"], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert_eq!(x.len(), 18);
    assert_eq!(count(&x, "agree", ""), 8, "{x:?}");
    let exited =
        |needle: &str| x.iter().filter(|(k, r)| k == "failed" && r.starts_with("batch ") && r.contains(needle)).count();
    assert_eq!(exited("the engine exited (exit status: 3) before it answered"), 8, "{x:?}");
    assert_eq!(exited("its standard error ends: fatal: simulated crash"), 8, "its standard error is quoted: {x:?}");
    assert_eq!(count(&x, "failed", "the engine is down: restarted 3 times"), 2, "{x:?}");
    assert_eq!(code, 1, "the gate failed cases");
    collide_unaffected(&v);
}

#[test]
fn a_hanging_engine_fails_its_batch_at_the_time_limit_and_the_run_goes_on() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("protocol-hang");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch");
    let case = |name: &str| {
        format!(
            r#"{{"name": "{name}", "query": "overlap", "a": {{"aabb": {{"min": [0,0,0], "max": [1,1,1]}}}},
                "b": {{"aabb": {{"min": [0.5,0.5,0.5], "max": [2,2,2]}}}}, "expect": {{"overlap": true}}}}"#
        )
    };
    let file = dir.join("hang.json");
    let cases = [case("first"), case("hang here"), case("third"), case("fourth")].join(",");
    std::fs::write(&file, format!(r#"{{"schema": "crashtest-fixture/1", "cases": [{cases}]}}"#)).expect("write");
    let started = Instant::now();
    let (code, v) = check_with(
        &script("hangs"),
        &["--engine-batch", "1", "--engine-timeout", "2"],
        &[file.to_str().expect("utf-8")],
    );
    let x = verdicts(&v, "x");
    assert_eq!(x[1], ("failed".to_string(), "batch 2: no answer within 2 s".to_string()), "{x:?}");
    assert_eq!(count(&x, "agree", ""), 3, "the others, answered by the restarted engine: {x:?}");
    assert_eq!(code, 1);
    assert!(started.elapsed() < Duration::from_secs(30), "the hang cost the time limit, not more");
    collide_unaffected(&v);
}

#[test]
fn output_that_is_not_a_message_names_the_line_and_the_column() {
    let (code, v) = check_with(&script("malformed"), &["--engine-batch", "6"], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert_eq!(count(&x, "failed", "line 2 of the engine's output is not a message: column 36: EOF while parsing"), 18);
    assert_eq!(x.len(), 18);
    assert_eq!(code, 1);
    collide_unaffected(&v);
    // Six batches of three, two in flight: each fault fails the batch awaited
    // and sends the one behind it again to the restarted engine (the hello is
    // line 1 of each process); after the third restart's fault the engine is
    // down, and the last two batches fail saying so.
    let (_, v) = check_with(&script("malformed"), &["--engine-batch", "3"], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert_eq!(
        count(&x, "failed", "the engine is down: restarted 3 times; the last fault: batch 7: line 2"),
        6,
        "{x:?}"
    );
}

#[test]
fn an_unknown_field_in_an_answer_names_the_field() {
    let (_, v) = check_with(&script("bad_field"), &[], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    let named = "line 2 of the engine's output is not a message: field `answers[0].answer.overlapp`: unknown field";
    assert!(x.iter().all(|(k, r)| k == "failed" && r.contains(named)), "{x:?}");
    collide_unaffected(&v);
}

#[test]
fn a_wrong_number_of_answers_fails_the_batch() {
    let (_, v) = check_with(&script("wrong_count"), &[], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert!(x.iter().all(|(k, r)| k == "failed" && r.contains("answered 17 cases of 18")), "{x:?}");
    collide_unaffected(&v);
}

#[test]
fn noise_on_standard_error_is_not_a_fault() {
    let (code, v) = check_with(&script("noisy"), &["--engine-batch", "2"], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert!(x.iter().all(|(k, _)| k == "agree"), "{x:?}");
    assert_eq!(code, 0);
}

#[test]
fn a_wrong_protocol_version_or_a_missing_command_is_down_from_the_start() {
    let (_, v) = check_with(&script("bad_hello"), &[], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert!(
        x.iter().all(|(k, r)| k == "failed"
            && r.contains(
                "the handshake failed: the engine speaks `crashtest-engine/99`; crashtest speaks `crashtest-engine/1`"
            )),
        "{x:?}"
    );
    collide_unaffected(&v);
    let (_, v) = check_with("/nonexistent/engine --flag", &[], &["fixtures/overlap.json"]);
    let x = verdicts(&v, "x");
    assert!(x.iter().all(|(k, r)| k == "failed" && r.contains("cannot start `/nonexistent/engine --flag`")), "{x:?}");
}

#[test]
fn pairs_outside_the_capabilities_are_unsupported_without_a_message() {
    // The scripts declare overlap and sphere–sphere contact only.
    let (_, v) = check_with(&script("trivial"), &[], &["fixtures/intersect.json"]);
    let x = verdicts(&v, "x");
    assert!(x.iter().all(|(k, r)| k == "unsupported" && r == "not among the engine's capabilities"), "{x:?}");
}

#[test]
fn engines_asked_side_by_side_answer_as_each_does_alone() {
    // Two process engines in one run are asked side by side (docs/PROTOCOL.md,
    // `batch`), with two threads even on a one-core machine: one restarts after
    // every batch, the other answers every case. Each must get the verdicts it
    // gets alone: no answer, fault or restart crosses from one to the other.
    let py = format!("python3 {ROOT}/engines/python-reference/engine.py");
    let faulty = script("exits_mid_batch");
    let files = ["fixtures/overlap.json", "fixtures/contact.json"];
    let run = |engines: &str, specs: &[String]| {
        let mut args = vec!["check", "--json", "--engines", engines, "--engine-batch", "2"];
        for s in specs {
            args.extend(["--engine", s.as_str()]);
        }
        args.extend(files);
        let child = Command::new(env!("CARGO_BIN_EXE_crashtest"))
            .current_dir(ROOT)
            .env("RAYON_NUM_THREADS", "2")
            .args(&args)
            .output()
            .expect("crashtest runs");
        let out = String::from_utf8_lossy(&child.stdout).to_string();
        serde_json::from_str::<Value>(&out).unwrap_or_else(|e| panic!("not JSON ({e}):\n{out}"))
    };
    let (x, y) = (format!("x={py}"), format!("y={faulty}"));
    let both = run("collide/robust,x,y", &[x.clone(), y.clone()]);
    let x_alone = run("collide/robust,x", &[x]);
    let y_alone = run("collide/robust,y", &[y]);
    let (bx, by) = (verdicts(&both, "x"), verdicts(&both, "y"));
    assert!(count(&bx, "agree", "") >= 20 && count(&bx, "failed", "") == 0, "{bx:?}");
    assert!(count(&by, "failed", "the engine exited") > 0, "the faulty engine fails batches: {by:?}");
    assert_eq!(bx, verdicts(&x_alone, "x"));
    assert_eq!(by, verdicts(&y_alone, "y"));
    collide_unaffected(&both);
}

#[test]
fn the_python_reference_engine_is_judged_beside_collide() {
    let py = format!("python3 {ROOT}/engines/python-reference/engine.py");
    let files = [
        "fixtures/contact.json",
        "fixtures/intersect.json",
        "fixtures/barycentric.json",
        "fixtures/overlap.json",
        "fixtures/toi.json",
        "fixtures/response.json",
    ];
    let (code, v) = check_with(&py, &[], &files);
    assert_eq!(code, 0, "the reference engine passes every shipped case it answers: {} failed", v["failed"]);
    let x = verdicts(&v, "x");
    assert!(count(&x, "agree", "") >= 100, "{x:?}");
    assert_eq!(count(&x, "failed", ""), 0, "{x:?}");
    // Known wrong, asserted as it is: its bounding sphere is the lecture's
    // (the centroid and the farthest point), not the minimal one, so it is
    // larger than the minimal radius wherever the points are not symmetric
    // about their centroid; its boxes agree.
    let (code, v) = check_with(&py, &[], &["fixtures/bounds.json"]);
    assert_eq!(code, 1);
    let x = verdicts(&v, "x");
    let disagree: Vec<_> = x.iter().filter(|(k, _)| k == "disagree").collect();
    assert!(!disagree.is_empty() && disagree.len() < x.len(), "{x:?}");
    for c in v["cases"].as_array().expect("cases") {
        let r = c["engines"].as_array().expect("engines").iter().find(|r| r["engine"] == "x").expect("x");
        if r["verdict"] == "disagree" {
            let reasons = r["reasons"].to_string();
            assert!(reasons.contains("bounding radius off by") && !reasons.contains("box"), "{}: {reasons}", c["name"]);
        }
    }
}

#[test]
fn the_conformance_run_reports_support_scores_probes_and_violations() {
    let collide = env!("CARGO_BIN_EXE_crashtest-engine-collide");
    let (code, out, err) = crashtest(&["engine", "test", collide]);
    assert_eq!(code, 0, "{out}{err}");
    // collide serves every pair of the table.
    assert!(out.contains(&format!("supports ({}):", crashtest::Pair::ALL.len())), "{out}");
    assert!(out.contains("protocol violations: none"), "{out}");
    assert!(out.contains("ok    a shape kind the format does not have: error: the case does not read"), "{out}");
    let py = format!("{ROOT}/engines/python-reference/engine.py");
    let (code, out, _) = crashtest(&["engine", "test", "python3", &py]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("hello: python-reference"), "{out}");
    let malformed = format!("{}/tests/engines/malformed.py", env!("CARGO_MANIFEST_DIR"));
    let (code, out, _) = crashtest(&["engine", "test", "--engine-timeout", "5", "python3", &malformed]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("is not a message") && out.contains("the engine is down"), "{out}");
}

#[test]
fn an_engines_file_names_commands_and_its_errors_name_the_file_and_field() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("protocol-engines-file");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch");
    let good = dir.join("engines.json");
    let py = format!("{ROOT}/engines/python-reference/engine.py");
    std::fs::write(&good, serde_json::json!({ "engines": { "py": ["python3", py] } }).to_string()).expect("write");
    let (code, out, err) = crashtest(&[
        "check",
        "--engines-file",
        good.to_str().expect("utf-8"),
        "--engines",
        "py",
        "fixtures/overlap.json",
    ]);
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(out.lines().last(), Some("18 passed, 0 failed (gate: py)"), "{out}");
    let bad = dir.join("bad.json");
    std::fs::write(&bad, r#"{"engines": {"py": "python3 engine.py"}}"#).expect("write");
    let (code, _, err) = crashtest(&["check", "--engines-file", bad.to_str().expect("utf-8"), "fixtures/overlap.json"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("bad.json: field `engines.py`: expected a command ([\"program\", \"arg\", …])"), "{err}");
}

#[test]
fn a_sweep_judges_a_process_engine_beside_collide() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("protocol-sweep");
    let _ = std::fs::remove_dir_all(&dir);
    let py = format!("py=python3 {ROOT}/engines/python-reference/engine.py");
    let (code, out, err) = crashtest(&[
        "sweep",
        "concentric",
        "--poses",
        "1",
        "--engines",
        "collide/robust,py",
        "--engine",
        &py,
        "--out",
        dir.to_str().expect("utf-8"),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let data = std::fs::read_to_string(dir.join("concentric.json")).expect("data written");
    assert!(data.contains("\"py\""), "the sweep's data has the process engine's series");
}

/// The dynamics section of a report made with `engines` (plus `extra`
/// arguments), as its `dynamics.json`.
fn dynamics_of(dir_name: &str, engines: &str, extra: &[&str]) -> Value {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(dir_name);
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().expect("utf-8");
    let args = ["report", "--engines", engines, "--cases", "3", "--full-range", "0", "--no-timing", "--out", out];
    let (code, stdout, err) = crashtest(&[&args[..], extra].concat());
    assert_eq!(code, 0, "{stdout}{err}");
    let text = std::fs::read_to_string(dir.join("latest/dynamics.json")).expect("dynamics.json");
    serde_json::from_str(&text).expect("json")
}

#[test]
fn a_world_that_fails_is_listed_with_its_reason_and_the_rest_of_the_dynamics_still_runs() {
    let wf = format!("wf={}", script("world_faults"));
    let d = dynamics_of("protocol-world-faults", "collide/robust,wf", &["--engine", &wf]);
    let failures = d["world_failures"].as_array().expect("failures listed");
    let reason = |world: &str| {
        failures.iter().find(|f| f["world"] == world).and_then(|f| f["reason"].as_str()).unwrap_or("").to_string()
    };
    assert!(reason("bounce, e = 0").contains("a trajectory of 1 samples"), "{failures:?}");
    assert_eq!(reason("bounce, e = 0.25"), "the engine's error: simulated solver failure");
    let crash = reason("bounce, e = 0.5");
    assert!(crash.contains("exited (exit status: 4)") && crash.contains("simulated crash in a world"), "{crash}");
    assert_eq!(failures.len(), 3, "only the three faulty worlds fail: {failures:?}");
    // After the crash the engine is restarted: the later worlds are stepped.
    let wf_bounces: Vec<f64> = d["bounces"]
        .as_array()
        .expect("bounces")
        .iter()
        .filter(|b| b["engine"] == "wf")
        .filter_map(|b| b["restitution"].as_f64())
        .collect();
    assert_eq!(wf_bounces.len(), 2, "e = 0.8 and 1 stepped: {wf_bounces:?}");
    let rows = d["tunnel"].as_array().expect("tunnel").iter().filter(|r| r["method"] == "wf, CCD off").count();
    assert_eq!(rows, 27, "every thickness and speed");
    assert_eq!(d["engine_settings"][0]["engine"], "wf");
}

/// A process engine whose normals are 1.01 or 1.5 times too long, its points,
/// depths and times collide's own: every case where collide agrees with a
/// contact, a hit or an impact is a disagreement that says the normal is not
/// unit; every other case keeps collide's verdict. (Before normals' lengths
/// were judged, every one of them agreed.)
#[test]
fn normals_that_are_not_unit_disagree_over_the_protocol() {
    let collide = env!("CARGO_BIN_EXE_crashtest-engine-collide");
    let files = [
        "fixtures/contact.json",
        "fixtures/intersect.json",
        "fixtures/toi.json",
        "fixtures/mesh.json",
        "fixtures/peers",
        "fixtures/regressions",
    ];
    for k in ["1.01", "1.5"] {
        let command = format!("{} {k} {collide}", script("scaled_normals"));
        let (_, v) = check_with(&command, &[], &files);
        let (mut with_normal, mut without) = (0, 0);
        for c in v["cases"].as_array().expect("cases") {
            let of = |name: &str| {
                c["engines"].as_array().expect("engines").iter().find(|r| r["engine"] == name).expect("engine").clone()
            };
            let (here, x) = (of("collide/robust"), of("x"));
            let answer = &here["answer"];
            let normal = ["contact", "hit", "toi"].iter().any(|key| answer[key].get("normal").is_some());
            if here["verdict"] == "agree" && normal {
                with_normal += 1;
                let reasons = x["reasons"].to_string();
                assert!(
                    x["verdict"] == "disagree" && reasons.contains("normal not unit"),
                    "×{k}, {}: {} {reasons}",
                    c["name"],
                    x["verdict"]
                );
            } else if !normal {
                without += 1;
                assert_eq!(x["verdict"], here["verdict"], "×{k}, {}: no normal to scale", c["name"]);
            }
        }
        assert!(with_normal >= 100 && without >= 20, "×{k}: {with_normal} cases with a normal, {without} without");
    }
}
