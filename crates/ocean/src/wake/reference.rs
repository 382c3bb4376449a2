//! Independent f64 reference: the Kelvin wake of a pressure patch moving straight and steadily
//! over deep water, by numerical integration of the classical integral over wave angles.
//!
//! Boat frame: the boat is at the origin, moving in +x at speed U; ξ is the distance ahead
//! (negative behind), y the distance to the side. Linear theory with Rayleigh's vanishing
//! damping gives the steady field as a double Fourier integral; its poles at
//! k = k₀ sec²θ (k₀ = g/U²) leave the wave part (Havelock 1908; Lamb §256; Wehausen & Laitone
//! 1960 §13):
//!
//! η_w(ξ, y) = F k₀²/(π ρ g) ∫_{−π/2}^{π/2} H(−ϖ) sec⁴θ e^{−k₀² sec⁴θ R²/4} sin(k₀ sec²θ ϖ) dθ,
//! ϖ = ξ cos θ + y sin θ,
//!
//! for the Gaussian patch of force F and radius R (its Fourier transform is F e^{−k²R²/4}).
//! With u = tan θ (sec⁴θ dθ = (1 + u²) du, ϖ sec²θ = (ξ + y u)√(1 + u²)) the integrand is
//! smooth and decays like the Gaussian; the cut H(−ϖ) becomes ξ + y u < 0. It oscillates
//! ever faster as |u| grows, so it is integrated with 5-point Gauss–Legendre panels whose width
//! is `accuracy` × π / (local phase rate): a fixed number of points per oscillation.
//! `kelvin_reference` returns the value and the change when the panels are halved, so every
//! caller sees its own convergence. This shares nothing with `kelvin.rs` but the physics.

use std::f64::consts::PI;

use super::kelvin::SEA_WATER_DENSITY;

/// A steady, straight pressure patch: what the reference evaluates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyPatch {
    /// m/s, > 0.
    pub speed: f64,
    /// N.
    pub force: f64,
    /// m, > 0.
    pub hull_radius: f64,
    /// m/s².
    pub gravity: f64,
}

impl SteadyPatch {
    /// k₀ = g/U², rad/m.
    pub fn k0(&self) -> f64 {
        self.gravity / (self.speed * self.speed)
    }
    /// Transverse wavelength 2πU²/g, m.
    pub fn wavelength(&self) -> f64 {
        2.0 * PI / self.k0()
    }
}

const GL_X: [f64; 5] = [
    0.0,
    -0.538_469_310_105_683_1,
    0.538_469_310_105_683_1,
    -0.906_179_845_938_664,
    0.906_179_845_938_664,
];
const GL_W: [f64; 5] = [
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
    0.236_926_885_056_189_1,
];

/// The wave part at (ξ, y), m, with panels of `accuracy` × π / phase rate (0.25 is plenty).
pub fn kelvin_wave_height(p: &SteadyPatch, xi: f64, y: f64, accuracy: f64) -> f64 {
    let k0 = p.k0();
    let r = p.hull_radius;
    // Beyond |u| = uc the Gaussian is below e^{−36}: (k0 (1 + u²) R)²/4 ≥ 36.
    let uc = ((12.0 / (k0 * r)) - 1.0).max(0.0).sqrt() + 1.0;
    let (mut a, mut b) = (-uc, uc);
    if y > 0.0 {
        b = b.min(-xi / y);
    } else if y < 0.0 {
        a = a.max(-xi / y);
    } else if xi >= 0.0 {
        return 0.0;
    }
    if a >= b {
        return 0.0;
    }
    let integrand = |u: f64| {
        let s2 = 1.0 + u * u;
        let s = s2.sqrt();
        s2 * (-(k0 * s2 * r).powi(2) / 4.0).exp() * (k0 * (xi + y * u) * s).sin()
    };
    // |d/du| of the phase, plus the Gaussian's log-derivative: both set the panel width.
    let rate = |u: f64| {
        let s = (1.0 + u * u).sqrt();
        k0 * (y * s + (xi + y * u) * u / s).abs()
            + (k0 * r).powi(2) * (1.0 + u * u) * u.abs()
            + 1e-9
    };
    let mut sum = 0.0;
    let mut u = a;
    while u < b {
        let h = (accuracy * PI / rate(u)).min(0.05).min(b - u).max(1e-9);
        let m = u + 0.5 * h;
        for (x, w) in GL_X.iter().zip(GL_W) {
            sum += w * 0.5 * h * integrand(m + 0.5 * h * x);
        }
        u += h;
    }
    p.force * k0 * k0 / (PI * SEA_WATER_DENSITY * p.gravity) * sum
}

/// The reference value at (ξ, y) and its convergence: |value(accuracy) − value(accuracy/2)|.
pub fn kelvin_reference(p: &SteadyPatch, xi: f64, y: f64) -> (f64, f64) {
    let fine = kelvin_wave_height(p, xi, y, 0.125);
    let coarse = kelvin_wave_height(p, xi, y, 0.25);
    (fine, (fine - coarse).abs())
}
