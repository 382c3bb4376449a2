//! The objects behind ARCore's opaque pointers, and the helpers every export uses.

use std::ffi::c_void;

use ar::Intrinsics;
use glam::Mat4;

use crate::cameras::CameraConfig;
use crate::feed::PhoneImage;

/// `ArSession`.
pub struct Session {
    pub light_mode: i32,
    pub resumed: bool,
    /// The camera config in use (`ArSession_setCameraConfig`; the phone's default until set).
    pub camera: CameraConfig,
    /// The camera config of the last successful resume (`None` before the first).
    pub resumed_camera: Option<CameraConfig>,
    /// `ArSession_setDisplayGeometry`: rotation and view size (0 × 0: not set).
    pub rotation: i32,
    pub view: (i32, i32),
}

/// `ArConfig`.
#[derive(Clone, Copy, Default)]
pub struct Config {
    pub plane_finding: i32,
    pub light: i32,
    pub update: i32,
    pub texture: i32,
}

/// `ArFrame`: what `ArSession_update` showed into it.
#[derive(Default)]
pub struct Frame {
    pub timestamp_ns: i64,
    pub updated: bool,
}

/// `ArCamera`: the camera of one frame.
pub struct Camera {
    pub camera_to_world: Mat4,
    pub tracking: (i32, i32),
    pub intrinsics: Intrinsics,
    pub rotation: i32,
    pub view: (i32, i32),
}

/// `ArPose`: `[qx, qy, qz, qw, tx, ty, tz]`.
pub struct Pose(pub [f32; 7]);

/// `ArCameraIntrinsics`.
#[derive(Default)]
pub struct CameraIntrinsics(pub Option<Intrinsics>);

/// `ArImage`.
pub struct Image(pub PhoneImage);

/// `ArLightEstimate`.
#[derive(Default)]
pub struct LightEstimate {
    pub state: i32,
    pub mode: i32,
    pub towards: [f32; 3],
}

/// `ArTrackableList`: plane ids.
#[derive(Default)]
pub struct TrackableList(pub Vec<usize>);

/// `ArPlane` (an acquired `ArTrackable`): id into the simulator's plane list.
pub struct Plane(pub usize);

/// A new object for C: boxed, counted as live under `kind` by the caller.
pub fn into_c<T>(value: T) -> *mut c_void {
    Box::into_raw(Box::new(value)).cast()
}

/// Frees an object made by [`into_c`]; false for null.
///
/// SAFETY (callers): `p` is null or came from `into_c::<T>` and is freed once.
pub unsafe fn free_c<T>(p: *mut c_void) -> bool {
    if p.is_null() {
        return false;
    }
    // SAFETY: per the function's contract.
    drop(unsafe { Box::from_raw(p.cast::<T>()) });
    true
}

/// The object behind `p`, if not null.
///
/// SAFETY (callers): `p` is null or a live object of type `T`.
pub unsafe fn obj<'a, T>(p: *const c_void) -> Option<&'a T> {
    // SAFETY: per the function's contract.
    unsafe { p.cast::<T>().as_ref() }
}

/// Mutable access to the object behind `p`, if not null.
///
/// SAFETY (callers): as [`obj`], and no other reference to it lives.
pub unsafe fn obj_mut<'a, T>(p: *mut c_void) -> Option<&'a mut T> {
    // SAFETY: per the function's contract.
    unsafe { p.cast::<T>().as_mut() }
}

/// Writes `value` to `out` unless it is null.
///
/// SAFETY (callers): `out` is null or valid for a write of `T`.
pub unsafe fn put<T>(out: *mut T, value: T) {
    if !out.is_null() {
        // SAFETY: per the function's contract.
        unsafe { out.write(value) };
    }
}

/// Writes `values` to `out` unless it is null.
///
/// SAFETY (callers): `out` is null or valid for `values.len()` writes.
pub unsafe fn put_all<T: Copy>(out: *mut T, values: &[T]) {
    if !out.is_null() {
        // SAFETY: per the function's contract.
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), out, values.len()) };
    }
}
