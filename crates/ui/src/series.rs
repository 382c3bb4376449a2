//! Time series of the selected boats for the plots: speed and VMG over race time, and the gap
//! between two boats (metres of course and seconds). Pure computation on the race, no egui, so
//! the numbers are tested against the race's own roundings.

use race::{BoatState, Race, RankBasis, Standing};

use crate::leaderboard::KNOTS_PER_MPS;

/// Samples a plot takes over the race (a 40-minute race: one every 4 s).
pub const PLOT_SAMPLES: usize = 600;

/// At most this many samples of the ranking for the gap in seconds (1 s apart, fewer for
/// long races).
const GAP_GRID_MAX: f64 = 20_000.0;

/// Velocity made good towards or away from the wind, m/s (positive either way): the part of
/// `velocity` (race metres per second, `[east, south]`) along the wind's axis, for a wind
/// from `from_deg` (compass).
pub fn vmg_mps(velocity: [f64; 2], from_deg: f64) -> f64 {
    let a = from_deg.to_radians();
    // Unit vector towards where the wind comes from, in [east, south].
    let up = [a.sin(), -a.cos()];
    (velocity[0] * up[0] + velocity[1] * up[1]).abs()
}

/// `n` race times spread evenly over `span`, both ends included.
pub fn sample_times(span: (f64, f64), n: usize) -> Vec<f64> {
    let n = n.max(2);
    let (a, b) = span;
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

/// One boat's speed (and VMG, where the race states its wind) over race time, knots, only
/// where the boat is racing and not inside a gap in its data.
#[derive(Clone, Debug, PartialEq)]
pub struct BoatSeries {
    pub boat: usize,
    pub speed_kn: Vec<[f64; 2]>,
    pub vmg_kn: Option<Vec<[f64; 2]>>,
}

/// [`BoatSeries`] of `boat` at [`PLOT_SAMPLES`] times over the race.
pub fn boat_series(race: &Race, boat: usize) -> BoatSeries {
    let b = &race.boats[boat];
    let mut speed = Vec::with_capacity(PLOT_SAMPLES);
    let mut vmg = Vec::with_capacity(PLOT_SAMPLES);
    for t in sample_times(race.time_span(), PLOT_SAMPLES) {
        let s = b.state_at(t);
        if !s.racing || s.in_gap {
            continue;
        }
        speed.push([t, s.speed_mps * KNOTS_PER_MPS]);
        if let Some(w) = race.wind {
            vmg.push([t, vmg_mps(s.velocity, w.from_deg) * KNOTS_PER_MPS]);
        }
    }
    BoatSeries {
        boat,
        speed_kn: speed,
        vmg_kn: race.wind.map(|_| vmg),
    }
}

/// The gap from boat `a` back to boat `b` at one race time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GapSample {
    pub t: f64,
    /// Course metres `b` has still to sail more than `a` (negative: `b` is ahead).
    pub metres: f64,
    /// How long the boat behind took to reach the course position the one ahead had at `t`;
    /// positive when `b` is behind. `None` when it never got there in the data.
    pub seconds: Option<f64>,
}

/// Each boat's course metres still to sail on a regular grid of race time.
struct RemainingGrid {
    t0: f64,
    step: f64,
    /// `remaining[boat][i]` at `t0 + i × step`.
    remaining: [Vec<f64>; 2],
}

impl RemainingGrid {
    fn new(race: &Race, boats: [usize; 2]) -> Self {
        let (t0, t1) = race.time_span();
        let step = ((t1 - t0) / GAP_GRID_MAX).max(1.0);
        let n = ((t1 - t0) / step).floor() as usize + 1;
        let mut states: Vec<BoatState> = Vec::new();
        let mut standings: Vec<Standing> = Vec::new();
        let mut remaining = [Vec::with_capacity(n), Vec::with_capacity(n)];
        for i in 0..n {
            let t = t0 + i as f64 * step;
            race.states_at(t, &mut states);
            race.standings_into(t, &states, &mut standings);
            for (k, &boat) in boats.iter().enumerate() {
                let r = standings
                    .iter()
                    .find(|s| s.boat == boat)
                    .and_then(|s| s.remaining_m)
                    .unwrap_or(f64::NAN);
                remaining[k].push(r);
            }
        }
        Self {
            t0,
            step,
            remaining,
        }
    }

    fn at(&self, k: usize, t: f64) -> f64 {
        let i = ((t - self.t0) / self.step).round().max(0.0) as usize;
        self.remaining[k]
            .get(i.min(self.remaining[k].len().saturating_sub(1)))
            .copied()
            .unwrap_or(f64::NAN)
    }

    /// The first grid time at or after `t` when boat `k` has at most `target` metres to sail.
    fn reaches(&self, k: usize, t: f64, target: f64) -> Option<f64> {
        let i0 = ((t - self.t0) / self.step).ceil().max(0.0) as usize;
        (i0..self.remaining[k].len())
            .find(|&i| self.remaining[k][i] <= target)
            .map(|i| self.t0 + i as f64 * self.step)
    }
}

/// The gap from `a` back to `b` at [`PLOT_SAMPLES`] times over the race, from the start
/// signal on; empty without a course (no course position to compare).
pub fn gap_series(race: &Race, a: usize, b: usize) -> Vec<GapSample> {
    if race.rank_basis() != RankBasis::Course || a == b {
        return Vec::new();
    }
    let grid = RemainingGrid::new(race, [a, b]);
    let (t0, t1) = race.time_span();
    sample_times((t0.max(0.0), t1), PLOT_SAMPLES)
        .into_iter()
        .filter_map(|t| gap_at(&grid, t))
        .collect()
}

/// The gap between the grid's two boats at `t`, if both are on the course.
fn gap_at(grid: &RemainingGrid, t: f64) -> Option<GapSample> {
    let (ra, rb) = (grid.at(0, t), grid.at(1, t));
    if !(ra.is_finite() && rb.is_finite()) {
        return None;
    }
    let metres = rb - ra;
    let seconds = if metres >= 0.0 {
        grid.reaches(1, t, ra).map(|tb| tb - t)
    } else {
        grid.reaches(0, t, rb).map(|ta| -(ta - t))
    };
    Some(GapSample { t, metres, seconds })
}

/// The sample of `gaps` nearest to race time `t` (the panel's headline number), if any lies
/// within `tolerance` seconds.
pub fn gap_near(gaps: &[GapSample], t: f64, tolerance: f64) -> Option<GapSample> {
    gaps.iter()
        .min_by(|p, q| (p.t - t).abs().total_cmp(&(q.t - t).abs()))
        .filter(|g| (g.t - t).abs() <= tolerance)
        .copied()
}
