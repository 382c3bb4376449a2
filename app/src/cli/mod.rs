//! The command line contract (docs/command-line.md). One module per subcommand.

use clap::{Parser, Subcommand};

use crate::error::AppResult;

pub mod bench;
pub mod inputs;
#[cfg(not(target_os = "android"))]
pub mod phone_sim;
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
    /// Run time against error: writes JSON, Markdown and SVG plots into a folder (runs the
    /// `regatta-bench` program beside this one; `regatta bench --help` for its options).
    Bench(bench::BenchArgs),
    /// Recorded camera feeds: write the synthetic feed, check a replay or TUM RGB-D folder.
    Replay(replay::ReplayArgs),
    /// Boat states and ranks at a race time, or the import report (JSON on stdout).
    Race(race::RaceArgs),
    /// Render one frame headless to a PNG; the frame planner's record as JSON on stdout.
    Render(render::RenderArgs),
    /// Write a sea file from a JONSWAP sea state or an NDBC buoy spectrum (JSON on stdout).
    Sea(sea::SeaArgs),
    /// Open the desktop window (also what `regatta` alone does); `--phone` for the phone app.
    #[cfg(not(target_os = "android"))]
    Run(crate::desktop::RunArgs),
    /// The phone app headless, driven by a script: log.jsonl and screenshots in a folder.
    #[cfg(not(target_os = "android"))]
    PhoneSim(phone_sim::PhoneSimArgs),
}

impl Cli {
    /// Whether the command's result is printed on stdout (everything but the window).
    pub fn writes_stdout(&self) -> bool {
        match &self.command {
            None => false,
            #[cfg(not(target_os = "android"))]
            Some(Command::Run(_)) => false,
            Some(_) => true,
        }
    }
}

/// The command line, or exit ([`crate::terminal::parse_or_exit`]).
pub fn parse_args<I, T>(args: I) -> Cli
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    crate::terminal::parse_or_exit(args)
}

pub fn dispatch(cli: Cli) -> AppResult {
    match cli.command {
        #[cfg(not(target_os = "android"))]
        None => crate::desktop::run(crate::desktop::RunArgs::default_app()),
        #[cfg(target_os = "android")]
        None => Err(crate::error::AppError::new(
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
        #[cfg(not(target_os = "android"))]
        Some(Command::PhoneSim(a)) => phone_sim::run(a),
    }
}
