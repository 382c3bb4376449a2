//! The phone app on the host, headless: `regatta phone-sim --script FILE --out DIR`. The app
//! core's phone app ([`crate::core::app::App`]) drawn into an offscreen window
//! (lavapipe in CI), with the simulated ARCore ([`crate::sim_phone`]) as its AR backend, driven by a
//! script ([`script`], docs/phone-sim.md): the events an Android activity would send, in order,
//! with time stepped exactly (no wall clock).

pub mod script;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::Ordering;

use ar::arcore::ffi::ScriptedJni;

use glam::DVec2;

use crate::core::app::{App, AppEvent, PhoneStatus};
use crate::core::feed::CameraFeed;
use crate::hud::touch::TouchAction;
use crate::setup::RaceSetup;
use crate::sim_phone::Cues;
use crate::sim_phone::backend::{Availability, SimArCore, SimControl};
use script::{Line, Step};

/// Display frames per simulated second. Low, so lavapipe runs a minute of session in seconds;
/// taps (down, one frame, up: 0.1 s) stay under the tap limit of 0.3 s.
pub const SIM_FPS: f64 = 10.0;

/// A phone session on the host: the app, the simulated ARCore's cues, the screen.
pub struct PhoneSim {
    pub app: App,
    pub cues: Cues,
    /// The screen in its natural (portrait) orientation, pixels.
    portrait: [u32; 2],
    /// Display rotation, quarter turns counter-clockwise.
    rotation: u32,
    foreground: bool,
    /// The app has been started (the first step that is not a cue starts it).
    launched: bool,
    /// The Java side that delivers shared files (`open FILE`): the FFI's scripted JNI, or one
    /// of its own beside the scripted stand-in.
    intents: Arc<ScriptedJni>,
    /// The status bar's and navigation bar's heights, dp (`bars`); none by default.
    bars_dp: [f64; 2],
    ppp: f32,
}

impl PhoneSim {
    /// The embedded race on a phone screen of `portrait` pixels at `ppp` pixels per point,
    /// frames from `feed`, not yet launched (cues may be set first). `data_dir` receives
    /// recordings.
    pub fn new(feed: CameraFeed, portrait: [u32; 2], ppp: f32, data_dir: Option<PathBuf>) -> Self {
        let (backend, control) = SimArCore::new(feed);
        Self::with_backend(
            Box::new(backend),
            Cues::Scripted(control),
            portrait,
            ppp,
            data_dir,
        )
    }

    /// [`PhoneSim::new`] through the phone's own ARCore glue loading the simulator `library`
    /// (`crates/arcore_sim`), playing `replay` or its synthetic table.
    pub fn with_ffi(
        library: &Path,
        replay: Option<&Path>,
        portrait: [u32; 2],
        ppp: f32,
        data_dir: Option<PathBuf>,
    ) -> Result<Self, String> {
        let (backend, cues) = Cues::ffi(library, replay)?;
        Ok(Self::with_backend(backend, cues, portrait, ppp, data_dir))
    }

    fn with_backend(
        backend: Box<dyn crate::core::ar::ArBackend>,
        cues: Cues,
        portrait: [u32; 2],
        ppp: f32,
        data_dir: Option<PathBuf>,
    ) -> Self {
        let world = RaceSetup::load_world(&[], None).expect("the embedded race and sea load");
        let mut app = App::phone(world, backend);
        app.data_dir = data_dir;
        app.on(AppEvent::Density(ppp));
        let intents = match &cues {
            Cues::Ffi { jni, .. } => Arc::clone(jni),
            Cues::Scripted(_) => Arc::new(ScriptedJni::default()),
        };
        PhoneSim {
            intents,
            app,
            cues,
            portrait,
            rotation: 0,
            foreground: false,
            launched: false,
            bars_dp: [0.0, 0.0],
            ppp,
        }
    }

    /// The scripted stand-in's state (tests of the scripted backend).
    pub fn scripted(&self) -> &SimControl {
        match &self.cues {
            Cues::Scripted(c) => c,
            Cues::Ffi { .. } => panic!("this session runs the FFI, not the scripted stand-in"),
        }
    }

    /// Before launch: how the user will answer the permission dialog. After: the user's
    /// answer from then on, in the dialog or in Settings > Apps > Regatta.
    fn set_permission(&self, granted: bool) {
        let launched = self.launched;
        match &self.cues {
            Cues::Scripted(c) => c.lock().permission = granted,
            Cues::Ffi { jni, .. } => jni.script(|s| {
                s.dialog_answer = granted;
                if launched {
                    s.permission_granted = granted;
                }
            }),
        }
    }

    /// The display's rotation as Android reports it, without any event to the app.
    fn set_display_rotation(&self, quarter_turns: u32) {
        let r = quarter_turns as i32;
        match &self.cues {
            Cues::Scripted(c) => c.lock().display_rotation = r,
            Cues::Ffi { jni, .. } => jni.script(|s| s.rotation = r),
        }
    }

    /// The window's content rect (Android's): the window less the status bar at the top and
    /// the navigation bar at the bottom (portrait) or on the side it turned to (landscape).
    fn content_rect(&self) -> [i32; 4] {
        let [w, h] = self.size();
        let px = |dp: f64| (dp * f64::from(self.ppp)).round() as i32;
        let (status, nav) = (px(self.bars_dp[0]), px(self.bars_dp[1]));
        let (w, h) = (w as i32, h as i32);
        match self.rotation {
            1 => [0, status, w - nav, h],
            3 => [nav, status, w, h],
            _ => [0, status, w, h - nav],
        }
    }

    fn set_availability(&self, a: Availability) {
        match &self.cues {
            Cues::Scripted(c) => c.lock().availability = a,
            Cues::Ffi { sim, missing, .. } => {
                missing.store(a == Availability::Missing, Ordering::SeqCst);
                sim.set_availability(a);
            }
        }
    }

    fn set_tracking(&self, lost: Option<i32>) {
        match &self.cues {
            Cues::Scripted(c) => c.lock().lost = lost,
            Cues::Ffi { sim, .. } => sim.set_tracking(lost),
        }
    }

    /// [`PhoneSim::new`], launched: the app resumed with a window and one frame drawn.
    pub fn launch(
        feed: CameraFeed,
        portrait: [u32; 2],
        ppp: f32,
        data_dir: Option<PathBuf>,
    ) -> Self {
        let mut sim = Self::new(feed, portrait, ppp, data_dir);
        sim.resume();
        sim
    }

    /// The screen as the display is turned now, pixels.
    pub fn size(&self) -> [u32; 2] {
        let [w, h] = self.portrait;
        if self.rotation % 2 == 1 {
            [h, w]
        } else {
            [w, h]
        }
    }

    fn frames(&mut self, seconds: f64) {
        let n = (seconds * SIM_FPS).ceil().max(1.0) as usize;
        for _ in 0..n {
            self.frame(seconds / n as f64);
        }
    }

    /// One display frame `dt` seconds after the last.
    pub fn frame(&mut self, dt: f64) {
        self.cues.before_frame(&mut self.app, dt, self.foreground);
        self.app.frame(dt);
    }

    fn px(&self, p: [f64; 2]) -> [f32; 2] {
        let [w, h] = self.size();
        [(p[0] * f64::from(w)) as f32, (p[1] * f64::from(h)) as f32]
    }

    fn touch(&mut self, action: TouchAction, fingers: &[[f32; 2]]) {
        self.app.on(AppEvent::touch(action, fingers));
    }

    /// A finger down at `p` (screen units), one frame, up.
    pub fn tap(&mut self, p: [f64; 2]) {
        let px = self.px(p);
        self.touch(TouchAction::Down(0), &[px]);
        self.frame(1.0 / SIM_FPS);
        self.touch(TouchAction::Up(0), &[px]);
        self.frame(1.0 / SIM_FPS);
    }

    /// A finger down at `from`, moved to `to` over `seconds`, up.
    pub fn drag(&mut self, from: [f64; 2], to: [f64; 2], seconds: f64) {
        let n = (seconds * SIM_FPS).ceil().max(1.0) as usize;
        self.touch(TouchAction::Down(0), &[self.px(from)]);
        self.frame(1.0 / SIM_FPS);
        for i in 1..=n {
            let s = i as f64 / n as f64;
            let p = [
                from[0] + s * (to[0] - from[0]),
                from[1] + s * (to[1] - from[1]),
            ];
            self.touch(TouchAction::Move, &[self.px(p)]);
            self.frame(seconds / n as f64);
        }
        self.touch(TouchAction::Up(0), &[self.px(to)]);
        self.frame(1.0 / SIM_FPS);
    }

    /// Two fingers about the centre, 0.2 screen widths apart, spread by `scale` and turned by
    /// `twist_deg` (counter-clockwise on screen) over five frames.
    pub fn pinch(&mut self, scale: f64, twist_deg: f64) {
        let [w, h] = self.size();
        let c = DVec2::new(f64::from(w), f64::from(h)) / 2.0;
        let r0 = 0.1 * f64::from(w);
        let at = |s: f64| -> [[f32; 2]; 2] {
            let r = r0 * (1.0 + s * (scale - 1.0));
            // Screen y points down: counter-clockwise on screen is a negative angle here.
            let a = -(s * twist_deg).to_radians();
            let d = DVec2::new(a.cos(), a.sin()) * r;
            [(c - d).as_vec2().to_array(), (c + d).as_vec2().to_array()]
        };
        let start = at(0.0);
        self.touch(TouchAction::Down(0), &start[..1]);
        self.touch(TouchAction::PointerDown(1), &start);
        self.frame(1.0 / SIM_FPS);
        for i in 1..=5 {
            self.touch(TouchAction::Move, &at(f64::from(i) / 5.0));
            self.frame(1.0 / SIM_FPS);
        }
        let end = at(1.0);
        self.touch(TouchAction::PointerUp(1), &end);
        self.touch(TouchAction::Up(0), &end[..1]);
        self.frame(1.0 / SIM_FPS);
    }

    /// To the background: paused, then the window destroyed (its surface dropped).
    pub fn pause(&mut self) {
        self.app.on(AppEvent::Paused);
        self.app.on(AppEvent::WindowDestroyed);
        self.foreground = false;
    }

    /// Back: resumed, a new window, one frame.
    pub fn resume(&mut self) {
        self.launched = true;
        self.app.on(AppEvent::Resumed);
        self.app.on(AppEvent::WindowCreated {
            surface: None,
            size: self.size(),
        });
        self.app.on(AppEvent::ContentRect(self.content_rect()));
        self.foreground = true;
        self.frame(0.0);
    }

    /// The display turned to `degrees`: the new rotation and the window's new size.
    pub fn rotate(&mut self, degrees: u32) {
        self.rotation = degrees / 90 % 4;
        self.set_display_rotation(self.rotation);
        self.app.on(AppEvent::Rotation(self.rotation as i32));
        self.app.on(AppEvent::Resized(self.size()));
        self.app.on(AppEvent::ContentRect(self.content_rect()));
        self.frame(1.0 / SIM_FPS);
    }

    /// The phone turned by 180°: the display's rotation changes and nothing else reaches the
    /// app (same size, same orientation class: no window or configuration event).
    pub fn flip(&mut self) {
        self.rotation = (self.rotation + 2) % 4;
        self.set_display_rotation(self.rotation);
        self.frame(1.0 / SIM_FPS);
    }

    /// Shares the host file `path` with the app as a chat app does ("Share": `ACTION_SEND`
    /// with a `content://` URI showing the file's name), and the app reads it through the
    /// ContentResolver as on Android; one frame.
    pub fn open(&mut self, path: &Path) -> Result<crate::core::app::Opened, String> {
        let bytes = std::fs::read(path)
            .map_err(|e| format!("{} could not be read ({e})", input::show_path(path)))?;
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let mime = crate::core::app::EXTENSION_OF_MIME
            .iter()
            .find(|(_, e)| Some(*e) == ext.as_deref())
            .map_or("application/octet-stream", |(m, _)| m);
        self.intents.share(name.as_deref(), bytes, Some(mime));
        let opened = self
            .open_intent()
            .unwrap_or_else(|| Err("the share carried no file".into()));
        self.frame(1.0 / SIM_FPS);
        opened
    }

    /// The app reads the intent the scripted Java side holds now (as at an Activity's start).
    pub fn open_intent(&mut self) -> Option<Result<crate::core::app::Opened, String>> {
        self.app.open_intent(&*self.intents)
    }

    /// The scripted Java side that delivers shared files (tests script its provider).
    pub fn intents(&self) -> &ScriptedJni {
        &self.intents
    }

    /// Carries out one step; an error says why the step failed.
    pub fn step(&mut self, step: &Step, out: &Path) -> Result<(), String> {
        let cue = matches!(
            step,
            Step::Permission(_) | Step::ArCore(_) | Step::Tracking(_) | Step::Bars(..)
        );
        // The phone as the leading cues describe it, then the launch.
        if !self.launched && !cue && *step != Step::Resume {
            self.resume();
        }
        match step {
            Step::Wait(s) => self.frames(*s),
            Step::Tap(p) => self.tap(*p),
            Step::Drag(a, b, s) => self.drag(*a, *b, *s),
            Step::Pinch(s, d) => self.pinch(*s, *d),
            Step::Pause => self.pause(),
            Step::Resume => self.resume(),
            Step::Rotate(d) => self.rotate(*d),
            Step::Flip => self.flip(),
            Step::Bars(status, nav) => {
                self.bars_dp = [*status, *nav];
                if self.launched {
                    self.app.on(AppEvent::ContentRect(self.content_rect()));
                    self.frame(1.0 / SIM_FPS);
                }
            }
            Step::Permission(g) => self.set_permission(*g),
            Step::ArCore(a) => self.set_availability(*a),
            Step::Tracking(lost) => {
                self.set_tracking(*lost);
                if self.launched {
                    self.frame(1.0 / SIM_FPS);
                }
            }
            Step::Screenshot(name) => {
                let img = self
                    .app
                    .screenshot()
                    .ok_or("no window to take a screenshot of (the app is in the background)")??;
                let path = out.join(format!("{name}.png"));
                img.save(&path)
                    .map_err(|e| format!("{}: {e}", input::show_path(&path)))?;
            }
            Step::Record(start) => {
                if self.app.status().recording != *start {
                    self.app.record_button();
                }
                self.frame(1.0 / SIM_FPS);
                if self.app.status().recording != *start {
                    return Err(if *start {
                        "the recording did not start (no camera frame yet?)".into()
                    } else {
                        "the recording did not stop".into()
                    });
                }
            }
            Step::Scene(s) => {
                self.app.choose_scene(*s);
                self.frame(1.0 / SIM_FPS);
            }
            Step::Race(name) => {
                // The Races panel opens (the folder is read again), then the race is chosen.
                self.app.panels.show_races = true;
                self.frame(1.0 / SIM_FPS);
                let chosen = self.app.choose_race(name);
                self.frame(1.0 / SIM_FPS);
                chosen?;
            }
            Step::Open(path) => {
                self.open(path)?;
            }
        }
        Ok(())
    }
}

/// One line of `log.jsonl`.
#[derive(serde::Serialize)]
struct LogLine<'a> {
    line: usize,
    step: &'a str,
    ok: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
    #[serde(flatten)]
    status: PhoneStatus,
}

/// Runs `lines` on `sim`, writing `log.jsonl` into `out`; the number of failed steps.
pub fn run_script(sim: &mut PhoneSim, lines: &[Line], out: &Path) -> Result<usize, String> {
    let log_path = out.join("log.jsonl");
    let mut log = std::fs::File::create(&log_path)
        .map(std::io::BufWriter::new)
        .map_err(|e| format!("{}: {e}", input::show_path(&log_path)))?;
    let mut failed = 0;
    for l in lines {
        let result = sim.step(&l.step, out);
        failed += usize::from(result.is_err());
        let line = LogLine {
            line: l.number,
            step: &l.text,
            ok: result.is_ok(),
            error: result.err().map(|e| input::one_line(&e)),
            status: sim.app.status(),
        };
        let json = serde_json::to_string(&line).map_err(|e| e.to_string())?;
        writeln!(log, "{json}").map_err(|e| format!("{}: {e}", input::show_path(&log_path)))?;
    }
    log.flush()
        .map_err(|e| format!("{}: {e}", input::show_path(&log_path)))?;
    Ok(failed)
}
