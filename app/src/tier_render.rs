//! Quality tiers onto the renderer: every field of [`quality::TierSettings`] mapped onto the
//! renderer's options ([`RenderOptions`]: render scale, clip-map error target), the AR
//! effects' set-up ([`ArConfig`]: which effects run, reflection texture size, the caustic tier
//! and map cells, the flow map as the `flowmap` effect) and the wakes ([`WakeParams`] source
//! spacing, the renderer's per-frame wake source budget). `regatta render --tier`, the budget
//! bench, the desktop app's and the phone's governor all go through [`TierRender`], so a tier
//! means the same frame everywhere; a tier changed on a running renderer
//! ([`TierRender::apply_live`]) draws the frame a renderer built at that tier draws.
//!
//! The overlay detail ([`TierRender::overlay`]) decides which race overlays a tier draws (of
//! those the user chose): the desktop's, the phone's and `regatta render --tier`'s overlays
//! take it (`scene_overlay::OverlaySettings::detail`; what each detail draws is the
//! `scene_overlay::OVERLAYS` table).

use std::sync::Arc;

use effects::EffectSet;
use effects::passes::{ArConfig, EffectsHandle};
use ocean::wake::{Wake, WakeParams};
use quality::{OverlayDetail, Tier, TierSettings};
use render::{RenderOptions, Renderer};

use crate::error::{AppError, AppResult};

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
    /// Which race overlays the tier draws (`scene_overlay::OverlaySettings::detail`).
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

    /// A tier change on a running renderer, the renderer's part: the options and wake source
    /// budget ([`TierRender::apply_to`]) and the AR effects' set-up through their handle
    /// (which effects run, reflection size, caustic tier and map cells:
    /// `EffectsHandle::set_quality`). The wakes, emitted again at the tier's spacing
    /// ([`TierRender::respaced_wake`]), and the Scene panel's switches are the window's and the
    /// phone's one tier path's (`crate::panels::SceneApplier::follow_tier`).
    pub fn apply_live(
        &self,
        gpu: &render::Gpu,
        renderer: &mut Renderer,
        fx: Option<&EffectsHandle>,
    ) {
        self.apply_to(renderer);
        if let Some(fx) = fx {
            fx.set_quality(gpu, &self.ar);
        }
    }

    /// `race`'s wakes at this tier's source spacing in hull radii (the other parameters
    /// `current`'s), when `current` was emitted at another spacing; `None` when it fits or
    /// there is none.
    pub fn respaced_wake(
        &self,
        race: &race::Race,
        current: Option<&Wake>,
    ) -> AppResult<Option<Arc<Wake>>> {
        let Some(w) = current else {
            return Ok(None);
        };
        let spacing = self.wake.spacing / self.wake.hull_radius * w.params.hull_radius;
        if (w.params.spacing - spacing).abs() <= 1e-9 * spacing {
            return Ok(None);
        }
        let params = WakeParams {
            spacing,
            ..w.params
        };
        crate::wakes::race_wake(race, params).map(|w| Some(Arc::new(w)))
    }

    /// The race's wakes with this tier's source spacing.
    pub fn race_wake(&self, race: &race::Race) -> AppResult<Arc<Wake>> {
        crate::wakes::race_wake(race, self.wake).map(Arc::new)
    }
}

/// `--tier NAME`: a tier by name; the error lists the names.
pub fn parse_tier(name: &str) -> AppResult<Tier> {
    Tier::from_name(name.trim()).ok_or_else(|| {
        let names: Vec<&str> = Tier::ALL.iter().map(|t| t.name()).collect();
        AppError::new(format!(
            "--tier {} is not a quality tier; the tiers are: {}",
            input::quote(name),
            names.join(", ")
        ))
    })
}
