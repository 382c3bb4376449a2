//! The sea's longest waves summed per vertex and interpolated to the pixels.
//!
//! A water pixel forms the surface's frame (`surface_frame` in `shaders/render/common.wgsl`)
//! from five sums over the frame's waves, sorted by wavenumber: ∂x/∂x, ∂x/∂z, ∂z/∂z (the
//! horizontal map's Jacobian terms, each k A D D · −sin θ) and ∂y/∂x, ∂y/∂z (k A D · cos θ).
//! A wave much longer than the clip-map's cells is nearly linear across a triangle, so its
//! terms interpolated from the triangle's vertices are nearly its terms at the pixel: the
//! compute stage sums the first `first_pixel_wave` waves of each level per vertex
//! (`vertex_slope_sums`), the vertex stage hands the five sums to the pixels, and a pixel's
//! wave loops start from them at the first wave the vertices did not sum. Everything else
//! the pixel does is unchanged.
//!
//! **Error.** A term c·sin(k D·x + θ₀) (or cos) interpolated linearly over a triangle errs by
//! at most c k² L²/8, where L is the triangle's extent along D (the clip-map's own bound for
//! its heights, `clipmap` module docs: a Jensen gap of a function of D·x whose second
//! derivative is at most c k², at most half of it times the variance of D·x over the
//! vertices, ≤ L²/4). L is taken on the next coarser level's lattice: in its morph band a
//! level's triangles slide into that level's, and a triangle's extent is convex in the
//! morph. Each level takes waves, longest first, while the sum of those bounds over its
//! waves, with c the largest of the wave's five coefficients, stays within
//! [`VERTEX_SLOPE_BOUND`]: each of the five sums a pixel forms errs by at most that much
//! (`tests::the_interpolated_sums_stay_within_their_bound` measures it on real meshes,
//! morph bands included: the worst error met is 10–100 % of its level's bound). A gradient
//! off by 0.01 turns the normal by at most 0.57°.
//!
//! **The pixel filter.** A pixel fades a wave from k·footprint = π/4 (the footprint: the pixel's
//! size on the rest plane), but adds the waves its vertices summed whole. So a level takes a
//! wave only where no pixel of the level would fade it: k·[`level_footprints`] < π/4, the bound
//! being the widest pixel of a flat sea at the level's farthest corner seen from above the
//! highest crest. Facets that the waves turn away from the eye span more than a flat sea's
//! pixel; in the tests' three views 0.004–0.3 % of the water's fragments are such facets
//! (`tests::few_pixels_lose_the_filter_of_the_vertex_waves`).
//!
//! **Cost.** A pixel's wave loops take about 26 operations a wave; in the budget model's OPPO
//! A54 `ultra` frame a pixel sums 1.8 waves fewer on average (3 in the nearest levels), a
//! vertex about one more (docs/quality.md).

use std::f64::consts::SQRT_2;

use glam::{DVec2, DVec3};

use crate::clipmap::{ClipMapConfig, ErrorTarget, LevelPlan, extent_along, height_over_crests};

/// The most each of the five sums a pixel forms may err by coming from its triangle's
/// vertices instead of from its own rest point (see the module docs).
pub const VERTEX_SLOPE_BOUND: f64 = 0.01;

/// What the vertices of one clip-map level sum of the sea's slopes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexWaves {
    /// The waves 0..first_pixel_wave (the frame's GPU order, longest first) are summed per
    /// vertex; a pixel sums the rest.
    pub first_pixel_wave: u32,
    /// The bound of each interpolated sum's error at this level: Σ c k² L²/8 over those waves.
    pub bound: f64,
}

/// Each level's [`VertexWaves`] for the frame's `waves` (sorted by wavenumber, longest first)
/// on `clipmap`'s lattice, where level l's pixels are at most `footprints[l]` metres across
/// on the rest plane ([`level_footprints`]): a level takes a wave only while the pixel filter
/// leaves it whole in every pixel (k·footprint < π/4) and the sums' bound holds.
pub fn vertex_waves(
    clipmap: &ClipMapConfig,
    levels: &[LevelPlan],
    footprints: &[f64],
    waves: &[ocean::GpuWave],
) -> Vec<VertexWaves> {
    levels
        .iter()
        .enumerate()
        .map(|(l, level)| {
            // In the morph band a level's triangles slide into the coarser level's (each one
            // degenerate or inside a coarse triangle on the border), and a triangle's extent
            // along any direction is convex in the morph: at most the coarser cell's.
            let cell = levels
                .get(l + 1)
                .map_or(level.cell, |c| c.cell.max(level.cell));
            let mut out = VertexWaves {
                first_pixel_wave: 0,
                bound: 0.0,
            };
            let footprint = footprints.get(l).copied().unwrap_or(f64::INFINITY);
            for w in waves {
                let bound = out.bound + interpolation_bound(clipmap, cell, w);
                // A NaN footprint or bound takes no wave.
                let whole = f64::from(w.k) * footprint < std::f64::consts::FRAC_PI_4;
                if !whole || bound.is_nan() || bound > VERTEX_SLOPE_BOUND {
                    break;
                }
                out = VertexWaves {
                    first_pixel_wave: out.first_pixel_wave + 1,
                    bound,
                };
            }
            out
        })
        .collect()
}

/// Each level's widest pixel on the rest plane, metres, for an eye at world `eye` over a sea
/// whose waves lift and move it at most `lift` metres: at the level's farthest point, its
/// square's corner pushed out by `lift`, seen from above the highest crest
/// ([`footprint_bound`]).
pub fn level_footprints(
    clipmap: &ClipMapConfig,
    levels: &[LevelPlan],
    target: &ErrorTarget,
    eye: DVec3,
    lift: f64,
) -> Vec<f64> {
    let eye_xz = DVec2::new(eye.x, eye.z);
    let height = height_over_crests(eye.y, lift);
    (0..levels.len())
        .map(|l| {
            let centre = clipmap.centre(l as u32, eye_xz);
            let across = (centre - eye_xz).length() + levels[l].half_extent * SQRT_2;
            let distance = across.hypot(eye.y.abs() + lift);
            footprint_bound(target, distance, height)
        })
        .collect()
}

/// The most a pixel of a level whose farthest point is `distance` metres from an eye `height`
/// metres above the highest crest spans on the rest plane, metres: a pixel of `target` spans
/// metres_per_pixel(d) across the view at distance d and d/h times that along it, where the
/// view meets a flat sea at a grazing angle whose sine is h/d. Facets that the waves turn
/// away from the eye span more (the tests count them).
fn footprint_bound(target: &ErrorTarget, distance: f64, height: f64) -> f64 {
    target.metres_per_pixel(distance) * distance / height.max(1e-9)
}

/// The bound c k² L²/8 of wave `w`'s terms interpolated over a level of `cell` metres: c its
/// largest coefficient, L the lattice triangles' extent along its direction.
fn interpolation_bound(clipmap: &ClipMapConfig, cell: f64, w: &ocean::GpuWave) -> f64 {
    let k = f64::from(w.k);
    let c = [w.slope_xx, w.slope_xz, w.slope_zz, w.slope_x, w.slope_z]
        .iter()
        .map(|c| f64::from(c.abs()))
        .fold(0.0, f64::max);
    if k.is_nan() || k <= 0.0 {
        return if c > 0.0 { f64::INFINITY } else { 0.0 };
    }
    let d = DVec2::new(f64::from(w.wavevector[0]), f64::from(w.wavevector[1])) / k;
    let d = clipmap.to_lattice(d);
    let l = extent_along([d.x, d.y]) * cell;
    c * k * k * l * l / 8.0
}

/// The uniform's `vertex_waves` (`Frame` in `shaders/render/common.wgsl`): level l's first
/// pixel wave at [l / 4][l % 4] (16 levels at most, as the level masks).
pub fn uniform_counts(per_level: &[VertexWaves]) -> [[u32; 4]; 4] {
    let mut out = [[0u32; 4]; 4];
    for (l, v) in per_level.iter().enumerate().take(16) {
        out[l / 4][l % 4] = v.first_pixel_wave;
    }
    out
}

/// The five sums of waves `waves[..n]` at local rest point `p`, f64: (∂x/∂x, ∂x/∂z, ∂z/∂z,
/// ∂y/∂x, ∂y/∂z), as `with_wave` in WGSL adds them (∂x/∂x and ∂z/∂z start at 1).
pub fn slope_sums(waves: &[ocean::GpuWave], n: usize, p: DVec2) -> [f64; 5] {
    let mut s = [1.0, 0.0, 1.0, 0.0, 0.0];
    for w in waves.iter().take(n) {
        let theta = f64::from(w.wavevector[0]) * p.x
            + f64::from(w.wavevector[1]) * p.y
            + f64::from(w.phase0);
        let (sn, cs) = theta.sin_cos();
        s[0] -= f64::from(w.slope_xx) * sn;
        s[1] -= f64::from(w.slope_xz) * sn;
        s[2] -= f64::from(w.slope_zz) * sn;
        s[3] += f64::from(w.slope_x) * cs;
        s[4] += f64::from(w.slope_z) * cs;
    }
    s
}

#[cfg(test)]
mod tests;
