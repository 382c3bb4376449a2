//! The desktop profile of the app as a state machine, without winit: the events the window's
//! shell hands in (`AppEvent`: the left button as one finger, the wheel, keys, dropped files)
//! and what the app does with them, headless on lavapipe with an offscreen window.
//!
//! - A click (a press that lifts within the one tap threshold, `TAP_MAX_PX` = 20 px and
//!   `TAP_MAX_S` = 0.3 s, the phone's) selects the boat under it; a press that moves farther
//!   orbits the view instead (by `OrbitCamera::drag`'s 0.005 rad a pixel) and selects nothing.
//!   Before the one app the desktop had its own 4 px click threshold and no time limit.
//! - The wheel zooms (0.9 of the distance a notch), F follows the selected boat (the orbit
//!   turns about the boat's position from its track).
//! - A dropped file that does not load leaves the race shown and says why in the Races panel
//!   (the file named); a good one replaces the race.
//! - Space pauses and plays; ←/→ step one second of race at 1× (docs/panels.md, "Shortcuts"),
//!   [ halves the speed, Home goes to the start signal; Escape asks the shell to quit.
//! - A lost device is rebuilt on OpenGL ES with a new egui context, which the window's shell
//!   follows (its egui-winit state made anew), and the panels take input on it.

mod common;

use regatta::core::app::{App, AppEvent, DesktopStart, Key, TAP_MAX_PX, TAP_MAX_S};
use regatta::hud::SceneChoice;
use regatta::hud::touch::TouchAction;
use regatta::setup::RaceSetup;

const SIZE: [u32; 2] = [480, 360];

/// The desktop app on the sample race (orbit view, ultra pinned), one frame drawn.
fn desktop() -> Option<App> {
    render::gpu::test_gpu()?;
    let start = DesktopStart {
        feed: None,
        water: render::water_look::WaterLook::default(),
        tier: Some(quality::Tier::Low),
        scene: SceneChoice::Race,
        pool_sea: None,
    };
    let world = RaceSetup::world(race::Race::sample(), ocean::WaveSet::default_sea());
    let mut app = App::desktop(world, start);
    // The side panels off: the scene's middle is free for clicks.
    app.panels.show_leaderboard = false;
    app.panels.show_perf = false;
    let mut app = common::shown(app, SIZE);
    app.frame(1.0 / 30.0);
    Some(app)
}

/// The left button: down at `from`, moved to `to`, up there (pixels), no frame between.
fn press_move_release(app: &mut App, from: [f32; 2], to: [f32; 2]) {
    app.on(AppEvent::touch(TouchAction::Down(0), &[from]));
    app.on(AppEvent::touch(TouchAction::Move, &[to]));
    app.on(AppEvent::touch(TouchAction::Up(0), &[to]));
}

/// A boat drawn in the middle of the scene, away from the panels, with nothing else under its
/// centre (its hull, pixels).
fn boat_in_the_middle(app: &App) -> (usize, [f32; 2]) {
    let hulls = app.overlays.hulls();
    let h = hulls
        .iter()
        .filter(|h| h.centre[1] > 60.0 && h.centre[1] < 220.0)
        .filter(|h| h.centre[0] > 40.0 && h.centre[0] < 440.0)
        .find(|h| app.overlays.pick(h.centre) == Some(h.boat))
        .expect("a boat in the middle of the view");
    (h.boat, [h.centre[0] as f32, h.centre[1] as f32])
}

#[test]
fn a_click_within_the_tap_threshold_selects_and_a_drag_orbits() {
    let Some(mut app) = desktop() else {
        return;
    };
    assert!(app.overlays.selected().is_empty());
    let (boat, c) = boat_in_the_middle(&app);
    // 19 px of travel, released on the boat: a click (the old desktop's 4 px said drag).
    let within = (TAP_MAX_PX - 1.0) as f32;
    let yaw = app.orbit().yaw;
    press_move_release(&mut app, [c[0] - within, c[1]], c);
    assert_eq!(app.overlays.selected(), &[boat]);
    // The press moved the view by its travel as it went, as a drag does.
    let expected = yaw - f64::from(within) * 0.005;
    assert!((app.orbit().yaw - expected).abs() < 1e-12);
    // A click on the same boat again unselects it.
    press_move_release(&mut app, c, c);
    assert!(app.overlays.selected().is_empty());
    // 21 px: a drag. It orbits by 0.005 rad a pixel and selects nothing.
    let beyond = (TAP_MAX_PX + 1.0) as f32;
    let yaw = app.orbit().yaw;
    press_move_release(&mut app, [c[0] - beyond, c[1]], c);
    assert!(app.overlays.selected().is_empty(), "a drag selected");
    let expected = yaw - f64::from(beyond) * 0.005;
    assert!(
        (app.orbit().yaw - expected).abs() < 1e-12,
        "{} vs {expected}",
        app.orbit().yaw
    );
    // A press held longer than the tap's time is no click either.
    app.on(AppEvent::touch(TouchAction::Down(0), &[c]));
    let frames = (TAP_MAX_S / (1.0 / 30.0)).ceil() as usize + 1;
    for _ in 0..frames {
        app.frame(1.0 / 30.0);
    }
    app.on(AppEvent::touch(TouchAction::Up(0), &[c]));
    assert!(app.overlays.selected().is_empty(), "a long press selected");
}

#[test]
fn the_wheel_zooms_and_follow_turns_the_view_about_the_selected_boat() {
    let Some(mut app) = desktop() else {
        return;
    };
    let (boat, c) = boat_in_the_middle(&app);
    let distance = app.orbit().distance;
    app.on(AppEvent::Wheel { steps: 2.0, px: c });
    let expected = (distance * 0.9 * 0.9).clamp(3.0, 5000.0);
    assert!((app.orbit().distance - expected).abs() < 1e-9 * expected);
    press_move_release(&mut app, c, c);
    assert_eq!(app.overlays.selected(), &[boat]);
    app.on(AppEvent::Key(Key::Char('f')));
    assert!(app.panels.follow);
    app.frame(1.0 / 30.0);
    // The orbit's target is the boat on the water at the frame's race time, from its track.
    let t = app.race_time();
    let p = app.race().boats[boat].state_at(t).position;
    let target = app.orbit().target;
    assert_eq!([target.x, target.y, target.z], [p[0], 0.0, p[1]]);
}

#[test]
fn a_dropped_bad_file_leaves_the_race_and_says_why() {
    let Some(mut app) = desktop() else {
        return;
    };
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("desktop_app_drop");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.gpx");
    std::fs::write(&bad, "<gpx><trk><trkseg><trkpt lat=\"95\" lon=\"0\">\n").unwrap();
    let shown = app.race().name.clone();
    app.on(AppEvent::FileDropped(bad));
    app.frame(1.0 / 30.0);
    assert_eq!(app.race().name, shown, "the race shown stays");
    let error = app.race_error().expect("the panel says why");
    assert!(
        error.contains("bad.gpx") && !error.contains('\n'),
        "{error}"
    );
    // A good file (a real track of the Valencia fleet) replaces the race; the error goes.
    let good = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/races/valencia/2025-06-21-ESP30782-P01.gpx");
    app.on(AppEvent::FileDropped(good.clone()));
    app.frame(1.0 / 30.0);
    let opened = regatta::panels::load_race_files(&[good]).unwrap();
    assert_eq!(app.race().name, opened.name);
    assert_ne!(app.race().name, shown);
    assert_eq!(app.race_error(), None);
}

#[test]
fn space_pauses_and_the_arrows_step_race_time() {
    let Some(mut app) = desktop() else {
        return;
    };
    assert!(app.panels.clock.is_playing());
    app.on(AppEvent::Key(Key::Space));
    let t0 = app.race_time();
    app.frame(0.5);
    assert_eq!(app.race_time(), t0, "paused, time stands");
    // 8× at the start (hud::initial_clock): three halvings make 1×, where a step is 1 s.
    for _ in 0..3 {
        app.on(AppEvent::Key(Key::Char('[')));
    }
    app.on(AppEvent::Key(Key::Right));
    assert_eq!(app.race_time(), t0 + 1.0);
    app.on(AppEvent::Key(Key::Right));
    app.on(AppEvent::Key(Key::Left));
    assert_eq!(app.race_time(), t0 + 1.0);
    app.on(AppEvent::Key(Key::Home));
    assert_eq!(app.race_time(), 0f64.max(app.race().time_span().0));
    // Space plays again at 1×: half a second of wall time is half a second of race.
    app.on(AppEvent::Key(Key::Space));
    let t1 = app.race_time();
    app.frame(0.5);
    assert!((app.race_time() - (t1 + 0.5)).abs() < 1e-9);
    assert!(!app.quit_requested());
    app.on(AppEvent::Key(Key::Escape));
    assert!(app.quit_requested());
}

/// A lost device (destroyed here, which fires wgpu's lost callback as a driver reset does) is
/// rebuilt on OpenGL ES at the next frame, with a new egui context: `App::egui_context` names
/// the new one (the window's shell makes its egui-winit state anew when
/// `desktop::egui_input_stale` says so), the banner's note says
/// so, and the panels' input reaches the panels on the new context: a click on the timeline's
/// pause button pauses race time.
#[test]
fn after_a_lost_device_the_panels_run_on_the_new_egui_context() {
    let Some(mut app) = desktop() else {
        return;
    };
    let before = app.egui_context().unwrap();
    // The window's shell keeps its egui-winit state while the app's context is the same.
    let stale = regatta::desktop::egui_input_stale;
    assert!(!stale(Some(&before), app.egui_context().as_ref()));
    app.lose_device();
    app.frame(1.0 / 30.0);
    let Some(after) = app.egui_context() else {
        panic!("no device after the loss: {:?}", app.graphics_note());
    };
    assert!(
        after != before,
        "the rebuilt device's egui context is a new one"
    );
    // ... and the shell makes a new state on it after this frame.
    assert!(stale(Some(&before), Some(&after)));
    assert!(!stale(Some(&after), app.egui_context().as_ref()));
    assert_eq!(
        app.graphics_note(),
        Some("The GPU was lost; drawing with OpenGL ES.")
    );
    app.frame(1.0 / 30.0);
    app.panels.clock.pause();
    // The scrub track as egui laid it out on the new context: the widest drag-sensing widget
    // of the track's height (points; the window's density is 1).
    let track = common::scrub_track(&after)
        .expect("the timeline's scrub track is laid out on the new context");
    let at = egui::pos2(track.left() + 0.63 * track.width(), track.center().y);
    let button = |pressed| egui::Event::PointerButton {
        pos: at,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    let input = |events| egui::RawInput {
        events,
        ..Default::default()
    };
    app.on(AppEvent::PanelInput(input(vec![
        egui::Event::PointerMoved(at),
    ])));
    app.frame(0.0);
    app.on(AppEvent::PanelInput(input(vec![
        button(true),
        button(false),
    ])));
    app.frame(0.0);
    // The time under the pointer: its place along the track.
    let s = f64::from((at.x - track.left()) / track.width());
    let (a, b) = app.panels.clock.span();
    let want = a + s * (b - a);
    let got = app.race_time();
    assert!(
        (got - want).abs() < 0.05,
        "race time {got}, pointer at {want}"
    );
}
