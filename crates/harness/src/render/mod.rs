//! How a report is shown: its page ([`html`]), its Markdown ([`markdown`]), its
//! charts ([`charts`], drawn with [`plot`]) and the sections the experiments
//! add ([`section`]). Rendering takes measured data — a [`Summary`], a
//! section's tables and charts — and never runs anything.

pub mod charts;
pub mod html;
pub mod markdown;
pub mod opening;
pub mod plot;
pub mod section;
pub mod xml;

use crate::summary::Summary;
use std::path::PathBuf;

/// The rendered files of a report besides its JSON: `index.html`, `summary.md`
/// and `charts/*.svg`, as (path relative to the report folder, contents).
pub fn pages(summary: &Summary) -> Vec<(PathBuf, String)> {
    pages_with(summary, &opening::Opening::default())
}

/// [`pages`] opening with `opening`.
pub fn pages_with(summary: &Summary, opening: &opening::Opening) -> Vec<(PathBuf, String)> {
    let charts = charts::all(summary);
    let mut files = vec![
        (PathBuf::from("index.html"), html::index_html_with(summary, &charts, opening)),
        (PathBuf::from("summary.md"), markdown::summary_md_with(summary, &opening.markdown)),
    ];
    files.extend(charts.into_iter().map(|c| (PathBuf::from("charts").join(c.file), c.svg)));
    files
}
