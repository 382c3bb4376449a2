//! The Android defects of issue 19, each caught on the host: the app's ARCore glue
//! (`ar::arcore::ffi`) runs against the simulator and the scripted Java side, which record
//! what a phone would have seen.

mod common;

use ar::FrameSource;
use ar::arcore::ffi::{JavaObject, JavaScript, ScriptedJni};
use ar::arcore::session::status;
use ar::arcore::{Event, SessionState, Unavailable};
use common::{Sim, granted, start};

/// Defect 1: `ArCoreApk_requestInstall` gets the Activity (ARCore starts the install
/// activity on it; the simulator fails it otherwise, as ARCore's Java side throws) and
/// `ArSession_create` a Context (the Application). Before: both got ndk_context's object,
/// the Application, and the install check failed with AR_ERROR_FATAL.
#[test]
fn install_request_gets_the_activity_and_session_create_the_application() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    assert_eq!(start(&mut core), SessionState::Running);
    assert_eq!(
        sim.object("RegattaSim_installObject"),
        ScriptedJni::ACTIVITY_HANDLE
    );
    assert_eq!(
        sim.object("RegattaSim_createContext"),
        ScriptedJni::APPLICATION_HANDLE
    );
}

/// Defect 2: `requestPermissions` and `getWindowManager` go to the Activity (on the
/// Application they do not exist: the fake throws NoSuchMethodError there, as Android does).
/// Before: both went to the Application: no dialog ("permission refused") and rotation 0.
#[test]
fn permission_dialog_and_display_rotation_are_asked_of_the_activity() {
    let sim = Sim::take();
    let (mut core, jni) = sim.arcore(JavaScript {
        permission_granted: false,
        dialog_answer: true,
        rotation: 1,
        ..JavaScript::default()
    });
    let mut state = start(&mut core);
    assert_eq!(state, SessionState::AwaitingPermission);
    assert!(jni.take_dialog_shown(), "the permission dialog was shown");
    // Android pauses the activity for the dialog and resumes it after the answer.
    core.drive(&mut state, Event::AppPaused);
    core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(state, SessionState::Running);
    assert_eq!(core.display_rotation(), 1, "landscape is read, not 0");
    let calls = jni.calls();
    for method in ["requestPermissions", "getWindowManager"] {
        let on: Vec<_> = calls
            .iter()
            .filter(|c| c.method == method)
            .map(|c| c.on)
            .collect();
        assert_eq!(on, [JavaObject::Activity], "{method}");
    }
}

/// The dialog refused: the session ends as "permission refused", nothing was created.
#[test]
fn a_refused_permission_falls_back_without_a_session() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(JavaScript {
        dialog_answer: false,
        ..JavaScript::default()
    });
    let mut state = start(&mut core);
    core.drive(&mut state, Event::AppPaused);
    let told = core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(
        state,
        SessionState::Unavailable(Unavailable::PermissionRefused)
    );
    assert_eq!(told.fell_back, Some(Unavailable::PermissionRefused));
    assert_eq!(sim.calls("ArSession_create"), 0);
}

/// Defect 4: hardware-buffer texture mode needs API 27 while minSdk is 24. Decision: keep
/// minSdk 24 and fall back to 3D with a banner saying why (docs/phone-arcore.md). Before: the
/// session was created and configuring failed as "ARCore failed (status -8)".
#[test]
fn below_api_27_ar_falls_back_before_a_session_is_made_and_says_why() {
    let sim = Sim::take();
    sim.set("RegattaSim_setApiLevel", 26);
    let (mut core, _jni) = sim.arcore(JavaScript {
        sdk_int: 26,
        ..granted()
    });
    let mut state = SessionState::Start;
    let told = core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(
        state,
        SessionState::Unavailable(Unavailable::AndroidTooOld(26))
    );
    assert!(told.fell_back.unwrap().message().contains("API 27"));
    assert_eq!(
        sim.calls("ArSession_create") + sim.calls("ArCoreApk_requestInstall"),
        0
    );

    // At 27 the same phone runs AR (the simulator accepts hardware-buffer mode from 27).
    let sim_27 = {
        drop(core);
        sim.set("RegattaSim_setApiLevel", 27);
        sim.arcore(JavaScript {
            sdk_int: 27,
            ..granted()
        })
    };
    let (mut core, _jni) = sim_27;
    assert_eq!(start(&mut core), SessionState::Running);
}

/// The simulator itself refuses hardware-buffer mode below 27, as ARCore does: what the gate
/// above avoids.
#[test]
fn the_simulator_refuses_hardware_buffers_below_api_27() {
    let sim = Sim::take();
    sim.set("RegattaSim_setApiLevel", 26);
    // The Java side claims 27 (the gate passes): configuring fails, HDR then ambient.
    let (mut core, _jni) = sim.arcore(JavaScript {
        sdk_int: 27,
        ..granted()
    });
    let state = start(&mut core);
    assert_eq!(
        state,
        SessionState::Unavailable(Unavailable::Failed(status::ERROR_UNSUPPORTED_CONFIGURATION))
    );
    assert_eq!(sim.calls("ArSession_configure"), 2);
    // The fall-back destroys the session on its own thread.
    sim.wait_destroy_started(1);
    drop(core);
}

/// Defect 5: after an update error the session is given up: paused (camera closed), frame
/// and session destroyed, pointers nulled. Before: `FallBack` only logged; the session stayed
/// resumed with the camera open.
#[test]
fn an_update_error_pauses_and_destroys_the_session() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    let mut state = start(&mut core);
    sim.fail_updates(status::ERROR_FATAL, 1);
    let answer = core.update().expect("the update fails");
    let told = core.drive(&mut state, answer);
    assert_eq!(
        told.fell_back,
        Some(Unavailable::Failed(status::ERROR_FATAL))
    );
    assert_eq!(sim.calls("ArSession_pause"), 1, "the camera is closed");
    assert_eq!(sim.calls("ArFrame_destroy"), 1);
    assert!(!core.has_session(), "the pointers are nulled");
    assert_eq!(core.update(), None, "nothing is called on a dead session");
    assert_eq!(sim.calls("ArSession_update"), 1);
    // The destroy runs on its own thread; once it has, nothing is left.
    sim.wait_destroy_started(1);
    drop(core);
    while sim.destroys_finished() < 1 {
        std::thread::yield_now();
    }
    assert_eq!(sim.live(None), 0);
}

/// Defect 7: `ArSession_destroy` ("will take several seconds") runs on another thread: with
/// the simulator's destroy blocked, closing returns and the session is already unreachable.
/// Before: it ran in `Drop` on the calling thread (Android's main thread waits: ANR risk);
/// this test would not return.
#[test]
fn the_session_is_destroyed_off_the_calling_thread() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);
    sim.set("RegattaSim_setDestroyBlocking", 1);
    let destroying = core.close().expect("a session to close");
    drop(core);
    sim.wait_destroy_started(1);
    assert_eq!(sim.destroys_finished(), 0, "the destroy is still running");
    sim.set("RegattaSim_setDestroyBlocking", 0);
    destroying.join().unwrap();
    assert_eq!(sim.destroys_finished(), 1);
    assert_eq!(sim.live(None), 0);
}

/// Defect 8a: the HDR light direction is read only when HDR is configured. The simulator, as
/// ARCore, answers straight up in ambient mode. Before: read always; after the fall-back to
/// ambient the race was lit from the zenith.
#[test]
fn the_light_direction_is_read_only_in_hdr_mode() {
    let sim = Sim::take();
    sim.set("RegattaSim_setHdrSupported", 0);
    let (mut core, _jni) = sim.arcore(granted());
    assert_eq!(start(&mut core), SessionState::Running);
    assert_eq!(
        sim.calls("ArSession_configure"),
        2,
        "HDR refused, then ambient"
    );
    core.update();
    core.next_frame().unwrap().unwrap();
    assert_eq!(core.view.unwrap().light_towards, None);
    assert_eq!(
        sim.calls("ArLightEstimate_getEnvironmentalHdrMainLightDirection"),
        0
    );
    drop(core);

    sim.call0("RegattaSim_reset");
    sim.set_light(true, [0.0, 3.0, 4.0]);
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);
    core.update();
    core.next_frame().unwrap().unwrap();
    let towards = core.view.unwrap().light_towards.expect("HDR light");
    assert!((towards - glam::DVec3::new(0.0, 0.6, 0.8)).length() < 1e-6);
}

/// Defect 8b: an unchanged `ArFrame_getTimestamp` is the same image: not copied (nor, in the
/// app, uploaded) again. Before: every display frame acquired and copied the image.
#[test]
fn an_unchanged_timestamp_skips_the_image_copy() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);
    sim.set("RegattaSim_holdFrame", 1);
    core.update();
    assert!(core.next_frame().unwrap().is_some());
    core.update();
    assert!(
        core.next_frame().unwrap().is_none(),
        "same timestamp: nothing new"
    );
    assert_eq!(sim.calls("ArFrame_acquireCameraImage"), 1);
    assert!(core.view.is_some(), "the display camera is still read");
    sim.set("RegattaSim_holdFrame", 0);
    core.update();
    assert!(core.next_frame().unwrap().is_some(), "a new image is read");
    assert_eq!(sim.calls("ArFrame_acquireCameraImage"), 2);
}

/// Defect 8c: a plane subsumed by another is listed by ARCore beside its parent; it is
/// skipped. Before: the table came twice.
#[test]
fn a_subsumed_plane_is_skipped() {
    let sim = Sim::take();
    sim.set("RegattaSim_setSubsumedCopy", 1);
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);
    core.update();
    let frame = core.next_frame().unwrap().unwrap();
    assert_eq!(frame.planes.len(), 1);
    assert_eq!(sim.calls("ArTrackableList_acquireItem"), 2);
    assert_eq!(
        sim.live(Some("trackable")),
        0,
        "the parent acquired for the check is released"
    );
}

/// Scripted tracking: PAUSED with each reason gives its hint; STOPPED too; back to tracking.
#[test]
fn tracking_states_and_failure_reasons_reach_the_hint() {
    let sim = Sim::take();
    let (mut core, _jni) = sim.arcore(granted());
    start(&mut core);
    for (state, reason, hint) in [
        (1, 2, "Too dark"),
        (1, 3, "more slowly"),
        (1, 4, "textured"),
        (1, 5, "in use"),
        (1, 1, "slowly"),
        (2, 0, "slowly"),
    ] {
        sim.set2("RegattaSim_setTracking", state, reason);
        core.update();
        let frame = core.next_frame().unwrap().unwrap();
        let expected = if state == 1 {
            ar::TrackingState::Paused
        } else {
            ar::TrackingState::Stopped
        };
        assert_eq!(frame.tracking, expected);
        assert!(core.view.unwrap().hint.unwrap().contains(hint), "{reason}");
    }
    sim.set2("RegattaSim_setTracking", 0, 0);
    core.update();
    core.next_frame().unwrap().unwrap();
    assert_eq!(core.view.unwrap().hint, None);
}

/// ArCoreApk availability and a busy camera, through the session machine.
#[test]
fn apk_missing_unsupported_and_camera_busy() {
    let sim = Sim::take();
    for (mode, expected) in [
        (
            3,
            SessionState::Unavailable(Unavailable::DeviceNotSupported),
        ),
        (1, SessionState::InstallRequested),
    ] {
        sim.call0("RegattaSim_reset");
        sim.set("RegattaSim_setApk", mode);
        let (mut core, _jni) = sim.arcore(granted());
        assert_eq!(start(&mut core), expected, "mode {mode}");
        if mode == 1 {
            // Back from the Play Store without installing.
            let mut state = expected;
            core.drive(
                &mut state,
                Event::AppResumed {
                    library_loaded: true,
                },
            );
            assert_eq!(
                state,
                SessionState::Unavailable(Unavailable::InstallDeclined)
            );
        }
    }
    sim.call0("RegattaSim_reset");
    sim.set("RegattaSim_setApk", 2);
    let (mut core, _jni) = sim.arcore(granted());
    let mut state = start(&mut core);
    core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(
        state,
        SessionState::Running,
        "installed from the Play Store"
    );
    drop(core);

    sim.call0("RegattaSim_reset");
    let (mut core, _jni) = sim.arcore(granted());
    let mut state = start(&mut core);
    sim.set("RegattaSim_setCameraAvailable", 0);
    let answer = core.update().unwrap();
    let told = core.drive(&mut state, answer);
    assert_eq!(state, SessionState::Paused);
    assert!(told.note.unwrap().contains("in use"));
    sim.set("RegattaSim_setCameraAvailable", 1);
    core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(state, SessionState::Running);
}
