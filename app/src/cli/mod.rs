//! The command line contract (docs/command-line.md). One module per subcommand.

use clap::{Parser, Subcommand};

use crate::error::CliResult;

pub mod bench;
pub mod inputs;
pub mod output;
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

/// The command line, or exit: help and version print as clap prints them; every other clap
/// error (unknown or repeated flag, bad value, missing argument) is one line on stderr, exit 2.
pub fn parse_args<I, T>(args: I) -> Cli
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    use clap::error::ErrorKind;
    match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
            _ => {
                eprintln!("regatta: {}", clap_one_line(&e.to_string()));
                std::process::exit(2);
            }
        },
    }
}

/// A clap error (`error: …`, indented details, tips, then a usage block) as one line: the first
/// paragraph and the tips, joined; the usage block is left to `--help`.
pub fn clap_one_line(rendered: &str) -> String {
    let mut parts = Vec::new();
    for (i, paragraph) in rendered.split("\n\n").enumerate() {
        let text = paragraph
            .lines()
            .map(str::trim)
            .collect::<Vec<_>>()
            .join(" ");
        if i == 0 {
            parts.push(text.trim_start_matches("error: ").to_string());
        } else if text.starts_with("tip:") {
            parts.push(text);
        }
    }
    input::one_line(&format!("{} (see --help)", parts.join("; ")))
}

/// A message for stderr as the one `regatta:` line every message is: control characters
/// escaped, cut, one `regatta:` prefix (log lines that carry their own keep one).
pub fn user_line(msg: &str) -> String {
    let msg = msg.strip_prefix("regatta: ").unwrap_or(msg);
    format!("regatta: {}", input::one_line(msg))
}

/// True when descriptor 1 was closed when the program started (`>&-`). Rust's runtime reopens
/// a closed stdout on /dev/null (read-write) before `main`, so the output would vanish with exit
/// 0; a shell's `>/dev/null` opens it write-only, which stays allowed. Linux and Android tell
/// the two apart through /proc; elsewhere only a still-closed descriptor is detected.
pub fn stdout_is_closed() -> bool {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        let Ok(fd) = std::io::stdout().as_fd().try_clone_to_owned() else {
            return true;
        };
        #[cfg(any(target_os = "linux", target_os = "android"))]
        {
            use std::os::unix::fs::{FileTypeExt, MetadataExt};
            let (Ok(out), Ok(null)) = (
                std::fs::File::from(fd).metadata(),
                std::fs::metadata("/dev/null"),
            ) else {
                return false;
            };
            if !out.file_type().is_char_device() || out.rdev() != null.rdev() {
                return false;
            }
            const O_ACCMODE: u32 = 0o3;
            const O_RDWR: u32 = 0o2;
            std::fs::read_to_string("/proc/self/fdinfo/1")
                .ok()
                .and_then(|info| {
                    let flags = info.lines().find_map(|l| l.strip_prefix("flags:"))?;
                    u32::from_str_radix(flags.trim(), 8).ok()
                })
                .is_some_and(|flags| flags & O_ACCMODE == O_RDWR)
        }
        #[cfg(not(any(target_os = "linux", target_os = "android")))]
        {
            drop(fd);
            false
        }
    }
    #[cfg(not(unix))]
    false
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
        #[cfg(not(target_os = "android"))]
        Some(Command::PhoneSim(a)) => phone_sim::run(a),
    }
}

pub use output::print_stdout;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_lines_print_as_one_regatta_line() {
        assert_eq!(
            user_line("regatta: no wakes\nsecond line"),
            "regatta: no wakes\\nsecond line"
        );
        assert_eq!(
            user_line("no GPU timings this frame: x"),
            "regatta: no GPU timings this frame: x"
        );
    }

    #[test]
    fn clap_errors_become_one_line_with_their_details_and_tips() {
        let two = "error: the following required arguments were not provided:\n  --out <OUT>\n\nUsage: regatta render --out <OUT>\n\nFor more information, try '--help'.\n";
        assert_eq!(
            clap_one_line(two),
            "the following required arguments were not provided: --out <OUT> (see --help)"
        );
        let tip = "error: unexpected argument '--fo\u{1b}o' found\n\n  tip: to pass '--fo\u{1b}o' as a value, use '-- --fo\u{1b}o'\n\nUsage: regatta race [OPTIONS]\n";
        assert_eq!(
            clap_one_line(tip),
            "unexpected argument '--fo\\u{1b}o' found; tip: to pass '--fo\\u{1b}o' as a value, use '-- --fo\\u{1b}o' (see --help)"
        );
    }
}
