//! A report's extra sections: parts that are not per-query statistics —
//! dynamics, stability sweeps, what a scene needs, time of impact — each
//! rendered by its own module into one [`Section`].
//!
//! Decision: a section arrives already rendered (HTML body, Markdown, SVG
//! charts) plus its data. The report writes them as they are, and keeps every
//! section in `sections.json`, so that `crashtest merge` carries the sections
//! of a sharded run into the merged report unchanged instead of dropping them.

use super::xml::escape;
use serde::{Deserialize, Serialize};
use std::fmt::Write;
use std::path::PathBuf;

/// One extra section of a report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// Its anchor in `index.html` and the stem of its data file (`<id>.json`).
    pub id: String,
    /// Its heading.
    pub title: String,
    /// Its body in `index.html`, already escaped, without the heading; the
    /// charts follow it.
    pub html: String,
    /// Its part of `summary.md`, starting with `## <title>`.
    pub markdown: String,
    /// Its charts: inlined after the body and written to `charts/<file>`.
    pub charts: Vec<SectionChart>,
    /// Everything it measured, written as `<id>.json`.
    pub data: serde_json::Value,
}

/// One chart of a section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SectionChart {
    /// Its caption.
    pub title: String,
    /// Its file name inside the report's `charts/` folder.
    pub file: String,
    /// The SVG document (no XML declaration, no element ids: it inlines as is).
    pub svg: String,
}

impl Section {
    /// The section saying which of the engines given it did not run, and why
    /// (unchanged when `engines` is empty).
    pub fn with_not_run(mut self, engines: &[&str], reason: &str) -> Self {
        if !engines.is_empty() {
            let line = format!("Not run here: {} — {reason}", engines.join(", "));
            let _ = writeln!(self.html, "<p class=\"not-run\">{}</p>", escape(&line));
            let _ = write!(self.markdown, "\n{line}\n");
        }
        self
    }

    /// Its part of `index.html`: heading, body, charts as figures.
    pub fn to_html(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "<section id=\"{}\">\n<h2>{}</h2>", escape(&self.id), escape(&self.title));
        out.push_str(&self.html);
        for c in &self.charts {
            let _ = writeln!(
                out,
                "<figure>{}<figcaption>{} — <a href=\"charts/{f}\">charts/{f}</a></figcaption></figure>",
                c.svg,
                escape(&c.title),
                f = escape(&c.file)
            );
        }
        out.push_str("</section>\n");
        out
    }

    /// The files it adds to a report: `<id>.json` and its charts.
    pub fn files(&self) -> Vec<(PathBuf, String)> {
        // Compact: a section's data can run to megabytes (every sweep point of
        // every engine); pretty-printing it would multiply that about five-fold.
        let mut data = serde_json::to_string(&self.data).unwrap_or_else(|e| format!("\"unserializable: {e}\""));
        data.push('\n');
        let mut out = vec![(PathBuf::from(format!("{}.json", self.id)), data)];
        out.extend(self.charts.iter().map(|c| (PathBuf::from("charts").join(&c.file), c.svg.clone())));
        out
    }
}

/// Adds `sections` to rendered report files: each section's HTML goes before
/// the last heading of `index.html` (the list of the report's files), with a
/// link in that list to its data file; its Markdown is appended to
/// `summary.md`; its data and charts become files; and `sections.json` keeps
/// them all for merging.
pub fn add_sections(files: &mut Vec<(PathBuf, String)>, sections: &[Section]) {
    let mut html = String::new();
    let mut links = String::new();
    let mut md = String::new();
    for s in sections {
        html.push_str(&s.to_html());
        md.push('\n');
        md.push_str(&s.markdown);
        let _ = writeln!(
            links,
            "<li><a href=\"{f}.json\"><code>{f}.json</code></a> — {}: everything it measured</li>",
            escape(&s.title),
            f = escape(&s.id)
        );
        for c in &s.charts {
            let _ = writeln!(
                links,
                "<li><a href=\"charts/{f}\"><code>charts/{f}</code></a> — {}</li>",
                escape(&c.title),
                f = escape(&c.file)
            );
        }
    }
    for (path, contents) in files.iter_mut() {
        if path.as_os_str() == "summary.md" {
            contents.push_str(&md);
        } else if path.as_os_str() == "index.html" {
            if let Some(at) = contents.find("</ul>\n</main>") {
                contents.insert_str(at, &links);
            }
            if let Some(at) = contents.rfind("<h2") {
                contents.insert_str(at, &html);
            }
            if let Some(at) = contents.find("<a href=\"#throughput\">") {
                let nav: String =
                    sections.iter().map(|s| format!("<a href=\"#{}\">{}</a>", escape(&s.id), escape(&s.id))).collect();
                contents.insert_str(at, &nav);
            }
        }
    }
    for s in sections {
        files.extend(s.files());
    }
    let mut all = serde_json::to_string(sections).unwrap_or_else(|e| format!("\"unserializable: {e}\""));
    all.push('\n');
    files.push((PathBuf::from("sections.json"), all));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::charts::fixture;

    fn sample() -> Section {
        Section {
            id: "stability".into(),
            title: "Stability <sweeps>".into(),
            html: "<p>body</p>\n".into(),
            markdown: "## Stability\n\ntext\n".into(),
            charts: vec![SectionChart {
                title: "angle".into(),
                file: "stability-angle.svg".into(),
                svg: "<svg></svg>".into(),
            }],
            data: serde_json::json!({"points": [1, 2]}),
        }
    }

    #[test]
    fn sections_land_in_every_page_and_file() {
        let mut files = crate::render::pages(&fixture::summary());
        add_sections(&mut files, &[sample()]);
        let get = |name: &str| files.iter().find(|(p, _)| p.as_os_str() == name).map(|(_, c)| c.clone());
        let html = get("index.html").expect("index.html");
        let body = html.find("<section id=\"stability\">").expect("section inlined");
        assert!(body < html.find("id=\"files\"").expect("files list"), "before the list of files");
        assert!(html.contains("Stability &lt;sweeps&gt;"), "title escaped");
        assert!(html.contains("href=\"#stability\""), "nav link");
        assert!(html.contains("href=\"stability.json\"") && html.contains("href=\"charts/stability-angle.svg\""));
        assert!(get("summary.md").expect("summary.md").ends_with("## Stability\n\ntext\n"));
        assert!(get("stability.json").expect("data file").contains("\"points\""));
        assert_eq!(get("charts/stability-angle.svg").as_deref(), Some("<svg></svg>"));
        let back: Vec<Section> = serde_json::from_str(&get("sections.json").expect("sections.json")).expect("parses");
        assert_eq!(back, vec![sample()], "sections.json round-trips");
    }
}
