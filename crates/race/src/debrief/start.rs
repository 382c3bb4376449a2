//! The start at the gun (race time 0): each boat's distance to the line, position along it,
//! speed, time to the line, whether it was over early; the line's bias to the wind.
//!
//! The line is the course's first element when it is a start line with two ends. Which end is
//! the pin: the left-hand end looking upwind (the committee boat is conventionally at the
//! starboard end). The course side is the side of the first mark, or upwind where the course
//! has no first mark.

use serde::Serialize;

use super::wind::WindModel;
use crate::{MarkKind, Race};

/// One boat at the gun.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoatStart {
    pub boat: String,
    /// Perpendicular distance to the line at the gun, metres: positive on the pre-start side,
    /// negative over it (on the course side).
    pub distance_to_line_m: f64,
    /// Distance to the segment between the ends, metres (equals |distance_to_line_m| between
    /// the ends); what SailGP's `PC_DTL_m` measures is of this kind.
    pub distance_to_segment_m: f64,
    /// Where along the line, 0 % at the pin, 100 % at the committee end (outside 0–100 beyond
    /// the ends).
    pub along_line_pct: f64,
    /// Speed at the gun, m/s.
    pub speed_mps: f64,
    /// Seconds to reach the line at the gun's speed straight towards it (None when not moving
    /// towards it); the time the boat was late.
    pub time_to_line_s: Option<f64>,
    /// On the course side at the gun.
    pub over_early: bool,
    /// First time at or after the gun that the boat crosses the line between the ends from the
    /// pre-start side, race seconds (None if never, in its track).
    pub crossed_s: Option<f64>,
}

/// The start report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StartReport {
    /// Race metres `[x, z]` of the pin and the committee end.
    pub pin: [f64; 2],
    pub committee: [f64; 2],
    pub line_length_m: f64,
    /// Degrees the line is off square to the wind; positive: the pin end is upwind (favoured).
    pub bias_deg: f64,
    /// How much further upwind the favoured end is, metres (the sign as `bias_deg`).
    pub bias_m: f64,
    /// The wind direction used, degrees, and whether measured or estimated.
    pub wind_from_deg: f64,
    pub wind_source: super::wind::WindSource,
    pub boats: Vec<BoatStart>,
}

/// The start line in race metres, oriented: pin and committee ends, the unit vector along it
/// (pin to committee) and the unit normal towards the course side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartLine {
    pub pin: [f64; 2],
    pub committee: [f64; 2],
    pub along: [f64; 2],
    pub normal: [f64; 2],
    pub length_m: f64,
    /// The wind direction at the gun that oriented it, degrees.
    pub wind_from_deg: f64,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

impl StartLine {
    /// The race's start line, where the course begins with one; `Err` says why not.
    pub fn of(race: &Race, wind: Option<&WindModel>) -> Result<StartLine, String> {
        let Some(&first) = race.course.first() else {
            return Err("the race has no course".into());
        };
        let line = &race.marks[first];
        let (MarkKind::StartLine, Some([e0, e1])) = (line.kind, line.ends) else {
            return Err(format!(
                "the course starts at {}, which is no start line with two ends",
                line.name
            ));
        };
        let Some(wind) = wind else {
            return Err("the race has no wind, measured or estimated".into());
        };
        let wdeg = wind.from_deg_at(0.0);
        let r = wdeg.to_radians();
        let up = [r.sin(), -r.cos()];
        // Looking upwind, left: facing north (up = [0, -1] in [east, south]) left is west,
        // [-1, 0] = [up.z, -up.x].
        let left = [up[1], -up[0]];
        let (pin, committee) = if dot(e0, left) >= dot(e1, left) {
            (e0, e1)
        } else {
            (e1, e0)
        };
        let d = [committee[0] - pin[0], committee[1] - pin[1]];
        let len = d[0].hypot(d[1]);
        if len < 1.0 {
            return Err(format!("the start line {} is shorter than 1 m", line.name));
        }
        let along = [d[0] / len, d[1] / len];
        let mut normal = [-along[1], along[0]];
        let course_point = race
            .course
            .get(1)
            .map(|&m| race.marks[m].position)
            .unwrap_or([pin[0] + 1e3 * up[0], pin[1] + 1e3 * up[1]]);
        if dot([course_point[0] - pin[0], course_point[1] - pin[1]], normal) < 0.0 {
            normal = [-normal[0], -normal[1]];
        }
        Ok(StartLine {
            pin,
            committee,
            along,
            normal,
            length_m: len,
            wind_from_deg: wdeg,
        })
    }

    /// Signed distance of a point to the line, metres: positive on the course side.
    pub fn course_side_m(&self, p: [f64; 2]) -> f64 {
        dot([p[0] - self.pin[0], p[1] - self.pin[1]], self.normal)
    }

    /// Distance from a point to the segment between the ends, metres.
    pub fn segment_distance_m(&self, p: [f64; 2]) -> f64 {
        let rel = [p[0] - self.pin[0], p[1] - self.pin[1]];
        let s = dot(rel, self.along).clamp(0.0, self.length_m);
        (rel[0] - s * self.along[0]).hypot(rel[1] - s * self.along[1])
    }

    /// One boat against the line at race time t (the gun is t = 0).
    pub fn boat_at(&self, b: &crate::Boat, t: f64) -> BoatStart {
        let s = b.state_at(t);
        let over = self.course_side_m(s.position);
        let rel = [s.position[0] - self.pin[0], s.position[1] - self.pin[1]];
        let towards = -dot(s.velocity, self.normal) * over.signum();
        BoatStart {
            boat: b.id.clone(),
            distance_to_line_m: -over,
            distance_to_segment_m: self.segment_distance_m(s.position),
            along_line_pct: 100.0 * dot(rel, self.along) / self.length_m,
            speed_mps: s.speed_mps,
            time_to_line_s: (towards > 0.05).then(|| over.abs() / towards),
            over_early: over > 0.0 && s.racing,
            crossed_s: self.crossing(b),
        }
    }

    /// First crossing of the segment from the pre-start side to the course side at t ≥ 0.
    fn crossing(&self, b: &crate::Boat) -> Option<f64> {
        let (pin, len) = (self.pin, self.length_m);
        let side = |p: [f64; 2]| self.course_side_m(p);
        let along = |p: [f64; 2]| dot([p[0] - pin[0], p[1] - pin[1]], self.along);
        let f = b.fixes();
        let i0 = f.partition_point(|x| x.t < 0.0).saturating_sub(1);
        // Start from the gun's own position so a boat over at the gun must come back first.
        let mut prev = (0.0f64.max(f.first()?.t), b.state_at(0.0).position);
        for x in &f[i0..] {
            if x.t <= prev.0 {
                continue;
            }
            let (s0, s1) = (side(prev.1), side(x.pos()));
            if s0 <= 0.0 && s1 > 0.0 {
                let k = s0 / (s0 - s1);
                let p = [
                    prev.1[0] + k * (x.x - prev.1[0]),
                    prev.1[1] + k * (x.z - prev.1[1]),
                ];
                let a = along(p);
                if (0.0..=len).contains(&a) {
                    return Some(prev.0 + k * (x.t - prev.0));
                }
            }
            prev = (x.t, x.pos());
        }
        None
    }
}

/// The start report, where the course begins with a start line; `Err` says why not.
pub fn start_report(race: &Race, wind: Option<&WindModel>) -> Result<StartReport, String> {
    let line = StartLine::of(race, wind)?;
    let wind = wind.expect("StartLine::of needs a wind");
    let r = line.wind_from_deg.to_radians();
    let up = [r.sin(), -r.cos()];
    let bias_m = dot(
        [
            line.pin[0] - line.committee[0],
            line.pin[1] - line.committee[1],
        ],
        up,
    );
    let bias_deg = (bias_m / line.length_m)
        .clamp(-1.0, 1.0)
        .asin()
        .to_degrees();
    Ok(StartReport {
        pin: line.pin,
        committee: line.committee,
        line_length_m: line.length_m,
        bias_deg,
        bias_m,
        wind_from_deg: line.wind_from_deg,
        wind_source: wind.source,
        boats: race
            .boats
            .iter()
            .filter(|b| !b.fixes().is_empty())
            .map(|b| line.boat_at(b, 0.0))
            .collect(),
    })
}
