//! Findings: one root cause per finding, shrunk cases that replay with their
//! signature, a standalone parry reproduction that fails on the pinned parry,
//! and `diff` telling noise from change.

use harness::engines::EngineSet;
use harness::findings::diff::{Change, diff};
use harness::findings::shrink::judge_one;
use harness::findings::signature::{Cause, WRONG_ANSWERS};
use harness::findings::{Finding, FindingsFile};
use harness::load::load_paths;
use harness::report::campaign::{Config, Outcome, run};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A campaign of the built-in engines: `cases` random cases per query kind
/// (a tenth as many of the full-range family), the fixtures, no timing.
fn campaign(seed: u64, cases: u64, fixtures: Vec<PathBuf>) -> Outcome {
    run(
        &Config {
            seed,
            cases_per_query: cases,
            full_range_per_query: cases / 10,
            fixtures,
            timing: false,
            progress: false,
            sections: false,
            engines: EngineSet::default(),
            ..Config::default()
        },
        Default::default(),
    )
}

/// The finding of a cause.
fn find<'a>(f: &'a FindingsFile, engine: &str, pair: &str, class: &str) -> Vec<&'a Finding> {
    f.findings
        .iter()
        .filter(|x| x.engines.contains_key(engine) && x.cause.pair == pair && x.cause.class == class)
        .collect()
}

/// Where the parry reproduction is kept: the test compares the generated
/// program with it, compiles it (below, `include!`) and runs it.
const PARRY_REPRODUCTION: &str = "tests/reproductions/parry_ball_half_space.rs";

mod parry_ball_half_space {
    include!("reproductions/parry_ball_half_space.rs");
    pub fn run() {
        main()
    }
}

#[test]
fn parrys_ball_half_space_defect_is_one_finding_with_a_failing_reproduction_of_at_most_15_lines() {
    let out = campaign(11, 300, vec![root().join("fixtures/contact.json")]);
    let f = &out.findings;
    // Every way the defect shows — false contacts, missed contacts, wrong
    // depths and points, in every family — is one finding.
    let found = find(f, "parry3d-f64", "contact sphere–plane", WRONG_ANSWERS);
    assert_eq!(found.len(), 1, "{:#?}", f.findings.iter().map(|x| &x.title).collect::<Vec<_>>());
    let finding = found[0];
    let ways: Vec<&str> = finding.variants.iter().map(|(s, _)| s.wrong.as_str()).collect();
    assert!(
        ways.contains(&"false contact") && ways.contains(&"missed contact") && ways.iter().any(|w| w.ends_with(" off")),
        "{ways:?}"
    );
    // Its ball-second sibling has no such finding: the defect is the ball-first order's.
    assert!(find(f, "parry3d-f64", "contact plane–sphere", WRONG_ANSWERS).is_empty());
    let repro = finding.reproduction.as_ref().expect("parry gives a reproduction for contact sphere–plane");
    assert_eq!(repro.language, "rust");
    let lines = repro.code.lines().count();
    assert!(lines <= 15, "{lines} lines:\n{}", repro.code);
    let kept = root().join(PARRY_REPRODUCTION);
    if std::env::var_os("CRASHTEST_BLESS").is_some() {
        std::fs::write(&kept, &repro.code).unwrap();
    }
    let text = std::fs::read_to_string(&kept).unwrap();
    assert_eq!(
        text, repro.code,
        "{PARRY_REPRODUCTION} is not the generated reproduction; run with CRASHTEST_BLESS=1 to write it"
    );
    // Compiled into this test against the pinned parry (the module above):
    // it must fail, as parry 0.31.1 answers the ball-first contact wrong.
    let failed = std::panic::catch_unwind(parry_ball_half_space::run).is_err();
    assert!(failed, "the reproduction passed: parry's answer is right now");
}

mod parry_mesh_contact {
    include!("reproductions/parry_mesh_contact.rs");
    pub fn run() {
        main()
    }
}

mod parry_mesh_ray {
    include!("reproductions/parry_mesh_ray.rs");
    pub fn run() {
        main()
    }
}

mod parry_barycentric {
    include!("reproductions/parry_barycentric.rs");
    pub fn run() {
        main()
    }
}

mod parry_bounds {
    include!("reproductions/parry_bounds.rs");
    pub fn run() {
        main()
    }
}

#[test]
fn parrys_programs_for_meshes_barycentrics_and_bounds_compile_and_fail_exactly_on_a_wrong_answer() {
    // Fixture cases, parry3d-f64's program for each (kept under
    // tests/reproductions/, compiled into this test above), and whether
    // crashtest judges parry's answer wrong: the program must panic exactly then.
    let set = EngineSet::select("parry3d-f64", Some("parry3d-f64")).unwrap();
    let engine = &set.judged[0];
    /// A fixture file and case, its program's name and the compiled program,
    /// and whether parry's answer is wrong.
    type Program = (&'static str, &'static str, &'static str, fn(), bool);
    let cases: [Program; 4] = [
        (
            "mesh.json",
            "sphere–mesh: inside, three faces equally near",
            "parry_mesh_contact",
            parry_mesh_contact::run,
            true,
        ),
        ("mesh.json", "tetrahedron, down through the slanted face first", "parry_mesh_ray", parry_mesh_ray::run, false),
        ("barycentric.json", "centroid", "parry_barycentric", parry_barycentric::run, false),
        ("bounds.json", "regular tetrahedron", "parry_bounds", parry_bounds::run, false),
    ];
    for (file, name, program, run, wrong) in cases {
        let loaded = load_paths(&[root().join("fixtures").join(file)]);
        let lc = loaded.cases.iter().find(|c| c.case.name == name).unwrap_or_else(|| panic!("{file}: {name}"));
        let truth = harness::check::Truth::of(&set.referee, lc);
        let judged = harness::check::judge_engine(engine, &set, lc, &truth);
        assert_eq!(
            matches!(judged.verdict, harness::judge::Verdict::Disagree { .. }),
            wrong,
            "{name}: {:?}",
            judged.verdict
        );
        let repro = harness::findings::draft::reproduction(engine, lc, &truth).expect("parry gives a program");
        let kept = root().join(format!("tests/reproductions/{program}.rs"));
        if std::env::var_os("CRASHTEST_BLESS").is_some() {
            std::fs::write(&kept, &repro.code).unwrap();
        }
        let text = std::fs::read_to_string(&kept).unwrap_or_default();
        assert_eq!(
            text,
            repro.code,
            "{} is not the generated program; run with CRASHTEST_BLESS=1 to write it",
            kept.display()
        );
        let failed = std::panic::catch_unwind(run).is_err();
        assert_eq!(failed, wrong, "{program}: the program {} on {name}", if failed { "failed" } else { "passed" });
    }
}

/// What a replay's failure adds: a changed judgement or engine makes a kept
/// sample stale.
const AGAIN: &str = " (if crashtest's judgement or an engine's pinned version changed on purpose, write \
                     reports/sample again: reports/README.md says how)";

/// Replays every shrunk case of `file` from the report folder `dir` with its
/// engine of `set` and checks that it shows its finding's defect and cause —
/// in one of `3 · shrink::REPLAYS` judgements: an engine that answers one case
/// differently between calls (FCL's distance on a degenerate triangle shows
/// its error about half the time) can be asked to show its defect, not to
/// show it every time; crashtest's own engines and parry answer the same every
/// time, and the first judgement is theirs. Returns how many were replayed.
fn replay_all(file: &FindingsFile, dir: &Path, set: &EngineSet) -> usize {
    let mut n = 0;
    for f in file.findings.iter().filter(|f| f.is_discrepancy()) {
        let Some(s) = &f.shrunk else { continue };
        let loaded = load_paths(&[dir.join(&s.file)]);
        assert!(loaded.errors.is_empty(), "{}: {:?}", s.file, loaded.errors);
        let lc = &loaded.cases[0];
        let engine = set.judged.iter().find(|e| e.name == f.engine()).expect("the finding's engine");
        let judged = || {
            let (sig, result, _) = judge_one(engine, set, lc);
            sig.map(|sig| (harness::findings::signature::cause_of(&sig, lc, Some(engine), &result), sig))
        };
        // Known as it is: a process engine's finding whose every case the
        // report lists as unstable (its answer changes between processes:
        // FCL's distance on a degenerate triangle answers it with an error, a
        // wrong point or the right one, the same in all of one process's
        // replays and otherwise in the next) cannot be asked to show it
        // again; it is counted, its listing checked.
        let unsteady = !f.fixture_cases.is_empty()
            && f.fixture_cases.iter().all(|c| file.unstable.iter().any(|(e, u)| e == f.engine() && u == c));
        if unsteady {
            assert!(engine.process().is_some(), "{}: only a process engine's answers change between calls", s.file);
            n += 1;
            continue;
        }
        // A process engine whose answers depend on what its process asked
        // before (Coal's do: engines/coal/README.md) may not show the defect
        // after this test's other replays; its file's own replay, `crashtest
        // check FILE`, asks it first in a new process: so is it asked last.
        let fresh = || engine.process().is_some() && engine.fresh_process().is_ok();
        let (cause, sig): (Cause, _) = (0..3 * harness::findings::shrink::REPLAYS)
            .filter_map(|_| judged())
            .find(|(_, sig)| f.signature.same_defect(sig))
            .or_else(|| fresh().then(judged).flatten().filter(|(_, sig)| f.signature.same_defect(sig)))
            .or_else(judged)
            .unwrap_or_else(|| panic!("{}: the shrunk case no longer shows a discrepancy{AGAIN}", s.file));
        // A process engine may show the defect with one more field off: FCL's
        // distance on a degenerate triangle leaves its witness point
        // uninitialised now and then (7.6e37, 7.4e176 seen beside the zero
        // normal the finding records).
        let shown = f.signature.same_defect(&sig)
            || (engine.process().is_some()
                && (&f.signature.engine, f.signature.query, &f.signature.pair, &f.signature.magnitude)
                    == (&sig.engine, sig.query, &sig.pair, &sig.magnitude)
                && at_least(&f.signature.wrong, &sig.wrong));
        assert!(shown, "{}: {:?} replays as {:?}{AGAIN}", s.file, f.signature, sig);
        assert_eq!(cause, f.cause, "{}{AGAIN}", s.file);
        n += 1;
    }
    n
}

/// Whether the wrong parts `replay` names (`"normal is the zero vector;
/// distance, normal, witness point off"`) hold every one of `recorded`'s: each
/// clause, and each field of an "… off" clause.
fn at_least(recorded: &str, replay: &str) -> bool {
    let parts = |w: &str| -> (Vec<String>, Vec<String>) {
        let (mut clauses, mut off) = (Vec::new(), Vec::new());
        for c in w.split("; ") {
            match c.strip_suffix(" off") {
                Some(fields) => off.extend(fields.split(", ").map(str::to_string)),
                None => clauses.push(c.to_string()),
            }
        }
        (clauses, off)
    };
    let ((rc, ro), (pc, po)) = (parts(recorded), parts(replay));
    rc.iter().all(|c| pc.contains(c)) && ro.iter().all(|o| po.contains(o))
}

#[test]
fn a_replay_with_one_more_field_off_shows_at_least_the_recorded_defect() {
    let recorded = "normal is the zero vector; distance, normal off";
    assert!(at_least(recorded, "normal is the zero vector; distance, normal, witness point off"));
    assert!(at_least(recorded, recorded));
    assert!(!at_least(recorded, "distance, normal, witness point off"));
    assert!(!at_least(recorded, "normal is the zero vector; normal off"));
}

#[test]
fn every_shrunk_case_replays_from_its_file_with_its_findings_signature() {
    let out = campaign(5, 400, vec![root().join("fixtures")]);
    let dir = std::env::temp_dir().join(format!("crashtest-findings-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let written = harness::report::write::write_outcome(&dir, "r", &out).unwrap();
    let file = harness::findings::read(&written).unwrap();
    let discrepancy_findings = file.findings.iter().filter(|f| f.is_discrepancy()).count();
    assert!(discrepancy_findings > 10, "a campaign of the built-in engines has findings");
    // Every discrepancy is in exactly one finding.
    let covered: u64 = file.findings.iter().filter(|f| f.is_discrepancy()).map(|f| f.count).sum();
    assert_eq!(covered, out.summary.discrepancies);
    let n = replay_all(&file, &written, &EngineSet::default());
    assert_eq!(n, discrepancy_findings, "every finding was shrunk");
    // The report opens with the findings, and `crashtest findings` prints them.
    let md = std::fs::read_to_string(written.join("summary.md")).unwrap();
    assert!(md.find("## Findings").unwrap() < md.find("## Provenance").unwrap());
    let html = std::fs::read_to_string(written.join("index.html")).unwrap();
    assert!(html.find("id=\"findings\"").unwrap() < html.find("id=\"provenance\"").unwrap());
    assert!(html.contains("class=\"sortable\"") && html.contains("<script>") && !html.contains("<script src"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_shrunk_case_of_the_sample_report_replays_with_its_signature() {
    // `reports/sample` holds the default report's findings (README there says
    // how it is regenerated); the peers are judged when installed, and their
    // findings are skipped otherwise, with the count printed.
    let dir = root().join("reports/sample");
    let file = harness::findings::read(&dir).unwrap();
    let peers =
        crashtest::process_engines(&[], Some(&crashtest::peer_engines_file().expect("the shipped list").0), 60.0)
            .unwrap();
    let set = EngineSet::select_with("all", None, peers).unwrap();
    let mut replayable = file.clone();
    replayable.findings.retain(|f| set.judged.iter().any(|e| e.name == f.engine()));
    let skipped = file.findings.len() - replayable.findings.len();
    assert!(set.missing.is_empty() || skipped > 0, "engines missing ({:?}) but every finding replayable", set.missing);
    eprintln!("{skipped} findings of engines not installed here: {:?}", set.missing);
    let n = replay_all(&replayable, &dir, &set);
    assert!(n > 0);
}

#[test]
fn diff_of_two_seeds_has_no_false_change_and_sees_a_real_one() {
    let a = campaign(1, 2000, vec![root().join("fixtures")]);
    let b = campaign(2, 2000, vec![root().join("fixtures")]);
    let d = diff((&a.summary, &a.findings), (&b.summary, &b.findings), &[]);
    let changed: Vec<String> = d
        .findings
        .iter()
        .filter(|f| !matches!(f.change, Change::Noise | Change::Same))
        .map(|f| format!("{:?} {} {:?} {:?} z {:.1}", f.change, f.title, f.old, f.new, f.z))
        .collect();
    assert!(changed.is_empty(), "the engines did not change, yet:\n{}", changed.join("\n"));
    let scores: Vec<String> = d
        .scores
        .iter()
        .filter(|s| s.change != Change::Same)
        .map(|s| format!("{} {} {:?} {:?} z {:.1}", s.engine, s.query, s.old, s.new, s.z))
        .collect();
    assert!(scores.is_empty(), "{}", scores.join("\n"));
    assert!(d.worse(&["collide/robust".into(), "parry3d-f64".into()]).is_empty());
    // The lecture's methods in place of the robust ones: worse, and said so.
    let d = diff(
        (&a.summary, &a.findings),
        (&b.summary, &b.findings),
        &[("collide/robust".into(), "collide/lecture".into())],
    );
    assert_eq!(d.worse(&["collide/robust".into()]), vec!["collide/robust".to_string()]);
    assert!(d.findings.iter().any(|f| f.change == Change::New && f.signature.engine == "collide/robust"));
}

/// The absolute paths in `text`: a `/` that begins a word (after a space, a
/// bracket, a quote, a backtick, `=` or a line's start) followed by a letter,
/// in a word holding another `/` — `/srv/build/engines/…`, `/opt/u/.cargo/…` —
/// with its line number.
fn absolute_paths(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let chars: Vec<char> = line.chars().collect();
        for i in 0..chars.len() {
            let starts = i == 0 || " ([{\"'`=:".contains(chars[i - 1]);
            if chars[i] == '/' && starts && chars.get(i + 1).is_some_and(char::is_ascii_alphabetic) {
                let word: String =
                    chars[i..].iter().take_while(|c| !c.is_whitespace() && !")]}\"'`,".contains(**c)).collect();
                if word[1..].contains('/') {
                    out.push((n + 1, word));
                }
            }
        }
    }
    out
}

/// Nothing committed under `reports/sample/` names the machine that made it:
/// the drafts and the findings give commands relative to the repository
/// (`engines/.venv/bin/python engines/fcl/engine.py`) and a dependency's
/// panic from its crate's folder.
#[test]
fn the_sample_report_holds_no_absolute_path() {
    assert_eq!(absolute_paths("run /srv/build/engines/x.py and (/opt/u/.cargo/a.rs)").len(), 2);
    assert!(absolute_paths("1/2 of a/b, km/s, engines/fcl/engine.py, </a>").is_empty());
    let mut found = Vec::new();
    let mut stack = vec![root().join("reports/sample")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("the sample's folder reads") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let text = std::fs::read_to_string(&path).expect("a text file");
                for (line, word) in absolute_paths(&text) {
                    found.push(format!("{}:{line}: {word}", path.display()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "{} absolute paths, the first:\n{}",
        found.len(),
        found[..found.len().min(10)].join("\n")
    );
}
