//! The report's charts, as SVG text.
//!
//! Every function here is pure: the same [`Summary`] gives byte-identical SVG
//! (no clock, no randomness, no hash-map order; coordinates are printed with one
//! decimal).
//!
//! Decision: the SVG is written by hand rather than through a plotting crate. The
//! charts are a few dozen elements (axes, decade ticks, circles, polylines, text),
//! and writing them directly gives what the report needs without a font backend:
//! text is emitted as `<text>` and laid out by the browser, labels are placed
//! beside their points with a small collision pass, zero errors get their own
//! marked floor, and the markup carries no element ids, so any number of charts
//! can be inlined in one HTML page without clashing.

use super::plot::{Axis, Line, line_chart};
use super::xml::escape;
use crate::case::Query;
use crate::summary::{BINS_PER_DECADE, Dist, EngineQueryStats, Summary};
use std::fmt::Write;

/// A p99 error of exactly 0 cannot sit on a log axis: it is drawn at this floor
/// (dimensionless, like the headline error), with a hollow marker and a dotted
/// line labelled as standing for zero. 1e-18 is about a hundredth of an f64 ulp at
/// scale 1 (2.2e-16), so it lies below every error an f64 engine can make on a
/// scene of unit scale. When an engine's non-zero p99 lies lower still, the floor
/// moves one decade below it (see [`zero_floor`]).
pub const ZERO_FLOOR: f64 = 1e-18;

/// One chart of a report, ready to be written to `charts/<file>` and inlined in
/// `index.html`.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    /// The query kind it shows.
    pub query: Query,
    /// Its caption.
    pub title: String,
    /// Its file name inside the report's `charts/` folder.
    pub file: String,
    /// The SVG document (no XML declaration, no element ids: it inlines as is).
    pub svg: String,
}

/// Every chart of a summary: per query kind present in it (in [`Query::ALL`]
/// order), the accuracy–speed chart and the error distribution, each when it
/// has something to show.
pub fn all(summary: &Summary) -> Vec<Chart> {
    let mut out = Vec::new();
    for query in Query::ALL {
        if !summary.stats.iter().any(|s| s.query == Some(query)) {
            continue;
        }
        if let Some(svg) = accuracy_speed(summary, query) {
            out.push(Chart {
                query,
                title: format!("{query}: accuracy against speed"),
                file: format!("{query}-accuracy-speed.svg"),
                svg,
            });
        }
        if let Some(svg) = error_distribution(summary, query) {
            out.push(Chart {
                query,
                title: format!("{query}: distribution of the headline error"),
                file: format!("{query}-error-distribution.svg"),
                svg,
            });
        }
        if let Some(svg) = ulps_distribution(summary, query) {
            out.push(Chart {
                query,
                title: format!("{query}: accuracy in ulps"),
                file: format!("{query}-ulps.svg"),
                svg,
            });
        }
    }
    if let Some(svg) = cost_growth(summary) {
        out.push(Chart {
            query: Query::Distance,
            title: "distance: cost against the hull's vertex count".into(),
            file: "distance-cost-growth.svg".into(),
            svg,
        });
    }
    out
}

/// `distance`'s cost per query against the hull's vertex count, log–log, one
/// line per engine and the referee (`report::growth`): a slope of 1 is linear
/// growth. `None` when the run measured none.
pub fn cost_growth(summary: &Summary) -> Option<String> {
    if summary.growth.is_empty() {
        return None;
    }
    let series: Vec<Line> = summary
        .growth
        .iter()
        .enumerate()
        .map(|(i, g)| Line {
            name: g.engine.clone(),
            style: i,
            points: g.points.iter().map(|&(n, ns)| (n as f64, ns)).collect(),
            failures: Vec::new(),
        })
        .collect();
    let xa = Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
    let ya = Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.1)));
    Some(line_chart(
        "distance: cost against vertex count (hulls apart)",
        "vertices of the hull",
        "ns per query (median)",
        xa,
        ya,
        &series,
        0.0,
    ))
}

/// Indices of the points on the Pareto front of `(x, y)` pairs where smaller is
/// better on both axes (here: time per query and p99 error), sorted by `x` then
/// `y` then index.
///
/// A point is on the front when no other point dominates it; `a` dominates `b`
/// when `a.x <= b.x` and `a.y <= b.y` with at least one strict. Equal points do
/// not dominate each other, so both stay. A pair with a NaN coordinate is never on
/// the front and dominates nothing (callers pass finite values).
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let valid = |p: &(f64, f64)| !p.0.is_nan() && !p.1.is_nan();
    let dominates = |a: &(f64, f64), b: &(f64, f64)| a.0 <= b.0 && a.1 <= b.1 && (a.0 < b.0 || a.1 < b.1);
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| valid(&points[i]))
        .filter(|&i| !points.iter().any(|q| valid(q) && dominates(q, &points[i])))
        .collect();
    front.sort_by(|&a, &b| {
        points[a].0.total_cmp(&points[b].0).then(points[a].1.total_cmp(&points[b].1)).then(a.cmp(&b))
    });
    front
}

/// The value a p99 of exactly zero is drawn at: [`ZERO_FLOOR`], or one decade
/// below the smallest positive value when that lies at or under the floor (so a
/// zero is never drawn above a real error). `positives` holds the non-zero p99s.
pub fn zero_floor(positives: &[f64]) -> f64 {
    let smallest = positives.iter().copied().filter(|v| *v > 0.0 && v.is_finite()).fold(f64::INFINITY, f64::min);
    if smallest <= ZERO_FLOOR * 1.5 { 10f64.powi(smallest.log10().floor() as i32 - 1) } else { ZERO_FLOOR }
}

/// Accuracy against speed for one query kind: x is nanoseconds per query (the
/// criterion benchmark's figure when the report read one — see
/// [`crate::report::bench`] — else the median of the campaign's timing repetitions), y the p99 of the headline error, both on
/// log axes with decade ticks; one circle per engine, labelled with the engine's
/// name (which carries its method and precision); the Pareto front (engines no
/// other engine beats in both time and error, [`pareto_front`]) drawn as a step
/// line. A p99 of zero is drawn at [`zero_floor`] with a hollow marker and a
/// dotted line that says so. Engines without timing or without a measured error
/// are named in a note under the chart.
///
/// `None` when no engine has timing for this query (or none of those has a
/// measured headline error).
pub fn accuracy_speed(summary: &Summary, query: Query) -> Option<String> {
    let colors = EngineColors::new(summary);
    let mut points: Vec<(&EngineQueryStats, f64, f64)> = Vec::new();
    let mut untimed = Vec::new();
    let mut unmeasured = Vec::new();
    for s in summary.stats.iter().filter(|s| s.query == Some(query)) {
        let t = s.bench_ns.or(s.timing.map(|t| t.median_ns)).filter(|t| t.is_finite() && *t > 0.0);
        let p99 = s.headline.p99().filter(|v| v.is_finite());
        match (t, p99) {
            (None, _) => untimed.push(s.engine.as_str()),
            (Some(_), None) => unmeasured.push(s.engine.as_str()),
            (Some(t), Some(e)) => points.push((s, t, e)),
        }
    }
    if points.is_empty() {
        return None;
    }
    let raw: Vec<(f64, f64)> = points.iter().map(|p| (p.1, p.2)).collect();
    let front = pareto_front(&raw);
    let positives: Vec<f64> = raw.iter().map(|p| p.1).filter(|v| *v > 0.0).collect();
    let floor = zero_floor(&positives);
    let has_zero = raw.iter().any(|p| p.1 == 0.0);
    let plotted: Vec<(f64, f64)> = raw.iter().map(|&(x, y)| (x, if y == 0.0 { floor } else { y })).collect();

    let (w, h) = (760.0, 540.0);
    let (left, right, top, bottom) = (80.0, 730.0, 50.0, 430.0);
    let xs: Vec<f64> = plotted.iter().map(|p| p.0).collect();
    let ys: Vec<f64> = plotted.iter().map(|p| p.1).collect();
    let xa = LogAxis::covering(&xs, left, right);
    let ya = LogAxis::covering(&ys, bottom, top);

    let mut svg = String::new();
    let title = format!("{query}: accuracy against speed");
    open_svg(&mut svg, w, h, &title);
    frame(&mut svg, &xa, &ya, left, right, top, bottom);
    let x_title = if points.iter().any(|p| p.0.bench_ns.is_some()) {
        "time per query, ns (criterion benchmark, weighted by this campaign's mix)"
    } else {
        "time per query, ns (median of repetitions)"
    };
    x_axis(&mut svg, &xa, bottom, x_title);
    y_axis(&mut svg, &ya, left, top, bottom, "headline error, p99");

    if has_zero {
        let y = ya.pos(floor);
        let _ = write!(
            svg,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#888" stroke-dasharray="1 3"/>"##,
            n(left),
            n(y),
            n(right),
            n(y)
        );
    }

    // The Pareto front as a step line: from each front point, across to the next
    // one's time, then down to its error.
    if front.len() > 1 {
        let mut pts = String::new();
        for (k, &i) in front.iter().enumerate() {
            let (px, py) = (xa.pos(plotted[i].0), ya.pos(plotted[i].1));
            if k > 0 {
                let prev_y = ya.pos(plotted[front[k - 1]].1);
                let _ = write!(pts, "{},{} ", n(px), n(prev_y));
            }
            let _ = write!(pts, "{},{} ", n(px), n(py));
        }
        let _ = write!(
            svg,
            r##"<polyline points="{}" fill="none" stroke="#333" stroke-width="1.5" stroke-dasharray="6 3"/>"##,
            pts.trim_end()
        );
    }

    // Points, then labels placed beside them without overlapping each other.
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        ya.pos(plotted[a].1)
            .total_cmp(&ya.pos(plotted[b].1))
            .then(xa.pos(plotted[a].0).total_cmp(&xa.pos(plotted[b].0)))
            .then(a.cmp(&b))
    });
    for &i in &order {
        let (px, py) = (xa.pos(plotted[i].0), ya.pos(plotted[i].1));
        let color = colors.color(&points[i].0.engine);
        let on_front = front.contains(&i);
        let r = if on_front { 5.5 } else { 4.5 };
        if raw[i].1 == 0.0 {
            let _ = write!(
                svg,
                r##"<circle cx="{}" cy="{}" r="{}" fill="#fff" stroke="{}" stroke-width="2.5"/>"##,
                n(px),
                n(py),
                n(r),
                color
            );
        } else {
            let outline = if on_front { "#222" } else { "#fff" };
            let _ = write!(
                svg,
                r##"<circle cx="{}" cy="{}" r="{}" fill="{}" stroke="{}" stroke-width="1.2"/>"##,
                n(px),
                n(py),
                n(r),
                color,
                outline
            );
        }
    }
    let anchors: Vec<(f64, f64)> = plotted.iter().map(|p| (xa.pos(p.0), ya.pos(p.1))).collect();
    let mut placed: Vec<Rect> = Vec::new();
    for &i in &order {
        let name = &points[i].0.engine;
        let (px, py) = anchors[i];
        let label = place_label(name, px, py, &anchors, &placed, (left, w - 4.0), (top, bottom));
        placed.push(label.rect);
        if label.dy != 0.0 {
            let lx = if label.anchor_end { label.x + 2.0 } else { label.x - 2.0 };
            let _ = write!(
                svg,
                r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#aaa" stroke-width="0.8"/>"##,
                n(px),
                n(py),
                n(lx),
                n(label.y - 4.0)
            );
        }
        let _ = write!(
            svg,
            r##"<text x="{}" y="{}"{} fill="#222">{}</text>"##,
            n(label.x),
            n(label.y),
            if label.anchor_end { r#" text-anchor="end""# } else { "" },
            escape(name)
        );
    }
    if has_zero {
        // Say what the dotted line means, beside it where no label or point is.
        let text = format!("p99 = 0 (exact), drawn at {}", decade_or_sci(floor));
        let y = ya.pos(floor);
        let r = free_spot(&text, y, (left, right), &anchors, &placed);
        let _ = write!(
            svg,
            r##"<text x="{}" y="{}"{} fill="#666">{}</text>"##,
            n(r.x),
            n(r.y),
            if r.anchor_end { r#" text-anchor="end""# } else { "" },
            escape(&text)
        );
    }

    // Key and notes under the axis title.
    let mut y = bottom + 66.0;
    let _ = write!(
        svg,
        r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#333" stroke-width="1.5" stroke-dasharray="6 3"/><text x="{}" y="{}" fill="#444">Pareto front: engines that no other engine beats in both time and error (circled dark)</text>"##,
        n(left),
        n(y - 4.0),
        n(left + 28.0),
        n(y - 4.0),
        n(left + 36.0),
        n(y)
    );
    if has_zero {
        y += 17.0;
        let _ = write!(
            svg,
            r##"<circle cx="{}" cy="{}" r="4.5" fill="#fff" stroke="#555" stroke-width="2.5"/><text x="{}" y="{}" fill="#444">hollow: p99 error exactly 0, drawn at {} (a log axis has no zero)</text>"##,
            n(left + 14.0),
            n(y - 4.0),
            n(left + 36.0),
            n(y),
            decade_or_sci(floor)
        );
    }
    for (what, names) in [("not timed", &untimed), ("no error measured", &unmeasured)] {
        if !names.is_empty() {
            y += 17.0;
            let _ = write!(
                svg,
                r##"<text x="{}" y="{}" fill="#444">Not plotted ({}): {}</text>"##,
                n(left),
                n(y),
                what,
                escape(&names.join(", "))
            );
        }
    }
    svg.push_str("</svg>\n");
    Some(svg)
}

/// The distribution of the headline error for one query kind, per engine: the
/// complementary CDF (the fraction of cases whose error exceeds x) on log–log
/// axes, read from each engine's histogram (bin edges 10^(k/B), B =
/// [`BINS_PER_DECADE`]; within a bin the curve is a straight line, which is all a
/// histogram knows). A curve starts at the fraction of non-zero errors and ends
/// at the engine's exact maximum, where it drops to the bottom of the axis; the
/// further right and the higher a curve, the worse the engine's tail. One line
/// per engine (color and dash pattern), with a legend; engines whose every error
/// was exactly zero, or that measured none, are named in a note.
///
/// `None` when no engine of this query has a non-zero headline error.
pub fn error_distribution(summary: &Summary, query: Query) -> Option<String> {
    distribution(summary, query, |s| &s.headline, "distribution of the headline error", "headline error x")
}

/// The distribution of the accuracy in ulps for one query kind, per engine
/// (`judge::Errors::ulps`: the largest error of an answer beyond what its
/// conditioning allows, in the engine's ulps of the field's magnitude), drawn
/// as [`error_distribution`] draws the headline error: where a curve crosses
/// `x = N`, the fraction of answers that `--ulps N` would call wrong.
pub fn ulps_distribution(summary: &Summary, query: Query) -> Option<String> {
    distribution(summary, query, |s| &s.ulps.dist, "accuracy in ulps", "ulps beyond the conditioning x")
}

/// The complementary CDF chart of the distribution `get` of one query kind,
/// per engine (see [`error_distribution`]).
fn distribution(
    summary: &Summary,
    query: Query,
    get: fn(&EngineQueryStats) -> &Dist,
    what: &str,
    x_title: &str,
) -> Option<String> {
    let colors = EngineColors::new(summary);
    let mut curves: Vec<(&EngineQueryStats, Vec<(f64, f64)>)> = Vec::new();
    let mut exact = Vec::new();
    let mut unmeasured = Vec::new();
    for s in summary.stats.iter().filter(|s| s.query == Some(query)) {
        let d = get(s);
        if d.n == 0 {
            unmeasured.push(s.engine.as_str());
        } else if d.bins.is_empty() {
            exact.push(s.engine.as_str());
        } else {
            curves.push((s, ccdf(d)));
        }
    }
    if curves.is_empty() {
        return None;
    }
    let max_n = curves.iter().map(|c| get(c.0).n).max().unwrap_or(1).max(1);
    let xs: Vec<f64> = curves.iter().flat_map(|c| c.1.iter().map(|p| p.0)).collect();

    let legend_chars = curves.iter().map(|c| c.0.engine.chars().count()).max().unwrap_or(0);
    let legend_w = 44.0 + CHAR_W * legend_chars as f64;
    let (left, right, top, bottom) = (80.0, 600.0, 50.0, 410.0);
    let w = (right + 24.0 + legend_w).max(760.0);
    let h = 500.0;
    let xa = LogAxis::covering(&xs, left, right);
    // y: from 1 down to the decade holding 1/n of the largest sample.
    let y_lo = -((max_n as f64).log10().ceil() as i32).max(1);
    let ya = LogAxis { lo: y_lo, hi: 0, p0: bottom, p1: top };

    let mut svg = String::new();
    let title = format!("{query}: {what}");
    open_svg(&mut svg, w, h, &title);
    frame(&mut svg, &xa, &ya, left, right, top, bottom);
    x_axis(&mut svg, &xa, bottom, x_title);
    y_axis(&mut svg, &ya, left, top, bottom, "fraction of cases with error > x");

    for (idx, (s, pts)) in curves.iter().enumerate() {
        // Below its smallest non-zero error, the fraction above x is flat: the
        // curve starts at the axis's left edge.
        let mut line = format!("{},{} ", n(left), n(ya.pos(pts[0].1.max(ya.min_value()))));
        for &(x, f) in pts {
            let py = if f > 0.0 { ya.pos(f.max(ya.min_value())) } else { bottom };
            let _ = write!(line, "{},{} ", n(xa.pos(x)), n(py));
        }
        let _ = write!(
            svg,
            r##"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.8"{}/>"##,
            line.trim_end(),
            colors.color(&s.engine),
            colors.dash_attr(&s.engine)
        );
        let ly = top + 8.0 + 18.0 * idx as f64;
        let lx = right + 24.0;
        let _ = write!(
            svg,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="2.2"{}/><text x="{}" y="{}" fill="#222">{}</text>"##,
            n(lx),
            n(ly),
            n(lx + 30.0),
            n(ly),
            colors.color(&s.engine),
            colors.dash_attr(&s.engine),
            n(lx + 36.0),
            n(ly + 4.0),
            escape(&s.engine)
        );
    }

    let mut y = bottom + 66.0;
    let _ = write!(
        svg,
        r##"<text x="{}" y="{}" fill="#444">Read from histograms with {} bins per decade; exact zeros never exceed x. A curve ends at the engine's largest error.</text>"##,
        n(left),
        n(y),
        BINS_PER_DECADE
    );
    for (what, names) in [("every error exactly 0", &exact), ("no error measured", &unmeasured)] {
        if !names.is_empty() {
            y += 17.0;
            let _ = write!(
                svg,
                r##"<text x="{}" y="{}" fill="#444">No curve ({}): {}</text>"##,
                n(left),
                n(y),
                what,
                escape(&names.join(", "))
            );
        }
    }
    svg.push_str("</svg>\n");
    Some(svg)
}

/// The complementary CDF of a distribution with at least one positive sample, as
/// `(x, fraction of samples > x)` vertices: from the lowest bin's lower edge at the
/// fraction of non-zero samples, through every bin's edges, to the exact maximum
/// at fraction 0.
fn ccdf(d: &Dist) -> Vec<(f64, f64)> {
    let total = d.n.max(1) as f64;
    let mut above = d.n.saturating_sub(d.zeros);
    let mut out = Vec::new();
    let edge = |k: i32| 10f64.powf(k as f64 / BINS_PER_DECADE as f64);
    for (i, &(k, c)) in d.bins.iter().enumerate() {
        let lower = edge(k).min(d.max);
        let upper = edge(k + 1).min(d.max);
        let last = i + 1 == d.bins.len();
        out.push((lower, above as f64 / total));
        above = above.saturating_sub(c);
        // The last bin ends at the exact maximum, where nothing is above any more.
        let upper = if last && d.max.is_finite() { d.max.max(lower) } else { upper };
        let frac = if last { 0.0 } else { above as f64 / total };
        out.push((upper, frac));
    }
    out
}

/// Average advance of one character of the charts' 11 px sans-serif text, px (an
/// estimate: the browser picks the face, so label boxes are padded by it).
const CHAR_W: f64 = 6.4;
/// Height of one label line, px.
const LINE_H: f64 = 13.0;

/// Colors and dash patterns per engine, fixed by the engine's first appearance in
/// the summary, so an engine keeps its color in every chart of a report.
struct EngineColors<'a> {
    names: Vec<&'a str>,
}

/// Colorblind-aware categorical palette (dark enough to read on white).
const PALETTE: [&str; 8] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#e08a0b", "#17becf", "#8c564b", "#e377c2"];
/// Dash patterns, changed each time the palette wraps around.
const DASHES: [&str; 4] = ["", "7 3", "2 2", "9 3 2 3"];

impl<'a> EngineColors<'a> {
    fn new(summary: &'a Summary) -> Self {
        let mut names: Vec<&str> = Vec::new();
        for s in &summary.stats {
            if !names.contains(&s.engine.as_str()) {
                names.push(&s.engine);
            }
        }
        EngineColors { names }
    }

    fn index(&self, engine: &str) -> usize {
        self.names.iter().position(|n| *n == engine).unwrap_or(0)
    }

    fn color(&self, engine: &str) -> &'static str {
        PALETTE[self.index(engine) % PALETTE.len()]
    }

    fn dash_attr(&self, engine: &str) -> String {
        let dash = DASHES[(self.index(engine) / PALETTE.len() + self.index(engine)) % DASHES.len()];
        if dash.is_empty() { String::new() } else { format!(r#" stroke-dasharray="{dash}""#) }
    }
}

/// A log axis spanning whole decades `10^lo ..= 10^hi`, mapped to pixels `p0 ..= p1`
/// (`p0` the low end: left for x, bottom for y).
struct LogAxis {
    lo: i32,
    hi: i32,
    p0: f64,
    p1: f64,
}

/// Room left around the data, in decades, before rounding out to whole decades,
/// so that no point sits on the frame.
const AXIS_PAD_DECADES: f64 = 0.15;

impl LogAxis {
    /// The whole decades covering the positive finite `values` with a margin; one
    /// decade around 1 when there are none.
    fn covering(values: &[f64], p0: f64, p1: f64) -> Self {
        let logs: Vec<f64> = values.iter().filter(|v| **v > 0.0 && v.is_finite()).map(|v| v.log10()).collect();
        let min = logs.iter().copied().fold(f64::INFINITY, f64::min);
        let max = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (lo, hi) = if min.is_finite() {
            ((min - AXIS_PAD_DECADES).floor() as i32, (max + AXIS_PAD_DECADES).ceil() as i32)
        } else {
            (0, 1)
        };
        LogAxis { lo, hi: hi.max(lo + 1), p0, p1 }
    }

    fn pos(&self, v: f64) -> f64 {
        let t = (v.log10() - self.lo as f64) / (self.hi - self.lo) as f64;
        self.p0 + t.clamp(0.0, 1.0) * (self.p1 - self.p0)
    }

    fn min_value(&self) -> f64 {
        10f64.powi(self.lo)
    }

    /// Every how many decades a tick carries a label (at most about 12 labels).
    fn label_step(&self) -> i32 {
        ((self.hi - self.lo) + 11) / 12
    }
}

/// The label of decade `10^k`: plain for 1 to 1000, else `1e<k>`.
fn decade_label(k: i32) -> String {
    match k {
        0 => "1".into(),
        1 => "10".into(),
        2 => "100".into(),
        3 => "1000".into(),
        _ => format!("1e{k}"),
    }
}

/// A value drawn as its decade label when it is a power of ten, else `1.2e-19`.
fn decade_or_sci(v: f64) -> String {
    let k = v.log10().round();
    if (v / 10f64.powi(k as i32) - 1.0).abs() < 1e-9 { decade_label(k as i32) } else { format!("{v:.1e}") }
}

/// A pixel coordinate with one decimal (and no negative zero).
fn n(x: f64) -> String {
    format!("{:.1}", x + 0.0)
}

fn open_svg(svg: &mut String, w: f64, h: f64, title: &str) {
    let _ = write!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}" role="img" aria-label="{t}" font-family="system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif" font-size="11"><title>{t}</title><rect x="0" y="0" width="{w}" height="{h}" fill="#fff"/><text x="{x}" y="26" font-size="15" font-weight="600" fill="#111">{t}</text>"##,
        w = n(w),
        h = n(h),
        t = escape(title),
        x = 80.0,
    );
}

/// The plot area's frame, decade grid lines and minor ticks (minor ticks at 2..9
/// times each decade when the axis spans at most 8 decades).
fn frame(svg: &mut String, xa: &LogAxis, ya: &LogAxis, left: f64, right: f64, top: f64, bottom: f64) {
    for k in xa.lo..=xa.hi {
        let x = xa.pos(10f64.powi(k));
        let _ =
            write!(svg, r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#e6e6e6"/>"##, n(x), n(top), n(x), n(bottom));
    }
    for k in ya.lo..=ya.hi {
        let y = ya.pos(10f64.powi(k));
        let _ =
            write!(svg, r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#e6e6e6"/>"##, n(left), n(y), n(right), n(y));
    }
    for (axis, horizontal) in [(xa, true), (ya, false)] {
        if axis.hi - axis.lo > 8 {
            continue;
        }
        for k in axis.lo..axis.hi {
            for m in 2..=9 {
                let p = axis.pos(m as f64 * 10f64.powi(k));
                let _ = if horizontal {
                    write!(
                        svg,
                        r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#999"/>"##,
                        n(p),
                        n(bottom),
                        n(p),
                        n(bottom + 3.0)
                    )
                } else {
                    write!(
                        svg,
                        r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#999"/>"##,
                        n(left - 3.0),
                        n(p),
                        n(left),
                        n(p)
                    )
                };
            }
        }
    }
    let _ = write!(
        svg,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#555"/>"##,
        n(left),
        n(top),
        n(right - left),
        n(bottom - top)
    );
}

fn x_axis(svg: &mut String, xa: &LogAxis, bottom: f64, title: &str) {
    let step = xa.label_step();
    for k in xa.lo..=xa.hi {
        let x = xa.pos(10f64.powi(k));
        let _ = write!(
            svg,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#555"/>"##,
            n(x),
            n(bottom),
            n(x),
            n(bottom + 6.0)
        );
        if k.rem_euclid(step) == 0 {
            let _ = write!(
                svg,
                r##"<text x="{}" y="{}" text-anchor="middle" fill="#333">{}</text>"##,
                n(x),
                n(bottom + 19.0),
                decade_label(k)
            );
        }
    }
    let mid = (xa.p0 + xa.p1) / 2.0;
    let _ = write!(
        svg,
        r##"<text x="{}" y="{}" text-anchor="middle" font-size="12" fill="#222">{}</text>"##,
        n(mid),
        n(bottom + 40.0),
        escape(title)
    );
}

fn y_axis(svg: &mut String, ya: &LogAxis, left: f64, top: f64, bottom: f64, title: &str) {
    let step = ya.label_step();
    for k in ya.lo..=ya.hi {
        let y = ya.pos(10f64.powi(k));
        let _ = write!(
            svg,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#555"/>"##,
            n(left - 6.0),
            n(y),
            n(left),
            n(y)
        );
        if k.rem_euclid(step) == 0 {
            let _ = write!(
                svg,
                r##"<text x="{}" y="{}" text-anchor="end" fill="#333">{}</text>"##,
                n(left - 9.0),
                n(y + 4.0),
                decade_label(k)
            );
        }
    }
    let mid = (top + bottom) / 2.0;
    let _ = write!(
        svg,
        r##"<text transform="translate(20 {}) rotate(-90)" text-anchor="middle" font-size="12" fill="#222">{}</text>"##,
        n(mid),
        escape(title)
    );
}

/// An axis-aligned box in pixels.
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Rect {
    fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
}

/// Where a point's label goes.
struct Label {
    x: f64,
    y: f64,
    dy: f64,
    anchor_end: bool,
    rect: Rect,
}

/// Radius around a point that a label keeps clear of, px.
const POINT_CLEARANCE: f64 = 6.0;

/// Places a label beside its point: to the right first, then to the left, each at
/// the point's height and then stepping a line up and down, taking the first spot
/// that stays inside `xlim` × `ylim` and overlaps neither an earlier label nor
/// another point. Falls back to the right of the point at its height.
fn place_label(
    text: &str,
    px: f64,
    py: f64,
    points: &[(f64, f64)],
    placed: &[Rect],
    xlim: (f64, f64),
    ylim: (f64, f64),
) -> Label {
    let width = CHAR_W * text.chars().count() as f64;
    let make = |anchor_end: bool, dy: f64| {
        let y = py + 4.0 + dy;
        let x = if anchor_end { px - 9.0 } else { px + 9.0 };
        let (x0, x1) = if anchor_end { (x - width, x) } else { (x, x + width) };
        Label { x, y, dy, anchor_end, rect: Rect { x0, y0: y - 10.0, x1, y1: y + 3.0 } }
    };
    for anchor_end in [false, true] {
        for step in 0u8..8 {
            let dy = match step {
                0 => 0.0,
                s if s % 2 == 1 => -LINE_H * f64::from(s.div_ceil(2)),
                s => LINE_H * f64::from(s / 2),
            };
            let l = make(anchor_end, dy);
            let r = l.rect;
            let inside = r.x0 >= xlim.0 && r.x1 <= xlim.1 && r.y0 >= ylim.0 - 12.0 && r.y1 <= ylim.1 + 2.0;
            let clear_of_labels = placed.iter().all(|p| !p.overlaps(&r));
            let clear_of_points = points.iter().all(|&(qx, qy)| !point_box(qx, qy).overlaps(&r));
            if inside && clear_of_labels && clear_of_points {
                return l;
            }
        }
    }
    make(false, 0.0)
}

/// A spot for a note on the horizontal line at height `y` between `xlim.0` and
/// `xlim.1`: just above or just below the line, at its right end, left end or
/// middle, whichever first overlaps no placed label and no point.
fn free_spot(text: &str, y: f64, xlim: (f64, f64), points: &[(f64, f64)], placed: &[Rect]) -> Label {
    let width = CHAR_W * text.chars().count() as f64;
    let mid = (xlim.0 + xlim.1 - width) / 2.0;
    let mut first = None;
    for baseline in [y - 4.0, y + 13.0] {
        for (x0, anchor_end) in [(xlim.1 - 4.0 - width, true), (xlim.0 + 6.0, false), (mid, false)] {
            let rect = Rect { x0, y0: baseline - 10.0, x1: x0 + width, y1: baseline + 3.0 };
            let x = if anchor_end { x0 + width } else { x0 };
            let label = Label { x, y: baseline, dy: 0.0, anchor_end, rect };
            let clear = placed.iter().all(|p| !p.overlaps(&rect))
                && points.iter().all(|&(qx, qy)| !point_box(qx, qy).overlaps(&rect));
            if clear {
                return label;
            }
            first.get_or_insert(label);
        }
    }
    first.expect("at least one candidate")
}

/// The box a point keeps clear of labels.
fn point_box(x: f64, y: f64) -> Rect {
    Rect { x0: x - POINT_CLEARANCE, y0: y - POINT_CLEARANCE, x1: x + POINT_CLEARANCE, y1: y + POINT_CLEARANCE }
}

#[cfg(test)]
pub(crate) mod fixture {
    //! A hand-built summary: two engines, two query kinds, known numbers.

    use crate::case::Query;
    use crate::summary::{Dist, EngineInfo, EngineQueryStats, Provenance, Summary, Timing};

    /// A distribution of the given samples.
    pub(crate) fn dist(samples: &[f64]) -> Dist {
        let mut d = Dist::default();
        for &x in samples {
            d.add(x);
        }
        d
    }

    fn timing(median_ns: f64) -> Option<Timing> {
        Some(Timing { median_ns, min_ns: median_ns * 0.9, max_ns: median_ns * 1.2, reps: 5, queries: 100 })
    }

    /// Engines `fast<f32>` (20 ns, p99 1e-6) and `exact` (900 ns, p99 1e-15) on
    /// contact, and on intersect `fast<f32>` (30 ns, p99 1e-5) and `exact`
    /// (800 ns, every error zero).
    pub(crate) fn summary() -> Summary {
        let mut stats = Vec::new();
        for (engine, query, ns, err) in [
            ("fast<f32>", Query::Contact, 20.0, 1e-6),
            ("exact", Query::Contact, 900.0, 1e-15),
            ("fast<f32>", Query::Intersect, 30.0, 1e-5),
            ("exact", Query::Intersect, 800.0, 0.0),
        ] {
            let samples = vec![err; 100];
            stats.push(EngineQueryStats {
                engine: engine.into(),
                query: Some(query),
                cases: 100,
                agree: 97,
                disagree: 1,
                borderline: 1,
                known: 1,
                false_positives: 1,
                point_rel: dist(&samples),
                depth_rel: dist(&samples),
                normal_rad: dist(&samples),
                headline: dist(&samples),
                timing: timing(ns),
                ..Default::default()
            });
        }
        Summary {
            format: "crashtest-summary/1".into(),
            provenance: Provenance {
                crashtest: "0.1.0".into(),
                commit: Some("abc1234-dirty".into()),
                rustc: "rustc 1.95.0".into(),
                profile: "release".into(),
                machine: "linux x86_64, 2 cores".into(),
                engines: vec![
                    EngineInfo {
                        name: "fast<f32>".into(),
                        version: "collide (this commit), f32".into(),
                        process: None,
                    },
                    EngineInfo { name: "exact".into(), version: "referee".into(), process: None },
                ],
                missing_engines: vec![("absent<peer>".into(), "not installed; install it with `x & y`".into())],
                seed: 42,
                peers: None,
                ulps: None,
                cases_per_query: 100,
                full_range_per_query: 0,
                only: None,
                shards: vec![],
                fixture_cases: 12,
                random_cases: 200,
                wall_seconds: 3.25,
                phases: vec![("judging".into(), 3.0)],
                referee_stages: Vec::new(),
                started: "2026-01-01T00:00:00Z".into(),
                speed_source: None,
            },
            stats,
            full_range: Vec::new(),
            discrepancies: 3,
            throughput: vec![("fast<f32>".into(), 1.5e6), ("all".into(), 2.0e4)],
            growth: Vec::new(),
        }
    }

    /// A summary shaped like a real campaign's (six engines, four query kinds,
    /// spread-out errors from a fixed linear congruential sequence), to exercise
    /// label placement and curves with many bins.
    pub(crate) fn realistic() -> Summary {
        let engines: [(&str, f64, f64, f64); 6] = [
            // name, ns per query, typical error, fraction of exact zeros
            ("collide-f64/robust", 38.0, 2e-16, 0.3),
            ("collide-f64/lecture", 21.0, 4e-15, 0.2),
            ("collide-f32/lecture", 17.0, 3e-7, 0.05),
            ("parry3d-f64", 55.0, 6e-16, 0.25),
            ("parry3d", 49.0, 2e-7, 0.05),
            ("referee", 41000.0, 0.0, 1.0),
        ];
        let queries = [Query::Contact, Query::Intersect, Query::Barycentric, Query::Overlap];
        let mut state: u64 = 0x2545_F491_4F6C_DD1D;
        let mut uniform = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut stats = Vec::new();
        for (e, &(name, ns, typical, zeros)) in engines.iter().enumerate() {
            for (qi, &query) in queries.iter().enumerate() {
                let mut head = Dist::default();
                let mut point = Dist::default();
                let mut bary = Dist::default();
                let cases = 10_000u64;
                let mut misses = 0;
                for _ in 0..cases {
                    let u = uniform();
                    let x = if u < zeros {
                        0.0
                    } else if query == Query::Overlap {
                        if uniform() < 0.002 * e as f64 { 1.0 } else { 0.0 }
                    } else {
                        // Log-uniform over four decades, with a heavier tail.
                        let v = uniform();
                        typical * 10f64.powf(4.0 * v * v - 1.0)
                    };
                    if x >= 1.0 {
                        misses += 1;
                    }
                    head.add(x);
                    if query == Query::Barycentric {
                        bary.add(x);
                    } else if query != Query::Overlap {
                        point.add(x);
                    }
                }
                let t = ns * (1.0 + 0.4 * qi as f64);
                stats.push(EngineQueryStats {
                    engine: name.into(),
                    query: Some(query),
                    cases,
                    agree: cases - misses,
                    false_negatives: misses,
                    point_rel: point,
                    barycentric: bary,
                    headline: head,
                    timing: Some(Timing { median_ns: t, min_ns: t * 0.97, max_ns: t * 1.08, reps: 7, queries: cases }),
                    ..Default::default()
                });
            }
        }
        let mut s = summary();
        s.provenance.engines = engines
            .iter()
            .map(|e| EngineInfo { name: e.0.into(), version: format!("{} (sample)", e.0), process: None })
            .collect();
        s.stats = stats;
        s.throughput = engines.iter().map(|e| (e.0.to_string(), 1e9 / e.1)).collect();
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::Timing;

    /// Checks that every element opened is closed, in order (the SVG has no
    /// comments, CDATA or processing instructions), and returns the element names
    /// in document order.
    fn balanced_tags(svg: &str) -> Vec<String> {
        let mut stack: Vec<String> = Vec::new();
        let mut names = Vec::new();
        let mut rest = svg;
        while let Some(i) = rest.find('<') {
            let j = rest[i..].find('>').expect("unclosed '<'") + i;
            let tag = &rest[i + 1..j];
            if let Some(name) = tag.strip_prefix('/') {
                assert_eq!(stack.pop().as_deref(), Some(name), "mismatched </{name}>");
            } else {
                let name: String = tag.chars().take_while(|c| c.is_ascii_alphanumeric()).collect();
                assert!(!name.is_empty(), "bad tag <{tag}>");
                names.push(name.clone());
                if !tag.ends_with('/') {
                    stack.push(name);
                }
            }
            rest = &rest[j + 1..];
        }
        assert!(stack.is_empty(), "unclosed elements: {stack:?}");
        names
    }

    #[test]
    fn pareto_front_keeps_exactly_the_non_dominated_points() {
        // Hand-derived: (1,9) fastest; (2,5) better error than it; (3,6) is beaten
        // by (2,5) in both; (4,1) best error; (5,1) beaten by (4,1) on time only;
        // (4,1) duplicated at index 5 stays (equal points do not dominate).
        let pts = [(1.0, 9.0), (2.0, 5.0), (3.0, 6.0), (4.0, 1.0), (5.0, 1.0), (4.0, 1.0)];
        assert_eq!(pareto_front(&pts), vec![0, 1, 3, 5]);
    }

    #[test]
    fn pareto_front_handles_zero_error_and_nan() {
        let pts = [(10.0, 0.0), (1.0, 1e-3), (f64::NAN, 0.0), (20.0, 0.0)];
        assert_eq!(pareto_front(&pts), vec![1, 0]);
        assert!(pareto_front(&[]).is_empty());
    }

    #[test]
    fn zero_floor_stays_below_every_positive_error() {
        // Relative slack for comparing a returned power of ten with the constant.
        const SAME_REL: f64 = 1e-12;
        assert!((zero_floor(&[1e-6, 1e-15]) / ZERO_FLOOR - 1.0).abs() < SAME_REL, "default floor");
        assert!(zero_floor(&[3e-19]) < 3e-19, "floor must lie under the smallest error");
        assert!(zero_floor(&[1e-18]) < 1e-18, "floor must lie under an error at the floor");
    }

    #[test]
    fn accuracy_speed_has_a_point_per_engine_log_ticks_and_the_front() {
        let s = fixture::summary();
        let svg = accuracy_speed(&s, Query::Contact).expect("both engines are timed");
        let tags = balanced_tags(&svg);
        assert_eq!(tags.iter().filter(|t| *t == "circle").count(), 2, "one circle per engine");
        assert!(svg.contains(">1e-6<") && svg.contains(">1e-15<"), "decade labels of the errors");
        assert!(svg.contains(">10<") && svg.contains(">1000<"), "decade labels of the times");
        assert!(svg.contains("fast&lt;f32&gt;"), "engine name escaped: {svg}");
        assert!(!svg.contains("fast<f32>"), "raw '<' in a label");
        // Neither engine beats the other in both: both on the front, joined by one
        // step line of three vertices.
        assert_eq!(svg.matches("<polyline").count(), 1);
        assert!(!svg.contains("p99 = 0"), "no zero error here");
    }

    #[test]
    fn accuracy_speed_outlines_exactly_the_front() {
        // A third engine, slower and less accurate than `fast<f32>`: dominated.
        let mut s = fixture::summary();
        let mut slow = s.stats[0].clone();
        slow.engine = "slow".into();
        slow.headline = fixture::dist(&[1e-3; 100]);
        slow.timing = Some(Timing { median_ns: 50.0, ..Timing::default() });
        s.stats.push(slow);
        let svg = accuracy_speed(&s, Query::Contact).expect("timed");
        balanced_tags(&svg);
        assert_eq!(svg.matches(r##"stroke="#222" stroke-width="1.2""##).count(), 2, "two on the front");
        assert_eq!(svg.matches(r##"stroke="#fff" stroke-width="1.2""##).count(), 1, "one off it");
        let line = svg.split("<polyline points=\"").nth(1).expect("front line");
        let vertices = line.split('"').next().expect("points").split(' ').count();
        assert_eq!(vertices, 3, "two front points joined by one step: {line}");
    }

    #[test]
    fn labels_of_a_crowded_chart_do_not_overlap() {
        let s = fixture::realistic();
        for c in all(&s) {
            balanced_tags(&c.svg);
        }
        // Re-run the placement the chart does and check the boxes pairwise.
        let pts: Vec<(f64, f64)> = (0..6).map(|i| (300.0 + 4.0 * i as f64, 200.0 + 3.0 * i as f64)).collect();
        let mut placed: Vec<Rect> = Vec::new();
        for (i, &(x, y)) in pts.iter().enumerate() {
            let l = place_label(&format!("engine-{i}/name"), x, y, &pts, &placed, (80.0, 756.0), (50.0, 430.0));
            assert!(placed.iter().all(|p| !p.overlaps(&l.rect)), "label {i} overlaps");
            placed.push(l.rect);
        }
    }

    #[test]
    fn accuracy_speed_marks_a_zero_p99_at_the_floor() {
        let s = fixture::summary();
        let svg = accuracy_speed(&s, Query::Intersect).expect("timed");
        balanced_tags(&svg);
        assert!(svg.contains("p99 = 0 (exact), drawn at 1e-18"), "{svg}");
        assert!(svg.contains(r##"fill="#fff" stroke="#d62728""##), "hollow marker for the exact engine");
        assert!(svg.contains(">1e-18<"), "floor decade labelled");
    }

    #[test]
    fn accuracy_speed_is_none_without_timing() {
        let mut s = fixture::summary();
        for st in &mut s.stats {
            st.timing = None;
        }
        assert!(accuracy_speed(&s, Query::Contact).is_none());
        assert!(accuracy_speed(&fixture::summary(), Query::Toi).is_none(), "query absent");
    }

    #[test]
    fn error_distribution_draws_one_line_per_engine_with_errors() {
        let s = fixture::summary();
        let svg = error_distribution(&s, Query::Contact).expect("errors measured");
        balanced_tags(&svg);
        assert_eq!(svg.matches("<polyline").count(), 2, "one curve per engine");
        assert!(svg.contains("fast&lt;f32&gt;") && svg.contains(">exact<"), "legend");
        let svg = error_distribution(&s, Query::Intersect).expect("one engine has errors");
        assert_eq!(svg.matches("<polyline").count(), 1);
        assert!(svg.contains("every error exactly 0): exact"), "{svg}");
    }

    #[test]
    fn ccdf_runs_from_the_nonzero_fraction_down_to_the_maximum() {
        let d = fixture::dist(&[0.0, 0.0, 1e-3, 1e-3, 5e-2]);
        let c = ccdf(&d);
        let first = c.first().expect("vertices");
        assert!((first.1 - 0.6).abs() < 1e-12, "3 of 5 samples are non-zero: {c:?}");
        let last = c.last().expect("vertices");
        assert!((last.0 / 5e-2 - 1.0).abs() < 1e-12 && last.1 == 0.0, "ends at max: {c:?}");
        assert!(c.windows(2).all(|w| w[1].0 >= w[0].0 && w[1].1 <= w[0].1), "monotone: {c:?}");
    }

    #[test]
    fn charts_are_byte_identical_for_identical_input() {
        let a = all(&fixture::summary());
        let b = all(&fixture::summary());
        assert_eq!(a.len(), 4, "two charts per query kind");
        assert_eq!(a, b);
        assert_eq!(a[0].file, "contact-accuracy-speed.svg");
    }
}
