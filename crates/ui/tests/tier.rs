//! The tier control of the Effects panel driven through egui_kittest (no GPU).

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use quality::Tier;
use ui::tier::{TierPanel, tier_ui};

fn harness(panel: TierPanel) -> Harness<'static, (TierPanel, bool)> {
    Harness::builder().build_ui_state(
        |ui, (p, changed): &mut (TierPanel, bool)| {
            *changed |= tier_ui(ui, p);
        },
        (panel, false),
    )
}

#[test]
fn the_panel_shows_the_tier_and_pins_the_one_clicked() {
    let mut h = harness(TierPanel {
        current: Tier::High,
        pinned: None,
    });
    h.get_by_label("Quality tier: high (auto)");
    h.get_by_label("low").click();
    h.run();
    assert_eq!(h.state().0.pinned, Some(Tier::Low));
    assert!(h.state().1, "the change is reported");
    h.get_by_label("auto").click();
    h.run();
    assert_eq!(h.state().0.pinned, None);
}

#[test]
fn a_pinned_tier_says_so() {
    let h = harness(TierPanel {
        current: Tier::Medium,
        pinned: Some(Tier::Medium),
    });
    h.get_by_label("Quality tier: medium (pinned)");
}
