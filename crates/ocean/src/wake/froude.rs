//! Froude-scaled wakes: the wake of a boat drawn as a model (a 5 cm hull on a table) instead of
//! the wake of the boat itself.
//!
//! Three frames (docs/wakes.md, "Wakes at table scale"):
//!
//! - **the boat**: waterline length L (= 4R, the pressure patch's), speed U, gravity g, time t;
//! - **the model**: a hull of length L_m on real water (the table), λ = L_m/L. Froude
//!   similarity (equal Froude number U/√(gL)) makes every length ×λ, every speed and time
//!   ×√λ and every height ×λ: the model sails at U_m = U√λ and its transverse waves are
//!   2πU_m²/g = λ·2πU²/g long; the Kelvin half-angle arcsin(1/3) does not change;
//! - **the world the renderer draws** (race metres, race seconds): the table magnified by
//!   `world_per_table` (race metres per table metre), with the model riding the boat's track at
//!   the boat's own speed U. With s = λ·world_per_table (drawn hull / boat length, both in race
//!   metres), a model second is s/√λ race seconds, and the model's wake in this world is the
//!   wake of a boat of patch radius sR and weight ×s² under gravity g/s. That is
//!   [`WakeParams::froude_scaled`]: the same closed form, so the wake stays a function of race
//!   time (scrubbing equals playing). Straight steady legs are exact (the boat's wake
//!   magnified s times, [`Wake`] tests it to rounding); what is not: the track is the boat's,
//!   so relative to its hull the model turns s times tighter and changes speed s times faster.

use super::kelvin::{Wake, WakeParams};
use super::track::TrackSample;
use super::track::WakeError;

/// How a boat is drawn on a table: the numbers that fix the Froude mapping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableModel {
    /// Waterline length L of the boat whose wake is modelled, m ([`WakeParams::waterline_length`]).
    pub boat_length: f64,
    /// Length L_m of the model as drawn on the table, table metres.
    pub model_length: f64,
    /// Race (world) metres per table metre.
    pub world_per_table: f64,
}

impl TableModel {
    /// λ = L_m/L: the model's size against the boat's.
    pub fn length_ratio(&self) -> f64 {
        self.model_length / self.boat_length
    }

    /// s = drawn hull / boat length, both in world metres: what [`WakeParams::froude_scaled`]
    /// takes.
    pub fn world_scale(&self) -> f64 {
        self.length_ratio() * self.world_per_table
    }

    /// The model's speed on the table for a boat speed `u` (same Froude number), m/s.
    pub fn model_speed(&self, u: f64) -> f64 {
        u * self.length_ratio().sqrt()
    }

    /// Model seconds (on the table) in `dt` race seconds of the drawn wake: dt·√λ/s.
    pub fn model_time(&self, dt: f64) -> f64 {
        dt * self.length_ratio().sqrt() / self.world_scale()
    }
}

/// Surface tension over density of clean fresh water at 20 °C, m³/s² (σ = 0.0728 N/m,
/// ρ = 998 kg/m³): what a model on a real table would also feel.
pub const FRESH_WATER_SIGMA_OVER_RHO: f64 = 0.0728 / 998.0;

/// Kinematic viscosity of fresh water at 20 °C, m²/s.
pub const FRESH_WATER_VISCOSITY: f64 = 1.0e-6;

/// Length of the stationary transverse wave behind a body at speed `u` on capillary-gravity
/// water (ω² = gk + (σ/ρ)k³, phase speed = u, the gravity branch), m; `None` below the
/// minimum phase speed (4g σ/ρ)^{1/4} ≈ 0.23 m/s, where no such wave exists.
pub fn capillary_gravity_transverse_wavelength(u: f64, g: f64, sigma_over_rho: f64) -> Option<f64> {
    // (σ/ρ) k² − u² k + g = 0, smaller root.
    let disc = u.powi(4) - 4.0 * g * sigma_over_rho;
    (disc >= 0.0).then(|| {
        let k = 2.0 * g / (u * u + disc.sqrt());
        2.0 * std::f64::consts::PI / k
    })
}

impl WakeParams {
    /// Waterline length of the boat the pressure patch stands for, 4R, m.
    pub fn waterline_length(&self) -> f64 {
        4.0 * self.hull_radius
    }

    /// The parameters of the same boat drawn `s` times larger in the world, Froude-similar
    /// (module docs): gravity g/s, lengths ×s (patch, source spacing, foam width), times ×s
    /// (source interval, lifetime, foam lifetime), weight ×s² (so heights are ×s), speeds
    /// unchanged (jump and foam speeds: the drawn boat sails at the boat's speed).
    pub fn froude_scaled(&self, s: f64) -> WakeParams {
        WakeParams {
            gravity: self.gravity / s,
            hull_radius: self.hull_radius * s,
            force: self.force * s * s,
            spacing: self.spacing * s,
            max_interval: self.max_interval * s,
            max_age: self.max_age * s,
            jump_speed: self.jump_speed,
            foam_width: self.foam_width * s,
            foam_spread: self.foam_spread,
            foam_lifetime: self.foam_lifetime * s,
            foam_speed: self.foam_speed,
        }
    }
}

impl Wake {
    /// The same tracks' wake with [`WakeParams::froude_scaled`]`(s)`: what a boat drawn `s`
    /// times larger leaves. `s` must be a positive finite number.
    pub fn froude_scaled(&self, s: f64) -> Result<Wake, WakeError> {
        if !(s.is_finite() && s > 0.0) {
            return Err(WakeError::Param {
                field: "froude scale",
                reason: "must be a positive finite number",
            });
        }
        let refs: Vec<&[TrackSample]> = self.tracks.iter().map(Vec::as_slice).collect();
        Wake::new(&refs, self.params.froude_scaled(s))
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::super::measure::{cusp_half_angle_deg_in, transverse_wavelength};
    use super::*;

    const G: f64 = crate::STANDARD_GRAVITY;

    /// A boat along +x at `u`, at the origin at `t_end`, for `duration` s in `n` equal steps
    /// (the track is exactly linear whatever the step).
    fn straight(u: f64, duration: f64, t_end: f64, n: usize) -> Vec<TrackSample> {
        (0..=n)
            .map(|i| {
                let t = t_end - duration + i as f64 * duration / n as f64;
                TrackSample {
                    t,
                    x: u * (t - t_end),
                    z: 0.0,
                }
            })
            .collect()
    }

    /// The sample race on the synthetic table: a 5 cm model of the 6 m wake boat, 3 000 race
    /// metres per table metre (s = 25).
    fn table() -> TableModel {
        TableModel {
            boat_length: WakeParams::default().waterline_length(),
            model_length: 0.05,
            world_per_table: 3000.0,
        }
    }

    #[test]
    fn a_straight_legs_scaled_wake_is_the_boats_magnified_s_times() {
        // Exact similarity: η_s(sξ, sy) = s·η(ξ, y) for the track s times as long.
        let (u, s) = (5.0, 25.0);
        let prm = WakeParams {
            max_age: 40.0,
            ..WakeParams::default()
        };
        let real = straight(u, prm.max_age + 5.0, 100.0, 45);
        let big = straight(u, s * (prm.max_age + 5.0), 100.0 * s, 45);
        let w = Wake::new(&[&real], prm).unwrap();
        let ws = Wake::new(&[&big], prm).unwrap().froude_scaled(s).unwrap();
        assert_eq!(ws.source_count(), w.source_count());
        let mut peak = 0.0f64;
        let mut worst = 0.0f64;
        for i in 0..40 {
            for j in -10..=10 {
                let (xi, y) = (-1.0 - 4.0 * i as f64, 3.0 * j as f64);
                let a = s * w.height([xi, y], 100.0);
                let b = ws.height([s * xi, s * y], 100.0 * s);
                peak = peak.max(a.abs());
                worst = worst.max((a - b).abs());
            }
        }
        assert!(peak > 1e-3, "the wake must be there: {peak}");
        assert!(
            worst <= 1e-9 * peak,
            "scaled vs magnified: {worst} of {peak}"
        );
    }

    #[test]
    fn the_table_models_wake_has_kelvins_angle_and_the_models_wavelength() {
        let m = table();
        let s = m.world_scale();
        assert!((s - 25.0).abs() < 1e-12);
        let kelvin = (1.0f64 / 3.0).asin().to_degrees();
        let u = 5.0;
        // Closed form at the model's speed on the table, in table metres, then in the world.
        let um = m.model_speed(u);
        let lam_table = 2.0 * PI * um * um / G;
        let lam = lam_table * m.world_per_table;
        // The boat's patch (R = 1.5 m) and a wake reaching 16 λ behind, in boat units.
        let reach = 16.0 * lam / s;
        let prm = WakeParams {
            max_age: 2.5 * reach / u / 0.8,
            ..WakeParams::default()
        };
        let t_end = 2000.0 * s;
        let n = (prm.max_age + 5.0).ceil() as usize;
        let track = straight(u, s * (prm.max_age + 5.0), t_end, n);
        let wake = Wake::new(&[&track], prm).unwrap().froude_scaled(s).unwrap();
        let f = |xi: f64, y: f64| wake.height([xi, y], t_end);
        let measured = transverse_wavelength(&f, 3.0 * lam, 10.0 * lam, lam / 40.0).unwrap();
        eprintln!(
            "model {:.3} m/s: transverse wavelength {:.4} table m (2πU_m²/g = {lam_table:.4})",
            um,
            measured / m.world_per_table
        );
        assert!(
            (measured / lam - 1.0).abs() < 1.5e-3,
            "{measured} vs {lam} world m"
        );
        let a = cusp_half_angle_deg_in(&f, lam, 15.0 * lam, 12.0, 26.0).unwrap();
        eprintln!("half-angle {a:.2}°");
        assert!((a - kelvin).abs() <= 0.5, "half-angle {a:.2}°");
    }

    #[test]
    fn model_time_and_speed_follow_froude() {
        let m = table();
        let lam = m.length_ratio();
        // The transverse wave's period, 2πU/g for the boat, is s race seconds per boat second
        // in the drawn world (gravity g/s) and √λ model seconds on the table.
        let u = 4.0;
        let t_boat = 2.0 * PI * u / G;
        let t_world = 2.0 * PI * u / WakeParams::default().froude_scaled(m.world_scale()).gravity;
        let t_model = 2.0 * PI * m.model_speed(u) / G;
        assert!((t_world / t_boat - m.world_scale()).abs() < 1e-9);
        assert!((m.model_time(t_world) - t_model).abs() < 1e-12);
        assert!((t_model / t_boat - lam.sqrt()).abs() < 1e-12);
        // The Froude number is the boat's.
        let fr = |u: f64, l: f64, g: f64| u / (g * l).sqrt();
        assert!((fr(m.model_speed(u), m.model_length, G) - fr(u, m.boat_length, G)).abs() < 1e-12);
    }

    #[test]
    fn capillarity_shortens_the_models_transverse_wave() {
        let sr = FRESH_WATER_SIGMA_OVER_RHO;
        // Pure gravity far above the minimum speed.
        let l = capillary_gravity_transverse_wavelength(20.0, G, sr).unwrap();
        assert!((l / (2.0 * PI * 400.0 / G) - 1.0).abs() < 1e-6);
        // The minimum phase speed (4gσ/ρ)^¼ = 0.231 m/s: nothing below it.
        let cmin = (4.0 * G * sr).powf(0.25);
        assert!((cmin - 0.2314).abs() < 5e-4, "{cmin}");
        assert!(capillary_gravity_transverse_wavelength(0.99 * cmin, G, sr).is_none());
        // At the minimum, k = √(gρ/σ): λ = 1.71 cm.
        let lmin = capillary_gravity_transverse_wavelength(cmin, G, sr).unwrap();
        assert!((lmin - 2.0 * PI * (sr / G).sqrt()).abs() < 1e-9);
        // The table model at 5 m/s (0.456 m/s): 1.7 % shorter than pure gravity (docs).
        let um = table().model_speed(5.0);
        let lg = 2.0 * PI * um * um / G;
        let lc = capillary_gravity_transverse_wavelength(um, G, sr).unwrap();
        let err = lc / lg - 1.0;
        eprintln!("5 m/s boat: model {um:.3} m/s, capillary-gravity / gravity − 1 = {err:.4}");
        assert!(err < -0.01 && err > -0.03, "{err}");
    }

    #[test]
    fn a_bad_scale_is_refused() {
        let t = straight(3.0, 10.0, 10.0, 10);
        let w = Wake::new(&[&t], WakeParams::default()).unwrap();
        for s in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = w.froude_scaled(s).unwrap_err().to_string();
            assert!(e.contains("froude scale"), "{e}");
        }
        assert_eq!(w.froude_scaled(1.0).unwrap(), w);
    }
}
