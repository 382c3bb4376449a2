//! The smoke test's hooks, the same for every scene of the window: `REGATTA_EXIT_AFTER_FRAMES=N`
//! exits after N drawn frames, and `REGATTA_SCREENSHOT=FILE.png` then writes what the window
//! showed (surface textures cannot be read back, so the scene is drawn once more offscreen).

use std::path::PathBuf;

/// Counts drawn frames against `REGATTA_EXIT_AFTER_FRAMES`.
#[derive(Debug, Default)]
pub struct ExitAfter {
    frames: u64,
    limit: Option<u64>,
}

impl ExitAfter {
    pub fn from_env() -> ExitAfter {
        ExitAfter {
            frames: 0,
            limit: std::env::var("REGATTA_EXIT_AFTER_FRAMES")
                .ok()
                .and_then(|v| v.parse().ok()),
        }
    }

    /// Counts a drawn frame; true when the app should exit.
    pub fn frame_done(&mut self) -> bool {
        self.frames += 1;
        self.limit.is_some_and(|n| self.frames >= n)
    }
}

/// `REGATTA_SCREENSHOT`, when set.
pub fn screenshot_path() -> Option<PathBuf> {
    std::env::var_os("REGATTA_SCREENSHOT").map(PathBuf::from)
}

/// Writes `img`, read back from a texture of the surface's `format` (BGRA swapped to RGBA), as
/// the PNG `path`, whole or not at all. Errors are one sentence naming the file.
pub fn write_screenshot(
    mut img: image::RgbaImage,
    format: wgpu::TextureFormat,
    path: &std::path::Path,
) -> Result<(), String> {
    if matches!(
        format,
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
    ) {
        for p in img.pixels_mut() {
            p.0.swap(0, 2);
        }
    }
    crate::cli::output::ImageOut::new(path, "REGATTA_SCREENSHOT")
        .and_then(|out| out.save(&img))
        .map_err(|e| format!("the screenshot could not be written: {e}"))
}
