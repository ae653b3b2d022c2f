//! Line charts as SVG text, shared by the report's sections (dynamics,
//! stability sweeps, the scene's needs, time of impact).
//!
//! Pure: the same series give byte-identical SVG (coordinates printed with one
//! decimal, no element ids, so any number of charts inline in one page).

use super::xml::escape;
use std::fmt::Write;

/// One polyline of a chart.
pub struct Line {
    /// Its name in the legend.
    pub name: String,
    /// Its colour and dash pattern (cycled).
    pub style: usize,
    /// Its points, in data coordinates; those an axis cannot draw are skipped.
    pub points: Vec<(f64, f64)>,
    /// Parameter values (x) where this series failed — NaN, a caught panic, a
    /// wrong classification: drawn as × marks in the band above the plot, in
    /// the series' colour, so a failure is never mistaken for a small error.
    pub failures: Vec<f64>,
}

/// An axis: linear with a tick step, or logarithmic over whole decades.
pub enum Axis {
    /// Linear from `min` to `max`, a tick every `step`.
    Linear {
        /// Left or bottom end.
        min: f64,
        /// Right or top end.
        max: f64,
        /// Tick spacing.
        step: f64,
    },
    /// Logarithmic from `10^lo` to `10^hi`.
    Log {
        /// Lowest decade.
        lo: i32,
        /// Highest decade.
        hi: i32,
    },
}

impl Axis {
    /// Whole decades covering the positive finite values (one decade round 1
    /// when there are none).
    pub fn log_covering(values: impl Iterator<Item = f64>) -> Axis {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
            lo = lo.min(v.log10());
            hi = hi.max(v.log10());
        }
        if lo.is_finite() {
            let (lo, hi) = (lo.floor() as i32, hi.ceil() as i32);
            Axis::Log { lo, hi: hi.max(lo + 1) }
        } else {
            Axis::Log { lo: 0, hi: 1 }
        }
    }

    /// Position in `[0, 1]` along the axis, `None` when the value cannot be drawn.
    pub fn frac(&self, v: f64) -> Option<f64> {
        match *self {
            Axis::Linear { min, max, .. } => v.is_finite().then(|| ((v - min) / (max - min)).clamp(0.0, 1.0)),
            Axis::Log { lo, hi } => {
                (v > 0.0 && v.is_finite()).then(|| ((v.log10() - lo as f64) / (hi - lo) as f64).clamp(0.0, 1.0))
            }
        }
    }

    /// Tick values and labels.
    pub fn ticks(&self) -> Vec<(f64, String)> {
        match *self {
            Axis::Linear { min, max, step } => {
                let n = ((max - min) / step).round() as i64;
                (0..=n).map(|i| min + i as f64 * step).map(|v| (v, format!("{v}"))).collect()
            }
            Axis::Log { lo, hi } => (lo..=hi)
                .map(|k| {
                    // Every decade gets a grid line; labels thin out to at
                    // most about ten so that wide sweeps (17 decades and
                    // more) keep them legible.
                    let every = ((hi - lo) as f64 / MAX_LOG_LABELS).ceil().max(1.0) as i32;
                    if (k - lo) % every != 0 {
                        return (10f64.powi(k), String::new());
                    }
                    let label = match k {
                        0 => "1".to_string(),
                        1 => "10".into(),
                        2 => "100".into(),
                        3 => "1000".into(),
                        _ => format!("1e{k}"),
                    };
                    (10f64.powi(k), label)
                })
                .collect(),
        }
    }
}

/// Most labelled decades on a log axis: the x axis is 420 px wide and a label
/// such as `1e-16` takes about 35 px at 11 px type.
const MAX_LOG_LABELS: f64 = 10.0;

/// Colour-blind-aware palette (as the report's other charts use).
pub const PALETTE: [&str; 8] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#e08a0b", "#17becf", "#8c564b", "#e377c2"];
/// Dash patterns, cycled with the palette.
pub const DASHES: [&str; 3] = ["", "6 3", "2 2"];

/// A pixel coordinate with one decimal (and no negative zero).
pub fn px(x: f64) -> String {
    format!("{:.1}", x + 0.0)
}

/// A line chart as SVG text: frame, ticks, one polyline with markers per
/// series, a legend at the right. `offset` shifts series `i` of `n` by
/// `(i − (n − 1)/2) · offset` px vertically (0 for none).
pub fn line_chart(
    title: &str,
    x_label: &str,
    y_label: &str,
    xa: Axis,
    ya: Axis,
    series: &[Line],
    offset: f64,
) -> String {
    const W: f64 = 760.0;
    const H: f64 = 440.0;
    let (left, right, top, bottom) = (80.0, 500.0, 50.0, 360.0);
    let x = |v: f64| xa.frac(v).map(|f| left + f * (right - left));
    let y = |v: f64| ya.frac(v).map(|f| bottom - f * (bottom - top));
    let mut s = String::new();
    let _ = write!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}" role="img" aria-label="{t}" font-family="system-ui, -apple-system, 'Segoe UI', Roboto, 'Helvetica Neue', Arial, sans-serif" font-size="11"><title>{t}</title><rect x="0" y="0" width="{w}" height="{h}" fill="#fff"/><text x="{left}" y="28" font-size="15" font-weight="600" fill="#111">{t}</text>"##,
        w = W,
        h = H,
        t = escape(title),
    );
    for (v, label) in xa.ticks() {
        if let Some(px_x) = x(v) {
            let _ = write!(
                s,
                r##"<line x1="{a}" y1="{t}" x2="{a}" y2="{b}" stroke="#e6e6e6"/><text x="{a}" y="{l}" text-anchor="middle" fill="#333">{label}</text>"##,
                a = px(px_x),
                t = px(top),
                b = px(bottom),
                l = px(bottom + 18.0),
            );
        }
    }
    for (v, label) in ya.ticks() {
        if let Some(px_y) = y(v) {
            let _ = write!(
                s,
                r##"<line x1="{l}" y1="{a}" x2="{r}" y2="{a}" stroke="#e6e6e6"/><text x="{tx}" y="{ty}" text-anchor="end" fill="#333">{label}</text>"##,
                a = px(px_y),
                l = px(left),
                r = px(right),
                tx = px(left - 8.0),
                ty = px(px_y + 4.0),
            );
        }
    }
    let _ = write!(
        s,
        r##"<rect x="{l}" y="{t}" width="{w}" height="{h}" fill="none" stroke="#555"/><text x="{mx}" y="{xb}" text-anchor="middle" font-size="12" fill="#222">{xl}</text><text x="18" y="{my}" text-anchor="middle" font-size="12" fill="#222" transform="rotate(-90 18 {my})">{yl}</text>"##,
        l = px(left),
        t = px(top),
        w = px(right - left),
        h = px(bottom - top),
        mx = px((left + right) / 2.0),
        xb = px(bottom + 40.0),
        my = px((top + bottom) / 2.0),
        xl = escape(x_label),
        yl = escape(y_label),
    );
    let n = series.len() as f64;
    for (i, line) in series.iter().enumerate() {
        let color = PALETTE[line.style % PALETTE.len()];
        let dash = DASHES[line.style % DASHES.len()];
        let dash_attr = if dash.is_empty() { String::new() } else { format!(r#" stroke-dasharray="{dash}""#) };
        let shift = (i as f64 - (n - 1.0) / 2.0) * offset;
        let pts: Vec<(f64, f64)> = line.points.iter().filter_map(|&(a, b)| Some((x(a)?, y(b)? + shift))).collect();
        if pts.len() > 1 {
            let path: Vec<String> = pts.iter().map(|(a, b)| format!("{},{}", px(*a), px(*b))).collect();
            let _ = write!(
                s,
                r##"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1.8"{dash_attr}/>"##,
                path.join(" ")
            );
        }
        for (a, b) in &pts {
            let _ = write!(s, r##"<circle cx="{}" cy="{}" r="3" fill="{color}"/>"##, px(*a), px(*b));
        }
        for fx in line.failures.iter().filter_map(|&v| x(v)) {
            // A × in the failure band above the plot, one row per series.
            let fy = top - 6.0 - 4.0 * (i % 3) as f64;
            let _ = write!(
                s,
                r##"<path d="M{a},{b}L{c},{d}M{a},{d}L{c},{b}" stroke="{color}" stroke-width="1.6"/>"##,
                a = px(fx - 3.5),
                b = px(fy - 3.5),
                c = px(fx + 3.5),
                d = px(fy + 3.5),
            );
        }
        let ly = top + 14.0 + 18.0 * i as f64;
        let _ = write!(
            s,
            r##"<line x1="{x1}" y1="{y}" x2="{x2}" y2="{y}" stroke="{color}" stroke-width="2"{dash_attr}/><text x="{tx}" y="{ty}" fill="#222">{name}</text>"##,
            x1 = px(right + 16.0),
            x2 = px(right + 40.0),
            y = px(ly),
            tx = px(right + 46.0),
            ty = px(ly + 4.0),
            name = escape(&line.name),
        );
    }
    if series.iter().any(|l| !l.failures.is_empty()) {
        let _ = write!(
            s,
            r##"<text x="{}" y="{}" fill="#666">× above the plot: a failure at that value (NaN, panic or wrong classification)</text>"##,
            px(left),
            px(H - 24.0)
        );
    }
    if offset != 0.0 {
        let _ = write!(
            s,
            r##"<text x="{}" y="{}" fill="#666">lines offset by {offset} px each so that equal values stay visible</text>"##,
            px(left),
            px(H - 8.0)
        );
    }
    s.push_str("</svg>");
    s
}
