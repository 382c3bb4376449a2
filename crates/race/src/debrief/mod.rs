//! The debrief: where each boat gained and lost. The wind (measured or estimated, and said
//! so), every tack and gybe with the metres it cost, the start at the gun, and the legs.
//! Everything here is derived from the race's public data (tracks, course, series); it runs
//! once per race, not per frame.

pub mod legs;
pub mod manoeuvres;
pub mod start;
pub mod wind;

use serde::Serialize;

pub use legs::{LegResult, leg_results};
pub use manoeuvres::{Manoeuvre, ManoeuvreKind, Settings};
pub use start::{BoatStart, StartLine, StartReport, start_report};
pub use wind::{WindModel, WindSource, race_wind};

use crate::Race;

/// One boat's manoeuvres and their summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoatManoeuvres {
    /// Index into `Race::boats`.
    pub boat: usize,
    pub id: String,
    /// Race seconds the detector looked at (the start, or the first fix, to the finish or the
    /// last fix).
    pub from_s: f64,
    pub to_s: f64,
    pub tacks: usize,
    pub gybes: usize,
    /// Median and largest distance lost over all manoeuvres, metres (None without any).
    pub median_loss_m: Option<f64>,
    pub worst_loss_m: Option<f64>,
    pub manoeuvres: Vec<Manoeuvre>,
}

/// The whole debrief of a race.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Debrief {
    /// `None` where there is no file wind and too little sailing to estimate one; then no
    /// manoeuvre can be told.
    pub wind: Option<WindModel>,
    pub manoeuvres: Vec<BoatManoeuvres>,
    pub start: Result<StartReport, String>,
    pub legs: Vec<LegResult>,
}

impl Debrief {
    /// Analyse a race with the default detector.
    pub fn of(race: &Race) -> Debrief {
        Debrief::with(race, &Settings::default())
    }

    /// Analyse a race with these detector settings.
    pub fn with(race: &Race, settings: &Settings) -> Debrief {
        let wind = race_wind(race);
        let manoeuvres = match &wind {
            Some(w) => race
                .boats
                .iter()
                .enumerate()
                .map(|(i, _)| boat_manoeuvres(race, i, w, settings))
                .collect(),
            None => Vec::new(),
        };
        Debrief {
            start: start_report(race, wind.as_ref()),
            legs: leg_results(race),
            wind,
            manoeuvres,
        }
    }

    /// The manoeuvres of every boat in time order, as (boat index, manoeuvre).
    pub fn all_manoeuvres(&self) -> Vec<(usize, &Manoeuvre)> {
        let mut v: Vec<(usize, &Manoeuvre)> = self
            .manoeuvres
            .iter()
            .flat_map(|b| b.manoeuvres.iter().map(move |m| (b.boat, m)))
            .collect();
        v.sort_by(|a, b| a.1.t.total_cmp(&b.1.t).then(a.0.cmp(&b.0)));
        v
    }
}

/// The span a boat's manoeuvres are looked for in: from the start (where the race has one)
/// or the first fix, to its finish (where it finished the course) or its last fix.
pub fn racing_span(race: &Race, boat: usize) -> (f64, f64) {
    let b = &race.boats[boat];
    let (t0, t1) = b.time_span();
    let has_start = race.start_time.is_some() || race.course.len() >= 2;
    let from = if has_start { t0.max(0.0) } else { t0 };
    let to = if race.course.len() >= 2 {
        b.roundings()
            .last()
            .copied()
            .flatten()
            .map_or(t1, |f| f.min(t1))
    } else {
        t1
    };
    (from, to)
}

/// One boat's manoeuvres over its [`racing_span`].
pub fn boat_manoeuvres(
    race: &Race,
    boat: usize,
    wind: &WindModel,
    settings: &Settings,
) -> BoatManoeuvres {
    let (from, to) = racing_span(race, boat);
    let ms = manoeuvres::detect(&race.boats[boat], wind, from, to, settings);
    let mut losses: Vec<f64> = ms.iter().map(|m| m.loss_m).collect();
    losses.sort_by(f64::total_cmp);
    let median = (!losses.is_empty()).then(|| {
        let n = losses.len();
        if n % 2 == 1 {
            losses[n / 2]
        } else {
            0.5 * (losses[n / 2 - 1] + losses[n / 2])
        }
    });
    BoatManoeuvres {
        boat,
        id: race.boats[boat].id.clone(),
        from_s: from,
        to_s: to,
        tacks: ms.iter().filter(|m| m.kind == ManoeuvreKind::Tack).count(),
        gybes: ms.iter().filter(|m| m.kind == ManoeuvreKind::Gybe).count(),
        median_loss_m: median,
        worst_loss_m: losses.last().copied(),
        manoeuvres: ms,
    }
}

#[cfg(test)]
mod tests;
