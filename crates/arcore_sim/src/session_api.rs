//! Exported: `ArCoreApk_requestInstall`, `ArSession_*` lifecycle and configuration,
//! `ArConfig_*`, `ArFrame_create`/`destroy`. Signatures as in `arcore_c_api.h`.

use std::ffi::c_void;

use ar::arcore::session::status;

use crate::objects::{Config, Frame, Session, free_c, into_c, obj, obj_mut, put};
use crate::state::{Apk, DESTROY, Sim, destroy_gate, sim};

type O = c_void;

/// `AR_INSTALL_STATUS_INSTALLED`, `AR_INSTALL_STATUS_INSTALL_REQUESTED`.
const INSTALLED: i32 = 0;
const INSTALL_REQUESTED: i32 = 1;
/// `AR_LIGHT_ESTIMATION_MODE_ENVIRONMENTAL_HDR`, `AR_TEXTURE_UPDATE_MODE_EXPOSE_HARDWARE_BUFFER`.
const LIGHT_HDR: i32 = 2;
const TEXTURE_HARDWARE_BUFFER: i32 = 1;

/// The layout of the host's fake `JNIEnv` (`ar::arcore::ffi::jni::HostEnv`, repeated here
/// because the simulator answers the C API only): a magic number, then the pending exception.
#[repr(C)]
struct HostEnv {
    magic: u64,
    exception: [u8; 256],
}

const HOST_ENV_MAGIC: u64 = 0x4A4E_4945_4E56_0001;

/// Leaves `exception` pending in `env` when it is the host's fake env (any other env, e.g. a
/// test's dummy pointer, is not touched).
///
/// SAFETY: `env` is null, the host's `HostEnv`, or points to at least 8 readable bytes.
unsafe fn throw(env: *mut O, exception: &str) {
    let env = env.cast::<HostEnv>();
    // SAFETY: per the contract; the magic is read before anything is written.
    unsafe {
        if env.is_null() || (*env).magic != HOST_ENV_MAGIC {
            return;
        }
        let slot = &mut (*env).exception;
        let n = exception.len().min(slot.len() - 1);
        slot[..n].copy_from_slice(&exception.as_bytes()[..n]);
        slot[n] = 0;
    }
}

/// The Java exception a call of `function` needing the Java class `class` leaves pending, if
/// the script says so: a class not found fails the call (`true`), a throw after does not.
fn java_failure(s: &mut Sim, function: &str, class: &str) -> Option<(String, bool)> {
    if s.script.missing_class.as_deref() == Some(class) {
        return Some((
            format!("java.lang.ClassNotFoundException: Didn't find class \"{class}\""),
            true,
        ));
    }
    match &s.script.throw_after {
        Some((f, e)) if f == function => {
            let e = e.clone();
            s.script.throw_after = None;
            Some((e, false))
        }
        _ => None,
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCoreApk_requestInstall(
    env: *mut O,
    application_activity: *mut O,
    user_requested_install: i32,
    out_install_status: *mut i32,
) -> i32 {
    let mut s = sim("ArCoreApk_requestInstall");
    s.install_object = application_activity as usize;
    // ARCore's Java side calls startActivity on this object: anything but the Activity throws.
    let expected = s.script.activity;
    if env.is_null() || application_activity.is_null() {
        return status::ERROR_INVALID_ARGUMENT;
    }
    if expected != 0 && application_activity as usize != expected {
        s.last_error = "ArCoreApk_requestInstall: the object is not the Activity".into();
        return status::ERROR_FATAL;
    }
    let java = java_failure(
        &mut s,
        "ArCoreApk_requestInstall",
        "com.google.ar.core.ArCoreApk",
    );
    if let Some((exception, true)) = &java {
        // SAFETY: the app's env (see `throw`).
        unsafe { throw(env, exception) };
        return status::ERROR_FATAL;
    }
    let (st, install) = match (s.script.apk, s.install_pending) {
        (Apk::Installed, _) => (status::SUCCESS, INSTALLED),
        (Apk::Unsupported, _) => (status::UNAVAILABLE_DEVICE_NOT_COMPATIBLE, 0),
        (Apk::Missing | Apk::Installable, false) if user_requested_install != 0 => {
            s.install_pending = true;
            (status::SUCCESS, INSTALL_REQUESTED)
        }
        (Apk::Installable, true) => {
            s.script.apk = Apk::Installed;
            s.install_pending = false;
            (status::SUCCESS, INSTALLED)
        }
        (Apk::Missing | Apk::Installable, _) => {
            s.install_pending = false;
            (status::UNAVAILABLE_USER_DECLINED_INSTALLATION, 0)
        }
    };
    // SAFETY: ARCore's contract: a valid out pointer; the app's env (see `throw`).
    unsafe {
        put(out_install_status, install);
        if let Some((exception, _)) = &java {
            throw(env, exception);
        }
    }
    st
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_create(
    env: *mut O,
    context: *mut O,
    out_session_pointer: *mut *mut O,
) -> i32 {
    let mut s = sim("ArSession_create");
    s.create_context = context as usize;
    if env.is_null() || context.is_null() || out_session_pointer.is_null() {
        return status::ERROR_INVALID_ARGUMENT;
    }
    if !s.script.camera_available {
        return status::ERROR_CAMERA_NOT_AVAILABLE;
    }
    if s.script.apk != Apk::Installed {
        return status::UNAVAILABLE_ARCORE_NOT_INSTALLED;
    }
    let java = java_failure(
        &mut s,
        "ArSession_create",
        "com.google.ar.core.SessionCreateJniHelper",
    );
    if let Some((exception, true)) = &java {
        // SAFETY: the app's env (see `throw`).
        unsafe { throw(env, exception) };
        return status::ERROR_FATAL;
    }
    s.made("session");
    let session = into_c(Session {
        light_mode: 0,
        resumed: false,
        camera: s.default_camera_config(),
        resumed_camera: None,
        rotation: 0,
        view: (0, 0),
    });
    // SAFETY: checked non-null above; the app's env (see `throw`).
    unsafe {
        put(out_session_pointer, session);
        if let Some((exception, _)) = &java {
            throw(env, exception);
        }
    }
    status::SUCCESS
}

/// Blocks while the destroy gate is closed (`RegattaSim_setDestroyBlocking`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_destroy(session: *mut O) {
    {
        let mut gate = destroy_gate();
        gate.started += 1;
        DESTROY.1.notify_all();
        while gate.closed {
            gate = DESTROY.1.wait(gate).unwrap_or_else(|e| e.into_inner());
        }
    }
    let mut s = sim("ArSession_destroy");
    // SAFETY: a session made by ArSession_create, destroyed once (the app's contract).
    if unsafe { free_c::<Session>(session) } {
        s.released("session");
    }
    drop(s);
    destroy_gate().finished += 1;
    DESTROY.1.notify_all();
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArConfig_create(_session: *const O, out_config: *mut *mut O) {
    let mut s = sim("ArConfig_create");
    if out_config.is_null() {
        return;
    }
    s.made("config");
    // SAFETY: checked non-null.
    unsafe { put(out_config, into_c(Config::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArConfig_destroy(config: *mut O) {
    let mut s = sim("ArConfig_destroy");
    // SAFETY: a config made by ArConfig_create, destroyed once.
    if unsafe { free_c::<Config>(config) } {
        s.released("config");
    }
}

macro_rules! config_setter {
    ($name:ident, $field:ident) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(_session: *const O, config: *mut O, value: i32) {
            let _s = sim(stringify!($name));
            // SAFETY: a live config (the caller's contract).
            if let Some(c) = unsafe { obj_mut::<Config>(config) } {
                c.$field = value;
            }
        }
    };
}

config_setter!(ArConfig_setPlaneFindingMode, plane_finding);
config_setter!(ArConfig_setLightEstimationMode, light);
config_setter!(ArConfig_setUpdateMode, update);
config_setter!(ArConfig_setTextureUpdateMode, texture);

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_configure(session: *mut O, config: *const O) -> i32 {
    let s = sim("ArSession_configure");
    // SAFETY: live session and config (the caller's contract).
    let (Some(session), Some(config)) = (unsafe { obj_mut::<Session>(session) }, unsafe {
        obj::<Config>(config)
    }) else {
        return status::ERROR_INVALID_ARGUMENT;
    };
    if config.light == LIGHT_HDR && !s.script.hdr_supported {
        return status::ERROR_UNSUPPORTED_CONFIGURATION;
    }
    if config.texture == TEXTURE_HARDWARE_BUFFER && s.script.api_level < 27 {
        return status::ERROR_UNSUPPORTED_CONFIGURATION;
    }
    session.light_mode = config.light;
    status::SUCCESS
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_resume(session: *mut O) -> i32 {
    let mut s = sim("ArSession_resume");
    // SAFETY: a live session.
    let Some(session) = (unsafe { obj_mut::<Session>(session) }) else {
        return status::ERROR_INVALID_ARGUMENT;
    };
    if let Some(st) = s.script.fail_resume.take() {
        return st;
    }
    if !s.script.camera_available {
        return status::ERROR_CAMERA_NOT_AVAILABLE;
    }
    // A new camera config needs every camera image released first (`arcore_c_api.h`,
    // `ArSession_setCameraConfig`).
    let images_held = s.live.get("image").copied().unwrap_or(0) > 0;
    if session.resumed_camera.is_some_and(|c| c != session.camera) && images_held {
        return status::ERROR_ILLEGAL_STATE;
    }
    session.resumed = true;
    session.resumed_camera = Some(session.camera);
    status::SUCCESS
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_pause(session: *mut O) -> i32 {
    let _s = sim("ArSession_pause");
    // SAFETY: a live session.
    let Some(session) = (unsafe { obj_mut::<Session>(session) }) else {
        return status::ERROR_INVALID_ARGUMENT;
    };
    session.resumed = false;
    status::SUCCESS
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_update(session: *mut O, frame: *mut O) -> i32 {
    let mut s = sim("ArSession_update");
    // SAFETY: live session and frame.
    let (Some(session), Some(frame)) = (unsafe { obj::<Session>(session) }, unsafe {
        obj_mut::<Frame>(frame)
    }) else {
        return status::ERROR_INVALID_ARGUMENT;
    };
    if !session.resumed {
        return status::ERROR_SESSION_PAUSED;
    }
    if let (st, n @ 1..) = s.script.fail_updates {
        s.script.fail_updates.1 = n - 1;
        return st;
    }
    if !s.script.camera_available {
        return status::ERROR_CAMERA_NOT_AVAILABLE;
    }
    let image = session.camera.image.map(|v| v.max(0) as u32);
    if let Err(e) = s.advance(image) {
        log::error!("arcore_sim: {e}");
        s.last_error = e;
        return status::ERROR_FATAL;
    }
    if let Some(shown) = &s.shown {
        frame.timestamp_ns = shown.timestamp_ns;
        frame.updated = true;
    }
    status::SUCCESS
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_setDisplayGeometry(
    session: *mut O,
    rotation: i32,
    width: i32,
    height: i32,
) {
    let _s = sim("ArSession_setDisplayGeometry");
    // SAFETY: a live session.
    if let Some(session) = unsafe { obj_mut::<Session>(session) } {
        session.rotation = rotation.rem_euclid(4);
        session.view = (width.max(0), height.max(0));
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_create(_session: *const O, out_frame: *mut *mut O) {
    let mut s = sim("ArFrame_create");
    if out_frame.is_null() {
        return;
    }
    s.made("frame");
    // SAFETY: checked non-null.
    unsafe { put(out_frame, into_c(Frame::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_destroy(frame: *mut O) {
    let mut s = sim("ArFrame_destroy");
    // SAFETY: a frame made by ArFrame_create, destroyed once.
    if unsafe { free_c::<Frame>(frame) } {
        s.released("frame");
    }
}
