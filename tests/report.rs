//! The report: determinism, reproducible discrepancies, atomic writes.

use harness::check::check_case;
use harness::engines::EngineSet;
use harness::engines::judged;
use harness::load::{Loaded, LoadedCase, load_str_into};
use harness::report::campaign::{Config, run};
use harness::summary::Summary;
use std::path::{Path, PathBuf};

/// A campaign small enough for a test: 150 random cases per query kind, no timing.
fn small(seed: u64) -> Config {
    Config {
        seed,
        cases_per_query: 150,
        full_range_per_query: 30,
        timing: false,
        progress: false,
        sections: false,
        ..Config::default()
    }
}

/// The summary with its timing and provenance fields blanked: what must not
/// depend on the run.
fn comparable(mut s: Summary) -> Summary {
    s.provenance = Default::default();
    s.throughput.clear();
    s.growth.clear();
    for st in &mut s.stats {
        st.timing = None;
    }
    s
}

#[test]
fn the_same_seed_gives_the_same_summary() {
    let a = run(&small(7), Default::default());
    let b = run(&small(7), Default::default());
    let (ja, jb) = (
        serde_json::to_string(&comparable(a.summary)).unwrap(),
        serde_json::to_string(&comparable(b.summary)).unwrap(),
    );
    assert!(ja == jb, "two runs with seed 7 differ");
    let c = run(&small(8), Default::default());
    assert!(serde_json::to_string(&comparable(c.summary)).unwrap() != ja, "seed 8 gave seed 7's summary");
}

#[test]
fn every_discrepancy_reproduces_from_its_fixture() {
    let outcome = run(&small(11), Default::default());
    assert!(!outcome.discrepancies.is_empty(), "a campaign with lecture and f32 engines finds some discrepancies");
    let set = EngineSet::of(judged());
    for d in &outcome.discrepancies {
        let text = serde_json::to_string(&d.fixture).unwrap();
        let mut loaded = Loaded::default();
        load_str_into(Path::new("discrepancy.json"), &text, &mut loaded);
        assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
        let lc: &LoadedCase = &loaded.cases[0];
        let again = check_case(lc, &set);
        let r = again.engines.iter().find(|r| r.engine == d.engine).expect("same engines");
        assert_eq!(r.verdict.label(), d.verdict.label(), "{} on {}: {:?}", d.engine, d.origin, r.verdict);
    }
}

#[test]
fn the_chunk_size_changes_nothing() {
    // A run streams its cases chunk by chunk; chunks of 7 cases (several per
    // query kind, and a chunk boundary inside each) give the summary, the
    // discrepancies and the findings of one chunk per kind.
    let whole = run(&small(3), Default::default());
    let chunked = run(&Config { chunk: 7, ..small(3) }, Default::default());
    let json = |o: &harness::report::campaign::Outcome| {
        (
            serde_json::to_string(&comparable(o.summary.clone())).unwrap(),
            serde_json::to_string(&o.discrepancies).unwrap(),
            o.findings.findings.iter().map(|f| (f.name.clone(), f.count)).collect::<Vec<_>>(),
        )
    };
    assert!(!whole.discrepancies.is_empty(), "the small campaign has discrepancies to compare");
    assert!(json(&whole) == json(&chunked), "chunks of 7 changed the outcome");
}

#[test]
fn shards_merge_into_the_whole_campaign() {
    use harness::report::write::{ReadReport, merge};
    let shard = |i| {
        let o = run(&Config { shard: Some((i, 2)), ..small(5) }, Default::default());
        ReadReport { dir: PathBuf::new(), summary: o.summary, discrepancies: Vec::new(), sections: Vec::new() }
    };
    let (merged, _) = merge(&[shard(0), shard(1)]).expect("same campaign");
    let whole = run(&small(5), Default::default()).summary;
    assert_eq!(merged.provenance.shards, vec![(0, 2), (1, 2)]);
    assert_eq!(merged.provenance.random_cases, whole.provenance.random_cases);
    assert!(
        serde_json::to_string(&comparable(merged).stats).unwrap()
            == serde_json::to_string(&comparable(whole).stats).unwrap(),
        "the merged shards' counts and histograms differ from the whole run's"
    );
}

#[test]
fn merged_shards_keep_the_sections_of_the_shard_that_ran_them() {
    use harness::render::section::{Section, SectionChart};
    use harness::report::write::{ReadReport, merge_sections};
    let section = |id: &str, body: &str| Section {
        id: id.into(),
        title: id.into(),
        html: body.into(),
        markdown: format!("## {id}\n"),
        charts: vec![SectionChart { title: id.into(), file: format!("{id}.svg"), svg: "<svg></svg>".into() }],
        data: serde_json::json!({ "body": body }),
    };
    let shard = |sections| ReadReport {
        dir: PathBuf::new(),
        summary: run(&Config { cases_per_query: 4, ..small(1) }, Default::default()).summary,
        discrepancies: Vec::new(),
        sections,
    };
    let merged = merge_sections(&[
        shard(Vec::new()),
        shard(vec![section("dynamics", "first"), section("stability", "s")]),
        shard(vec![section("dynamics", "second")]),
    ]);
    assert_eq!(merged, vec![section("dynamics", "first"), section("stability", "s")]);
}

#[test]
fn the_peer_section_shows_every_engine_on_every_peer_case_and_collide_meets_them_all() {
    let loaded = harness::load::load_paths(&[PathBuf::from("fixtures")]);
    assert!(loaded.errors.is_empty(), "{:?}", loaded.errors);
    let result = harness::check::check(&loaded.cases, &loaded.errors, &Default::default());
    let rows = harness::report::peers::rows(&result.cases);
    for issue in ["issue 17:", "issue 76", "issue 123", "issue 171:", "issue 315", "issue 429", "issue 984"] {
        assert!(rows.iter().any(|r| r.name.contains(issue)), "no peer regression case for {issue}");
    }
    let engines: Vec<String> = judged().iter().map(|e| e.name.clone()).collect();
    for r in &rows {
        let names: Vec<String> = r.engines.iter().map(|c| c.engine.clone()).collect();
        assert_eq!(names, engines, "{}: every engine has a cell", r.name);
        let robust = &r.engines[0];
        assert_eq!(robust.meets_expect, Some(true), "collide/robust fails {} › {}", r.file, r.name);
    }
    let section = harness::report::peers::section(&result.cases).expect("peer cases exist");
    assert_eq!(section.html.matches("<tr>").count(), rows.len() + 1, "one table row per case, plus the header");
}

/// A timed run with distance cases measures every built-in engine's distance
/// cost at each vertex count of the ladder, and the referee's, and draws it.
#[test]
fn a_timed_distance_run_measures_and_charts_the_cost_growth() {
    use harness::case::Query;
    use harness::report::growth::GROWTH_POINTS;
    let config = Config {
        only: Some(Query::Distance),
        cases_per_query: 10,
        full_range_per_query: 0,
        timing: true,
        progress: false,
        sections: false,
        engines: EngineSet::of(judged()),
        ..Config::default()
    };
    let out = run(&config, Default::default());
    let growth = &out.summary.growth;
    // Every built-in engine answers distance; the referee is last.
    let mut want: Vec<String> = judged().iter().map(|e| e.name.clone()).collect();
    want.push("referee".into());
    let names: Vec<&str> = growth.iter().map(|g| g.engine.as_str()).collect();
    assert_eq!(names, want.iter().map(String::as_str).collect::<Vec<_>>());
    for g in growth {
        let counts: Vec<u64> = g.points.iter().map(|p| p.0).collect();
        assert_eq!(counts, GROWTH_POINTS.iter().map(|&n| n as u64).collect::<Vec<_>>(), "{}", g.engine);
        assert!(g.points.iter().all(|p| p.1 > 0.0 && p.1.is_finite()), "{}: {:?}", g.engine, g.points);
    }
    let charts = harness::render::charts::all(&out.summary);
    let chart = charts.iter().find(|c| c.file == "distance-cost-growth.svg").expect("the growth chart");
    assert!(want.iter().all(|name| chart.svg.contains(name.as_str())), "every engine in the legend");
    let md = harness::render::markdown::summary_md(&out.summary);
    assert!(md.contains("## distance: cost by vertex count"), "{md}");
}
