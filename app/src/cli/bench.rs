//! `regatta bench [--quick] [--out DIR] [--only SECTION ...]`: run time against error tables.

use std::path::PathBuf;

use clap::Args;

use crate::bench::{BenchContext, run_all};
use crate::error::CliResult;

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Fewer repetitions and smaller grids (a minute or two instead of many).
    #[arg(long)]
    pub quick: bool,
    /// Output folder for report.json, report.md and the SVG plots.
    #[arg(long, default_value = "bench-out")]
    pub out: PathBuf,
    /// Run only these sections (repeatable).
    #[arg(long)]
    pub only: Vec<String>,
}

pub fn run(a: BenchArgs) -> CliResult {
    let ctx = BenchContext {
        out_dir: a.out.clone(),
        quick: a.quick,
    };
    let tables = run_all(&ctx, &a.only)?;
    eprintln!(
        "bench: wrote {} tables to {}",
        tables.len(),
        input::show_path(&a.out.join("report.md"))
    );
    super::output::print_stdout(
        "the bench summary",
        &serde_json::json!({ "out": a.out, "tables": tables.len() }),
    )
}
