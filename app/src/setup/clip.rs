//! A race clip: frames over a span of race time, each drawn as `regatta render --t` draws a
//! still (overlays included), encoded as an animated GIF by the `gif` crate (image-rs's
//! maintained encoder; its NeuQuant palette per frame through `color_quant`). `regatta render
//! --from --to`, the desktop's and the phone's "Share clip" all write clips here.
//!
//! Frames: `n = floor((T1 − T0) · fps) + 1` frames at `T0 + i / fps`, i = 0 … n − 1 (both ends
//! included when the span is a whole number of frame steps). GIF delays are whole centiseconds:
//! frame i lasts `round(100 (i + 1) / fps) − round(100 i / fps)` cs, so no frame is off by
//! more than half a centisecond from 1/fps and the clip's length is exact to half a centisecond.

use std::io::Write;
use std::path::Path;

use super::{Profile, RaceSetup};
use crate::error::{AppError, AppResult};
use crate::world::RaceWorld;

/// Frame rate without `--fps`, frames per second.
pub const DEFAULT_FPS: f64 = 15.0;
/// Slowest `--fps`: one frame every ten seconds of race time.
pub const MIN_FPS: f64 = 0.1;
/// Fastest `--fps`: GIF delays are whole centiseconds and viewers draw delays under 2 cs as
/// 10 cs, so 50 frames per second is the fastest a GIF plays as asked.
pub const MAX_FPS: f64 = 50.0;
/// Most frames in one clip: 200 s at 15 fps, 60 s at 50 fps; a longer clip is a film, not a
/// message to share, and each frame is a full render.
pub const MAX_FRAMES: usize = 3000;
/// Pixels NeuQuant learns each palette from, at least: it learns from every `speed`-th pixel,
/// and `gif`'s default speed 10 on a 48x32 frame (153 samples) more than doubled the mean
/// palette error (6.3 against 2.8 per channel, 0–255, at speed 1, every pixel).
pub const QUANT_SAMPLES: u64 = 100_000;

/// NeuQuant's sampling factor for a frame of `size` (1 every pixel … 10, `gif`'s default):
/// the fastest that still learns from [`QUANT_SAMPLES`] pixels. At speed 1 a 1280x720 frame
/// took about 0.95 s to quantise on this 2-core machine, at 10 about 0.1 s (lavapipe's render
/// of the frame about 0.9 s), so large frames take the sparser sampling.
pub fn quant_speed(size: [u32; 2]) -> i32 {
    let pixels = u64::from(size[0]) * u64::from(size[1]);
    (pixels / QUANT_SAMPLES).clamp(1, 10) as i32
}

/// A clip's frame times: `count` frames from `from`, `1 / fps` seconds of race time apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipTimes {
    pub from: f64,
    pub fps: f64,
    pub count: usize,
}

impl ClipTimes {
    /// Checks the span against the race's `(start, end)` (seconds) and the frame cap.
    pub fn new(from: f64, to: f64, fps: f64, race_span: (f64, f64)) -> AppResult<ClipTimes> {
        let show = input::show_number;
        if !from.is_finite() || !to.is_finite() {
            return Err(AppError::new(format!(
                "--from {} --to {}: both must be finite seconds since the start",
                show(from),
                show(to)
            )));
        }
        if from >= to {
            return Err(AppError::new(format!(
                "--from {} is not before --to {}: a clip needs a span of race time",
                show(from),
                show(to)
            )));
        }
        let (start, end) = race_span;
        if from < start || to > end {
            let flag = if from < start { "--from" } else { "--to" };
            return Err(AppError::new(format!(
                "{flag}: {} to {} s lies outside the race, which runs {} to {} s",
                show(from),
                show(to),
                show(start),
                show(end)
            )));
        }
        if !(MIN_FPS..=MAX_FPS).contains(&fps) {
            return Err(AppError::new(format!(
                "--fps {} is outside {MIN_FPS} to {MAX_FPS} frames per second (GIF delays are whole centiseconds)",
                show(fps)
            )));
        }
        let steps = ((to - from) * fps + 1e-9).floor();
        if steps + 1.0 > MAX_FRAMES as f64 {
            return Err(AppError::new(format!(
                "--from {} --to {} at --fps {} is {} frames, more than the {MAX_FRAMES} a clip may have: shorten the span or lower --fps",
                show(from),
                show(to),
                show(fps),
                steps + 1.0
            )));
        }
        Ok(ClipTimes {
            from,
            fps,
            count: steps as usize + 1,
        })
    }

    /// The app's "Share clip": the `seconds` of race time up to `playhead`, cut at the race's
    /// start (a playhead too near the start to leave one frame step is refused).
    pub fn before_playhead(
        playhead: f64,
        seconds: f64,
        fps: f64,
        race_span: (f64, f64),
    ) -> AppResult<ClipTimes> {
        let to = playhead.clamp(race_span.0, race_span.1);
        ClipTimes::new((to - seconds).max(race_span.0), to, fps, race_span)
    }

    /// Race time of frame `i`, seconds.
    pub fn time(&self, i: usize) -> f64 {
        self.from + i as f64 / self.fps
    }

    /// How long frame `i` shows, centiseconds (see the module's note on rounding).
    pub fn delay_cs(&self, i: usize) -> u16 {
        let at = |k: usize| (100.0 * k as f64 / self.fps).round();
        (at(i + 1) - at(i)).clamp(0.0, u16::MAX as f64) as u16
    }
}

/// How a clip draws each frame: what `regatta render` takes besides the times.
#[derive(Debug, Clone)]
pub struct ClipLook {
    /// Frame size, pixels.
    pub size: [u32; 2],
    /// A fixed camera; `None` frames the fleet at each frame's time, as the still does.
    pub camera: Option<render::Camera>,
    pub overlays: crate::scene_overlay::OverlaySettings,
    /// The race's debrief for the trails' manoeuvre marks (worked out once, before the clip),
    /// or `None` for trails without them.
    pub debrief: Option<race::Debrief>,
    pub wakes: bool,
    /// Clip-map screen-space error target, pixels.
    pub error_px: f64,
}

/// Draws `world` at each of `times` headless, as the still render does (overlays included),
/// and writes the GIF to `out` atomically (nothing left on error). `progress(done, total, t)`
/// is called after each frame: the CLI prints it, an app can show it from a worker thread
/// (everything here owns its own headless GPU device).
pub fn write_gif(
    world: &RaceWorld,
    times: &ClipTimes,
    look: &ClipLook,
    out: &Path,
    progress: &mut dyn FnMut(usize, usize, f64),
) -> AppResult {
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("cannot render: {e}")))?;
    let mut setup = RaceSetup::new(Profile::Picture);
    setup.options.error_px = look.error_px;
    setup.wakes = look.wakes;
    let mut renderer = setup.renderer(&gpu, render::OFFSCREEN_FORMAT, setup.wake(&world.race)?);
    // The overlay passes keep the layers they were added with: one for every frame.
    let layers = render::passes::segments::SegmentLayers::default();
    crate::setup::output::write_atomically(out, |tmp| {
        let file = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
        let mut gif = GifWriter::new(std::io::BufWriter::new(file), look.size)?;
        for i in 0..times.count {
            let t = times.time(i);
            let scene = world.scene_at(t, look.camera);
            let (img, _) = crate::scene_overlay::render_headless_with(
                &gpu,
                &mut renderer,
                &layers,
                (&world.race, look.debrief.as_ref()),
                &scene,
                look.size,
                &look.overlays,
            )
            .map_err(|e| format!("cannot render frame {i}: {e}"))?;
            gif.push(img, times.delay_cs(i))?;
            progress(i + 1, times.count, t);
        }
        gif.finish()
    })
}

/// An animated GIF being written: one palette per frame, looping forever.
pub struct GifWriter<W: Write> {
    encoder: gif::Encoder<W>,
    size: [u32; 2],
}

impl<W: Write> GifWriter<W> {
    /// A GIF of `size` pixels (each side at most 65,535, GIF's limit) into `out`.
    pub fn new(out: W, size: [u32; 2]) -> Result<Self, String> {
        let side = |s: u32| u16::try_from(s).map_err(|_| format!("{s} px is wider than a GIF"));
        let mut encoder =
            gif::Encoder::new(out, side(size[0])?, side(size[1])?, &[]).map_err(gif_error)?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(gif_error)?;
        Ok(GifWriter { encoder, size })
    }

    /// Adds `img` (RGBA, `size`), shown for `delay_cs` centiseconds.
    pub fn push(&mut self, img: image::RgbaImage, delay_cs: u16) -> Result<(), String> {
        if img.dimensions() != (self.size[0], self.size[1]) {
            return Err(format!(
                "a frame of {:?} px in a {:?} px clip",
                img.dimensions(),
                self.size
            ));
        }
        let mut rgba = img.into_raw();
        let mut frame = gif::Frame::from_rgba_speed(
            self.size[0] as u16,
            self.size[1] as u16,
            &mut rgba,
            quant_speed(self.size),
        );
        frame.delay = delay_cs;
        self.encoder.write_frame(&frame).map_err(gif_error)
    }

    /// Writes the trailer and flushes.
    pub fn finish(self) -> Result<(), String> {
        let mut out = self.encoder.into_inner().map_err(gif_error)?;
        out.flush().map_err(|e| e.to_string())
    }
}

fn gif_error(e: impl std::fmt::Display) -> String {
    format!("GIF encoder: {e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    const RACE: (f64, f64) = (0.0, 1000.0);

    #[test]
    fn frame_count_includes_both_ends_of_a_whole_span() {
        let t = ClipTimes::new(10.0, 12.0, 15.0, RACE).unwrap();
        assert_eq!(t.count, 31);
        assert_eq!(t.time(30), 12.0);
        // A span that is not a whole number of steps stops at the last step inside it.
        let t = ClipTimes::new(10.0, 10.25, 10.0, RACE).unwrap();
        assert_eq!(t.count, 3);
        assert!(t.time(2) <= 10.25);
    }

    #[test]
    fn delays_add_up_to_the_span_and_each_is_within_half_a_centisecond() {
        for fps in [15.0, 7.0, 50.0, 0.1, 23.976] {
            let t = ClipTimes::new(0.0, 20.0, fps, RACE).unwrap();
            let total: u32 = (0..t.count).map(|i| u32::from(t.delay_cs(i))).sum();
            let exact = 100.0 * t.count as f64 / fps;
            assert!(
                (f64::from(total) - exact).abs() <= 0.5,
                "{fps}: {total} vs {exact}"
            );
            for i in 0..t.count {
                let d = f64::from(t.delay_cs(i));
                assert!((d - 100.0 / fps).abs() <= 1.0, "{fps} frame {i}: {d}");
            }
        }
    }

    #[test]
    fn bad_spans_name_their_flag() {
        let cases = [
            (12.0, 10.0, 15.0, "--from 12 is not before --to 10"),
            (10.0, 10.0, 15.0, "is not before"),
            (-5.0, 10.0, 15.0, "--from: -5 to 10 s lies outside the race"),
            (10.0, 2000.0, 15.0, "--to: 10 to 2000 s lies outside"),
            (f64::NAN, 10.0, 15.0, "must be finite"),
            (0.0, 10.0, 0.0, "--fps 0 is outside"),
            (0.0, 10.0, -3.0, "--fps -3 is outside"),
            (0.0, 10.0, 1000.0, "--fps 1000 is outside"),
            (0.0, 1000.0, 15.0, "15001 frames, more than the 3000"),
        ];
        for (from, to, fps, needle) in cases {
            let e = ClipTimes::new(from, to, fps, RACE).unwrap_err().0;
            assert!(e.contains(needle), "{from} {to} {fps}: {e}");
        }
        assert_eq!(ClipTimes::new(0.0, 199.9, 15.0, RACE).unwrap().count, 2999);
    }

    #[test]
    fn the_share_button_span_ends_at_the_playhead_and_stops_at_the_start() {
        let t = ClipTimes::before_playhead(700.0, 20.0, 15.0, RACE).unwrap();
        assert_eq!((t.from, t.count, t.time(t.count - 1)), (680.0, 301, 700.0));
        let t = ClipTimes::before_playhead(5.0, 20.0, 15.0, RACE).unwrap();
        assert_eq!((t.from, t.count), (0.0, 76));
        assert!(ClipTimes::before_playhead(0.0, 20.0, 15.0, RACE).is_err());
    }

    #[test]
    fn small_frames_are_quantised_from_every_pixel_large_ones_from_a_sample() {
        assert_eq!(quant_speed([48, 32]), 1);
        assert_eq!(quant_speed([640, 360]), 2);
        assert_eq!(quant_speed([1280, 720]), 9);
        assert_eq!(quant_speed([8192, 8192]), 10);
    }
}
