//! The app core: everything the desktop window, the phone and the headless phone sessions share,
//! free of any platform (compiled and tested on the host).
//!
//! - the race at time t: [`crate::world`] (below the core: the race overlays and the set-up
//!   use it too).
//! - time: race time is the panels' `ui::RaceClock`; the shells feed wall seconds
//!   (`crate::wall_clock::Ticker`, outside the core).
//! - [`table`]: one mapping of the race onto the table (`ar::arcore::CoursePlacement`).
//! - [`camera_frame`]: one conversion of an AR camera frame into the effect passes' frame.
//! - [`gfx`]: renderer setup, the window's target with its kept configuration, surface loss,
//!   the OpenGL ES fallback.
//! - [`ar`]: the AR backend trait and the session's state; ARCore's C API implements it
//!   (`ar_ffi`: Google's library on the phone, `crates/arcore_sim` on the host).
//! - [`app`]: the app of the desktop window and the phone, one type ([`app::App`]) driven by
//!   events ([`app::AppEvent`]) and frames, with a profile for what differs.
//! - [`feed`]: the camera feed (recorded or synthetic) and the race on its table, which the
//!   desktop app draws behind the race (and `regatta render --replay`, the simulated ARCore).
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
