//! The desktop window (`regatta`, `regatta run`): a shell over the app's desktop profile
//! ([`App::desktop`]: the embedded race and sea, or the files given, under the orbit view or on
//! a camera feed's table). It opens the window and translates winit's events into
//! [`AppEvent`]s: the left button as one finger (a click selects a boat, a drag orbits: the
//! app's one tap threshold), the wheel, the keys, dropped files, and the panels' input through
//! egui-winit; each redraw hands the app the wall seconds since the last frame and the app draws
//! and presents. What the app asks of the window (its title, egui's cursor and clipboard,
//! quitting) is carried out here; nothing else is decided here.
//!
//! winit 0.30's `ApplicationHandler`; the device comes from the app's first window
//! (`core::gfx`). `--phone` opens the phone profile instead (`phone.rs`).

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use glam::DVec2;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key as WinitKey, NamedKey};
use winit::window::{Window, WindowId};

use crate::core::app::{App, AppEvent, DesktopStart, Key};
use crate::error::{AppError, AppResult};
use crate::hud::SceneChoice;
use crate::hud::touch::TouchAction;
use crate::setup::{RaceSetup, SceneKind};
use crate::wall_clock::Ticker;

pub mod phone;
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
            replay: Some(PathBuf::from(crate::core::feed::SYNTH)),
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
    let world = RaceSetup::load_world(&a.race, a.sea.as_ref())?;
    // A bad feed is refused before a window opens (file and line named).
    let mut feed = a
        .replay
        .as_deref()
        .map(crate::core::feed::FeedView::open)
        .transpose()?;
    let water = match feed.as_mut() {
        Some(f) => {
            f.set_water(a.water.look(f.water())?);
            f.water()
        }
        None => a.water.look(render::water_look::WaterLook::default())?,
    };
    let tier = a
        .tier
        .as_deref()
        .map(crate::tier_render::parse_tier)
        .transpose()?;
    let event_loop = event_loop()?;
    let pool = a.scene == SceneKind::Pool;
    let start = DesktopStart {
        feed,
        water,
        tier,
        scene: if pool {
            SceneChoice::Pool
        } else {
            SceneChoice::Race
        },
        pool_sea: (pool && a.sea.is_some()).then(|| (*world.given_sea).clone()),
    };
    let mut shell = Shell {
        app: App::desktop(world, start),
        window: None,
        egui: None,
        size: [1, 1],
        ticker: Ticker::default(),
        cursor: DVec2::ZERO,
        left: false,
        exit_after: smoke::ExitAfter::from_env(),
        error: None,
    };
    event_loop
        .run_app(&mut shell)
        .map_err(|e| AppError::new(format!("the window's event loop failed: {e}")))?;
    shell.error.map_or(Ok(()), Err)
}

/// The window's first size: 1280×720 points, or `REGATTA_WINDOW_SIZE=WxH` (physical pixels;
/// the smoke test keeps lavapipe's frames small with it).
pub fn window_size() -> winit::dpi::Size {
    let env = std::env::var("REGATTA_WINDOW_SIZE").ok();
    match env.as_deref().map(crate::setup::inputs::parse_frame_size) {
        Some(Ok((w, h))) => winit::dpi::PhysicalSize::new(w, h).into(),
        Some(Err(e)) => {
            log::warn!("REGATTA_WINDOW_SIZE: {e}; opening 1280x720");
            winit::dpi::LogicalSize::new(1280.0, 720.0).into()
        }
        None => winit::dpi::LogicalSize::new(1280.0, 720.0).into(),
    }
}

/// The wheel's turn in lines (up > 0); a touchpad's pixels count 40 to a line.
fn wheel_steps(delta: MouseScrollDelta) -> f64 {
    match delta {
        MouseScrollDelta::LineDelta(_, y) => f64::from(y),
        MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
    }
}

/// winit's event loop, or the sentence saying why there is no window.
fn event_loop() -> AppResult<EventLoop<()>> {
    EventLoop::new().map_err(|e| {
        AppError::new(format!(
            "cannot open a window (no display?): {}",
            smoke::window_error(&e)
        ))
    })
}

/// Whether egui input translated on `held` (the window's egui-winit state's context) would
/// miss the app's `current` context (`App::egui_context`): one is a different context (egui
/// compares contexts by identity), or only one exists.
pub fn egui_input_stale(held: Option<&egui::Context>, current: Option<&egui::Context>) -> bool {
    held != current
}

/// Translates winit's events into the app's.
struct Shell {
    app: App,
    window: Option<Arc<Window>>,
    /// The panels' input from winit (egui-winit), on the app's egui context.
    egui: Option<egui_winit::State>,
    /// The window's size, physical pixels.
    size: [u32; 2],
    ticker: Ticker,
    /// The pointer, physical pixels.
    cursor: DVec2,
    /// The left button is down (the app's one finger).
    left: bool,
    exit_after: smoke::ExitAfter,
    error: Option<AppError>,
}

/// The app's key for a winit key, where the app has one.
fn key_of(key: &WinitKey) -> Option<Key> {
    Some(match key {
        WinitKey::Named(NamedKey::Space) => Key::Space,
        WinitKey::Named(NamedKey::ArrowLeft) => Key::Left,
        WinitKey::Named(NamedKey::ArrowRight) => Key::Right,
        WinitKey::Named(NamedKey::Home) => Key::Home,
        WinitKey::Named(NamedKey::PageUp) => Key::PageUp,
        WinitKey::Named(NamedKey::PageDown) => Key::PageDown,
        WinitKey::Named(NamedKey::Escape) => Key::Escape,
        WinitKey::Character(c) => Key::Char(c.chars().next()?),
        _ => return None,
    })
}

impl Shell {
    fn fail(&mut self, el: &ActiveEventLoop, msg: String) {
        self.error = Some(AppError::new(msg));
        el.exit();
    }

    fn finger(&mut self, action: TouchAction) {
        let c = self.cursor.as_vec2().to_array();
        self.app.on(AppEvent::touch(action, &[c]));
    }

    /// The panels' input translator (egui-winit) on the app's egui context now: the app makes
    /// a new context with each device (a lost GPU rebuilt on OpenGL ES), and a translator kept
    /// on the old one would read and write a context nothing draws with.
    fn follow_egui_context(&mut self, window: &Window) {
        let current = self.app.egui_context();
        let held = self.egui.as_ref().map(egui_winit::State::egui_ctx);
        if !egui_input_stale(held, current.as_ref()) {
            return;
        }
        self.egui = current.map(|ctx| {
            egui_winit::State::new(
                ctx,
                egui::ViewportId::ROOT,
                window,
                Some(window.scale_factor() as f32),
                None,
                None,
            )
        });
    }

    fn redraw(&mut self, el: &ActiveEventLoop) {
        let Some(window) = self.window.clone() else {
            return;
        };
        if let Some(e) = self.egui.as_mut() {
            self.app
                .on(AppEvent::PanelInput(e.take_egui_input(&window)));
        }
        self.app.frame(self.ticker.tick());
        // A lost device was rebuilt in that frame with a new egui context.
        self.follow_egui_context(&window);
        if let Some(e) = self.app.take_failure() {
            return self.fail(el, e);
        }
        if let (Some(e), Some(out)) = (self.egui.as_mut(), self.app.take_platform_output()) {
            e.handle_platform_output(&window, out);
        }
        window.set_title(&self.app.title());
        if self.exit_after.frame_done() {
            // The smoke test's exit: save what the window showed, if asked.
            if let Err(e) = smoke::save_screenshot(&mut self.app, self.size) {
                return self.fail(el, e);
            }
            el.exit();
        }
        if self.app.quit_requested() {
            el.exit();
        }
    }
}

impl ApplicationHandler for Shell {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        let window = match &self.window {
            Some(w) => w.clone(),
            None => {
                let attrs = Window::default_attributes()
                    .with_title("Regatta")
                    .with_inner_size(window_size());
                match el.create_window(attrs) {
                    Ok(w) => Arc::new(w),
                    Err(e) => return self.fail(el, format!("cannot open a window: {e}")),
                }
            }
        };
        let s = window.inner_size();
        self.size = [s.width.max(1), s.height.max(1)];
        self.window = Some(window.clone());
        self.app.on(AppEvent::Density(window.scale_factor() as f32));
        self.app.on(AppEvent::Resumed);
        let surface_window = window.clone();
        self.app.on(AppEvent::WindowCreated {
            surface: Some(Box::new(move |i: &wgpu::Instance| {
                i.create_surface(surface_window.clone())
                    .map_err(|e| e.to_string())
            })),
            size: self.size,
        });
        if self.app.egui_context().is_none() {
            return self.fail(el, "cannot draw into the window: no GPU device".into());
        }
        if let Some(gpu) = self.app.describe_gpu() {
            log::info!("window on {gpu}");
        }
        self.follow_egui_context(&window);
        self.ticker.stop();
    }

    fn suspended(&mut self, _el: &ActiveEventLoop) {
        self.app.on(AppEvent::Paused);
        self.app.on(AppEvent::WindowDestroyed);
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        // The panels see every event; the app decides which reach the scene.
        if let (Some(e), Some(w)) = (self.egui.as_mut(), self.window.as_ref()) {
            let _ = e.on_window_event(w, &event);
        }
        match event {
            WindowEvent::CloseRequested => el.exit(),
            WindowEvent::DroppedFile(path) => self.app.on(AppEvent::FileDropped(path)),
            WindowEvent::Resized(s) => {
                self.size = [s.width.max(1), s.height.max(1)];
                self.app.on(AppEvent::Resized(self.size));
            }
            WindowEvent::ScaleFactorChanged { scale_factor, .. } => {
                self.app.on(AppEvent::Density(scale_factor as f32));
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => match (state, self.left) {
                (ElementState::Pressed, false) => {
                    self.left = true;
                    self.finger(TouchAction::Down(0));
                }
                (ElementState::Released, true) => {
                    self.left = false;
                    self.finger(TouchAction::Up(0));
                }
                _ => {}
            },
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = DVec2::new(position.x, position.y);
                if self.left {
                    self.finger(TouchAction::Move);
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = wheel_steps(delta);
                let px = self.cursor.as_vec2().to_array();
                self.app.on(AppEvent::Wheel { steps, px });
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                if let Some(key) = key_of(&event.logical_key) {
                    self.app.on(AppEvent::Key(key));
                    if self.app.quit_requested() {
                        el.exit();
                    }
                }
            }
            WindowEvent::RedrawRequested => self.redraw(el),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _el: &ActiveEventLoop) {
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }
}
