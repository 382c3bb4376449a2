//! The one camera-frame interface shared by every platform: desktop replay, the synthetic feed and
//! ARCore on Android all yield [`CameraFrame`]s through [`FrameSource`].
//!
//! Conventions (those of ARCore and OpenGL, so the Android path needs no conversion):
//! - world: metres, right-handed, y up (docs/command-line.md: x east, y up, z south);
//! - camera: x right, y up, looking down -z; `camera_to_world` maps camera coordinates to world;
//! - image: pixel (0, 0) is the top-left corner of the top-left pixel, u right, v down; a pixel's
//!   centre is at (i + 0.5, j + 0.5).

use glam::{Affine2, DMat4, DVec2, DVec3, Mat4, Vec2};

use crate::ArError;
use camera_image::{CameraImage, StridedYuv420, Yuv420, YuvRange};

/// The camera image of one frame.
#[derive(Clone, Debug, PartialEq)]
pub enum FrameImage {
    /// Tightly packed RGBA8 rows, top row first (`data.len() == width * height * 4`), sRGB.
    Rgba8 {
        width: u32,
        height: u32,
        data: Vec<u8>,
    },
    /// YUV 4:2:0 as ARCore's `AImage` gives it (BT.601 full range): a full-size luma plane and two
    /// half-size chroma planes, each with its own row stride; `uv_pixel_stride` is 1 for planar
    /// (I420) and 2 for interleaved (NV12/NV21) chroma.
    Yuv420 {
        width: u32,
        height: u32,
        y: Vec<u8>,
        y_row_stride: u32,
        u: Vec<u8>,
        v: Vec<u8>,
        uv_row_stride: u32,
        uv_pixel_stride: u32,
    },
}

impl FrameImage {
    /// Image size in pixels, (width, height).
    pub fn size(&self) -> (u32, u32) {
        match self {
            FrameImage::Rgba8 { width, height, .. } | FrameImage::Yuv420 { width, height, .. } => {
                (*width, *height)
            }
        }
    }

    /// The image as an `image` crate RGBA buffer, converted on the CPU.
    pub fn to_rgba_image(&self) -> image::RgbaImage {
        let (w, h) = self.size();
        image::RgbaImage::from_raw(w, h, self.to_rgba8())
            .expect("to_rgba8 gives width × height × 4 bytes")
    }

    /// The image as tightly packed RGBA8 (YUV through the CPU reference,
    /// [`camera_image::Yuv420::to_rgba8`], BT.601 full range). A YUV image whose planes do not
    /// fit their strides comes out black, with an error logged (ARCore's reader checks them).
    pub fn to_rgba8(&self) -> Vec<u8> {
        match self.to_camera_image() {
            Ok(CameraImage::Rgba(img)) => img.into_raw(),
            Ok(CameraImage::Yuv420(p)) => p.to_rgba8(),
            Err(e) => {
                log::error!("{e}");
                let (w, h) = self.size();
                [0, 0, 0, 255].repeat(w as usize * h as usize)
            }
        }
    }

    /// The image as the renderer takes it: RGBA as it is, YUV as normalised planes (tight luma,
    /// interleaved chroma) that the renderer converts in the shader. Refuses an RGBA buffer of
    /// the wrong length or YUV planes too short for their strides.
    pub fn to_camera_image(&self) -> Result<CameraImage, ArError> {
        match self {
            FrameImage::Rgba8 {
                width,
                height,
                data,
            } => image::RgbaImage::from_raw(*width, *height, data.clone())
                .map(CameraImage::Rgba)
                .ok_or_else(|| {
                    ArError::new(format!(
                        "RGBA image {width}×{height}: needs {} bytes, got {}",
                        4 * *width as usize * *height as usize,
                        data.len()
                    ))
                }),
            FrameImage::Yuv420 {
                width,
                height,
                y,
                y_row_stride,
                u,
                v,
                uv_row_stride,
                uv_pixel_stride,
            } => {
                let planes = StridedYuv420 {
                    width: *width,
                    height: *height,
                    y,
                    y_row_stride: *y_row_stride,
                    u,
                    v,
                    uv_row_stride: *uv_row_stride,
                    uv_pixel_stride: *uv_pixel_stride,
                };
                Yuv420::from_strided(&planes, YuvRange::Full)
                    .map(CameraImage::Yuv420)
                    .map_err(|e| ArError::new(e.0))
            }
        }
    }
}

impl FrameImage {
    /// The image, halved until neither side exceeds `max_side` (a GPU's largest texture):
    /// unchanged when it fits; YUV comes back normalised (tight luma, interleaved chroma).
    pub fn fit_within(self, max_side: u32) -> Result<FrameImage, ArError> {
        let (w, h) = self.size();
        if w <= max_side && h <= max_side {
            return Ok(self);
        }
        Ok(match self.to_camera_image()?.fit_within(max_side) {
            CameraImage::Rgba(img) => FrameImage::Rgba8 {
                width: img.width(),
                height: img.height(),
                data: img.into_raw(),
            },
            CameraImage::Yuv420(p) => {
                let [cw, _] = Yuv420::chroma_size(p.width(), p.height());
                FrameImage::Yuv420 {
                    width: p.width(),
                    height: p.height(),
                    y: p.y().to_vec(),
                    y_row_stride: p.width(),
                    u: p.uv().to_vec(),
                    v: p.uv()[1..].to_vec(),
                    uv_row_stride: 2 * cw,
                    uv_pixel_stride: 2,
                }
            }
        })
    }
}

/// Pinhole intrinsics in pixels for an image of `width` × `height` (same pixel convention as the
/// module docs: `cx = width / 2` is the image centre).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Intrinsics {
    /// Focal lengths, pixels.
    pub fx: f64,
    pub fy: f64,
    /// Principal point, pixels from the top-left corner.
    pub cx: f64,
    pub cy: f64,
    /// Image size, pixels.
    pub width: u32,
    pub height: u32,
}

impl Intrinsics {
    /// Intrinsics of an ideal camera with a horizontal field of view `hfov_rad`, square pixels and
    /// the principal point at the image centre.
    pub fn from_hfov(width: u32, height: u32, hfov_rad: f64) -> Self {
        let fx = 0.5 * f64::from(width) / (0.5 * hfov_rad).tan();
        Self {
            fx,
            fy: fx,
            cx: 0.5 * f64::from(width),
            cy: 0.5 * f64::from(height),
            width,
            height,
        }
    }

    /// Refuses focal lengths that are not positive and finite, a principal point that is not
    /// finite, or an empty image; `what` names the file and field for the message.
    pub fn validate(&self, what: &str) -> Result<(), ArError> {
        let ok = self.fx.is_finite()
            && self.fy.is_finite()
            && self.fx > 0.0
            && self.fy > 0.0
            && self.cx.is_finite()
            && self.cy.is_finite()
            && self.width > 0
            && self.height > 0;
        if ok {
            Ok(())
        } else {
            // The values as a person reads them (JSON field names), not Rust's Debug text.
            let n = input::show_number;
            Err(ArError::new(format!(
                "{what}: intrinsics need positive finite fx and fy, finite cx and cy and a non-empty image, got fx {}, fy {}, cx {}, cy {}, {}x{} pixels",
                n(self.fx),
                n(self.fy),
                n(self.cx),
                n(self.cy),
                self.width,
                self.height
            )))
        }
    }

    /// Pixel position of a point given in camera coordinates (module conventions), or `None`
    /// behind the camera (z ≥ 0).
    pub fn project_camera_point(&self, p: DVec3) -> Option<DVec2> {
        if p.z >= 0.0 {
            return None;
        }
        let d = -p.z;
        Some(DVec2::new(
            self.cx + self.fx * p.x / d,
            self.cy - self.fy * p.y / d,
        ))
    }

    /// Direction in camera coordinates (not normalised, z = -1) of the ray through pixel
    /// position `px` (pixel centres at half-integers).
    pub fn ray_through_pixel(&self, px: DVec2) -> DVec3 {
        DVec3::new(
            (px.x - self.cx) / self.fx,
            -(px.y - self.cy) / self.fy,
            -1.0,
        )
    }

    /// OpenGL-style projection matrix for wgpu clip space (depth 0 at `near`, 1 at `far`) that
    /// reproduces these intrinsics exactly: a camera-space point lands at the same pixel that
    /// [`Intrinsics::project_camera_point`] gives.
    pub fn projection_wgpu(&self, near: f64, far: f64) -> DMat4 {
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        // x_ndc = 2 (cx + fx x/dist) / w - 1 with dist = -z = clip w, so clip x = (2 fx/w) x + b z.
        let a = 2.0 * self.fx / w;
        let b = 1.0 - 2.0 * self.cx / w;
        // y_ndc = 1 - 2 (cy - fy y/dist) / h, so clip y = (2 fy/h) y + d z.
        let c = 2.0 * self.fy / h;
        let d = 2.0 * self.cy / h - 1.0;
        // Right-handed depth in [0, 1]: z_ndc = (e z + f) / -z is 0 at z = -near and 1 at z = -far.
        let e = far / (near - far);
        let f = near * far / (near - far);
        DMat4::from_cols_array(&[
            a, 0.0, 0.0, 0.0, //
            0.0, c, 0.0, 0.0, //
            b, d, e, -1.0, //
            0.0, 0.0, f, 0.0,
        ])
    }
}

/// What kind of surface a detected plane is (ARCore's `ArPlaneType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneKind {
    /// Horizontal, facing up: floors and table tops.
    HorizontalUp,
    /// Horizontal, facing down: ceilings.
    HorizontalDown,
    Vertical,
}

/// A detected plane, as ARCore reports it: a centre pose whose local y axis is the plane's
/// normal, and a boundary in the plane's local x-z coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct DetectedPlane {
    /// Plane-to-world transform (rigid): origin at the plane's centre, local +y the normal.
    pub center_pose: Mat4,
    /// Full size along the local x and z axes, metres (ARCore `ArPlane_getExtentX/Z`).
    pub extent: Vec2,
    /// Boundary polygon in the local x-z plane, metres, counter-clockwise seen from +y; may be
    /// empty when only the extent is known (then the plane is the extent's rectangle).
    pub polygon: Vec<Vec2>,
    pub kind: PlaneKind,
}

/// Whether the pose of a frame can be trusted (ARCore's `ArTrackingState`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrackingState {
    Tracking,
    /// Tracking is lost for now; the pose is the last good one.
    Paused,
    Stopped,
}

/// One camera frame: everything the renderer needs to put the scene over the real image.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraFrame {
    pub image: FrameImage,
    /// Camera-to-world transform (rigid) in the module's conventions. f32 is enough: AR worlds are
    /// metres around the session origin.
    pub camera_to_world: Mat4,
    pub intrinsics: Intrinsics,
    /// Planes detected so far (desktop replays: the table plane from `session.json`, if given).
    pub planes: Vec<DetectedPlane>,
    /// Seconds since the source's first frame (replays) or the sensor clock (ARCore), seconds.
    pub timestamp: f64,
    /// Maps a screen UV (0..1, origin top-left of the view) to the image UV to sample there.
    /// Identity when the view shows the image as it is; on Android it carries the display rotation
    /// and crop (`ArFrame_transformCoordinates2d`).
    pub display_uv: Affine2,
    pub tracking: TrackingState,
}

impl CameraFrame {
    /// World-to-camera transform (the view matrix).
    pub fn view_matrix(&self) -> Mat4 {
        self.camera_to_world.inverse()
    }

    /// Pixel position where the world point `p` shows in this frame, or `None` behind the camera.
    /// Evaluated in f64 so tests can compare to the exact synthetic projection.
    pub fn project_world_point(&self, p: DVec3) -> Option<DVec2> {
        let w2c = self.camera_to_world.as_dmat4().inverse();
        self.intrinsics
            .project_camera_point(w2c.transform_point3(p))
    }
}

/// A source of camera frames: a replay folder, the synthetic feed, or ARCore.
///
/// The app calls [`FrameSource::next_frame`] once per displayed frame. A source that has nothing
/// new returns `Ok(None)` and the app keeps drawing the last frame; an error is a sentence naming
/// what failed (file and line for replays).
pub trait FrameSource {
    /// The newest frame, or `None` when nothing new is available yet (ARCore not tracking yet, a
    /// replay that has not reached its next frame time).
    fn next_frame(&mut self) -> Result<Option<CameraFrame>, ArError>;

    /// A short description for logs and the UI, e.g. `"replay assets/feed (48 frames)"`.
    fn describe(&self) -> String;
}
