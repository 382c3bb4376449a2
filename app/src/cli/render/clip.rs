//! `regatta render --from T0 --to T1 --out clip.gif`: the race over a span of race time as a
//! GIF, drawn and written by the scene set-up's clip (`crate::setup::clip`, the same frames the
//! app's "Share clip" writes).
//!
//! MP4 is refused with one line: no maintained pure-Rust H.264 encoder fits the build. openh264
//! (0.9) binds Cisco's C++ encoder, compiled from source by its -sys crate (or a binary fetched at
//! run time); rav1e (0.8) writes AV1, not H.264, and is a large build of its own; less-avc (0.1)
//! stores every macroblock uncompressed (I_PCM), so its files are as large as the raw frames.
//! So the clip is a GIF, which share sheets and chat apps take.

use std::path::Path;

use super::RenderArgs;
use crate::error::{AppError, AppResult};
use crate::setup::RaceSetup;
use crate::setup::clip::{ClipLook, ClipTimes, DEFAULT_FPS, write_gif};
use crate::world::FAR_M;

/// The file kind a clip's `--out` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClipFormat {
    Gif,
    Mp4,
}

/// The clip format `path`'s extension names, if any.
pub fn clip_format(path: &Path) -> Option<ClipFormat> {
    let ext = path.extension()?.to_string_lossy().to_ascii_lowercase();
    match ext.as_str() {
        "gif" => Some(ClipFormat::Gif),
        "mp4" => Some(ClipFormat::Mp4),
        _ => None,
    }
}

/// `render` with a `.gif` or `.mp4` `--out`.
pub fn run(a: &RenderArgs, format: ClipFormat) -> AppResult {
    if format == ClipFormat::Mp4 {
        return Err(AppError::new(format!(
            "--out {}: MP4 is not available in this build (no maintained pure-Rust H.264 encoder); write a .gif instead",
            input::show_path(&a.out)
        )));
    }
    let refused = [
        (a.t.is_some(), "--t (a clip runs --from … --to)"),
        (a.replay.is_some(), "--replay"),
        (a.effects.is_some(), "--effects"),
        (a.tier.is_some(), "--tier"),
        (a.report.is_some(), "--report"),
        (a.scene != super::SceneKind::Race, "--scene pool"),
    ];
    if let Some((_, flag)) = refused.iter().find(|(given, _)| *given) {
        return Err(AppError::new(format!(
            "{flag} has no meaning for a clip (--out .gif): clips draw the race scene with its overlays"
        )));
    }
    let (Some(from), Some(to)) = (a.from, a.to) else {
        return Err(AppError::new(
            "--out .gif writes a clip: give --from SECONDS and --to SECONDS",
        ));
    };
    let size = super::parse_size(&a.size)?;
    super::check_error_px(a.error_px)?;
    let overlays = super::overlay_settings(a)?;
    let camera = a
        .camera
        .as_deref()
        .map(|c| super::parse_camera(c, FAR_M))
        .transpose()?;
    let world = RaceSetup::load_world(&a.race, a.sea.as_ref())?;
    let times = ClipTimes::new(
        from,
        to,
        a.fps.unwrap_or(DEFAULT_FPS),
        world.race.time_span(),
    )?;
    let look = ClipLook {
        size,
        camera,
        debrief: crate::scene_overlay::manoeuvres::debrief_if_shown(&world.race, &overlays),
        overlays,
        wakes: !a.no_wakes,
        error_px: a.error_px,
    };
    let progress_every = times.count.div_ceil(10).max(1);
    write_gif(&world, &times, &look, &a.out, &mut |done, total, t| {
        if done % progress_every == 0 || done == total {
            eprintln!("regatta render: frame {done}/{total} (t = {t:.2} s)");
        }
    })?;
    let summary = serde_json::json!({
        "out": a.out.display().to_string(),
        "format": "gif",
        "frames": times.count,
        "fps": times.fps,
        "from": times.from,
        "to": times.time(times.count - 1),
        "size": size,
    });
    crate::terminal::print_stdout("the clip summary", &summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_formats_follow_the_extension() {
        assert_eq!(clip_format(Path::new("a.GIF")), Some(ClipFormat::Gif));
        assert_eq!(clip_format(Path::new("a.mp4")), Some(ClipFormat::Mp4));
        assert_eq!(clip_format(Path::new("a.png")), None);
    }
}
