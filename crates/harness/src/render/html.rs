//! `index.html`: the whole report on one self-contained page.
//!
//! No external CSS, script or font: the style sheet is inline, the charts are
//! inline SVG, and the text uses the reader's system sans-serif. The page opens
//! with the provenance, then per query kind its table, its charts and (folded)
//! its error details, then throughput, how to read the tables, and links to the
//! report's other files. Every piece of text is escaped. The function is pure:
//! the same input gives byte-identical output.

use super::charts::Chart;
use super::markdown::{
    GROWTH_NOTE, Table, detail_table, engines_table, growth_table, provenance_lines, queries, query_table, query_title,
    reading_notes, throughput_table,
};
use crate::summary::Summary;
use std::fmt::Write;

pub use super::xml::escape;

/// The page's style sheet: readable system typography, tables with aligned
/// figures, charts scaled to the column.
const STYLE: &str = "\
:root{color-scheme:light;--fg:#1b1b1b;--muted:#5b5b5b;--rule:#dcdcdc;--band:#f6f7f9;--accent:#1f5fa8}
*{box-sizing:border-box}
body{margin:0;color:var(--fg);background:#fff;font:15px/1.5 system-ui,-apple-system,'Segoe UI',Roboto,'Helvetica Neue',Arial,sans-serif}
main{max-width:1240px;margin:0 auto;padding:28px 28px 64px}
h1{font-size:28px;margin:0 0 4px;letter-spacing:-.01em}
h2{font-size:21px;margin:40px 0 12px;padding-top:12px;border-top:1px solid var(--rule)}
h3{font-size:16px;margin:20px 0 8px}
.sub{color:var(--muted);margin:0 0 20px}
a{color:var(--accent)}
dl.prov{display:grid;grid-template-columns:max-content 1fr;gap:2px 18px;margin:0 0 16px;padding:14px 18px;background:var(--band);border-radius:6px}
dl.prov dt{color:var(--muted)}
dl.prov dd{margin:0;font-variant-numeric:tabular-nums;overflow-wrap:anywhere}
nav{margin:8px 0 0}
nav a{margin-right:14px}
.scroll{overflow-x:auto;margin:0 0 12px}
table{border-collapse:collapse;font-size:13px;font-variant-numeric:tabular-nums}
th,td{padding:4px 7px;border-bottom:1px solid var(--rule);white-space:nowrap;text-align:left}
th{font-weight:600;background:var(--band);white-space:normal;vertical-align:bottom;min-width:3.5em}
td.n,th.n{text-align:right}
tbody tr:hover{background:#fafbfc}
figure{margin:18px 0 26px}
figure svg{display:block;max-width:100%;height:auto;border:1px solid var(--rule);border-radius:4px}
figcaption{color:var(--muted);font-size:13px;margin-top:6px}
details{margin:6px 0 0}
summary{cursor:pointer;color:var(--accent)}
ul.notes li,ul.files li{margin:4px 0}
code{font:13px ui-monospace,SFMono-Regular,Menlo,Consolas,monospace}
";

/// A [`Table`] as an HTML table (wrapped to scroll sideways on narrow screens).
pub fn table_html(t: &Table) -> String {
    let class = |i: usize| {
        if t.numeric.get(i).copied().unwrap_or(false) { r#" class="n""# } else { "" }
    };
    let mut out = String::from("<div class=\"scroll\"><table>\n<thead><tr>");
    for (i, h) in t.header.iter().enumerate() {
        let _ = write!(out, "<th{}>{}</th>", class(i), escape(h));
    }
    out.push_str("</tr></thead>\n<tbody>\n");
    for row in &t.rows {
        out.push_str("<tr>");
        for (i, c) in row.iter().enumerate() {
            let _ = write!(out, "<td{}>{}</td>", class(i), escape(c));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</tbody></table></div>\n");
    out
}

/// A section anchor for a query kind.
fn anchor(title: &str) -> String {
    format!("q-{}", title.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '-' }).collect::<String>())
}

/// A page of the report beside `index.html`: its title, its body's HTML, and
/// the extra style and inline script it needs, with the report's own style.
pub fn page(title: &str, body: &str, style: &str, script: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>\n{STYLE}{style}</style>\n</head>\n<body>\n<main>\n<h1>{}</h1>\n\
         <p><a href=\"index.html\">← the report</a></p>\n{body}</main>\n<script>\n{script}</script>\n</body>\n</html>\n",
        escape(title),
        escape(title)
    )
}

/// The whole of `index.html`.
///
/// `charts` are the report's charts ([`super::charts::all`]); each is shown
/// inline under its query kind's table and linked as `charts/<file>` at the end,
/// beside `summary.md`, `summary.json` and `discrepancies.json`.
pub fn index_html(summary: &Summary, charts: &[Chart]) -> String {
    index_html_with(summary, charts, &super::opening::Opening::default())
}

/// [`index_html`] opening with `opening` (the findings) after its title; its
/// script, inline, closes the page.
pub fn index_html_with(summary: &Summary, charts: &[Chart], opening: &super::opening::Opening) -> String {
    let p = &summary.provenance;
    let commit = p.commit.clone().unwrap_or_else(|| "unknown commit".into());
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>crashtest report — {}</title>\n<style>\n{}{}</style>\n</head>\n<body>\n<main>\n",
        escape(&commit),
        STYLE,
        opening.style
    );
    let _ = writeln!(out, "<h1>crashtest report</h1>");
    let _ = writeln!(
        out,
        "<p class=\"sub\">{} · {} · {} random + {} fixture cases · {} discrepancies</p>",
        escape(&commit),
        escape(&p.started),
        p.random_cases,
        p.fixture_cases,
        summary.discrepancies
    );
    out.push_str(&opening.html);

    out.push_str("<h2 id=\"provenance\">Provenance</h2>\n<dl class=\"prov\">\n");
    for (k, v) in provenance_lines(summary) {
        let _ = writeln!(out, "<dt>{}</dt><dd>{}</dd>", escape(&k), escape(&v));
    }
    out.push_str("</dl>\n");
    if !p.engines.is_empty() {
        out.push_str(&table_html(&engines_table(summary)));
    }

    let qs = queries(summary);
    if !qs.is_empty() {
        out.push_str("<nav>");
        for q in &qs {
            let t = query_title(*q);
            let _ = write!(out, "<a href=\"#{}\">{}</a>", anchor(&t), escape(&t));
        }
        if !crate::render::markdown::ulps_table(summary).rows.is_empty() {
            out.push_str("<a href=\"#ulps\">ulps</a>");
        }
        if !summary.full_range.is_empty() {
            out.push_str("<a href=\"#full-range\">full range</a>");
        }
        out.push_str("<a href=\"#throughput\">throughput</a><a href=\"#files\">files</a></nav>\n");
    } else {
        out.push_str("<p>No results.</p>\n");
    }

    for q in qs {
        let t = query_title(q);
        let _ = writeln!(out, "<h2 id=\"{}\">{}</h2>", anchor(&t), escape(&t));
        out.push_str(&table_html(&query_table(summary, q)));
        for c in charts.iter().filter(|c| Some(c.query) == q) {
            let _ = writeln!(
                out,
                "<figure>\n{}<figcaption>{} — <a href=\"charts/{}\">charts/{}</a></figcaption>\n</figure>",
                c.svg,
                escape(&c.title),
                escape(&c.file),
                escape(&c.file)
            );
        }
        let detail = detail_table(summary, q);
        if !detail.rows.is_empty() {
            out.push_str("<details><summary>Error distributions (median, p99, max)</summary>\n");
            out.push_str(&table_html(&detail));
            out.push_str("</details>\n");
        }
    }

    let ulps = crate::render::markdown::ulps_table(summary);
    if !ulps.rows.is_empty() {
        out.push_str("<h2 id=\"ulps\">Accuracy in ulps</h2>\n");
        let _ = writeln!(out, "<p>{}</p>", escape(crate::render::markdown::ULPS_NOTE));
        out.push_str(&table_html(&ulps));
    }

    if !summary.full_range.is_empty() {
        out.push_str("<h2 id=\"full-range\">Full range</h2>\n");
        let _ = writeln!(out, "<p>{}</p>", escape(crate::render::markdown::FULL_RANGE_NOTE));
        out.push_str(&table_html(&crate::render::markdown::full_range_table(summary)));
    }

    out.push_str("<h2 id=\"throughput\">Throughput</h2>\n");
    if summary.throughput.is_empty() {
        out.push_str("<p>Not measured.</p>\n");
    } else {
        out.push_str(&table_html(&throughput_table(summary)));
    }
    if !summary.growth.is_empty() {
        out.push_str("<h2 id=\"growth\">distance: cost by vertex count</h2>\n");
        let _ = writeln!(out, "<p>{}</p>", escape(GROWTH_NOTE));
        out.push_str(&table_html(&growth_table(summary)));
    }

    out.push_str("<h2 id=\"reading\">Reading the tables</h2>\n<ul class=\"notes\">\n");
    for note in reading_notes() {
        let _ = writeln!(out, "<li>{}</li>", escape(&note));
    }
    out.push_str("</ul>\n");

    out.push_str("<h2 id=\"files\">Files of this report</h2>\n<ul class=\"files\">\n");
    for (file, what) in [
        ("summary.md", "these tables as Markdown"),
        ("summary.json", "everything measured, mergeable across shards"),
        ("discrepancies.json", "each discrepancy with its case as a fixture for crashtest check"),
    ] {
        let _ = writeln!(out, "<li><a href=\"{f}\"><code>{f}</code></a> — {}</li>", escape(what), f = escape(file));
    }
    for c in charts {
        let _ = writeln!(
            out,
            "<li><a href=\"charts/{f}\"><code>charts/{f}</code></a> — {}</li>",
            escape(&c.title),
            f = escape(&c.file)
        );
    }
    out.push_str("</ul>\n</main>\n");
    if !opening.script.is_empty() {
        let _ = writeln!(out, "<script>{}</script>", opening.script);
    }
    out.push_str("</body>\n</html>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::charts::{self, fixture};

    #[test]
    fn escape_covers_markup_and_quotes() {
        assert_eq!(escape(r#"<a href="x">&'</a>"#), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
    }

    #[test]
    fn index_html_opens_with_provenance_and_shows_every_engine_and_chart() {
        let s = fixture::summary();
        let charts = charts::all(&s);
        let html = index_html(&s, &charts);
        let prov = html.find("id=\"provenance\"").expect("provenance section");
        let contact = html.find("id=\"q-contact\"").expect("contact section");
        assert!(prov < contact, "provenance comes first");
        for needle in ["abc1234-dirty", "rustc 1.95.0", "release", "linux x86_64, 2 cores", "seed", ">42<"] {
            assert!(html.contains(needle), "missing {needle:?}");
        }
        assert!(html.contains("fast&lt;f32&gt;") && html.contains(">exact<"), "engine names");
        assert!(!html.contains("fast<f32>"), "an engine name with '<' must be escaped");
        assert_eq!(html.matches("<svg ").count(), charts.len(), "charts inline");
        for c in &charts {
            assert!(html.contains(&format!("href=\"charts/{}\"", c.file)), "link to {}", c.file);
        }
        for f in ["summary.md", "summary.json", "discrepancies.json"] {
            assert!(html.contains(&format!("href=\"{f}\"")), "link to {f}");
        }
        assert_eq!(
            html.matches("http").count(),
            html.matches("http://www.w3.org/2000/svg").count(),
            "no address but the SVG namespace"
        );
        assert!(!html.contains("<script") && !html.contains("<link"), "self-contained");
    }

    #[test]
    fn index_html_is_byte_identical_for_identical_input() {
        let a = index_html(&fixture::summary(), &charts::all(&fixture::summary()));
        let b = index_html(&fixture::summary(), &charts::all(&fixture::summary()));
        assert_eq!(a, b);
    }
}
