//! One race scene's set-up (ripgrep's `HiArgs` idea): validated options (a race and a sea, a
//! profile, a tier, AR effects, wakes, the water's look, overlays) become the race world and a
//! renderer with its effects, wakes and overlays, in this one place. The desktop window, the
//! phone core, `regatta render` (still, clip and `--replay`), `phone-sim` (through the phone
//! core) and the bench build their race renderer here; before, five copies of it had drifted
//! (a tier's renderer set no water look, the clip's and the window's options were written
//! out again).

use std::path::PathBuf;
use std::sync::Arc;

use effects::EffectSet;
use effects::passes::{ArConfig, EffectsHandle};
use ocean::wake::Wake;
use quality::Tier;
use render::water_look::WaterLook;
use render::{Gpu, RenderOptions, Renderer};

use crate::error::{AppError, AppResult};
use crate::scene_overlay::OverlaySettings;
use crate::tier_render::TierRender;
use crate::world::RaceWorld;

/// Who the renderer draws for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Profile {
    /// The desktop window: full resolution, still frames kept, no GPU timestamps waited on.
    Desktop,
    /// The phone: [`PHONE_RENDER_SCALE`], every frame drawn (the camera image changes).
    Phone,
    /// A picture written to a file (`regatta render`, clips, tests): full resolution, the GPU
    /// time measured for the frame record.
    Picture,
}

/// The phone's scene is drawn at this fraction of the screen per side and stretched onto it
/// (panels are painted at full resolution over it). From the budget bench (docs/phone.md): at ½
/// the Pixel 2 XL reaches 60 fps on paper, at full size about 17.
pub const PHONE_RENDER_SCALE: f64 = 0.5;

impl Profile {
    /// The renderer's options for this profile, before any tier.
    pub fn options(self) -> RenderOptions {
        match self {
            Profile::Desktop => RenderOptions {
                measure_gpu_time: false,
                keep_still_frames: true,
                ..Default::default()
            },
            Profile::Phone => RenderOptions {
                measure_gpu_time: false,
                render_scale: PHONE_RENDER_SCALE,
                ..Default::default()
            },
            Profile::Picture => RenderOptions::default(),
        }
    }
}

/// The validated options of a race scene, and what they make.
#[derive(Debug, Clone)]
pub struct RaceSetup {
    /// The renderer's options before a tier: the profile's, with a chosen error target
    /// (`--error-px`).
    pub options: RenderOptions,
    /// What a quality tier sets (render scale, error target, AR effects and their sizes, wake
    /// spacing and budget; [`RaceSetup::with_tier`] puts it over `options`), or none.
    pub tier: Option<TierRender>,
    /// AR effects over the scene's synthetic camera frame (`regatta render --effects`), when no
    /// tier chooses them; none: the water only.
    pub effects: Option<EffectSet>,
    /// Whether the boats' wakes are drawn.
    pub wakes: bool,
    /// The open sea's body: its water type's colour (`render::view_light`).
    pub sea_water: WaterLook,
    /// The water over a table the AR effects draw (its type, depth and turbidity).
    pub table_water: WaterLook,
    /// The race overlays drawn over a picture.
    pub overlays: OverlaySettings,
}

impl RaceSetup {
    /// The defaults of `profile`: no tier, no AR effects, wakes, the default waters, every
    /// overlay.
    pub fn new(profile: Profile) -> RaceSetup {
        RaceSetup {
            options: profile.options(),
            tier: None,
            effects: None,
            wakes: true,
            sea_water: WaterLook::default(),
            table_water: ArConfig::default().water,
            overlays: OverlaySettings::default(),
        }
    }

    /// The race world of `race` on `sea` (cut to the waves the renderer draws).
    pub fn world(race: race::Race, sea: ocean::WaveSet) -> RaceWorld {
        RaceWorld::new(race, super::inputs::drawable_sea(sea))
    }

    /// The race world of the race files `race` (the embedded sample race without any) on the
    /// sea file `sea` (the embedded default sea without it): [`RaceSetup::world`] of what
    /// [`load_race`](super::inputs::load_race) and [`load_sea`](super::inputs::load_sea)
    /// read. The desktop window, the phone's shells and `regatta render`'s clip start here.
    pub fn load_world(race: &[PathBuf], sea: Option<&PathBuf>) -> AppResult<RaceWorld> {
        let race = super::inputs::load_race(race)?;
        let sea = super::inputs::load_sea(sea)?;
        Ok(RaceSetup::world(race, sea))
    }

    /// The renderer's options: the tier's, else [`RaceSetup::options`].
    pub fn render_options(&self) -> RenderOptions {
        self.tier.as_ref().map_or(self.options, |t| t.options)
    }

    /// The same set-up at `tier`, over its options.
    pub fn with_tier(mut self, tier: Tier) -> RaceSetup {
        self.tier = Some(TierRender::over(
            tier,
            self.options,
            ArConfig::default(),
            ocean::wake::WakeParams::default(),
        ));
        self
    }

    /// A picture's set-up at `tier`.
    pub fn at_tier(tier: Tier) -> RaceSetup {
        RaceSetup::new(Profile::Picture).with_tier(tier)
    }

    /// The race's wakes as drawn: none without wakes, else emitted at the tier's source spacing
    /// (the default spacing without a tier).
    pub fn wake(&self, race: &race::Race) -> AppResult<Option<Arc<Wake>>> {
        if !self.wakes {
            return Ok(None);
        }
        match &self.tier {
            Some(t) => t.race_wake(race).map(Some),
            None => crate::world::race_wake(race).map(Some),
        }
    }

    /// [`RaceSetup::wake`], or none (logged) when the wakes cannot be built: the apps draw on.
    pub fn wake_or_none(&self, race: &race::Race) -> Option<Arc<Wake>> {
        self.wake(race)
            .map_err(|e| log::warn!("regatta: {e}; drawing no wakes"))
            .ok()
            .flatten()
    }

    /// The race renderer for `format`: the options, the tier's wake source budget, `wake` (from
    /// [`RaceSetup::wake`], or a table's scaled one) and the open sea's water.
    pub fn renderer(
        &self,
        gpu: &Gpu,
        format: wgpu::TextureFormat,
        wake: Option<Arc<Wake>>,
    ) -> Renderer {
        let mut renderer = Renderer::new(gpu, format, self.render_options());
        if let Some(t) = &self.tier {
            t.apply_to(&mut renderer);
        }
        renderer.set_wake(wake);
        renderer.set_water_look(self.sea_water);
        renderer
    }

    /// The AR effects over `scene`'s synthetic camera frame on `renderer` (`size` pixels): the
    /// tier's, else [`RaceSetup::effects`], over the table's water; none without either.
    pub fn scene_effects(
        &self,
        renderer: &mut Renderer,
        gpu: &Gpu,
        scene: &render::Scene,
        size: [u32; 2],
    ) -> Option<EffectsHandle> {
        let cfg = match (&self.tier, self.effects) {
            (Some(t), _) => t.ar.clone(),
            (None, Some(effects)) => ArConfig {
                effects,
                ..ArConfig::default()
            },
            (None, None) => return None,
        };
        let table_depth = cfg.table_depth;
        let h = effects::passes::add_scene_effects_with(renderer, gpu, scene, size, cfg);
        // The synthetic table stays where its image shows it; the water's optics are asked.
        h.set_water(self.table_water, table_depth);
        Some(h)
    }

    /// A picture's renderer for `scene` at `size` ([`render::OFFSCREEN_FORMAT`]): `race`'s
    /// wakes (none without a race), and the AR effects over the scene's synthetic camera frame
    /// ([`RaceSetup::scene_effects`]).
    pub fn scene_renderer(
        &self,
        gpu: &Gpu,
        race: Option<&race::Race>,
        scene: &render::Scene,
        size: [u32; 2],
    ) -> AppResult<(Renderer, Option<EffectsHandle>)> {
        let wake = match race {
            Some(race) => self.wake(race)?,
            None => None,
        };
        let mut renderer = self.renderer(gpu, render::OFFSCREEN_FORMAT, wake);
        let fx = self.scene_effects(&mut renderer, gpu, scene, size);
        Ok((renderer, fx))
    }

    /// A picture's renderer for `scene` at `size` drawn at `tier` (the bench's and the tier
    /// tests'): its options and wake source budget, `race`'s wakes at the tier's spacing (none
    /// without a race), and the tier's AR effects over the scene's synthetic camera frame.
    pub fn tier_renderer(
        tier: &TierRender,
        gpu: &Gpu,
        race: Option<&race::Race>,
        scene: &render::Scene,
        size: [u32; 2],
    ) -> AppResult<(Renderer, EffectsHandle)> {
        let setup = RaceSetup {
            tier: Some(tier.clone()),
            ..RaceSetup::new(Profile::Picture)
        };
        let (renderer, fx) = setup.scene_renderer(gpu, race, scene, size)?;
        let fx = fx.ok_or_else(|| AppError::new("a tier's renderer has its AR effects"))?;
        Ok((renderer, fx))
    }

    /// `world`'s race drawn in `scene` headless with [`RaceSetup::overlays`] (the trails'
    /// manoeuvre marks from the race's debrief when trails are shown): a picture and its frame
    /// record.
    pub fn picture(
        &self,
        gpu: &Gpu,
        renderer: &mut Renderer,
        world: &RaceWorld,
        scene: &render::Scene,
        size: [u32; 2],
    ) -> AppResult<(image::RgbaImage, render::FrameReport)> {
        let debrief =
            crate::scene_overlay::manoeuvres::debrief_if_shown(&world.race, &self.overlays);
        let drawn = (&world.race, debrief.as_ref());
        crate::scene_overlay::render_headless(gpu, renderer, drawn, scene, size, &self.overlays)
            .map_err(|e| AppError::new(format!("cannot render: {e}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shells' one world: the embedded race and the embedded sea as `assets/` hold them
    /// (the default sea's waves, counted in its own JSON, all under the drawn cap, so none cut),
    /// and a race file that is not there refused with its name, not a panic.
    #[test]
    fn load_world_reads_the_embedded_inputs_or_names_the_missing_file() {
        let world = RaceSetup::load_world(&[], None).unwrap();
        let json: serde_json::Value = serde_json::from_str(ocean::DEFAULT_SEA_JSON).unwrap();
        let waves = json["waves"].as_array().unwrap().len();
        assert!(waves <= super::super::inputs::MAX_DRAWN_WAVES);
        assert_eq!(world.given_sea.waves.len(), waves);
        assert_eq!(world.race.boats.len(), race::Race::sample().boats.len());
        let missing = PathBuf::from("no-such-race.gpx");
        let e = RaceSetup::load_world(std::slice::from_ref(&missing), None).unwrap_err();
        assert!(e.to_string().contains("no-such-race.gpx"), "{e}");
    }
}
