//! The CCD benchmark section (`report --ccd-benchmark DIR`) on a tiny
//! benchmark folder written here: hand-made queries whose answers are known,
//! one of them with a ground-truth bit set wrong on purpose (the referee must
//! be seen to disagree with it, by file and query), and a file with a query
//! that is not exactly doubles (named among the errors, its neighbours still
//! run).

use harness::ccd_report::{self, CcdReport, Clock, Counts, Settings};
use harness::engine::{Engine, Queries, Reply, Unsupported};
use harness::engines::{self, EngineSet};
use oracle::geom::{CcdAnswer, MovingPoint, MovingSegment, MovingTriangle};
use std::path::{Path, PathBuf};

/// One benchmark row: a position as three rationals and the truth bit.
fn row(p: [(i64, u64); 3], truth: bool) -> String {
    let [(xn, xd), (yn, yd), (zn, zd)] = p;
    format!("{xn},{xd},{yn},{yd},{zn},{zd},{}\n", u8::from(truth))
}

fn whole(x: i64) -> (i64, u64) {
    (x, 1)
}

/// The triangle (0,0,0), (1,0,0), (0,1,0), standing still.
const TRIANGLE: [[(i64, u64); 3]; 3] = [[(0, 1); 3], [(1, 1), (0, 1), (0, 1)], [(0, 1), (1, 1), (0, 1)]];

/// A vertex–face query: the point from `p0` to `p1` against [`TRIANGLE`].
fn vertex_face(p0: [(i64, u64); 3], p1: [(i64, u64); 3], truth: bool) -> String {
    let mut s = row(p0, truth);
    for v in TRIANGLE {
        s += &row(v, truth);
    }
    s += &row(p1, truth);
    for v in TRIANGLE {
        s += &row(v, truth);
    }
    s
}

/// An edge–edge query: edge a from (0,0,0) to (1,0,0), standing still; edge
/// b parallel to y at x = `x`, from z = 1 down to z = −1.
fn edge_edge(x: i64, truth: bool) -> String {
    let a = [[whole(0); 3], [whole(1), whole(0), whole(0)]];
    let b = |z: i64| [[whole(x), whole(-1), whole(z)], [whole(x), whole(1), whole(z)]];
    let mut s = String::new();
    for p in [a[0], a[1], b(1)[0], b(1)[1], a[0], a[1], b(-1)[0], b(-1)[1]] {
        s += &row(p, truth);
    }
    s
}

const Q: (i64, u64) = (1, 4);

/// Through the triangle's inside at t = 1/2: an impact.
fn through(truth: bool) -> String {
    vertex_face([Q, Q, whole(1)], [Q, Q, whole(-1)], truth)
}

/// The folder: `unit` (three vertex–face queries, one an impact; two
/// edge–edge, one an impact), `wrong` (an impact marked 0) and `bad` (a
/// coordinate of 1/3 in its first query, then a good query).
fn benchmark(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    let write = |rel: &str, text: &str| {
        let p = dir.join(rel);
        std::fs::create_dir_all(p.parent().expect("a folder")).expect("the folder is made");
        std::fs::write(p, text).expect("the file is written");
    };
    let beside = vertex_face([whole(2), whole(2), whole(1)], [whole(2), whole(2), whole(-1)], false);
    let short = vertex_face([Q, Q, whole(1)], [Q, Q, (1, 2)], false);
    write("unit/vertex-face/a.csv", &(through(true) + &beside + &short));
    write("unit/edge-edge/a.csv", &(edge_edge(0, false).replace(",0\n", ",1\n") + &edge_edge(2, false)));
    write("wrong/vertex-face/w.csv", &through(false));
    write("bad/vertex-face/b.csv", &(through(true).replacen("1,4,1,4,1,1,1", "1,3,1,4,1,1,1", 1) + &beside));
    dir
}

/// Answers every vertex–face query with an impact at 1/2, panics on every
/// edge–edge query.
struct Toy;

impl Queries for Toy {
    fn ccd_point_triangle(&self, _: &MovingPoint, _: &MovingTriangle, _: f64) -> Reply<CcdAnswer> {
        Ok(CcdAnswer { t: Some(0.5), degenerate: false })
    }
    fn ccd_segment_segment(&self, _: &MovingSegment, _: &MovingSegment, _: f64) -> Reply<CcdAnswer> {
        panic!("toy: no edge–edge")
    }
}

/// Answers nothing.
struct Nothing;
impl Queries for Nothing {}

/// Refuses every edge–edge query, answers no impact for vertex–face.
struct Half;
impl Queries for Half {
    fn ccd_point_triangle(&self, _: &MovingPoint, _: &MovingTriangle, _: f64) -> Reply<CcdAnswer> {
        Ok(CcdAnswer { t: None, degenerate: false })
    }
    fn ccd_segment_segment(&self, _: &MovingSegment, _: &MovingSegment, _: f64) -> Reply<CcdAnswer> {
        Err(Unsupported("half: vertex–face only".into()))
    }
}

fn set() -> EngineSet {
    let collide: Vec<Engine> = engines::judged()
        .into_iter()
        .filter(|e| ["collide/robust", "collide/lecture"].contains(&e.name.as_str()))
        .collect();
    let mut judged = collide;
    judged.push(Engine::new("toy", Some(53), Toy));
    judged.push(Engine::new("half", Some(53), Half));
    judged.push(Engine::new("nothing", Some(53), Nothing));
    EngineSet::new(judged, "toy").expect("a valid set")
}

fn total<'a>(r: &'a CcdReport, engine: &str) -> &'a Counts {
    &r.engines.iter().find(|e| e.engine == engine).unwrap_or_else(|| panic!("{engine} has a row: {r:#?}")).total
}

/// (queries, false positives, false negatives, unsupported, failed).
fn counts(c: &Counts) -> (usize, usize, usize, usize, usize) {
    (c.queries, c.false_positives, c.false_negatives, c.unsupported, c.failed)
}

#[test]
fn the_section_counts_each_engine_against_the_ground_truth_and_the_referee() {
    let dir = benchmark("ccd-bench-counts");
    let r = ccd_report::run(&dir, &Settings { timing: false, ..Settings::default() }, &set());

    // The bad file: its first query named, its second still run.
    assert_eq!(r.errors.len(), 1, "{:?}", r.errors);
    assert!(r.errors[0].contains("b.csv") && r.errors[0].contains("query 0: row 1"), "{}", r.errors[0]);
    assert_eq!((r.queries, r.positives), (7, 2));
    let groups: Vec<(&str, &str, usize)> = r.groups.iter().map(|g| (&*g.scene, &*g.kind, g.queries)).collect();
    assert_eq!(
        groups,
        [("bad", "vertex-face", 1), ("unit", "vertex-face", 3), ("unit", "edge-edge", 2), ("wrong", "vertex-face", 1)]
    );

    // The engine that answers nothing has no row, and the section says why.
    assert!(r.not_answering.iter().any(|n| n.engine == "nothing"), "{:?}", r.not_answering);
    assert!(r.engines.iter().all(|e| e.engine != "nothing"));

    // The toy: an impact on every vertex–face query (false on `beside` twice,
    // `short`, and the one marked wrong), a panic on edge–edge (failed, never
    // a negative).
    let toy = total(&r, "toy");
    assert_eq!(counts(toy), (7, 4, 0, 0, 2));
    assert_eq!(toy.answered, 5);
    // Half: no impact on vertex–face (the `through` impact missed; the wrong
    // one's bit is 0), edge–edge refused: unsupported, not negative.
    assert_eq!(counts(total(&r, "half")), (7, 0, 1, 2, 0));

    // The referee agrees with every bit but the one set wrong, listed by file
    // and query.
    assert_eq!(r.referee.unanswered, 0, "{:?}", r.referee.unanswered_examples);
    let d: Vec<(&str, usize, bool)> = r.referee.disagreements.iter().map(|q| (&*q.file, q.index, q.truth)).collect();
    assert_eq!(d, [("wrong/vertex-face/w.csv", 0, false)]);
    assert_eq!(r.referee.agree, 6);
    let referee = total(&r, engines::REFEREE);
    assert_eq!(counts(referee), (7, 1, 0, 0, 0));
    assert!(referee.vs_referee.is_none());

    // Against the referee: the toy agrees where there is an impact at 1/2
    // (the impacts here are at exactly 1/2), and its false impacts are
    // disagreements.
    let v = toy.vs_referee.as_ref().expect("judged");
    assert_eq!((v.agree, v.disagree, v.false_impacts, v.missed_impacts), (2, 3, 3, 0));
    let v = total(&r, "half").vs_referee.clone().expect("judged");
    assert_eq!((v.agree, v.disagree, v.missed_impacts), (3, 2, 2));

    // collide's methods classify every query as the referee does (these
    // queries are far from every boundary): one false positive each against
    // the ground truth, the one set wrong.
    for name in ["collide/robust", "collide/lecture"] {
        let c = total(&r, name);
        assert_eq!(counts(c), (7, 1, 0, 0, 0), "{name}");
        let v = c.vs_referee.as_ref().expect("judged");
        assert_eq!(v.agree, 7, "{name}: {v:?}");
        let e = r.engines.iter().find(|e| e.engine == name).expect("a row");
        assert_eq!(e.misclassified.len(), 1);
        assert_eq!((e.misclassified[0].file.as_str(), e.misclassified[0].index), ("wrong/vertex-face/w.csv", 0));
    }

    // Rows per scene and kind add up to the total.
    for e in &r.engines {
        let sum: usize = e.rows.iter().map(|row| row.counts.false_positives).sum();
        assert_eq!(sum, e.total.false_positives, "{}", e.engine);
        assert_eq!(e.rows.len(), r.groups.len());
        assert!(e.total.mean_ns.is_none(), "nothing timed");
    }

    let s = ccd_report::section_of(&r);
    assert_eq!(s.id, "ccd-benchmark");
    assert!(s.markdown.starts_with("## CCD benchmark\n"), "{}", s.markdown);
    assert!(s.markdown.contains("DISAGREE on 1 of 7 queries"), "{}", s.markdown);
    assert!(s.markdown.contains("| wrong/vertex-face/w.csv | 0 | none | impact at 5e-1 |"), "{}", s.markdown);
    assert!(s.markdown.contains("Answers no ccd query: nothing"), "{}", s.markdown);
    assert!(s.markdown.contains("Nothing was timed"), "{}", s.markdown);
    assert!(s.html.contains("<table>") && s.html.contains("b.csv"), "{}", s.html);
    assert_eq!(s.data["referee"]["disagreements"][0]["file"], "wrong/vertex-face/w.csv");
}

#[test]
fn timed_engines_say_how_and_agreement_is_said_in_words() {
    let dir = benchmark("ccd-bench-timed");
    std::fs::remove_dir_all(dir.join("wrong")).expect("removed");
    std::fs::remove_dir_all(dir.join("bad")).expect("removed");
    let r = ccd_report::run(&dir, &Settings { timing: true, reps: 1 }, &set());
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert!(ccd_report::referee_words(&r).contains("agrees with the ground truth on all 5 queries"), "{r:#?}");
    for e in &r.engines {
        assert_eq!(e.clock, Clock::InProcess);
        let answered = e.total.answered;
        assert_eq!(e.total.timed, answered, "{}", e.engine);
        assert!(e.total.mean_ns.is_some_and(|ns| ns > 0.0), "{}: {:?}", e.engine, e.total);
    }
}

#[test]
fn a_missing_folder_is_an_error_naming_it_and_the_section_still_renders() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("ccd-bench-missing");
    let _ = std::fs::remove_dir_all(&dir);
    let (s, errors) = ccd_report::section(&dir, &Settings::default(), &set());
    assert_eq!(errors.len(), 1);
    assert!(errors[0].contains("ccd-bench-missing") && errors[0].contains("not a readable folder"), "{errors:?}");
    assert!(s.markdown.contains("Not read: ") && s.markdown.contains("0 queries"), "{}", s.markdown);
}
