//! Exported: the per-frame reads (`ArFrame_*`, `ArCamera_*`, `ArCameraIntrinsics_*`,
//! `ArPose_*`, `ArImage_*`, `ArLightEstimate_*`, `ArTrackableList_*`, `ArTrackable_*`,
//! `ArPlane_*`). Signatures as in `arcore_c_api.h`.

use std::ffi::c_void;

use ar::arcore::session::status;
use ar::{DetectedPlane, PlaneKind};
use glam::{Mat4, Vec2};

use crate::display::{display_camera, transform};
use crate::objects::{
    Camera, CameraIntrinsics, Frame, Image, LightEstimate, Plane, Pose, Session, TrackableList,
    free_c, into_c, obj, obj_mut, put, put_all,
};
use crate::state::{Sim, sim};

type O = c_void;

/// `AR_TRACKABLE_BASE_TRACKABLE`, `AR_TRACKABLE_PLANE`.
const TRACKABLE_ANY: i32 = 0x4152_0100;
const TRACKABLE_PLANE: i32 = 0x4152_0101;
const LIGHT_HDR: i32 = 2;

fn raw_pose(m: Mat4) -> [f32; 7] {
    let (_, q, t) = m.to_scale_rotation_translation();
    [q.x, q.y, q.z, q.w, t.x, t.y, t.z]
}

/// The camera of the frame shown now, with the session's display geometry.
fn camera_now(s: &mut Sim, session: Option<&Session>) -> Camera {
    let tracking = s.script.tracking;
    // The intrinsics of the CPU image shown (its size is the camera config's).
    let intrinsics = match (&s.shown, session) {
        (Some(shown), _) => shown.frame.intrinsics,
        (None, Some(x)) => s.feed.intrinsics(x.camera.image.map(|v| v.max(0) as u32)),
        (None, None) => s
            .feed
            .intrinsics(s.default_camera_config().image.map(|v| v.max(0) as u32)),
    };
    let shown_pose = s.shown.as_ref().map(|f| f.frame.camera_to_world);
    let camera_to_world = match (tracking.0, shown_pose) {
        (0, Some(p)) => {
            s.last_pose = Some(p);
            p
        }
        _ => s.last_pose.or(shown_pose).unwrap_or(Mat4::IDENTITY),
    };
    Camera {
        camera_to_world,
        // No image yet: ARCore reports the camera as not tracking.
        tracking: if s.shown.is_some() { tracking } else { (1, 0) },
        intrinsics,
        rotation: session.map_or(0, |x| x.rotation),
        view: session.map_or((0, 0), |x| x.view),
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_acquireCamera(
    session: *const O,
    _frame: *const O,
    out_camera: *mut *mut O,
) {
    let mut s = sim("ArFrame_acquireCamera");
    if out_camera.is_null() {
        return;
    }
    // SAFETY: a live session (the caller's contract).
    let camera = camera_now(&mut s, unsafe { obj::<Session>(session) });
    s.made("camera");
    // SAFETY: checked non-null.
    unsafe { put(out_camera, into_c(camera)) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_release(camera: *mut O) {
    let mut s = sim("ArCamera_release");
    // SAFETY: an acquired camera, released once.
    if unsafe { free_c::<Camera>(camera) } {
        s.released("camera");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_getViewMatrix(_s: *const O, camera: *const O, out: *mut f32) {
    let _s = sim("ArCamera_getViewMatrix");
    // SAFETY: a live camera; `out` holds 16 floats.
    if let Some(c) = unsafe { obj::<Camera>(camera) } {
        let (view, _) = display_camera(c, 0.1, 100.0);
        unsafe { put_all(out, &view.to_cols_array()) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_getProjectionMatrix(
    _s: *const O,
    camera: *const O,
    near: f32,
    far: f32,
    dest_col_major_4x4: *mut f32,
) {
    let _s = sim("ArCamera_getProjectionMatrix");
    // SAFETY: a live camera; `dest` holds 16 floats.
    if let Some(c) = unsafe { obj::<Camera>(camera) } {
        let (_, projection) = display_camera(c, near, far);
        unsafe { put_all(dest_col_major_4x4, &projection.to_cols_array()) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_getTrackingState(_s: *const O, camera: *const O, out: *mut i32) {
    let _s = sim("ArCamera_getTrackingState");
    // SAFETY: a live camera and out pointer.
    if let Some(c) = unsafe { obj::<Camera>(camera) } {
        unsafe { put(out, c.tracking.0) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_getTrackingFailureReason(
    _s: *const O,
    camera: *const O,
    out: *mut i32,
) {
    let _s = sim("ArCamera_getTrackingFailureReason");
    // SAFETY: a live camera and out pointer.
    if let Some(c) = unsafe { obj::<Camera>(camera) } {
        unsafe { put(out, c.tracking.1) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_getPose(_s: *const O, camera: *const O, out_pose: *mut O) {
    let _s = sim("ArCamera_getPose");
    // SAFETY: a live camera and pose.
    if let (Some(c), Some(p)) = unsafe { (obj::<Camera>(camera), obj_mut::<Pose>(out_pose)) } {
        p.0 = raw_pose(c.camera_to_world);
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCamera_getImageIntrinsics(_s: *const O, camera: *const O, out: *mut O) {
    let _s = sim("ArCamera_getImageIntrinsics");
    // SAFETY: a live camera and intrinsics object.
    if let (Some(c), Some(k)) = unsafe { (obj::<Camera>(camera), obj_mut::<CameraIntrinsics>(out)) }
    {
        k.0 = Some(c.intrinsics);
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraIntrinsics_create(_s: *const O, out: *mut *mut O) {
    let mut s = sim("ArCameraIntrinsics_create");
    if out.is_null() {
        return;
    }
    s.made("intrinsics");
    // SAFETY: checked non-null.
    unsafe { put(out, into_c(CameraIntrinsics::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraIntrinsics_destroy(k: *mut O) {
    let mut s = sim("ArCameraIntrinsics_destroy");
    // SAFETY: made by ArCameraIntrinsics_create, destroyed once.
    if unsafe { free_c::<CameraIntrinsics>(k) } {
        s.released("intrinsics");
    }
}

/// Reads a pair from live intrinsics into two out pointers.
unsafe fn intrinsics_pair<T>(
    k: *const O,
    a: *mut T,
    b: *mut T,
    f: impl Fn(&ar::Intrinsics) -> (T, T),
) {
    // SAFETY: the caller's contract: live intrinsics, valid out pointers.
    if let Some(CameraIntrinsics(Some(k))) = unsafe { obj::<CameraIntrinsics>(k) } {
        let (x, y) = f(k);
        unsafe {
            put(a, x);
            put(b, y);
        }
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraIntrinsics_getFocalLength(
    _s: *const O,
    k: *const O,
    out_fx: *mut f32,
    out_fy: *mut f32,
) {
    let _s = sim("ArCameraIntrinsics_getFocalLength");
    // SAFETY: forwarded contract.
    unsafe { intrinsics_pair(k, out_fx, out_fy, |k| (k.fx as f32, k.fy as f32)) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraIntrinsics_getPrincipalPoint(
    _s: *const O,
    k: *const O,
    out_cx: *mut f32,
    out_cy: *mut f32,
) {
    let _s = sim("ArCameraIntrinsics_getPrincipalPoint");
    // SAFETY: forwarded contract.
    unsafe { intrinsics_pair(k, out_cx, out_cy, |k| (k.cx as f32, k.cy as f32)) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArCameraIntrinsics_getImageDimensions(
    _s: *const O,
    k: *const O,
    out_width: *mut i32,
    out_height: *mut i32,
) {
    let _s = sim("ArCameraIntrinsics_getImageDimensions");
    // SAFETY: forwarded contract.
    unsafe {
        intrinsics_pair(k, out_width, out_height, |k| {
            (k.width as i32, k.height as i32)
        })
    };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPose_create(_s: *const O, pose_raw: *const f32, out: *mut *mut O) {
    let mut s = sim("ArPose_create");
    if out.is_null() {
        return;
    }
    let mut raw = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
    if !pose_raw.is_null() {
        // SAFETY: ARCore's contract: 7 floats.
        unsafe { std::ptr::copy_nonoverlapping(pose_raw, raw.as_mut_ptr(), 7) };
    }
    s.made("pose");
    // SAFETY: checked non-null.
    unsafe { put(out, into_c(Pose(raw))) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPose_destroy(pose: *mut O) {
    let mut s = sim("ArPose_destroy");
    // SAFETY: made by ArPose_create, destroyed once.
    if unsafe { free_c::<Pose>(pose) } {
        s.released("pose");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPose_getPoseRaw(_s: *const O, pose: *const O, out_raw: *mut f32) {
    let _s = sim("ArPose_getPoseRaw");
    // SAFETY: a live pose; `out_raw` holds 7 floats.
    if let Some(p) = unsafe { obj::<Pose>(pose) } {
        unsafe { put_all(out_raw, &p.0) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_getTimestamp(_s: *const O, frame: *const O, out: *mut i64) {
    let _s = sim("ArFrame_getTimestamp");
    // SAFETY: a live frame and out pointer.
    if let Some(f) = unsafe { obj::<Frame>(frame) } {
        unsafe { put(out, f.timestamp_ns) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_transformCoordinates2d(
    session: *const O,
    _frame: *const O,
    input_coordinates: i32,
    number_of_vertices: i32,
    vertices_2d: *const f32,
    output_coordinates: i32,
    out_vertices_2d: *mut f32,
) {
    let mut s = sim("ArFrame_transformCoordinates2d");
    if vertices_2d.is_null() || out_vertices_2d.is_null() || number_of_vertices <= 0 {
        return;
    }
    // SAFETY: a live session.
    let camera = camera_now(&mut s, unsafe { obj::<Session>(session) });
    let n = number_of_vertices as usize;
    // SAFETY: ARCore's contract: 2 n floats in and out.
    let input = unsafe { std::slice::from_raw_parts(vertices_2d, 2 * n) };
    let out: Vec<f32> = input
        .chunks_exact(2)
        .flat_map(|p| {
            transform(
                &camera,
                input_coordinates,
                output_coordinates,
                Vec2::new(p[0], p[1]),
            )
            .to_array()
        })
        .collect();
    unsafe { put_all(out_vertices_2d, &out) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_acquireCameraImage(
    _session: *mut O,
    frame: *mut O,
    out_image: *mut *mut O,
) -> i32 {
    let mut s = sim("ArFrame_acquireCameraImage");
    // SAFETY: a live frame.
    let updated = unsafe { obj::<Frame>(frame) }.is_some_and(|f| f.updated);
    let image = match (&s.shown, updated, out_image.is_null()) {
        (_, _, true) => return status::ERROR_INVALID_ARGUMENT,
        (Some(shown), true, false) => shown.image.clone(),
        _ => return status::ERROR_NOT_YET_AVAILABLE,
    };
    s.made("image");
    // SAFETY: checked non-null.
    unsafe { put(out_image, into_c(Image(image))) };
    status::SUCCESS
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArImage_release(image: *mut O) {
    let mut s = sim("ArImage_release");
    // SAFETY: an acquired image, released once.
    if unsafe { free_c::<Image>(image) } {
        s.released("image");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArImage_getWidth(_s: *const O, image: *const O, out: *mut i32) {
    let _s = sim("ArImage_getWidth");
    // SAFETY: a live image and out pointer.
    if let Some(i) = unsafe { obj::<Image>(image) } {
        unsafe { put(out, i.0.width as i32) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArImage_getHeight(_s: *const O, image: *const O, out: *mut i32) {
    let _s = sim("ArImage_getHeight");
    // SAFETY: a live image and out pointer.
    if let Some(i) = unsafe { obj::<Image>(image) } {
        unsafe { put(out, i.0.height as i32) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArImage_getPlaneData(
    _s: *const O,
    image: *const O,
    plane_index: i32,
    out_data: *mut *const u8,
    out_data_length: *mut i32,
) {
    let _s = sim("ArImage_getPlaneData");
    // SAFETY: a live image; the data stays valid until ArImage_release.
    if let Some((data, _, _)) = unsafe { obj::<Image>(image) }.and_then(|i| i.0.plane(plane_index))
    {
        unsafe {
            put(out_data, data.as_ptr());
            put(out_data_length, data.len() as i32);
        }
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArImage_getPlaneRowStride(
    _s: *const O,
    image: *const O,
    plane_index: i32,
    out: *mut i32,
) {
    let _s = sim("ArImage_getPlaneRowStride");
    // SAFETY: a live image and out pointer.
    if let Some((_, row, _)) = unsafe { obj::<Image>(image) }.and_then(|i| i.0.plane(plane_index)) {
        unsafe { put(out, row as i32) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArImage_getPlanePixelStride(
    _s: *const O,
    image: *const O,
    plane_index: i32,
    out: *mut i32,
) {
    let _s = sim("ArImage_getPlanePixelStride");
    // SAFETY: a live image and out pointer.
    if let Some((_, _, px)) = unsafe { obj::<Image>(image) }.and_then(|i| i.0.plane(plane_index)) {
        unsafe { put(out, px as i32) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArLightEstimate_create(_s: *const O, out: *mut *mut O) {
    let mut s = sim("ArLightEstimate_create");
    if out.is_null() {
        return;
    }
    s.made("light");
    // SAFETY: checked non-null.
    unsafe { put(out, into_c(LightEstimate::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArLightEstimate_destroy(light: *mut O) {
    let mut s = sim("ArLightEstimate_destroy");
    // SAFETY: made by ArLightEstimate_create, destroyed once.
    if unsafe { free_c::<LightEstimate>(light) } {
        s.released("light");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArFrame_getLightEstimate(
    session: *const O,
    frame: *const O,
    out_light_estimate: *mut O,
) {
    let s = sim("ArFrame_getLightEstimate");
    // SAFETY: live session, frame and estimate.
    let (Some(session), Some(frame), Some(light)) = (unsafe {
        (
            obj::<Session>(session),
            obj::<Frame>(frame),
            obj_mut::<LightEstimate>(out_light_estimate),
        )
    }) else {
        return;
    };
    light.mode = session.light_mode;
    light.state = i32::from(s.script.light_valid && session.light_mode != 0 && frame.updated);
    light.towards = s.script.light_towards;
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArLightEstimate_getState(_s: *const O, light: *const O, out: *mut i32) {
    let _s = sim("ArLightEstimate_getState");
    // SAFETY: a live estimate and out pointer.
    if let Some(l) = unsafe { obj::<LightEstimate>(light) } {
        unsafe { put(out, l.state) };
    }
}

/// In any mode but Environmental HDR ARCore answers straight up (what the app must not use).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArLightEstimate_getEnvironmentalHdrMainLightDirection(
    _s: *const O,
    light: *const O,
    out_direction_3: *mut f32,
) {
    let _s = sim("ArLightEstimate_getEnvironmentalHdrMainLightDirection");
    // SAFETY: a live estimate; the out pointer holds 3 floats.
    if let Some(l) = unsafe { obj::<LightEstimate>(light) } {
        let d = if l.mode == LIGHT_HDR {
            glam::Vec3::from(l.towards).normalize_or(glam::Vec3::Y)
        } else {
            glam::Vec3::Y
        };
        unsafe { put_all(out_direction_3, &d.to_array()) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArTrackableList_create(_s: *const O, out: *mut *mut O) {
    let mut s = sim("ArTrackableList_create");
    if out.is_null() {
        return;
    }
    s.made("list");
    // SAFETY: checked non-null.
    unsafe { put(out, into_c(TrackableList::default())) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArTrackableList_destroy(list: *mut O) {
    let mut s = sim("ArTrackableList_destroy");
    // SAFETY: made by ArTrackableList_create, destroyed once.
    if unsafe { free_c::<TrackableList>(list) } {
        s.released("list");
    }
}

/// The planes ARCore knows now: the feed's (the table), and the scripted subsumed copy of the
/// first (identical to it, as ARCore keeps a merged plane).
fn planes_now(s: &Sim) -> Vec<DetectedPlane> {
    if s.shown.is_none() || !s.script.planes_visible {
        return Vec::new();
    }
    let mut planes = s.feed.planes();
    if s.script.subsumed_copy && !planes.is_empty() {
        planes.push(planes[0].clone());
    }
    planes
}

/// The plane that subsumes plane `id`, if any.
fn parent_of(s: &Sim, id: usize) -> Option<usize> {
    (s.script.subsumed_copy && id == s.feed.planes().len() && id > 0).then_some(0)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArSession_getAllTrackables(
    _s: *const O,
    filter_type: i32,
    out_list: *mut O,
) {
    let s = sim("ArSession_getAllTrackables");
    // SAFETY: a live list.
    if let Some(list) = unsafe { obj_mut::<TrackableList>(out_list) } {
        list.0 = if filter_type == TRACKABLE_PLANE || filter_type == TRACKABLE_ANY {
            (0..planes_now(&s).len()).collect()
        } else {
            Vec::new()
        };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArTrackableList_getSize(_s: *const O, list: *const O, out: *mut i32) {
    let _s = sim("ArTrackableList_getSize");
    // SAFETY: a live list and out pointer.
    if let Some(l) = unsafe { obj::<TrackableList>(list) } {
        unsafe { put(out, l.0.len() as i32) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArTrackableList_acquireItem(
    _s: *const O,
    list: *const O,
    index: i32,
    out_trackable: *mut *mut O,
) {
    let mut s = sim("ArTrackableList_acquireItem");
    // SAFETY: a live list.
    let id = unsafe { obj::<TrackableList>(list) }
        .and_then(|l| l.0.get(usize::try_from(index).ok()?).copied());
    if let (Some(id), false) = (id, out_trackable.is_null()) {
        s.made("trackable");
        // SAFETY: checked non-null.
        unsafe { put(out_trackable, into_c(Plane(id))) };
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArTrackable_release(trackable: *mut O) {
    let mut s = sim("ArTrackable_release");
    // SAFETY: an acquired trackable, released once.
    if unsafe { free_c::<Plane>(trackable) } {
        s.released("trackable");
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArTrackable_getTrackingState(
    _s: *const O,
    _trackable: *const O,
    out: *mut i32,
) {
    let _s = sim("ArTrackable_getTrackingState");
    // Every listed plane tracks (a subsumed one too: ARCore keeps it "as if independently
    // tracked").
    // SAFETY: a valid out pointer.
    unsafe { put(out, 0) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_acquireSubsumedBy(
    _s: *const O,
    plane: *const O,
    out_subsumed_by: *mut *mut O,
) {
    let mut s = sim("ArPlane_acquireSubsumedBy");
    // SAFETY: a live plane.
    let parent = unsafe { obj::<Plane>(plane) }.and_then(|p| parent_of(&s, p.0));
    let out = match parent {
        Some(id) => {
            s.made("trackable");
            into_c(Plane(id))
        }
        None => std::ptr::null_mut(),
    };
    // SAFETY: a valid out pointer.
    unsafe { put(out_subsumed_by, out) };
}

/// Runs `f` on the data of the live plane `plane`.
///
/// SAFETY (callers): `plane` is a live plane.
unsafe fn with_plane(name: &'static str, plane: *const O, f: impl FnOnce(&DetectedPlane)) {
    let s = sim(name);
    // SAFETY: per the function's contract.
    if let Some(p) = unsafe { obj::<Plane>(plane) }
        && let Some(data) = planes_now(&s).get(p.0)
    {
        f(data);
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_getType(_s: *const O, plane: *const O, out: *mut i32) {
    // SAFETY: forwarded contract; a valid out pointer.
    unsafe {
        with_plane("ArPlane_getType", plane, |p| {
            put(
                out,
                match p.kind {
                    PlaneKind::HorizontalUp => 0,
                    PlaneKind::HorizontalDown => 1,
                    PlaneKind::Vertical => 2,
                },
            )
        })
    };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_getCenterPose(_s: *const O, plane: *const O, out_pose: *mut O) {
    // SAFETY: forwarded contract; a live pose.
    unsafe {
        with_plane("ArPlane_getCenterPose", plane, |p| {
            if let Some(pose) = obj_mut::<Pose>(out_pose) {
                pose.0 = raw_pose(p.center_pose);
            }
        })
    };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_getExtentX(_s: *const O, plane: *const O, out: *mut f32) {
    // SAFETY: forwarded contract; a valid out pointer.
    unsafe { with_plane("ArPlane_getExtentX", plane, |p| put(out, p.extent.x)) };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_getExtentZ(_s: *const O, plane: *const O, out: *mut f32) {
    // SAFETY: forwarded contract; a valid out pointer.
    unsafe { with_plane("ArPlane_getExtentZ", plane, |p| put(out, p.extent.y)) };
}

/// The number of floats (two per vertex), as ARCore counts it.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_getPolygonSize(_s: *const O, plane: *const O, out: *mut i32) {
    // SAFETY: forwarded contract; a valid out pointer.
    unsafe {
        with_plane("ArPlane_getPolygonSize", plane, |p| {
            put(out, 2 * p.polygon.len() as i32)
        })
    };
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn ArPlane_getPolygon(_s: *const O, plane: *const O, out: *mut f32) {
    // SAFETY: forwarded contract; `out` holds ArPlane_getPolygonSize floats.
    unsafe {
        with_plane("ArPlane_getPolygon", plane, |p| {
            let xz: Vec<f32> = p.polygon.iter().flat_map(|v| v.to_array()).collect();
            put_all(out, &xz)
        })
    };
}
