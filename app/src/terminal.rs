//! What a command-line program of the app (`regatta`, `regatta-bench`) prints: every message
//! as one `regatta:` line on stderr, clap's errors too, output on stdout that reports a closed
//! pipe instead of panicking, and a stdout closed before the program started.

use crate::error::{AppError, AppResult};

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

/// Print `what`'s JSON (or text) on stdout. A closed pipe (`regatta … | head`) is one clear
/// error, not the panic `println!` makes of it.
pub fn print_stdout(what: &str, text: &dyn std::fmt::Display) -> AppResult {
    use std::io::Write;
    writeln!(std::io::stdout().lock(), "{text}")
        .map_err(|e| AppError::new(format!("could not write {what} to stdout: {e}")))
}

/// Warnings for people print as every other message does, `regatta: <one line>` (the
/// logger's `[time WARN module]` prefix broke that style, and a failing phone-sim printed two
/// lines); with `RUST_LOG` set, a developer gets the logger's own format. For `regatta` and
/// `regatta-bench` alike.
#[cfg(not(target_os = "android"))]
pub fn init_logging() {
    let mut b = env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"));
    if std::env::var_os("RUST_LOG").is_none() {
        b.format(|buf, record| {
            use std::io::Write;
            writeln!(buf, "{}", user_line(&record.args().to_string()))
        });
    }
    b.init();
}

/// The command line as `P`, or exit: help and version print as clap prints them; every other
/// clap error (unknown or repeated flag, bad value, missing argument) is one line on stderr,
/// exit 2.
pub fn parse_or_exit<P, I, T>(args: I) -> P
where
    P: clap::Parser,
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    use clap::error::ErrorKind;
    match P::try_parse_from(args) {
        Ok(parsed) => parsed,
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

/// A program's run and end: with stdout closed (`regatta race --t 10 >&-`) a run that
/// `writes_stdout` is refused before anything opens a file into descriptor 1 (Rust's stdout
/// ignores EBADF: the output would vanish and the exit be 0); an error prints as one line of
/// safe text, whatever it holds, and exits 1.
pub fn run_and_exit(writes_stdout: bool, run: impl FnOnce() -> AppResult) {
    let result = if writes_stdout && stdout_is_closed() {
        Err(AppError::new(
            "stdout is closed, so the output has nowhere to go (was it run with >&-?)",
        ))
    } else {
        run()
    };
    if let Err(e) = result {
        eprintln!("regatta: {}", input::one_line(&e.to_string()));
        std::process::exit(1);
    }
}

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
