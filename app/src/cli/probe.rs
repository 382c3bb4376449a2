//! `regatta probe`: sea, wake and foam values at world points (docs/command-line.md contract).
//!
//! Per point: the wave surface is sampled at the world point (Newton inverse of the horizontal
//! displacement, tolerance [`ocean::DEFAULT_TOLERANCE`]), then whatever the wakes add there
//! ([`WakeSample`], zero until wakes exist) is added to the height and to the slopes, and the
//! normal of the total surface is formed from the summed slopes: n ∝ (−∂h/∂x, 1, −∂h/∂z).
//!
//! Foam: sea foam is `clamp((0.6 − J) / 0.6, 0, 1)` with J the Jacobian determinant of the
//! horizontal wave map at the rest point ([`ocean::foam_from_jacobian`]); sea and wake foam
//! combine as coverages: `1 − (1 − f_sea)(1 − f_wake)`.

use std::path::PathBuf;

use clap::Args;
use serde_json::json;

use crate::error::{AppError, AppResult};
use crate::setup::inputs::{load_race, load_sea};

#[derive(Debug, Args)]
pub struct ProbeArgs {
    /// Race time in seconds since the start.
    #[arg(long, allow_hyphen_values = true, value_name = "SECONDS")]
    pub t: Option<String>,
    /// A world point "X,Z" in metres (x east, z south); repeatable.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Z")]
    pub at: Vec<String>,
    /// Sea file (JSON, see docs/command-line.md); the embedded default sea without it.
    #[arg(long, value_name = "FILE")]
    pub sea: Option<PathBuf>,
    /// Race files whose boats make the wakes; the embedded sample race without them.
    #[arg(long, value_name = "PATH", num_args = 1..)]
    pub race: Vec<PathBuf>,
}

/// What the wakes add at a world point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WakeSample {
    /// Metres above the wave surface.
    pub height: f64,
    /// ∂/∂x, ∂/∂z of that height over the world point.
    pub gradient: [f64; 2],
    /// Foam coverage in [0, 1].
    pub foam: f64,
}

/// Largest |x| or |z| of a world point, metres: 1000 km, far beyond any race area (a race's
/// boats lie within tens of km of its origin), and small enough that f64 keeps a position to
/// 1.2e-10 m, far below the inverse's tolerance. At 1e155 m the inverse had no digits left and
/// probe printed nulls.
pub const MAX_WORLD_M: f64 = 1.0e6;
pub use super::inputs::MAX_TIME_S;

/// The race time of `--t`: a number of seconds within ±[`MAX_TIME_S`].
pub fn parse_time(t: Option<&str>) -> AppResult<f64> {
    let Some(t) = t else {
        return Err(AppError::new(
            "probe needs the race time: --t SECONDS is missing",
        ));
    };
    match t.trim().parse::<f64>() {
        Ok(v) if v.abs() <= MAX_TIME_S => Ok(v),
        _ => Err(AppError::new(format!(
            "--t {} is not a finite number of seconds within ±{MAX_TIME_S:e}",
            input::quote(t)
        ))),
    }
}

/// A world point of `--at X,Z`: two numbers of metres within ±[`MAX_WORLD_M`].
pub fn parse_point(s: &str) -> AppResult<[f64; 2]> {
    let parts: Vec<&str> = s.split(',').collect();
    let nums: Vec<Option<f64>> = parts
        .iter()
        .map(|p| p.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect();
    match nums[..] {
        [Some(x), Some(z)] if x.abs().max(z.abs()) <= MAX_WORLD_M => Ok([x, z]),
        [Some(_), Some(_)] => Err(AppError::new(format!(
            "--at {} lies outside the world: x and z must lie within ±{MAX_WORLD_M:e} m",
            input::quote(s)
        ))),
        _ => Err(AppError::new(format!(
            "--at {} is not a point X,Z of two finite numbers of metres",
            input::quote(s)
        ))),
    }
}

/// The JSON of one point: the wave surface there plus `wake`.
pub fn probe_point(
    sea: &ocean::WaveSet,
    t: f64,
    at: [f64; 2],
    wake: WakeSample,
) -> AppResult<serde_json::Value> {
    let s = sea
        .sample_at(at, t, ocean::DEFAULT_TOLERANCE)
        .map_err(|e| AppError::new(e.to_string()))?;
    let gx = s.gradient[0] + wake.gradient[0];
    let gz = s.gradient[1] + wake.gradient[1];
    let len = (gx * gx + 1.0 + gz * gz).sqrt();
    let foam = ocean::foam_coverage(s.foam, wake.foam);
    Ok(json!({
        "at": at,
        "sea_height": s.height,
        "wake_height": wake.height,
        "height": s.height + wake.height,
        "normal": [-gx / len, 1.0 / len, -gz / len],
        "rest": s.rest.rest,
        "foam": foam,
    }))
}

pub fn run(a: ProbeArgs) -> AppResult {
    let t = parse_time(a.t.as_deref())?;
    if a.at.is_empty() {
        return Err(AppError::new(
            "probe needs at least one world point: --at X,Z is missing",
        ));
    }
    let points =
        a.at.iter()
            .map(|s| parse_point(s))
            .collect::<AppResult<Vec<_>>>()?;
    let sea = load_sea(a.sea.as_ref())?;
    // The race's Kelvin wakes (ocean::wake), added at the world point; slopes by central
    // differences over R/20, far below the wake's shortest waves (≈ R).
    let wake = crate::wakes::race_wake(&load_race(&a.race)?, ocean::wake::WakeParams::default())?;
    let h = wake.params.hull_radius / 20.0;
    let wake_at = |at: [f64; 2]| WakeSample {
        height: wake.height(at, t),
        gradient: wake.gradient(at, t, h),
        foam: wake.foam(at, t),
    };
    let out = points
        .iter()
        .map(|&at| probe_point(&sea, t, at, wake_at(at)))
        .collect::<AppResult<Vec<_>>>()?;
    crate::terminal::print_stdout("the probe JSON", &json!({ "t": t, "points": out }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The total surface: wake height and slopes add to the sea's, the normal comes from the
    /// summed slopes, and foam combines as coverage.
    #[test]
    fn wake_terms_add_to_the_sea() {
        let sea = ocean::WaveSet::default_sea();
        let (t, at) = (77.0, [12.0, -3.0]);
        let s = sea.sample_at(at, t, ocean::DEFAULT_TOLERANCE).unwrap();
        let calm = probe_point(&sea, t, at, WakeSample::default()).unwrap();
        let n = calm["normal"].as_array().unwrap();
        for (a, b) in n.iter().zip(s.normal) {
            assert!((a.as_f64().unwrap() - b).abs() < 1e-12);
        }
        let wake = WakeSample {
            height: 0.25,
            gradient: [0.1, -0.2],
            foam: 0.5,
        };
        let v = probe_point(&sea, t, at, wake).unwrap();
        assert_eq!(v["height"].as_f64().unwrap(), s.height + 0.25);
        assert_eq!(v["wake_height"].as_f64().unwrap(), 0.25);
        let (gx, gz) = (s.gradient[0] + 0.1, s.gradient[1] - 0.2);
        let len = (gx * gx + 1.0 + gz * gz).sqrt();
        let want = [-gx / len, 1.0 / len, -gz / len];
        for (a, b) in v["normal"].as_array().unwrap().iter().zip(want) {
            assert!((a.as_f64().unwrap() - b).abs() < 1e-12);
        }
        let foam = 1.0 - (1.0 - s.foam) * 0.5;
        assert!((v["foam"].as_f64().unwrap() - foam).abs() < 1e-12);
    }

    /// `--at 1e155,0` printed nulls with exit 0; points and times are now bounded.
    #[test]
    fn points_and_times_outside_the_world_are_refused() {
        let e = parse_point("1e155,0").unwrap_err().0;
        assert_eq!(
            e,
            "--at \"1e155,0\" lies outside the world: x and z must lie within ±1e6 m"
        );
        assert!(parse_point("0,-1000001").is_err());
        assert_eq!(parse_point("-1e6,1e6").unwrap(), [-1e6, 1e6]);
        assert!(
            parse_time(Some("1e155"))
                .unwrap_err()
                .0
                .contains("within ±1e9")
        );
        assert_eq!(parse_time(Some("-5")).unwrap(), -5.0);
    }
}
