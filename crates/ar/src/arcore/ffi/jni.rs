//! The few Java calls around ARCore, behind one narrow trait: [`Jni`]. On the phone the app
//! implements it with the `jni` crate (`app/src/android/jni_calls.rs`); on the host
//! [`ScriptedJni`] answers from a script and records which Java object each call went to
//! (docs/phone-arcore.md says why a fake and not a JVM).
//!
//! The receiver is explicit in every call ([`JavaObject`]) because it is what goes wrong on a
//! device: android-activity gives `ndk_context` the Application, while
//! `ArCoreApk_requestInstall`, `requestPermissions` and `getWindowManager` need the Activity.

use std::ffi::c_void;
use std::sync::{Mutex, MutexGuard};

/// The Java object a call goes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JavaObject {
    /// The current `android.app.Activity` (`AndroidApp::activity_as_ptr()`).
    Activity,
    /// The `android.app.Application` (`ndk_context::android_context().context()`).
    Application,
}

/// `android.permission.CAMERA`.
pub const CAMERA_PERMISSION: &str = "android.permission.CAMERA";
/// The request code of the camera permission dialog.
pub const CAMERA_REQUEST_CODE: i32 = 1;

/// The Java side of the ARCore glue.
pub trait Jni {
    /// Runs `f` with this thread's `JNIEnv*` and the raw `jobject` of `on`, for the C calls
    /// that take them (`ArCoreApk_requestInstall`, `ArSession_create`). ARCore's native half
    /// calls its Java half through that env; a Java exception it leaves pending (a class its
    /// DEX lacks, the install activity refused) is caught after `f`, cleared (the next JNI call
    /// would abort on it) and returned as the error, named, even though `f` itself ran to the
    /// end (jni 0.22 reports it so; issue 26, defect 2). Whatever `f` wrote stays written.
    fn with_env(
        &self,
        on: JavaObject,
        f: &mut dyn FnMut(*mut c_void, *mut c_void),
    ) -> Result<(), String>;
    /// `on.checkSelfPermission(permission) == PackageManager.PERMISSION_GRANTED`.
    fn check_self_permission(&self, on: JavaObject, permission: &str) -> Result<bool, String>;
    /// `on.requestPermissions(new String[] {permission}, request_code)`.
    fn request_permissions(
        &self,
        on: JavaObject,
        permission: &str,
        request_code: i32,
    ) -> Result<(), String>;
    /// `on.getWindowManager().getDefaultDisplay().getRotation()` (`Surface.ROTATION_*`).
    fn display_rotation(&self, on: JavaObject) -> Result<i32, String>;
    /// `Build.VERSION.SDK_INT`.
    fn sdk_int(&self) -> u32;
}

impl<T: Jni + ?Sized> Jni for std::sync::Arc<T> {
    fn with_env(
        &self,
        on: JavaObject,
        f: &mut dyn FnMut(*mut c_void, *mut c_void),
    ) -> Result<(), String> {
        (**self).with_env(on, f)
    }
    fn check_self_permission(&self, on: JavaObject, permission: &str) -> Result<bool, String> {
        (**self).check_self_permission(on, permission)
    }
    fn request_permissions(&self, on: JavaObject, p: &str, code: i32) -> Result<(), String> {
        (**self).request_permissions(on, p, code)
    }
    fn display_rotation(&self, on: JavaObject) -> Result<i32, String> {
        (**self).display_rotation(on)
    }
    fn sdk_int(&self) -> u32 {
        (**self).sdk_int()
    }
}

/// One Java call the host fake saw: the method and its receiver.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JavaCall {
    pub method: &'static str,
    pub on: JavaObject,
}

/// What the host fake answers.
#[derive(Clone, Debug)]
pub struct JavaScript {
    pub permission_granted: bool,
    /// The user's answer to the next permission dialog (applied when it is shown).
    pub dialog_answer: bool,
    /// `Surface.ROTATION_*` (0..=3).
    pub rotation: i32,
    pub sdk_int: u32,
}

impl Default for JavaScript {
    fn default() -> Self {
        Self {
            permission_granted: false,
            dialog_answer: true,
            rotation: 0,
            // The Pixel 2 XL's last Android (11).
            sdk_int: 30,
        }
    }
}

/// What the host fake hands C calls as their `JNIEnv*`: not JNI's function table but the one
/// thing the simulated ARCore (`crates/arcore_sim`, which repeats this layout) does with an env:
/// leave a Java exception pending in it, as ARCore's native half does when its Java half throws.
/// `exception` holds the pending throwable as NUL-terminated `class: message`, empty when none.
#[repr(C)]
#[derive(Debug)]
pub struct HostEnv {
    /// [`HostEnv::MAGIC`]: the simulator writes only into an env that carries it.
    pub magic: u64,
    pub exception: [u8; HostEnv::EXCEPTION_BYTES],
}

impl HostEnv {
    pub const MAGIC: u64 = 0x4A4E_4945_4E56_0001;
    pub const EXCEPTION_BYTES: usize = 256;

    fn new() -> Self {
        Self {
            magic: Self::MAGIC,
            exception: [0; Self::EXCEPTION_BYTES],
        }
    }

    /// The pending exception, cleared (JNI's `ExceptionOccurred` then `ExceptionClear`).
    fn catch(&mut self) -> Option<String> {
        let len = self.exception.iter().position(|&b| b == 0)?;
        if len == 0 {
            return None;
        }
        let text = String::from_utf8_lossy(&self.exception[..len]).into_owned();
        self.exception = [0; Self::EXCEPTION_BYTES];
        Some(text)
    }
}

/// The host's [`Jni`]: scripted answers, every call recorded with its receiver. It keeps
/// Android's rule that `requestPermissions` and `getWindowManager` exist only on `Activity`
/// (Android API reference: `android.app.Activity`; `Application` is a `ContextWrapper`
/// without them): on the Application they fail as `NoSuchMethodError`, as on a device. Its env
/// ([`HostEnv`]) is where the simulated ARCore leaves Java exceptions pending; [`Jni::with_env`]
/// reports them as jni 0.22 does.
#[derive(Debug, Default)]
pub struct ScriptedJni {
    state: Mutex<(JavaScript, Vec<JavaCall>, bool)>,
    /// The Activity's intent and the content provider behind it ([`super::intent_file`]).
    pub(super) content: Mutex<super::intent_file::ContentScript>,
    /// The media store and the share sheet ([`super::share_media`]).
    pub(super) media: Mutex<super::share_media::MediaScript>,
    /// Boxed: C calls keep its address for the call's length.
    env: Mutex<Option<Box<HostEnv>>>,
}

impl ScriptedJni {
    /// The fake `jobject`s handed to C calls: distinct, recognisable, never dereferenced by
    /// the simulator.
    pub const ACTIVITY_HANDLE: usize = 0xAC71_0000;
    pub const APPLICATION_HANDLE: usize = 0xA991_0000;

    pub fn new(script: JavaScript) -> Self {
        Self {
            state: Mutex::new((script, Vec::new(), false)),
            content: Mutex::default(),
            media: Mutex::default(),
            env: Mutex::new(None),
        }
    }

    fn lock(&self) -> MutexGuard<'_, (JavaScript, Vec<JavaCall>, bool)> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Changes the script (rotation, the dialog's answer, the permission).
    pub fn script(&self, f: impl FnOnce(&mut JavaScript)) {
        f(&mut self.lock().0);
    }

    /// Every call so far, in order.
    pub fn calls(&self) -> Vec<JavaCall> {
        self.lock().1.clone()
    }

    /// Whether a permission dialog was shown since the last call (and takes the flag).
    pub fn take_dialog_shown(&self) -> bool {
        std::mem::take(&mut self.lock().2)
    }

    /// The raw handle of `on`, as C calls receive it.
    pub fn handle(on: JavaObject) -> usize {
        match on {
            JavaObject::Activity => Self::ACTIVITY_HANDLE,
            JavaObject::Application => Self::APPLICATION_HANDLE,
        }
    }

    pub(super) fn record(&self, method: &'static str, on: JavaObject) {
        self.lock().1.push(JavaCall { method, on });
    }

    pub(super) fn activity_only(method: &str, on: JavaObject) -> Result<(), String> {
        match on {
            JavaObject::Activity => Ok(()),
            JavaObject::Application => Err(format!(
                "java.lang.NoSuchMethodError: no method {method} on android.app.Application"
            )),
        }
    }
}

impl Jni for ScriptedJni {
    fn with_env(
        &self,
        on: JavaObject,
        f: &mut dyn FnMut(*mut c_void, *mut c_void),
    ) -> Result<(), String> {
        self.record("<jobject passed to C>", on);
        let mut slot = self.env.lock().unwrap_or_else(|e| e.into_inner());
        let env = slot.get_or_insert_with(|| Box::new(HostEnv::new()));
        f(
            std::ptr::from_mut::<HostEnv>(env).cast(),
            Self::handle(on) as *mut c_void,
        );
        match env.catch() {
            Some(exception) => Err(format!("Java exception left pending: {exception}")),
            None => Ok(()),
        }
    }

    fn check_self_permission(&self, on: JavaObject, permission: &str) -> Result<bool, String> {
        self.record("checkSelfPermission", on);
        Ok(permission == CAMERA_PERMISSION && self.lock().0.permission_granted)
    }

    fn request_permissions(&self, on: JavaObject, _: &str, _: i32) -> Result<(), String> {
        self.record("requestPermissions", on);
        Self::activity_only("requestPermissions", on)?;
        let mut s = self.lock();
        s.0.permission_granted = s.0.dialog_answer;
        s.2 = true;
        Ok(())
    }

    fn display_rotation(&self, on: JavaObject) -> Result<i32, String> {
        self.record("getWindowManager", on);
        Self::activity_only("getWindowManager", on)?;
        Ok(self.lock().0.rotation)
    }

    fn sdk_int(&self) -> u32 {
        self.lock().0.sdk_int
    }
}
