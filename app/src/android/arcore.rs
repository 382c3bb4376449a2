//! The ARCore C API, loaded at run time from `libarcore_sdk_c.so` (packaged from Google's AAR by
//! `scripts/build-apk.sh --arcore-aar`), and the JNI calls around it (camera permission). It
//! carries out the session state machine's [`Command`]s and answers with [`Event`]s; all
//! decisions are in `ar::arcore::session`.
//!
//! Per frame: `ArSession_update` here, then `frame.rs` reads the camera, its image, the planes
//! and the light estimate into an [`ar::CameraFrame`] ([`ar::FrameSource`] for [`ArCore`]).

use std::ffi::c_void;

use ar::arcore::session::status;
use ar::arcore::{Command, Event, LightMode};
use jni::objects::JObject;
use jni::{JValue, jni_sig, jni_str};

type Status = i32;
type Opaque = c_void;

/// Function pointers of the ARCore C API (signatures from `arcore_c_api.h`).
struct Api {
    request_install: unsafe extern "C" fn(*mut c_void, *mut c_void, i32, *mut i32) -> Status,
    session_create: unsafe extern "C" fn(*mut c_void, *mut c_void, *mut *mut Opaque) -> Status,
    session_destroy: unsafe extern "C" fn(*mut Opaque),
    config_create: unsafe extern "C" fn(*const Opaque, *mut *mut Opaque),
    config_destroy: unsafe extern "C" fn(*mut Opaque),
    config_set_plane_finding: unsafe extern "C" fn(*const Opaque, *mut Opaque, i32),
    config_set_light: unsafe extern "C" fn(*const Opaque, *mut Opaque, i32),
    config_set_update: unsafe extern "C" fn(*const Opaque, *mut Opaque, i32),
    config_set_texture_update: unsafe extern "C" fn(*const Opaque, *mut Opaque, i32),
    session_configure: unsafe extern "C" fn(*mut Opaque, *const Opaque) -> Status,
    session_resume: unsafe extern "C" fn(*mut Opaque) -> Status,
    session_pause: unsafe extern "C" fn(*mut Opaque) -> Status,
    session_update: unsafe extern "C" fn(*mut Opaque, *mut Opaque) -> Status,
    session_set_display_geometry: unsafe extern "C" fn(*mut Opaque, i32, i32, i32),
    frame_create: unsafe extern "C" fn(*const Opaque, *mut *mut Opaque),
    frame_destroy: unsafe extern "C" fn(*mut Opaque),
    pub(super) library: libloading::Library,
}

impl Api {
    fn load() -> Result<Self, libloading::Error> {
        // SAFETY: loading ARCore's library runs no initialiser with preconditions of ours.
        let lib = unsafe { libloading::Library::new("libarcore_sdk_c.so") }?;
        // SAFETY: each symbol has the C signature stated in arcore_c_api.h.
        unsafe {
            Ok(Self {
                request_install: *lib.get(b"ArCoreApk_requestInstall\0")?,
                session_create: *lib.get(b"ArSession_create\0")?,
                session_destroy: *lib.get(b"ArSession_destroy\0")?,
                config_create: *lib.get(b"ArConfig_create\0")?,
                config_destroy: *lib.get(b"ArConfig_destroy\0")?,
                config_set_plane_finding: *lib.get(b"ArConfig_setPlaneFindingMode\0")?,
                config_set_light: *lib.get(b"ArConfig_setLightEstimationMode\0")?,
                config_set_update: *lib.get(b"ArConfig_setUpdateMode\0")?,
                config_set_texture_update: *lib.get(b"ArConfig_setTextureUpdateMode\0")?,
                session_configure: *lib.get(b"ArSession_configure\0")?,
                session_resume: *lib.get(b"ArSession_resume\0")?,
                session_pause: *lib.get(b"ArSession_pause\0")?,
                session_update: *lib.get(b"ArSession_update\0")?,
                session_set_display_geometry: *lib.get(b"ArSession_setDisplayGeometry\0")?,
                frame_create: *lib.get(b"ArFrame_create\0")?,
                frame_destroy: *lib.get(b"ArFrame_destroy\0")?,
                library: lib,
            })
        }
    }
}

/// `AR_PLANE_FINDING_MODE_HORIZONTAL`, `AR_UPDATE_MODE_LATEST_CAMERA_IMAGE`,
/// `AR_TEXTURE_UPDATE_MODE_EXPOSE_HARDWARE_BUFFER` (no GL context: wgpu draws with Vulkan).
const PLANES_HORIZONTAL: i32 = 1;
const UPDATE_LATEST: i32 = 1;
const TEXTURE_HARDWARE_BUFFER: i32 = 1;

/// The loaded API (if any) and the live session and frame.
pub struct ArCore {
    api: Option<Api>,
    /// The per-frame reads (camera, image, planes, light), from the same library.
    pub(super) frame_api: Option<super::frame::FrameApi>,
    pub(super) session: *mut Opaque,
    pub(super) frame: *mut Opaque,
    /// What the last [`ar::FrameSource::next_frame`] read besides the camera frame.
    pub view: Option<super::frame::DisplayCamera>,
}

impl ArCore {
    /// Loads the library; without it every AR command is refused and the app draws 3D only.
    pub fn load() -> Self {
        let api = match Api::load() {
            Ok(api) => Some(api),
            Err(e) => {
                log::warn!("regatta: ARCore library not loaded: {e}");
                None
            }
        };
        let frame_api = api.as_ref().and_then(|a| {
            super::frame::FrameApi::load(&a.library)
                .map_err(|e| log::warn!("regatta: ARCore frame functions missing: {e}"))
                .ok()
        });
        Self {
            api,
            frame_api,
            session: std::ptr::null_mut(),
            frame: std::ptr::null_mut(),
            view: None,
        }
    }

    pub fn is_loaded(&self) -> bool {
        self.api.is_some()
    }

    /// Carries out one command; returns ARCore's or Android's answer when it is immediate.
    pub fn carry_out(&mut self, command: Command) -> Option<Event> {
        let api = self.api.as_ref()?;
        match command {
            Command::RequestInstall { user_requested } => with_activity(|env, activity| {
                let mut install = 0;
                // SAFETY: env and activity are live for this call (attached thread).
                let st = unsafe {
                    (api.request_install)(env, activity, i32::from(user_requested), &mut install)
                };
                Event::Install {
                    status: st,
                    install_status: install,
                }
            }),
            Command::RequestCameraPermission => {
                camera_permission(true).map(|granted| Event::Permission { granted })
            }
            Command::CheckCameraPermission => {
                camera_permission(false).map(|granted| Event::Permission { granted })
            }
            Command::CreateSession => with_activity(|env, activity| {
                let mut session = std::ptr::null_mut();
                // SAFETY: as above; ARCore writes the session pointer.
                let st = unsafe { (api.session_create)(env, activity, &mut session) };
                if st == status::SUCCESS {
                    self.session = session;
                    // SAFETY: a live session.
                    unsafe { (api.frame_create)(session, &mut self.frame) };
                }
                Event::Created { status: st }
            }),
            Command::Configure(light) => Some(Event::Configured {
                status: self.configure(light)?,
            }),
            Command::Resume => {
                // SAFETY: a live session.
                let st = unsafe { (api.session_resume)(self.live_session()?) };
                Some(Event::Resumed { status: st })
            }
            Command::Pause => {
                // SAFETY: a live session.
                unsafe { (api.session_pause)(self.live_session()?) };
                None
            }
            Command::Tell(_) | Command::FallBack(_) => None,
        }
    }

    pub(super) fn live_session(&self) -> Option<*mut Opaque> {
        (!self.session.is_null()).then_some(self.session)
    }

    fn configure(&mut self, light: LightMode) -> Option<i32> {
        let api = self.api.as_ref()?;
        let session = self.live_session()?;
        let mut config = std::ptr::null_mut();
        // SAFETY: a live session; the config is destroyed below.
        unsafe {
            (api.config_create)(session, &mut config);
            (api.config_set_plane_finding)(session, config, PLANES_HORIZONTAL);
            (api.config_set_light)(session, config, light as i32);
            (api.config_set_update)(session, config, UPDATE_LATEST);
            (api.config_set_texture_update)(session, config, TEXTURE_HARDWARE_BUFFER);
            let st = (api.session_configure)(session, config);
            (api.config_destroy)(config);
            Some(st)
        }
    }

    /// `ArSession_update` for this frame; an answer only when it did not succeed.
    pub fn update(&mut self) -> Option<Event> {
        let api = self.api.as_ref()?;
        let session = self.live_session()?;
        // SAFETY: live session and frame.
        let st = unsafe { (api.session_update)(session, self.frame) };
        (st != status::SUCCESS).then_some(Event::Updated { status: st })
    }
}

impl ArCore {
    /// Tells ARCore the view's size (pixels) and the display rotation (`Surface.ROTATION_*`), so
    /// that its view and projection matrices and the display UV transform match the screen.
    pub fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32) {
        let (Some(api), Some(session)) = (self.api.as_ref(), self.live_session()) else {
            return;
        };
        let (w, h) = (
            width.min(i32::MAX as u32) as i32,
            height.min(i32::MAX as u32) as i32,
        );
        // SAFETY: a live session.
        unsafe { (api.session_set_display_geometry)(session, rotation, w, h) };
    }
}

/// The display rotation (`Display.getRotation()`, `Surface.ROTATION_0..270` = 0..3) through JNI;
/// 0 when it cannot be read.
pub fn display_rotation() -> i32 {
    let ctx = ndk_context::android_context();
    // SAFETY: as in with_activity.
    let vm = unsafe { jni::JavaVM::from_raw(ctx.vm().cast()) };
    let result = vm.attach_current_thread(|env| -> jni::errors::Result<i32> {
        // SAFETY: the activity is a live global reference owned by the native activity.
        let activity = unsafe { JObject::from_raw(env, ctx.context().cast()) };
        let wm = env
            .call_method(
                &activity,
                jni_str!("getWindowManager"),
                jni_sig!("()Landroid/view/WindowManager;"),
                &[],
            )?
            .l()?;
        let display = env
            .call_method(
                &wm,
                jni_str!("getDefaultDisplay"),
                jni_sig!("()Landroid/view/Display;"),
                &[],
            )?
            .l()?;
        env.call_method(&display, jni_str!("getRotation"), jni_sig!("()I"), &[])?
            .i()
    });
    result.unwrap_or_else(|e| {
        log::warn!("regatta: display rotation not read ({e}); assuming 0");
        0
    })
}

impl Drop for ArCore {
    fn drop(&mut self) {
        if let (Some(api), Some(session)) = (self.api.as_ref(), self.live_session()) {
            // SAFETY: frame and session were made by this ArCore and are released once.
            unsafe {
                if !self.frame.is_null() {
                    (api.frame_destroy)(self.frame);
                }
                (api.session_destroy)(session);
            }
        }
    }
}

/// Runs `f` with the JNI env of this thread and the activity object (ndk-context).
fn with_activity<T>(f: impl FnOnce(*mut c_void, *mut c_void) -> T) -> Option<T> {
    let ctx = ndk_context::android_context();
    // SAFETY: ndk-context holds the process's JavaVM, set by android-activity.
    let vm = unsafe { jni::JavaVM::from_raw(ctx.vm().cast()) };
    vm.attach_current_thread(|env| -> jni::errors::Result<T> {
        Ok(f(env.get_raw().cast(), ctx.context()))
    })
    .map_err(|e| log::error!("regatta: JNI attach failed: {e}"))
    .ok()
}

/// Whether the camera permission is granted; when it is not and `request` is set, asks for it
/// (Android pauses the activity for the dialog, and the answer is read on the next resume).
fn camera_permission(request: bool) -> Option<bool> {
    let ctx = ndk_context::android_context();
    // SAFETY: as in with_activity.
    let vm = unsafe { jni::JavaVM::from_raw(ctx.vm().cast()) };
    let result = vm.attach_current_thread(|env| -> jni::errors::Result<Option<bool>> {
        // SAFETY: the activity is a live global reference owned by the native activity.
        let activity = unsafe { JObject::from_raw(env, ctx.context().cast()) };
        let name = env.new_string("android.permission.CAMERA")?;
        let granted = env
            .call_method(
                &activity,
                jni_str!("checkSelfPermission"),
                jni_sig!("(Ljava/lang/String;)I"),
                &[JValue::Object(&name)],
            )?
            .i()?
            == 0;
        if granted || !request {
            return Ok(Some(granted));
        }
        let string_class = env.find_class(jni_str!("java/lang/String"))?;
        let names = env.new_object_array(1, &string_class, &name)?;
        env.call_method(
            &activity,
            jni_str!("requestPermissions"),
            jni_sig!("([Ljava/lang/String;I)V"),
            &[JValue::Object(&names), JValue::Int(1)],
        )?;
        Ok(None)
    });
    result.unwrap_or_else(|e| {
        log::error!("regatta: camera permission check failed: {e}");
        Some(false)
    })
}
