//! The peer engines crashtest ships adapters for (`engines/engines.json`: FCL's
//! two GJK solvers, Coal's three GJK variants, MuJoCo, Bullet, ipctk's two CCD
//! methods), each through `crashtest-engine/1`, on a fresh machine
//! after `engines/install` (the README's test command runs it first; a peer
//! that is not installed fails these tests, it is never skipped):
//!
//! - the conformance run (handshake, the fixture corpus against the referee,
//!   the malformed-case probes) finds no protocol violation;
//! - every case of the engine's `divergences.json` (beside its `known.json`) gets the verdict its
//!   `source` records — `known divergence:` the known divergence that pins it
//!   (from the adapter's `known.json`), `engine error:` DISAGREE or FAILED,
//!   `borderline:` borderline — so a known divergence that stops happening, or
//!   an engine error that is fixed, fails here;
//! - `--engines all` runs every installed peer and says which are not
//!   installed and how to install them.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// The workspace root: the runs read `fixtures/` and `engines/` from here.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Every run here is killed, and its test failed, past this: far more than
/// any of them takes (a Python peer answers the fixture corpus in seconds).
const TIME_LIMIT: Duration = Duration::from_secs(300);

fn crashtest(args: &[&str]) -> (i32, String, String) {
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_crashtest")).current_dir(ROOT).args(args).output().expect("runs");
    assert!(start.elapsed() < TIME_LIMIT, "crashtest {args:?} took {:?}", start.elapsed());
    let text = |b: &[u8]| String::from_utf8_lossy(b).to_string();
    (out.status.code().unwrap_or(-1), text(&out.stdout), text(&out.stderr))
}

fn peers_file() -> PathBuf {
    Path::new(ROOT).join("engines/engines.json")
}

/// The peer `name` from the shipped list, installed (or the test fails saying
/// how to install it).
fn peer(name: &str) -> harness::engines::listed::Listed {
    let listed = harness::engines::listed::read(&peers_file()).expect("engines/engines.json reads");
    let p = listed.into_iter().find(|l| l.spec.name == name).unwrap_or_else(|| panic!("{name} is not listed"));
    assert!(
        p.missing.is_none(),
        "{name}: {} (the README's test command runs engines/install first)",
        p.missing.as_deref().unwrap_or("")
    );
    p
}

/// The conformance run and the adapter's divergences, for one peer.
fn judged_as_recorded(name: &str) {
    let p = peer(name);
    let mut command = vec!["engine", "test", p.spec.program.as_str()];
    command.extend(p.spec.args.iter().map(String::as_str));
    let (code, out, err) = crashtest(&command);
    assert_eq!(code, 0, "{name}: the conformance run found a violation or could not run:\n{out}\n{err}");
    assert!(out.contains("protocol violations: none"), "{name}:\n{out}");

    // The engine's divergences file lies beside its known divergences
    // (`engines/fcl/` for fcl/libccd, `engines/fcl/indep/` for fcl/indep).
    let known = p.known_file.as_ref().unwrap_or_else(|| panic!("{name}: no known file in engines/engines.json"));
    let divergences = known.with_file_name("divergences.json").to_str().expect("utf-8 path").to_string();
    let (code, out, err) =
        crashtest(&["check", "--json", "--engines", &format!("collide/robust,{name}"), &divergences]);
    assert!(code == 0 || code == 1, "{name}: check on {divergences} exited {code}:\n{err}");
    let report: serde_json::Value = serde_json::from_str(&out).expect("check --json");
    let cases = report["cases"].as_array().expect("cases");
    let text = std::fs::read_to_string(Path::new(ROOT).join(&divergences)).expect("reads");
    let file: serde_json::Value = serde_json::from_str(&text).expect("json");
    let sources: Vec<(&str, &str)> = file["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .map(|c| (c["name"].as_str().unwrap_or(""), c["source"].as_str().unwrap_or("")))
        .collect();
    assert_eq!(cases.len(), sources.len(), "{name}: every case of {divergences} is judged");
    let mut wrong = Vec::new();
    for (case_name, source) in &sources {
        let Some(c) = cases.iter().find(|c| c["name"] == *case_name) else {
            wrong.push(format!("{case_name}: not judged"));
            continue;
        };
        let Some(r) = c["engines"].as_array().and_then(|es| es.iter().find(|e| e["engine"] == name)) else {
            wrong.push(format!("{case_name}: no verdict of {name}"));
            continue;
        };
        let verdict = r["verdict"].as_str().unwrap_or("");
        let reason = r["reason"].as_str().unwrap_or("");
        let pins: Vec<&str> =
            p.known.iter().filter(|k| k.pinned_by.iter().any(|n| n == case_name)).map(|k| k.what.as_str()).collect();
        let ok = if source.starts_with("known divergence:") {
            verdict == "known_divergence" && pins.iter().any(|what| reason.starts_with(what))
        } else if source.starts_with("engine error:") {
            pins.is_empty() && (verdict == "disagree" || verdict == "failed")
        } else if source.starts_with("borderline:") {
            pins.is_empty() && verdict == "borderline"
        } else {
            false
        };
        if !ok {
            wrong.push(format!("{case_name}: recorded `{source:.40}…`, pinned by {pins:?}; judged {verdict} {reason}"));
        }
    }
    for k in &p.known {
        for pin in &k.pinned_by {
            if !sources.iter().any(|(n, _)| n == pin) {
                wrong.push(format!("known divergence `{}`: its case `{pin}` is not in {divergences}", k.what));
            }
        }
    }
    assert!(wrong.is_empty(), "{name}: {} case(s) not judged as recorded:\n{}", wrong.len(), wrong.join("\n"));
}

#[test]
fn fcl_libccd_is_judged_as_recorded() {
    judged_as_recorded("fcl/libccd");
}

#[test]
fn fcl_indep_is_judged_as_recorded() {
    judged_as_recorded("fcl/indep");
}

#[test]
fn fcl_toi_workers_side_by_side_answer_as_one_case_at_a_time() {
    // FCL's toi cases run in forked workers, several at once within a batch
    // (engines/fcl/README.md, "toi"); a crash is the case's own. A batch of
    // one case uses one worker; batches of many use them all. The verdicts,
    // crashes included, must be the same either way.
    let (code, cases, err) = crashtest(&["cases", "--only", "toi", "--count", "240"]);
    assert_eq!(code, 0, "{err}");
    let file = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fcl-workers.json");
    std::fs::write(&file, cases).expect("writes the cases");
    peer("fcl/libccd");
    let verdicts = |batch: &str| {
        let args = ["check", "--json", "--engines", "collide/robust,fcl/libccd", "--engine-batch", batch];
        let (code, out, err) = crashtest(&[&args[..], &[file.to_str().expect("path")]].concat());
        assert!(code == 0 || code == 1, "check exited {code}:\n{err}");
        let v: serde_json::Value = serde_json::from_str(&out).expect("check --json");
        v["cases"]
            .as_array()
            .expect("cases")
            .iter()
            .map(|c| {
                let r = c["engines"]
                    .as_array()
                    .and_then(|es| es.iter().find(|e| e["engine"] == "fcl/libccd"))
                    .expect("fcl/libccd");
                (c["name"].to_string(), r["verdict"].to_string(), r["reason"].to_string())
            })
            .collect::<Vec<_>>()
    };
    let (one, many) = (verdicts("1"), verdicts("240"));
    std::fs::remove_file(&file).ok();
    let crashes = |v: &[(String, String, String)]| v.iter().filter(|(_, _, r)| r.contains("FCL crashed")).count();
    assert!(crashes(&many) > 0, "the cases include crashes: {many:?}");
    assert_eq!(one.len(), 240);
    let differ: Vec<_> = one.iter().zip(&many).filter(|(a, b)| a != b).collect();
    assert!(differ.is_empty(), "{} of 240 differ: {:?}", differ.len(), &differ[..differ.len().min(5)]);
}

#[test]
fn coal_is_judged_as_recorded() {
    judged_as_recorded("coal");
}

#[test]
fn coal_nesterov_is_judged_as_recorded() {
    judged_as_recorded("coal/nesterov");
}

#[test]
fn coal_polyak_is_judged_as_recorded() {
    judged_as_recorded("coal/polyak");
}

#[test]
fn mujoco_is_judged_as_recorded() {
    judged_as_recorded("mujoco");
}

#[test]
fn bullet_is_judged_as_recorded() {
    judged_as_recorded("bullet");
}

#[test]
fn ipctk_tight_inclusion_is_judged_as_recorded() {
    judged_as_recorded("ipctk/tight-inclusion");
}

#[test]
fn ipctk_additive_is_judged_as_recorded() {
    judged_as_recorded("ipctk/additive");
}

#[test]
fn all_runs_every_installed_peer_and_names_the_missing_with_how_to_install() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("peers-missing");
    std::fs::create_dir_all(&dir).expect("dir");
    let file = dir.join("engines.json");
    std::fs::write(&file, r#"{"install": "make install-ghost", "engines": {"ghost": ["{here}/no/such/engine"]}}"#)
        .expect("write");
    let file = file.to_str().expect("utf-8");
    let (code, out, err) = crashtest(&["check", "--engines-file", file, "fixtures/overlap.json"]);
    assert_eq!(code, 0, "{out}\n{err}");
    for name in ["fcl/libccd", "coal", "mujoco", "bullet"] {
        assert!(out.contains(&format!("\n  {name} ")), "{name} runs under `all`:\n{out}");
    }
    assert!(
        err.contains("note: engine `ghost` not run: not installed")
            && err.contains("install it with `make install-ghost`"),
        "{err}"
    );
    let (code, _, err) =
        crashtest(&["check", "--engines-file", file, "--engines", "collide/robust,ghost", "fixtures/overlap.json"]);
    assert_eq!(code, 2, "naming a missing engine is an error: {err}");
    assert!(err.contains("engine `ghost`: not installed") && err.contains("make install-ghost"), "{err}");

    // The report's provenance says so too.
    let out_dir = dir.join("report");
    let out_dir = out_dir.to_str().expect("utf-8");
    let args = ["report", "--engines-file", file, "--cases", "20", "--full-range", "0", "--no-sections", "--no-timing"];
    let (code, _, err) = crashtest(&[&args[..], &["--out", out_dir]].concat());
    assert_eq!(code, 0, "{err}");
    let summary = std::fs::read_to_string(Path::new(out_dir).join("latest/summary.json")).expect("summary");
    let summary: serde_json::Value = serde_json::from_str(&summary).expect("json");
    let engines: Vec<&str> = summary["provenance"]["engines"]
        .as_array()
        .expect("engines")
        .iter()
        .filter_map(|e| e["name"].as_str())
        .collect();
    for name in [
        "collide/robust",
        "parry3d-f64",
        "fcl/libccd",
        "fcl/indep",
        "coal",
        "coal/nesterov",
        "coal/polyak",
        "mujoco",
        "bullet",
        "ipctk/tight-inclusion",
        "ipctk/additive",
    ] {
        assert!(engines.contains(&name), "{name} in {engines:?}");
    }
    // Each peer says how many cases it was sent and how long the exchanges
    // took; an in-process engine has no such line.
    for e in summary["provenance"]["engines"].as_array().expect("engines") {
        let (name, process) = (e["name"].as_str().unwrap_or(""), &e["process"]);
        let peers = [
            "fcl/libccd",
            "fcl/indep",
            "coal",
            "coal/nesterov",
            "coal/polyak",
            "mujoco",
            "bullet",
            "ipctk/tight-inclusion",
            "ipctk/additive",
        ];
        if peers.contains(&name) {
            let (sent, seconds) = (process["cases_sent"].as_u64(), process["seconds_sent"].as_f64());
            assert!(sent.is_some_and(|n| n > 0) && seconds.is_some_and(|s| s > 0.0), "{name}: {process}");
        } else {
            assert!(process.is_null(), "{name}: {process}");
        }
    }
    let missing = &summary["provenance"]["missing_engines"];
    assert_eq!(missing[0][0], "ghost", "{missing}");
    assert!(missing[0][1].as_str().is_some_and(|w| w.contains("make install-ghost")), "{missing}");
}

/// Momentum is conserved in a two-ball impact whatever the contact model:
/// `|Δ(m_a v_a + m_b v_b)|` over the initial momentum's scale may be no more
/// than this (dimensionless). A soft contact's internal forces cancel to the
/// solver's tolerance; a velocity read in the wrong frame or of the wrong
/// body breaks it by order 1.
const MOMENTUM_REL: f64 = 1e-6;

#[test]
fn mujoco_and_bullet_step_the_dynamics_worlds() {
    for name in ["mujoco", "bullet"] {
        peer(name);
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("peers-worlds");
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().expect("utf-8");
    let (code, stdout, err) = crashtest(&[
        "report",
        "--engines",
        "collide/robust,mujoco,bullet",
        "--cases",
        "3",
        "--full-range",
        "0",
        "--no-timing",
        "--out",
        out,
    ]);
    assert_eq!(code, 0, "{stdout}{err}");
    let text = std::fs::read_to_string(dir.join("latest/dynamics.json")).expect("dynamics.json");
    let d: serde_json::Value = serde_json::from_str(&text).expect("json");
    assert!(d.get("world_failures").is_none(), "every world stepped: {}", d["world_failures"]);
    for name in ["mujoco", "bullet"] {
        let bounces = d["bounces"].as_array().expect("bounces").iter().filter(|b| b["engine"] == name).count();
        assert_eq!(bounces, 5, "{name}: a series per restitution");
        for method in [format!("{name}, CCD off"), format!("{name}, CCD requested")] {
            let rows: Vec<&serde_json::Value> =
                d["tunnel"].as_array().expect("tunnel").iter().filter(|r| r["method"] == method.as_str()).collect();
            assert_eq!(rows.len(), 27, "{method}: every thickness and speed");
            assert!(rows.iter().all(|r| r["runs"] == 8), "{method}: every start phase stepped");
        }
        let settings = d["engine_settings"].as_array().expect("settings").iter().find(|s| s["engine"] == name);
        assert!(
            settings.is_some_and(|s| !s["settings"].as_array().expect("list").is_empty()),
            "{name} echoes its settings"
        );
        let pairs: Vec<&serde_json::Value> =
            d["pairs"].as_array().expect("pairs").iter().filter(|p| p["engine"] == name).collect();
        assert_eq!(pairs.len(), 5, "{name}: every two-ball scene");
        // Head-on, masses 1 and 3: a at 4 m/s, b at rest.
        let p = pairs.iter().find(|p| p["scene"] == "head-on, masses 1 and 3, e = 0.5").expect("scene");
        let v = |k: &str| -> Vec<f64> { p[k].as_array().expect("v").iter().filter_map(|x| x.as_f64()).collect() };
        let (va, vb) = (v("velocity_a"), v("velocity_b"));
        let momentum = (0..3).map(|i| (va[i] + 3.0 * vb[i] - if i == 0 { 4.0 } else { 0.0 }).abs()).fold(0.0, f64::max);
        assert!(momentum <= MOMENTUM_REL * 4.0, "{name}: momentum changed by {momentum}: a {va:?}, b {vb:?}");
    }
}

/// The Bullet adapter gives `getClosestPoints` a sphere as a bare collision
/// shape, not a body (building a body is pybullet's dearest call): on seeded
/// random and exact cases of every pair it answers with a sphere, in both
/// argument orders, its points must be those of two bodies bit for bit
/// (`engines/bullet/bare_spheres.py`, which exits 1 naming the first case that
/// differs).
#[test]
fn bullet_bare_spheres_answer_as_bodies_do() {
    let p = peer("bullet");
    let start = Instant::now();
    let out = Command::new(&p.spec.program)
        .current_dir(ROOT)
        .arg("engines/bullet/bare_spheres.py")
        .output()
        .expect("the bullet adapter's python runs");
    assert!(start.elapsed() < TIME_LIMIT, "bare_spheres.py took {:?}", start.elapsed());
    let text = |b: &[u8]| String::from_utf8_lossy(b).to_string();
    assert!(out.status.success(), "{}{}", text(&out.stdout), text(&out.stderr));
    assert!(text(&out.stdout).contains("bit for bit"), "{}", text(&out.stdout));
}
