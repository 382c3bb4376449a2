//! The simulator's state: one per process (the C API has no context argument besides the
//! session), behind a mutex. The script says what ARCore and the phone do; the counters say
//! what the app called and what it still holds.

use std::collections::BTreeMap;
use std::sync::{Condvar, LazyLock, Mutex, MutexGuard};

use ar::CameraFrame;
use glam::Mat4;

use crate::cameras::{CameraConfig, PhoneCameras, phone_configs, single_config};
use crate::feed::{Feed, PhoneImage, default_synth};

/// ARCore's answer to `ArCoreApk_requestInstall` (`RegattaSim_setApk`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Apk {
    /// Google Play Services for AR is installed.
    Installed,
    /// Not installed; the user declines the Play Store's offer.
    Missing,
    /// Not installed; the install succeeds (the next check, on return, finds it).
    Installable,
    /// The phone is not ARCore-certified.
    Unsupported,
}

/// What the simulated phone and ARCore do.
#[derive(Clone, Debug)]
pub struct Script {
    pub apk: Apk,
    /// The `jobject` ARCore accepts as the Activity in `ArCoreApk_requestInstall` (0: any).
    pub activity: usize,
    /// `Build.VERSION.SDK_INT` (hardware-buffer texture mode needs 27).
    pub api_level: u32,
    pub hdr_supported: bool,
    pub camera_available: bool,
    /// `ArTrackingState` and `ArTrackingFailureReason` of the camera.
    pub tracking: (i32, i32),
    pub light_valid: bool,
    /// Towards the main light, AR world axes (Environmental HDR).
    pub light_towards: [f32; 3],
    /// The next updates fail with this status, this many times.
    pub fail_updates: (i32, u32),
    /// `ArSession_resume` fails once with this status.
    pub fail_resume: Option<i32>,
    /// Updates keep the current camera image (same timestamp).
    pub hold_frame: bool,
    pub planes_visible: bool,
    /// A second plane, merged into the table (`ArPlane_acquireSubsumedBy` gives the table).
    pub subsumed_copy: bool,
    /// A Java class ARCore's native half cannot find (its DEX is not in the APK): the C call
    /// that needs it fails with `ClassNotFoundException` pending (`RegattaSim_failClassLookup`).
    pub missing_class: Option<String>,
    /// The next call of this exported function does its work and leaves this Java exception
    /// pending (`RegattaSim_throwAfter`).
    pub throw_after: Option<(String, String)>,
    /// The next `ArSession_setCameraConfig` of a paused session fails with this status
    /// (`RegattaSim_failCameraConfig`).
    pub fail_camera_config: Option<i32>,
}

impl Default for Script {
    fn default() -> Self {
        Self {
            apk: Apk::Installed,
            activity: 0,
            api_level: 30,
            hdr_supported: true,
            camera_available: true,
            tracking: (0, 0),
            light_valid: true,
            light_towards: [0.36, 0.8, 0.48],
            fail_updates: (0, 0),
            fail_resume: None,
            hold_frame: false,
            planes_visible: true,
            subsumed_copy: false,
            missing_class: None,
            throw_after: None,
            fail_camera_config: None,
        }
    }
}

/// The frame ARCore shows: which feed frame, when, and as what image.
pub struct Shown {
    pub index: usize,
    pub timestamp_ns: i64,
    pub frame: CameraFrame,
    pub image: PhoneImage,
}

pub struct Sim {
    pub script: Script,
    pub feed: Feed,
    /// The camera configs the phone offers (`camera_config`), and the one a new session uses.
    pub camera_configs: Vec<CameraConfig>,
    pub default_camera: usize,
    /// The config of the last successful `ArSession_setCameraConfig`.
    pub last_camera_set: Option<CameraConfig>,
    /// Calls per exported function name.
    pub calls: BTreeMap<&'static str, u64>,
    /// Live objects per kind (`session`, `frame`, `camera`, `image`, `trackable`, …).
    pub live: BTreeMap<&'static str, i64>,
    /// Updates so far: frame `n % len` of loop `n / len` shows after update `n + 1`.
    pub updates: u64,
    pub shown: Option<Shown>,
    /// The last good camera pose (a paused camera keeps it).
    pub last_pose: Option<Mat4>,
    /// The `jobject`s the app passed to `ArCoreApk_requestInstall` and `ArSession_create`.
    pub install_object: usize,
    pub create_context: usize,
    /// An install was requested and not yet answered (`Apk::Missing`, `Apk::Installable`).
    pub install_pending: bool,
    pub last_error: String,
}

impl Sim {
    fn new() -> Self {
        let mut sim = Self::new_without_feed();
        if let Some(dir) = std::env::var_os("REGATTA_SIM_REPLAY") {
            match Feed::open(std::path::Path::new(&dir)) {
                Ok(feed) => {
                    let configs = feed.recorded_size().map(|[w, h]| single_config(w, h));
                    sim.use_feed(feed, configs.unwrap_or_default());
                }
                Err(e) => log::error!("arcore_sim: {e}; playing the synthetic feed"),
            }
        }
        sim
    }

    /// Back to the start of a run (the feed and the camera configs that go with it stay).
    pub fn reset(&mut self) {
        let feed = std::mem::replace(&mut self.feed, Feed::Synth(default_synth()));
        let camera_configs = std::mem::take(&mut self.camera_configs);
        *self = Self {
            feed,
            camera_configs,
            default_camera: self.default_camera,
            ..Self::new_without_feed()
        };
    }

    /// The config a new session uses.
    pub fn default_camera_config(&self) -> CameraConfig {
        self.camera_configs[self.default_camera.min(self.camera_configs.len() - 1)]
    }

    /// Plays `feed` on a phone offering `configs` (the first session config at `default`).
    pub fn use_feed(&mut self, feed: Feed, (configs, default): (Vec<CameraConfig>, usize)) {
        self.feed = feed;
        if !configs.is_empty() {
            self.camera_configs = configs;
            self.default_camera = default;
        }
        self.updates = 0;
        self.shown = None;
    }

    fn new_without_feed() -> Self {
        let (camera_configs, default_camera) = phone_configs(PhoneCameras::ThirtyFps);
        Self {
            script: Script::default(),
            feed: Feed::Synth(default_synth()),
            camera_configs,
            default_camera,
            last_camera_set: None,
            calls: BTreeMap::new(),
            live: BTreeMap::new(),
            updates: 0,
            shown: None,
            last_pose: None,
            install_object: 0,
            create_context: 0,
            install_pending: false,
            last_error: String::new(),
        }
    }

    pub fn count(&mut self, name: &'static str) {
        *self.calls.entry(name).or_default() += 1;
    }

    pub fn made(&mut self, kind: &'static str) {
        *self.live.entry(kind).or_default() += 1;
    }

    pub fn released(&mut self, kind: &'static str) {
        *self.live.entry(kind).or_default() -= 1;
    }

    /// Shows the next frame of the feed (looping) with a CPU image of `image` pixels (the
    /// session's camera config), unless the script holds the current one.
    pub fn advance(&mut self, image: [u32; 2]) -> Result<(), String> {
        if self.script.hold_frame && self.shown.is_some() {
            return Ok(());
        }
        let n = self.feed.frames() as u64;
        let index = (self.updates % n) as usize;
        let lap = self.updates / n;
        self.updates += 1;
        let frame = self.feed.frame(index, image)?;
        let image = PhoneImage::from_frame(&frame.image)?;
        let t = lap as f64 * self.feed.period() + frame.timestamp;
        self.shown = Some(Shown {
            index,
            // Nanoseconds of a sensor clock that did not start at zero.
            timestamp_ns: 1_000_000_000 + (t * 1e9).round() as i64,
            frame,
            image,
        });
        Ok(())
    }
}

static SIM: LazyLock<Mutex<Sim>> = LazyLock::new(|| Mutex::new(Sim::new()));

/// The simulator, counting a call to `name`.
pub fn sim(name: &'static str) -> MutexGuard<'static, Sim> {
    let mut s = SIM.lock().unwrap_or_else(|e| e.into_inner());
    s.count(name);
    s
}

/// `ArSession_destroy` blocks while the gate is closed (`RegattaSim_setDestroyBlocking`), so a
/// test sees that the app does not wait for it.
#[derive(Default)]
pub struct DestroyGate {
    pub closed: bool,
    pub started: u64,
    pub finished: u64,
}

pub static DESTROY: LazyLock<(Mutex<DestroyGate>, Condvar)> =
    LazyLock::new(|| (Mutex::new(DestroyGate::default()), Condvar::new()));

pub fn destroy_gate() -> MutexGuard<'static, DestroyGate> {
    DESTROY.0.lock().unwrap_or_else(|e| e.into_inner())
}
