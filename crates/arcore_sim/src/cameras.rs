//! The cameras a simulated phone offers: the camera configs `arcore_c_api.h` documents for a
//! back camera (a VGA CPU image, a middle one, typically 1280 × 720, and one as large as the GPU
//! texture, 1920 × 1080 on most phones; every texture the same), again at 60 fps on a phone
//! with a 60 fps camera, and the selfie camera's (listed since ARCore 1.23). Plain data: the C
//! API over it is [`crate::camera_config`].

/// `AR_CAMERA_CONFIG_FACING_DIRECTION_BACK`, `_FRONT`.
pub const FACING_BACK: i32 = 0;
pub const FACING_FRONT: i32 = 1;
/// `AR_CAMERA_CONFIG_TARGET_FPS_30`, `_60` (bits).
pub const FPS_30: u32 = 0x0001;
pub const FPS_60: u32 = 0x0002;

/// One camera config a phone offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CameraConfig {
    /// CPU image, pixels.
    pub image: [i32; 2],
    /// GPU texture, pixels.
    pub texture: [i32; 2],
    /// Capture rate range, frames per second.
    pub fps: [i32; 2],
    pub facing: i32,
}

impl CameraConfig {
    pub const fn back(image: [i32; 2], texture: [i32; 2], fps: i32) -> Self {
        Self {
            image,
            texture,
            fps: [fps, fps],
            facing: FACING_BACK,
        }
    }

    /// The `ArCameraConfigTargetFps` bit this config answers to.
    pub fn target_fps(&self) -> u32 {
        if self.fps[1] >= 60 { FPS_60 } else { FPS_30 }
    }
}

/// The three back-camera configs of `arcore_c_api.h` with a 1920 × 1080 texture
/// (`ar::arcore::DOCUMENTED_BACK_CAMERA`), at 30 fps.
fn back_30() -> [CameraConfig; 3] {
    let px = |v: [u32; 2]| v.map(|x| x as i32);
    ar::arcore::DOCUMENTED_BACK_CAMERA.map(|c| CameraConfig::back(px(c.image), px(c.texture), 30))
}

/// The selfie camera's config (listed since ARCore 1.23; a filter for the back camera drops
/// it).
const FRONT: CameraConfig = CameraConfig {
    image: [640, 480],
    texture: [1280, 720],
    fps: [30, 30],
    facing: FACING_FRONT,
};

/// Which phone's list the simulator gives (`RegattaSim_useCameraConfigs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhoneCameras {
    /// An OPPO A54 class phone: the three 30 fps back configs and the front camera's.
    ThirtyFps,
    /// A Pixel 2 XL class phone (a 60 fps camera): the three back configs at 30 fps, the same
    /// three at 60 fps, and the front camera's.
    SixtyFps,
}

/// The configs a phone lists, and the index of the one a new session uses (ARCore's default:
/// the back camera's VGA image at 30 fps).
pub fn phone_configs(phone: PhoneCameras) -> (Vec<CameraConfig>, usize) {
    // ARCore lists the config that best matches the filter first, a 60 fps one before 30.
    let mut list = Vec::new();
    if phone == PhoneCameras::SixtyFps {
        list.extend(back_30().map(|c| CameraConfig { fps: [60, 60], ..c }));
    }
    list.extend(back_30());
    list.push(FRONT);
    (list, 0)
}

/// A phone whose camera offers one size (a replay's, or a test's synthetic feed).
pub fn single_config(width: u32, height: u32) -> (Vec<CameraConfig>, usize) {
    let size = [
        width.min(i32::MAX as u32) as i32,
        height.min(i32::MAX as u32) as i32,
    ];
    (vec![CameraConfig::back(size, size, 30)], 0)
}
