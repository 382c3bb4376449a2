//! Regatta's egui panels: the race-timeline scrubber ([`RaceClock`] + [`timeline_ui`], reverse
//! play, the race's events), the leaderboard, the Boats panel (follow, speed/VMG plot, compare
//! two boats, and the race's debrief: manoeuvres, the start, the legs), the Events list, the Scene panel (effects and the quality tier, overlays,
//! water), the Races panel (open a race), the performance overlay, and [`RegattaUi`] which lays
//! them out over the scene, on a desktop window and on a phone held upright alike.
//!
//! Knows nothing of wgpu device setup or Android (ARCHITECTURE.md): the app hands it plain data
//! ([`PerfStats`], [`EffectToggle`]s, the race) and paints its output.

pub mod clock;
pub mod debrief;
pub mod effects;
pub mod events;
pub mod leaderboard;
pub mod manoeuvres;
pub mod open;
pub mod perf;
pub mod plots;
pub mod series;
pub mod settings;
pub mod tier;
pub mod timeline;

pub use clock::{RaceClock, SPEEDS, format_race_time};
pub use debrief::{BoatsView, DebriefView, wind_line, wind_source_text};
pub use effects::{EffectToggle, effects_ui};
pub use events::{TimelineEvent, event_list_ui, timeline_events};
pub use leaderboard::{LeaderboardRow, leaderboard_rows, leaderboard_ui};
pub use manoeuvres::manoeuvre_jump_ui;
pub use open::{OpenRequest, RaceEntry, RacesPanel, list_races, races_ui};
pub use perf::{FpsMeter, PassStat, PerfStats, perf_ui};
pub use plots::{PlotCache, compare_ui, speed_plot_ui};
pub use settings::{SceneSettings, SettingChange, scene_settings_ui};
pub use tier::{TierChange, TierPanel, tier_ui};
pub use timeline::timeline_ui;

mod layout;
pub use layout::{MAX_SELECTED, RegattaUi, UiFrame, UiResponse, toggle_selection};
