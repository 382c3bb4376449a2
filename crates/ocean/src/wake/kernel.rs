//! What the GPU reads of each wake source, and the exact f32 mirror of the WGSL kernel that
//! evaluates it (`shaders/ocean/wake.wgsl`).
//!
//! A frame's sources are culled, binned and bounded on the CPU as `GpuWakeSource`s (`gpu.rs`): the
//! physical quantities (q = g s²/4, the strength F/(√2πρg)·w(s), R²/4, the cull radius, the
//! foam strip). The kernel runs once per (point, source) pair, the water's costliest loop, so
//! what is fixed per source is formed here once per frame, in f64 from those f32 fields and
//! rounded once, and uploaded instead ([`WakeKernelSource`], the same 48 bytes):
//!
//! - the term's sign and strength folded into the segment vector, −strength·ΔX (the term is
//!   linear in both), so the kernel never multiplies by them;
//! - R² = 4·(R²/4), so k²R² (the 4g its brackets use) is one product and e^{−g} = e^{−k²R²/4};
//! - the squared radius inside which the Gaussian cut-off (k²R²/4 > 40) zeroes the term, so one
//!   range test on r² replaces the cut-off's test of g (it is never below `MIN_R2`, so the
//!   kernel never divides by zero);
//! - the foam strip's −1/w², so its density is `foam · exp(r² · rate)`;
//! - −q (exact), so −k = −q/r², the band fade's rising variable, is one division: the fade
//!   1 − smoothstep(1, 2, k·spacing) is smoothstep(−2/spacing, −1/spacing, −k), its edges
//!   formed once per point ([`band_edges`]), so a pair pays the smoothstep alone;
//! - q/2π (from the f32 q in f64, rounded once), so the phase in turns Φ/2π = (q/2π)·(1/r) is
//!   one product with the 1/r that Φ = q·(1/r) uses: the kernel takes sin Φ and cos Φ from the
//!   table of one turn ([`crate::turn_table`]) at fract(Φ/2π), where it reduced Φ to [−π, π]
//!   (Φ reaches thousands of radians; phones' sin and cos are accurate only there) and took
//!   sin and cos: 12 operations become 2 and a look-up on the texture unit. The phase in turns
//!   errs by at most 6u of Φ/2π (u = 2⁻²⁴: q/2π rounded once, ½u; a GPU's `inverseSqrt`, 2
//!   ULP, 4u; the product, ½u; `fract` is exact), less than the reduction's 12u of Φ that
//!   [`super::gpu::f32_height_error_bound`] carries; sin and cos then err by the table's
//!   bound ([`crate::turn_table::turn_table_error`]).
//!
//! The gradient: with h = F(r)·(d·dx), F = (q²/r⁶) e^{−g}·B, B = sin Φ + (4g − 3)/Φ cos Φ
//! (g = k²R²/4, Φ = q/r), r·F'/(F/B) is (4g − 6)·B (the amplitude's derivative) plus
//! (4g − 3) sin Φ − Φ cos Φ − (12g + 3)/Φ cos Φ (the bracket's), which the kernel forms
//! regrouped around B as (4g − 9)·B + 4g sin Φ − (Φ + 12/Φ) cos Φ: 8 operations where the
//! sum as written took 11; exact in real arithmetic, only f32 rounding moves.

use crate::turn_table::turn_sin_cos_f32;

/// Below this squared distance (m²) a source is skipped: its term is e^{−k*²R²/4} ≈ 0 there,
/// and the shader must never divide by zero (the floor of `WakeKernelSource::inner_r2`).
pub const MIN_R2: f32 = 1e-6;

/// Where the band limit starts and ends, in k·spacing (radians per sample spacing).
pub const BAND_START: f32 = 1.0;
pub const BAND_END: f32 = 2.0;

/// The least spacing (m) the band limit's edges are formed for: a spacing of 0 (no band limit)
/// gives edges −2·10³⁰ and −10³⁰ in −k, which no source's wavenumber reaches (k = q/r² is at
/// most q/[`MIN_R2`], below 10¹⁰ for any age a wake keeps), so the fade is exactly 1 and no
/// edge is infinite (WGSL leaves a division by zero indeterminate).
pub const SPACING_MIN: f32 = 1e-30;

/// One wake source as the WGSL kernel reads it (`WakeSource` in `shaders/ocean/wake.wgsl`,
/// std430: 48 bytes, 8-byte aligned), formed from a `GpuWakeSource` by `From` (in `gpu.rs`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WakeKernelSource {
    /// Segment midpoint − local origin (x, z), m.
    pub pos: [f32; 2],
    /// −strength · ΔX (x, z): the segment vector with the term's sign and strength, m⁴.
    pub dx: [f32; 2],
    /// q = g s²/4 for the source's age s, m.
    pub q: f32,
    /// R², the pressure patch's radius squared, m²: k²R² = 4g.
    pub hull_r2: f32,
    /// r_c²: the term is below ε beyond r_c, m².
    pub cull_r2: f32,
    /// Inside this squared distance the term is nothing: the Gaussian cut-off's radius,
    /// k²R²/4 > 40 for r² < q·√(R²/4/40), and never below [`MIN_R2`], m².
    pub inner_r2: f32,
    /// Foam density at the segment's centre.
    pub foam: f32,
    /// −1/w², w the foam strip's width, 1/m².
    pub foam_rate: f32,
    /// −q, m (exact): −k = −q/r² is then one division, the band fade's rising variable.
    pub neg_q: f32,
    /// q/2π, m (from q in f64, rounded once): the phase in turns Φ/2π = (q/2π)/r.
    pub q_turns: f32,
}

/// WGSL's `inverseSqrt` in f32 (its square root, then the reciprocal).
fn inverse_sqrt(x: f32) -> f32 {
    1.0 / x.sqrt()
}

/// WGSL's `smoothstep(lo, hi, x)` in f32 as WGSL defines it: t²(3 − 2t),
/// t = clamp((x − lo)/(hi − lo), 0, 1).
fn smoothstep(lo: f32, hi: f32, x: f32) -> f32 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The band limit's edges in −k for points sampled every `spacing` metres, f32 exactly as
/// `wake_band_edges` in WGSL: (−BAND_END/s, −BAND_START/s), s = max(spacing, SPACING_MIN).
/// The fade 1 − smoothstep(BAND_START, BAND_END, k·spacing) is smoothstep(lo, hi, −k) (the
/// Hermite step is symmetric: s(1 − t) = 1 − s(t)), so a (point, source) pair pays the
/// smoothstep alone.
pub fn band_edges(spacing: f32) -> [f32; 2] {
    let s = spacing.max(SPACING_MIN);
    [-BAND_END / s, -BAND_START / s]
}

/// The band fade at −k = `neg_k` between `band`'s edges, f32 as the WGSL kernel forms it.
pub(crate) fn band_fade_at(neg_k: f32, band: [f32; 2]) -> f32 {
    smoothstep(band[0], band[1], neg_k)
}

impl WakeKernelSource {
    /// Is the term nothing at squared distance `r2`: beyond the cull radius or inside the
    /// cut-off's (`wake_source_*`'s first test).
    fn outside(&self, r2: f32) -> bool {
        r2 > self.cull_r2 || r2 < self.inner_r2
    }

    /// The height term at offset `d` = p − pos (`r2` = |d|²), m, exactly as
    /// `wake_source_height` in WGSL: (q²/r⁶) e^{−k²R²/4} [sin Φ + (k²R² − 3)/Φ cos Φ] (d·dx).
    pub fn height(&self, d: [f32; 2], r2: f32) -> f32 {
        if self.outside(r2) {
            return 0.0;
        }
        let k = self.q / r2;
        let kk = k * k;
        let big_g = kk * self.hull_r2;
        let inv_r = inverse_sqrt(r2);
        let phi = self.q * inv_r;
        let [sn, cs] = turn_sin_cos_f32(self.q_turns * inv_r);
        let bracket = sn + (big_g - 3.0) / phi * cs;
        kk / r2 * (-0.25 * big_g).exp() * bracket * (d[0] * self.dx[0] + d[1] * self.dx[1])
    }

    /// The height term and its gradient at offset `d` (`r2` = |d|²), band limited for points
    /// `spacing` metres apart (0: not limited), (w, ∂w/∂x, ∂w/∂z) in m and m/m, exactly as
    /// `wake_source_height_grad_at` in WGSL with the edges `wake_band_edges(spacing)`.
    pub fn height_grad(&self, d: [f32; 2], r2: f32, spacing: f32) -> [f32; 3] {
        self.height_grad_in_band(d, r2, band_edges(spacing))
    }

    /// [`Self::height_grad`] with the band limit's edges already formed ([`band_edges`]), as
    /// `wake_at` in WGSL forms them once per point.
    pub fn height_grad_in_band(&self, d: [f32; 2], r2: f32, band: [f32; 2]) -> [f32; 3] {
        if self.outside(r2) {
            return [0.0; 3];
        }
        let neg_k = self.neg_q / r2;
        if neg_k <= band[0] {
            return [0.0; 3];
        }
        let kk = neg_k * neg_k;
        let big_g = kk * self.hull_r2;
        let inv_r = inverse_sqrt(r2);
        let phi = self.q * inv_r;
        let [sn, cs] = turn_sin_cos_f32(self.q_turns * inv_r);
        let c = kk / r2 * (-0.25 * big_g).exp() * band_fade_at(neg_k, band);
        let bracket = sn + (big_g - 3.0) / phi * cs;
        let radial_bracket = (big_g - 9.0) * bracket + big_g * sn - (phi + 12.0 / phi) * cs;
        let proj = d[0] * self.dx[0] + d[1] * self.dx[1];
        let f = c * bracket;
        let radial = c * radial_bracket * proj / r2;
        [
            f * proj,
            radial * d[0] + f * self.dx[0],
            radial * d[1] + f * self.dx[1],
        ]
    }

    /// The foam density at squared distance `r2`, exactly as `wake_source_foam` in WGSL.
    pub fn foam_density(&self, r2: f32) -> f32 {
        self.foam * (r2 * self.foam_rate).exp()
    }
}

#[cfg(test)]
mod tests;
