//! Inputs shared by several subcommands: the sea (`--sea`), sizes, and the checks of numeric
//! options, and the race of `--race` (every format `race::load` reads, combined into one race).

use std::ops::RangeInclusive;
use std::path::PathBuf;

use ocean::WaveSet;

use crate::error::{CliError, CliResult};

/// clap's parser for a whole-number option: `--waves -1` or `--seed x` is refused by saying
/// the values the option takes (`takes`, e.g. "from 1 to 4096"), where clap took `-1` for an
/// unknown flag before (the argument also sets `allow_negative_numbers`). A value that parses is
/// range-checked where the option is used, as before.
pub fn whole_number<T>(
    takes: &'static str,
) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: std::str::FromStr + Clone + Send + Sync + 'static,
{
    move |s: &str| {
        s.trim()
            .parse::<T>()
            .map_err(|_| format!("give a whole number {takes}"))
    }
}

/// Largest |race time|, seconds, for `--t` of `probe`, `race` and `render`: 31 years; a phase
/// ω t keeps 1e-7 rad there.
pub const MAX_TIME_S: f64 = 1.0e9;

/// `--t` of `race` and `render`: the same cap `probe` has (±[`MAX_TIME_S`], 31
/// years), where they took `--t 1e300` before.
pub fn check_race_time(t: f64) -> CliResult<f64> {
    if t.abs() <= MAX_TIME_S {
        Ok(t)
    } else {
        Err(CliError::new(format!(
            "--t {} is not a finite number of seconds within ±{:e}",
            input::show_number(t),
            MAX_TIME_S
        )))
    }
}

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

/// The sea of `--sea FILE` (read capped and validated by [`WaveSet::read_file`]), or the
/// embedded default sea.
pub fn load_sea(sea: Option<&PathBuf>) -> CliResult<WaveSet> {
    match sea {
        Some(p) => WaveSet::read_file(p).map_err(|e| CliError::new(e.to_string())),
        None => Ok(WaveSet::default_sea()),
    }
}

/// Most waves the renderers evaluate per vertex and frame: the GPU's wave buffer holds this
/// many, and the planner's per-frame culling costs grow with the count (a 10,000-wave sea drew
/// 2 frames a minute).
pub const MAX_DRAWN_WAVES: usize = render::clipmap::MAX_WAVES;

/// The sea to draw: its [`MAX_DRAWN_WAVES`] largest waves ([`WaveSet::keep_largest`]), with
/// the bound of what the rest would move the surface said on stderr when any are dropped.
pub fn drawable_sea(sea: WaveSet) -> WaveSet {
    if sea.waves.len() <= MAX_DRAWN_WAVES {
        return sea;
    }
    let c = sea.keep_largest(MAX_DRAWN_WAVES);
    eprintln!("regatta: {}", drawn_waves_note(sea.waves.len(), &c));
    c.sea
}

/// The stderr line of [`drawable_sea`].
pub fn drawn_waves_note(total: usize, c: &ocean::Culled) -> String {
    format!(
        "the sea has {total} waves; drawing the {} largest, the {} dropped move the surface by at most {:.3e} m (height at a world point {:.3e} m, slope {:.3e})",
        c.sea.waves.len(),
        total - c.sea.waves.len(),
        c.displacement_bound,
        c.height_bound,
        c.slope_bound
    )
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
