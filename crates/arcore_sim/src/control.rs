//! The scripting interface: `RegattaSim_*` functions the host side (tests, `regatta phone-sim`)
//! calls to say what the phone and ARCore do next and to read what the app did. Flags are
//! `int32_t` (0 = no); counts are 64-bit. None of them exists in ARCore.

use std::ffi::{CStr, c_char, c_void};
use std::path::Path;

use crate::cameras::{PhoneCameras, phone_configs, single_config};
use crate::feed::Feed;
use crate::state::{Apk, DESTROY, destroy_gate, sim};

/// The text behind a C string, if it is one.
///
/// SAFETY (callers): `p` is null or a NUL-terminated string.
unsafe fn text<'a>(p: *const c_char) -> Option<&'a str> {
    // SAFETY: per the function's contract.
    (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_str().ok())?
}

/// Back to a fresh run: the default script, no calls counted, no objects live, the feed
/// rewound (the feed itself stays). Destroys still running (on the app's teardown thread)
/// are let through and waited for first, so they count in the run that made them.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_reset() {
    {
        let mut gate = destroy_gate();
        gate.closed = false;
        DESTROY.1.notify_all();
        while gate.finished < gate.started {
            gate = DESTROY.1.wait(gate).unwrap_or_else(|e| e.into_inner());
        }
        *gate = Default::default();
    }
    sim("RegattaSim_reset").reset();
}

/// Plays the replay folder `dir` (`ar::replay` format or TUM RGB-D) from its first frame.
/// 0 on success; -1 with the reason in [`RegattaSim_lastError`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn RegattaSim_openReplay(dir: *const c_char) -> i32 {
    let mut s = sim("RegattaSim_openReplay");
    // SAFETY: the caller passes a C string.
    let Some(dir) = (unsafe { text(dir) }) else {
        s.last_error = "RegattaSim_openReplay: the path is not UTF-8".into();
        return -1;
    };
    match Feed::open(Path::new(dir)) {
        Ok(feed) => {
            // A replay was recorded at one size: the simulated phone offers that one.
            let configs = feed.recorded_size().map(|[w, h]| single_config(w, h));
            s.use_feed(feed, configs.unwrap_or_default());
            0
        }
        Err(e) => {
            s.last_error = e;
            -1
        }
    }
}

/// Plays the synthetic table feed at `width` × `height` pixels, `frames` frames a loop (a
/// phone camera's full-size image, e.g. 4032 × 3024, for the texture-limit tests), on a phone
/// whose camera offers that one size.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_useSynth(width: u32, height: u32, frames: u32) {
    let mut s = sim("RegattaSim_useSynth");
    let (width, height) = (width.max(2), height.max(2));
    let feed = Feed::Synth(ar::SynthConfig {
        width,
        height,
        frames: frames.max(1) as usize,
        ..crate::feed::default_synth()
    });
    s.use_feed(feed, single_config(width, height));
}

/// Plays the synthetic table feed (`frames` frames a loop) on a phone offering the camera
/// configs of `arcore_c_api.h`'s back camera (`camera_config`): 0 an OPPO A54 class phone
/// (640 × 480, 1280 × 720, 1920 × 1080 CPU images at 30 fps, a 1920 × 1080 texture, and the
/// front camera's), 1 a Pixel 2 XL class phone (the same, and again at 60 fps). A new session
/// uses the 640 × 480 config, ARCore's default.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_useCameraConfigs(phone: i32, frames: u32) {
    let mut s = sim("RegattaSim_useCameraConfigs");
    let phone = match phone {
        1 => PhoneCameras::SixtyFps,
        _ => PhoneCameras::ThirtyFps,
    };
    let feed = Feed::Synth(ar::SynthConfig {
        frames: frames.max(1) as usize,
        ..crate::feed::default_synth()
    });
    s.use_feed(feed, phone_configs(phone));
}

/// The highest capture rate (fps) of the config last set with `ArSession_setCameraConfig`
/// (0: none set since the reset).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_lastCameraConfigFps() -> i32 {
    sim("RegattaSim_lastCameraConfigFps")
        .last_camera_set
        .map_or(0, |c| c.fps[1])
}

/// The next `ArSession_setCameraConfig` on a paused session returns `status` (0: none).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_failCameraConfig(status: i32) {
    sim("RegattaSim_failCameraConfig").script.fail_camera_config = (status != 0).then_some(status);
}

/// Copies the last error (UTF-8, NUL-terminated, truncated to `len`) into `buf`; returns its
/// full length in bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn RegattaSim_lastError(buf: *mut c_char, len: usize) -> usize {
    let s = sim("RegattaSim_lastError");
    let bytes = s.last_error.as_bytes();
    if !buf.is_null() && len > 0 {
        let n = bytes.len().min(len - 1);
        // SAFETY: the caller's buffer holds `len` bytes.
        unsafe {
            std::ptr::copy_nonoverlapping(bytes.as_ptr().cast(), buf, n);
            buf.add(n).write(0);
        }
    }
    bytes.len()
}

/// `ArCoreApk_requestInstall`'s world: 0 installed, 1 missing (the user declines the
/// install), 2 installable (the install succeeds), 3 unsupported device.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setApk(mode: i32) {
    let mut s = sim("RegattaSim_setApk");
    s.script.apk = match mode {
        1 => Apk::Missing,
        2 => Apk::Installable,
        3 => Apk::Unsupported,
        _ => Apk::Installed,
    };
    s.install_pending = false;
}

/// The Java class ARCore's native half fails to find (`com.google.ar.core.ArCoreApk` for
/// `ArCoreApk_requestInstall`, `com.google.ar.core.SessionCreateJniHelper` for
/// `ArSession_create`), as in an APK without ARCore's classes: the call that needs it returns
/// `AR_ERROR_FATAL` with `java.lang.ClassNotFoundException` pending in its env. Null: none.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn RegattaSim_failClassLookup(class_name: *const c_char) {
    // SAFETY: the caller passes null or a C string.
    let class = unsafe { text(class_name) }.map(str::to_string);
    sim("RegattaSim_failClassLookup").script.missing_class = class;
}

/// The next call of the exported ARCore function `function` does its work as usual and leaves
/// the Java exception `exception` (`class: message`) pending in its env, as when ARCore's Java
/// half throws after the native call succeeded. Null `function`: none.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn RegattaSim_throwAfter(function: *const c_char, exception: *const c_char) {
    // SAFETY: the caller passes null or C strings.
    let (f, e) = unsafe { (text(function), text(exception)) };
    sim("RegattaSim_throwAfter").script.throw_after = f.map(|f| {
        (
            f.to_string(),
            e.unwrap_or("java.lang.RuntimeException").to_string(),
        )
    });
}

/// The `jobject` that is the Activity: `ArCoreApk_requestInstall` fails (`AR_ERROR_FATAL`,
/// as ARCore's Java side throws) when given another object. Null: accept any.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_expectActivity(activity: *mut c_void) {
    sim("RegattaSim_expectActivity").script.activity = activity as usize;
}

/// The `jobject`s the app passed to `ArCoreApk_requestInstall` and to `ArSession_create`.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_installObject() -> *mut c_void {
    sim("RegattaSim_installObject").install_object as *mut c_void
}

#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_createContext() -> *mut c_void {
    sim("RegattaSim_createContext").create_context as *mut c_void
}

/// `Build.VERSION.SDK_INT`: below 27 hardware-buffer texture mode is refused
/// (`AR_ERROR_UNSUPPORTED_CONFIGURATION`).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setApiLevel(level: i32) {
    sim("RegattaSim_setApiLevel").script.api_level = level.max(0) as u32;
}

/// Whether Environmental HDR light estimation is supported (else configuring it fails).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setHdrSupported(supported: i32) {
    sim("RegattaSim_setHdrSupported").script.hdr_supported = supported != 0;
}

/// Whether the camera can be opened (else resume and update give
/// `AR_ERROR_CAMERA_NOT_AVAILABLE`, and `ArSession_create` too).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setCameraAvailable(available: i32) {
    sim("RegattaSim_setCameraAvailable").script.camera_available = available != 0;
}

/// The camera's `ArTrackingState` (0 tracking, 1 paused, 2 stopped) and
/// `ArTrackingFailureReason` (0 none … 5 camera unavailable).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setTracking(state: i32, reason: i32) {
    sim("RegattaSim_setTracking").script.tracking = (state, reason);
}

/// The light estimate: valid or not, and the direction towards the main light (HDR mode).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setLight(valid: i32, x: f32, y: f32, z: f32) {
    let mut s = sim("RegattaSim_setLight");
    s.script.light_valid = valid != 0;
    s.script.light_towards = [x, y, z];
}

/// The next `count` calls of `ArSession_update` return `status` (a session error).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_failUpdates(status: i32, count: u32) {
    sim("RegattaSim_failUpdates").script.fail_updates = (status, count);
}

/// The next `ArSession_resume` returns `status`.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_failResume(status: i32) {
    sim("RegattaSim_failResume").script.fail_resume = Some(status);
}

/// While set, updates keep the current image and timestamp (no new camera frame).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_holdFrame(hold: i32) {
    sim("RegattaSim_holdFrame").script.hold_frame = hold != 0;
}

/// Whether the table is detected (listed by `ArSession_getAllTrackables`).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setPlanesVisible(visible: i32) {
    sim("RegattaSim_setPlanesVisible").script.planes_visible = visible != 0;
}

/// Lists a second plane identical to the table and subsumed by it.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setSubsumedCopy(on: i32) {
    sim("RegattaSim_setSubsumedCopy").script.subsumed_copy = on != 0;
}

/// The feed frame shown now (-1 before the first update).
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_frameIndex() -> i64 {
    sim("RegattaSim_frameIndex")
        .shown
        .as_ref()
        .map_or(-1, |f| f.index as i64)
}

/// While set, `ArSession_destroy` blocks (until this is cleared), as ARCore's takes seconds.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_setDestroyBlocking(block: i32) {
    destroy_gate().closed = block != 0;
    DESTROY.1.notify_all();
}

/// Blocks until `ArSession_destroy` has been entered `n` times in all.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_waitDestroyStarted(n: u64) {
    let mut gate = destroy_gate();
    while gate.started < n {
        gate = DESTROY.1.wait(gate).unwrap_or_else(|e| e.into_inner());
    }
}

/// How many `ArSession_destroy` calls have returned.
#[unsafe(no_mangle)]
pub extern "C" fn RegattaSim_destroysFinished() -> u64 {
    destroy_gate().finished
}

/// Calls of the exported ARCore function `name` since the last reset.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn RegattaSim_callCount(name: *const c_char) -> u64 {
    let s = sim("RegattaSim_callCount");
    // SAFETY: the caller passes a C string.
    unsafe { text(name) }.map_or(0, |n| s.calls.get(n).copied().unwrap_or(0))
}

/// Objects made and not yet released/destroyed, of `kind` (`session`, `frame`, `config`,
/// `camera`, `image`, `pose`, `intrinsics`, `light`, `list`, `trackable`, `camera_config`,
/// `camera_config_list`, `camera_config_filter`), or of every kind when `kind` is null.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn RegattaSim_liveObjects(kind: *const c_char) -> i64 {
    let s = sim("RegattaSim_liveObjects");
    // SAFETY: the caller passes null or a C string.
    match unsafe { text(kind) } {
        Some(k) => s.live.get(k).copied().unwrap_or(0),
        None => s.live.values().sum(),
    }
}
