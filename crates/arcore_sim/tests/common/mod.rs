//! The simulator as tests drive it: loaded through the app's FFI (`ar::arcore::ffi::ArCore`)
//! and, for scripting and counters, its `RegattaSim_*` functions through libloading (the
//! same library: the loader hands out one instance per process).

#![allow(dead_code)]

use std::ffi::{CString, c_char, c_void};
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use ar::arcore::ffi::{ArCore, JavaScript, ScriptedJni};
use ar::arcore::{Event, SessionState};

/// One simulator per process: tests of one binary take turns.
static TURN: Mutex<()> = Mutex::new(());

pub struct Sim {
    lib: libloading::Library,
    pub path: PathBuf,
    _turn: MutexGuard<'static, ()>,
}

impl Sim {
    /// Takes the simulator (reset) for this test.
    pub fn take() -> Sim {
        let turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
        let path =
            arcore_sim::built_library().expect("cargo builds libarcore_sim.so with the tests");
        // SAFETY: the simulator runs no initialiser with preconditions.
        let lib = unsafe { libloading::Library::new(&path) }.expect("the simulator loads");
        let sim = Sim {
            lib,
            path,
            _turn: turn,
        };
        sim.call0("RegattaSim_reset");
        sim
    }

    fn sym<T: Copy>(&self, name: &str) -> T {
        // SAFETY: the caller names the function's true signature.
        unsafe { *self.lib.get::<T>(name.as_bytes()).expect(name) }
    }

    pub fn call0(&self, name: &str) {
        // SAFETY: a `void f(void)` export.
        unsafe { self.sym::<unsafe extern "C" fn()>(name)() }
    }

    pub fn set(&self, name: &str, v: i32) {
        // SAFETY: a `void f(int32_t)` export.
        unsafe { self.sym::<unsafe extern "C" fn(i32)>(name)(v) }
    }

    pub fn set2(&self, name: &str, a: i32, b: i32) {
        // SAFETY: a `void f(int32_t, int32_t)` export.
        unsafe { self.sym::<unsafe extern "C" fn(i32, i32)>(name)(a, b) }
    }

    pub fn set2_u32(&self, name: &str, a: u32, b: u32, c: u32) {
        // SAFETY: a `void f(uint32_t, uint32_t, uint32_t)` export.
        unsafe { self.sym::<unsafe extern "C" fn(u32, u32, u32)>(name)(a, b, c) }
    }

    /// `RegattaSim_useCameraConfigs`: the synthetic table on a phone listing the back camera's
    /// documented configs (0: 30 fps only, 1: also 60 fps), `frames` frames a loop.
    pub fn use_camera_configs(&self, phone: i32, frames: u32) {
        // SAFETY: `void RegattaSim_useCameraConfigs(int32_t, uint32_t)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(i32, u32)>("RegattaSim_useCameraConfigs")(phone, frames)
        }
    }

    /// `RegattaSim_lastCameraConfigFps`: the capture rate of the config last set (0: none).
    pub fn last_camera_config_fps(&self) -> i32 {
        // SAFETY: `int32_t RegattaSim_lastCameraConfigFps(void)`.
        unsafe { self.sym::<unsafe extern "C" fn() -> i32>("RegattaSim_lastCameraConfigFps")() }
    }

    pub fn expect_activity(&self, handle: usize) {
        // SAFETY: `void RegattaSim_expectActivity(void *)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(*mut c_void)>("RegattaSim_expectActivity")(
                handle as *mut c_void,
            )
        }
    }

    pub fn object(&self, name: &str) -> usize {
        // SAFETY: a `void *f(void)` export.
        unsafe { self.sym::<unsafe extern "C" fn() -> *mut c_void>(name)() as usize }
    }

    pub fn fail_updates(&self, status: i32, count: u32) {
        // SAFETY: `void RegattaSim_failUpdates(int32_t, uint32_t)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(i32, u32)>("RegattaSim_failUpdates")(status, count)
        }
    }

    pub fn set_light(&self, valid: bool, towards: [f32; 3]) {
        // SAFETY: `void RegattaSim_setLight(int32_t, float, float, float)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(i32, f32, f32, f32)>("RegattaSim_setLight")(
                i32::from(valid),
                towards[0],
                towards[1],
                towards[2],
            )
        }
    }

    /// `RegattaSim_failClassLookup`: ARCore's native half cannot find this Java class.
    pub fn fail_class_lookup(&self, class: &str) {
        let c = CString::new(class).expect("no NUL");
        // SAFETY: `void RegattaSim_failClassLookup(const char *)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(*const c_char)>("RegattaSim_failClassLookup")(
                c.as_ptr(),
            )
        }
    }

    /// `RegattaSim_throwAfter`: the next call of `function` succeeds and leaves `exception`.
    pub fn throw_after(&self, function: &str, exception: &str) {
        let (f, e) = (
            CString::new(function).expect("no NUL"),
            CString::new(exception).expect("no NUL"),
        );
        // SAFETY: `void RegattaSim_throwAfter(const char *, const char *)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(*const c_char, *const c_char)>("RegattaSim_throwAfter")(
                f.as_ptr(),
                e.as_ptr(),
            )
        }
    }

    pub fn calls(&self, function: &str) -> u64 {
        let c = CString::new(function).expect("no NUL");
        // SAFETY: `uint64_t RegattaSim_callCount(const char *)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(*const c_char) -> u64>("RegattaSim_callCount")(
                c.as_ptr(),
            )
        }
    }

    /// Live objects of `kind`, or of all kinds.
    pub fn live(&self, kind: Option<&str>) -> i64 {
        let c = kind.map(|k| CString::new(k).expect("no NUL"));
        let p = c.as_ref().map_or(std::ptr::null(), |c| c.as_ptr());
        // SAFETY: `int64_t RegattaSim_liveObjects(const char *)`.
        unsafe {
            self.sym::<unsafe extern "C" fn(*const c_char) -> i64>("RegattaSim_liveObjects")(p)
        }
    }

    pub fn frame_index(&self) -> i64 {
        // SAFETY: `int64_t RegattaSim_frameIndex(void)`.
        unsafe { self.sym::<unsafe extern "C" fn() -> i64>("RegattaSim_frameIndex")() }
    }

    pub fn wait_destroy_started(&self, n: u64) {
        // SAFETY: `void RegattaSim_waitDestroyStarted(uint64_t)`.
        unsafe { self.sym::<unsafe extern "C" fn(u64)>("RegattaSim_waitDestroyStarted")(n) }
    }

    pub fn destroys_finished(&self) -> u64 {
        // SAFETY: `uint64_t RegattaSim_destroysFinished(void)`.
        unsafe { self.sym::<unsafe extern "C" fn() -> u64>("RegattaSim_destroysFinished")() }
    }

    /// The app's ARCore glue on this simulator, with a host Java side scripted by `script`.
    pub fn arcore(&self, script: JavaScript) -> (Core, Arc<ScriptedJni>) {
        let jni = Arc::new(ScriptedJni::new(script));
        self.expect_activity(ScriptedJni::ACTIVITY_HANDLE);
        let core = ArCore::load_from(&self.path, Box::new(Arc::clone(&jni)));
        assert!(
            core.is_loaded(),
            "the FFI finds every function in the simulator"
        );
        (Core(core), jni)
    }
}

/// The app's [`ArCore`]; dropped, it waits for its session's teardown thread, so that the
/// destroy counts in the test that made the session (the app itself does not wait).
pub struct Core(pub ArCore);

impl std::ops::Deref for Core {
    type Target = ArCore;
    fn deref(&self) -> &ArCore {
        &self.0
    }
}

impl std::ops::DerefMut for Core {
    fn deref_mut(&mut self) -> &mut ArCore {
        &mut self.0
    }
}

impl Drop for Core {
    fn drop(&mut self) {
        if let Some(teardown) = self.0.close() {
            let _ = teardown.join();
        }
    }
}

/// A Java side where the camera permission is already granted.
pub fn granted() -> JavaScript {
    JavaScript {
        permission_granted: true,
        ..JavaScript::default()
    }
}

/// Resumes the app from the start; returns the state reached.
pub fn start(core: &mut ArCore) -> SessionState {
    let mut state = SessionState::Start;
    core.drive(
        &mut state,
        Event::AppResumed {
            library_loaded: true,
        },
    );
    state
}
