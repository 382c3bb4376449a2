//! The `regatta` package: the command line and desktop app (host), and the Android cdylib
//! (`android_main`). Everything here is wiring; the domain lives in the crates.

pub mod bench;
pub mod cli;
#[cfg(not(target_os = "android"))]
pub mod desktop;
pub mod error;
pub mod overlay;
pub mod pool_play;
pub mod tier_control;
pub mod tier_render;
pub mod wakes;

#[cfg(target_os = "android")]
mod android;
