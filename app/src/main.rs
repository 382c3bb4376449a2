//! `regatta`: the desktop app and the command line of ../shared/DESIGN.md.
//!
//! Every subcommand lives in its own module under `cli/`. Output that a program reads is JSON
//! on stdout; messages for people go to stderr. A bad input exits non-zero with one sentence.

use clap::Parser;
use regatta::cli::{Cli, dispatch};

fn main() {
    #[cfg(not(target_os = "android"))]
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let cli = Cli::parse();
    if let Err(e) = dispatch(cli) {
        eprintln!("regatta: {e}");
        std::process::exit(1);
    }
}
