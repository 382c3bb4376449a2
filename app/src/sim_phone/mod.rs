//! The simulated phone the phone core runs against on the host, for the headless `phone-sim`
//! and the `regatta run --phone` window alike: the device profiles ([`device`]), the scripted
//! ARCore stand-in ([`backend`]) and the simulated ARCore library behind the phone's own FFI
//! ([`ffi`]), and where a session's cues go ([`Cues`]). Neither shell borrows the other's
//! module for it.
//!
//! It never knows winit or a script's syntax: the shells drive it.

pub mod backend;
pub mod device;
pub mod ffi;

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use ar::arcore::ffi::ScriptedJni;

use crate::core::app::{App, AppEvent};
use backend::SimControl;
use ffi::{FfiBackend, SimLibrary};

/// Where a script's cues go: the scripted stand-in, or the simulated ARCore behind the
/// phone's own FFI with its scripted Java side.
pub enum Cues {
    Scripted(SimControl),
    Ffi {
        sim: SimLibrary,
        jni: Arc<ScriptedJni>,
        missing: Arc<AtomicBool>,
    },
}

impl Cues {
    /// The phone's own ARCore glue loading the simulator `library`, playing `replay` or its
    /// synthetic table; its cues.
    pub fn ffi(
        library: &Path,
        replay: Option<&Path>,
    ) -> Result<(Box<dyn crate::core::ar::ArBackend>, Cues), String> {
        let sim = SimLibrary::open(library, replay, [320, 240, 32])?;
        let jni = ffi::fresh_install();
        let backend = FfiBackend::new(library, Arc::clone(&jni));
        let missing = Arc::clone(&backend.missing);
        Ok((Box::new(backend), Cues::Ffi { sim, jni, missing }))
    }

    /// Before a display frame `dt` seconds after the last: the scripted feed's time moves on
    /// (in the foreground); a permission dialog shown pauses and resumes the activity, as
    /// Android does.
    pub fn before_frame(&self, app: &mut App, dt: f64, foreground: bool) {
        match self {
            Cues::Scripted(c) if foreground => c.lock().t += dt,
            Cues::Ffi { jni, .. } if jni.take_dialog_shown() => {
                app.on(AppEvent::Paused);
                app.on(AppEvent::Resumed);
            }
            _ => {}
        }
    }
}
