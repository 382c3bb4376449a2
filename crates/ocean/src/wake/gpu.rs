//! The per-frame wake sources for a GPU, their culling, and the f32 mirror of
//! `shaders/ocean/wake.wgsl` (whose kernel reads each source's constants, `kernel.rs`).
//!
//! f32 safety: a source's age s is reduced on the CPU to q = g s²/4 (s ≤ max_age, never the
//! race time) and positions are relative to a local origin near the camera. The shader then
//! forms k* = q/r², Φ = q/r from local quantities only.
//!
//! Culling: for r ≥ r_m = √(qR/2) (where k* ≤ 2/R, so |k*²R² − 3| ≤ 3 and e^{−k*²R²/4} ≤ 1)
//! a source's term is at most B(r) = C (q²/r⁵ + 3q/r⁴), C = F/(√2πρg)·w(s)·|ΔX|, and B falls
//! with r. So beyond r_c = max(r_m, (2Cq²/ε)^{1/5}, (6Cq/ε)^{1/4}) the term is below ε. A source
//! is sent when the view rectangle comes within r_c of it, and the shader skips it at points
//! farther than r_c. At every point in the view the height then errs by at most
//! Σ_culled B(distance to the view) + ε × sent sources: `GpuWakeFrame::cull_bound`.

use super::kelvin::{GAUSS_CUTOFF, KelvinSource, Wake, foam_shape};
pub use super::kernel::{BAND_END, BAND_START, MIN_R2, SPACING_MIN, band_edges};
use super::kernel::{WakeKernelSource, band_fade_at};
use crate::turn_table::{TURN_TABLE_TEXELS, turn_table_error};

/// One wake source of a frame as the CPU culls, bins and bounds it (48 bytes): its physical
/// quantities in f32. The GPU reads its [`WakeKernelSource`] (the constants the kernel needs,
/// formed from these fields once per frame: [`GpuWakeFrame::bytes`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuWakeSource {
    /// Segment midpoint − local origin (x, z), m.
    pub pos: [f32; 2],
    /// Segment vector ΔX (x, z), m.
    pub dx: [f32; 2],
    /// q = g s²/4 for the source's age s, m.
    pub q: f32,
    /// F/(√2πρg) · w(s), m³.
    pub strength: f32,
    /// R²/4, m².
    pub gauss: f32,
    /// r_c²: the term is below ε beyond r_c, m².
    pub cull_r2: f32,
    /// Squared width of the foam Gaussian, m².
    pub foam_w2: f32,
    /// Foam density at the segment's centre.
    pub foam: f32,
    pub _pad: [f32; 2],
}

/// The world rectangle (x, z) whose points the renderer will evaluate, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WakeView {
    pub min: [f64; 2],
    pub max: [f64; 2],
}

impl WakeView {
    /// A square of half-size `radius` around `centre`.
    pub fn around(centre: [f64; 2], radius: f64) -> WakeView {
        WakeView {
            min: [centre[0] - radius, centre[1] - radius],
            max: [centre[0] + radius, centre[1] + radius],
        }
    }
    /// Squared distance from `p` to the rectangle (0 inside).
    pub fn distance2(&self, p: [f64; 2]) -> f64 {
        let dx = (self.min[0] - p[0]).max(0.0).max(p[0] - self.max[0]);
        let dz = (self.min[1] - p[1]).max(0.0).max(p[1] - self.max[1]);
        dx * dx + dz * dz
    }
}

/// What the renderer uploads for one frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GpuWakeFrame {
    pub sources: Vec<GpuWakeSource>,
    /// Alive sources left out because they cannot reach the view.
    pub culled: usize,
    /// Bound of the culling error of the height at any point in the view, m (before f32):
    /// Σ over culled sources of B(their distance to the view) + ε × sent sources.
    pub cull_bound: f64,
}

/// B(r) = c (q²/r⁵ + 3q/r⁴): bound of a source's term at distance r ≥ r_m (module docs).
pub(crate) fn term_bound(c: f64, q: f64, r: f64) -> f64 {
    c * (q * q / r.powi(5) + 3.0 * q / r.powi(4))
}

impl GpuWakeFrame {
    /// The sources as the bytes of a storage buffer of `WakeSource` (shaders/ocean/wake.wgsl):
    /// each one's [`WakeKernelSource`], in order.
    pub fn bytes(&self) -> Vec<u8> {
        let kernel: Vec<WakeKernelSource> =
            self.sources.iter().map(WakeKernelSource::from).collect();
        bytemuck::cast_slice(&kernel).to_vec()
    }
}

/// r_c of a source (module docs); `c` = F/(√2πρg)·w(s)·|ΔX|.
pub(crate) fn cull_radius(c: f64, q: f64, hull_radius: f64, epsilon: f64) -> f64 {
    let r_m = (q * hull_radius / 2.0).sqrt();
    let r5 = (2.0 * c * q * q / epsilon).powf(0.2);
    let r4 = (6.0 * c * q / epsilon).powf(0.25);
    r_m.max(r5).max(r4)
}

impl Wake {
    /// The sources alive at race time `t` that can reach `view`, relative to `origin`, with
    /// ε = `epsilon` metres per left-out source (see the module docs).
    pub fn gpu_sources(
        &self,
        t: f64,
        origin: [f64; 2],
        view: &WakeView,
        epsilon: f64,
    ) -> GpuWakeFrame {
        let prm = &self.params;
        let mut frame = GpuWakeFrame::default();
        let mut bound = 0.0;
        for s in self.active(t) {
            let age = t - s.t;
            let fade = prm.age_fade(age);
            if fade == 0.0 {
                continue;
            }
            let strength = prm.source_constant() * fade;
            let q = prm.gravity * age * age / 4.0;
            let c = strength * s.dx[0].hypot(s.dx[1]);
            let rc = cull_radius(c, q, prm.hull_radius, epsilon);
            let d2 = view.distance2(s.pos);
            if d2 > rc * rc {
                frame.culled += 1;
                bound += term_bound(c, q, d2.sqrt());
                continue;
            }
            bound += epsilon;
            let (fw, fs) = foam_shape(s, t, prm).unwrap_or((1.0, 0.0));
            frame.sources.push(GpuWakeSource {
                pos: [(s.pos[0] - origin[0]) as f32, (s.pos[1] - origin[1]) as f32],
                dx: [s.dx[0] as f32, s.dx[1] as f32],
                q: q as f32,
                strength: strength as f32,
                gauss: (prm.hull_radius * prm.hull_radius / 4.0) as f32,
                cull_r2: (rc * rc) as f32,
                foam_w2: (fw * fw) as f32,
                foam: fs as f32,
                _pad: [0.0; 2],
            });
        }
        frame.cull_bound = bound;
        frame
    }
}

/// Bound of a source's height term anywhere, m: what leaving it out of a frame can cost.
///
/// With u = r_m/r (r_m² = qR/2, so k* = 2u²/R and G = k*²R²/4 = u⁴), the term of
/// [`source_height_f32`] is at most C·k*²/r·e^{−G}·(1 + |4G − 3|/Φ) (|sin|, |cos| ≤ 1 and
/// |d·ΔX|/r ≤ |ΔX|; C = strength·|ΔX|), which is
/// 4C/(R² r_m)·[u⁵e^{−u⁴} + (r_m/q)·u⁴e^{−u⁴}|4u⁴ − 3|]. Over all u > 0 the first bracket
/// term peaks at u⁴ = 5/4 and the second at u⁴ = (11 + √73)/8, hence the bound
/// 4C/(R² r_m)·[M₁ + (r_m/q) M₂]. Holds for the f64 term; the f32 rounding is apart.
pub fn source_peak_bound(s: &GpuWakeSource) -> f64 {
    let c = f64::from(s.strength) * f64::from(s.dx[0]).hypot(f64::from(s.dx[1]));
    let q = f64::from(s.q);
    // gauss = R²/4.
    let r_sq = 4.0 * f64::from(s.gauss);
    let r_m = (q * r_sq.sqrt() / 2.0).sqrt();
    if !(c > 0.0 && q > 0.0 && r_m > 0.0) {
        return 0.0;
    }
    let m1 = 1.25f64.powf(1.25) * (-1.25f64).exp();
    let v = (11.0 + 73f64.sqrt()) / 8.0;
    let m2 = v * (4.0 * v - 3.0) * (-v).exp();
    4.0 * c / (r_sq * r_m) * (m1 + r_m / q * m2)
}

/// One source's height term at local point `p`, f32, exactly as `wake_source_height` in WGSL
/// (which reads the source's [`WakeKernelSource`]; a point beyond the cull radius is nothing
/// there too, so the constants are formed only within it).
pub fn source_height_f32(s: &GpuWakeSource, p: [f32; 2]) -> f32 {
    let d = [p[0] - s.pos[0], p[1] - s.pos[1]];
    let r2 = d[0] * d[0] + d[1] * d[1];
    if r2 > s.cull_r2 {
        return 0.0;
    }
    WakeKernelSource::from(s).height(d, r2)
}

/// The band limit of a field sampled every `spacing` metres: a term of local wavenumber k is
/// faded out from k·spacing = [`BAND_START`] to [`BAND_END`] (1 to 2: the clip-map's own rule
/// for the sea's waves, which a level drops from k·cell = 2 on, a wave shorter than π cells
/// erring by half its amplitude or more when interpolated; the fade spans the octave below),
/// f32 exactly as the WGSL kernel forms it: `smoothstep` between `wake_band_edges(spacing)`
/// at −k ([`band_edges`]). `spacing` = 0: 1 (no limit).
pub fn band_fade_f32(k: f32, spacing: f32) -> f32 {
    band_fade_at(-k, band_edges(spacing))
}

/// Bound of |[`band_fade_f32`] − [`band_fade`]| for the same f32 k and spacing, IEEE f32
/// (u = 2⁻²⁴): the edges lo = fl(−2/s) (relative error ε ≤ u) and hi = lo/2 exactly, so
/// hi − lo = −hi is exact; smoothstep's t = fl(fl(−k − lo)/(hi − lo)) then errs by
/// (2 − t)|ε| + 2u·t ≤ 4u on [0, 1] (the clamp is exact and 1-Lipschitz), and
/// t²(3 − 2t), of slope at most 1.5, adds three roundings: 1.5·4u + 3u = 9u. (On a GPU,
/// WGSL's divisions are good to 2.5 ULP, so the edges err by 5u each and hi − lo is no longer
/// exact: t errs by 10u + 22u·t ≤ 32u and the fade by 1.5·32u + 3u = 51u.)
pub const BAND_FADE_F32_ERROR: f64 = 9.0 / 16_777_216.0;

/// [`band_fade_f32`] in f64: the reference the f32 mirror and the GPU are held to.
pub fn band_fade(k: f64, spacing: f64) -> f64 {
    let (a, b) = (f64::from(BAND_START), f64::from(BAND_END));
    let t = ((k * spacing - a) / (b - a)).clamp(0.0, 1.0);
    1.0 - t * t * (3.0 - 2.0 * t)
}

/// The squared radius (m²) inside which a source adds nothing at points sampled every
/// `spacing` metres: its Gaussian cut-off (k²R²/4 > 40, k = q/r², so r² < q·√(R²/4/40)) or
/// the band limit (k·spacing ≥ 2, so r² ≤ q·spacing/2), whichever is larger. Slightly
/// under the exact value (1 part in 10⁴), so that f32 rounding of a point's r² near it never
/// drops a source the shader would still add (both fades are e^{−40} or 0 there anyway).
pub fn inner_radius2(s: &GpuWakeSource, spacing: f32) -> f32 {
    let q = f64::from(s.q.max(0.0));
    let hole = gauss_hole_r2(s);
    let band = q * f64::from(spacing.max(0.0)) / f64::from(BAND_END);
    (hole.max(band) * (1.0 - 1e-4)) as f32
}

/// The foam density below which a source's foam strip is left out of a point's sum: the
/// foam coverage 1 − e^{−Σ} is 1-Lipschitz in the density, so each left-out source errs by
/// less than this.
pub const FOAM_EPSILON: f32 = 1e-4;

/// The squared distance (m²) beyond which a source's foam density `foam · e^{−r²/w²}` is
/// below [`FOAM_EPSILON`] (0 for a source with less foam than that at its centre).
pub fn foam_radius2(s: &GpuWakeSource) -> f32 {
    if !(s.foam > FOAM_EPSILON && s.foam_w2 > 0.0) {
        return 0.0;
    }
    (f64::from(s.foam_w2) * (f64::from(s.foam) / f64::from(FOAM_EPSILON)).ln()) as f32
}

/// One source's height term and its gradient at local point `p`, (w, ∂w/∂x, ∂w/∂z) in m and
/// m/m, f32, exactly as `wake_source_height_grad` in WGSL (the closed-form derivative of
/// [`source_height_f32`]).
pub fn source_height_grad_f32(s: &GpuWakeSource, p: [f32; 2]) -> [f32; 3] {
    source_height_grad_sampled_f32(s, p, 0.0)
}

/// [`source_height_grad_f32`] band limited for points sampled every `spacing` metres
/// ([`band_fade_f32`]), exactly as `wake_source_height_grad_at` in WGSL (on the source's
/// [`WakeKernelSource`], formed only within the cull radius, beyond which both give nothing).
pub fn source_height_grad_sampled_f32(s: &GpuWakeSource, p: [f32; 2], spacing: f32) -> [f32; 3] {
    let d = [p[0] - s.pos[0], p[1] - s.pos[1]];
    let r2 = d[0] * d[0] + d[1] * d[1];
    if r2 > s.cull_r2 {
        return [0.0; 3];
    }
    WakeKernelSource::from(s).height_grad(d, r2, spacing)
}

/// Wake height and gradient at local point `p`, f32: the mirror of `wake_at` in WGSL.
pub fn wake_height_grad_f32(sources: &[GpuWakeSource], p: [f32; 2]) -> [f32; 3] {
    wake_height_grad_sampled_f32(sources, p, 0.0)
}

/// [`wake_height_grad_f32`] band limited for points sampled every `spacing` metres.
pub fn wake_height_grad_sampled_f32(
    sources: &[GpuWakeSource],
    p: [f32; 2],
    spacing: f32,
) -> [f32; 3] {
    sources.iter().fold([0.0; 3], |acc, s| {
        let g = source_height_grad_sampled_f32(s, p, spacing);
        [acc[0] + g[0], acc[1] + g[1], acc[2] + g[2]]
    })
}

/// Wake height at local point `p`, m, f32: the mirror of `wake_height` in WGSL.
pub fn wake_height_f32(sources: &[GpuWakeSource], p: [f32; 2]) -> f32 {
    sources.iter().map(|s| source_height_f32(s, p)).sum()
}

/// Wake foam at local point `p` in [0, 1], f32: the mirror of `wake_foam` in WGSL.
pub fn wake_foam_f32(sources: &[GpuWakeSource], p: [f32; 2]) -> f32 {
    let mut sum = 0.0f32;
    for s in sources {
        let d = [p[0] - s.pos[0], p[1] - s.pos[1]];
        sum += foam_density_f32(s, d[0] * d[0] + d[1] * d[1]);
    }
    (1.0 - (-sum).exp()).clamp(0.0, 1.0)
}

/// sin Φ and cos Φ's absolute error in the CPU mirror ([`source_height_f32`] and the rest): the
/// table of one turn filtered exactly (`turn_table_error(..).exact_filter()`, 2.45·10⁻⁴).
pub fn mirror_sin_cos_error() -> f64 {
    turn_table_error(TURN_TABLE_TEXELS).exact_filter()
}

/// sin Φ and cos Φ's absolute error on a conforming GPU: the table as a GPU may filter it
/// (`turn_table_error(..).total()`, 9.6·10⁻⁴, where WGSL's own sin and cos would be 2⁻¹¹): a
/// GPU's `wake_height` is within `f32_height_error_bound(.., gpu_sin_cos_error())` of the f64
/// terms.
pub fn gpu_sin_cos_error() -> f64 {
    turn_table_error(TURN_TABLE_TEXELS).total()
}

/// A first-order bound of |wake_height_f32 − Σ f64 terms of the same sources| at local point
/// `p`, m, for IEEE f32 arithmetic, exp within a few ulp and sin Φ, cos Φ within `sin_error`
/// (absolute: [`mirror_sin_cos_error`] on the CPU, [`gpu_sin_cos_error`] on a GPU). Per
/// source, with T = C (k*²/r) e^{−G}(1 + |4G − 3|/Φ)(1 + 1/Φ) the size of the term and its
/// Φ-derivative, the rounding of p, pos, q and r gives r a relative error
/// ε_r = 2u(|p| + |pos|)/r + 2u (u = 2⁻²⁴), which moves Φ ∝ 1/r by Φε_r, the amplitude ∝ r⁻⁵
/// by 5ε_r and G ∝ r⁻⁴ by 4Gε_r; the phase the table is read at, (q/2π)·(1/r) turns, errs by
/// at most 6u of Φ (`kernel.rs`), within the 12u per unit of Φ carried here (the reduction of Φ
/// to [−π, π] the kernel made before it took the table), the ~22 roundings of the formula and
/// of the source's kernel constants (−strength·ΔX is rounded once on the CPU, R² is exact) at
/// most 16·12u of the amplitude, and sin and cos their own error:
/// bound = Σ T [(Φ + 16)·12u + (Φ + 4G + 6) ε_r + 2 sin_error].
pub fn f32_height_error_bound(sources: &[GpuWakeSource], p: [f32; 2], sin_error: f64) -> f64 {
    const U: f64 = 1.0 / 16_777_216.0;
    let mut b = 0.0;
    for s in sources {
        let d = [(p[0] - s.pos[0]) as f64, (p[1] - s.pos[1]) as f64];
        let r2 = d[0] * d[0] + d[1] * d[1];
        if r2 < MIN_R2 as f64 {
            continue;
        }
        let r = r2.sqrt();
        let q = s.q as f64;
        let k = q / r2;
        let g = k * k * s.gauss as f64;
        if g > GAUSS_CUTOFF + 1.0 {
            continue;
        }
        let phi = q / r;
        let len = (s.dx[0] as f64).hypot(s.dx[1] as f64);
        let t = s.strength as f64 * len * k * k / r
            * (-g).exp()
            * (1.0 + (4.0 * g - 3.0).abs() / phi)
            * (1.0 + 1.0 / phi);
        let pn = (p[0] as f64).hypot(p[1] as f64);
        let sn = (s.pos[0] as f64).hypot(s.pos[1] as f64);
        let eps_r = 2.0 * U * (pn + sn) / r + 2.0 * U;
        b += t * ((phi + 16.0) * 12.0 * U + (phi + 4.0 * g + 6.0) * eps_r + 2.0 * sin_error);
    }
    b
}

/// The f64 terms of exactly the sources in `frame` at world point `o + p` (for tests and the
/// bench: what the f32 path approximates).
pub fn frame_height_f64(
    wake: &Wake,
    t: f64,
    origin: [f64; 2],
    view: &WakeView,
    epsilon: f64,
    p: [f64; 2],
) -> f64 {
    let prm = &wake.params;
    let world = [origin[0] + p[0], origin[1] + p[1]];
    wake.active(t)
        .filter(|s: &&KelvinSource| {
            let age = t - s.t;
            let fade = prm.age_fade(age);
            if fade == 0.0 {
                return false;
            }
            let q = prm.gravity * age * age / 4.0;
            let c = prm.source_constant() * fade * s.dx[0].hypot(s.dx[1]);
            let rc = cull_radius(c, q, prm.hull_radius, epsilon);
            view.distance2(s.pos) <= rc * rc
                && (world[0] - s.pos[0]).powi(2) + (world[1] - s.pos[1]).powi(2) <= rc * rc
        })
        .map(|s| super::kelvin::source_height(s, world, t, prm))
        .sum()
}

/// The squared radius of a source's Gaussian cut-off, m² (f64 from its f32 fields): inside
/// it k²R²/4 > [`GAUSS_CUTOFF`] (k = q/r², so r² < q·√(R²/4 / cut-off)).
pub(crate) fn gauss_hole_r2(s: &GpuWakeSource) -> f64 {
    f64::from(s.q.max(0.0)) * (f64::from(s.gauss.max(0.0)) / GAUSS_CUTOFF).sqrt()
}

/// The foam strip's −1/w², 1/m², rounded once from f64.
fn foam_rate(s: &GpuWakeSource) -> f32 {
    (-1.0 / f64::from(s.foam_w2)) as f32
}

impl From<&GpuWakeSource> for WakeKernelSource {
    fn from(s: &GpuWakeSource) -> WakeKernelSource {
        let strength = f64::from(s.strength);
        WakeKernelSource {
            pos: s.pos,
            dx: s.dx.map(|v| (-strength * f64::from(v)) as f32),
            q: s.q,
            hull_r2: (4.0 * f64::from(s.gauss)) as f32,
            cull_r2: s.cull_r2,
            inner_r2: (gauss_hole_r2(s) as f32).max(MIN_R2),
            foam: s.foam,
            foam_rate: foam_rate(s),
            neg_q: -s.q,
            q_turns: (f64::from(s.q) / std::f64::consts::TAU) as f32,
        }
    }
}

/// A source's foam density at squared distance `r2` from its centre, f32 as the GPU forms it
/// (the kernel's −1/w², without forming the rest of its [`WakeKernelSource`]).
pub(crate) fn foam_density_f32(s: &GpuWakeSource, r2: f32) -> f32 {
    s.foam * (r2 * foam_rate(s)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wake::kernel::band_fade_at;

    /// The f64 value of [`source_height_f32`]'s formula (no cut-offs but r > 0).
    fn term_f64(s: &GpuWakeSource, p: [f64; 2]) -> f64 {
        let d = [p[0] - f64::from(s.pos[0]), p[1] - f64::from(s.pos[1])];
        let r2 = d[0] * d[0] + d[1] * d[1];
        let (q, r) = (f64::from(s.q), r2.sqrt());
        let k = q / r2;
        let g = k * k * f64::from(s.gauss);
        let phi = q / r;
        let amp = f64::from(s.strength) * k * k / r * (-g).exp();
        let proj = d[0] * f64::from(s.dx[0]) + d[1] * f64::from(s.dx[1]);
        -amp * (phi.sin() + (4.0 * g - 3.0) / phi * phi.cos()) * proj / r
    }

    #[test]
    fn the_peak_bound_holds_everywhere_and_is_tight_within_a_factor_four() {
        // Young and old sources of a 1 m and a 3 m hull, sampled on polar rays (dense near
        // the source, where the peak is).
        for (age, hull) in [(2.0, 1.0), (10.0, 1.0), (40.0, 3.0), (90.0, 2.0)] {
            let q: f64 = 9.81 * age * age / 4.0;
            let s = GpuWakeSource {
                pos: [3.0, -2.0],
                dx: [0.8, 0.6],
                q: q as f32,
                strength: 0.02,
                gauss: (hull * hull / 4.0) as f32,
                cull_r2: 1e12,
                ..Default::default()
            };
            let bound = source_peak_bound(&s);
            let mut worst = 0.0f64;
            for a in 0..72 {
                let th = f64::from(a) * std::f64::consts::TAU / 72.0;
                for i in 1..4000 {
                    let r = 0.01 * 1.003f64.powi(i);
                    let p = [3.0 + r * th.cos(), -2.0 + r * th.sin()];
                    worst = worst.max(term_f64(&s, p).abs());
                }
            }
            assert!(worst <= bound, "age {age}: {worst} > bound {bound}");
            assert!(
                bound < 4.0 * worst,
                "age {age}: bound {bound} vs peak {worst}"
            );
        }
    }
    fn old_source(age: f64, hull: f64) -> GpuWakeSource {
        GpuWakeSource {
            pos: [3.0, -2.0],
            dx: [0.8, 0.6],
            q: (9.81 * age * age / 4.0) as f32,
            strength: 0.02,
            gauss: (hull * hull / 4.0) as f32,
            cull_r2: 1e12,
            ..Default::default()
        }
    }

    /// The f32 fade is the f64 smoothstep within its stated bound at spacings that round and
    /// that do not, 1 below k·spacing = 1 and 0 from 2, no fade at spacing 0; the edges of a
    /// spacing 0.1 % off miss the bound.
    #[test]
    fn the_band_fade_is_the_sea_rule_in_f32_and_f64() {
        let mut worst = 0.0f64;
        for spacing in [0.3f32, 1.0, 1.7, 6.0] {
            let s = f64::from(spacing);
            let mut broken = 0.0f64;
            for i in 0..=2200 {
                let k = (f64::from(i) * 1e-3 / s) as f32;
                let x = f64::from(k) * s;
                let (a, b) = (band_fade_f32(k, spacing), band_fade(f64::from(k), s));
                assert!(
                    (f64::from(a) - b).abs() <= BAND_FADE_F32_ERROR,
                    "spacing {spacing} k {k}: {a} vs {b}"
                );
                worst = worst.max((f64::from(a) - b).abs());
                if x <= 1.0 {
                    assert_eq!((a, b), (1.0, 1.0), "spacing {spacing} k {k}");
                }
                if x >= 2.0 {
                    assert_eq!((a, b), (0.0, 0.0), "spacing {spacing} k {k}");
                }
                let off = band_fade_at(-k, band_edges(spacing * 1.001));
                broken = broken.max((f64::from(off) - b).abs());
            }
            assert!(broken > 100.0 * BAND_FADE_F32_ERROR, "{spacing}: {broken}");
        }
        eprintln!(
            "band fade f32 vs f64: worst {:.2} u (bound 9 u)",
            worst * 16_777_216.0
        );
        assert_eq!(band_fade_f32(1e6, 0.0), 1.0);
        assert_eq!(band_edges(0.0), [-2e30, -1e30]);
        // Halfway in k·spacing the smoothstep is ½.
        assert_eq!(band_fade(1.5, 1.0), 0.5);
    }

    /// Inside `inner_radius2` a source adds exactly nothing at the spacing it was computed
    /// for (and at every coarser one); just outside it, something.
    #[test]
    fn nothing_inside_the_inner_radius() {
        for (age, hull) in [(2.0, 1.0), (10.0, 1.5), (40.0, 3.0), (60.0, 1.5)] {
            let s = old_source(age, hull);
            for spacing in [0.0f32, 0.5, 1.7, 6.0] {
                let r_in = inner_radius2(&s, spacing).sqrt();
                for a in 0..36 {
                    let th = f64::from(a) * std::f64::consts::TAU / 36.0;
                    for f in [0.01, 0.3, 0.9, 0.9999] {
                        let r = f64::from(r_in) * f;
                        let p = [3.0 + (r * th.cos()) as f32, -2.0 + (r * th.sin()) as f32];
                        for coarser in [spacing, spacing * 2.0] {
                            let g = source_height_grad_sampled_f32(&s, p, coarser);
                            assert_eq!(g, [0.0; 3], "age {age} spacing {coarser} r {r}");
                        }
                    }
                }
                // Past the band limit's radius by a tenth the term lives (where the hole does
                // not set the radius).
                let r = 1.1 * f64::from(r_in);
                let p = [3.0 + r as f32, -2.0];
                let hole = f64::from(s.q) * (f64::from(s.gauss) / 40.0).sqrt();
                if r * r > hole * 1.5 && spacing > 0.0 {
                    assert_ne!(source_height_grad_sampled_f32(&s, p, spacing)[0], 0.0);
                }
            }
        }
    }

    /// Band limiting only scales the term: sampled = fade(k·spacing) × unlimited, f32, at
    /// three spacings. The bound: the fade's own error (`BAND_FADE_F32_ERROR`, 9u) and one
    /// rounding of its product, and the ~15 roundings after it in either path (the two
    /// gradient products summed), about 4·10⁻⁶ of the unlimited term. Edges formed for a
    /// spacing 1 % off miss it.
    #[test]
    fn the_band_limited_term_is_the_faded_term() {
        let s = old_source(20.0, 1.5);
        let kernel = WakeKernelSource::from(&s);
        let mut faded = 0;
        for spacing in [0.7f32, 2.0, 5.0] {
            let mut broken = 0.0f64;
            for i in 1..400 {
                let r = 0.5 * f64::from(i);
                let p = [3.0 + r as f32, -2.0 + (0.3 * r) as f32];
                let d = [p[0] - s.pos[0], p[1] - s.pos[1]];
                let r2 = d[0] * d[0] + d[1] * d[1];
                let k = s.q / r2;
                let full = source_height_grad_f32(&s, p);
                let lim = source_height_grad_sampled_f32(&s, p, spacing);
                let off = kernel.height_grad_in_band(d, r2, band_edges(spacing * 1.01));
                let fade = band_fade(f64::from(k), f64::from(spacing));
                faded += usize::from(fade > 0.0 && fade < 1.0);
                for c in 0..3 {
                    let want = f64::from(full[c]) * fade;
                    let bound = 4e-6 * f64::from(full[c].abs()) + 1e-30;
                    assert!(
                        (f64::from(lim[c]) - want).abs() <= bound,
                        "spacing {spacing} r {r} c {c}: {} vs {want}",
                        lim[c]
                    );
                    broken = broken.max((f64::from(off[c]) - want).abs() / bound);
                }
            }
            assert!(broken > 100.0, "spacing {spacing}: {broken}");
        }
        assert!(faded > 30, "{faded} points in the fade");
    }
}
