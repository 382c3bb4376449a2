//! f32-safe wave inputs for a GPU.
//!
//! A shader evaluates θ = k D·p + θ0 at a *local* point p = x0 − o, where o is a local origin
//! near the camera (a few hundred metres at most from anything drawn) and
//! θ0 = (k D·o − ω t + φ) mod 2π is reduced here in f64. So the shader never sees an absolute
//! race time or a large coordinate, and every argument of sin/cos it computes is bounded by
//! k |p| + 2π. Phone GPUs lose accuracy on large sin() arguments; lavapipe does not, so the
//! tests assert the bound on θ0 rather than trusting a desktop render.

use std::f64::consts::TAU;

use crate::WaveSet;

/// Reduce an angle to [0, 2π) in f64.
pub fn reduce_phase(theta: f64) -> f64 {
    let r = theta.rem_euclid(TAU);
    // rem_euclid can return TAU itself for tiny negative inputs after rounding.
    if r >= TAU { 0.0 } else { r }
}

/// One wave as a shader reads it (uniform layout: 64 bytes, 16-byte aligned; its WGSL twin is
/// `struct Wave` in `shaders/render/common.wgsl`).
///
/// Every product of the wave's constants that a shader would otherwise form per pixel or per
/// vertex is formed here in f64 and rounded once: the phase is one dot product and one
/// addition (`wavevector`), a displacement needs no direction × amplitude product
/// (`amplitude_direction`), and a slope sum needs no k·A × direction product (`slope_xx` …
/// `slope_z`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuWave {
    /// The wavevector k D (x, z), rad/m: θ = k D·p + θ0 at local point p.
    pub wavevector: [f32; 2],
    /// θ0 = (k D·o − ω t + φ) mod 2π, radians, in [0, 2π).
    pub phase0: f32,
    /// k, rad/m (the pixel filter compares it with its cut-off wavenumbers).
    pub k: f32,
    /// A D (x, z), metres: the horizontal displacement's amplitude.
    pub amplitude_direction: [f32; 2],
    /// A, metres.
    pub amplitude: f32,
    /// (k·A)²/2, its mean square slope (the slope variance a shader keeps for a faded wave).
    pub half_slope2: f32,
    /// Σ of `half_slope2` over this wave and every wave after it in the list (summed in f64):
    /// in a list sorted by wavenumber ([`sort_by_wavenumber`]) a shader whose pixel filter has
    /// faded this wave out has faded all the rest too, stops there and keeps their variance
    /// in one addition.
    pub tail_half_slope2: f32,
    /// k A D_x², k A D_x D_z, k A D_z²: the wave's terms of the horizontal map's Jacobian
    /// (each times −sin θ), which every pixel's `surface_frame` sums.
    pub slope_xx: f32,
    pub slope_xz: f32,
    pub slope_zz: f32,
    /// k A D_x, k A D_z: its terms of the height's gradient (each times cos θ).
    pub slope_x: f32,
    pub slope_z: f32,
    pub _pad: [f32; 2],
}

impl WaveSet {
    /// The waves as f32-safe GPU inputs at race time `t` for local origin `origin` (x, z).
    /// `tail_half_slope2` is summed in the list's order (the sea's).
    pub fn gpu_waves(&self, t: f64, origin: [f64; 2]) -> Vec<GpuWave> {
        let mut waves: Vec<GpuWave> = self
            .waves
            .iter()
            .map(|w| {
                let theta0 = reduce_phase(self.phase_at(w, origin, t));
                let (k, a) = (w.k(), w.amplitude());
                let [dx, dz] = w.direction;
                let slope = k * a;
                GpuWave {
                    wavevector: [(k * dx) as f32, (k * dz) as f32],
                    phase0: theta0 as f32,
                    k: k as f32,
                    amplitude_direction: [(a * dx) as f32, (a * dz) as f32],
                    amplitude: a as f32,
                    half_slope2: (0.5 * slope * slope) as f32,
                    tail_half_slope2: 0.0,
                    slope_xx: (slope * dx * dx) as f32,
                    slope_xz: (slope * dx * dz) as f32,
                    slope_zz: (slope * dz * dz) as f32,
                    slope_x: (slope * dx) as f32,
                    slope_z: (slope * dz) as f32,
                    _pad: [0.0; 2],
                }
            })
            .collect();
        set_tails(&mut waves);
        waves
    }
}

/// Fill `tail_half_slope2` in `waves`' order: each term the shader's own `half_slope2` (the
/// f64 value rounded once), summed in f64.
fn set_tails(waves: &mut [GpuWave]) {
    let mut tail = 0.0f64;
    for w in waves.iter_mut().rev() {
        tail += f64::from(w.half_slope2);
        w.tail_half_slope2 = tail as f32;
    }
}

/// Sort `waves` by wavenumber, longest first (a stable sort: equal k keep their order), and
/// refill the tail sums for the new order. Returns, for each slot of the sorted list, the
/// index the wave had before, so per-wave masks built on the old order can follow.
///
/// Why: a pixel's filter (`surface_frame` in `shaders/render/common.wgsl`) fades waves by
/// k·footprint, so in this order the waves it still sees are a prefix of the list and its
/// loop stops at the first faded one.
pub fn sort_by_wavenumber(waves: &mut Vec<GpuWave>) -> Vec<usize> {
    let mut order: Vec<usize> = (0..waves.len()).collect();
    order.sort_by(|&a, &b| waves[a].k.total_cmp(&waves[b].k));
    *waves = order.iter().map(|&i| waves[i]).collect();
    set_tails(waves);
    order
}

/// The displacement (dx, y, dz) at local rest point `p` in f32, exactly as the WGSL does it.
/// The f32 path that benches and tests compare against the f64 reference.
pub fn displace_f32(waves: &[GpuWave], p: [f32; 2]) -> [f32; 3] {
    let mut d = [0.0f32; 3];
    for w in waves {
        let theta = (w.wavevector[0] * p[0] + w.wavevector[1] * p[1]) + w.phase0;
        let (s, c) = theta.sin_cos();
        d[0] += w.amplitude_direction[0] * c;
        d[1] += w.amplitude * s;
        d[2] += w.amplitude_direction[1] * c;
    }
    d
}

/// f32 unit roundoff (round to nearest): 2⁻²⁴.
const F32_UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

/// A bound, in metres, of |displace_f32(gpu_waves(t, o), p) − (displace(o + p, t) − (o + p))|
/// per component, for local points with |p| ≤ `radius` metres, on an IEEE f32 path with a
/// sin/cos accurate to 1 ulp (CPU libm; a GPU's sin may be coarser, see WGSL's 2⁻¹¹ absolute
/// error in [−π, π]).
///
/// Derivation, u = 2⁻²⁴: the phase k D·p + θ0 is formed from the wavevector k D (f64, rounded
/// once), p and θ0 ∈ [0, 2π) rounded to f32; the two products, their sum and the last addition
/// each round once and |k D·p| ≤ k |p|, so its error is at most u (4 k |p| + 4π) to first
/// order (the bound keeps the u (8 k |p| + 6π) of the earlier path, which formed k·(D·p) from
/// k and D apart, with room to spare). The wave's term A D_x cos θ then errs by at most
/// A (δθ + 4u) (sin/cos, the rounding of A D_x or A, the product). Summing n terms adds at most
/// n u Σ A. So
///
/// bound = u · Σ_i A_i (8 k_i |p| + 6π + 4 + n).
///
/// It grows with k|p|, never with t: that is why phases are reduced on the CPU.
pub fn f32_error_bound(waves: &[GpuWave], radius: f64) -> f64 {
    let n = waves.len() as f64;
    F32_UNIT_ROUNDOFF
        * waves
            .iter()
            .map(|w| {
                w.amplitude as f64
                    * (8.0 * w.k as f64 * radius + 6.0 * std::f64::consts::PI + 4.0 + n)
            })
            .sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sort is a permutation that orders by k and says where each wave came from; the tail
    /// sums are the f64 suffix sums of (k a)²/2 in the new order.
    #[test]
    fn sorting_by_wavenumber_keeps_every_wave_and_its_tail() {
        let mut sea = WaveSet::default_sea();
        sea.waves.swap(0, 4);
        sea.waves.swap(1, 5);
        let before = sea.gpu_waves(12.5, [300.0, -40.0]);
        let mut sorted = before.clone();
        let order = sort_by_wavenumber(&mut sorted);
        assert!(sorted.windows(2).all(|p| p[0].k <= p[1].k));
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..before.len()).collect::<Vec<_>>());
        for (slot, &i) in order.iter().enumerate() {
            let (a, b) = (sorted[slot], before[i]);
            assert_eq!((a.k, a.phase0, a.wavevector), (b.k, b.phase0, b.wavevector));
            let tail: f64 = order[slot..]
                .iter()
                .map(|&j| {
                    let w = &sea.waves[j];
                    0.5 * (w.k() * w.amplitude()).powi(2)
                })
                .sum();
            assert!((f64::from(a.tail_half_slope2) - tail).abs() <= 1e-6 * tail);
        }
    }

    #[test]
    fn reduce_phase_stays_in_range() {
        for &th in &[0.0, -1e-300, -1e-17, TAU, -TAU, 1e7, -3.9e7, 123.456] {
            let r = reduce_phase(th);
            assert!((0.0..TAU).contains(&r), "{th} -> {r}");
            // Same angle: sin and cos agree to the f64 rounding of |θ|.
            let tol = 1e-15 * th.abs().max(1.0) * 4.0;
            assert!((r.sin() - th.sin()).abs() <= tol && (r.cos() - th.cos()).abs() <= tol);
        }
    }

    #[test]
    fn gpu_waves_are_reduced_and_match_f64_at_a_long_race_time() {
        let s = WaveSet::default_sea();
        let (t, o) = (9.5e6, [-8000.0, 7000.0]);
        let g = s.gpu_waves(t, o);
        assert_eq!(std::mem::size_of::<GpuWave>(), 64);
        for w in &g {
            assert!((0.0..=TAU as f32).contains(&w.phase0));
        }
        let p = [37.5f32, -120.25f32];
        let d = displace_f32(&g, p);
        let x0 = [o[0] + p[0] as f64, o[1] + p[1] as f64];
        let r = s.displace(x0, t);
        let bound = f32_error_bound(&g, 130.0);
        assert!(bound < 1e-4, "{bound}");
        assert!(((d[0] as f64) - (r[0] - x0[0])).abs() <= bound);
        assert!(((d[1] as f64) - r[1]).abs() <= bound);
        assert!(((d[2] as f64) - (r[2] - x0[1])).abs() <= bound);
    }

    /// `surface_frame`'s sums with no band limit (footprint 0, every wave whole), in f32 as
    /// `resolved_waves` does them: the unnormalised upward normal and the Jacobian.
    fn surface_frame_f32(waves: &[GpuWave], p: [f32; 2]) -> ([f32; 3], f32) {
        let (mut xx, mut xz, mut zz, mut yx, mut yz) = (1.0f32, 0.0f32, 1.0f32, 0.0f32, 0.0f32);
        for w in waves {
            let theta = (w.wavevector[0] * p[0] + w.wavevector[1] * p[1]) + w.phase0;
            let (sn, cs) = theta.sin_cos();
            xx -= w.slope_xx * sn;
            xz -= w.slope_xz * sn;
            zz -= w.slope_zz * sn;
            yx += w.slope_x * cs;
            yz += w.slope_z * cs;
        }
        let jacobian = xx * zz - xz * xz;
        ([yz * xz - zz * yx, jacobian, xz * yx - yz * xx], jacobian)
    }

    /// The k A·direction products `gpu_waves` forms on the CPU are the surface's: the f32
    /// sums of them give the f64 surface's unit normal and Jacobian (`WaveSet::surface`, its
    /// own analytic derivatives) within their rounding, and a product in the wrong slot
    /// misses by far more.
    #[test]
    fn the_carried_slope_products_give_the_f64_surface() {
        let s = WaveSet::default_sea();
        let (t, o) = (9.5e6, [-8000.0, 7000.0]);
        let g = s.gpu_waves(t, o);
        let steepness = s.total_steepness();
        assert!(steepness < 1.0);
        // Each of the five sums is f32_error_bound's derivation with A → k A (the product
        // rounded once, sin/cos, the product with it, the sum), and the start value 1 of the
        // diagonal sums rounded in each of the n additions.
        let radius = 130.0;
        let slopes: Vec<GpuWave> = g
            .iter()
            .map(|w| GpuWave {
                amplitude: w.k * w.amplitude,
                ..*w
            })
            .collect();
        let n = g.len() as f64;
        let delta = f32_error_bound(&slopes, radius) + 2.0 * n * F32_UNIT_ROUNDOFF;
        // A component a·b − c·d of the normal or the Jacobian: each factor ≤ 1 + Σ kA off by
        // δ, and three roundings of products of at most (1 + Σ kA)².
        let big = 1.0 + steepness;
        let component = 4.0 * big * delta + 3.0 * F32_UNIT_ROUNDOFF * big * big;
        // The unit normal of up + e against up's: at most 2 |e| / |up|, |up| ≥ J ≥ 1 − Σ kA.
        let normal_bound = 2.0 * 3f64.sqrt() * component / (1.0 - steepness);
        // Loose (the phase's 8 k |p| of f32_error_bound, the 1 / (1 − Σ kA)), yet under a
        // tenth of a degree: not a free pass.
        assert!(normal_bound < 2e-3, "{normal_bound}");
        let misses = |waves: &[GpuWave]| {
            let (mut normal_miss, mut jacobian_miss) = (0.0f64, 0.0f64);
            for p in [
                [37.5f32, -120.25],
                [0.0, 0.0],
                [-64.0, 3.5],
                [90.0, 90.0],
                [-20.5, 77.0],
            ] {
                let (up, jacobian) = surface_frame_f32(waves, p);
                let length = up.iter().map(|c| f64::from(*c).powi(2)).sum::<f64>().sqrt();
                let want = s.surface([o[0] + f64::from(p[0]), o[1] + f64::from(p[1])], t);
                for (got, exact) in up.iter().zip(want.normal) {
                    normal_miss = normal_miss.max((f64::from(*got) / length - exact).abs());
                }
                jacobian_miss = jacobian_miss.max((f64::from(jacobian) - want.jacobian).abs());
            }
            (normal_miss, jacobian_miss)
        };
        let (normal_miss, jacobian_miss) = misses(&g);
        assert!(
            normal_miss <= normal_bound,
            "{normal_miss} > {normal_bound}"
        );
        assert!(jacobian_miss <= component, "{jacobian_miss} > {component}");
        // D_x D_z where D_z² belongs, and k A D_z where k A D_x belongs.
        let swapped: Vec<GpuWave> = g
            .iter()
            .map(|w| GpuWave {
                slope_zz: w.slope_xz,
                slope_x: w.slope_z,
                ..*w
            })
            .collect();
        let (normal_miss, jacobian_miss) = misses(&swapped);
        assert!(normal_miss > 100.0 * normal_bound, "{normal_miss}");
        assert!(jacobian_miss > 100.0 * component, "{jacobian_miss}");
    }
}
