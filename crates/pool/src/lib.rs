//! `pool`: the pool scene (`--scene pool`): a tiled box pool with moving water, floating and moving
//! spheres, reflection and refraction traced against the analytic spheres and the box, the full
//! Fresnel equations, Phong shading and caustics on the floor and walls.
//!
//! The CS114 WebGL pool report (2018, report 004 in docs/sources.md) draws this scene in WebGL with still water and no caustics; here the water
//! moves (Gerstner waves from `ocean` plus analytic ripples where a sphere moves, see
//! [`water`]) and the caustics come from the moving surface (area ratio, see [`caustics`]).
//!
//! Invariant: it knows nothing of ARCore, egui, the command line, races or the AR effects;
//! `render` (the core it draws with) knows nothing of it.
//!
//! Everything here but [`gpu`] is f64 and GPU-free: it is the reference the shader
//! (`shaders/pool_common.wgsl` with `pool_scene.wgsl`, `pool_water.wgsl` and
//! `pool_caustics.wgsl`) is tested against, and it gives the shader its f32-safe inputs.
//! Pool space: metres, x east, y up, z south, the water's rest level at y = 0, the pool centred
//! on the origin. In AR a model transform puts pool space on the detected table, exactly as it
//! does for the race course.

pub mod caustics;
pub mod geometry;
pub mod gpu;
pub mod interact;
pub mod scene;
pub mod trace;
pub mod water;
pub mod wgsl;

pub use caustics::CausticMap;
pub use geometry::{BoxHit, Face, PoolBox, Ray, Sphere};
pub use gpu::{PoolFrame, PoolRenderer, PoolReport, PoolSettings, PoolView, render_pool_image};
pub use interact::pointer_ray;
pub use scene::{Floater, Mover, PoolScene};
pub use water::{PoolWater, Ring, RippleModel, SpherePath, WaterPoint};

/// The time `regatta render --scene pool` draws without `--t`, seconds.
pub const DEFAULT_T: f64 = 4.0;
/// Far clip distance of the pool's cameras, metres.
pub const FAR_M: f64 = 50.0;

#[cfg(test)]
mod gpu_tests;
