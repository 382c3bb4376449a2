//! Frame sources for Regatta: the one [`FrameSource`] interface that the desktop replay and
//! synthetic feeds and ARCore on Android share, and the desktop readers and writers.
//!
//! Knows nothing of wgpu or egui (ARCHITECTURE.md).

pub mod arcore;
mod error;
mod frame;
mod frame_file;
mod pose;
pub mod replay;
pub mod synth;

pub use error::ArError;
pub use frame::{
    CameraFrame, DetectedPlane, FrameImage, FrameSource, Intrinsics, PlaneKind, TrackingState,
};
pub use pose::{Pose, QUAT_NORM_TOLERANCE};
pub use replay::{ReplayFeed, ReplayPlayer, ReplayWriter};
pub use synth::SynthConfig;
