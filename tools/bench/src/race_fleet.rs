//! Bench table `race_fleet`: import time against the fleet's size. One tracker CSV of N boats
//! (10 fixes each, `race::synth_logs::fleet_csv`) is loaded by `Race::from_files`; the time per
//! boat stays flat when the import is linear in the boat count. Issue 30: it grew faster than
//! quadratically (10k boats 0.5 s, 20k 2.9 s, 40k 16.6 s) while each row looked its boat up by
//! scanning every boat read so far, and assembling checked ids and duplicate tracks pairwise.

use std::time::Instant;

use race::Race;
use race::synth_logs::fleet_csv;
use serde_json::json;

use crate::{BenchContext, Table};
use regatta::error::{AppError, AppResult};

/// Fixes per boat in the generated fleet.
const FIXES: usize = 10;

pub fn table(ctx: &BenchContext) -> AppResult<Table> {
    let fleets: &[usize] = if ctx.quick {
        &[2_500, 5_000, 10_000]
    } else {
        &[10_000, 20_000, 40_000]
    };
    let mut t = Table::new(
        "race_fleet",
        "Race import time against the fleet's size (one CSV, 10 fixes a boat)",
        &[
            "boats",
            "file MB",
            "import s (wall)",
            "µs per boat",
            "× the smallest fleet's µs per boat",
        ],
    );
    let mut first_per_boat = None;
    for &boats in fleets {
        ctx.progress(format!("race fleet: {boats} boats"));
        let text = fleet_csv(boats, FIXES);
        let t0 = Instant::now();
        let race = Race::from_files(&[("fleet.csv", text.as_bytes())])
            .map_err(|e| AppError::new(format!("the bench fleet did not load: {e}")))?;
        let secs = t0.elapsed().as_secs_f64();
        if race.boats.len() != boats {
            return Err(AppError::new(format!(
                "the bench fleet loaded {} boats of {boats}",
                race.boats.len()
            )));
        }
        let per_boat_us = secs / boats as f64 * 1e6;
        let base = *first_per_boat.get_or_insert(per_boat_us);
        t.row(vec![
            json!(boats),
            json!(text.len() as f64 / 1e6),
            json!(secs),
            json!(per_boat_us),
            json!(per_boat_us / base),
        ]);
    }
    t.note(
        "Method: the fleet file is generated in memory, then loaded once (detection, parsing, \
         splitting rows by boat, cleaning, derivation, roundings); wall time of that load. \
         Linear import keeps the last column near 1; the goal (issue 30) is a 40,000-boat CSV \
         in under 5 s.",
    );
    Ok(t)
}
