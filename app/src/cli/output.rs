//! Output for programs on stdout.

use crate::error::{CliError, CliResult};

/// Print `what`'s JSON (or text) on stdout. A closed pipe (`regatta … | head`) is one clear
/// error, not the panic `println!` makes of it.
pub fn print_stdout(what: &str, text: &dyn std::fmt::Display) -> CliResult {
    use std::io::Write;
    writeln!(std::io::stdout().lock(), "{text}")
        .map_err(|e| CliError::new(format!("could not write {what} to stdout: {e}")))
}
