//! Output files written whole or not at all (`regatta render --out`, the bench's reports, the
//! window's screenshots, shared clips).
//!
//! `render --out x.jpg` used to leave a 0-byte file: the file was created, then the encoder
//! refused RGBA for JPEG. Every output goes to a temporary file beside the target and is renamed
//! over it only when complete (a rename within one folder is atomic); on any error the temporary
//! file is removed and the target is untouched. The image format follows the extension, checked
//! before anything is drawn ([`ImageOut::new`]).

use std::path::{Path, PathBuf};

use image::ImageFormat;

use crate::error::{AppError, AppResult};

/// The temporary file beside `path` (same folder, so the rename cannot cross file systems);
/// its name keeps the extension and is hidden.
fn temp_beside(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.partial", std::process::id()))
}

/// Writes `path` through `write` (which gets the temporary path), then renames it into place;
/// on error nothing is left behind.
pub fn write_atomically(path: &Path, write: impl FnOnce(&Path) -> Result<(), String>) -> AppResult {
    let tmp = temp_beside(path);
    let done = write(&tmp).and_then(|()| std::fs::rename(&tmp, path).map_err(|e| e.to_string()));
    done.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        AppError::new(format!("could not write {}: {e}", input::show_path(path)))
    })
}

/// Writes text to `path` atomically.
pub fn write_text(path: &Path, text: &str) -> AppResult {
    write_atomically(path, |tmp| {
        std::fs::write(tmp, text).map_err(|e| e.to_string())
    })
}

/// An image file to write, its format chosen by its extension (PNG or JPEG).
#[derive(Debug, Clone)]
pub struct ImageOut {
    pub path: PathBuf,
    format: ImageFormat,
}

impl ImageOut {
    /// `flag` names the option in the message when the extension is not .png, .jpg or .jpeg.
    pub fn new(path: &Path, flag: &str) -> AppResult<ImageOut> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let format = match ext.as_deref() {
            Some("png") => ImageFormat::Png,
            Some("jpg" | "jpeg") => ImageFormat::Jpeg,
            _ => {
                return Err(AppError::new(format!(
                    "{flag} {} must name a .png or .jpg file",
                    input::quote(&path.display().to_string())
                )));
            }
        };
        Ok(ImageOut {
            path: path.to_path_buf(),
            format,
        })
    }

    /// Writes `img` atomically (JPEG has no alpha: its RGB is written).
    pub fn save(&self, img: &image::RgbaImage) -> AppResult {
        let image = image::DynamicImage::ImageRgba8(img.clone());
        let image = match self.format {
            ImageFormat::Jpeg => image::DynamicImage::ImageRgb8(image.to_rgb8()),
            _ => image,
        };
        write_atomically(&self.path, |tmp| {
            image
                .save_with_format(tmp, self.format)
                .map_err(|e| e.to_string())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_neither_target_nor_temporary_file() {
        let dir = std::env::temp_dir().join(format!("regatta-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("out.png");
        let e = write_atomically(&target, |tmp| {
            std::fs::write(tmp, b"half").unwrap();
            Err("the encoder failed".into())
        })
        .unwrap_err();
        assert!(e.0.ends_with("out.png: the encoder failed"), "{e}");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        write_text(&target, "whole").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "whole");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn image_formats_follow_the_extension() {
        assert!(ImageOut::new(Path::new("a.PNG"), "--out").is_ok());
        assert!(ImageOut::new(Path::new("a.jpeg"), "--out").is_ok());
        let e = ImageOut::new(Path::new("a.bmp"), "--out").unwrap_err();
        assert_eq!(e.0, "--out \"a.bmp\" must name a .png or .jpg file");
    }
}
