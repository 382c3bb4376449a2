//! The pool's moving water: Gerstner waves from `ocean` plus analytic ripple rings where a
//! sphere moves through the surface. Both are closed-form functions of time and of the spheres'
//! paths, so a scrubbed or replayed frame is the same frame.
//!
//! # The ripple formula
//!
//! A sphere that moves through the surface emits a ring at every emission time t_j = j·Δt
//! (j an integer: the grid is fixed in time, so the rings at a time t do not depend on when the
//! frame was asked for). Ring j is centred on the sphere's horizontal position p_j = p(t_j) and
//! its amplitude is the distance the sphere moved during the interval, times how deep the
//! sphere cuts the surface:
//!
//! A_j = κ · w(y(t_j)) · min(|p_xz(t_j) − p_xz(t_j − Δt)|, R),   w(y) = max(0, 1 − |y|/R),
//!
//! (R the sphere's radius, y its centre's height above the rest level: a sphere clear of the
//! surface or deep below it makes no ripple, and a still one makes none). The height of the
//! ripples at a horizontal point x at time t is
//!
//! η(x, t) = Σ_j A_j · e^(−a_j/τ) · √(R/(R + r_j)) · exp(−(r_j − c_g a_j)² / (2σ²)) · cos(k r_j − ω a_j)
//!
//! with a_j = t − t_j ≥ 0 the ring's age and r_j = √(|x − p_j|² + ε²) its radius (ε removes the
//! cone tip at the centre, so η is smooth everywhere). Each ring is a packet of deep-water
//! waves of wave number k: its crests move at the phase speed ω/k, ω = √(g k), and its envelope
//! (a Gaussian of width σ) at the group speed c_g = ω/(2k), so rings spread as they travel; the
//! √(R/(R + r)) factor is the cylindrical spreading that keeps a ring's energy as its
//! circumference grows, and e^(−a/τ) the viscous and contact-line damping. The pool is 1 m deep
//! and λ ≈ 0.2 m, so tanh(k h) = 1 to 1e-13 and deep water is exact here.
//!
//! Only rings younger than `window_decays · τ` are summed: an older one has decayed below
//! e^(−window_decays) of its starting amplitude (1.8 % for the default 4), the truncation bound.
//! The gradient ∇η is the analytic derivative of the same sum (tested against differences).

use glam::DVec3;
use ocean::WaveSet;
use std::f64::consts::TAU;

/// The constants of the ripple formula (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RippleModel {
    /// λ, metres.
    pub wavelength: f64,
    /// g, m/s².
    pub gravity: f64,
    /// τ, seconds.
    pub decay_s: f64,
    /// σ, metres.
    pub packet_width: f64,
    /// κ, dimensionless.
    pub coupling: f64,
    /// Δt between emissions, seconds.
    pub emit_interval: f64,
    /// Rings older than this many τ are dropped.
    pub window_decays: f64,
    /// ε, metres.
    pub core: f64,
}

impl Default for RippleModel {
    fn default() -> Self {
        RippleModel {
            wavelength: 0.2,
            gravity: ocean::STANDARD_GRAVITY,
            decay_s: 1.0,
            packet_width: 0.08,
            coupling: 0.25,
            emit_interval: 1.0 / 16.0,
            window_decays: 4.0,
            core: 0.01,
        }
    }
}

impl RippleModel {
    /// k, rad/m.
    pub fn k(&self) -> f64 {
        TAU / self.wavelength
    }
    /// ω = √(g k), rad/s.
    pub fn omega(&self) -> f64 {
        (self.gravity * self.k()).sqrt()
    }
    /// c_g = ω / (2k), m/s.
    pub fn group_speed(&self) -> f64 {
        self.omega() / (2.0 * self.k())
    }
    /// The most rings one moving sphere can have alive at once.
    pub fn max_rings_per_sphere(&self) -> usize {
        (self.window_decays * self.decay_s / self.emit_interval).floor() as usize + 1
    }
}

/// How a moving sphere moves: a closed-form function of time.
#[derive(Debug, Clone, PartialEq)]
pub enum SpherePath {
    /// An ellipse in a horizontal plane: centre + (a cos θ, 0, b sin θ), θ = 2π t / period + φ.
    Orbit {
        center: DVec3,
        radii: [f64; 2],
        period_s: f64,
        phase: f64,
    },
    /// Samples (t, position), strictly increasing in t, joined by straight lines and held
    /// before the first and after the last: what a drag with the mouse or a finger records.
    Track(Vec<(f64, DVec3)>),
}

impl SpherePath {
    /// The centre at time `t`, metres.
    pub fn position(&self, t: f64) -> DVec3 {
        match self {
            SpherePath::Orbit {
                center,
                radii,
                period_s,
                phase,
            } => {
                // Reduce the angle in f64 so a long session stays exact.
                let theta = ocean::reduce_phase(TAU * (t / period_s).fract() + phase);
                let (s, c) = theta.sin_cos();
                *center + DVec3::new(radii[0] * c, 0.0, radii[1] * s)
            }
            SpherePath::Track(samples) => {
                let Some(first) = samples.first() else {
                    return DVec3::ZERO;
                };
                if t <= first.0 {
                    return first.1;
                }
                // The first sample later than t; the segment before it holds t.
                let i = samples.partition_point(|(ts, _)| *ts <= t);
                if i == samples.len() {
                    return samples[i - 1].1;
                }
                let (t0, p0) = samples[i - 1];
                let (t1, p1) = samples[i];
                p0.lerp(p1, (t - t0) / (t1 - t0))
            }
        }
    }
}

/// One ripple ring at the time it is evaluated (what the shader gets, in f32).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ring {
    /// Horizontal centre (x, z), metres.
    pub center: [f64; 2],
    /// a_j, seconds, ≥ 0.
    pub age: f64,
    /// A_j, metres.
    pub amplitude: f64,
    /// R of the sphere that emitted it, metres.
    pub source_radius: f64,
}

/// The rings alive at time `t` from a sphere of radius `radius` moving along `path`.
pub fn rings_of(model: &RippleModel, path: &SpherePath, radius: f64, t: f64) -> Vec<Ring> {
    let dt = model.emit_interval;
    let window = model.window_decays * model.decay_s;
    let newest = (t / dt).floor();
    let mut rings = Vec::new();
    for n in 0..model.max_rings_per_sphere() {
        let tj = (newest - n as f64) * dt;
        let age = t - tj;
        if age > window {
            break;
        }
        let p = path.position(tj);
        let before = path.position(tj - dt);
        // A sphere cannot push more water than its own size in one interval: the cap keeps a
        // jump (a drag that starts away from the sphere) from making a tidal wave.
        let moved = ((p.x - before.x).powi(2) + (p.z - before.z).powi(2))
            .sqrt()
            .min(radius);
        let immersion = (1.0 - p.y.abs() / radius).max(0.0);
        let amplitude = model.coupling * immersion * moved;
        if amplitude > 0.0 {
            rings.push(Ring {
                center: [p.x, p.z],
                age,
                amplitude,
                source_radius: radius,
            });
        }
    }
    rings
}

/// η and its gradient (∂η/∂x, ∂η/∂z) at the horizontal point `x` (module docs' formula).
pub fn ripple_height(model: &RippleModel, rings: &[Ring], x: [f64; 2]) -> (f64, [f64; 2]) {
    let k = model.k();
    let omega = model.omega();
    let cg = model.group_speed();
    let sigma2 = model.packet_width * model.packet_width;
    let (mut h, mut gx, mut gz) = (0.0, 0.0, 0.0);
    for ring in rings {
        let dx = x[0] - ring.center[0];
        let dz = x[1] - ring.center[1];
        let r = (dx * dx + dz * dz + model.core * model.core).sqrt();
        let big_r = ring.source_radius;
        let spread = (big_r / (big_r + r)).sqrt();
        let u = r - cg * ring.age;
        let envelope = (-u * u / (2.0 * sigma2)).exp();
        let (sin, cos) = (k * r - omega * ring.age).sin_cos();
        let a = ring.amplitude * (-ring.age / model.decay_s).exp();
        h += a * spread * envelope * cos;
        // d/dr of spread · envelope · cos, by the product rule.
        let dspread = -spread / (2.0 * (big_r + r));
        let denvelope = -u / sigma2 * envelope;
        let dcos = -k * sin;
        let dh_dr =
            a * (dspread * envelope * cos + spread * denvelope * cos + spread * envelope * dcos);
        // ∂r/∂x = dx / r (r > 0 always, thanks to ε).
        gx += dh_dr * dx / r;
        gz += dh_dr * dz / r;
    }
    (h, [gx, gz])
}

/// A point of the total water surface: position and unit normal (pointing up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterPoint {
    pub position: DVec3,
    pub normal: DVec3,
}

/// The water of the pool: Gerstner waves (rest level y = 0) plus ripples.
#[derive(Debug, Clone, PartialEq)]
pub struct PoolWater {
    pub waves: WaveSet,
    pub ripples: RippleModel,
}

impl PoolWater {
    /// The surface point that the waves carry the rest point `x0` to at time `t`, lifted by the
    /// ripples at the point where it lands.
    ///
    /// The normal adds slopes: the Gerstner surface, seen as a height field, has slopes
    /// (−n_x/n_y, −n_z/n_y); the ripples add ∇η; the normal of the sum is (−s_x, 1, −s_z)
    /// normalised.
    pub fn point(&self, x0: [f64; 2], t: f64, rings: &[Ring]) -> WaterPoint {
        let g = self.waves.surface(x0, t);
        let [x, y, z] = g.position;
        let (eta, grad) = ripple_height(&self.ripples, rings, [x, z]);
        let [nx, ny, nz] = g.normal;
        let sx = -nx / ny + grad[0];
        let sz = -nz / ny + grad[1];
        WaterPoint {
            position: DVec3::new(x, y + eta, z),
            normal: DVec3::new(-sx, 1.0, -sz).normalize(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_ring(age: f64) -> Vec<Ring> {
        vec![Ring {
            center: [0.2, -0.1],
            age,
            amplitude: 0.01,
            source_radius: 0.15,
        }]
    }

    #[test]
    fn ripple_gradient_matches_central_differences() {
        let m = RippleModel::default();
        let rings = [
            one_ring(0.4)[0],
            Ring {
                center: [-0.3, 0.25],
                age: 1.1,
                amplitude: 0.02,
                source_radius: 0.2,
            },
        ];
        let h = 1e-6;
        for x in [[0.0, 0.0], [0.31, -0.05], [-0.1, 0.4], [0.2, -0.1]] {
            let (_, g) = ripple_height(&m, &rings, x);
            let fx = (ripple_height(&m, &rings, [x[0] + h, x[1]]).0
                - ripple_height(&m, &rings, [x[0] - h, x[1]]).0)
                / (2.0 * h);
            let fz = (ripple_height(&m, &rings, [x[0], x[1] + h]).0
                - ripple_height(&m, &rings, [x[0], x[1] - h]).0)
                / (2.0 * h);
            assert!((g[0] - fx).abs() < 1e-6, "{g:?} vs {fx}");
            assert!((g[1] - fz).abs() < 1e-6, "{g:?} vs {fz}");
        }
    }

    #[test]
    fn ring_crest_travels_at_group_speed_and_is_round() {
        let m = RippleModel::default();
        let age = 1.5;
        let rings = one_ring(age);
        // Sample the envelope |η| along +x and find where it peaks: at r ≈ c_g · age.
        let mut best = (0.0, 0.0);
        for i in 0..4000 {
            let r = i as f64 * 0.0005;
            let env = (0..8)
                .map(|q| {
                    let x = [0.2 + r + q as f64 * m.wavelength / 8.0, -0.1];
                    ripple_height(&m, &rings, x).0.abs()
                })
                .fold(0.0, f64::max);
            if env > best.1 {
                best = (r, env);
            }
        }
        let expected = m.group_speed() * age;
        assert!(
            (best.0 - expected).abs() < 0.5 * m.wavelength,
            "peak at {} m, expected {expected} m",
            best.0
        );
        // Round: the same height at the same distance in any direction.
        let at = |ang: f64| {
            let r = 0.37;
            ripple_height(&m, &rings, [0.2 + r * ang.cos(), -0.1 + r * ang.sin()]).0
        };
        for ang in [0.3, 1.7, 3.0, 4.4] {
            assert!((at(ang) - at(0.0)).abs() < 1e-15);
        }
    }

    #[test]
    fn still_sphere_makes_no_rings_and_moving_one_does() {
        let m = RippleModel::default();
        let still = SpherePath::Track(vec![(0.0, DVec3::new(0.1, 0.0, 0.2))]);
        assert!(rings_of(&m, &still, 0.15, 3.0).is_empty());
        let orbit = SpherePath::Orbit {
            center: DVec3::ZERO,
            radii: [0.5, 0.3],
            period_s: 6.0,
            phase: 0.0,
        };
        let t = 10.03;
        let rings = rings_of(&m, &orbit, 0.15, t);
        // One ring per emission time j·Δt in [t − 4τ, t].
        let window = m.window_decays * m.decay_s;
        let expected = (0..1000)
            .map(|j| j as f64 * m.emit_interval)
            .filter(|tj| *tj <= t && t - tj <= window)
            .count();
        assert_eq!(rings.len(), expected);
        assert!(rings.len() <= m.max_rings_per_sphere());
        // Each ring's amplitude is κ times the chord the sphere moved in Δt (centre at y = 0,
        // so fully cutting the surface).
        for r in &rings {
            let tj = t - r.age;
            let a = orbit.position(tj);
            let b = orbit.position(tj - m.emit_interval);
            let chord = ((a.x - b.x).powi(2) + (a.z - b.z).powi(2)).sqrt();
            assert!((r.amplitude - m.coupling * chord).abs() < 1e-15);
            assert!(r.age <= m.window_decays * m.decay_s && r.age >= 0.0);
        }
        // A sphere deep below the surface (centre 2 R down) makes none.
        let deep = SpherePath::Orbit {
            center: DVec3::new(0.0, -0.3, 0.0),
            radii: [0.5, 0.3],
            period_s: 6.0,
            phase: 0.0,
        };
        assert!(rings_of(&m, &deep, 0.15, 10.0).is_empty());
    }

    #[test]
    fn rings_depend_only_on_time_not_on_when_asked() {
        // Scrubbing: the rings at t are the same whatever frame came before.
        let m = RippleModel::default();
        let orbit = SpherePath::Orbit {
            center: DVec3::ZERO,
            radii: [0.5, 0.3],
            period_s: 6.0,
            phase: 0.4,
        };
        let a = rings_of(&m, &orbit, 0.15, 7.3);
        let _ = rings_of(&m, &orbit, 0.15, 2.0);
        let b = rings_of(&m, &orbit, 0.15, 7.3);
        assert_eq!(a, b);
    }

    #[test]
    fn track_interpolates_linearly_and_holds_at_the_ends() {
        let p = SpherePath::Track(vec![
            (1.0, DVec3::new(0.0, 0.0, 0.0)),
            (3.0, DVec3::new(2.0, 0.0, -1.0)),
        ]);
        assert_eq!(p.position(0.0), DVec3::ZERO);
        assert_eq!(p.position(2.0), DVec3::new(1.0, 0.0, -0.5));
        assert_eq!(p.position(9.0), DVec3::new(2.0, 0.0, -1.0));
    }

    #[test]
    fn flat_sea_normal_is_ripple_gradient_normal() {
        let water = PoolWater {
            waves: WaveSet {
                gravity: 9.81,
                depth: None,
                waves: vec![],
            },
            ripples: RippleModel::default(),
        };
        let rings = one_ring(0.6);
        let x = [0.33, 0.05];
        let p = water.point(x, 0.0, &rings);
        let (eta, g) = ripple_height(&water.ripples, &rings, x);
        assert_eq!(p.position, DVec3::new(x[0], eta, x[1]));
        let n = DVec3::new(-g[0], 1.0, -g[1]).normalize();
        assert!((p.normal - n).length() < 1e-15);
    }
}
