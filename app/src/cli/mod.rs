//! The command line contract of ../shared/DESIGN.md. One module per subcommand.

use clap::{Parser, Subcommand};

use crate::error::{CliError, CliResult};

pub mod bench;
pub mod inputs;
pub mod probe;
pub mod race;
pub mod render;
pub mod replay;
pub mod sea;

/// Regatta: a sailing race on a real table, with a living sea drawn over it.
#[derive(Debug, Parser)]
#[command(name = "regatta", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Print wave, wake and foam values at world points and a race time (JSON on stdout).
    Probe(probe::ProbeArgs),
    /// Run time against error: writes JSON, Markdown and SVG plots into a folder.
    Bench(bench::BenchArgs),
    /// Recorded camera feeds: write the synthetic feed, check a replay or TUM RGB-D folder.
    Replay(replay::ReplayArgs),
    /// Boat states and ranks at a race time, or the import report (JSON on stdout).
    Race(race::RaceArgs),
    /// Render one frame headless to a PNG; the frame planner's record as JSON on stdout.
    Render(render::RenderArgs),
    /// Write a sea file from a JONSWAP sea state or an NDBC buoy spectrum (JSON on stdout).
    Sea(sea::SeaArgs),
    /// Open the desktop window (also what `regatta` alone does).
    #[cfg(not(target_os = "android"))]
    Run(crate::desktop::RunArgs),
}

pub fn dispatch(cli: Cli) -> CliResult {
    match cli.command {
        #[cfg(not(target_os = "android"))]
        None => crate::desktop::run(crate::desktop::RunArgs::default_app()),
        #[cfg(target_os = "android")]
        None => Err(crate::error::CliError::new(
            "the desktop window does not run on Android; the APK starts the AR app",
        )),
        Some(Command::Probe(a)) => probe::run(a),
        Some(Command::Bench(a)) => bench::run(a),
        Some(Command::Replay(a)) => replay::run(a),
        Some(Command::Race(a)) => race::run(a),
        Some(Command::Render(a)) => render::run(a),
        Some(Command::Sea(a)) => sea::run(a),
        #[cfg(not(target_os = "android"))]
        Some(Command::Run(a)) => crate::desktop::run(a),
    }
}

/// Print `what`'s JSON (or text) on stdout. A closed pipe (`regatta … | head`) is one clear
/// error, not the panic `println!` makes of it.
pub fn print_stdout(what: &str, text: &dyn std::fmt::Display) -> CliResult {
    use std::io::Write;
    writeln!(std::io::stdout().lock(), "{text}")
        .map_err(|e| CliError::new(format!("could not write {what} to stdout: {e}")))
}
