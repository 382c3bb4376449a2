//! `regatta run --replay DIR`: a recorded camera feed (replay folder or TUM RGB-D, `crates/ar`)
//! as the background, the race on its table.
//!
//! The table maps to the race uniformly: the race's play area (tracks and marks plus margin)
//! is fitted onto the table's extent, so one AR metre is `scale` race metres, the table's centre
//! is the play area's centre, and the table top lies `table_depth` race metres below the sea's
//! rest level (the refraction effect's table). The feed's camera poses, mapped the same way,
//! become the render camera; its image, through the window's crop, the background.
//!
//! The effects take their camera frame when they are built (`add_effect_passes`), so a new feed
//! frame rebuilds the renderer's passes: cheap next to a frame on a GPU, slow on lavapipe.

use std::sync::Arc;
use std::time::Instant;

use ar::{CameraFrame, ReplayFeed, SynthConfig};
use glam::{DMat4, DVec2, DVec3};
use render::effects::camera_frame::CameraFrame as RenderCameraFrame;
use render::effects::passes::{ArConfig, add_effect_passes};
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
    shown: Option<usize>,
    /// The current frame's render camera.
    camera: Option<Camera>,
    map: Option<TableMap>,
}

/// Length of a boat model on the table, AR metres: a real boat at table scale is a fraction of
/// a millimetre, so the boats are drawn as 5 cm models (their positions stay exact).
pub const MODEL_BOAT_M: f64 = 0.05;

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
            camera: None,
            map: None,
        })
    }

    /// Puts `scene` on the table: the feed's camera, boats drawn as table-sized models
    /// (after [`FeedView::prepare`]).
    pub fn apply(&self, scene: &mut Scene) {
        if let (Some(c), Some(m)) = (self.camera, self.map) {
            scene.camera = c;
            for b in &mut scene.boats {
                b.length = b.length.max(MODEL_BOAT_M * m.scale);
            }
        }
    }

    /// Picks the feed frame for the wall clock; when it changed, rebuilds `renderer` with the
    /// effects over the new frame. `scene` gives the play area; `size` is the window's.
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
        if self.shown == Some(i) {
            return Ok(());
        }
        let frame = match &mut self.source {
            Source::Replay(f) => f.frame(i).map_err(|e| CliError::new(e.to_string()))?,
            Source::Synth(c, cache) => cache[i].get_or_insert_with(|| c.frame(i)).clone(),
        };
        let rebuild = Instant::now();
        let cfg = ArConfig::default();
        let (extent, centre) = match frame.planes.first() {
            Some(p) => (
                p.extent.as_dvec2(),
                p.center_pose.w_axis.truncate().as_dvec3(),
            ),
            // No table recorded (TUM): a 1 m table under the first frame's view centre.
            None => (DVec2::ONE, DVec3::ZERO),
        };
        let map = TableMap::fit(scene.play_area, centre, extent, cfg.table_depth);
        let (camera, render_frame) = to_render(&frame, &map, size);
        let mut fresh = Renderer::new(
            gpu,
            format,
            RenderOptions {
                measure_gpu_time: false,
                ..Default::default()
            },
        );
        fresh.set_wake(wake);
        add_effect_passes(&mut fresh, gpu, cfg, render_frame);
        *renderer = fresh;
        log::debug!(
            "feed frame {i}: renderer rebuilt in {:.1} ms",
            rebuild.elapsed().as_secs_f64() * 1e3
        );
        self.camera = Some(camera);
        self.map = Some(map);
        self.shown = Some(i);
        Ok(())
    }
}

/// The render camera and the effects' camera frame for an AR frame, for a window of `size`:
/// the image fills the window and is cropped to its aspect (display transform), and the render
/// camera's field of view is the crop's.
pub fn to_render(
    frame: &CameraFrame,
    map: &TableMap,
    size: [u32; 2],
) -> (Camera, RenderCameraFrame) {
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
        fov_y,
        near: (0.02 * map.scale).max(0.01),
        far: crate::cli::render::FAR_M,
    };
    let image = frame.image.to_rgba_image();
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
            image,
            camera: pinhole,
            display,
        },
    )
}
