//! One ARCore frame read into the platform-independent [`CameraFrame`]: the physical camera's
//! pose and image intrinsics, the CPU image as YUV 4:2:0 planes, the display UV transform, the
//! detected planes and the tracking state; and, beside it, the display-oriented view and
//! projection matrices and the light estimate ([`DisplayCamera`]).
//!
//! Only [`super::api`] is imported: the session (`super::session`) calls in here, never the
//! other way round.

use glam::{DMat4, DVec3, Mat4, Vec2};

use super::api::{FrameApi, O, S, consts};
use crate::TrackingState;
use crate::arcore::session::{status, tracking_hint};
use crate::arcore::{affine_from_three, pose_from_raw};
use crate::{ArError, CameraFrame, DetectedPlane, FrameImage, Intrinsics, PlaneKind};

/// Near and far clip distances for ARCore's projection, AR metres.
pub const NEAR_M: f32 = 0.01;
pub const FAR_M: f32 = 100.0;

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

/// What [`read_frame`] read: always the display camera; the camera frame only when the frame's
/// timestamp is new (an unchanged timestamp is the same image: no copy, no upload).
pub(super) struct FrameRead {
    pub display: DisplayCamera,
    pub frame: Option<CameraFrame>,
    pub timestamp_ns: i64,
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
            let image = FrameImage::Yuv420 {
                width: w.max(0) as u32,
                height: h.max(0) as u32,
                y,
                y_row_stride,
                u,
                v,
                uv_row_stride,
                uv_pixel_stride,
            };
            // The same layout check the upload makes (the last row may be shorter than its
            // stride): a bad image is skipped here, with the reason, not drawn black.
            match image.to_camera_image() {
                Ok(_) => Some(image),
                Err(e) => {
                    log::warn!("regatta: ARCore camera image skipped: {e}");
                    None
                }
            }
        }
    }

    /// The planes ARCore tracks now, each once: a plane subsumed by another (merged into it,
    /// `ArPlane_acquireSubsumedBy` non-null) is skipped, its parent is listed.
    ///
    /// SAFETY (callers): live session `s`.
    unsafe fn planes(&self, s: S) -> Vec<DetectedPlane> {
        let mut out = Vec::new();
        let mut list = std::ptr::null_mut();
        // SAFETY: live session; the list and each acquired item are released here.
        unsafe {
            (self.list_create)(s, &mut list);
            (self.all_trackables)(s, consts::TRACKABLE_PLANE, list);
            let mut n = 0;
            (self.list_size)(s, list, &mut n);
            for i in 0..n {
                let mut plane = std::ptr::null_mut();
                (self.list_item)(s, list, i, &mut plane);
                if plane.is_null() {
                    continue;
                }
                let mut parent = std::ptr::null_mut();
                (self.plane_subsumed_by)(s, plane, &mut parent);
                let subsumed = !parent.is_null();
                if subsumed {
                    (self.trackable_release)(parent);
                }
                let mut state = consts::STOPPED;
                (self.trackable_state)(s, plane, &mut state);
                if state == consts::TRACKING && !subsumed {
                    out.push(self.plane(s, plane));
                }
                (self.trackable_release)(plane);
            }
            (self.list_destroy)(list);
        }
        out
    }

    /// SAFETY (callers): live session `s` and acquired plane `plane`.
    unsafe fn plane(&self, s: S, plane: *mut O) -> DetectedPlane {
        // SAFETY: per the function's contract.
        unsafe {
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
            DetectedPlane {
                center_pose,
                extent: Vec2::new(ex, ez),
                polygon: xz.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect(),
                kind: match kind {
                    consts::PLANE_UP => PlaneKind::HorizontalUp,
                    consts::PLANE_DOWN => PlaneKind::HorizontalDown,
                    _ => PlaneKind::Vertical,
                },
            }
        }
    }

    /// The main light's direction when the session runs in Environmental HDR mode and the
    /// estimate is valid. In ambient mode the direction is never read: ARCore then returns
    /// straight up, which would light the race from the zenith.
    ///
    /// SAFETY (callers): live session `s` and frame `f`.
    unsafe fn light_towards(&self, s: S, f: S, hdr: bool) -> Option<DVec3> {
        if !hdr {
            return None;
        }
        let mut light = std::ptr::null_mut();
        let mut state = 0;
        let mut dir = [0f32; 3];
        // SAFETY: per the function's contract; the estimate is destroyed here.
        unsafe {
            (self.light_create)(s, &mut light);
            (self.frame_light)(s, f, light);
            (self.light_state)(s, light, &mut state);
            if state == consts::LIGHT_VALID {
                (self.light_direction)(s, light, dir.as_mut_ptr());
            }
            (self.light_destroy)(light);
        }
        (state == consts::LIGHT_VALID)
            .then(|| DVec3::from(dir.map(f64::from)))
            .filter(|d| d.length_squared() > 0.5)
    }
}

/// What [`read_frame`] needs to know of the session and the app.
pub(super) struct ReadOptions {
    /// The session is configured for Environmental HDR light estimation.
    pub hdr: bool,
    /// The timestamp of the last frame read; when ARCore's is the same, the image, planes and
    /// intrinsics are not read again.
    pub last_timestamp_ns: Option<i64>,
    /// The largest image side the GPU takes (`max_texture_dimension_2d`); a larger image is
    /// halved until it fits, its intrinsics with it.
    pub max_image_side: Option<u32>,
}

/// Reads the frame of the last `ArSession_update`.
///
/// SAFETY (callers): live session `s` and frame `f` on which `ArSession_update` ran.
pub(super) unsafe fn read_frame(
    api: &FrameApi,
    s: S,
    f: S,
    options: &ReadOptions,
) -> Result<FrameRead, ArError> {
    let ReadOptions {
        hdr,
        last_timestamp_ns,
        max_image_side,
    } = *options;
    let mut camera = std::ptr::null_mut();
    // SAFETY: per the function's contract; every ARCore object made here is released.
    unsafe {
        let mut t_ns = 0i64;
        (api.timestamp)(s, f, &mut t_ns);
        (api.acquire_camera)(s, f, &mut camera);
        let (mut view, mut proj) = ([0f32; 16], [0f32; 16]);
        (api.camera_view)(s, camera, view.as_mut_ptr());
        (api.camera_projection)(s, camera, NEAR_M, FAR_M, proj.as_mut_ptr());
        let (mut state, mut reason) = (0, 0);
        (api.camera_tracking)(s, camera, &mut state);
        (api.camera_failure)(s, camera, &mut reason);
        let display = DisplayCamera {
            view: mat4(view),
            projection_gl: mat4(proj),
            hint: tracking_hint(state, reason),
            light_towards: api.light_towards(s, f, hdr),
        };
        if last_timestamp_ns == Some(t_ns) {
            (api.camera_release)(camera);
            return Ok(FrameRead {
                display,
                frame: None,
                timestamp_ns: t_ns,
            });
        }
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

        // Screen UV → image UV from three points (origin and the two axes).
        let corners = [0f32, 0.0, 1.0, 0.0, 0.0, 1.0];
        let mut uv = [0f32; 6];
        (api.transform_2d)(
            s,
            f,
            consts::COORDS_VIEW_NORMALIZED,
            3,
            corners.as_ptr(),
            consts::COORDS_IMAGE_NORMALIZED,
            uv.as_mut_ptr(),
        );
        let pts = |a: [f32; 6]| [0, 2, 4].map(|i| Vec2::new(a[i], a[i + 1]));
        let display_uv = affine_from_three(pts(corners), pts(uv)).unwrap_or_default();

        let Some(image) = api.image(s, f) else {
            return Ok(FrameRead {
                display,
                frame: None,
                timestamp_ns: t_ns,
            });
        };
        let image = match max_image_side {
            Some(max) => image.fit_within(max)?,
            None => image,
        };
        // The intrinsics are for the CPU image's size; should ARCore give another size (or
        // the image be halved to fit the GPU), scale them to the image actually handed over.
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
        let frame = CameraFrame {
            image,
            camera_to_world,
            intrinsics,
            planes: api.planes(s),
            timestamp: t_ns as f64 * 1e-9,
            display_uv,
            tracking: match state {
                consts::TRACKING => TrackingState::Tracking,
                consts::PAUSED => TrackingState::Paused,
                _ => TrackingState::Stopped,
            },
        };
        Ok(FrameRead {
            display,
            frame: Some(frame),
            timestamp_ns: t_ns,
        })
    }
}
