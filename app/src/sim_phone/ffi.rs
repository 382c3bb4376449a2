//! The phone's own ARCore glue on the host: `ar::arcore::ffi::ArCore` loading the simulated
//! ARCore (`crates/arcore_sim`, a cdylib with the C API subset), its Java calls answered by
//! `ar::arcore::ffi::ScriptedJni`. A script's cues go to the simulator's `RegattaSim_*`
//! functions (the same library, loaded a second time: the loader hands out one instance) and to
//! the scripted Java side.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use ar::arcore::ffi::{ArCore, JavaScript, ScriptedJni};
use ar::arcore::{Command, Event, SessionState};
use ar::{ArError, CameraFrame};

use super::backend::Availability;
use crate::core::ar::{ArBackend, DisplayCamera};

/// The simulator's scripting functions.
pub struct SimLibrary {
    lib: libloading::Library,
}

impl SimLibrary {
    /// Loads the simulator at `path`; the feed is `replay` (a replay folder) or the synthetic
    /// table at `synth` (width, height, frames).
    pub fn open(path: &Path, replay: Option<&Path>, synth: [u32; 3]) -> Result<SimLibrary, String> {
        // SAFETY: the simulator runs no initialiser with preconditions.
        let lib = unsafe { libloading::Library::new(path) }
            .map_err(|e| format!("{}: {e}", input::show_path(path)))?;
        let sim = SimLibrary { lib };
        // SAFETY (every call below): each export is called with its true C signature.
        unsafe { sim.sym::<unsafe extern "C" fn()>("RegattaSim_reset")?() };
        match replay {
            Some(dir) => {
                let c = std::ffi::CString::new(dir.to_string_lossy().as_bytes())
                    .map_err(|_| format!("{}: a NUL in the path", input::show_path(dir)))?;
                let open = sim.sym::<unsafe extern "C" fn(*const std::ffi::c_char) -> i32>(
                    "RegattaSim_openReplay",
                )?;
                if unsafe { open(c.as_ptr()) } != 0 {
                    return Err(format!(
                        "{}: the simulator cannot play it",
                        input::show_path(dir)
                    ));
                }
            }
            // A smaller synthetic table where the simulator offers one (else its own).
            None => {
                if let Ok(synth_feed) =
                    sim.sym::<unsafe extern "C" fn(u32, u32, u32)>("RegattaSim_useSynth")
                {
                    unsafe { synth_feed(synth[0], synth[1], synth[2]) };
                }
            }
        }
        Ok(sim)
    }

    fn sym<F: Copy>(&self, name: &str) -> Result<F, String> {
        // SAFETY: callers name the export's true signature.
        unsafe { self.lib.get::<F>(name.as_bytes()) }
            .map(|f| *f)
            .map_err(|e| format!("the simulator has no {name}: {e}"))
    }

    fn set(&self, name: &str, a: i32, b: i32) {
        match self.sym::<unsafe extern "C" fn(i32, i32)>(name) {
            // SAFETY: `void f(int32_t, int32_t)`.
            Ok(f) => unsafe { f(a, b) },
            Err(e) => log::error!("regatta: {e}"),
        }
    }

    fn set_one(&self, name: &str, a: i32) {
        match self.sym::<unsafe extern "C" fn(i32)>(name) {
            // SAFETY: `void f(int32_t)`.
            Ok(f) => unsafe { f(a) },
            Err(e) => log::error!("regatta: {e}"),
        }
    }

    /// The synthetic table (`frames` a loop) on a phone listing the back camera's documented
    /// configs (`RegattaSim_useCameraConfigs`: 0 an OPPO A54 class phone, 30 fps; 1 a Pixel 2
    /// XL class phone, also 60 fps): the CPU image has the size of the config the app sets.
    pub fn use_camera_configs(&self, phone: i32, frames: u32) -> Result<(), String> {
        let f = self.sym::<unsafe extern "C" fn(i32, u32)>("RegattaSim_useCameraConfigs")?;
        // SAFETY: `void RegattaSim_useCameraConfigs(int32_t, uint32_t)`.
        unsafe { f(phone, frames) };
        Ok(())
    }

    /// ARCore installed (0) or installed on an unsupported phone (3).
    pub fn set_availability(&self, a: Availability) {
        self.set_one(
            "RegattaSim_setApk",
            i32::from(a == Availability::Unsupported) * 3,
        );
    }

    /// `AR_TRACKING_STATE_PAUSED` for `reason`, or tracking.
    pub fn set_tracking(&self, lost: Option<i32>) {
        match lost {
            Some(reason) => self.set("RegattaSim_setTracking", 1, reason),
            None => self.set("RegattaSim_setTracking", 0, 0),
        }
    }
}

/// The FFI backend; `missing` plays an APK built without ARCore's library.
pub struct FfiBackend {
    core: ArCore,
    pub missing: Arc<AtomicBool>,
}

impl FfiBackend {
    /// ARCore's glue loading `library`, its Java side `jni`.
    pub fn new(library: &Path, jni: Arc<ScriptedJni>) -> FfiBackend {
        FfiBackend {
            core: ArCore::load_from(library, Box::new(jni)),
            missing: Arc::default(),
        }
    }
}

/// A Java side as a fresh install has it: no permission yet, the user allows the dialog.
pub fn fresh_install() -> Arc<ScriptedJni> {
    Arc::new(ScriptedJni::new(JavaScript::default()))
}

impl ArBackend for FfiBackend {
    fn is_loaded(&self) -> bool {
        ArBackend::is_loaded(&self.core) && !self.missing.load(Ordering::SeqCst)
    }
    fn carry_out(&mut self, command: Command) -> Option<Event> {
        ArBackend::carry_out(&mut self.core, command)
    }
    fn drive(&mut self, state: &mut SessionState, event: Event) -> Option<&'static str> {
        ArBackend::drive(&mut self.core, state, event)
    }
    fn set_display_geometry(&mut self, rotation: i32, width: u32, height: u32) {
        ArBackend::set_display_geometry(&mut self.core, rotation, width, height);
    }
    fn update(&mut self) -> Option<Event> {
        ArBackend::update(&mut self.core)
    }
    fn next_frame(&mut self) -> Result<Option<(CameraFrame, DisplayCamera)>, ArError> {
        ArBackend::next_frame(&mut self.core)
    }
    fn display_rotation(&self) -> Option<i32> {
        ArBackend::display_rotation(&self.core)
    }
    fn set_camera_budget(&mut self, budget: ar::arcore::ffi::CameraBudget) {
        ArBackend::set_camera_budget(&mut self.core, budget);
    }
}
