//! The camera image's colour: ARCore's CPU image is YUV 4:2:0 (`AIMAGE_FORMAT_YUV_420_888`),
//! which Android's camera stack fills with BT.601 full-range (JFIF) values; limited range
//! (16–235 luma) is kept for recordings from other sources. The phone uploads the Y plane and
//! the interleaved chroma as two textures (wgpu has no external textures) and the `effects`
//! crate's camera upload (`shaders/effects/camera_yuv.wgsl`) applies [`YuvToRgb`] once per
//! camera frame into the RGBA texture its `sample_camera` reads; the CPU path ([`crate::Yuv420::to_rgba8`]) uses
//! the same matrix.

/// Quantisation range of the YUV samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum YuvRange {
    /// JFIF: Y, Cb, Cr all use 0–255 (Cb, Cr centred at 128). Android camera images.
    Full,
    /// Studio swing: Y in 16–235, Cb and Cr in 16–240 (ITU-R BT.601 quantisation).
    Limited,
}

/// BT.601 luma weights of red and blue (green is 1 − KR − KB).
pub const KR: f64 = 0.299;
pub const KB: f64 = 0.114;

/// `rgb = matrix · (y, u, v) + offset` for samples normalised to 0..1 (texture values), giving
/// non-linear (gamma-encoded) R'G'B' in 0..1 before clamping. Rows are R, G, B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YuvToRgb {
    pub matrix: [[f64; 3]; 3],
    pub offset: [f64; 3],
}

impl YuvToRgb {
    /// The BT.601 decoding matrix for `range`, derived from KR and KB (not typed in), so it is
    /// exactly the inverse of the standard's encoding equations.
    pub fn bt601(range: YuvRange) -> Self {
        let kg = 1.0 - KR - KB;
        // Normalised sample s in 0..1 → E'Y in 0..1 and E'Cb, E'Cr in -0.5..0.5.
        let (y_scale, y_bias, c_scale) = match range {
            YuvRange::Full => (1.0, 0.0, 1.0),
            YuvRange::Limited => (255.0 / 219.0, -16.0 / 219.0, 255.0 / 224.0),
        };
        let c_bias = -128.0 / 255.0 * c_scale;
        // R = Y + 2(1−KR) Cr,  B = Y + 2(1−KB) Cb,  G = (Y − KR R − KB B) / KG.
        let r_cr = 2.0 * (1.0 - KR);
        let b_cb = 2.0 * (1.0 - KB);
        let g_cb = -KB * b_cb / kg;
        let g_cr = -KR * r_cr / kg;
        let rows = [[1.0, 0.0, r_cr], [1.0, g_cb, g_cr], [1.0, b_cb, 0.0]];
        let mut matrix = [[0.0; 3]; 3];
        let mut offset = [0.0; 3];
        for (k, row) in rows.iter().enumerate() {
            matrix[k] = [row[0] * y_scale, row[1] * c_scale, row[2] * c_scale];
            offset[k] = row[0] * y_bias + (row[1] + row[2]) * c_bias;
        }
        Self { matrix, offset }
    }

    /// One pixel from 8-bit samples to 8-bit R'G'B' (rounded, clamped).
    pub fn convert(&self, y: u8, u: u8, v: u8) -> [u8; 3] {
        let s = [
            f64::from(y) / 255.0,
            f64::from(u) / 255.0,
            f64::from(v) / 255.0,
        ];
        std::array::from_fn(|k| {
            let m = self.matrix[k];
            let x = m[0] * s[0] + m[1] * s[1] + m[2] * s[2] + self.offset[k];
            (x * 255.0).round().clamp(0.0, 255.0) as u8
        })
    }

    /// The matrix as three `vec4<f32>` columns for a WGSL uniform (`mat3x3` padded), with the
    /// offset as the fourth column: `rgb = mat3x3(c0, c1, c2) * yuv + c3`.
    pub fn to_gpu_columns(&self) -> [[f32; 4]; 4] {
        let mut cols = [[0.0f32; 4]; 4];
        for (c, col) in cols.iter_mut().enumerate().take(3) {
            for (r, x) in col.iter_mut().enumerate().take(3) {
                *x = self.matrix[r][c] as f32;
            }
        }
        for (r, x) in cols[3].iter_mut().enumerate().take(3) {
            *x = self.offset[r] as f32;
        }
        cols
    }
}

/// Copies one image plane of `height` rows, `row_bytes` used bytes each, from rows `row_stride`
/// bytes apart (AImage's layout) into rows `padded_row` bytes apart (wgpu needs a multiple of
/// 256 for texture uploads). `None` when `src` is too short for the stated layout.
pub fn repack_plane(
    src: &[u8],
    row_stride: usize,
    row_bytes: usize,
    height: usize,
    padded_row: usize,
) -> Option<Vec<u8>> {
    if row_bytes > row_stride.max(row_bytes) || padded_row < row_bytes || height == 0 {
        return None;
    }
    let needed = (height - 1) * row_stride + row_bytes;
    if src.len() < needed {
        return None;
    }
    let mut out = vec![0u8; padded_row * height];
    for j in 0..height {
        out[j * padded_row..j * padded_row + row_bytes]
            .copy_from_slice(&src[j * row_stride..j * row_stride + row_bytes]);
    }
    Some(out)
}

/// Interleaves the chroma planes (`u`, `v` with their row and pixel strides, as AImage gives
/// them; for NV21 both point into one buffer with pixel stride 2) into an RG8 texture of
/// `width` × `height` chroma samples, rows `padded_row` bytes apart. `None` when a plane is too
/// short for the stated layout.
pub fn interleave_chroma(
    u: &[u8],
    v: &[u8],
    row_stride: usize,
    pixel_stride: usize,
    width: usize,
    height: usize,
    padded_row: usize,
) -> Option<Vec<u8>> {
    if width == 0 || height == 0 || pixel_stride == 0 || padded_row < 2 * width {
        return None;
    }
    let needed = (height - 1) * row_stride + (width - 1) * pixel_stride + 1;
    if u.len() < needed || v.len() < needed {
        return None;
    }
    let mut out = vec![0u8; padded_row * height];
    for j in 0..height {
        for i in 0..width {
            let s = j * row_stride + i * pixel_stride;
            out[j * padded_row + 2 * i] = u[s];
            out[j * padded_row + 2 * i + 1] = v[s];
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard's encoding: R'G'B' in 0..1 → 8-bit Y'CbCr (BT.601 §2.5.1–2.5.3).
    fn encode(rgb: [f64; 3], range: YuvRange) -> [u8; 3] {
        let y = KR * rgb[0] + (1.0 - KR - KB) * rgb[1] + KB * rgb[2];
        let cb = (rgb[2] - y) / (2.0 * (1.0 - KB));
        let cr = (rgb[0] - y) / (2.0 * (1.0 - KR));
        let q = |x: f64| x.round().clamp(0.0, 255.0) as u8;
        match range {
            YuvRange::Full => [q(255.0 * y), q(128.0 + 255.0 * cb), q(128.0 + 255.0 * cr)],
            YuvRange::Limited => [
                q(16.0 + 219.0 * y),
                q(128.0 + 224.0 * cb),
                q(128.0 + 224.0 * cr),
            ],
        }
    }

    #[test]
    fn limited_range_colour_bars_match_the_published_codes() {
        // 100 % bars, BT.601 8-bit studio range (e.g. EBU/SMPTE tables).
        let bars: [([u8; 3], [u8; 3]); 5] = [
            ([255, 255, 255], [235, 128, 128]),
            ([0, 0, 0], [16, 128, 128]),
            ([255, 0, 0], [81, 90, 240]),
            ([0, 255, 0], [145, 54, 34]),
            ([0, 0, 255], [41, 240, 110]),
        ];
        let m = YuvToRgb::bt601(YuvRange::Limited);
        for (rgb, yuv) in bars {
            let rgbf = rgb.map(|c| f64::from(c) / 255.0);
            assert_eq!(
                encode(rgbf, YuvRange::Limited),
                yuv,
                "encoder check for {rgb:?}"
            );
            let back = m.convert(yuv[0], yuv[1], yuv[2]);
            for k in 0..3 {
                assert!(
                    (i32::from(back[k]) - i32::from(rgb[k])).abs() <= 2,
                    "{rgb:?} -> {yuv:?} -> {back:?}"
                );
            }
        }
    }

    #[test]
    fn full_range_jfif_red_and_grey() {
        let m = YuvToRgb::bt601(YuvRange::Full);
        // JFIF: pure red is (76, 85, 255) (255 after clamping 255.5).
        assert_eq!(encode([1.0, 0.0, 0.0], YuvRange::Full), [76, 85, 255]);
        assert_eq!(m.convert(128, 128, 128), [128, 128, 128]);
        assert_eq!(m.convert(0, 128, 128), [0, 0, 0]);
        assert_eq!(m.convert(255, 128, 128), [255, 255, 255]);
    }

    #[test]
    fn decode_inverts_encode_within_quantisation() {
        // Every 17th level of each channel: the round trip's error is the 8-bit quantisation of
        // the chroma (one code of Cb is 1.772/255 of blue), so at most 2 codes.
        for range in [YuvRange::Full, YuvRange::Limited] {
            let m = YuvToRgb::bt601(range);
            let mut worst = 0;
            for r in (0..=255).step_by(17) {
                for g in (0..=255).step_by(17) {
                    for b in (0..=255).step_by(17) {
                        let rgb = [r, g, b].map(|c: i32| f64::from(c) / 255.0);
                        let [y, u, v] = encode(rgb, range);
                        let back = m.convert(y, u, v);
                        for (k, c) in [r, g, b].into_iter().enumerate() {
                            worst = worst.max((i32::from(back[k]) - c).abs());
                        }
                    }
                }
            }
            assert!(
                worst <= 2,
                "{range:?}: worst round-trip error {worst} codes"
            );
        }
    }

    #[test]
    fn gpu_columns_reproduce_the_matrix() {
        let m = YuvToRgb::bt601(YuvRange::Limited);
        let c = m.to_gpu_columns();
        let s = [0.3f32, 0.6, 0.2];
        for (r, (row, off)) in m.matrix.iter().zip(m.offset).enumerate() {
            let gpu = c[0][r] * s[0] + c[1][r] * s[1] + c[2][r] * s[2] + c[3][r];
            let cpu = row[0] * 0.3 + row[1] * 0.6 + row[2] * 0.2 + off;
            assert!((f64::from(gpu) - cpu).abs() < 1e-6);
        }
    }

    #[test]
    fn repack_and_interleave_follow_the_strides() {
        // 3×2 luma with row stride 5 → rows 8 apart.
        let y = [1, 2, 3, 0, 0, 4, 5, 6];
        let out = repack_plane(&y, 5, 3, 2, 8).unwrap();
        assert_eq!(out, vec![1, 2, 3, 0, 0, 0, 0, 0, 4, 5, 6, 0, 0, 0, 0, 0]);
        assert_eq!(repack_plane(&y[..7], 5, 3, 2, 8), None);
        // NV21: V U V U in one buffer; u starts one byte after v, pixel stride 2, row stride 4.
        let vu = [10, 20, 11, 21, 12, 22, 13, 23];
        let out = interleave_chroma(&vu[1..], &vu, 4, 2, 2, 2, 4).unwrap();
        assert_eq!(out, vec![20, 10, 21, 11, 22, 12, 23, 13]);
        assert_eq!(interleave_chroma(&vu[1..3], &vu, 4, 2, 2, 2, 4), None);
    }
}
