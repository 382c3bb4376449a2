//! The governor: holds a frame-rate target by moving between tiers.
//!
//! Policy, in order:
//! 1. The frame time it trusts is the **median** of the frames of the last `window_s` seconds
//!    (and at least `min_frames` frames) drawn at the current tier: a spike of fewer than half
//!    the window's frames does not move a median; it would move a mean.
//! 2. **Down** when that median stays over `budget × down_margin` for `confirm_s`: straight to
//!    the richest tier predicted to fit `budget × fit_margin`, not one step at a time, so a slow
//!    phone settles in one change. Prediction: the median scaled by the tiers' relative costs
//!    (priors from [`Tier::prior_cost`], replaced by the ratio measured across each change).
//! 3. **Up** only when a richer tier is predicted to fit `budget × fit_margin` for `up_hold_s`.
//!    Down at 1.05 × budget and up only below `fit_margin` (0.85) is the hysteresis: a frame time
//!    between the two thresholds changes nothing.
//! 4. At most one change per `min_dwell_s`; none while the user scrubs (no popping mid-drag)
//!    or while a tier is pinned.

use std::collections::VecDeque;

use crate::Tier;

/// The frame rate to hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// 30 frames per second.
    Fps30,
    /// 60 frames per second.
    Fps60,
    /// 60 where a tier of at least `medium` holds it, else 30.
    Auto,
}

impl Target {
    /// The name used in the panel and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Target::Fps30 => "30",
            Target::Fps60 => "60",
            Target::Auto => "auto",
        }
    }
}

/// The governor's thresholds and times (seconds of trace time).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GovernorConfig {
    /// Frames of the last this many seconds make the median...
    pub window_s: f64,
    /// ...but never fewer than this many frames: on a slow phone half a second is a handful of
    /// frames, and a spike of a few long frames would fill it.
    pub min_frames: usize,
    /// A too-slow median must last this long before stepping down.
    pub confirm_s: f64,
    /// Room for a richer tier must last this long before stepping up.
    pub up_hold_s: f64,
    /// At most one change per this many seconds.
    pub min_dwell_s: f64,
    /// Too slow: median over `budget × down_margin`.
    pub down_margin: f64,
    /// A tier fits when its predicted frame time is under `budget × fit_margin`.
    pub fit_margin: f64,
}

impl Default for GovernorConfig {
    fn default() -> Self {
        GovernorConfig {
            window_s: 0.5,
            min_frames: 11,
            confirm_s: 0.25,
            up_hold_s: 2.0,
            min_dwell_s: 3.0,
            down_margin: 1.05,
            fit_margin: 0.85,
        }
    }
}

/// One decision of the governor, for the frame report and the tests.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Change {
    /// Trace time of the decision, seconds.
    pub at_s: f64,
    pub from: Tier,
    pub to: Tier,
    /// The median frame time that caused it, milliseconds.
    pub median_ms: f64,
    /// The frame budget it was held against, milliseconds.
    pub budget_ms: f64,
}

/// Holds a frame-rate target by choosing the tier. Feed it every frame with
/// [`Governor::observe`]; it answers with a [`Change`] when the app should switch tiers.
#[derive(Debug, Clone)]
pub struct Governor {
    config: GovernorConfig,
    target: Target,
    tier: Tier,
    pinned: Option<Tier>,
    /// Relative frame cost per tier (index = `Tier::index`); only ratios matter.
    cost: [f64; 4],
    /// (trace time s, frame ms) of the frames drawn at the current tier, the last `window_s`.
    frames: VecDeque<(f64, f64)>,
    /// Trace time the current tier began.
    tier_since: Option<f64>,
    last_change: Option<f64>,
    slow_since: Option<f64>,
    room_since: Option<f64>,
    /// The tier before the last change and its median then: the next full window at the new
    /// tier measures the ratio of their costs.
    learn_from: Option<(Tier, f64)>,
}

impl Governor {
    /// A governor starting at `tier`, holding `target`.
    pub fn new(target: Target, tier: Tier) -> Self {
        Governor::with_config(target, tier, GovernorConfig::default())
    }

    pub fn with_config(target: Target, tier: Tier, config: GovernorConfig) -> Self {
        Governor {
            config,
            target,
            tier,
            pinned: None,
            cost: Tier::ALL.map(Tier::prior_cost),
            frames: VecDeque::new(),
            tier_since: None,
            last_change: None,
            slow_since: None,
            room_since: None,
            learn_from: None,
        }
    }

    /// The tier the app should draw at now.
    pub fn tier(&self) -> Tier {
        self.pinned.unwrap_or(self.tier)
    }

    pub fn target(&self) -> Target {
        self.target
    }

    /// A new target (the panel's choice); the tier stays until the frames say otherwise.
    pub fn set_target(&mut self, target: Target) {
        self.target = target;
        self.slow_since = None;
        self.room_since = None;
    }

    /// Pin a tier (the user's choice in the panel), or `None` to let the governor choose again.
    pub fn pin(&mut self, tier: Option<Tier>) {
        self.pinned = tier;
        if let Some(t) = tier {
            self.switch_to(t, None);
        }
    }

    pub fn pinned(&self) -> Option<Tier> {
        self.pinned
    }

    /// The frame budget in milliseconds that the governor holds now.
    pub fn budget_ms(&self) -> f64 {
        1000.0 / self.fps(median(self.frames.iter().map(|&(_, ms)| ms)))
    }

    /// One drawn frame: trace time `t_s` (seconds, non-decreasing), its frame time in
    /// milliseconds (GPU time where timestamps exist, else the present interval), and whether
    /// the user is scrubbing the timeline. Returns the change to make, if any.
    pub fn observe(&mut self, t_s: f64, frame_ms: f64, scrubbing: bool) -> Option<Change> {
        if !(t_s.is_finite() && frame_ms.is_finite() && frame_ms > 0.0) {
            return None;
        }
        let since = *self.tier_since.get_or_insert(t_s);
        self.frames.push_back((t_s, frame_ms));
        while self.frames.len() > self.config.min_frames
            && self
                .frames
                .front()
                .is_some_and(|&(t, _)| t < t_s - self.config.window_s)
        {
            self.frames.pop_front();
        }
        if scrubbing || self.pinned.is_some() {
            self.slow_since = None;
            self.room_since = None;
            return None;
        }
        // A full window at this tier, or nothing to judge yet.
        if t_s - since < self.config.window_s || self.frames.len() < self.config.min_frames {
            return None;
        }
        let median = median(self.frames.iter().map(|&(_, ms)| ms));
        if let Some((from, from_ms)) = self.learn_from.take() {
            let ratio = median / from_ms;
            self.cost[self.tier.index()] = self.cost[from.index()] * ratio;
        }
        let budget = 1000.0 / self.fps(median);
        let may_change = self
            .last_change
            .is_none_or(|c| t_s - c >= self.config.min_dwell_s);
        if median > budget * self.config.down_margin {
            self.room_since = None;
            let slow_since = *self.slow_since.get_or_insert(t_s);
            if may_change && t_s - slow_since >= self.config.confirm_s {
                let to = self.richest_fitting(median, budget).unwrap_or(Tier::Low);
                if to < self.tier {
                    return Some(self.change(t_s, to, median, budget));
                }
            }
            return None;
        }
        self.slow_since = None;
        match self.richest_fitting(median, budget) {
            Some(to) if to > self.tier => {
                let room_since = *self.room_since.get_or_insert(t_s);
                if may_change && t_s - room_since >= self.config.up_hold_s {
                    return Some(self.change(t_s, to, median, budget));
                }
            }
            _ => self.room_since = None,
        }
        None
    }

    /// The frame time predicted at `tier` from `median` measured at the current tier.
    pub fn predict_ms(&self, tier: Tier, median: f64) -> f64 {
        median * self.cost[tier.index()] / self.cost[self.tier.index()]
    }

    /// The frame rate held, given the median frame time at the current tier (NaN: none yet).
    fn fps(&self, median_ms: f64) -> f64 {
        match self.target {
            Target::Fps30 => 30.0,
            Target::Fps60 => 60.0,
            Target::Auto => {
                // 60 when the frames measured so far say a tier of at least `medium` fits it.
                let fits_60 = median_ms.is_finite()
                    && self.predict_ms(Tier::Medium, median_ms)
                        <= 1000.0 / 60.0 * self.config.fit_margin;
                if fits_60 { 60.0 } else { 30.0 }
            }
        }
    }

    fn richest_fitting(&self, median: f64, budget: f64) -> Option<Tier> {
        Tier::ALL
            .into_iter()
            .rev()
            .find(|&t| self.predict_ms(t, median) <= budget * self.config.fit_margin)
    }

    fn change(&mut self, t_s: f64, to: Tier, median: f64, budget: f64) -> Change {
        let from = self.tier;
        self.switch_to(to, Some(t_s));
        self.learn_from = Some((from, median));
        Change {
            at_s: t_s,
            from,
            to,
            median_ms: median,
            budget_ms: budget,
        }
    }

    fn switch_to(&mut self, to: Tier, at: Option<f64>) {
        self.tier = to;
        self.frames.clear();
        self.tier_since = None;
        self.slow_since = None;
        self.room_since = None;
        self.learn_from = None;
        if at.is_some() {
            self.last_change = at;
        }
    }
}

/// The median of some values (NaN when there are none).
fn median(values: impl Iterator<Item = f64>) -> f64 {
    let mut v: Vec<f64> = values.collect();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_even_and_none() {
        assert_eq!(median([3.0, 1.0, 2.0].into_iter()), 2.0);
        assert_eq!(median([4.0, 1.0, 2.0, 3.0].into_iter()), 2.5);
        assert!(median(std::iter::empty()).is_nan());
    }

    #[test]
    fn a_pinned_tier_is_kept_whatever_the_frames_say() {
        let mut g = Governor::new(Target::Fps30, Tier::Ultra);
        g.pin(Some(Tier::High));
        for i in 0..600 {
            assert_eq!(g.observe(i as f64 / 30.0, 500.0, false), None);
        }
        assert_eq!(g.tier(), Tier::High);
        g.pin(None);
        assert_eq!(g.tier(), Tier::High);
    }

    #[test]
    fn bad_frame_times_are_ignored() {
        let mut g = Governor::new(Target::Fps30, Tier::Ultra);
        for (i, ms) in [f64::NAN, -1.0, 0.0, f64::INFINITY].into_iter().enumerate() {
            assert_eq!(g.observe(i as f64, ms, false), None);
        }
        assert!(g.frames.is_empty());
    }
}
