//! `regatta run --replay DIR`: a recorded camera feed (replay folder or TUM RGB-D, `crates/ar`)
//! as the background, the race on its table.
//!
//! The table maps to the race uniformly: the race's play area (tracks and marks plus margin)
//! is fitted onto the table's extent, so one AR metre is `scale` race metres, the table's centre
//! is the play area's centre, and the table top lies `table_depth` race metres below the sea's
//! rest level (the refraction effect's table). The feed's camera poses, mapped the same way,
//! become the render camera; its image, through the window's crop, the background.
//!
//! The first feed frame builds the renderer with the effect passes (`add_effect_passes`); each
//! later frame, and a resized window, goes through the returned `EffectsHandle`
//! (`set_camera_frame`: the image is written into the same textures, RGBA as it is, YUV planes
//! converted in the shader), so nothing is rebuilt per frame.

use std::sync::Arc;
use std::time::Instant;

use ar::{CameraFrame, ReplayFeed, SynthConfig};
use effects::camera_frame::CameraFrame as RenderCameraFrame;
use effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use glam::{DMat4, DVec2, DVec3};
use render::optics::PinholeCamera;
use render::{Camera, RenderOptions, Renderer, Scene};

use crate::error::{CliError, CliResult};

/// Where the frames come from.
enum Source {
    Replay(ReplayFeed),
    /// The synthetic table of `ar::synth`, rendered frame by frame (no files needed) and kept:
    /// after the first loop, frames cost nothing.
    Synth(SynthConfig, Vec<Option<CameraFrame>>),
}

/// The `--replay` value that chooses the built-in synthetic feed.
pub const SYNTH: &str = "synth";

/// The feed, where it maps in the race, and which frame the renderer holds.
pub struct FeedView {
    source: Source,
    start: Instant,
    /// The frame the effects show, and the window size it was fitted to.
    shown: Option<(usize, [u32; 2])>,
    /// The effects' camera frame, once the renderer has them.
    effects: Option<EffectsHandle>,
    /// The current frame's render camera.
    camera: Option<Camera>,
    map: Option<TableMap>,
    /// The effects drawn over the feed (all of them in the window; `--effects` for
    /// `regatta render --replay`).
    config: ArConfig,
    /// The water's depth (real metres: the table lies that deep under the race's sea, in race
    /// metres `depth × scale`) and turbidity.
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

/// Length of a boat model on the table, AR metres: a real boat at table scale is a fraction of
/// a millimetre, so the boats are drawn as 5 cm models (their positions stay exact).
pub const MODEL_BOAT_M: f64 = 0.05;

/// The length boats are drawn at on the table of `map`, race metres: [`MODEL_BOAT_M`] in race
/// metres, or `None` where that is no longer than the full-size hull (a small course: boats
/// and wakes at full size).
pub fn model_length(map: &TableMap) -> Option<f64> {
    let model = MODEL_BOAT_M * map.scale;
    (model > crate::cli::render::BOAT_LENGTH_M).then_some(model)
}

/// How the table's AR metres map to race metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableMap {
    /// Race metres per AR metre.
    pub scale: f64,
    /// The table's centre (AR metres).
    pub table_centre: DVec3,
    /// Where the table's centre lands in the race world (y = −table depth).
    pub race_centre: DVec3,
}

impl TableMap {
    /// Fits the play area `[min x, min z, max x, max z]` (race metres) onto a table of `extent`
    /// (AR metres, x and z) centred at `table_centre`, the table top `table_depth` below y = 0.
    pub fn fit(play_area: [f64; 4], table_centre: DVec3, extent: DVec2, table_depth: f64) -> Self {
        let [ax, az, bx, bz] = play_area;
        let scale = ((bx - ax) / extent.x).max((bz - az) / extent.y).max(1e-9);
        TableMap {
            scale,
            table_centre,
            race_centre: DVec3::new(0.5 * (ax + bx), -table_depth, 0.5 * (az + bz)),
        }
    }

    /// An AR point in race metres.
    pub fn to_race(&self, p: DVec3) -> DVec3 {
        self.race_centre + self.scale * (p - self.table_centre)
    }
}

impl FeedView {
    /// Opens a replay or TUM folder, or the synthetic feed for [`SYNTH`].
    pub fn open(dir: &std::path::Path) -> CliResult<Self> {
        let source = if dir.as_os_str() == SYNTH {
            let cfg = SynthConfig::default();
            Source::Synth(cfg, vec![None; cfg.frames])
        } else {
            let feed = ReplayFeed::open(dir).map_err(|e| CliError::new(e.to_string()))?;
            log::info!(
                "replay {}: {} frames, {:.1} s",
                dir.display(),
                feed.len(),
                feed.duration()
            );
            Source::Replay(feed)
        };
        Ok(FeedView {
            source,
            start: Instant::now(),
            shown: None,
            effects: None,
            camera: None,
            map: None,
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

    /// The water's look on the table from the next frame on (the panel's setter; ranges as
    /// `WaterLook::check`, out-of-range values are clamped into them).
    pub fn set_water(&mut self, water: render::water_look::WaterLook) {
        use render::water_look::{MAX_DEPTH_M, MAX_TURBIDITY_NTU, MIN_DEPTH_M};
        let clamp =
            |v: f64, lo: f64, hi: f64, or: f64| if v.is_finite() { v.clamp(lo, hi) } else { or };
        let base = render::water_look::WaterLook::default();
        self.water = render::water_look::WaterLook {
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
        match &self.source {
            Source::Replay(f) => f.len(),
            Source::Synth(c, _) => c.frames,
        }
    }

    /// Whether the feed has no frames (a feed that opened always has some).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Puts `scene` on the table: the feed's camera, boats drawn as table-sized models
    /// (after [`FeedView::prepare`]).
    pub fn apply(&self, scene: &mut Scene) {
        if let (Some(c), Some(m)) = (self.camera, self.map) {
            scene.camera = c;
            if let Some(model) = model_length(&m) {
                for b in &mut scene.boats {
                    b.length = b.length.max(model);
                }
            }
        }
    }

    /// The wake to draw on the table of `map` for `given`, and whether it differs from what
    /// was drawn before (then the renderer must take it).
    fn wake_for_table(
        &mut self,
        given: Option<Arc<ocean::wake::Wake>>,
        map: &TableMap,
    ) -> (Option<Arc<ocean::wake::Wake>>, bool) {
        let same = |a: &Option<Arc<_>>, b: &Option<Arc<_>>| match (a, b) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        if let Some(tw) = &self.table_wake
            && tw.scale == map.scale
            && same(&tw.given, &given)
        {
            return (tw.drawn.clone(), false);
        }
        let drawn = match (&given, model_length(map)) {
            (Some(w), Some(model)) => Some(crate::wakes::table_wake(w, model, map.scale)),
            _ => given.clone(),
        };
        self.table_wake = Some(TableWake {
            given,
            scale: map.scale,
            drawn: drawn.clone(),
        });
        (drawn, true)
    }

    /// Picks the feed frame for the wall clock; when it or the window's `size` changed, hands
    /// it to the effects. The first time, `renderer` is built anew (for `format`, with `wake`)
    /// with the effect passes; later frames only go through their handle. `scene` gives the
    /// play area.
    pub fn prepare(
        &mut self,
        gpu: &render::Gpu,
        renderer: &mut Renderer,
        format: wgpu::TextureFormat,
        wake: Option<Arc<ocean::wake::Wake>>,
        scene: &Scene,
        size: [u32; 2],
    ) -> CliResult {
        let t = self.start.elapsed().as_secs_f64();
        let i = match &self.source {
            Source::Replay(f) => f.index_at(t),
            Source::Synth(c, _) => c.index_at(t),
        };
        let options = RenderOptions {
            measure_gpu_time: false,
            // A new camera image is drawn even while the scene stands still: the background
            // pass's revision changes with it.
            keep_still_frames: true,
            ..Default::default()
        };
        self.prepare_frame(gpu, renderer, format, options, wake, scene, size, i)
    }

    /// [`FeedView::prepare`] for feed frame `i` (below [`FeedView::len`]), a renderer built
    /// with `options` the first time: what `regatta render --replay --frame i` draws.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare_frame(
        &mut self,
        gpu: &render::Gpu,
        renderer: &mut Renderer,
        format: wgpu::TextureFormat,
        options: RenderOptions,
        wake: Option<Arc<ocean::wake::Wake>>,
        scene: &Scene,
        size: [u32; 2],
        i: usize,
    ) -> CliResult {
        if self.shown == Some((i, size)) {
            if let Some(map) = self.map {
                let (w, changed) = self.wake_for_table(wake, &map);
                if changed {
                    renderer.set_wake(w);
                }
            }
            return Ok(());
        }
        let frame = match &mut self.source {
            Source::Replay(f) => f.frame(i).map_err(|e| CliError::new(e.to_string()))?,
            Source::Synth(c, cache) => cache[i].get_or_insert_with(|| c.frame(i)).clone(),
        };
        let started = Instant::now();
        let mut cfg = self.config.clone();
        let (extent, centre) = match frame.planes.first() {
            Some(p) => (
                p.extent.as_dvec2(),
                p.center_pose.w_axis.truncate().as_dvec3(),
            ),
            // No table recorded (TUM): a 1 m table under the first frame's view centre.
            None => (DVec2::ONE, DVec3::ZERO),
        };
        // The table lies the water's depth down, in race metres at the table's scale.
        let scale = TableMap::fit(scene.play_area, centre, extent, 0.0).scale;
        cfg.table_depth = self.water.depth_m * scale;
        cfg.water = self.water;
        let map = TableMap::fit(scene.play_area, centre, extent, cfg.table_depth);
        let (camera, view) = to_render(&frame, &map, size);
        let image = frame
            .image
            .to_camera_image()
            .map_err(|e| CliError::new(format!("feed frame {i}: {e}")))?;
        let render_frame = view.with_image(image);
        let (wake, wake_changed) = self.wake_for_table(wake, &map);
        match &self.effects {
            Some(effects) => {
                effects.set_camera_frame(gpu, render_frame);
                effects.set_water(cfg.water, cfg.table_depth);
                if wake_changed {
                    renderer.set_wake(wake);
                }
            }
            None => {
                let mut fresh = Renderer::new(gpu, format, options);
                fresh.set_wake(wake);
                self.effects = Some(add_effect_passes(&mut fresh, gpu, cfg, render_frame));
                *renderer = fresh;
            }
        }
        log::debug!(
            "feed frame {i}: handed to the effects in {:.1} ms",
            started.elapsed().as_secs_f64() * 1e3
        );
        self.camera = Some(camera);
        self.map = Some(map);
        self.shown = Some((i, size));
        Ok(())
    }
}

/// The render camera and the effects' camera and display transform (the frame without its
/// image) for an AR frame, for a window of `size`: the image fills the window and is cropped to
/// its aspect (display transform), and the render camera's field of view is the crop's.
pub fn to_render(
    frame: &CameraFrame,
    map: &TableMap,
    size: [u32; 2],
) -> (Camera, RenderCameraFrame<()>) {
    let k = frame.intrinsics;
    let (iw, ih) = (f64::from(k.width), f64::from(k.height));
    let a_img = iw / ih;
    let a_win = f64::from(size[0].max(1)) / f64::from(size[1].max(1));
    // Screen uv → image uv, rows of a 2×3 affine map.
    let (display, fov_y) = if a_win >= a_img {
        // Wider window: the full image width, a band of its height.
        let f = a_img / a_win;
        (
            [[1.0, 0.0, 0.0], [0.0, f, 0.5 * (1.0 - f)]],
            2.0 * (0.5 * ih * f / k.fy).atan(),
        )
    } else {
        let f = a_win / a_img;
        (
            [[f, 0.0, 0.5 * (1.0 - f)], [0.0, 1.0, 0.0]],
            2.0 * (0.5 * ih / k.fy).atan(),
        )
    };
    let c2w = frame.camera_to_world.as_dmat4();
    let (_, rot, pos) = c2w.to_scale_rotation_translation();
    let eye = map.to_race(pos);
    let forward = rot * DVec3::NEG_Z;
    let pose = DMat4::from_rotation_translation(rot, eye);
    let camera = Camera {
        eye,
        target: eye + forward,
        up: rot * DVec3::Y,
        fov_y,
        near: (0.02 * map.scale).max(0.01),
        far: crate::cli::render::FAR_M,
    };
    let pinhole = PinholeCamera {
        fx: k.fx,
        fy: k.fy,
        cx: k.cx,
        cy: k.cy,
        width: iw,
        height: ih,
        pose,
    };
    (
        camera,
        RenderCameraFrame {
            image: (),
            camera: pinhole,
            display,
        },
    )
}
