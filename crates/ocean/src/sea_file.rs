//! The sea file of DESIGN.md (JSON), validated: bad input is refused with one sentence naming
//! the file and the wave, never clamped.

use std::fmt;

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
        let raw: SeaJson = serde_json::from_str(text).map_err(|e| SeaError {
            message: format!(
                "{source}: not a valid sea file at line {}, column {}: {e}",
                e.line(),
                e.column()
            ),
        })?;
        let err = |m: String| SeaError {
            message: format!("{source}: {m}"),
        };
        let gravity = raw.gravity.unwrap_or(STANDARD_GRAVITY);
        if !gravity.is_finite() || gravity <= 0.0 {
            return Err(err(format!(
                "\"gravity\" must be a positive number, got {gravity}"
            )));
        }
        if let Some(h) = raw.depth
            && (!h.is_finite() || h <= 0.0)
        {
            return Err(err(format!(
                "\"depth\" must be a positive number or null, got {h}"
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
            let len = (dx * dx + dz * dz).sqrt();
            if len == 0.0 {
                return Err(err(format!("wave {i} has a zero \"direction\"")));
            }
            if w.wavelength <= 0.0 {
                return Err(err(format!(
                    "wave {i} has \"wavelength\" {} but it must be positive",
                    w.wavelength
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

    /// The embedded default sea.
    pub fn default_sea() -> WaveSet {
        WaveSet::from_json_str(crate::DEFAULT_SEA_JSON, "the embedded default sea")
            .expect("the embedded default sea is valid (checked by a test)")
    }
}

impl WaveSet {
    /// The sea file of DESIGN.md for this sea: `from_json_str` reads it back to the same set
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
            .contains("wave 1 has \"wavelength\" 0")
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
}
