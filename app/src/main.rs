//! `regatta`: the desktop app and the command line (docs/command-line.md).
//!
//! Every subcommand lives in its own module under `cli/`. Output that a program reads is JSON
//! on stdout; messages for people go to stderr. A bad input exits non-zero with one sentence.

use regatta::cli::{dispatch, parse_args};

fn main() {
    #[cfg(not(target_os = "android"))]
    regatta::terminal::init_logging();
    let cli = parse_args(std::env::args_os());
    regatta::terminal::run_and_exit(cli.writes_stdout(), || dispatch(cli));
}
