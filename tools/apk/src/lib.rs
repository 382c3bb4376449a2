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
/// under CI it fails, elsewhere it skips and is counted (`skip_log`, docs/testing.md).
#[doc(hidden)]
pub use skip_log::unless_ci as skip_unless_ci;
