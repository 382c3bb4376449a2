//! `regatta`: the desktop app and the command line (docs/command-line.md).
//!
//! Every subcommand lives in its own module under `cli/`. Output that a program reads is JSON
//! on stdout; messages for people go to stderr. A bad input exits non-zero with one sentence.

use regatta::cli::{dispatch, parse_args};
use regatta::terminal::stdout_is_closed;

fn main() {
    #[cfg(not(target_os = "android"))]
    regatta::terminal::init_logging();
    let cli = parse_args(std::env::args_os());
    // With stdout closed (`regatta race --t 10 >&-`) the JSON would vanish and the exit be 0:
    // Rust's stdout ignores EBADF. Refuse before anything opens a file into descriptor 1.
    let result = if stdout_is_closed() && cli.writes_stdout() {
        Err(regatta::error::AppError::new(
            "stdout is closed, so the output has nowhere to go (was it run with >&-?)",
        ))
    } else {
        dispatch(cli)
    };
    if let Err(e) = result {
        // The last defence: whatever a message holds, it prints as one line of safe text.
        eprintln!("regatta: {}", input::one_line(&e.to_string()));
        std::process::exit(1);
    }
}
