//! One ARCore frame read into the platform-independent [`CameraFrame`]: the physical camera's
//! pose and image intrinsics, the CPU image as YUV 4:2:0 planes, the display UV transform, the
//! detected planes and the tracking state; and, beside it, the display-oriented view and
//! projection matrices and the light estimate ([`DisplayCamera`]). Signatures and enum values
//! are those of `arcore_c_api.h`.

use std::ffi::c_void;

use ar::TrackingState;
use ar::arcore::session::{status, tracking_hint};
use ar::arcore::{affine_from_three, pose_from_raw};
use ar::{ArError, CameraFrame, DetectedPlane, FrameImage, FrameSource, Intrinsics, PlaneKind};
use glam::{DMat4, DVec3, Mat4, Vec2};

use super::arcore::ArCore;

type O = c_void;
type S = *const O;

/// Near and far clip distances for ARCore's projection, AR metres.
pub const NEAR_M: f32 = 0.01;
pub const FAR_M: f32 = 100.0;

/// `AR_TRACKABLE_PLANE`, `AR_COORDINATES_2D_VIEW_NORMALIZED`, `AR_COORDINATES_2D_IMAGE_NORMALIZED`,
/// `AR_LIGHT_ESTIMATE_STATE_VALID`.
const TRACKABLE_PLANE: i32 = 0x4152_0101;
const COORDS_VIEW_NORMALIZED: i32 = 8;
const COORDS_IMAGE_NORMALIZED: i32 = 3;
const LIGHT_VALID: i32 = 1;

macro_rules! frame_api {
    ($($field:ident: fn($($arg:ty),*) $(-> $ret:ty)? = $sym:literal;)*) => {
        /// Per-frame functions of the ARCore C API.
        pub struct FrameApi {
            $($field: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl FrameApi {
            pub fn load(lib: &libloading::Library) -> Result<Self, libloading::Error> {
                // SAFETY: each symbol has the C signature stated in arcore_c_api.h; the
                // library outlives these pointers (both live in one `ArCore`).
                unsafe { Ok(Self { $($field: *lib.get(concat!($sym, "\0").as_bytes())?,)* }) }
            }
        }
    };
}

frame_api! {
    acquire_camera: fn(S, S, *mut *mut O) = "ArFrame_acquireCamera";
    camera_release: fn(*mut O) = "ArCamera_release";
    camera_view: fn(S, S, *mut f32) = "ArCamera_getViewMatrix";
    camera_projection: fn(S, S, f32, f32, *mut f32) = "ArCamera_getProjectionMatrix";
    camera_tracking: fn(S, S, *mut i32) = "ArCamera_getTrackingState";
    camera_failure: fn(S, S, *mut i32) = "ArCamera_getTrackingFailureReason";
    camera_pose: fn(S, S, *mut O) = "ArCamera_getPose";
    camera_intrinsics: fn(S, S, *mut O) = "ArCamera_getImageIntrinsics";
    intrinsics_create: fn(S, *mut *mut O) = "ArCameraIntrinsics_create";
    intrinsics_destroy: fn(*mut O) = "ArCameraIntrinsics_destroy";
    intrinsics_focal: fn(S, S, *mut f32, *mut f32) = "ArCameraIntrinsics_getFocalLength";
    intrinsics_centre: fn(S, S, *mut f32, *mut f32) = "ArCameraIntrinsics_getPrincipalPoint";
    intrinsics_size: fn(S, S, *mut i32, *mut i32) = "ArCameraIntrinsics_getImageDimensions";
    pose_create: fn(S, *const f32, *mut *mut O) = "ArPose_create";
    pose_destroy: fn(*mut O) = "ArPose_destroy";
    pose_raw: fn(S, S, *mut f32) = "ArPose_getPoseRaw";
    timestamp: fn(S, S, *mut i64) = "ArFrame_getTimestamp";
    transform_2d: fn(S, S, i32, i32, *const f32, i32, *mut f32) = "ArFrame_transformCoordinates2d";
    acquire_image: fn(S, S, *mut *mut O) -> i32 = "ArFrame_acquireCameraImage";
    image_release: fn(*mut O) = "ArImage_release";
    image_width: fn(S, S, *mut i32) = "ArImage_getWidth";
    image_height: fn(S, S, *mut i32) = "ArImage_getHeight";
    plane_data: fn(S, S, i32, *mut *const u8, *mut i32) = "ArImage_getPlaneData";
    plane_row_stride: fn(S, S, i32, *mut i32) = "ArImage_getPlaneRowStride";
    plane_pixel_stride: fn(S, S, i32, *mut i32) = "ArImage_getPlanePixelStride";
    light_create: fn(S, *mut *mut O) = "ArLightEstimate_create";
    light_destroy: fn(*mut O) = "ArLightEstimate_destroy";
    frame_light: fn(S, S, *mut O) = "ArFrame_getLightEstimate";
    light_state: fn(S, S, *mut i32) = "ArLightEstimate_getState";
    light_direction: fn(S, S, *mut f32) = "ArLightEstimate_getEnvironmentalHdrMainLightDirection";
    list_create: fn(S, *mut *mut O) = "ArTrackableList_create";
    list_destroy: fn(*mut O) = "ArTrackableList_destroy";
    all_trackables: fn(S, i32, *mut O) = "ArSession_getAllTrackables";
    list_size: fn(S, S, *mut i32) = "ArTrackableList_getSize";
    list_item: fn(S, S, i32, *mut *mut O) = "ArTrackableList_acquireItem";
    trackable_release: fn(*mut O) = "ArTrackable_release";
    trackable_state: fn(S, S, *mut i32) = "ArTrackable_getTrackingState";
    plane_type: fn(S, S, *mut i32) = "ArPlane_getType";
    plane_centre: fn(S, S, *mut O) = "ArPlane_getCenterPose";
    plane_extent_x: fn(S, S, *mut f32) = "ArPlane_getExtentX";
    plane_extent_z: fn(S, S, *mut f32) = "ArPlane_getExtentZ";
    polygon_size: fn(S, S, *mut i32) = "ArPlane_getPolygonSize";
    polygon: fn(S, S, *mut f32) = "ArPlane_getPolygon";
}

/// What the screen shows besides the camera image: ARCore's display-oriented camera and light.
#[derive(Clone, Copy, Debug)]
pub struct DisplayCamera {
    /// AR world → display-oriented camera (`ArCamera_getViewMatrix`).
    pub view: DMat4,
    /// OpenGL projection for the view (`ArCamera_getProjectionMatrix`, [`NEAR_M`]..[`FAR_M`]).
    pub projection_gl: DMat4,
    /// What to tell the user while not tracking ("move the phone slowly"), else `None`.
    pub hint: Option<&'static str>,
    /// Unit vector towards the main light in AR world axes (Environmental HDR), when valid.
    pub light_towards: Option<DVec3>,
}

fn mat4(m: [f32; 16]) -> DMat4 {
    Mat4::from_cols_array(&m).as_dmat4()
}

impl FrameApi {
    /// Reads an `ArPose` filled by `fill` as a rigid transform.
    ///
    /// SAFETY (callers): `s` is a live session and `fill` writes into the pose it is given.
    unsafe fn read_pose(&self, s: S, fill: impl FnOnce(*mut O)) -> Mat4 {
        let mut pose = std::ptr::null_mut();
        let mut raw = [0f32; 7];
        // SAFETY: per the function's contract; the pose is destroyed here.
        unsafe {
            (self.pose_create)(s, std::ptr::null(), &mut pose);
            fill(pose);
            (self.pose_raw)(s, pose, raw.as_mut_ptr());
            (self.pose_destroy)(pose);
        }
        pose_from_raw(raw)
    }

    /// The CPU image as YUV 4:2:0 planes, or `None` while ARCore has none yet.
    ///
    /// SAFETY (callers): live session `s` and frame `f`.
    unsafe fn image(&self, s: S, f: S) -> Option<FrameImage> {
        let mut img = std::ptr::null_mut();
        // SAFETY: live session and frame; the image is released below.
        unsafe {
            if (self.acquire_image)(s, f, &mut img) != status::SUCCESS || img.is_null() {
                return None;
            }
            let (mut w, mut h) = (0, 0);
            (self.image_width)(s, img, &mut w);
            (self.image_height)(s, img, &mut h);
            let plane = |i: i32| {
                let (mut data, mut len, mut row, mut px) = (std::ptr::null(), 0, 0, 0);
                (self.plane_data)(s, img, i, &mut data, &mut len);
                (self.plane_row_stride)(s, img, i, &mut row);
                (self.plane_pixel_stride)(s, img, i, &mut px);
                let bytes = if data.is_null() || len <= 0 {
                    Vec::new()
                } else {
                    std::slice::from_raw_parts(data, len as usize).to_vec()
                };
                (bytes, row.max(0) as u32, px.max(1) as u32)
            };
            let (y, y_row_stride, _) = plane(0);
            let (u, uv_row_stride, uv_pixel_stride) = plane(1);
            let (v, _, _) = plane(2);
            (self.image_release)(img);
            let (width, height) = (w.max(0) as u32, h.max(0) as u32);
            // The last row of a plane may be shorter than its stride: index only what exists.
            let need_y =
                (height as usize).saturating_sub(1) * y_row_stride as usize + width as usize;
            let need_uv = (height as usize / 2).saturating_sub(1) * uv_row_stride as usize
                + (width as usize / 2).saturating_sub(1) * uv_pixel_stride as usize
                + 1;
            if width == 0
                || height == 0
                || y.len() < need_y
                || u.len() < need_uv
                || v.len() < need_uv
            {
                log::warn!("regatta: camera image {width}×{height} has short planes; skipped");
                return None;
            }
            Some(FrameImage::Yuv420 {
                width,
                height,
                y,
                y_row_stride,
                u,
                v,
                uv_row_stride,
                uv_pixel_stride,
            })
        }
    }

    /// The planes ARCore tracks now.
    ///
    /// SAFETY (callers): live session `s`.
    unsafe fn planes(&self, s: S) -> Vec<DetectedPlane> {
        let mut out = Vec::new();
        let mut list = std::ptr::null_mut();
        // SAFETY: live session; the list and each acquired item are released here.
        unsafe {
            (self.list_create)(s, &mut list);
            (self.all_trackables)(s, TRACKABLE_PLANE, list);
            let mut n = 0;
            (self.list_size)(s, list, &mut n);
            for i in 0..n {
                let mut plane = std::ptr::null_mut();
                (self.list_item)(s, list, i, &mut plane);
                let mut state = 0;
                (self.trackable_state)(s, plane, &mut state);
                if state == 0 {
                    let mut kind = 0;
                    (self.plane_type)(s, plane, &mut kind);
                    let (mut ex, mut ez, mut np) = (0f32, 0f32, 0);
                    (self.plane_extent_x)(s, plane, &mut ex);
                    (self.plane_extent_z)(s, plane, &mut ez);
                    (self.polygon_size)(s, plane, &mut np);
                    let mut xz = vec![0f32; np.max(0) as usize];
                    if !xz.is_empty() {
                        (self.polygon)(s, plane, xz.as_mut_ptr());
                    }
                    let center_pose = self.read_pose(s, |p| (self.plane_centre)(s, plane, p));
                    out.push(DetectedPlane {
                        center_pose,
                        extent: Vec2::new(ex, ez),
                        polygon: xz.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect(),
                        kind: match kind {
                            0 => PlaneKind::HorizontalUp,
                            1 => PlaneKind::HorizontalDown,
                            _ => PlaneKind::Vertical,
                        },
                    });
                }
                (self.trackable_release)(plane);
            }
            (self.list_destroy)(list);
        }
        out
    }
}

impl FrameSource for ArCore {
    /// Reads the frame of the last `ArSession_update` ([`ArCore::update`]); `None` until ARCore
    /// has a camera image. Also refreshes [`ArCore::view`].
    fn next_frame(&mut self) -> Result<Option<CameraFrame>, ArError> {
        let (Some(api), Some(session)) = (self.frame_api.as_ref(), self.live_session()) else {
            return Ok(None);
        };
        let (s, f) = (session as S, self.frame as S);
        let mut camera = std::ptr::null_mut();
        // SAFETY: live session and frame (update ran); every ARCore object made here is released.
        unsafe {
            (api.acquire_camera)(s, f, &mut camera);
            let (mut view, mut proj) = ([0f32; 16], [0f32; 16]);
            (api.camera_view)(s, camera, view.as_mut_ptr());
            (api.camera_projection)(s, camera, NEAR_M, FAR_M, proj.as_mut_ptr());
            let (mut state, mut reason) = (0, 0);
            (api.camera_tracking)(s, camera, &mut state);
            (api.camera_failure)(s, camera, &mut reason);
            let camera_to_world = api.read_pose(s, |p| (api.camera_pose)(s, camera, p));
            let mut k = std::ptr::null_mut();
            (api.intrinsics_create)(s, &mut k);
            (api.camera_intrinsics)(s, camera, k);
            let (mut fx, mut fy, mut cx, mut cy, mut w, mut h) = (0f32, 0f32, 0f32, 0f32, 0, 0);
            (api.intrinsics_focal)(s, k, &mut fx, &mut fy);
            (api.intrinsics_centre)(s, k, &mut cx, &mut cy);
            (api.intrinsics_size)(s, k, &mut w, &mut h);
            (api.intrinsics_destroy)(k);
            (api.camera_release)(camera);

            let mut light = std::ptr::null_mut();
            (api.light_create)(s, &mut light);
            (api.frame_light)(s, f, light);
            let mut light_state = 0;
            (api.light_state)(s, light, &mut light_state);
            let mut dir = [0f32; 3];
            (api.light_direction)(s, light, dir.as_mut_ptr());
            (api.light_destroy)(light);
            let light_towards = (light_state == LIGHT_VALID)
                .then(|| DVec3::from(dir.map(f64::from)))
                .filter(|d| d.length_squared() > 0.5);

            self.view = Some(DisplayCamera {
                view: mat4(view),
                projection_gl: mat4(proj),
                hint: tracking_hint(state, reason),
                light_towards,
            });

            // Screen UV → image UV from three points (origin and the two axes).
            let corners = [0f32, 0.0, 1.0, 0.0, 0.0, 1.0];
            let mut uv = [0f32; 6];
            (api.transform_2d)(
                s,
                f,
                COORDS_VIEW_NORMALIZED,
                3,
                corners.as_ptr(),
                COORDS_IMAGE_NORMALIZED,
                uv.as_mut_ptr(),
            );
            let pts = |a: [f32; 6]| [0, 2, 4].map(|i| Vec2::new(a[i], a[i + 1]));
            let display_uv = affine_from_three(pts(corners), pts(uv)).unwrap_or_default();

            let Some(image) = api.image(s, f) else {
                return Ok(None);
            };
            let mut t_ns = 0i64;
            (api.timestamp)(s, f, &mut t_ns);
            // The intrinsics are for the CPU image's size; should ARCore give another size,
            // scale them to the image actually handed over.
            let (iw, ih) = image.size();
            let sx = f64::from(iw) / f64::from(w.max(1));
            let sy = f64::from(ih) / f64::from(h.max(1));
            let intrinsics = Intrinsics {
                fx: f64::from(fx) * sx,
                fy: f64::from(fy) * sy,
                cx: f64::from(cx) * sx,
                cy: f64::from(cy) * sy,
                width: iw,
                height: ih,
            };
            intrinsics.validate("ARCore image intrinsics")?;
            Ok(Some(CameraFrame {
                image,
                camera_to_world,
                intrinsics,
                planes: api.planes(s),
                timestamp: t_ns as f64 * 1e-9,
                display_uv,
                tracking: match state {
                    0 => TrackingState::Tracking,
                    1 => TrackingState::Paused,
                    _ => TrackingState::Stopped,
                },
            }))
        }
    }

    fn describe(&self) -> String {
        if self.is_loaded() {
            "ARCore camera".to_string()
        } else {
            "ARCore (library not loaded)".to_string()
        }
    }
}
