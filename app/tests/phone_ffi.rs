//! Phone sessions through the phone's own ARCore glue (`ar::arcore::ffi`, the code the APK
//! runs) against the simulated ARCore (`crates/arcore_sim`'s cdylib, built by cargo as a
//! dev-dependency), its Java calls answered by the scripted JNI: the permission dialog, ARCore
//! unsupported, tracking lost and regained, a tap placing the course on the simulator's table.
//! One simulator per process: the tests take turns.

use std::path::PathBuf;
use std::sync::Mutex;

use ar::arcore::Unavailable;
use ar::arcore::session::tracking_hint;
use regatta::core::table::{course_pivot, table_depth};
use regatta::phone_sim::PhoneSim;
use regatta::phone_sim::device::Device;
use regatta::phone_sim::script::Step;

static TURN: Mutex<()> = Mutex::new(());
const SIZE: [u32; 2] = [180, 400];

/// The session through the FFI, the simulator reset; `None` (skip) without a GPU.
fn session(cues: &[Step]) -> Option<(PhoneSim, std::sync::MutexGuard<'static, ()>)> {
    let turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
    render::gpu::test_gpu()?;
    let lib = arcore_sim::built_library().expect("cargo builds libarcore_sim.so for the tests");
    let mut sim = PhoneSim::with_ffi(&lib, None, SIZE, Device::A54.pixels_per_point(SIZE), None)
        .expect("the simulator loads");
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    for c in cues {
        sim.step(c, &out).unwrap();
    }
    sim.step(&Step::Wait(0.3), &out).unwrap();
    Some((sim, turn))
}

#[test]
fn a_fresh_install_asks_for_the_camera_and_a_tap_places_the_course_on_the_table() {
    let Some((mut sim, _turn)) = session(&[]) else {
        return;
    };
    assert_eq!(format!("{:?}", sim.app.session()), "Running");
    assert_eq!(
        sim.app.status().banner.as_deref(),
        Some("Tap the table to place the course.")
    );
    sim.tap([0.5, 0.6]);
    let course = sim
        .app
        .course()
        .expect("the tap found the simulator's table");
    let world =
        regatta::core::scene::RaceWorld::new(race::Race::sample(), ocean::WaveSet::default_sea());
    let on_table = course
        .race_to_ar()
        .transform_point3(course_pivot(world.play_area, table_depth()));
    // The simulator's table: the plane y = 0, 1.2 m × 0.8 m about the origin (ar::synth).
    let [ex, ez] = ar::synth::TABLE_EXTENT;
    assert!(on_table.y.abs() < 1e-4, "{on_table}");
    assert!(
        on_table.x.abs() <= ex / 2.0 && on_table.z.abs() <= ez / 2.0,
        "{on_table}"
    );
    assert!(sim.app.status().frames_drawn > 3);
}

#[test]
fn refusing_the_dialog_says_so() {
    let Some((sim, _turn)) = session(&[Step::Permission(false)]) else {
        return;
    };
    assert_eq!(
        sim.app.status().banner,
        Some(Unavailable::PermissionRefused.message())
    );
}

#[test]
fn an_unsupported_phone_says_so() {
    let Some((sim, _turn)) = session(&[Step::ArCore(
        regatta::phone_sim::backend::Availability::Unsupported,
    )]) else {
        return;
    };
    assert_eq!(
        sim.app.status().banner,
        Some(Unavailable::DeviceNotSupported.message())
    );
}

#[test]
fn tracking_lost_and_regained_through_the_ffi() {
    let Some((mut sim, _turn)) = session(&[]) else {
        return;
    };
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    sim.step(&Step::Tracking(Some(3)), &out).unwrap();
    sim.step(&Step::Wait(0.2), &out).unwrap();
    assert_eq!(
        sim.app.status().banner.as_deref(),
        Some(tracking_hint(1, 3).unwrap())
    );
    sim.step(&Step::Tracking(None), &out).unwrap();
    sim.step(&Step::Wait(0.2), &out).unwrap();
    assert_eq!(
        sim.app.status().banner.as_deref(),
        Some("Tap the table to place the course.")
    );
}
