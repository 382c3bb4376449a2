//! The app core: everything the desktop window, the phone and the headless phone sessions share,
//! free of any platform (compiled and tested on the host).
//!
//! - the race at time t: [`crate::world`] (below the core: the race overlays, the set-up and
//!   the feed use it too).
//! - time: race time is the panels' `ui::RaceClock`; the shells feed wall seconds
//!   (`crate::wall_clock::Ticker`, outside the core).
//! - [`table`]: one mapping of the race onto the table (`ar::arcore::CoursePlacement`).
//! - [`camera_frame`]: one conversion of an AR camera frame into the effect passes' frame.
//! - [`gfx`]: renderer setup, the window's target with its kept configuration, surface loss,
//!   the OpenGL ES fallback.
//! - [`ar`]: the AR backend trait and the session's state; ARCore's C API implements it
//!   (`ar_ffi`: Google's library on the phone, `crates/arcore_sim` on the host).
//! - [`phone`]: the phone app, driven by events ([`phone::AppEvent`]).
//! - [`vulkan_marker`]: a launch that crashed on its first Vulkan frames sends the next one to
//!   OpenGL ES.
//!
//! Invariant: nothing here names winit, android-activity, JNI or a clock of the OS; the
//! adapters (`desktop`, `android`, `phone_sim`) translate their platform's events and wall time
//! into calls on this core and hold no decision of their own.

pub mod app;
pub mod ar;
mod ar_ffi;
pub mod camera_frame;
pub mod feed;
pub mod gfx;
pub mod table;
pub mod vulkan_marker;
