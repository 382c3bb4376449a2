//! `ocean`: the sea state of a race as closed-form functions of race time.
//!
//! Pure math in f64: Gerstner waves as the Sailing+ wave-model thesis (TU Delft 2022, report 003 in docs/sources.md) states them (plus finite depth),
//! their inverse, normals and Jacobian; the wakes; and f32-safe inputs for a GPU whose phases
//! are reduced here, in f64, so that no shader ever sees an absolute race time or a large
//! coordinate.
//!
//! Invariant: this crate knows nothing of wgpu, egui, Android or the race model's types.
//! Units: metres and seconds; world frame x east, y up, z south (docs/command-line.md).

pub mod cull;
pub mod gerstner;
pub mod gpu;
pub mod inverse;
pub mod ndbc;
pub mod sea_file;
pub mod spectrum;
pub mod turn_table;
pub mod wake;

pub use cull::Culled;
pub use gerstner::{
    FOAM_ONSET_JACOBIAN, SurfacePoint, Wave, WaveSet, foam_coverage, foam_from_jacobian,
};
pub use gpu::{GpuWave, displace_f32, f32_error_bound, reduce_phase, sort_by_wavenumber};
pub use inverse::{DEFAULT_TOLERANCE, InverseError, RestPoint, WorldSample};
pub use sea_file::SeaError;

/// Standard gravity used when a sea file does not say otherwise, m/s².
pub const STANDARD_GRAVITY: f64 = 9.81;

/// The default sea, embedded from `assets/seas/default.json`.
pub const DEFAULT_SEA_JSON: &str = include_str!("../../../assets/seas/default.json");
