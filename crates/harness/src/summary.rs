//! What a campaign measured, as data: `summary.json` is this, serialized. It is
//! mergeable (counts add, histograms add, maxima take the larger), so sharded
//! campaigns join into one summary without their raw samples.

use crate::case::Query;
use serde::{Deserialize, Serialize};

/// Error histograms have this many bins per decade (bin edges 10^(k/BINS_PER_DECADE)):
/// quantiles read from them are within a factor 10^(1/50) ≈ 1.047 (under 5%) of
/// the sample's.
pub const BINS_PER_DECADE: i32 = 50;
/// The smallest error a histogram resolves: 1e-30. Smaller positive errors count
/// in the lowest bin; exact zeros are counted apart.
pub const HIST_MIN_EXP: i32 = -30;
/// The largest: 1e10 (larger errors count in the top bin; the maximum is kept exactly).
pub const HIST_MAX_EXP: i32 = 10;

/// A mergeable distribution of non-negative errors: exact zeros, a log-scale
/// histogram, and the exact maximum.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Dist {
    /// Number of samples.
    pub n: u64,
    /// Samples exactly 0.
    pub zeros: u64,
    /// Largest sample; an infinite one (an error beyond f64's range, such as
    /// a point error over a subnormal scale) is written `"Infinity"`, since
    /// JSON has no number for it (a `null` from an earlier report reads as
    /// infinity too).
    #[serde(with = "max_json")]
    pub max: f64,
    /// Counts per bin, sparse: `(bin, count)` with bin `k` covering
    /// `[10^(k/B), 10^((k+1)/B))`, `B` = [`BINS_PER_DECADE`], sorted by bin.
    pub bins: Vec<(i32, u64)>,
}

/// [`Dist::max`] in JSON: a number, or `"Infinity"` for +∞.
mod max_json {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        if x.is_finite() { s.serialize_f64(*x) } else { s.serialize_str("Infinity") }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Max {
            Number(f64),
            Text(String),
            Null(()),
        }
        match Max::deserialize(d)? {
            Max::Number(x) => Ok(x),
            Max::Text(t) if t == "Infinity" => Ok(f64::INFINITY),
            Max::Text(t) => Err(serde::de::Error::custom(format!("`{t}`: expected a number or \"Infinity\""))),
            Max::Null(()) => Ok(f64::INFINITY),
        }
    }
}

impl Dist {
    /// Adds one sample (negative or NaN samples are taken as their absolute value
    /// or as infinity, so nothing is lost silently).
    pub fn add(&mut self, x: f64) {
        let x = if x.is_nan() { f64::INFINITY } else { x.abs() };
        self.n += 1;
        if x > self.max {
            self.max = x;
        }
        if x == 0.0 {
            self.zeros += 1;
            return;
        }
        let k = (x.log10() * BINS_PER_DECADE as f64).floor();
        let k = k.clamp((HIST_MIN_EXP * BINS_PER_DECADE) as f64, (HIST_MAX_EXP * BINS_PER_DECADE) as f64) as i32;
        match self.bins.binary_search_by_key(&k, |b| b.0) {
            Ok(i) => self.bins[i].1 += 1,
            Err(i) => self.bins.insert(i, (k, 1)),
        }
    }

    /// Joins another distribution into this one.
    pub fn merge(&mut self, o: &Dist) {
        self.n += o.n;
        self.zeros += o.zeros;
        self.max = self.max.max(o.max);
        for &(k, c) in &o.bins {
            match self.bins.binary_search_by_key(&k, |b| b.0) {
                Ok(i) => self.bins[i].1 += c,
                Err(i) => self.bins.insert(i, (k, c)),
            }
        }
    }

    /// The `q`-quantile (0 ≤ q ≤ 1), read from the histogram as the upper edge
    /// of the bin that holds it (capped at the exact maximum); `None` when empty.
    pub fn quantile(&self, q: f64) -> Option<f64> {
        if self.n == 0 {
            return None;
        }
        let rank = ((q * self.n as f64).ceil() as u64).clamp(1, self.n);
        if rank <= self.zeros {
            return Some(0.0);
        }
        let mut seen = self.zeros;
        for &(k, c) in &self.bins {
            seen += c;
            if seen >= rank {
                let upper = 10f64.powf((k + 1) as f64 / BINS_PER_DECADE as f64);
                return Some(upper.min(self.max));
            }
        }
        Some(self.max)
    }

    /// Median.
    pub fn median(&self) -> Option<f64> {
        self.quantile(0.5)
    }

    /// 99th percentile.
    pub fn p99(&self) -> Option<f64> {
        self.quantile(0.99)
    }
}

/// The ulps at which [`Ulps::within`] counts answers: 1, 4 and 64 (one
/// rounding, a few roundings, and the fixed allowance a careful library
/// might document).
pub const ULPS_THRESHOLDS: [u64; 3] = [1, 4, 64];

/// A distribution of accuracies in ulps, with exact counts at the
/// thresholds (the histogram's bins are 5% wide; a share within 4 ulps
/// should not be read off them).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Ulps {
    /// The distribution (median, p99, maximum).
    pub dist: Dist,
    /// How many samples are at most each of [`ULPS_THRESHOLDS`].
    pub within: [u64; 3],
}

impl Ulps {
    /// Adds one answer's ulps.
    pub fn add(&mut self, u: f64) {
        self.dist.add(u);
        for (n, t) in self.within.iter_mut().zip(ULPS_THRESHOLDS) {
            *n += u64::from(u <= t as f64);
        }
    }

    /// Joins another distribution into this one.
    pub fn merge(&mut self, o: &Ulps) {
        self.dist.merge(&o.dist);
        for (a, b) in self.within.iter_mut().zip(o.within) {
            *a += b;
        }
    }

    /// The share of samples within each threshold, `None` when empty.
    pub fn shares(&self) -> Option<[f64; 3]> {
        (self.dist.n > 0).then(|| self.within.map(|k| k as f64 / self.dist.n as f64))
    }
}

/// Time per query of one engine on one query kind: the median over repetitions of
/// a tight loop over the same cases, with the spread of the repetitions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timing {
    /// Median over repetitions, nanoseconds per query.
    pub median_ns: f64,
    /// Fastest repetition.
    pub min_ns: f64,
    /// Slowest repetition.
    pub max_ns: f64,
    /// Repetitions.
    pub reps: u32,
    /// Queries per repetition.
    pub queries: u64,
}

/// One engine on one query kind.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EngineQueryStats {
    /// Engine name.
    pub engine: String,
    /// Query kind.
    pub query: Option<Query>,
    /// Cases run.
    pub cases: u64,
    /// Same classification, errors within tolerance.
    pub agree: u64,
    /// Beyond tolerance.
    pub disagree: u64,
    /// Classification differs inside the referee's tolerance band.
    pub borderline: u64,
    /// Explained by a documented divergence.
    pub known: u64,
    /// Not answered by the engine.
    pub unsupported: u64,
    /// Panicked or returned a non-finite number.
    pub failed: u64,
    /// Of the failures, answers holding NaN or an infinity where the exact
    /// answer is finite.
    #[serde(default)]
    pub non_finite: u64,
    /// Of `failed`, the engine's panics that were caught (each one line with
    /// its location in the verdict's reason; none printed). Absent in reports
    /// written before it was counted.
    #[serde(default)]
    pub panics: u64,
    /// Reported contact / hit / overlap where the referee has none (outside the band).
    pub false_positives: u64,
    /// Missed a contact / hit / overlap the referee has (outside the band).
    pub false_negatives: u64,
    /// Other classification differences (parallel, degenerate flags).
    pub flag_mismatches: u64,
    /// Point errors, absolute.
    pub point_abs: Dist,
    /// Point errors relative to the answer's scale (`judge::answer_scale`).
    pub point_rel: Dist,
    /// Depth (or bounding radius) errors, absolute.
    pub depth_abs: Dist,
    /// Depth (or radius) errors relative to the answer's scale.
    pub depth_rel: Dist,
    /// Normal angle errors, radians.
    pub normal_rad: Dist,
    /// How far the normals' lengths are from 1 (`|‖n‖ − 1|`). Absent in
    /// reports written before normals' lengths were judged.
    #[serde(default)]
    pub normal_length: Dist,
    /// Segment parameter errors.
    pub t: Dist,
    /// Barycentric coordinate errors.
    pub barycentric: Dist,
    /// The headline error per case: the largest of its relative errors (points,
    /// depths, radii relative to the scene; normals in radians; t and
    /// barycentrics as they are), and 1 for a misclassification outside the band
    /// or a failure. The accuracy–speed chart plots its p99.
    pub headline: Dist,
    /// Accuracy in ulps ([`crate::judge::Errors::ulps`]) of every answer
    /// judged (a misclassification by the referee's margin): its
    /// distribution and how many are within 1, 4 and 64 ulps. Absent in
    /// reports written before it was measured.
    #[serde(default)]
    pub ulps: Ulps,
    /// Time per query, if timed.
    pub timing: Option<Timing>,
    /// Nanoseconds per query from the criterion benchmark, weighted by this
    /// campaign's mix of shape pairs ([`crate::report::bench`]), when a
    /// benchmark file was read; the accuracy–speed chart prefers it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bench_ns: Option<f64>,
}

/// An engine's identity in the provenance.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EngineInfo {
    /// Its name.
    pub name: String,
    /// What it is and its version (`parry3d-f64 0.31.1`, `collide (this commit), f32`).
    pub version: String,
    /// A process engine's command, hello (with what it asked the provenance
    /// to echo), restarts, time limit and faults.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub process: Option<crate::protocol::client::ProcessInfo>,
}

/// Where and how a report was made.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// crashtest's version.
    pub crashtest: String,
    /// `git rev-parse HEAD` of the working tree (with `-dirty` when it has changes), if known.
    pub commit: Option<String>,
    /// `rustc --version` at build time.
    pub rustc: String,
    /// Build profile (`release`, `debug`).
    pub profile: String,
    /// Machine: OS, architecture, CPU model, cores.
    pub machine: String,
    /// The engines and their versions.
    pub engines: Vec<EngineInfo>,
    /// Engines the run would have judged but that are not installed: each
    /// name, and why (with how to install it).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub missing_engines: Vec<(String, String)>,
    /// Where the peer engines' list was read, and by which rule (or why
    /// there was none): `crashtest::peer_engines_file`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peers: Option<String>,
    /// The campaign's seed.
    pub seed: u64,
    /// The judging rule `--ulps N`: every fixed allowance was `N` of the
    /// engine's ulps of the field's magnitude. Absent for the tolerance
    /// table's default verdicts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ulps: Option<f64>,
    /// Random cases per query kind (before sharding).
    pub cases_per_query: u64,
    /// Full-range cases per query kind (before sharding), scored apart.
    #[serde(default)]
    pub full_range_per_query: u64,
    /// The one query kind run (`--only`), or absent for every kind.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub only: Option<Query>,
    /// Shards joined in this report: `(index, count)` of each.
    pub shards: Vec<(u32, u32)>,
    /// Fixture cases run.
    pub fixture_cases: u64,
    /// Random cases run (all query kinds).
    pub random_cases: u64,
    /// Wall time of the run, seconds (for merged reports, the sum over shards).
    pub wall_seconds: f64,
    /// Where the wall time went: each phase of the run (making the cases,
    /// asking the process engines, judging, shrinking the findings, timing,
    /// the extra sections) and its seconds, in run order (for merged reports,
    /// summed over shards by phase).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub phases: Vec<(String, f64)>,
    /// The referee's two-stage computations while the cases were judged: each
    /// stage's label, how often the floating-point stage settled it and how
    /// often the exact stage had to (for merged reports, summed).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub referee_stages: Vec<(String, u64, u64)>,
    /// When the run started, UTC, RFC 3339.
    pub started: String,
    /// Where the accuracy–speed charts' times come from: the criterion run
    /// read ([`crate::report::bench`]), or absent for the campaign's own
    /// timing loops.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_source: Option<String>,
}

/// The whole of `summary.json`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// The format of this file.
    pub format: String,
    /// Where and how it was made.
    pub provenance: Provenance,
    /// Per engine and query kind, in engine order then query order.
    pub stats: Vec<EngineQueryStats>,
    /// The full-range family's (`generate::full_range`), per query kind then
    /// engine, scored apart from `stats`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub full_range: Vec<EngineQueryStats>,
    /// Disagreements and failures found, all engines (`discrepancies.json` holds
    /// the first few of each engine and query kind in full).
    pub discrepancies: u64,
    /// Campaign throughput, cases per second, per engine (referee included) and
    /// for the whole run with and without the referee's share.
    pub throughput: Vec<(String, f64)>,
    /// `distance`'s cost per query against the hulls' vertex counts, per
    /// engine and the referee (`report::growth`); empty when the run was not
    /// timed or had no distance cases.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub growth: Vec<Growth>,
}

/// The hulls' vertex counts of `distance`'s cost growth
/// (`report::growth`): half decades from 4 to 10⁴.
pub const GROWTH_POINTS: [usize; 8] = [4, 10, 32, 100, 316, 1000, 3162, 10_000];

/// Orders of the points timed per count.
pub const GROWTH_CASES: u64 = 3;

/// One engine's cost per query by vertex count.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Growth {
    /// The engine (or the referee).
    pub engine: String,
    /// `(vertices, median ns per query)`, for the counts it answered.
    pub points: Vec<(u64, f64)>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_infinite_maximum_reads_back_from_json() {
        let mut d = Dist::default();
        d.add(1e-3);
        d.add(f64::INFINITY);
        let text = serde_json::to_string(&d).unwrap();
        assert!(text.contains("\"max\":\"Infinity\""), "{text}");
        let back: Dist = serde_json::from_str(&text).unwrap();
        assert_eq!(back, d);
        // A report written before: `null`.
        let old: Dist = serde_json::from_str(r#"{"n":1,"zeros":0,"max":null,"bins":[]}"#).unwrap();
        assert!(old.max.is_infinite());
        assert!(serde_json::from_str::<Dist>(r#"{"n":1,"zeros":0,"max":"big","bins":[]}"#).is_err());
    }
}
