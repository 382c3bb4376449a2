//! The new panels driven through egui_kittest (no GPU) and their snapshots (lavapipe):
//! reverse play, the event list, the Scene panel's named changes, the Boats panel (selection,
//! follow, plots) and the Races panel.

use egui::Vec2;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use ui::{
    EffectToggle, OpenRequest, RaceClock, RaceEntry, RacesPanel, RegattaUi, SceneSettings,
    SettingChange, TimelineEvent, UiFrame, event_list_ui, races_ui, scene_settings_ui,
    timeline_events, timeline_ui,
};

mod common;
use common::snapshot;

fn effects() -> Vec<EffectToggle> {
    vec![
        EffectToggle::new("reflection", "Reflections", true),
        EffectToggle::new("caustics", "Caustics", true),
        EffectToggle::new("wakes", "Wakes", true),
    ]
}

/// "◀▶" turns 8× into −8×; playing then runs race time backwards.
#[test]
fn the_reverse_button_plays_backwards() {
    let ev: Vec<TimelineEvent> = Vec::new();
    let mut clock = RaceClock::new((0.0, 1000.0));
    clock.scrub_to(500.0);
    clock.set_speed(8.0);
    let mut h = Harness::builder()
        .with_size(Vec2::new(900.0, 90.0))
        .build_ui_state(
            |ui, c: &mut RaceClock| {
                timeline_ui(ui, c, &ev);
            },
            clock,
        );
    h.get_by_label("◀▶").click();
    h.run();
    assert_eq!(h.state().speed(), -8.0);
    h.get_by_label("◀ Play back").click();
    h.run();
    assert!(h.state().is_playing());
    h.state_mut().advance(2.0);
    assert_eq!(h.state().time(), 484.0);
}

/// A click on an event's row jumps race time to it and pauses.
#[test]
fn the_event_list_jumps_to_the_event() {
    let race = race::Race::sample();
    let ev = timeline_events(&race);
    let first_w = ev.iter().find(|e| e.label == "EOS rounds W").unwrap().t;
    let mut clock = RaceClock::new(race.time_span());
    clock.play();
    let mut h = Harness::builder()
        .with_size(Vec2::new(360.0, 600.0))
        .build_ui_state(
            |ui, c: &mut RaceClock| {
                event_list_ui(ui, &ev, c);
            },
            clock,
        );
    // EOS rounds W twice (both beats): the first row is the first rounding.
    let row = |h: &Harness<'_, RaceClock>, text: &str| {
        h.get_all_by_label_contains(text).next().unwrap().rect()
    };
    h.get_all_by_label_contains("EOS rounds W")
        .next()
        .unwrap()
        .click();
    h.run();
    assert_eq!(h.state().time(), first_w);
    assert!(!h.state().is_playing());
    // The start is the first row, at race time 0.
    assert!(h.get_by_label("Start").rect().top() < row(&h, "EOS rounds W").top());
}

/// The Scene panel reports each change by its command-line name; an unavailable switch is
/// greyed out and a click on it changes nothing.
#[test]
fn the_scene_panel_reports_changes_by_name() {
    let mut s = SceneSettings::new(effects());
    s.overlays = common::race_overlays();
    s.unavailable
        .push(("wind".into(), "no wind in the race".into()));
    let mut h = Harness::builder()
        .with_size(Vec2::new(340.0, 500.0))
        .build_ui_state(
            |ui, st: &mut (SceneSettings, Vec<SettingChange>)| {
                let c = scene_settings_ui(ui, &mut st.0);
                st.1.extend(c);
            },
            (s, Vec::new()),
        );
    h.get_by_label("Caustics").click();
    h.run();
    h.get_by_label("Trails").click();
    h.run();
    h.get_by_label("Wind").click();
    h.run();
    assert_eq!(
        h.state().1,
        vec![
            SettingChange::Effect {
                key: "caustics".into(),
                enabled: false
            },
            SettingChange::Overlay {
                key: "trails".into(),
                enabled: false
            },
        ]
    );
    assert!(h.state().0.overlay("wind"));
    assert!(!h.state().0.effect("caustics"));
}

/// The layout's state under test: the panels, the app's selection, and the last response.
struct App {
    ui: RegattaUi,
    selection: Vec<usize>,
    last: ui::UiResponse,
}

fn app_harness<'a>(race: &'a race::Race, ev: &'a [TimelineEvent], size: Vec2) -> Harness<'a, App> {
    let mut panels = RegattaUi::new(RaceClock::new(race.time_span()), effects());
    panels.settings.overlays = common::race_overlays();
    panels.show_boats = true;
    Harness::builder().with_size(size).build_ui_state(
        move |ui, app: &mut App| {
            let rows = ui::leaderboard_rows(race, app.ui.clock.time());
            let r = app.ui.show(
                ui,
                &UiFrame {
                    rows: &rows,
                    events: ev,
                    title: &race.name,
                    race: Some(race),
                    selection: &app.selection,
                    ..Default::default()
                },
            );
            if let Some(b) = r.clicked_boat {
                ui::toggle_selection(&mut app.selection, b);
            }
            if r.clear_selection {
                app.selection.clear();
            }
            app.last = r;
        },
        App {
            ui: panels,
            selection: Vec::new(),
            last: Default::default(),
        },
    )
}

/// Boat chips select (a third drops the oldest), "Follow" needs a selection, "Clear" empties
/// it.
#[test]
fn the_boats_panel_selects_and_follows() {
    let race = race::Race::sample();
    let ev = timeline_events(&race);
    let mut h = app_harness(&race, &ev, Vec2::new(1280.0, 800.0));
    h.run();
    let follow_disabled = |h: &Harness<'_, App>| {
        h.get_by_label("Follow the selected boat")
            .accesskit_node()
            .is_disabled()
    };
    assert!(follow_disabled(&h));
    // The chips are the Boats panel's; the leaderboard's rows name the boats in full.
    for id in ["EOS", "GAL", "AUR"] {
        h.get_by_label(id).click();
        h.run();
    }
    assert_eq!(h.state().selection, vec![6, 0]);
    assert!(!follow_disabled(&h));
    h.get_by_label("Follow the selected boat").click();
    h.run();
    assert!(h.state().ui.follow);
    // Clicking a name in the leaderboard selects too.
    h.get_by_label("Eos").click();
    h.run();
    assert_eq!(h.state().selection, vec![0, 4]);
    h.get_by_label("Clear").click();
    h.run();
    assert!(h.state().selection.is_empty());
}

/// The Races panel: a folder entry opens its files; the error sentence is shown.
#[test]
fn the_races_panel_opens_an_entry_and_shows_the_error() {
    let entries = vec![RaceEntry {
        name: "valencia-p02".into(),
        files: vec!["a.gpx".into(), "b.gpx".into()],
    }];
    let err = "b.gpx, line 3: the text is not valid UTF-8";
    let mut h = Harness::builder()
        .with_size(Vec2::new(340.0, 300.0))
        .build_ui_state(
            |ui, out: &mut Option<OpenRequest>| {
                let r = races_ui(
                    ui,
                    &RacesPanel {
                        current: "Sample fleet",
                        error: Some(err),
                        entries: &entries,
                        folder: Some("/sdcard/Android/data/org.regatta.app/files/races"),
                        dialog: true,
                    },
                );
                if r.is_some() {
                    *out = r;
                }
            },
            None,
        );
    h.run();
    h.get_by_label(err);
    h.get_by_label("valencia-p02  (2 files)").click();
    h.run();
    assert_eq!(
        *h.state(),
        Some(OpenRequest::Files(vec!["a.gpx".into(), "b.gpx".into()]))
    );
    h.get_by_label("📂 Open race files…").click();
    h.run();
    assert_eq!(*h.state(), Some(OpenRequest::Dialog));
}

#[test]
fn snapshot_scene_panel() {
    let mut s = SceneSettings::new(effects());
    s.overlays = common::race_overlays();
    s.unavailable
        .push(("wind".into(), "no wind in the race".into()));
    s.tier = Some(ui::TierPanel::auto(quality::Tier::High));
    snapshot("scene_panel", Vec2::new(340.0, 420.0), move |ui| {
        scene_settings_ui(ui, &mut s);
    });
}

#[test]
fn snapshot_event_list() {
    let race = race::Race::valencia();
    let ev = timeline_events(&race);
    let mut clock = RaceClock::new(race.time_span());
    clock.scrub_to(600.0);
    snapshot("event_list", Vec2::new(360.0, 300.0), move |ui| {
        event_list_ui(ui, &ev, &mut clock);
    });
}

#[test]
fn snapshot_races_panel() {
    let entries = vec![
        RaceEntry {
            name: "fleet.json".into(),
            files: vec!["fleet.json".into()],
        },
        RaceEntry {
            name: "valencia-p02".into(),
            files: vec!["a.gpx".into(), "b.gpx".into(), "m.json".into()],
        },
    ];
    snapshot("races_panel", Vec2::new(360.0, 260.0), move |ui| {
        races_ui(
            ui,
            &RacesPanel {
                current: "Sample fleet",
                error: Some("bad.gpx, line 12: latitude 95 is not a number in [-90, 90]"),
                entries: &entries,
                folder: Some("/sdcard/Android/data/org.regatta.app/files/races"),
                dialog: true,
            },
        );
    });
}
