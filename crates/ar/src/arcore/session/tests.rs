//! The session machine against ARCore's status table: every transition a row, every other
//! (state, event) pair ignored, and the paths of a first run.

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
        // A refused camera is checked again on each resume (it may have been allowed in
        // Settings), and asked for again from the banner's button.
        (
            u(Unavailable::PermissionRefused),
            loaded,
            S::AwaitingPermission,
            vec![C::CheckCameraPermission],
        ),
        (
            u(Unavailable::PermissionRefused),
            E::AskPermissionAgain,
            S::AwaitingPermission,
            vec![C::RequestCameraPermission],
        ),
        // Every other reason is final for the run.
        (
            u(Unavailable::InstallDeclined),
            loaded,
            u(Unavailable::InstallDeclined),
            vec![],
        ),
        // A check or a create that never answered is asked again on the next resume.
        (
            S::CheckingInstall,
            loaded,
            S::CheckingInstall,
            vec![C::RequestInstall {
                user_requested: false,
            }],
        ),
        (S::Creating, loaded, S::Creating, vec![C::CreateSession]),
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
        S::Unavailable(Unavailable::InstallDeclined),
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
        E::AskPermissionAgain,
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
            | E::Updated { .. }
            | E::AskPermissionAgain => {}
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
        E::AskPermissionAgain => (8, 0),
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

/// Issue 26, defect 6, as a user tries it: the camera refused, then allowed in Settings
/// while the app is in the background; back in the app the session runs. Before, the
/// refusal was final and no number of resumes changed it.
#[test]
fn a_camera_allowed_in_settings_after_a_refusal_starts_the_session() {
    let mut s = S::AwaitingPermission.on(E::Permission { granted: false }).0;
    assert_eq!(s, u_refused());
    for e in [E::AppPaused, LOADED] {
        let (next, cmds) = s.on(e);
        s = next;
        if e == LOADED {
            assert_eq!(cmds, [C::CheckCameraPermission], "checked, no dialog");
        }
    }
    // Settings said yes.
    let (s, cmds) = s.on(E::Permission { granted: true });
    assert_eq!((s, cmds), (S::Creating, vec![C::CreateSession]));
    // Still refused: back to the banner, which can ask again.
    let (s, _) = S::AwaitingPermission.on(E::Permission { granted: false });
    assert_eq!(
        s.on(E::AskPermissionAgain),
        (S::AwaitingPermission, vec![C::RequestCameraPermission])
    );
}

fn u_refused() -> S {
    S::Unavailable(Unavailable::PermissionRefused)
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
        Unavailable::JavaFailed,
        Unavailable::Failed(-2),
    ] {
        assert!(u.message().contains("3D without the camera"), "{u:?}");
    }
    assert_eq!(tracking_hint(0, 3), None);
    assert_eq!(tracking_hint(1, 3), Some("Move the phone more slowly."));
    assert!(tracking_hint(1, 0).unwrap().contains("slowly"));
}
