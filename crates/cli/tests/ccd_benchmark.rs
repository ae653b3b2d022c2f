//! `crashtest report --ccd-benchmark DIR` through the binary: the section
//! lands in the report's files, and a folder that cannot be read is named on
//! standard error with exit code 2 while the report is still written.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root: the runs start there as a user's would.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Runs crashtest: its exit code, standard output and standard error.
fn crashtest(args: &[&str]) -> (i32, String, String) {
    let out =
        Command::new(env!("CARGO_BIN_EXE_crashtest")).current_dir(ROOT).args(args).output().expect("crashtest runs");
    let text = |b: &[u8]| String::from_utf8_lossy(b).to_string();
    (out.status.code().unwrap_or(-1), text(&out.stdout), text(&out.stderr))
}

/// A folder of this test binary, removed first.
fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A vertex–face query of the benchmark's format: a point from (1/4, 1/4, 1)
/// to (1/4, 1/4, `z1`) against the triangle (0,0,0), (1,0,0), (0,1,0).
fn vertex_face(z1: i64, truth: u8) -> String {
    let triangle = format!("0,1,0,1,0,1,{truth}\n1,1,0,1,0,1,{truth}\n0,1,1,1,0,1,{truth}\n");
    format!("1,4,1,4,1,1,{truth}\n{triangle}1,4,1,4,{z1},1,{truth}\n{triangle}")
}

/// A benchmark folder of two vertex–face queries, an impact and a miss.
fn benchmark(name: &str) -> PathBuf {
    let dir = fresh(name);
    let file = dir.join("unit-tests").join("vertex-face").join("data.csv");
    std::fs::create_dir_all(file.parent().expect("a folder")).expect("made");
    std::fs::write(&file, vertex_face(-1, 1) + &vertex_face(2, 0)).expect("written");
    dir
}

fn report(bench: &Path, out: &Path) -> (i32, String, String) {
    crashtest(&[
        "report",
        "--ccd-benchmark",
        bench.to_str().expect("a UTF-8 path"),
        "--cases",
        "0",
        "--full-range",
        "0",
        "--no-sections",
        "--no-timing",
        "--engines",
        "collide/robust,collide/lecture",
        "--out",
        out.to_str().expect("a UTF-8 path"),
    ])
}

#[test]
fn the_ccd_benchmark_section_is_written_with_the_report() {
    let bench = benchmark("ccd-cli-bench");
    let out = fresh("ccd-cli-report");
    let (code, stdout, stderr) = report(&bench, &out);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains("sections: ccd-benchmark"), "its phase is timed: {stdout}");
    let latest = out.join("latest");
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(latest.join("ccd-benchmark.json")).expect("the section's data"))
            .expect("JSON");
    assert_eq!((data["queries"].as_u64(), data["positives"].as_u64()), (Some(2), Some(1)));
    let engines: Vec<&str> =
        data["engines"].as_array().expect("engines").iter().filter_map(|e| e["engine"].as_str()).collect();
    assert_eq!(engines, ["collide/robust", "collide/lecture", "referee"]);
    for e in data["engines"].as_array().expect("engines") {
        let t = &e["total"];
        assert_eq!((t["false_positives"].as_u64(), t["false_negatives"].as_u64()), (Some(0), Some(0)), "{e}");
    }
    let md = std::fs::read_to_string(latest.join("summary.md")).expect("summary.md");
    assert!(md.contains("## CCD benchmark"), "{md}");
    assert!(md.contains("The referee agrees with the ground truth on all 2 queries."), "{md}");
    let html = std::fs::read_to_string(latest.join("index.html")).expect("index.html");
    assert!(html.contains("<section id=\"ccd-benchmark\">") && html.contains("ccd-benchmark.json"), "linked");
}

#[test]
fn a_missing_ccd_benchmark_folder_exits_2_naming_it_and_the_report_is_still_written() {
    let missing = fresh("ccd-cli-no-such-folder");
    let out = fresh("ccd-cli-report-missing");
    let (code, stdout, stderr) = report(&missing, &out);
    assert_eq!(code, 2, "{stdout}{stderr}");
    let line = stderr.lines().find(|l| l.contains("ccd-cli-no-such-folder")).unwrap_or_else(|| panic!("{stderr}"));
    assert!(line.starts_with("error: --ccd-benchmark: ") && line.contains("not a readable folder"), "{line}");
    let latest = out.join("latest");
    assert!(latest.join("index.html").is_file() && latest.join("summary.json").is_file(), "the report is written");
    let md = std::fs::read_to_string(latest.join("summary.md")).expect("summary.md");
    assert!(md.contains("## CCD benchmark") && md.contains("Not read: "), "the section says what it could not read");
}
