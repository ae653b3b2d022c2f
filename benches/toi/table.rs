//! The table printed at the end of a toi run (and written to
//! `target/criterion/crashtest-toi-table.md`): criterion's estimates of this
//! run as nanoseconds per query, with the ratios the speed target is stated in.
//!
//! Reads criterion's `estimates.json` files through `benches/shared`, as the
//! other tables do.

use std::fmt::Write as _;

use std::time::SystemTime;

pub use super::criterion_files::{cell, criterion_dir, ns_per, ratio};

/// The engines of the table: criterion's benchmark id and the column's heading.
pub const ENGINES: [(&str, &str); 8] = [
    ("collide_robust_f64", "collide robust f64"),
    ("collide_robust_f32", "collide robust f32"),
    ("textbook_f64", "textbook closed form f64, no checks"),
    ("collide_halving_f64", "collide halving to 1e-12 f64"),
    ("parry64", "parry3d-f64 cast_shapes"),
    ("parry32", "parry3d cast_shapes"),
    ("parry64_adapter", "parry3d-f64 via adapter"),
    ("parry32_adapter", "parry3d via adapter"),
];

/// One pair of shapes: criterion's group, its heading, queries per iteration,
/// the robust method's name and the hit fraction.
pub struct Row {
    /// criterion's group name.
    pub group: &'static str,
    /// The row's heading.
    pub label: &'static str,
    /// collide's robust method on it.
    pub robust: &'static str,
    /// Queries per iteration (the cases).
    pub per_iter: usize,
    /// Fraction of the cases with an impact (the referee's classification is
    /// collide's robust answer's, up to borderline cases).
    pub hits: f64,
}

/// One target: `numerator / denominator ≤ target` on a group.
pub struct Target {
    /// Group.
    pub group: &'static str,
    /// What is compared.
    pub what: &'static str,
    /// Benchmark ids of the numerator and the denominator.
    pub ids: (&'static str, &'static str),
    /// Largest ratio that meets it.
    pub target: f64,
}

/// The whole table as Markdown.
pub fn render(rows: &[Row], targets: &[Target], seed: u64, since: SystemTime) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# crashtest speed: time of impact, collide against parry, one run\n");
    let _ = writeln!(
        s,
        "Nanoseconds per query (criterion's slope estimate divided by the cases per iteration; `—`: not run). \
         The same pre-generated cases for every engine (seed {seed:#x}, the campaign's toi generators and mix: \
         hits, misses, grazing, overlapping, tunneling). collide robust: the closed form (sphere–sphere, \
         sphere–plane) or conservative advancement (sphere–triangle); halving: the lecture's, to a bracket of \
         1e-12. parry3d-f64 / parry3d: `query::cast_shapes` called directly on inputs already in parry's types, \
         with the oracle's options; \"via adapter\": through `oracle::parry::ParryCast`, which converts inside \
         each call. The textbook closed form (sphere–sphere only) is the formula with nothing around it — no \
         range checks, no screen, no bound on the normal's length, no degenerate cases — a reference for what collide's checks \
         cost, not an engine. {}\n",
        super::criterion_files::PAIRED_MARK
    );
    let _ = write!(s, "| pair | robust method | hits |");
    for (_, h) in ENGINES {
        let _ = write!(s, " {h} |");
    }
    let _ = writeln!(
        s,
        " robust f64 / parry3d-f64 | textbook f64 / parry3d-f64 | robust f64 / textbook f64 | halving / robust f64 |"
    );
    let _ = write!(s, "| --- | --- | ---: |");
    for _ in ENGINES {
        let _ = write!(s, " ---: |");
    }
    let _ = writeln!(s, " ---: | ---: | ---: | ---: |");
    for r in rows {
        let get = |id: &str| ns_per(r.group, id, r.per_iter, since);
        let _ = write!(s, "| {} | {} | {:.0}% |", r.label, r.robust, 100.0 * r.hits);
        for (id, _) in ENGINES {
            let _ = write!(s, " {} |", cell(get(id)));
        }
        let (robust, textbook) = (get("collide_robust_f64"), get("textbook_f64"));
        let _ = writeln!(
            s,
            " {} | {} | {} | {} |",
            super::criterion_files::ratio_cell(
                ratio(robust, get("parry64")),
                super::criterion_files::paired_ratio(r.group, "collide_robust_f64", "parry64")
            ),
            cell(ratio(textbook, get("parry64"))),
            cell(ratio(robust, textbook)),
            cell(ratio(get("collide_halving_f64"), robust))
        );
    }
    use super::criterion_files::{judged, paired_ratio, target_row, targets_heading, verdict};
    s.push('\n');
    s.push_str(&targets_heading());
    for t in targets {
        let per = rows.iter().find(|r| r.group == t.group).map_or(1, |r| r.per_iter);
        let r = ratio(ns_per(t.group, t.ids.0, per, since), ns_per(t.group, t.ids.1, per, since));
        let paired = paired_ratio(t.group, t.ids.0, t.ids.1);
        s.push_str(&target_row(t.what, t.target, r, paired, verdict(judged(r, paired), t.target)));
    }
    s
}

/// Prints the table and writes it beside criterion's files.
pub fn publish(report: &str) {
    println!("\n{report}");
    let path = criterion_dir().join("crashtest-toi-table.md");
    match std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, report)) {
        Ok(()) => println!("(written to {})", path.display()),
        Err(e) => eprintln!("could not write {}: {e}", path.display()),
    }
}
