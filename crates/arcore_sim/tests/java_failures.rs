//! Issue 26, defect 2, and the library kept loaded: what a first run on a phone meets when a
//! Java call around ARCore fails. The simulator leaves Java exceptions pending in the host's
//! fake env (a class its DEX lacks, an exception thrown after a call that succeeded), and the
//! fake reports them as jni 0.22 does; the session must answer each with a fall-back and a
//! one-sentence banner, and a session already made must be destroyed, not leaked.

mod common;

use ar::arcore::ffi::ArCore;
use ar::arcore::{Event, SessionState, Unavailable};
use common::{Sim, granted, start};

/// An APK without ARCore's classes: `ArCoreApk_requestInstall` fails to find
/// `com.google.ar.core.ArCoreApk` and leaves `ClassNotFoundException` pending. Before, the
/// failed Java call gave the machine no answer and the banner said "Checking ARCore…" forever.
#[test]
fn a_class_missing_from_the_apk_falls_back_with_a_reason() {
    let sim = Sim::take();
    sim.fail_class_lookup("com.google.ar.core.ArCoreApk");
    let (mut core, _jni) = sim.arcore(granted());
    let mut state = start(&mut core);
    assert_eq!(state, SessionState::Unavailable(Unavailable::JavaFailed));
    // A later resume does not start over: the reason stays on screen.
    core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(state, SessionState::Unavailable(Unavailable::JavaFailed));
    assert_eq!(sim.calls("ArCoreApk_requestInstall"), 1);
    assert_eq!(sim.live(Some("session")), 0);
}

/// `ArSession_create` cannot find `SessionCreateJniHelper`: the same, one step later.
#[test]
fn a_session_helper_missing_from_the_apk_falls_back() {
    let sim = Sim::take();
    sim.fail_class_lookup("com.google.ar.core.SessionCreateJniHelper");
    let (mut core, _jni) = sim.arcore(granted());
    assert_eq!(
        start(&mut core),
        SessionState::Unavailable(Unavailable::JavaFailed)
    );
    assert_eq!(sim.calls("ArSession_create"), 1);
    assert_eq!(sim.live(Some("session")), 0);
}

/// `ArSession_create` made a session, then its Java half left an exception pending: jni 0.22
/// reports the call as failed although it returned. Before, the session pointer was dropped on
/// the floor (the simulator counted it live forever) and the state stayed `Creating`. Now the
/// session is kept long enough for the fall-back to close it: destroyed, nothing live.
#[test]
fn a_session_made_before_a_java_exception_is_destroyed_not_leaked() {
    let sim = Sim::take();
    sim.throw_after(
        "ArSession_create",
        "java.lang.IllegalStateException: late failure",
    );
    let (mut core, _jni) = sim.arcore(granted());
    assert_eq!(
        start(&mut core),
        SessionState::Unavailable(Unavailable::JavaFailed)
    );
    assert!(!core.has_session());
    // The fall-back destroys the session on ARCore's teardown thread: wait for it (bounded,
    // so that a leak fails the test rather than hangs it).
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(10);
    while sim.destroys_finished() < 1 && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    drop(core);
    assert_eq!(sim.destroys_finished(), 1, "the session made was destroyed");
    assert_eq!(sim.live(None), 0, "every object ARCore made was released");
}

/// The library is never unloaded while the process lives (issue 26: ARCore keeps threads for up
/// to 10 s after a pause; unloading its code under them crashes). The loader's own answer is the
/// truth: `dlopen(RTLD_NOLOAD)` finds a library only while it is loaded. A private copy of the
/// simulator is used so that no other handle (the tests' own) keeps it.
#[test]
fn the_arcore_library_stays_loaded_after_its_last_user_is_gone() {
    let sim = Sim::take();
    let dir = std::env::temp_dir().join(format!("regatta-keep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let copy = dir.join("libarcore_copy.so");
    std::fs::copy(&sim.path, &copy).unwrap();
    let loaded = || {
        // SAFETY: RTLD_NOLOAD only asks the loader; nothing is loaded or run.
        unsafe {
            libloading::os::unix::Library::open(
                Some(&copy),
                libloading::os::unix::RTLD_LAZY | libc_rtld_noload(),
            )
        }
        .is_ok()
    };
    assert!(!loaded(), "not loaded before ArCore loads it");
    {
        let core = ArCore::load_from(&copy, Box::new(ar::arcore::ffi::ScriptedJni::default()));
        assert!(core.is_loaded());
        assert!(loaded());
    }
    assert!(loaded(), "still loaded after the last ArCore is gone");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `RTLD_NOLOAD` (glibc and bionic: 4).
fn libc_rtld_noload() -> i32 {
    4
}
