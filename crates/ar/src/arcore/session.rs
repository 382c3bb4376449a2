//! The ARCore session's life, as a pure state machine: the Android glue feeds it what ARCore and
//! Android answered ([`Event`]) and carries out the [`Command`]s it returns, so every path
//! (permission refused, installation declined, old ARCore, busy camera, background) is decided
//! here and tested against ARCore's status codes (values from `arcore_c_api.h`).

/// `ArStatus` codes used here (`arcore_c_api.h`).
pub mod status {
    pub const SUCCESS: i32 = 0;
    pub const ERROR_INVALID_ARGUMENT: i32 = -1;
    pub const ERROR_FATAL: i32 = -2;
    pub const ERROR_SESSION_PAUSED: i32 = -3;
    pub const ERROR_SESSION_NOT_PAUSED: i32 = -4;
    pub const ERROR_NOT_TRACKING: i32 = -5;
    pub const ERROR_TEXTURE_NOT_SET: i32 = -6;
    pub const ERROR_MISSING_GL_CONTEXT: i32 = -7;
    pub const ERROR_UNSUPPORTED_CONFIGURATION: i32 = -8;
    pub const ERROR_CAMERA_PERMISSION_NOT_GRANTED: i32 = -9;
    pub const ERROR_DEADLINE_EXCEEDED: i32 = -10;
    pub const ERROR_RESOURCE_EXHAUSTED: i32 = -11;
    pub const ERROR_NOT_YET_AVAILABLE: i32 = -12;
    pub const ERROR_CAMERA_NOT_AVAILABLE: i32 = -13;
    pub const ERROR_ILLEGAL_STATE: i32 = -20;
    pub const UNAVAILABLE_ARCORE_NOT_INSTALLED: i32 = -100;
    pub const UNAVAILABLE_DEVICE_NOT_COMPATIBLE: i32 = -101;
    pub const UNAVAILABLE_APK_TOO_OLD: i32 = -103;
    pub const UNAVAILABLE_SDK_TOO_OLD: i32 = -104;
    pub const UNAVAILABLE_USER_DECLINED_INSTALLATION: i32 = -105;
    /// `ArInstallStatus`.
    pub const INSTALL_STATUS_INSTALLED: i32 = 0;
    pub const INSTALL_STATUS_INSTALL_REQUESTED: i32 = 1;
}

/// Light estimation mode to configure (`ArLightEstimationMode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightMode {
    /// `AR_LIGHT_ESTIMATION_MODE_ENVIRONMENTAL_HDR` (2): main light direction for the sun.
    EnvironmentalHdr = 2,
    /// `AR_LIGHT_ESTIMATION_MODE_AMBIENT_INTENSITY` (1): the fallback where HDR is unsupported.
    AmbientIntensity = 1,
}

/// Why the app runs without AR; each has a message for the user.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unavailable {
    /// libarcore_sdk_c.so is not in the APK (built without `--arcore-aar`).
    LibraryMissing,
    PermissionRefused,
    InstallDeclined,
    DeviceNotSupported,
    /// "Google Play Services for AR" is older than the SDK needs.
    ArCoreTooOld,
    /// The app's ARCore SDK is older than the installed ARCore supports.
    AppTooOld,
    /// Android older than API 27 (this API level): ARCore cannot hand the camera image over
    /// as a hardware buffer, and without GL there is no other way (docs/phone-arcore.md).
    AndroidTooOld(u32),
    /// A Java call around ARCore failed or left an exception pending (ARCore's classes missing
    /// from the APK, the install activity refused); the log names the exception.
    JavaFailed,
    /// Any other ARCore error, with its status.
    Failed(i32),
}

impl Unavailable {
    pub fn message(self) -> String {
        let tail = "Regatta shows the race in 3D without the camera.";
        match self {
            Self::LibraryMissing => format!("This build has no ARCore library; {tail}"),
            Self::PermissionRefused => format!(
                "Camera permission refused: {tail} Allow the camera in Settings > Apps > Regatta to see the race on your table."
            ),
            Self::InstallDeclined => {
                format!("Google Play Services for AR was not installed: {tail}")
            }
            Self::DeviceNotSupported => format!("This phone does not support ARCore: {tail}"),
            Self::ArCoreTooOld => format!(
                "Google Play Services for AR is too old: update it from the Play Store. {tail}"
            ),
            Self::AppTooOld => {
                format!("This Regatta build is too old for the installed ARCore: {tail}")
            }
            Self::AndroidTooOld(api) => format!(
                "AR needs Android 8.1 (API 27) or newer to pass the camera to Vulkan; this phone has API {api}: {tail}"
            ),
            Self::JavaFailed => format!(
                "ARCore's Java side failed (the log says why: adb logcat -s regatta): {tail}"
            ),
            Self::Failed(code) => format!("ARCore failed (status {code}): {tail}"),
        }
    }
}

/// Where the session is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SessionState {
    /// Nothing asked yet.
    Start,
    /// `ArCoreApk_requestInstall` was called.
    CheckingInstall,
    /// The Play Store is installing ARCore; ask again (without prompting) on the next resume.
    InstallRequested,
    /// The camera permission was requested.
    AwaitingPermission,
    /// `ArSession_create` was called.
    Creating,
    /// `ArSession_configure` was called with this light mode.
    Configuring(LightMode),
    /// `ArSession_resume` was called.
    Resuming,
    /// Frames flow: call `ArSession_update` each frame.
    Running,
    /// The app is in the background, or the camera was busy; resume on the next app resume.
    Paused,
    /// No AR: the 3D view without camera. Final for this run, except a refused camera
    /// permission, which is checked again on every resume and can be asked for again.
    Unavailable(Unavailable),
}

/// What Android or ARCore answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// The activity is in the foreground (`onResume`); `library_loaded` says whether
    /// libarcore_sdk_c.so and its functions were found.
    AppResumed {
        library_loaded: bool,
    },
    /// The activity went to the background (`onPause`).
    AppPaused,
    /// `ArCoreApk_requestInstall` returned `status` and wrote `install_status`.
    Install {
        status: i32,
        install_status: i32,
    },
    /// The camera permission is (now) granted or refused.
    Permission {
        granted: bool,
    },
    Created {
        status: i32,
    },
    Configured {
        status: i32,
    },
    Resumed {
        status: i32,
    },
    /// `ArSession_update` returned `status`.
    Updated {
        status: i32,
    },
    /// The user asked for the camera again (the banner's button after a refusal).
    AskPermissionAgain,
}

/// What the glue must do next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// `ArCoreApk_requestInstall(env, activity, user_requested_install, &out)`.
    RequestInstall { user_requested: bool },
    /// Check, and if not granted request, `android.permission.CAMERA` (the answer comes now
    /// when already granted, else after the dialog, on the next resume).
    RequestCameraPermission,
    /// Only check the permission (after the dialog): granted or refused, no new dialog.
    CheckCameraPermission,
    /// `ArSession_create`.
    CreateSession,
    /// `ArSession_configure`: horizontal planes, this light mode, latest-camera-image updates,
    /// hardware-buffer texture mode (no GL context).
    Configure(LightMode),
    /// `ArSession_resume`.
    Resume,
    /// `ArSession_pause`.
    Pause,
    /// Show this message to the user (also logged).
    Tell(&'static str),
    /// Give up AR for this run: drop the session, show [`Unavailable::message`], draw 3D.
    FallBack(Unavailable),
}

const CAMERA_BUSY: &str =
    "The camera is in use by another app; Regatta will retry when you return.";

impl SessionState {
    /// The next state and the commands to carry out, in order.
    pub fn on(self, event: Event) -> (SessionState, Vec<Command>) {
        use Command as C;
        use Event as E;
        use SessionState as S;
        use status as st;
        let fall = |why: Unavailable| (S::Unavailable(why), vec![C::FallBack(why)]);
        match (self, event) {
            // A refused camera may have been allowed in Settings meanwhile: check on every
            // resume (no dialog), and ask again when the user says so (issue 26, defect 6).
            (S::Unavailable(Unavailable::PermissionRefused), E::AppResumed { .. }) => {
                (S::AwaitingPermission, vec![C::CheckCameraPermission])
            }
            (S::Unavailable(Unavailable::PermissionRefused), E::AskPermissionAgain) => {
                (S::AwaitingPermission, vec![C::RequestCameraPermission])
            }
            // Any other reason is final for this run; the background does not change it.
            (S::Unavailable(u), _) => (S::Unavailable(u), vec![]),
            (
                S::Start,
                E::AppResumed {
                    library_loaded: false,
                },
            ) => fall(Unavailable::LibraryMissing),
            (S::Start, E::AppResumed { .. }) => (
                S::CheckingInstall,
                vec![C::RequestInstall {
                    user_requested: true,
                }],
            ),
            // Back from the Play Store, or a check that never answered (issue 26, defect 2):
            // ask again, without prompting a second time.
            (S::InstallRequested | S::CheckingInstall, E::AppResumed { .. }) => (
                S::CheckingInstall,
                vec![C::RequestInstall {
                    user_requested: false,
                }],
            ),
            (
                S::CheckingInstall,
                E::Install {
                    status,
                    install_status,
                },
            ) => match status {
                st::SUCCESS if install_status == st::INSTALL_STATUS_INSTALLED => {
                    (S::AwaitingPermission, vec![C::RequestCameraPermission])
                }
                st::SUCCESS => (S::InstallRequested, vec![]),
                other => fall(unavailable(other)),
            },
            (S::AwaitingPermission, E::AppResumed { .. }) => {
                (S::AwaitingPermission, vec![C::CheckCameraPermission])
            }
            (S::AwaitingPermission, E::Permission { granted: true }) => {
                (S::Creating, vec![C::CreateSession])
            }
            (S::AwaitingPermission, E::Permission { granted: false }) => {
                fall(Unavailable::PermissionRefused)
            }
            (
                S::Creating,
                E::Created {
                    status: st::SUCCESS,
                },
            ) => (
                S::Configuring(LightMode::EnvironmentalHdr),
                vec![C::Configure(LightMode::EnvironmentalHdr)],
            ),
            (S::Creating, E::Created { status }) => fall(unavailable(status)),
            // A create that never answered: ask again (the glue answers with the session it
            // already made rather than make a second).
            (S::Creating, E::AppResumed { .. }) => (S::Creating, vec![C::CreateSession]),
            (
                S::Configuring(_),
                E::Configured {
                    status: st::SUCCESS,
                },
            ) => (S::Resuming, vec![C::Resume]),
            (
                S::Configuring(LightMode::EnvironmentalHdr),
                E::Configured {
                    status: st::ERROR_UNSUPPORTED_CONFIGURATION,
                },
            ) => (
                S::Configuring(LightMode::AmbientIntensity),
                vec![C::Configure(LightMode::AmbientIntensity)],
            ),
            (S::Configuring(_), E::Configured { status }) => fall(unavailable(status)),
            (
                S::Resuming,
                E::Resumed {
                    status: st::SUCCESS,
                },
            ) => (S::Running, vec![]),
            (
                S::Resuming,
                E::Resumed {
                    status: st::ERROR_CAMERA_NOT_AVAILABLE,
                },
            ) => (S::Paused, vec![C::Tell(CAMERA_BUSY)]),
            (S::Resuming, E::Resumed { status }) => fall(unavailable(status)),
            (
                S::Running,
                E::Updated {
                    status: st::SUCCESS,
                },
            ) => (S::Running, vec![]),
            (
                S::Running,
                E::Updated {
                    status: st::ERROR_CAMERA_NOT_AVAILABLE,
                },
            ) => (S::Paused, vec![C::Pause, C::Tell(CAMERA_BUSY)]),
            (
                S::Running,
                E::Updated {
                    status: st::ERROR_SESSION_PAUSED,
                },
            ) => (S::Paused, vec![]),
            (S::Running, E::Updated { status }) => fall(unavailable(status)),
            (S::Running | S::Resuming, E::AppPaused) => (S::Paused, vec![C::Pause]),
            (S::Paused, E::AppResumed { .. }) => (S::Resuming, vec![C::Resume]),
            // Backgrounded while asking: ask again on return (Android re-delivers results).
            (s, E::AppPaused) => (s, vec![]),
            // Anything else is out of order (a late answer): ignore it.
            (s, _) => (s, vec![]),
        }
    }

    /// Whether frames should be pulled from ARCore.
    pub fn is_running(self) -> bool {
        self == SessionState::Running
    }
}

/// The reason for an ARCore failure status.
pub fn unavailable(status: i32) -> Unavailable {
    match status {
        status::UNAVAILABLE_USER_DECLINED_INSTALLATION => Unavailable::InstallDeclined,
        status::UNAVAILABLE_DEVICE_NOT_COMPATIBLE => Unavailable::DeviceNotSupported,
        status::UNAVAILABLE_ARCORE_NOT_INSTALLED => Unavailable::InstallDeclined,
        status::UNAVAILABLE_APK_TOO_OLD => Unavailable::ArCoreTooOld,
        status::UNAVAILABLE_SDK_TOO_OLD => Unavailable::AppTooOld,
        status::ERROR_CAMERA_PERMISSION_NOT_GRANTED => Unavailable::PermissionRefused,
        other => Unavailable::Failed(other),
    }
}

/// `ArTrackingFailureReason` → the hint to show while not tracking (`None` when tracking or no
/// reason is known). Values from `arcore_c_api.h`.
pub fn tracking_hint(tracking_state: i32, failure_reason: i32) -> Option<&'static str> {
    if tracking_state == 0 {
        return None;
    }
    Some(match failure_reason {
        2 => "Too dark: turn on a light.",
        3 => "Move the phone more slowly.",
        4 => "Point the phone at the textured table top, not a blank surface.",
        5 => "The camera is in use by another app.",
        _ => "Move the phone slowly to find the table.",
    })
}

#[cfg(test)]
mod tests;
