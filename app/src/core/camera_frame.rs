//! One conversion of an AR camera frame (`ar::CameraFrame`, AR metres) into the effect passes'
//! backdrop (`effects::backdrop::Backdrop`, race metres) and the render camera,
//! for the desktop feed and the phone. The course placement maps the camera's pose; the display
//! transform says which part of the image the view shows: ARCore's (`display_uv`, rotation and
//! crop) on the phone, a crop of the image to the window's aspect on the desktop.

use ar::CameraFrame;
use ar::arcore::CoursePlacement;
use effects::backdrop::{Backdrop, CameraImage};
use glam::{DMat4, DQuat, DVec3};
use render::Camera;
use render::optics::PinholeCamera;

/// Screen uv → image uv as a 2×3 affine map (rows), as the effect passes take it.
pub type Display = [[f64; 3]; 2];

/// The frame's own display transform (ARCore's `ArFrame_transformCoordinates2d`).
pub fn display_of(frame: &CameraFrame) -> Display {
    let d = frame.display_uv;
    [
        [
            f64::from(d.matrix2.x_axis.x),
            f64::from(d.matrix2.y_axis.x),
            f64::from(d.translation.x),
        ],
        [
            f64::from(d.matrix2.x_axis.y),
            f64::from(d.matrix2.y_axis.y),
            f64::from(d.translation.y),
        ],
    ]
}

/// The image filling a view of `size` pixels, cropped to its aspect: the display transform and
/// the vertical field of view of the crop.
pub fn fill_view(k: &ar::Intrinsics, size: [u32; 2]) -> (Display, f64) {
    let (iw, ih) = (f64::from(k.width), f64::from(k.height));
    let a_img = iw / ih;
    let a_win = f64::from(size[0].max(1)) / f64::from(size[1].max(1));
    if a_win >= a_img {
        // Wider view: the full image width, a band of its height.
        let f = a_img / a_win;
        (
            [[1.0, 0.0, 0.0], [0.0, f, 0.5 * (1.0 - f)]],
            2.0 * (0.5 * ih * f / k.fy).atan(),
        )
    } else {
        let f = a_win / a_img;
        (
            [[f, 0.0, 0.5 * (1.0 - f)], [0.0, 1.0, 0.0]],
            2.0 * (0.5 * ih / k.fy).atan(),
        )
    }
}

/// The physical camera's pose in race metres: rotation with the placement's turn undone, the
/// position mapped.
fn race_pose(frame: &CameraFrame, placement: &CoursePlacement) -> (DQuat, DVec3) {
    let (_, rot, pos) = frame
        .camera_to_world
        .as_dmat4()
        .to_scale_rotation_translation();
    (
        DQuat::from_rotation_y(-placement.yaw) * rot,
        placement.ar_to_race().transform_point3(pos),
    )
}

/// The effect passes' backdrop (without its image) for `frame` on the table of `placement`.
pub fn backdrop_of(
    frame: &CameraFrame,
    placement: &CoursePlacement,
    display: Display,
) -> Backdrop<()> {
    let (rot, eye) = race_pose(frame, placement);
    let k = frame.intrinsics;
    Backdrop {
        image: (),
        camera: PinholeCamera {
            fx: k.fx,
            fy: k.fy,
            cx: k.cx,
            cy: k.cy,
            width: f64::from(k.width),
            height: f64::from(k.height),
            pose: DMat4::from_rotation_translation(rot, eye),
        },
        display,
    }
}

/// [`backdrop_of`] with the image as the GPU takes it (YUV planes repacked, or RGBA).
pub fn backdrop_with_image(
    frame: &CameraFrame,
    placement: &CoursePlacement,
    display: Display,
) -> Result<Backdrop<CameraImage>, ar::ArError> {
    Ok(backdrop_of(frame, placement, display).with_image(frame.image.to_camera_image()?))
}

/// The render camera (race metres) looking through the physical camera with vertical field of
/// view `fov_y`.
pub fn physical_camera(frame: &CameraFrame, placement: &CoursePlacement, fov_y: f64) -> Camera {
    let (rot, eye) = race_pose(frame, placement);
    Camera {
        eye,
        target: eye + rot * DVec3::NEG_Z,
        up: rot * DVec3::Y,
        fov_y,
        near: (0.02 / placement.course_to_table).max(0.01),
        far: crate::world::FAR_M,
    }
}
