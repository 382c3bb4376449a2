//! The race (or the pool) on the table: where it stands in ARCore's world
//! ([`CoursePlacement`]), the render camera and sun from ARCore's camera and light, the camera
//! image as the background pass's frame, and the record toggle writing the replay format.
//!
//! The camera image goes to the GPU as ARCore gives it, YUV 4:2:0 planes
//! (`ar::FrameImage::to_camera_image` only repacks the strided planes); the effect passes
//! convert it in the shader. A new image reaches passes built once through
//! `EffectsHandle::set_camera_frame`.

use std::path::Path;

use ar::arcore::ffi::DisplayCamera;
use ar::arcore::{CoursePlacement, hit_test, tap_ray};
use ar::replay::{FrameFileFormat, TablePlane};
use ar::{CameraFrame, PlaneKind, Pose, ReplayWriter};
use glam::{DMat4, DQuat, DVec2, DVec3};
use render::Camera;
use render::effects::camera_frame::{CameraFrame as RenderCameraFrame, CameraImage};
use render::optics::PinholeCamera;

/// Length of a boat model on the table, AR metres (a real boat at table scale is a speck; the
/// desktop feed draws the same 5 cm models).
const MODEL_BOAT_M: f64 = 0.05;
/// Width of the table the course is first fitted to, AR metres.
const FIRST_TABLE_M: f64 = 1.0;
/// AR metres per pool metre when the pool is first placed: the 2 m × 1.6 m pool becomes a
/// 30 cm tub on the table.
pub const POOL_TO_TABLE: f64 = 0.15;

/// The AR state of the app.
#[derive(Default)]
pub struct ArView {
    pub placement: Option<CoursePlacement>,
    /// The latest camera frame (for taps, the background and recording).
    pub frame: Option<CameraFrame>,
    /// Counts the frames taken, so a frame is uploaded once.
    pub frame_seq: u64,
    /// The hint shown last, so it is logged once per change.
    pub hint: Option<&'static str>,
    pub recorder: Option<Recorder>,
}

/// The play area's centre at the table's depth below the sea: the race point that sits on the
/// tapped table point (as in the desktop feed, the water stands `table_depth` above the table).
pub fn course_pivot(play_area: [f64; 4], table_depth: f64) -> DVec3 {
    let [ax, az, bx, bz] = play_area;
    DVec3::new(0.5 * (ax + bx), -table_depth, 0.5 * (az + bz))
}

impl ArView {
    /// Takes a new frame; logs the tracking hint when it changes.
    pub fn on_frame(&mut self, frame: CameraFrame, view: Option<&DisplayCamera>) {
        let hint = view.and_then(|v| v.hint);
        if hint != self.hint {
            match hint {
                Some(h) => log::warn!("regatta: {h}"),
                None => log::info!("regatta: tracking"),
            }
            self.hint = hint;
        }
        if let Some(r) = self.recorder.as_mut()
            && let Err(e) = r.write(&frame)
        {
            log::error!("regatta: recording stopped: {e}");
            self.recorder = None;
        }
        self.frame = Some(frame);
        self.frame_seq += 1;
    }

    /// The point (AR metres) of the detected plane under a tap at `px` (view pixels) on a view
    /// of `size` pixels, if one is there.
    pub fn hit(&self, px: DVec2, size: [u32; 2]) -> Option<DVec3> {
        let frame = self.frame.as_ref()?;
        let screen = px / DVec2::new(f64::from(size[0].max(1)), f64::from(size[1].max(1)));
        let image_uv = frame
            .display_uv
            .transform_point2(screen.as_vec2())
            .as_dvec2();
        let k = frame.intrinsics;
        let image_px = image_uv * DVec2::new(f64::from(k.width), f64::from(k.height));
        let hit = hit_test(&tap_ray(frame, image_px), &frame.planes).map(|(_, point)| point);
        if hit.is_none() {
            log::info!("regatta: no table under the tap yet; move the phone slowly over it");
        }
        hit
    }

    /// Puts the course's pivot on `point` (AR metres), keeping its turn and scale once placed.
    pub fn place_course(&mut self, point: DVec3, play_area: [f64; 4], table_depth: f64) {
        let [ax, az, bx, bz] = play_area;
        let mut placement = self.placement.unwrap_or(CoursePlacement {
            anchor: DVec3::ZERO,
            yaw: 0.0,
            course_to_table: FIRST_TABLE_M / (bx - ax).max(bz - az).max(1.0),
        });
        placement.put(course_pivot(play_area, table_depth), point);
        log::info!(
            "regatta: course placed at {point:.3} (1:{:.0})",
            1.0 / placement.course_to_table
        );
        self.placement = Some(placement);
    }

    /// The pool's placement with its centre on `point` (AR metres), keeping the turn and scale
    /// of `current` once placed.
    pub fn place_pool(current: Option<CoursePlacement>, point: DVec3) -> CoursePlacement {
        let mut placement = current.unwrap_or(CoursePlacement {
            anchor: DVec3::ZERO,
            yaw: 0.0,
            course_to_table: POOL_TO_TABLE,
        });
        placement.put(DVec3::ZERO, point);
        log::info!("regatta: pool placed at {point:.3}");
        placement
    }

    /// The render camera (race metres) for ARCore's display-oriented camera.
    pub fn camera(placement: &CoursePlacement, view: &DisplayCamera) -> Camera {
        Camera::from_view_projection(view.view * placement.race_to_ar(), view.projection_gl)
    }

    /// ARCore's main light direction turned into race axes (the placement's turn undone).
    pub fn sun(placement: &CoursePlacement, towards_ar: DVec3) -> DVec3 {
        (DQuat::from_rotation_y(-placement.yaw) * towards_ar).normalize()
    }

    /// Smallest boat length to draw, race metres, so boats stay visible as table models.
    pub fn boat_length(placement: &CoursePlacement) -> f64 {
        MODEL_BOAT_M / placement.course_to_table
    }

    /// The background pass's frame: the image as ARCore gave it (YUV planes, converted on the
    /// GPU), the physical camera in the metres of the world `placement` puts on the table.
    pub fn background(
        placement: &CoursePlacement,
        frame: &CameraFrame,
    ) -> Result<RenderCameraFrame<CameraImage>, ar::ArError> {
        let ar_to_race = placement.ar_to_race();
        let c2w = frame.camera_to_world.as_dmat4();
        let (_, rot, pos) = c2w.to_scale_rotation_translation();
        let rot = DQuat::from_rotation_y(-placement.yaw) * rot;
        let k = frame.intrinsics;
        let d = frame.display_uv;
        Ok(RenderCameraFrame {
            image: frame.image.to_camera_image()?,
            camera: PinholeCamera {
                fx: k.fx,
                fy: k.fy,
                cx: k.cx,
                cy: k.cy,
                width: f64::from(k.width),
                height: f64::from(k.height),
                pose: DMat4::from_rotation_translation(rot, ar_to_race.transform_point3(pos)),
            },
            display: [
                [
                    f64::from(d.matrix2.x_axis.x),
                    f64::from(d.matrix2.y_axis.x),
                    f64::from(d.translation.x),
                ],
                [
                    f64::from(d.matrix2.x_axis.y),
                    f64::from(d.matrix2.y_axis.y),
                    f64::from(d.translation.y),
                ],
            ],
        })
    }

    /// Starts or stops recording into a new folder under `root`.
    pub fn toggle_recording(&mut self, root: Option<&Path>) {
        if let Some(r) = self.recorder.take() {
            match r.writer.finish() {
                Ok(dir) => log::info!("regatta: recording saved in {}", dir.display()),
                Err(e) => log::error!("regatta: recording not saved: {e}"),
            }
            return;
        }
        let (Some(root), Some(frame)) = (root, &self.frame) else {
            log::warn!("regatta: nothing to record yet (no camera frame or no app storage)");
            return;
        };
        let stamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        let dir = root.join("recordings").join(format!("regatta-{stamp}"));
        match Recorder::start(&dir, frame) {
            Ok(r) => {
                log::info!("regatta: recording into {}", dir.display());
                self.recorder = Some(r);
            }
            Err(e) => log::error!("regatta: cannot record: {e}"),
        }
    }
}

/// A recording in the replay format (`crates/ar/src/replay.rs`): frames, poses, intrinsics and
/// the table plane under the course when recording started.
pub struct Recorder {
    writer: ReplayWriter,
    /// Sensor time of the first frame, seconds.
    t0: f64,
    last_t: Option<f64>,
}

impl Recorder {
    fn start(dir: &Path, first: &CameraFrame) -> Result<Recorder, ar::ArError> {
        let table = first
            .planes
            .iter()
            .find(|p| p.kind == PlaneKind::HorizontalUp)
            .map(|p| {
                let (_, rot, centre) = p.center_pose.to_scale_rotation_translation();
                TablePlane {
                    center: centre.as_dvec3().to_array(),
                    rotation: rot.as_dquat().to_array(),
                    extent: p.extent.as_dvec2().to_array(),
                }
            });
        Ok(Recorder {
            writer: ReplayWriter::create(
                dir,
                first.intrinsics,
                30.0,
                table,
                FrameFileFormat::Jpeg(85),
            )?,
            t0: first.timestamp,
            last_t: None,
        })
    }

    /// Writes `frame` unless it repeats the last one's time (ARCore may hand the same image twice).
    fn write(&mut self, frame: &CameraFrame) -> Result<(), ar::ArError> {
        let t = frame.timestamp - self.t0;
        if self.last_t.is_some_and(|l| t <= l) {
            return Ok(());
        }
        self.writer
            .write_frame(t, &frame.image, &Pose::from_mat4(frame.camera_to_world))?;
        self.last_t = Some(t);
        Ok(())
    }
}
