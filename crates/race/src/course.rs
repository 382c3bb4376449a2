//! The course: marks in rounding order, legs, rounding detection and the leaderboard.
//!
//! `course[0]` is the start: every boat passes it at the start signal (t = 0, or its first fix
//! if later). Each later mark is rounded at the moment of closest approach during the boat's
//! first visit inside the rounding radius after it rounded the previous mark.

use serde::Serialize;

use crate::track::{Boat, BoatState};

/// What a course element is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum MarkKind {
    /// One buoy.
    #[default]
    Mark,
    /// Two buoys; a boat rounds either (or sails through between them).
    Gate,
    /// The start line between two marks.
    StartLine,
    /// The finish line between two marks.
    FinishLine,
    /// Where the fleet was at the start signal: the course's start when a file lists marks
    /// but no course and no start line.
    FleetStart,
}

/// A course mark in race metres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mark {
    pub name: String,
    /// `[x east, z south]`, metres; the middle of a gate or line.
    pub position: [f64; 2],
    #[serde(default)]
    pub kind: MarkKind,
    /// A gate's or line's two buoys, metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ends: Option<[[f64; 2]; 2]>,
    /// The rounding side as the file states it ("Port", "Starboard", "SP", "PS").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rounding: Option<String>,
}

impl Mark {
    /// A single buoy.
    pub fn buoy(name: impl Into<String>, position: [f64; 2]) -> Mark {
        Mark {
            name: name.into(),
            position,
            kind: MarkKind::Mark,
            ends: None,
            rounding: None,
        }
    }

    /// Distance from `p` to the mark: to the buoy, or to the segment between a gate's or a
    /// line's two buoys (a boat through a gate is at distance 0).
    pub fn distance(&self, p: [f64; 2]) -> f64 {
        match self.ends {
            None => dist(p, self.position),
            Some([a, b]) => {
                let d = [b[0] - a[0], b[1] - a[1]];
                let len2 = d[0] * d[0] + d[1] * d[1];
                let s = if len2 > 0.0 {
                    (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                dist(p, [a[0] + s * d[0], a[1] + s * d[1]])
            }
        }
    }

    /// The buoys to draw: one, or a gate's or line's two; none for the fleet's start.
    pub fn buoys(&self) -> Vec<[f64; 2]> {
        match (self.kind, self.ends) {
            (MarkKind::FleetStart, _) => Vec::new(),
            (_, Some([a, b])) => vec![a, b],
            (_, None) => vec![self.position],
        }
    }
}

/// A boat's place at one time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Standing {
    /// Index into `Race::boats`.
    pub boat: usize,
    /// 1 = leading.
    pub rank: usize,
    /// Course marks passed (the start counts once the boat is racing).
    pub legs_completed: usize,
    /// Course distance behind the leader, metres (0 for the leader).
    pub distance_m: f64,
    /// Course distance still to sail (to the next mark, then leg by leg); `None` without a course.
    pub remaining_m: Option<f64>,
    pub finished: bool,
    pub racing: bool,
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The rounding radius for a course: 5 % of its shortest leg, and at least five times the
/// fleet's median step between fixes, between 15 m and 80 m. GPS on a dinghy passes a buoy at
/// 5–20 m; an F50 moves ~15 m between its 1 Hz fixes and rounds a single mark wide: in SailGP
/// Auckland race 5 the boats pass M1 at 27–64 m (ESP) and their own logs count the rounding.
/// Gates and lines are measured to the segment between their buoys, so a boat through a gate
/// is at 0 m whatever the radius.
pub fn rounding_radius(marks: &[Mark], course: &[usize], typical_step_m: f64) -> f64 {
    let shortest = course
        .windows(2)
        .map(|w| dist(marks[w[0]].position, marks[w[1]].position))
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    let step = if typical_step_m.is_finite() {
        5.0 * typical_step_m
    } else {
        0.0
    };
    if shortest.is_finite() {
        (0.05 * shortest).max(step).clamp(15.0, 80.0)
    } else {
        30.0
    }
}

/// The median distance between successive fixes of every boat (at most 10,000 steps looked
/// at per boat), metres; NaN without steps.
pub fn typical_step(boats: &[Boat]) -> f64 {
    let mut d: Vec<f64> = boats
        .iter()
        .flat_map(|b| {
            let f = b.fixes();
            let every = (f.len() / 10_000).max(1);
            f.windows(2)
                .step_by(every)
                .map(|w| dist(w[0].pos(), w[1].pos()))
        })
        .collect();
    if d.is_empty() {
        return f64::NAN;
    }
    let mid = d.len() / 2;
    *d.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// Times a boat passed each course mark (see the module docs).
pub(crate) fn detect_roundings(
    boat: &Boat,
    marks: &[Mark],
    course: &[usize],
    radius: f64,
) -> Vec<Option<f64>> {
    let mut out = vec![None; course.len()];
    let fixes = boat.fixes();
    if course.is_empty() || fixes.is_empty() {
        return out;
    }
    let (t0, t1) = boat.time_span();
    if t1 < 0.0 {
        return out;
    }
    out[0] = Some(t0.max(0.0));
    let mut i = fixes.partition_point(|f| f.t < 0.0);
    for (k, &m) in course.iter().enumerate().skip(1) {
        // First fix inside the radius.
        let mk = &marks[m];
        let Some(enter) = (i..fixes.len()).find(|&j| mk.distance(fixes[j].pos()) <= radius) else {
            break;
        };
        // Closest approach before leaving the radius again.
        let mut best = enter;
        let mut j = enter;
        while j < fixes.len() && mk.distance(fixes[j].pos()) <= radius {
            if mk.distance(fixes[j].pos()) < mk.distance(fixes[best].pos()) {
                best = j;
            }
            j += 1;
        }
        out[k] = Some(fixes[best].t);
        i = best + 1;
    }
    out
}

/// Course metres from a mark to the finish: `tail[k]` = sum of the legs after course[k].
pub(crate) fn tail_lengths(marks: &[Mark], course: &[usize]) -> Vec<f64> {
    let mut tail = vec![0.0; course.len()];
    for k in (0..course.len().saturating_sub(1)).rev() {
        tail[k] = tail[k + 1] + dist(marks[course[k]].position, marks[course[k + 1]].position);
    }
    tail
}

/// Rank boats at time t into `out` (cleared first): racing boats by legs completed, then by
/// course distance still to sail; finished boats first, in finishing order; boats not yet
/// started last. Without a course (fewer than two marks) by metres sailed.
/// No allocation once `out` has room for every boat.
pub(crate) fn standings_into(
    t: f64,
    boats: &[Boat],
    states: &[BoatState],
    marks: &[Mark],
    course: &[usize],
    tail: &[f64],
    out: &mut Vec<Standing>,
) {
    out.clear();
    let has_course = course.len() >= 2;
    for (b, (boat, s)) in boats.iter().zip(states).enumerate() {
        let done = boat
            .roundings()
            .iter()
            .take_while(|r| r.is_some_and(|r| r <= t))
            .count();
        let finished = has_course && done == course.len();
        let remaining = has_course.then(|| {
            if finished {
                0.0
            } else if done == 0 {
                marks[course[0]].distance(s.position) + tail[0]
            } else {
                marks[course[done]].distance(s.position) + tail[done]
            }
        });
        out.push(Standing {
            boat: b,
            rank: 0,
            legs_completed: done,
            distance_m: 0.0,
            remaining_m: remaining,
            finished,
            racing: s.racing,
        });
    }
    let finish_time = |st: &Standing| {
        if st.finished {
            boats[st.boat].roundings()[course.len() - 1].unwrap_or(f64::INFINITY)
        } else {
            f64::INFINITY
        }
    };
    let started = |st: &Standing| boats[st.boat].fixes().first().is_some_and(|f| f.t <= t);
    out.sort_unstable_by(|a, b| {
        started(b)
            .cmp(&started(a))
            .then(b.finished.cmp(&a.finished))
            .then(finish_time(a).total_cmp(&finish_time(b)))
            .then(b.legs_completed.cmp(&a.legs_completed))
            .then(match (a.remaining_m, b.remaining_m) {
                (Some(x), Some(y)) => x.total_cmp(&y),
                _ => states[b.boat].sailed_m.total_cmp(&states[a.boat].sailed_m),
            })
            .then(a.boat.cmp(&b.boat))
    });
    let lead_rem = out.first().and_then(|s| s.remaining_m);
    let lead_sailed = out.first().map_or(0.0, |s| states[s.boat].sailed_m);
    for (r, st) in out.iter_mut().enumerate() {
        st.rank = r + 1;
        st.distance_m = match (st.remaining_m, lead_rem) {
            (Some(x), Some(l)) => (x - l).max(0.0),
            _ => (lead_sailed - states[st.boat].sailed_m).max(0.0),
        };
    }
}
