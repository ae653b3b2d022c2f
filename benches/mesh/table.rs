//! The table printed at the end of a mesh run (and written to
//! `target/criterion/crashtest-mesh-table.md`): criterion's estimates of this
//! run as time per query and per build, with the ratios collide / parry.
//!
//! Reads criterion's `estimates.json` files through `benches/shared`, as the
//! other tables do.

use std::fmt::Write as _;

use std::time::SystemTime;

pub use super::criterion_files::{cell, criterion_dir, ns_per, ratio};

/// One engine of a table: benchmark id and heading.
pub struct Column {
    /// criterion's benchmark id.
    pub id: &'static str,
    /// The column's heading.
    pub heading: &'static str,
}

/// One row: a criterion group, elements per iteration, a heading, the unit
/// divisor (1 for ns, 1e6 for ms) and the unit's name.
pub struct Row {
    /// criterion's group.
    pub group: &'static str,
    /// The row's heading.
    pub label: String,
    /// Elements (queries, builds) per iteration.
    pub per_iter: usize,
    /// Nanoseconds per displayed unit.
    pub unit_ns: f64,
    /// The unit's name.
    pub unit: &'static str,
}

/// One speed target: `numerator / denominator ≤ target` in one group.
pub struct Target {
    /// The group.
    pub group: &'static str,
    /// Elements per iteration.
    pub per_iter: usize,
    /// What is compared, for the reader.
    pub what: String,
    /// Benchmark ids of the numerator and the denominator.
    pub ids: (&'static str, &'static str),
    /// The largest ratio that meets it.
    pub target: f64,
}

/// Renders one table: a row per group, a column per engine, then the ratios
/// of `ratios` (numerator id, denominator id, heading).
pub fn render(
    title: &str,
    intro: &str,
    columns: &[Column],
    rows: &[Row],
    ratios: &[(&str, &str, &str)],
    since: SystemTime,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## {title}\n\n{intro} {}\n", super::criterion_files::PAIRED_MARK);
    let _ = write!(s, "| | unit |");
    for c in columns {
        let _ = write!(s, " {} |", c.heading);
    }
    for r in ratios {
        let _ = write!(s, " {} |", r.2);
    }
    let _ = write!(s, "\n| --- | --- |");
    for _ in columns.iter().map(|_| ()).chain(ratios.iter().map(|_| ())) {
        let _ = write!(s, " ---: |");
    }
    let _ = writeln!(s);
    for r in rows {
        let get = |id: &str| ns_per(r.group, id, r.per_iter, since);
        let _ = write!(s, "| {} | {} |", r.label, r.unit);
        for c in columns {
            let _ = write!(s, " {} |", cell(get(c.id).map(|v| v / r.unit_ns)));
        }
        for (num, den, _) in ratios {
            let paired = super::criterion_files::paired_ratio(r.group, num, den);
            let _ = write!(s, " {} |", super::criterion_files::ratio_cell(ratio(get(num), get(den)), paired));
        }
        let _ = writeln!(s);
    }
    s
}

/// Renders the targets with their verdicts.
pub fn render_targets(targets: &[Target], since: SystemTime) -> String {
    use super::criterion_files::{judged, paired_ratio, target_row, targets_heading, verdict};
    let mut s = targets_heading();
    for t in targets {
        let r = ratio(ns_per(t.group, t.ids.0, t.per_iter, since), ns_per(t.group, t.ids.1, t.per_iter, since));
        let paired = paired_ratio(t.group, t.ids.0, t.ids.1);
        s.push_str(&target_row(&t.what, t.target, r, paired, verdict(judged(r, paired), t.target)));
    }
    s
}

/// Prints the report and writes it beside criterion's files.
pub fn publish(report: &str) {
    println!("\n{report}");
    let path = criterion_dir().join("crashtest-mesh-table.md");
    match std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, report)) {
        Ok(()) => println!("(written to {})", path.display()),
        Err(e) => eprintln!("could not write {}: {e}", path.display()),
    }
}
