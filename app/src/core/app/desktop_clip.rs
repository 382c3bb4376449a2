//! The desktop's "Share clip" button: the last [`ClipRequest::DESKTOP`] seconds of race time
//! before the playhead written as a GIF (`setup::clip::write_gif`, the frames `regatta
//! render --from --to` draws) into `clips/` under the folder the app runs in, on a worker thread
//! with its own headless GPU device, so the window keeps drawing; the button shows the
//! progress, then the file's path or the one-line error.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use crate::setup::clip::{ClipLook, ClipTimes, write_gif};
use crate::world::RaceWorld;

/// What a clip covers and how it is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipRequest {
    /// Race time before the playhead, seconds.
    pub seconds: f64,
    /// Frames per second of race time.
    pub fps: f64,
    /// Frame size, pixels.
    pub size: [u32; 2],
}

impl ClipRequest {
    /// The button's clip: 20 s at 15 fps, 640x360 (301 frames; about 3 minutes on lavapipe's
    /// 2 CPU cores).
    pub const DESKTOP: ClipRequest = ClipRequest {
        seconds: 20.0,
        fps: 15.0,
        size: [640, 360],
    };
}

/// Where the worker is.
#[derive(Debug, Clone, PartialEq)]
pub enum ClipStatus {
    Idle,
    Rendering { done: usize, total: usize },
    Written(PathBuf),
    Failed(String),
}

/// The button's state and its worker.
#[derive(Debug)]
pub struct ShareClip {
    status: Arc<Mutex<ClipStatus>>,
    worker: Option<std::thread::JoinHandle<()>>,
}

impl Default for ShareClip {
    fn default() -> Self {
        ShareClip {
            status: Arc::new(Mutex::new(ClipStatus::Idle)),
            worker: None,
        }
    }
}

impl ShareClip {
    pub fn status(&self) -> ClipStatus {
        self.status
            .lock()
            .map(|s| s.clone())
            .unwrap_or(ClipStatus::Idle)
    }

    /// Starts writing the clip of `request` ending at `playhead` into `folder/clips/`, with
    /// the race's `debrief` (the trails' manoeuvre marks) where the window has it; the path it
    /// will have, or why not (a clip already being written, a span the race lacks).
    pub fn start(
        &mut self,
        (world, debrief): (&RaceWorld, Option<&race::Debrief>),
        playhead: f64,
        folder: &Path,
        request: ClipRequest,
    ) -> Result<PathBuf, String> {
        if matches!(self.status(), ClipStatus::Rendering { .. }) {
            return Err("a clip is already being written".into());
        }
        let times = ClipTimes::before_playhead(
            playhead,
            request.seconds,
            request.fps,
            world.race.time_span(),
        )
        .map_err(|e| e.0)?;
        let to = times.time(times.count - 1);
        let dir = folder.join("clips");
        let out = dir.join(format!("regatta-{:.0}-{:.0}s.gif", times.from, to));
        let look = ClipLook {
            size: request.size,
            camera: None,
            overlays: Default::default(),
            debrief: debrief.cloned(),
            wakes: true,
            error_px: render::renderer::DEFAULT_ERROR_PX,
        };
        *self.status.lock().map_err(|e| e.to_string())? = ClipStatus::Rendering {
            done: 0,
            total: times.count,
        };
        let (world, status, path) = (world.clone(), self.status.clone(), out.clone());
        self.worker = Some(std::thread::spawn(move || {
            let set = |s: ClipStatus| {
                if let Ok(mut g) = status.lock() {
                    *g = s;
                }
            };
            let written = std::fs::create_dir_all(&dir)
                .map_err(|e| format!("could not make {}: {e}", input::show_path(&dir)))
                .and_then(|()| {
                    write_gif(&world, &times, &look, &path, &mut |done, total, _| {
                        set(ClipStatus::Rendering { done, total })
                    })
                    .map_err(|e| e.0)
                });
            set(match written {
                Ok(()) => ClipStatus::Written(path),
                Err(e) => ClipStatus::Failed(e),
            });
        }));
        Ok(out)
    }

    /// Shows `why` a clip could not start.
    pub fn set_failed(&self, why: String) {
        if let Ok(mut g) = self.status.lock() {
            *g = ClipStatus::Failed(why);
        }
    }

    /// Waits for the worker (tests; the window never waits).
    pub fn wait(&mut self) {
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }

    /// The button and its line: true when it was pressed this frame.
    pub fn ui(&self, ui: &mut egui::Ui) -> bool {
        let status = self.status();
        let busy = matches!(status, ClipStatus::Rendering { .. });
        let pressed = ui
            .add_enabled(!busy, egui::Button::new("Share clip"))
            .on_hover_text("The last 20 s of race time before the playhead, as a GIF")
            .clicked();
        match status {
            ClipStatus::Idle => {}
            ClipStatus::Rendering { done, total } => {
                ui.add(
                    egui::ProgressBar::new(done as f32 / total.max(1) as f32)
                        .text(format!("frame {done}/{total}")),
                );
            }
            ClipStatus::Written(p) => {
                ui.label(format!("written: {}", p.display()));
            }
            ClipStatus::Failed(e) => {
                ui.colored_label(egui::Color32::LIGHT_RED, input::one_line(&e));
            }
        }
        pressed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The worker writes the GIF the request asks for: read back with `gif`'s decoder, its
    /// frame count is seconds·fps + 1 and its size the request's.
    #[test]
    fn the_button_writes_the_seconds_before_the_playhead_as_a_gif() {
        if render::gpu::test_gpu().is_none() {
            return;
        }
        let race = crate::setup::inputs::load_race(&[]).unwrap();
        let sea = crate::setup::inputs::drawable_sea(crate::setup::inputs::load_sea(None).unwrap());
        let world = RaceWorld::new(race, sea);
        let folder = std::env::temp_dir().join(format!("regatta-share-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&folder);
        let mut clip = ShareClip::default();
        let request = ClipRequest {
            seconds: 1.0,
            fps: 2.0,
            size: [32, 24],
        };
        let out = clip.start((&world, None), 700.0, &folder, request).unwrap();
        clip.wait();
        assert_eq!(clip.status(), ClipStatus::Written(out.clone()));
        assert_eq!(out, folder.join("clips").join("regatta-699-700s.gif"));
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut d = options
            .read_info(std::fs::File::open(&out).unwrap())
            .unwrap();
        assert_eq!((d.width(), d.height()), (32, 24));
        let mut frames = 0;
        while d.read_next_frame().unwrap().is_some() {
            frames += 1;
        }
        assert_eq!(frames, 3);
        // A playhead at the start leaves no span: refused, nothing started.
        let e = clip
            .start((&world, None), -1e6, &folder, request)
            .unwrap_err();
        assert!(e.contains("--from"), "{e}");
        let _ = std::fs::remove_dir_all(&folder);
    }
}
