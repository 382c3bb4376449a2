//! The baseline: the ring wake of the Sailing+ wave-model thesis (TU Delft 2022, report 003 in docs/sources.md), its eq. 3, exactly as stated.
//!
//! For boat point j (the boat's position P_j and unit direction P_j^d at time t − j·Δt,
//! j = 1..=n: "the past n positions", a fixed time apart) and a point p, with
//! l = (p − P_j)/L in UV units (L: the play-area length that maps metres to UV),
//!
//! strength_j = lerp(1, 0, |P_j^d · l|) · a / (b |r_j² − l·l|² + j c),
//!
//! counted only inside the 2r_j × 2r_j square around P_j (003 draws only those pixels), and
//! summed over j and boats. lerp(1, 0, z) = 1 − z (unclamped, as stated). 003 says the rings
//! "widen the older they become" but gives no law or values: here r_j = r₀ + v_r·j·Δt in
//! metres (over L in UV), and a, b, c, r₀, v_r, Δt, L are the defaults below. The strength is
//! a texture value, not metres: 003 scales it into a displacement and into foam; the bench fits
//! the best scale factor against the reference before it measures any error, which favours the
//! baseline. Because the rings grow at a fixed v_r, the envelope of their V is a Mach cone of
//! half-angle arcsin(v_r/U), right at one speed only; a boat slower than v_r stacks rings
//! (003's own limitation).

use super::track::{TrackSample, WakeError, check_track, state_at};

/// The ring model's knobs (003 eq. 3 and its text).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingParams {
    /// n: rings per boat.
    pub points: usize,
    /// Δt between the boat points, s.
    pub interval: f64,
    /// a: overall strength.
    pub a: f64,
    /// b: sharpness ("blur") of a ring, UV⁻⁴.
    pub b: f64,
    /// c: fade per ring index.
    pub c: f64,
    /// r₀: radius of a ring at age 0, m.
    pub r0: f64,
    /// v_r: growth of the radius with age, m/s (set for a 19.47° V at 5 m/s by default).
    pub growth: f64,
    /// L: metres per UV unit (the play area's length).
    pub uv_length: f64,
}

impl Default for RingParams {
    fn default() -> Self {
        RingParams {
            points: 10,
            interval: 2.0,
            a: 1.0,
            b: 1.0e4,
            c: 1.0,
            r0: 1.0,
            growth: 5.0 / 3.0,
            uv_length: 100.0,
        }
    }
}

/// 003's wake for a fleet: the tracks, evaluated at any time.
#[derive(Debug, Clone, PartialEq)]
pub struct RingWake {
    pub params: RingParams,
    pub tracks: Vec<Vec<TrackSample>>,
}

impl RingWake {
    /// Check the tracks (same rules as [`super::Wake::new`]).
    pub fn new(tracks: &[&[TrackSample]], params: RingParams) -> Result<RingWake, WakeError> {
        for (field, v) in [
            ("interval", params.interval),
            ("uv_length", params.uv_length),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(WakeError::Param {
                    field,
                    reason: "must be a positive finite number",
                });
            }
        }
        for (i, tr) in tracks.iter().enumerate() {
            check_track(i, tr)?;
        }
        Ok(RingWake {
            params,
            tracks: tracks.iter().map(|t| t.to_vec()).collect(),
        })
    }

    /// Σ strength at world point `p` and time `t` (eq. 3), dimensionless.
    pub fn strength(&self, p: [f64; 2], t: f64) -> f64 {
        let q = &self.params;
        let mut sum = 0.0;
        for tr in &self.tracks {
            for j in 1..=q.points {
                let age = j as f64 * q.interval;
                let Some((pos, vel)) = state_at(tr, t - age) else {
                    continue;
                };
                let speed = vel[0].hypot(vel[1]);
                let dir = if speed > 0.0 {
                    [vel[0] / speed, vel[1] / speed]
                } else {
                    [0.0, 0.0]
                };
                let l = [(p[0] - pos[0]) / q.uv_length, (p[1] - pos[1]) / q.uv_length];
                let r = (q.r0 + q.growth * age) / q.uv_length;
                if l[0].abs() > r || l[1].abs() > r {
                    continue;
                }
                let lerp = 1.0 - (dir[0] * l[0] + dir[1] * l[1]).abs();
                let ring = (r * r - (l[0] * l[0] + l[1] * l[1])).abs();
                sum += lerp * q.a / (q.b * ring * ring + j as f64 * q.c);
            }
        }
        sum
    }

    /// 003's foam: the texture value, clamped to [0, 1].
    pub fn foam(&self, p: [f64; 2], t: f64) -> f64 {
        self.strength(p, t).clamp(0.0, 1.0)
    }
}
