//! A recorded frame's image file, read for a feed: refused when it is missing, a directory,
//! larger than [`MAX_FRAME_FILE_BYTES`], cut short, or undecodable.
//!
//! Why "cut short" needs its own check: JPEG decoders fill a truncated scan with grey and
//! return an image (the image crate's does), so a copy that stopped half-way played as a frame
//! with its lower part missing. A complete JPEG ends its last scan with the end-of-image marker
//! (FF D9 after the last start-of-scan FF DA; bytes after it are allowed, as some cameras append
//! data); a complete PNG ends with its IEND chunk.

use std::path::Path;

use image::{DynamicImage, ImageFormat};

/// Largest frame image read, bytes: a 4096 × 4096 RGBA PNG stored without compression.
pub const MAX_FRAME_FILE_BYTES: u64 = 64 << 20;

/// The PNG's last chunk: length 0, `IEND`, its CRC.
const PNG_IEND: [u8; 12] = [0, 0, 0, 0, b'I', b'E', b'N', b'D', 0xAE, 0x42, 0x60, 0x82];

/// Why `bytes` (of `format`) are cut short, if they are.
fn truncated(bytes: &[u8], format: ImageFormat) -> Option<&'static str> {
    let last_marker = |m: u8| bytes.windows(2).rposition(|w| w == [0xFF, m]);
    match format {
        ImageFormat::Jpeg => match (last_marker(0xDA), last_marker(0xD9)) {
            (Some(sos), Some(eoi)) if eoi > sos => None,
            (None, _) => Some("the JPEG has no image data (no start-of-scan marker)"),
            _ => Some("the JPEG is cut short: its last scan has no end-of-image marker"),
        },
        ImageFormat::Png if !bytes.ends_with(&PNG_IEND) => {
            Some("the PNG is cut short: it does not end with its IEND chunk")
        }
        _ => None,
    }
}

/// `path` as a kind of file, for "frame image X is a directory" and the like; `None` for a
/// regular file.
pub(crate) fn not_a_file(path: &Path) -> Option<&'static str> {
    match std::fs::metadata(path) {
        Err(_) => Some("does not exist"),
        Ok(m) if m.is_dir() => Some("is a directory, not an image file"),
        Ok(m) if !m.is_file() => Some("is not a regular file"),
        Ok(_) => None,
    }
}

/// Reads and decodes a frame image; the error is the reason, without the file's name.
pub(crate) fn decode(path: &Path) -> Result<DynamicImage, String> {
    if let Some(why) = not_a_file(path) {
        return Err(why.to_string());
    }
    let bytes = input::read_capped(path, MAX_FRAME_FILE_BYTES, "a frame image", |_| None)
        .map_err(|e| e.0)?;
    let format = image::guess_format(&bytes).map_err(|e| format!("not an image: {e}"))?;
    if let Some(why) = truncated(&bytes, format) {
        return Err(why.to_string());
    }
    image::load_from_memory_with_format(&bytes, format).map_err(|e| format!("cannot decode: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encoded(format: ImageFormat) -> Vec<u8> {
        let img = DynamicImage::ImageRgb8(image::RgbImage::from_fn(32, 24, |x, y| {
            image::Rgb([(x * 8) as u8, (y * 10) as u8, 77])
        }));
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, format).unwrap();
        out.into_inner()
    }

    #[test]
    fn complete_files_pass_and_cut_ones_do_not() {
        for format in [ImageFormat::Jpeg, ImageFormat::Png] {
            let full = encoded(format);
            assert_eq!(truncated(&full, format), None, "{format:?}");
            // Trailing bytes after a JPEG's end-of-image marker are allowed.
            if format == ImageFormat::Jpeg {
                let mut padded = full.clone();
                padded.extend_from_slice(b"trailer");
                assert_eq!(truncated(&padded, format), None);
            }
            for keep in [full.len() - 1, full.len() * 3 / 4, full.len() / 2] {
                assert!(
                    truncated(&full[..keep], format).is_some(),
                    "{format:?} {keep}"
                );
            }
        }
    }
}
