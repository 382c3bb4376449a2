//! The app, one for the desktop window and the phone (as wgpu's example framework has one
//! type with init, resize, event and frame): platform events in ([`AppEvent`]), a frame out
//! ([`App::frame`], wall seconds since the last frame). What both profiles do lives here once:
//! the race clock and panels, the race overlays and click/tap-to-select (one threshold,
//! [`TAP_MAX_PX`]), the orbit view and the camera that follows a boat, opening a race (a
//! failure said in the Races panel, the race shown kept), the quality governor and its one tier
//! path, the window's surface through suspend and resume.
//!
//! What differs is the profile ([`crate::setup::Profile`]):
//! - the phone ([`App::phone`]): the race or the pool on the table through the AR backend, the
//!   phone's bar and banner, touch as the only input, safe insets; driven by the Android
//!   activity, the `regatta run --phone` window or a `regatta phone-sim` script.
//! - the desktop ([`App::desktop`], `desktop.rs`): the orbit view over the sky or over a camera
//!   feed's table (`FeedView`), the mouse (translated into one finger by the window), the wheel,
//!   the timeline's keys, dropped race files, the performance panel; driven by the `regatta`
//!   window.
//!
//! Lifecycle (wgpu issue 2302): the device is made on the first window; each new window gets a
//! surface configured as the first one was ([`super::gfx::Window`]); a destroyed window's
//! surface is dropped before the event returns. In the background nothing is drawn and time
//! stops. A lost device is rebuilt on OpenGL ES on the next frame.

mod clip;
pub mod desktop;
mod draw;
mod hud;
mod input;
mod races;
mod shared;
mod tiers;

use std::path::PathBuf;

use ar::arcore::{CoursePlacement, Event, SessionState};
use render::OrbitCamera;
use ui::{RegattaUi, TimelineEvent};

use super::ar::{ArBackend, ArState};
use super::gfx::SurfaceMaker;
use super::table;
use crate::hud::SceneChoice;
use crate::hud::banner::{ArStatus, Tone, banner};
use crate::hud::touch::{Touch, TouchInput};
use crate::pool_play::PoolPlay;
use crate::world::RaceWorld;

pub use clip::{
    CHOOSER_TITLE, CLIP_FOLDER, ClipRequest, ClipState, ClipWorker, GIF_MIME, HandOff, NO_SPAN,
    media_store_hand_off,
};
pub use desktop::{DesktopStart, Key};
pub use draw::Graphics;
pub use input::{TAP_MAX_PX, TAP_MAX_S};
pub use races::{RACES_DIR_ENV, host_races_dir};
pub use shared::{EXTENSION_OF_MIME, Opened, SHARED_MAX_BYTES, SharedFile, kept_name, read_intent};
pub use tiers::PHONE_START_TIER;

/// Frames between two reads of the display rotation (a quarter second at 60 fps).
pub const ROTATION_POLL_FRAMES: u32 = 15;

/// What happens to the app, in the platform's words translated.
pub enum AppEvent {
    /// A native window exists (Android `InitWindow`, winit `resumed`); `surface` makes its wgpu
    /// surface, `None` for an offscreen window (headless sessions).
    WindowCreated {
        surface: Option<SurfaceMaker>,
        size: [u32; 2],
    },
    /// The native window goes away (Android `TerminateWindow`): its surface is dropped now.
    WindowDestroyed,
    /// The window's size changed (rotation, split screen).
    Resized([u32; 2]),
    /// The app came to the foreground.
    Resumed,
    /// The app went to the background.
    Paused,
    Touch(Touch),
    /// Display rotation, `Surface.ROTATION_*` (0..3).
    Rotation(i32),
    /// Physical pixels per egui point (density / 160 on Android).
    Density(f32),
    /// The window's part free of the status bar, navigation bar and cutout (Android's content
    /// rect): left, top, right, bottom in physical pixels.
    ContentRect([i32; 4]),
    /// The hardware key that starts and stops a recording (volume up).
    RecordKey,
    /// The panels' input the desktop's window system made (egui-winit: the pointer's hover,
    /// the wheel over a panel, keys), for the next frame; the phone makes its own from touches.
    PanelInput(egui::RawInput),
    /// The mouse wheel at `px` (physical pixels), `steps` lines (up > 0): zooms the orbit view
    /// where no panel is under it.
    Wheel {
        steps: f64,
        px: [f32; 2],
    },
    /// A key pressed (the timeline's keys; Escape asks to quit).
    Key(Key),
    /// A file dropped on the window (a drop of several arrives as several events; they open
    /// together as one race at the next frame).
    FileDropped(PathBuf),
}

impl AppEvent {
    /// A touch of fingers 0, 1, … at `px` (physical pixels).
    pub fn touch(action: crate::hud::touch::TouchAction, px: &[[f32; 2]]) -> AppEvent {
        AppEvent::Touch(Touch {
            action,
            fingers: px
                .iter()
                .enumerate()
                .map(|(i, px)| crate::hud::touch::Finger {
                    id: i as i32,
                    px: *px,
                })
                .collect(),
        })
    }
}

/// What a session log shows of the app after a step.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PhoneStatus {
    pub session: String,
    pub banner: Option<String>,
    pub placed: bool,
    pub frames_drawn: u64,
    pub race_time: f64,
    pub scene: &'static str,
    pub recording: bool,
    /// The race shown (its name).
    pub race: String,
    /// How many boats it has.
    pub boats: usize,
}

/// The app's state.
pub struct App {
    world: RaceWorld,
    /// The desktop profile's parts (`desktop.rs`); `None` on the phone.
    desktop: Option<desktop::Desktop>,
    /// The race panels (their clock owns race time) and the timeline's mark roundings.
    pub panels: RegattaUi,
    events: Vec<TimelineEvent>,
    /// The pool's time, seconds.
    pool_t: f64,
    /// Seconds the app has run in the foreground (egui's and the tap's clock).
    now: f64,
    pub scene: SceneChoice,
    orbit: OrbitCamera,
    pool_orbit: OrbitCamera,
    pool: PoolPlay,
    course: Option<CoursePlacement>,
    pool_placement: Option<CoursePlacement>,
    resumed: bool,
    /// The next frame is the first after a resume: its wall time was spent in the background.
    back_from_background: bool,
    pub ar: ArState,
    backend: Box<dyn ArBackend>,
    touch: TouchInput,
    gesture: input::Gesture,
    /// The root ui's rect left free by the panels in the last frame (egui points).
    ui_free: egui::Rect,
    rotation: i32,
    /// Frames since the display rotation was last read (a 180° turn sends no event).
    rotation_age: u32,
    /// The phone's bar as last laid out (points): its buttons, for tests and taps.
    pub bar: Option<crate::hud::PhoneBar>,
    /// Where recordings go (the app's storage).
    pub data_dir: Option<PathBuf>,
    /// The surface maker of the current window (kept to rebuild after a lost device).
    maker: Option<SurfaceMaker>,
    graphics: Option<Graphics>,
    /// The last recording folder written.
    pub last_recording: Option<PathBuf>,
    /// The race overlays over the scene (labels, trails, course, lines, wind), as on the
    /// desktop; boats are selected by a tap on them or in the Boats panel.
    pub overlays: crate::scene_overlay::live::LiveOverlays,
    /// The room on the table the course was first fitted to (the tapped plane's), where its
    /// water is drawn.
    table_room: table::TableRoom,
    /// The Races panel's folder and list.
    races: races::RaceList,
    /// The quality governor: frame times in, the tier drawn out (docs/quality.md).
    pub tiers: crate::tier_control::TierControl,
    /// What the last shared file did (opened, boats added, or why not), shown on the banner
    /// until the app time given (`shared.rs`).
    notice: Option<(String, Tone, f64)>,
    /// "Share clip": the clip's worker and what it says (`clip.rs`).
    pub clip: ClipWorker,
    /// `Build.VERSION.SDK_INT` on Android (the adapter sets it); `None` on the host.
    pub android_sdk: Option<u32>,
    /// What the button's clip covers ([`ClipRequest::PHONE`], [`ClipRequest::DESKTOP`]; tests
    /// draw smaller ones).
    pub clip_request: ClipRequest,
}

/// How the app starts: what differs by profile, given once (the rest starts the same).
pub enum Start {
    /// The phone: the AR session's backend (ARCore, or the simulated ARCore on the host).
    Phone(Box<dyn ArBackend>),
    /// The desktop: the command line's choices (boxed: a feed is large beside a backend).
    Desktop(Box<DesktopStart>),
}

/// The fields a profile starts with its own values; [`App::new`] builds each of them once,
/// from its profile only.
struct ProfileStart {
    backend: Box<dyn ArBackend>,
    desktop: Option<desktop::Desktop>,
    panels: RegattaUi,
    tiers: crate::tier_control::TierControl,
    scene: SceneChoice,
    pool: PoolPlay,
    races: races::RaceList,
    clip_request: ClipRequest,
}

impl ProfileStart {
    /// The phone's start: the race scene on the table, the governor from
    /// [`PHONE_START_TIER`], the small screen's panels, the Races panel's folder (no dialog).
    fn phone(world: &RaceWorld, backend: Box<dyn ArBackend>) -> ProfileStart {
        let mut panels = RegattaUi::new(crate::hud::initial_clock(&world.race), Vec::new());
        panels.settings.overlays = crate::scene_overlay::panel_toggles(Default::default());
        // The phone's screen is small: the timeline and the bar; the leaderboard behind its
        // toggle in the timeline's header, no frame statistics.
        panels.show_perf = false;
        panels.show_leaderboard = false;
        // The Scene panel's water: the table's real sea (type, depth, turbidity).
        crate::panels::set_water_ranges(&mut panels.settings, true);
        ProfileStart {
            backend,
            desktop: None,
            panels,
            tiers: tiers::phone_tiers(),
            scene: SceneChoice::Race,
            pool: PoolPlay::new(None),
            races: Default::default(),
            clip_request: ClipRequest::PHONE,
        }
    }
}

impl App {
    /// The app of `start`'s profile showing `world`.
    pub fn new(world: RaceWorld, start: Start) -> Self {
        let mut overlays = crate::scene_overlay::live::LiveOverlays::default();
        let profile = match start {
            Start::Phone(backend) => ProfileStart::phone(&world, backend),
            Start::Desktop(start) => {
                ProfileStart::desktop(&world, *start, &mut overlays.settings.selected)
            }
        };
        App {
            events: ui::timeline_events(&world.race),
            panels: profile.panels,
            world,
            desktop: profile.desktop,
            pool_t: 0.0,
            now: 0.0,
            scene: profile.scene,
            orbit: crate::world::race_orbit(),
            pool_orbit: PoolPlay::orbit(),
            pool: profile.pool,
            course: None,
            pool_placement: None,
            resumed: false,
            back_from_background: false,
            ar: ArState::default(),
            backend: profile.backend,
            touch: TouchInput::new(1.0),
            gesture: input::Gesture::default(),
            ui_free: egui::Rect::EVERYTHING,
            rotation: 0,
            rotation_age: 0,
            bar: None,
            data_dir: None,
            maker: None,
            graphics: None,
            last_recording: None,
            overlays,
            table_room: table::TableRoom::FIRST,
            races: profile.races,
            tiers: profile.tiers,
            notice: None,
            clip: ClipWorker::default(),
            android_sdk: None,
            clip_request: profile.clip_request,
        }
    }

    /// The phone: `world` on the table through `backend`, the AR session.
    pub fn phone(world: RaceWorld, backend: Box<dyn ArBackend>) -> Self {
        App::new(world, Start::Phone(backend))
    }

    /// Whether frames are drawn: in the foreground with a window.
    pub fn visible(&self) -> bool {
        self.resumed
            && self
                .graphics
                .as_ref()
                .is_some_and(|g| g.window.is_attached())
    }

    /// Every event of `events`, in order.
    pub fn on_all(&mut self, events: impl IntoIterator<Item = AppEvent>) {
        for e in events {
            self.on(e);
        }
    }

    pub fn on(&mut self, event: AppEvent) {
        match event {
            AppEvent::WindowCreated { surface, size } => {
                self.maker = surface;
                self.attach_window(size);
            }
            AppEvent::WindowDestroyed => {
                if let Some(g) = self.graphics.as_mut() {
                    g.window.detach();
                }
                self.maker = None;
            }
            AppEvent::Resized(size) => {
                if let Some(g) = self.graphics.as_mut() {
                    g.window.resize(&g.gpu, size[0], size[1]);
                }
            }
            AppEvent::Resumed => {
                self.resumed = true;
                // Time in the background does not count.
                self.back_from_background = true;
                if self.desktop.is_some() {
                    return;
                }
                let loaded = self.backend.is_loaded();
                // The tier drawn now decides the camera image of this resume (a running
                // session keeps its camera config: ARCore changes it only while paused).
                self.backend.set_camera_budget(self.camera_budget());
                self.session_event(Event::AppResumed {
                    library_loaded: loaded,
                });
                // The phone may have been turned while away.
                self.rotation_age = ROTATION_POLL_FRAMES;
                // Files may have been pushed while the app was away.
                self.rescan_races();
            }
            AppEvent::Paused => {
                self.resumed = false;
                if self.desktop.is_some() {
                    return;
                }
                if self.ar.recorder.is_some() {
                    self.toggle_recording();
                }
                self.session_event(Event::AppPaused);
            }
            AppEvent::Touch(t) => self.on_touch(&t),
            AppEvent::Rotation(r) => self.rotation = r,
            AppEvent::Density(ppp) => self.touch.pixels_per_point = ppp.max(0.5),
            AppEvent::ContentRect(r) => self.touch.content_px = Some(r),
            AppEvent::RecordKey => self.toggle_recording(),
            AppEvent::PanelInput(raw) => self.panel_input(raw),
            AppEvent::Wheel { steps, px } => self.wheel(steps, px),
            AppEvent::Key(key) => self.key(key),
            AppEvent::FileDropped(path) => self.file_dropped(path),
        }
    }

    /// Steps the AR session with `event` through the backend.
    fn session_event(&mut self, event: Event) {
        self.ar.step(self.backend.as_mut(), event);
    }

    /// One display frame, `dt` wall seconds after the last: time, AR, drawing (when visible).
    pub fn frame(&mut self, dt: f64) {
        if !self.visible() {
            return;
        }
        let dt = if std::mem::take(&mut self.back_from_background) {
            0.0
        } else {
            dt.max(0.0)
        };
        self.now += dt;
        self.panels.clock.advance(dt);
        self.pool_t += dt;
        if self.desktop.is_some() {
            self.desktop_frame_start(dt);
        } else {
            self.poll_rotation();
            let size = self.view_size();
            self.ar.update(self.backend.as_mut(), self.rotation, size);
        }
        self.draw();
        self.govern();
    }

    /// Reads the display rotation every [`ROTATION_POLL_FRAMES`] frames while AR runs: a 180°
    /// turn changes neither the window's size nor its orientation class, so Android sends no
    /// window or configuration event for it (issue 26, defect 3). ARCore's own
    /// `DisplayRotationHelper` listens to `DisplayManager`'s display events, which needs a
    /// Java class of ours; a poll needs none, and costs three JNI calls a quarter second.
    fn poll_rotation(&mut self) {
        if !self.ar.session.is_running() {
            return;
        }
        self.rotation_age += 1;
        if self.rotation_age < ROTATION_POLL_FRAMES {
            return;
        }
        self.rotation_age = 0;
        if let Some(r) = self.backend.display_rotation()
            && r != self.rotation
        {
            log::info!("regatta: display rotation {} -> {r}", self.rotation);
            self.rotation = r;
        }
    }

    pub fn race_time(&self) -> f64 {
        self.panels.clock.time()
    }

    /// The window's size in pixels (1 × 1 without one).
    pub fn view_size(&self) -> [u32; 2] {
        self.graphics.as_ref().map_or([1, 1], |g| g.window.size())
    }

    fn placed(&self) -> Option<CoursePlacement> {
        match self.scene {
            SceneChoice::Race => self.course,
            SceneChoice::Pool => self.pool_placement,
        }
    }

    /// The room on the table the course was first fitted to (the tapped plane's).
    pub fn table_room(&self) -> table::TableRoom {
        self.table_room
    }

    /// Where the course stands on the table, once placed.
    pub fn course(&self) -> Option<CoursePlacement> {
        self.course
    }

    pub fn pool_placement(&self) -> Option<CoursePlacement> {
        self.pool_placement
    }

    /// The banner's text and tone now.
    pub fn banner(&self) -> Option<(String, Tone)> {
        // A clip being drawn says how far it is.
        if self.clip.busy()
            && let Some(line) = self.clip.line()
        {
            return Some((line, Tone::Hint));
        }
        // A shared file's outcome, for a few seconds, before the session's message.
        if let Some((text, tone, until)) = &self.notice
            && self.now < *until
        {
            return Some((text.clone(), *tone));
        }
        let note = self
            .ar
            .note
            .as_deref()
            .or(self.graphics.as_ref().and_then(|g| g.note.as_deref()));
        let message = banner(&ArStatus {
            session: self.ar.session,
            tracking_hint: self.ar.hint,
            has_frame: self.ar.frame.is_some(),
            placed: self.placed().is_some(),
            what: self.scene.noun(),
            note,
        });
        // The GPU's fallback is said even when the session has nothing to say.
        match (message, self.graphics.as_ref().and_then(|g| g.note.clone())) {
            (None, Some(n)) => Some((n, Tone::Warning)),
            (m, _) => m,
        }
    }

    pub fn session(&self) -> SessionState {
        self.ar.session
    }

    /// What a session log records.
    pub fn status(&self) -> PhoneStatus {
        PhoneStatus {
            session: format!("{:?}", self.ar.session),
            banner: self.banner().map(|(t, _)| t),
            placed: self.placed().is_some(),
            frames_drawn: self.graphics.as_ref().map_or(0, |g| g.frames_drawn),
            race_time: self.race_time(),
            scene: self.scene.noun(),
            recording: self.ar.recorder.is_some(),
            race: self.world.race.name.clone(),
            boats: self.world.race.boats.len(),
        }
    }

    /// The latest frame drawn, read back (offscreen windows only).
    pub fn screenshot(&self) -> Option<Result<image::RgbaImage, String>> {
        let g = self.graphics.as_ref()?;
        let t = g.window.offscreen_texture()?;
        Some(g.gpu.read_texture(t).map_err(|e| e.to_string()))
    }

    /// What the graphics said of their device (the OpenGL ES fallbacks), if anything.
    pub fn graphics_note(&self) -> Option<&str> {
        self.graphics.as_ref().and_then(|g| g.note.as_deref())
    }

    /// The device's adapter, for logs.
    pub fn describe_gpu(&self) -> Option<String> {
        self.graphics.as_ref().map(|g| g.gpu.describe())
    }

    /// The configuration the current window was given (tests of the kept configuration).
    pub fn window_config(&self) -> Option<wgpu::SurfaceConfiguration> {
        self.graphics
            .as_ref()
            .and_then(|g| g.window.config().cloned())
    }

    /// The egui context of the panels (tests find widgets in its last pass). A new one comes
    /// with each device (after a lost device, on OpenGL ES): what translates the platform's
    /// input for egui (the desktop shell's egui-winit state) follows this one.
    pub fn egui_context(&self) -> Option<egui::Context> {
        self.graphics.as_ref().map(|g| g.egui.ctx.clone())
    }

    /// Loses the device as a driver reset or a hung GPU does: `wgpu::Device::destroy` fires
    /// the device's lost callback, and the next frame rebuilds on OpenGL ES (tests of that
    /// path; the app never calls it).
    #[doc(hidden)]
    pub fn lose_device(&self) {
        if let Some(g) = self.graphics.as_ref() {
            g.gpu.device.destroy();
            // The lost callback runs once the queue is empty, at the next maintenance.
            let _ = g.gpu.device.poll(wgpu::PollType::wait_indefinitely());
        }
    }

    /// Loses the device without polling it: wgpu runs the lost callback only from a poll (a
    /// driver's loss found by a submit runs it there, in the middle of a frame), so the app
    /// meets a lost device whose callback has not run (tests of that path; the app never
    /// calls it).
    #[doc(hidden)]
    pub fn lose_device_unpolled(&self) {
        if let Some(g) = self.graphics.as_ref() {
            g.gpu.device.destroy();
        }
    }

    /// The backend, for adapters that script it (the simulated ARCore).
    pub fn backend_mut(&mut self) -> &mut dyn ArBackend {
        self.backend.as_mut()
    }

    fn toggle_recording(&mut self) {
        let stamp = (self.now * 1000.0) as u64 + self.ar.frame_seq;
        if let Some(dir) = self.ar.toggle_recording(self.data_dir.as_deref(), stamp) {
            self.last_recording = Some(dir);
        }
    }

    /// Switches the scene (the bar's toggle; `scene race|pool` in scripts).
    pub fn choose_scene(&mut self, choice: SceneChoice) {
        if choice != self.scene {
            self.end_gesture();
            self.scene = choice;
        }
    }

    /// Starts or stops recording (the bar's button).
    pub fn record_button(&mut self) {
        self.toggle_recording();
    }
}
