//! The camera feed: recorded or synthetic camera frames over time, and the race on the feed's
//! table ([`FeedView`]: the desktop app's `regatta run --replay`, `regatta render --replay`, the
//! tests that draw the table). The phone's simulated ARCore (`phone_sim`) plays the same
//! [`CameraFeed`].
//!
//! It never knows a platform (winit, android-activity) or the command line: the app, the shells
//! and the `render` command reach the feed here, and none of them borrows another's.

mod table_frame;
mod view;

pub use table_frame::TableFrame;
pub use view::{FeedView, to_render};

use std::path::Path;

use ar::{CameraFrame, ReplayFeed, SynthConfig};

use crate::error::{AppError, AppResult};

/// The `--replay` value that chooses the built-in synthetic feed.
pub const SYNTH: &str = "synth";

/// Where a feed's frames come from: a replay folder (or TUM RGB-D folder), or the synthetic
/// table of `ar::synth`, rendered frame by frame (no files needed) and kept: after the first
/// loop, frames cost nothing.
pub enum CameraFeed {
    Synth(SynthConfig, Vec<Option<CameraFrame>>),
    Replay(ReplayFeed),
}

impl CameraFeed {
    /// The synthetic table at `cfg`.
    pub fn synth(cfg: SynthConfig) -> CameraFeed {
        CameraFeed::Synth(cfg, vec![None; cfg.frames.max(1)])
    }

    /// A replay or TUM folder, or the synthetic feed at its default size for [`SYNTH`].
    pub fn open(dir: &Path) -> AppResult<CameraFeed> {
        if dir.as_os_str() == SYNTH {
            return Ok(CameraFeed::synth(SynthConfig::default()));
        }
        let feed = ReplayFeed::open(dir).map_err(|e| AppError::new(e.to_string()))?;
        log::info!(
            "replay {}: {} frames, {:.1} s",
            dir.display(),
            feed.len(),
            feed.duration()
        );
        Ok(CameraFeed::Replay(feed))
    }

    /// The simulated phone camera's feed: the replay folder `replay`, or without one a small
    /// synthetic table (320 × 240, 32 frames).
    pub fn for_phone(replay: Option<&Path>) -> AppResult<CameraFeed> {
        Ok(match replay {
            Some(dir) => {
                CameraFeed::Replay(ReplayFeed::open(dir).map_err(|e| AppError::new(e.to_string()))?)
            }
            None => CameraFeed::synth(SynthConfig {
                frames: 32,
                width: 320,
                height: 240,
                supersample: 1,
                ..SynthConfig::default()
            }),
        })
    }

    /// The frame shown at feed time `t`, seconds.
    pub fn index_at(&self, t: f64) -> usize {
        match self {
            CameraFeed::Synth(c, _) => c.index_at(t),
            CameraFeed::Replay(f) => f.index_at(t),
        }
    }

    /// Frame `i` (below [`CameraFeed::len`]).
    pub fn frame(&mut self, i: usize) -> Result<CameraFrame, ar::ArError> {
        match self {
            CameraFeed::Synth(c, cache) => Ok(cache[i].get_or_insert_with(|| c.frame(i)).clone()),
            CameraFeed::Replay(f) => f.frame(i),
        }
    }

    /// How many frames the feed has.
    pub fn len(&self) -> usize {
        match self {
            CameraFeed::Replay(f) => f.len(),
            CameraFeed::Synth(c, _) => c.frames,
        }
    }

    /// Whether the feed has no frames (a feed that opened always has some).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
