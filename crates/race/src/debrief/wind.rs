//! The race's wind direction over time, and whether it was measured or estimated.
//!
//! Where a file brings wind (a `twd` channel of an instrument log: NMEA MWD, Expedition TWD,
//! a SailGP log's TWD; or one stated direction: maxSail metadata, native JSON), that is used
//! and [`WindSource::Data`] says so. Otherwise the direction is estimated from the fleet
//! ([`WindSource::Estimated`]): boats sailing upwind hold about the same angle to the wind on
//! both tacks, so the wind comes from the bisector of the two upwind headings.
//!
//! The estimate, step by step:
//! 1. steady sailing only: every boat every [`SAMPLE_STEP_S`] from the start to its finish,
//!    where it sails at least half its median speed and turns less than 20° over 4 s;
//! 2. the wind's axis: the heading histogram (1° bins, weighted by speed) is mirror-symmetric
//!    about the wind axis (both tacks upwind, both gybes downwind); the axis is the mirror
//!    line of largest self-correlation;
//! 3. which end: the first leg's direction (start to first mark) where the course has one,
//!    else the end whose boats sail slower (upwind is slower for every class whose log this
//!    was tested on: dinghies, F50s);
//! 4. the bisector: the circular mean of the mean upwind heading on each tack (|TWA| < 90°),
//!    re-classified twice; downwind headings' bisector where no boat sails upwind;
//! 5. over time: the same bisector in windows of [`WINDOW_S`] every [`WINDOW_STEP_S`],
//!    classified against the race-long estimate; a window without both tacks is skipped.
//!
//! Uncertainty (one sigma, degrees): the statistical error of each tack's mean heading
//! (circular standard deviation over √n_eff, with one independent sample per
//! [`CORRELATION_S`] of sailing), halved for the bisector, combined with half the difference
//! between the upwind and the downwind bisectors where both exist (a current or unequal tack
//! angles move them apart). Measured against SailGP's own TWD in `tests/debrief_sailgp.rs`.

use serde::Serialize;

use crate::track::bearing_deg;
use crate::{MarkKind, Race};

/// Where the wind direction comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WindSource {
    /// A file's wind (instrument channel or a stated direction).
    Data,
    /// Estimated from the boats' headings (see the module docs).
    Estimated,
}

impl WindSource {
    /// The word every display of the wind shows beside it.
    pub fn label(self) -> &'static str {
        match self {
            WindSource::Data => "measured",
            WindSource::Estimated => "estimated",
        }
    }
}

/// Seconds between the samples of each boat that the estimate looks at.
pub const SAMPLE_STEP_S: f64 = 2.0;
/// Width of the sliding window of the estimate over time, seconds.
pub const WINDOW_S: f64 = 600.0;
/// Step between the windows, seconds.
pub const WINDOW_STEP_S: f64 = 120.0;
/// Sailing time over which one boat's headings count as one independent sample, seconds.
pub const CORRELATION_S: f64 = 20.0;
/// Bin width of a data wind's time series, seconds (the fleet's channels are pooled per bin).
pub const DATA_BIN_S: f64 = 10.0;

/// The wind direction over the race: samples in time (held before the first and after the
/// last, interpolated along the shorter arc between).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindModel {
    pub source: WindSource,
    /// One phrase: which file or channel, or which estimate.
    pub method: String,
    /// The race-long direction the wind blows from, compass degrees [0, 360).
    pub from_deg: f64,
    /// Speed where a file states it, m/s (an estimate from positions has none).
    pub speed_mps: Option<f64>,
    /// One sigma of `from_deg`, degrees (0 is never claimed: a data wind states its sensor's
    /// usual 2°).
    pub uncertainty_deg: f64,
    /// `(race seconds, from degrees)`, sorted by time; at least one.
    pub samples: Vec<(f64, f64)>,
}

/// The uncertainty stated for a measured direction, degrees: a masthead or mark-boat vane
/// calibrated to a couple of degrees.
pub const DATA_UNCERTAINTY_DEG: f64 = 2.0;

impl WindModel {
    /// A constant wind.
    pub fn constant(source: WindSource, method: &str, from_deg: f64, sigma: f64) -> WindModel {
        WindModel {
            source,
            method: method.to_string(),
            from_deg: from_deg.rem_euclid(360.0),
            speed_mps: None,
            uncertainty_deg: sigma,
            samples: vec![(0.0, from_deg.rem_euclid(360.0))],
        }
    }

    /// The direction the wind blows from at race time t, compass degrees [0, 360).
    pub fn from_deg_at(&self, t: f64) -> f64 {
        let s = &self.samples;
        let k = s.partition_point(|p| p.0 <= t);
        if k == 0 {
            return s[0].1;
        }
        if k == s.len() {
            return s[k - 1].1;
        }
        let (a, b) = (s[k - 1], s[k]);
        let f = (t - a.0) / (b.0 - a.0);
        (a.1 + f * angle_diff(b.1, a.1)).rem_euclid(360.0)
    }

    /// The same model turned by `deg` (for the error of what depends on it).
    pub fn turned(&self, deg: f64) -> WindModel {
        let mut w = self.clone();
        w.from_deg = (w.from_deg + deg).rem_euclid(360.0);
        for s in &mut w.samples {
            s.1 = (s.1 + deg).rem_euclid(360.0);
        }
        w
    }
}

/// `a - b` in (-180, 180], degrees.
pub fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 { d - 360.0 } else { d }
}

/// True wind angle of a heading, degrees in (-180, 180]: the wind's direction minus the
/// heading, so positive is starboard tack (the wind over the starboard side), negative port
/// tack, as SailGP's `TWA_SGP_deg`.
pub fn twa_deg(heading_deg: f64, wind_from_deg: f64) -> f64 {
    angle_diff(wind_from_deg, heading_deg)
}

/// Circular mean of angles (degrees) with weights; NaN when they cancel.
pub fn circular_mean(angles: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    let (mut s, mut c, mut w) = (0.0, 0.0, 0.0);
    for (a, wt) in angles {
        let r = a.to_radians();
        s += wt * r.sin();
        c += wt * r.cos();
        w += wt;
    }
    if w <= 0.0 || s.hypot(c) < 1e-9 * w {
        return (f64::NAN, 0.0);
    }
    let mean = s.atan2(c).to_degrees().rem_euclid(360.0);
    (mean, s.hypot(c) / w)
}

/// The race's wind: the files' where they bring one, else the fleet's estimate; `None` when
/// neither exists (no file wind and no boat sailing on both tacks).
pub fn race_wind(race: &Race) -> Option<WindModel> {
    from_data(race).or_else(|| estimate(race))
}

/// The wind the files bring: a `twd` channel (pooled over the fleet in [`DATA_BIN_S`] bins)
/// or the one direction a file states.
pub fn from_data(race: &Race) -> Option<WindModel> {
    let twd: Vec<&crate::Series> = race.series.iter().filter(|s| s.channel == "twd").collect();
    if !twd.is_empty() {
        let mut pts: Vec<(f64, f64)> = twd
            .iter()
            .flat_map(|s| s.t.iter().zip(&s.v).map(|(&t, &v)| (t, v as f64)))
            .filter(|(t, v)| t.is_finite() && v.is_finite())
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut samples = Vec::new();
        let mut i = 0;
        while i < pts.len() {
            let bin = (pts[i].0 / DATA_BIN_S).floor();
            let j = i + pts[i..].partition_point(|p| (p.0 / DATA_BIN_S).floor() <= bin);
            let (m, _) = circular_mean(pts[i..j].iter().map(|p| (p.1, 1.0)));
            if m.is_finite() {
                samples.push(((bin + 0.5) * DATA_BIN_S, m));
            }
            i = j;
        }
        if !samples.is_empty() {
            let in_race: Vec<(f64, f64)> = samples
                .iter()
                .filter(|s| s.0 >= 0.0)
                .map(|s| (s.1, 1.0))
                .collect();
            let (mean, _) = if in_race.is_empty() {
                circular_mean(samples.iter().map(|s| (s.1, 1.0)))
            } else {
                circular_mean(in_race.into_iter())
            };
            let speed = race
                .wind
                .map(|w| w.speed_mps)
                .or_else(|| channel_median(race, "tws"));
            return Some(WindModel {
                source: WindSource::Data,
                method: format!(
                    "the logs' true wind direction (twd, {} channel(s))",
                    twd.len()
                ),
                from_deg: mean,
                speed_mps: speed,
                uncertainty_deg: DATA_UNCERTAINTY_DEG,
                samples,
            });
        }
    }
    race.wind.map(|w| {
        let mut m = WindModel::constant(
            WindSource::Data,
            "the direction a race file states",
            w.from_deg,
            DATA_UNCERTAINTY_DEG,
        );
        m.speed_mps = Some(w.speed_mps);
        m
    })
}

fn channel_median(race: &Race, channel: &str) -> Option<f64> {
    let mut v: Vec<f64> = race
        .series
        .iter()
        .filter(|s| s.channel == channel)
        .flat_map(|s| s.v.iter().map(|&x| x as f64))
        .filter(|x| x.is_finite())
        .collect();
    if v.is_empty() {
        return None;
    }
    let mid = v.len() / 2;
    Some(*v.select_nth_unstable_by(mid, f64::total_cmp).1)
}

/// One steady-sailing sample of one boat.
#[derive(Debug, Clone, Copy)]
struct Sample {
    t: f64,
    heading: f64,
    speed: f64,
}

/// Every boat's steady-sailing samples (see the module docs, step 1).
fn steady_samples(race: &Race) -> Vec<Sample> {
    let mut out = Vec::new();
    for b in &race.boats {
        let (t0, t1) = b.time_span();
        let finish = b.roundings().last().copied().flatten();
        let from = if race.start_time.is_some() || race.course.len() >= 2 {
            t0.max(0.0)
        } else {
            t0
        };
        let to = match finish {
            Some(f) if race.course.len() >= 2 => f.min(t1),
            _ => t1,
        };
        if to <= from {
            continue;
        }
        let n = ((to - from) / SAMPLE_STEP_S) as usize;
        let mut speeds: Vec<f64> = (0..=n)
            .map(|k| b.state_at(from + k as f64 * SAMPLE_STEP_S).speed_mps)
            .collect();
        let mid = speeds.len() / 2;
        let median = *speeds.select_nth_unstable_by(mid, f64::total_cmp).1;
        for k in 0..=n {
            let t = from + k as f64 * SAMPLE_STEP_S;
            let s = b.state_at(t);
            if s.in_gap || s.speed_mps < 0.5 * median || s.speed_mps <= 0.0 {
                continue;
            }
            let before = b.state_at(t - 2.0).heading_deg;
            let after = b.state_at(t + 2.0).heading_deg;
            if angle_diff(after, before).abs() > 20.0 {
                continue;
            }
            out.push(Sample {
                t,
                heading: s.heading_deg,
                speed: s.speed_mps,
            });
        }
    }
    out
}

/// Step 2: the mirror axis of the speed-weighted heading histogram, degrees in [0, 180).
fn symmetry_axis(samples: &[Sample]) -> f64 {
    let mut h = [0.0f64; 360];
    for s in samples {
        h[(s.heading.rem_euclid(360.0) as usize) % 360] += s.speed;
    }
    // Smooth with a ±6° triangle so tack angles a degree or two apart still overlap.
    let mut sm = [0.0f64; 360];
    for (i, v) in sm.iter_mut().enumerate() {
        for d in -6i32..=6 {
            *v += h[(i as i32 + d).rem_euclid(360) as usize] * (7 - d.abs()) as f64;
        }
    }
    let mut best = (0.0, f64::NEG_INFINITY);
    // Half-degree candidates: the mirror of bin i about a is bin 2a - i.
    for a2 in 0..360 {
        let score: f64 = (0..360)
            .map(|i| sm[i] * sm[(a2 - i as i32).rem_euclid(360) as usize])
            .sum();
        if score > best.1 {
            best = (a2 as f64 * 0.5, score);
        }
    }
    best.0
}

/// The bisector of the mean headings on the two tacks among `samples` with |TWA| below
/// (upwind) or above (downwind) 90° from `wind`; with each side's count and circular spread.
fn bisector(samples: &[Sample], wind: f64, upwind: bool) -> Option<Bisector> {
    let pick = |sign: f64| {
        samples.iter().filter(move |s| {
            let a = twa_deg(s.heading, wind);
            (a.abs() < 90.0) == upwind && a * sign > 0.0
        })
    };
    let side = |sign: f64| {
        let (m, r) = circular_mean(pick(sign).map(|s| (s.heading, 1.0)));
        (m, r, pick(sign).count())
    };
    let (ms, rs, ns) = side(1.0);
    let (mp, rp, np) = side(-1.0);
    if ns < 5 || np < 5 || !ms.is_finite() || !mp.is_finite() {
        return None;
    }
    // The bisector of the two mean headings, on the side of the wind.
    let mid = (mp + 0.5 * angle_diff(ms, mp)).rem_euclid(360.0);
    let from = if upwind { mid } else { (mid + 180.0) % 360.0 };
    let from = if angle_diff(from, wind).abs() > 90.0 {
        (from + 180.0) % 360.0
    } else {
        from
    };
    let sd = |r: f64| (-2.0 * r.max(1e-12).ln()).sqrt().to_degrees();
    let n_eff = |n: usize| (n as f64 * SAMPLE_STEP_S / CORRELATION_S).max(1.0);
    let sigma = 0.5 * (sd(rs).powi(2) / n_eff(ns) + sd(rp).powi(2) / n_eff(np)).sqrt();
    Some(Bisector {
        from,
        sigma,
        count: ns + np,
    })
}

#[derive(Debug, Clone, Copy)]
struct Bisector {
    from: f64,
    sigma: f64,
    count: usize,
}

/// The fleet's estimate (see the module docs); `None` without enough steady sailing.
pub fn estimate(race: &Race) -> Option<WindModel> {
    let samples = steady_samples(race);
    if samples.len() < 20 {
        return None;
    }
    let axis = symmetry_axis(&samples);
    let ends = [axis, axis + 180.0];
    let course_leg = first_leg_bearing(race);
    let (mut wind, end_rule) = match course_leg {
        Some(b) => (
            *ends
                .iter()
                .min_by(|a, c| {
                    angle_diff(**a, b)
                        .abs()
                        .total_cmp(&angle_diff(**c, b).abs())
                })
                .unwrap(),
            "the first leg is upwind",
        ),
        None => {
            let median_speed = |end: f64| {
                let mut v: Vec<f64> = samples
                    .iter()
                    .filter(|s| angle_diff(s.heading, end).abs() < 90.0)
                    .map(|s| s.speed)
                    .collect();
                if v.is_empty() {
                    return f64::INFINITY;
                }
                let mid = v.len() / 2;
                *v.select_nth_unstable_by(mid, f64::total_cmp).1
            };
            let e = if median_speed(ends[0]) <= median_speed(ends[1]) {
                ends[0]
            } else {
                ends[1]
            };
            (e, "upwind is the slower end")
        }
    };
    let mut up = None;
    for _ in 0..3 {
        up = bisector(&samples, wind, true);
        if let Some(b) = up {
            wind = b.from;
        }
    }
    let down = bisector(&samples, wind, false);
    let (from, sigma_stat, how) = match (up, down) {
        (Some(u), _) => (
            u.from,
            u.sigma,
            "bisector of upwind headings on opposite tacks",
        ),
        (None, Some(d)) => (
            d.from,
            d.sigma,
            "bisector of downwind headings on opposite gybes",
        ),
        (None, None) => (wind, 20.0, "mirror axis of the fleet's headings"),
    };
    let systematic = match (up, down) {
        (Some(u), Some(d)) => 0.5 * angle_diff(u.from, d.from).abs(),
        _ => 0.0,
    };
    let uncertainty = sigma_stat.hypot(systematic).max(1.0);
    // Over time: windows classified against the race-long estimate.
    let (t_lo, t_hi) = samples
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, s| {
            (a.0.min(s.t), a.1.max(s.t))
        });
    let mut series = Vec::new();
    let mut c = t_lo + 0.5 * WINDOW_S;
    loop {
        let lo = c - 0.5 * WINDOW_S;
        let hi = c + 0.5 * WINDOW_S;
        let win: Vec<Sample> = samples
            .iter()
            .filter(|s| s.t >= lo && s.t < hi)
            .copied()
            .collect();
        if let Some(b) = bisector(&win, from, true).filter(|b| b.count >= 20)
            && let Some(b2) = bisector(&win, b.from, true)
        {
            series.push((c.min(t_hi), b2.from));
        }
        if c >= t_hi - 0.5 * WINDOW_S {
            break;
        }
        c += WINDOW_STEP_S;
    }
    if series.is_empty() {
        series.push((0.0, from));
    }
    Some(WindModel {
        source: WindSource::Estimated,
        method: format!(
            "estimated from the fleet: {how} ({end_rule}), over {:.0} min windows",
            WINDOW_S / 60.0
        ),
        from_deg: from,
        speed_mps: None,
        uncertainty_deg: uncertainty,
        samples: series,
    })
}

/// Compass bearing from the start to the first mark, where the course has both.
fn first_leg_bearing(race: &Race) -> Option<f64> {
    if race.course.len() < 2 {
        return None;
    }
    let start = &race.marks[race.course[0]];
    if start.kind == MarkKind::FleetStart {
        return None;
    }
    let m1 = &race.marks[race.course[1]];
    let d = [
        m1.position[0] - start.position[0],
        m1.position[1] - start.position[1],
    ];
    (d[0].hypot(d[1]) > 1.0).then(|| bearing_deg(d))
}
