//! The dynamics section's rendering: its Markdown, charts and section, from
//! the measured data alone.

use super::data::{
    ApexSeries, BOUNCES, DynamicsReport, PHASES, RESTITUTIONS, SPEEDS, THICKNESSES, TUNNEL_RADIUS, TUNNEL_RESTITUTION,
    TUNNEL_STEPS, methods_of, vec_str,
};
use crate::render::plot::{Axis, Line, line_chart};
use std::fmt::Write;

/// One chart of the dynamics section.
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicsChart {
    /// Its caption.
    pub title: String,
    /// Its file name inside the report's `charts/` folder.
    pub file: String,
    /// The SVG document (no XML declaration, no element ids).
    pub svg: String,
}

fn file_number(x: f64) -> String {
    format!("{x}").replace('.', "_")
}

/// The section's Markdown: settings, apex tables, pass-through tables, the
/// two-ball velocities and rapier's deviations; charts are linked as
/// `charts/<file>` ([`charts`]).
pub fn markdown(r: &DynamicsReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## Dynamics\n");
    let _ = writeln!(
        s,
        "Stepped worlds at a fixed dt: {} and worlds of our own built on collide (time of impact + one \
         impulse per impact), against the analytic laws. rapier's settings, every one:\n",
        r.rapier
    );
    let _ = writeln!(s, "| setting | value |\n| --- | --- |");
    for e in &r.settings {
        let _ = writeln!(s, "| {} | {} |", e.name, e.value);
    }
    let b = &r.bounce_design;
    let _ = writeln!(
        s,
        "\n### Bounces\n\nA ball of radius {} m released at rest {} m above the ground, {} s simulated. Apex \
         heights of the ball's lowest point (m) after each impact; `—` where the samples no longer resolve a \
         flight (shorter than about two steps, or at rest). The analytic law is h_k = e^(2k) h_0.\n",
        b.radius, b.drop_height, b.duration
    );
    for &e in &RESTITUTIONS {
        let series: Vec<&ApexSeries> = r.bounces.iter().filter(|a| a.restitution.total_cmp(&e).is_eq()).collect();
        let _ = writeln!(s, "**e = {e}**\n");
        let _ = write!(s, "| bounce |");
        for a in &series {
            let _ = write!(s, " {} |", a.engine);
        }
        let _ = write!(s, "\n| --- |");
        for _ in &series {
            let _ = write!(s, " ---: |");
        }
        let _ = writeln!(s);
        for k in 0..BOUNCES {
            let _ = write!(s, "| {} |", k + 1);
            for a in &series {
                match a.apexes.get(k) {
                    Some(h) => {
                        let _ = write!(s, " {h:.6} |");
                    }
                    None => {
                        let _ = write!(s, " — |");
                    }
                }
            }
            let _ = writeln!(s);
        }
        if e == 0.0 {
            let _ = write!(s, "| highest after landing |");
            for a in &series {
                match a.highest_after_landing {
                    Some(h) => {
                        let _ = write!(s, " {h:.3e} |");
                    }
                    None => {
                        let _ = write!(s, " 0 |");
                    }
                }
            }
            let _ = writeln!(s);
        } else {
            let _ = writeln!(s, "\n![apex heights, e = {e}](charts/dynamics-apex-e{}.svg)", file_number(e));
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(
        s,
        "### Tunnelling\n\nA ball of radius {TUNNEL_RADIUS} m shot along x at a wall, restitution \
         {TUNNEL_RESTITUTION}, {PHASES} start phases per speed (the unobstructed touch falls at 2 + (j + ½)/{PHASES} \
         steps), {TUNNEL_STEPS} steps; a run passes when the ball ends beyond the wall's mid-plane. Passes out of \
         {PHASES}:\n"
    );
    let methods = methods_of(r);
    for &w in &THICKNESSES {
        let _ = writeln!(s, "**wall {w} m**\n");
        let _ = write!(s, "| speed (m/s) |");
        for m in &methods {
            let _ = write!(s, " {m} |");
        }
        let _ = write!(s, "\n| ---: |");
        for _ in &methods {
            let _ = write!(s, " ---: |");
        }
        let _ = writeln!(s);
        for &v in &SPEEDS {
            let _ = write!(s, "| {v} |");
            for m in &methods {
                let row = r
                    .tunnel
                    .iter()
                    .find(|p| &p.method == m && p.thickness.total_cmp(&w).is_eq() && p.speed.total_cmp(&v).is_eq());
                let _ = write!(s, " {} |", row.map_or("—".to_string(), |p| p.passed.to_string()));
            }
            let _ = writeln!(s);
        }
        let _ = writeln!(s, "\n![pass-through, wall {w} m](charts/dynamics-tunnel-w{}.svg)\n", file_number(w));
    }
    let _ = writeln!(
        s,
        "### Two balls\n\nVelocities after the impact (m/s); error: largest velocity difference from the analytic \
         answer over the largest initial speed; energy: relative change of the kinetic energy.\n"
    );
    let _ = writeln!(s, "| scene | engine | a | b | error | energy |\n| --- | --- | --- | --- | ---: | ---: |");
    for p in &r.pairs {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.3e} | {:+.3e} |",
            p.scene,
            p.engine,
            vec_str(&p.velocity_a),
            vec_str(&p.velocity_b),
            p.error,
            p.energy_change
        );
    }
    for e in &r.engine_settings {
        let _ = writeln!(
            s,
            "\n### {}: its worlds\n\nStepped through the engine protocol (`world` messages); the settings it used, \
             as it echoed them:\n",
            e.engine
        );
        let _ = writeln!(s, "| setting | value |\n| --- | --- |");
        for x in &e.settings {
            let _ = writeln!(s, "| {} | {} |", x.name, x.value);
        }
    }
    if !r.world_failures.is_empty() {
        let _ = writeln!(s, "\n### Worlds not stepped\n\n| engine | world | why |\n| --- | --- | --- |");
        for f in &r.world_failures {
            let _ = writeln!(s, "| {} | {} | {} |", f.engine, f.world, f.reason);
        }
    }
    let _ = writeln!(s, "\n### rapier against the laws\n\nReported as they are, not corrected:\n");
    if r.deviations.is_empty() {
        let _ = writeln!(s, "None.");
    } else {
        let _ = writeln!(s, "| experiment | case | analytic | rapier | difference |\n| --- | --- | --- | --- | --- |");
        for d in &r.deviations {
            let _ = writeln!(s, "| {} | {} | {} | {} | {} |", d.experiment, d.case, d.analytic, d.rapier, d.difference);
        }
    }
    s
}

/// The dynamics section of a report: its Markdown (also shown folded in the
/// page), its charts, and the whole [`DynamicsReport`] as `dynamics.json`.
pub fn section(r: &DynamicsReport) -> crate::render::section::Section {
    use crate::render::section::{Section, SectionChart};
    let md = markdown(r);
    Section {
        id: "dynamics".into(),
        title: "Dynamics: bounces, tunneling, two balls".into(),
        html: format!(
            "<details><summary>Tables (as in summary.md)</summary><pre>{}</pre></details>\n",
            crate::render::html::escape(&md)
        ),
        markdown: md,
        charts: charts(r).into_iter().map(|c| SectionChart { title: c.title, file: c.file, svg: c.svg }).collect(),
        data: serde_json::to_value(r).unwrap_or_else(|e| serde_json::Value::String(format!("unserializable: {e}"))),
    }
}

/// The section's charts: apex heights per bounce per engine for each
/// restitution above 0 (log y), and pass-throughs against speed per method for
/// each wall thickness (log x).
pub fn charts(r: &DynamicsReport) -> Vec<DynamicsChart> {
    let mut out = Vec::new();
    for &e in RESTITUTIONS.iter().filter(|e| **e > 0.0) {
        let series: Vec<Line> = r
            .bounces
            .iter()
            .filter(|a| a.restitution.total_cmp(&e).is_eq())
            .enumerate()
            .map(|(i, a)| Line {
                name: a.engine.clone(),
                style: i,
                points: std::iter::once((0.0, r.bounce_design.drop_height))
                    .chain(a.apexes.iter().enumerate().map(|(k, h)| ((k + 1) as f64, *h)))
                    .collect(),
                failures: Vec::new(),
            })
            .collect();
        let title = format!("Apex height per bounce, e = {e}");
        out.push(DynamicsChart {
            svg: line_chart(
                &title,
                "bounce",
                "apex height (m)",
                Axis::Linear { min: 0.0, max: BOUNCES as f64, step: 1.0 },
                Axis::log_covering(series.iter().flat_map(|l| l.points.iter().map(|p| p.1))),
                &series,
                0.0,
            ),
            file: format!("dynamics-apex-e{}.svg", file_number(e)),
            title,
        });
    }
    for &w in &THICKNESSES {
        let series: Vec<Line> = methods_of(r)
            .into_iter()
            .enumerate()
            .map(|(i, m)| Line {
                points: r
                    .tunnel
                    .iter()
                    .filter(|p| p.method == m && p.thickness.total_cmp(&w).is_eq())
                    .map(|p| (p.speed, p.passed as f64 / p.runs.max(1) as f64))
                    .collect(),
                name: m,
                style: i,
                failures: Vec::new(),
            })
            .collect();
        let title = format!("Pass-through against speed, wall {w} m");
        out.push(DynamicsChart {
            svg: line_chart(
                &title,
                "speed (m/s)",
                "fraction of runs passing through",
                Axis::log_covering(SPEEDS.iter().copied()),
                Axis::Linear { min: 0.0, max: 1.0, step: 0.25 },
                &series,
                LINE_OFFSET_PX,
            ),
            file: format!("dynamics-tunnel-w{}.svg", file_number(w)),
            title,
        });
    }
    out
}

/// Vertical offset between the lines of a pass-through chart, px: lines at the
/// same value (most sit at 0 or 1) would hide each other, so each is shifted by
/// `(i − (n − 1)/2) ·` this; the caption says so. Under 1 % of the axis.
const LINE_OFFSET_PX: f64 = 2.5;
