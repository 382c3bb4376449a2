//! The phone's "Share clip": the last [`PhoneClip::seconds`] of race time before the playhead,
//! drawn as `regatta render --from --to` draws a clip (`setup::clip::write_gif`, overlays
//! and the trails' manoeuvre marks included) from the phone's camera pose at the moment of the
//! press, on a worker thread with its own headless GPU device, into the app's files folder
//! (`clips/`); then handed to Android: into the media store (`Pictures/Regatta`) and to the
//! share sheet, through [`ShareJni`] (the Android calls in `app/src/android/share.rs`, the
//! host's `ScriptedJni` in tests).
//!
//! Background: the sky and the sea, not the camera image. A clip's frames follow race time
//! while the camera image is one still moment; held still behind moving boats it would also
//! need the AR effect passes and the table's cut on the worker's own device. The camera pose is
//! kept, so the clip shows the race from where the phone looked.
//!
//! What the user sees is one line ([`ClipShare::line`]): the frames' progress, then "pick an
//! app", or one sentence saying what failed (Android older than 10, a full disk, the media
//! store's refusal, a Java exception).

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use ar::arcore::ffi::share::MEDIA_STORE_MIN_SDK;
use ar::arcore::ffi::{JavaObject, MediaItem, ShareJni};

use crate::setup::clip::{ClipLook, ClipTimes, write_gif};
use crate::world::RaceWorld;

/// What a phone clip covers and how large it is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhoneClip {
    /// Race time before the playhead, seconds.
    pub seconds: f64,
    /// Frames per second of race time.
    pub fps: f64,
    /// Frame size, pixels.
    pub size: [u32; 2],
}

impl PhoneClip {
    /// The button's clip: 10 s at 10 fps, 360 × 640 portrait (101 frames; a chat app's size).
    pub const BUTTON: PhoneClip = PhoneClip {
        seconds: 10.0,
        fps: 10.0,
        size: [360, 640],
    };
}

/// The media store's folder for clips.
pub const CLIP_FOLDER: &str = "Pictures/Regatta";
/// The share sheet's title.
pub const CHOOSER_TITLE: &str = "Share clip";
pub const GIF_MIME: &str = "image/gif";

/// Where the share is.
#[derive(Debug, Clone, PartialEq)]
pub enum ShareState {
    Idle,
    Rendering {
        done: usize,
        total: usize,
    },
    /// The GIF is written; the next [`ClipShare::poll`] hands it to Android.
    Written(PathBuf),
    /// The share sheet was opened with the clip's media store URI.
    Shared(String),
    Failed(String),
}

/// The button's state and its worker.
#[derive(Debug)]
pub struct ClipShare {
    state: Arc<Mutex<ShareState>>,
    worker: Option<std::thread::JoinHandle<()>>,
}

impl Default for ClipShare {
    fn default() -> Self {
        ClipShare {
            state: Arc::new(Mutex::new(ShareState::Idle)),
            worker: None,
        }
    }
}

impl ClipShare {
    pub fn state(&self) -> ShareState {
        self.state
            .lock()
            .map(|s| s.clone())
            .unwrap_or(ShareState::Idle)
    }

    fn set(&self, s: ShareState) {
        if let Ok(mut g) = self.state.lock() {
            *g = s;
        }
    }

    /// What the screen says, one line; `None` when idle.
    pub fn line(&self) -> Option<String> {
        match self.state() {
            ShareState::Idle => None,
            ShareState::Rendering { done, total } => {
                Some(format!("Drawing the clip: frame {done} of {total}"))
            }
            ShareState::Written(_) => Some("Handing the clip to Android…".into()),
            ShareState::Shared(_) => Some("Clip saved in Pictures/Regatta: pick an app".into()),
            ShareState::Failed(e) => Some(input::one_line(&e)),
        }
    }

    /// Whether a clip is being drawn or handed over (the button is off then).
    pub fn busy(&self) -> bool {
        matches!(
            self.state(),
            ShareState::Rendering { .. } | ShareState::Written(_)
        )
    }

    /// The button: draws the clip of `clip` ending at `playhead` from `camera` (the phone's
    /// pose; `None` frames the fleet) into `folder/clips/` on a worker thread. On Android
    /// older than 10 (`sdk_int` < 29) it says so and draws nothing.
    pub fn start(
        &mut self,
        (world, debrief): (&RaceWorld, Option<&race::Debrief>),
        camera: Option<render::Camera>,
        playhead: f64,
        folder: &Path,
        clip: PhoneClip,
        sdk_int: u32,
    ) {
        if self.busy() {
            return;
        }
        if sdk_int < MEDIA_STORE_MIN_SDK {
            return self.set(ShareState::Failed(format!(
                "Sharing a clip needs Android 10 or newer (this phone runs API {sdk_int})."
            )));
        }
        let times = match ClipTimes::before_playhead(
            playhead,
            clip.seconds,
            clip.fps,
            world.race.time_span(),
        ) {
            Ok(t) => t,
            Err(_) => {
                return self.set(ShareState::Failed(
                    "No clip: the playhead is at the race's start; play the race first.".into(),
                ));
            }
        };
        let to = times.time(times.count - 1);
        let dir = folder.join("clips");
        let out = dir.join(format!("regatta-{:.0}-{:.0}s.gif", times.from, to));
        let look = ClipLook {
            size: clip.size,
            camera,
            overlays: Default::default(),
            debrief: debrief.cloned(),
            wakes: true,
            error_px: render::renderer::DEFAULT_ERROR_PX,
        };
        self.set(ShareState::Rendering {
            done: 0,
            total: times.count,
        });
        let (world, state) = (world.clone(), self.state.clone());
        self.worker = Some(std::thread::spawn(move || {
            let set = |s: ShareState| {
                if let Ok(mut g) = state.lock() {
                    *g = s;
                }
            };
            let written = std::fs::create_dir_all(&dir)
                .map_err(|e| format!("could not make {}: {e}", input::show_path(&dir)))
                .and_then(|()| {
                    write_gif(&world, &times, &look, &out, &mut |done, total, _| {
                        set(ShareState::Rendering { done, total })
                    })
                    .map_err(|e| e.0)
                });
            set(match written {
                Ok(()) => ShareState::Written(out),
                Err(e) => ShareState::Failed(format!("Could not write the clip: {e}")),
            });
        }));
    }

    /// Each frame: a written clip goes into the media store and to the share sheet (on the
    /// caller's thread, the one attached to Java).
    pub fn poll(&mut self, jni: &dyn ShareJni) {
        let ShareState::Written(path) = self.state() else {
            return;
        };
        self.set(match hand_off(jni, &path) {
            Ok(uri) => ShareState::Shared(uri),
            Err(e) => ShareState::Failed(e),
        });
    }

    /// Waits for the worker (tests; the app never waits).
    pub fn wait(&mut self) {
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }
}

/// The GIF at `path` into the media store and to the share sheet: its URI, or one sentence.
pub fn hand_off(jni: &dyn ShareJni, path: &Path) -> Result<String, String> {
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
