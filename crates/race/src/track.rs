//! One boat's cleaned track and its state at any time: shape-preserving (PCHIP) position,
//! smoothed velocity and heading, heel where logged. Queries are a binary search and a few
//! flops: O(log n), no allocation.

use serde::Serialize;

/// One cleaned sample: race time (s since the start) and race metres (x east, z south).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fix {
    pub t: f64,
    pub x: f64,
    pub z: f64,
}

impl Fix {
    pub fn pos(&self) -> [f64; 2] {
        [self.x, self.z]
    }
}

/// Half-width of the centred window that smooths velocity and heading, seconds. A 1 Hz GPS
/// jitters by a metre or so; over a 4 s window that turns the heading by a few degrees instead
/// of spinning the boat, while a 10 s tack still shows.
pub const SMOOTH_HALF_WINDOW_S: f64 = 2.0;
/// Below this smoothed speed the heading is held: a drifting boat's GPS noise has no direction.
pub const HEADING_HOLD_SPEED_MPS: f64 = 0.25;

/// Per-sample derived values, kept beside the fixes so `Boat::fixes` stays a plain
/// `&[Fix]` for the wakes. f32 is ample: slopes and velocities are below 100 m/s, so the
/// rounding is < 1e-5 m/s (position error < 1e-4 m over a 10 s interval, and the interpolant
/// is clamped to the interval's samples anyway), headings < 1e-5 degrees.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Derived {
    /// PCHIP slopes dx/dt, dz/dt at the sample, m/s.
    mx: f32,
    mz: f32,
    /// Smoothed velocity (centred secant over the window), m/s.
    vx: f32,
    vz: f32,
    /// Smoothed or logged heading, compass degrees [0, 360).
    heading: f32,
    /// Heel, degrees; NaN where not logged.
    heel: f32,
    /// Metres sailed from the first fix to this one (straight lines; gaps count as their chord).
    sailed: f64,
    /// The interval from this sample to the next is a gap: not drawn, not interpolated smoothly.
    gap_after: bool,
}

/// A boat's state at one race time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoatState {
    /// Race metres `[x east, z south]`.
    pub position: [f64; 2],
    /// Metres per second, `[east, south]`: smoothed over ±2 s.
    pub velocity: [f64; 2],
    /// |velocity|, m/s.
    pub speed_mps: f64,
    /// Compass bearing of the bow, degrees in [0, 360): 0 north, 90 east. The logged heading
    /// where the file has one, else the smoothed course over ground.
    pub heading_deg: f64,
    /// Heel, degrees (positive to starboard as logged), where the file logs it.
    pub heel_deg: Option<f64>,
    /// False before the first fix and after the last (the boat is held at its end fix).
    pub racing: bool,
    /// True inside a gap in the data: the position is a straight line across the gap, and a
    /// renderer should not draw the boat or its wake through it.
    pub in_gap: bool,
    /// Metres sailed since the first fix.
    pub sailed_m: f64,
}

/// Compass bearing (degrees, [0, 360)) of a race-metre vector `[east, south]`.
pub fn bearing_deg(v: [f64; 2]) -> f64 {
    let b = v[0].atan2(-v[1]).to_degrees();
    if b < 0.0 { b + 360.0 } else { b }
}

/// Interpolate an angle in degrees along the shorter arc.
fn lerp_deg(a: f64, b: f64, s: f64) -> f64 {
    let d = (b - a + 540.0).rem_euclid(360.0) - 180.0;
    (a + s * d).rem_euclid(360.0)
}

/// A boat: identity, cleaned fixes and what is derived from them.
#[derive(Debug, Clone)]
pub struct Boat {
    pub id: String,
    pub name: String,
    /// `#rrggbb`.
    pub color: String,
    fixes: Vec<Fix>,
    derived: Vec<Derived>,
    /// Time buckets: `bucket[k]` is the last fix at or before `t0 + k / inv_w`, so a query
    /// searches only the few fixes of its bucket (a binary search over the whole track touches
    /// ~17 cache lines of a 3-hour 10 Hz log; this touches 2–3).
    bucket: Vec<u32>,
    inv_w: f64,
    /// Time each course mark was rounded (index = position in the course), `None` if not (yet).
    pub(crate) roundings: Vec<Option<f64>>,
}

/// Per-sample inputs that come from the log rather than the positions.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Logged {
    /// Degrees or NaN.
    pub heading: f32,
    /// Degrees or NaN.
    pub heel: f32,
}

impl Boat {
    /// Build from cleaned fixes (sorted, strictly increasing t, finite) with the gap flags
    /// (`gap_after[i]`: no interpolation between fix i and i + 1) and the logged extras.
    pub(crate) fn build(
        id: String,
        name: String,
        color: String,
        fixes: Vec<Fix>,
        gap_after: Vec<bool>,
        logged: Vec<Logged>,
    ) -> Boat {
        let n = fixes.len();
        debug_assert_eq!(gap_after.len(), n);
        debug_assert_eq!(logged.len(), n);
        let mut derived = vec![
            Derived {
                mx: 0.0,
                mz: 0.0,
                vx: 0.0,
                vz: 0.0,
                heading: 0.0,
                heel: f32::NAN,
                sailed: 0.0,
                gap_after: false,
            };
            n
        ];
        // Segments: runs of fixes without a gap inside.
        let mut start = 0;
        for (i, &gap) in gap_after.iter().enumerate() {
            if gap || i + 1 == n {
                let seg = start..i + 1;
                let ts: Vec<f64> = fixes[seg.clone()].iter().map(|f| f.t).collect();
                let xs: Vec<f64> = fixes[seg.clone()].iter().map(|f| f.x).collect();
                let zs: Vec<f64> = fixes[seg.clone()].iter().map(|f| f.z).collect();
                let mx = pchip_slopes(&ts, &xs);
                let mz = pchip_slopes(&ts, &zs);
                for (k, j) in seg.clone().enumerate() {
                    derived[j].mx = mx[k] as f32;
                    derived[j].mz = mz[k] as f32;
                }
                smooth_velocity(&fixes[seg.clone()], &mut derived[seg]);
                start = i + 1;
            }
        }
        let mut sailed = 0.0;
        let mut held = f64::NAN;
        for i in 0..n {
            if i > 0 {
                sailed += (fixes[i].x - fixes[i - 1].x).hypot(fixes[i].z - fixes[i - 1].z);
            }
            let d = &mut derived[i];
            d.sailed = sailed;
            d.gap_after = gap_after[i];
            d.heel = logged[i].heel;
            let v = [d.vx as f64, d.vz as f64];
            let h = if logged[i].heading.is_finite() {
                (logged[i].heading as f64).rem_euclid(360.0)
            } else if v[0].hypot(v[1]) >= HEADING_HOLD_SPEED_MPS || held.is_nan() {
                bearing_deg(v)
            } else {
                held
            };
            held = h;
            d.heading = h as f32;
        }
        // A drifting start has no heading yet: take the first heading the boat shows.
        if let Some(first) = derived
            .iter()
            .position(|d| (d.vx as f64).hypot(d.vz as f64) >= HEADING_HOLD_SPEED_MPS)
        {
            let h = derived[first].heading;
            for (d, l) in derived[..first].iter_mut().zip(&logged) {
                if !l.heading.is_finite() {
                    d.heading = h;
                }
            }
        }
        let (bucket, inv_w) = bucket_index(&fixes);
        Boat {
            id,
            name,
            color,
            fixes,
            derived,
            bucket,
            inv_w,
            roundings: Vec::new(),
        }
    }

    /// The cleaned samples (race seconds, race metres), sorted by time; for wakes and plots.
    pub fn fixes(&self) -> &[Fix] {
        &self.fixes
    }

    /// The fixes with `t0 <= t <= t1` (a wake needs only the last minute or so): two binary
    /// searches, no copy.
    pub fn fixes_between(&self, t0: f64, t1: f64) -> &[Fix] {
        let a = self.fixes.partition_point(|f| f.t < t0);
        let b = self.fixes.partition_point(|f| f.t <= t1);
        if a < b { &self.fixes[a..b] } else { &[] }
    }

    /// Indices `i` where the data has a gap between fix `i` and `i + 1`.
    pub fn gaps(&self) -> impl Iterator<Item = usize> + '_ {
        self.derived
            .iter()
            .enumerate()
            .filter(|(_, d)| d.gap_after)
            .map(|(i, _)| i)
    }

    /// Whether the interval after fix `i` is a gap.
    pub fn gap_after(&self, i: usize) -> bool {
        self.derived.get(i).is_some_and(|d| d.gap_after)
    }

    /// Whether the file logged heel for this boat.
    pub fn has_heel(&self) -> bool {
        self.derived.iter().any(|d| d.heel.is_finite())
    }

    /// First and last fix time, seconds.
    pub fn time_span(&self) -> (f64, f64) {
        match (self.fixes.first(), self.fixes.last()) {
            (Some(a), Some(b)) => (a.t, b.t),
            _ => (0.0, 0.0),
        }
    }

    /// Time each course mark was rounded (index = position in the race's course).
    pub fn roundings(&self) -> &[Option<f64>] {
        &self.roundings
    }

    /// Metres sailed since the first fix, at time t.
    pub fn sailed_at(&self, t: f64) -> f64 {
        self.state_at(t).sailed_m
    }

    /// State at race time `t`: O(log n), no allocation. Before the first fix and after the last
    /// the boat is held there with `racing = false`.
    pub fn state_at(&self, t: f64) -> BoatState {
        let n = self.fixes.len();
        if n == 0 {
            return BoatState {
                position: [0.0, 0.0],
                velocity: [0.0, 0.0],
                speed_mps: 0.0,
                heading_deg: 0.0,
                heel_deg: None,
                racing: false,
                in_gap: false,
                sailed_m: 0.0,
            };
        }
        let first = &self.fixes[0];
        let last = &self.fixes[n - 1];
        if !(t >= first.t && t <= last.t) || n == 1 {
            // NaN t lands here too: hold the nearer end.
            let i = if t > last.t { n - 1 } else { 0 };
            let mut s = self.sample_state(i);
            s.racing = n == 1 && t == first.t;
            s.velocity = [0.0, 0.0];
            s.speed_mps = 0.0;
            return s;
        }
        // i: last fix with t_i <= t (i < n - 1 unless t == last.t).
        let i = self.index_at(t);
        if i == n - 1 {
            return self.sample_state(i);
        }
        let (f0, f1) = (&self.fixes[i], &self.fixes[i + 1]);
        let (d0, d1) = (&self.derived[i], &self.derived[i + 1]);
        let h = f1.t - f0.t;
        let s = (t - f0.t) / h;
        let chord = (f1.x - f0.x).hypot(f1.z - f0.z);
        let sailed = d0.sailed + s * chord;
        if d0.gap_after {
            // Straight across the gap, flagged so the renderer does not draw it.
            let v = [(f1.x - f0.x) / h, (f1.z - f0.z) / h];
            return BoatState {
                position: [f0.x + s * (f1.x - f0.x), f0.z + s * (f1.z - f0.z)],
                velocity: v,
                speed_mps: v[0].hypot(v[1]),
                heading_deg: lerp_deg(d0.heading as f64, d1.heading as f64, s),
                heel_deg: None,
                racing: true,
                in_gap: true,
                sailed_m: sailed,
            };
        }
        let x = hermite(f0.x, f1.x, d0.mx as f64, d1.mx as f64, h, s);
        let z = hermite(f0.z, f1.z, d0.mz as f64, d1.mz as f64, h, s);
        let v = [
            d0.vx as f64 + s * (d1.vx as f64 - d0.vx as f64),
            d0.vz as f64 + s * (d1.vz as f64 - d0.vz as f64),
        ];
        let heel = if d0.heel.is_finite() && d1.heel.is_finite() {
            Some(d0.heel as f64 + s * (d1.heel as f64 - d0.heel as f64))
        } else if d0.heel.is_finite() {
            Some(d0.heel as f64)
        } else {
            None
        };
        BoatState {
            position: [x, z],
            velocity: v,
            speed_mps: v[0].hypot(v[1]),
            heading_deg: lerp_deg(d0.heading as f64, d1.heading as f64, s),
            heel_deg: heel,
            racing: true,
            in_gap: false,
            sailed_m: sailed,
        }
    }

    /// The last fix with `t_i <= t`, for `t` within the track: bucket, then binary search
    /// inside it (O(log n) in the worst case, a few comparisons for regular sampling).
    fn index_at(&self, t: f64) -> usize {
        let nb = self.bucket.len();
        let k = (((t - self.fixes[0].t) * self.inv_w) as usize).min(nb - 1);
        let lo = self.bucket[k] as usize;
        let hi = if k + 1 < nb {
            self.bucket[k + 1] as usize + 1
        } else {
            self.fixes.len()
        };
        let mut i = (lo + self.fixes[lo..hi].partition_point(|f| f.t <= t)).saturating_sub(1);
        // Rounding of the bucket edges can leave the answer one fix outside the bucket.
        while i > 0 && self.fixes[i].t > t {
            i -= 1;
        }
        while i + 1 < self.fixes.len() && self.fixes[i + 1].t <= t {
            i += 1;
        }
        i
    }

    fn sample_state(&self, i: usize) -> BoatState {
        let f = &self.fixes[i];
        let d = &self.derived[i];
        let v = [d.vx as f64, d.vz as f64];
        BoatState {
            position: [f.x, f.z],
            velocity: v,
            speed_mps: v[0].hypot(v[1]),
            heading_deg: d.heading as f64,
            heel_deg: d.heel.is_finite().then_some(d.heel as f64),
            racing: true,
            in_gap: false,
            sailed_m: d.sailed,
        }
    }

    /// Bytes held per sample (fix + derived values), for the scale benchmark.
    /// (The time buckets add 1 byte per sample: one u32 per 4 fixes.)
    pub const BYTES_PER_SAMPLE: usize =
        std::mem::size_of::<Fix>() + std::mem::size_of::<Derived>() + 1;
}

/// One bucket per 4 fixes, evenly over the track's time span.
fn bucket_index(fixes: &[Fix]) -> (Vec<u32>, f64) {
    let n = fixes.len();
    if n < 2 {
        return (vec![0], 0.0);
    }
    let (t0, t1) = (fixes[0].t, fixes[n - 1].t);
    let nb = n / 4 + 1;
    let inv_w = nb as f64 / (t1 - t0);
    let mut bucket = Vec::with_capacity(nb);
    let mut i = 0;
    for k in 0..nb {
        let edge = t0 + k as f64 / inv_w;
        while i + 1 < n && fixes[i + 1].t <= edge {
            i += 1;
        }
        bucket.push(i as u32);
    }
    (bucket, inv_w)
}

/// Cubic Hermite on one interval of width h at s ∈ [0, 1], clamped to the interval's end
/// values. PCHIP slopes already keep each interval monotone between its ends (Fritsch and
/// Carlson 1980), so the clamp only removes f32 rounding of the slopes: no overshoot, ever.
pub fn hermite(p0: f64, p1: f64, m0: f64, m1: f64, h: f64, s: f64) -> f64 {
    let s2 = s * s;
    let s3 = s2 * s;
    let v = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
        + (s3 - 2.0 * s2 + s) * h * m0
        + (-2.0 * s3 + 3.0 * s2) * p1
        + (s3 - s2) * h * m1;
    v.clamp(p0.min(p1), p0.max(p1))
}

/// PCHIP slopes (Fritsch–Carlson with the Fritsch–Butland weighted harmonic mean, as in
/// SciPy's `PchipInterpolator`): zero at local extrema and where either side is flat, so the
/// interpolant is monotone on every interval and never passes beyond a sample.
pub fn pchip_slopes(t: &[f64], y: &[f64]) -> Vec<f64> {
    let n = t.len();
    let mut m = vec![0.0; n];
    if n < 2 {
        return m;
    }
    let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
    if n == 2 {
        m[0] = d[0];
        m[1] = d[0];
        return m;
    }
    for k in 1..n - 1 {
        if d[k - 1] * d[k] <= 0.0 {
            m[k] = 0.0;
        } else {
            let w1 = 2.0 * h[k] + h[k - 1];
            let w2 = h[k] + 2.0 * h[k - 1];
            m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
        }
    }
    m[0] = pchip_end(h[0], h[1], d[0], d[1]);
    m[n - 1] = pchip_end(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
    m
}

/// The one-sided three-point end slope, limited to keep the end interval monotone.
fn pchip_end(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if m.signum() != d0.signum() || d0 == 0.0 {
        0.0
    } else if d0.signum() != d1.signum() && m.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        m
    }
}

/// Centred secant velocity over ±SMOOTH_HALF_WINDOW_S within one segment (two pointers, O(n)).
fn smooth_velocity(fixes: &[Fix], out: &mut [Derived]) {
    let n = fixes.len();
    if n < 2 {
        return;
    }
    let (mut lo, mut hi) = (0usize, 0usize);
    for k in 0..n {
        let t = fixes[k].t;
        while fixes[lo].t < t - SMOOTH_HALF_WINDOW_S {
            lo += 1;
        }
        while hi + 1 < n && fixes[hi + 1].t <= t + SMOOTH_HALF_WINDOW_S {
            hi += 1;
        }
        // At least one neighbour on some side, even when samples are sparser than the window.
        let (a, b) = if lo == hi {
            if k + 1 < n { (k, k + 1) } else { (k - 1, k) }
        } else {
            (lo, hi)
        };
        let dt = fixes[b].t - fixes[a].t;
        out[k].vx = ((fixes[b].x - fixes[a].x) / dt) as f32;
        out[k].vz = ((fixes[b].z - fixes[a].z) / dt) as f32;
    }
}
