//! How sweeps are shown: the breaking-point table, one log–log chart per sweep
//! (and per query for `crashtest sweep`), the report's stability section, and
//! the files `crashtest sweep` writes.
//!
//! Every function here is pure: the same results give byte-identical text.

use super::catalog::{BREAK_REL, SWEEPS, Settings};
use super::measure::{Series, SweepResult};
use crate::render::charts::zero_floor;
use crate::render::html::{escape, table_html};
use crate::render::markdown::{Table, escape_md, table_md};
use crate::render::plot::{Axis, Line, line_chart};
use crate::render::section::{Section, SectionChart};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// The stability section's id: its anchor and the stem of its data file.
pub const SECTION_ID: &str = "stability";

/// Pixels between neighbouring engines' lines, so that equal values (every
/// exact method at the floor) stay visible side by side.
const LINE_OFFSET_PX: f64 = 1.5;

/// The style (colour and dash) of the threshold line: past the six engines'.
const THRESHOLD_STYLE: usize = 7;

/// One engine's breaking points as a table cell: `none`, or the first
/// breaking value and why (`2.5e-9 (misclass)`); a sweep walked both ways
/// gives both (`↓ none · ↑ 1e6 (error)`). An engine that answers none of the
/// query's cases is `unsupported`; one whose every answer is a documented
/// divergence, `known divergence`.
fn cell(s: &Series) -> String {
    if s.answered() == 0 {
        return "unsupported".into();
    }
    let failures: u32 = s.points.iter().map(|p| p.failures()).sum();
    if s.measured() == 0 && failures == 0 {
        return "known divergence".into();
    }
    let one = |w: &super::measure::Walk| match &w.breaks_at {
        None => "none".to_string(),
        Some(b) => format!("{} ({})", b.label, b.why.word()),
    };
    match s.walks.as_slice() {
        [w] => one(w),
        [down, up] => format!("↓ {} · ↑ {}", one(down), one(up)),
        ws => ws.iter().map(one).collect::<Vec<_>>().join(" · "),
    }
}

/// The breaking-point table: one row per sweep and query, one column per
/// engine.
pub fn breaking_table(results: &[SweepResult]) -> Table {
    let engines: Vec<String> = results
        .first()
        .and_then(|r| r.probes.first())
        .map(|p| p.engines.iter().map(|e| e.engine.clone()).collect())
        .unwrap_or_default();
    let mut header = vec!["sweep".to_string(), "query".to_string()];
    header.extend(engines.iter().cloned());
    let mut rows = Vec::new();
    for r in results {
        for p in &r.probes {
            let mut row = vec![r.name.clone(), p.name.clone()];
            row.extend(p.engines.iter().map(cell));
            rows.push(row);
        }
    }
    Table { numeric: vec![false; header.len()], header, rows }
}

/// How to read the table, one sentence each.
fn legend(settings: &Settings) -> Vec<String> {
    vec![
        format!(
            "Each cell is where the engine first breaks, walking from the benign end of the sweep: the first \
             parameter value at which its largest error over {} poses exceeds {BREAK_REL:.0e} of the scene's \
             scale (radians for normals; segment parameters and barycentrics plain), or at which it fails on \
             any pose: a misclassification (hit or miss, contact or none, a parallel or degenerate flag the \
             exact referee does not share), a NaN, or a caught panic. “none”: it never breaks in range.",
            settings.poses
        ),
        "↓ and ↑: a sweep degenerate at both ends (size-ratio) is walked from 1 toward each.".into(),
        "Errors and classifications are judged exactly as in the campaign (against the referee, known \
         divergences of an engine's documented conventions set apart). An f32 engine is judged on the f64 \
         scene: rounding its input is part of what it is judged on."
            .into(),
        format!(
            "Seed {}; exact poses permute the axes without rounding (the parameter holds exactly, even at 1e-17 \
             and exactly on), rotated poses turn and move the scene (every coordinate rounds once).",
            settings.seed
        ),
    ]
}

/// The x at which an exact point is drawn: a decade below the smallest grid
/// value.
fn exact_x(r: &SweepResult) -> f64 {
    let smallest = r.points.iter().filter(|p| !p.exact).map(|p| p.value).fold(f64::INFINITY, f64::min);
    10f64.powi(smallest.log10().round() as i32 - 1)
}

fn x_of(r: &SweepResult, i: usize) -> f64 {
    if r.points[i].exact { exact_x(r) } else { r.points[i].value }
}

/// One chart of a sweep: per engine, the largest error over the poses at each
/// point (over all its queries, or only `probe`), log–log; a point where the
/// engine fails on some pose is also marked ×. Exact zeros are drawn at
/// [`zero_floor`]; an exact point a decade below the grid; the threshold
/// [`BREAK_REL`] as its own line.
pub fn chart(r: &SweepResult, probe: Option<usize>) -> SectionChart {
    let probes: Vec<usize> = match probe {
        Some(p) => vec![p],
        None => (0..r.probes.len()).collect(),
    };
    let n_engines = r.probes.first().map_or(0, |p| p.engines.len());
    // Each engine's line, zeros still zero (floored below, once the floor is known).
    let mut series: Vec<Line> = (0..n_engines)
        .map(|ei| {
            let mut line = Line {
                name: r.probes[0].engines[ei].engine.clone(),
                style: ei,
                points: Vec::new(),
                failures: Vec::new(),
            };
            for i in 0..r.points.len() {
                let at = probes.iter().map(|&p| &r.probes[p].engines[ei].points[i]);
                if let Some(m) = at.clone().filter_map(|s| s.max).reduce(f64::max) {
                    line.points.push((x_of(r, i), m));
                }
                if at.map(|s| s.failures()).sum::<u32>() > 0 {
                    line.failures.push(x_of(r, i));
                }
            }
            line
        })
        .collect();
    let positives: Vec<f64> = series.iter().flat_map(|l| l.points.iter().map(|q| q.1)).filter(|y| *y > 0.0).collect();
    let floor = zero_floor(&positives);
    for p in series.iter_mut().flat_map(|l| l.points.iter_mut()) {
        if p.1 <= 0.0 {
            p.1 = floor;
        }
    }
    let xs: Vec<f64> = (0..r.points.len()).map(|i| x_of(r, i)).collect();
    let xa = Axis::log_covering(xs.iter().copied());
    let (x0, x1) = match xa {
        Axis::Log { lo, hi } => (10f64.powi(lo), 10f64.powi(hi)),
        Axis::Linear { min, max, .. } => (min, max),
    };
    series.push(Line {
        name: format!("{BREAK_REL:.0e}: breaking threshold"),
        style: THRESHOLD_STYLE,
        points: vec![(x0, BREAK_REL), (x1, BREAK_REL)],
        failures: Vec::new(),
    });
    let ya = Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.1)));
    let queries = match probe {
        Some(p) => r.probes[p].name.clone(),
        None => r.probes.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", "),
    };
    let inner = match probe {
        Some(p) => format!("{}: {}", r.name, r.probes[p].name),
        None => format!("{}: {}", r.name, r.title),
    };
    let svg = line_chart(
        &inner,
        &r.parameter,
        "largest error over the poses (÷ scene scale)",
        xa,
        ya,
        &series,
        LINE_OFFSET_PX,
    );
    let mut caption = format!(
        "{} — largest error over {} poses{} against {}, per engine; × marks a point where the engine \
         fails on some pose (misclassification, NaN, panic); an exact zero is drawn at {:.0e}",
        inner,
        r.settings.poses,
        if probe.is_none() && r.probes.len() > 1 { format!(", worst of {queries},") } else { String::new() },
        r.parameter,
        floor
    );
    if let Some(p) = r.points.iter().find(|p| p.exact) {
        let _ = write!(caption, "; {} is drawn at {:.0e}", p.label, exact_x(r));
    }
    let file = match probe {
        Some(p) => format!("{}-{}.svg", r.name, slug(&r.probes[p].name)),
        None => format!("{}.svg", r.name),
    };
    SectionChart { title: caption, file, svg }
}

/// A file-name-safe form of a query's name (`toi sphere–plane` →
/// `toi-sphere-plane`).
fn slug(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

/// Rounds every float of a JSON tree to three significant digits: errors are
/// meaningful to a few percent, and the data file shrinks by half.
fn round_floats(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Number(n) if n.is_f64() => {
            if let Some(x) = n.as_f64() {
                let short: f64 = format!("{x:.2e}").parse().unwrap_or(x);
                if let Some(m) = serde_json::Number::from_f64(short) {
                    *n = m;
                }
            }
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(round_floats),
        serde_json::Value::Object(o) => o.values_mut().for_each(round_floats),
        _ => {}
    }
}

fn data(results: &[SweepResult], settings: &Settings) -> serde_json::Value {
    let mut v = serde_json::json!({
        "format": "crashtest-sweeps/1",
        "break_rel": BREAK_REL,
        "settings": settings,
        "sweeps": results,
    });
    round_floats(&mut v);
    v
}

/// The stability section from results already run: it opens with the
/// breaking-point table, then how to read it and how each sweep is built; one
/// chart per sweep; `data` holds every per-point result.
pub fn section_from(results: &[SweepResult], settings: &Settings) -> Section {
    let title = "Stability: where methods break".to_string();
    let table = breaking_table(results);
    let charts: Vec<SectionChart> = results
        .iter()
        .map(|r| {
            let c = chart(r, None);
            SectionChart { file: format!("{SECTION_ID}-{}", c.file), ..c }
        })
        .collect();

    let mut html = table_html(&table);
    html.push_str("<ul class=\"notes\">\n");
    for l in legend(settings) {
        let _ = writeln!(html, "<li>{}</li>", escape(&l));
    }
    html.push_str("</ul>\n<h3>The sweeps</h3>\n<ul class=\"notes\">\n");
    for r in results {
        let about = SWEEPS.iter().find(|s| s.name == r.name).map_or("", |s| s.about);
        let _ = writeln!(
            html,
            "<li><b>{}</b> — {}: {}. {}</li>",
            escape(&r.name),
            escape(&r.title),
            escape(&r.parameter),
            escape(about)
        );
    }
    html.push_str("</ul>\n");

    let mut md = format!("## {title}\n\n");
    md.push_str(&table_md(&table));
    md.push('\n');
    for l in legend(settings) {
        let _ = writeln!(md, "- {}", escape_md(&l));
    }
    md.push_str("\n### The sweeps\n\n");
    for r in results {
        let about = SWEEPS.iter().find(|s| s.name == r.name).map_or("", |s| s.about);
        let _ = writeln!(
            md,
            "- **{}** — {}: {}. {}",
            escape_md(&r.name),
            escape_md(&r.title),
            escape_md(&r.parameter),
            escape_md(about)
        );
    }
    md.push('\n');
    for c in &charts {
        let _ = writeln!(md, "![{}](charts/{})\n", escape_md(&c.title), c.file);
    }
    Section { id: SECTION_ID.into(), title, html, markdown: md, charts, data: data(results, settings) }
}

/// The files `crashtest sweep` writes for one sweep: `<name>.json` (every
/// per-point result), `<name>.svg` (the chart over all its queries), and for a
/// sweep of several queries `<name>-<query>.svg` for each.
pub fn files(r: &SweepResult) -> Vec<(PathBuf, String)> {
    let mut text = serde_json::to_string_pretty(&data(std::slice::from_ref(r), &r.settings))
        .unwrap_or_else(|e| format!("\"unserializable: {e}\""));
    text.push('\n');
    let mut out = vec![(PathBuf::from(format!("{}.json", r.name)), text)];
    let main = chart(r, None);
    out.push((PathBuf::from(main.file), main.svg));
    if r.probes.len() > 1 {
        for p in 0..r.probes.len() {
            let c = chart(r, Some(p));
            out.push((PathBuf::from(c.file), c.svg));
        }
    }
    out
}

/// Writes [`files`] into `dir` (created if needed); the paths written.
pub fn write(r: &SweepResult, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    for (name, contents) in files(r) {
        let path = dir.join(name);
        std::fs::write(&path, contents)?;
        written.push(path);
    }
    Ok(written)
}

/// The breaking-point table as aligned plain text, for a terminal.
pub fn table_text(results: &[SweepResult]) -> String {
    let t = breaking_table(results);
    let mut width: Vec<usize> = t.header.iter().map(|h| h.chars().count()).collect();
    for row in &t.rows {
        for (w, c) in width.iter_mut().zip(row) {
            *w = (*w).max(c.chars().count());
        }
    }
    let line = |cells: &[String]| {
        let padded: Vec<String> =
            cells.iter().zip(&width).map(|(c, w)| format!("{c}{}", " ".repeat(w - c.chars().count()))).collect();
        padded.join("  ").trim_end().to_string() + "\n"
    };
    let mut s = line(&t.header);
    for row in &t.rows {
        s.push_str(&line(row));
    }
    s
}
