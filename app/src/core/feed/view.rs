//! The race on a camera feed's table (the window's `regatta run --replay DIR`, and `regatta
//! render --replay` through [`TableFrame`](super::TableFrame)): a recorded feed (replay folder
//! or TUM RGB-D, `crates/ar`) or the synthetic one as the background.
//!
//! The table maps to the race as on the phone (`core::table`): the race's bounds (its tracks
//! and marks) are fitted onto the table's extent with a margin, the table's centre is the
//! bounds' centre, and the table top lies `table_depth` race metres below the sea's rest level
//! (the refraction effect's table). The water drawn is cut to the table (the scene's play area
//! becomes the table's rectangle in race metres), so it covers the table to its edges. The feed's camera poses, mapped the same way
//! (`core::camera_frame`), become the render camera; its image, through the window's crop, the
//! background.
//!
//! The first feed frame builds the renderer with the effect passes (`add_effect_passes`); each
//! later frame, and a resized window, goes through the returned `EffectsHandle`
//! (`set_backdrop`: the image is written into the same textures, RGBA as it is, YUV planes
//! converted in the shader), so nothing is rebuilt per frame.

use std::sync::Arc;

use ar::CameraFrame;
use ar::arcore::CoursePlacement;
use effects::backdrop::Backdrop;
use effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use glam::{DVec2, DVec3};
use render::{Camera, Renderer, Scene};

use crate::core::camera_frame::{backdrop_of, fill_view, physical_camera};
use crate::core::table::{boats_as_models, fit_on_table, table_area};

use super::CameraFeed;
use crate::error::{AppError, AppResult};

/// The feed, where it maps in the race, and which frame the renderer holds.
pub struct FeedView {
    source: CameraFeed,
    /// The frame the effects show, and the window size it was fitted to.
    shown: Option<(usize, [u32; 2])>,
    /// The effects' camera frame, once the renderer has them.
    effects: Option<EffectsHandle>,
    /// The current frame's render camera.
    camera: Option<Camera>,
    map: Option<CoursePlacement>,
    /// The table's rectangle in race metres (`core::table::table_area`): the water drawn.
    table_area: Option<[f64; 4]>,
    /// The effects drawn over the feed (all of them in the window; `--effects` for
    /// `regatta render --replay`).
    config: ArConfig,
    /// The real sea: its water type, depth (race metres: the table lies that deep under the
    /// race's sea; on the table `depth × scale`) and turbidity.
    water: render::water_look::WaterLook,
    /// The wake handed in (the boats' own, or none) and what the renderer draws for it on this
    /// table: Froude-scaled for the models ([`crate::wakes::table_wake`]), per map scale.
    table_wake: Option<TableWake>,
}

/// A wake as handed in, the table's scale it was fitted for, and the wake drawn.
struct TableWake {
    given: Option<Arc<ocean::wake::Wake>>,
    scale: f64,
    drawn: Option<Arc<ocean::wake::Wake>>,
}

impl FeedView {
    /// Opens a replay or TUM folder, or the synthetic feed for [`SYNTH`](super::SYNTH).
    pub fn open(dir: &std::path::Path) -> AppResult<Self> {
        let source = CameraFeed::open(dir)?;
        Ok(FeedView {
            source,
            shown: None,
            effects: None,
            camera: None,
            map: None,
            table_area: None,
            config: ArConfig::default(),
            water: render::water_look::WaterLook::default(),
            table_wake: None,
        })
    }

    /// The same feed with these effects over its image.
    pub fn with_effects(mut self, effects: effects::EffectSet) -> Self {
        self.config.effects = effects;
        self
    }

    /// The same feed drawn at a quality tier's effect set-up (`TierRender::ar`: which effects
    /// run, reflection size, caustic tier and map cells; the water and table stay the feed's).
    pub fn with_quality(mut self, ar: &ArConfig) -> Self {
        self.config.effects = ar.effects;
        self.config.reflection_fraction = ar.reflection_fraction;
        self.config.cheap_caustics = ar.cheap_caustics;
        self.config.caustic_resolution = ar.caustic_resolution;
        self
    }

    /// The water's look on the table from the next frame on (the panel's setter; ranges as
    /// `WaterLook::check`, out-of-range values are clamped into them).
    pub fn set_water(&mut self, water: render::water_look::WaterLook) {
        use render::water_look::{MAX_DEPTH_M, MAX_TURBIDITY_NTU, MIN_DEPTH_M};
        let clamp =
            |v: f64, lo: f64, hi: f64, or: f64| if v.is_finite() { v.clamp(lo, hi) } else { or };
        let base = render::water_look::WaterLook::default();
        self.water = render::water_look::WaterLook {
            water_type: water.water_type,
            depth_m: clamp(water.depth_m, MIN_DEPTH_M, MAX_DEPTH_M, base.depth_m),
            turbidity_ntu: clamp(
                water.turbidity_ntu,
                0.0,
                MAX_TURBIDITY_NTU,
                base.turbidity_ntu,
            ),
        };
        // The next frame fits the table anew (its depth) and hands the water to the effects.
        self.shown = None;
    }

    /// The water's look on the table.
    pub fn water(&self) -> render::water_look::WaterLook {
        self.water
    }

    /// The effect passes' handle, once the first frame built them (the Scene panel's
    /// switches go through it).
    pub fn effects_handle(&self) -> Option<&EffectsHandle> {
        self.effects.as_ref()
    }

    /// How many frames the feed has.
    pub fn len(&self) -> usize {
        self.source.len()
    }

    /// Whether the feed has no frames (a feed that opened always has some).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Where the race stands on the table (race metres → AR metres), once a frame is prepared.
    pub fn placement(&self) -> Option<CoursePlacement> {
        self.map
    }

    /// Puts `scene` on the table: the feed's camera, boats drawn as table-sized models, the
    /// water cut to the table (after [`FeedView::prepare`]).
    pub fn apply(&self, scene: &mut Scene) {
        if let (Some(c), Some(m), Some(area)) = (self.camera, self.map, self.table_area) {
            scene.camera = c;
            boats_as_models(scene, &m);
            scene.play_area = area;
        }
    }

    /// The wake to draw on the table of `map` for `given`, and whether it differs from what
    /// was drawn before (then the renderer must take it).
    fn wake_for_table(
        &mut self,
        given: Option<Arc<ocean::wake::Wake>>,
        map: &CoursePlacement,
    ) -> (Option<Arc<ocean::wake::Wake>>, bool) {
        // Race metres per table metre.
        let scale = 1.0 / map.course_to_table;
        let same = |a: &Option<Arc<_>>, b: &Option<Arc<_>>| match (a, b) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        if let Some(tw) = &self.table_wake
            && tw.scale == scale
            && same(&tw.given, &given)
        {
            return (tw.drawn.clone(), false);
        }
        // Boats are drawn as table models where a model is longer than the hull itself.
        let model = crate::core::table::model_boat_length(map);
        let drawn = match &given {
            Some(w) if model > crate::world::BOAT_LENGTH_M => {
                Some(crate::wakes::table_wake(w, model, scale))
            }
            _ => given.clone(),
        };
        self.table_wake = Some(TableWake {
            given,
            scale,
            drawn: drawn.clone(),
        });
        (drawn, true)
    }

    /// Picks the feed frame for `played_s`, the wall seconds the feed has played (the shell's
    /// clock: the feed names none); when it or the window's `size` changed, hands
    /// it to the effects. The first time, `renderer` is built anew (for `format`, with `wake`)
    /// with the effect passes; later frames only go through their handle. `race_bounds`
    /// (`RaceWorld::race_bounds`) are what is fitted on the table.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare(
        &mut self,
        gpu: &render::Gpu,
        renderer: &mut Renderer,
        format: wgpu::TextureFormat,
        wake: Option<Arc<ocean::wake::Wake>>,
        race_bounds: [f64; 4],
        size: [u32; 2],
        played_s: f64,
    ) -> AppResult {
        let i = self.source.index_at(played_s);
        // The window's renderer: a new camera image is drawn even while the scene stands
        // still (the background pass's revision changes with it).
        let setup = crate::setup::RaceSetup::new(crate::setup::Profile::Desktop);
        self.prepare_frame(gpu, renderer, format, &setup, wake, race_bounds, size, i)
    }

    /// [`FeedView::prepare`] for feed frame `i` (below [`FeedView::len`]), a renderer built
    /// by `setup` the first time: what `regatta render --replay --frame i` draws.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare_frame(
        &mut self,
        gpu: &render::Gpu,
        renderer: &mut Renderer,
        format: wgpu::TextureFormat,
        setup: &crate::setup::RaceSetup,
        wake: Option<Arc<ocean::wake::Wake>>,
        race_bounds: [f64; 4],
        size: [u32; 2],
        i: usize,
    ) -> AppResult {
        if self.shown == Some((i, size)) {
            if let Some(map) = self.map {
                let (w, changed) = self.wake_for_table(wake, &map);
                if changed {
                    renderer.set_wake(w);
                }
            }
            return Ok(());
        }
        let frame = self
            .source
            .frame(i)
            .map_err(|e| AppError::new(e.to_string()))?;
        let mut cfg = self.config.clone();
        let (extent, centre) = match frame.planes.first() {
            Some(p) => (
                p.extent.as_dvec2(),
                p.center_pose.w_axis.truncate().as_dvec3(),
            ),
            // No table recorded (TUM): a 1 m table under the first frame's view centre.
            None => (DVec2::ONE, DVec3::ZERO),
        };
        // The table lies the real sea's depth down, in race metres (optical similarity: the
        // water over the table is depth × scale deep, its optics the real sea's).
        cfg.table_depth = self.water.depth_m;
        cfg.water = self.water;
        let map = fit_on_table(race_bounds, centre, extent, cfg.table_depth);
        let (camera, view) = to_render(&frame, &map, size);
        let image = frame
            .image
            .to_camera_image()
            .map_err(|e| AppError::new(format!("feed frame {i}: {e}")))?;
        let backdrop = view.with_image(image);
        let (wake, wake_changed) = self.wake_for_table(wake, &map);
        match &self.effects {
            Some(effects) => {
                effects.set_backdrop(gpu, backdrop);
                effects.set_water(cfg.water, cfg.table_depth);
                if wake_changed {
                    renderer.set_wake(wake);
                }
            }
            None => {
                let mut fresh = setup.renderer(gpu, format, wake);
                self.effects = Some(add_effect_passes(&mut fresh, gpu, cfg, backdrop));
                *renderer = fresh;
            }
        }
        log::debug!("feed frame {i}: handed to the effects");
        self.camera = Some(camera);
        self.map = Some(map);
        self.table_area = Some(table_area(race_bounds, extent));
        self.shown = Some((i, size));
        Ok(())
    }
}

/// The render camera and the effects' camera and display transform (the frame without its
/// image) for an AR frame on the table of `map`, for a window of `size`: the image fills the
/// window and is cropped to its aspect, and the render camera's field of view is the crop's.
pub fn to_render(
    frame: &CameraFrame,
    map: &CoursePlacement,
    size: [u32; 2],
) -> (Camera, Backdrop<()>) {
    let (display, fov_y) = fill_view(&frame.intrinsics, size);
    (
        physical_camera(frame, map, fov_y),
        backdrop_of(frame, map, display),
    )
}
