//! `summary.md`, and the tables it shares with `index.html`.
//!
//! The tables are built once as plain text cells ([`Table`]); each page escapes
//! them for its own syntax. Every function is pure: the same [`Summary`] gives
//! byte-identical text.

use crate::case::Query;
use crate::summary::{BINS_PER_DECADE, Dist, EngineQueryStats, Summary, Timing};
use std::fmt::Write;

/// A table of plain-text cells (not yet escaped for any page).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Column titles.
    pub header: Vec<String>,
    /// Whether each column holds numbers (right-aligned).
    pub numeric: Vec<bool>,
    /// Rows of cells, as many as there are columns.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    fn new(columns: &[(&str, bool)]) -> Self {
        Table {
            header: columns.iter().map(|c| c.0.to_string()).collect(),
            numeric: columns.iter().map(|c| c.1).collect(),
            rows: Vec::new(),
        }
    }
}

/// A number in compact scientific notation with two significant digits
/// (`1.2e-15`, `3.0e2`): histogram quantiles are only good to 5% (see
/// [`BINS_PER_DECADE`]), so more digits would claim what was not measured.
/// Exactly zero is `0`, infinity `inf`, NaN `NaN`.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x:.1e}")
    }
}

/// A quantity with three significant digits, plain between 1 and 10^6 (`41.2`,
/// `1530`, `87500`), in scientific notation outside (`5.00e-1`).
pub fn sig3(x: f64) -> String {
    let a = x.abs();
    if !(1.0..1e6).contains(&a) {
        return format!("{x:.2e}");
    }
    let mut digits = a.log10().floor() as i32;
    if (a / 10f64.powi(digits - 2)).round() >= 1000.0 {
        // Rounding carried into the next decade (9.996 → 10.0).
        digits += 1;
    }
    if digits >= 2 {
        let unit = 10f64.powi(digits - 2);
        format!("{:.0}", (x / unit).round() * unit)
    } else {
        let decimals = (2 - digits) as usize;
        format!("{x:.decimals$}")
    }
}

/// Time per query: the median and, in parentheses, the fastest and slowest
/// repetition (`41.2 (40.8–43.0)`), nanoseconds; `—` when not timed.
pub fn timing(t: Option<&Timing>) -> String {
    match t {
        None => "—".into(),
        Some(t) => format!("{} ({}–{})", sig3(t.median_ns), sig3(t.min_ns), sig3(t.max_ns)),
    }
}

/// The p99 of a distribution, or `—` when it holds no sample.
fn p99(d: &Dist) -> String {
    d.p99().map_or_else(|| "—".into(), sci)
}

/// The query kinds present in a summary, in [`Query::ALL`] order, with `None`
/// (statistics not tied to a query kind) last when present.
pub fn queries(summary: &Summary) -> Vec<Option<Query>> {
    let mut out: Vec<Option<Query>> =
        Query::ALL.into_iter().filter(|q| summary.stats.iter().any(|s| s.query == Some(*q))).map(Some).collect();
    if summary.stats.iter().any(|s| s.query.is_none()) {
        out.push(None);
    }
    out
}

/// A section title for a query kind.
pub fn query_title(query: Option<Query>) -> String {
    query.map_or_else(|| "other".into(), |q| q.as_str().into())
}

/// The statistics of one query kind, in summary order.
fn stats_of(summary: &Summary, query: Option<Query>) -> Vec<&EngineQueryStats> {
    summary.stats.iter().filter(|s| s.query == query).collect()
}

/// The error measures of a [`EngineQueryStats`], with their column title in the
/// main table (absent: only in the detail table) and their name in the detail table.
#[allow(clippy::type_complexity)]
const MEASURES: [(Option<&str>, &str, fn(&EngineQueryStats) -> &Dist); 8] = [
    (None, "point, absolute", |s| &s.point_abs),
    (Some("point p99 (rel)"), "point, relative to scale", |s| &s.point_rel),
    (None, "depth / radius, absolute", |s| &s.depth_abs),
    (Some("depth p99 (rel)"), "depth / radius, relative to scale", |s| &s.depth_rel),
    (Some("normal p99 (rad)"), "normal angle, rad", |s| &s.normal_rad),
    (Some("t p99"), "segment parameter t", |s| &s.t),
    (Some("bary p99"), "barycentric coordinates", |s| &s.barycentric),
    (None, "headline", |s| &s.headline),
];

/// The count columns every score table shares: cases, then each verdict.
const COUNTS: [&str; 7] = ["cases", "agree", "disagree", "borderline", "known", "unsupported", "failed"];

/// The cells of [`COUNTS`] for one engine and query kind.
fn counts(s: &EngineQueryStats) -> [String; 7] {
    [s.cases, s.agree, s.disagree, s.borderline, s.known, s.unsupported, s.failed].map(|n| n.to_string())
}

/// The main table of one query kind: per engine its counts (cases, agree,
/// disagree, borderline, known, unsupported, failed, of them panics, false +,
/// false −), the p99
/// of its relative point and depth errors, normal angle, t and barycentric
/// errors, the largest headline error and the time per query.
///
/// An error column appears only when some engine of this query measured that
/// error (so a contact table has no barycentric column); a "flags ≠" column
/// appears only when some engine's parallel or degenerate flags differed from
/// the referee's.
pub fn query_table(summary: &Summary, query: Option<Query>) -> Table {
    let stats = stats_of(summary, query);
    let measures: Vec<_> = MEASURES
        .iter()
        .filter_map(|(col, _, get)| col.map(|c| (c, get)))
        .filter(|(_, get)| stats.iter().any(|s| get(s).n > 0))
        .collect();
    let flags = stats.iter().any(|s| s.flag_mismatches > 0);
    let mut cols: Vec<(&str, bool)> = vec![("engine", false)];
    cols.extend(COUNTS.map(|c| (c, true)));
    cols.extend([("panics", true), ("false +", true), ("false −", true)]);
    if flags {
        cols.push(("flags ≠", true));
    }
    cols.extend(measures.iter().map(|(c, _)| (*c, true)));
    cols.push(("max headline", true));
    cols.push(("ns/query (min–max)", true));
    let mut t = Table::new(&cols);
    for s in stats {
        let mut row = vec![s.engine.clone()];
        row.extend(counts(s));
        row.extend([s.panics.to_string(), s.false_positives.to_string(), s.false_negatives.to_string()]);
        if flags {
            row.push(s.flag_mismatches.to_string());
        }
        row.extend(measures.iter().map(|(_, get)| p99(get(s))));
        row.push(if s.headline.n > 0 { sci(s.headline.max) } else { "—".into() });
        row.push(timing(s.timing.as_ref()));
        t.rows.push(row);
    }
    t
}

/// The full-range family's table (`generate::full_range`: raw bit patterns,
/// huge, tiny and subnormal magnitudes, signed zeros, multi-scale scenes),
/// scored apart from the ordinary mix: per query kind and engine, the counts,
/// the non-finite answers and caught panics among the failures, and the p99 and largest headline
/// error. Empty when the campaign ran no full-range case.
pub fn full_range_table(summary: &Summary) -> Table {
    let mut cols: Vec<(&str, bool)> = vec![("query", false), ("engine", false)];
    cols.extend(COUNTS.map(|c| (c, true)));
    cols.extend([
        ("non-finite", true),
        ("panics", true),
        ("false +", true),
        ("false −", true),
        ("headline p99", true),
        ("max headline", true),
    ]);
    let mut t = Table::new(&cols);
    for s in &summary.full_range {
        let mut row = vec![query_title(s.query), s.engine.clone()];
        row.extend(counts(s));
        row.extend([
            s.non_finite.to_string(),
            s.panics.to_string(),
            s.false_positives.to_string(),
            s.false_negatives.to_string(),
            p99(&s.headline),
            if s.headline.n > 0 { sci(s.headline.max) } else { "—".into() },
        ]);
        t.rows.push(row);
    }
    t
}

/// The paragraph under the full-range table.
pub const FULL_RANGE_NOTE: &str = "Cases over the whole finite range of f64, scored apart from the \
     tables above: raw bit patterns, huge and tiny (subnormal) magnitudes, signed zeros, and \
     multi-scale scenes (a small sphere, segment or point beside a triangle with legs up to 1e300; \
     plane normals of length 2^±600; masses from the subnormals to 1e300). Every allowance is the \
     problem's own scale, so a wrong answer disagrees at any magnitude. A case whose exact answer \
     lies beyond f64's range is refused by the referee and counted unsupported for every engine; \
     f32 engines cannot represent most of these inputs (their scores here show that).";

/// What the ulp table measures, for its heading.
pub const ULPS_NOTE: &str = "Each answer by its largest error beyond what the field's conditioning \
     allows, in units of the engine's own ulp (ε of its precision) at the field's magnitude — the \
     sizes the verdict is judged by: the error of a point in ulps of the point's local scale, a \
     normal's angle in ε radians, its length's distance from 1 in ε; a contact, hit or impact found \
     or missed against the referee by the referee's margin from the decision, measured the same \
     way. An engine within N ulps on every answer has no disagreement under `--ulps N` (its \
     misclassifications are borderline); a correctly rounded one is within 1. Median and p99 are \
     read from histograms (5% bins); the maximum and the shares are exact.";

/// The accuracy in ulps, per engine and query kind (the manner of a math
/// library's max-ulp table): answers measured, median, p99 and largest
/// ulps, and the shares within 1, 4 and 64 ulps. Empty when nothing was
/// measured (a report written before ulps were).
pub fn ulps_table(summary: &Summary) -> Table {
    let mut t = Table::new(&[
        ("query", false),
        ("engine", false),
        ("answers", true),
        ("median", true),
        ("p99", true),
        ("max", true),
        ("≤ 1 ulp", true),
        ("≤ 4 ulps", true),
        ("≤ 64 ulps", true),
    ]);
    let pct = |x: f64| format!("{:.1}%", 100.0 * x);
    // The histogram's top bin holds everything from 1e10 up (its quantile
    // reads as that bin's edge): a quantile there is "≥ 1e10", not 1e10.
    let top = 10f64.powi(crate::summary::HIST_MAX_EXP);
    let beyond = |x: f64| if x >= top { format!("≥ {}", sci(top)) } else { sci(x) };
    for q in queries(summary) {
        for s in stats_of(summary, q).into_iter().filter(|s| s.ulps.dist.n > 0) {
            let d = &s.ulps.dist;
            let shares = s.ulps.shares().unwrap_or_default();
            t.rows.push(vec![
                query_title(q),
                s.engine.clone(),
                d.n.to_string(),
                d.median().map_or_else(|| "—".into(), beyond),
                d.p99().map_or_else(|| "—".into(), beyond),
                sci(d.max),
                pct(shares[0]),
                pct(shares[1]),
                pct(shares[2]),
            ]);
        }
    }
    t
}

/// The error distributions of one query kind in full: per engine and measured
/// error, the sample count, exact zeros, median, p99 and maximum.
pub fn detail_table(summary: &Summary, query: Option<Query>) -> Table {
    let mut t = Table::new(&[
        ("engine", false),
        ("error", false),
        ("n", true),
        ("exact zeros", true),
        ("median", true),
        ("p99", true),
        ("max", true),
    ]);
    for s in stats_of(summary, query) {
        for (_, name, get) in &MEASURES {
            let d = get(s);
            if d.n == 0 {
                continue;
            }
            t.rows.push(vec![
                s.engine.clone(),
                (*name).into(),
                d.n.to_string(),
                d.zeros.to_string(),
                d.median().map_or_else(|| "—".into(), sci),
                p99(d),
                sci(d.max),
            ]);
        }
    }
    t
}

/// Campaign throughput: cases per second per engine and for the whole run.
pub fn throughput_table(summary: &Summary) -> Table {
    let mut t = Table::new(&[("engine", false), ("cases / s", true)]);
    for (name, rate) in &summary.throughput {
        t.rows.push(vec![name.clone(), sig3(*rate)]);
    }
    t
}

/// `distance`'s cost by the hull's vertex count (`report::growth`): µs per
/// query, per engine and the referee.
pub fn growth_table(summary: &Summary) -> Table {
    let counts: Vec<u64> = crate::summary::GROWTH_POINTS.iter().map(|&n| n as u64).collect();
    let labels: Vec<String> = counts.iter().map(|n| format!("{n} pts")).collect();
    let mut columns: Vec<(&str, bool)> = vec![("engine", false)];
    columns.extend(labels.iter().map(|l| (l.as_str(), true)));
    let mut t = Table::new(&columns);
    for g in &summary.growth {
        let mut row = vec![g.engine.clone()];
        for n in &counts {
            let cell = g.points.iter().find(|(m, _)| m == n).map_or_else(|| "—".into(), |(_, ns)| sig3(ns / 1e3));
            row.push(cell);
        }
        t.rows.push(row);
    }
    t
}

/// What the growth table and chart measure.
pub const GROWTH_NOTE: &str = "Median µs per distance query for a hull of n points on the unit sphere above a unit \
     cube given as the hull of its corners (the cores apart: GJK's growth), three orders of the points per count. \
     In-process engines are timed whole, building their shapes from the points included; process engines report \
     their own engine call. Chart: charts/distance-cost-growth.svg.";

/// The engines and their versions.
pub fn engines_table(summary: &Summary) -> Table {
    let mut t = Table::new(&[("engine", false), ("version", false)]);
    for e in &summary.provenance.engines {
        let mut version = e.version.clone();
        if let Some(p) = &e.process {
            version.push_str(&process_line(p));
        }
        t.rows.push(vec![e.name.clone(), version]);
    }
    for (name, why) in &summary.provenance.missing_engines {
        t.rows.push(vec![name.clone(), format!("NOT RUN: {why}")]);
    }
    t
}

/// What the provenance says of a process engine beyond its version: what it
/// asked to be echoed, the time limit, restarts, and whether it went down.
fn process_line(p: &crate::protocol::client::ProcessInfo) -> String {
    let mut out = String::new();
    if let Some(h) = &p.hello {
        for (k, v) in &h.provenance {
            out.push_str(&format!("; {k}: {v}"));
        }
    }
    out.push_str(&format!(
        "; times measured inside the engine; time limit {} s per batch; {} restart{}; {} cases sent, exchanged in {:.1} s of wall time",
        p.timeout_seconds,
        p.restarts,
        if p.restarts == 1 { "" } else { "s" },
        p.cases_sent,
        p.seconds_sent
    ));
    if let Some(d) = &p.down {
        out.push_str(&format!("; DOWN: {d}"));
    }
    out
}

/// How often each of the referee's floating-point stages settled its work:
/// "bounds: … 10990 / 29 (99.7 % without the exact stage)", and the query
/// kinds the exact stage alone answers.
fn referee_stages(p: &crate::summary::Provenance) -> String {
    if p.referee_stages.is_empty() {
        return "none counted".into();
    }
    let mut parts: Vec<String> = p
        .referee_stages
        .iter()
        .map(|(label, fast, exact)| {
            let share = 100.0 * *fast as f64 / (*fast + *exact).max(1) as f64;
            format!("{label} {fast} / {exact} ({share:.1} % without the exact stage)")
        })
        .collect();
    parts.push(format!("{}: the exact stage alone (0 % without it)", oracle::referee::EXACT_STAGE_ONLY));
    parts.join("; ")
}

/// The wall time, with the phases it went to when the run recorded them:
/// "55.3 s (making the cases 0.4 s, asking the process engines 30.1 s, …)".
fn wall_time(p: &crate::summary::Provenance) -> String {
    let total = format!("{} s", sig3(p.wall_seconds));
    if p.phases.is_empty() {
        return total;
    }
    let parts: Vec<String> = p.phases.iter().map(|(name, s)| format!("{name} {} s", sig3(*s))).collect();
    format!("{total} ({})", parts.join(", "))
}

/// The provenance as `(field, value)` lines, in the order a report shows them.
pub fn provenance_lines(summary: &Summary) -> Vec<(String, String)> {
    let p = &summary.provenance;
    let shards = if p.shards.is_empty() {
        "none (one run)".to_string()
    } else {
        p.shards.iter().map(|(i, n)| format!("{i}/{n}")).collect::<Vec<_>>().join(", ")
    };
    vec![
        ("crashtest".into(), p.crashtest.clone()),
        ("commit".into(), p.commit.clone().unwrap_or_else(|| "unknown".into())),
        ("rustc".into(), p.rustc.clone()),
        ("profile".into(), p.profile.clone()),
        ("machine".into(), p.machine.clone()),
        ("started".into(), p.started.clone()),
        ("wall time".into(), wall_time(p)),
        ("referee stages".into(), referee_stages(p)),
        ("seed".into(), p.seed.to_string()),
        ("peer engines' list".into(), p.peers.clone().unwrap_or_else(|| "not read (a library run)".into())),
        (
            "judged by".into(),
            match p.ulps {
                Some(n) => {
                    format!("--ulps {n}: every fixed allowance {n} of the engine's ulps of the field's magnitude")
                }
                None => "the tolerance table (crates/harness/src/judge/tolerance.rs)".into(),
            },
        ),
        ("random cases per query".into(), p.cases_per_query.to_string()),
        ("full-range cases per query".into(), p.full_range_per_query.to_string()),
        ("shards".into(), shards),
        ("fixture cases".into(), p.fixture_cases.to_string()),
        ("random cases".into(), p.random_cases.to_string()),
        ("discrepancies".into(), format!("{} (discrepancies.json)", summary.discrepancies)),
        (
            "speed on the charts".into(),
            p.speed_source.clone().unwrap_or_else(|| "the campaign's timing loops (no criterion figures read)".into()),
        ),
        ("format".into(), summary.format.clone()),
    ]
}

/// How to read the tables, one paragraph per item.
pub fn reading_notes() -> Vec<String> {
    vec![
        "Counts are against the exact referee: agree (same classification, errors within tolerance), \
         disagree (beyond tolerance), borderline (classification differs inside the referee's \
         tolerance band), known (a documented divergence), unsupported, failed (panicked or \
         non-finite; panics counts the caught panics among them; discrepancies.json gives the first of each engine \
         and query kind with the panic's location); false + and false − are misclassifications outside the band."
            .into(),
        "Errors are relative to the answer's own scale (points, depths, radii: the magnitudes that \
         decide them, not the scene's size), in radians (normals), or as they are (t, barycentric \
         coordinates). The headline error of a case is the largest of them, and 1 for a \
         misclassification or failure."
            .into(),
        format!(
            "Quantiles are read from log histograms with {BINS_PER_DECADE} bins per decade: within 5% \
             of the sample's. Maxima are exact. — means nothing was measured."
        ),
        "Time per query: median over repetitions of a tight loop over the same cases, with the \
         fastest and slowest repetition."
            .into(),
    ]
}

/// Escapes text for a Markdown table cell or line: every character that could
/// start Markdown or HTML syntax is backslash-escaped (CommonMark allows that for
/// any ASCII punctuation), and line breaks become spaces.
pub fn escape_md(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '\\' | '`' | '*' | '_' | '[' | ']' | '<' | '>' | '|' | '#' | '&' | '!' | '~' => {
                out.push('\\');
                out.push(c);
            }
            '\n' | '\r' => out.push(' '),
            _ => out.push(c),
        }
    }
    out
}

/// A [`Table`] as a Markdown (GitHub) table, cells escaped.
pub fn table_md(t: &Table) -> String {
    let mut out = String::new();
    let row = |cells: &[String]| {
        let cells: Vec<String> = cells.iter().map(|c| escape_md(c)).collect();
        format!("| {} |\n", cells.join(" | "))
    };
    out.push_str(&row(&t.header));
    let rule: Vec<&str> = t.numeric.iter().map(|&n| if n { "---:" } else { "---" }).collect();
    let _ = writeln!(out, "| {} |", rule.join(" | "));
    for r in &t.rows {
        out.push_str(&row(r));
    }
    out
}

/// Each engine against the referee, one row per engine and one column per
/// query kind: `agree · disagree · known · unsupported`, and the borderline
/// and failed verdicts in brackets where there are any (the campaign's
/// cases, fixtures included; the full range is apart).
pub fn overview_table(summary: &Summary) -> Table {
    let queries = queries(summary);
    let titles: Vec<String> = queries.iter().map(|q| query_title(*q)).collect();
    let mut columns: Vec<(&str, bool)> = vec![("engine", false)];
    columns.extend(titles.iter().map(|t| (t.as_str(), false)));
    let mut t = Table::new(&columns);
    // Engines with a verdict (the referee, timed beside them, has none).
    let mut engines: Vec<&str> = Vec::new();
    for s in &summary.stats {
        let judged = s.agree + s.disagree + s.borderline + s.known + s.unsupported + s.failed > 0;
        if judged && !engines.contains(&s.engine.as_str()) {
            engines.push(&s.engine);
        }
    }
    for e in engines {
        let mut row = vec![e.to_string()];
        for q in &queries {
            let cell = match summary.stats.iter().find(|s| s.engine == e && s.query == *q) {
                Some(s) => {
                    let mut c = format!("{} · {} · {} · {}", s.agree, s.disagree, s.known, s.unsupported);
                    if s.borderline + s.failed > 0 {
                        c.push_str(&format!(" ({} borderline, {} failed)", s.borderline, s.failed));
                    }
                    c
                }
                None => "—".into(),
            };
            row.push(cell);
        }
        t.rows.push(row);
    }
    t
}

/// The whole of `summary.md`: provenance (commit, rustc, profile, machine,
/// engine versions, seed, case counts, wall time), then per query kind its main
/// table and its error details, then throughput, then how to read it all.
pub fn summary_md(summary: &Summary) -> String {
    summary_md_with(summary, "")
}

/// [`summary_md`] opening with `opening` (the findings, Markdown) after its title.
pub fn summary_md_with(summary: &Summary, opening: &str) -> String {
    let mut out = String::from("# crashtest report\n\n");
    out.push_str(opening);
    out.push_str("## Provenance\n\n");
    for (k, v) in provenance_lines(summary) {
        let _ = writeln!(out, "- **{}**: {}", escape_md(&k), escape_md(&v));
    }
    out.push('\n');
    if !summary.provenance.engines.is_empty() {
        out.push_str(&table_md(&engines_table(summary)));
        out.push('\n');
    }
    if !summary.stats.is_empty() {
        out.push_str("## Each engine against the referee\n\n");
        out.push_str(
            "Per query kind: agree · disagree · known divergence · unsupported (borderline and failed in \
             brackets); the tables below have the errors.\n\n",
        );
        out.push_str(&table_md(&overview_table(summary)));
        out.push('\n');
    }
    let queries = queries(summary);
    if queries.is_empty() {
        out.push_str("No results.\n\n");
    }
    for q in queries {
        let _ = writeln!(out, "## {}\n", escape_md(&query_title(q)));
        out.push_str(&table_md(&query_table(summary, q)));
        let detail = detail_table(summary, q);
        if !detail.rows.is_empty() {
            out.push_str("\nError distributions:\n\n");
            out.push_str(&table_md(&detail));
        }
        out.push('\n');
    }
    let ulps = ulps_table(summary);
    if !ulps.rows.is_empty() {
        out.push_str("## Accuracy in ulps\n\n");
        let _ = writeln!(out, "{}\n", escape_md(ULPS_NOTE));
        out.push_str(&table_md(&ulps));
        out.push('\n');
    }
    if !summary.full_range.is_empty() {
        out.push_str("## Full range\n\n");
        let _ = writeln!(out, "{}\n", escape_md(FULL_RANGE_NOTE));
        out.push_str(&table_md(&full_range_table(summary)));
        out.push('\n');
    }
    if !summary.throughput.is_empty() {
        out.push_str("## Throughput\n\n");
        out.push_str(&table_md(&throughput_table(summary)));
        out.push('\n');
    }
    if !summary.growth.is_empty() {
        out.push_str("## distance: cost by vertex count\n\n");
        let _ = writeln!(out, "{}\n", escape_md(GROWTH_NOTE));
        out.push_str(&table_md(&growth_table(summary)));
        out.push('\n');
    }
    out.push_str("## Reading the tables\n\n");
    for note in reading_notes() {
        let _ = writeln!(out, "- {note}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::charts::fixture;

    #[test]
    fn sci_is_compact_and_total() {
        assert_eq!(sci(0.0), "0");
        assert_eq!(sci(1.234e-15), "1.2e-15");
        assert_eq!(sci(250.0), "2.5e2");
        assert_eq!(sci(f64::INFINITY), "inf");
        assert_eq!(sig3(41.25), "41.2");
        assert_eq!(sig3(1530.4), "1530");
        assert_eq!(sig3(87494.0), "87500");
        assert_eq!(sig3(9.996), "10.0");
        assert_eq!(sig3(0.5), "5.00e-1");
    }

    #[test]
    fn summary_md_opens_with_provenance_and_has_a_table_per_query() {
        let md = summary_md(&fixture::summary());
        let prov = md.find("## Provenance").expect("provenance");
        let contact = md.find("## contact").expect("contact section");
        let intersect = md.find("## intersect").expect("intersect section");
        assert!(prov < contact && contact < intersect, "order");
        for needle in [
            "abc1234-dirty",
            "rustc 1.95.0",
            "release",
            "linux x86\\_64, 2 cores",
            "collide (this commit), f32",
            "**seed**: 42",
            "**fixture cases**: 12",
            "**random cases**: 200",
            "3.25 s",
            "**discrepancies**: 3",
        ] {
            assert!(md.contains(needle), "missing {needle:?} in\n{md}");
        }
        assert!(md.contains("| fast\\<f32\\> | 100 | 97 | 1 | 1 | 1 | 0 | 0 | 0 | 1 | 0 |"), "{md}");
        assert!(md.contains("1.0e-6"), "p99 of fast on contact: {md}");
        assert!(md.contains("20.0 (18.0–24.0)"), "timing with spread: {md}");
        assert!(!md.contains("bary p99"), "no barycentric column without samples");
        assert!(md.find("## Throughput").expect("throughput") > intersect);
        // The overview: fast<f32> on contact, 97 agree, 1 disagree, 1 known, 1 borderline.
        let overview = md.find("## Each engine against the referee").expect("overview");
        assert!(prov < overview && overview < contact, "the overview comes before the query tables");
        assert!(md.contains("| fast\\<f32\\> | 97 · 1 · 1 · 0 (1 borderline, 0 failed) |"), "{md}");
        // The provenance names an engine that was not installed.
        assert!(md.contains("NOT RUN: not installed; install it with \\`x \\& y\\`"), "{md}");
    }

    #[test]
    fn the_ulps_table_gives_the_distribution_and_exact_shares() {
        let mut summary = fixture::summary();
        assert!(!summary_md(&summary).contains("## Accuracy in ulps"), "nothing measured, no table");
        let s = &mut summary.stats[0];
        for u in [0.0, 0.5, 1.0, 3.0, 4.0, 10.0, 64.0, 65.0] {
            s.ulps.add(u);
        }
        assert_eq!(s.ulps.within, [3, 5, 7]);
        let (engine, query) = (s.engine.clone(), query_title(s.query));
        let md = summary_md(&summary);
        let at = md.find("## Accuracy in ulps").expect("the ulps section");
        assert!(at > md.find("## contact").expect("contact") && at < md.find("## Throughput").expect("throughput"));
        // 8 answers: median (upper edge of its 5% bin) ≈ 3.0, max 65, shares
        // 3/8, 5/8 and 7/8.
        let row = format!("| {query} | {} | 8 | ", escape_md(&engine));
        let line = md[at..].lines().find(|l| l.starts_with(&row)).unwrap_or_else(|| panic!("no row {row} in\n{md}"));
        assert!(line.ends_with("| 6.5e1 | 37.5% | 62.5% | 87.5% |"), "{line}");
        // Beyond the histogram's top bin, a quantile says so.
        let s = &mut summary.stats[0];
        for _ in 0..100 {
            s.ulps.add(7e15);
        }
        let md = summary_md(&summary);
        let line = md
            .lines()
            .find(|l| l.starts_with(&format!("| {query} | {} | 108 | ", escape_md(&engine))))
            .expect("the row");
        assert!(line.contains("| ≥ 1.0e10 | ≥ 1.0e10 | 7.0e15 |"), "{line}");
    }

    #[test]
    fn the_full_range_table_comes_after_the_queries_with_its_counts() {
        let mut summary = fixture::summary();
        assert!(!summary_md(&summary).contains("## Full range"), "no full-range cases, no table");
        let mut s = summary.stats[0].clone();
        s.non_finite = 2;
        s.panics = 3;
        summary.full_range = vec![s];
        let md = summary_md(&summary);
        let full = md.find("## Full range").expect("a full-range section");
        assert!(full > md.find("## intersect").expect("intersect section"), "after the query tables");
        assert!(md.contains("| contact | fast\\<f32\\> | 100 | 97 | 1 | 1 | 1 | 0 | 0 | 2 | 3 |"), "{md}");
    }

    #[test]
    fn markdown_escapes_table_syntax() {
        assert_eq!(escape_md("a|b<c>*"), "a\\|b\\<c\\>\\*");
    }
}
