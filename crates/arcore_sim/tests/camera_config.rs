//! The camera config (issue 26, "first run on a real phone"): ARCore's default CPU image is
//! 640 × 480, blurry behind the water on a 1080 × 2400 screen. Before each resume the app's
//! FFI sets the back camera's 30 fps config with the largest CPU image within the tier's budget;
//! the frames then arrive at that size. ARCore takes a config only while the session is paused:
//! a set while it runs is refused and the session goes on with the config it has.
//!
//! Truth: the configs `arcore_c_api.h` documents for a back camera (640 × 480, 1280 × 720,
//! 1920 × 1080 CPU images, every texture 1920 × 1080), which the simulator lists, and the
//! budget's pixel count: the expected image is the largest of the three within it.

mod common;

use ar::FrameSource;
use ar::arcore::ffi::{CameraBudget, CameraConfigOutcome};
use ar::arcore::session::status;
use ar::arcore::{CameraConfigSize, Event, SessionState};
use common::{Core, Sim, granted, start};

/// The synthetic feed's frames per loop here (each is drawn at the config's size).
const FRAMES: u32 = 4;
/// A 1080 × 2400 portrait phone.
const SCREEN: [u32; 2] = [1080, 2400];

fn budget(max_image_px: u64) -> CameraBudget {
    CameraBudget {
        max_image_px,
        screen: Some(SCREEN),
    }
}

fn config(image: [u32; 2]) -> CameraConfigSize {
    CameraConfigSize {
        image,
        texture: [1920, 1080],
    }
}

/// The size of the next camera frame's CPU image.
fn next_image(core: &mut Core) -> [u32; 2] {
    assert_eq!(core.update(), None, "ArSession_update succeeds");
    let frame = core.next_frame().expect("reads").expect("a camera image");
    let (w, h) = frame.image.size();
    // The intrinsics are the image's (the synthetic camera keeps its 65° field of view).
    assert_eq!((frame.intrinsics.width, frame.intrinsics.height), (w, h));
    let hfov = 2.0 * (f64::from(w) / 2.0 / frame.intrinsics.fx).atan();
    assert!(
        (hfov.to_degrees() - 65.0).abs() < 1e-3,
        "{}",
        hfov.to_degrees()
    );
    [w, h]
}

/// Pauses and resumes the app (the activity to the background and back).
fn pause_resume(core: &mut Core, state: &mut SessionState) {
    core.drive(state, Event::AppPaused);
    assert_eq!(*state, SessionState::Paused);
    core.drive(
        state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    assert_eq!(*state, SessionState::Running);
}

#[test]
fn without_a_budget_the_phone_gets_arcores_default_640_by_480() {
    let sim = Sim::take();
    sim.use_camera_configs(0, FRAMES);
    let (mut core, _jni) = sim.arcore(granted());
    assert_eq!(start(&mut core), SessionState::Running);
    assert_eq!(next_image(&mut core), [640, 480]);
    assert_eq!(core.camera_config(), Some(config([640, 480])));
    assert_eq!(sim.calls("ArSession_setCameraConfig"), 0);
}

#[test]
fn each_budget_gets_the_largest_image_within_it_in_its_frames() {
    for (phone, max_px, expected) in [
        // Below VGA: nothing fits, the smallest (the back camera's, not the selfie camera's
        // 640 × 480 with its smaller texture: the filter asks for the back camera).
        (0, 300_000, [640, 480]),
        // The low and medium tiers' budget (925,000 px): 1280 × 720 = 921,600.
        (0, 925_000, [1280, 720]),
        (0, 921_599, [640, 480]),
        // The high and ultra tiers' (3,333,000 px): 1920 × 1080.
        (0, 3_333_000, [1920, 1080]),
        // A phone with a 60 fps camera lists each size twice, the 60 fps ones first: the
        // 30 fps one is set (checked below).
        (1, 3_333_000, [1920, 1080]),
    ] {
        let sim = Sim::take();
        sim.use_camera_configs(phone, FRAMES);
        let (mut core, _jni) = sim.arcore(granted());
        core.set_camera_budget(budget(max_px));
        assert_eq!(start(&mut core), SessionState::Running);
        let mut sizes = vec![next_image(&mut core), next_image(&mut core)];
        sizes.dedup();
        assert_eq!(sizes, vec![expected], "budget {max_px} px, phone {phone}");
        assert_eq!(core.camera_config(), Some(config(expected)));
        // Set only when it differs from ARCore's default.
        let sets = u64::from(expected != [640, 480]);
        assert_eq!(sim.calls("ArSession_setCameraConfig"), sets);
        let fps = if sets == 1 { 30 } else { 0 };
        assert_eq!(sim.last_camera_config_fps(), fps, "the 30 fps config");
        drop(core);
        for kind in [
            "camera_config",
            "camera_config_list",
            "camera_config_filter",
        ] {
            assert_eq!(sim.live(Some(kind)), 0, "{kind} released");
        }
    }
}

#[test]
fn a_set_while_running_is_refused_and_the_session_goes_on_until_the_next_resume() {
    let sim = Sim::take();
    sim.use_camera_configs(0, FRAMES);
    let (mut core, _jni) = sim.arcore(granted());
    core.set_camera_budget(budget(3_333_000));
    let mut state = start(&mut core);
    assert_eq!(next_image(&mut core), [1920, 1080]);

    // The tier drops: the running session keeps its config; forced now, ARCore refuses.
    core.set_camera_budget(budget(925_000));
    assert_eq!(next_image(&mut core), [1920, 1080]);
    assert_eq!(
        core.apply_camera_budget(),
        Some(CameraConfigOutcome::Refused {
            wanted: config([1280, 720]),
            status: status::ERROR_SESSION_NOT_PAUSED,
            kept: Some(config([1920, 1080])),
        })
    );
    assert_eq!(state, SessionState::Running);
    assert_eq!(next_image(&mut core), [1920, 1080]);

    // At the next pause and resume the new budget's image comes.
    pause_resume(&mut core, &mut state);
    assert_eq!(next_image(&mut core), [1280, 720]);
    assert_eq!(core.camera_config(), Some(config([1280, 720])));
    // And a resume with the same budget sets nothing.
    let sets = sim.calls("ArSession_setCameraConfig");
    pause_resume(&mut core, &mut state);
    assert_eq!(next_image(&mut core), [1280, 720]);
    assert_eq!(sim.calls("ArSession_setCameraConfig"), sets);
}

#[test]
fn a_refused_set_before_the_first_resume_keeps_the_default_and_runs() {
    let sim = Sim::take();
    sim.use_camera_configs(0, FRAMES);
    sim.set(
        "RegattaSim_failCameraConfig",
        status::ERROR_INVALID_ARGUMENT,
    );
    let (mut core, _jni) = sim.arcore(granted());
    core.set_camera_budget(budget(3_333_000));
    let mut state = start(&mut core);
    assert_eq!(state, SessionState::Running);
    assert_eq!(next_image(&mut core), [640, 480]);
    assert_eq!(sim.calls("ArSession_setCameraConfig"), 1);
    // The refusal was once: the next resume sets it.
    pause_resume(&mut core, &mut state);
    assert_eq!(next_image(&mut core), [1920, 1080]);
}
