//! `regatta run --phone [--device pixel2xl|a54] [--replay DIR]`: the phone app of the app core
//! in a portrait window of the phone's aspect and density, through the simulated ARCore (the
//! synthetic table, or the recorded feed; with `--arcore-lib`, the phone's own ARCore glue
//! against `crates/arcore_sim`). The mouse is one finger; a right-drag is two fingers
//! about the press (up/down pinches, left/right twists), and so is Ctrl+wheel (pinch).
//! `REGATTA_EXIT_AFTER_FRAMES` and `REGATTA_SCREENSHOT` work as in the other scenes.

use std::sync::Arc;

use glam::DVec2;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::ModifiersState;
use winit::window::{Window, WindowId};

use super::RunArgs;
use crate::core::app::{App, AppEvent};
use crate::error::{AppError, AppResult};
use crate::hud::touch::TouchAction;
use crate::setup::RaceSetup;
use crate::sim_phone::Cues;
use crate::sim_phone::backend::SimArCore;
use crate::wall_clock::Ticker;

/// The tallest window the host gives the phone, pixels (an 800-pixel-high screen keeps its
/// title bar).
const MAX_HEIGHT: u32 = 760;
/// Half the distance between the two fingers a right-drag or the wheel makes, pixels.
const TWO_FINGER_RADIUS: f64 = 60.0;

pub fn run(a: RunArgs) -> AppResult {
    if !a.race.is_empty() || a.sea.is_some() || a.scene != crate::setup::SceneKind::Race {
        return Err(AppError::new(
            "--race, --sea and --scene have no meaning with --phone (the phone app has its race and a Race | Pool toggle)",
        ));
    }
    let (backend, cues) = match &a.arcore_lib {
        Some(lib) => Cues::ffi(lib, a.replay.as_deref()).map_err(AppError::new)?,
        None => {
            let feed = crate::core::feed::CameraFeed::for_phone(a.replay.as_deref())?;
            let (backend, control) = SimArCore::new(feed);
            let backend: Box<dyn crate::core::ar::ArBackend> = Box::new(backend);
            (backend, Cues::Scripted(control))
        }
    };
    let mut app = App::phone(RaceSetup::load_world(&[], None)?, backend);
    app.data_dir = std::env::current_dir().ok();
    // The Races panel lists $REGATTA_RACES_DIR, else ./races.
    app.set_races_dir(crate::core::app::host_races_dir(app.data_dir.as_deref()));
    let [w, h] = a.device.host_size();
    let size = if h > MAX_HEIGHT {
        [w * MAX_HEIGHT / h, MAX_HEIGHT]
    } else {
        [w, h]
    };
    app.on(AppEvent::Density(a.device.pixels_per_point(size)));
    let event_loop = super::event_loop()?;
    let mut shell = Shell {
        app,
        cues,
        size,
        window: None,
        ticker: Ticker::default(),
        cursor: DVec2::ZERO,
        left: false,
        right: None,
        modifiers: ModifiersState::empty(),
        exit_after: super::smoke::ExitAfter::from_env(),
        error: None,
    };
    event_loop
        .run_app(&mut shell)
        .map_err(|e| AppError::new(format!("the window's event loop failed: {e}")))?;
    shell.error.map_or(Ok(()), Err)
}

/// Translates winit's events into the phone app's.
struct Shell {
    app: App,
    cues: Cues,
    size: [u32; 2],
    window: Option<Arc<Window>>,
    ticker: Ticker,
    cursor: DVec2,
    left: bool,
    /// Where a right-drag began.
    right: Option<DVec2>,
    modifiers: ModifiersState,
    exit_after: super::smoke::ExitAfter,
    error: Option<AppError>,
}

impl Shell {
    fn touch(&mut self, action: TouchAction, fingers: &[DVec2]) {
        let px: Vec<[f32; 2]> = fingers.iter().map(|p| p.as_vec2().to_array()).collect();
        self.app.on(AppEvent::touch(action, &px));
    }

    /// Two fingers about `centre`, `spread` times apart and turned by `twist` radians.
    fn two(centre: DVec2, spread: f64, twist: f64) -> [DVec2; 2] {
        let d = DVec2::new(twist.cos(), -twist.sin()) * TWO_FINGER_RADIUS * spread;
        [centre - d, centre + d]
    }

    /// A right-drag from `from` to the cursor: pinch by the vertical, twist by the horizontal.
    fn right_fingers(&self, from: DVec2) -> [DVec2; 2] {
        let d = self.cursor - from;
        Self::two(from, (-d.y / 200.0).exp(), d.x / 200.0)
    }

    fn wheel_pinch(&mut self, steps: f64) {
        let c = self.cursor;
        let start = Self::two(c, 1.0, 0.0);
        self.touch(TouchAction::Down(0), &start[..1]);
        self.touch(TouchAction::PointerDown(1), &start);
        let end = Self::two(c, 1.1f64.powf(steps), 0.0);
        self.touch(TouchAction::Move, &end);
        self.touch(TouchAction::PointerUp(1), &end);
        self.touch(TouchAction::Up(0), &end[..1]);
    }
}

impl ApplicationHandler for Shell {
    fn resumed(&mut self, el: &ActiveEventLoop) {
        let window = match &self.window {
            Some(w) => w.clone(),
            None => {
                let attrs = Window::default_attributes()
                    .with_title("Regatta (phone)")
                    .with_resizable(false)
                    .with_inner_size(winit::dpi::PhysicalSize::new(self.size[0], self.size[1]));
                match el.create_window(attrs) {
                    Ok(w) => Arc::new(w),
                    Err(e) => {
                        self.error = Some(AppError::new(format!("cannot open a window: {e}")));
                        return el.exit();
                    }
                }
            }
        };
        let s = window.inner_size();
        self.size = [s.width.max(1), s.height.max(1)];
        self.window = Some(window.clone());
        self.app.on(AppEvent::Resumed);
        self.app.on(AppEvent::WindowCreated {
            surface: Some(Box::new(move |i: &wgpu::Instance| {
                i.create_surface(window.clone()).map_err(|e| e.to_string())
            })),
            size: self.size,
        });
        self.ticker.stop();
    }

    fn suspended(&mut self, _el: &ActiveEventLoop) {
        self.app.on(AppEvent::Paused);
        self.app.on(AppEvent::WindowDestroyed);
    }

    fn window_event(&mut self, el: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => el.exit(),
            WindowEvent::Resized(s) => {
                self.size = [s.width.max(1), s.height.max(1)];
                self.app.on(AppEvent::Resized(self.size));
            }
            WindowEvent::ModifiersChanged(m) => self.modifiers = m.state(),
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = DVec2::new(position.x, position.y);
                if let Some(from) = self.right {
                    let f = self.right_fingers(from);
                    self.touch(TouchAction::Move, &f);
                } else if self.left {
                    let c = self.cursor;
                    self.touch(TouchAction::Move, &[c]);
                }
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let pressed = state == ElementState::Pressed;
                let c = self.cursor;
                match (button, pressed) {
                    (MouseButton::Left, true) if self.right.is_none() => {
                        self.left = true;
                        self.touch(TouchAction::Down(0), &[c]);
                    }
                    (MouseButton::Left, false) if self.left => {
                        self.left = false;
                        self.touch(TouchAction::Up(0), &[c]);
                    }
                    (MouseButton::Right, true) if !self.left => {
                        self.right = Some(c);
                        let f = Self::two(c, 1.0, 0.0);
                        self.touch(TouchAction::Down(0), &f[..1]);
                        self.touch(TouchAction::PointerDown(1), &f);
                    }
                    (MouseButton::Right, false) => {
                        if let Some(from) = self.right.take() {
                            let f = self.right_fingers(from);
                            self.touch(TouchAction::PointerUp(1), &f);
                            self.touch(TouchAction::Up(0), &f[..1]);
                        }
                    }
                    _ => {}
                }
            }
            WindowEvent::MouseWheel { delta, .. } if self.modifiers.control_key() => {
                self.wheel_pinch(super::wheel_steps(delta));
            }
            WindowEvent::RedrawRequested => {
                let dt = self.ticker.tick();
                self.cues.before_frame(&mut self.app, dt, true);
                self.app.frame(dt);
                if self.exit_after.frame_done() {
                    if let Err(e) = super::smoke::save_screenshot(&mut self.app, self.size) {
                        self.error = Some(AppError::new(e));
                    }
                    el.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _el: &ActiveEventLoop) {
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }
}
