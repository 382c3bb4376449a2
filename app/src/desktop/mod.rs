//! The desktop window (`regatta`, `regatta run`): the embedded race and sea (or the files
//! given) under an orbiting camera. Left-drag orbits, the wheel zooms, space pauses, the arrow
//! keys step race time by ±10 s. Race time plays at real speed from the start and loops.
//! Race files dropped on the window (or chosen in the Races panel's dialog) replace the race;
//! one that fails to load leaves the race shown and says why in the panel.
//!
//! winit 0.30's `ApplicationHandler`; the device comes from `render::Gpu::for_window`.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use clap::Args;
use render::{OrbitCamera, Renderer};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::core::gfx::{self, Acquired};
use crate::error::{AppError, AppResult};
use crate::setup::SceneKind;
use crate::setup::inputs::{load_race, load_sea};
use crate::setup::{Profile, RaceSetup};
use crate::wall_clock::Ticker;
use crate::world::RaceWorld;

pub mod hud;
pub mod phone;
pub mod pool;
pub mod share_clip;
pub mod smoke;

#[derive(Debug, Args, Default)]
pub struct RunArgs {
    /// Race files (native race JSON, maxSail JSON, GPX, CSV logs and exports, Expedition, NMEA
    /// 0183, SailGP / AC race XML, FIT, TCX, KML / KMZ, NMEA 2000 logs: candump, Actisense CSV,
    /// canboat JSON; several combine into one race); the embedded sample race without it.
    #[arg(long, num_args = 1..)]
    pub race: Vec<PathBuf>,
    /// Sea file (JSON); the embedded default sea without it.
    #[arg(long)]
    pub sea: Option<PathBuf>,
    /// Which scene: the race, or the tiled pool (drag the green ball to make ripples).
    #[arg(long, value_enum, default_value_t)]
    pub scene: SceneKind,
    /// A recorded camera feed (replay folder or TUM RGB-D) as the background, the race on its
    /// table; `synth` for the built-in synthetic table (what `regatta` alone opens). With
    /// `--phone`, the simulated ARCore's camera.
    #[arg(long, value_name = "DIR")]
    pub replay: Option<PathBuf>,
    /// The real sea on the table: water type, depth and turbidity (docs/water-look.md).
    #[command(flatten)]
    pub water: crate::water::WaterArgs,
    /// The phone app in a portrait window of the phone's aspect and density, through the
    /// simulated ARCore (mouse = one finger; right-drag or Ctrl+wheel = pinch and twist).
    #[arg(long)]
    pub phone: bool,
    /// Which phone `--phone` shows.
    #[arg(long, value_enum, default_value_t, requires = "phone")]
    pub device: crate::sim_phone::device::Device,
    /// With `--phone`: the simulated ARCore library (crates/arcore_sim's cdylib) that the
    /// phone's own ARCore glue loads; a scripted stand-in without it.
    #[arg(long, value_name = "FILE", requires = "phone")]
    pub arcore_lib: Option<PathBuf>,
    /// Pin a quality tier (low, medium, high, ultra); without it the governor chooses
    /// (docs/quality.md).
    #[arg(long)]
    pub tier: Option<String>,
}

impl RunArgs {
    /// What `regatta` without a subcommand opens: the embedded race and sea on the synthetic
    /// feed's table.
    pub fn default_app() -> RunArgs {
        RunArgs {
            replay: Some(PathBuf::from(crate::feed::SYNTH)),
            ..RunArgs::default()
        }
    }
}

/// Open the window and run until it is closed.
pub fn run(a: RunArgs) -> AppResult {
    smoke::check_exit_after_env().map_err(AppError::new)?;
    if a.phone {
        return phone::run(a);
    }
    let sea = crate::setup::inputs::drawable_sea(load_sea(a.sea.as_ref())?);
    let race = load_race(&a.race)?;
    // A bad feed is refused before a window opens (file and line named).
    let mut feed = a
        .replay
        .as_deref()
        .map(crate::feed::FeedView::open)
        .transpose()?;
    let water = match feed.as_mut() {
        Some(f) => {
            f.set_water(a.water.look(f.water())?);
            f.water()
        }
        None => a.water.look(render::water_look::WaterLook::default())?,
    };
    let pinned = a
        .tier
        .as_deref()
        .map(crate::tier_render::parse_tier)
        .transpose()?;
    let event_loop = EventLoop::new().map_err(|e| {
        AppError::new(format!(
            "cannot open a window (no display?): {}",
            smoke::window_error(&e)
        ))
    })?;
    let pool = (a.scene == SceneKind::Pool)
        .then(|| pool::PoolMode::new(a.sea.is_some().then(|| sea.clone())));
    // Without the panels (the pool), race time plays at real speed from the start and loops.
    let mut clock = ui::RaceClock::new(race.time_span());
    clock.looping = true;
    clock.play();
    let mut app = App {
        orbit: match pool {
            Some(_) => pool::PoolMode::orbit(),
            None => crate::world::race_orbit(),
        },
        pool,
        feed,
        water,
        world: RaceWorld::new(race, sea),
        state: None,
        clock,
        ticker: Ticker::default(),
        drag: None,
        press_at: None,
        cursor: (0.0, 0.0),
        error: None,
        dropped: Vec::new(),
        tiers: crate::tier_control::TierControl::new(
            pinned.unwrap_or(quality::Tier::Ultra),
            pinned.is_some(),
        ),
        started: Instant::now(),
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| AppError::new(format!("the window's event loop failed: {e}")))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct State {
    window: Arc<Window>,
    gpu: render::Gpu,
    target: gfx::Window,
    renderer: Renderer,
    /// The egui panels (timeline, leaderboard, performance); `None` in the pool scene.
    hud: Option<hud::Hud>,
}

struct App {
    /// `Some` with `--scene pool`: the pool replaces the race.
    pool: Option<pool::PoolMode>,
    /// `Some` with `--replay`: the feed's camera and image replace the orbit and the sky.
    feed: Option<crate::feed::FeedView>,
    /// The water the command line chose (the Scene panel starts there; its type colours the
    /// open sea too).
    water: render::water_look::WaterLook,
    world: RaceWorld,
    state: Option<State>,
    orbit: OrbitCamera,
    /// Race time without the panels (with them, the timeline's clock).
    clock: ui::RaceClock,
    ticker: Ticker,
    drag: Option<(f64, f64)>,
    /// Where the left button went down (a release there is a click).
    press_at: Option<(f64, f64)>,
    cursor: (f64, f64),
    error: Option<AppError>,
    /// Files dropped on the window since the last frame (one drop of several files arrives as
    /// several events): loaded together as one race at the next frame.
    dropped: Vec<PathBuf>,
    /// The quality governor: frame times in, the tier's renderer settings out.
    tiers: crate::tier_control::TierControl,
    started: Instant,
}

impl App {
    fn fail(&mut self, el: &ActiveEventLoop, msg: String) {
        self.error = Some(AppError::new(msg));
        el.exit();
    }

    /// Race time for this frame: the timeline's with the panels, else the app's clock.
    fn tick(&mut self) -> f64 {
        let dt = self.ticker.tick();
        match self.state.as_mut().and_then(|s| s.hud.as_mut()) {
            Some(o) => o.tick(),
            None => {
                self.clock.advance(dt);
                self.clock.time()
            }
        }
    }

    /// Opens what was dropped on the window or asked for in the Races panel.
    fn open_requested(&mut self) {
        let Some(st) = self.state.as_mut() else {
            return;
        };
        let Some(o) = st.hud.as_mut() else {
            return;
        };
        let mut files = std::mem::take(&mut self.dropped);
        match o.open_request.take() {
            Some(ui::OpenRequest::Files(f)) => files = f,
            Some(ui::OpenRequest::Dialog) => {
                if let Some(f) = crate::panels::pick_race_files() {
                    files = f;
                }
            }
            Some(ui::OpenRequest::Rescan) | None => {}
        }
        if files.is_empty() {
            return;
        }
        match crate::panels::load_race_files(&files) {
            Ok(race) => {
                log::info!("opened {}", race.name);
                o.set_race(&race, &mut st.renderer);
                // Its wakes at the tier's spacing from the next frame (`set_race`).
                self.world = self.world.with_race(race);
            }
            Err(e) => {
                log::warn!("{e}");
                o.load_error = Some(e);
            }
        }
    }

    fn draw(&mut self, el: &ActiveEventLoop) {
        self.open_requested();
        let t = self.tick();
        if let Some(p) = self.pool.as_mut() {
            if let Some(st) = self.state.as_mut() {
                match p.draw(&st.gpu, &mut st.target, &st.window, t, &self.orbit) {
                    Ok(false) => {}
                    Ok(true) => el.exit(),
                    Err(e) => self.fail(el, e),
                }
            }
            return;
        }
        let mut scene = self.world.orbit_scene(t, &mut self.orbit);
        // "Follow": the orbit turns about the first selected boat instead of the fleet.
        if let Some(o) = self.state.as_ref().and_then(|s| s.hud.as_ref())
            && o.panels.follow
            && let Some(target) =
                crate::panels::follow_target(&self.world.race, o.scene_overlays.selected(), t)
        {
            self.orbit.target = target;
            scene.camera = self.orbit.camera();
        }
        // With a feed, its camera (mapped onto the race) replaces the orbit.
        if let (Some(f), Some(st)) = (self.feed.as_mut(), self.state.as_mut()) {
            let size = st.target.size();
            let wake = st.hud.as_ref().and_then(|o| o.wake());
            let format = st.target.format().unwrap_or(render::OFFSCREEN_FORMAT);
            let bounds = self.world.race_bounds;
            let played_s = self.started.elapsed().as_secs_f64();
            if let Err(e) = f.prepare(
                &st.gpu,
                &mut st.renderer,
                format,
                wake,
                bounds,
                size,
                played_s,
            ) {
                self.fail(el, e.to_string());
                return;
            }
            f.apply(&mut scene);
        }
        let Some(st) = self.state.as_mut() else {
            return;
        };
        let frame = match st.target.acquire(&st.gpu) {
            Acquired::Frame(f) => f,
            Acquired::Skip => return,
            Acquired::Failed(e) => return self.fail(el, e),
        };
        let view = frame.texture().create_view(&Default::default());
        let size = st.target.size();
        if let Some(o) = st.hud.as_mut() {
            let handle = self.feed.as_ref().and_then(|f| f.effects_handle()).cloned();
            let handle = handle.as_ref();
            o.apply_effects(&mut st.renderer, handle);
            // The open sea's body colour follows the Scene panel's water type.
            st.renderer.set_water_look(o.water_look());
            if let Some(feed) = self.feed.as_mut() {
                let look = o.water_look();
                if feed.water() != look {
                    feed.set_water(look);
                }
            }
            let ppp = st.window.scale_factor();
            let (race, r) = (&self.world.race, &mut st.renderer);
            let debrief = o.scene_overlays.debrief(&mut o.panels.debrief, race);
            o.scene_overlays
                .prepare(&st.gpu, r, (race, debrief), &scene, size, ppp);
            // The tier drawn, every setting, live (the governor's or the panel's pin), when it
            // or the feed's effect passes (built on its first frame) changed.
            o.follow_tier(self.tiers.tier(), &st.gpu, &mut st.renderer, handle, race);
        }
        // A failed frame is logged by the renderer; the window shows the next one.
        let report = st.renderer.render(&st.gpu, &view, size, &scene).ok();
        if let Some(r) = &report {
            log::debug!("frame: {} triangles", r.triangles);
        }
        // The governor: GPU time where measured, else the present interval; no change while
        // the user drags the view or a panel (the timeline's scrubber).
        let scrubbing = self.drag.is_some() || st.hud.as_ref().is_some_and(|o| o.wants_pointer());
        let now = self.started.elapsed().as_secs_f64();
        let gpu_ms = report.as_ref().and_then(|r| r.gpu_ms);
        // The change is applied before the next frame is drawn.
        if let Some(tier) = self.tiers.frame(now, gpu_ms, scrubbing) {
            log::info!("quality tier {}", tier.tier);
        }
        let race = &self.world.race;
        if let Some(o) = st.hud.as_mut() {
            if let Some(c) = o.tier_change.take() {
                self.tiers.answer(c);
            }
            o.panels.settings.tier = Some(self.tiers.panel());
            if let Some(r) = &report {
                o.record(r);
            }
            o.paint(
                &st.window,
                &st.gpu.device,
                &st.gpu.queue,
                frame.texture(),
                size,
                race,
            );
            if std::mem::take(&mut o.share_requested) {
                let folder = std::env::current_dir().unwrap_or_default();
                let t = o.panels.clock.time();
                let request = share_clip::ClipRequest::DESKTOP;
                let debrief = o.scene_overlays.debrief(&mut o.panels.debrief, race);
                let world = (&self.world, debrief);
                if let Err(e) = o.share_clip.start(world, t, &folder, request) {
                    o.share_clip.set_failed(e);
                }
            }
        }
        st.window.pre_present_notify();
        st.target.present(&st.gpu, frame);
        if let Some(o) = st.hud.as_mut()
            && o.frame_done()
        {
            // The smoke test's exit: save what the window showed, if asked (REGATTA_SCREENSHOT).
            let saved =
                o.save_screenshot(&st.window, &st.gpu, &mut st.renderer, &scene, size, race);
            if let Err(e) = saved {
                self.fail(el, e);
            }
            el.exit();
            return;
        }
        let playing = st
            .hud
            .as_ref()
            .map_or(self.clock.is_playing(), |o| o.panels.clock.is_playing());
        st.window.set_title(&format!(
            "Regatta: {} at t = {t:.0} s{}, quality {} ({})",
            race.name,
            if playing { "" } else { " (paused)" },
            self.tiers.tier(),
            if self.tiers.pinned().is_some() {
                "pinned"
            } else {
                "auto"
            }
        ));
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        if self.state.is_some() {
            return;
        }
        let attrs = Window::default_attributes()
            .with_title("Regatta")
            .with_inner_size(hud::window_size());
        let window = match el.create_window(attrs) {
            Ok(w) => Arc::new(w),
            Err(e) => return self.fail(el, format!("cannot open a window: {e}")),
        };
        let size = window.inner_size();
        match render::Gpu::for_window(window.clone(), size.width, size.height) {
            Ok((gpu, mut surface)) => {
                let setup = RaceSetup {
                    sea_water: self.water,
                    ..RaceSetup::new(Profile::Desktop)
                };
                let wake = setup.wake_or_none(&self.world.race);
                let renderer = setup.renderer(&gpu, surface.config.format, wake);
                // The tier is applied before the first frame is drawn (`draw`).
                log::info!("window on {}", gpu.describe());
                let hud = self.pool.is_none().then(|| {
                    let race = &self.world.race;
                    let fx = self.feed.is_some();
                    let mut o = hud::Hud::new(
                        &window,
                        &gpu.device,
                        &mut surface,
                        race,
                        race.name.clone(),
                        fx,
                    );
                    // The sliders start at the water the command line chose.
                    o.panels.settings.water_type = self.water.water_type.name().to_string();
                    o.panels.settings.water_depth_m = self.water.depth_m;
                    o.panels.settings.turbidity = self.water.turbidity_ntu;
                    o
                });
                let mut target = gfx::Window::default();
                target.first_surface(surface);
                self.state = Some(State {
                    window,
                    gpu,
                    target,
                    renderer,
                    hud,
                });
            }
            Err(e) => self.fail(el, format!("cannot draw into the window: {e}")),
        }
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        if let Some(st) = self.state.as_mut()
            && let Some(o) = st.hud.as_mut()
            && hud::handle_event(o, &st.window, &event)
        {
            return;
        }
        match event {
            WindowEvent::CloseRequested => el.exit(),
            WindowEvent::DroppedFile(path) => self.dropped.push(path),
            WindowEvent::Resized(s) => {
                if let Some(st) = self.state.as_mut() {
                    st.target.resize(&st.gpu, s.width, s.height);
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                let pressed = state == ElementState::Pressed;
                // A click without a drag on the scene selects the boat under it.
                if !pressed
                    && self
                        .press_at
                        .is_some_and(|(x, y)| (x - self.cursor.0).hypot(y - self.cursor.1) < 4.0)
                    && let Some(o) = self.state.as_mut().and_then(|s| s.hud.as_mut())
                {
                    o.scene_overlays.click([self.cursor.0, self.cursor.1]);
                }
                self.press_at = pressed.then_some(self.cursor);
                // In the pool, a press on a moving ball grabs the ball instead of the camera.
                let t = self.clock.time();
                let grabbed = self
                    .pool
                    .as_mut()
                    .is_some_and(|p| p.press(pressed, self.cursor, t));
                self.drag = (pressed && !grabbed).then_some(self.cursor);
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x, position.y);
                if let Some(p) = self.pool.as_mut() {
                    p.pointer_moved(self.cursor, self.clock.time());
                }
                if let Some((x, y)) = self.drag {
                    self.orbit.drag(position.x - x, position.y - y);
                    self.drag = Some(self.cursor);
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.orbit.zoom(steps);
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                match event.logical_key {
                    Key::Named(NamedKey::Space) => self.clock.toggle(),
                    Key::Named(NamedKey::ArrowRight) => {
                        self.clock.scrub_to(self.clock.time() + 10.0);
                    }
                    Key::Named(NamedKey::ArrowLeft) => {
                        self.clock.scrub_to(self.clock.time() - 10.0);
                    }
                    Key::Named(NamedKey::Escape) => el.exit(),
                    _ => {}
                }
            }
            WindowEvent::RedrawRequested => self.draw(el),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _el: &ActiveEventLoop) {
        if let Some(st) = &self.state {
            st.window.request_redraw();
        }
    }
}
