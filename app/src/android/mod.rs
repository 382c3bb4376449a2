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

use std::time::{Duration, Instant};

use android_activity::input::{InputEvent, MotionAction};
use android_activity::{AndroidApp, InputStatus, MainEvent, PollEvent};
use ar::arcore::{Command, Event, SessionState, TwoFingerGesture};
use glam::{DVec2, DVec3};
use render::{OrbitCamera, RenderOptions, Renderer};

use crate::cli::render::{FAR_M, scene_at};

mod arcore;

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
}

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
        })
    }

    fn visible(&self) -> bool {
        self.resumed && self.graphics.as_ref().is_some_and(|g| g.surface.is_some())
    }

    /// Returns true when the app must end.
    fn on_main_event(&mut self, app: &AndroidApp, event: MainEvent<'_>) -> bool {
        match event {
            MainEvent::InitWindow { .. } => self.attach_window(app),
            // Drop the surface while its window still exists (wgpu issue 2302).
            MainEvent::TerminateWindow { .. } => {
                if let Some(g) = self.graphics.as_mut() {
                    g.surface = None;
                }
            }
            MainEvent::WindowResized { .. } | MainEvent::ConfigChanged { .. } => {
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
                        let mut renderer = Renderer::new(
                            &gpu,
                            surface.config.format,
                            RenderOptions {
                                measure_gpu_time: false,
                                ..Default::default()
                            },
                        );
                        match crate::cli::render::race_wake(&self.race) {
                            Ok(wake) => renderer.set_wake(Some(wake)),
                            Err(e) => log::warn!("regatta: {e}; drawing no wakes"),
                        }
                        log::info!("regatta: drawing on {}", gpu.describe());
                        self.graphics = Some(Graphics {
                            gpu,
                            renderer,
                            surface: Some(surface),
                        });
                    }
                    Err(e) => log::error!("regatta: {e}"),
                }
            }
        }
    }

    /// Touch: one finger orbits the 3D view, two fingers pinch (zoom) and twist (turn).
    fn handle_input(&mut self, app: &AndroidApp) {
        let Ok(mut iter) = app.input_events_iter() else {
            return;
        };
        loop {
            let more = iter.next(|event| {
                if let InputEvent::MotionEvent(m) = event {
                    let pts: Vec<DVec2> = m
                        .pointers()
                        .map(|p| DVec2::new(f64::from(p.x()), f64::from(p.y())))
                        .collect();
                    match (m.action(), pts.as_slice()) {
                        (MotionAction::Down, [p]) => self.drag = Some(*p),
                        (MotionAction::PointerDown, [a, b, ..]) => {
                            self.drag = None;
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
                                self.orbit.distance =
                                    (self.orbit.distance / pinch).clamp(5.0, 5000.0);
                                self.orbit.yaw += twist;
                            }
                        }
                        (MotionAction::Up | MotionAction::Cancel, _) => {
                            self.drag = None;
                            self.pinch = None;
                        }
                        _ => {}
                    }
                    return InputStatus::Handled;
                }
                InputStatus::Unhandled
            });
            if !more {
                break;
            }
        }
    }

    fn draw(&mut self) {
        self.clock.tick();
        if self.session.is_running()
            && let Some(answer) = self.ar.update()
        {
            self.session_event(answer);
        }
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
