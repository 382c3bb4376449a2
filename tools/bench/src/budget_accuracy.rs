//! What each quality tier costs in accuracy, measured against the f64 references:
//!
//! - mesh: the clip-map's worst level error bound of the frame (`render::mesh_error`, f64),
//!   in screen pixels (the drawn frame's pixels over the render scale);
//! - wakes: the Kelvin wake's RMS height error against the Havelock integral at the tier's
//!   source spacing (relative to the reference's RMS, the wakes bench's measurement), and the
//!   height error bound of the sources the tier's budget drops in the frame;
//! - caustics: the RMS error of the light on the table against the converged area-ratio map
//!   (512² surface grid) of the effects bench's demo table: the tier's map, the cheap
//!   overhead-sun tier (the AR water thesis's formula as `shaders/caustics.wgsl` applies it), or flat
//!   light where caustics are off.

use effects::caustics::{MAX_INTENSITY, area_ratio, cheap_caustic_light};
use effects::demo_table_scene;
use effects::passes::{ArConfig, caustic_region};

use crate::BenchContext;
use quality::Tier;
use regatta::error::AppResult;

/// One tier's accuracy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TierAccuracy {
    /// Worst clip-map level error bound, screen pixels.
    pub mesh_px: f64,
    /// Wake RMS error / reference RMS at the tier's spacing.
    pub wake_rel_rms: f64,
    /// Bound of the wake height error of the sources the budget dropped, m.
    pub wake_drop_bound_m: f64,
    /// RMS error of the caustic light (1 = flat water's light).
    pub caustic_rms: f64,
}

/// The caustic light's RMS error of `tier` on the demo table (see the module docs).
pub fn caustic_rms(tier: Tier) -> f64 {
    let s = tier.settings();
    let scene = demo_table_scene(40.0);
    let cfg = ArConfig::default();
    let size = [640, 480];
    let region = caustic_region(&scene, size, &cfg);
    let out = s.caustic_resolution.1;
    let map = |src: usize| {
        area_ratio(
            &scene.sea,
            scene.t,
            -scene.sun,
            cfg.table_depth,
            region,
            src,
            out,
        )
    };
    let reference = map(512);
    let shown = |v: f64| v.clamp(0.0, MAX_INTENSITY);
    let light: Vec<f64> = if !s.effects.contains(&"caustics") {
        vec![1.0; reference.intensity.len()]
    } else if s.cheap_caustics {
        // The cheap tier at each cell's centre, the normal of the surface above it.
        let cell = region.size / out as f64;
        (0..out * out)
            .map(|k| {
                let (i, j) = (k % out, k / out);
                let x = region.min[0] + (i as f64 + 0.5) * cell;
                let z = region.min[1] + (j as f64 + 0.5) * cell;
                let n = scene.sea.surface([x, z], scene.t).normal;
                cheap_caustic_light(glam::DVec3::from(n))
            })
            .collect()
    } else {
        map(s.caustic_resolution.0).intensity
    };
    let n = light.len() as f64;
    (light
        .iter()
        .zip(&reference.intensity)
        .map(|(a, b)| (shown(*a) - shown(*b)).powi(2))
        .sum::<f64>()
        / n)
        .sqrt()
}

/// `tier`'s accuracy in a frame whose record is `report` (drawn at the tier's render scale).
pub fn tier_accuracy(
    ctx: &BenchContext,
    tier: Tier,
    report: &render::FrameReport,
) -> AppResult<TierAccuracy> {
    let s = tier.settings();
    let mesh_drawn = report
        .clipmap
        .per_level
        .iter()
        .map(|l| l.error_bound_px)
        .fold(0.0, f64::max);
    Ok(TierAccuracy {
        mesh_px: mesh_drawn / s.render_scale,
        wake_rel_rms: super::wakes::spacing_relative_rms(ctx, s.wake_spacing_radii)?,
        wake_drop_bound_m: report.wakes.as_ref().map_or(0.0, |w| w.drop_bound_m),
        caustic_rms: caustic_rms(tier),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The area-ratio map converges to its reference and the cheap tier does not: richer
    /// caustics are more accurate, and caustics off errs by the whole caustic signal.
    #[test]
    fn richer_caustic_tiers_err_less() {
        let e: Vec<f64> = Tier::ALL.iter().map(|t| caustic_rms(*t)).collect();
        // low: off; medium: cheap; high and ultra: the area-ratio map.
        assert!(e[2] < e[1] && e[2] < e[0], "{e:?}");
        assert!(e[3] <= e[2] * 1.0001, "{e:?}");
        assert!(e.iter().all(|v| v.is_finite() && *v >= 0.0), "{e:?}");
    }
}
