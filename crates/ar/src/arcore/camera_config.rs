//! Which ARCore camera config to ask for: the one whose CPU image is the largest the frame
//! budget affords. Pure: the FFI (`ffi::camera_config`) reads the configs ARCore supports and
//! sets the one chosen here; the budget comes from the quality tier (`camera_image_max_px`).
//!
//! The app draws the camera background from ARCore's CPU image (YUV 4:2:0, converted on the
//! GPU once per camera frame), never from ARCore's GPU texture, so only the CPU image's size
//! buys sharpness; its pixels cost the upload and the conversion pass every camera frame.

/// What a camera config offers, pixels (landscape, as ARCore reports them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CameraConfigSize {
    /// The CPU image (`ArCameraConfig_getImageDimensions`).
    pub image: [u32; 2],
    /// ARCore's GPU texture (`ArCameraConfig_getTextureDimensions`): ARCore fills it whatever
    /// the app reads, so a smaller one is less work for the same CPU image.
    pub texture: [u32; 2],
}

impl CameraConfigSize {
    pub fn image_px(&self) -> u64 {
        u64::from(self.image[0]) * u64::from(self.image[1])
    }

    pub fn texture_px(&self) -> u64 {
        u64::from(self.texture[0]) * u64::from(self.texture[1])
    }
}

/// The back camera's configs as `arcore_c_api.h` documents them for every ARCore phone: three
/// CPU images, VGA (640 × 480), a middle one ("typically 1280x720") and one as large as the GPU
/// texture, which is the same in every config ("most devices provide a GPU texture resolution
/// of 1920x1080"). Phones with a 60 fps camera list them again at 60 fps; the app asks for
/// 30 fps. The simulated ARCore offers these, and the budget model prices them.
pub const DOCUMENTED_BACK_CAMERA: [CameraConfigSize; 3] = [
    CameraConfigSize {
        image: [640, 480],
        texture: [1920, 1080],
    },
    CameraConfigSize {
        image: [1280, 720],
        texture: [1920, 1080],
    },
    CameraConfigSize {
        image: [1920, 1080],
        texture: [1920, 1080],
    },
];

/// How far an image's shape is from the screen's: |ln(long/short of the image) − ln(long/short
/// of the screen)|, 0 for the same shape whatever the orientation (ARCore's images are
/// landscape; the phone's screen is usually portrait).
pub fn aspect_mismatch(image: [u32; 2], screen: [u32; 2]) -> f64 {
    let ratio = |[w, h]: [u32; 2]| {
        let (a, b) = (f64::from(w.max(1)), f64::from(h.max(1)));
        a.max(b) / a.min(b)
    };
    (ratio(image).ln() - ratio(screen).ln()).abs()
}

/// The config to use, as an index into `configs` (`None` for an empty list):
///
/// 1. the largest CPU image of at most `max_image_px` pixels;
/// 2. when none is that small, the smallest CPU image (the cheapest the phone offers);
/// 3. among CPU images of the same pixel count, the one whose shape is closest to `screen`'s
///    (less of it is cropped away; no screen: no preference), then the smaller GPU texture,
///    then the first listed (ARCore lists its preferred config first).
pub fn choose_camera_config(
    configs: &[CameraConfigSize],
    max_image_px: u64,
    screen: Option<[u32; 2]>,
) -> Option<usize> {
    let fits = |c: &CameraConfigSize| c.image_px() <= max_image_px;
    let any_fits = configs.iter().any(fits);
    let mismatch = |c: &CameraConfigSize| screen.map_or(0.0, |s| aspect_mismatch(c.image, s));
    // The best of two (by the rules above): true when `a` beats `b`.
    let better = |a: &CameraConfigSize, b: &CameraConfigSize| {
        if a.image_px() != b.image_px() {
            return if any_fits {
                a.image_px() > b.image_px()
            } else {
                a.image_px() < b.image_px()
            };
        }
        let (ma, mb) = (mismatch(a), mismatch(b));
        if (ma - mb).abs() > 1e-12 {
            return ma < mb;
        }
        a.texture_px() < b.texture_px()
    };
    let mut best: Option<usize> = None;
    for (i, c) in configs.iter().enumerate() {
        if any_fits && !fits(c) {
            continue;
        }
        if best.is_none_or(|b| better(c, &configs[b])) {
            best = Some(i);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(image: [u32; 2], texture: [u32; 2]) -> CameraConfigSize {
        CameraConfigSize { image, texture }
    }

    fn three() -> Vec<CameraConfigSize> {
        DOCUMENTED_BACK_CAMERA.to_vec()
    }

    #[test]
    fn the_largest_image_within_the_budget_is_chosen() {
        let c = three();
        // Exactly at a size's pixel count: that size (the bound is inclusive).
        assert_eq!(choose_camera_config(&c, 1920 * 1080, None), Some(2));
        assert_eq!(choose_camera_config(&c, u64::MAX, None), Some(2));
        assert_eq!(choose_camera_config(&c, 1920 * 1080 - 1, None), Some(1));
        assert_eq!(choose_camera_config(&c, 1280 * 720, None), Some(1));
        assert_eq!(choose_camera_config(&c, 1280 * 720 - 1, None), Some(0));
        assert_eq!(choose_camera_config(&c, 640 * 480, None), Some(0));
        // The list's order does not matter.
        let reversed: Vec<_> = c.iter().rev().copied().collect();
        assert_eq!(choose_camera_config(&reversed, 1_000_000, None), Some(1));
    }

    #[test]
    fn with_nothing_within_the_budget_the_smallest_image_is_chosen() {
        let c = three();
        assert_eq!(choose_camera_config(&c, 640 * 480 - 1, None), Some(0));
        assert_eq!(choose_camera_config(&c, 0, None), Some(0));
        let reversed: Vec<_> = c.iter().rev().copied().collect();
        assert_eq!(choose_camera_config(&reversed, 1, None), Some(2));
        assert_eq!(choose_camera_config(&[], u64::MAX, None), None);
    }

    #[test]
    fn equal_pixel_counts_go_to_the_screens_shape_then_the_smaller_texture() {
        // 1440 × 1080 (4:3) and 1920 × 810 (64:27): the same 1,555,200 pixels.
        let c = vec![
            config([1440, 1080], [1920, 1080]),
            config([1920, 810], [1920, 1080]),
        ];
        assert_eq!(c[0].image_px(), c[1].image_px());
        // A 1080 × 2400 portrait screen (20:9 = 2.22) is closer to 64:27 (2.37) than to 4:3.
        assert_eq!(
            choose_camera_config(&c, u64::MAX, Some([1080, 2400])),
            Some(1)
        );
        // A 3:4 tablet in portrait: 4:3 exactly.
        assert_eq!(
            choose_camera_config(&c, u64::MAX, Some([1536, 2048])),
            Some(0)
        );
        // The same CPU image with two textures (ARCore 1.15+ lists lower-texture configs):
        // the smaller texture, wherever it is listed.
        let t = vec![
            config([640, 480], [1920, 1080]),
            config([640, 480], [1280, 720]),
        ];
        assert_eq!(choose_camera_config(&t, u64::MAX, None), Some(1));
        assert_eq!(
            choose_camera_config(&t, u64::MAX, Some([1080, 2400])),
            Some(1)
        );
        // Identical configs (the 30 and 60 fps pair): the first listed.
        let same = vec![three()[1], three()[1]];
        assert_eq!(choose_camera_config(&same, u64::MAX, None), Some(0));
    }

    #[test]
    fn the_shape_mismatch_is_zero_for_the_same_shape_turned() {
        assert_eq!(aspect_mismatch([1920, 1080], [1080, 1920]), 0.0);
        // ln(20/9) − ln(16/9) = ln(1.25).
        let m = aspect_mismatch([1280, 720], [1080, 2400]);
        assert!((m - 1.25f64.ln()).abs() < 1e-12, "{m}");
    }
}
