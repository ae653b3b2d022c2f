//! The built-in fixtures: the repository's `fixtures/` folder, embedded in
//! the binary when it is built, so that `crashtest report` runs the same
//! cases from any folder and after `cargo install` as from the repository's
//! root. Their cases are shown under `fixtures/…`, as a run at the root
//! names them; a mesh a built-in fixture names by `file` is read from the
//! embedded files too.

use std::path::{Component, Path, PathBuf};

mod files {
    include!(concat!(env!("OUT_DIR"), "/builtin_fixtures.rs"));
}

/// How the command line and the library name the built-in fixtures (the
/// default of `--fixtures`): a path of this name, or below it
/// (`built-in:fixtures/peers`), is never read from disk.
pub const NAME: &str = "built-in:fixtures";

/// The folder their cases are shown under.
pub const SHOWN: &str = "fixtures";

/// What `path` selects of the built-in fixtures, when it names them: the
/// part after [`NAME`] (empty for all of them; `contact.json` or `peers` for
/// one file or folder), as shown (`fixtures/contact.json`).
pub fn selects(path: &Path) -> Option<PathBuf> {
    let rest = path.strip_prefix(NAME).ok()?;
    Some(Path::new(SHOWN).join(rest))
}

/// The built-in fixture files (`.json` and `.obj`), each as it is shown
/// (`fixtures/contact.json`) with its bytes, in the order a walk of the
/// folder reads them.
pub fn files() -> impl Iterator<Item = (PathBuf, &'static [u8])> {
    files::FILES.iter().map(|(rel, bytes)| (Path::new(SHOWN).join(rel), *bytes))
}

/// The embedded file shown as `path` (`fixtures/meshes/bunny.obj`, `..`
/// resolved), if there is one.
pub fn file(path: &Path) -> Option<&'static [u8]> {
    let mut parts: Vec<&str> = Vec::new();
    for c in path.components() {
        match c {
            Component::Normal(p) => parts.push(p.to_str()?),
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::CurDir => {}
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    let (first, rest) = parts.split_first()?;
    if *first != SHOWN {
        return None;
    }
    let rel = rest.join("/");
    files::FILES.iter().find(|(r, _)| *r == rel).map(|(_, b)| *b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_repository_fixtures_are_embedded_byte_for_byte() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
        let mut n = 0;
        for (shown, bytes) in files() {
            let on_disk =
                std::fs::read(root.join(shown.strip_prefix(SHOWN).unwrap())).expect("the file is in fixtures/");
            assert_eq!(on_disk, bytes, "{}", shown.display());
            n += 1;
        }
        assert!(n >= 20, "{n} files embedded");
        assert!(file(Path::new("fixtures/meshes/../meshes/bunny.obj")).is_some());
        assert!(file(Path::new("fixtures/nowhere.json")).is_none());
        assert!(file(Path::new("/fixtures/contact.json")).is_none());
        assert_eq!(selects(Path::new(NAME)), Some(PathBuf::from(SHOWN)));
        assert_eq!(selects(&Path::new(NAME).join("peers")), Some(Path::new(SHOWN).join("peers")));
        assert_eq!(selects(Path::new("fixtures")), None);
    }
}
