//! Boat wakes, analytic at any race time: the ring model of the Sailing+ wave-model thesis (TU Delft 2022, report 003 in docs/sources.md) (its eq. 3, the
//! baseline) and a Kelvin-correct model, with an independent f64 reference and the per-frame
//! GPU source buffer.
//!
//! Input: each boat's sampled track, `&[TrackSample { t, x, z }]` (race seconds, world metres),
//! times non-decreasing; never the race crate's types.
//!
//! - [`Wake`] (`kelvin.rs`): the Kelvin-correct wake. Sources are emitted by distance sailed
//!   along the (curved) path; each is a Cauchy–Poisson ring-wave packet of a Gaussian pressure
//!   patch (force F = m g, radius R) whose radius grows with the group speed and whose phase
//!   follows deep-water dispersion; summed, they make the Kelvin wake (19.47° half-angle at
//!   every speed, transverse wavelength 2πU²/g, nothing from a boat that does not move). The
//!   amplitude law and its source are in `kelvin.rs`. `Wake::height(p, t)` and
//!   `Wake::foam(p, t)` depend only on the sources alive at t (younger than `max_age`): the
//!   same t gives the same bits whether reached by playing or scrubbing.
//! - [`RingWake`] (`ring.rs`): 003 eq. 3 as stated, for comparison.
//! - [`reference`]: the Havelock integral for a straight steady track, f64, with its own
//!   convergence estimate.
//! - [`measure`]: the envelope half-angle and the transverse wavelength of any field.
//!
//! For the renderer (`gpu.rs`), per frame:
//!
//! ```text
//! let frame = wake.gpu_sources(t, origin, &WakeView { min, max }, 1e-6);
//! // upload frame.bytes() (each source's WakeKernelSource) as a storage buffer of
//! // WakeSource (`wake_wgsl()`: shaders/ocean/wake.wgsl after its constants) and
//! // turn_table::turn_table_bytes() as an Rg16Float texture (`turn_table_bindings`); a shader sums
//! // wake_source_height(p) (or its gradient) and wake_source_foam(p) over the sources,
//! // p = world (x, z) − origin, both f32.
//! ```
//!
//! The cost per point is the number of sources that reach the view, not the course size or a
//! texture (the kernel's one texture is the 8 KiB table of one turn it takes sin and cos from,
//! `crate::turn_table`). `wake_height_f32`/`wake_foam_f32` are the CPU mirrors of the WGSL;
//! culling, f32 and the table have stated error bounds (`GpuWakeFrame::cull_bound`,
//! `f32_height_error_bound` with `gpu_sin_cos_error()` for a GPU). `app/tests/wake_gpu.rs` runs the WGSL in a compute pass and
//! checks it against the mirror.

pub mod froude;
pub mod gpu;
pub mod kelvin;
pub mod kernel;
pub mod measure;
pub mod reference;
pub mod ring;
mod track;
pub mod wgsl;

#[cfg(test)]
mod tests;

pub use froude::{TableModel, capillary_gravity_transverse_wavelength};
pub use gpu::{
    BAND_END, BAND_FADE_F32_ERROR, BAND_START, FOAM_EPSILON, GpuWakeFrame, GpuWakeSource, WakeView,
    band_edges, band_fade, band_fade_f32, f32_height_error_bound, foam_radius2, gpu_sin_cos_error,
    inner_radius2, mirror_sin_cos_error, source_height_grad_f32, source_height_grad_sampled_f32,
    source_peak_bound, wake_foam_f32, wake_height_f32, wake_height_grad_f32,
    wake_height_grad_sampled_f32,
};
pub use kelvin::{KelvinSource, SEA_WATER_DENSITY, Wake, WakeParams};
pub use kernel::WakeKernelSource;
pub use reference::{SteadyPatch, kelvin_reference, kelvin_wave_height};
pub use ring::{RingParams, RingWake};
pub use track::{TrackSample, WakeError};
pub use wgsl::{turn_table_bindings, wake_wgsl};
