//! The camera config through the C API: the configs ARCore offers for the back camera at
//! 30 fps (`ArSession_getSupportedCameraConfigsWithFilter`), the one in use
//! (`ArSession_getCameraConfig`), and setting the one [`choose_camera_config`] picks
//! (`ArSession_setCameraConfig`, which ARCore accepts only while the session is paused).
//!
//! Only [`super::api`] is imported: the session (`super::session`) calls in here.

use super::api::{CameraConfigApi, O, S, consts};
use crate::arcore::camera_config::{CameraConfigSize, choose_camera_config};
use crate::arcore::session::status;

/// What the session should afford for its camera image (from the quality tier).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CameraBudget {
    /// The largest CPU image, pixels, whose upload and conversion fit the tier's share of a
    /// frame (`quality::TierSettings::camera_image_max_px`).
    pub max_image_px: u64,
    /// The screen (or view), pixels, for the shape tie-break; `None` when not known yet.
    pub screen: Option<[u32; 2]>,
}

/// What [`apply`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraConfigOutcome {
    /// ARCore listed no back-camera config at 30 fps: whatever it uses stays.
    NoneOffered,
    /// The config chosen is the one in use: nothing was set.
    Kept(CameraConfigSize),
    /// ARCore took the config chosen; it applies from the next resume.
    Set(CameraConfigSize),
    /// ARCore refused it (`status`, e.g. `AR_ERROR_SESSION_NOT_PAUSED`): the config in use
    /// (`kept`, as ARCore reports it) stays, and the session goes on.
    Refused {
        wanted: CameraConfigSize,
        status: i32,
        kept: Option<CameraConfigSize>,
    },
}

/// A config's sizes and facing direction.
///
/// SAFETY (callers): live session `s` and config `c`.
unsafe fn read(api: &CameraConfigApi, s: S, c: S) -> (CameraConfigSize, i32) {
    let (mut iw, mut ih, mut tw, mut th, mut facing) = (0, 0, 0, 0, -1);
    // SAFETY: per the function's contract.
    unsafe {
        (api.image_size)(s, c, &mut iw, &mut ih);
        (api.texture_size)(s, c, &mut tw, &mut th);
        (api.facing)(s, c, &mut facing);
    }
    let px = |v: i32| v.max(0) as u32;
    let size = CameraConfigSize {
        image: [px(iw), px(ih)],
        texture: [px(tw), px(th)],
    };
    (size, facing)
}

/// The config the session uses now (ARCore's default until one is set).
///
/// SAFETY (callers): live session `s`.
pub(super) unsafe fn current(api: &CameraConfigApi, s: S) -> Option<CameraConfigSize> {
    let mut c = std::ptr::null_mut();
    // SAFETY: live session; the config is destroyed here.
    unsafe {
        (api.config_create)(s, &mut c);
        if c.is_null() {
            return None;
        }
        (api.session_get)(s, c);
        let (size, _) = read(api, s, c);
        (api.config_destroy)(c);
        (size.image_px() > 0).then_some(size)
    }
}

/// Chooses the back camera's 30 fps config with the largest CPU image within `budget` and sets
/// it when it is not the one in use. A refusal leaves the session as it was.
///
/// 30 fps only: ARCore's default rate on every phone; a 60 fps camera doubles the images to
/// upload and convert each second and, ARCore warns, the power drawn.
///
/// SAFETY (callers): live session `s` (paused, or ARCore refuses, which is handled).
pub(super) unsafe fn apply(
    api: &CameraConfigApi,
    s: *mut O,
    budget: CameraBudget,
) -> CameraConfigOutcome {
    let s = s as S;
    let (mut filter, mut list) = (std::ptr::null_mut(), std::ptr::null_mut());
    // SAFETY: live session; the filter, the list and every config made here are destroyed
    // here.
    unsafe {
        (api.filter_create)(s, &mut filter);
        (api.filter_set_target_fps)(s, filter, consts::CAMERA_TARGET_FPS_30);
        (api.filter_set_facing)(s, filter, consts::CAMERA_FACING_BACK);
        (api.list_create)(s, &mut list);
        (api.supported)(s, filter, list);
        (api.filter_destroy)(filter);
        let mut n = 0;
        (api.list_size)(s, list, &mut n);
        // Index in ARCore's list of each config kept (back camera, a real image).
        let mut listed = Vec::new();
        let mut config = std::ptr::null_mut();
        (api.config_create)(s, &mut config);
        for i in 0..n.max(0) {
            (api.list_item)(s, list, i, config);
            let (size, facing) = read(api, s, config);
            if facing == consts::CAMERA_FACING_BACK && size.image_px() > 0 {
                listed.push((i, size));
            }
        }
        let sizes: Vec<CameraConfigSize> = listed.iter().map(|&(_, c)| c).collect();
        let outcome = match choose_camera_config(&sizes, budget.max_image_px, budget.screen) {
            None => CameraConfigOutcome::NoneOffered,
            Some(k) => {
                let (i, wanted) = listed[k];
                let in_use = current(api, s);
                if in_use == Some(wanted) {
                    CameraConfigOutcome::Kept(wanted)
                } else {
                    (api.list_item)(s, list, i, config);
                    match (api.session_set)(s, config) {
                        status::SUCCESS => CameraConfigOutcome::Set(wanted),
                        st => CameraConfigOutcome::Refused {
                            wanted,
                            status: st,
                            kept: in_use,
                        },
                    }
                }
            }
        };
        (api.config_destroy)(config);
        (api.list_destroy)(list);
        outcome
    }
}

/// One log line for what [`apply`] did.
pub(super) fn log_outcome(outcome: &CameraConfigOutcome, budget: CameraBudget) {
    let show = |c: &CameraConfigSize| format!("{} × {}", c.image[0], c.image[1]);
    match outcome {
        CameraConfigOutcome::NoneOffered => log::warn!(
            "regatta: ARCore lists no back-camera config at 30 fps; its default camera image stays"
        ),
        CameraConfigOutcome::Kept(c) => log::info!(
            "regatta: camera image {} (budget {} px) already in use",
            show(c),
            budget.max_image_px
        ),
        CameraConfigOutcome::Set(c) => log::info!(
            "regatta: camera image {} (budget {} px) from the next resume",
            show(c),
            budget.max_image_px
        ),
        CameraConfigOutcome::Refused {
            wanted,
            status,
            kept,
        } => log::warn!(
            "regatta: ARCore refused the camera config with a {} image (status {status}); \
             keeping {}",
            show(wanted),
            kept.as_ref().map_or("its default".to_string(), show)
        ),
    }
}
