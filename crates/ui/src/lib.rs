//! Regatta's egui panels: the race-timeline scrubber ([`RaceClock`] + [`timeline_ui`]), the
//! leaderboard, effect toggles and the performance overlay, and [`RegattaUi`] which lays them
//! out over the scene.
//!
//! Knows nothing of wgpu device setup or Android (ARCHITECTURE.md): the app hands it plain data
//! ([`PerfStats`], [`EffectToggle`]s, the race) and paints its output.

pub mod clock;
pub mod effects;
pub mod leaderboard;
pub mod perf;
pub mod tier;
pub mod timeline;

pub use clock::{RaceClock, SPEEDS, format_race_time};
pub use effects::{EffectToggle, effects_ui};
pub use leaderboard::{LeaderboardRow, leaderboard_rows, leaderboard_ui};
pub use perf::{FpsMeter, PassStat, PerfStats, perf_ui};
pub use tier::{TierPanel, tier_ui};
pub use timeline::{TimelineEvent, timeline_ui};

use egui::{Align2, Color32, Frame, Ui};

/// The timeline's jump targets: every mark rounding after the start, in time order.
pub fn timeline_events(race: &race::Race) -> Vec<TimelineEvent> {
    race.rounding_events()
        .into_iter()
        .filter(|e| e.course_index > 0)
        .map(|e| {
            let boat = &race.boats[e.boat];
            TimelineEvent {
                t: e.t,
                label: format!("{} rounds {}", boat.id, e.mark),
                color: leaderboard::parse_hex_color(&boat.color).unwrap_or(Color32::GRAY),
            }
        })
        .collect()
}

/// What changed this frame because of the user.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UiResponse {
    /// Race time or play state moved (play, scrub, step, jump, speed).
    pub clock_changed: bool,
    pub effects_changed: bool,
}

/// Per-frame inputs of [`RegattaUi::show`].
#[derive(Clone, Copy, Debug, Default)]
pub struct UiFrame<'a> {
    pub rows: &'a [LeaderboardRow],
    pub events: &'a [TimelineEvent],
    pub perf: Option<&'a PerfStats>,
    /// Title line: race name and, when one plays, the camera feed.
    pub title: &'a str,
}

/// All panels and their state.
#[derive(Clone, Debug)]
pub struct RegattaUi {
    pub clock: RaceClock,
    pub effects: Vec<EffectToggle>,
    pub show_leaderboard: bool,
    pub show_effects: bool,
    pub show_perf: bool,
}

impl RegattaUi {
    pub fn new(clock: RaceClock, effects: Vec<EffectToggle>) -> Self {
        Self {
            clock,
            effects,
            show_leaderboard: true,
            show_effects: false,
            show_perf: true,
        }
    }

    /// Lays out the panels over the scene: the timeline along the bottom, the leaderboard top
    /// right, the performance overlay top left, effects under a toggle. Translucent frames keep
    /// the camera image visible behind them.
    pub fn show(&mut self, ui: &mut Ui, frame: &UiFrame<'_>) -> UiResponse {
        let mut out = UiResponse::default();
        let ctx = ui.ctx().clone();
        let glass = Frame::window(&ctx.global_style())
            .fill(Color32::from_black_alpha(170))
            .corner_radius(6.0);
        egui::Panel::bottom("timeline")
            .frame(
                Frame::side_top_panel(&ctx.global_style())
                    .fill(Color32::from_black_alpha(190))
                    .inner_margin(8.0),
            )
            .show(ui, |ui| {
                ui.horizontal(|ui| {
                    ui.label(egui::RichText::new(frame.title).strong());
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        ui.toggle_value(&mut self.show_perf, "Perf");
                        ui.toggle_value(&mut self.show_effects, "Effects");
                        ui.toggle_value(&mut self.show_leaderboard, "Leaderboard");
                    });
                });
                out.clock_changed = timeline_ui(ui, &mut self.clock, frame.events);
            });
        if self.show_leaderboard && !frame.rows.is_empty() {
            egui::Area::new(egui::Id::unique("leaderboard-area"))
                .anchor(Align2::RIGHT_TOP, [-10.0, 10.0])
                .show(&ctx, |ui| {
                    glass.show(ui, |ui| leaderboard_ui(ui, frame.rows));
                });
        }
        if self.show_perf
            && let Some(p) = frame.perf
        {
            egui::Area::new(egui::Id::unique("perf-area"))
                .anchor(Align2::LEFT_TOP, [10.0, 10.0])
                .show(&ctx, |ui| {
                    glass.show(ui, |ui| perf_ui(ui, p));
                });
        }
        if self.show_effects {
            egui::Area::new(egui::Id::unique("effects-area"))
                .anchor(Align2::LEFT_BOTTOM, [10.0, -110.0])
                .show(&ctx, |ui| {
                    glass.show(ui, |ui| {
                        ui.label(egui::RichText::new("Effects").strong());
                        out.effects_changed = effects_ui(ui, &mut self.effects);
                    });
                });
        }
        out
    }
}
