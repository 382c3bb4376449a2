//! `regatta-bench`: what `regatta bench ARGS` runs (the app finds this binary beside its own and
//! passes the arguments on; app/src/cli/bench.rs). Messages are `regatta:` lines as every other
//! subcommand's; the summary is JSON on stdout (docs/command-line.md).

use std::path::PathBuf;

use clap::Parser;
use regatta::error::AppResult;
use regatta_bench::{BenchContext, run_all};

/// Run time against error: writes JSON, Markdown and SVG plots into a folder.
#[derive(Debug, Parser)]
#[command(name = "regatta bench", bin_name = "regatta bench", version)]
struct BenchArgs {
    /// Fewer repetitions and smaller grids (a minute or two instead of many).
    #[arg(long)]
    quick: bool,
    /// Output folder for report.json, report.md and the SVG plots.
    #[arg(long, default_value = "bench-out")]
    out: PathBuf,
    /// Run only these sections (repeatable).
    #[arg(long)]
    only: Vec<String>,
}

fn run(a: BenchArgs) -> AppResult {
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
    regatta::terminal::print_stdout(
        "the bench summary",
        &serde_json::json!({ "out": a.out, "tables": tables.len() }),
    )
}

fn main() {
    #[cfg(not(target_os = "android"))]
    regatta::terminal::init_logging();
    let args: BenchArgs = regatta::terminal::parse_or_exit(std::env::args_os());
    regatta::terminal::run_and_exit(true, || run(args));
}
