//! A boat's sampled track: positions in time, checked, and linearly interpolated.

use std::fmt;

/// One sampled position of a boat: race time `t` (s) and world position `x` (east, m),
/// `z` (south, m). Samples of a track must have non-decreasing `t`; two samples at the same
/// time are a jump (the boat is put somewhere else, e.g. a GPS glitch), not a motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackSample {
    pub t: f64,
    pub x: f64,
    pub z: f64,
}

/// Why wake input was refused.
#[derive(Debug, Clone, PartialEq)]
pub enum WakeError {
    /// A track sample: which boat (index in the input) and which sample.
    Track {
        boat: usize,
        sample: usize,
        reason: &'static str,
    },
    /// A field of `WakeParams`.
    Param {
        field: &'static str,
        reason: &'static str,
    },
}

impl fmt::Display for WakeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WakeError::Track {
                boat,
                sample,
                reason,
            } => write!(
                f,
                "the track of boat {boat} is invalid at sample {sample}: {reason}"
            ),
            WakeError::Param { field, reason } => {
                write!(f, "the wake parameter `{field}` {reason}")
            }
        }
    }
}

impl std::error::Error for WakeError {}

/// Check a track: finite values, non-decreasing times.
pub(crate) fn check_track(boat: usize, samples: &[TrackSample]) -> Result<(), WakeError> {
    for (i, s) in samples.iter().enumerate() {
        let err = |reason| WakeError::Track {
            boat,
            sample: i,
            reason,
        };
        if !(s.t.is_finite() && s.x.is_finite() && s.z.is_finite()) {
            return Err(err("t, x and z must be finite numbers"));
        }
        if i > 0 && s.t < samples[i - 1].t {
            return Err(err("its time is earlier than the previous sample's"));
        }
    }
    Ok(())
}

/// Position and velocity (m, m/s) of a checked track at time `t`, linearly interpolated; held
/// at the first/last sample outside the track (velocity zero there). `None` for no samples.
pub(crate) fn state_at(samples: &[TrackSample], t: f64) -> Option<([f64; 2], [f64; 2])> {
    let first = samples.first()?;
    let last = samples.last()?;
    if t <= first.t {
        return Some(([first.x, first.z], [0.0, 0.0]));
    }
    if t >= last.t {
        return Some(([last.x, last.z], [0.0, 0.0]));
    }
    // First sample with time > t; t is strictly inside, so 1 ≤ i < len.
    let i = samples.partition_point(|s| s.t <= t);
    let (a, b) = (samples[i - 1], samples[i]);
    let dt = b.t - a.t;
    // dt > 0 because a.t ≤ t < b.t.
    let f = (t - a.t) / dt;
    let v = [(b.x - a.x) / dt, (b.z - a.z) / dt];
    Some(([a.x + f * (b.x - a.x), a.z + f * (b.z - a.z)], v))
}
