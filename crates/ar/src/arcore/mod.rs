//! ARCore on Android, the parts that are pure and tested on the host: the camera image's YUV
//! decoding ([`yuv`]), the camera config to ask for ([`camera_config`]), ARCore's pose and
//! projection conventions and the course placement ([`pose`]), the display rotation transform
//! ([`display`]), the tap hit test and two-finger gestures ([`hit`]), and the session state
//! machine ([`session`]). With the `ffi` feature,
//! [`ffi`] is the glue that calls the ARCore C API (loaded with libloading), on the phone and,
//! against `crates/arcore_sim`, on the host.

pub mod camera_config;
pub mod display;
#[cfg(feature = "ffi")]
pub mod ffi;
pub mod hit;
pub mod pose;
pub mod session;
pub mod yuv;

pub use camera_config::{CameraConfigSize, DOCUMENTED_BACK_CAMERA, choose_camera_config};
pub use display::{DisplayRotation, affine_from_three, display_uv_transform};
pub use hit::{Ray, TwoFingerGesture, hit_plane, hit_test, tap_ray};
pub use pose::{CoursePlacement, gl_projection_to_wgpu, intrinsics_from_projection, pose_from_raw};
pub use session::{Command, Event, LightMode, SessionState, Unavailable};
pub use yuv::{YuvRange, YuvToRgb};
