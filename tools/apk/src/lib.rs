//! Packages Regatta's Android APK on the build host, without the Android SDK: reads the cargo-apk
//! metadata of `app/Cargo.toml` (so `cargo apk build` and `scripts/build-apk.sh` make the same
//! manifest), then builds, aligns and signs the APK with the `rust-apk` crate, with a debug key
//! generated on first use.

#[cfg(not(target_os = "android"))]
pub mod aar;
#[cfg(not(target_os = "android"))]
pub mod bench_free;
#[cfg(not(target_os = "android"))]
pub mod check;
#[cfg(not(target_os = "android"))]
pub mod key;
#[cfg(not(target_os = "android"))]
pub mod metadata;
#[cfg(not(target_os = "android"))]
pub mod package;
#[cfg(not(target_os = "android"))]
pub mod symbols;

/// A packaging error: one sentence naming the file (and field) at fault.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApkError(pub String);

impl std::fmt::Display for ApkError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ApkError {}

/// For a test whose prerequisite (an Android C toolchain, `../shared/data/android`) is missing:
/// under CI (`CI=true`, as scripts/test.sh passes it on) the test fails with `reason`; elsewhere
/// it skips, printing "skipped: REASON" and appending "TEST: REASON" to the file named by
/// `REGATTA_SKIP_LOG`, which scripts/test.sh counts (see docs/testing.md).
#[doc(hidden)]
pub fn skip_unless_ci(reason: &str) {
    use std::io::Write;
    let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
    assert!(!ci, "CI=true but {reason}");
    eprintln!("skipped: {reason}");
    if let Some(log) = std::env::var_os("REGATTA_SKIP_LOG") {
        let test = std::thread::current().name().unwrap_or("?").to_owned();
        std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&log)
            .and_then(|mut f| f.write_all(format!("{test}: {reason}\n").as_bytes()))
            .unwrap_or_else(|e| panic!("REGATTA_SKIP_LOG {}: {e}", log.display()));
    }
}
