//! The app's ARCore C API glue, built on every target (feature `ffi`): on Android it loads
//! Google's `libarcore_sdk_c.so`; on the host the same code loads the simulator
//! (`crates/arcore_sim`, path from [`LIBRARY_ENV`]) so that the phone's code paths run in tests.
//!
//! - [`api`]: the function tables (names and signatures of `arcore_c_api.h`), loaded with
//!   libloading;
//! - [`frame`]: one frame read into an [`crate::CameraFrame`] and a [`DisplayCamera`];
//! - [`session`]: [`ArCore`], which carries out the session machine's commands;
//! - [`camera_config`]: the camera config with the largest CPU image the budget affords, set
//!   before a resume ([`CameraBudget`]);
//! - [`jni`]: the Java calls behind one trait ([`Jni`]), with the host's scripted fake;
//! - [`intent`]: the file an "Open with" or "Share" intent carries, read through the
//!   ContentResolver ([`IntentJni`]; the scripted fake plays the content provider);
//! - [`share`]: a file into the media store and to the share sheet ([`ShareJni`]; the
//!   scripted fake plays the media store and records the chooser).
//!
//! `session` imports `frame`, `camera_config` and `api`; `frame` and `camera_config` import
//! only `api` (no module cycle).

pub mod api;
pub mod camera_config;
pub mod frame;
pub mod intent;
mod intent_file;
pub mod jni;
pub mod session;
pub mod share;
mod share_media;

pub use camera_config::{CameraBudget, CameraConfigOutcome};
pub use frame::{DisplayCamera, FAR_M, NEAR_M};
pub use intent::{IntentFile, IntentJni};
pub use jni::{JavaObject, JavaScript, Jni, ScriptedJni};
pub use session::{ARCORE_LIBRARY, ArCore, LIBRARY_ENV, Told, library_path};
pub use share::{MediaItem, ShareJni};
