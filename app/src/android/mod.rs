//! Android entry point (native activity, android-activity 0.6).
//!
//! Lifecycle (wgpu issue 2302: a surface must not outlive its `ANativeWindow`): the device is
//! made once, on the first `InitWindow`; each `InitWindow` creates a surface for the new window
//! and each `TerminateWindow` drops it before returning. In the background (`Pause`) nothing is
//! drawn and the race clock stops; the clock and the view survive pause, rotation and a new
//! window because they live in [`App`], not in the surface.
//!
//! AR: [`arcore::ArCore`] loads `libarcore_sdk_c.so` with libloading and the pure session state
//! machine (`ar::arcore::session`) decides what happens; where the library is missing (an APK
//! built without `--arcore-aar`) the app says so and runs the 3D race view without the camera.
//! Each frame `frame.rs` reads ARCore's frame into an `ar::CameraFrame`; once a tap has put the
//! course on a detected plane, [`ar_view`] draws the race over the camera image with ARCore's
//! camera and light. Touch: tap places, two fingers scale and turn the course (or, before it is
//! placed, orbit and zoom the 3D view); the volume-up key starts and stops a recording.

use std::time::{Duration, Instant};

use std::sync::Arc;

use android_activity::input::{InputEvent, KeyAction, Keycode, MotionAction};
use android_activity::{AndroidApp, InputStatus, MainEvent, PollEvent};
use ar::FrameSource;
use ar::arcore::{Command, Event, SessionState, TwoFingerGesture};
use glam::{DVec2, DVec3};
use render::effects::passes::{ArConfig, add_effect_passes};
use render::{OrbitCamera, RenderOptions, Renderer};

use crate::cli::render::{FAR_M, scene_at};

mod ar_view;
mod arcore;
mod frame;

// std's `_Unwind_*` come from the `unwinding` crate (see app/Cargo.toml); naming the crate links it.
use unwinding as _;

#[unsafe(no_mangle)]
fn android_main(app: AndroidApp) {
    android_logger::init_once(
        android_logger::Config::default().with_max_level(log::LevelFilter::Info),
    );
    log::info!("regatta: android_main started");
    let mut state = match App::new() {
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

/// Race time: plays at real speed while the app is in the foreground, loops over the race.
struct Clock {
    t: f64,
    span: (f64, f64),
    running: bool,
    last: Instant,
}

impl Clock {
    fn tick(&mut self) {
        let now = Instant::now();
        if self.running {
            self.t += now.duration_since(self.last).as_secs_f64();
        }
        self.last = now;
        let (a, b) = self.span;
        if self.t > b || self.t < a {
            self.t = a + (self.t - a).rem_euclid(b - a);
        }
    }

    /// Stops or restarts the clock; time spent in the background does not count.
    fn set_running(&mut self, running: bool) {
        self.tick();
        self.running = running;
    }
}

/// The device, made on the first window, and the surface of the current window.
struct Graphics {
    gpu: render::Gpu,
    renderer: Renderer,
    surface: Option<render::gpu::SurfaceTarget>,
    wake: Option<Arc<ocean::wake::Wake>>,
}

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
            ..Default::default()
        },
    );
    renderer.set_wake(wake);
    renderer
}

/// A touch that may become a tap: where and when the finger went down.
const TAP_MAX_PX: f64 = 20.0;
const TAP_MAX_S: f64 = 0.3;

struct App {
    race: race::Race,
    sea: ocean::WaveSet,
    clock: Clock,
    orbit: OrbitCamera,
    graphics: Option<Graphics>,
    resumed: bool,
    ar: arcore::ArCore,
    session: SessionState,
    /// One-finger drag start (pixels), or the two-finger gesture.
    drag: Option<DVec2>,
    pinch: Option<TwoFingerGesture>,
    touch_down: Option<(DVec2, Instant)>,
    ar_view: ar_view::ArView,
    /// Display rotation (`Surface.ROTATION_*`) and the geometry last given to ARCore.
    rotation: i32,
    geometry_set: Option<(i32, u32, u32)>,
    data_dir: Option<std::path::PathBuf>,
}

impl App {
    fn new() -> Result<Self, String> {
        let sea = crate::cli::inputs::load_sea(None).map_err(|e| e.to_string())?;
        let race = crate::cli::inputs::load_race(&[]).map_err(|e| e.to_string())?;
        let (t0, t1) = race.time_span();
        Ok(Self {
            race,
            sea,
            clock: Clock {
                t: t0,
                span: (t0, t1.max(t0 + 1.0)),
                running: false,
                last: Instant::now(),
            },
            orbit: OrbitCamera {
                target: DVec3::ZERO,
                distance: 90.0,
                yaw: 2.4,
                pitch: 0.35,
                far: FAR_M,
            },
            graphics: None,
            resumed: false,
            ar: arcore::ArCore::load(),
            session: SessionState::Start,
            drag: None,
            pinch: None,
            touch_down: None,
            ar_view: ar_view::ArView::default(),
            rotation: 0,
            geometry_set: None,
            data_dir: None,
        })
    }

    fn visible(&self) -> bool {
        self.resumed && self.graphics.as_ref().is_some_and(|g| g.surface.is_some())
    }

    /// Returns true when the app must end.
    fn on_main_event(&mut self, app: &AndroidApp, event: MainEvent<'_>) -> bool {
        match event {
            MainEvent::InitWindow { .. } => {
                self.data_dir = app.internal_data_path();
                self.rotation = arcore::display_rotation();
                self.attach_window(app);
            }
            // Drop the surface while its window still exists (wgpu issue 2302).
            MainEvent::TerminateWindow { .. } => {
                if let Some(g) = self.graphics.as_mut() {
                    g.surface = None;
                }
            }
            MainEvent::WindowResized { .. } | MainEvent::ConfigChanged { .. } => {
                self.rotation = arcore::display_rotation();
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
                self.clock.set_running(true);
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
                self.clock.set_running(false);
                self.session_event(Event::AppPaused);
            }
            MainEvent::Destroy => return true,
            _ => {}
        }
        false
    }

    /// Steps the AR session and carries out what it asks for.
    fn session_event(&mut self, event: Event) {
        let mut queue = vec![event];
        while let Some(e) = queue.pop() {
            let (next, commands) = self.session.on(e);
            self.session = next;
            for c in commands {
                match c {
                    Command::FallBack(why) => log::warn!("regatta: {}", why.message()),
                    Command::Tell(msg) => log::warn!("regatta: {msg}"),
                    other => {
                        if let Some(answer) = self.ar.carry_out(other) {
                            queue.push(answer);
                        }
                    }
                }
            }
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
                    Ok((gpu, surface)) => {
                        let wake = crate::cli::render::race_wake(&self.race)
                            .map_err(|e| log::warn!("regatta: {e}; drawing no wakes"))
                            .ok();
                        log::info!("regatta: drawing on {}", gpu.describe());
                        self.graphics = Some(Graphics {
                            renderer: fresh_renderer(&gpu, wake.clone(), surface.config.format),
                            gpu,
                            surface: Some(surface),
                            wake,
                        });
                    }
                    Err(e) => log::error!("regatta: {e}"),
                }
            }
        }
    }

    /// Touch: a tap places the course on the table; one finger orbits the 3D view; two fingers
    /// pinch and twist (the course once placed, else the 3D view). Volume-up toggles recording.
    fn handle_input(&mut self, app: &AndroidApp) {
        let Ok(mut iter) = app.input_events_iter() else {
            return;
        };
        let size = self.view_size();
        let play_area = scene_at(&self.race, &self.sea, self.clock.t, None).play_area;
        let table_depth = ArConfig::default().table_depth;
        loop {
            let more = iter.next(|event| match event {
                InputEvent::KeyEvent(k) if k.key_code() == Keycode::VolumeUp => {
                    if k.action() == KeyAction::Down {
                        self.ar_view.toggle_recording(self.data_dir.as_deref());
                    }
                    InputStatus::Handled
                }
                InputEvent::MotionEvent(m) => {
                    let pts: Vec<DVec2> = m
                        .pointers()
                        .map(|p| DVec2::new(f64::from(p.x()), f64::from(p.y())))
                        .collect();
                    match (m.action(), pts.as_slice()) {
                        (MotionAction::Down, [p]) => {
                            self.drag = Some(*p);
                            self.touch_down = Some((*p, Instant::now()));
                        }
                        (MotionAction::PointerDown, [a, b, ..]) => {
                            self.drag = None;
                            self.touch_down = None;
                            self.pinch = Some(TwoFingerGesture::new(*a, *b));
                        }
                        (MotionAction::Move, [p]) => {
                            if let Some(d) = self.drag.replace(*p) {
                                let delta = *p - d;
                                self.orbit.yaw -= delta.x * 0.005;
                                self.orbit.pitch = (self.orbit.pitch + delta.y * 0.005)
                                    .clamp(OrbitCamera::MIN_PITCH, 89f64.to_radians());
                            }
                        }
                        (MotionAction::Move, [a, b, ..]) => {
                            if let Some(g) = self.pinch.as_mut() {
                                let (pinch, twist) = g.update(*a, *b);
                                match self.ar_view.placement.as_mut() {
                                    Some(p) => p.apply_gesture_about(
                                        ar_view::course_pivot(play_area, table_depth),
                                        pinch,
                                        twist,
                                    ),
                                    None => {
                                        self.orbit.distance =
                                            (self.orbit.distance / pinch).clamp(5.0, 5000.0);
                                        self.orbit.yaw += twist;
                                    }
                                }
                            }
                        }
                        (MotionAction::Up, [p]) => {
                            if let Some((down, at)) = self.touch_down.take()
                                && (*p - down).length() < TAP_MAX_PX
                                && at.elapsed().as_secs_f64() < TAP_MAX_S
                            {
                                self.ar_view.tap(*p, size, play_area, table_depth);
                            }
                            self.drag = None;
                            self.pinch = None;
                        }
                        (MotionAction::Up | MotionAction::Cancel, _) => {
                            self.drag = None;
                            self.pinch = None;
                            self.touch_down = None;
                        }
                        _ => {}
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
        self.clock.tick();
        self.update_ar();
        let mut scene = scene_at(&self.race, &self.sea, self.clock.t, None);
        if !scene.boats.is_empty() {
            let c =
                scene.boats.iter().map(|b| b.position).sum::<DVec2>() / scene.boats.len() as f64;
            self.orbit.target = DVec3::new(c.x, 0.0, c.y);
        }
        scene.camera = self.orbit.camera();
        let Some(g) = self.graphics.as_mut() else {
            return;
        };
        let Some(s) = g.surface.as_mut() else { return };
        // On the table once placed: ARCore's camera and light, the camera image behind.
        if let (Some(p), Some(view), Some(frame)) = (
            self.ar_view.placement,
            self.ar.view.as_ref(),
            self.ar_view.frame.as_ref(),
        ) {
            scene.camera = ar_view::ArView::camera(&p, view);
            if let Some(l) = view.light_towards {
                scene.sun = ar_view::ArView::sun(&p, l);
            }
            let min_len = ar_view::ArView::boat_length(&p);
            for b in &mut scene.boats {
                b.length = b.length.max(min_len);
            }
            if self
                .ar_view
                .background_at
                .is_none_or(|t| t.elapsed().as_secs_f64() >= ar_view::BACKGROUND_REFRESH_S)
            {
                let rebuild = Instant::now();
                let mut fresh = fresh_renderer(&g.gpu, g.wake.clone(), s.config.format);
                let background = ar_view::ArView::background(&p, frame);
                add_effect_passes(&mut fresh, &g.gpu, ArConfig::default(), background);
                g.renderer = fresh;
                self.ar_view.background_at = Some(Instant::now());
                log::debug!(
                    "regatta: effect passes rebuilt over the camera image in {:.1} ms",
                    rebuild.elapsed().as_secs_f64() * 1e3
                );
            }
        }
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
        let view = frame.texture.create_view(&Default::default());
        let size = [s.config.width, s.config.height];
        g.renderer.render(&g.gpu, &view, size, &scene);
        g.gpu.queue.present(frame);
    }
}
