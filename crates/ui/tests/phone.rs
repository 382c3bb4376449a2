//! The panels on phones held upright, at their size in dp and their density, with their
//! system bars as safe-area insets: the OPPO A54 (720×1600 px at 320 dpi: 360×800 dp, 2 px per
//! dp) and the Pixel 2 XL (1440×2880 px at 560 dpi: 411×823 dp, 3.5 px per dp). Each panel is
//! opened in turn by its switch (on a narrow screen one at a time) and every control on the
//! screen must lie inside the screen minus the insets: reachable by a finger and not cut off.
//! The event list is the one scrolled list: its rows may run above or below its window (they
//! are reached by scrolling), but never off the sides, and a screenful of them is visible.
//! The selected boat's manoeuvre list in the Boats panel is scrolled likewise.
//! Snapshots of the A54 with the Boats panel's views are kept for looking at.

use egui::accesskit::Role;
use egui::{Rect, Vec2};
use egui_kittest::kittest::{By, NodeT, Queryable};
use egui_kittest::{Harness, HarnessBuilder};
use ui::{EffectToggle, RaceClock, RaceEntry, RacesPanel, RegattaUi, UiFrame, timeline_events};

mod common;

/// A phone: size in dp, pixels per dp, and the status bar (top) and the three-button
/// navigation bar (bottom), dp.
struct Phone {
    name: &'static str,
    size: Vec2,
    pixels_per_point: f32,
    top: f32,
    bottom: f32,
}

const PHONES: [Phone; 2] = [
    Phone {
        name: "OPPO A54",
        size: Vec2::new(360.0, 800.0),
        pixels_per_point: 2.0,
        top: 24.0,
        bottom: 48.0,
    },
    Phone {
        name: "Pixel 2 XL",
        size: Vec2::new(411.0, 823.0),
        pixels_per_point: 3.5,
        top: 24.0,
        bottom: 48.0,
    },
];

const SWITCHES: [&str; 6] = ["Leaderboard", "Boats", "Events", "Scene", "Races", "Perf"];

struct App {
    ui: RegattaUi,
    selection: Vec<usize>,
}

fn phone_harness<'a>(
    builder: HarnessBuilder<App>,
    race: &'a race::Race,
    ev: &'a [ui::TimelineEvent],
    entries: &'a [RaceEntry],
    perf: &'a ui::PerfStats,
) -> Harness<'a, App> {
    let effects = vec![
        EffectToggle::new("background", "Camera image", true),
        EffectToggle::new("reflection", "Reflections", true),
        EffectToggle::new("refraction", "Refraction of the table", true),
        EffectToggle::new("caustics", "Caustics", true),
        EffectToggle::new("flowmap", "Current around marks", true),
        EffectToggle::new("wakes", "Wakes", true),
    ];
    let mut panels = RegattaUi::new(RaceClock::new(race.time_span()), effects);
    // The race overlays' switches, as the app hands them in (ui keeps no list).
    panels.settings.overlays = common::race_overlays();
    panels.clock.scrub_to(600.0);
    builder.build_ui_state(
        move |ui, app: &mut App| {
            let rows = ui::leaderboard_rows(race, app.ui.clock.time());
            app.ui.show(
                ui,
                &UiFrame {
                    rows: &rows,
                    events: ev,
                    perf: Some(perf),
                    title: &race.name,
                    race: Some(race),
                    selection: &app.selection,
                    races: Some(RacesPanel {
                        current: &race.name,
                        error: Some("bad.gpx, line 12: latitude 95 is not a number in [-90, 90]"),
                        entries,
                        folder: Some("/sdcard/Android/data/org.regatta.app/files/races"),
                        dialog: false,
                    }),
                },
            );
        },
        App {
            ui: panels,
            // Two boats, so the comparison is drawn too.
            selection: vec![4, 6],
        },
    )
}

fn builder(p: &Phone) -> HarnessBuilder<App> {
    Harness::builder()
        .with_size(p.size)
        .with_pixels_per_point(p.pixels_per_point)
}

fn set_insets(h: &mut Harness<'_, App>, p: &Phone) {
    h.input_mut().safe_area_insets = Some(egui::SafeAreaInsets(egui::epaint::MarginF32 {
        left: 0.0,
        right: 0.0,
        top: p.top,
        bottom: p.bottom,
    }));
}

/// Every control (button, checkbox, slider, combo box, toggle) on screen, by label and rect.
fn controls(h: &Harness<'_, App>) -> Vec<(String, Rect)> {
    h.query_all(By::new().predicate(|n| {
        matches!(
            n.role(),
            Role::Button
                | Role::CheckBox
                | Role::Slider
                | Role::ComboBox
                | Role::RadioButton
                | Role::SpinButton
        )
    }))
    .map(|n| {
        let label = n.accesskit_node().label().unwrap_or_default();
        (label, n.rect())
    })
    .collect()
}

fn sample_entries() -> Vec<RaceEntry> {
    vec![
        RaceEntry {
            name: "fleet.json".into(),
            files: vec!["fleet.json".into()],
        },
        RaceEntry {
            name: "valencia-p02".into(),
            files: vec!["a.gpx".into(), "b.gpx".into()],
        },
    ]
}

/// Each panel, opened alone on each phone: its controls and the timeline's lie inside the safe
/// area, at least some of the panel's own controls are there, and no two controls overlap.
#[test]
fn every_control_is_inside_the_safe_area_on_phones() {
    let race = race::Race::sample();
    // The Valencia race's events: its sail numbers make the longest rows
    // ("ESP30782 takes the lead from ESP29375").
    let ev = timeline_events(&race::Race::valencia());
    let entries = sample_entries();
    let perf = ui::PerfStats {
        fps: 30.0,
        frame_ms: 33.3,
        triangles: 250_000,
        adapter: "PowerVR Rogue GE8320 (Vulkan)".into(),
        passes: Vec::new(),
    };
    for p in &PHONES {
        let mut h = phone_harness(builder(p), &race, &ev, &entries, &perf);
        set_insets(&mut h, p);
        h.run();
        // The desktop's start (leaderboard and Perf both open) becomes one panel on a phone.
        let open = (h.state().ui.show_leaderboard, h.state().ui.show_perf);
        assert_eq!(open, (true, false), "{}", p.name);
        let safe = Rect::from_min_max(
            egui::pos2(0.0, p.top),
            egui::pos2(p.size.x, p.size.y - p.bottom),
        );
        for switch in SWITCHES {
            h.get_by_label(switch).click();
            h.run();
            let (rows, all): (Vec<_>, Vec<_>) = controls(&h)
                .into_iter()
                .partition(|(label, _)| ev.iter().any(|e| label.ends_with(&e.label)));
            assert!(all.len() > 12, "{} {switch}: {all:?}", p.name);
            for (label, r) in &rows {
                assert!(
                    r.left() >= safe.left() && r.right() <= safe.right(),
                    "{} event row \"{label}\" at {r:?} runs off the side",
                    p.name
                );
            }
            if switch == "Events" {
                let visible = rows.iter().filter(|(_, r)| safe.contains_rect(*r)).count();
                assert!(visible >= 5, "{}: {visible} event rows visible", p.name);
            }
            for (label, r) in &all {
                assert!(
                    safe.contains_rect(*r),
                    "{} with {switch} open: \"{label}\" at {r:?} is outside the safe area {safe:?}",
                    p.name
                );
            }
            for (i, (a, ra)) in all.iter().enumerate() {
                for (b, rb) in &all[i + 1..] {
                    let overlap = ra.intersect(*rb);
                    assert!(
                        overlap.width() <= 1.0 || overlap.height() <= 1.0,
                        "{} with {switch} open: \"{a}\" {ra:?} overlaps \"{b}\" {rb:?}",
                        p.name
                    );
                }
            }
        }
        // The Boats panel's debrief views, each in turn: their controls inside the safe area
        // too (the fleet's manoeuvre table and the selected boat's list are buttons).
        if !h.state().ui.show_boats {
            h.get_by_label("Boats").click();
            h.run();
        }
        for tab in ["Manoeuvres", "Start", "Legs", "Speed"] {
            h.get_by_label(tab).click();
            h.run();
            assert_eq!(h.state().ui.boats_view.label(), tab);
            // The selected boat's manoeuvres (rows labelled by their race time, "12:04") are
            // a list the panel scrolls to, as the events are: below the screen is allowed,
            // off the sides is not, and a screenful shows.
            let (rows, all): (Vec<_>, Vec<_>) = controls(&h).into_iter().partition(|(l, _)| {
                l.contains(':') && l.chars().all(|c| c.is_ascii_digit() || c == ':')
            });
            assert!(all.len() > 12, "{} {tab}: {all:?}", p.name);
            for (label, r) in &rows {
                assert!(
                    r.left() >= safe.left() && r.right() <= safe.right(),
                    "{} manoeuvre row \"{label}\" at {r:?} runs off the side",
                    p.name
                );
            }
            if tab == "Manoeuvres" {
                let visible = rows.iter().filter(|(_, r)| safe.contains_rect(*r)).count();
                assert!(visible >= 3, "{}: {visible} manoeuvre rows visible", p.name);
            }
            for (label, r) in &all {
                assert!(
                    safe.contains_rect(*r),
                    "{} with the Boats panel's {tab}: \"{label}\" at {r:?} is outside the safe area {safe:?}",
                    p.name
                );
            }
        }
        // Back to one other panel, so the Boats heading no longer shares its switch's label.
        h.get_by_label("Perf").click();
        h.run();
        // The panels' own controls are among them.
        for (switch, control) in [
            ("Boats", "Follow the selected boat"),
            ("Scene", "Trails"),
            ("Races", "valencia-p02  (2 files)"),
        ] {
            h.get_by_label(switch).click();
            h.run();
            let r = h.get_by_label(control).rect();
            assert!(safe.contains_rect(r), "{} {control}: {r:?}", p.name);
        }
    }
}

/// The A54 with the Boats panel open (speed and comparison plots), for looking at.
#[test]
fn snapshot_a54_boats() {
    let race = race::Race::sample();
    let ev = timeline_events(&race);
    let entries = sample_entries();
    let perf = ui::PerfStats::default();
    let p = &PHONES[0];
    let Some(b) = common::gpu_builder(p.size) else {
        return;
    };
    let b = b.with_pixels_per_point(p.pixels_per_point);
    let mut h = phone_harness(b, &race, &ev, &entries, &perf);
    set_insets(&mut h, p);
    h.run();
    h.get_by_label("Boats").click();
    h.run();
    h.snapshot("phone_a54_boats");
}

/// The A54 with one of the Boats panel's debrief views (the sample with a start line), for
/// looking at: nothing may run off the 360 dp (720 px) width.
fn snapshot_a54_view(tab: &str) {
    let race = common::sample_with_a_start_line();
    let ev = timeline_events(&race);
    let entries = sample_entries();
    let perf = ui::PerfStats::default();
    let p = &PHONES[0];
    let Some(b) = common::gpu_builder(p.size) else {
        return;
    };
    let b = b.with_pixels_per_point(p.pixels_per_point);
    let mut h = phone_harness(b, &race, &ev, &entries, &perf);
    set_insets(&mut h, p);
    h.run();
    h.get_by_label("Boats").click();
    h.run();
    h.get_by_label(tab).click();
    h.run();
    h.snapshot(format!("phone_a54_{}", tab.to_lowercase()));
}

#[test]
fn snapshot_a54_manoeuvres() {
    snapshot_a54_view("Manoeuvres");
}

#[test]
fn snapshot_a54_start() {
    snapshot_a54_view("Start");
}

#[test]
fn snapshot_a54_legs() {
    snapshot_a54_view("Legs");
}
