//! Per boat and leg: elapsed time, rank at the leg's end, places and seconds gained, distance
//! sailed against the leg's length. A leg is course element `k − 1` to `k` (leg 1 starts at the
//! start, rounded by every boat at the gun or its first fix); ranks are the order of rounding
//! times among the boats that rounded.

use serde::Serialize;

use crate::Race;

/// One boat on one leg.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LegResult {
    /// 1-based.
    pub leg: usize,
    pub boat: String,
    /// The mark that ends the leg.
    pub to_mark: String,
    /// Race seconds at the leg's start and end.
    pub t_start: f64,
    pub t_end: f64,
    pub elapsed_s: f64,
    /// Rank at the leg's end (1 = first round).
    pub rank: usize,
    /// Rank at the leg's start (`None` on leg 1: everyone starts together).
    pub rank_at_start: Option<usize>,
    /// Places gained on the leg (positive = gained).
    pub places_gained: Option<i64>,
    /// Seconds gained on the leader of each mark (behind-leader at the start minus at the end).
    pub seconds_gained: f64,
    /// Metres sailed on the leg (straight lines between fixes).
    pub sailed_m: f64,
    /// The leg's length mark to mark, metres.
    pub leg_length_m: f64,
    /// `sailed_m / leg_length_m`.
    pub sailed_ratio: f64,
}

/// Every completed leg of every boat, by leg then rank.
pub fn leg_results(race: &Race) -> Vec<LegResult> {
    let lengths = race.leg_lengths();
    let mut out = Vec::new();
    let rank_at = |k: usize, b: usize| -> Option<usize> {
        let t = race.boats[b].roundings().get(k).copied().flatten()?;
        Some(
            1 + race
                .boats
                .iter()
                .filter(|o| {
                    o.roundings()
                        .get(k)
                        .copied()
                        .flatten()
                        .is_some_and(|u| u < t)
                })
                .count(),
        )
    };
    let first_at = |k: usize| {
        race.boats
            .iter()
            .filter_map(|o| o.roundings().get(k).copied().flatten())
            .fold(f64::INFINITY, f64::min)
    };
    for k in 1..race.course.len() {
        let mut leg: Vec<LegResult> = Vec::new();
        for (bi, b) in race.boats.iter().enumerate() {
            let r = b.roundings();
            let (Some(Some(t0)), Some(Some(t1))) = (r.get(k - 1), r.get(k)) else {
                continue;
            };
            let rank = rank_at(k, bi).unwrap_or(0);
            let rank_at_start = if k == 1 { None } else { rank_at(k - 1, bi) };
            let behind0 = t0 - first_at(k - 1);
            let behind1 = t1 - first_at(k);
            let sailed = b.sailed_at(*t1) - b.sailed_at(*t0);
            let len = lengths[k - 1];
            leg.push(LegResult {
                leg: k,
                boat: b.id.clone(),
                to_mark: race.marks[race.course[k]].name.clone(),
                t_start: *t0,
                t_end: *t1,
                elapsed_s: t1 - t0,
                rank,
                rank_at_start,
                places_gained: rank_at_start.map(|s| s as i64 - rank as i64),
                seconds_gained: behind0 - behind1,
                sailed_m: sailed,
                leg_length_m: len,
                sailed_ratio: if len > 0.0 { sailed / len } else { f64::NAN },
            });
        }
        leg.sort_by_key(|l| l.rank);
        out.extend(leg);
    }
    out
}
