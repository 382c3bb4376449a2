//! The AR side of the app core: the backend that carries out the session machine's commands
//! (`ar::arcore::session`) and hands out frames ([`ArBackend`]: ARCore through its C API on the
//! phone, the simulated ARCore on the host), and what the app keeps of it ([`ArState`]: the
//! session state, the latest frame and display camera, the tracking hint, the recording).

use std::path::Path;

use ar::arcore::{Command, Event, SessionState, hit_test, tap_ray};
use ar::replay::{FrameFileFormat, TablePlane};
use ar::{CameraFrame, PlaneKind, Pose, ReplayWriter};
use glam::{DVec2, DVec3};

/// What the screen shows besides the camera image: the display-oriented AR camera and light.
pub use ar::arcore::ffi::DisplayCamera;

/// An AR system the core drives: ARCore on the phone, the simulated ARCore on the host.
pub trait ArBackend {
    /// Whether the AR library could be loaded.
    fn is_loaded(&self) -> bool;
    /// Carries out one command; returns the answer when it is immediate.
    fn carry_out(&mut self, command: Command) -> Option<Event>;
    /// The view's size (pixels) and display rotation (`Surface.ROTATION_*`, 0..3).
    fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32);
    /// Steps the session for this display frame; an answer only when it did not succeed.
    fn update(&mut self) -> Option<Event>;
    /// The newest camera frame and display camera, `None` when nothing is new.
    fn next_frame(&mut self) -> Result<Option<(CameraFrame, DisplayCamera)>, ar::ArError>;
    /// Steps `state` with `event` and carries out every command, feeding immediate answers
    /// back in; the note to show, if the session asked to tell one. A fall-back leaves
    /// nothing of the AR system running.
    fn drive(&mut self, state: &mut SessionState, event: Event) -> Option<&'static str> {
        let mut note = None;
        let mut queue = vec![event];
        while let Some(e) = queue.pop() {
            let (next, commands) = state.on(e);
            if next != *state {
                note = None;
            }
            *state = next;
            for c in commands {
                match c {
                    Command::Tell(msg) => note = Some(msg),
                    Command::FallBack(why) => {
                        log::warn!("regatta: {}", why.message());
                        self.carry_out(Command::Pause);
                    }
                    other => queue.extend(self.carry_out(other)),
                }
            }
        }
        note
    }
    /// Camera images are kept within `max_side` pixels (the GPU's largest texture).
    fn limit_image_side(&mut self, _max_side: u32) {}
    /// What the camera image may cost from the next session resume on (the quality tier's
    /// budget): ARCore's camera config is chosen only while the session is paused.
    fn set_camera_budget(&mut self, _budget: ar::arcore::ffi::CameraBudget) {}
    /// The display rotation now (`Surface.ROTATION_*`, 0..3), read from the platform; `None`
    /// where it cannot be read (then the window events' rotation stands).
    fn display_rotation(&self) -> Option<i32> {
        None
    }
    /// The point (AR metres) of a detected upward plane under the screen point `screen`
    /// (0..1 from the top-left) of `frame`'s view.
    fn hit_test(&self, frame: &CameraFrame, screen: DVec2) -> Option<DVec3> {
        screen_hit(frame, screen)
    }
}

/// No AR session: nothing loads and no frame comes. The desktop's backend (the feed, where
/// there is one, is played by the app itself), and a phone without ARCore, which draws the
/// race in 3D under its orbit view.
pub struct NoAr;

impl ArBackend for NoAr {
    fn is_loaded(&self) -> bool {
        false
    }
    fn carry_out(&mut self, _: ar::arcore::Command) -> Option<ar::arcore::Event> {
        None
    }
    fn set_display_geometry(&mut self, _: i32, _: u32, _: u32) {}
    fn update(&mut self) -> Option<ar::arcore::Event> {
        None
    }
    fn next_frame(&mut self) -> Result<Option<(ar::CameraFrame, DisplayCamera)>, ar::ArError> {
        Ok(None)
    }
}

/// The hit test of `ar::arcore::hit`: the screen point through the display transform to an
/// image pixel, its ray against the frame's upward planes.
pub fn screen_hit(frame: &CameraFrame, screen: DVec2) -> Option<DVec3> {
    let image_uv = frame
        .display_uv
        .transform_point2(screen.as_vec2())
        .as_dvec2();
    let k = frame.intrinsics;
    let image_px = image_uv * DVec2::new(f64::from(k.width), f64::from(k.height));
    hit_test(&tap_ray(frame, image_px), &frame.planes).map(|(_, point)| point)
}

/// The session and what the app keeps of the AR frames.
pub struct ArState {
    pub session: SessionState,
    /// The last message the session asked to tell (the camera is busy), or the GPU's note.
    pub note: Option<String>,
    pub frame: Option<CameraFrame>,
    pub display: Option<DisplayCamera>,
    /// Counts the frames taken, so a frame is uploaded once.
    pub frame_seq: u64,
    pub hint: Option<&'static str>,
    pub recorder: Option<Recorder>,
    /// The geometry last given to the backend (rotation, width, height).
    geometry: Option<(i32, u32, u32)>,
}

impl Default for ArState {
    fn default() -> Self {
        ArState {
            session: SessionState::Start,
            note: None,
            frame: None,
            display: None,
            frame_seq: 0,
            hint: None,
            recorder: None,
            geometry: None,
        }
    }
}

impl ArState {
    /// Steps the session machine with `event` through `backend`.
    pub fn step(&mut self, backend: &mut dyn ArBackend, event: Event) {
        let before = self.session;
        let note = backend.drive(&mut self.session, event);
        if let Some(n) = note {
            log::warn!("regatta: {n}");
        }
        if self.session != before || note.is_some() {
            self.note = note.map(str::to_string);
        }
        if matches!(self.session, SessionState::Unavailable(_)) {
            self.frame = None;
            self.display = None;
        }
    }

    /// One display frame: geometry when it changed, the session's update, then the frame.
    pub fn update(&mut self, backend: &mut dyn ArBackend, rotation: i32, size: [u32; 2]) {
        if !self.session.is_running() {
            return;
        }
        let geometry = (rotation, size[0], size[1]);
        if self.geometry != Some(geometry) {
            backend.set_display_geometry(rotation, size[0], size[1]);
            self.geometry = Some(geometry);
        }
        if let Some(answer) = backend.update() {
            self.step(backend, answer);
            return;
        }
        match backend.next_frame() {
            Ok(Some((frame, display))) => self.on_frame(frame, display),
            Ok(None) => {}
            Err(e) => log::warn!("regatta: {e}"),
        }
    }

    fn on_frame(&mut self, frame: CameraFrame, display: DisplayCamera) {
        if display.hint != self.hint {
            match display.hint {
                Some(h) => log::warn!("regatta: {h}"),
                None => log::info!("regatta: tracking"),
            }
            self.hint = display.hint;
        }
        if let Some(r) = self.recorder.as_mut()
            && let Err(e) = r.write(&frame)
        {
            log::error!("regatta: recording stopped: {e}");
            self.recorder = None;
        }
        self.frame = Some(frame);
        self.display = Some(display);
        self.frame_seq += 1;
    }

    /// The display camera with the latest frame, when both exist.
    pub fn view(&self) -> Option<(&DisplayCamera, &CameraFrame)> {
        Some((self.display.as_ref()?, self.frame.as_ref()?))
    }

    /// Starts or stops recording into a new folder under `root` (named by `stamp`); the folder
    /// written when one stopped.
    pub fn toggle_recording(
        &mut self,
        root: Option<&Path>,
        stamp: u64,
    ) -> Option<std::path::PathBuf> {
        if let Some(r) = self.recorder.take() {
            return match r.writer.finish() {
                Ok(dir) => {
                    log::info!("regatta: recording saved in {}", dir.display());
                    Some(dir)
                }
                Err(e) => {
                    log::error!("regatta: recording not saved: {e}");
                    None
                }
            };
        }
        let (Some(root), Some(frame)) = (root, &self.frame) else {
            log::warn!("regatta: nothing to record yet (no camera frame or no app storage)");
            return None;
        };
        let dir = root.join("recordings").join(format!("regatta-{stamp}"));
        match Recorder::start(&dir, frame) {
            Ok(r) => {
                log::info!("regatta: recording into {}", dir.display());
                self.recorder = Some(r);
            }
            Err(e) => log::error!("regatta: cannot record: {e}"),
        }
        None
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
