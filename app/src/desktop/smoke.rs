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

/// `REGATTA_EXIT_AFTER_FRAMES`, checked before a window opens: a whole number of frames from 1,
/// or why not (`-1`, `abc`, `1e30` and an empty value were ignored, and the window never
/// closed, as a smoke test waited).
pub fn check_exit_after_env() -> Result<(), String> {
    match std::env::var("REGATTA_EXIT_AFTER_FRAMES") {
        Err(std::env::VarError::NotPresent) => Ok(()),
        Err(std::env::VarError::NotUnicode(_)) => Err(
            "REGATTA_EXIT_AFTER_FRAMES is not UTF-8 text; give a whole number of frames from 1"
                .into(),
        ),
        Ok(v) => match v.trim().parse::<u64>() {
            Ok(n) if n >= 1 => Ok(()),
            _ => Err(format!(
                "REGATTA_EXIT_AFTER_FRAMES is {}; give a whole number of frames from 1 (or unset it)",
                input::quote(&v)
            )),
        },
    }
}

/// A window-system error for a person: winit's OS errors name the source file of the library
/// that raised them ("os error at /root/.cargo/registry/…/x11/mod.rs:123: …"); the location
/// is dropped, the error kept.
pub fn window_error(e: &dyn std::fmt::Display) -> String {
    let msg = e.to_string();
    if let Some(at) = msg.find("os error at ") {
        let rest = &msg[at + "os error at ".len()..];
        // The location ends at ":LINE: " (a path may hold colons, the line is digits).
        let mut i = 0;
        while let Some(k) = rest[i..].find(": ") {
            let before = &rest[..i + k];
            if before
                .rsplit(':')
                .next()
                .is_some_and(|l| !l.is_empty() && l.bytes().all(|b| b.is_ascii_digit()))
            {
                return format!("{}{}", &msg[..at], &rest[i + k + 2..]);
            }
            i += k + 2;
        }
    }
    msg
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
fn screenshot_path() -> Option<PathBuf> {
    std::env::var_os("REGATTA_SCREENSHOT").map(PathBuf::from)
}

/// With `REGATTA_SCREENSHOT`: surface textures cannot be read back, so `app` draws the same
/// frame (no time passes) once more into an offscreen window of `size` and the current
/// window's configuration, and that is written. Both windows (`regatta`, `run --phone`) save
/// theirs here.
pub fn save_screenshot(app: &mut crate::core::app::App, size: [u32; 2]) -> Result<(), String> {
    use crate::core::app::AppEvent;
    let Some(path) = screenshot_path() else {
        return Ok(());
    };
    app.on(AppEvent::WindowDestroyed);
    app.on(AppEvent::WindowCreated {
        surface: None,
        size,
    });
    app.frame(0.0);
    let format = app
        .window_config()
        .map_or(render::OFFSCREEN_FORMAT, |c| c.format);
    let img = app.screenshot().ok_or("no frame to save")??;
    write_screenshot(img, format, &path)
}

/// Writes `img`, read back from a texture of the surface's `format` (BGRA swapped to RGBA), as
/// the PNG `path`, whole or not at all. Errors are one sentence naming the file.
fn write_screenshot(
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
    crate::setup::output::ImageOut::new(path, "REGATTA_SCREENSHOT")
        .and_then(|out| out.save(&img))
        .map_err(|e| format!("the screenshot could not be written: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_winit_os_error_loses_its_source_location() {
        assert_eq!(
            window_error(
                &"os error at /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/winit-0.30.12/src/platform_impl/linux/mod.rs:764: neither WAYLAND_DISPLAY nor DISPLAY is set"
            ),
            "neither WAYLAND_DISPLAY nor DISPLAY is set"
        );
        assert_eq!(window_error(&"no display"), "no display");
    }
}
