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
use regatta::phone_sim::script::Step;
use regatta::sim_phone::device::Device;

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
    let world = regatta::world::RaceWorld::new(race::Race::sample(), ocean::WaveSet::default_sea());
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
        regatta::sim_phone::backend::Availability::Unsupported,
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

// Issue 26: what a first run on a phone meets, through the phone's own ARCore glue.

fn out() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
}

/// Defect 6, exactly as the issue reproduces it (`tests/phone/permission_allowed_later.txt`),
/// through `regatta phone-sim` with the simulated ARCore behind the FFI and with the scripted
/// stand-in: refused, allowed in Settings while away, back: the course is placed. Before, the
/// refusal was final and the session stayed `Unavailable(PermissionRefused)`.
#[test]
fn a_camera_allowed_in_settings_after_a_refusal_places_the_course() {
    let _turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let lib = arcore_sim::built_library().expect("cargo builds libarcore_sim.so for the tests");
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/phone/permission_allowed_later.txt");
    for ffi in [true, false] {
        let dir = out().join(format!("allowed-later-{ffi}"));
        let _ = std::fs::remove_dir_all(&dir);
        let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_regatta"));
        cmd.args([
            "phone-sim",
            "--device",
            "a54",
            "--size",
            "180x400",
            "--script",
        ])
        .arg(&script)
        .arg("--out")
        .arg(&dir);
        if ffi {
            cmd.arg("--arcore-lib").arg(&lib);
        }
        let o = cmd.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let log = std::fs::read_to_string(dir.join("log.jsonl")).unwrap();
        let lines: Vec<serde_json::Value> = log
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        // After `wait 1`: refused, and the banner says so.
        assert_eq!(
            lines[1]["session"], "Unavailable(PermissionRefused)",
            "ffi {ffi}"
        );
        let end = lines.last().unwrap();
        assert_eq!(end["session"], "Running", "ffi {ffi}: {end}");
        assert_eq!(end["placed"], true, "ffi {ffi}: {end}");
    }
}

/// Defect 6: after a refusal the banner has a button that asks again; the user accepts the new
/// dialog and the session runs, without leaving the app.
#[test]
fn the_banners_button_asks_for_the_camera_again() {
    let Some((mut sim, _turn)) = session(&[Step::Permission(false)]) else {
        return;
    };
    assert_eq!(
        sim.app.session(),
        ar::arcore::SessionState::Unavailable(Unavailable::PermissionRefused)
    );
    let button = sim
        .app
        .bar
        .and_then(|b| b.banner_button)
        .expect("the refused banner has a button");
    // The user will accept this time.
    match &sim.cues {
        regatta::sim_phone::Cues::Ffi { jni, .. } => jni.script(|s| s.dialog_answer = true),
        regatta::sim_phone::Cues::Scripted(_) => unreachable!("an FFI session"),
    }
    let ppp = Device::A54.pixels_per_point(SIZE);
    let at = |p: egui::Pos2| {
        [
            f64::from(p.x * ppp) / f64::from(SIZE[0]),
            f64::from(p.y * ppp) / f64::from(SIZE[1]),
        ]
    };
    sim.tap(at(button.center()));
    sim.step(&Step::Wait(0.5), &out()).unwrap();
    assert_eq!(sim.app.session(), ar::arcore::SessionState::Running);
    sim.tap([0.5, 0.6]);
    assert!(sim.app.course().is_some(), "the course stands on the table");
}

/// Defect 5: with a 24 dp status bar and a 48 dp navigation bar (Android's default heights,
/// AOSP `status_bar_height` and `navigation_bar_height`), the bar and its buttons lie below the
/// status bar, the panels' content rect is the window less both bars, and a tap on the Pool
/// button lands. Before, the bar sat 10 points from the top, under the status bar.
#[test]
fn the_bar_and_panels_keep_clear_of_the_system_bars() {
    let Some((mut sim, _turn)) = session(&[Step::Bars(24.0, 48.0)]) else {
        return;
    };
    let ctx = sim.app.egui_context().unwrap();
    let content = ctx.content_rect();
    // The A54's layout is 360 × 800 dp (points).
    assert_eq!(
        content,
        egui::Rect::from_min_max(egui::pos2(0.0, 24.0), egui::pos2(360.0, 752.0))
    );
    let bar = sim.app.bar.expect("the bar was laid out");
    for b in [bar.race_button, bar.pool_button, bar.record_button] {
        assert!(content.contains_rect(b), "{b:?} inside {content:?}");
        assert!(b.top() >= 24.0, "{b:?} below the status bar");
    }
    let ppp = Device::A54.pixels_per_point(SIZE);
    let c = bar.pool_button.center();
    sim.tap([
        f64::from(c.x * ppp) / f64::from(SIZE[0]),
        f64::from(c.y * ppp) / f64::from(SIZE[1]),
    ]);
    assert_eq!(sim.app.scene, regatta::hud::SceneChoice::Pool);
}

/// Defect 3: the phone turned by 180° sends no window or configuration event; the app reads the
/// display's rotation itself and ARCore's display transform follows. The truth: turning the
/// screen by 180° maps each screen point p to 1 − p, so the image point shown at p after the
/// turn is the one shown at 1 − p before it (the camera held still: one frame held).
#[test]
fn a_180_degree_turn_without_an_event_turns_the_camera_image() {
    let Some((mut sim, _turn)) = session(&[]) else {
        return;
    };
    let before = sim.app.ar.frame.as_ref().unwrap().display_uv;
    sim.flip();
    // The rotation is read every 15 frames: 1.5 s of the simulated 10 fps phone.
    sim.step(&Step::Wait(2.0), &out()).unwrap();
    let after = sim.app.ar.frame.as_ref().unwrap().display_uv;
    for p in [[0.2f32, 0.3], [0.5, 0.5], [0.9, 0.1]] {
        let p = glam::Vec2::from(p);
        let want = before.transform_point2(glam::Vec2::ONE - p);
        let got = after.transform_point2(p);
        assert!((got - want).length() < 1e-4, "{p}: {got} vs {want}");
    }
}

/// The Vulkan crash marker: a launch "killed" before its first good frames leaves the marker;
/// the next launch draws with OpenGL ES and says so. A launch that draws its frames clears it.
#[test]
fn a_launch_killed_on_its_first_vulkan_frames_sends_the_next_to_opengl_es() {
    use regatta::core::vulkan_marker::{FELL_BACK_NOTE, GOOD_FRAMES, VulkanMarker};
    let _turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    if gpu.adapter.get_info().backend != wgpu::Backend::Vulkan {
        return;
    }
    let dir = out().join("vulkan-marker");
    let _ = std::fs::remove_dir_all(&dir);
    let marker = VulkanMarker::in_dir(&dir);
    let feed = || regatta::core::feed::CameraFeed::synth(ar::SynthConfig::default());
    let ppp = Device::A54.pixels_per_point(SIZE);
    // A good launch: armed on its first frame, cleared after GOOD_FRAMES.
    let mut sim = PhoneSim::launch(feed(), SIZE, ppp, Some(dir.clone()));
    assert!(marker.left_by_a_crash(), "armed before the first submit");
    sim.step(&Step::Wait(GOOD_FRAMES as f64 / 10.0 + 0.2), &out())
        .unwrap();
    assert!(!marker.path().exists(), "cleared after the good frames");
    drop(sim);
    // A launch killed after one frame: the marker stays.
    let sim = PhoneSim::launch(feed(), SIZE, ppp, Some(dir.clone()));
    assert!(sim.app.graphics_note().is_none());
    // Killed: nothing more runs (dropping clears nothing).
    drop(sim);
    assert!(marker.left_by_a_crash());
    // The next launch goes to OpenGL ES, and says so.
    let sim = PhoneSim::launch(feed(), SIZE, ppp, Some(dir.clone()));
    let gl = sim.app.describe_gpu().is_some_and(|d| d.ends_with("(Gl)"));
    if gl {
        assert_eq!(sim.app.graphics_note(), Some(FELL_BACK_NOTE));
        assert!(
            marker.left_by_a_crash(),
            "kept: this build stays on OpenGL ES"
        );
    } else {
        // No OpenGL ES on this host: it went back to Vulkan after trying (logged).
        eprintln!("no OpenGL ES here: {:?}", sim.app.describe_gpu());
    }
}
