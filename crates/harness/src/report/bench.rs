//! Speed figures from the criterion benchmark (`cargo bench --bench queries`)
//! for the report's accuracy–speed charts.
//!
//! The benchmark writes `crashtest-bench.json` beside criterion's own output
//! (`target/criterion/`): nanoseconds per query for each benchmark group (one
//! shape pair: `sphere_sphere`, `segment_triangle`, …) and engine. A report run
//! after it reads the file and, per query kind and engine, weights the groups'
//! figures by the campaign's own mix of shape pairs — so a `contact` point on
//! the chart is the criterion time of the contact cases this campaign ran, in
//! the proportions it ran them. The campaign's timing loops stay in the tables;
//! the charts prefer the criterion figures and say so.
//!
//! Decision: the benchmark's per-pair figures are combined here, not in the
//! benchmark, because only the campaign knows its mix.

use crate::case::{Query, Shape};
use crate::load::LoadedCase;
use crate::summary::EngineQueryStats;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The file's format tag.
pub const FORMAT: &str = "crashtest-bench/1";

/// The benchmark's figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BenchFile {
    /// [`FORMAT`].
    pub format: String,
    /// When the benchmark run ended, UTC, RFC 3339.
    pub written: String,
    /// The machine it ran on.
    pub machine: String,
    /// One figure per benchmark group and engine.
    pub rows: Vec<BenchRow>,
}

/// One benchmark figure.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BenchRow {
    /// The shape pair (criterion's group): `sphere_sphere`, `sphere_plane`,
    /// `sphere_triangle`, `segment_plane`, `segment_triangle`, `barycentric`,
    /// `overlap`, `bounding_sphere`.
    pub group: String,
    /// The engine, by its report name (`collide/robust`, `parry3d-f64`, …).
    pub engine: String,
    /// Nanoseconds per query (criterion's estimate).
    pub ns: f64,
}

/// Reads the benchmark's file: `Ok(None)` when there is none, an error naming
/// the file when it cannot be read or parsed or has another format.
pub fn load(path: &Path) -> Result<Option<BenchFile>, String> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(format!("{}: cannot read: {e}", path.display())),
    };
    let file: BenchFile = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    if file.format != FORMAT {
        return Err(format!("{}: format `{}`, expected `{FORMAT}`", path.display(), file.format));
    }
    Ok(Some(file))
}

/// The benchmark group a case's shape pair falls in (`None`: no benchmark
/// times it, e.g. meshes, toi, response).
pub fn group(lc: &LoadedCase) -> Option<&'static str> {
    let kinds = |s: &Shape| s.kind();
    let a = kinds(&lc.case.a);
    let b = lc.case.b.as_ref().map(kinds);
    let has = |k: &str| a == k || b == Some(k);
    Some(match lc.case.query {
        Query::Contact if has("plane") => "sphere_plane",
        Query::Contact if has("triangle") => "sphere_triangle",
        Query::Contact => "sphere_sphere",
        Query::Intersect if has("plane") => "segment_plane",
        Query::Intersect if has("triangle") => "segment_triangle",
        Query::Barycentric => "barycentric",
        Query::Overlap => "overlap",
        Query::Bounds if a == "points" => "bounding_sphere",
        _ => return None,
    })
}

/// Fills `bench_ns` of every statistic the benchmark covers: per query kind,
/// the groups' figures weighted by how many of `cases` (the campaign's timed
/// cases) fall in each group. An engine missing a figure for a group the
/// campaign ran gets none for that query kind.
pub fn apply(stats: &mut [EngineQueryStats], cases: &[LoadedCase], bench: &BenchFile) {
    let mut mix = Mix::default();
    for lc in cases {
        mix.add(lc);
    }
    apply_mix(stats, &mix, bench);
}

/// How many of a campaign's generated cases fall in each benchmark group, per
/// query kind: folded case by case, so a streaming run needs none of its cases
/// kept.
#[derive(Clone, Debug, Default)]
pub struct Mix(BTreeMap<Query, BTreeMap<&'static str, u64>>);

impl Mix {
    /// Counts `lc` when it is a generated case of some group.
    pub fn add(&mut self, lc: &LoadedCase) {
        if lc.case.source.starts_with("generated")
            && let Some(g) = group(lc)
        {
            *self.0.entry(lc.case.query).or_default().entry(g).or_default() += 1;
        }
    }
}

/// [`apply`] with the mix already counted.
pub fn apply_mix(stats: &mut [EngineQueryStats], mix: &Mix, bench: &BenchFile) {
    let mix = &mix.0;
    for s in stats.iter_mut() {
        let Some(groups) = s.query.and_then(|q| mix.get(&q)) else { continue };
        let total: u64 = groups.values().sum();
        let mut ns = 0.0;
        let mut complete = total > 0;
        for (g, n) in groups {
            match bench.rows.iter().find(|r| r.group == *g && r.engine == s.engine && r.ns.is_finite() && r.ns > 0.0) {
                Some(r) => ns += r.ns * *n as f64 / total as f64,
                None => complete = false,
            }
        }
        s.bench_ns = complete.then_some(ns);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::{Loaded, load_str_into};

    fn case(name: &str, query: &str, a: &str, b: &str) -> String {
        format!(r#"{{"name":"{name}","source":"generated test","query":"{query}","a":{a},"b":{b}}}"#)
    }

    #[test]
    fn figures_are_weighted_by_the_campaigns_mix_of_pairs() {
        let sphere = r#"{"sphere":{"center":[0,0,0],"radius":1}}"#;
        let plane = r#"{"plane":{"normal":[0,0,1],"offset":0}}"#;
        let text = format!(
            r#"{{"schema":"crashtest-fixture/1","cases":[{},{},{}]}}"#,
            case("c0", "contact", sphere, sphere),
            case("c1", "contact", sphere, plane),
            case("c2", "contact", plane, sphere)
        );
        let mut loaded = Loaded::default();
        load_str_into(Path::new("t.json"), &text, &mut loaded);
        assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
        let row = |group: &str, engine: &str, ns| BenchRow { group: group.into(), engine: engine.into(), ns };
        let bench = BenchFile {
            format: FORMAT.into(),
            written: String::new(),
            machine: String::new(),
            rows: vec![row("sphere_sphere", "a", 3.0), row("sphere_plane", "a", 6.0), row("sphere_sphere", "b", 1.0)],
        };
        let stat = |engine: &str| EngineQueryStats {
            engine: engine.into(),
            query: Some(Query::Contact),
            ..Default::default()
        };
        let mut stats = vec![stat("a"), stat("b")];
        apply(&mut stats, &loaded.cases, &bench);
        // One sphere–sphere and two sphere–plane cases: (3 + 2·6) / 3 = 5.
        const EXACT_IN_F64: f64 = 1e-12; // 15 / 3 in binary: a few ulps at most
        assert!((stats[0].bench_ns.expect("a has both groups") - 5.0).abs() < EXACT_IN_F64);
        assert_eq!(stats[1].bench_ns, None, "b lacks sphere_plane: no figure rather than a partial one");
    }

    #[test]
    fn a_missing_file_is_none_and_a_broken_one_names_itself() {
        let dir = std::env::temp_dir().join(format!("crashtest-bench-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        assert_eq!(load(&dir.join("absent.json")), Ok(None));
        let broken = dir.join("broken.json");
        std::fs::write(&broken, "{").unwrap();
        let err = load(&broken).unwrap_err();
        assert!(err.contains("broken.json"), "{err}");
        std::fs::write(&broken, r#"{"format":"other/1","written":"","machine":"","rows":[]}"#).unwrap();
        assert!(load(&broken).unwrap_err().contains("other/1"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
