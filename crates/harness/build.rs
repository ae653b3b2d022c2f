//! Records the compiler's version for report provenance, and embeds the
//! built-in fixtures (the workspace's `fixtures/` folder: every `.json` and
//! `.obj` file) so that an installed binary runs them from any folder.

use std::path::{Path, PathBuf};

fn main() {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = std::process::Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=CRASHTEST_RUSTC={version}");
    let profile = std::env::var("PROFILE").unwrap_or_else(|_| "unknown".into());
    println!("cargo:rustc-env=CRASHTEST_PROFILE={profile}");
    println!("cargo:rerun-if-changed=build.rs");
    embed_fixtures();
}

/// Writes `$OUT_DIR/builtin_fixtures.rs`: `FILES`, each fixture file's path
/// relative to the fixtures folder (with `/`) and its bytes, sorted by path.
/// A crate built outside the workspace (no `fixtures/` two folders up) embeds
/// none.
fn embed_fixtures() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let root = manifest.join("../../fixtures");
    println!("cargo:rerun-if-changed={}", root.display());
    let mut files = Vec::new();
    if root.is_dir() {
        walk(&root, &root, &mut files);
    }
    files.sort();
    let mut out = String::from(
        "/// The built-in fixture files: each path relative to the fixtures folder, and its bytes.\n\
         pub static FILES: &[(&str, &[u8])] = &[\n",
    );
    for (rel, abs) in &files {
        out.push_str(&format!("    ({rel:?}, include_bytes!({:?})),\n", abs.display().to_string()));
    }
    out.push_str("];\n");
    let dest = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("builtin_fixtures.rs");
    std::fs::write(dest, out).expect("OUT_DIR is writable");
}

/// Every `.json` and `.obj` file under `dir`, as (path relative to `root`
/// with `/` between components, canonical absolute path).
fn walk(root: &Path, dir: &Path, files: &mut Vec<(String, PathBuf)>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            walk(root, &path, files);
        } else if path.extension().is_some_and(|e| e == "json" || e == "obj") {
            let rel = path.strip_prefix(root).expect("under the root");
            let rel: Vec<String> = rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
            let abs = std::fs::canonicalize(&path).unwrap_or(path);
            files.push((rel.join("/"), abs));
        }
    }
}
