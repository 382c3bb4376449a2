//! The desktop window (`regatta`, `regatta run`): the embedded race and sea (or the files
//! given) under an orbiting camera. Left-drag orbits, the wheel zooms, space pauses, the arrow
//! keys step race time by ±10 s. Race time plays at real speed from the start and loops.
//!
//! winit 0.30's `ApplicationHandler`; the device comes from `render::Gpu::for_window`.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use clap::Args;
use glam::{DVec2, DVec3};
use render::{OrbitCamera, RenderOptions, Renderer};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::cli::inputs::{load_race, load_sea};
use crate::cli::render::{SceneKind, scene_at};
use crate::error::{CliError, CliResult};

pub mod feed;
pub mod overlay;
pub mod pool;
pub mod smoke;

#[derive(Debug, Args, Default)]
pub struct RunArgs {
    /// Race files (native JSON, GPX, CSV); the embedded sample race without it.
    #[arg(long, num_args = 1..)]
    pub race: Vec<PathBuf>,
    /// Sea file (JSON); the embedded default sea without it.
    #[arg(long)]
    pub sea: Option<PathBuf>,
    /// Which scene: the race, or the tiled pool (drag the green ball to make ripples).
    #[arg(long, value_enum, default_value_t)]
    pub scene: SceneKind,
    /// A recorded camera feed (replay folder or TUM RGB-D) as the background, the race on its
    /// table; `synth` for the built-in synthetic table (what `regatta` alone opens).
    #[arg(long, value_name = "DIR")]
    pub replay: Option<PathBuf>,
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
            replay: Some(PathBuf::from(feed::SYNTH)),
            ..RunArgs::default()
        }
    }
}

/// Open the window and run until it is closed.
pub fn run(a: RunArgs) -> CliResult {
    let sea = crate::cli::inputs::drawable_sea(load_sea(a.sea.as_ref())?);
    let race = load_race(&a.race)?;
    // A bad feed is refused before a window opens (file and line named).
    let feed = a.replay.as_deref().map(feed::FeedView::open).transpose()?;
    let pinned = a
        .tier
        .as_deref()
        .map(crate::tier_render::parse_tier)
        .transpose()?;
    let event_loop = EventLoop::new()
        .map_err(|e| CliError::new(format!("cannot open a window (no display?): {e}")))?;
    let (t0, t1) = race.time_span();
    let pool = (a.scene == SceneKind::Pool)
        .then(|| pool::PoolMode::new(a.sea.is_some().then(|| sea.clone())));
    let mut app = App {
        pool,
        feed,
        race,
        sea,
        span: (t0, t1.max(t0 + 1.0)),
        state: None,
        orbit: crate::cli::render::race_orbit(),
        clock: Clock {
            t: t0,
            playing: true,
            last: Instant::now(),
        },
        drag: None,
        cursor: (0.0, 0.0),
        error: None,
        tiers: crate::tier_control::TierControl::new(
            pinned.unwrap_or(quality::Tier::Ultra),
            pinned.is_some(),
        ),
        started: Instant::now(),
    };
    if app.pool.is_some() {
        app.orbit = pool::PoolMode::orbit();
    }
    event_loop
        .run_app(&mut app)
        .map_err(|e| CliError::new(format!("the window's event loop failed: {e}")))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// The scene the window draws at race time `t`: the race on the sea, the camera orbiting the
/// fleet's centre (`orbit` keeps the user's angle and distance, its target follows the fleet).
/// A function of `t` and the orbit alone, so playing to t and scrubbing to t draw the same frame.
pub fn race_scene(
    race: &race::Race,
    sea: &ocean::WaveSet,
    t: f64,
    orbit: &mut OrbitCamera,
) -> render::Scene {
    let mut scene = scene_at(race, sea, t, None);
    if !scene.boats.is_empty() {
        let c = scene.boats.iter().map(|b| b.position).sum::<DVec2>() / scene.boats.len() as f64;
        orbit.target = DVec3::new(c.x, 0.0, c.y);
    }
    scene.camera = orbit.camera();
    scene
}

/// The window's race renderer: still frames kept (the timeline paused, the camera still), the
/// race's wakes on. Tests that play frame by frame build theirs here too.
pub fn window_renderer(
    gpu: &render::Gpu,
    format: wgpu::TextureFormat,
    race: &race::Race,
) -> Renderer {
    let mut renderer = Renderer::new(
        gpu,
        format,
        RenderOptions {
            measure_gpu_time: false,
            keep_still_frames: true,
            ..Default::default()
        },
    );
    match crate::cli::render::race_wake(race) {
        Ok(w) => renderer.set_wake(Some(w)),
        Err(e) => log::warn!("{e}; drawing no wakes"),
    }
    renderer
}

/// Race time: plays at real speed, pauses, loops over the race's span.
struct Clock {
    t: f64,
    playing: bool,
    last: Instant,
}

struct State {
    window: Arc<Window>,
    gpu: render::Gpu,
    surface: render::gpu::SurfaceTarget,
    renderer: Renderer,
    /// The egui panels (timeline, leaderboard, overlay); `None` in the pool scene.
    overlay: Option<overlay::Overlay>,
}

struct App {
    /// `Some` with `--scene pool`: the pool replaces the race.
    pool: Option<pool::PoolMode>,
    /// `Some` with `--replay`: the feed's camera and image replace the orbit and the sky.
    feed: Option<feed::FeedView>,
    race: race::Race,
    sea: ocean::WaveSet,
    span: (f64, f64),
    state: Option<State>,
    orbit: OrbitCamera,
    clock: Clock,
    drag: Option<(f64, f64)>,
    cursor: (f64, f64),
    error: Option<CliError>,
    /// The quality governor: frame times in, the tier's renderer settings out.
    tiers: crate::tier_control::TierControl,
    started: Instant,
}

impl App {
    fn fail(&mut self, el: &ActiveEventLoop, msg: String) {
        self.error = Some(CliError::new(msg));
        el.exit();
    }

    fn tick(&mut self) {
        // With the panels, race time is the timeline's (play, scrub, speed).
        if let Some(o) = self.state.as_mut().and_then(|s| s.overlay.as_mut()) {
            self.clock.t = o.tick();
            self.clock.playing = o.panels.clock.is_playing();
            return;
        }
        let now = Instant::now();
        if self.clock.playing {
            self.clock.t += now.duration_since(self.clock.last).as_secs_f64();
        }
        self.clock.last = now;
        let (a, b) = self.span;
        if self.clock.t > b || self.clock.t < a {
            self.clock.t = a + (self.clock.t - a).rem_euclid(b - a);
        }
    }

    fn draw(&mut self, el: &ActiveEventLoop) {
        self.tick();
        if let Some(p) = self.pool.as_mut() {
            if let Some(st) = self.state.as_ref() {
                match p.draw(st, self.clock.t, &self.orbit) {
                    Ok(false) => {}
                    Ok(true) => el.exit(),
                    Err(e) => self.fail(el, e),
                }
            }
            return;
        }
        let mut scene = race_scene(&self.race, &self.sea, self.clock.t, &mut self.orbit);
        // With a feed, its camera (mapped onto the race) replaces the orbit.
        if let (Some(f), Some(st)) = (self.feed.as_mut(), self.state.as_mut()) {
            let size = [st.surface.config.width, st.surface.config.height];
            let wake = st.overlay.as_ref().and_then(|o| o.wake());
            let format = st.surface.config.format;
            if let Err(e) = f.prepare(&st.gpu, &mut st.renderer, format, wake, &scene, size) {
                self.fail(el, e.to_string());
                return;
            }
            f.apply(&mut scene);
        }
        let Some(st) = self.state.as_mut() else {
            return;
        };
        let frame = match st.surface.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                let (w, h) = (st.surface.config.width, st.surface.config.height);
                st.surface.resize(&st.gpu.device, w, h);
                return;
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return;
            }
            other => {
                let msg = format!("the window surface failed: {other:?}");
                self.fail(el, msg);
                return;
            }
        };
        let view = frame.texture.create_view(&Default::default());
        let size = [st.surface.config.width, st.surface.config.height];
        if let Some(o) = st.overlay.as_mut() {
            o.apply_effects(&mut st.renderer);
        }
        // A failed frame is logged by the renderer; the window shows the next one.
        let report = st.renderer.render(&st.gpu, &view, size, &scene).ok();
        if let Some(r) = &report {
            log::debug!("frame: {} triangles", r.triangles);
        }
        // The governor: GPU time where measured, else the present interval; no change while
        // the user drags the view or a panel (the timeline's scrubber).
        let scrubbing =
            self.drag.is_some() || st.overlay.as_ref().is_some_and(|o| o.wants_pointer());
        let now = self.started.elapsed().as_secs_f64();
        let gpu_ms = report.as_ref().and_then(|r| r.gpu_ms);
        if let Some(tier) = self.tiers.frame(now, gpu_ms, scrubbing) {
            log::info!("quality tier {}", tier.tier);
            tier.apply_to(&mut st.renderer);
        }
        if let Some(o) = st.overlay.as_mut() {
            if let Some(r) = &report {
                o.record(r);
            }
            o.paint(
                &st.window,
                &st.gpu.device,
                &st.gpu.queue,
                &frame.texture,
                size,
                &self.race,
            );
        }
        st.window.pre_present_notify();
        st.gpu.queue.present(frame);
        if let Some(o) = st.overlay.as_mut()
            && o.frame_done()
        {
            // The smoke test's exit: save what the window showed, if asked (REGATTA_SCREENSHOT).
            let saved = o.save_screenshot(
                &st.window,
                &st.gpu,
                &mut st.renderer,
                &scene,
                size,
                &self.race,
            );
            if let Err(e) = saved {
                self.fail(el, e);
            }
            el.exit();
            return;
        }
        st.window.set_title(&format!(
            "Regatta: {} at t = {:.0} s{}, quality {} ({})",
            self.race.name,
            self.clock.t,
            if self.clock.playing { "" } else { " (paused)" },
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
            .with_inner_size(overlay::window_size());
        let window = match el.create_window(attrs) {
            Ok(w) => Arc::new(w),
            Err(e) => return self.fail(el, format!("cannot open a window: {e}")),
        };
        let size = window.inner_size();
        match render::Gpu::for_window(window.clone(), size.width, size.height) {
            Ok((gpu, mut surface)) => {
                let mut renderer = window_renderer(&gpu, surface.config.format, &self.race);
                if self.tiers.pinned().is_some() {
                    crate::tier_render::TierRender::of(self.tiers.tier()).apply_to(&mut renderer);
                }
                log::info!("window on {}", gpu.describe());
                let overlay = self.pool.is_none().then(|| {
                    let title = self.race.name.clone();
                    overlay::Overlay::new(&window, &gpu.device, &mut surface, &self.race, title)
                });
                self.state = Some(State {
                    window,
                    gpu,
                    surface,
                    renderer,
                    overlay,
                });
            }
            Err(e) => self.fail(el, format!("cannot draw into the window: {e}")),
        }
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        if let Some(st) = self.state.as_mut()
            && let Some(o) = st.overlay.as_mut()
            && overlay::handle_event(o, &st.window, &event)
        {
            return;
        }
        match event {
            WindowEvent::CloseRequested => el.exit(),
            WindowEvent::Resized(s) => {
                if let Some(st) = self.state.as_mut() {
                    st.surface.resize(&st.gpu.device, s.width, s.height);
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                let pressed = state == ElementState::Pressed;
                // In the pool, a press on a moving ball grabs the ball instead of the camera.
                let grabbed = self
                    .pool
                    .as_mut()
                    .is_some_and(|p| p.press(pressed, self.cursor, self.clock.t));
                self.drag = (pressed && !grabbed).then_some(self.cursor);
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x, position.y);
                if let Some(p) = self.pool.as_mut() {
                    p.pointer_moved(self.cursor, self.clock.t);
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
                    Key::Named(NamedKey::Space) => self.clock.playing = !self.clock.playing,
                    Key::Named(NamedKey::ArrowRight) => self.clock.t += 10.0,
                    Key::Named(NamedKey::ArrowLeft) => self.clock.t -= 10.0,
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
