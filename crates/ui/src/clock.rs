//! The race clock: the one race time that the whole scene is evaluated at. Pure logic, no egui.
//!
//! Playing advances race time by `speed × wall seconds`; scrubbing sets it. Both only move one
//! number: nothing in the scene depends on how the clock got there, so a frame reached by playing
//! to t equals the frame reached by scrubbing to t (tested in `tests/clock.rs` and by the app).

/// Playback speeds, race seconds per wall second: backwards (−64× … −1×) and forwards
/// (1× … 64×).
pub const SPEEDS: [f64; 14] = [
    -64.0, -32.0, -16.0, -8.0, -4.0, -2.0, -1.0, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0,
];

/// The index of 1× in [`SPEEDS`].
const FORWARD_1X: usize = 7;

/// Race time under the timeline's control.
#[derive(Clone, Debug, PartialEq)]
pub struct RaceClock {
    /// Race seconds since the start signal.
    t: f64,
    /// First and last race time with data, seconds; the clock stays inside.
    span: (f64, f64),
    playing: bool,
    /// Index into [`SPEEDS`].
    speed: usize,
    /// Start playing again from the start when play runs off the end (from the end when
    /// reverse play runs off the start).
    pub looping: bool,
}

impl RaceClock {
    /// A paused clock at the start of `span` (race seconds), at 1×. An empty or reversed span is
    /// widened to one second so the scrubber always has a range.
    pub fn new(span: (f64, f64)) -> Self {
        let (a, b) = span;
        let span = if b > a { (a, b) } else { (a, a + 1.0) };
        Self {
            t: span.0,
            span,
            playing: false,
            speed: FORWARD_1X,
            looping: false,
        }
    }

    /// Race seconds.
    pub fn time(&self) -> f64 {
        self.t
    }

    pub fn span(&self) -> (f64, f64) {
        self.span
    }

    pub fn is_playing(&self) -> bool {
        self.playing
    }

    /// Race seconds per wall second; negative plays backwards.
    pub fn speed(&self) -> f64 {
        SPEEDS[self.speed]
    }

    /// Whether play runs backwards.
    pub fn is_reverse(&self) -> bool {
        self.speed() < 0.0
    }

    /// Plays; at the end (at the start, playing backwards) it starts over from the other end.
    pub fn play(&mut self) {
        if !self.is_reverse() && self.t >= self.span.1 {
            self.t = self.span.0;
        } else if self.is_reverse() && self.t <= self.span.0 {
            self.t = self.span.1;
        }
        self.playing = true;
    }

    pub fn pause(&mut self) {
        self.playing = false;
    }

    pub fn toggle(&mut self) {
        if self.playing {
            self.pause()
        } else {
            self.play()
        }
    }

    /// Sets the speed to the nearest of [`SPEEDS`].
    pub fn set_speed(&mut self, speed: f64) {
        self.speed = (0..SPEEDS.len())
            .min_by(|&a, &b| {
                (SPEEDS[a] - speed)
                    .abs()
                    .total_cmp(&(SPEEDS[b] - speed).abs())
            })
            .unwrap_or(FORWARD_1X);
    }

    /// Twice as fast in the same direction (up to 64×).
    pub fn faster(&mut self) {
        self.speed = if self.is_reverse() {
            self.speed.saturating_sub(1)
        } else {
            (self.speed + 1).min(SPEEDS.len() - 1)
        };
    }

    /// Half as fast in the same direction (down to 1×).
    pub fn slower(&mut self) {
        if self.is_reverse() {
            self.speed = (self.speed + 1).min(FORWARD_1X - 1);
        } else {
            self.speed = self.speed.saturating_sub(1).max(FORWARD_1X);
        }
    }

    /// The same speed the other way (8× ↔ −8×).
    pub fn reverse(&mut self) {
        self.set_speed(-self.speed());
    }

    /// Advances by `wall_dt` wall seconds when playing (backwards at a negative speed);
    /// returns whether race time moved. Play stops at the end of the span, or at its start
    /// playing backwards (or goes round to the other end, with `looping`).
    pub fn advance(&mut self, wall_dt: f64) -> bool {
        if !self.playing || wall_dt.is_nan() || wall_dt <= 0.0 {
            return false;
        }
        let before = self.t;
        self.t += wall_dt * self.speed();
        let (a, b) = self.span;
        if self.t >= b || self.t <= a {
            if self.looping {
                self.t = a + (self.t - a).rem_euclid(b - a);
            } else {
                self.t = self.t.clamp(a, b);
                self.playing = false;
            }
        }
        self.t != before
    }

    /// Sets race time (clamped to the span); playing continues from there.
    pub fn scrub_to(&mut self, t: f64) {
        if t.is_finite() {
            self.t = t.clamp(self.span.0, self.span.1);
        }
    }

    /// One step of `step_s(speed)` race seconds forward (`+1`) or back (`-1`), pausing first.
    pub fn step(&mut self, direction: i32) {
        self.pause();
        self.scrub_to(self.t + f64::from(direction.signum()) * self.step_seconds());
    }

    /// The step size: one second of race at 1×, growing with speed (either way) so a step
    /// stays visible.
    pub fn step_seconds(&self) -> f64 {
        self.speed().abs()
    }

    /// Jumps to the start signal (race time 0), or the span's start when the data begin later.
    pub fn jump_to_start(&mut self) {
        self.scrub_to(0.0f64.max(self.span.0));
    }

    /// Jumps to the first of `events` (race seconds, sorted) after now, if any; returns it.
    /// Events within a millisecond of now count as now, so repeated jumps walk through them.
    pub fn jump_to_next(&mut self, events: &[f64]) -> Option<f64> {
        let t = events.iter().copied().find(|&e| e > self.t + 1e-3)?;
        self.scrub_to(t);
        Some(t)
    }

    /// Jumps to the last of `events` before now, if any; returns it.
    pub fn jump_to_previous(&mut self, events: &[f64]) -> Option<f64> {
        let t = events.iter().rev().copied().find(|&e| e < self.t - 1e-3)?;
        self.scrub_to(t);
        Some(t)
    }
}

/// Race time as a sailor reads a race clock: `-0:30` before the start, `12:05`, `1:02:03`.
pub fn format_race_time(t: f64) -> String {
    let sign = if t < 0.0 { "-" } else { "" };
    let s = t.abs().floor() as u64;
    let (h, m, s) = (s / 3600, (s / 60) % 60, s % 60);
    if h > 0 {
        format!("{sign}{h}:{m:02}:{s:02}")
    } else {
        format!("{sign}{m}:{s:02}")
    }
}
