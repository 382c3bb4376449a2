//! The scene's inputs: the race (every format `race::Race::load_with` reads, several files
//! combined into one race; the embedded sample without any), the sea (a sea file or the
//! embedded default, cut to the waves the renderer draws), and picture sizes. The command line,
//! the desktop window, the phone and the bench read them here.

use std::ops::RangeInclusive;
use std::path::PathBuf;

use ocean::WaveSet;

use crate::error::{AppError, AppResult};

/// Parse `--size WxH` (or `WXH`) with each side in `sides` pixels; a bad size is the sentence
/// `--size "S" is not {expected}`.
pub fn parse_size_in(s: &str, sides: RangeInclusive<u32>, expected: &str) -> AppResult<[u32; 2]> {
    let bad = || AppError::new(format!("--size \"{s}\" is not {expected}"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if !sides.contains(&w) || !sides.contains(&h) {
        return Err(bad());
    }
    Ok([w, h])
}

/// A camera frame's or window's size `WxH`, both 16 to 4096 pixels: the synthetic feed's
/// images (`regatta replay synth --size`) and the window's first size (`REGATTA_WINDOW_SIZE`).
pub fn parse_frame_size(s: &str) -> AppResult<(u32, u32)> {
    let [w, h] = parse_size_in(
        s,
        16..=4096,
        "WxH with width and height from 16 to 4096 pixels",
    )?;
    Ok((w, h))
}

/// The sea of `sea` (`--sea FILE`, read capped and validated by [`WaveSet::read_file`]), or the
/// embedded default sea.
pub fn load_sea(sea: Option<&PathBuf>) -> AppResult<WaveSet> {
    match sea {
        Some(p) => WaveSet::read_file(p).map_err(|e| AppError::new(e.to_string())),
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

/// The race of `paths` (`--race PATH ...`: files combined into one race), or the embedded
/// sample race without any.
pub fn load_race(paths: &[PathBuf]) -> AppResult<race::Race> {
    load_race_with(paths, &race::LoadOptions::default())
}

/// [`load_race`] with options (`regatta race --keep-going --session --marks --course`). What
/// the import dropped or changed is said on stderr, one escaped line each, so nothing is lost
/// silently (the same warnings are in `regatta race --report`).
pub fn load_race_with(paths: &[PathBuf], opts: &race::LoadOptions) -> AppResult<race::Race> {
    if paths.is_empty() {
        return Ok(race::Race::sample());
    }
    let r = race::Race::load_with(paths, opts).map_err(|e| AppError::new(e.to_string()))?;
    for w in &r.report.warnings {
        eprintln!("regatta: warning: {}", race::text::escape(w));
    }
    Ok(r)
}
