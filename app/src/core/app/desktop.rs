//! The desktop profile of the [`App`]: what the `regatta` window shows and takes that the phone
//! does not. The orbit view over the sky, or the race on a camera feed's table ([`FeedView`]:
//! a replay folder or the synthetic table, played by the app's own seconds); the window's mouse,
//! which the window hands in as one finger, so a click selects a boat within the one tap
//! threshold ([`super::TAP_MAX_PX`], [`super::TAP_MAX_S`]) and a longer or farther press drags
//! the orbit, as on the phone; the wheel (zoom); the timeline's keys; race files dropped on the
//! window or chosen in the Races panel's dialog; the performance panel; the "Share clip" GIF
//! into `clips/` (`clip.rs`, [`super::HandOff::File`]). The governor starts at ultra (or the pinned `--tier`).
//!
//! It never knows the window system: the shell (`crate::desktop`) turns winit's events into
//! [`AppEvent`](super::AppEvent)s and presents what [`App::frame`] drew.

use std::path::PathBuf;

use ui::{FpsMeter, PerfStats, RegattaUi};

use super::App;
use crate::core::feed::FeedView;
use crate::hud::SceneChoice;
use crate::pool_play::PoolPlay;
use crate::setup::Profile;
use crate::world::RaceWorld;

/// A key the desktop app acts on (the window's keyboard, translated).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    Space,
    Left,
    Right,
    Home,
    PageUp,
    PageDown,
    Escape,
    /// A key that types a character (R, F, [ and ] are the timeline's).
    Char(char),
}

/// How the desktop app starts (the command line's choices, validated by the shell's caller).
pub struct DesktopStart {
    /// The camera feed behind the race (`--replay`), its table's water already set.
    pub feed: Option<FeedView>,
    /// The water the command line chose: the Scene panel starts there, and its type colours
    /// the open sea.
    pub water: render::water_look::WaterLook,
    /// The tier pinned by `--tier`; the governor chooses from ultra without it.
    pub tier: Option<quality::Tier>,
    /// The race or the pool (`--scene`).
    pub scene: SceneChoice,
    /// The sea the pool's waves take (`--sea` with `--scene pool`).
    pub pool_sea: Option<ocean::WaveSet>,
}

/// The desktop profile's own state.
pub(super) struct Desktop {
    /// `Some` with `--replay`: the feed's camera and image replace the orbit and the sky.
    pub(super) feed: Option<FeedView>,
    /// The water the command line chose (the renderer is built with it).
    pub(super) sea_water: render::water_look::WaterLook,
    fps: FpsMeter,
    /// The performance panel's numbers of the last frame.
    pub(super) perf: PerfStats,
    /// Files dropped since the last frame.
    dropped: Vec<PathBuf>,
    /// The panels' input from the window system since the last frame.
    panel_input: Option<egui::RawInput>,
    /// What egui asked of the window system in the last frame (cursor, clipboard).
    pub(super) platform_output: Option<egui::PlatformOutput>,
    /// Escape was pressed.
    quit: bool,
    /// Why the app cannot go on (a feed frame that could not be read), for the shell to end
    /// with.
    pub(super) failure: Option<String>,
}

impl super::ProfileStart {
    /// The desktop's start: `start`'s scene, feed, water and tier (the governor from ultra
    /// without one), the window's panels with the performance panel, the Races panel's file
    /// dialog; panels opened and boats selected (`selected`) from the environment for
    /// screenshots and the smoke test.
    pub(super) fn desktop(
        world: &RaceWorld,
        start: DesktopStart,
        selected: &mut Vec<usize>,
    ) -> super::ProfileStart {
        let fx = start.feed.is_some();
        let mut panels = RegattaUi::new(
            crate::hud::initial_clock(&world.race),
            crate::panels::effect_toggles(fx),
        );
        panels.settings.overlays = crate::scene_overlay::panel_toggles(Default::default());
        crate::panels::set_water_ranges(&mut panels.settings, fx);
        // The sliders start at the water the command line chose.
        panels.settings.water_type = start.water.water_type.name().to_string();
        panels.settings.water_depth_m = start.water.depth_m;
        panels.settings.turbidity = start.water.turbidity_ntu;
        crate::panels::panels_from_env(&mut panels, selected, &world.race);
        super::ProfileStart {
            backend: Box::new(crate::core::ar::NoAr),
            panels,
            tiers: crate::tier_control::TierControl::new(
                start.tier.unwrap_or(quality::Tier::Ultra),
                start.tier.is_some(),
            ),
            scene: start.scene,
            pool: PoolPlay::new(start.pool_sea),
            races: super::races::RaceList::with_dialog(),
            clip_request: super::ClipRequest::DESKTOP,
            desktop: Some(Desktop {
                feed: start.feed,
                sea_water: start.water,
                fps: FpsMeter::new(30),
                perf: PerfStats::default(),
                dropped: Vec::new(),
                panel_input: None,
                platform_output: None,
                quit: false,
                failure: None,
            }),
        }
    }
}

impl App {
    /// The desktop: `world` under the orbit view or on `start.feed`'s table.
    pub fn desktop(world: RaceWorld, start: DesktopStart) -> App {
        App::new(world, super::Start::Desktop(Box::new(start)))
    }

    /// Which profile the app runs: `Profile::Desktop` or `Profile::Phone`.
    pub fn profile(&self) -> Profile {
        match self.desktop {
            Some(_) => Profile::Desktop,
            None => Profile::Phone,
        }
    }

    /// Escape was pressed: the shell closes the window.
    pub fn quit_requested(&self) -> bool {
        self.desktop.as_ref().is_some_and(|d| d.quit)
    }

    /// Why the app cannot go on, once (the shell ends with it).
    pub fn take_failure(&mut self) -> Option<String> {
        self.desktop.as_mut().and_then(|d| d.failure.take())
    }

    /// What egui asked of the window system in the last frame (the shell carries it out).
    pub fn take_platform_output(&mut self) -> Option<egui::PlatformOutput> {
        self.desktop.as_mut().and_then(|d| d.platform_output.take())
    }

    /// The window's title: the race, its time, paused or not, the tier and who chose it; the
    /// pool and its time.
    pub fn title(&self) -> String {
        match self.scene {
            SceneChoice::Pool => format!("Regatta: the pool at t = {:.1} s", self.pool_t),
            SceneChoice::Race => format!(
                "Regatta: {} at t = {:.0} s{}, quality {} ({})",
                self.world.race.name,
                self.race_time(),
                if self.panels.clock.is_playing() {
                    ""
                } else {
                    " (paused)"
                },
                self.tiers.tier(),
                if self.tiers.pinned().is_some() {
                    "pinned"
                } else {
                    "auto"
                }
            ),
        }
    }

    /// The camera feed behind the race, on the desktop with `--replay`.
    pub fn feed(&self) -> Option<&FeedView> {
        self.desktop.as_ref().and_then(|d| d.feed.as_ref())
    }

    /// The orbit view's camera now (the follow camera's target included).
    pub fn orbit(&self) -> &render::OrbitCamera {
        &self.orbit
    }

    pub(super) fn panel_input(&mut self, raw: egui::RawInput) {
        let Some(d) = self.desktop.as_mut() else {
            return;
        };
        // Input arriving between two frames is one frame's.
        match d.panel_input.as_mut() {
            Some(kept) => {
                kept.events.extend(raw.events);
                kept.focused = raw.focused;
            }
            None => d.panel_input = Some(raw),
        }
    }

    /// The panels' raw input for this frame: the phone's from its touches; the desktop's from
    /// the window system, on the screen the touch input measures (size and density).
    pub(super) fn take_panel_input(&mut self, size: [u32; 2]) -> egui::RawInput {
        let mut raw = self.touch.take_raw_input(size, self.now);
        if let Some(d) = self.desktop.as_mut() {
            // The mouse reached egui from the window system: the finger's copy goes.
            raw.events.clear();
            if let Some(given) = d.panel_input.take() {
                raw.events = given.events;
                raw.focused = given.focused;
            }
        }
        raw
    }

    /// The wheel at `px`: zooms the view shown, unless a panel is under it (the panel scrolls).
    pub(super) fn wheel(&mut self, steps: f64, px: [f32; 2]) {
        if self.over_panels(px) {
            return;
        }
        self.end_gesture();
        self.active_orbit().zoom(steps);
    }

    /// Whether a panel lies under `px` (physical pixels) in the last frame's layout.
    pub(super) fn over_panels(&self, px: [f32; 2]) -> bool {
        let Some(g) = self.graphics.as_ref() else {
            return false;
        };
        let p = egui::pos2(px[0], px[1]) / self.touch.pixels_per_point;
        crate::hud::touch::over_egui(&g.egui.ctx, self.ui_free, p)
    }

    /// The timeline's keys (docs/panels.md, "Shortcuts"), unless egui has the keyboard (a
    /// text field): space plays and pauses, ←/→ step, Home jumps to the start, PgUp/PgDn
    /// between events, R plays the other way, [ and ] halve and double the speed, F follows the
    /// selected boat; Escape asks to quit.
    pub(super) fn key(&mut self, key: Key) {
        if key == Key::Escape {
            if let Some(d) = self.desktop.as_mut() {
                d.quit = true;
            }
            return;
        }
        if self
            .egui_context()
            .is_some_and(|c| c.egui_wants_keyboard_input())
        {
            return;
        }
        let times: Vec<f64> = self.events.iter().map(|e| e.t).collect();
        let clock = &mut self.panels.clock;
        match key {
            Key::Space => clock.toggle(),
            Key::Right => clock.step(1),
            Key::Left => clock.step(-1),
            Key::Home => clock.jump_to_start(),
            Key::PageDown => {
                clock.jump_to_next(&times);
            }
            Key::PageUp => {
                clock.jump_to_previous(&times);
            }
            Key::Char('r' | 'R') => clock.reverse(),
            Key::Char('[') => clock.slower(),
            Key::Char(']') => clock.faster(),
            Key::Char('f' | 'F') => {
                self.panels.follow = !self.panels.follow && !self.overlays.selected().is_empty()
            }
            Key::Char(_) | Key::Escape => {}
        }
    }

    pub(super) fn file_dropped(&mut self, path: PathBuf) {
        if let Some(d) = self.desktop.as_mut() {
            d.dropped.push(path);
        }
    }

    /// The desktop's part of a frame before it is drawn: the frame meter, and the files
    /// dropped since the last frame opened as one race (a failure said in the Races panel).
    pub(super) fn desktop_frame_start(&mut self, dt: f64) {
        let Some(d) = self.desktop.as_mut() else {
            return;
        };
        d.fps.push(dt);
        let files = std::mem::take(&mut d.dropped);
        if !files.is_empty() {
            // The error is in the panel; the race shown stays.
            let _ = self.open_race(&files);
        }
    }

    /// The frame's record onto the performance panel.
    pub(super) fn record(&mut self, report: &render::FrameReport) {
        if let Some(d) = self.desktop.as_mut() {
            d.perf = crate::hud::perf_stats(report, &d.fps);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setup::RaceSetup;

    fn world() -> RaceWorld {
        RaceSetup::load_world(&[], None).unwrap()
    }

    /// One constructor, two starts: each profile starts as docs/quality.md and docs/panels.md
    /// say, with nothing of the other's (the desktop's start once took the phone's and wrote
    /// over it). The phone: the governor free from high, the race scene, no perf panel or
    /// leaderboard, no Races panel until a folder is set. The desktop: the
    /// `--tier` pinned, its `--scene`, the perf panel and leaderboard, the file dialog.
    #[test]
    fn each_profile_starts_with_its_own_parts_only() {
        let phone = App::phone(world(), Box::new(crate::core::ar::NoAr));
        assert_eq!(phone.profile(), Profile::Phone);
        assert_eq!(phone.tiers.tier(), quality::Tier::High);
        assert_eq!(phone.tiers.pinned(), None);
        assert_eq!(phone.scene, SceneChoice::Race);
        assert!(!phone.panels.show_perf && !phone.panels.show_leaderboard);
        assert!(phone.races.panel("sample").is_none());
        assert_eq!(phone.clip_request, super::super::ClipRequest::PHONE);

        let start = DesktopStart {
            feed: None,
            water: render::water_look::WaterLook::default(),
            tier: Some(quality::Tier::Low),
            scene: SceneChoice::Pool,
            pool_sea: None,
        };
        let desktop = App::desktop(world(), start);
        assert_eq!(desktop.profile(), Profile::Desktop);
        assert_eq!(desktop.tiers.tier(), quality::Tier::Low);
        assert_eq!(desktop.tiers.pinned(), Some(quality::Tier::Low));
        assert_eq!(desktop.scene, SceneChoice::Pool);
        assert!(desktop.panels.show_perf && desktop.panels.show_leaderboard);
        assert!(desktop.races.panel("sample").is_some_and(|p| p.dialog));
        assert_eq!(desktop.clip_request, super::super::ClipRequest::DESKTOP);

        // Without `--tier` the desktop's governor is free from ultra.
        let free = App::desktop(
            world(),
            DesktopStart {
                feed: None,
                water: render::water_look::WaterLook::default(),
                tier: None,
                scene: SceneChoice::Race,
                pool_sea: None,
            },
        );
        assert_eq!(free.tiers.tier(), quality::Tier::Ultra);
        assert_eq!(free.tiers.pinned(), None);
    }
}
