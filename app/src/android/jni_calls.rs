//! The phone's [`Jni`]: the Java calls of the ARCore glue through the `jni` crate, each on the
//! object it names: the Activity (`AndroidApp::activity_as_ptr()`) or the Application that
//! android-activity hands to `ndk_context`. The host runs the same glue against
//! `ar::arcore::ffi::ScriptedJni`.

use std::ffi::c_void;

use android_activity::AndroidApp;
use ar::arcore::ffi::{JavaObject, Jni};
use jni::objects::JObject;
use jni::{JValue, jni_sig, jni_str};

pub struct AndroidJni {
    /// The Activity's `jobject`: a global reference held by the native activity for its life.
    activity: *mut c_void,
    sdk_int: u32,
}

impl AndroidJni {
    pub fn new(app: &AndroidApp) -> Self {
        Self {
            activity: app.activity_as_ptr(),
            sdk_int: app.config().sdk_version().max(0) as u32,
        }
    }

    fn object(&self, on: JavaObject) -> *mut c_void {
        match on {
            JavaObject::Activity => self.activity,
            JavaObject::Application => ndk_context::android_context().context(),
        }
    }

    /// `f` on this thread attached to the VM, with `on`'s object (also `intents.rs`'s calls).
    pub(super) fn attached<T>(
        &self,
        on: JavaObject,
        f: impl FnOnce(&mut jni::Env<'_>, JObject<'_>) -> jni::errors::Result<T>,
    ) -> Result<T, String> {
        let ctx = ndk_context::android_context();
        // SAFETY: ndk-context holds the process's JavaVM, set by android-activity.
        let vm = unsafe { jni::JavaVM::from_raw(ctx.vm().cast()) };
        let object = self.object(on);
        vm.attach_current_thread(|env| -> jni::errors::Result<T> {
            // SAFETY: both objects are global references that live as long as the app.
            let receiver = unsafe { JObject::from_raw(env, object.cast()) };
            f(env, receiver)
        })
        .map_err(|e| e.to_string())
    }
}

impl Jni for AndroidJni {
    fn with_env(
        &self,
        on: JavaObject,
        f: &mut dyn FnMut(*mut c_void, *mut c_void),
    ) -> Result<(), String> {
        let object = self.object(on);
        self.attached(on, |env, _| {
            f(env.get_raw().cast(), object);
            // ARCore's native half calls its Java half (the install activity,
            // SessionCreateJniHelper); what that throws stays pending here. Caught, it is
            // cleared (the next JNI call would abort on it) and becomes this call's error with
            // its class, message and stack, which the glue logs (issue 26, defect 2).
            env.exception_catch()
        })
    }

    fn check_self_permission(&self, on: JavaObject, permission: &str) -> Result<bool, String> {
        self.attached(on, |env, receiver| {
            let name = env.new_string(permission)?;
            Ok(env
                .call_method(
                    &receiver,
                    jni_str!("checkSelfPermission"),
                    jni_sig!("(Ljava/lang/String;)I"),
                    &[JValue::Object(&name)],
                )?
                .i()?
                == 0)
        })
    }

    fn request_permissions(
        &self,
        on: JavaObject,
        permission: &str,
        request_code: i32,
    ) -> Result<(), String> {
        self.attached(on, |env, receiver| {
            let name = env.new_string(permission)?;
            let string_class = env.find_class(jni_str!("java/lang/String"))?;
            let names = env.new_object_array(1, &string_class, &name)?;
            env.call_method(
                &receiver,
                jni_str!("requestPermissions"),
                jni_sig!("([Ljava/lang/String;I)V"),
                &[JValue::Object(&names), JValue::Int(request_code)],
            )?;
            Ok(())
        })
    }

    fn display_rotation(&self, on: JavaObject) -> Result<i32, String> {
        self.attached(on, |env, receiver| {
            let wm = env
                .call_method(
                    &receiver,
                    jni_str!("getWindowManager"),
                    jni_sig!("()Landroid/view/WindowManager;"),
                    &[],
                )?
                .l()?;
            let display = env
                .call_method(
                    &wm,
                    jni_str!("getDefaultDisplay"),
                    jni_sig!("()Landroid/view/Display;"),
                    &[],
                )?
                .l()?;
            env.call_method(&display, jni_str!("getRotation"), jni_sig!("()I"), &[])?
                .i()
        })
    }

    fn sdk_int(&self) -> u32 {
        self.sdk_int
    }
}
