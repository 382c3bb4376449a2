//! Inputs shared by several subcommands: the sea (`--sea`). Races (`--race`) join here when the
//! race crate lands.

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use ocean::WaveSet;

use crate::error::{CliError, CliResult};

/// Parse `--size WxH` (or `WXH`) with each side in `sides` pixels; a bad size is the sentence
/// `--size "S" is not {expected}`.
pub fn parse_size_in(s: &str, sides: RangeInclusive<u32>, expected: &str) -> CliResult<[u32; 2]> {
    let bad = || CliError::new(format!("--size \"{s}\" is not {expected}"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if !sides.contains(&w) || !sides.contains(&h) {
        return Err(bad());
    }
    Ok([w, h])
}

/// Read a file into a string, with the path named in the error.
pub fn read_text(path: &Path) -> CliResult<String> {
    std::fs::read_to_string(path)
        .map_err(|e| CliError::new(format!("could not read {}: {e}", path.display())))
}

/// The sea of `--sea FILE`, or the embedded default sea.
pub fn load_sea(sea: Option<&PathBuf>) -> CliResult<WaveSet> {
    match sea {
        Some(p) => Ok(
            WaveSet::from_json_str(&read_text(p)?, &p.display().to_string())
                .map_err(|e| CliError::new(e.to_string()))?,
        ),
        None => Ok(WaveSet::default_sea()),
    }
}

/// The race of `--race PATH ...` (files combined into one race), or the embedded sample race.
pub fn load_race(paths: &[PathBuf]) -> CliResult<race::Race> {
    load_race_with(paths, &race::LoadOptions::default())
}

/// [`load_race`] with options (`regatta race --keep-going --session --marks --course`). What
/// the import dropped or changed is said on stderr, one escaped line each, so nothing is lost
/// silently (the same warnings are in `regatta race --report`).
pub fn load_race_with(paths: &[PathBuf], opts: &race::LoadOptions) -> CliResult<race::Race> {
    if paths.is_empty() {
        return Ok(race::Race::sample());
    }
    let r = race::Race::load_with(paths, opts).map_err(|e| CliError::new(e.to_string()))?;
    for w in &r.report.warnings {
        eprintln!("regatta: warning: {}", race::text::escape(w));
    }
    Ok(r)
}
