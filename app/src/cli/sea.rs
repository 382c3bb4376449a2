//! `regatta sea`: write a sea file (docs/command-line.md format, JSON on stdout) from real conditions:
//! a JONSWAP / Pierson–Moskowitz sea state, or an NDBC buoy's spectral files. What the
//! generation did (Hs kept, the amplitude scale that keeps Σ kA below the limit) goes to stderr.
//!
//! ```text
//! regatta sea --hs 2 --tp 8 [--gamma 3.3] [--from-deg 270] [--spreading 10] [--waves 32]
//! regatta sea --ndbc 41010.data_spec [--ndbc-dir 41010.swdir] [--ndbc-r1 41010.swr1]
//!             [--time "2020-06-08 03:50"]
//! common: [--seed 1] [--max-steepness 0.8] [--depth H]
//! ```

use std::path::PathBuf;

use clap::Args;
use ocean::ndbc::{NdbcSpectrum, NdbcTable, NdbcTime};
use ocean::spectrum::{SeaState, SpectralOptions, SpectralSea, travel_direction_from_compass};

use crate::error::{AppError, AppResult};

#[derive(Debug, Args)]
pub struct SeaArgs {
    /// Significant wave height Hs, metres (parametric spectrum).
    #[arg(long, allow_hyphen_values = true)]
    pub hs: Option<f64>,
    /// Peak period Tp, seconds (parametric spectrum).
    #[arg(long, allow_hyphen_values = true)]
    pub tp: Option<f64>,
    /// JONSWAP peak enhancement γ (1 = Pierson–Moskowitz).
    #[arg(long, default_value_t = 3.3, allow_hyphen_values = true)]
    pub gamma: f64,
    /// Compass direction the waves come from, degrees (0 = north).
    #[arg(long, default_value_t = 270.0, allow_hyphen_values = true)]
    pub from_deg: f64,
    /// cos-2s spreading exponent s.
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub spreading: f64,
    /// Number of waves (parametric spectrum).
    #[arg(long, default_value_t = 32, allow_negative_numbers = true,
        value_parser = super::inputs::whole_number::<usize>("from 1 to 4096"))]
    pub waves: usize,
    /// NDBC spectral density file (realtime `.data_spec` or historical `w` file, .gz allowed).
    #[arg(long)]
    pub ndbc: Option<PathBuf>,
    /// NDBC mean direction (alpha1) file matching `--ndbc`.
    #[arg(long)]
    pub ndbc_dir: Option<PathBuf>,
    /// NDBC r1 file matching `--ndbc`.
    #[arg(long)]
    pub ndbc_r1: Option<PathBuf>,
    /// Record time "YYYY-MM-DD hh:mm" (UTC); the file's first record without it.
    #[arg(long)]
    pub time: Option<String>,
    /// Seed of the random frequencies, directions and phases.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true,
        value_parser = super::inputs::whole_number::<u64>("from 0 to 18446744073709551615"))]
    pub seed: u64,
    /// Σ kA is scaled down to this if the spectrum is steeper (must be below 1).
    #[arg(long, default_value_t = 0.8, allow_hyphen_values = true)]
    pub max_steepness: f64,
    /// Water depth in metres (deep water without it).
    #[arg(long, allow_hyphen_values = true)]
    pub depth: Option<f64>,
}

/// Significant wave height, metres: above 0, at most 30 (the highest Hs a buoy has measured
/// is about 19 m). At 1e300 m the steepness came out as null.
pub const HS_RANGE_M: (f64, f64) = (0.0, 30.0);
/// Peak period, seconds: with the bands from 0.6 fp to 4 fp this keeps every generated
/// wavelength within the sea file's 0.01 m to 5000 m (deep water: λ = g T² / 2π). At 1e-300 s
/// the sea came out empty.
pub const TP_RANGE_S: (f64, f64) = (0.5, 30.0);
/// JONSWAP peak enhancement γ: 1 (Pierson–Moskowitz) to 10, above the 1–7 measured in the
/// JONSWAP experiment. At γ = 1e9 the spectrum's normalisation underflowed to an empty sea.
pub const GAMMA_RANGE: (f64, f64) = (1.0, 10.0);
/// cos-2s spreading exponent s: 0 (all directions) to 200, beyond the narrowest swell (~75).
pub const SPREADING_RANGE: (f64, f64) = (0.0, 200.0);

/// `v` for `--{name}` when it lies in (lo, hi] (`open_low`) or [lo, hi].
fn in_range(
    name: &str,
    v: f64,
    (lo, hi): (f64, f64),
    unit: &str,
    open_low: bool,
) -> AppResult<f64> {
    let low_ok = if open_low { v > lo } else { v >= lo };
    if low_ok && v <= hi {
        Ok(v)
    } else {
        let open = if open_low { "(" } else { "[" };
        Err(AppError::new(format!(
            "--{name} is {}{unit}, outside {open}{lo}, {hi}]{unit}",
            input::show_number(v)
        )))
    }
}

/// "YYYY-MM-DD hh:mm" as an NDBC record time.
pub fn parse_time(s: &str) -> AppResult<NdbcTime> {
    let bad = || {
        AppError::new(format!(
            "--time {} is not a time \"YYYY-MM-DD hh:mm\"",
            input::quote(s)
        ))
    };
    let (date, clock) = s.trim().split_once(' ').ok_or_else(bad)?;
    let d: Vec<u32> = date
        .split('-')
        .map(|p| p.parse().map_err(|_| bad()))
        .collect::<AppResult<_>>()?;
    let c: Vec<u32> = clock
        .split(':')
        .map(|p| p.parse().map_err(|_| bad()))
        .collect::<AppResult<_>>()?;
    let time = match (&d[..], &c[..]) {
        ([year, month, day], [hour, minute]) => NdbcTime {
            year: *year,
            month: *month,
            day: *day,
            hour: *hour,
            minute: *minute,
        },
        _ => return Err(bad()),
    };
    match time.invalid_because() {
        Some(why) => Err(AppError::new(format!(
            "--time {} is not a real time: {why}",
            input::quote(s)
        ))),
        None => Ok(time),
    }
}

/// The sea the arguments describe.
pub fn generate(a: &SeaArgs) -> AppResult<SpectralSea> {
    if !(a.max_steepness > 0.0 && a.max_steepness < 1.0) {
        return Err(AppError::new(format!(
            "--max-steepness must lie in (0, 1) or the surface folds over, got {}",
            a.max_steepness
        )));
    }
    if let Some(h) = a.depth {
        // The sea file's own range: a depth written here must read back.
        let range = ocean::sea_file::DEPTH_RANGE;
        if !range.contains(&h) {
            return Err(AppError::new(format!(
                "--depth must lie in {}..={} m (a centimetre of water to the deepest trench; a sea file holds no other), got {}",
                range.start(),
                range.end(),
                input::show_number(h)
            )));
        }
    }
    let opts = SpectralOptions {
        seed: a.seed,
        max_total_steepness: a.max_steepness,
        depth: a.depth,
        ..Default::default()
    };
    let ndbc_err = |e: ocean::ndbc::NdbcError| AppError::new(e.to_string());
    match (&a.ndbc, a.hs, a.tp) {
        (Some(density), None, None) => {
            let density = NdbcTable::read(density).map_err(ndbc_err)?;
            let dir = a
                .ndbc_dir
                .as_deref()
                .map(NdbcTable::read)
                .transpose()
                .map_err(ndbc_err)?;
            let r1 = a
                .ndbc_r1
                .as_deref()
                .map(NdbcTable::read)
                .transpose()
                .map_err(ndbc_err)?;
            let time = a.time.as_deref().map(parse_time).transpose()?;
            let s = NdbcSpectrum::from_tables(&density, dir.as_ref(), r1.as_ref(), time)
                .map_err(ndbc_err)?;
            eprintln!(
                "regatta sea: NDBC record {} with Hs = {:.2} m",
                s.time,
                s.hs()
            );
            Ok(ocean::spectrum::sea_from_bands(
                &s.bands(a.from_deg, a.spreading),
                &opts,
            ))
        }
        (None, Some(hs), Some(tp)) => {
            in_range("gamma", a.gamma, GAMMA_RANGE, "", false)?;
            in_range("spreading", a.spreading, SPREADING_RANGE, "", false)?;
            if !a.from_deg.is_finite() {
                return Err(AppError::new(
                    "--from-deg must be a finite number of degrees",
                ));
            }
            if a.waves == 0 || a.waves > 4096 {
                return Err(AppError::new(format!(
                    "--waves must be between 1 and 4096, got {}",
                    a.waves
                )));
            }
            let state = SeaState {
                hs: in_range("hs", hs, HS_RANGE_M, " m", true)?,
                tp: in_range("tp", tp, TP_RANGE_S, " s", false)?,
                gamma: a.gamma,
                direction: travel_direction_from_compass(a.from_deg),
                spreading: a.spreading,
            };
            Ok(state.to_sea(a.waves, &opts))
        }
        _ => Err(AppError::new(
            "sea needs either --hs and --tp (a JONSWAP spectrum) or --ndbc FILE (a buoy spectrum), not both",
        )),
    }
}

pub fn run(a: SeaArgs) -> AppResult {
    let g = generate(&a)?;
    eprintln!(
        "regatta sea: {} waves, Hs {:.3} m of the spectrum, {:.3} m in the waves (amplitude scale {:.4}: Σ kA {:.3} → {:.3})",
        g.sea.waves.len(),
        g.hs_spectrum,
        g.hs_waves,
        g.amplitude_scale,
        g.unscaled_total_steepness,
        g.sea.total_steepness()
    );
    crate::terminal::print_stdout("the sea file", &g.sea.to_json_string())
}
