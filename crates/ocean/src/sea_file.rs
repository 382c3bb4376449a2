//! The sea file of docs/command-line.md (JSON), validated: bad input is refused with one sentence naming
//! the file and the wave, never clamped.
//!
//! Ranges (docs/command-line-errors.md says why): wavelength [`MIN_WAVELENGTH_M`] to
//! [`MAX_WAVELENGTH_M`], gravity [`GRAVITY_RANGE`], depth [`DEPTH_RANGE`], at most
//! [`MAX_SEA_FILE_WAVES`] waves in a file of at most [`MAX_SEA_FILE_BYTES`].

use std::fmt;
use std::ops::RangeInclusive;
use std::path::Path;

use serde::Deserialize;

use crate::{STANDARD_GRAVITY, Wave, WaveSet};

/// Why a sea was refused. The message is one sentence naming the source and the field.
#[derive(Debug, Clone, PartialEq)]
pub struct SeaError {
    pub message: String,
}

impl fmt::Display for SeaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SeaError {}

impl SeaError {
    /// A message whose text may hold input: made one safe line ([`input::one_line`]).
    fn new(message: impl AsRef<str>) -> SeaError {
        SeaError {
            message: input::one_line(message.as_ref()),
        }
    }
}

/// Shortest wavelength a sea file may hold, metres: below about 1.7 cm surface tension, not
/// gravity, sets the speed of a water wave, so a gravity wave of 1 cm is already a stretch.
pub const MIN_WAVELENGTH_M: f64 = 0.01;
/// Longest wavelength a sea file may hold, metres: a deep-water wave of 57 s, beyond the longest
/// swell a buoy measures (NDBC's lowest band, 0.02 Hz, is a 3.9 km wave).
pub const MAX_WAVELENGTH_M: f64 = 5000.0;
/// Gravity a sea file may state, m/s²: from below the Moon's 1.62 to ten times the Earth's.
pub const GRAVITY_RANGE: RangeInclusive<f64> = 1.0..=100.0;
/// Water depth a sea file may state, metres (1 cm to the deepest trench).
pub const DEPTH_RANGE: RangeInclusive<f64> = 0.01..=11_000.0;
/// Most waves in a sea file: 16 times what `regatta sea` writes at most (4096); the renderer
/// draws the largest [`crate::cull`] keeps, the rest go into the stated error bound.
pub const MAX_SEA_FILE_WAVES: usize = 65_536;
/// Largest sea file, bytes: room for [`MAX_SEA_FILE_WAVES`] waves written one per line.
pub const MAX_SEA_FILE_BYTES: u64 = 16 << 20;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SeaJson {
    #[serde(default)]
    gravity: Option<f64>,
    #[serde(default)]
    depth: Option<f64>,
    waves: Vec<WaveJson>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WaveJson {
    direction: [f64; 2],
    steepness: f64,
    wavelength: f64,
    #[serde(default)]
    phase: f64,
}

impl WaveSet {
    /// Parse and validate a sea file. `source` names it in error messages (a path, or
    /// "the embedded default sea").
    pub fn from_json_str(text: &str, source: &str) -> Result<WaveSet, SeaError> {
        // A byte-order mark is text, not a syntax error.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let raw: SeaJson = serde_json::from_str(text).map_err(|e| {
            SeaError::new(format!(
                "{source}: not a valid sea file at line {}, column {}: {e}",
                e.line(),
                e.column()
            ))
        })?;
        let err = |m: String| SeaError::new(format!("{source}: {m}"));
        let gravity = raw.gravity.unwrap_or(STANDARD_GRAVITY);
        if !GRAVITY_RANGE.contains(&gravity) {
            return Err(err(format!(
                "\"gravity\" is {} m/s², outside {GRAVITY_RANGE:?} m/s²",
                input::show_number(gravity)
            )));
        }
        if let Some(h) = raw.depth
            && !DEPTH_RANGE.contains(&h)
        {
            return Err(err(format!(
                "\"depth\" is {} m, outside {DEPTH_RANGE:?} m (null for deep water)",
                input::show_number(h)
            )));
        }
        if raw.waves.len() > MAX_SEA_FILE_WAVES {
            return Err(err(format!(
                "{} waves, more than the {MAX_SEA_FILE_WAVES} a sea file may hold",
                raw.waves.len()
            )));
        }
        let mut waves = Vec::with_capacity(raw.waves.len());
        for (i, w) in raw.waves.iter().enumerate() {
            let [dx, dz] = w.direction;
            let nums = [dx, dz, w.steepness, w.wavelength, w.phase];
            if nums.iter().any(|v| !v.is_finite()) {
                return Err(err(format!(
                    "wave {i} has a number that is NaN or infinite"
                )));
            }
            let len = dx.hypot(dz);
            if len == 0.0 {
                return Err(err(format!("wave {i} has a zero \"direction\"")));
            }
            if !len.is_finite() {
                return Err(err(format!(
                    "wave {i} has a \"direction\" too long to normalise"
                )));
            }
            if !(MIN_WAVELENGTH_M..=MAX_WAVELENGTH_M).contains(&w.wavelength) {
                return Err(err(format!(
                    "wave {i} has \"wavelength\" {} m, outside {MIN_WAVELENGTH_M}..={MAX_WAVELENGTH_M} m",
                    input::show_number(w.wavelength)
                )));
            }
            if !(0.0..=1.0).contains(&w.steepness) {
                return Err(err(format!(
                    "wave {i} has \"steepness\" {} outside [0, 1]",
                    w.steepness
                )));
            }
            waves.push(Wave {
                direction: [dx / len, dz / len],
                steepness: w.steepness,
                wavelength: w.wavelength,
                phase: w.phase,
            });
        }
        let set = WaveSet {
            gravity,
            depth: raw.depth,
            waves,
        };
        let total = set.total_steepness();
        if total >= 1.0 {
            return Err(err(format!(
                "the total steepness Σ kA of the waves is {total:.3}, but it must stay below 1 or the surface folds over"
            )));
        }
        Ok(set)
    }

    /// Read and validate the sea file at `path`: at most [`MAX_SEA_FILE_BYTES`], and a JSON
    /// object from its first byte (so `/dev/zero` or a binary file is refused at once).
    pub fn read_file(path: &Path) -> Result<WaveSet, SeaError> {
        let bytes = input::read_capped(
            path,
            MAX_SEA_FILE_BYTES,
            "a sea file",
            input::json_object_sniff,
        )
        .map_err(|e| SeaError::new(e.0))?;
        let name = input::show_path(path);
        let text = String::from_utf8(bytes).map_err(|e| {
            SeaError::new(format!(
                "{name}: byte {} is not UTF-8 text",
                e.utf8_error().valid_up_to()
            ))
        })?;
        WaveSet::from_json_str(&text, &name)
    }

    /// The embedded default sea.
    pub fn default_sea() -> WaveSet {
        WaveSet::from_json_str(crate::DEFAULT_SEA_JSON, "the embedded default sea")
            .expect("the embedded default sea is valid (checked by a test)")
    }
}

impl WaveSet {
    /// The sea file of docs/command-line.md for this sea: `from_json_str` reads it back to the same set
    /// (numbers are written with Rust's shortest round-trip formatting).
    pub fn to_json_string(&self) -> String {
        let waves: Vec<serde_json::Value> = self
            .waves
            .iter()
            .map(|w| {
                serde_json::json!({
                    "direction": w.direction,
                    "steepness": w.steepness,
                    "wavelength": w.wavelength,
                    "phase": w.phase,
                })
            })
            .collect();
        let v = serde_json::json!({ "gravity": self.gravity, "depth": self.depth, "waves": waves });
        serde_json::to_string_pretty(&v).expect("a sea serialises")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sea_round_trips_through_its_file() {
        let s = WaveSet::default_sea();
        let r = WaveSet::from_json_str(&s.to_json_string(), "x").unwrap();
        assert_eq!(
            (r.gravity, r.depth, r.waves.len()),
            (s.gravity, s.depth, s.waves.len())
        );
        for (a, b) in r.waves.iter().zip(&s.waves) {
            assert_eq!(
                (a.steepness, a.wavelength, a.phase),
                (b.steepness, b.wavelength, b.phase)
            );
            // Directions are normalised again on load: equal to an ulp.
            assert!((a.direction[0] - b.direction[0]).abs() < 1e-15);
            assert!((a.direction[1] - b.direction[1]).abs() < 1e-15);
        }
    }

    #[test]
    fn refusals_name_the_source_and_the_wave() {
        let e = |t: &str| WaveSet::from_json_str(t, "sea.json").unwrap_err().message;
        let w = |s: &str| {
            format!(
                r#"{{"waves": [{{"direction": [1, 0], "steepness": 0.1, "wavelength": 5}}, {s}]}}"#
            )
        };
        assert_eq!(
            e(&w(
                r#"{"direction": [0, 0], "steepness": 0.1, "wavelength": 5}"#
            )),
            "sea.json: wave 1 has a zero \"direction\""
        );
        assert!(
            e(&w(
                r#"{"direction": [1, 0], "steepness": 0.1, "wavelength": 0}"#
            ))
            .contains("wave 1 has \"wavelength\" 0 m, outside 0.01..=5000 m")
        );
        assert!(
            e(&w(
                r#"{"direction": [1, 0], "steepness": -0.1, "wavelength": 3}"#
            ))
            .contains("outside [0, 1]")
        );
        assert!(
            e(&w(
                r#"{"direction": [1, 0], "steepness": 0.9, "wavelength": 3}"#
            ))
            .contains("Σ kA of the waves is 1.000")
        );
        assert!(e(r#"{"depth": -2, "waves": []}"#).contains("\"depth\""));
        assert!(
            e(r#"{"waves": [{"direction": [1, 0], "steepness": 0.1, "wavelength": 1e999}]}"#)
                .starts_with("sea.json: not a valid sea file at line 1")
        );
    }

    /// λ = 1e300 or 1e-300 passed before and then drew nothing (or 256 "did not converge"
    /// warnings); gravity and depth had no upper or lower end either.
    #[test]
    fn wavelengths_gravity_and_depth_outside_their_ranges_are_refused() {
        let e = |t: &str| WaveSet::from_json_str(t, "sea.json").unwrap_err().message;
        let wave = |l: &str| {
            format!(
                r#"{{"waves": [{{"direction": [1, 0], "steepness": 0.1, "wavelength": {l}}}]}}"#
            )
        };
        assert_eq!(
            e(&wave("1e300")),
            "sea.json: wave 0 has \"wavelength\" 1e300 m, outside 0.01..=5000 m"
        );
        assert_eq!(
            e(&wave("1e-300")),
            "sea.json: wave 0 has \"wavelength\" 1e-300 m, outside 0.01..=5000 m"
        );
        assert!(WaveSet::from_json_str(&wave("0.01"), "x").is_ok());
        assert!(WaveSet::from_json_str(&wave("5000"), "x").is_ok());
        assert!(e(r#"{"gravity": 1e300, "waves": []}"#).contains("\"gravity\" is 1e300 m/s²"));
        assert!(e(r#"{"depth": 1e-300, "waves": []}"#).contains("\"depth\" is 1e-300 m"));
        assert!(
            e(r#"{"waves": [{"direction": [1.5e308, 1.5e308], "steepness": 0.1, "wavelength": 5}]}"#)
                .contains("too long to normalise")
        );
    }

    /// serde quotes an unknown key as it is: a key `"\name"` (newline + "ame") made a two-line
    /// message, an ESC drove the terminal. Now every control character is escaped.
    #[test]
    fn control_characters_in_keys_and_names_are_escaped() {
        let m = WaveSet::from_json_str(r#"{"\name\u001b[2J\u0007": 1, "waves": []}"#, "a\rb.json")
            .unwrap_err()
            .message;
        assert!(!m.chars().any(|c| c.is_control()), "{m:?}");
        assert!(m.starts_with("a\\rb.json: not a valid sea file"), "{m}");
        assert!(m.contains("unknown field `\\name\\u{1b}[2J\\u{7}`"), "{m}");
        // A byte-order mark is accepted.
        assert!(WaveSet::from_json_str("\u{feff}{\"waves\": []}", "bom.json").is_ok());
    }
}
