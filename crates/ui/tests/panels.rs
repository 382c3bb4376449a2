//! The panels driven through egui_kittest: interactions (no GPU) and snapshot images rendered
//! with wgpu (lavapipe in CI). Snapshots live in `tests/snapshots/`; update them with
//! `UPDATE_SNAPSHOTS=1 cargo test -p ui --test panels` and look at the images.
//!
//! Without a GPU adapter the snapshot tests print "skipped" and pass, except under
//! `REGATTA_REQUIRE_GPU=true`, where they fail (`render::gpu::test_gpu`).

use egui::Vec2;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

mod common;
use common::snapshot;
use ui::{
    EffectToggle, LeaderboardRow, PassStat, PerfStats, RaceClock, RegattaUi, TimelineEvent,
    UiFrame, effects_ui, leaderboard_rows, leaderboard_ui, perf_ui, timeline_events, timeline_ui,
};

/// A timeline harness over `span` (race seconds) whose state is the clock.
fn timeline_harness(ev: &[TimelineEvent], span: (f64, f64)) -> Harness<'_, RaceClock> {
    Harness::builder()
        .with_size(Vec2::new(900.0, 90.0))
        .build_ui_state(
            |ui, clock: &mut RaceClock| {
                timeline_ui(ui, clock, ev);
            },
            RaceClock::new(span),
        )
}

fn events() -> Vec<TimelineEvent> {
    let red = egui::Color32::from_rgb(220, 40, 40);
    let blue = egui::Color32::from_rgb(40, 90, 230);
    vec![
        TimelineEvent {
            t: 300.0,
            label: "NZL rounds W1".into(),
            color: red,
        },
        TimelineEvent {
            t: 312.0,
            label: "GBR rounds W1".into(),
            color: blue,
        },
        TimelineEvent {
            t: 640.0,
            label: "NZL rounds L1".into(),
            color: red,
        },
    ]
}

fn perf_stats() -> PerfStats {
    PerfStats {
        fps: 59.7,
        frame_ms: 16.75,
        triangles: 412_345,
        adapter: "llvmpipe (Vulkan)".into(),
        passes: vec![
            PassStat {
                name: "water".into(),
                ran: true,
                reason: "water in view".into(),
                triangles: 401_000,
                gpu_ms: Some(3.21),
            },
            PassStat {
                name: "boats".into(),
                ran: true,
                reason: "8 boats in view".into(),
                triangles: 11_345,
                gpu_ms: Some(0.42),
            },
            PassStat {
                name: "reflection".into(),
                ran: false,
                reason: "no boat above water in view".into(),
                triangles: 0,
                gpu_ms: None,
            },
            PassStat {
                name: "caustics".into(),
                ran: false,
                reason: "calm sea".into(),
                triangles: 0,
                gpu_ms: None,
            },
        ],
    }
}

fn toggles() -> Vec<EffectToggle> {
    vec![
        EffectToggle::new("reflection", "Reflections", true),
        EffectToggle::new("refraction", "Refraction of the table", true),
        EffectToggle::new("caustics", "Caustics", false),
        EffectToggle::new("wakes", "Wakes", true),
    ]
}

/// On a phone held upright (380 points) the transport row wraps: every control stays on
/// screen and the row takes more than one line; at 900 points it stays one line.
#[test]
fn the_transport_row_wraps_on_a_narrow_screen() {
    let ev = events();
    let controls = [
        "⏮ Start",
        "⏪ Event",
        "◀ Step",
        "▶ Play",
        "Step ▶",
        "Event ⏩",
    ];
    for (width, one_line) in [(380.0, false), (900.0, true)] {
        let mut h = Harness::builder()
            .with_size(Vec2::new(width, 200.0))
            .build_ui_state(
                |ui, clock: &mut RaceClock| {
                    timeline_ui(ui, clock, &ev);
                },
                RaceClock::new((-60.0, 900.0)),
            );
        h.run();
        let rects: Vec<egui::Rect> = controls.iter().map(|c| h.get_by_label(c).rect()).collect();
        for (c, r) in controls.iter().zip(&rects) {
            assert!(
                r.right() <= width,
                "{c} at {r:?} is off a {width}-point screen"
            );
        }
        let same_line = rects
            .iter()
            .all(|r| (r.center().y - rects[0].center().y).abs() < 1.0);
        assert_eq!(same_line, one_line, "{width}: {rects:?}");
    }
}

#[test]
fn play_button_and_mark_jumps_drive_the_clock() {
    let ev = events();
    let mut h = timeline_harness(&ev, (-60.0, 900.0));
    h.get_by_label("▶ Play").click();
    h.run();
    assert!(h.state().is_playing());
    h.get_by_label("⏸ Pause").click();
    h.run();
    assert!(!h.state().is_playing());
    h.get_by_label("Event ⏩").click();
    h.run();
    assert_eq!(h.state().time(), 300.0);
    h.get_by_label("Event ⏩").click();
    h.run();
    assert_eq!(h.state().time(), 312.0);
    h.get_by_label("⏪ Event").click();
    h.run();
    assert_eq!(h.state().time(), 300.0);
    h.get_by_label("Step ▶").click();
    h.run();
    assert_eq!(h.state().time(), 301.0);
    h.get_by_label("⏮ Start").click();
    h.run();
    assert_eq!(h.state().time(), 0.0);
}

#[test]
fn clicking_the_track_scrubs_to_that_fraction_of_the_race() {
    let ev = events();
    let mut h = timeline_harness(&ev, (0.0, 1000.0));
    let track = h.get_by_label("Race time");
    let r = track.rect();
    let x = r.left() + 0.25 * r.width();
    let p = egui::pos2(x, r.center().y);
    h.hover_at(p);
    h.drag_at(p);
    h.run();
    h.drop_at(p);
    h.run();
    let t = h.state().time();
    // The pointer is at a quarter of the track, to within one point of 1000 s over its width.
    assert!(
        (t - 250.0).abs() <= 1000.0 / f64::from(r.width()) + 1e-9,
        "t = {t}"
    );
}

#[test]
fn effect_checkboxes_toggle_their_effect() {
    let mut h = Harness::builder().build_ui_state(
        |ui, t: &mut Vec<EffectToggle>| {
            effects_ui(ui, t);
        },
        toggles(),
    );
    h.get_by_label("Caustics").click();
    h.run();
    assert!(h.state()[2].enabled);
    assert_eq!(
        ui::effects::enabled_list(h.state()),
        "reflection,refraction,caustics,wakes"
    );
}

#[test]
fn snapshot_timeline() {
    let ev = events();
    let mut clock = RaceClock::new((-60.0, 900.0));
    clock.scrub_to(420.0);
    clock.set_speed(16.0);
    snapshot("timeline", Vec2::new(900.0, 80.0), move |ui| {
        timeline_ui(ui, &mut clock, &ev);
    });
}

#[test]
fn snapshot_leaderboard() {
    let race = race::Race::sample();
    let (t0, t1) = race.time_span();
    let rows: Vec<LeaderboardRow> = leaderboard_rows(&race, t0 + 0.5 * (t1 - t0));
    snapshot("leaderboard", Vec2::new(420.0, 280.0), move |ui| {
        leaderboard_ui(ui, &rows, &[1]);
    });
}

#[test]
fn snapshot_perf_overlay() {
    let stats = perf_stats();
    snapshot("perf_overlay", Vec2::new(480.0, 150.0), move |ui| {
        perf_ui(ui, &stats)
    });
}

#[test]
fn snapshot_effects() {
    let mut t = toggles();
    snapshot("effects", Vec2::new(260.0, 110.0), move |ui| {
        effects_ui(ui, &mut t);
    });
}

#[test]
fn snapshot_whole_layout() {
    let race = race::Race::sample();
    let (t0, t1) = race.time_span();
    let t = t0 + 0.5 * (t1 - t0);
    let rows = leaderboard_rows(&race, t);
    let ev = timeline_events(&race);
    let stats = perf_stats();
    let mut clock = RaceClock::new((t0, t1));
    clock.scrub_to(t);
    let mut app = RegattaUi::new(clock, toggles());
    app.settings.overlays = common::race_overlays();
    app.show_scene = true;
    app.show_boats = true;
    let title = format!("{} · synthetic feed", race.name);
    snapshot("layout", Vec2::new(1280.0, 800.0), move |ui| {
        // A table-coloured backdrop stands in for the scene.
        ui.painter()
            .rect_filled(ui.max_rect(), 0.0, egui::Color32::from_rgb(150, 110, 70));
        app.show(
            ui,
            &UiFrame {
                rows: &rows,
                events: &ev,
                perf: Some(&stats),
                title: &title,
                race: Some(&race),
                // Eos and Gale, compared.
                selection: &[4, 6],
                ..Default::default()
            },
        );
    });
}
