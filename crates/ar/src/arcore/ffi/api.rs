//! The function tables of the ARCore C API subset Regatta calls, loaded from one library with
//! libloading. Names and C signatures are those of `arcore_c_api.h` (ARCore SDK 1.x,
//! `libraries/include/arcore_c_api.h`); `*const` where the header says `const`, and
//! `ArFrame_acquireCameraImage`'s non-const session and frame passed as the same pointers.
//! No other module of the FFI is imported here: `session` and `frame` both build on this one.

use std::ffi::c_void;

/// An ARCore object (`ArSession`, `ArFrame`, `ArCamera`, …): opaque to us.
pub type O = c_void;
/// `const ArSession *` and the other const object pointers.
pub type S = *const O;
/// `ArStatus`.
pub type Status = i32;

macro_rules! c_api {
    ($(#[$doc:meta])* $name:ident {
        $($field:ident: fn($($arg:ty),*) $(-> $ret:ty)? = $sym:literal;)*
    }) => {
        $(#[$doc])*
        pub struct $name {
            $(pub $field: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl $name {
            /// Looks every function up in `lib`; the first missing name is the error.
            pub fn load(lib: &libloading::Library) -> Result<Self, libloading::Error> {
                // SAFETY: each symbol has the C signature stated in arcore_c_api.h; the
                // library is never unloaded (`Apis::load`).
                unsafe { Ok(Self { $($field: *lib.get(concat!($sym, "\0").as_bytes())?,)* }) }
            }
        }
    };
}

c_api! {
    /// Install check, session lifecycle and configuration.
    SessionApi {
        request_install: fn(*mut O, *mut O, i32, *mut i32) -> Status = "ArCoreApk_requestInstall";
        session_create: fn(*mut O, *mut O, *mut *mut O) -> Status = "ArSession_create";
        session_destroy: fn(*mut O) = "ArSession_destroy";
        config_create: fn(S, *mut *mut O) = "ArConfig_create";
        config_destroy: fn(*mut O) = "ArConfig_destroy";
        config_set_plane_finding: fn(S, *mut O, i32) = "ArConfig_setPlaneFindingMode";
        config_set_light: fn(S, *mut O, i32) = "ArConfig_setLightEstimationMode";
        config_set_update: fn(S, *mut O, i32) = "ArConfig_setUpdateMode";
        config_set_texture_update: fn(S, *mut O, i32) = "ArConfig_setTextureUpdateMode";
        session_configure: fn(*mut O, S) -> Status = "ArSession_configure";
        session_resume: fn(*mut O) -> Status = "ArSession_resume";
        session_pause: fn(*mut O) -> Status = "ArSession_pause";
        session_update: fn(*mut O, *mut O) -> Status = "ArSession_update";
        session_set_display_geometry: fn(*mut O, i32, i32, i32) = "ArSession_setDisplayGeometry";
        frame_create: fn(S, *mut *mut O) = "ArFrame_create";
        frame_destroy: fn(*mut O) = "ArFrame_destroy";
    }
}

c_api! {
    /// Per-frame reads: camera, image, light estimate, planes.
    FrameApi {
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
        acquire_image: fn(S, S, *mut *mut O) -> Status = "ArFrame_acquireCameraImage";
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
        plane_subsumed_by: fn(S, S, *mut *mut O) = "ArPlane_acquireSubsumedBy";
        plane_type: fn(S, S, *mut i32) = "ArPlane_getType";
        plane_centre: fn(S, S, *mut O) = "ArPlane_getCenterPose";
        plane_extent_x: fn(S, S, *mut f32) = "ArPlane_getExtentX";
        plane_extent_z: fn(S, S, *mut f32) = "ArPlane_getExtentZ";
        polygon_size: fn(S, S, *mut i32) = "ArPlane_getPolygonSize";
        polygon: fn(S, S, *mut f32) = "ArPlane_getPolygon";
    }
}

c_api! {
    /// The camera configs: the CPU image sizes ARCore offers, the one in use, and setting one
    /// (while the session is paused). Enum arguments (`ArCameraConfigTargetFps` bits,
    /// `ArCameraConfigFacingDirection`) are `uint32_t` and `int32_t` as in the header.
    CameraConfigApi {
        filter_create: fn(S, *mut *mut O) = "ArCameraConfigFilter_create";
        filter_destroy: fn(*mut O) = "ArCameraConfigFilter_destroy";
        filter_set_target_fps: fn(S, *mut O, u32) = "ArCameraConfigFilter_setTargetFps";
        filter_set_facing: fn(S, *mut O, i32) = "ArCameraConfigFilter_setFacingDirection";
        list_create: fn(S, *mut *mut O) = "ArCameraConfigList_create";
        list_destroy: fn(*mut O) = "ArCameraConfigList_destroy";
        list_size: fn(S, S, *mut i32) = "ArCameraConfigList_getSize";
        list_item: fn(S, S, i32, *mut O) = "ArCameraConfigList_getItem";
        supported: fn(S, S, *mut O) = "ArSession_getSupportedCameraConfigsWithFilter";
        config_create: fn(S, *mut *mut O) = "ArCameraConfig_create";
        config_destroy: fn(*mut O) = "ArCameraConfig_destroy";
        image_size: fn(S, S, *mut i32, *mut i32) = "ArCameraConfig_getImageDimensions";
        texture_size: fn(S, S, *mut i32, *mut i32) = "ArCameraConfig_getTextureDimensions";
        facing: fn(S, S, *mut i32) = "ArCameraConfig_getFacingDirection";
        session_set: fn(S, S) -> Status = "ArSession_setCameraConfig";
        session_get: fn(S, *mut O) = "ArSession_getCameraConfig";
    }
}

/// The tables, pointing into a library that stays loaded for the rest of the process.
pub struct Apis {
    pub session: SessionApi,
    pub frame: FrameApi,
    pub camera_config: CameraConfigApi,
}

impl Apis {
    /// Loads the library at `path` (a bare file name searches the loader's path, as on
    /// Android) and every function of every table.
    ///
    /// The library's handle is leaked on purpose: it is never `dlclose`d. ARCore keeps threads
    /// running for up to 10 s after a pause, and its session is destroyed on a thread of ours
    /// after the activity is gone; unloading its code under them would crash the process
    /// (issue 26). A second load of the same file only raises the loader's count.
    pub fn load(path: &std::path::Path) -> Result<Self, libloading::Error> {
        // SAFETY: loading ARCore's library (or the simulator) runs no initialiser with
        // preconditions of ours.
        let library = unsafe { libloading::Library::new(path) }?;
        let library: &'static libloading::Library = Box::leak(Box::new(library));
        Ok(Self {
            session: SessionApi::load(library)?,
            frame: FrameApi::load(library)?,
            camera_config: CameraConfigApi::load(library)?,
        })
    }
}

/// `arcore_c_api.h` enum values the FFI passes or reads.
pub mod consts {
    /// `AR_PLANE_FINDING_MODE_HORIZONTAL`.
    pub const PLANES_HORIZONTAL: i32 = 1;
    /// `AR_UPDATE_MODE_LATEST_CAMERA_IMAGE`.
    pub const UPDATE_LATEST: i32 = 1;
    /// `AR_TEXTURE_UPDATE_MODE_EXPOSE_HARDWARE_BUFFER` (no GL context: wgpu draws with Vulkan).
    pub const TEXTURE_HARDWARE_BUFFER: i32 = 1;
    /// `AR_TRACKABLE_PLANE`.
    pub const TRACKABLE_PLANE: i32 = 0x4152_0101;
    /// `AR_COORDINATES_2D_IMAGE_NORMALIZED`, `AR_COORDINATES_2D_VIEW_NORMALIZED`.
    pub const COORDS_IMAGE_NORMALIZED: i32 = 3;
    pub const COORDS_VIEW_NORMALIZED: i32 = 8;
    /// `AR_LIGHT_ESTIMATE_STATE_VALID`.
    pub const LIGHT_VALID: i32 = 1;
    /// `AR_TRACKING_STATE_TRACKING`, `_PAUSED`, `_STOPPED`.
    pub const TRACKING: i32 = 0;
    pub const PAUSED: i32 = 1;
    pub const STOPPED: i32 = 2;
    /// `AR_PLANE_HORIZONTAL_UPWARD_FACING`, `_DOWNWARD_FACING`, `AR_PLANE_VERTICAL`.
    pub const PLANE_UP: i32 = 0;
    pub const PLANE_DOWN: i32 = 1;
    pub const PLANE_VERTICAL: i32 = 2;
    /// `AR_CAMERA_CONFIG_TARGET_FPS_30` (a bit of `ArCameraConfigTargetFps`).
    pub const CAMERA_TARGET_FPS_30: u32 = 0x0001;
    /// `AR_CAMERA_CONFIG_FACING_DIRECTION_BACK`.
    pub const CAMERA_FACING_BACK: i32 = 0;
    /// Android API level from which `AR_TEXTURE_UPDATE_MODE_EXPOSE_HARDWARE_BUFFER` works
    /// (Android 8.1: `AHardwareBuffer`).
    pub const HARDWARE_BUFFER_MIN_API: u32 = 27;
}
