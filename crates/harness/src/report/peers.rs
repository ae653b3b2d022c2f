//! The report's "peers' reported failures" section: every fixture case that
//! recreates a failure users reported against a peer engine (the cases under
//! `fixtures/peers/`, and any case named after a peer's issue), with each
//! engine's verdict against the referee and against the case's expectation.
//!
//! Decision: the section reads the campaign's own results for those cases —
//! nothing is run twice — so it shows exactly what the report's tables count.

use crate::check::CaseResult;
use crate::render::html::{escape, table_html};
use crate::render::markdown::{Table, table_md};
use crate::render::section::Section;
use serde::Serialize;
use std::fmt::Write;

/// One engine's result on one case, as the section shows it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// The engine.
    pub engine: String,
    /// Its verdict against the referee (`agree`, `DISAGREE`, …).
    pub verdict: String,
    /// Whether it met the case's expectation (`None` when it gave no answer).
    pub meets_expect: Option<bool>,
}

/// One case of the section.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// Its fixture file.
    pub file: String,
    /// Its name (which names its source).
    pub name: String,
    /// Its query kind.
    pub query: String,
    /// Every engine's result, in report order.
    pub engines: Vec<Cell>,
}

/// Whether a case recreates a failure reported against a peer engine: it lives
/// under a `peers/` folder, or its name cites an issue (`… issue 429: …`).
pub fn is_peer_case(r: &CaseResult) -> bool {
    r.file.replace('\\', "/").contains("/peers/") || r.name.contains("issue ")
}

/// The rows of the section, in the campaign's case order.
pub fn rows(results: &[CaseResult]) -> Vec<Row> {
    results
        .iter()
        .filter(|r| is_peer_case(r))
        .map(|r| Row {
            file: r.file.clone(),
            name: r.name.clone(),
            query: r.query.to_string(),
            engines: r
                .engines
                .iter()
                .map(|e| Cell {
                    engine: e.engine.clone(),
                    verdict: e.verdict.label().to_string(),
                    meets_expect: e.expect_mismatches.as_ref().map(|m| m.is_empty()),
                })
                .collect(),
        })
        .collect()
}

fn cell_text(c: &Cell) -> String {
    match c.meets_expect {
        Some(true) => format!("{} · ✓", c.verdict),
        Some(false) => format!("{} · ✗", c.verdict),
        None => c.verdict.clone(),
    }
}

/// The section, or `None` when the campaign ran no such case.
pub fn section(results: &[CaseResult]) -> Option<Section> {
    let rows = rows(results);
    let first = rows.first()?;
    let mut header = vec!["case".to_string(), "query".to_string()];
    header.extend(first.engines.iter().map(|c| c.engine.clone()));
    let numeric = vec![false; header.len()];
    let table = Table {
        header,
        numeric,
        rows: rows
            .iter()
            .map(|r| {
                let file = r.file.rsplit(['/', '\\']).next().unwrap_or(&r.file);
                let mut row = vec![format!("{file} › {}", r.name), r.query.clone()];
                row.extend(r.engines.iter().map(cell_text));
                row
            })
            .collect(),
    };
    let totals: Vec<String> = first
        .engines
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let ok = rows.iter().filter(|r| r.engines.get(i).is_some_and(|e| e.meets_expect == Some(true))).count();
            format!("{} {ok}/{}", c.engine, rows.len())
        })
        .collect();
    let intro = format!(
        "Cases recreating failures users reported against peer engines (parry, rapier, and cases transcribed \
         from Jolt, FCL and OpenGeoSys test suites), in crashtest's shapes and queries; each case's name and \
         `source` cite where it comes from. Each cell: the engine's verdict against the referee, then ✓ or ✗ for \
         the case's hand-derived expectation (its tolerance, 1e-9 absolute unless the case says otherwise, is          beyond most f32 answers: the f32 engines' verdicts against the referee use their own precision's          tolerance). Expectations met: {}.",
        totals.join(", ")
    );
    let mut html = String::new();
    let _ = writeln!(html, "<p>{}</p>", escape(&intro));
    html.push_str(&table_html(&table));
    let markdown = format!("## Peers' reported failures\n\n{intro}\n\n{}", table_md(&table));
    Some(Section {
        id: "peers".into(),
        title: "Peers' reported failures".into(),
        html,
        markdown,
        charts: Vec::new(),
        data: serde_json::to_value(&rows).unwrap_or_else(|e| serde_json::Value::String(format!("unserializable: {e}"))),
    })
}
