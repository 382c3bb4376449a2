//! The backdrop: the camera image the effects draw the scene over (RGBA, or YUV 4:2:0 planes
//! that the shader converts), the pinhole camera that took it (in the scene's world frame) and
//! the display's UV transform. (A camera frame is what a frame source
//! delivers: image, tracked pose, intrinsics, planes; the app turns it into a backdrop.) ARCore
//! and the replay feed (`crates/ar`) hand one over per frame
//! (`EffectsHandle::set_backdrop`); without a frame source, [`Backdrop::synthetic`]
//! draws what a camera at the render camera's pose would see of a checkered table under the
//! water and a striped room around it.

use glam::{DMat4, DVec2, DVec3};

use render::camera::Camera;
use render::optics::{PinholeCamera, Plane};

pub use camera_image::{CameraImage, LayoutError, StridedYuv420, Yuv420, YuvRange, YuvToRgb};

/// One backdrop; `Backdrop<()>` is its camera and display transform without the image.
#[derive(Debug, Clone)]
pub struct Backdrop<I = CameraImage> {
    /// The image: sRGB-encoded RGBA, or YUV planes.
    pub image: I,
    /// The camera that took it: intrinsics in the image's pixels, pose in world metres.
    pub camera: PinholeCamera,
    /// Screen uv → image uv as a 2×3 affine map (rows), e.g. for a rotated display; identity
    /// when the image is upright and fills the screen.
    pub display: [[f64; 3]; 2],
}

/// The identity display transform.
pub const DISPLAY_IDENTITY: [[f64; 3]; 2] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

impl<I> Backdrop<I> {
    /// The image, and the frame without it.
    pub fn split(self) -> (I, Backdrop<()>) {
        let Backdrop {
            image,
            camera,
            display,
        } = self;
        (
            image,
            Backdrop {
                image: (),
                camera,
                display,
            },
        )
    }

    /// This frame's camera and display with `image`.
    pub fn with_image<J>(self, image: J) -> Backdrop<J> {
        Backdrop {
            image,
            camera: self.camera,
            display: self.display,
        }
    }

    /// World → camera matrix for points given relative to `origin` (x, z), as the shaders
    /// get them.
    pub fn view_local(&self, origin: DVec2) -> DMat4 {
        self.camera.pose.inverse() * DMat4::from_translation(DVec3::new(origin.x, 0.0, origin.y))
    }
}

impl Backdrop {
    /// The pinhole camera equivalent to the render camera `cam` on an image of `size` pixels
    /// (square pixels, principal point at the centre).
    pub fn pinhole(cam: &Camera, size: [u32; 2]) -> PinholeCamera {
        let (w, h) = (f64::from(size[0]), f64::from(size[1]));
        let f = 0.5 * h / (0.5 * cam.fov_y).tan();
        let view = glam::dcamera::rh::view::look_at_mat4(cam.eye, cam.target, cam.up);
        PinholeCamera {
            fx: f,
            fy: f,
            cx: 0.5 * w,
            cy: 0.5 * h,
            width: w,
            height: h,
            pose: view.inverse(),
        }
    }

    /// A synthetic frame of `size` pixels as the render camera `cam` would see a table
    /// `table_depth` metres below the water's rest level (checkers of `square` metres, out to
    /// `ring_radius` around `centre`) and a room with vertical stripes beyond it.
    pub fn synthetic(
        cam: &Camera,
        size: [u32; 2],
        table_depth: f64,
        centre: DVec2,
        ring_radius: f64,
        square: f64,
    ) -> Backdrop {
        let camera = Self::pinhole(cam, size);
        let table = Plane::horizontal(-table_depth);
        let image = image::RgbaImage::from_fn(size[0], size[1], |x, y| {
            let ray = camera.pixel_ray(DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5));
            let lin = match table.intersect_ray(camera.position(), ray) {
                Some((_, p)) if (DVec2::new(p.x, p.z) - centre).length() < 1.6 * ring_radius => {
                    let (i, j) = ((p.x / square).floor(), (p.z / square).floor());
                    let odd = (i + j).rem_euclid(2.0) == 1.0;
                    // Light and dark wood.
                    if odd {
                        [0.45, 0.30, 0.16]
                    } else {
                        [0.70, 0.55, 0.36]
                    }
                }
                _ => {
                    // The room: wall stripes by azimuth, brighter upwards.
                    let az = ray.z.atan2(ray.x);
                    let stripe = (az * 12.0).sin() > 0.0;
                    let up = ray.y.clamp(-1.0, 1.0) * 0.5 + 0.5;
                    let base = if stripe {
                        [0.25, 0.45, 0.30]
                    } else {
                        [0.80, 0.78, 0.70]
                    };
                    base.map(|c| c * (0.5 + 0.5 * up))
                }
            };
            let s = lin.map(|c: f64| (linear_to_srgb(c) * 255.0).round() as u8);
            image::Rgba([s[0], s[1], s[2], 255])
        });
        Backdrop {
            image: CameraImage::Rgba(image),
            camera,
            display: DISPLAY_IDENTITY,
        }
    }
}

fn linear_to_srgb(c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pinhole_matches_the_render_camera() {
        let cam = Camera::look_at(DVec3::new(3.0, 20.0, 30.0), DVec3::new(0.0, 0.0, 0.0), 1e3);
        let pin = Backdrop::pinhole(&cam, [320, 200]);
        // The target is at the image centre, and a point at the top edge of the field of view
        // at the top row.
        let c = pin.project(cam.target).unwrap();
        assert!((c - DVec2::new(160.0, 100.0)).length() < 1e-9);
        let proj = cam.view_proj_local(DVec2::ZERO, 320.0 / 200.0);
        for p in [DVec3::new(5.0, 0.0, -3.0), DVec3::new(-8.0, 2.0, 4.0)] {
            let clip = proj * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let px = pin.project(p).unwrap();
            let expect = DVec2::new((ndc.x * 0.5 + 0.5) * 320.0, (0.5 - ndc.y * 0.5) * 200.0);
            assert!((px - expect).length() < 1e-6, "{px} vs {expect}");
        }
    }

    #[test]
    fn the_synthetic_frame_shows_the_table_below_and_the_room_above() {
        let cam = Camera::look_at(DVec3::new(0.0, 10.0, 20.0), DVec3::ZERO, 1e3);
        let f = Backdrop::synthetic(&cam, [64, 48], 1.0, DVec2::ZERO, 15.0, 2.0);
        let CameraImage::Rgba(img) = &f.image else {
            panic!("synthetic frames are RGBA");
        };
        assert_eq!(img.dimensions(), (64, 48));
        // Bottom centre sees the table (wood: red > blue); some rows see the room.
        let bottom = img.get_pixel(32, 47);
        assert!(bottom[0] > bottom[2], "{bottom:?}");
        let top = img.get_pixel(32, 0);
        assert_ne!(top, bottom);
    }
}
