//! Tacks and gybes of one boat, with the metres each one cost.
//!
//! **Detection.** Every [`Settings::step_s`] the boat's true wind angle (TWA: the wind's
//! direction, [`WindModel`], minus the boat's heading) puts it on a side: starboard where
//! `margin ≤ TWA ≤ 180° − margin`, port for the mirror, none near head-to-wind or dead
//! downwind or below [`Settings::min_speed_fraction`] of its median speed (a drifting boat's
//! GPS heading is noise). Runs of one side shorter than [`Settings::hold_s`] are noise and
//! dropped. Between two kept runs, each multiple of 180° that the TWA's unwrapped path passes
//! net is one manoeuvre: 0° (mod 360°) a tack, 180° a gybe ([`crossings`]), at the last time
//! the path passes it (a boat running by the lee wobbles across 180° before it gybes); a wobble across the wind that comes back passes nothing, and a
//! 360° turn is one tack and one gybe, as the racing rules count a penalty turn. A mark rounding that keeps the side (bearing away from starboard upwind to starboard
//! downwind, heading up at a leeward mark) is no manoeuvre; a rounding that changes side is a
//! real tack or gybe and counts.
//!
//! **Distance lost** (metres): against sailing on at the entry VMG,
//! `loss = VMG_entry · (t_end − t_entry) − (d(t_end) − d(t_entry))`, where `d(t)` is the
//! boat's position projected on the wind axis (towards the wind for a tack, away for a gybe;
//! the direction at the crossing, held through the manoeuvre), `t_entry` is where the turn
//! starts (the heading turns faster than [`Settings::turn_rate_deg_s`] from there to the
//! crossing), `VMG_entry` is the mean VMG over the [`Settings::entry_window_s`] before
//! `t_entry` (a chord of positions), and `t_end` is the first time after the turn ends that the
//! boat's VMG is back to `VMG_entry`, at most [`Settings::recovery_cap_s`] later. Since
//! `∫ VMG dt = Δd`, this is the integral of the VMG deficit over the manoeuvre.
//!
//! **Its error** (one sigma, [`Manoeuvre::loss_sigma_m`]): positions enter at three times
//! (`t_entry − E`, `t_entry`, `t_end`), each with the boat's GPS noise σp (from its track:
//! robust spread of second differences / √6), so
//! `σ_pos² = σp² (1 + T/E)² + σp² (T/E)² + σp²` with `T = t_end − t_entry`; the wind's
//! uncertainty σW moves the axis: `σ_wind = |loss(W + σW) − loss(W − σW)| / 2`; the two add in
//! quadrature. A 1 Hz track interpolated by PCHIP adds less than a metre on a 10 m/s boat
//! (tested on closed-form tracks).

use serde::Serialize;

use super::wind::{WindModel, angle_diff, twa_deg};
use crate::track::Boat;

/// Tack or gybe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ManoeuvreKind {
    /// Through head to wind.
    Tack,
    /// Through dead downwind.
    Gybe,
}

/// One tack or gybe.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Manoeuvre {
    pub kind: ManoeuvreKind,
    /// Race seconds at which the TWA crosses 0° (tack) or 180° (gybe).
    pub t: f64,
    /// Where the turn starts and ends, race seconds.
    pub t_entry: f64,
    pub t_exit: f64,
    /// `t_exit − t_entry`, seconds.
    pub duration_s: f64,
    /// Side before: `"starboard"` or `"port"`.
    pub from_side: &'static str,
    /// Mean speed over the entry window, m/s.
    pub entry_speed_mps: f64,
    /// Slowest speed in the manoeuvre, m/s.
    pub min_speed_mps: f64,
    /// Speed at `t_end`, m/s.
    pub exit_speed_mps: f64,
    /// Mean VMG over the entry window, m/s (towards the wind for a tack, away for a gybe).
    pub entry_vmg_mps: f64,
    /// Where the VMG is back to the entry VMG (or the cap), race seconds.
    pub t_end: f64,
    /// Distance lost against sailing on at the entry VMG, metres (see the module docs).
    pub loss_m: f64,
    /// One sigma of `loss_m`, metres.
    pub loss_sigma_m: f64,
}

/// The detector's thresholds. The defaults suit dinghies and F50s alike (tested on both).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Sampling step, seconds.
    pub step_s: f64,
    /// No side within this many degrees of head-to-wind or dead downwind.
    pub margin_deg: f64,
    /// A side must hold this long to count, seconds.
    pub hold_s: f64,
    /// Below this fraction of the boat's median speed it has no side.
    pub min_speed_fraction: f64,
    /// A turn is turning faster than this, degrees per second (heading over ±2 s).
    pub turn_rate_deg_s: f64,
    /// The entry VMG's window, seconds.
    pub entry_window_s: f64,
    /// Longest recovery after the turn counted in the loss, seconds.
    pub recovery_cap_s: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            step_s: 1.0,
            margin_deg: 15.0,
            hold_s: 8.0,
            min_speed_fraction: 0.3,
            turn_rate_deg_s: 4.0,
            entry_window_s: 10.0,
            recovery_cap_s: 30.0,
        }
    }
}

/// Seconds before the span asked for that the sides are read from.
pub const LEAD_IN_S: f64 = 60.0;

/// One run of a side: sign (+1 starboard, −1 port), first and last sample index.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideRun {
    pub side: i8,
    pub first: usize,
    pub last: usize,
}

/// The side of each sample (+1, −1, or 0 for none) from its TWA and whether its speed counts.
pub fn side_of(twa: f64, moving: bool, margin_deg: f64) -> i8 {
    if !moving || !twa.is_finite() {
        return 0;
    }
    let a = twa.abs();
    if a >= margin_deg && a <= 180.0 - margin_deg {
        if twa > 0.0 { 1 } else { -1 }
    } else {
        0
    }
}

/// The kept runs of sides (see the module docs): samples of no side are skipped, runs shorter
/// than `hold_s` dropped, neighbours of one side merged. `times` sorted.
pub fn side_runs(times: &[f64], sides: &[i8], hold_s: f64) -> Vec<SideRun> {
    let mut runs: Vec<SideRun> = Vec::new();
    for (i, &s) in sides.iter().enumerate() {
        if s == 0 {
            continue;
        }
        match runs.last_mut() {
            Some(r) if r.side == s => r.last = i,
            _ => runs.push(SideRun {
                side: s,
                first: i,
                last: i,
            }),
        }
    }
    let dur = |r: &SideRun| times[r.last] - times[r.first];
    let mut kept: Vec<SideRun> = Vec::new();
    for r in runs.into_iter().filter(|r| dur(r) >= hold_s) {
        match kept.last_mut() {
            Some(k) if k.side == r.side => k.last = r.last,
            _ => kept.push(r),
        }
    }
    kept
}

/// The boat's tacks and gybes between race times `from` and `to`.
pub fn detect(
    boat: &Boat,
    wind: &WindModel,
    from: f64,
    to: f64,
    settings: &Settings,
) -> Vec<Manoeuvre> {
    let st = settings;
    if to.partial_cmp(&from) != Some(std::cmp::Ordering::Greater) || boat.fixes().len() < 3 {
        return Vec::new();
    }
    // Look from a minute earlier, so a manoeuvre just after `from` has its side before.
    let (t_keep, from) = (from, (from - LEAD_IN_S).max(boat.time_span().0));
    let n = ((to - from) / st.step_s) as usize + 1;
    let times: Vec<f64> = (0..n).map(|k| from + k as f64 * st.step_s).collect();
    let states: Vec<_> = times.iter().map(|&t| boat.state_at(t)).collect();
    let mut speeds: Vec<f64> = states.iter().map(|s| s.speed_mps).collect();
    let mid = speeds.len() / 2;
    let median = *speeds.select_nth_unstable_by(mid, f64::total_cmp).1;
    let twa: Vec<f64> = times
        .iter()
        .zip(&states)
        .map(|(&t, s)| twa_deg(s.heading_deg, wind.from_deg_at(t)))
        .collect();
    let sides: Vec<i8> = states
        .iter()
        .zip(&twa)
        .map(|(s, &a)| {
            side_of(
                a,
                s.racing && !s.in_gap && s.speed_mps >= st.min_speed_fraction * median,
                st.margin_deg,
            )
        })
        .collect();
    let runs = side_runs(&times, &sides, st.hold_s);
    let sigma_p = position_noise(boat);
    let mut out = Vec::new();
    for w in runs.windows(2) {
        let (a, b) = (w[0], w[1]);
        // The TWA's path from the last sample of one side to the first of the next, unwrapped.
        let mut path = vec![twa[a.last]];
        for k in a.last + 1..=b.first {
            let prev = *path.last().unwrap();
            path.push(prev + angle_diff(twa[k], twa[k - 1]));
        }
        for (boundary, t_c) in crossings(&path, times[a.last], st.step_s) {
            let kind = if (boundary / 180.0).round().rem_euclid(2.0) == 0.0 {
                ManoeuvreKind::Tack
            } else {
                ManoeuvreKind::Gybe
            };
            // The side before this crossing: TWA just below the boundary on the way.
            let before = path[0] + (boundary - path[0]) * 0.999;
            let side = if angle_diff(before, 0.0) > 0.0 { 1 } else { -1 };
            if t_c < t_keep {
                continue;
            }
            if let Some(m) = measure(boat, wind, kind, side, t_c, sigma_p, st) {
                out.push(m);
            }
        }
    }
    out
}

/// The multiples of 180° that an unwrapped TWA path passes net (from its first to its last
/// value), in the order it passes them, each with the time it last passes it (linear between
/// samples `step` apart from `t0`). A wobble that comes back passes nothing; a 360° turn passes
/// one 0° and one 180°, a tack and a gybe (as the racing rules count a penalty turn).
pub fn crossings(path: &[f64], t0: f64, step: f64) -> Vec<(f64, f64)> {
    let (Some(&a0), Some(&a1)) = (path.first(), path.last()) else {
        return Vec::new();
    };
    let up = a1 > a0;
    let (lo, hi) = if up { (a0, a1) } else { (a1, a0) };
    let mut bounds: Vec<f64> = ((lo / 180.0).ceil() as i64..=(hi / 180.0).floor() as i64)
        .map(|k| k as f64 * 180.0)
        .filter(|b| *b > lo && *b < hi)
        .collect();
    if !up {
        bounds.reverse();
    }
    bounds
        .into_iter()
        .map(|b| {
            // The last time it passes: a boat running by the lee crosses 180° back and forth
            // before it settles on the new gybe, and the settling is the gybe.
            let mut t = t0 + (path.len() - 1) as f64 * step;
            for k in (1..path.len()).rev() {
                let (p0, p1) = (path[k - 1] - b, path[k] - b);
                if p0 == 0.0 || p0.signum() != p1.signum() {
                    let f = if p1 == p0 { 0.0 } else { p0 / (p0 - p1) };
                    t = t0 + (k as f64 - 1.0 + f) * step;
                    break;
                }
            }
            (b, t)
        })
        .collect()
}

/// Heading turn rate at t over ±2 s, degrees per second.
fn turn_rate(boat: &Boat, t: f64) -> f64 {
    angle_diff(
        boat.state_at(t + 2.0).heading_deg,
        boat.state_at(t - 2.0).heading_deg,
    )
    .abs()
        / 4.0
}

/// Entry, exit, speeds and the distance lost of a manoeuvre crossing at `t_c`.
fn measure(
    boat: &Boat,
    wind: &WindModel,
    kind: ManoeuvreKind,
    from_side: i8,
    t_c: f64,
    sigma_p: f64,
    st: &Settings,
) -> Option<Manoeuvre> {
    let (f0, f1) = boat.time_span();
    let limit = st.recovery_cap_s;
    let mut t_entry = t_c;
    while t_entry > t_c - limit
        && t_entry - 1.0 > f0
        && turn_rate(boat, t_entry) > st.turn_rate_deg_s
    {
        t_entry -= 1.0;
    }
    let mut t_exit = t_c;
    while t_exit < t_c + limit && t_exit + 1.0 < f1 && turn_rate(boat, t_exit) > st.turn_rate_deg_s
    {
        t_exit += 1.0;
    }
    let e = st.entry_window_s.min(t_entry - f0);
    if e < 2.0 {
        return None;
    }
    let loss_at = |w: f64| loss(boat, kind, w, t_entry, t_exit, e, st);
    let w = wind.from_deg_at(t_c);
    let (loss_m, vmg, t_end) = loss_at(w);
    let span = t_end - t_entry;
    let sigma_pos = sigma_p * ((1.0 + span / e).powi(2) + (span / e).powi(2) + 1.0).sqrt();
    let sw = wind.uncertainty_deg;
    let sigma_wind = 0.5 * (loss_at(w + sw).0 - loss_at(w - sw).0).abs();
    let p0 = boat.state_at(t_entry - e).position;
    let p1 = boat.state_at(t_entry).position;
    let min_speed = (0..=((t_end - t_entry) as usize))
        .map(|k| boat.state_at(t_entry + k as f64).speed_mps)
        .fold(f64::INFINITY, f64::min);
    Some(Manoeuvre {
        kind,
        t: t_c,
        t_entry,
        t_exit,
        duration_s: t_exit - t_entry,
        from_side: if from_side > 0 { "starboard" } else { "port" },
        entry_speed_mps: (p1[0] - p0[0]).hypot(p1[1] - p0[1]) / e,
        min_speed_mps: min_speed,
        exit_speed_mps: boat.state_at(t_end).speed_mps,
        entry_vmg_mps: vmg,
        t_end,
        loss_m,
        loss_sigma_m: sigma_pos.hypot(sigma_wind),
    })
}

/// (loss, entry VMG, t_end) with the wind from `wind_deg` (see the module docs).
fn loss(
    boat: &Boat,
    kind: ManoeuvreKind,
    wind_deg: f64,
    t_entry: f64,
    t_exit: f64,
    e: f64,
    st: &Settings,
) -> (f64, f64, f64) {
    let r = wind_deg.to_radians();
    // Unit vector towards where the wind comes from, race metres [east, south].
    let mut u = [r.sin(), -r.cos()];
    if kind == ManoeuvreKind::Gybe {
        u = [-u[0], -u[1]];
    }
    let d = |t: f64| {
        let p = boat.state_at(t).position;
        p[0] * u[0] + p[1] * u[1]
    };
    let vmg = (d(t_entry) - d(t_entry - e)) / e;
    let (_, f1) = boat.time_span();
    let cap = (t_exit + st.recovery_cap_s).min(f1);
    let mut t_end = t_exit.min(cap);
    while t_end < cap {
        let v = boat.state_at(t_end).velocity;
        if v[0] * u[0] + v[1] * u[1] >= vmg {
            break;
        }
        t_end = (t_end + st.step_s).min(cap);
    }
    let loss = vmg * (t_end - t_entry) - (d(t_end) - d(t_entry));
    (loss, vmg, t_end)
}

/// A boat's GPS position noise, metres (one sigma per axis): the median absolute second
/// difference of evenly spaced fixes, scaled to a sigma (×1.4826) and divided by √6 (a second
/// difference of independent errors has variance 6σ²). Real accelerations only raise it, so
/// it errs high. 1 m where the track has too few even triples.
pub fn position_noise(boat: &Boat) -> f64 {
    let f = boat.fixes();
    let mut d: Vec<f64> = f
        .windows(3)
        .filter(|w| ((w[2].t - w[1].t) - (w[1].t - w[0].t)).abs() < 1e-3)
        .flat_map(|w| {
            [
                (w[2].x - 2.0 * w[1].x + w[0].x).abs(),
                (w[2].z - 2.0 * w[1].z + w[0].z).abs(),
            ]
        })
        .collect();
    if d.len() < 20 {
        return 1.0;
    }
    let mid = d.len() / 2;
    let mad = *d.select_nth_unstable_by(mid, f64::total_cmp).1;
    1.4826 * mad / 6f64.sqrt()
}
