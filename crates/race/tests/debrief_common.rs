// Helpers for the debrief's tests on ../shared/data (included with `mod debrief_common;`).
#![allow(dead_code)]

use std::path::PathBuf;

/// `../shared/data/<rel>` relative to the workspace root; `REGATTA_SHARED_DATA` names another
/// copy of that folder (a git worktree outside the checkout's parent).
pub fn shared(rel: &str) -> PathBuf {
    match std::env::var_os("REGATTA_SHARED_DATA") {
        Some(d) => PathBuf::from(d).join(rel),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../../shared/data")
            .join(rel),
    }
}

/// The file's text, or `None` where the shared data are absent.
pub fn read_shared(rel: &str) -> Option<String> {
    let p = shared(rel);
    if !p.exists() {
        return None;
    }
    Some(std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display())))
}

/// A test without its data: fails under `CI=true`, elsewhere prints `skipped: ...` and appends
/// `TEST: REASON` to the file `REGATTA_SKIP_LOG` names (scripts/test.sh counts them).
pub fn skip(test: &str, missing: &str) {
    let reason = format!("{missing} is absent");
    if std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("{test}: {reason}, and CI must have it");
    }
    eprintln!("skipped: {reason}");
    if let Some(log) = std::env::var_os("REGATTA_SKIP_LOG") {
        use std::io::Write;
        let mut f = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&log)
            .unwrap_or_else(|e| panic!("REGATTA_SKIP_LOG {}: {e}", log.to_string_lossy()));
        writeln!(f, "{test}: {reason}").unwrap();
    }
}

/// Seconds of a time of day "HH:MM:SS(.fff)".
pub fn hms(s: &str) -> f64 {
    let v: Vec<f64> = s.split(':').map(|p| p.parse().unwrap()).collect();
    v[0] * 3600.0 + v[1] * 60.0 + v[2]
}
