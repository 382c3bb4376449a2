//! The checks of numeric options shared by several subcommands (whole numbers, race time).
//! The race, the sea and sizes are the scene set-up's (`crate::setup::inputs`): the desktop
//! window and the phone read them too.

use crate::error::{AppError, AppResult};

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
pub fn check_race_time(t: f64) -> AppResult<f64> {
    if t.abs() <= MAX_TIME_S {
        Ok(t)
    } else {
        Err(AppError::new(format!(
            "--t {} is not a finite number of seconds within ±{:e}",
            input::show_number(t),
            MAX_TIME_S
        )))
    }
}
