//! The quality tier in the Effects panel: which tier the governor draws now, and a row of
//! buttons to pin one ("auto" lets the governor choose; docs/quality.md).

use egui::Ui;
use quality::Tier;

/// What the panel shows and edits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TierPanel {
    /// The tier drawn now (the governor's or the pinned one).
    pub current: Tier,
    /// The user's pin; `None`: auto.
    pub pinned: Option<Tier>,
}

/// The tier line and the pin buttons; returns true when the user changed the pin.
pub fn tier_ui(ui: &mut Ui, panel: &mut TierPanel) -> bool {
    let how = if panel.pinned.is_some() {
        "pinned"
    } else {
        "auto"
    };
    ui.label(format!("Quality tier: {} ({how})", panel.current));
    let mut changed = false;
    ui.horizontal_wrapped(|ui| {
        changed |= ui
            .selectable_value(&mut panel.pinned, None, "auto")
            .changed();
        for t in Tier::ALL {
            changed |= ui
                .selectable_value(&mut panel.pinned, Some(t), t.name())
                .changed();
        }
    });
    changed
}
