//! `regatta bench ARGS`: runs the `regatta-bench` program (tools/bench) from the folder this
//! executable is in, as cargo runs `cargo-NAME` for `cargo NAME`. The bench is a package of its
//! own on this library, so the Android library carries none of it; cargo forbids the cycle an
//! in-process call would need. Its arguments, stdio and exit code pass through unchanged.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use clap::Args;

use crate::error::{AppError, AppResult};

/// The bench's own arguments (`regatta bench --help` prints them): passed on untouched.
#[derive(Debug, Args)]
#[command(disable_help_flag = true, disable_version_flag = true)]
pub struct BenchArgs {
    #[arg(trailing_var_arg = true, allow_hyphen_values = true, num_args = 0..)]
    pub args: Vec<OsString>,
}

/// The bench program's file name on this platform.
pub const BENCH_PROGRAM: &str = if cfg!(windows) {
    "regatta-bench.exe"
} else {
    "regatta-bench"
};

/// Where the bench program must be: beside the running executable.
fn bench_beside(exe: &Path) -> PathBuf {
    exe.with_file_name(BENCH_PROGRAM)
}

/// The sentence for a missing bench: where it was looked for and the cargo command that builds
/// it (`--release` when the running executable is a release build).
pub fn missing_bench(path: &Path) -> String {
    let release = path
        .parent()
        .and_then(Path::file_name)
        .is_some_and(|d| d == "release");
    format!(
        "the bench is a program of its own and {} does not exist; build it with `cargo build{} -p regatta-bench`",
        input::show_path(path),
        if release { " --release" } else { "" }
    )
}

/// Runs the bench with `a`'s arguments; returns only on success or when it could not start, and
/// otherwise exits with the bench's own exit code.
pub fn run(a: BenchArgs) -> AppResult {
    let exe = std::env::current_exe()
        .map_err(|e| AppError::new(format!("cannot tell where this program is: {e}")))?;
    let bench = bench_beside(&exe);
    if !bench.is_file() {
        return Err(AppError::new(missing_bench(&bench)));
    }
    let status = std::process::Command::new(&bench)
        .args(&a.args)
        .status()
        .map_err(|e| AppError::new(format!("could not start {}: {e}", input::show_path(&bench))))?;
    match status.code() {
        Some(0) => Ok(()),
        Some(code) => std::process::exit(code),
        // Ended by a signal: the shell's convention, 128 + the signal's number.
        None => std::process::exit(signal_exit_code(&status)),
    }
}

#[cfg(unix)]
fn signal_exit_code(status: &std::process::ExitStatus) -> i32 {
    use std::os::unix::process::ExitStatusExt;
    status.signal().map_or(1, |s| 128 + s)
}

#[cfg(not(unix))]
fn signal_exit_code(_: &std::process::ExitStatus) -> i32 {
    1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_bench_names_its_path_and_the_build_command_of_the_same_profile() {
        let debug = missing_bench(Path::new("/t/target/debug/regatta-bench"));
        assert!(
            debug.ends_with("build it with `cargo build -p regatta-bench`"),
            "{debug}"
        );
        assert!(debug.contains("/t/target/debug/regatta-bench"), "{debug}");
        let release = missing_bench(Path::new("/t/target/release/regatta-bench"));
        assert!(
            release.ends_with("`cargo build --release -p regatta-bench`"),
            "{release}"
        );
    }
}
