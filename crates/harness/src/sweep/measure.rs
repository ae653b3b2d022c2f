//! Running a sweep: every case through every judged engine and the referee (the
//! campaign's [`check_case`]), folded per query, engine and point into
//! [`PointStats`], and walked for breaking points.

use super::catalog::{BREAK_REL, SWEEPS, Settings, Sweep, SweepPoint, cases};
use crate::case::Query;
use crate::check::{CaseResult, check_case};
use crate::engines::EngineSet;
use crate::judge::{Misclass, Verdict};
use rayon::prelude::*;
use serde::Serialize;

pub use crate::judge::headline;

/// What one engine did at one point of one query, over the poses.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PointStats {
    /// Cases run (poses).
    pub cases: u32,
    /// Cases with a measured error: answered with the referee's classification
    /// (or only a flag differing), not a known divergence.
    pub measured: u32,
    /// Largest headline error over the measured cases.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
    /// Median headline error over the measured cases (the lower middle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub median: Option<f64>,
    /// Caught panics.
    #[serde(skip_serializing_if = "is_zero")]
    pub panics: u32,
    /// Answers with a NaN or an infinity.
    #[serde(skip_serializing_if = "is_zero")]
    pub non_finite: u32,
    /// A contact, hit or overlap the referee does not have.
    #[serde(skip_serializing_if = "is_zero")]
    pub false_positives: u32,
    /// A contact, hit or overlap the referee has, missed.
    #[serde(skip_serializing_if = "is_zero")]
    pub false_negatives: u32,
    /// A `parallel` or `degenerate` flag the referee does not share.
    #[serde(skip_serializing_if = "is_zero")]
    pub flags: u32,
    /// Of the misclassifications, those within the tolerance band of the
    /// referee's decision boundary (the campaign counts them apart).
    #[serde(skip_serializing_if = "is_zero")]
    pub borderline: u32,
    /// Verdicts beyond the campaign's tolerance (value or classification).
    #[serde(skip_serializing_if = "is_zero")]
    pub disagree: u32,
    /// Known divergences (documented conventions, not errors; unmeasured).
    #[serde(skip_serializing_if = "is_zero")]
    pub known: u32,
    /// Unanswered: the engine does not do this query, or the referee refused.
    #[serde(skip_serializing_if = "is_zero")]
    pub unsupported: u32,
}

fn is_zero(x: &u32) -> bool {
    *x == 0
}

impl PointStats {
    /// Misclassifications of every kind.
    pub fn misclassified(&self) -> u32 {
        self.false_positives + self.false_negatives + self.flags
    }

    /// Failures: panics, non-finite answers and misclassifications.
    pub fn failures(&self) -> u32 {
        self.panics + self.non_finite + self.misclassified()
    }

    /// Misclassifications outside the tolerance band of the referee's decision
    /// boundary: the ones the campaign calls disagreements.
    pub fn misclassified_outside_band(&self) -> u32 {
        self.misclassified() - self.borderline
    }

    /// Disagreements on values alone (classification right, an error beyond the
    /// campaign's tolerance).
    pub fn beyond_tolerance(&self) -> u32 {
        self.disagree - self.misclassified_outside_band()
    }

    /// Why this point breaks, if it does: the gravest failure, else an error
    /// above [`BREAK_REL`].
    pub fn breaks(&self) -> Option<BreakWhy> {
        if self.panics > 0 {
            Some(BreakWhy::Panic { count: self.panics, of: self.cases })
        } else if self.non_finite > 0 {
            Some(BreakWhy::NonFinite { count: self.non_finite, of: self.cases })
        } else if self.misclassified() > 0 {
            Some(BreakWhy::Misclassified { count: self.misclassified(), of: self.cases })
        } else {
            self.max.filter(|m| *m > BREAK_REL).map(|max| BreakWhy::Error { max })
        }
    }
}

/// Why a point breaks.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum BreakWhy {
    /// The largest error exceeds [`BREAK_REL`].
    Error {
        /// That error.
        max: f64,
    },
    /// Some poses are classified otherwise than by the referee.
    Misclassified {
        /// How many.
        count: u32,
        /// Of how many poses.
        of: u32,
    },
    /// Some answers carry a NaN or an infinity.
    NonFinite {
        /// How many.
        count: u32,
        /// Of how many poses.
        of: u32,
    },
    /// The engine panicked on some poses.
    Panic {
        /// How many.
        count: u32,
        /// Of how many poses.
        of: u32,
    },
}

impl BreakWhy {
    /// A short word for tables: `error`, `misclass`, `NaN`, `panic`.
    pub fn word(&self) -> &'static str {
        match self {
            BreakWhy::Error { .. } => "error",
            BreakWhy::Misclassified { .. } => "misclass",
            BreakWhy::NonFinite { .. } => "NaN",
            BreakWhy::Panic { .. } => "panic",
        }
    }
}

/// Where a walk breaks.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Break {
    /// Index of the point in the sweep's points.
    pub point: usize,
    /// The parameter there (0 at the exact point).
    pub value: f64,
    /// As printed.
    pub label: String,
    /// Why.
    pub why: BreakWhy,
}

/// One walk from the benign end toward a degenerate end.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Walk {
    /// The end it walks to (its label).
    pub toward: String,
    /// Where it first breaks; `None` if it never does in range.
    pub breaks_at: Option<Break>,
}

/// One engine along one query of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Series {
    /// The engine.
    pub engine: String,
    /// Per point, in the sweep's point order (written column by column: one
    /// array per field, aligned with the sweep's points, a failure kind only
    /// when it occurs).
    #[serde(serialize_with = "columns")]
    pub points: Vec<PointStats>,
    /// Its breaking point per walk.
    pub walks: Vec<Walk>,
    /// Largest error anywhere in the sweep.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst: Option<f64>,
}

/// A count's name in the data and how to read it.
type Count = (&'static str, fn(&PointStats) -> u32);

/// [`PointStats`] as columns: `{"cases": [...], "max": [...], ...}`, counts
/// that are zero at every point left out; a point without a measured error is
/// `null` in `max` and `median`.
fn columns<S: serde::Serializer>(points: &[PointStats], s: S) -> Result<S::Ok, S::Error> {
    use serde_json::{Map, Value};
    let mut m = Map::new();
    let counts: [Count; 12] = [
        ("cases", |p| p.cases),
        ("measured", |p| p.measured),
        ("panics", |p| p.panics),
        ("non_finite", |p| p.non_finite),
        ("false_positives", |p| p.false_positives),
        ("false_negatives", |p| p.false_negatives),
        ("flags", |p| p.flags),
        ("borderline", |p| p.borderline),
        ("disagree", |p| p.disagree),
        ("known", |p| p.known),
        ("unsupported", |p| p.unsupported),
        ("failures", |p| p.failures()),
    ];
    for (name, get) in counts {
        let col: Vec<u32> = points.iter().map(get).collect();
        if col.iter().any(|x| *x != 0) || name == "cases" {
            m.insert(name.into(), Value::from(col));
        }
    }
    let floats = |get: fn(&PointStats) -> Option<f64>| -> Value {
        Value::Array(points.iter().map(|p| get(p).map_or(Value::Null, Value::from)).collect())
    };
    m.insert("max".into(), floats(|p| p.max));
    m.insert("median".into(), floats(|p| p.median));
    serde::Serialize::serialize(&m, s)
}

impl Series {
    /// Cases it answered (measured, failed or known), over all points.
    pub fn answered(&self) -> u32 {
        self.points.iter().map(|p| p.cases - p.unsupported).sum()
    }

    /// Cases with a measured error, over all points.
    pub fn measured(&self) -> u32 {
        self.points.iter().map(|p| p.measured).sum()
    }
}

/// One query of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ProbeResult {
    /// Its name.
    pub name: String,
    /// Its query kind.
    pub query: Query,
    /// Cases the referee refused, per point (an engine's answer to those is
    /// unjudged).
    pub referee_refused: Vec<u32>,
    /// Every judged engine, in report order.
    pub engines: Vec<Series>,
}

/// Everything one sweep measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepResult {
    /// The sweep's name.
    pub name: String,
    /// What moves.
    pub title: String,
    /// The parameter.
    pub parameter: String,
    /// Its points, ascending.
    pub points: Vec<SweepPoint>,
    /// The poses and the seed.
    pub settings: Settings,
    /// Per query.
    pub probes: Vec<ProbeResult>,
}

/// One engine's outcome on one case, reduced to what the statistics need.
#[derive(Clone, Copy, Debug)]
struct Outcome {
    error: Option<f64>,
    verdict: Kind,
    misclass: Option<Misclass>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Agree,
    Borderline,
    Disagree,
    Known,
    Unsupported,
    Panic,
    NonFinite,
}

fn outcomes(c: &CaseResult) -> (bool, Vec<Outcome>) {
    let refused = c.referee.is_none();
    let v = c
        .engines
        .iter()
        .map(|r| {
            let kind = match &r.verdict {
                Verdict::Agree => Kind::Agree,
                Verdict::Borderline { .. } => Kind::Borderline,
                Verdict::Disagree { .. } => Kind::Disagree,
                Verdict::KnownDivergence { .. } => Kind::Known,
                Verdict::Unsupported { .. } => Kind::Unsupported,
                Verdict::Failed { reason } if reason.starts_with("panicked") => Kind::Panic,
                Verdict::Failed { .. } => Kind::NonFinite,
            };
            let misclass = r.errors.misclass;
            let judged = matches!(kind, Kind::Agree | Kind::Borderline | Kind::Disagree);
            // A missed or false contact or hit has no error to measure: it is a
            // failure. A flag alone leaves the values comparable.
            let measurable =
                judged && !matches!(misclass, Some(Misclass::FalsePositive) | Some(Misclass::FalseNegative));
            Outcome { error: measurable.then(|| headline(&r.errors, c.scale)), verdict: kind, misclass }
        })
        .collect();
    (refused, v)
}

fn fold_point(stats: &mut PointStats, errors: &mut Vec<f64>, o: &Outcome) {
    stats.cases += 1;
    match o.verdict {
        Kind::Panic => stats.panics += 1,
        Kind::NonFinite => stats.non_finite += 1,
        Kind::Known => stats.known += 1,
        Kind::Unsupported => stats.unsupported += 1,
        Kind::Agree | Kind::Borderline | Kind::Disagree => {
            match o.misclass {
                Some(Misclass::FalsePositive) => stats.false_positives += 1,
                Some(Misclass::FalseNegative) => stats.false_negatives += 1,
                Some(Misclass::Flag) => stats.flags += 1,
                None => {}
            }
            if o.misclass.is_some() && o.verdict == Kind::Borderline {
                stats.borderline += 1;
            }
            if o.verdict == Kind::Disagree {
                stats.disagree += 1;
            }
        }
    }
    if let Some(e) = o.error {
        stats.measured += 1;
        errors.push(e);
    }
}

fn finish_point(stats: &mut PointStats, errors: &mut [f64]) {
    errors.sort_by(f64::total_cmp);
    stats.max = errors.last().copied();
    stats.median = (!errors.is_empty()).then(|| errors[(errors.len() - 1) / 2]);
}

/// The breaking point of one walk over `points` (indices from the benign end).
fn walk(stats: &[PointStats], points: &[SweepPoint], path: &[usize]) -> Walk {
    let end = path.last().copied().unwrap_or(0);
    let breaks_at = path.iter().find_map(|&i| {
        stats[i].breaks().map(|why| Break { point: i, value: points[i].value, label: points[i].label.clone(), why })
    });
    Walk { toward: points[end].label.clone(), breaks_at }
}

/// Runs one sweep: every case judged (in parallel, folded in order).
pub fn run(sweep: &Sweep, settings: &Settings, engines: &EngineSet) -> SweepResult {
    let judged = &engines.judged;
    let points = sweep.points();
    let all = cases(sweep, settings);
    engines.prefetch(all.iter().map(|c| &c.case));
    let results: Vec<(bool, Vec<Outcome>)> = all.par_iter().map(|c| outcomes(&check_case(&c.case, engines))).collect();

    let walks = sweep.walks();
    let mut probes = Vec::new();
    for (pi, probe) in sweep.probes.iter().enumerate() {
        let mut referee_refused = vec![0u32; points.len()];
        let mut series: Vec<(Vec<PointStats>, Vec<Vec<f64>>)> = judged
            .iter()
            .map(|_| (vec![PointStats::default(); points.len()], vec![Vec::new(); points.len()]))
            .collect();
        for (c, (refused, outs)) in all.iter().zip(&results).filter(|(c, _)| c.probe == pi) {
            if *refused {
                referee_refused[c.point] += 1;
            }
            for (ei, o) in outs.iter().enumerate() {
                let (stats, errors) = &mut series[ei];
                fold_point(&mut stats[c.point], &mut errors[c.point], o);
            }
        }
        let engines = judged
            .iter()
            .zip(series)
            .map(|(engine, (mut stats, mut errors))| {
                for (s, e) in stats.iter_mut().zip(errors.iter_mut()) {
                    finish_point(s, e);
                }
                let worst = stats.iter().filter_map(|s| s.max).reduce(f64::max);
                let walks = walks.iter().map(|path| walk(&stats, &points, path)).collect();
                Series { engine: engine.name.clone(), points: stats, walks, worst }
            })
            .collect();
        probes.push(ProbeResult { name: probe.name.to_string(), query: probe.query, referee_refused, engines });
    }
    SweepResult {
        name: sweep.name.to_string(),
        title: sweep.title.to_string(),
        parameter: sweep.parameter.to_string(),
        points,
        settings: *settings,
        probes,
    }
}

/// Runs every sweep, in order.
pub fn run_all(settings: &Settings, engines: &EngineSet) -> Vec<SweepResult> {
    SWEEPS.iter().filter(|s| !super::catalog::standalone(s.name)).map(|s| run(s, settings, engines)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::judge::Errors;

    fn point(value: f64) -> SweepPoint {
        SweepPoint { value, label: format!("{value:e}"), exact: value == 0.0 }
    }

    fn measured(max: f64) -> PointStats {
        PointStats { cases: 4, measured: 4, max: Some(max), median: Some(max / 2.0), ..Default::default() }
    }

    #[test]
    fn a_walk_breaks_at_the_first_point_past_the_threshold() {
        let points: Vec<SweepPoint> = [0.0, 1e-3, 1e-2, 1e-1, 1.0].map(point).to_vec();
        let stats = vec![measured(1.0), measured(1e-5), measured(1e-7), measured(1e-16), measured(0.0)];
        let w = walk(&stats, &points, &[4, 3, 2, 1, 0]);
        let b = w.breaks_at.expect("breaks");
        assert_eq!(b.point, 1, "1e-5 is the first error above 1e-6 from the benign end");
        assert!(matches!(b.why, BreakWhy::Error { .. }));
        assert_eq!(w.toward, points[0].label);
    }

    #[test]
    fn a_failure_breaks_a_walk_even_with_small_errors() {
        let points: Vec<SweepPoint> = [1e-2, 1e-1, 1.0].map(point).to_vec();
        let mut bad = measured(0.0);
        bad.false_negatives = 1;
        let stats = vec![measured(0.0), bad, measured(0.0)];
        let w = walk(&stats, &points, &[2, 1, 0]);
        assert_eq!(w.breaks_at.map(|b| (b.point, b.why.word())), Some((1, "misclass")));
    }

    #[test]
    fn a_walk_that_never_breaks_says_so() {
        let points: Vec<SweepPoint> = [1e-2, 1e-1, 1.0].map(point).to_vec();
        let stats = vec![measured(1e-9), measured(1e-12), measured(0.0)];
        assert_eq!(walk(&stats, &points, &[2, 1, 0]).breaks_at, None);
    }

    #[test]
    fn panics_outrank_other_failures_in_the_reason() {
        let s = PointStats { cases: 8, panics: 1, non_finite: 2, flags: 3, max: Some(1.0), ..Default::default() };
        assert_eq!(s.breaks(), Some(BreakWhy::Panic { count: 1, of: 8 }));
        let s = PointStats { cases: 8, non_finite: 2, flags: 3, ..Default::default() };
        assert_eq!(s.breaks(), Some(BreakWhy::NonFinite { count: 2, of: 8 }));
    }

    #[test]
    fn the_median_is_the_lower_middle_and_the_max_the_largest() {
        let mut s = PointStats::default();
        let mut e = vec![3.0, 1.0, 4.0, 2.0];
        finish_point(&mut s, &mut e);
        assert_eq!(s.max.map(f64::to_bits), Some(4.0f64.to_bits()));
        assert_eq!(s.median.map(f64::to_bits), Some(2.0f64.to_bits()));
    }

    #[test]
    fn the_headline_divides_lengths_by_the_scale_and_keeps_angles() {
        let e = Errors { point: Some(2.0), depth: Some(-4.0), normal: Some(0.5), ..Default::default() };
        assert_eq!(headline(&e, 10.0).to_bits(), 0.5f64.to_bits(), "the normal's 0.5 rad beats 0.4 and 0.2");
        assert_eq!(headline(&Errors::default(), 10.0).to_bits(), 0.0f64.to_bits(), "nothing to compare: exact");
    }
}
