//! Quality tiers onto the renderer: every field of [`quality::TierSettings`] mapped onto the
//! renderer's options ([`RenderOptions`]: render scale, clip-map error target), the AR
//! effects' set-up ([`ArConfig`]: which effects run, reflection texture size, the caustic tier
//! and map cells, the flow map as the `flowmap` effect) and the wakes ([`WakeParams`] source
//! spacing, the renderer's per-frame wake source budget). `regatta render --tier`, the budget
//! bench and the desktop app's governor all go through [`TierRender`], so a tier means the
//! same frame everywhere.
//!
//! The overlay detail is carried for the race-overlay passes; they read
//! [`TierRender::overlay`] when they land (nothing draws overlays through the renderer yet).

use std::sync::Arc;

use effects::EffectSet;
use effects::passes::{ArConfig, EffectsHandle};
use ocean::wake::{Wake, WakeParams};
use quality::{OverlayDetail, Tier, TierSettings};
use render::{RenderOptions, Renderer};

use crate::error::{CliError, CliResult};

/// What one tier sets on the renderer.
#[derive(Debug, Clone, PartialEq)]
pub struct TierRender {
    pub tier: Tier,
    /// Render scale and clip-map error target (GPU timing as the base had it).
    pub options: RenderOptions,
    /// Effects, reflection size, caustic tier and map cells (the rest as the base had it).
    pub ar: ArConfig,
    /// The wake model with the tier's source spacing.
    pub wake: WakeParams,
    /// Most wake sources a frame draws.
    pub wake_source_budget: usize,
    pub overlay: OverlayDetail,
}

impl TierRender {
    /// `tier` over the defaults.
    pub fn of(tier: Tier) -> TierRender {
        TierRender::over(
            tier,
            RenderOptions::default(),
            ArConfig::default(),
            WakeParams::default(),
        )
    }

    /// `tier`'s settings over `options`, `ar` and `wake` (fields a tier does not set are kept).
    pub fn over(tier: Tier, options: RenderOptions, ar: ArConfig, wake: WakeParams) -> TierRender {
        let s: TierSettings = tier.settings();
        let effects = s
            .effects
            .iter()
            .filter_map(|name| effects::Effect::from_name(name))
            .fold(EffectSet::NONE, EffectSet::with);
        TierRender {
            tier,
            options: RenderOptions {
                render_scale: s.render_scale,
                error_px: s.error_px,
                ..options
            },
            ar: ArConfig {
                effects,
                reflection_fraction: s.reflection_fraction,
                cheap_caustics: s.cheap_caustics,
                caustic_resolution: s.caustic_resolution,
                ..ar
            },
            wake: WakeParams {
                spacing: s.wake_spacing_radii * wake.hull_radius,
                ..wake
            },
            wake_source_budget: s.wake_source_budget as usize,
            overlay: s.overlay,
        }
    }

    /// Set the renderer's options and wake source budget to this tier's (the AR effects are
    /// added with [`TierRender::ar`]; the wake is built with [`TierRender::wake`]).
    pub fn apply_to(&self, renderer: &mut Renderer) {
        renderer.options.render_scale = self.options.render_scale;
        renderer.options.error_px = self.options.error_px;
        renderer.set_wake_source_budget(self.wake_source_budget);
        renderer.invalidate();
    }

    /// A renderer for `scene` at `size` drawn at this tier: its options and wake source
    /// budget, `race`'s wakes at the tier's spacing (none without a race), and the tier's AR
    /// effects over the scene's synthetic camera frame.
    pub fn renderer(
        &self,
        gpu: &render::Gpu,
        race: Option<&race::Race>,
        scene: &render::Scene,
        size: [u32; 2],
    ) -> CliResult<(Renderer, EffectsHandle)> {
        let mut renderer = Renderer::new(gpu, render::OFFSCREEN_FORMAT, self.options);
        self.apply_to(&mut renderer);
        if let Some(race) = race {
            renderer.set_wake(Some(self.race_wake(race)?));
        }
        let fx = effects::passes::add_scene_effects_with(
            &mut renderer,
            gpu,
            scene,
            size,
            self.ar.clone(),
        );
        Ok((renderer, fx))
    }

    /// The race's wakes with this tier's source spacing.
    pub fn race_wake(&self, race: &race::Race) -> CliResult<Arc<Wake>> {
        crate::wakes::race_wake(race, self.wake).map(Arc::new)
    }
}

/// `--tier NAME`: a tier by name; the error lists the names.
pub fn parse_tier(name: &str) -> CliResult<Tier> {
    Tier::from_name(name.trim()).ok_or_else(|| {
        let names: Vec<&str> = Tier::ALL.iter().map(|t| t.name()).collect();
        CliError::new(format!(
            "--tier {} is not a quality tier; the tiers are: {}",
            input::quote(name),
            names.join(", ")
        ))
    })
}

#[cfg(test)]
mod tests;
