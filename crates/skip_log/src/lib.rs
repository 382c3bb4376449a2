//! How a test that cannot run here says so (no GPU adapter, no `xvfb-run`, no Android clang, no
//! `../shared/data`): it never passes silently.
//!
//! A skip prints `skipped: REASON` on stderr (which the test harness hides for a passing test)
//! and appends one line `TEST: REASON` to the file named by [`LOG_ENV`]. `scripts/test.sh` sets
//! that variable, prints the count and the lines at the end, and fails a run under `CI=true`
//! that skipped anything. A test whose missing input CI must have calls [`unless_ci`], which
//! fails at once under CI.
//!
//! It never knows what a test tests: only the environment and the log file.

use std::io::Write;
use std::path::Path;

/// The environment variable naming the file that gets one line per skipped test.
pub const LOG_ENV: &str = "REGATTA_SKIP_LOG";

/// True under CI (`CI=true` or `CI=1`), where nothing may skip.
pub fn ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true" || v == "1")
}

/// Report a test that skips: `skipped: REASON` on stderr, and `TEST: REASON` appended to the
/// file [`LOG_ENV`] names (the test is the current thread's name, as the harness sets it).
/// Panics when that file cannot be written: a skip that is not counted would pass silently.
pub fn record(reason: &str) {
    eprintln!("skipped: {reason}");
    if let Some(log) = std::env::var_os(LOG_ENV) {
        let test = std::thread::current().name().unwrap_or("?").to_owned();
        if let Err(e) = append(Path::new(&log), &test, reason) {
            panic!(
                "{LOG_ENV}: cannot append to {}: {e}",
                Path::new(&log).display()
            );
        }
    }
}

/// [`record`] outside CI; under CI a failure: `CI=true but REASON`.
pub fn unless_ci(reason: &str) {
    assert!(!ci(), "CI=true but {reason}");
    record(reason);
}

/// Append `TEST: REASON` as one line (newlines in the reason become spaces), in one short
/// `O_APPEND` write, so test binaries running at once do not interleave their lines.
fn append(log: &Path, test: &str, reason: &str) -> std::io::Result<()> {
    let line = format!("{test}: {}\n", reason.replace(['\n', '\r'], " "));
    std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(log)?
        .write_all(line.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two skips append two whole lines, each named by its test and with the reason's
    /// newlines flattened: the format scripts/test.sh counts with `grep -c .`.
    #[test]
    fn each_skip_is_one_line_named_by_its_test() {
        let dir = std::env::temp_dir().join(format!("skip_log-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let log = dir.join("skips");
        let _ = std::fs::remove_file(&log);
        append(&log, "a::test", "no GPU adapter\n(lavapipe missing)").unwrap();
        append(&log, "b::test", "no xvfb-run").unwrap();
        let text = std::fs::read_to_string(&log).unwrap();
        assert_eq!(
            text,
            "a::test: no GPU adapter (lavapipe missing)\nb::test: no xvfb-run\n"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
