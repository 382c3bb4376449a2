//! Android entry point (native activity, android-activity 0.6).
//!
//! Lifecycle (wgpu issue 2302: a surface must not outlive its `ANativeWindow`): the device is
//! made once, on the first `InitWindow`; each `InitWindow` creates a surface for the new window
//! and each `TerminateWindow` drops it before returning. In the background (`Pause`) nothing is
//! drawn and the race clock stops; the clock and the view survive pause, rotation and a new
//! window because they live in [`App`], not in the surface.
//!
//! AR: [`ArCore`] (`ar::arcore::ffi`, host-tested against `crates/arcore_sim`) loads
//! `libarcore_sdk_c.so` with libloading and the pure session state machine
//! (`ar::arcore::session`) decides what happens; the Java calls go through
//! [`jni_calls::AndroidJni`]; where the library is missing (an APK
//! built without `--arcore-aar`) the app says so and runs the 3D race view without the camera.
//! Each frame `frame.rs` reads ARCore's frame into an `ar::CameraFrame`; once a tap has put the
//! course on a detected plane, [`ar_view`] draws the race over the camera image with ARCore's
//! camera and light. Until then the camera image alone is shown (where ARCore runs), so the user
//! sees the table to tap.
//!
//! The egui overlay of the desktop (`crate::overlay`) is drawn over the scene: the race panels'
//! timeline scrubber (which owns race time), and the phone's bar: the scene toggle (race |
//! pool), the record button and the session's banner (`overlay::banner`). Touch
//! (`overlay::touch`): every gesture goes to egui; one that began outside the panels also goes
//! to the scene: a tap places the course (or the pool), two fingers scale and turn it (or,
//! before it is placed, zoom and turn the 3D view), one finger orbits the 3D view or, in the
//! pool, drags a moving ball (`crate::pool_play`, as the desktop's mouse does). The volume-up
//! key also starts and stops a recording.

use std::sync::Arc;
use std::time::{Duration, Instant};

use android_activity::input::{InputEvent, KeyAction, Keycode, MotionAction, MotionEvent};
use android_activity::{AndroidApp, InputStatus, MainEvent, PollEvent};
use ar::FrameSource;
use ar::arcore::ffi::{ArCore, DisplayCamera};
use ar::arcore::{CoursePlacement, Event, SessionState, TwoFingerGesture};
use glam::{DVec2, DVec3};
use render::effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use render::pool::{PoolFrame, PoolRenderer, PoolSettings, PoolView};
use render::{Camera, OrbitCamera, RenderOptions, Renderer};
use ui::{RegattaUi, TimelineEvent};

use crate::cli::render::scene_at;
use crate::overlay::banner::{ArStatus, Tone, banner};
use crate::overlay::touch::{Finger, Touch, TouchAction, TouchInput, over_egui};
use crate::overlay::{EguiPainter, SceneChoice, phone_bar, race_panels};
use crate::pool_play::PoolPlay;

mod ar_view;
mod jni_calls;

// std's `_Unwind_*` come from the `unwinding` crate (see app/Cargo.toml); naming the crate links it.
use unwinding as _;

#[unsafe(no_mangle)]
fn android_main(app: AndroidApp) {
    android_logger::init_once(
        android_logger::Config::default().with_max_level(log::LevelFilter::Info),
    );
    log::info!("regatta: android_main started");
    let mut state = match App::new(&app) {
        Ok(s) => s,
        Err(e) => {
            log::error!("regatta: {e}");
            return;
        }
    };
    let mut quit = false;
    while !quit {
        let timeout = if state.visible() {
            Some(Duration::ZERO)
        } else {
            None
        };
        app.poll_events(timeout, |event| {
            if let PollEvent::Main(main) = event {
                quit = state.on_main_event(&app, main);
            }
        });
        state.handle_input(&app);
        if state.visible() {
            state.draw();
        }
    }
    log::info!("regatta: android_main ends");
}

/// The device, made on the first window, the surface of the current window, and what draws
/// into it.
struct Graphics {
    gpu: render::Gpu,
    surface: Option<render::gpu::SurfaceTarget>,
    /// The race: plain 3D until the course stands on the table, then with the effect passes
    /// over the camera image (`race_effects`, built on the first such frame).
    race: Renderer,
    race_effects: Option<EffectsHandle>,
    /// The camera image alone (effect passes, the sea taken out): behind the pool, and before
    /// anything is placed.
    backdrop: Option<(Renderer, EffectsHandle)>,
    pool: Option<PoolRenderer>,
    /// (frame, placement) last uploaded to `race_effects` and to `backdrop`.
    race_upload: Option<(u64, CoursePlacement)>,
    backdrop_upload: Option<u64>,
    egui: EguiPainter,
}

/// The scene is drawn at this fraction of the screen per side and stretched onto it (the
/// panels are painted at full resolution over it). From the budget bench (docs/phone.md, "On a
/// phone"): at ½ the Pixel 2 XL reaches 60 fps on paper, at full size about 17; not yet
/// measured on a phone.
const PHONE_RENDER_SCALE: f64 = 0.5;

/// A renderer for the surface's `format`, with the race's wakes.
fn fresh_renderer(
    gpu: &render::Gpu,
    wake: Option<Arc<ocean::wake::Wake>>,
    format: wgpu::TextureFormat,
) -> Renderer {
    let mut renderer = Renderer::new(
        gpu,
        format,
        RenderOptions {
            measure_gpu_time: false,
            render_scale: PHONE_RENDER_SCALE,
            ..Default::default()
        },
    );
    renderer.set_wake(wake);
    renderer
}

/// Takes the sea's place in the backdrop renderer: only the camera image is drawn.
struct NoSea;

impl render::Pass for NoSea {
    fn name(&self) -> &'static str {
        "water"
    }
    fn condition(&self) -> &'static str {
        "never: the camera image alone, behind the pool or before anything is placed"
    }
    fn plan(&self, _: &render::frame::FrameContext) -> Result<String, String> {
        Err("no sea in the camera-image backdrop".into())
    }
    fn prepare(&mut self, _: &render::Gpu, _: &render::frame::FrameContext) {}
    fn draw(&self, _: &mut wgpu::RenderPass<'_>) -> u64 {
        0
    }
}

/// A touch that may become a tap: where and when the finger went down.
const TAP_MAX_PX: f64 = 20.0;
const TAP_MAX_S: f64 = 0.3;

/// The world of the backdrop: AR metres as they are.
const AR_AS_IS: CoursePlacement = CoursePlacement {
    anchor: DVec3::ZERO,
    yaw: 0.0,
    course_to_table: 1.0,
};

struct App {
    race: race::Race,
    sea: ocean::WaveSet,
    /// The race panels (their clock owns race time) and the timeline's mark roundings.
    panels: RegattaUi,
    events: Vec<TimelineEvent>,
    /// The pool's time, seconds: plays while the app is in the foreground.
    pool_t: f64,
    last_tick: Instant,
    started: Instant,
    scene: SceneChoice,
    orbit: OrbitCamera,
    pool_orbit: OrbitCamera,
    pool: PoolPlay,
    pool_placement: Option<CoursePlacement>,
    graphics: Option<Graphics>,
    resumed: bool,
    ar: ArCore,
    session: SessionState,
    /// The last message the session asked to tell (the camera is busy).
    note: Option<&'static str>,
    touch: TouchInput,
    /// The root ui's rect left free by the panels in the last frame (egui points).
    ui_free: egui::Rect,
    /// One-finger drag start (pixels), or the two-finger gesture.
    drag: Option<DVec2>,
    pinch: Option<TwoFingerGesture>,
    touch_down: Option<(DVec2, Instant)>,
    /// The finger holds a pool ball.
    holding_ball: bool,
    ar_view: ar_view::ArView,
    /// Display rotation (`Surface.ROTATION_*`) and the geometry last given to ARCore.
    rotation: i32,
    geometry_set: Option<(i32, u32, u32)>,
    data_dir: Option<std::path::PathBuf>,
}

impl App {
    fn new(app: &AndroidApp) -> Result<Self, String> {
        let sea = crate::cli::inputs::load_sea(None).map_err(|e| e.to_string())?;
        let race = crate::cli::inputs::load_race(&[]).map_err(|e| e.to_string())?;
        let mut panels = RegattaUi::new(crate::overlay::initial_clock(&race), Vec::new());
        // The phone's screen is small: the timeline and the bar; the leaderboard behind its
        // toggle in the timeline's header (it would cover the bar on an upright phone), no frame
        // statistics.
        panels.show_perf = false;
        panels.show_leaderboard = false;
        Ok(Self {
            events: ui::timeline_events(&race),
            panels,
            race,
            sea,
            pool_t: 0.0,
            last_tick: Instant::now(),
            started: Instant::now(),
            scene: SceneChoice::Race,
            orbit: crate::cli::render::race_orbit(),
            pool_orbit: PoolPlay::orbit(),
            pool: PoolPlay::new(None),
            pool_placement: None,
            graphics: None,
            resumed: false,
            ar: ArCore::load(Box::new(jni_calls::AndroidJni::new(app))),
            session: SessionState::Start,
            note: None,
            touch: TouchInput::new(1.0),
            ui_free: egui::Rect::EVERYTHING,
            drag: None,
            pinch: None,
            touch_down: None,
            holding_ball: false,
            ar_view: ar_view::ArView::default(),
            rotation: 0,
            geometry_set: None,
            data_dir: None,
        })
    }

    fn visible(&self) -> bool {
        self.resumed && self.graphics.as_ref().is_some_and(|g| g.surface.is_some())
    }

    /// Physical pixels per egui point: the display's density over Android's 160 dpi baseline.
    fn read_density(&mut self, app: &AndroidApp) {
        let dpi = app.config().density().unwrap_or(160);
        self.touch.pixels_per_point = (dpi as f32 / 160.0).max(0.5);
    }

    /// Returns true when the app must end.
    fn on_main_event(&mut self, app: &AndroidApp, event: MainEvent<'_>) -> bool {
        match event {
            MainEvent::InitWindow { .. } => {
                self.data_dir = app.internal_data_path();
                self.rotation = self.ar.display_rotation();
                self.read_density(app);
                self.attach_window(app);
            }
            // Drop the surface while its window still exists (wgpu issue 2302).
            MainEvent::TerminateWindow { .. } => {
                if let Some(g) = self.graphics.as_mut() {
                    g.surface = None;
                }
            }
            MainEvent::WindowResized { .. } | MainEvent::ConfigChanged { .. } => {
                self.rotation = self.ar.display_rotation();
                self.read_density(app);
                if let (Some(g), Some(w)) = (self.graphics.as_mut(), app.native_window())
                    && let Some(s) = g.surface.as_mut()
                {
                    s.resize(
                        &g.gpu.device,
                        w.width().max(1) as u32,
                        w.height().max(1) as u32,
                    );
                }
            }
            MainEvent::Resume { .. } => {
                self.resumed = true;
                // Time in the background does not count.
                self.last_tick = Instant::now();
                let loaded = self.ar.is_loaded();
                self.session_event(Event::AppResumed {
                    library_loaded: loaded,
                });
            }
            MainEvent::Pause => {
                self.resumed = false;
                if self.ar_view.recorder.is_some() {
                    self.ar_view.toggle_recording(None);
                }
                self.session_event(Event::AppPaused);
            }
            MainEvent::Destroy => return true,
            _ => {}
        }
        false
    }

    /// Steps the AR session and carries out what it asks for (a fall-back also closes the
    /// session: paused, destroyed off this thread).
    fn session_event(&mut self, event: Event) {
        let before = self.session;
        let told = self.ar.drive(&mut self.session, event);
        if self.session != before || told.note.is_some() {
            self.note = told.note;
        }
    }

    fn attach_window(&mut self, app: &AndroidApp) {
        let Some(window) = app.native_window() else {
            return;
        };
        let (w, h) = (window.width().max(1) as u32, window.height().max(1) as u32);
        let raw_window = wgpu::rwh::RawWindowHandle::AndroidNdk(
            wgpu::rwh::AndroidNdkWindowHandle::new(window.ptr().cast()),
        );
        let raw_display =
            wgpu::rwh::RawDisplayHandle::Android(wgpu::rwh::AndroidDisplayHandle::new());
        match self.graphics.as_mut() {
            Some(g) => {
                // SAFETY: the surface is dropped on TerminateWindow, before the window goes.
                let surface = unsafe {
                    g.gpu
                        .instance
                        .create_surface_unsafe(wgpu::SurfaceTargetUnsafe::RawHandle {
                            raw_display_handle: Some(raw_display),
                            raw_window_handle: raw_window,
                        })
                };
                match surface {
                    Ok(surface) => {
                        // The last window's configuration (format and egui's view format) so
                        // every renderer made for it still fits.
                        let mut config = g
                            .surface
                            .as_ref()
                            .map(|s| s.config.clone())
                            .unwrap_or_else(|| {
                                surface
                                    .get_default_config(&g.gpu.adapter, w, h)
                                    .expect("the adapter presented to the first window")
                            });
                        config.width = w;
                        config.height = h;
                        surface.configure(&g.gpu.device, &config);
                        g.surface = Some(render::gpu::SurfaceTarget { surface, config });
                    }
                    Err(e) => log::error!("regatta: cannot create the window surface: {e}"),
                }
            }
            None => {
                // SAFETY: as above.
                match unsafe { render::Gpu::for_raw_window(raw_display, raw_window, w, h) } {
                    Ok((gpu, mut surface)) => {
                        let wake = crate::cli::render::race_wake(&self.race)
                            .map_err(|e| log::warn!("regatta: {e}; drawing no wakes"))
                            .ok();
                        log::info!("regatta: drawing on {}", gpu.describe());
                        // Camera images above the GPU's largest texture are halved to fit.
                        self.ar
                            .set_max_image_side(gpu.device.limits().max_texture_dimension_2d);
                        let view_formats = gpu
                            .adapter
                            .get_downlevel_capabilities()
                            .flags
                            .contains(wgpu::DownlevelFlags::SURFACE_VIEW_FORMATS);
                        let egui = EguiPainter::new(&gpu.device, &mut surface, view_formats);
                        self.graphics = Some(Graphics {
                            race: fresh_renderer(&gpu, wake, surface.config.format),
                            race_effects: None,
                            backdrop: None,
                            pool: None,
                            race_upload: None,
                            backdrop_upload: None,
                            egui,
                            gpu,
                            surface: Some(surface),
                        });
                    }
                    Err(e) => log::error!("regatta: {e}"),
                }
            }
        }
    }

    /// Touch goes to egui; a gesture that began outside the panels goes to the scene too.
    /// Volume-up toggles recording.
    fn handle_input(&mut self, app: &AndroidApp) {
        let Ok(mut iter) = app.input_events_iter() else {
            return;
        };
        let ctx = self.graphics.as_ref().map(|g| g.egui.ctx.clone());
        loop {
            let more = iter.next(|event| match event {
                InputEvent::KeyEvent(k) if k.key_code() == Keycode::VolumeUp => {
                    if k.action() == KeyAction::Down {
                        self.ar_view.toggle_recording(self.data_dir.as_deref());
                    }
                    InputStatus::Handled
                }
                InputEvent::MotionEvent(m) => {
                    if let Some(touch) = touch_of(m) {
                        let free = self.ui_free;
                        let over_ui = |p| ctx.as_ref().is_some_and(|c| over_egui(c, free, p));
                        if self.touch.on_touch(&touch, over_ui) {
                            self.scene_touch(&touch);
                        }
                    }
                    InputStatus::Handled
                }
                _ => InputStatus::Unhandled,
            });
            if !more {
                break;
            }
        }
    }

    /// A touch on the scene: tap places, one finger orbits (or drags a pool ball), two fingers
    /// pinch and twist what stands on the table (else zoom and turn the 3D view).
    fn scene_touch(&mut self, touch: &Touch) {
        let pts: Vec<DVec2> = touch
            .fingers
            .iter()
            .map(|f| DVec2::new(f64::from(f.px[0]), f64::from(f.px[1])))
            .collect();
        let pool = self.scene == SceneChoice::Pool;
        match (touch.action, pts.as_slice()) {
            (TouchAction::Down(_), [p]) => {
                self.touch_down = Some((*p, Instant::now()));
                self.holding_ball = pool && self.pool.press(true, p.to_array(), self.pool_t);
                self.drag = (!self.holding_ball).then_some(*p);
            }
            (TouchAction::PointerDown(_), [a, b, ..]) => {
                self.release_ball();
                self.drag = None;
                self.touch_down = None;
                self.pinch = Some(TwoFingerGesture::new(*a, *b));
            }
            (TouchAction::Move, [p]) => {
                if self.holding_ball {
                    self.pool.pointer_moved(p.to_array(), self.pool_t);
                } else if let Some(d) = self.drag.replace(*p) {
                    let delta = *p - d;
                    self.active_orbit().drag(delta.x, delta.y);
                }
            }
            (TouchAction::Move, [a, b, ..]) => {
                if let Some(g) = self.pinch.as_mut() {
                    let (pinch, twist) = g.update(*a, *b);
                    self.gesture(pinch, twist);
                }
            }
            (TouchAction::Up(_), [p]) => {
                if let Some((down, at)) = self.touch_down.take()
                    && !self.holding_ball
                    && (*p - down).length() < TAP_MAX_PX
                    && at.elapsed().as_secs_f64() < TAP_MAX_S
                {
                    self.tap(*p);
                }
                self.end_gesture();
            }
            (TouchAction::Up(_) | TouchAction::Cancel, _) => self.end_gesture(),
            _ => {}
        }
    }

    fn release_ball(&mut self) {
        if self.holding_ball {
            self.pool.press(false, [0.0; 2], self.pool_t);
            self.holding_ball = false;
        }
    }

    fn end_gesture(&mut self) {
        self.release_ball();
        self.drag = None;
        self.pinch = None;
        self.touch_down = None;
    }

    fn active_orbit(&mut self) -> &mut OrbitCamera {
        match self.scene {
            SceneChoice::Race => &mut self.orbit,
            SceneChoice::Pool => &mut self.pool_orbit,
        }
    }

    /// Two fingers: scale by `pinch` and turn by `twist` what stands on the table, or zoom and
    /// turn the 3D view.
    fn gesture(&mut self, pinch: f64, twist: f64) {
        let play_area = scene_at(&self.race, &self.sea, self.race_time(), None).play_area;
        let (placed, zoom) = match self.scene {
            SceneChoice::Race => (self.ar_view.placement.as_mut(), (5.0, 5000.0)),
            SceneChoice::Pool => (self.pool_placement.as_mut(), (0.5, 30.0)),
        };
        match (placed, self.scene) {
            (Some(p), SceneChoice::Race) => {
                let pivot = ar_view::course_pivot(play_area, ArConfig::default().table_depth);
                p.apply_gesture_about(pivot, pinch, twist);
            }
            // The pool's origin is its placement's anchor: it scales and turns about it.
            (Some(p), SceneChoice::Pool) => p.apply_gesture(pinch, twist),
            (None, _) => {
                let o = self.active_orbit();
                o.distance = (o.distance / pinch).clamp(zoom.0, zoom.1);
                o.yaw += twist;
            }
        }
    }

    /// A tap on the scene: stands the course (or the pool) on the table under the finger.
    fn tap(&mut self, px: DVec2) {
        let Some(point) = self.ar_view.hit(px, self.view_size()) else {
            return;
        };
        match self.scene {
            SceneChoice::Race => {
                let play_area = scene_at(&self.race, &self.sea, self.race_time(), None).play_area;
                let depth = ArConfig::default().table_depth;
                self.ar_view.place_course(point, play_area, depth);
            }
            SceneChoice::Pool => {
                self.pool_placement = Some(ar_view::ArView::place_pool(self.pool_placement, point));
            }
        }
    }

    fn race_time(&self) -> f64 {
        self.panels.clock.time()
    }

    /// The window's size in pixels (1 × 1 without one).
    fn view_size(&self) -> [u32; 2] {
        self.graphics
            .as_ref()
            .and_then(|g| g.surface.as_ref())
            .map_or([1, 1], |s| [s.config.width, s.config.height])
    }

    /// Steps ARCore: display geometry when it changed, `ArSession_update`, then the frame.
    fn update_ar(&mut self) {
        if !self.session.is_running() {
            return;
        }
        let [w, h] = self.view_size();
        let geometry = (self.rotation, w, h);
        if self.geometry_set != Some(geometry) {
            self.ar.set_display_geometry(self.rotation, w, h);
            self.geometry_set = Some(geometry);
        }
        if let Some(answer) = self.ar.update() {
            self.session_event(answer);
            return;
        }
        match self.ar.next_frame() {
            Ok(Some(frame)) => self.ar_view.on_frame(frame, self.ar.view.as_ref()),
            Ok(None) => {}
            Err(e) => log::warn!("regatta: {e}"),
        }
    }

    fn draw(&mut self) {
        let now = Instant::now();
        let dt = now.duration_since(self.last_tick).as_secs_f64();
        self.last_tick = now;
        self.panels.clock.advance(dt);
        self.pool_t += dt;
        self.update_ar();
        if let Some(mut g) = self.graphics.take() {
            self.draw_with(&mut g);
            self.graphics = Some(g);
        }
    }

    fn draw_with(&mut self, g: &mut Graphics) {
        let Some(s) = g.surface.as_mut() else { return };
        let frame = match s.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                let (w, h) = (s.config.width, s.config.height);
                s.resize(&g.gpu.device, w, h);
                return;
            }
            other => {
                log::debug!("regatta: no surface texture this frame: {other:?}");
                return;
            }
        };
        let size = [s.config.width, s.config.height];
        let format = s.config.format;
        let target = frame.texture.create_view(&Default::default());
        match self.scene {
            SceneChoice::Race => self.draw_race(g, &target, size, format),
            SceneChoice::Pool => self.draw_pool(g, &target, size, format),
        }
        self.draw_overlay(g, &frame.texture, size);
        g.gpu.queue.present(frame);
    }

    /// ARCore's display camera in AR metres, with the latest frame, when both exist.
    fn ar_frame(&self) -> Option<(&DisplayCamera, &ar::CameraFrame)> {
        Some((self.ar.view.as_ref()?, self.ar_view.frame.as_ref()?))
    }

    /// The camera image alone into `target`; false when there is none.
    fn draw_backdrop(
        &self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) -> bool {
        let Some((view, frame)) = self.ar_frame() else {
            return false;
        };
        let seq = self.ar_view.frame_seq;
        if g.backdrop_upload != Some(seq) {
            let background = match ar_view::ArView::background(&AR_AS_IS, frame) {
                Ok(b) => b,
                Err(e) => {
                    log::warn!("regatta: {e}");
                    return false;
                }
            };
            match &g.backdrop {
                Some((_, handle)) => handle.set_camera_frame(&g.gpu, background),
                None => {
                    let mut r = fresh_renderer(&g.gpu, None, format);
                    let handle = add_effect_passes(&mut r, &g.gpu, ArConfig::default(), background);
                    r.replace_pass("water", Box::new(NoSea));
                    g.backdrop = Some((r, handle));
                }
            }
            g.backdrop_upload = Some(seq);
        }
        let mut scene = scene_at(&self.race, &self.sea, self.race_time(), None);
        scene.boats.clear();
        scene.marks.clear();
        scene.camera = Camera::from_view_projection(view.view, view.projection_gl);
        if let Some((r, _)) = g.backdrop.as_mut() {
            // A failed frame is logged by the renderer; the next one tries again.
            let _ = r.render(&g.gpu, target, size, &scene);
        }
        true
    }

    fn draw_race(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) {
        let mut scene = scene_at(&self.race, &self.sea, self.race_time(), None);
        if !scene.boats.is_empty() {
            let c =
                scene.boats.iter().map(|b| b.position).sum::<DVec2>() / scene.boats.len() as f64;
            self.orbit.target = DVec3::new(c.x, 0.0, c.y);
        }
        scene.camera = self.orbit.camera();
        let Some(p) = self.ar_view.placement else {
            // Not placed: the camera image where ARCore runs (to see the table), else 3D.
            if !self.draw_backdrop(g, target, size, format) {
                let _ = g.race.render(&g.gpu, target, size, &scene);
            }
            return;
        };
        // On the table: ARCore's camera and light, the camera image behind.
        if let Some((view, frame)) = self.ar_frame() {
            scene.camera = ar_view::ArView::camera(&p, view);
            if let Some(l) = view.light_towards {
                scene.sun = ar_view::ArView::sun(&p, l);
            }
            let min_len = ar_view::ArView::boat_length(&p);
            for b in &mut scene.boats {
                b.length = b.length.max(min_len);
            }
            let upload = (self.ar_view.frame_seq, p);
            if g.race_upload != Some(upload) {
                match ar_view::ArView::background(&p, frame) {
                    Ok(background) => match &g.race_effects {
                        Some(handle) => handle.set_camera_frame(&g.gpu, background),
                        None => {
                            g.race_effects = Some(add_effect_passes(
                                &mut g.race,
                                &g.gpu,
                                ArConfig::default(),
                                background,
                            ));
                        }
                    },
                    Err(e) => log::warn!("regatta: {e}"),
                }
                g.race_upload = Some(upload);
            }
        }
        let _ = g.race.render(&g.gpu, target, size, &scene);
    }

    fn draw_pool(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) {
        let settings = PoolSettings::default();
        let mut view = PoolView {
            camera: self.pool_orbit.camera(),
            ..PoolView::default_desktop(size)
        };
        let backdrop = self.draw_backdrop(g, target, size, format);
        if let (true, Some(place), Some((display, _))) =
            (backdrop, self.pool_placement, self.ar_frame())
        {
            view = PoolView {
                camera: Camera::from_view_projection(display.view, display.projection_gl),
                model: PoolView::standing_on(place.race_to_ar(), &self.pool.scene, &settings),
                size,
                over_camera_image: true,
            };
        } else if backdrop {
            // The camera image is shown until the pool is placed.
            self.pool.view = None;
            return;
        }
        let frame = PoolFrame::new(&self.pool.scene, self.pool_t, &view, &settings);
        g.pool
            .get_or_insert_with(|| PoolRenderer::new(&g.gpu, format, settings))
            .render(&g.gpu, target, &frame);
        self.pool.view = Some(view);
    }

    /// The panels (race only), the phone's bar and the banner over the frame.
    fn draw_overlay(&mut self, g: &mut Graphics, texture: &wgpu::Texture, size: [u32; 2]) {
        let placed = match self.scene {
            SceneChoice::Race => self.ar_view.placement.is_some(),
            SceneChoice::Pool => self.pool_placement.is_some(),
        };
        let message = banner(&ArStatus {
            session: self.session,
            tracking_hint: self.ar_view.hint,
            has_frame: self.ar_view.frame.is_some(),
            placed,
            what: self.scene.noun(),
            note: self.note,
        });
        let raw = self
            .touch
            .take_raw_input(size, self.started.elapsed().as_secs_f64());
        let recording = self.ar_view.recorder.is_some();
        let mut choice = self.scene;
        let mut record = false;
        let mut free = self.ui_free;
        let (panels, race, events) = (&mut self.panels, &self.race, &self.events);
        // Android has no cursor or clipboard to update: the platform output is not needed.
        let _ = g
            .egui
            .paint(&g.gpu.device, &g.gpu.queue, texture, size, raw, |ui| {
                if choice == SceneChoice::Race {
                    race_panels(ui, panels, race, events, None, &race.name);
                }
                let bar = phone_bar(ui.ctx(), &mut choice, recording, message.as_ref());
                record |= bar.record_toggled;
                free = ui.available_rect_before_wrap();
            });
        self.ui_free = free;
        if record {
            self.ar_view.toggle_recording(self.data_dir.as_deref());
        }
        if choice != self.scene {
            self.end_gesture();
            self.scene = choice;
        }
        if let Some((text, Tone::Warning)) = &message {
            log::debug!("regatta: {text}");
        }
    }
}

/// An Android motion event as the overlay's [`Touch`]: the action, and every finger in
/// physical pixels. `None` for actions that are not touches (hover, scroll, buttons).
fn touch_of(m: &MotionEvent<'_>) -> Option<Touch> {
    let i = m.pointer_index();
    let action = match m.action() {
        MotionAction::Down => TouchAction::Down(i),
        MotionAction::PointerDown => TouchAction::PointerDown(i),
        MotionAction::Move => TouchAction::Move,
        MotionAction::PointerUp => TouchAction::PointerUp(i),
        MotionAction::Up => TouchAction::Up(i),
        MotionAction::Cancel => TouchAction::Cancel,
        _ => return None,
    };
    Some(Touch {
        action,
        fingers: m
            .pointers()
            .map(|p| Finger {
                id: p.pointer_id(),
                px: [p.x(), p.y()],
            })
            .collect(),
    })
}
