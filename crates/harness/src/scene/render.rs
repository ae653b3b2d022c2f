//! The scene section's rendering: its Markdown, HTML, tables and charts, from
//! the measured data alone.

use super::data::{CLOUD_FAMILIES, CLOUD_SIZES, METHODS, SceneNeeds, SceneReport, TightnessStats};
use crate::render::html::{escape, table_html};
use crate::render::markdown::{Table, table_md};
use crate::render::plot::{Axis, Line, PALETTE, line_chart, px};
use crate::render::section::{Section, SectionChart};
use crate::summary::Timing;
use std::fmt::Write;

/// A rate as a percentage with one decimal.
fn percent(x: Option<f64>) -> String {
    x.map_or("—".into(), |r| format!("{:.1}%", 100.0 * r))
}

/// A non-negative quantity with about three significant digits, plain
/// (`0.512`, `4.75`, `18.3`, `187`).
fn num(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else if x >= 1.0 {
        format!("{x:.2}")
    } else {
        format!("{x:.3}")
    }
}

/// Microseconds per query, median (fastest–slowest).
fn micros(t: Option<&Timing>) -> String {
    t.map_or("—".into(), |t| format!("{} ({}–{})", num(t.median_ns / 1e3), num(t.min_ns / 1e3), num(t.max_ns / 1e3)))
}

/// A scene's table: one row per level, the cheapest lossless marked.
pub fn scene_table(s: &SceneNeeds) -> Table {
    let header = [
        ("level", false),
        ("cheap test passes", true),
        ("false-positive rate", true),
        ("contacts lost", true),
        ("exact tests / query", true),
        ("time / query (µs)", true),
        ("needed?", false),
    ];
    Table {
        header: header.iter().map(|h| h.0.to_string()).collect(),
        numeric: header.iter().map(|h| h.1).collect(),
        rows: s
            .levels
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let mark = if s.cheapest_lossless == Some(i) {
                    format!("◀ cheapest lossless (by {})", s.cheapest_by)
                } else if l.lost > 0 {
                    "loses contacts".into()
                } else {
                    String::new()
                };
                vec![
                    l.level.label().into(),
                    format!("{} of {}", l.passed, s.queries),
                    percent(l.false_positive_rate),
                    l.lost.to_string(),
                    num(l.exact_tests_per_query),
                    micros(l.timing.as_ref()),
                    mark,
                ]
            })
            .collect(),
    }
}

/// The tightness table: per set of clouds, each method's mean (max).
pub fn tightness_table(r: &SceneReport) -> Table {
    let mut header = vec![("clouds".to_string(), false)];
    header.extend(METHODS.iter().map(|m| (format!("{m}: mean (max)"), true)));
    let cell = |t: &TightnessStats| format!("{:.4} ({:.4})", t.mean, t.max);
    let mut rows = Vec::new();
    if !r.bunny_tightness.is_empty() {
        let n = r.bunny_tightness[0].values.len();
        let mut row = vec![format!("the bunny, {n} random rotations")];
        row.extend(r.bunny_tightness.iter().map(cell));
        rows.push(row);
    }
    for c in &r.cloud_tightness {
        let n = c.methods.first().map_or(0, |m| m.values.len());
        let mut row = vec![format!("{}, {} points ({n} clouds)", c.family, c.points)];
        row.extend(c.methods.iter().map(cell));
        rows.push(row);
    }
    Table { header: header.iter().map(|h| h.0.clone()).collect(), numeric: header.iter().map(|h| h.1).collect(), rows }
}

/// The section's text before its tables.
fn intro() -> &'static str {
    "For each scene and bounding level, every query first meets the level's cheap test (none; the query \
     against the whole scene's bounding sphere or AABB; the tree's boxes) and goes on to the exact test only \
     if it passes (every element, or the elements of the leaves reached). False-positive rate: of the queries \
     without contact, the fraction the cheap test still let through. Contacts lost: queries in contact whose \
     answer at that level has none (every element tested exactly is the truth). The cheapest lossless level \
     is the fastest that loses no contact; time per query is the median over repetitions of a loop over the \
     (timed) queries, fastest–slowest in parentheses."
}

/// The headline sentence of a scene.
fn headline(s: &SceneNeeds) -> String {
    match s.cheapest_lossless.and_then(|i| s.levels.get(i)) {
        Some(l) => format!(
            "{}: {} of {} queries in contact; cheapest lossless level: {} (by {}).",
            s.name,
            s.contacts,
            s.queries,
            l.level.label(),
            s.cheapest_by
        ),
        None => format!("{}: no level is lossless.", s.name),
    }
}

/// The section's Markdown (for `summary.md`).
pub fn markdown(r: &SceneReport) -> String {
    let mut md = String::from("## What the scene needs\n\n");
    let _ = writeln!(md, "{}\n", intro());
    for p in &r.problems {
        let _ = writeln!(md, "**Not measured:** {p}\n");
    }
    for s in &r.scenes {
        let _ = writeln!(md, "### {}\n\n{}.\n\n{}\n", s.name, s.description, headline(s));
        md.push_str(&table_md(&scene_table(s)));
        md.push('\n');
    }
    let _ = writeln!(
        md,
        "### Bounding-sphere tightness\n\nRadius over the exact minimal radius (the referee's), per method: \
         mean (max) over the clouds. 1 is the minimal sphere.\n"
    );
    for n in tightness_notes(r) {
        let _ = writeln!(md, "{n}\n");
    }
    md.push_str(&table_md(&tightness_table(r)));
    md
}

/// Observations read off the tightness numbers: methods that give the same
/// value under every rotation of the bunny (they do not depend on the axes),
/// and methods that give the same radius on every cloud (within
/// [`SAME_RADIUS_REL`]).
pub fn tightness_notes(r: &SceneReport) -> Vec<String> {
    let mut notes = Vec::new();
    let invariant: Vec<&str> = r
        .bunny_tightness
        .iter()
        .filter(|t| t.values.len() > 1 && t.max - t.min <= SAME_RADIUS_REL * t.max)
        .map(|t| t.method.as_str())
        .collect();
    if !invariant.is_empty() {
        notes.push(format!(
            "On the bunny, the same radius under every rotation (they do not depend on the axes): {}.",
            invariant.join(", ")
        ));
    }
    for (a, name_a) in METHODS.iter().enumerate() {
        for (b, name_b) in METHODS.iter().enumerate().skip(a + 1) {
            let all_sets = r
                .cloud_tightness
                .iter()
                .map(|c| &c.methods)
                .chain((!r.bunny_tightness.is_empty()).then_some(&r.bunny_tightness));
            let mut any = false;
            let same = all_sets.into_iter().all(|m| match (m.get(a), m.get(b)) {
                (Some(x), Some(y)) => {
                    any |= !x.values.is_empty();
                    x.values.len() == y.values.len()
                        && x.values.iter().zip(&y.values).all(|(p, q)| (p - q).abs() <= SAME_RADIUS_REL * p.abs())
                }
                _ => false,
            });
            if any && same {
                notes.push(format!("{name_a} and {name_b} give the same radius on every cloud."));
            }
        }
    }
    notes
}

/// Two radii relative to the minimal one are "the same" within this relative
/// difference: a few roundings (the methods compute the same quantity in a
/// different order).
pub const SAME_RADIUS_REL: f64 = 1e-12;

/// The section's HTML body.
fn html(r: &SceneReport) -> String {
    let mut h = String::new();
    let _ = writeln!(h, "<p>{}</p>", escape(intro()));
    for p in &r.problems {
        let _ = writeln!(h, "<p><strong>Not measured:</strong> {}</p>", escape(p));
    }
    for s in &r.scenes {
        let _ = writeln!(
            h,
            "<h3>{}</h3>\n<p>{}.</p>\n<p>{}</p>",
            escape(&s.name),
            escape(&s.description),
            escape(&headline(s))
        );
        h.push_str(&table_html(&scene_table(s)));
    }
    let _ = writeln!(
        h,
        "<h3>Bounding-sphere tightness</h3>\n<p>Radius over the exact minimal radius (the referee's), per \
         method: mean (max) over the clouds. 1 is the minimal sphere.</p>"
    );
    for n in tightness_notes(r) {
        let _ = writeln!(h, "<p>{}</p>", escape(&n));
    }
    h.push_str(&table_html(&tightness_table(r)));
    h
}

/// Tightness against cloud size for one family: one line per method (means).
fn cloud_chart(r: &SceneReport, family: &str) -> String {
    let series: Vec<Line> = METHODS
        .iter()
        .enumerate()
        .map(|(m, name)| Line {
            name: (*name).into(),
            style: m,
            points: r
                .cloud_tightness
                .iter()
                .filter(|c| c.family == family)
                .filter_map(|c| Some((c.points as f64, c.methods.get(m)?.mean)))
                .collect(),
            failures: Vec::new(),
        })
        .collect();
    let top = series.iter().flat_map(|l| l.points.iter().map(|p| p.1)).fold(1.0, f64::max);
    let step = if top > 1.5 { 0.25 } else { 0.05 };
    let max = 1.0 + ((top - 1.0) / step).ceil().max(1.0) * step;
    line_chart(
        &format!("Bounding-sphere tightness, random clouds ({family})"),
        "points per cloud",
        "radius / minimal radius (mean)",
        Axis::log_covering(CLOUD_SIZES.iter().map(|&n| n as f64)),
        Axis::Linear { min: 1.0, max, step },
        &series,
        LINE_OFFSET_PX,
    )
}

/// Vertical offset between the tightness lines, in pixels: parry's sphere is
/// built as the lecture's is (centroid, largest distance), so their lines
/// would otherwise coincide.
const LINE_OFFSET_PX: f64 = 3.0;

/// A strip chart: one row per method, one dot per rotation at its tightness
/// (x), on a linear axis from 1. Pure: the same values give the same SVG.
pub fn strip_chart(title: &str, rows: &[TightnessStats]) -> String {
    const W: f64 = 760.0;
    let (left, right, top) = (190.0, 720.0, 60.0);
    let row_h = 44.0;
    let bottom = top + row_h * rows.len().max(1) as f64;
    let h = bottom + 60.0;
    let hi = rows.iter().flat_map(|r| r.values.iter().copied()).filter(|x| x.is_finite()).fold(1.0, f64::max);
    let step = if hi > 1.5 { 0.25 } else { 0.05 };
    let max = 1.0 + ((hi - 1.0) / step).ceil().max(1.0) * step;
    let x = |t: f64| left + ((t - 1.0) / (max - 1.0)).clamp(0.0, 1.0) * (right - left);
    let mut s = String::new();
    let _ = write!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {W} {h}" width="{W}" height="{h}" role="img" aria-label="{t}" font-family="system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif" font-size="11"><title>{t}</title><rect x="0" y="0" width="{W}" height="{h}" fill="#fff"/><text x="{left}" y="28" font-size="15" font-weight="600" fill="#111">{t}</text>"##,
        h = px(h),
        t = escape(title),
    );
    let ticks = ((max - 1.0) / step).round() as usize;
    for i in 0..=ticks {
        let t = 1.0 + i as f64 * step;
        let _ = write!(
            s,
            r##"<line x1="{a}" y1="{t0}" x2="{a}" y2="{b}" stroke="#e6e6e6"/><text x="{a}" y="{l}" text-anchor="middle" fill="#333">{t:.2}</text>"##,
            a = px(x(t)),
            t0 = px(top),
            b = px(bottom),
            l = px(bottom + 18.0),
        );
    }
    for (i, r) in rows.iter().enumerate() {
        let y = top + row_h * (i as f64 + 0.5);
        let color = PALETTE[i % PALETTE.len()];
        let _ = write!(
            s,
            r##"<text x="{tx}" y="{ty}" text-anchor="end" fill="#222">{name}</text>"##,
            tx = px(left - 10.0),
            ty = px(y + 4.0),
            name = escape(&r.method),
        );
        for (k, t) in r.values.iter().enumerate() {
            // A fixed small vertical spread by index keeps equal values apart.
            let dy = ((k % 5) as f64 - 2.0) * 3.0;
            let _ = write!(
                s,
                r##"<circle cx="{}" cy="{}" r="3" fill="{color}" fill-opacity="0.7"/>"##,
                px(x(*t)),
                px(y + dy)
            );
        }
        let _ = write!(
            s,
            r##"<line x1="{a}" y1="{y0}" x2="{a}" y2="{y1}" stroke="{color}" stroke-width="2" stroke-dasharray="4 3"/>"##,
            a = px(x(r.mean)),
            y0 = px(y - 14.0),
            y1 = px(y + 14.0),
        );
    }
    let _ = write!(
        s,
        r##"<rect x="{l}" y="{t}" width="{w}" height="{hh}" fill="none" stroke="#555"/><text x="{mx}" y="{xb}" text-anchor="middle" font-size="12" fill="#222">radius / minimal radius (dots: one per rotation; dashed: mean)</text></svg>"##,
        l = px(left),
        t = px(top),
        w = px(right - left),
        hh = px(bottom - top),
        mx = px((left + right) / 2.0),
        xb = px(bottom + 40.0),
    );
    s
}

/// The section's charts.
pub fn charts(r: &SceneReport) -> Vec<SectionChart> {
    let mut out = Vec::new();
    if !r.bunny_tightness.is_empty() {
        let n = r.bunny_tightness[0].values.len();
        let title = format!("Bounding-sphere tightness, the bunny under {n} random rotations");
        out.push(SectionChart {
            svg: strip_chart(&title, &r.bunny_tightness),
            file: "scene-tightness-bunny.svg".into(),
            title,
        });
    }
    for (i, family) in CLOUD_FAMILIES.iter().enumerate() {
        out.push(SectionChart {
            title: format!("Bounding-sphere tightness against cloud size, {family}"),
            file: format!("scene-tightness-clouds-{}.svg", ["uniform", "gaussian"][i]),
            svg: cloud_chart(r, family),
        });
    }
    out
}

/// The section "What the scene needs" of measurements already made: its
/// Markdown, HTML and charts; the data is the whole [`SceneReport`].
pub fn section_of(r: &SceneReport) -> Section {
    Section {
        id: "scene".into(),
        title: "What the scene needs".into(),
        html: html(r),
        markdown: markdown(r),
        charts: charts(r),
        data: serde_json::to_value(r).unwrap_or_else(|e| serde_json::Value::String(format!("unserializable: {e}"))),
    }
}
