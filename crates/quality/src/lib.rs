//! `quality`: what the renderer may spend on a frame, and the governor that chooses it.
//!
//! - [`Tier`] names a documented set of renderer settings ([`TierSettings`]: render scale,
//!   clip-map error target, which AR effects run and at what resolution, the flow map, the wake
//!   source spacing and budget, the overlay detail, the largest camera image), from `low` (an
//!   OPPO A54 at 30 fps) to `ultra` (everything at full size).
//! - [`Governor`] watches frame times (GPU timestamps where the adapter has them, else the
//!   intervals between presents) and moves between tiers to hold a frame-rate target, with
//!   hysteresis and a minimum dwell so it never oscillates, and never while the user scrubs.
//!
//! Invariant: pure policy. It never knows wgpu, egui, a clock or a platform: the app feeds it
//! (time, frame time, scrubbing) and maps a tier's settings onto its renderer options. Every
//! decision is a function of the samples it was given, so a recorded or synthetic trace replays
//! to the same decisions.

mod governor;
mod tier;

pub use governor::{Change, Governor, GovernorConfig, Target};
pub use tier::{CAMERA_IMAGE_SHARE, OverlayDetail, Tier, TierSettings};
