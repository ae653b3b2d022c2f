//! The table printed at the end of a run (and written to
//! `target/criterion/crashtest-table.md`): criterion's estimates of this run,
//! per query and engine, as nanoseconds per query, with the ratios the speed
//! targets are stated in and the lower bound from the hand-counted arithmetic.

use super::cost::Cost;
use super::peak::Peak;
use std::fmt::Write as _;

use std::time::SystemTime;

/// The engines of the main table: criterion's benchmark id and the column's
/// heading.
pub const ENGINES: [(&str, &str); 9] = [
    ("collide_lecture_f64", "collide lecture f64"),
    ("collide_robust_f64", "collide robust f64"),
    ("collide_lecture_f32", "collide lecture f32"),
    ("collide_robust_f32", "collide robust f32"),
    ("parry64", "parry3d-f64"),
    ("parry64_like", "parry3d-f64 like for like"),
    ("parry32", "parry3d"),
    ("parry64_adapter", "parry3d-f64 via adapter"),
    ("parry32_adapter", "parry3d via adapter"),
];

/// One query of the main table.
pub struct Row {
    /// criterion's group name (the benchmark ids are [`ENGINES`]'s).
    pub group: &'static str,
    /// The row's heading.
    pub label: &'static str,
    /// Queries per benchmark iteration (the cases).
    pub per_iter: usize,
    /// Mean arithmetic per query over the cases (`None`: not counted).
    pub cost: Option<Cost>,
    /// Fraction of the cases that hit (contact, intersect, overlap), for the
    /// reader.
    pub hits: Option<f64>,
    /// The lecture column's engine when it is not `collide_lecture_*` (the
    /// query has one method: the robust one is the lecture's).
    pub one_method: bool,
}

/// One comparison of the batch table.
pub struct BatchRow {
    /// criterion's group name.
    pub group: &'static str,
    /// The row's heading.
    pub label: &'static str,
    /// Pairs per benchmark iteration.
    pub per_iter: usize,
    /// Benchmark ids: the one-at-a-time loop, then the batch call.
    pub ids: (&'static str, &'static str),
    /// Arithmetic per pair.
    pub cost: Option<Cost>,
}

pub use super::criterion_files::criterion_dir;
use super::criterion_files::{
    PAIRED_MARK, cell, judged, ns_per, paired_ratio, ratio, ratio_cell, target_row, targets_heading, verdict,
};
use super::families::{FamilyTable, family_table};

/// One speed target: `numerator / denominator ≤ target`, over one group.
pub struct Target {
    /// Group.
    pub group: &'static str,
    /// What is compared, for the reader.
    pub what: &'static str,
    /// Benchmark ids of the numerator and the denominator.
    pub ids: (&'static str, &'static str),
    /// The largest ratio that meets it.
    pub target: f64,
    /// A benchmark id of the same group that does no more than read the
    /// numerator's inputs: its paired ratio to the denominator is the least
    /// ratio any function of those inputs can have in this loop, and the
    /// verdict says so when that is above the target.
    pub floor: Option<&'static str>,
}

/// Everything the report renders from.
pub struct Tables<'a> {
    /// The main table's queries.
    pub rows: &'a [Row],
    /// The batch table's comparisons.
    pub batches: &'a [BatchRow],
    /// The speed targets.
    pub targets: &'a [Target],
    /// The by-family tables.
    pub families: &'a [FamilyTable],
}

/// Renders the whole report as Markdown.
pub fn render(tables: &Tables, peak: &Peak, since: SystemTime) -> String {
    let Tables { rows, batches, targets, families } = *tables;
    let mut s = String::new();
    let _ = writeln!(s, "# crashtest speed: collide against parry, one run\n");
    let _ = writeln!(
        s,
        "Nanoseconds per query (criterion's slope estimate over the run's samples, divided by \
         the cases per iteration; `—`: not run). Same pre-generated cases for every engine \
         (seed {:#x}, the campaign's generators and mix). parry3d-f64 / parry3d: parry called \
         directly on pre-converted inputs; \"via adapter\": through `oracle::parry::ParryEngine`, \
         which converts and translates inside each call; \"like for like\": parry doing what \
         collide's function does — for the contact queries its pair function without \
         `query::contact`'s dynamic dispatch, for segment–plane the same ray cast also \
         answering the hit point and the normal, as collide does.\n",
        super::cases::SEED
    );
    let _ = writeln!(
        s,
        "Peak of this build on this machine (packed SIMD, measured): {:.2} f64 ops/ns, {:.2} f32 \
         ops/ns, {:.3} f64 sqrt/ns, {:.3} f64 div/ns, {:.1} input bytes/ns read one record at a \
         time. Bound = the query's hand-counted arithmetic (mean over the cases) and its input's \
         bytes at that peak: FP pipes, divider and loads in parallel, the largest time. A target \
         that asks for less than the bound cannot be met by this build on this machine; its \
         verdict says so. {PAIRED_MARK}\n",
        peak.ops_f64, peak.ops_f32, peak.sqrt_f64, peak.div_f64, peak.read_bytes
    );

    let _ = write!(s, "| query | hits |");
    for (_, h) in ENGINES {
        let _ = write!(s, " {h} |");
    }
    let _ =
        writeln!(s, " robust f64 / parry3d-f64 | lecture f64 / parry3d-f64 | bound f64 (ns) | robust f64 / bound |");
    let _ = write!(s, "| --- | ---: |");
    for _ in ENGINES {
        let _ = write!(s, " ---: |");
    }
    let _ = writeln!(s, " ---: | ---: | ---: | ---: |");
    for r in rows {
        let get = |id: &str| ns_per(r.group, id, r.per_iter, since);
        let hits = r.hits.map_or("—".into(), |h| format!("{:.0}%", 100.0 * h));
        let _ = write!(s, "| {} | {hits} |", r.label);
        for (id, _) in ENGINES {
            let v = if r.one_method && id.starts_with("collide_lecture") { None } else { get(id) };
            let shown =
                if r.one_method && id.starts_with("collide_lecture") { "= robust".to_string() } else { cell(v) };
            let _ = write!(s, " {shown} |");
        }
        let robust = get("collide_robust_f64");
        let lecture = if r.one_method { robust } else { get("collide_lecture_f64") };
        let parry = get("parry64");
        let bound = r.cost.map(|c| peak.bound_ns(c));
        let _ = writeln!(
            s,
            " {} | {} | {} | {} |",
            ratio_cell(ratio(robust, parry), paired_ratio(r.group, "collide_robust_f64", "parry64")),
            cell(ratio(lecture, parry)),
            cell(bound),
            cell(ratio(robust, bound)),
        );
    }

    if !batches.is_empty() {
        let _ = writeln!(
            s,
            "\n## Batch against one at a time\n\nBound: the arithmetic and the input bytes at the measured \
             read rate, as for one query at a time (streaming the arrays reads the same bytes).\n\n| comparison | one at a time (ns/pair) | batch \
             (ns/pair) | speed-up | bound f64 (ns/pair) |\n| --- | ---: | ---: | ---: | ---: |"
        );
        for b in batches {
            let one = ns_per(b.group, b.ids.0, b.per_iter, since);
            let batch = ns_per(b.group, b.ids.1, b.per_iter, since);
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} |",
                b.label,
                cell(one),
                cell(batch),
                ratio(one, batch).map_or("—".into(), |x| format!("{x:.2}×")),
                cell(b.cost.map(|c| peak.bound_ns(c))),
            );
        }
    }

    s.push('\n');
    s.push_str(&targets_heading());
    for t in targets {
        let per = rows
            .iter()
            .find(|r| r.group == t.group)
            .map(|r| r.per_iter)
            .or_else(|| batches.iter().find(|b| b.group == t.group).map(|b| b.per_iter))
            .unwrap_or(1);
        let denominator = ns_per(t.group, t.ids.1, per, since);
        let r = ratio(ns_per(t.group, t.ids.0, per, since), denominator);
        let paired = paired_ratio(t.group, t.ids.0, t.ids.1);
        let judged = judged(r, paired);
        // The bound of the numerator's row: the main table's for a query one
        // at a time, the batch table's for a batch.
        let cost = if t.ids.0.starts_with("collide_") {
            rows.iter().find(|r| r.group == t.group).and_then(|r| r.cost)
        } else {
            batches.iter().find(|b| b.group == t.group && b.ids.1 == t.ids.0).and_then(|b| b.cost)
        };
        let bound = cost.map(|c| peak.bound_ns(c));
        let mut v = verdict(judged, t.target).to_string();
        if let (Some(r), Some(d), Some(b)) = (judged, denominator, bound)
            && r > t.target
            && t.target * d < b
        {
            let _ = write!(v, ": asks for {} ns, below the bound ({} ns)", cell(Some(t.target * d)), cell(Some(b)));
        }
        if let Some(floor) = t.floor.and_then(|f| paired_ratio(t.group, f, t.ids.1))
            && floor.median > t.target
        {
            let _ = write!(
                v,
                "; unreachable in this loop: reading the inputs and nothing else takes {} of the denominator's \
                 time, paired",
                floor.quartiles()
            );
        }
        s.push_str(&target_row(t.what, t.target, r, paired, &v));
    }
    s.push_str(&family_table(
        families,
        "The mixes above are the campaign's: half uniform random cases, half drawn toward where methods fail. Here \
         each family's cases are timed alone, collide robust f64 against parry3d-f64, paired as the targets are, to \
         show where the time goes: the exact predicates' fallbacks run on the families near a degeneracy.",
        ("robust f64", "parry3d-f64"),
    ));
    s
}

/// Prints the report and writes it beside criterion's files.
pub fn publish(report: &str) {
    println!("\n{report}");
    let path = criterion_dir().join("crashtest-table.md");
    match std::fs::create_dir_all(criterion_dir()).and_then(|()| std::fs::write(&path, report)) {
        Ok(()) => println!("(written to {})", path.display()),
        Err(e) => eprintln!("could not write {}: {e}", path.display()),
    }
}

/// The report's names of the main table's engines (criterion id → engine).
const REPORT_NAMES: [(&str, &str); 6] = [
    ("collide_lecture_f64", "collide/lecture"),
    ("collide_robust_f64", "collide/robust"),
    ("collide_lecture_f32", "collide-f32/lecture"),
    ("collide_robust_f32", "collide-f32/robust"),
    ("parry64", "parry3d-f64"),
    ("parry32", "parry3d"),
];

/// Writes this run's figures as `crashtest-bench.json` beside criterion's
/// files, for `crashtest report` to place the engines on its accuracy–speed
/// charts (`harness::report::bench`). A query with one method gives its
/// robust figure to the lecture's engine as well, as the table does.
pub fn write_figures(rows: &[Row], since: SystemTime) {
    use harness::report::bench::{BenchFile, BenchRow, FORMAT};
    let dir = criterion_dir();
    let mut out = Vec::new();
    for r in rows {
        for (id, engine) in REPORT_NAMES {
            let id = match (r.one_method, id) {
                (true, "collide_lecture_f64") => "collide_robust_f64",
                (true, "collide_lecture_f32") => "collide_robust_f32",
                _ => id,
            };
            if let Some(ns) = ns_per(r.group, id, r.per_iter, since) {
                out.push(BenchRow { group: r.group.to_string(), engine: engine.to_string(), ns });
            }
        }
    }
    let file = BenchFile {
        format: FORMAT.into(),
        written: harness::report::provenance::rfc3339(SystemTime::now()),
        machine: harness::report::provenance::machine(),
        rows: out,
    };
    let path = dir.join("crashtest-bench.json");
    let text = serde_json::to_string_pretty(&file).unwrap_or_default();
    match std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&path, text)) {
        Ok(()) => println!("(figures for `crashtest report` written to {})", path.display()),
        Err(e) => eprintln!("could not write {}: {e}", path.display()),
    }
}
