//! The camera image a phone session gets (issue 26, "first run on a real phone"): ARCore's
//! default CPU image is 640 × 480, blurry behind the water on a 1080 × 2400 screen. Through
//! the whole phone app (`PhoneSim`, the phone's own ARCore glue on the simulated ARCore listing
//! the back camera's documented configs), each quality tier gets the largest CPU image its
//! budget affords, in the frames the app draws; a tier change takes effect at the next pause
//! and resume (ARCore takes a camera config only while the session is paused).
//!
//! Truth: `arcore_c_api.h`'s back-camera configs (640 × 480, 1280 × 720, 1920 × 1080) and the
//! tiers' stated budgets (docs/quality.md: 925,000 px for `low` and `medium`, which 1280 × 720 =
//! 921,600 fits and 1920 × 1080 does not; 3,333,000 px for `high` and `ultra`, which
//! 1920 × 1080 = 2,073,600 fits). Before the app set a budget, every tier got 640 × 480.

use std::path::PathBuf;
use std::sync::Mutex;

use quality::Tier;
use regatta::phone_sim::PhoneSim;
use regatta::phone_sim::script::Step;
use regatta::sim_phone::Cues;
use regatta::sim_phone::device::Device;

static TURN: Mutex<()> = Mutex::new(());
const SIZE: [u32; 2] = [180, 400];

fn out() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
}

/// A phone session through the FFI on an OPPO A54 class phone's camera configs, the tier
/// pinned before launch, run for half a second; `None` (skip) without a GPU.
fn session(tier: Tier) -> Option<(PhoneSim, std::sync::MutexGuard<'static, ()>)> {
    let turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
    render::gpu::test_gpu()?;
    let lib = arcore_sim::built_library().expect("cargo builds libarcore_sim.so for the tests");
    let mut sim = PhoneSim::with_ffi(&lib, None, SIZE, Device::A54.pixels_per_point(SIZE), None)
        .expect("the simulator loads");
    match &sim.cues {
        Cues::Ffi { sim: library, .. } => library.use_camera_configs(0, 8).expect("the control"),
        Cues::Scripted(_) => unreachable!("with_ffi"),
    }
    sim.app.tiers.pin(Some(tier));
    sim.step(&Step::Wait(0.5), &out()).unwrap();
    Some((sim, turn))
}

/// The size of the camera image the app holds now.
fn image(sim: &PhoneSim) -> [u32; 2] {
    let frame = sim.app.ar.frame.as_ref().expect("a camera frame");
    let (w, h) = frame.image.size();
    [w, h]
}

#[test]
fn each_tier_gets_the_largest_camera_image_its_budget_affords() {
    for (tier, expected) in [
        (Tier::Low, [1280, 720]),
        (Tier::Medium, [1280, 720]),
        (Tier::High, [1920, 1080]),
        (Tier::Ultra, [1920, 1080]),
    ] {
        let Some((sim, _turn)) = session(tier) else {
            return;
        };
        assert_eq!(format!("{:?}", sim.app.session()), "Running");
        assert_eq!(sim.app.tier_drawn(), Some(tier));
        assert_eq!(image(&sim), expected, "{tier}");
    }
}

#[test]
fn a_tier_change_takes_effect_at_the_next_pause_and_resume() {
    let Some((mut sim, _turn)) = session(Tier::High) else {
        return;
    };
    assert_eq!(image(&sim), [1920, 1080]);
    // The tier drops while the session runs (pinned in the Scene panel, as a click on "low"
    // does): drawn at once, the camera config kept.
    let panel = sim
        .app
        .panels
        .settings
        .tier
        .as_mut()
        .expect("the tier control");
    panel.pinned = Some(Tier::Low);
    sim.step(&Step::Wait(0.5), &out()).unwrap();
    assert_eq!(sim.app.tier_drawn(), Some(Tier::Low));
    assert_eq!(image(&sim), [1920, 1080]);
    // To the background and back: the low tier's image.
    for step in [Step::Pause, Step::Resume, Step::Wait(0.5)] {
        sim.step(&step, &out()).unwrap();
    }
    assert_eq!(format!("{:?}", sim.app.session()), "Running");
    assert_eq!(image(&sim), [1280, 720]);
}
