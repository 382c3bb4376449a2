//! The shells' wall clock. Race time is the race panels' `ui::RaceClock` everywhere (play,
//! pause, speed, scrub, loop); the pool's time runs with the wall clock. Only the shells (the
//! desktop window, the Android activity) read the OS clock: they measure wall time with a
//! [`Ticker`] and hand the app core seconds, so the core names no OS clock, scripted sessions
//! (phone-sim) step time exactly, and time in the background never counts.

use std::time::Instant;

/// Wall seconds between frames; the first frame after [`Ticker::stop`] counts zero.
#[derive(Debug, Default)]
pub struct Ticker {
    last: Option<Instant>,
}

impl Ticker {
    /// Seconds since the last tick (0 for the first).
    pub fn tick(&mut self) -> f64 {
        let now = Instant::now();
        let dt = self
            .last
            .map_or(0.0, |l| now.duration_since(l).as_secs_f64());
        self.last = Some(now);
        dt
    }

    /// The app went to the background: the time until the next tick does not count.
    pub fn stop(&mut self) {
        self.last = None;
    }
}
