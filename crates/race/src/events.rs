//! The moments of a race worth jumping to: the start signal, every mark rounding, and every
//! change of leader, in time order. Computed from the course and ranking code (roundings of
//! [`crate::course`], ranks of [`Race::standings_into`]), so the timeline's ticks agree with the
//! leaderboard.
//!
//! A lead change is counted only when the new leader keeps the lead for [`LEAD_HOLD_S`]: two
//! boats side by side swap rank-1 many times a minute in the noise of the GPS, which no sailor
//! calls a lead change.

use serde::Serialize;

use crate::{BoatState, Race, RankBasis, Standing};

/// How long (race seconds) a new leader must stay ahead before the change counts.
pub const LEAD_HOLD_S: f64 = 10.0;

/// At most this many samples of the ranking are taken over a race (the step grows for long
/// races; a 40-minute race is sampled every second).
const MAX_SAMPLES: f64 = 20_000.0;

/// What happened.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum EventKind {
    /// The start signal (race time 0).
    Start,
    /// `boat` passed course mark `course_index` (≥ 1), named `mark`.
    Rounding {
        boat: usize,
        course_index: usize,
        mark: String,
    },
    /// `boat` took the lead from `from`.
    LeadChange { boat: usize, from: usize },
}

/// One event on the timeline.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RaceEvent {
    /// Race seconds.
    pub t: f64,
    pub kind: EventKind,
}

impl RaceEvent {
    /// The boat it is about, if any.
    pub fn boat(&self) -> Option<usize> {
        match self.kind {
            EventKind::Start => None,
            EventKind::Rounding { boat, .. } | EventKind::LeadChange { boat, .. } => Some(boat),
        }
    }

    /// A line for the event list, e.g. "ESP30782 rounds B1", "NZL takes the lead from GBR".
    pub fn describe(&self, race: &Race) -> String {
        let name = |b: usize| race.boats.get(b).map_or("?", |b| b.id.as_str());
        match &self.kind {
            EventKind::Start => "Start".to_string(),
            EventKind::Rounding {
                boat,
                course_index,
                mark,
            } => {
                if *course_index + 1 == race.course.len() {
                    format!("{} finishes at {mark}", name(*boat))
                } else {
                    format!("{} rounds {mark}", name(*boat))
                }
            }
            EventKind::LeadChange { boat, from } => {
                format!("{} takes the lead from {}", name(*boat), name(*from))
            }
        }
    }
}

/// Every event of `race`, sorted by time (the start first among equal times).
pub fn race_events(race: &Race) -> Vec<RaceEvent> {
    let (t0, t1) = race.time_span();
    let mut out = Vec::new();
    if t0 <= 0.0 && t1 >= 0.0 && !race.boats.is_empty() {
        out.push(RaceEvent {
            t: 0.0,
            kind: EventKind::Start,
        });
    }
    out.extend(
        race.rounding_events()
            .into_iter()
            .filter(|e| e.course_index > 0)
            .map(|e| RaceEvent {
                t: e.t,
                kind: EventKind::Rounding {
                    boat: e.boat,
                    course_index: e.course_index,
                    mark: e.mark,
                },
            }),
    );
    out.extend(
        lead_changes(race)
            .into_iter()
            .map(|(t, boat, from)| RaceEvent {
                t,
                kind: EventKind::LeadChange { boat, from },
            }),
    );
    // Stable: at equal times the start, then roundings, then lead changes.
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    out
}

/// Times the leader changed after the start, as `(t, new leader, old leader)`: the ranking is
/// sampled every second (longer races: [`MAX_SAMPLES`] samples) from the start signal to the
/// end, and a new rank-1 boat counts from the first sample it led once it has led for
/// [`LEAD_HOLD_S`]. None without a course (no ranks, [`RankBasis::NoCourse`]) or with fewer
/// than two boats.
pub fn lead_changes(race: &Race) -> Vec<(f64, usize, usize)> {
    let (t0, t1) = race.time_span();
    let start = t0.max(0.0);
    if race.rank_basis() != RankBasis::Course || race.boats.len() < 2 || t1 <= start {
        return Vec::new();
    }
    let step = ((t1 - start) / MAX_SAMPLES).max(1.0);
    let mut states: Vec<BoatState> = Vec::new();
    let mut standings: Vec<Standing> = Vec::new();
    let mut leader_at = |t: f64| {
        race.states_at(t, &mut states);
        race.standings_into(t, &states, &mut standings);
        standings.iter().find(|s| s.rank == 1).map(|s| s.boat)
    };
    let mut out = Vec::new();
    let mut leader: Option<usize> = None;
    // A boat that took rank 1 and when, not yet held long enough.
    let mut candidate: Option<(usize, f64)> = None;
    let n = ((t1 - start) / step).floor() as usize;
    for i in 0..=n {
        let t = start + i as f64 * step;
        let Some(now) = leader_at(t) else { continue };
        let Some(held) = leader else {
            leader = Some(now);
            continue;
        };
        if now == held {
            candidate = None;
            continue;
        }
        match candidate {
            Some((c, since)) if c == now => {
                if t - since >= LEAD_HOLD_S {
                    out.push((since, now, held));
                    leader = Some(now);
                    candidate = None;
                }
            }
            _ => candidate = Some((now, t)),
        }
    }
    out
}
