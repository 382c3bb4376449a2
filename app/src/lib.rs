//! The `regatta` package: the command line and desktop app (host), and the Android cdylib
//! (`android_main`). Everything here is wiring; the domain lives in the crates.

pub mod cli;
pub mod core;
#[cfg(not(target_os = "android"))]
pub mod desktop;
pub mod error;
pub mod hud;
pub mod panels;
#[cfg(not(target_os = "android"))]
pub mod phone_sim;
pub mod pool_play;
pub mod scene_overlay;
pub mod setup;
#[cfg(not(target_os = "android"))]
pub mod sim_phone;
pub mod terminal;
pub mod tier_control;
pub mod tier_render;
pub mod wakes;
pub mod wall_clock;
pub mod water;
pub mod world;

#[cfg(target_os = "android")]
mod android;
#[cfg(any(target_os = "android", test))]
mod android_log;
