//! The tier control of the Effects part of the Scene panel driven through egui_kittest (no
//! GPU): alone, and in the whole layout the desktop and the phone share.

use egui::Vec2;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use quality::{Target, Tier};
use ui::tier::{TierChange, TierPanel, tier_ui};
use ui::{EffectToggle, RaceClock, RegattaUi, UiFrame};

mod common;

fn harness(panel: TierPanel) -> Harness<'static, (TierPanel, Vec<TierChange>)> {
    Harness::builder().build_ui_state(
        |ui, (p, changes): &mut (TierPanel, Vec<TierChange>)| {
            changes.extend(tier_ui(ui, p));
        },
        (panel, Vec::new()),
    )
}

#[test]
fn the_control_shows_the_tier_and_pins_the_one_clicked() {
    let mut h = harness(TierPanel::auto(Tier::High));
    h.get_by_label("Quality tier: high (auto)");
    h.get_by_label("low").click();
    h.run();
    assert_eq!(h.state().0.pinned, Some(Tier::Low));
    h.get_by_label("Quality tier: low (pinned)");
    h.get_by_label("auto").click();
    h.run();
    assert_eq!(h.state().0.pinned, None);
    h.get_by_label("30 fps").click();
    h.run();
    assert_eq!(h.state().0.target, Target::Fps30);
    assert_eq!(
        h.state().1,
        vec![
            TierChange::Pin(Some(Tier::Low)),
            TierChange::Pin(None),
            TierChange::Target(Target::Fps30),
        ]
    );
}

#[test]
fn a_pinned_tier_says_so() {
    let h = harness(TierPanel {
        pinned: Some(Tier::Medium),
        ..TierPanel::auto(Tier::Medium)
    });
    h.get_by_label("Quality tier: medium (pinned)");
}

/// The layout under test: the panels and the last tier change they reported.
struct App {
    ui: RegattaUi,
    changes: Vec<TierChange>,
}

/// The whole layout with the Scene panel open at `size`, the tier control at `current`
/// (as the app sets it each frame from its governor).
fn layout(race: &race::Race, size: Vec2, current: Tier) -> Harness<'_, App> {
    let mut panels = RegattaUi::new(
        RaceClock::new(race.time_span()),
        vec![EffectToggle::new("wakes", "Wakes", true)],
    );
    panels.settings.overlays = common::race_overlays();
    panels.show_scene = true;
    panels.settings.tier = Some(TierPanel::auto(current));
    Harness::builder().with_size(size).build_ui_state(
        move |ui, app: &mut App| {
            let r = app.ui.show(
                ui,
                &UiFrame {
                    title: &race.name,
                    race: Some(race),
                    ..Default::default()
                },
            );
            // The response carries the change by itself, not as an effect change.
            if let Some(c) = r.tier {
                assert!(!r.effects_changed);
                app.changes.push(c);
            }
        },
        App {
            ui: panels,
            changes: Vec::new(),
        },
    )
}

/// In the Scene panel of the desktop's window and of the phone held upright (360 points
/// wide: the column takes the screen), a click on a tier pins it: the response says so and
/// the panel shows the tier.
#[test]
fn clicking_a_tier_in_the_scene_panel_pins_it() {
    let race = race::Race::sample();
    for size in [Vec2::new(1280.0, 800.0), Vec2::new(360.0, 800.0)] {
        let mut h = layout(&race, size, Tier::Ultra);
        h.run();
        h.get_by_label("Quality tier: ultra (auto)");
        h.get_by_label("medium").click();
        h.run();
        assert_eq!(h.state().changes, [TierChange::Pin(Some(Tier::Medium))]);
        h.get_by_label("Quality tier: medium (pinned)");
        let panel = h.state().ui.settings.tier.unwrap();
        assert_eq!(
            (panel.current, panel.pinned),
            (Tier::Medium, Some(Tier::Medium))
        );
        h.get_by_label("60 fps").click();
        h.run();
        assert_eq!(
            h.state().changes[1..],
            [TierChange::Target(Target::Fps60)],
            "{size:?}"
        );
    }
}
