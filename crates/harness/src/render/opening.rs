//! What a report opens with: its findings, rendered by their module.

/// What a report opens with, before its provenance: its findings, already
/// rendered (the page's part may carry its own style and script).
#[derive(Clone, Debug, Default)]
pub struct Opening {
    /// HTML, placed after the page's title.
    pub html: String,
    /// Extra style sheet for it.
    pub style: String,
    /// Its inline script (placed at the end of the page).
    pub script: String,
    /// Markdown, placed after `summary.md`'s title.
    pub markdown: String,
}
