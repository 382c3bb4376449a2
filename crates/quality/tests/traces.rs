//! The governor on synthetic frame-time traces, closed loop: a phone model answers each tier
//! the governor picks with a frame time (its own true tier costs, which differ from the
//! governor's priors, a slowdown over time, ±5 % jitter from a fixed-seed generator), and the
//! trace time advances by each frame's present interval (at least one 60 Hz vsync).
//!
//! The goals (issue "phone frame budget"): settle within 2 s of trace time, then hold the target
//! within 10 % (every second's median frame time ≤ 1.1 × budget), change tier at most once per
//! 3 s, never while scrubbing.

use quality::{Change, Governor, Target, Tier};

/// A phone: frame time at ultra, true relative costs per tier, a slowdown factor over time.
struct Phone {
    ultra_ms: f64,
    true_cost: [f64; 4],
    slowdown: Box<dyn Fn(f64) -> f64>,
}

/// One frame of a run.
struct Frame {
    t: f64,
    ms: f64,
}

struct Run {
    frames: Vec<Frame>,
    changes: Vec<Change>,
}

/// A fixed-seed generator for ±5 % jitter (deterministic: the same trace every run).
struct Jitter(u64);
impl Jitter {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let u = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        1.0 + 0.1 * (u - 0.5)
    }
}

fn run(
    phone: &Phone,
    mut g: Governor,
    seconds: f64,
    scrubbing: impl Fn(f64) -> bool,
    spike: impl Fn(f64) -> Option<f64>,
) -> Run {
    let mut jitter = Jitter(7);
    let (mut t, mut frames, mut changes) = (0.0, Vec::new(), Vec::new());
    while t < seconds {
        let tier = g.tier();
        let ms = spike(t).unwrap_or_else(|| {
            phone.ultra_ms * phone.true_cost[tier.index()] * (phone.slowdown)(t) * jitter.next()
        });
        if let Some(c) = g.observe(t, ms, scrubbing(t)) {
            changes.push(c);
        }
        frames.push(Frame { t, ms });
        t += ms.max(1000.0 / 60.0) / 1000.0;
    }
    Run { frames, changes }
}

fn steady(phone: &Phone, g: Governor, seconds: f64) -> Run {
    run(phone, g, seconds, |_| false, |_| None)
}

/// The median frame time of each whole second in [from, to).
fn second_medians(r: &Run, from: f64, to: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut s = from;
    while s + 1.0 <= to {
        let mut v: Vec<f64> = r
            .frames
            .iter()
            .filter(|f| f.t >= s && f.t < s + 1.0)
            .map(|f| f.ms)
            .collect();
        v.sort_by(f64::total_cmp);
        out.push((s, v[v.len() / 2]));
        s += 1.0;
    }
    out
}

fn assert_holds(r: &Run, budget_ms: f64, from: f64, to: f64) {
    for (s, m) in second_medians(r, from, to) {
        assert!(
            m <= 1.1 * budget_ms,
            "second {s}: median {m:.1} ms over 1.1 × {budget_ms:.1} ms; changes {:?}",
            r.changes
        );
    }
}

fn assert_dwell(r: &Run) {
    for pair in r.changes.windows(2) {
        assert!(
            pair[1].at_s - pair[0].at_s >= 3.0,
            "two changes within 3 s: {:?}",
            r.changes
        );
    }
}

fn no_slowdown() -> Box<dyn Fn(f64) -> f64> {
    Box::new(|_| 1.0)
}

/// An OPPO A54 class phone: ultra at 110 ms, low at ≈ 29 ms (true costs off the priors).
fn slow_phone() -> Phone {
    Phone {
        ultra_ms: 110.0,
        true_cost: [0.26, 0.36, 0.62, 1.0],
        slowdown: no_slowdown(),
    }
}

#[test]
fn a_slow_phone_settles_in_one_change_within_two_seconds_and_holds_30_fps() {
    let r = steady(
        &slow_phone(),
        Governor::new(Target::Fps30, Tier::Ultra),
        60.0,
    );
    let first = r.changes.first().expect("the governor must leave ultra");
    assert!(first.at_s <= 2.0, "settled at {} s", first.at_s);
    assert_eq!(first.to, Tier::Low);
    assert_eq!(r.changes.len(), 1, "{:?}", r.changes);
    assert_holds(&r, 1000.0 / 30.0, 2.0, 60.0);
}

#[test]
fn thermal_slowdown_after_five_minutes_steps_down_within_two_seconds() {
    // A Pixel 2 XL class phone at 60 fps on `high` (12 ms), throttled by 1.5× at t = 300 s.
    let phone = Phone {
        ultra_ms: 20.0,
        true_cost: [0.25, 0.35, 0.6, 1.0],
        slowdown: Box::new(|t| if t < 300.0 { 1.0 } else { 1.5 }),
    };
    let r = steady(&phone, Governor::new(Target::Fps60, Tier::High), 360.0);
    assert_dwell(&r);
    let before: Vec<&Change> = r.changes.iter().filter(|c| c.at_s < 300.0).collect();
    assert!(before.is_empty(), "changed before the slowdown: {before:?}");
    let after = r
        .changes
        .iter()
        .find(|c| c.at_s >= 300.0)
        .expect("a step down");
    assert!(after.at_s <= 302.0, "stepped down at {} s", after.at_s);
    assert!(after.to < Tier::High);
    assert_holds(&r, 1000.0 / 60.0, 0.0, 300.0);
    assert_holds(&r, 1000.0 / 60.0, 302.0, 360.0);
}

#[test]
fn a_gradual_thermal_ramp_changes_at_most_once_per_three_seconds_and_is_held_after() {
    let phone = Phone {
        ultra_ms: 20.0,
        true_cost: [0.25, 0.35, 0.6, 1.0],
        slowdown: Box::new(|t: f64| 1.0 + 0.8 * ((t - 300.0) / 30.0).clamp(0.0, 1.0)),
    };
    let r = steady(&phone, Governor::new(Target::Fps60, Tier::High), 400.0);
    assert_dwell(&r);
    assert!(!r.changes.is_empty());
    assert!(r.changes.len() <= 3, "{:?}", r.changes);
    assert_holds(&r, 1000.0 / 60.0, 332.0, 400.0);
}

#[test]
fn a_spike_of_a_few_long_frames_changes_nothing() {
    let phone = Phone {
        ultra_ms: 20.0,
        true_cost: [0.25, 0.35, 0.6, 1.0],
        slowdown: no_slowdown(),
    };
    // 12 ms frames at `high`, then five 200 ms frames at t = 10 s (e.g. a shader compile).
    let spike_start = 10.0;
    let r = run(
        &phone,
        Governor::new(Target::Fps60, Tier::High),
        30.0,
        |_| false,
        |t| (t >= spike_start && t < spike_start + 1.0).then_some(200.0),
    );
    assert!(r.changes.is_empty(), "{:?}", r.changes);
}

#[test]
fn no_change_while_the_user_scrubs() {
    // Scrubbing makes frames 3× slower (offscreen passes redone every frame): no popping.
    let phone = Phone {
        ultra_ms: 20.0,
        true_cost: [0.25, 0.35, 0.6, 1.0],
        slowdown: Box::new(|t| if (20.0..25.0).contains(&t) { 3.0 } else { 1.0 }),
    };
    let r = run(
        &phone,
        Governor::new(Target::Fps60, Tier::High),
        40.0,
        |t| (20.0..25.0).contains(&t),
        |_| None,
    );
    assert!(r.changes.is_empty(), "{:?}", r.changes);
}

#[test]
fn a_frame_time_between_the_thresholds_never_oscillates() {
    // `ultra` just over the budget (17.5 ms at 60 fps) and `high` comfortably under it: the
    // governor steps down once and never goes back up in five minutes.
    let phone = Phone {
        ultra_ms: 17.5,
        true_cost: [0.25, 0.35, 0.6, 1.0],
        slowdown: no_slowdown(),
    };
    let r = steady(&phone, Governor::new(Target::Fps60, Tier::Ultra), 300.0);
    assert_eq!(r.changes.len(), 1, "{:?}", r.changes);
    assert_eq!(r.changes[0].to, Tier::High);
}

#[test]
fn room_to_grow_moves_up_after_the_hold_time() {
    // A fast phone started at `low` (4.4 ms): after 2 s of room it goes to `ultra` (16 × 0.85 fits).
    let phone = Phone {
        ultra_ms: 12.0,
        true_cost: [0.22, 0.30, 0.6, 1.0],
        slowdown: no_slowdown(),
    };
    let r = steady(&phone, Governor::new(Target::Fps60, Tier::Low), 30.0);
    assert_eq!(r.changes.len(), 1, "{:?}", r.changes);
    let c = r.changes[0];
    assert_eq!(c.to, Tier::Ultra);
    assert!(c.at_s >= 2.0 && c.at_s <= 3.0, "{c:?}");
}

#[test]
fn auto_holds_60_on_a_fast_phone_and_30_on_a_slow_one() {
    let fast = Phone {
        ultra_ms: 20.0,
        true_cost: [0.25, 0.35, 0.6, 1.0],
        slowdown: no_slowdown(),
    };
    let mut g = Governor::new(Target::Auto, Tier::High);
    let r = steady(&fast, g.clone(), 20.0);
    assert!(r.changes.is_empty(), "{:?}", r.changes);
    for f in r.frames.iter().take(40) {
        g.observe(f.t, f.ms, false);
    }
    assert_eq!(g.budget_ms(), 1000.0 / 60.0);

    let r = steady(
        &slow_phone(),
        Governor::new(Target::Auto, Tier::Ultra),
        30.0,
    );
    assert_eq!(r.changes[0].budget_ms, 1000.0 / 30.0);
    assert_holds(&r, 1000.0 / 30.0, 2.0, 30.0);
}
