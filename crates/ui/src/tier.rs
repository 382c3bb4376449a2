//! The quality tier in the Effects part of the Scene panel: which tier the governor draws now,
//! a row of buttons to pin one ("auto" lets the governor choose) and the frame-rate target the
//! governor holds (30, 60 or auto; docs/quality.md).

use egui::Ui;
use quality::{Target, Tier};

/// What the panel shows and edits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TierPanel {
    /// The tier drawn now (the governor's or the pinned one).
    pub current: Tier,
    /// The user's pin; `None`: auto.
    pub pinned: Option<Tier>,
    /// The frame rate the governor holds.
    pub target: Target,
}

impl TierPanel {
    /// Auto at `current`, the auto target.
    pub fn auto(current: Tier) -> TierPanel {
        TierPanel {
            current,
            pinned: None,
            target: Target::Auto,
        }
    }
}

/// What the user changed in the tier control, for the app's governor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TierChange {
    /// Pin this tier (`None`: let the governor choose again).
    Pin(Option<Tier>),
    /// Hold this frame rate.
    Target(Target),
}

/// The frame-rate targets as the panel offers them.
const TARGETS: [(Target, &str); 3] = [
    (Target::Auto, "auto fps"),
    (Target::Fps30, "30 fps"),
    (Target::Fps60, "60 fps"),
];

/// The tier line, the pin buttons and the target buttons; returns what the user changed.
pub fn tier_ui(ui: &mut Ui, panel: &mut TierPanel) -> Option<TierChange> {
    let how = if panel.pinned.is_some() {
        "pinned"
    } else {
        "auto"
    };
    ui.label(format!("Quality tier: {} ({how})", panel.current));
    let mut change = None;
    ui.horizontal_wrapped(|ui| {
        if ui
            .selectable_value(&mut panel.pinned, None, "auto")
            .changed()
        {
            change = Some(TierChange::Pin(None));
        }
        for t in Tier::ALL {
            if ui
                .selectable_value(&mut panel.pinned, Some(t), t.name())
                .changed()
            {
                change = Some(TierChange::Pin(Some(t)));
            }
        }
    });
    ui.horizontal_wrapped(|ui| {
        ui.label("Frame rate:");
        for (target, label) in TARGETS {
            if ui
                .selectable_value(&mut panel.target, target, label)
                .on_hover_text(match target {
                    Target::Auto => "60 where the medium tier or better holds it, else 30",
                    _ => "the governor holds this frame rate",
                })
                .changed()
            {
                change = Some(TierChange::Target(target));
            }
        }
    });
    // A pin shows at once, before the app answers with the tier it draws.
    if let Some(TierChange::Pin(Some(t))) = change {
        panel.current = t;
    }
    change
}
