//! [`RegattaUi`]: every panel and where it goes. The timeline runs along the bottom with a row
//! of panel switches; the leaderboard sits top right, the performance overlay top left, and the
//! open panels (Boats, Events, Scene, Races) in a column on the left. On a narrow screen (a
//! phone held upright) the column takes the whole width and only one panel is open at a time,
//! so every control stays on the screen.

use egui::{Align2, Color32, Frame, RichText, Ui};

use crate::debrief::{
    BoatsView, DebriefView, boats_view_tabs, legs::legs_ui, manoeuvre_table::manoeuvre_table_ui,
    start::start_ui,
};
use crate::events::event_list_ui;
use crate::leaderboard::{LeaderboardRow, leaderboard_ui, parse_hex_color};
use crate::manoeuvres::manoeuvre_jump_ui;
use crate::open::{OpenRequest, RacesPanel, races_ui};
use crate::perf::{PerfStats, perf_ui};
use crate::plots::{PlotCache, compare_ui, speed_plot_ui};
use crate::settings::{SceneSettings, SettingChange, scene_settings_ui};
use crate::timeline::{NARROW_WIDTH, timeline_ui};
use crate::{EffectToggle, RaceClock, TimelineEvent};

/// Width of the left column on a wide screen, points.
pub const COLUMN_WIDTH: f32 = 340.0;

/// How many boats can be selected at once (two: compare).
pub const MAX_SELECTED: usize = 2;

/// Selects `boat`, or unselects it when selected; a third selection drops the oldest.
pub fn toggle_selection(selection: &mut Vec<usize>, boat: usize) {
    if let Some(i) = selection.iter().position(|&b| b == boat) {
        selection.remove(i);
    } else {
        selection.push(boat);
        if selection.len() > MAX_SELECTED {
            selection.remove(0);
        }
    }
}

/// What changed this frame because of the user.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UiResponse {
    /// Race time or play state moved (play, scrub, step, jump, speed, an event or plot click).
    pub clock_changed: bool,
    /// Some effect, overlay or water setting changed (the list: `settings`).
    pub effects_changed: bool,
    /// The tier control's change (also in `settings`): the app pins the tier or sets the
    /// governor's target.
    pub tier: Option<crate::tier::TierChange>,
    /// What the Scene panel changed, by name, for the app to map onto its renderer.
    pub settings: Vec<SettingChange>,
    /// A boat whose name was clicked: the app toggles it in its selection
    /// ([`toggle_selection`]).
    pub clicked_boat: Option<usize>,
    /// "Clear" in the Boats panel.
    pub clear_selection: bool,
    /// The Races panel asked to open a race, show the file dialog or rescan.
    pub open: Option<OpenRequest>,
    /// The part of the screen the panels left to the scene (egui points): a touch there is
    /// the scene's (the phone's tap to place).
    pub scene_rect: Option<egui::Rect>,
}

/// Per-frame inputs of [`RegattaUi::show`].
#[derive(Clone, Copy, Debug, Default)]
pub struct UiFrame<'a> {
    pub rows: &'a [LeaderboardRow],
    pub events: &'a [TimelineEvent],
    pub perf: Option<&'a PerfStats>,
    /// Title line: race name and, when one plays, the camera feed.
    pub title: &'a str,
    /// The race (for the Boats panel's plots); `None` hides them.
    pub race: Option<&'a race::Race>,
    /// The selected boats (indices into `race.boats`, at most two), owned by the app.
    pub selection: &'a [usize],
    /// The Races panel's contents; `None`: no Races panel.
    pub races: Option<RacesPanel<'a>>,
}

/// The panels of the left column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Boats,
    Events,
    Scene,
    Races,
}

/// All panels and their state.
#[derive(Clone, Debug)]
pub struct RegattaUi {
    pub clock: RaceClock,
    pub settings: SceneSettings,
    pub show_leaderboard: bool,
    pub show_perf: bool,
    pub show_boats: bool,
    pub show_events: bool,
    /// The Scene panel (effects, overlays, water).
    pub show_scene: bool,
    pub show_races: bool,
    /// The orbit camera follows the first selected boat.
    pub follow: bool,
    pub plots: PlotCache,
    /// The race's debrief (once per race): the timeline's tack jumps and the Boats panel's
    /// Manoeuvres, Start and Legs views.
    pub debrief: DebriefView,
    /// Which view the Boats panel shows under its boat chips.
    pub boats_view: BoatsView,
    /// Points at the top of the screen kept free for the platform's own bar (the phone's
    /// Race | Pool | Record bar).
    pub top_inset: f32,
}

impl RegattaUi {
    pub fn new(clock: RaceClock, effects: Vec<EffectToggle>) -> Self {
        Self {
            clock,
            settings: SceneSettings::new(effects),
            show_leaderboard: true,
            show_perf: true,
            show_boats: false,
            show_events: false,
            show_scene: false,
            show_races: false,
            follow: false,
            plots: PlotCache::default(),
            debrief: DebriefView::default(),
            boats_view: BoatsView::default(),
            top_inset: 0.0,
        }
    }

    fn side_open(&self, s: Side) -> bool {
        match s {
            Side::Boats => self.show_boats,
            Side::Events => self.show_events,
            Side::Scene => self.show_scene,
            Side::Races => self.show_races,
        }
    }

    /// The switches row (in reverse order for a right-to-left layout); on a narrow screen
    /// turning one panel on turns the others off.
    fn switches(&mut self, ui: &mut Ui, narrow: bool, has_races: bool, reversed: bool) {
        const LABELS: [&str; 6] = ["Leaderboard", "Boats", "Events", "Scene", "Races", "Perf"];
        let before = self.panel_flags();
        let mut flags = before;
        let mut order: Vec<usize> = (0..LABELS.len())
            .filter(|&i| has_races || LABELS[i] != "Races")
            .collect();
        if reversed {
            order.reverse();
        }
        for i in order {
            ui.toggle_value(&mut flags[i], LABELS[i]);
        }
        if narrow && let Some(i) = (0..flags.len()).find(|&i| flags[i] && !before[i]) {
            flags = [false; 6];
            flags[i] = true;
        }
        self.set_panel_flags(flags);
    }

    /// On a narrow screen at most one panel is open (the window may have been narrowed, or
    /// started with several open): a column panel first, then the leaderboard, then Perf.
    fn one_panel_only(&mut self) {
        let flags = self.panel_flags();
        if flags.iter().filter(|&&f| f).count() > 1
            && let Some(i) = [1, 2, 3, 4, 0, 5].into_iter().find(|&i| flags[i])
        {
            let mut only = [false; 6];
            only[i] = true;
            self.set_panel_flags(only);
        }
    }

    fn panel_flags(&self) -> [bool; 6] {
        [
            self.show_leaderboard,
            self.show_boats,
            self.show_events,
            self.show_scene,
            self.show_races,
            self.show_perf,
        ]
    }

    fn set_panel_flags(&mut self, f: [bool; 6]) {
        [
            self.show_leaderboard,
            self.show_boats,
            self.show_events,
            self.show_scene,
            self.show_races,
            self.show_perf,
        ] = f;
    }

    /// Lays out the panels over the scene (see the module docs), inside the screen's safe area
    /// (`Context::content_rect`: the screen minus the phone's status and navigation bars).
    /// Translucent frames keep the scene visible behind them.
    /// The first selected boat's previous/next tack or gybe buttons (and, with `count`, how
    /// many it made); nothing without a race and a selection. True when race time moved.
    fn tack_jumps(&mut self, ui: &mut Ui, frame: &UiFrame<'_>, count: bool) -> bool {
        let (Some(race), Some(&boat)) = (frame.race, frame.selection.first()) else {
            return false;
        };
        let Some(b) = race.boats.get(boat) else {
            return false;
        };
        self.debrief.update(race);
        let starts = self.debrief.starts_of(boat);
        let moved = manoeuvre_jump_ui(ui, &mut self.clock, &b.name, starts);
        if count {
            ui.label(format!("{}: {} tacks and gybes", b.name, starts.len()));
        }
        moved
    }

    pub fn show(&mut self, ui: &mut Ui, frame: &UiFrame<'_>) -> UiResponse {
        let safe = ui.ctx().content_rect();
        ui.scope_builder(egui::UiBuilder::new().max_rect(safe), |ui| {
            self.show_inside(ui, frame)
        })
        .inner
    }

    fn show_inside(&mut self, ui: &mut Ui, frame: &UiFrame<'_>) -> UiResponse {
        let mut out = UiResponse::default();
        let ctx = ui.ctx().clone();
        let screen = ctx.content_rect();
        let narrow = screen.width() < NARROW_WIDTH;
        if narrow {
            self.one_panel_only();
        }
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
                let has_races = frame.races.is_some();
                if narrow {
                    ui.label(RichText::new(frame.title).strong());
                    ui.horizontal_wrapped(|ui| self.switches(ui, true, has_races, false));
                } else {
                    ui.horizontal(|ui| {
                        ui.label(RichText::new(frame.title).strong());
                        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                            self.switches(ui, false, has_races, true)
                        });
                    });
                }
                out.clock_changed |= timeline_ui(ui, &mut self.clock, frame.events);
                ui.horizontal(|ui| out.clock_changed |= self.tack_jumps(ui, frame, true));
            });
        let sides: Vec<Side> = [Side::Boats, Side::Events, Side::Scene, Side::Races]
            .into_iter()
            .filter(|&s| self.side_open(s) && (s != Side::Races || frame.races.is_some()))
            .collect();
        let mut column = 0.0;
        if !sides.is_empty() {
            let width = if narrow { screen.width() } else { COLUMN_WIDTH };
            column = width;
            egui::Panel::left("side-panels")
                .exact_size(width)
                .resizable(false)
                .frame(
                    Frame::side_top_panel(&ctx.global_style())
                        .fill(Color32::from_black_alpha(170))
                        .inner_margin(8.0),
                )
                .show(ui, |ui| {
                    ui.add_space(self.top_inset);
                    egui::ScrollArea::vertical()
                        .auto_shrink([false, false])
                        .show(ui, |ui| {
                            for (i, s) in sides.iter().enumerate() {
                                if i > 0 {
                                    ui.separator();
                                }
                                self.side_ui(ui, *s, frame, &mut out);
                            }
                        });
                });
        }
        if self.show_leaderboard && !frame.rows.is_empty() {
            egui::Area::new(egui::Id::unique("leaderboard-area"))
                .anchor(Align2::RIGHT_TOP, [-10.0, 10.0 + self.top_inset])
                .show(&ctx, |ui| {
                    glass.show(ui, |ui| {
                        if let Some(b) = leaderboard_ui(ui, frame.rows, frame.selection) {
                            out.clicked_boat = Some(b);
                        }
                    });
                });
        }
        if self.show_perf
            && let Some(p) = frame.perf
        {
            egui::Area::new(egui::Id::unique("perf-area"))
                .anchor(Align2::LEFT_TOP, [column + 10.0, 10.0 + self.top_inset])
                .show(&ctx, |ui| {
                    glass.show(ui, |ui| perf_ui(ui, p));
                });
        }
        out.tier = out.settings.iter().find_map(|c| match c {
            SettingChange::Tier(t) => Some(*t),
            _ => None,
        });
        out.effects_changed = out
            .settings
            .iter()
            .any(|c| !matches!(c, SettingChange::Tier(_)));
        out.scene_rect = Some(ui.available_rect_before_wrap());
        out
    }

    fn side_ui(&mut self, ui: &mut Ui, side: Side, frame: &UiFrame<'_>, out: &mut UiResponse) {
        let heading = |ui: &mut Ui, s: &str| ui.label(RichText::new(s).strong().size(16.0));
        match side {
            Side::Boats => {
                heading(ui, "Boats");
                self.boats_ui(ui, frame, out);
            }
            Side::Events => {
                heading(ui, "Events");
                out.clock_changed |= event_list_ui(ui, frame.events, &mut self.clock);
            }
            Side::Scene => {
                heading(ui, "Scene");
                out.settings = scene_settings_ui(ui, &mut self.settings);
            }
            Side::Races => {
                heading(ui, "Races");
                if let Some(r) = &frame.races {
                    out.open = races_ui(ui, r);
                }
            }
        }
    }

    /// Selection (every boat as a chip), follow, and one view: the speed plot and the
    /// comparison, the manoeuvres, the start or the legs.
    fn boats_ui(&mut self, ui: &mut Ui, frame: &UiFrame<'_>, out: &mut UiResponse) {
        let Some(race) = frame.race else {
            ui.label(RichText::new("No race").weak());
            return;
        };
        ui.horizontal_wrapped(|ui| {
            for (i, b) in race.boats.iter().enumerate() {
                // The boat's colour, white on the highlight when selected (colour on blue is
                // hard to read).
                let selected = frame.selection.contains(&i);
                let colour = parse_hex_color(&b.color).unwrap_or(Color32::GRAY);
                let text = RichText::new(&b.id)
                    .color(if selected { Color32::WHITE } else { colour })
                    .strong();
                if ui.selectable_label(selected, text).clicked() {
                    out.clicked_boat = Some(i);
                }
            }
            if !frame.selection.is_empty() && ui.small_button("Clear").clicked() {
                out.clear_selection = true;
            }
        });
        ui.add_enabled(
            !frame.selection.is_empty(),
            egui::Checkbox::new(&mut self.follow, "Follow the selected boat"),
        )
        .on_hover_text("The camera orbits the first selected boat (F)")
        .on_disabled_hover_text("Select a boat to follow it");
        boats_view_tabs(ui, &mut self.boats_view);
        let mut scrub = None;
        match self.boats_view {
            BoatsView::Speed => {
                self.plots.update(race, frame.selection);
                let t = self.clock.time();
                ui.label(RichText::new("Speed").strong());
                scrub = speed_plot_ui(ui, race, &self.plots, t);
                ui.label(RichText::new("Compare").strong());
                scrub = scrub.or(compare_ui(ui, race, &self.plots, frame.selection, t));
            }
            BoatsView::Manoeuvres => {
                self.debrief.update(race);
                if let Some(d) = self.debrief.debrief() {
                    out.clock_changed |= manoeuvre_table_ui(
                        ui,
                        race,
                        d,
                        frame.selection.first().copied(),
                        &mut self.clock,
                    );
                }
            }
            BoatsView::Start => {
                self.debrief.update(race);
                if let Some(d) = self.debrief.debrief() {
                    start_ui(ui, race, d);
                }
            }
            BoatsView::Legs => {
                self.debrief.update(race);
                if let Some(d) = self.debrief.debrief() {
                    legs_ui(ui, race, &d.legs);
                }
            }
        }
        if let Some(t) = scrub {
            self.clock.pause();
            self.clock.scrub_to(t);
            out.clock_changed = true;
        }
    }
}
