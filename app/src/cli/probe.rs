//! `regatta probe`: sea, wake and foam values at world points (DESIGN.md contract).

use clap::Args;

use crate::error::CliResult;

#[derive(Debug, Args)]
pub struct ProbeArgs {
    /// Race time in seconds since the start.
    #[arg(long)]
    pub t: f64,
}

pub fn run(_a: ProbeArgs) -> CliResult {
    Err(crate::error::CliError::new("probe is not implemented yet"))
}
