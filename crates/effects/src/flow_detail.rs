//! The flow map's detail field (the pattern the current advects, [`super::flowmap`]): its f64
//! reference, its texture baked once on the CPU, and the bound on the texture against the field.
//!
//! The field is a tiling height field on the unit square, three rounded triangle waves with
//! integer frequencies k_i (so it tiles) and weights c_i: h(uv) = 0.02 Σ c_i H(k_i·uv), whose
//! slopes are 0.02 Σ c_i k_i B(k_i·uv) with B = [`periodic_bump`] (B is H's derivative, up to
//! the scale the 0.02 absorbs). The AR water samples the slopes from a [`DETAIL_TEXELS`]²
//! texture of 16-bit floats (`Rg16Float`), bilinear with wrap-around, where it evaluated the
//! waves twice per pixel (`shaders/effects/flowmap.wgsl`, `detail_slope`).
//!
//! The texture against the field ([`detail_texture_error`], per slope component j, texel
//! spacing h = 1/N on the unit square):
//!
//! - interpolation: bilinear is linear interpolation along u then along v, each a convex
//!   combination, so it errs by at most h²/8 (max|∂²f_j/∂u²| + max|∂²f_j/∂v²|) (the linear
//!   interpolant's remainder f''(ξ)(x − a)(b − x)/2 ≤ h² f''/8; B is C²). In closed form:
//!   max|B''| = 48 (below), so max|∂²f_j/∂u_a²| = 0.02 · 48 · Σ |c_i k_ij| k_ia²;
//! - the texel format: each texel rounded to the nearest f16, at most half a unit in the last
//!   place (ULP) of the largest |f_j|; the filter may compute and hold its result in half
//!   floats too (WGSL and Vulkan do not say; as `render::wgsl_accuracy` takes it, the weight's
//!   product and the sum each rounded by ½ ULP: 1 ULP): 1.5 ULP in all;
//! - the GPU's filtering position: Vulkan guarantees only `subTexelPrecisionBits` ≥ 4, the
//!   sample position snapped to 1/16 of a texel per axis. The specification says "snap"
//!   without saying whether to the nearest (≤ 1/32) or down (Direct3D's reference truncates),
//!   so the bound takes the whole step, h/16 per axis
//!   (`render::wgsl_accuracy::sub_texel_snap_texels`). The bilinear interpolant's slope along
//!   an axis is a blend of texel differences over h, each at most max|∂f_j/∂u_a| plus the two
//!   texels' rounding (1 ULP)/h, so the snap moves the value by at most
//!   (1/16) Σ_a (h max|∂f_j/∂u_a| + 1 ULP), with max|∂f_j/∂u_a| = 0.02 · 6 · Σ |c_i k_ij k_ia|
//!   (max|B'| = 6);
//! - the texel coordinate: u·N − ½ in f32 (and the wrap), at most 2⁻²² (|uv| + 1) in uv units
//!   per axis for a sample at |uv|, times the same slopes.
//!
//! [`DETAIL_TEXELS`] is the smallest power of two whose bound is within 1 % of the field's
//! largest slope ([`texels_for`]); at 512 the weak filtering term dominates (about 3/4).

use std::sync::OnceLock;

use glam::DVec2;
use render::wgsl_accuracy::{half_float_ulp, sub_texel_snap_texels};

/// The detail field's waves: wavenumber (cycles per tile along u and v) and weight.
pub const DETAIL_WAVES: [(DVec2, f64); 3] = [
    (DVec2::new(3.0, 2.0), 1.0),
    (DVec2::new(-2.0, 5.0), 1.0),
    (DVec2::new(7.0, 1.0), 0.4),
];

/// The detail field's slope scale (dimensionless: slope per unit of the waves' sum).
pub const DETAIL_SCALE: f64 = 0.02;

/// Texels per side of the baked detail texture (a 1 MiB `Rg16Float` texture).
pub const DETAIL_TEXELS: u32 = 512;

/// The largest bound, as a fraction of the field's largest slope, that [`DETAIL_TEXELS`] is
/// chosen for.
pub const DETAIL_BOUND_FRACTION: f64 = 0.01;

/// A smooth periodic bump: 1 at whole x, −1 at half; a triangle wave s (slope ±4) with its
/// corners rounded by s (3 − s²)/2, continuous in slope and curvature: B' = ±6 (1 − s²),
/// B'' = −48 s. Within 0.021 of cos(2π x).
pub fn periodic_bump(x: f64) -> f64 {
    let s = 4.0 * (x - x.floor() - 0.5).abs() - 1.0;
    s * (1.5 - 0.5 * s * s)
}

/// The detail field's slopes (∂/∂u, ∂/∂v scaled by [`DETAIL_SCALE`]) at `uv` (tiles; period 1
/// in both).
pub fn detail_slope(uv: DVec2) -> DVec2 {
    DETAIL_WAVES
        .iter()
        .map(|&(k, c)| k * c * periodic_bump(k.dot(uv)))
        .sum::<DVec2>()
        * DETAIL_SCALE
}

/// max |∂f_j/∂u_a| over the field: `[j][a]` for slope component j along axis a.
pub fn detail_gradient_max() -> [[f64; 2]; 2] {
    let mut g = [[0.0; 2]; 2];
    for (k, c) in DETAIL_WAVES {
        for (j, gj) in g.iter_mut().enumerate() {
            for (a, ga) in gj.iter_mut().enumerate() {
                *ga += (c * k[j] * k[a]).abs() * 6.0 * DETAIL_SCALE;
            }
        }
    }
    g
}

/// max |∂²f_j/∂u_a²| over the field: `[j][a]`.
pub fn detail_curvature_max() -> [[f64; 2]; 2] {
    let mut g = [[0.0; 2]; 2];
    for (k, c) in DETAIL_WAVES {
        for (j, gj) in g.iter_mut().enumerate() {
            for (a, ga) in gj.iter_mut().enumerate() {
                *ga += (c * k[j]).abs() * k[a] * k[a] * 48.0 * DETAIL_SCALE;
            }
        }
    }
    g
}

/// max |f_j| over the field.
pub fn detail_slope_max() -> DVec2 {
    DETAIL_WAVES
        .iter()
        .map(|&(k, c)| (k * c).abs())
        .sum::<DVec2>()
        * DETAIL_SCALE
}

/// The parts of the bound on the sampled texture against [`detail_slope`], per slope
/// component (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetailTextureError {
    /// Bilinear interpolation of the exact texels.
    pub interpolation: DVec2,
    /// The texels' f16 rounding (½ ULP) and the filter's in half floats (1 ULP).
    pub rounding: DVec2,
    /// The filtering position snapped to Vulkan's least sub-texel step.
    pub filtering: DVec2,
    /// The f32 texel coordinate of a sample at the given |uv|.
    pub coordinate: DVec2,
}

impl DetailTextureError {
    /// What the CPU's exact bilinear filter of the texture may err by (interpolation and the
    /// texels' rounding).
    pub fn exact_filter(&self) -> DVec2 {
        self.interpolation + self.rounding / 3.0
    }

    /// What a conforming GPU's sample may err by.
    pub fn total(&self) -> DVec2 {
        self.interpolation + self.rounding + self.filtering + self.coordinate
    }
}

/// The bound for a texture of `texels` per side sampled at |u|, |v| ≤ `uv_magnitude`.
pub fn detail_texture_error(texels: u32, uv_magnitude: f64) -> DetailTextureError {
    let h = 1.0 / f64::from(texels);
    let (g, c, m) = (
        detail_gradient_max(),
        detail_curvature_max(),
        detail_slope_max(),
    );
    let per = |f: &dyn Fn(usize) -> f64| DVec2::new(f(0), f(1));
    let ulp = per(&|j| half_float_ulp(m[j]));
    DetailTextureError {
        interpolation: per(&|j| h * h / 8.0 * (c[j][0] + c[j][1])),
        rounding: 1.5 * ulp,
        filtering: per(&|j| sub_texel_snap_texels() * (h * (g[j][0] + g[j][1]) + 2.0 * ulp[j])),
        coordinate: per(&|j| (g[j][0] + g[j][1]) * (uv_magnitude + 1.0) * 2f64.powi(-22)),
    }
}

/// The smallest power-of-two texture whose bound ([`DetailTextureError::total`], near the
/// tile) is within `fraction` of the field's largest slope, per component.
pub fn texels_for(fraction: f64) -> u32 {
    let m = detail_slope_max();
    (4..=14)
        .map(|b| 1u32 << b)
        .find(|&n| {
            let e = detail_texture_error(n, 1.0).total();
            e.x <= fraction * m.x && e.y <= fraction * m.y
        })
        .unwrap_or(1 << 14)
}

/// The texture of `texels`² texels: texel (i, j) (row j) holds the f16 bits of the slopes at
/// its centre ((i + ½)/N, (j + ½)/N), as `Rg16Float` lays them out.
pub fn bake_detail(texels: u32) -> Vec<[u16; 2]> {
    bake_detail_at(texels, 0.5)
}

/// [`bake_detail`] with texel (i, j) holding the slopes at ((i + o)/N, (j + o)/N): o = ½ is the
/// texture; any other offset is a wrongly baked one, for the tests that must catch it.
pub fn bake_detail_at(texels: u32, o: f64) -> Vec<[u16; 2]> {
    let n = f64::from(texels);
    (0..texels * texels)
        .map(|k| {
            let (i, j) = (f64::from(k % texels), f64::from(k / texels));
            let s = detail_slope(DVec2::new((i + o) / n, (j + o) / n));
            [
                half::f16::from_f64(s.x).to_bits(),
                half::f16::from_f64(s.y).to_bits(),
            ]
        })
        .collect()
}

/// The baked texture at [`DETAIL_TEXELS`], made once per process.
pub fn detail_texture() -> &'static [[u16; 2]] {
    static TEXTURE: OnceLock<Vec<[u16; 2]>> = OnceLock::new();
    TEXTURE.get_or_init(|| bake_detail(DETAIL_TEXELS))
}

/// The texture sampled at `uv` as a sampler with linear filtering and repeat addressing
/// samples it, in exact arithmetic (the weights unsnapped): the CPU side of the bound.
pub fn bilinear(texture: &[[u16; 2]], texels: u32, uv: DVec2) -> DVec2 {
    let n = i64::from(texels);
    let texel = |i: i64, j: i64| {
        let t = texture[(j.rem_euclid(n) * n + i.rem_euclid(n)) as usize];
        DVec2::new(
            half::f16::from_bits(t[0]).to_f64(),
            half::f16::from_bits(t[1]).to_f64(),
        )
    };
    let x = uv * f64::from(texels) - 0.5;
    let base = x.floor();
    let w = x - base;
    let (i, j) = (base.x as i64, base.y as i64);
    let row = |j| texel(i, j).lerp(texel(i + 1, j), w.x);
    row(j).lerp(row(j + 1), w.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rnd(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn the_bump_is_near_a_cosine_and_its_derivatives_are_as_stated() {
        let h = 1e-5;
        let (mut worst_cos, mut d1, mut d2) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..20_000 {
            let x = -3.0 + i as f64 * 3.1e-4;
            worst_cos = worst_cos.max((periodic_bump(x) - (std::f64::consts::TAU * x).cos()).abs());
            let first = (periodic_bump(x + h) - periodic_bump(x - h)) / (2.0 * h);
            let second =
                (periodic_bump(x + h) - 2.0 * periodic_bump(x) + periodic_bump(x - h)) / (h * h);
            d1 = d1.max(first.abs());
            d2 = d2.max(second.abs());
        }
        assert!(worst_cos < 0.021, "{worst_cos}");
        // The maxima the bound uses, reached (within the differences' own error).
        assert!(d1 <= 6.0 + 1e-6 && d1 > 5.99, "max |B'| {d1}");
        assert!(d2 <= 48.0 + 1e-3 && d2 > 47.5, "max |B''| {d2}");
    }

    #[test]
    fn the_field_tiles_and_its_maxima_bound_it() {
        let (g, c) = (detail_gradient_max(), detail_curvature_max());
        let m = detail_slope_max();
        let mut seed = 3;
        let (h, h2) = (1e-6, 1e-4);
        let (mut big, mut grad, mut curv) = (DVec2::ZERO, [[0.0f64; 2]; 2], [[0.0f64; 2]; 2]);
        for _ in 0..20_000 {
            let uv = DVec2::new(rnd(&mut seed), rnd(&mut seed));
            let s = detail_slope(uv);
            for shift in [DVec2::X, DVec2::Y, DVec2::new(-3.0, 2.0)] {
                assert!((detail_slope(uv + shift) - s).length() < 1e-12, "{uv}");
            }
            big = big.max(s.abs());
            for (a, axis) in [DVec2::X, DVec2::Y].into_iter().enumerate() {
                let e = axis * h;
                let d = (detail_slope(uv + e) - detail_slope(uv - e)) / (2.0 * h);
                grad[0][a] = grad[0][a].max(d.x.abs());
                grad[1][a] = grad[1][a].max(d.y.abs());
                let e = axis * h2;
                let d2 = (detail_slope(uv + e) - 2.0 * s + detail_slope(uv - e)) / (h2 * h2);
                curv[0][a] = curv[0][a].max(d2.x.abs());
                curv[1][a] = curv[1][a].max(d2.y.abs());
            }
        }
        for j in 0..2 {
            assert!(big[j] <= m[j] * (1.0 + 1e-12), "{big} {m}");
            for a in 0..2 {
                assert!(grad[j][a] <= g[j][a] * (1.0 + 1e-6), "{grad:?} {g:?}");
                // The central second difference is a weighted mean of the curvature over its
                // interval (the field is C²), so it never exceeds the maximum.
                assert!(curv[j][a] <= c[j][a] * (1.0 + 1e-6), "{curv:?} {c:?}");
            }
        }
        // Bounds, not far above what the field reaches (the waves' maxima do not all meet).
        assert!(
            big.x > 0.5 * m.x && grad[0][0] > 0.5 * g[0][0] && curv[0][0] > 0.5 * c[0][0],
            "{big} {grad:?}"
        );
    }

    #[test]
    fn the_resolution_is_the_smallest_within_one_percent() {
        assert_eq!(texels_for(DETAIL_BOUND_FRACTION), DETAIL_TEXELS);
        let e = detail_texture_error(DETAIL_TEXELS, 1.0);
        let m = detail_slope_max();
        eprintln!(
            "detail texture {DETAIL_TEXELS}²: bound {:.3e}, {:.3e} (interpolation {:.2e}, \
             rounding {:.2e}, filtering {:.2e}) of slopes up to {:.3}, {:.3}",
            e.total().x,
            e.total().y,
            e.interpolation.x,
            e.rounding.x,
            e.filtering.x,
            m.x,
            m.y
        );
        // Half the texels would miss the goal: the choice is the bound's, not a round number's.
        let coarser = detail_texture_error(DETAIL_TEXELS / 2, 1.0).total();
        assert!(coarser.x > DETAIL_BOUND_FRACTION * m.x || coarser.y > DETAIL_BOUND_FRACTION * m.y);
    }

    #[test]
    fn the_baked_texture_filtered_exactly_is_the_field_within_its_bound() {
        let texture = detail_texture();
        assert_eq!(texture.len(), (DETAIL_TEXELS * DETAIL_TEXELS) as usize);
        let mut seed = 11;
        let (mut worst, mut ratio) = (DVec2::ZERO, 0.0f64);
        let magnitude = 3.0;
        let bound = detail_texture_error(DETAIL_TEXELS, magnitude).exact_filter();
        for k in 0..200_000 {
            // Anywhere in a few tiles either side, and on texel centres and edges.
            let uv = if k % 4 == 0 {
                let n = f64::from(DETAIL_TEXELS);
                DVec2::new(
                    ((rnd(&mut seed) * 6.0 - 3.0) * n).round() / n,
                    ((rnd(&mut seed) * 6.0 - 3.0) * n).round() / n + 0.5 / n,
                )
            } else {
                DVec2::new(
                    rnd(&mut seed) * 2.0 * magnitude - magnitude,
                    rnd(&mut seed) * 2.0 * magnitude - magnitude,
                )
            };
            let err = (bilinear(texture, DETAIL_TEXELS, uv) - detail_slope(uv)).abs();
            assert!(
                err.x <= bound.x && err.y <= bound.y,
                "{err} > {bound} at {uv}"
            );
            worst = worst.max(err);
            ratio = ratio.max((err / bound).max_element());
        }
        eprintln!("detail texture, exact filter: worst {worst} against {bound}, ratio {ratio:.3}");
        // Not vacuous: the error reaches a good part of the bound.
        assert!(ratio > 0.3, "{ratio}");
    }

    #[test]
    fn a_texture_baked_half_a_texel_off_breaks_the_bound() {
        // Texel centres at i/N instead of (i + ½)/N: the bilinear then errs by up to
        // max|∇f| h/2, far past the bound.
        let n = DETAIL_TEXELS;
        let shifted = bake_detail_at(n, 0.0);
        let bound = detail_texture_error(n, 1.0).total();
        let mut seed = 5;
        let broken = (0..10_000).any(|_| {
            let uv = DVec2::new(rnd(&mut seed), rnd(&mut seed));
            let err = (bilinear(&shifted, n, uv) - detail_slope(uv)).abs();
            err.x > bound.x || err.y > bound.y
        });
        assert!(broken);
    }
}
