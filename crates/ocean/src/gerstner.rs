//! Superimposed Gerstner waves, exactly as the Sailing+ wave-model thesis (TU Delft 2022, report 003 in docs/sources.md) states them (its eqs. 1–2):
//!
//! W = (Dx, Dz, steepness Ω, wavelength λ), k = 2π/λ, A = Ω/k, c = sqrt(g/k), and for a rest
//! point x0 = (x, z):
//!
//! θ = k (D·x0 − c t) + φ,   x' = x0 + D A cos θ,   y = A sin θ,
//!
//! summed over the waves. With a finite depth h the dispersion relation is ω² = g k tanh(k h)
//! and c = ω/k, so k c t = ω t. Because the horizontal map compresses by at most Σ kA (its
//! Jacobian is I − Σ kA sin θ D Dᵀ), the surface stays a graph (no fold-over) while Σ kA < 1;
//! sea files that break this are refused on load.

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
    /// Determinant of the Jacobian of the horizontal map x0 -> x'. Low values mean the surface
    /// bunches up at a sharp crest, where foam forms ([`foam_from_jacobian`]). Always
    /// ≥ 1 − Σ kA > 0 for a valid sea.
    pub jacobian: f64,
}

/// The Jacobian determinant at and above which there is no foam.
pub const FOAM_ONSET_JACOBIAN: f64 = 0.6;

/// Foam coverage in [0, 1] from the Jacobian determinant J of the horizontal map:
/// `foam = clamp((J_onset − J) / J_onset, 0, 1)` with J_onset = [`FOAM_ONSET_JACOBIAN`].
/// J = 1 on a flat sea, J < 1 where the crest squeezes the surface together (Tessendorf's
/// choppy-wave foam criterion); J → 0 is the fold-over that Σ kA < 1 rules out.
pub fn foam_from_jacobian(jacobian: f64) -> f64 {
    ((FOAM_ONSET_JACOBIAN - jacobian) / FOAM_ONSET_JACOBIAN).clamp(0.0, 1.0)
}

/// Two foam coverages in [0, 1] on the same water (the sea's and a wake's) combined as
/// independent coverages: 1 − (1 − a)(1 − b). The one rule `regatta probe` reports and the
/// water shaders draw (`foam_coverage` in shaders/render/common.wgsl`, its constants generated
/// from these by `render::shader::prelude`).
pub fn foam_coverage(a: f64, b: f64) -> f64 {
    1.0 - (1.0 - a.clamp(0.0, 1.0)) * (1.0 - b.clamp(0.0, 1.0))
}

/// One wave frozen at a race time: what the inner loops need, with the time part of the phase
/// φ − ω t formed once and brought near [0, 2π) by subtracting a multiple of 2π. That constant
/// carries the f64 rounding of ω t (≤ 1e-8 rad at t = 1e7 s) for every point alike, so the
/// surface stays smooth in x0: without it, k D·x0 + φ − ω t would round to 7e-9 rad steps
/// between neighbouring points at t = 1e7 s and spoil finite differences and Newton.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WaveAt {
    pub d: [f64; 2],
    pub k: f64,
    pub a: f64,
    pub ka: f64,
    pub theta_t: f64,
}

impl WaveAt {
    pub fn new(w: &Wave, gravity: f64, depth: Option<f64>, t: f64) -> Self {
        let k = w.k();
        WaveAt {
            d: w.direction,
            k,
            a: w.steepness / k,
            ka: w.steepness,
            theta_t: {
                let th = w.phase - w.omega(gravity, depth) * t;
                // Cheaper than `reduce_phase` (rem_euclid) and as exact as θ itself here.
                th - TAU * (th / TAU).floor()
            },
        }
    }
}

/// Position, height gradient terms and horizontal Jacobian of the sum at one rest point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    /// Displaced position (x', y, z').
    pub pos: [f64; 3],
    /// ∂x'/∂x0, ∂x'/∂z0 (= ∂z'/∂x0: the Jacobian is symmetric), ∂z'/∂z0.
    pub jxx: f64,
    pub jxz: f64,
    pub jzz: f64,
    /// ∂y/∂x0, ∂y/∂z0.
    pub gx: f64,
    pub gz: f64,
}

impl Eval {
    pub fn det(&self) -> f64 {
        self.jxx * self.jzz - self.jxz * self.jxz
    }
    /// Unit normal of the displaced surface: (∂P/∂z0) × (∂P/∂x0), up for a flat sea.
    pub fn normal(&self) -> [f64; 3] {
        let tx = [self.jxx, self.gx, self.jxz];
        let tz = [self.jxz, self.gz, self.jzz];
        let n = [
            tz[1] * tx[2] - tz[2] * tx[1],
            tz[2] * tx[0] - tz[0] * tx[2],
            tz[0] * tx[1] - tz[1] * tx[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        [n[0] / len, n[1] / len, n[2] / len]
    }
    /// Gradient of the height over the *world* horizontal point: J⁻ᵀ ∇_x0 y (J is symmetric).
    pub fn world_gradient(&self) -> [f64; 2] {
        let det = self.det();
        [
            (self.jzz * self.gx - self.jxz * self.gz) / det,
            (self.jxx * self.gz - self.jxz * self.gx) / det,
        ]
    }
}

/// The one kernel every f64 evaluation goes through: one sin_cos per wave.
pub(crate) fn eval(waves: impl Iterator<Item = WaveAt>, x0: [f64; 2]) -> Eval {
    let mut e = Eval {
        pos: [x0[0], 0.0, x0[1]],
        jxx: 1.0,
        jxz: 0.0,
        jzz: 1.0,
        gx: 0.0,
        gz: 0.0,
    };
    for w in waves {
        let [dx, dz] = w.d;
        let theta = w.k * (dx * x0[0] + dz * x0[1]) + w.theta_t;
        let (s, c) = theta.sin_cos();
        let ac = w.a * c;
        e.pos[0] += dx * ac;
        e.pos[1] += w.a * s;
        e.pos[2] += dz * ac;
        let kas = w.ka * s;
        e.jxx -= dx * dx * kas;
        e.jxz -= dx * dz * kas;
        e.jzz -= dz * dz * kas;
        let kac = w.ka * c;
        e.gx += dx * kac;
        e.gz += dz * kac;
    }
    e
}

impl WaveSet {
    /// Σ kA over the waves: the largest possible horizontal compression. Must stay below 1.
    pub fn total_steepness(&self) -> f64 {
        self.waves.iter().map(|w| w.steepness).sum()
    }

    /// Σ A over the waves, metres: no point of the surface is farther than this from its rest
    /// point (each wave moves it by a vector of length exactly A).
    pub fn total_amplitude(&self) -> f64 {
        self.waves.iter().map(|w| w.amplitude()).sum()
    }

    /// The phase θ = k (D·x0 − c t) + φ of one wave at a rest point, in f64, unreduced.
    pub fn phase_at(&self, w: &Wave, x0: [f64; 2], t: f64) -> f64 {
        let k = w.k();
        k * (w.direction[0] * x0[0] + w.direction[1] * x0[1])
            - w.omega(self.gravity, self.depth) * t
            + w.phase
    }

    /// The waves frozen at time `t` (internal fast path of the inverse, culling and benches).
    pub(crate) fn at_time(&self, t: f64) -> impl Iterator<Item = WaveAt> + '_ {
        self.waves
            .iter()
            .map(move |w| WaveAt::new(w, self.gravity, self.depth, t))
    }

    /// The displaced surface point of the rest point `x0` at race time `t` (003 eqs. 1–2).
    pub fn displace(&self, x0: [f64; 2], t: f64) -> [f64; 3] {
        let (mut x, mut y, mut z) = (x0[0], 0.0, x0[1]);
        for w in self.at_time(t) {
            let theta = w.k * (w.d[0] * x0[0] + w.d[1] * x0[1]) + w.theta_t;
            let (s, c) = theta.sin_cos();
            x += w.d[0] * w.a * c;
            z += w.d[1] * w.a * c;
            y += w.a * s;
        }
        [x, y, z]
    }

    /// Position, analytic unit normal and horizontal Jacobian at the rest point `x0`.
    pub fn surface(&self, x0: [f64; 2], t: f64) -> SurfacePoint {
        let e = eval(self.at_time(t), x0);
        SurfacePoint {
            position: e.pos,
            normal: e.normal(),
            jacobian: e.det(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sea() -> WaveSet {
        WaveSet::default_sea()
    }

    #[test]
    fn single_wave_matches_the_closed_form_of_003() {
        // One wave along +x: x' = x + A cos(k(x − c t)), y = A sin(k(x − c t)), c = sqrt(g/k).
        let w = Wave {
            direction: [1.0, 0.0],
            steepness: 0.3,
            wavelength: 40.0,
            phase: 0.0,
        };
        let s = WaveSet {
            gravity: 9.8,
            depth: None,
            waves: vec![w],
        };
        let k = TAU / 40.0;
        let a = 0.3 / k;
        let c = (9.8 / k).sqrt();
        for &(x, z, t) in &[(0.0, 0.0, 0.0), (3.7, -2.0, 1.5), (-120.0, 55.0, 3600.0)] {
            let th = k * (x - c * t);
            let p = s.displace([x, z], t);
            assert!((p[0] - (x + a * th.cos())).abs() < 1e-9, "{p:?}");
            assert!((p[1] - a * th.sin()).abs() < 1e-9);
            assert!((p[2] - z).abs() < 1e-12);
        }
    }

    #[test]
    fn finite_depth_dispersion_is_slower_and_tends_to_deep_water() {
        let w = Wave {
            direction: [1.0, 0.0],
            steepness: 0.1,
            wavelength: 100.0,
            phase: 0.0,
        };
        let g = 9.81;
        let k = TAU / 100.0;
        // Shallow limit: c → sqrt(g h) for k h ≪ 1.
        let shallow = w.speed(g, Some(0.5));
        assert!(
            (shallow / (g * 0.5f64).sqrt() - 1.0).abs() < 1e-3,
            "{shallow}"
        );
        // Deep limit: tanh(k h) = 1 to double precision at h = 1 km.
        assert_eq!(w.omega(g, Some(1000.0)), (g * k).sqrt());
        assert!(w.speed(g, Some(10.0)) < w.speed(g, None));
    }

    /// Central differences of `displace` in f64 against the analytic Jacobian and normal.
    #[test]
    fn analytic_normal_and_jacobian_match_finite_differences() {
        let s = sea();
        let h = 1e-4;
        for &(x, z, t) in &[
            (0.0, 0.0, 0.0),
            (12.3, -7.7, 13.0),
            (-4000.0, 2500.0, 86_400.0),
            (9000.0, 9000.0, 1e7),
        ] {
            let sp = s.surface([x, z], t);
            let px = |d: f64| s.displace([x + d, z], t);
            let pz = |d: f64| s.displace([x, z + d], t);
            let tx: Vec<f64> = (0..3).map(|i| (px(h)[i] - px(-h)[i]) / (2.0 * h)).collect();
            let tz: Vec<f64> = (0..3).map(|i| (pz(h)[i] - pz(-h)[i]) / (2.0 * h)).collect();
            let det = tx[0] * tz[2] - tx[2] * tz[0];
            assert!((det - sp.jacobian).abs() < 1e-6, "{det} vs {}", sp.jacobian);
            let n = [
                tz[1] * tx[2] - tz[2] * tx[1],
                tz[2] * tx[0] - tz[0] * tx[2],
                tz[0] * tx[1] - tz[1] * tx[0],
            ];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            for (a, b) in n.iter().zip(sp.normal) {
                assert!((a / len - b).abs() < 1e-6, "{n:?} {sp:?}");
            }
            assert!(sp.normal[1] > 0.0);
            assert!(sp.jacobian >= 1.0 - s.total_steepness() - 1e-12);
            // The position agrees with `displace` exactly (same kernel arithmetic).
            let p = s.displace([x, z], t);
            for (a, b) in p.iter().zip(sp.position) {
                assert!((a - b).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn foam_formula() {
        assert_eq!(foam_from_jacobian(1.0), 0.0);
        assert_eq!(foam_from_jacobian(FOAM_ONSET_JACOBIAN), 0.0);
        assert!((foam_from_jacobian(0.3) - 0.5).abs() < 1e-12);
        assert_eq!(foam_from_jacobian(-1.0), 1.0);
        // Coverages: none adds nothing, full covers all, halves leave a quarter bare.
        assert!((foam_coverage(0.3, 0.0) - 0.3).abs() < 1e-15);
        assert_eq!(foam_coverage(1.0, 0.4), 1.0);
        assert!((foam_coverage(0.5, 0.5) - 0.75).abs() < 1e-15);
    }
}
