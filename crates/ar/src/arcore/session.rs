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
    /// No AR for this run: the 3D view without camera.
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
            // Unavailable is final for this run; the background does not change it.
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
            (S::InstallRequested, E::AppResumed { .. }) => (
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
mod tests {
    use super::status as st;
    use super::*;
    use Command as C;
    use Event as E;
    use SessionState as S;

    const LOADED: E = E::AppResumed {
        library_loaded: true,
    };

    /// The table: state, event → state, commands. Every branch of [`SessionState::on`] that
    /// does something has a row here (checked by `every_state_and_event_is_a_row_or_ignored`).
    fn table() -> Vec<(S, E, S, Vec<C>)> {
        let loaded = LOADED;
        let hdr = LightMode::EnvironmentalHdr;
        let amb = LightMode::AmbientIntensity;
        let u = |x| S::Unavailable(x);
        let fb = |x| vec![C::FallBack(x)];
        let mut rows = vec![
            (
                S::Start,
                E::AppResumed {
                    library_loaded: false,
                },
                u(Unavailable::LibraryMissing),
                fb(Unavailable::LibraryMissing),
            ),
            (
                S::Start,
                loaded,
                S::CheckingInstall,
                vec![C::RequestInstall {
                    user_requested: true,
                }],
            ),
            (
                S::CheckingInstall,
                E::Install {
                    status: st::SUCCESS,
                    install_status: st::INSTALL_STATUS_INSTALLED,
                },
                S::AwaitingPermission,
                vec![C::RequestCameraPermission],
            ),
            (
                S::CheckingInstall,
                E::Install {
                    status: st::SUCCESS,
                    install_status: st::INSTALL_STATUS_INSTALL_REQUESTED,
                },
                S::InstallRequested,
                vec![],
            ),
            (
                S::InstallRequested,
                loaded,
                S::CheckingInstall,
                vec![C::RequestInstall {
                    user_requested: false,
                }],
            ),
            (
                S::CheckingInstall,
                E::Install {
                    status: -105,
                    install_status: 0,
                },
                u(Unavailable::InstallDeclined),
                fb(Unavailable::InstallDeclined),
            ),
            (
                S::CheckingInstall,
                E::Install {
                    status: -101,
                    install_status: 0,
                },
                u(Unavailable::DeviceNotSupported),
                fb(Unavailable::DeviceNotSupported),
            ),
            (
                S::AwaitingPermission,
                E::Permission { granted: true },
                S::Creating,
                vec![C::CreateSession],
            ),
            (
                S::AwaitingPermission,
                E::Permission { granted: false },
                u(Unavailable::PermissionRefused),
                fb(Unavailable::PermissionRefused),
            ),
            (
                S::Creating,
                E::Created { status: 0 },
                S::Configuring(hdr),
                vec![C::Configure(hdr)],
            ),
            (
                S::Creating,
                E::Created { status: -103 },
                u(Unavailable::ArCoreTooOld),
                fb(Unavailable::ArCoreTooOld),
            ),
            (
                S::Creating,
                E::Created { status: -104 },
                u(Unavailable::AppTooOld),
                fb(Unavailable::AppTooOld),
            ),
            (
                S::Creating,
                E::Created { status: -9 },
                u(Unavailable::PermissionRefused),
                fb(Unavailable::PermissionRefused),
            ),
            (
                S::Configuring(hdr),
                E::Configured { status: -8 },
                S::Configuring(amb),
                vec![C::Configure(amb)],
            ),
            (
                S::Configuring(amb),
                E::Configured { status: -8 },
                u(Unavailable::Failed(-8)),
                fb(Unavailable::Failed(-8)),
            ),
            (
                S::Configuring(amb),
                E::Configured { status: 0 },
                S::Resuming,
                vec![C::Resume],
            ),
            (S::Resuming, E::Resumed { status: 0 }, S::Running, vec![]),
            (
                S::Resuming,
                E::Resumed { status: -13 },
                S::Paused,
                vec![C::Tell(CAMERA_BUSY)],
            ),
            (S::Running, E::Updated { status: 0 }, S::Running, vec![]),
            (
                S::Running,
                E::Updated { status: -13 },
                S::Paused,
                vec![C::Pause, C::Tell(CAMERA_BUSY)],
            ),
            (
                S::Running,
                E::Updated { status: -2 },
                u(Unavailable::Failed(-2)),
                fb(Unavailable::Failed(-2)),
            ),
            (S::Running, E::AppPaused, S::Paused, vec![C::Pause]),
            (S::Paused, loaded, S::Resuming, vec![C::Resume]),
            (
                S::AwaitingPermission,
                E::AppPaused,
                S::AwaitingPermission,
                vec![],
            ),
            (
                u(Unavailable::PermissionRefused),
                loaded,
                u(Unavailable::PermissionRefused),
                vec![],
            ),
            // A late answer out of order is ignored.
            (S::Running, E::Created { status: 0 }, S::Running, vec![]),
            // Back from the permission dialog: only check, never ask twice.
            (
                S::AwaitingPermission,
                loaded,
                S::AwaitingPermission,
                vec![C::CheckCameraPermission],
            ),
            // ARCore paused the session itself (e.g. the app lost the camera): no second
            // pause, resume on the next app resume.
            (
                S::Running,
                E::Updated {
                    status: st::ERROR_SESSION_PAUSED,
                },
                S::Paused,
                vec![],
            ),
            (
                S::Resuming,
                E::Resumed {
                    status: st::ERROR_FATAL,
                },
                u(Unavailable::Failed(st::ERROR_FATAL)),
                fb(Unavailable::Failed(st::ERROR_FATAL)),
            ),
            (S::Resuming, E::AppPaused, S::Paused, vec![C::Pause]),
            // requestInstall answering "not installed" (after the user backed out of the Play
            // Store page) is a declined installation.
            (
                S::CheckingInstall,
                E::Install {
                    status: st::UNAVAILABLE_ARCORE_NOT_INSTALLED,
                    install_status: 0,
                },
                u(Unavailable::InstallDeclined),
                fb(Unavailable::InstallDeclined),
            ),
            (
                S::Configuring(hdr),
                E::Configured { status: 0 },
                S::Resuming,
                vec![C::Resume],
            ),
        ];
        // A status that some branch names, met where no branch names it, is a failure too.
        let failed = |from, event, code| {
            let why = Unavailable::Failed(code);
            (from, event, u(why), fb(why))
        };
        let (paused, unsupported, busy) = (
            st::ERROR_SESSION_PAUSED,
            st::ERROR_UNSUPPORTED_CONFIGURATION,
            st::ERROR_CAMERA_NOT_AVAILABLE,
        );
        for code in [paused, unsupported, busy] {
            rows.push(failed(S::Creating, E::Created { status: code }, code));
        }
        for mode in [hdr, amb] {
            for code in [paused, busy, st::ERROR_FATAL] {
                let event = E::Configured { status: code };
                rows.push(failed(S::Configuring(mode), event, code));
            }
        }
        for code in [paused, unsupported] {
            rows.push(failed(S::Resuming, E::Resumed { status: code }, code));
        }
        let event = E::Updated {
            status: unsupported,
        };
        rows.push(failed(S::Running, event, unsupported));
        rows
    }

    #[test]
    fn transitions_against_arcore_statuses() {
        for (from, event, to, cmds) in table() {
            assert_eq!(from.on(event), (to, cmds), "{from:?} + {event:?}");
        }
    }

    /// Every state, one value per variant (a new variant is a compile error here until added).
    fn every_state() -> Vec<S> {
        let all = vec![
            S::Start,
            S::CheckingInstall,
            S::InstallRequested,
            S::AwaitingPermission,
            S::Creating,
            S::Configuring(LightMode::EnvironmentalHdr),
            S::Configuring(LightMode::AmbientIntensity),
            S::Resuming,
            S::Running,
            S::Paused,
            S::Unavailable(Unavailable::PermissionRefused),
        ];
        for s in &all {
            match s {
                S::Start
                | S::CheckingInstall
                | S::InstallRequested
                | S::AwaitingPermission
                | S::Creating
                | S::Configuring(_)
                | S::Resuming
                | S::Running
                | S::Paused
                | S::Unavailable(_) => {}
            }
        }
        all
    }

    /// Every event the machine tells apart: each kind with SUCCESS, every status some branch
    /// names, and one status no branch names (a new variant is a compile error until added).
    fn every_event() -> Vec<E> {
        let statuses = [
            st::SUCCESS,
            st::ERROR_SESSION_PAUSED,
            st::ERROR_UNSUPPORTED_CONFIGURATION,
            st::ERROR_CAMERA_NOT_AVAILABLE,
            st::ERROR_FATAL,
        ];
        let mut all = vec![
            E::AppResumed {
                library_loaded: false,
            },
            LOADED,
            E::AppPaused,
            E::Permission { granted: true },
            E::Permission { granted: false },
        ];
        for install_status in [
            st::INSTALL_STATUS_INSTALLED,
            st::INSTALL_STATUS_INSTALL_REQUESTED,
        ] {
            all.push(E::Install {
                status: st::SUCCESS,
                install_status,
            });
        }
        for status in statuses {
            all.extend([
                E::Created { status },
                E::Configured { status },
                E::Resumed { status },
                E::Updated { status },
            ]);
        }
        for e in &all {
            match e {
                E::AppResumed { .. }
                | E::AppPaused
                | E::Install { .. }
                | E::Permission { .. }
                | E::Created { .. }
                | E::Configured { .. }
                | E::Resumed { .. }
                | E::Updated { .. } => {}
            }
        }
        all
    }

    /// What the machine can tell apart in an event: its kind, the flag or install status it
    /// carries, and its status where any branch names that status (any other failure is one
    /// class: the branches pass it on to [`unavailable`], tested on its own).
    fn event_class(state: S, e: E) -> (u8, i32) {
        let named = |status: i32| match status {
            st::SUCCESS
            | st::ERROR_SESSION_PAUSED
            | st::ERROR_UNSUPPORTED_CONFIGURATION
            | st::ERROR_CAMERA_NOT_AVAILABLE => status,
            _ => i32::MIN,
        };
        match e {
            // Only the first resume asks whether the library was found.
            E::AppResumed { library_loaded } => (0, i32::from(library_loaded || state != S::Start)),
            E::AppPaused => (1, 0),
            E::Install {
                status,
                install_status,
            } => (
                2,
                if status == st::SUCCESS {
                    install_status
                } else {
                    i32::MIN
                },
            ),
            E::Permission { granted } => (3, i32::from(granted)),
            E::Created { status } => (4, named(status)),
            E::Configured { status } => (5, named(status)),
            E::Resumed { status } => (6, named(status)),
            E::Updated { status } => (7, named(status)),
        }
    }

    /// A (state, event) pair that does anything (changes the state or issues a command) must be
    /// a row of [`table`]; every other pair must be ignored. A branch added to
    /// [`SessionState::on`] without a row, or a row deleted, fails here.
    #[test]
    fn every_state_and_event_is_a_row_or_ignored() {
        let rows = table();
        let mut missing = vec![];
        for state in every_state() {
            for event in every_event() {
                let has_row = rows
                    .iter()
                    .any(|r| r.0 == state && event_class(state, r.1) == event_class(state, event));
                let got = state.on(event);
                if !has_row && got != (state, vec![]) {
                    missing.push(format!("{state:?} + {event:?} -> {got:?}"));
                }
            }
        }
        assert!(
            missing.is_empty(),
            "no test row for:\n{}",
            missing.join("\n")
        );
    }

    /// Every `ArStatus` failure the machine can meet maps to the reason the user is told.
    #[test]
    fn failure_statuses_map_to_their_reason() {
        for (code, want) in [
            (
                st::UNAVAILABLE_ARCORE_NOT_INSTALLED,
                Unavailable::InstallDeclined,
            ),
            (
                st::UNAVAILABLE_USER_DECLINED_INSTALLATION,
                Unavailable::InstallDeclined,
            ),
            (
                st::UNAVAILABLE_DEVICE_NOT_COMPATIBLE,
                Unavailable::DeviceNotSupported,
            ),
            (st::UNAVAILABLE_APK_TOO_OLD, Unavailable::ArCoreTooOld),
            (st::UNAVAILABLE_SDK_TOO_OLD, Unavailable::AppTooOld),
            (
                st::ERROR_CAMERA_PERMISSION_NOT_GRANTED,
                Unavailable::PermissionRefused,
            ),
            (st::ERROR_FATAL, Unavailable::Failed(st::ERROR_FATAL)),
            (
                st::ERROR_ILLEGAL_STATE,
                Unavailable::Failed(st::ERROR_ILLEGAL_STATE),
            ),
        ] {
            assert_eq!(unavailable(code), want, "status {code}");
        }
    }

    #[test]
    fn a_whole_first_run_reaches_running() {
        let events = [
            E::AppResumed {
                library_loaded: true,
            },
            E::Install {
                status: 0,
                install_status: 1,
            },
            E::AppPaused,
            E::AppResumed {
                library_loaded: true,
            },
            E::Install {
                status: 0,
                install_status: 0,
            },
            E::Permission { granted: true },
            E::Created { status: 0 },
            E::Configured { status: 0 },
            E::Resumed { status: 0 },
            E::Updated { status: 0 },
        ];
        let end = events.iter().fold(S::Start, |s, &e| s.on(e).0);
        assert!(end.is_running());
    }

    #[test]
    fn every_unavailable_message_says_what_happens_instead() {
        for u in [
            Unavailable::LibraryMissing,
            Unavailable::PermissionRefused,
            Unavailable::InstallDeclined,
            Unavailable::DeviceNotSupported,
            Unavailable::ArCoreTooOld,
            Unavailable::AppTooOld,
            Unavailable::AndroidTooOld(26),
            Unavailable::Failed(-2),
        ] {
            assert!(u.message().contains("3D without the camera"), "{u:?}");
        }
        assert_eq!(tracking_hint(0, 3), None);
        assert_eq!(tracking_hint(1, 3), Some("Move the phone more slowly."));
        assert!(tracking_hint(1, 0).unwrap().contains("slowly"));
    }
}
