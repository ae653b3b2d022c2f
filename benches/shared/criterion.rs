//! Reading criterion's estimates back, shared by the benchmarks' tables
//! (`queries`, `mesh`, `toi`).

use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// Where criterion writes: `$CARGO_TARGET_DIR/criterion`, else the
/// workspace's `target/criterion`.
pub fn criterion_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("criterion")
}

/// Nanoseconds per query (or element) of benchmark `group/id`, from
/// criterion's estimate written during this run (`since`): its slope (time per
/// iteration, by regression over the samples) or, failing that, its mean,
/// divided by the queries per iteration. `None` when the benchmark did not run
/// this time.
pub fn ns_per(group: &str, id: &str, per_iter: usize, since: SystemTime) -> Option<f64> {
    let path = criterion_dir().join(group).join(id).join("new").join("estimates.json");
    let written = std::fs::metadata(&path).and_then(|m| m.modified()).ok()?;
    if written < since {
        return None;
    }
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).ok()?).ok()?;
    let pick = |k: &str| json.get(k)?.get("point_estimate")?.as_f64();
    let ns = pick("slope").or_else(|| pick("mean"))?;
    Some(ns / per_iter as f64)
}
