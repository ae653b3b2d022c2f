//! The CCD benchmark's sample queries (Wang, Ferguson, Schneider, Jiang,
//! Attene and Panozzo, "A Large-scale Benchmark and an Inclusion-based
//! Algorithm for Continuous Collision Detection", ACM TOG 40(5), 2021) read as
//! `ccd` cases.
//!
//! A benchmark folder holds one folder per scene (`unit-tests`,
//! `erleben-spikes`, …), each with `vertex-face/` and `edge-edge/` folders of
//! CSV files. A file is `8·n` rows of 7 integers: a query is 8 rows, each a
//! position as three rationals (numerator, denominator for x, y and z) and the
//! query's ground truth (1: the primitives meet in `[0, 1]`), the same on all
//! 8 rows. The rows are, for vertex–face, `v_t0, f0_t0, f1_t0, f2_t0, v_t1,
//! f0_t1, f1_t1, f2_t1`, and for edge–edge, `ea0_t0, ea1_t0, eb0_t0, eb1_t0,
//! ea0_t1, ea1_t1, eb0_t1, eb1_t1`.
//!
//! Every coordinate must be exactly a double (the benchmark's are dyadic): one
//! that is not is refused with its file, query, row and column, never rounded,
//! since a rounded query is another query and its ground truth would not hold.

use crate::case::{Case, Expect, Query, Shape};
use dashu::integer::{IBig, UBig};
use dashu::rational::RBig;
use oracle::geom::{MovingPoint, MovingSegment, MovingTriangle, P3};
use std::fmt;
use std::path::{Path, PathBuf};

/// The two kinds of query, as the benchmark's folders name them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    /// `vertex-face`: a moving point against a moving triangle.
    VertexFace,
    /// `edge-edge`: two moving segments.
    EdgeEdge,
}

impl Kind {
    /// The folder name.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::VertexFace => "vertex-face",
            Kind::EdgeEdge => "edge-edge",
        }
    }
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One query of the benchmark.
#[derive(Clone, Debug)]
pub struct BenchmarkQuery {
    /// The scene folder (`unit-tests`, `erleben-spikes`, …).
    pub scene: String,
    /// Vertex–face or edge–edge.
    pub kind: Kind,
    /// The file, relative to the benchmark folder, with `/` separators.
    pub file: String,
    /// The query's index in its file, from 0.
    pub index: usize,
    /// The benchmark's ground truth: the primitives meet in `[0, 1]`.
    pub truth: bool,
    /// The query as a `ccd` case, `expect.impact` its ground truth.
    pub case: Case,
}

/// A file that could not be read, or a query that could not be taken.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportError {
    /// The file (as the user named the folder, joined with the file's path).
    pub file: PathBuf,
    /// What is wrong, naming the query, row and column where there is one.
    pub message: String,
}

impl fmt::Display for ImportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.file.display(), self.message)
    }
}

/// Every query of the benchmark folder `dir`, in a fixed order (scene, kind,
/// file name, query), with the errors of the files that could not be read.
/// A file with a bad query keeps its good queries: only the bad one is left
/// out, and named among the errors.
pub fn read_dir(dir: &Path) -> (Vec<BenchmarkQuery>, Vec<ImportError>) {
    let mut queries = Vec::new();
    let mut errors = Vec::new();
    let mut files = Vec::new();
    match std::fs::read_dir(dir) {
        Err(e) => errors.push(ImportError { file: dir.to_path_buf(), message: format!("not a readable folder: {e}") }),
        Ok(scenes) => {
            for scene in scenes.flatten() {
                let Ok(name) = scene.file_name().into_string() else { continue };
                for kind in [Kind::VertexFace, Kind::EdgeEdge] {
                    let folder = scene.path().join(kind.as_str());
                    let Ok(entries) = std::fs::read_dir(&folder) else { continue };
                    for e in entries.flatten() {
                        let Ok(file) = e.file_name().into_string() else { continue };
                        if file.ends_with(".csv") {
                            files.push((name.clone(), kind, file));
                        }
                    }
                }
            }
        }
    }
    files.sort();
    if files.is_empty() && errors.is_empty() {
        errors.push(ImportError {
            file: dir.to_path_buf(),
            message: "no <scene>/vertex-face/*.csv or <scene>/edge-edge/*.csv under it".into(),
        });
    }
    for (scene, kind, file) in files {
        let rel = format!("{scene}/{kind}/{file}");
        let path = dir.join(&scene).join(kind.as_str()).join(&file);
        match std::fs::read_to_string(&path) {
            Ok(text) => {
                let (q, e) = read_csv(&scene, kind, &rel, &text);
                queries.extend(q);
                errors.extend(e.into_iter().map(|message| ImportError { file: path.clone(), message }));
            }
            Err(e) => errors.push(ImportError { file: path, message: format!("cannot read: {e}") }),
        }
    }
    (queries, errors)
}

/// The queries of one CSV file's text; `rel` names the file in cases. Errors
/// name the query (from 0), its row (1 to 8) and the file's line.
pub fn read_csv(scene: &str, kind: Kind, rel: &str, text: &str) -> (Vec<BenchmarkQuery>, Vec<String>) {
    let lines: Vec<(usize, &str)> =
        text.lines().enumerate().map(|(i, l)| (i + 1, l.trim())).filter(|(_, l)| !l.is_empty()).collect();
    let mut queries = Vec::new();
    let mut errors = Vec::new();
    if !lines.len().is_multiple_of(8) {
        errors.push(format!(
            "{} rows, not a multiple of 8: the last {} rows make no query and are left out",
            lines.len(),
            lines.len() % 8
        ));
    }
    for (index, rows) in lines.chunks_exact(8).enumerate() {
        match query(rows) {
            Ok((points, truth)) => queries.push(BenchmarkQuery {
                scene: scene.to_string(),
                kind,
                file: rel.to_string(),
                index,
                truth,
                case: case_of(kind, rel, index, &points, truth),
            }),
            Err(e) => errors.push(format!("query {index}: {e}")),
        }
    }
    (queries, errors)
}

/// The 8 positions and the ground truth of one query's rows.
fn query(rows: &[(usize, &str)]) -> Result<([P3; 8], bool), String> {
    let mut points = [[0.0; 3]; 8];
    let mut truth = None;
    for (r, (line, text)) in rows.iter().enumerate() {
        let at = |col: usize| format!("row {} (line {line}), column {}", r + 1, col + 1);
        let cols: Vec<&str> = text.split(',').map(str::trim).collect();
        if cols.len() != 7 {
            return Err(format!("row {} (line {line}): {} columns, expected 7", r + 1, cols.len()));
        }
        for axis in 0..3 {
            let (n, d) = (cols[2 * axis], cols[2 * axis + 1]);
            points[r][axis] = exact_double(n, d).map_err(|e| format!("{}: {e}", at(2 * axis)))?;
        }
        let bit = match cols[6] {
            "0" => false,
            "1" => true,
            other => return Err(format!("{}: ground truth {other:?}, expected 0 or 1", at(6))),
        };
        match truth {
            None => truth = Some(bit),
            Some(t) if t != bit => {
                return Err(format!("{}: ground truth {} differs from the query's first row's", at(6), u8::from(bit)));
            }
            Some(_) => {}
        }
    }
    Ok((points, truth.unwrap_or(false)))
}

/// `n / d` as the double it exactly is, or why it is not one.
fn exact_double(n: &str, d: &str) -> Result<f64, String> {
    let num: IBig = n.parse().map_err(|_| format!("numerator {n:?} is not an integer"))?;
    let den: UBig = d.parse().map_err(|_| format!("denominator {d:?} is not a positive integer"))?;
    if den == UBig::ZERO {
        return Err(format!("{n}/{d}: zero denominator"));
    }
    let r = RBig::from_parts(num, den);
    let f = match r.to_f64() {
        dashu::base::Approximation::Exact(f) | dashu::base::Approximation::Inexact(f, _) => f,
    };
    // Exactly that double, checked by taking the double back to a rational.
    match RBig::try_from(f) {
        Ok(back) if f.is_finite() && back == r => Ok(f),
        _ => Err(format!("{n}/{d} is not exactly a double (nearest {f:e})")),
    }
}

/// The case of one query: `a` the point or edge `a`, `b` the triangle or edge
/// `b`, `t_max` the benchmark's 1, `expect.impact` its ground truth.
fn case_of(kind: Kind, rel: &str, index: usize, p: &[P3; 8], truth: bool) -> Case {
    let (a, b) = match kind {
        Kind::VertexFace => (
            Shape::MovingPoint(MovingPoint { t0: p[0], t1: p[4] }),
            Shape::MovingTriangle(MovingTriangle { t0: [p[1], p[2], p[3]], t1: [p[5], p[6], p[7]] }),
        ),
        Kind::EdgeEdge => (
            Shape::MovingSegment(MovingSegment { t0: [p[0], p[1]], t1: [p[4], p[5]] }),
            Shape::MovingSegment(MovingSegment { t0: [p[2], p[3]], t1: [p[6], p[7]] }),
        ),
    };
    Case {
        name: format!("{rel} #{index}"),
        source: format!("CCD benchmark sample queries: {rel}, query {index} (ground truth {})", u8::from(truth)),
        query: Query::Ccd,
        a,
        b: Some(b),
        expect: Some(Expect { impact: Some(truth), ..Expect::default() }),
        tol: None,
        t_max: None,
        restitution: None,
    }
}

/// `count` queries of each file: half of them (rounded up) with an impact
/// and the rest without, each half evenly spaced through the file's queries of
/// that truth (where a file has too few of one truth, more of the other); a
/// file with at most `count` queries is kept whole. In the input's order.
pub fn evenly_per_file(queries: &[BenchmarkQuery], count: usize) -> Vec<&BenchmarkQuery> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < queries.len() {
        let file = &queries[start].file;
        let end = start + queries[start..].iter().take_while(|q| &q.file == file).count();
        let all = &queries[start..end];
        if all.len() <= count {
            out.extend(all);
        } else {
            let (pos, neg): (Vec<&BenchmarkQuery>, Vec<&BenchmarkQuery>) = all.iter().partition(|q| q.truth);
            let want_pos = count.div_ceil(2).min(pos.len());
            let want_neg = (count - want_pos).min(neg.len());
            let want_pos = (count - want_neg).min(pos.len());
            let spread = |v: &[&'_ BenchmarkQuery], n: usize| -> Vec<usize> {
                (0..n).map(|k| v[k * v.len() / n].index).collect()
            };
            let mut keep = spread(&pos, want_pos);
            keep.extend(spread(&neg, want_neg));
            out.extend(all.iter().filter(|q| keep.contains(&q.index)));
        }
        start = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const VF: &str = "0,1,0,1,1,1,1\n0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n\
                      1,4,1,4,-1,1,1\n0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n";

    /// A position's bits: the parser must give the benchmark's rationals
    /// exactly, so they are compared bit for bit.
    fn bits<const N: usize>(p: [P3; N]) -> [[u64; 3]; N] {
        p.map(|v| v.map(f64::to_bits))
    }

    #[test]
    fn a_vertex_face_query_becomes_a_case_with_its_rows_in_the_benchmark_order() {
        let (q, e) = read_csv("unit-tests", Kind::VertexFace, "unit-tests/vertex-face/data.csv", VF);
        assert!(e.is_empty(), "{e:?}");
        assert_eq!(q.len(), 1);
        let c = &q[0].case;
        assert!(q[0].truth);
        let (Shape::MovingPoint(p), Some(Shape::MovingTriangle(t))) = (&c.a, &c.b) else { panic!("{c:?}") };
        // Exact dyadic inputs: the parsed values are the rationals themselves.
        assert_eq!(bits([p.t0, p.t1]), bits([[0.0, 0.0, 1.0], [0.25, 0.25, -1.0]]));
        assert_eq!(bits(t.t0), bits([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]));
        assert_eq!(c.expect.as_ref().and_then(|e| e.impact), Some(true));
        assert_eq!(c.name, "unit-tests/vertex-face/data.csv #0");
        assert!(crate::load::validate(c).is_ok());
    }

    #[test]
    fn an_edge_edge_query_takes_edge_a_then_edge_b() {
        let text = "0,1,0,1,0,1,0\n1,1,0,1,0,1,0\n0,1,1,1,0,1,0\n0,1,2,1,0,1,0\n\
                    0,1,0,1,1,1,0\n1,1,0,1,1,1,0\n0,1,1,1,1,1,0\n0,1,2,1,1,1,0\n";
        let (q, e) = read_csv("s", Kind::EdgeEdge, "s/edge-edge/x.csv", text);
        assert!(e.is_empty(), "{e:?}");
        let (Shape::MovingSegment(a), Some(Shape::MovingSegment(b))) = (&q[0].case.a, &q[0].case.b) else { panic!() };
        assert_eq!(bits(a.t0), bits([[0.0; 3], [1.0, 0.0, 0.0]]));
        assert_eq!(bits(b.t0), bits([[0.0, 1.0, 0.0], [0.0, 2.0, 0.0]]));
        assert_eq!(bits(a.t1), bits([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0]]));
        assert!(!q[0].truth);
    }

    #[test]
    fn a_coordinate_that_is_not_a_double_is_refused_with_its_query_row_and_column() {
        let bad = VF.replacen("1,4,1,4", "1,3,1,4", 1);
        let (q, e) = read_csv("s", Kind::VertexFace, "s/vertex-face/x.csv", &bad);
        assert!(q.is_empty());
        assert_eq!(e.len(), 1);
        assert!(e[0].contains("query 0: row 5 (line 5), column 1: 1/3 is not exactly a double"), "{}", e[0]);
    }

    #[test]
    fn huge_dyadic_numerators_and_subnormal_values_are_exact() {
        let exact = |n: &str, d: &str| exact_double(n, d).map(f64::to_bits);
        // A dyadic with a 2^54 denominator: 6004799503160661 · 2^-54, exact.
        assert_eq!(
            exact("6004799503160661", "18014398509481984"),
            Ok((6004799503160661.0 / 18014398509481984.0f64).to_bits())
        );
        // 2^-1074, the smallest subnormal: 1 / 2^1074.
        let den = UBig::ONE << 1074;
        assert_eq!(exact("1", &den.to_string()), Ok(1));
        // 2^-1075 is below every double.
        let den = UBig::ONE << 1075;
        assert!(exact_double("1", &den.to_string()).is_err());
        // 2^53 + 1 needs 54 bits.
        assert!(exact_double("9007199254740993", "1").is_err());
        assert!(exact_double("1", "0").is_err());
        assert!(exact_double("x", "1").is_err());
    }

    #[test]
    fn rows_that_disagree_on_the_ground_truth_or_miss_a_column_are_refused() {
        let flipped = VF.replacen("0,1,1,1,0,1,1\n1,4", "0,1,1,1,0,1,0\n1,4", 1);
        let (_, e) = read_csv("s", Kind::VertexFace, "f", &flipped);
        assert!(e[0].contains("row 4 (line 4), column 7: ground truth 0 differs"), "{e:?}");
        let short = VF.replacen("0,1,0,1,1,1,1", "0,1,0,1,1,1", 1);
        let (_, e) = read_csv("s", Kind::VertexFace, "f", &short);
        assert!(e[0].contains("row 1 (line 1): 6 columns, expected 7"), "{e:?}");
        let (q, e) = read_csv("s", Kind::VertexFace, "f", &VF[..VF.len() - 14]);
        assert!(q.is_empty() && e[0].contains("not a multiple of 8"), "{e:?}");
    }

    #[test]
    fn evenly_per_file_takes_both_truths_spread_and_keeps_short_files_whole() {
        // File a: queries 0..10, those at 0, 4 and 8 with an impact.
        let miss = VF.replace(",1\n", ",0\n");
        let many: String = (0..10).map(|i| if i % 4 == 0 { VF } else { miss.as_str() }).collect();
        let (mut q, _) = read_csv("s", Kind::VertexFace, "a", &many);
        let (q2, _) = read_csv("s", Kind::VertexFace, "b", VF);
        q.extend(q2);
        let picked: Vec<(String, usize)> = evenly_per_file(&q, 4).iter().map(|q| (q.file.clone(), q.index)).collect();
        // Two of the impacts (0, 4 of [0, 4, 8]), two of the misses (1, 5 of
        // [1, 2, 3, 5, 6, 7, 9]), then b whole.
        assert_eq!(picked, [("a".into(), 0), ("a".into(), 1), ("a".into(), 4), ("a".into(), 5), ("b".into(), 0)]);
        // Too few impacts: the misses fill the count.
        let picked = evenly_per_file(&q, 8).iter().filter(|q| q.file == "a").count();
        assert_eq!(picked, 8);
    }
}
