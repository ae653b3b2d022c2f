//! Where and how a report was made: commit, compiler, profile, machine, time.

use crate::summary::Provenance;
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// The provenance of a run starting now, engines and counts still to fill in.
pub fn here() -> Provenance {
    Provenance {
        crashtest: env!("CARGO_PKG_VERSION").into(),
        commit: commit(),
        rustc: env!("CRASHTEST_RUSTC").into(),
        profile: env!("CRASHTEST_PROFILE").into(),
        machine: machine(),
        started: rfc3339(SystemTime::now()),
        ..Default::default()
    }
}

/// `git rev-parse HEAD`, with `-dirty` when the work tree has changes; `None`
/// outside a checkout or without git.
pub fn commit() -> Option<String> {
    let head = Command::new("git").args(["rev-parse", "HEAD"]).output().ok().filter(|o| o.status.success())?;
    let mut id = String::from_utf8_lossy(&head.stdout).trim().to_string();
    let dirty = Command::new("git")
        .args(["status", "--porcelain", "--untracked-files=no"])
        .output()
        .ok()
        .is_some_and(|o| !o.stdout.is_empty());
    if dirty {
        id.push_str("-dirty");
    }
    Some(id)
}

/// OS, architecture, CPU model and core count.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    format!("{} {}, {cpu}, {cores} cores", std::env::consts::OS, std::env::consts::ARCH)
}

/// A time as RFC 3339 UTC (`2026-11-22T23:14:06Z`).
pub fn rfc3339(t: SystemTime) -> String {
    let secs = t.duration_since(UNIX_EPOCH).map(|d| d.as_secs()).unwrap_or(0);
    let (days, rem) = (secs / 86_400, secs % 86_400);
    let (y, m, d) = civil_from_days(days as i64);
    format!("{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z", rem / 3600, rem % 3600 / 60, rem % 60)
}

/// A compact id for a report folder made at `t`: `20261122-231406`.
pub fn stamp(t: SystemTime) -> String {
    rfc3339(t).replace(['-', ':'], "").replace('T', "-").trim_end_matches('Z').to_string()
}

/// Days since 1970-01-01 to (year, month, day), proleptic Gregorian (Howard
/// Hinnant's `civil_from_days`).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (if m <= 2 { y + 1 } else { y }, m, d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn dates_are_civil() {
        // 2000-03-01T00:00:00Z is 951868800 s after the epoch (a leap-year boundary).
        assert_eq!(rfc3339(UNIX_EPOCH + Duration::from_secs(951_868_800)), "2000-03-01T00:00:00Z");
        // 2026-11-22T23:14:06Z = 1795389246 s.
        assert_eq!(rfc3339(UNIX_EPOCH + Duration::from_secs(1_795_389_246)), "2026-11-22T23:14:06Z");
        assert_eq!(stamp(UNIX_EPOCH + Duration::from_secs(1_795_389_246)), "20261122-231406");
    }
}
