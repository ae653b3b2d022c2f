//! Reports: the campaign ([`campaign`]), what it measured ([`summary`]), how it
//! is shown ([`charts`], [`markdown`], [`html`]) and written ([`write`](mod@write)).

pub mod bench;
pub mod campaign;
pub mod charts;
pub mod html;
pub mod markdown;
pub mod peers;
pub mod plot;
pub mod provenance;
pub mod section;
pub mod summary;
pub mod write;

use std::path::PathBuf;

/// The rendered files of a report besides its JSON: `index.html`, `summary.md`
/// and `charts/*.svg`, as (path relative to the report folder, contents).
pub fn pages(summary: &summary::Summary) -> Vec<(PathBuf, String)> {
    let charts = charts::all(summary);
    let mut files = vec![
        (PathBuf::from("index.html"), html::index_html(summary, &charts)),
        (PathBuf::from("summary.md"), markdown::summary_md(summary)),
    ];
    files.extend(charts.into_iter().map(|c| (PathBuf::from("charts").join(c.file), c.svg)));
    files
}
