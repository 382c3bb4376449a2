//! The governor in a render loop: the app feeds each presented frame (its GPU time where
//! timestamps exist, else the interval since the last present, and whether the user is
//! scrubbing) and applies the [`TierRender`] it gets back when the tier changes. The desktop
//! app and the phone (`regatta run --phone`, `regatta phone-sim`, Android) use it; the Scene
//! panel's tier control shows [`TierControl::panel`] and its changes go to
//! [`TierControl::answer`].

use quality::{Governor, Target, Tier};

use crate::tier_render::TierRender;

/// A governor and what it needs between frames.
pub struct TierControl {
    governor: Governor,
    /// Time of the last present, s (the frame time where no GPU time is measured).
    last_present: Option<f64>,
}

impl TierControl {
    /// Auto target, starting at `start` (pinned there when `pinned`).
    pub fn new(start: Tier, pinned: bool) -> TierControl {
        let mut governor = Governor::new(Target::Auto, start);
        if pinned {
            governor.pin(Some(start));
        }
        TierControl {
            governor,
            last_present: None,
        }
    }

    /// The tier drawn now.
    pub fn tier(&self) -> Tier {
        self.governor.tier()
    }

    /// The pinned tier, if the user pinned one.
    pub fn pinned(&self) -> Option<Tier> {
        self.governor.pinned()
    }

    /// Pin `tier` (or let the governor choose again with `None`): the settings to apply when
    /// the tier drawn changes.
    pub fn pin(&mut self, tier: Option<Tier>) -> Option<TierRender> {
        let before = self.tier();
        self.governor.pin(tier);
        (self.tier() != before).then(|| TierRender::of(self.tier()))
    }

    /// The frame-rate target (the panel's 30 / 60 / auto).
    pub fn set_target(&mut self, target: Target) {
        self.governor.set_target(target);
    }

    pub fn target(&self) -> Target {
        self.governor.target()
    }

    /// What the panel's tier control shows: the tier drawn, the pin, the target.
    pub fn panel(&self) -> ui::TierPanel {
        ui::TierPanel {
            current: self.tier(),
            pinned: self.pinned(),
            target: self.target(),
        }
    }

    /// The panel's change: a pin ([`TierControl::pin`]) or a target. The settings to apply
    /// when the tier drawn changes.
    pub fn answer(&mut self, change: ui::TierChange) -> Option<TierRender> {
        match change {
            ui::TierChange::Pin(tier) => self.pin(tier),
            ui::TierChange::Target(target) => {
                self.set_target(target);
                None
            }
        }
    }

    /// One presented frame at `now_s` (monotonic seconds): `gpu_ms` where the adapter measured
    /// it, else the present interval is the frame time. Returns the settings to apply when the
    /// governor changes tier (never while `scrubbing`).
    pub fn frame(
        &mut self,
        now_s: f64,
        gpu_ms: Option<f64>,
        scrubbing: bool,
    ) -> Option<TierRender> {
        let interval = self.last_present.map(|t| (now_s - t) * 1e3);
        self.last_present = Some(now_s);
        let frame_ms = gpu_ms.or(interval)?;
        self.governor
            .observe(now_s, frame_ms, scrubbing)
            .map(|c| TierRender::of(c.to))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Present intervals of `ms` from 0 for `seconds`, fed with no GPU time; the changes.
    fn run(
        c: &mut TierControl,
        ms: f64,
        from_s: f64,
        seconds: f64,
        scrubbing: bool,
    ) -> Vec<(f64, Tier)> {
        let mut out = Vec::new();
        let mut t = from_s;
        while t < from_s + seconds {
            if let Some(r) = c.frame(t, None, scrubbing) {
                out.push((t, r.tier));
            }
            t += ms / 1e3;
        }
        out
    }

    #[test]
    fn present_intervals_drive_the_governor_down_within_two_seconds() {
        // 20 fps at ultra, no timestamps: the intervals are the frame times.
        let mut c = TierControl::new(Tier::Ultra, false);
        let changes = run(&mut c, 50.0, 0.0, 3.0, false);
        assert_eq!(changes.len(), 1, "{changes:?}");
        let (at, to) = changes[0];
        assert!(at <= 2.0 && to < Tier::Ultra, "{changes:?}");
        assert_eq!(c.tier(), to);
    }

    #[test]
    fn gpu_time_is_preferred_over_the_present_interval() {
        // Presents every 50 ms (a vsync-bound or busy window) but the GPU takes 5 ms: no
        // reason to cut quality.
        let mut c = TierControl::new(Tier::Ultra, false);
        let mut t = 0.0;
        while t < 3.0 {
            assert!(c.frame(t, Some(5.0), false).is_none(), "at {t}");
            t += 0.05;
        }
    }

    #[test]
    fn scrubbing_and_pinning_hold_the_tier() {
        let mut c = TierControl::new(Tier::Ultra, false);
        assert!(run(&mut c, 50.0, 0.0, 5.0, true).is_empty());
        let mut p = TierControl::new(Tier::Ultra, true);
        assert!(run(&mut p, 50.0, 0.0, 5.0, false).is_empty());
        assert_eq!(p.pinned(), Some(Tier::Ultra));
        // Pinning another tier applies it at once; unpinning changes nothing by itself.
        assert_eq!(p.pin(Some(Tier::Low)).map(|r| r.tier), Some(Tier::Low));
        assert!(p.pin(None).is_none());
        assert_eq!(p.tier(), Tier::Low);
    }

    #[test]
    fn the_panels_changes_pin_and_set_the_target() {
        let mut c = TierControl::new(Tier::Ultra, false);
        assert_eq!(c.panel(), ui::TierPanel::auto(Tier::Ultra));
        let pinned = c.answer(ui::TierChange::Pin(Some(Tier::Medium)));
        assert_eq!(pinned.map(|r| r.tier), Some(Tier::Medium));
        assert!(c.answer(ui::TierChange::Target(Target::Fps60)).is_none());
        assert_eq!(
            c.panel(),
            ui::TierPanel {
                current: Tier::Medium,
                pinned: Some(Tier::Medium),
                target: Target::Fps60,
            }
        );
    }
}
