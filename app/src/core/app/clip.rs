//! "Share clip", one worker for both profiles: the last [`ClipRequest::seconds`] of race time
//! before the playhead, drawn as `regatta render --from --to` draws a clip
//! (`setup::clip::write_gif`, overlays and the trails' manoeuvre marks included) on a worker
//! thread with its own headless GPU device, so the app keeps drawing, into `clips/` of a
//! folder; then handed off ([`HandOff`], the one difference between the profiles):
//! - the desktop ([`HandOff::File`]): the GIF in `clips/` under the folder the app runs in is
//!   the result; the button shows the progress, then the file's path or the one-line error.
//! - the phone ([`HandOff::MediaStore`]): from the app's files folder into the media store
//!   (`Pictures/Regatta`) and to the share sheet, through [`ShareJni`] (the Android calls in
//!   `app/src/android/share.rs`, the host's `ScriptedJni` in tests); the banner says it.
//!
//! Background: the sky and the sea, not the camera image. A clip's frames follow race time
//! while the camera image is one still moment; held still behind moving boats it would also
//! need the AR effect passes and the table's cut on the worker's own device. The phone's camera
//! pose is kept, so its clip shows the race from where the phone looked.
//!
//! What the user sees is one line ([`ClipWorker::line`]): the frames' progress, then the file
//! or "pick an app", or one sentence saying what failed (no race time before the playhead,
//! Android older than 10, a full disk, the media store's refusal, a Java exception).

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use ar::arcore::ffi::share::MEDIA_STORE_MIN_SDK;
use ar::arcore::ffi::{JavaObject, MediaItem, ShareJni};

use super::App;
use crate::hud::banner::Tone;
use crate::setup::Profile;
use crate::setup::clip::{ClipLook, ClipTimes, write_gif};
use crate::world::RaceWorld;

/// What a clip covers and how large it is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipRequest {
    /// Race time before the playhead, seconds.
    pub seconds: f64,
    /// Frames per second of race time.
    pub fps: f64,
    /// Frame size, pixels.
    pub size: [u32; 2],
}

impl ClipRequest {
    /// The desktop button's clip: 20 s at 15 fps, 640x360 (301 frames; about 3 minutes on
    /// lavapipe's 2 CPU cores).
    pub const DESKTOP: ClipRequest = ClipRequest {
        seconds: 20.0,
        fps: 15.0,
        size: [640, 360],
    };
    /// The phone button's clip: 10 s at 10 fps, 360 × 640 portrait (101 frames; a chat app's
    /// size).
    pub const PHONE: ClipRequest = ClipRequest {
        seconds: 10.0,
        fps: 10.0,
        size: [360, 640],
    };
}

/// Where a written clip goes: the profiles' one difference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HandOff {
    /// The file is the result (the desktop).
    File,
    /// Into the media store and to the share sheet (the phone), on Android `sdk_int`
    /// (`Build.VERSION.SDK_INT`): the media store's columns need Android 10 (API 29).
    MediaStore { sdk_int: u32 },
}

/// The media store's folder for clips.
pub const CLIP_FOLDER: &str = "Pictures/Regatta";
/// The share sheet's title.
pub const CHOOSER_TITLE: &str = "Share clip";
pub const GIF_MIME: &str = "image/gif";
/// The one sentence for a playhead that leaves no race time before it.
pub const NO_SPAN: &str = "No clip: the playhead is at the race's start; play the race first.";

/// Where the clip is.
#[derive(Debug, Clone, PartialEq)]
pub enum ClipState {
    Idle,
    Rendering {
        done: usize,
        total: usize,
    },
    /// The GIF is written: the desktop's result; on the phone the next [`ClipWorker::poll`]
    /// hands it to Android.
    Written(PathBuf),
    /// The share sheet was opened with the clip's media store URI.
    Shared(String),
    Failed(String),
}

/// The button's state and its worker.
#[derive(Debug)]
pub struct ClipWorker {
    state: Arc<Mutex<ClipState>>,
    worker: Option<std::thread::JoinHandle<()>>,
    /// Where the clip being drawn or last drawn goes.
    hand_off: HandOff,
}

impl Default for ClipWorker {
    fn default() -> Self {
        ClipWorker {
            state: Arc::new(Mutex::new(ClipState::Idle)),
            worker: None,
            hand_off: HandOff::File,
        }
    }
}

impl ClipWorker {
    /// The state now. A worker that has ended while the state still says `Rendering` stopped
    /// part-way (it panicked: its last act on every other path is to set `Written` or
    /// `Failed`), so that reads as failed and the button is free again, not drawing for good.
    pub fn state(&self) -> ClipState {
        // Asked before the state is read: a worker that ended after setting its outcome is
        // never taken for one that stopped part-way.
        let ended = self.worker.as_ref().is_some_and(|w| w.is_finished());
        let state = match self.state.lock() {
            Ok(s) => s.clone(),
            Err(poisoned) => poisoned.into_inner().clone(),
        };
        match state {
            ClipState::Rendering { done, total } if ended => ClipState::Failed(format!(
                "Could not write the clip: drawing stopped at frame {done} of {total}."
            )),
            s => s,
        }
    }

    fn set(&self, s: ClipState) {
        match self.state.lock() {
            Ok(mut g) => *g = s,
            Err(poisoned) => *poisoned.into_inner() = s,
        }
    }

    /// What the screen says, one line; `None` when idle.
    pub fn line(&self) -> Option<String> {
        match self.state() {
            ClipState::Idle => None,
            ClipState::Rendering { done, total } => {
                Some(format!("Drawing the clip: frame {done} of {total}"))
            }
            ClipState::Written(p) => Some(match self.hand_off {
                HandOff::File => format!("written: {}", p.display()),
                HandOff::MediaStore { .. } => "Handing the clip to Android…".into(),
            }),
            ClipState::Shared(_) => Some("Clip saved in Pictures/Regatta: pick an app".into()),
            ClipState::Failed(e) => Some(input::one_line(&e)),
        }
    }

    /// Whether a clip is being drawn or handed over (the button is off then).
    pub fn busy(&self) -> bool {
        match self.state() {
            ClipState::Rendering { .. } => true,
            ClipState::Written(_) => self.hand_off != HandOff::File,
            _ => false,
        }
    }

    /// The button: draws the clip of `request` ending at `playhead` from `camera` (`None`
    /// frames the fleet at each frame's time) with the race's `debrief` (the trails' manoeuvre
    /// marks) into `folder/clips/` on a worker thread, for `hand_off`. Nothing starts while a
    /// clip is busy; a media store older than Android 10 or a playhead with no race time
    /// before it is said at once, and nothing is drawn.
    pub fn start(
        &mut self,
        (world, debrief): (&RaceWorld, Option<&race::Debrief>),
        camera: Option<render::Camera>,
        playhead: f64,
        (folder, request): (&Path, ClipRequest),
        hand_off: HandOff,
    ) {
        if self.busy() {
            return;
        }
        self.hand_off = hand_off;
        if let HandOff::MediaStore { sdk_int } = hand_off
            && sdk_int < MEDIA_STORE_MIN_SDK
        {
            return self.set(ClipState::Failed(format!(
                "Sharing a clip needs Android 10 or newer (this phone runs API {sdk_int})."
            )));
        }
        let span = world.race.time_span();
        let Ok(times) = ClipTimes::before_playhead(playhead, request.seconds, request.fps, span)
        else {
            return self.set(ClipState::Failed(NO_SPAN.into()));
        };
        let to = times.time(times.count - 1);
        let dir = folder.join("clips");
        let out = dir.join(format!("regatta-{:.0}-{:.0}s.gif", times.from, to));
        let look = ClipLook {
            size: request.size,
            camera,
            overlays: Default::default(),
            debrief: debrief.cloned(),
            wakes: true,
            error_px: render::renderer::DEFAULT_ERROR_PX,
        };
        self.set(ClipState::Rendering {
            done: 0,
            total: times.count,
        });
        let (world, state) = (world.clone(), self.state.clone());
        self.worker = Some(std::thread::spawn(move || {
            let set = |s: ClipState| {
                if let Ok(mut g) = state.lock() {
                    *g = s;
                }
            };
            let written = std::fs::create_dir_all(&dir)
                .map_err(|e| format!("could not make {}: {e}", input::show_path(&dir)))
                .and_then(|()| {
                    write_gif(&world, &times, &look, &out, &mut |done, total, _| {
                        set(ClipState::Rendering { done, total })
                    })
                    .map_err(|e| e.0)
                });
            set(match written {
                Ok(()) => ClipState::Written(out),
                Err(e) => ClipState::Failed(format!("Could not write the clip: {e}")),
            });
        }));
    }

    /// Each frame: on the phone, a written clip goes into the media store and to the share
    /// sheet (on the caller's thread, the one attached to Java); the desktop's file stays.
    pub fn poll(&mut self, jni: &dyn ShareJni) {
        if self.hand_off == HandOff::File {
            return;
        }
        let ClipState::Written(path) = self.state() else {
            return;
        };
        self.set(match media_store_hand_off(jni, &path) {
            Ok(uri) => ClipState::Shared(uri),
            Err(e) => ClipState::Failed(e),
        });
    }

    /// Waits for the worker (tests; the app never waits).
    pub fn wait(&mut self) {
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }

    /// The desktop's button and its line: true when it was pressed this frame.
    pub fn ui(&self, ui: &mut egui::Ui) -> bool {
        let state = self.state();
        let pressed = ui
            .add_enabled(!self.busy(), egui::Button::new("Share clip"))
            .on_hover_text("The last 20 s of race time before the playhead, as a GIF")
            .clicked();
        match state {
            ClipState::Idle => {}
            ClipState::Rendering { done, total } => {
                ui.add(
                    egui::ProgressBar::new(done as f32 / total.max(1) as f32)
                        .text(format!("frame {done}/{total}")),
                );
            }
            ClipState::Failed(_) => {
                ui.colored_label(egui::Color32::LIGHT_RED, self.line().unwrap_or_default());
            }
            ClipState::Written(_) | ClipState::Shared(_) => {
                ui.label(self.line().unwrap_or_default());
            }
        }
        pressed
    }
}

/// The GIF at `path` into the media store and to the share sheet: its URI, or one sentence.
pub fn media_store_hand_off(jni: &dyn ShareJni, path: &Path) -> Result<String, String> {
    let bytes = std::fs::read(path)
        .map_err(|e| format!("Could not read the clip {}: {e}", input::show_path(path)))?;
    let item = MediaItem {
        display_name: path
            .file_name()
            .map_or("regatta.gif".into(), |n| n.to_string_lossy().into_owned()),
        mime: GIF_MIME.into(),
        relative_path: CLIP_FOLDER.into(),
    };
    let uri = jni
        .insert_media(JavaObject::Activity, &item, &bytes)
        .map_err(|e| format!("Could not save the clip in {CLIP_FOLDER}: {e}"))?;
    jni.share_chooser(JavaObject::Activity, &uri, GIF_MIME, CHOOSER_TITLE)
        .map_err(|e| format!("Could not open the share sheet: {e}"))?;
    Ok(uri)
}

impl App {
    /// The "Share clip" button: the last [`App::clip_request`] seconds of race time before the
    /// playhead, from where the phone looks now (the AR camera once the course is placed, else
    /// the fleet framed; the desktop frames the fleet), drawn on a worker thread into `clips/`
    /// of the app's files folder (the phone) or of the folder the app runs in (the desktop);
    /// on the phone [`App::poll_share`] hands it to Android when written.
    pub fn share_clip(&mut self) {
        let t = self.race_time();
        let camera = self
            .course
            .zip(self.ar.view())
            .map(|(p, (view, _))| super::table::display_camera(&p, view));
        let (folder, hand_off) = match self.profile() {
            Profile::Phone | Profile::Picture => (
                self.data_dir.clone().unwrap_or_else(std::env::temp_dir),
                HandOff::MediaStore {
                    sdk_int: self.android_sdk.unwrap_or(u32::MAX),
                },
            ),
            Profile::Desktop => (std::env::current_dir().unwrap_or_default(), HandOff::File),
        };
        let debrief = self
            .overlays
            .debrief(&mut self.panels.debrief, &self.world.race);
        let request = (folder.as_path(), self.clip_request);
        self.clip
            .start((&self.world, debrief), camera, t, request, hand_off);
        self.notice_share();
    }

    /// Each frame, from the adapter that holds the Java calls: a written clip goes into the
    /// media store and to the share sheet; its outcome shows on the banner for a while.
    pub fn poll_share(&mut self, jni: &dyn ShareJni) {
        self.clip.poll(jni);
        self.notice_share();
    }

    /// A finished share's line onto the banner (a few seconds).
    fn notice_share(&mut self) {
        let tone = match self.clip.state() {
            ClipState::Shared(_) => Tone::Hint,
            ClipState::Failed(_) => Tone::Warning,
            _ => return,
        };
        if let Some(line) = self.clip.line() {
            self.notice = Some((line, tone, self.now + super::shared::NOTICE_S));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A worker that stops part-way (a panic while drawing) leaves the state at `Rendering`:
    /// read, that is a failure naming the frame it stopped at, and the button is free again.
    #[test]
    fn a_worker_that_stops_part_way_frees_the_button() {
        let mut clip = ClipWorker::default();
        clip.set(ClipState::Rendering { done: 3, total: 41 });
        let state = clip.state.clone();
        clip.worker = Some(std::thread::spawn(move || {
            *state.lock().unwrap() = ClipState::Rendering { done: 4, total: 41 };
            panic!("a frame could not be drawn");
        }));
        while !clip.worker.as_ref().unwrap().is_finished() {
            std::thread::yield_now();
        }
        assert_eq!(
            clip.state(),
            ClipState::Failed("Could not write the clip: drawing stopped at frame 4 of 41.".into())
        );
        assert!(!clip.busy());
        // A worker that ends after setting its outcome reads as that outcome.
        clip.set(ClipState::Written(PathBuf::from("clips/a.gif")));
        assert_eq!(
            clip.state(),
            ClipState::Written(PathBuf::from("clips/a.gif"))
        );
    }

    /// The desktop's hand-off: the worker writes the GIF the request asks for, and the file is
    /// the result (the button is free again, nothing polls it away). Read back with `gif`'s
    /// decoder, its frame count is seconds·fps + 1 and its size the request's.
    #[test]
    fn the_desktop_button_writes_the_seconds_before_the_playhead_as_a_gif() {
        if render::gpu::test_gpu().is_none() {
            return;
        }
        let world = crate::setup::RaceSetup::load_world(&[], None).unwrap();
        let folder = std::env::temp_dir().join(format!("regatta-share-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&folder);
        let mut clip = ClipWorker::default();
        let request = ClipRequest {
            seconds: 1.0,
            fps: 2.0,
            size: [32, 24],
        };
        clip.start(
            (&world, None),
            None,
            700.0,
            (&folder, request),
            HandOff::File,
        );
        clip.wait();
        let out = folder.join("clips").join("regatta-699-700s.gif");
        assert_eq!(clip.state(), ClipState::Written(out.clone()));
        assert!(!clip.busy(), "the desktop's written file is the result");
        assert_eq!(clip.line(), Some(format!("written: {}", out.display())));
        // Polling (the phone's hand-off) leaves the desktop's file as it is.
        clip.poll(&ar::arcore::ffi::ScriptedJni::new(Default::default()));
        assert_eq!(clip.state(), ClipState::Written(out.clone()));
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut d = options
            .read_info(std::fs::File::open(&out).unwrap())
            .unwrap();
        assert_eq!((d.width(), d.height()), (32, 24));
        let mut frames = 0;
        while d.read_next_frame().unwrap().is_some() {
            frames += 1;
        }
        assert_eq!(frames, 3);
        // A playhead at the start leaves no span: said in one sentence, nothing started.
        clip.start(
            (&world, None),
            None,
            -1e6,
            (&folder, request),
            HandOff::File,
        );
        assert_eq!(clip.state(), ClipState::Failed(NO_SPAN.into()));
        let _ = std::fs::remove_dir_all(&folder);
    }
}
