//! The display-oriented camera ARCore computes from `ArSession_setDisplayGeometry`: a back
//! camera whose sensor is mounted 90° clockwise (`SENSOR_ORIENTATION` of most phones), the
//! image filling the view and cropped evenly (`ar::arcore::display_uv_transform`).

use ar::Intrinsics;
use ar::arcore::{DisplayRotation, display_uv_transform, gl_projection_to_wgpu};
use glam::{Affine2, DMat4, DVec2, DVec3, Mat4, Vec2};

use crate::objects::Camera;

/// `CameraCharacteristics.SENSOR_ORIENTATION` of the simulated back camera, degrees.
pub const SENSOR_ORIENTATION: u32 = 90;

/// The view size: as set, or (before `ArSession_setDisplayGeometry`) the turned image's.
fn view_size(rotation: i32, view: (i32, i32), k: &Intrinsics) -> (u32, u32) {
    if view.0 > 0 && view.1 > 0 {
        return (view.0 as u32, view.1 as u32);
    }
    if turn_degrees(rotation).is_multiple_of(180) {
        (k.width, k.height)
    } else {
        (k.height, k.width)
    }
}

/// Clockwise turn of the sensor image on the display, degrees.
fn turn_degrees(rotation: i32) -> u32 {
    let rot = DisplayRotation::from_surface(rotation.rem_euclid(4)).unwrap_or(DisplayRotation::R0);
    (SENSOR_ORIENTATION + 360 - rot.degrees()) % 360
}

/// View-normalised UV → image-normalised UV.
pub fn view_to_image(rotation: i32, view: (i32, i32), k: &Intrinsics) -> Affine2 {
    let rot = DisplayRotation::from_surface(rotation.rem_euclid(4)).unwrap_or(DisplayRotation::R0);
    display_uv_transform(
        SENSOR_ORIENTATION,
        rot,
        (k.width, k.height),
        view_size(rotation, view, k),
    )
}

/// The display-oriented camera: (world → display camera, OpenGL projection, in pixels its
/// intrinsics for the view).
pub fn display_camera(cam: &Camera, near: f32, far: f32) -> (Mat4, Mat4) {
    let k = cam.intrinsics;
    let (vw, vh) = view_size(cam.rotation, cam.view, &k);
    let a = view_to_image(cam.rotation, cam.view, &k).as_daffine2();
    let (iw, ih) = (f64::from(k.width), f64::from(k.height));
    let (vwf, vhf) = (f64::from(vw), f64::from(vh));
    // Display camera axes in the image camera's: a counter-clockwise turn about z by the
    // clockwise turn of the image on screen.
    let turn = DMat4::from_rotation_z(f64::from(turn_degrees(cam.rotation)).to_radians());
    let inverse = a.inverse();
    // The view pixel where the image camera's ray `d` (camera axes, z = −1) shows.
    let view_px = |d: DVec3| {
        let p = DVec2::new(k.cx + k.fx * d.x / -d.z, k.cy - k.fy * d.y / -d.z);
        inverse.transform_point2(p / DVec2::new(iw, ih)) * DVec2::new(vwf, vhf)
    };
    let centre = view_px(DVec3::NEG_Z);
    let right = view_px(turn.transform_vector3(DVec3::new(1.0, 0.0, -1.0)));
    let up = view_px(turn.transform_vector3(DVec3::new(0.0, 1.0, -1.0)));
    let display_k = Intrinsics {
        fx: (right - centre).length(),
        fy: (up - centre).length(),
        cx: centre.x,
        cy: centre.y,
        width: vw,
        height: vh,
    };
    let wgpu = display_k.projection_wgpu(f64::from(near), f64::from(far));
    let gl = gl_projection_to_wgpu(DMat4::IDENTITY).inverse() * wgpu;
    let display_to_world = cam.camera_to_world.as_dmat4() * turn;
    (display_to_world.inverse().as_mat4(), gl.as_mat4())
}

/// `ArFrame_transformCoordinates2d` between the two normalised systems Regatta uses; other
/// pairs are passed through unchanged.
pub fn transform(cam: &Camera, from: i32, to: i32, p: Vec2) -> Vec2 {
    const IMAGE_NORMALIZED: i32 = 3;
    const VIEW_NORMALIZED: i32 = 8;
    let a = view_to_image(cam.rotation, cam.view, &cam.intrinsics);
    match (from, to) {
        (VIEW_NORMALIZED, IMAGE_NORMALIZED) => a.transform_point2(p),
        (IMAGE_NORMALIZED, VIEW_NORMALIZED) => a.inverse().transform_point2(p),
        _ => p,
    }
}
