//! The Kelvin-correct wake: ring-wave packets from sources emitted by distance sailed.
//!
//! Linear deep-water theory (ω² = g k) of a moving pressure patch p(x, t) = F/(πR²)
//! exp(−|x − X(t)|²/R²) (total force F, the boat's weight m g; radius R). Its response is the
//! integral over the path of the response to a pressure step switched on at the point where
//! the boat is: integrating the impulse (Cauchy–Poisson) response by parts in time,
//!
//! η(x, t) = static part − ∫ ∇ₓH(x − X(τ), t − τ) · dX(τ),
//!
//! with H(r, s) the step response. A path element dX weighs the integral, so a stationary boat
//! makes no wave at all (only a static dip, which is not a wake). The wave part of H is
//! H = F/(2πρg) ∫ k J₀(kr) e^{−k²R²/4} cos(ω s) dk, and by stationary phase in k
//! (k* = g s²/(4r²), the waves whose group speed ½√(g/k) carries them r in s) it is
//! H ≈ F/(√2 π ρ g) (k*/r) e^{−k*²R²/4} cos Φ with Φ = g s²/(4r) = k* r. Its gradient, keeping
//! the derivative of the amplitude too (it removes a 1/Φ bias near the boat), is
//! ∇H = r̂ F/(√2 π ρ g) (k*²/r) e^{−k*²R²/4} [sin Φ + (k*²R² − 3)/Φ · cos Φ].
//!
//! So a source j (segment ΔXⱼ of the path, midpoint Xⱼ, emitted at τⱼ, age s = t − τⱼ) adds
//!
//! ηⱼ = −F/(√2 π ρ g) · w(s) · (k*²/r) e^{−k*²R²/4} [sin Φ + (k*²R² − 3)/Φ cos Φ] (r̂·ΔXⱼ),
//!
//! where w(s) fades the source out over the last 20 % of the maximum age. Each ring's radius
//! grows with the group speed (k* above) and its phase with the phase speed: k* r − ω* s =
//! −g s²/(4r) = −Φ, the deep-water dispersion phase of the Cauchy–Poisson ring. Summed along a straight track at speed U this
//! is the Kelvin wake of the pressure patch (Havelock 1908; Lamb, *Hydrodynamics* §256): its
//! envelope half-angle is arcsin(1/3) at every speed, its transverse waves have wavelength
//! 2πU²/g, and on the track, a distance D behind the boat, their amplitude is
//!
//! A_T = F k₀² /(π ρ g) · e^{−k₀²R²/4} · √(2π/(k₀ D)),   k₀ = g/U²,
//!
//! the speed law of the wake: it rises like U⁻³ from nothing at low Froude number
//! (e^{−k₀²R²/4} → 0, the boat is long against its waves) and falls like U⁻³ past
//! k₀R ≈ 2. `reference.rs` evaluates the same physics independently (the Havelock integral
//! over wave angles), and the tests compare them.
//!
//! Emission: a new source whenever the distance sailed since the last one reaches `spacing`,
//! or `max_interval` seconds pass (a slow boat's long fast waves must still be
//! phase-resolved; a boat that did not move emits nothing). Precisely, the sources sit at the
//! integer crossings of σ(τ) = ∫ max(|Ẋ|/spacing, 1/max_interval) dτ: a closed form of the track,
//! so the sources at time t depend only on the track up to t, and scrubbing equals playing.
//! The source spacing must resolve the shortest waves the patch makes
//! (k ≲ 5/R, phase step k·spacing < π): the default is R/2; `regatta bench` measures it.

use std::f64::consts::{PI, SQRT_2};

use super::track::{TrackSample, WakeError, check_track};

/// Density of sea water, kg/m³.
pub const SEA_WATER_DENSITY: f64 = 1025.0;

/// Exponent k²R²/4 beyond which a source's term is dropped (e^{−40} ≈ 4·10⁻¹⁸: nothing).
pub(crate) const GAUSS_CUTOFF: f64 = 40.0;

/// How a boat makes its wake. Defaults: a small keelboat (6 m, 1 t).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WakeParams {
    /// m/s².
    pub gravity: f64,
    /// Radius R of the Gaussian pressure patch standing for the hull, m (about a quarter of the
    /// waterline length).
    pub hull_radius: f64,
    /// Total pressure force F = m g of the hull on the water, N.
    pub force: f64,
    /// Distance sailed between sources, m.
    pub spacing: f64,
    /// Longest time between sources of a moving boat, s.
    pub max_interval: f64,
    /// Sources older than this are gone, s (faded over the last 20 %).
    pub max_age: f64,
    /// A track segment faster than this is a jump (GPS glitch, teleport): it makes no wake, m/s.
    pub jump_speed: f64,
    /// Width of the foam strip at the stern, m; it widens by `foam_spread` m/s with age.
    pub foam_width: f64,
    pub foam_spread: f64,
    /// e-folding lifetime of the foam strip, s.
    pub foam_lifetime: f64,
    /// Speed at which the foam strip is fully white, m/s (it scales with (U/this)² below).
    pub foam_speed: f64,
}

impl Default for WakeParams {
    fn default() -> Self {
        let hull_radius = 1.5;
        WakeParams {
            gravity: crate::STANDARD_GRAVITY,
            hull_radius,
            force: 1000.0 * crate::STANDARD_GRAVITY,
            spacing: 0.5 * hull_radius,
            max_interval: 0.5,
            max_age: 60.0,
            jump_speed: 40.0,
            foam_width: 1.0,
            foam_spread: 0.05,
            foam_lifetime: 12.0,
            foam_speed: 4.0,
        }
    }
}

impl WakeParams {
    /// Refuse parameters that would make no sense (or loop forever).
    pub fn check(&self) -> Result<(), WakeError> {
        let positive = [
            ("gravity", self.gravity),
            ("hull_radius", self.hull_radius),
            ("spacing", self.spacing),
            ("max_interval", self.max_interval),
            ("max_age", self.max_age),
            ("jump_speed", self.jump_speed),
            ("foam_width", self.foam_width),
            ("foam_lifetime", self.foam_lifetime),
            ("foam_speed", self.foam_speed),
        ];
        for (field, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(WakeError::Param {
                    field,
                    reason: "must be a positive finite number",
                });
            }
        }
        for (field, v) in [("force", self.force), ("foam_spread", self.foam_spread)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(WakeError::Param {
                    field,
                    reason: "must be a finite number ≥ 0",
                });
            }
        }
        Ok(())
    }

    /// F/(√2 π ρ g): the constant in front of every source term, m³ (with k*²/r · |ΔX|).
    pub fn source_constant(&self) -> f64 {
        self.force / (SQRT_2 * PI * SEA_WATER_DENSITY * self.gravity)
    }

    /// The age fade w(s): 1 until 80 % of `max_age`, a smoothstep to 0 at `max_age`, 0 beyond
    /// and for s ≤ 0.
    pub fn age_fade(&self, age: f64) -> f64 {
        if !(age > 0.0 && age < self.max_age) {
            return 0.0;
        }
        let q = age / self.max_age;
        if q <= 0.8 {
            1.0
        } else {
            let z = (1.0 - q) / 0.2;
            z * z * (3.0 - 2.0 * z)
        }
    }

    /// The closed-form centreline amplitude A_T of the transverse waves of a straight, steady
    /// wake at speed `u` a distance `d` behind the boat, m (see the module docs).
    pub fn transverse_amplitude(&self, u: f64, d: f64) -> f64 {
        let k0 = self.gravity / (u * u);
        self.force * k0 * k0 / (PI * SEA_WATER_DENSITY * self.gravity)
            * (-(k0 * self.hull_radius).powi(2) / 4.0).exp()
            * (2.0 * PI / (k0 * d)).sqrt()
    }
}

/// One wake source: a path segment of a boat.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KelvinSource {
    /// Emission time τ (the segment's middle), s.
    pub t: f64,
    /// Time at which the segment ends: the source exists from then on, s.
    pub t_end: f64,
    /// Segment midpoint (x, z), m.
    pub pos: [f64; 2],
    /// Segment vector ΔX (x, z), m.
    pub dx: [f64; 2],
    /// Mean speed over the segment, m/s.
    pub speed: f64,
}

/// A segment that would emit more sources than this (a huge gap in a track) is a jump.
const MAX_SOURCES_PER_SEGMENT: f64 = 100_000.0;

/// Emit the sources of one checked track (see the module docs). Sources are in time order.
pub(crate) fn emit_sources(samples: &[TrackSample], p: &WakeParams) -> Vec<KelvinSource> {
    let mut out = Vec::new();
    let mut sigma = 0.0f64;
    // Start of the current segment of emission: (time, position).
    let mut prev: Option<(f64, [f64; 2])> = None;
    for w in samples.windows(2) {
        let (a, b) = (w[0], w[1]);
        let dt = b.t - a.t;
        let d = [b.x - a.x, b.z - a.z];
        let dl = d[0].hypot(d[1]);
        // σ grows by distance or by time, whichever is faster on this segment.
        let rate = (dl / p.spacing).max(dt / p.max_interval);
        if dl == 0.0 {
            // The boat stands still: no source, and the next one starts here.
            sigma += rate.min(MAX_SOURCES_PER_SEGMENT);
            prev = Some((b.t, [b.x, b.z]));
            continue;
        }
        if dt <= 0.0 || dl > p.jump_speed * dt || rate > MAX_SOURCES_PER_SEGMENT {
            // A jump: no wake along it; emission restarts where the boat lands.
            prev = Some((b.t, [b.x, b.z]));
            continue;
        }
        let (mut pt, mut px) = prev.unwrap_or((a.t, [a.x, a.z]));
        let s1 = sigma + rate;
        let mut m = sigma.floor() + 1.0;
        while m <= s1 {
            let f = (m - sigma) / rate;
            let tau = a.t + f * dt;
            let x = [a.x + f * d[0], a.z + f * d[1]];
            let seg = [x[0] - px[0], x[1] - px[1]];
            let len = seg[0].hypot(seg[1]);
            // A boat that did not move over the segment makes no source (no wave at all).
            if len > 0.0 && tau > pt {
                out.push(KelvinSource {
                    t: 0.5 * (pt + tau),
                    t_end: tau,
                    pos: [0.5 * (px[0] + x[0]), 0.5 * (px[1] + x[1])],
                    dx: seg,
                    speed: len / (tau - pt),
                });
            }
            (pt, px) = (tau, x);
            m += 1.0;
        }
        prev = Some((pt, px));
        sigma = s1;
    }
    out
}

/// The height that one source adds at `p` at race time `t`, m (module docs).
pub fn source_height(src: &KelvinSource, p: [f64; 2], t: f64, prm: &WakeParams) -> f64 {
    if t < src.t_end {
        return 0.0;
    }
    let age = t - src.t;
    let fade = prm.age_fade(age);
    if fade == 0.0 {
        return 0.0;
    }
    let d = [p[0] - src.pos[0], p[1] - src.pos[1]];
    let r2 = d[0] * d[0] + d[1] * d[1];
    let q = prm.gravity * age * age / 4.0;
    let k = q / r2;
    let gauss = k * k * prm.hull_radius * prm.hull_radius / 4.0;
    // Also catches r = 0 (k = ∞): the patch has no waves that short.
    if gauss.is_nan() || gauss > GAUSS_CUTOFF {
        return 0.0;
    }
    let r = r2.sqrt();
    let phi = q / r;
    let amp = prm.source_constant() * fade * k * k / r * (-gauss).exp();
    let bracket = phi.sin() + (4.0 * gauss - 3.0) / phi * phi.cos();
    -amp * bracket * (d[0] * src.dx[0] + d[1] * src.dx[1]) / r
}

/// Foam density that one source adds at `p` (before 1 − e^{−Σ}): a Gaussian strip of width
/// `foam_width + foam_spread·age` along the segment, fading with `foam_lifetime` and scaled by
/// min(1, (U/foam_speed)²); normalised so that a straight track at `foam_speed` gives a
/// density of 1 on its line while fresh.
pub fn source_foam(src: &KelvinSource, p: [f64; 2], t: f64, prm: &WakeParams) -> f64 {
    let (w, s) = match foam_shape(src, t, prm) {
        Some(v) => v,
        None => return 0.0,
    };
    let d = [p[0] - src.pos[0], p[1] - src.pos[1]];
    s * (-(d[0] * d[0] + d[1] * d[1]) / (w * w)).exp()
}

/// (width m, strength) of a source's foam Gaussian at time t; `None` when it has none.
pub(crate) fn foam_shape(src: &KelvinSource, t: f64, prm: &WakeParams) -> Option<(f64, f64)> {
    if t < src.t_end {
        return None;
    }
    let age = t - src.t;
    let fade = prm.age_fade(age);
    if fade == 0.0 {
        return None;
    }
    let w = prm.foam_width + prm.foam_spread * age;
    let len = src.dx[0].hypot(src.dx[1]);
    let speed = (src.speed / prm.foam_speed).powi(2).min(1.0);
    let s = fade * speed * len / (PI.sqrt() * w) * (-age / prm.foam_lifetime).exp();
    Some((w, s))
}

/// The wakes of a fleet: each boat's sources, precomputed once from its track.
#[derive(Debug, Clone, PartialEq)]
pub struct Wake {
    pub params: WakeParams,
    /// Per boat, sources in time order.
    pub boats: Vec<Vec<KelvinSource>>,
    /// The checked tracks the sources came from (to re-emit them for other parameters, e.g.
    /// [`Wake::froude_scaled`]).
    pub(crate) tracks: Vec<Vec<TrackSample>>,
}

impl Wake {
    /// Check the tracks and emit their sources. A track with fewer than two samples makes no
    /// wake. Errors name the boat (index) and the sample, or the parameter.
    pub fn new(tracks: &[&[TrackSample]], params: WakeParams) -> Result<Wake, WakeError> {
        params.check()?;
        let mut boats = Vec::with_capacity(tracks.len());
        for (i, tr) in tracks.iter().enumerate() {
            check_track(i, tr)?;
            boats.push(emit_sources(tr, &params));
        }
        Ok(Wake {
            params,
            boats,
            tracks: tracks.iter().map(|t| t.to_vec()).collect(),
        })
    }

    /// The sources alive at time t (emitted by t and younger than max_age), per boat slice.
    pub fn active(&self, t: f64) -> impl Iterator<Item = &KelvinSource> + '_ {
        let max_age = self.params.max_age;
        self.boats.iter().flat_map(move |b| {
            let lo = b.partition_point(|s| s.t <= t - max_age);
            let hi = b.partition_point(|s| s.t_end <= t);
            b[lo..hi.max(lo)].iter()
        })
    }

    /// Wake height at world point `p` (x, z) and race time `t`, m, f64.
    pub fn height(&self, p: [f64; 2], t: f64) -> f64 {
        self.active(t)
            .map(|s| source_height(s, p, t, &self.params))
            .sum()
    }

    /// Wake foam strength at `p`, in [0, 1].
    pub fn foam(&self, p: [f64; 2], t: f64) -> f64 {
        let sum: f64 = self
            .active(t)
            .map(|s| source_foam(s, p, t, &self.params))
            .sum();
        (1.0 - (-sum).exp()).clamp(0.0, 1.0)
    }

    /// Horizontal gradient (∂η/∂x, ∂η/∂z) by central differences of `height` with step `h` m
    /// (for normals: the wake's shortest waves are ≳ R long, so h = R/20 resolves them).
    pub fn gradient(&self, p: [f64; 2], t: f64, h: f64) -> [f64; 2] {
        let f = |q: [f64; 2]| self.height(q, t);
        [
            (f([p[0] + h, p[1]]) - f([p[0] - h, p[1]])) / (2.0 * h),
            (f([p[0], p[1] + h]) - f([p[0], p[1] - h])) / (2.0 * h),
        ]
    }

    /// Total number of sources of all boats.
    pub fn source_count(&self) -> usize {
        self.boats.iter().map(Vec::len).sum()
    }
}
