//! Camera images made to fit the GPU: a texture may not be wider or taller than the device's
//! `max_texture_dimension_2d` (2048 in `wgpu::Limits::downlevel_defaults`, below 8192 on
//! phones such as the OPPO A54's PowerVR GE8320). An image above it is halved, 2 × 2 samples
//! averaged (luma and chroma alike, so 4:2:0 stays 4:2:0), until it fits.

use crate::{CameraImage, Yuv420};

/// One plane of `w × h` samples of `channels` interleaved bytes, halved: each output sample is
/// the rounded mean of its 2 × 2 block (a block cut by an odd edge averages what it has).
fn halve_plane(src: &[u8], w: usize, h: usize, channels: usize) -> (Vec<u8>, usize, usize) {
    let (hw, hh) = (w.div_ceil(2), h.div_ceil(2));
    let mut out = Vec::with_capacity(hw * hh * channels);
    for j in 0..hh {
        for i in 0..hw {
            for c in 0..channels {
                let (mut sum, mut n) = (0u32, 0u32);
                for (x, y) in [
                    (2 * i, 2 * j),
                    (2 * i + 1, 2 * j),
                    (2 * i, 2 * j + 1),
                    (2 * i + 1, 2 * j + 1),
                ] {
                    if x < w && y < h {
                        sum += u32::from(src[(y * w + x) * channels + c]);
                        n += 1;
                    }
                }
                out.push(((sum + n / 2) / n) as u8);
            }
        }
    }
    (out, hw, hh)
}

impl Yuv420 {
    /// The image at half size (rounded up), each plane 2 × 2-averaged.
    pub fn halved(&self) -> Yuv420 {
        let (w, h) = (self.width() as usize, self.height() as usize);
        let [cw, ch] = Self::chroma_size(self.width(), self.height()).map(|v| v as usize);
        let (y, hw, hh) = halve_plane(self.y(), w, h, 1);
        let (uv, _, _) = halve_plane(self.uv(), cw, ch, 2);
        Yuv420::new(hw as u32, hh as u32, y, uv, self.range())
            .expect("the halved chroma planes have the chroma size of the halved image")
    }
}

impl CameraImage {
    /// The image, halved until neither side exceeds `max_side` (unchanged when it fits).
    pub fn fit_within(self, max_side: u32) -> CameraImage {
        let max_side = max_side.max(1);
        let mut image = self;
        while image.size().into_iter().any(|s| s > max_side) {
            image = match image {
                CameraImage::Rgba(img) => {
                    let (w, h) = (img.width() as usize, img.height() as usize);
                    let (data, hw, hh) = halve_plane(img.as_raw(), w, h, 4);
                    CameraImage::Rgba(
                        image::RgbaImage::from_raw(hw as u32, hh as u32, data)
                            .expect("halve_plane gives hw × hh × 4 bytes"),
                    )
                }
                CameraImage::Yuv420(p) => CameraImage::Yuv420(p.halved()),
            };
        }
        image
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::YuvRange;

    #[test]
    fn an_image_above_the_limit_is_halved_until_it_fits() {
        // 4100 × 2050 → 2050 × 1025 → 1025 × 513 for a 2048 limit.
        let w = 4100u32;
        let h = 2050u32;
        let [cw, ch] = Yuv420::chroma_size(w, h);
        let y: Vec<u8> = (0..w * h).map(|k| (k % w % 2 * 100 + 10) as u8).collect();
        let uv = vec![128u8; (2 * cw * ch) as usize];
        let image = CameraImage::Yuv420(Yuv420::new(w, h, y, uv, YuvRange::Full).unwrap());
        let fitted = image.fit_within(2048);
        assert_eq!(fitted.size(), [1025, 513]);
        let CameraImage::Yuv420(p) = fitted else {
            panic!("YUV stays YUV")
        };
        // Columns alternate 10 and 110: every 2 × 2 (and 4 × 4) block averages to 60.
        assert!(p.y().iter().all(|&v| v == 60), "{:?}", &p.y()[..4]);
        assert!(p.uv().iter().all(|&v| v == 128));
        assert_eq!(p.uv().len(), 2 * 513 * 257);
    }

    #[test]
    fn an_image_that_fits_is_unchanged_and_odd_edges_average_what_they_have() {
        let img = image::RgbaImage::from_fn(3, 1, |x, _| image::Rgba([x as u8 * 10, 0, 0, 255]));
        let fits = CameraImage::Rgba(img.clone()).fit_within(3);
        assert_eq!(fits, CameraImage::Rgba(img.clone()));
        let CameraImage::Rgba(half) = CameraImage::Rgba(img).fit_within(2) else {
            panic!("RGBA stays RGBA")
        };
        // (0 + 10) / 2 = 5, then the lone 20.
        assert_eq!(half.dimensions(), (2, 1));
        assert_eq!(half.get_pixel(0, 0)[0], 5);
        assert_eq!(half.get_pixel(1, 0)[0], 20);
    }
}
