//! Findings as text: the table a report opens with (Markdown and HTML), and
//! the terminal listing of `crashtest findings`.
//!
//! The HTML tables carry the class `sortable` and a filter box: the page's one
//! inline script ([`TABLE_SCRIPT`]) sorts them by a click on a column's title
//! and filters their rows by the text typed; a row opens, on a click, the
//! detail row below it (the case and every engine's answer). Nothing is
//! fetched: the page stays readable offline.

use super::model::{Finding, FindingsFile};
use crate::render::markdown::escape_md;
use crate::render::xml::escape;
use std::fmt::Write;

/// The page's script: sorting, filtering and opening rows of every table of
/// class `sortable`. Sorting compares numbers as numbers (a cell's
/// `data-v`, else its text read as a number) and text as text; a detail row
/// (class `more`) travels with the row above it. The filter matches a row's
/// own cells (not its detail, which names every engine).
pub const TABLE_SCRIPT: &str = r#"
document.querySelectorAll('table.sortable').forEach(function (t) {
  var body = t.tBodies[0];
  function groups() {
    var g = [], rows = Array.prototype.slice.call(body.rows);
    rows.forEach(function (r) { if (r.classList.contains('more') && g.length) g[g.length - 1].push(r); else g.push([r]); });
    return g;
  }
  function key(r, i) {
    var c = r.cells[i]; if (!c) return '';
    var v = c.getAttribute('data-v'); if (v === null) v = c.textContent.trim();
    var n = parseFloat(v); return isNaN(n) || !/^[-+0-9.eE%]+$/.test(v.replace(/ /g, '')) ? v.toLowerCase() : n;
  }
  Array.prototype.forEach.call(t.tHead.rows[0].cells, function (th, i) {
    th.style.cursor = 'pointer'; th.title = 'sort';
    th.addEventListener('click', function () {
      var dir = th.getAttribute('data-dir') === 'asc' ? 'desc' : 'asc';
      Array.prototype.forEach.call(t.tHead.rows[0].cells, function (h) { h.removeAttribute('data-dir'); });
      th.setAttribute('data-dir', dir);
      var g = groups();
      g.sort(function (a, b) {
        var x = key(a[0], i), y = key(b[0], i);
        var c = (typeof x === typeof y) ? (x < y ? -1 : x > y ? 1 : 0) : (typeof x === 'number' ? -1 : 1);
        return dir === 'asc' ? c : -c;
      });
      g.forEach(function (rows) { rows.forEach(function (r) { body.appendChild(r); }); });
    });
  });
  var box = document.querySelector('input[data-filter="' + t.id + '"]');
  if (box) box.addEventListener('input', function () {
    var q = box.value.toLowerCase(), shown = 0;
    groups().forEach(function (rows) {
      var hit = rows[0].textContent.toLowerCase().indexOf(q) >= 0;
      rows[0].hidden = !hit; if (hit) shown++;
      rows.slice(1).forEach(function (r) { if (!hit) r.hidden = true; });
    });
    var n = document.querySelector('[data-count="' + t.id + '"]'); if (n) n.textContent = shown;
  });
  Array.prototype.forEach.call(body.rows, function (r) {
    var next = r.nextElementSibling;
    if (r.classList.contains('more') || !next || !next.classList.contains('more')) return;
    r.style.cursor = 'pointer';
    r.addEventListener('click', function () { next.hidden = !next.hidden; });
  });
});
"#;

/// The style of the findings' and discrepancies' tables.
pub const TABLE_STYLE: &str = "\
tr.more td{white-space:normal;background:#fbfbfd}
tr.more pre{margin:4px 0;max-height:420px;overflow:auto;font:12px ui-monospace,SFMono-Regular,Menlo,Consolas,monospace}
th[data-dir=asc]::after{content:' ▲'}th[data-dir=desc]::after{content:' ▼'}
input.filter{font:inherit;padding:3px 8px;margin:0 0 8px;min-width:22em}
td.wrap{white-space:normal;min-width:16em}
";

/// A share as a percentage with two significant figures.
pub fn percent(x: f64) -> String {
    let p = 100.0 * x;
    if p >= 10.0 {
        format!("{p:.0} %")
    } else if p >= 1.0 {
        format!("{p:.1} %")
    } else {
        format!("{p:.2} %")
    }
}

/// An error as the tables write it.
fn err(x: Option<f64>) -> String {
    x.map_or_else(|| "–".into(), |v| if v == 0.0 { "0".into() } else { format!("{v:.1e}") })
}

/// The columns of the findings' tables.
const COLUMNS: [&str; 8] = ["engine", "pair", "what is wrong", "families", "cases", "share", "worst", "median"];

/// The ways a finding shows (its variants' `wrong`, with the magnitude class
/// where there is one, families added up), most cases first.
pub fn ways(f: &Finding) -> Vec<(String, u64)> {
    let mut m: std::collections::BTreeMap<String, u64> = std::collections::BTreeMap::new();
    for (s, n) in &f.variants {
        let k = if s.magnitude.is_empty() { s.wrong.clone() } else { format!("{} ({})", s.wrong, s.magnitude) };
        *m.entry(k).or_default() += n;
    }
    let mut v: Vec<(String, u64)> = m.into_iter().collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    v
}

/// The ways a finding shows, in one line: the three commonest and how many more.
fn ways_line(f: &Finding) -> String {
    let w = ways(f);
    let mut parts: Vec<String> = w.iter().take(3).map(|(k, n)| format!("{k} ×{n}")).collect();
    if w.len() > 3 {
        parts.push(format!("{} more", w.len() - 3));
    }
    parts.join(" · ")
}

/// The families a finding was met in: the commonest, and how many others.
fn families_line(f: &Finding) -> String {
    let mut v: Vec<(&String, &u64)> = f.families.iter().collect();
    v.sort_by(|a, b| b.1.cmp(a.1).then_with(|| a.0.cmp(b.0)));
    match v.as_slice() {
        [] => String::new(),
        [(one, _)] => (*one).clone(),
        [(first, _), rest @ ..] => format!("{first} and {} more", rest.len()),
    }
}

/// What is wrong: the cause's class, and the ways it shows when they say more.
fn wrong_cell(f: &Finding) -> String {
    let w = ways(f);
    if w.len() == 1 && w[0].0 == f.cause.class {
        f.cause.class.clone()
    } else {
        format!("{}: {}", f.cause.class, ways_line(f))
    }
}

fn row(f: &Finding) -> [String; 8] {
    [
        f.engines_label(),
        f.cause.pair.clone(),
        wrong_cell(f),
        families_line(f),
        f.count.to_string(),
        percent(f.share()),
        err(Some(f.errors.max)),
        err(f.errors.median()),
    ]
}

/// What the findings' section says first: how many findings hold how many
/// discrepancies.
fn lead(file: &FindingsFile) -> String {
    let n = file.discrepancy_findings().count();
    let known = file.findings.len() - n;
    let shrunk = file.discrepancy_findings().filter(|f| f.shrunk.is_some()).count();
    format!(
        "{} discrepancies in {n} findings. A finding is one root cause: an engine's code (two builds of one \
         code in two precisions share it), a pair in argument order, and what is wrong — wrong answers (false or \
         missed contacts, hits, impacts, overlaps, or values off), wrong flags only, or non-finite answers; one \
         named failure (a panic at one place, a crash, the engine's message) over every pair; or, per engine \
         and over every pair, inputs beyond its precision (products of the pair's degree outside the type's \
         range, or, in f32, inputs whose rounding explains the answer). Its variants are the signatures (what \
         exactly is wrong, case family, error's magnitude class) it shows as. {shrunk} have a shrunk case under \
         findings/, replayed by the command in their row. {known} groups of known divergences follow, each \
         with its documented reason. Errors are the headline relative errors (1 for a misclassification or a \
         failure).",
        file.discrepancies
    )
}

/// The findings as Markdown: the table of discrepancy findings with each
/// one's replay command, then the known divergences. `dir` is the report's
/// folder as the commands name it.
pub fn markdown(file: &FindingsFile, dir: &str) -> String {
    let mut out = String::from("## Findings\n\n");
    let _ = writeln!(out, "{}\n", escape_md(&lead(file)));
    let head = |out: &mut String, cols: &[&str]| {
        let _ = writeln!(out, "| {} |", cols.join(" | "));
        let _ = writeln!(out, "|{}|", cols.iter().map(|_| " --- ").collect::<Vec<_>>().join("|"));
    };
    let discrepancies: Vec<&Finding> = file.discrepancy_findings().collect();
    if discrepancies.is_empty() {
        out.push_str("No discrepancies.\n\n");
    } else {
        let mut cols = COLUMNS.to_vec();
        cols.push("replay (from the repository's root)");
        head(&mut out, &cols);
        for f in &discrepancies {
            let cells: Vec<String> = row(f).iter().map(|c| escape_md(c)).collect();
            let _ = writeln!(out, "| {} | `{}` |", cells.join(" | "), f.replay_command(dir));
        }
        out.push('\n');
    }
    let known: Vec<&Finding> = file.findings.iter().filter(|f| !f.is_discrepancy()).collect();
    if !known.is_empty() {
        out.push_str("### Known divergences\n\n");
        head(&mut out, &["engine", "pair", "cases", "share", "reason"]);
        for f in known {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} |",
                escape_md(&f.engines_label()),
                escape_md(&f.cause.pair),
                f.count,
                percent(f.share()),
                escape_md(f.known.as_deref().unwrap_or(""))
            );
        }
        out.push('\n');
    }
    out
}

/// A detail row's content: the shrunk case (or the first example), the
/// verdict's reasons and every engine's answer, as JSON.
fn detail(f: &Finding, dir: &str) -> String {
    let mut out = String::new();
    let _ = write!(out, "<p><b>{}</b></p>", escape(&f.title));
    let _ = write!(out, "<p>Replay: <code>{}</code>", escape(&f.replay_command(dir)));
    if f.draft_file().is_some() {
        let _ = write!(
            out,
            " · bug-report draft: <a href=\"findings/{0}.md\"><code>findings/{0}.md</code></a>",
            escape(&f.name)
        );
    }
    out.push_str("</p>");
    out.push_str("<p>Variants (signature: what is wrong; family; magnitude class):</p><ul>");
    for (sig, n) in &f.variants {
        let _ = write!(
            out,
            "<li>{n} × {}; {}{}</li>",
            escape(&sig.wrong),
            escape(&sig.family),
            if sig.magnitude.is_empty() { String::new() } else { format!("; {}", escape(&sig.magnitude)) }
        );
    }
    out.push_str("</ul>");
    if let Some(s) = &f.shrunk {
        let _ = write!(
            out,
            "<p>Shrunk case ({} → {} numbers; {} candidates judged; the defect shown in {} of {} replays): {}</p>\
             <pre>{}</pre>",
            s.numbers.0,
            s.numbers.1,
            s.evaluations,
            s.replayed,
            super::shrink::REPLAYS,
            escape(&s.reasons.join("; ")),
            escape(&serde_json::to_string_pretty(&s.case).unwrap_or_default())
        );
    }
    if let Some(e) = f.examples.first() {
        let _ = write!(
            out,
            "<p>First case, <code>{}</code> ({}): {}</p><pre>{}</pre><p>Every engine's answer:</p><pre>{}</pre>",
            escape(&e.case),
            escape(&e.origin),
            escape(&e.reasons.join("; ")),
            escape(&serde_json::to_string_pretty(&e.fixture).unwrap_or_default()),
            escape(&serde_json::to_string_pretty(&e.answers).unwrap_or_default())
        );
    }
    out
}

/// The findings as HTML: a filter box and a sortable table whose rows open
/// to their case and answers; then the known divergences.
pub fn html(file: &FindingsFile, dir: &str) -> String {
    let mut out = String::from("<h2 id=\"findings\">Findings</h2>\n");
    let _ = writeln!(out, "<p>{}</p>", escape(&lead(file)));
    let discrepancies: Vec<&Finding> = file.discrepancy_findings().collect();
    if discrepancies.is_empty() {
        out.push_str("<p>No discrepancies.</p>\n");
    } else {
        let _ = writeln!(
            out,
            "<p><input class=\"filter\" type=\"search\" placeholder=\"filter findings (engine, pair, …)\" \
             data-filter=\"findings-table\"> <span data-count=\"findings-table\">{}</span> shown · click a title \
             to sort, a row to open it</p>",
            discrepancies.len()
        );
        out.push_str("<div class=\"scroll\"><table class=\"sortable\" id=\"findings-table\">\n<thead><tr>");
        for (i, c) in COLUMNS.iter().enumerate() {
            let class = if i >= 4 { " class=\"n\"" } else { "" };
            let _ = write!(out, "<th{class}>{}</th>", escape(c));
        }
        out.push_str("</tr></thead>\n<tbody>\n");
        for f in discrepancies {
            let cells = row(f);
            out.push_str("<tr>");
            for (i, c) in cells.iter().enumerate() {
                let (class, v) = match i {
                    5 => (" class=\"n\"", format!(" data-v=\"{}\"", f.share())),
                    6 => (" class=\"n\"", format!(" data-v=\"{}\"", f.errors.max)),
                    7 => (" class=\"n\"", format!(" data-v=\"{}\"", f.errors.median().unwrap_or(0.0))),
                    4 => (" class=\"n\"", String::new()),
                    2 | 3 => (" class=\"wrap\"", String::new()),
                    _ => ("", String::new()),
                };
                let _ = write!(out, "<td{class}{v}>{}</td>", escape(c));
            }
            let _ = writeln!(
                out,
                "</tr>\n<tr class=\"more\" hidden><td colspan=\"{}\">{}</td></tr>",
                COLUMNS.len(),
                detail(f, dir)
            );
        }
        out.push_str("</tbody></table></div>\n");
    }
    let known: Vec<&Finding> = file.findings.iter().filter(|f| !f.is_discrepancy()).collect();
    if !known.is_empty() {
        out.push_str("<h3>Known divergences</h3>\n");
        out.push_str(
            "<div class=\"scroll\"><table class=\"sortable\" id=\"known-table\">\n<thead><tr><th>engine</th>\
             <th>pair</th><th class=\"n\">cases</th><th class=\"n\">share</th><th>reason</th></tr></thead>\n<tbody>\n",
        );
        for f in known {
            let _ = writeln!(
                out,
                "<tr><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\" data-v=\"{}\">{}</td>\
                 <td class=\"wrap\">{}</td></tr>",
                escape(&f.engines_label()),
                escape(&f.cause.pair),
                f.count,
                f.share(),
                percent(f.share()),
                escape(f.known.as_deref().unwrap_or(""))
            );
        }
        out.push_str("</tbody></table></div>\n");
    }
    out
}

/// The terminal listing of `crashtest findings`: one block per finding —
/// what, how often, how badly, and the command that replays it.
pub fn text(file: &FindingsFile, dir: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "{}\n", lead(file));
    for (i, f) in file.discrepancy_findings().enumerate() {
        let _ = writeln!(out, "{:>3}. {}", i + 1, f.title);
        let _ = writeln!(
            out,
            "     {} of {} cases ({}); worst error {}, median {}",
            f.count,
            f.of_cases,
            percent(f.share()),
            err(Some(f.errors.max)),
            err(f.errors.median())
        );
        let _ = writeln!(out, "     as: {}", ways_line(f));
        let _ = writeln!(out, "     families: {}", families_line(f));
        if let Some(s) = &f.shrunk {
            let _ = writeln!(
                out,
                "     shrunk: {} → {} numbers (simplicity {} → {})",
                s.numbers.0, s.numbers.1, s.cost.0, s.cost.1
            );
        }
        let _ = writeln!(out, "     replay: {}", f.replay_command(dir));
        if let Some(d) = f.draft_file() {
            let _ = writeln!(out, "     draft:  {dir}/{d}");
        }
    }
    let known: Vec<&Finding> = file.findings.iter().filter(|f| !f.is_discrepancy()).collect();
    if !known.is_empty() {
        let _ = writeln!(out, "\nKnown divergences:");
        for f in known {
            let _ = writeln!(
                out,
                "  {}: {}: {} cases ({}): {}",
                f.engines_label(),
                f.cause.pair,
                f.count,
                percent(f.share()),
                f.known.as_deref().unwrap_or("")
            );
        }
    }
    out
}

/// The discrepancies written out in full (`discrepancies.json`: the first
/// few of each engine and query kind) as a filterable, sortable table whose
/// rows open to their case and every engine's answer.
pub fn discrepancies_html(discrepancies: &[serde_json::Value]) -> String {
    let mut out = String::from("<h3 id=\"discrepancies\">Discrepancies</h3>\n");
    if discrepancies.is_empty() {
        out.push_str("<p>None.</p>\n");
        return out;
    }
    let _ = writeln!(
        out,
        "<p>The first few of each engine and query kind, as <code>discrepancies.json</code> holds them. \
         <input class=\"filter\" type=\"search\" placeholder=\"filter discrepancies\" \
         data-filter=\"discrepancies-table\"> <span data-count=\"discrepancies-table\">{}</span> shown</p>",
        discrepancies.len()
    );
    out.push_str(
        "<div class=\"scroll\"><table class=\"sortable\" id=\"discrepancies-table\">\n<thead><tr><th>engine</th>\
         <th>query</th><th>verdict</th><th>what differs</th><th>case</th></tr></thead>\n<tbody>\n",
    );
    let s = |v: &serde_json::Value, k: &str| v.get(k).and_then(|x| x.as_str()).unwrap_or("").to_string();
    for d in discrepancies {
        let verdict = d.get("verdict").cloned().unwrap_or_default();
        let label = s(&verdict, "verdict");
        let reasons: Vec<String> = match verdict.get("reasons").and_then(|r| r.as_array()) {
            Some(r) => r.iter().filter_map(|x| x.as_str().map(String::from)).collect(),
            None => vec![s(&verdict, "reason")],
        };
        let case = d.pointer("/fixture/cases/0/name").and_then(|x| x.as_str()).unwrap_or("");
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"wrap\">{}</td><td class=\"wrap\">{}</td></tr>\n\
             <tr class=\"more\" hidden><td colspan=\"5\"><p>From {}</p><pre>{}</pre><p>Every engine's answer:</p>\
             <pre>{}</pre></td></tr>",
            escape(&s(d, "engine")),
            escape(&s(d, "query")),
            escape(&label),
            escape(&reasons.join("; ")),
            escape(case),
            escape(&s(d, "origin")),
            escape(
                &serde_json::to_string_pretty(d.get("fixture").unwrap_or(&serde_json::Value::Null)).unwrap_or_default()
            ),
            escape(
                &serde_json::to_string_pretty(d.get("answers").unwrap_or(&serde_json::Value::Null)).unwrap_or_default()
            )
        );
    }
    out.push_str("</tbody></table></div>\n");
    out
}

/// Where the page sends its reader for the discrepancies in full: how many
/// `discrepancies.html` lists, per engine and query kind, and the link. The
/// table itself (every row with its case and every engine's answer) is most
/// of a report's weight, and is read row by row, not inline.
pub fn discrepancies_link(discrepancies: &[serde_json::Value]) -> String {
    let mut out = String::from("<h3 id=\"discrepancies\">Discrepancies</h3>\n");
    if discrepancies.is_empty() {
        out.push_str("<p>None.</p>\n");
        return out;
    }
    let mut counts: std::collections::BTreeMap<(String, String), usize> = Default::default();
    let s = |v: &serde_json::Value, k: &str| v.get(k).and_then(|x| x.as_str()).unwrap_or("").to_string();
    for d in discrepancies {
        *counts.entry((s(d, "engine"), s(d, "query"))).or_default() += 1;
    }
    let _ = writeln!(
        out,
        "<p>The first few of each engine and query kind ({} in all), each with its case and every engine's answer, \
         on a page of their own: <a href=\"discrepancies.html\">discrepancies.html</a> (filterable and sortable; \
         <code>discrepancies.json</code> holds the same).</p>",
        discrepancies.len()
    );
    out.push_str(
        "<details><summary>How many, per engine and query kind</summary><div class=\"scroll\"><table>\n\
         <thead><tr><th>engine</th><th>query</th><th class=\"n\">listed</th></tr></thead>\n<tbody>\n",
    );
    for ((engine, query), n) in counts {
        let _ =
            writeln!(out, "<tr><td>{}</td><td>{}</td><td class=\"n\">{n}</td></tr>", escape(&engine), escape(&query));
    }
    out.push_str("</tbody></table></div></details>\n");
    out
}

/// The report's opening: the findings (HTML with the link to the
/// discrepancies' page, and Markdown), with the tables' style and script.
pub fn opening(file: &FindingsFile, discrepancies: &[serde_json::Value], dir: &str) -> crate::render::opening::Opening {
    crate::render::opening::Opening {
        html: format!("{}{}", html(file, dir), discrepancies_link(discrepancies)),
        style: TABLE_STYLE.into(),
        script: TABLE_SCRIPT.into(),
        markdown: markdown(file, dir),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The page links the discrepancies and counts them per engine and query
    /// kind; their rows, cases and answers are on their own page.
    #[test]
    fn the_page_links_the_discrepancies_and_their_page_holds_them() {
        let d = |engine: &str, query: &str, case: &str| {
            serde_json::json!({"engine": engine, "query": query, "verdict": {"verdict": "disagree", "reasons": ["t off"]},
                "fixture": {"cases": [{"name": case}]}, "answers": {engine: {"toi": null}}, "origin": "generated"})
        };
        let all = [d("fcl", "toi", "case one"), d("fcl", "toi", "case two"), d("coal", "contact", "case three")];
        let link = discrepancies_link(&all);
        assert!(link.contains("<a href=\"discrepancies.html\">") && link.contains("(3 in all)"), "{link}");
        assert!(link.contains("<td>fcl</td><td>toi</td><td class=\"n\">2</td>"), "{link}");
        assert!(!link.contains("case one") && !link.contains("t off"), "no row on the page: {link}");
        let page = crate::render::html::page("discrepancies", &discrepancies_html(&all), TABLE_STYLE, TABLE_SCRIPT);
        assert!(page.contains("id=\"discrepancies-table\"") && page.contains("case one") && page.contains("t off"));
        assert!(page.contains("<a href=\"index.html\">") && page.starts_with("<!DOCTYPE html>"));
        assert_eq!(discrepancies_link(&[]), "<h3 id=\"discrepancies\">Discrepancies</h3>\n<p>None.</p>\n");
    }
}
