//! [`ArCore`]: the loaded library, the live session and frame, and the glue that carries out
//! the session state machine's [`Command`]s (`crate::arcore::session` decides; this only does).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread::JoinHandle;

use super::api::{Apis, O, S, consts};
use super::camera_config::{self, CameraBudget, CameraConfigOutcome};
use super::frame::{DisplayCamera, ReadOptions, read_frame};
use super::jni::{CAMERA_PERMISSION, CAMERA_REQUEST_CODE, JavaObject, Jni};
use crate::arcore::CameraConfigSize;
use crate::arcore::session::status;
use crate::arcore::{Command, Event, LightMode, SessionState, Unavailable};
use crate::{ArError, CameraFrame, FrameSource};

/// The ARCore library's file name in the APK (`lib/arm64-v8a/`, from Google's AAR).
pub const ARCORE_LIBRARY: &str = "libarcore_sdk_c.so";
/// On the host: the library to load instead (the simulator, `crates/arcore_sim`).
pub const LIBRARY_ENV: &str = "REGATTA_ARCORE_LIB";

/// The library to load: [`LIBRARY_ENV`] when set, else [`ARCORE_LIBRARY`].
pub fn library_path() -> PathBuf {
    std::env::var_os(LIBRARY_ENV).map_or_else(|| PathBuf::from(ARCORE_LIBRARY), PathBuf::from)
}

/// A Java call around an ARCore C function that failed (JNI attach, or an exception left
/// pending by ARCore's Java half): logged with what Java said, and AR given up.
fn java_failed(function: &str, called: Result<(), String>) -> Result<(), Unavailable> {
    called.map_err(|e| {
        log::error!("regatta: {function}: {e}");
        Unavailable::JavaFailed
    })
}

/// A raw ARCore session handed to the thread that destroys it.
struct SessionToDestroy(*mut O);
// SAFETY: ARCore's session may be destroyed from any thread once no other call uses it; the
// pointer is moved out of the `ArCore` (nulled there) before it crosses.
unsafe impl Send for SessionToDestroy {}

/// What a step of the session left for the user: the message to show, if any.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Told {
    /// A passing note (`Command::Tell`), e.g. the camera is busy.
    pub note: Option<&'static str>,
    /// AR was given up for this run (`Command::FallBack`); the session is gone.
    pub fell_back: Option<Unavailable>,
}

/// The loaded API (if any), the Java side, and the live session and frame.
pub struct ArCore {
    apis: Option<Arc<Apis>>,
    jni: Box<dyn Jni>,
    session: *mut O,
    frame: *mut O,
    /// The light mode of the last successful `ArSession_configure`.
    light: Option<LightMode>,
    /// Whether `ArSession_resume` succeeded and no pause followed.
    resumed: bool,
    /// The timestamp of the last camera frame read (an unchanged one is not read again).
    last_timestamp_ns: Option<i64>,
    /// The GPU's largest texture side: camera images are halved to fit it.
    max_image_side: Option<u32>,
    /// What the camera image may cost (the quality tier's); applied before each resume.
    camera_budget: Option<CameraBudget>,
    /// What the last [`FrameSource::next_frame`] read besides the camera frame.
    pub view: Option<DisplayCamera>,
}

impl ArCore {
    /// Loads the library at [`library_path`]; without it every AR command is refused and the
    /// app draws 3D only.
    pub fn load(jni: Box<dyn Jni>) -> Self {
        Self::load_from(&library_path(), jni)
    }

    /// Loads the library at `path`.
    pub fn load_from(path: &Path, jni: Box<dyn Jni>) -> Self {
        let apis = match Apis::load(path) {
            Ok(apis) => Some(Arc::new(apis)),
            Err(e) => {
                log::warn!(
                    "regatta: ARCore library {} not loaded: {e}",
                    input::show_path(path)
                );
                None
            }
        };
        Self {
            apis,
            jni,
            session: std::ptr::null_mut(),
            frame: std::ptr::null_mut(),
            light: None,
            resumed: false,
            last_timestamp_ns: None,
            max_image_side: None,
            camera_budget: None,
            view: None,
        }
    }

    /// The camera image the session may afford from now on: before each `ArSession_resume`
    /// (the first, and after every pause) the back camera's config with the largest CPU image
    /// of at most `budget.max_image_px` pixels is set, if not already in use. A running
    /// session keeps its camera config until it is paused and resumed (ARCore takes a config
    /// only while paused). Without a budget ARCore's default config stays (640 × 480 on most
    /// phones).
    pub fn set_camera_budget(&mut self, budget: CameraBudget) {
        self.camera_budget = Some(budget);
    }

    /// The camera config the session uses now, as ARCore reports it.
    pub fn camera_config(&self) -> Option<CameraConfigSize> {
        let (apis, session) = (self.apis.as_ref()?, self.live_session()?);
        // SAFETY: a live session.
        unsafe { camera_config::current(&apis.camera_config, session as S) }
    }

    /// Chooses and sets the camera config for the budget now (logged in one line); `None`
    /// without a session or a budget. [`ArCore::drive`] calls it before each resume; called
    /// while the session runs, ARCore refuses (`AR_ERROR_SESSION_NOT_PAUSED`) and the config
    /// in use stays.
    pub fn apply_camera_budget(&mut self) -> Option<CameraConfigOutcome> {
        let budget = self.camera_budget?;
        let (apis, session) = (self.apis.as_ref()?, self.live_session()?);
        // SAFETY: a live session; a refusal is an answer, not a failure.
        let outcome = unsafe { camera_config::apply(&apis.camera_config, session, budget) };
        camera_config::log_outcome(&outcome, budget);
        Some(outcome)
    }

    /// Camera images wider or taller than `max_side` pixels (the device's
    /// `max_texture_dimension_2d`) are halved until they fit, so no texture made from them is
    /// above the GPU's limits (phone realities, issue 19).
    pub fn set_max_image_side(&mut self, max_side: u32) {
        self.max_image_side = Some(max_side.max(1));
    }

    pub fn is_loaded(&self) -> bool {
        self.apis.is_some()
    }

    /// Whether a session exists (created and not yet given up).
    pub fn has_session(&self) -> bool {
        !self.session.is_null()
    }

    /// The display rotation (`Surface.ROTATION_*` = 0..3), read on the Activity; 0 when it
    /// cannot be read.
    pub fn display_rotation(&self) -> i32 {
        self.jni
            .display_rotation(JavaObject::Activity)
            .unwrap_or_else(|e| {
                log::warn!("regatta: display rotation not read ({e}); assuming 0");
                0
            })
    }

    /// The display rotation (`Surface.ROTATION_*` = 0..3) read on the Activity, `None` (logged)
    /// when it cannot be read.
    pub fn read_display_rotation(&self) -> Option<i32> {
        self.jni
            .display_rotation(JavaObject::Activity)
            .map_err(|e| log::warn!("regatta: display rotation not read ({e})"))
            .ok()
    }

    /// Steps `state` with `event` and carries out every command, feeding ARCore's and
    /// Android's immediate answers back in. Gives what the user must be told. A command that
    /// cannot be carried out (a Java call that failed, an exception left pending) is an answer
    /// too: AR is given up with its reason, never left waiting (issue 26, defect 2).
    pub fn drive(&mut self, state: &mut SessionState, event: Event) -> Told {
        let mut told = Told::default();
        let mut queue = vec![self.gate(*state, event)];
        while let Some(e) = queue.pop() {
            let (next, commands) = match e {
                Ok(e) => state.on(e),
                Err(why) => (SessionState::Unavailable(why), vec![Command::FallBack(why)]),
            };
            if next != *state {
                told.note = None;
            }
            *state = next;
            for c in commands {
                match c {
                    Command::Tell(msg) => {
                        log::warn!("regatta: {msg}");
                        told.note = Some(msg);
                    }
                    Command::FallBack(why) => {
                        log::warn!("regatta: {}", why.message());
                        // The join handle is dropped: the app goes on while ARCore tears down.
                        drop(self.close());
                        told.fell_back = Some(why);
                    }
                    other => queue.extend(self.try_carry_out(other).transpose()),
                }
            }
        }
        told
    }

    /// The first resume on an Android too old for hardware-buffer texture mode gives up AR
    /// before asking anything (docs/phone-arcore.md: minSdk stays 24, AR needs 27).
    fn gate(&self, state: SessionState, event: Event) -> Result<Event, Unavailable> {
        let api = self.jni.sdk_int();
        match (state, event) {
            (
                SessionState::Start,
                Event::AppResumed {
                    library_loaded: true,
                },
            ) if api < consts::HARDWARE_BUFFER_MIN_API => Err(Unavailable::AndroidTooOld(api)),
            _ => Ok(event),
        }
    }

    /// Carries out one command; returns ARCore's or Android's answer when it is immediate. A
    /// command that fails outright answers as ARCore's `AR_ERROR_FATAL` would (use
    /// [`ArCore::drive`] to keep the reason).
    pub fn carry_out(&mut self, command: Command) -> Option<Event> {
        match self.try_carry_out(command) {
            Ok(answer) => answer,
            Err(why) => {
                let fatal = status::ERROR_FATAL;
                log::error!("regatta: {}", why.message());
                match command {
                    Command::RequestInstall { .. } => Some(Event::Install {
                        status: fatal,
                        install_status: 0,
                    }),
                    Command::CreateSession => Some(Event::Created { status: fatal }),
                    Command::Configure(_) => Some(Event::Configured { status: fatal }),
                    Command::Resume => Some(Event::Resumed { status: fatal }),
                    _ => None,
                }
            }
        }
    }

    /// Carries out one command: `Ok(Some(answer))` when ARCore or Android answered now,
    /// `Ok(None)` when the answer comes later (the permission dialog) or none is due (pause),
    /// `Err(why)` when it could not be carried out.
    fn try_carry_out(&mut self, command: Command) -> Result<Option<Event>, Unavailable> {
        let apis = Arc::clone(self.apis.as_ref().ok_or(Unavailable::LibraryMissing)?);
        let api = &apis.session;
        let no_session = Unavailable::Failed(status::ERROR_FATAL);
        match command {
            Command::RequestInstall { user_requested } => {
                let mut answer = None;
                // ARCore starts the install activity on this object: the Activity.
                let called = self
                    .jni
                    .with_env(JavaObject::Activity, &mut |env, activity| {
                        let mut install = 0;
                        // SAFETY: env and activity are live for this call (attached thread).
                        let st = unsafe {
                            (api.request_install)(
                                env,
                                activity,
                                i32::from(user_requested),
                                &mut install,
                            )
                        };
                        answer = Some(Event::Install {
                            status: st,
                            install_status: install,
                        });
                    });
                java_failed("ArCoreApk_requestInstall", called)?;
                Ok(answer)
            }
            Command::RequestCameraPermission => Ok(self
                .camera_permission(true)
                .map(|granted| Event::Permission { granted })),
            Command::CheckCameraPermission => Ok(self
                .camera_permission(false)
                .map(|granted| Event::Permission { granted })),
            // Asked again (a resume while creating): the session made is the answer; a second
            // one would leak the first.
            Command::CreateSession if self.has_session() => Ok(Some(Event::Created {
                status: status::SUCCESS,
            })),
            Command::CreateSession => {
                let mut st = status::ERROR_FATAL;
                let mut session = std::ptr::null_mut();
                // A Context is enough here: the Application outlives every Activity.
                let called = self
                    .jni
                    .with_env(JavaObject::Application, &mut |env, context| {
                        // SAFETY: as above; ARCore writes the session pointer.
                        st = unsafe { (api.session_create)(env, context, &mut session) };
                    });
                // A session ARCore made is kept even when the call failed after making it, so
                // that the fall-back closes it (destroyed, not leaked).
                if st == status::SUCCESS && !session.is_null() {
                    self.session = session;
                    // SAFETY: a live session.
                    unsafe { (api.frame_create)(session, &mut self.frame) };
                }
                java_failed("ArSession_create", called)?;
                Ok(Some(Event::Created { status: st }))
            }
            Command::Configure(light) => Ok(Some(Event::Configured {
                status: self.configure(light).ok_or(no_session)?,
            })),
            Command::Resume => {
                let session = self.live_session().ok_or(no_session)?;
                if !self.resumed {
                    // The only moment ARCore takes a camera config: paused, before resuming.
                    self.apply_camera_budget();
                }
                // SAFETY: a live session.
                let st = unsafe { (api.session_resume)(session) };
                self.resumed = st == status::SUCCESS;
                Ok(Some(Event::Resumed { status: st }))
            }
            Command::Pause => {
                if let Some(session) = self.live_session() {
                    // SAFETY: a live session.
                    unsafe { (api.session_pause)(session) };
                }
                self.resumed = false;
                Ok(None)
            }
            Command::Tell(_) | Command::FallBack(_) => Ok(None),
        }
    }

    fn live_session(&self) -> Option<*mut O> {
        (!self.session.is_null()).then_some(self.session)
    }

    fn configure(&mut self, light: LightMode) -> Option<i32> {
        let api = &self.apis.as_ref()?.session;
        let session = self.live_session()?;
        let mut config = std::ptr::null_mut();
        // SAFETY: a live session; the config is destroyed below.
        let st = unsafe {
            (api.config_create)(session, &mut config);
            (api.config_set_plane_finding)(session, config, consts::PLANES_HORIZONTAL);
            (api.config_set_light)(session, config, light as i32);
            (api.config_set_update)(session, config, consts::UPDATE_LATEST);
            (api.config_set_texture_update)(session, config, consts::TEXTURE_HARDWARE_BUFFER);
            let st = (api.session_configure)(session, config);
            (api.config_destroy)(config);
            st
        };
        if st == status::SUCCESS {
            self.light = Some(light);
        }
        Some(st)
    }

    /// `ArSession_update` for this frame; an answer only when it did not succeed.
    pub fn update(&mut self) -> Option<Event> {
        let api = &self.apis.as_ref()?.session;
        let session = self.live_session()?;
        // SAFETY: live session and frame.
        let st = unsafe { (api.session_update)(session, self.frame) };
        (st != status::SUCCESS).then_some(Event::Updated { status: st })
    }

    /// Tells ARCore the view's size (pixels) and the display rotation (`Surface.ROTATION_*`), so
    /// that its view and projection matrices and the display UV transform match the screen.
    pub fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32) {
        let (Some(apis), Some(session)) = (self.apis.as_ref(), self.live_session()) else {
            return;
        };
        let (w, h) = (
            width.min(i32::MAX as u32) as i32,
            height.min(i32::MAX as u32) as i32,
        );
        // SAFETY: a live session.
        unsafe { (apis.session.session_set_display_geometry)(session, rotation, w, h) };
    }

    /// Gives the session up: pauses it (closing the camera) when resumed, destroys the frame,
    /// and destroys the session on another thread (ARCore: "will take several seconds"; the
    /// caller, often Android's main thread waiting on `onDestroy`, must not wait). The pointers
    /// are nulled here. The handle joins the destroying thread (tests); dropping it detaches.
    pub fn close(&mut self) -> Option<JoinHandle<()>> {
        let apis = Arc::clone(self.apis.as_ref()?);
        let session = self.live_session()?;
        let api = &apis.session;
        // SAFETY: session and frame were made by this ArCore and are released once: the
        // pointers are nulled before anything else can see them.
        unsafe {
            if self.resumed {
                (api.session_pause)(session);
            }
            if !self.frame.is_null() {
                (api.frame_destroy)(self.frame);
            }
        }
        self.session = std::ptr::null_mut();
        self.frame = std::ptr::null_mut();
        self.resumed = false;
        self.light = None;
        self.last_timestamp_ns = None;
        self.view = None;
        let doomed = SessionToDestroy(session);
        let apis_for_thread = Arc::clone(&apis);
        std::thread::Builder::new()
            .name("arcore-destroy".into())
            .spawn(move || {
                let doomed = doomed;
                // SAFETY: the session is no longer reachable from the app (see above).
                unsafe { (apis_for_thread.session.session_destroy)(doomed.0) };
            })
            .map_err(|e| log::error!("regatta: cannot start the ARCore teardown thread: {e}"))
            .ok()
    }

    /// Whether the camera permission is granted; when it is not and `request` is set, asks for
    /// it on the Activity (Android pauses the activity for the dialog, and the answer is read
    /// on the next resume: `None` now).
    fn camera_permission(&self, request: bool) -> Option<bool> {
        let on = JavaObject::Activity;
        let granted = match self.jni.check_self_permission(on, CAMERA_PERMISSION) {
            Ok(g) => g,
            Err(e) => {
                log::error!("regatta: camera permission check failed: {e}");
                return Some(false);
            }
        };
        if granted || !request {
            return Some(granted);
        }
        match self
            .jni
            .request_permissions(on, CAMERA_PERMISSION, CAMERA_REQUEST_CODE)
        {
            Ok(()) => None,
            Err(e) => {
                log::error!("regatta: camera permission request failed: {e}");
                Some(false)
            }
        }
    }
}

impl Drop for ArCore {
    fn drop(&mut self) {
        // Detached: the process may end before ARCore finishes, which is what Android expects.
        drop(self.close());
    }
}

impl FrameSource for ArCore {
    /// Reads the frame of the last `ArSession_update` ([`ArCore::update`]); `None` until ARCore
    /// has a camera image, and while its timestamp is unchanged (the same image). Also
    /// refreshes [`ArCore::view`].
    fn next_frame(&mut self) -> Result<Option<CameraFrame>, ArError> {
        let (Some(apis), Some(session)) = (self.apis.as_ref(), self.live_session()) else {
            return Ok(None);
        };
        let options = ReadOptions {
            hdr: self.light == Some(LightMode::EnvironmentalHdr),
            last_timestamp_ns: self.last_timestamp_ns,
            max_image_side: self.max_image_side,
        };
        // SAFETY: live session and frame (update ran).
        let read = unsafe { read_frame(&apis.frame, session as S, self.frame as S, &options) }?;
        self.view = Some(read.display);
        if read.frame.is_some() {
            self.last_timestamp_ns = Some(read.timestamp_ns);
        }
        Ok(read.frame)
    }

    fn describe(&self) -> String {
        if self.is_loaded() {
            "ARCore camera".to_string()
        } else {
            "ARCore (library not loaded)".to_string()
        }
    }
}
