//! `render`: the wgpu render core of Regatta, shared by the desktop app, `regatta render` and
//! the APK. It draws the analytic sea of `ocean` on a camera-following clip-map, the boats and
//! the marks, and records for every frame which passes ran and why (the frame planner). The AR
//! effects (`effects`) and the pool scene (`pool`) are crates on top of it.
//!
//! Invariant: it knows nothing of ARCore, egui, the command line, races (`race`), the AR
//! effects or the pool: they plug in through [`frame::Pass`] and the helpers here. Units: metres, seconds,
//! world x east, y up, z south. No absolute race time or large coordinate reaches a shader:
//! shaders work in *local* metres (world minus the frame's origin, the clip-map centre) and
//! get wave phases reduced in f64 on the CPU (`ocean::WaveSet::gpu_waves`).
//!
//! # Modules
//! - [`gpu`]: device setup for a window, headless and Android; [`gpu::test_gpu`] for tests.
//! - [`camera`], [`scene`]: what a frame shows, in world f64; floating bodies.
//! - [`clipmap`]: the LOD mesh from a screen-space error target, morphing, tile culling.
//! - [`frame`]: the pass framework, the frame uniform and the planner's [`frame::FrameReport`].
//! - [`passes`]: sky, water (with the boats' wakes), boats. [`renderer`]: runs the passes;
//!   offscreen images; [`renderer::Renderer::set_wake`] gives it a race's wakes.
//! - [`wake_bins`]: the wake sources binned for the GPU within the buffer limits and budget.
//! - [`compute`]: the same WGSL sea on a compute shader (the f64 parity test);
//!   [`mesh_error`]: a clip-map's measured screen-space height error (the mesh bench).
//! - [`wgsl_accuracy`]: the f32 accuracy WGSL guarantees per built-in and the running error
//!   bound every GPU parity test derives its tolerance from.
//!
//! # Adding a pass (effects, wakes, pool)
//! 1. **WGSL**: one file `shaders/<name>.wgsl` (in the crate that owns the pass) with `vs_main`/`fs_main` (or `cs_main`). It is
//!    appended to `shaders/common.wgsl` and `shaders/optics.wgsl` ([`shader::source`]), so it
//!    uses bind group 0 as declared there (`frame`, `waves`) and its helpers (`gerstner`,
//!    `surface_frame`, `sky_colour`, `fresnel_reflectance`, ...). Its own resources go in
//!    bind group 1 and up. Add an `include_str!` constant for it in `shader.rs` (or in your
//!    module).
//! 2. **Rust**: a module (`passes/<name>.rs`, or in your own crate as `effects`, `pool` do) with a type
//!    implementing [`frame::Pass`]: build the pipeline in `new` with
//!    [`passes::pipeline`] (or by hand when you need more bind groups, using
//!    [`renderer::Renderer::frame_layout`] for group 0); upload per-frame data in `prepare`;
//!    record draws in `draw` and return the triangles drawn.
//! 3. **Planner condition**: [`frame::Pass::condition`] states in words when the pass is
//!    needed; [`frame::Pass::plan`] decides it for a frame from the [`frame::FrameContext`]
//!    (camera, frustum, scene, clip-map) and returns `Ok(why)` or `Err(why not)`. The report
//!    carries both, with the triangles and GPU milliseconds (timestamp queries) per pass.
//! 4. Register it with [`renderer::Renderer::add_pass`] (drawn after sky, water, boats, in
//!    order) or, for a built-in pass, in `Renderer::new`. Each pass gets its own render pass
//!    on the shared colour and depth targets; the first one that runs clears them.

pub mod camera;
pub mod clipmap;
pub mod compute;
pub mod frame;
#[doc(hidden)]
pub mod golden;
pub mod gpu;
pub(crate) mod hull;
pub mod mesh_error;
pub mod optics;
pub mod passes;
pub mod pure_water;
pub mod renderer;
pub mod scene;
pub mod shader;
mod timing;
pub mod turn_table;
pub mod vertex_slopes;
pub mod view_light;
pub mod wake_bins;
pub mod wake_spacing;
pub mod water_look;
pub mod water_types;
pub mod wgsl_accuracy;

pub use camera::{Camera, OrbitCamera};
pub use frame::{FRAME_REUSED, FrameReport, Pass};
pub use gpu::{Gpu, GpuError};
pub use renderer::{OFFSCREEN_FORMAT, RenderOptions, Renderer, render_image};
pub use scene::{Boat, Mark, Scene};
