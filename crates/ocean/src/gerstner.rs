//! Superimposed Gerstner waves, exactly as source report 003 states them (its eqs. 1–2):
//!
//! W = (Dx, Dz, steepness Ω, wavelength λ), k = 2π/λ, A = Ω/k, c = sqrt(g/k), and for a rest
//! point x0 = (x, z):
//!
//! θ = k (D·x0 − c t) + φ,   x' = x0 + D A cos θ,   y = A sin θ,
//!
//! summed over the waves. With a finite depth h the dispersion relation is ω² = g k tanh(k h)
//! and c = ω/k. Because the horizontal map compresses by at most Σ kA, the surface stays a
//! graph (no fold-over) while Σ kA < 1; sea files that break this are refused on load.

use std::f64::consts::TAU;

/// One Gerstner wave. Direction is a unit vector in the (x, z) plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wave {
    /// Unit direction of travel (x east, z south).
    pub direction: [f64; 2],
    /// Ω = k A, dimensionless, in [0, 1].
    pub steepness: f64,
    /// λ, metres, > 0.
    pub wavelength: f64,
    /// φ, radians.
    pub phase: f64,
}

impl Wave {
    /// Wave number k = 2π/λ, rad/m.
    pub fn k(&self) -> f64 {
        TAU / self.wavelength
    }
    /// Amplitude A = Ω/k, metres.
    pub fn amplitude(&self) -> f64 {
        self.steepness / self.k()
    }
    /// Angular frequency ω, rad/s: ω² = g k (deep) or g k tanh(k h) (depth h).
    pub fn omega(&self, gravity: f64, depth: Option<f64>) -> f64 {
        let k = self.k();
        match depth {
            Some(h) => (gravity * k * (k * h).tanh()).sqrt(),
            None => (gravity * k).sqrt(),
        }
    }
    /// Phase speed c = ω/k, m/s (003: c = sqrt(g/k) in deep water).
    pub fn speed(&self, gravity: f64, depth: Option<f64>) -> f64 {
        self.omega(gravity, depth) / self.k()
    }
}

/// A sea: the waves, gravity and an optional finite depth.
#[derive(Debug, Clone, PartialEq)]
pub struct WaveSet {
    /// m/s².
    pub gravity: f64,
    /// Water depth in metres; `None` is deep water.
    pub depth: Option<f64>,
    pub waves: Vec<Wave>,
}

/// The surface at a rest point: where it goes and how the surface is oriented there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Displaced position (x', y, z'), metres.
    pub position: [f64; 3],
    /// Unit normal of the surface, pointing up (y > 0).
    pub normal: [f64; 3],
    /// Determinant of the Jacobian of the horizontal map x0 -> x'. Below ~0.3 the surface
    /// bunches up at a sharp crest: where foam forms. Always > 1 − Σ kA > 0 for a valid sea.
    pub jacobian: f64,
}

impl WaveSet {
    /// Σ kA over the waves: the largest possible horizontal compression. Must stay below 1.
    pub fn total_steepness(&self) -> f64 {
        self.waves.iter().map(|w| w.steepness).sum()
    }

    /// The phase θ = k (D·x0 − c t) + φ of one wave at a rest point, in f64, unreduced.
    pub fn phase_at(&self, w: &Wave, x0: [f64; 2], t: f64) -> f64 {
        let k = w.k();
        k * (w.direction[0] * x0[0] + w.direction[1] * x0[1])
            - w.omega(self.gravity, self.depth) * t
            + w.phase
    }

    /// The displaced surface point of the rest point `x0` at race time `t` (003 eqs. 1–2).
    pub fn displace(&self, x0: [f64; 2], t: f64) -> [f64; 3] {
        let (mut x, mut y, mut z) = (x0[0], 0.0, x0[1]);
        for w in &self.waves {
            let theta = self.phase_at(w, x0, t);
            let a = w.amplitude();
            let (s, c) = theta.sin_cos();
            x += w.direction[0] * a * c;
            z += w.direction[1] * a * c;
            y += a * s;
        }
        [x, y, z]
    }

    /// Position, analytic unit normal and horizontal Jacobian at the rest point `x0`.
    pub fn surface(&self, x0: [f64; 2], t: f64) -> SurfacePoint {
        let (mut x, mut y, mut z) = (x0[0], 0.0, x0[1]);
        // Partial derivatives of the horizontal map and of the height w.r.t. x0 and z0.
        let (mut dxdx, mut dxdz, mut dzdz) = (1.0, 0.0, 1.0);
        let (mut dydx, mut dydz) = (0.0, 0.0);
        for w in &self.waves {
            let theta = self.phase_at(w, x0, t);
            let a = w.amplitude();
            let ka = w.steepness;
            let [dx, dz] = w.direction;
            let (s, c) = theta.sin_cos();
            x += dx * a * c;
            z += dz * a * c;
            y += a * s;
            dxdx -= dx * dx * ka * s;
            dxdz -= dx * dz * ka * s;
            dzdz -= dz * dz * ka * s;
            dydx += dx * ka * c;
            dydz += dz * ka * c;
        }
        // Tangents along x0 and z0: Tx = (dxdx, dydx, dxdz), Tz = (dxdz, dydz, dzdz).
        // Normal = Tz × Tx points up for a flat sea.
        let tx = [dxdx, dydx, dxdz];
        let tz = [dxdz, dydz, dzdz];
        let n = [
            tz[1] * tx[2] - tz[2] * tx[1],
            tz[2] * tx[0] - tz[0] * tx[2],
            tz[0] * tx[1] - tz[1] * tx[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        SurfacePoint {
            position: [x, y, z],
            normal: [n[0] / len, n[1] / len, n[2] / len],
            jacobian: dxdx * dzdz - dxdz * dxdz,
        }
    }
}
