//! The scene set-up: what every app and command draws from, in one place. Validated options (a
//! race, a sea, a scene, sizes, a tier, effects, wakes, water, overlays) become the race world,
//! its renderer ([`RaceSetup`]) and the files it writes: the command line
//! keeps only its flags and the glue between them and this module (as ripgrep's binary does),
//! and the desktop window, the phone, `phone-sim` and the bench take the same set-up.
//!
//! It never knows the command line's argument structs (clap's `Args`, `cli::*Args`) or a
//! platform (winit, android-activity). Its one-line errors name the option a value stands for
//! (`--size`, `--from`), which the app's "Share clip" reports in the same words.

pub mod clip;
pub mod inputs;
pub mod output;
mod race_setup;

pub use race_setup::{PHONE_RENDER_SCALE, Profile, RaceSetup};

/// The scenes `regatta render` and `regatta run` draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum SceneKind {
    #[default]
    Race,
    Pool,
}
