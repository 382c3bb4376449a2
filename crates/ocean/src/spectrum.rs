//! Seas from real conditions: JONSWAP / Pierson–Moskowitz spectra with cos-2s directional
//! spreading, turned into a [`WaveSet`] with a fixed seed.
//!
//! Conventions as DNV-RP-C205 (2010) §3.5.5, written in frequency f (Hz), fp = 1/Tp:
//!
//! S_PM(f) = (5/16) Hs² fp⁴ f⁻⁵ exp(−5/4 (f/fp)⁻⁴),  ∫ S_PM df = Hs²/16 exactly;
//! S_J(f)  = A_γ S_PM(f) γ^exp(−(f − fp)² / (2 σ² fp²)),  σ = 0.07 (f ≤ fp), 0.09 (f > fp),
//! A_γ = 1 − 0.287 ln γ (so ∫ S_J df ≈ Hs²/16); γ = 1 is Pierson–Moskowitz.
//!
//! Directional spreading (Longuet-Higgins et al. 1963): D(Δ) = G(s) cos^{2s}(Δ/2) on
//! [−π, π], G(s) = 2^{2s−1} Γ(s+1)² / (π Γ(2s+1)); its first circular moment is
//! r1 = s/(s+1), which is how an NDBC buoy's r1 gives s.
//!
//! The discrete sea: the spectrum is cut into bands; each band becomes one wave with
//! A = sqrt(2 ∫band S df) (so the set's Hs = 4 sqrt(Σ A²/2) equals the band-limited spectrum's
//! 4 sqrt(m0)), a frequency drawn inside the band, a direction drawn from D around the mean
//! and a uniform phase, all from one seeded RNG. If Σ kA would reach the limit (default 0.8),
//! every amplitude is scaled by one factor, which is reported, never hidden.

use std::f64::consts::{PI, TAU};

use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

use crate::{STANDARD_GRAVITY, Wave, WaveSet};

/// Pierson–Moskowitz spectral density S(f), m²/Hz, for significant height `hs` (m) and peak
/// period `tp` (s).
pub fn pierson_moskowitz(f: f64, hs: f64, tp: f64) -> f64 {
    if f <= 0.0 {
        return 0.0;
    }
    let fp = 1.0 / tp;
    let r = fp / f;
    5.0 / 16.0 * hs * hs * fp.powi(4) * f.powi(-5) * (-1.25 * r.powi(4)).exp()
}

/// The JONSWAP normalising factor A_γ = 1 − 0.287 ln γ (DNV-RP-C205 eq. 3.5.5.2 area).
pub fn jonswap_normalisation(gamma: f64) -> f64 {
    1.0 - 0.287 * gamma.ln()
}

/// JONSWAP spectral density S(f), m²/Hz, with peak enhancement `gamma` (3.3 is the JONSWAP
/// mean; 1 gives Pierson–Moskowitz).
pub fn jonswap(f: f64, hs: f64, tp: f64, gamma: f64) -> f64 {
    let fp = 1.0 / tp;
    let sigma = if f <= fp { 0.07 } else { 0.09 };
    let x = (f - fp) / (sigma * fp);
    jonswap_normalisation(gamma) * pierson_moskowitz(f, hs, tp) * gamma.powf((-0.5 * x * x).exp())
}

/// ln Γ(x) for x > 0 (Lanczos, g = 7, 9 terms: ~1e-15 relative).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Γ(x) Γ(1 − x) = π / sin(πx).
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * TAU.ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// The cos-2s spreading density D(Δ) over Δ ∈ [−π, π] (radians⁻¹), Δ the angle from the mean.
pub fn cos2s(delta: f64, s: f64) -> f64 {
    let ln_g =
        (2.0 * s - 1.0) * 2f64.ln() + 2.0 * ln_gamma(s + 1.0) - PI.ln() - ln_gamma(2.0 * s + 1.0);
    ln_g.exp() * (0.5 * delta).cos().abs().powf(2.0 * s)
}

/// The spreading exponent s whose first circular moment is `r1` (r1 = s/(s+1)).
pub fn spreading_from_r1(r1: f64) -> f64 {
    let r1 = r1.clamp(0.0, 0.995);
    r1 / (1.0 - r1)
}

/// Travel direction (x east, z south) of waves that come *from* the compass bearing
/// `from_deg` (oceanographic convention: 0 = from north, 90 = from east).
pub fn travel_direction_from_compass(from_deg: f64) -> [f64; 2] {
    let b = from_deg.to_radians();
    // Travel bearing b + 180°: unit (sin, −cos) of it in x east, z south.
    [-b.sin(), b.cos()]
}

/// Wave number k, rad/m, of frequency `f` Hz: ω² = g k tanh(k h), solved by bisection.
/// Bracket: tanh x ≤ min(x, 1) makes both the deep (ω²/g) and the shallow (ω/sqrt(g h)) wave
/// numbers lower bounds; tanh x ≥ tanh(1) min(x, 1) makes their maximum / tanh(1) an upper one.
pub fn wave_number(f: f64, gravity: f64, depth: Option<f64>) -> f64 {
    let w2 = (TAU * f).powi(2);
    let deep = w2 / gravity;
    let Some(h) = depth else { return deep };
    let lo = deep.max((w2 / (gravity * h)).sqrt());
    let (mut lo, mut hi) = (lo, lo / 1f64.tanh());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if gravity * mid * (mid * h).tanh() < w2 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// One band of a discretised spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// Frequency range, Hz.
    pub f_lo: f64,
    pub f_hi: f64,
    /// ∫ S df over the band, m².
    pub energy: f64,
    /// Mean travel direction (unit, x east, z south).
    pub direction: [f64; 2],
    /// cos-2s spreading exponent (0 is isotropic).
    pub spreading: f64,
}

/// How a spectrum becomes waves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralOptions {
    /// Seed of every random choice (frequency inside a band, direction, phase).
    pub seed: u64,
    /// Σ kA is kept at or below this (< 1); amplitudes are scaled by one factor if needed.
    pub max_total_steepness: f64,
    pub gravity: f64,
    pub depth: Option<f64>,
}

impl Default for SpectralOptions {
    fn default() -> Self {
        SpectralOptions {
            seed: 1,
            max_total_steepness: 0.8,
            gravity: STANDARD_GRAVITY,
            depth: None,
        }
    }
}

/// A generated sea and what the generation did to it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralSea {
    pub sea: WaveSet,
    /// The factor every amplitude was multiplied by to keep Σ kA ≤ the limit (1 = untouched).
    pub amplitude_scale: f64,
    /// Σ kA before scaling.
    pub unscaled_total_steepness: f64,
    /// 4 sqrt(m0) of the bands (the spectrum as discretised), metres.
    pub hs_spectrum: f64,
    /// 4 sqrt(Σ A²/2) of the generated waves after scaling, metres.
    pub hs_waves: f64,
}

/// A sea state: the inputs of a parametric spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeaState {
    /// Significant wave height Hs, metres.
    pub hs: f64,
    /// Peak period Tp, seconds.
    pub tp: f64,
    /// JONSWAP peak enhancement γ ≥ 1 (1 = Pierson–Moskowitz, 3.3 = JONSWAP mean).
    pub gamma: f64,
    /// Mean travel direction (x east, z south); normalised on use.
    pub direction: [f64; 2],
    /// cos-2s spreading exponent s.
    pub spreading: f64,
}

impl SeaState {
    /// Cut the JONSWAP spectrum into `n` bands with geometric spacing from 0.6 fp to 4 fp
    /// (below 0.6 fp S is < 1e-4 of its peak; above 4 fp lies < 1 % of m0 and waves too short
    /// to matter at race scale).
    pub fn bands(&self, n: usize) -> Vec<Band> {
        let fp = 1.0 / self.tp;
        let (lo, hi) = (0.6 * fp, 4.0 * fp);
        let ratio = (hi / lo).powf(1.0 / n as f64);
        let len = self.direction[0].hypot(self.direction[1]);
        let dir = [self.direction[0] / len, self.direction[1] / len];
        (0..n)
            .map(|i| {
                let f_lo = lo * ratio.powi(i as i32);
                let f_hi = f_lo * ratio;
                Band {
                    f_lo,
                    f_hi,
                    energy: simpson(|f| jonswap(f, self.hs, self.tp, self.gamma), f_lo, f_hi, 64),
                    direction: dir,
                    spreading: self.spreading,
                }
            })
            .collect()
    }

    /// The sea of `n` waves for this sea state.
    pub fn to_sea(&self, n: usize, opts: &SpectralOptions) -> SpectralSea {
        sea_from_bands(&self.bands(n), opts)
    }
}

/// Composite Simpson integral of `f` over [a, b] with `n` (even) intervals.
pub fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let n = n.max(2) & !1;
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// Draw an angle from the cos-2s density by rejection (the envelope is uniform, since
/// cos^{2s}(Δ/2) ≤ 1).
fn sample_spread(rng: &mut SmallRng, s: f64) -> f64 {
    for _ in 0..10_000 {
        let d = rng.random_range(-PI..PI);
        if rng.random::<f64>() <= (0.5 * d).cos().abs().powf(2.0 * s) {
            return d;
        }
    }
    0.0
}

/// Turn bands into waves (one per band with energy), then scale to keep Σ kA ≤ the limit.
pub fn sea_from_bands(bands: &[Band], opts: &SpectralOptions) -> SpectralSea {
    let mut rng = SmallRng::seed_from_u64(opts.seed);
    let mut waves = Vec::new();
    let mut m0 = 0.0;
    for b in bands {
        // Draw every random number even for empty bands, so a band's waves do not depend on
        // whether an earlier band was empty.
        let f = rng.random_range(b.f_lo..=b.f_hi);
        let spread = sample_spread(&mut rng, b.spreading);
        let phase = rng.random_range(0.0..TAU);
        if b.energy.is_nan() || b.energy <= 0.0 {
            continue;
        }
        m0 += b.energy;
        let k = wave_number(f, opts.gravity, opts.depth);
        let a = (2.0 * b.energy).sqrt();
        let (sn, cs) = spread.sin_cos();
        let [dx, dz] = b.direction;
        waves.push(Wave {
            direction: [dx * cs - dz * sn, dx * sn + dz * cs],
            steepness: k * a,
            wavelength: TAU / k,
            phase,
        });
    }
    let unscaled: f64 = waves.iter().map(|w| w.steepness).sum();
    let scale = if unscaled > opts.max_total_steepness {
        opts.max_total_steepness / unscaled
    } else {
        1.0
    };
    for w in &mut waves {
        w.steepness *= scale;
    }
    let sea = WaveSet {
        gravity: opts.gravity,
        depth: opts.depth,
        waves,
    };
    let sum_a2: f64 = sea.waves.iter().map(|w| w.amplitude().powi(2)).sum();
    SpectralSea {
        amplitude_scale: scale,
        unscaled_total_steepness: unscaled,
        hs_spectrum: 4.0 * m0.sqrt(),
        hs_waves: 4.0 * (0.5 * sum_a2).sqrt(),
        sea,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pierson_moskowitz_integrates_to_hs_squared_over_16_and_peaks_at_fp() {
        for &(hs, tp) in &[(1.0, 5.0), (2.5, 8.0), (6.0, 14.0)] {
            let fp = 1.0 / tp;
            let m0 = simpson(
                |f| pierson_moskowitz(f, hs, tp),
                0.05 * fp,
                60.0 * fp,
                200_000,
            );
            assert!((m0 / (hs * hs / 16.0) - 1.0).abs() < 1e-5, "{m0}");
            // dS/df = 0 exactly at fp: the neighbours are lower.
            let p = pierson_moskowitz(fp, hs, tp);
            assert!(p > pierson_moskowitz(fp * 0.999, hs, tp));
            assert!(p > pierson_moskowitz(fp * 1.001, hs, tp));
            // Closed form at the peak: (5/16) Hs² Tp e^{-5/4}.
            assert!((p - 5.0 / 16.0 * hs * hs * tp * (-1.25f64).exp()).abs() < 1e-12 * p);
        }
    }

    #[test]
    fn jonswap_against_dnv_rp_c205() {
        // Published normalisation for the mean JONSWAP γ = 3.3: A_γ = 1 − 0.287 ln 3.3 = 0.6573.
        assert!((jonswap_normalisation(3.3) - 0.6573).abs() < 5e-5);
        let (hs, tp) = (3.0, 9.0);
        let fp = 1.0 / tp;
        // Peak enhancement: S_J(fp) / S_PM(fp) = γ A_γ.
        let ratio = jonswap(fp, hs, tp, 3.3) / pierson_moskowitz(fp, hs, tp);
        assert!((ratio - 3.3 * 0.657_34).abs() < 1e-4, "{ratio}");
        // γ = 1 is Pierson–Moskowitz.
        assert_eq!(jonswap(0.13, hs, tp, 1.0), pierson_moskowitz(0.13, hs, tp));
        // DNV: with A_γ the variance stays Hs²/16 to within a few per cent over 1 ≤ γ ≤ 7.
        for &g in &[1.0, 2.0, 3.3, 5.0, 7.0] {
            let m0 = simpson(|f| jonswap(f, hs, tp, g), 0.05 * fp, 60.0 * fp, 20_000);
            let rel = m0 / (hs * hs / 16.0) - 1.0;
            assert!(rel.abs() < 0.03, "γ = {g}: {rel}");
        }
        // The peak stays at fp (σ is narrow around it).
        let grid: Vec<f64> = (1..4000).map(|i| fp * (0.5 + i as f64 * 0.0005)).collect();
        let best = grid
            .iter()
            .copied()
            .max_by(|a, b| jonswap(*a, hs, tp, 3.3).total_cmp(&jonswap(*b, hs, tp, 3.3)))
            .unwrap();
        assert!((best / fp - 1.0).abs() < 0.001, "{best}");
    }

    #[test]
    fn cos2s_is_normalised_and_its_r1_is_s_over_s_plus_1() {
        // s = 1 closed form: (1 + cos Δ) / (2π).
        for &d in &[-3.0, -1.0, 0.0, 0.5, 2.9] {
            assert!((cos2s(d, 1.0) - (1.0 + f64::cos(d)) / TAU).abs() < 1e-12);
        }
        for &s in &[0.5, 1.0, 2.0, 7.5, 30.0] {
            let int = simpson(|d| cos2s(d, s), -PI, PI, 20_000);
            assert!((int - 1.0).abs() < 1e-9, "s = {s}: {int}");
            let r1 = simpson(|d| cos2s(d, s) * d.cos(), -PI, PI, 20_000);
            assert!((r1 - s / (s + 1.0)).abs() < 1e-9, "s = {s}: {r1}");
            assert!((spreading_from_r1(s / (s + 1.0)) - s).abs() < 1e-9);
        }
    }

    #[test]
    fn finite_depth_wave_number_solves_the_dispersion_relation() {
        for &(f, h) in &[(0.1, 5.0), (0.05, 20.0), (0.3, 2.0), (0.2, 500.0)] {
            let k = wave_number(f, 9.81, Some(h));
            let w2 = (TAU * f).powi(2);
            assert!((9.81 * k * (k * h).tanh() / w2 - 1.0).abs() < 1e-12);
        }
        assert_eq!(wave_number(0.1, 9.81, None), (TAU * 0.1f64).powi(2) / 9.81);
    }

    #[test]
    fn generated_sea_keeps_hs_and_total_steepness() {
        let state = SeaState {
            hs: 2.0,
            tp: 8.0,
            gamma: 3.3,
            direction: [1.0, 1.0],
            spreading: 10.0,
        };
        let g = state.to_sea(32, &SpectralOptions::default());
        assert_eq!(g.sea.waves.len(), 32);
        // Bands from 0.6 fp to 4 fp hold m0 to within 1.5 %: Hs within 0.75 %.
        assert!(
            (g.hs_spectrum / 2.0 - 1.0).abs() < 0.0075,
            "{}",
            g.hs_spectrum
        );
        assert!(g.sea.total_steepness() <= 0.8 + 1e-12);
        assert!(g.amplitude_scale <= 1.0);
        assert!((g.hs_waves - g.hs_spectrum * g.amplitude_scale).abs() < 1e-9);
        // Valid as a sea file would be, and reproducible from the seed.
        assert_eq!(g, state.to_sea(32, &SpectralOptions::default()));
        let other = state.to_sea(
            32,
            &SpectralOptions {
                seed: 2,
                ..Default::default()
            },
        );
        assert_ne!(g.sea, other.sea);
        // A steep short sea gets scaled, and says so.
        let steep = SeaState {
            hs: 4.0,
            tp: 4.0,
            ..state
        }
        .to_sea(32, &SpectralOptions::default());
        assert!(steep.unscaled_total_steepness > 0.8);
        assert!((steep.amplitude_scale - 0.8 / steep.unscaled_total_steepness).abs() < 1e-12);
        assert!((steep.sea.total_steepness() - 0.8).abs() < 1e-9);
        // Mean direction: energy-weighted travel direction is near (1, 1)/√2.
        let (mut sx, mut sz) = (0.0, 0.0);
        for w in &g.sea.waves {
            sx += w.amplitude().powi(2) * w.direction[0];
            sz += w.amplitude().powi(2) * w.direction[1];
        }
        let ang = sz.atan2(sx).to_degrees();
        assert!((ang - 45.0).abs() < 20.0, "{ang}");
    }

    #[test]
    fn compass_from_direction_to_travel_vector() {
        // Waves from the north travel south (+z); from the east they travel west (−x).
        let s = travel_direction_from_compass(0.0);
        assert!(s[0].abs() < 1e-12 && (s[1] - 1.0).abs() < 1e-12);
        let w = travel_direction_from_compass(90.0);
        assert!((w[0] + 1.0).abs() < 1e-12 && w[1].abs() < 1e-12);
    }
}
