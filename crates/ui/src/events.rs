//! The race's events on the timeline and in a list: the start, every mark rounding and every
//! lead change (`race::events`), coloured by kind, and a list whose rows jump race time there.

use egui::{Color32, RichText, Ui};

use crate::clock::{RaceClock, format_race_time};
use crate::leaderboard::parse_hex_color;

/// A moment on the timeline worth jumping to.
#[derive(Clone, Debug, PartialEq)]
pub struct TimelineEvent {
    /// Race seconds.
    pub t: f64,
    /// For the hover text and the list, e.g. "ESP29375 rounds B1".
    pub label: String,
    /// The boat's colour (a rounding), gold (a lead change), green (the start).
    pub color: Color32,
}

/// The start signal's colour on the track.
pub const START_COLOR: Color32 = Color32::from_rgb(40, 200, 90);
/// A lead change's colour on the track.
pub const LEAD_COLOR: Color32 = Color32::from_rgb(255, 200, 40);

/// The timeline's events of `race` (see `race::events`), in time order.
pub fn timeline_events(race: &race::Race) -> Vec<TimelineEvent> {
    race::race_events(race)
        .into_iter()
        .map(|e| {
            let color = match e.kind {
                race::EventKind::Start => START_COLOR,
                race::EventKind::LeadChange { .. } => LEAD_COLOR,
                race::EventKind::Rounding { boat, .. } => {
                    parse_hex_color(&race.boats[boat].color).unwrap_or(Color32::GRAY)
                }
            };
            TimelineEvent {
                t: e.t,
                label: e.describe(race),
                color,
            }
        })
        .collect()
}

/// The event list: one row per event (race time, a colour chip, what happened), the one last
/// passed highlighted; a click jumps race time there (pausing). Returns true when it did.
pub fn event_list_ui(ui: &mut Ui, events: &[TimelineEvent], clock: &mut RaceClock) -> bool {
    if events.is_empty() {
        ui.label(RichText::new("No events: the race has no course or start").weak());
        return false;
    }
    let now = clock.time();
    let current = events.iter().rposition(|e| e.t <= now + 1e-3);
    let mut jumped = None;
    egui::ScrollArea::vertical()
        .max_height(ui.available_height().max(120.0))
        .auto_shrink([false, true])
        .show(ui, |ui| {
            for (i, e) in events.iter().enumerate() {
                ui.horizontal(|ui| {
                    let (rect, _) =
                        ui.allocate_exact_size(egui::vec2(8.0, 14.0), egui::Sense::hover());
                    ui.painter().rect_filled(rect, 2.0, e.color);
                    // The clock in a fixed-width column, the sentence in the proportional
                    // font: a phone's width holds "ESP30782 takes the lead from ESP29375".
                    let time = format!("{:>7}", format_race_time(e.t));
                    ui.label(RichText::new(time).monospace().weak());
                    if ui
                        .selectable_label(Some(i) == current, e.label.as_str())
                        .clicked()
                    {
                        jumped = Some(e.t);
                    }
                });
            }
        });
    if let Some(t) = jumped {
        clock.pause();
        clock.scrub_to(t);
    }
    jumped.is_some()
}
