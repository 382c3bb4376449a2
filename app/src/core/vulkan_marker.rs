//! The Vulkan crash marker (issue 26): some PowerVR Rogue Vulkan drivers (the OPPO A54's
//! GE8320 class) have crashed inside `vkQueueSubmit` in other wgpu apps. A crash kills the
//! process, so no fallback can run in that launch; the next one must know. A file in the app's
//! storage is written before the first frame is submitted on Vulkan and removed after
//! [`GOOD_FRAMES`] frames were presented; a launch that finds it (the last one stopped on its
//! first frames) goes straight to OpenGL ES, logs it and says so on the banner.
//!
//! The marker holds the build's version: a marker left by another build is dropped (a new
//! build may bring a fixed wgpu), so an update tries Vulkan again. Once a launch fell back, the
//! marker stays and every launch of this build draws with OpenGL ES (clearing the app's storage
//! tries Vulkan again).

use std::path::{Path, PathBuf};

/// The marker's file name in the app's storage.
pub const MARKER_FILE: &str = "vulkan-first-frames";

/// Frames presented on Vulkan after which the driver is trusted (half a second at 60 fps;
/// the reported crashes came in the first submit).
pub const GOOD_FRAMES: u64 = 30;

/// What the marker says of this build.
fn this_build() -> String {
    format!("regatta {}\n", env!("CARGO_PKG_VERSION"))
}

/// The marker in one app storage folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VulkanMarker {
    path: PathBuf,
}

impl VulkanMarker {
    pub fn in_dir(dir: &Path) -> Self {
        Self {
            path: dir.join(MARKER_FILE),
        }
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether a launch of this build stopped before its first [`GOOD_FRAMES`] frames on
    /// Vulkan. A marker of another build is removed and does not count.
    pub fn left_by_a_crash(&self) -> bool {
        match std::fs::read_to_string(&self.path) {
            Ok(text) if text == this_build() => true,
            Ok(_) => {
                self.clear();
                false
            }
            Err(_) => false,
        }
    }

    /// Written before the first submit on Vulkan (a failure to write is logged: the launch goes
    /// on, unprotected).
    pub fn arm(&self) {
        if let Some(dir) = self.path.parent() {
            let _ = std::fs::create_dir_all(dir);
        }
        if let Err(e) = std::fs::write(&self.path, this_build()) {
            log::warn!(
                "regatta: cannot write the Vulkan marker {}: {e}",
                input::show_path(&self.path)
            );
        }
    }

    /// Removed once the driver drew [`GOOD_FRAMES`] frames.
    pub fn clear(&self) {
        match std::fs::remove_file(&self.path) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => log::warn!(
                "regatta: cannot remove the Vulkan marker {}: {e}",
                input::show_path(&self.path)
            ),
        }
    }
}

/// The banner's sentence when a launch found the marker.
pub const FELL_BACK_NOTE: &str =
    "The last start stopped while drawing with Vulkan; Regatta draws with OpenGL ES on this phone.";

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("regatta-marker-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn a_marker_left_armed_is_found_and_a_cleared_one_is_not() {
        let d = dir("armed");
        let m = VulkanMarker::in_dir(&d);
        assert!(!m.left_by_a_crash(), "a fresh install");
        m.arm();
        // The process dies here: the next launch sees it.
        assert!(VulkanMarker::in_dir(&d).left_by_a_crash());
        m.clear();
        assert!(!VulkanMarker::in_dir(&d).left_by_a_crash());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_marker_of_another_build_is_dropped() {
        let d = dir("other");
        std::fs::create_dir_all(&d).unwrap();
        let m = VulkanMarker::in_dir(&d);
        std::fs::write(m.path(), "regatta 0.0.0-old\n").unwrap();
        assert!(!m.left_by_a_crash());
        assert!(!m.path().exists(), "removed, so that Vulkan is tried again");
        let _ = std::fs::remove_dir_all(&d);
    }
}
