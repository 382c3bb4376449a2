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

/// A test without its data: fails under `CI=true`, elsewhere skips and is counted
/// (`skip_log::unless_ci`, docs/testing.md).
pub fn skip(test: &str, missing: &str) {
    skip_log::unless_ci(&format!("{test}: {missing} is absent"));
}

/// Seconds of a time of day "HH:MM:SS(.fff)".
pub fn hms(s: &str) -> f64 {
    let v: Vec<f64> = s.split(':').map(|p| p.parse().unwrap()).collect();
    v[0] * 3600.0 + v[1] * 60.0 + v[2]
}
