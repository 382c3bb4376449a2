//! `regatta run --replay DIR`: a recorded camera feed (replay folder or TUM RGB-D, `crates/ar`)
//! as the background, the race on its table.
//!
//! The table maps to the race as on the phone (`core::table`): the race's play area (tracks and
//! marks plus margin) is fitted onto the table's extent, the table's centre is the play area's
//! centre, and the table top lies `table_depth` race metres below the sea's rest level (the
//! refraction effect's table). The feed's camera poses, mapped the same way
//! (`core::camera_frame`), become the render camera; its image, through the window's crop, the
//! background.
//!
//! The first feed frame builds the renderer with the effect passes (`add_effect_passes`); each
//! later frame, and a resized window, goes through the returned `EffectsHandle`
//! (`set_camera_frame`: the image is written into the same textures, RGBA as it is, YUV planes
//! converted in the shader), so nothing is rebuilt per frame.

use std::sync::Arc;
use std::time::Instant;

use ar::arcore::CoursePlacement;
use ar::{CameraFrame, ReplayFeed, SynthConfig};
use glam::{DVec2, DVec3};
use render::effects::camera_frame::CameraFrame as RenderCameraFrame;
use render::effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use render::{Camera, RenderOptions, Renderer, Scene};

use crate::core::camera_frame::{fill_view, physical_camera, render_frame};
use crate::core::table::{boats_as_models, fit_on_table};

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
    map: Option<CoursePlacement>,
    /// The effects drawn over the feed (all of them in the window; `--effects` for
    /// `regatta render --replay`).
    config: ArConfig,
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
        })
    }

    /// The same feed with these effects over its image.
    pub fn with_effects(mut self, effects: render::effects::EffectSet) -> Self {
        self.config.effects = effects;
        self
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
            boats_as_models(scene, &m);
        }
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
            return Ok(());
        }
        let frame = match &mut self.source {
            Source::Replay(f) => f.frame(i).map_err(|e| CliError::new(e.to_string()))?,
            Source::Synth(c, cache) => cache[i].get_or_insert_with(|| c.frame(i)).clone(),
        };
        let started = Instant::now();
        let cfg = self.config.clone();
        let (extent, centre) = match frame.planes.first() {
            Some(p) => (
                p.extent.as_dvec2(),
                p.center_pose.w_axis.truncate().as_dvec3(),
            ),
            // No table recorded (TUM): a 1 m table under the first frame's view centre.
            None => (DVec2::ONE, DVec3::ZERO),
        };
        let map = fit_on_table(scene.play_area, centre, extent, cfg.table_depth);
        let (camera, view) = to_render(&frame, &map, size);
        let image = frame
            .image
            .to_camera_image()
            .map_err(|e| CliError::new(format!("feed frame {i}: {e}")))?;
        let render_frame = view.with_image(image);
        match &self.effects {
            Some(effects) => effects.set_camera_frame(gpu, render_frame),
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
/// image) for an AR frame on the table of `map`, for a window of `size`: the image fills the
/// window and is cropped to its aspect, and the render camera's field of view is the crop's.
pub fn to_render(
    frame: &CameraFrame,
    map: &CoursePlacement,
    size: [u32; 2],
) -> (Camera, RenderCameraFrame<()>) {
    let (display, fov_y) = fill_view(&frame.intrinsics, size);
    (
        physical_camera(frame, map, fov_y),
        render_frame(frame, map, display),
    )
}
