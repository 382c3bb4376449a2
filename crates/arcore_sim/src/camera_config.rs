//! Exported: the camera configs (`ArCameraConfigFilter_*`, `ArCameraConfigList_*`,
//! `ArCameraConfig_*`, `ArSession_getSupportedCameraConfigsWithFilter`,
//! `ArSession_setCameraConfig`, `ArSession_getCameraConfig`). Signatures as in
//! `arcore_c_api.h`.
//!
//! The simulated phone lists its cameras' configs ([`crate::cameras`]). The session starts on
//! the VGA config (ARCore's default CPU image on most
//! phones), and the CPU image it delivers has the size of the config in use
//! ([`crate::state::Sim::advance`]). A config is set only while the session is paused, as
//! ARCore requires.

use std::ffi::c_void;

use ar::arcore::session::status;

use crate::cameras::{CameraConfig, FACING_BACK, FPS_30, FPS_60};
use crate::objects::{Session, free_c, into_c, obj, obj_mut, put};
use crate::state::sim;

type O = c_void;

/// `ArCameraConfigFilter`: ARCore's default allows every rate; the back camera.
pub struct Filter {
    pub fps: u32,
    pub facing: i32,
}

impl Default for Filter {
    fn default() -> Self {
        Self {
            fps: FPS_30 | FPS_60,
            facing: FACING_BACK,
        }
    }
}

/// `ArCameraConfigList`.
#[derive(Default)]
pub struct ConfigList(pub Vec<CameraConfig>);

/// `ArCameraConfig`: empty until filled.
#[derive(Default)]
pub struct ConfigSlot(pub Option<CameraConfig>);

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigFilter_create(_s: *const O, out_filter: *mut *mut O) {
    let mut s = sim("ArCameraConfigFilter_create");
    if out_filter.is_null() {
        return;
    }
    s.made("camera_config_filter");
    // SAFETY: checked non-null.
    unsafe { put(out_filter, into_c(Filter::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigFilter_destroy(filter: *mut O) {
    let mut s = sim("ArCameraConfigFilter_destroy");
    // SAFETY: made by ArCameraConfigFilter_create, destroyed once.
    if unsafe { free_c::<Filter>(filter) } {
        s.released("camera_config_filter");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigFilter_setTargetFps(
    _s: *const O,
    filter: *mut O,
    fps_filters: u32,
) {
    let _s = sim("ArCameraConfigFilter_setTargetFps");
    // SAFETY: a live filter.
    if let Some(f) = unsafe { obj_mut::<Filter>(filter) } {
        f.fps = fps_filters;
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigFilter_setFacingDirection(
    _s: *const O,
    filter: *mut O,
    facing_direction_filter: i32,
) {
    let _s = sim("ArCameraConfigFilter_setFacingDirection");
    // SAFETY: a live filter.
    if let Some(f) = unsafe { obj_mut::<Filter>(filter) } {
        f.facing = facing_direction_filter;
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigList_create(_s: *const O, out_list: *mut *mut O) {
    let mut s = sim("ArCameraConfigList_create");
    if out_list.is_null() {
        return;
    }
    s.made("camera_config_list");
    // SAFETY: checked non-null.
    unsafe { put(out_list, into_c(ConfigList::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigList_destroy(list: *mut O) {
    let mut s = sim("ArCameraConfigList_destroy");
    // SAFETY: made by ArCameraConfigList_create, destroyed once.
    if unsafe { free_c::<ConfigList>(list) } {
        s.released("camera_config_list");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigList_getSize(
    _s: *const O,
    list: *const O,
    out_size: *mut i32,
) {
    let _s = sim("ArCameraConfigList_getSize");
    // SAFETY: a live list and out pointer.
    if let Some(l) = unsafe { obj::<ConfigList>(list) } {
        unsafe { put(out_size, l.0.len() as i32) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfigList_getItem(
    _s: *const O,
    list: *const O,
    index: i32,
    out_camera_config: *mut O,
) {
    let _s = sim("ArCameraConfigList_getItem");
    // SAFETY: a live list and config.
    if let (Some(l), Some(c)) = unsafe {
        (
            obj::<ConfigList>(list),
            obj_mut::<ConfigSlot>(out_camera_config),
        )
    } {
        c.0 = usize::try_from(index)
            .ok()
            .and_then(|i| l.0.get(i))
            .copied();
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_getSupportedCameraConfigsWithFilter(
    _session: *const O,
    filter: *const O,
    list: *mut O,
) {
    let s = sim("ArSession_getSupportedCameraConfigsWithFilter");
    // SAFETY: a live filter (null: ARCore's defaults) and list.
    let default = Filter::default();
    let filter = unsafe { obj::<Filter>(filter) }.unwrap_or(&default);
    if let Some(l) = unsafe { obj_mut::<ConfigList>(list) } {
        l.0 = s
            .camera_configs
            .iter()
            .filter(|c| c.facing == filter.facing && c.target_fps() & filter.fps != 0)
            .copied()
            .collect();
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfig_create(_s: *const O, out_camera_config: *mut *mut O) {
    let mut s = sim("ArCameraConfig_create");
    if out_camera_config.is_null() {
        return;
    }
    s.made("camera_config");
    // SAFETY: checked non-null.
    unsafe { put(out_camera_config, into_c(ConfigSlot::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfig_destroy(camera_config: *mut O) {
    let mut s = sim("ArCameraConfig_destroy");
    // SAFETY: made by ArCameraConfig_create, destroyed once.
    if unsafe { free_c::<ConfigSlot>(camera_config) } {
        s.released("camera_config");
    }
}

/// Reads a filled config into two out pointers.
///
/// SAFETY (callers): a live config, valid out pointers.
unsafe fn config_pair(
    c: *const O,
    a: *mut i32,
    b: *mut i32,
    f: impl Fn(&CameraConfig) -> [i32; 2],
) {
    // SAFETY: per the function's contract.
    if let Some(ConfigSlot(Some(c))) = unsafe { obj::<ConfigSlot>(c) } {
        let [x, y] = f(c);
        unsafe {
            put(a, x);
            put(b, y);
        }
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfig_getImageDimensions(
    _s: *const O,
    camera_config: *const O,
    out_width: *mut i32,
    out_height: *mut i32,
) {
    let _s = sim("ArCameraConfig_getImageDimensions");
    // SAFETY: forwarded contract.
    unsafe { config_pair(camera_config, out_width, out_height, |c| c.image) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfig_getTextureDimensions(
    _s: *const O,
    camera_config: *const O,
    out_width: *mut i32,
    out_height: *mut i32,
) {
    let _s = sim("ArCameraConfig_getTextureDimensions");
    // SAFETY: forwarded contract.
    unsafe { config_pair(camera_config, out_width, out_height, |c| c.texture) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraConfig_getFacingDirection(
    _s: *const O,
    camera_config: *const O,
    out_facing: *mut i32,
) {
    let _s = sim("ArCameraConfig_getFacingDirection");
    // SAFETY: a live config and out pointer.
    if let Some(ConfigSlot(Some(c))) = unsafe { obj::<ConfigSlot>(camera_config) } {
        unsafe { put(out_facing, c.facing) };
    }
}

/// Refused while the session runs (`AR_ERROR_SESSION_NOT_PAUSED`), or for a config that is not
/// one of the phone's (`AR_ERROR_INVALID_ARGUMENT`), or as scripted
/// (`RegattaSim_failCameraConfig`); otherwise the CPU image has the config's size from the
/// next resume.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_setCameraConfig(
    session: *const O,
    camera_config: *const O,
) -> i32 {
    let mut s = sim("ArSession_setCameraConfig");
    // SAFETY: a live session and config (the caller's contract); the session is the app's,
    // not otherwise borrowed during this call.
    let (Some(session), Some(ConfigSlot(Some(config)))) =
        (unsafe { obj_mut::<Session>(session.cast_mut()) }, unsafe {
            obj::<ConfigSlot>(camera_config)
        })
    else {
        return status::ERROR_INVALID_ARGUMENT;
    };
    if session.resumed {
        return status::ERROR_SESSION_NOT_PAUSED;
    }
    if !s.camera_configs.contains(config) {
        return status::ERROR_INVALID_ARGUMENT;
    }
    if let Some(st) = s.script.fail_camera_config.take() {
        return st;
    }
    session.camera = *config;
    s.last_camera_set = Some(*config);
    status::SUCCESS
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_getCameraConfig(session: *const O, out_camera_config: *mut O) {
    let _s = sim("ArSession_getCameraConfig");
    // SAFETY: a live session and config.
    if let (Some(session), Some(c)) = unsafe {
        (
            obj::<Session>(session),
            obj_mut::<ConfigSlot>(out_camera_config),
        )
    } {
        c.0 = Some(session.camera);
    }
}
