//! The camera image as the frame sources hand it over and the AR effects upload it: RGBA, or
//! YUV 4:2:0 planes normalised from the strided layout ARCore's CPU image (`AImage`) gives,
//! and their BT.601 colour ([`yuv`]). `crates/ar` makes these images, `crates/effects` draws
//! them (its camera upload: the Y and chroma planes as textures, converted in a shader with the
//! same [`YuvToRgb`]); this crate sits below both so that neither knows the other.

use std::fmt;

mod fit;
pub mod yuv;

pub use yuv::{YuvRange, YuvToRgb};

/// A camera image.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraImage {
    /// sRGB-encoded RGBA pixels.
    Rgba(image::RgbaImage),
    /// YUV 4:2:0 planes (gamma-encoded R'G'B' after [`YuvToRgb`]).
    Yuv420(Yuv420),
}

impl CameraImage {
    /// Size in pixels, [width, height].
    pub fn size(&self) -> [u32; 2] {
        match self {
            CameraImage::Rgba(img) => [img.width(), img.height()],
            CameraImage::Yuv420(p) => [p.width(), p.height()],
        }
    }

    /// The image as sRGB RGBA on the CPU (YUV through [`Yuv420::to_rgba8`]).
    pub fn to_rgba_image(&self) -> image::RgbaImage {
        match self {
            CameraImage::Rgba(img) => img.clone(),
            CameraImage::Yuv420(p) => p.to_rgba_image(),
        }
    }
}

impl From<image::RgbaImage> for CameraImage {
    fn from(img: image::RgbaImage) -> Self {
        CameraImage::Rgba(img)
    }
}

impl From<Yuv420> for CameraImage {
    fn from(p: Yuv420) -> Self {
        CameraImage::Yuv420(p)
    }
}

/// A plane layout that does not fit its buffers: one sentence naming the plane and field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LayoutError(pub String);

impl fmt::Display for LayoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for LayoutError {}

/// YUV 4:2:0 planes as `AImage` (`AIMAGE_FORMAT_YUV_420_888`) lays them out: a full-size luma
/// plane and two chroma planes of ⌈width/2⌉ × ⌈height/2⌉ samples, each with its own row stride
/// (bytes from one row to the next); `uv_pixel_stride` is 1 for planar (I420) and 2 for
/// interleaved (NV12/NV21, where `u` and `v` point into one buffer a byte apart) chroma.
#[derive(Clone, Copy, Debug)]
pub struct StridedYuv420<'a> {
    pub width: u32,
    pub height: u32,
    pub y: &'a [u8],
    pub y_row_stride: u32,
    pub u: &'a [u8],
    pub v: &'a [u8],
    pub uv_row_stride: u32,
    pub uv_pixel_stride: u32,
}

/// YUV 4:2:0 planes, normalised for upload: a tightly packed luma plane (`width × height`
/// bytes) and the chroma interleaved as (U, V) pairs (`2 × ⌈width/2⌉ × ⌈height/2⌉` bytes),
/// top row first. Each chroma sample covers a 2×2 block of pixels (replicated, not
/// interpolated, as in [`Yuv420::to_rgba8`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Yuv420 {
    width: u32,
    height: u32,
    y: Vec<u8>,
    uv: Vec<u8>,
    range: YuvRange,
}

impl Yuv420 {
    /// Chroma samples per row and rows for an image of `width × height` pixels.
    pub fn chroma_size(width: u32, height: u32) -> [u32; 2] {
        [width.div_ceil(2), height.div_ceil(2)]
    }

    /// Planes already in the normalised layout; refuses buffers of the wrong length.
    pub fn new(
        width: u32,
        height: u32,
        y: Vec<u8>,
        uv: Vec<u8>,
        range: YuvRange,
    ) -> Result<Yuv420, LayoutError> {
        let [cw, ch] = Self::chroma_size(width, height);
        let (n, nc) = (
            width as usize * height as usize,
            2 * cw as usize * ch as usize,
        );
        if width == 0 || height == 0 {
            return Err(LayoutError(format!(
                "YUV image: empty size {width}×{height}"
            )));
        }
        if y.len() != n || uv.len() != nc {
            return Err(LayoutError(format!(
                "YUV image {width}×{height}: needs {n} luma and {nc} chroma bytes, got {} and {}",
                y.len(),
                uv.len()
            )));
        }
        Ok(Yuv420 {
            width,
            height,
            y,
            uv,
            range,
        })
    }

    /// Normalises `AImage`-style strided planes (see [`StridedYuv420`]); refuses strides
    /// narrower than a row and planes too short for their stated layout (the last row may be
    /// shorter than its stride, as `AImage` gives it).
    pub fn from_strided(p: &StridedYuv420, range: YuvRange) -> Result<Yuv420, LayoutError> {
        let (w, h) = (p.width as usize, p.height as usize);
        if w == 0 || h == 0 {
            return Err(LayoutError(format!(
                "YUV image: empty size {}×{}",
                p.width, p.height
            )));
        }
        let [cw, ch] = Self::chroma_size(p.width, p.height).map(|v| v as usize);
        let (ys, cs, ps) = (
            p.y_row_stride as usize,
            p.uv_row_stride as usize,
            p.uv_pixel_stride as usize,
        );
        let err = |what: String| {
            Err(LayoutError(format!(
                "YUV image {}×{}: {what}",
                p.width, p.height
            )))
        };
        if ys < w {
            return err(format!("y_row_stride {ys} is less than the width {w}"));
        }
        if ps == 0 {
            return err("uv_pixel_stride is 0".to_string());
        }
        let chroma_row = (cw - 1) * ps + 1;
        if cs < chroma_row {
            return err(format!(
                "uv_row_stride {cs} is less than a chroma row ({cw} samples {ps} bytes apart)"
            ));
        }
        let need_y = (h - 1) * ys + w;
        let need_c = (ch - 1) * cs + chroma_row;
        for (name, plane, need) in [("y", p.y, need_y), ("u", p.u, need_c), ("v", p.v, need_c)] {
            if plane.len() < need {
                return err(format!(
                    "the {name} plane has {} bytes, its layout needs {need}",
                    plane.len()
                ));
            }
        }
        let y = yuv::repack_plane(p.y, ys, w, h, w);
        let uv = yuv::interleave_chroma(p.u, p.v, cs, ps, cw, ch, 2 * cw);
        match (y, uv) {
            (Some(y), Some(uv)) => Self::new(p.width, p.height, y, uv, range),
            _ => err("the planes do not fit their strides".to_string()),
        }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Luma, `width × height` bytes.
    pub fn y(&self) -> &[u8] {
        &self.y
    }

    /// Chroma as (U, V) pairs, [`Yuv420::chroma_size`] samples.
    pub fn uv(&self) -> &[u8] {
        &self.uv
    }

    pub fn range(&self) -> YuvRange {
        self.range
    }

    /// The decoding matrix of these samples.
    pub fn to_rgb(&self) -> YuvToRgb {
        YuvToRgb::bt601(self.range)
    }

    /// The CPU reference conversion: tightly packed sRGB RGBA8, each pixel through
    /// [`YuvToRgb::convert`] with the chroma sample of its 2×2 block.
    pub fn to_rgba8(&self) -> Vec<u8> {
        let m = self.to_rgb();
        let (w, h) = (self.width as usize, self.height as usize);
        let cw = Self::chroma_size(self.width, self.height)[0] as usize;
        let mut out = vec![255u8; w * h * 4];
        for j in 0..h {
            for i in 0..w {
                let c = 2 * ((j / 2) * cw + i / 2);
                let rgb = m.convert(self.y[j * w + i], self.uv[c], self.uv[c + 1]);
                out[(j * w + i) * 4..][..3].copy_from_slice(&rgb);
            }
        }
        out
    }

    /// Encode sRGB RGBA pixels as YUV 4:2:0 samples of `range`: each pixel through the inverse
    /// of [`YuvToRgb::bt601`], the chroma averaged over its 2×2 block (synthetic feeds and
    /// benches: what a camera that delivers YUV would hand over). Alpha is dropped.
    pub fn from_rgba(img: &image::RgbaImage, range: YuvRange) -> Result<Yuv420, LayoutError> {
        let (w, h) = (img.width(), img.height());
        let to_rgb = YuvToRgb::bt601(range);
        let inverse = invert3(to_rgb.matrix);
        let yuv_of = |p: &image::Rgba<u8>| -> [f64; 3] {
            let d: [f64; 3] = std::array::from_fn(|k| f64::from(p[k]) / 255.0 - to_rgb.offset[k]);
            std::array::from_fn(|r| (0..3).map(|c| inverse[r][c] * d[c]).sum())
        };
        let byte = |s: f64| (s * 255.0).round().clamp(0.0, 255.0) as u8;
        let y = img.pixels().map(|p| byte(yuv_of(p)[0])).collect();
        let [cw, ch] = Self::chroma_size(w, h);
        let mut uv = Vec::with_capacity(2 * (cw * ch) as usize);
        for j in 0..ch {
            for i in 0..cw {
                let block: Vec<[f64; 3]> = [(0, 0), (1, 0), (0, 1), (1, 1)]
                    .iter()
                    .map(|&(di, dj)| (2 * i + di, 2 * j + dj))
                    .filter(|&(x, y)| x < w && y < h)
                    .map(|(x, y)| yuv_of(img.get_pixel(x, y)))
                    .collect();
                let n = block.len() as f64;
                uv.push(byte(block.iter().map(|s| s[1]).sum::<f64>() / n));
                uv.push(byte(block.iter().map(|s| s[2]).sum::<f64>() / n));
            }
        }
        Yuv420::new(w, h, y, uv, range)
    }

    /// [`Yuv420::to_rgba8`] as an image.
    pub fn to_rgba_image(&self) -> image::RgbaImage {
        image::RgbaImage::from_raw(self.width, self.height, self.to_rgba8())
            .expect("to_rgba8 gives width × height × 4 bytes")
    }
}

/// The inverse of a 3×3 matrix (rows), by cofactors; the BT.601 matrices are well conditioned.
fn invert3(m: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let c = |r: usize, k: usize| {
        let (r0, r1) = ((r + 1) % 3, (r + 2) % 3);
        let (k0, k1) = ((k + 1) % 3, (k + 2) % 3);
        m[r0][k0] * m[r1][k1] - m[r0][k1] * m[r1][k0]
    };
    let det: f64 = (0..3).map(|k| m[0][k] * c(0, k)).sum();
    std::array::from_fn(|r| std::array::from_fn(|k| c(k, r) / det))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgba_encoded_as_yuv_decodes_back() {
        // Flat colours come back within one code (the 8-bit rounding of the samples), in both
        // ranges; a gentle gradient (2–3 codes per pixel) within four (its chroma shared by
        // each 2×2 block, half a pixel off, times the chroma's gain into R'G'B' of up to 1.8).
        for range in [YuvRange::Full, YuvRange::Limited] {
            for rgb in [[0u8, 0, 0], [255, 255, 255], [200, 40, 90], [12, 180, 250]] {
                let img =
                    image::RgbaImage::from_pixel(6, 5, image::Rgba([rgb[0], rgb[1], rgb[2], 255]));
                let back = Yuv420::from_rgba(&img, range)
                    .expect("sizes fit")
                    .to_rgba_image();
                for p in back.pixels() {
                    for k in 0..3 {
                        assert!(p[k].abs_diff(rgb[k]) <= 1, "{range:?} {rgb:?}: {p:?}");
                    }
                }
            }
            let img = image::RgbaImage::from_fn(33, 17, |x, y| {
                image::Rgba([
                    (x * 3) as u8,
                    (y * 2 + 40) as u8,
                    (x * 2 + y * 3) as u8,
                    255,
                ])
            });
            let back = Yuv420::from_rgba(&img, range)
                .expect("sizes fit")
                .to_rgba_image();
            for (p, q) in img.pixels().zip(back.pixels()) {
                for k in 0..3 {
                    assert!(p[k].abs_diff(q[k]) <= 4, "{range:?}: {p:?} → {q:?}");
                }
            }
        }
    }

    /// A hand-made 3×3 NV21 frame (odd size: chroma 2×2) with padded rows: luma rows 5 bytes
    /// apart, chroma rows 6 bytes apart with V U pairs, the last rows cut short as AImage
    /// gives them.
    fn nv21() -> (Vec<u8>, Vec<u8>) {
        let y = vec![
            10, 11, 12, 0, 0, //
            20, 21, 22, 0, 0, //
            30, 31, 32,
        ];
        // V U V U pad pad / V U V (last U is the next byte, present in the buffer).
        let vu = vec![
            100, 50, 101, 51, 0, 0, //
            102, 52, 103, 53,
        ];
        (y, vu)
    }

    /// The 3×3 NV21 buffers of [`nv21`] as ARCore's planes.
    fn nv21_planes<'a>(y: &'a [u8], vu: &'a [u8]) -> StridedYuv420<'a> {
        StridedYuv420 {
            width: 3,
            height: 3,
            y,
            y_row_stride: 5,
            u: &vu[1..],
            v: vu,
            uv_row_stride: 6,
            uv_pixel_stride: 2,
        }
    }

    #[test]
    fn strided_nv21_planes_normalise_to_tight_luma_and_uv_pairs() {
        let (y, vu) = nv21();
        let p = nv21_planes(&y, &vu);
        let n = Yuv420::from_strided(&p, YuvRange::Full).expect("fits");
        assert_eq!(n.y(), &[10, 11, 12, 20, 21, 22, 30, 31, 32]);
        assert_eq!(n.uv(), &[50, 100, 51, 101, 52, 102, 53, 103]);
        // The same samples as separate I420 planes give the same result.
        let (u, v) = ([50, 51, 52, 53], [100, 101, 102, 103]);
        let planar = StridedYuv420 {
            y_row_stride: 5,
            u: &u,
            v: &v,
            uv_row_stride: 2,
            uv_pixel_stride: 1,
            ..p
        };
        assert_eq!(Yuv420::from_strided(&planar, YuvRange::Full), Ok(n));
    }

    #[test]
    fn the_cpu_reference_uses_each_pixels_2x2_chroma_block() {
        let (y, vu) = nv21();
        let p = nv21_planes(&y, &vu);
        let img = Yuv420::from_strided(&p, YuvRange::Full).unwrap();
        let rgba = img.to_rgba8();
        let m = YuvToRgb::bt601(YuvRange::Full);
        // Pixel (i, j) → chroma (i/2, j/2), read by hand from the strided buffers.
        let expect = |i: usize, j: usize, yy: u8| {
            let c = (j / 2) * 6 + (i / 2) * 2;
            m.convert(yy, vu[c + 1], vu[c])
        };
        for j in 0..3 {
            for i in 0..3 {
                let px = &rgba[(j * 3 + i) * 4..][..4];
                assert_eq!(px[..3], expect(i, j, y[j * 5 + i]), "pixel {i},{j}");
                assert_eq!(px[3], 255);
            }
        }
    }

    #[test]
    fn bad_layouts_are_refused_with_the_plane_named() {
        let (y, vu) = nv21();
        let ok = StridedYuv420 {
            width: 3,
            height: 3,
            y: &y,
            y_row_stride: 5,
            u: &vu[1..],
            v: &vu,
            uv_row_stride: 6,
            uv_pixel_stride: 2,
        };
        let msg = |p: StridedYuv420| Yuv420::from_strided(&p, YuvRange::Full).unwrap_err().0;
        assert!(msg(StridedYuv420 { y: &y[..12], ..ok }).contains("the y plane has 12 bytes"));
        assert!(msg(StridedYuv420 { u: &vu[1..9], ..ok }).contains("the u plane has 8 bytes"));
        assert!(
            msg(StridedYuv420 {
                y_row_stride: 2,
                ..ok
            })
            .contains("y_row_stride 2")
        );
        assert!(
            msg(StridedYuv420 {
                uv_pixel_stride: 0,
                ..ok
            })
            .contains("uv_pixel_stride is 0")
        );
        assert!(
            msg(StridedYuv420 {
                uv_row_stride: 2,
                ..ok
            })
            .contains("uv_row_stride 2")
        );
        assert!(msg(StridedYuv420 { width: 0, ..ok }).contains("empty size 0×3"));
        assert!(
            Yuv420::new(2, 2, vec![0; 4], vec![0; 3], YuvRange::Full)
                .unwrap_err()
                .0
                .contains("needs 4 luma and 2 chroma bytes, got 4 and 3")
        );
    }
}
