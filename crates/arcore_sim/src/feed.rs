//! What the simulated camera sees: a replay folder (`ar::replay`) or, without one, the
//! synthetic table feed (`ar::synth`), and each frame's image as a phone's camera hands it
//! over: YUV 4:2:0 with padded rows and interleaved chroma.

use std::path::Path;

use ar::{CameraFrame, DetectedPlane, FrameImage, Intrinsics, ReplayFeed, SynthConfig};
use camera_image::{Yuv420, YuvRange};

/// Where the frames come from.
pub enum Feed {
    Synth(SynthConfig),
    Replay(ReplayFeed),
}

/// The synthetic feed the simulator plays without a replay: 640 × 480, so that the luma
/// rows are padded to 704 bytes as on many phones.
pub fn default_synth() -> SynthConfig {
    SynthConfig {
        frames: 16,
        width: 640,
        height: 480,
        supersample: 1,
        ..SynthConfig::default()
    }
}

impl Feed {
    pub fn open(dir: &Path) -> Result<Feed, String> {
        let feed = ReplayFeed::open(dir).map_err(|e| e.to_string())?;
        if feed.is_empty() {
            return Err(format!("replay {} has no frames", dir.display()));
        }
        Ok(Feed::Replay(feed))
    }

    /// Frames in one loop (at least one: an empty replay does not open).
    pub fn frames(&self) -> usize {
        match self {
            Feed::Synth(c) => c.frames.max(1),
            Feed::Replay(r) => r.len(),
        }
    }

    /// Seconds from one loop's start to the next.
    pub fn period(&self) -> f64 {
        match self {
            Feed::Synth(c) => c.period(),
            Feed::Replay(r) => r.duration() + 1.0 / r.frame_rate.max(1e-3),
        }
    }

    /// The intrinsics of a CPU image of `image` pixels: the synthetic camera keeps its
    /// horizontal field of view at every size (a 16:9 image is the 4:3 sensor cropped top and
    /// bottom, as on phones); a replay has its own size only.
    pub fn intrinsics(&self, image: [u32; 2]) -> Intrinsics {
        match self {
            Feed::Synth(c) => c.at_size(image).intrinsics(),
            Feed::Replay(r) => r.intrinsics,
        }
    }

    /// The size of a replay's images (`None` for the synthetic feed, drawn at any size).
    pub fn recorded_size(&self) -> Option<[u32; 2]> {
        match self {
            Feed::Synth(_) => None,
            Feed::Replay(r) => Some([r.intrinsics.width, r.intrinsics.height]),
        }
    }

    /// The detected planes (the table), when the feed has them.
    pub fn planes(&self) -> Vec<DetectedPlane> {
        match self {
            Feed::Synth(c) => vec![c.table().to_detected_plane()],
            Feed::Replay(r) => r.planes.clone(),
        }
    }

    /// Frame `i` (RGBA image, pose, time), the synthetic one drawn at `image` pixels (a
    /// replay's at its own size).
    pub fn frame(&self, i: usize, image: [u32; 2]) -> Result<CameraFrame, String> {
        match self {
            Feed::Synth(c) => Ok(c.at_size(image).frame(i)),
            Feed::Replay(r) => r.frame(i).map_err(|e| e.to_string()),
        }
    }
}

/// The synthetic camera at another image size, field of view kept.
trait AtSize {
    fn at_size(&self, image: [u32; 2]) -> SynthConfig;
}

impl AtSize for SynthConfig {
    fn at_size(&self, [width, height]: [u32; 2]) -> SynthConfig {
        SynthConfig {
            width: width.max(2),
            height: height.max(2),
            ..*self
        }
    }
}

/// A camera image laid out as `AImage` (`AIMAGE_FORMAT_YUV_420_888`) gives it on phones: luma
/// rows padded to [`row_stride`], chroma as one NV21 buffer (V, U, V, U, …) with rows as long
/// as the luma's, pixel stride 2; plane 1 (U) starts one byte after plane 2 (V). The last row
/// of each plane stops at its last sample (not padded), as on devices.
#[derive(Clone)]
pub struct PhoneImage {
    pub width: u32,
    pub height: u32,
    pub row_stride: u32,
    pub y: Vec<u8>,
    /// V at even offsets, U at odd ones.
    pub vu: Vec<u8>,
}

/// Bytes from one row to the next for an image `width` pixels wide: the width rounded up to
/// 64 plus 64 (640 → 704), a padding seen on phone camera HALs.
pub fn row_stride(width: u32) -> u32 {
    width.div_ceil(64) * 64 + 64
}

impl PhoneImage {
    /// The image's YUV samples (BT.601 full range, `camera_image`'s encoder), strided.
    pub fn from_frame(image: &FrameImage) -> Result<PhoneImage, String> {
        let yuv =
            Yuv420::from_rgba(&image.to_rgba_image(), YuvRange::Full).map_err(|e| e.to_string())?;
        let (w, h) = (yuv.width(), yuv.height());
        let [cw, ch] = Yuv420::chroma_size(w, h).map(|v| v as usize);
        let stride = row_stride(w) as usize;
        let (wu, hu) = (w as usize, h as usize);
        let mut y = vec![0u8; (hu - 1) * stride + wu];
        for j in 0..hu {
            y[j * stride..j * stride + wu].copy_from_slice(&yuv.y()[j * wu..(j + 1) * wu]);
        }
        let mut vu = vec![0u8; (ch - 1) * stride + 2 * cw];
        for j in 0..ch {
            for i in 0..cw {
                let (u, v) = (yuv.uv()[2 * (j * cw + i)], yuv.uv()[2 * (j * cw + i) + 1]);
                vu[j * stride + 2 * i] = v;
                vu[j * stride + 2 * i + 1] = u;
            }
        }
        Ok(PhoneImage {
            width: w,
            height: h,
            row_stride: stride as u32,
            y,
            vu,
        })
    }

    /// Plane `i` (0 = Y, 1 = U, 2 = V): its bytes, row stride and pixel stride.
    pub fn plane(&self, i: i32) -> Option<(&[u8], u32, u32)> {
        match i {
            0 => Some((&self.y, self.row_stride, 1)),
            // U: from the first U sample to the buffer's end (one byte shorter than V's).
            1 => Some((&self.vu[1..], self.row_stride, 2)),
            // V: the buffer without its last byte (the final U), as NV21 AImages give it.
            2 => Some((&self.vu[..self.vu.len() - 1], self.row_stride, 2)),
            _ => None,
        }
    }
}
