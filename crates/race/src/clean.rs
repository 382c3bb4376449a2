//! Cleaning a boat's samples, and the report of what was done.
//!
//! In order: sort by time (a warning names how many were out of order); merge samples with the
//! same timestamp (their mean); drop frozen fixes (a position repeated exactly while the boat
//! was moving: a receiver re-sending its last fix, as in the SailGP logs); drop spikes (a fix
//! that implies a speed above the class limit); mark gaps longer than the gap limit.

use serde::Serialize;

use crate::track::{Fix, Logged};

/// One sample as imported, in race metres and race seconds.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RawSample {
    pub t: f64,
    pub x: f64,
    pub z: f64,
    pub logged: Logged,
    /// Logged speed over ground, m/s, or NaN.
    pub sog: f64,
}

/// A moving boat (above this speed, m/s) does not report the same position twice.
const FROZEN_MIN_SPEED_MPS: f64 = 1.0;

/// What cleaning did to one boat.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct BoatReport {
    pub id: String,
    pub file: String,
    pub samples_read: usize,
    pub samples_kept: usize,
    pub out_of_order: usize,
    pub duplicates_merged: usize,
    pub frozen_removed: usize,
    /// Fixes at exactly 0° N 0° E (a receiver's "no fix"), removed before anything else.
    pub null_island_removed: usize,
    /// The class speed limit used for spikes, knots.
    pub max_speed_kn: f64,
    /// Removed spikes: race time and the speed (knots) of the step that condemned the fix.
    pub spikes: Vec<Spike>,
    /// The gap limit used, seconds.
    pub gap_limit_s: f64,
    /// Gaps marked: [from, to] race seconds.
    pub gaps: Vec<[f64; 2]>,
    /// Fastest step between kept fixes, knots.
    pub max_step_speed_kn: f64,
}

#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct Spike {
    pub t: f64,
    pub implied_speed_kn: f64,
}

pub const MPS_PER_KNOT: f64 = 1852.0 / 3600.0;

pub(crate) struct Cleaned {
    pub fixes: Vec<Fix>,
    pub gap_after: Vec<bool>,
    pub logged: Vec<Logged>,
    pub report: BoatReport,
}

/// The gap limit for a track: 20 s, or 5 median sampling intervals when the log is sparser
/// (Garmin "smart recording" writes every 1–18 s while sailing; a 99 s hole is a gap).
pub fn gap_limit(ts: &[f64]) -> f64 {
    let mut d: Vec<f64> = ts.windows(2).map(|w| w[1] - w[0]).collect();
    if d.is_empty() {
        return 20.0;
    }
    let mid = d.len() / 2;
    let (_, med, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
    (5.0 * *med).max(20.0)
}

fn speed(a: &RawSample, b: &RawSample) -> f64 {
    (b.x - a.x).hypot(b.z - a.z) / (b.t - a.t)
}

pub(crate) fn clean(
    id: &str,
    file: &str,
    mut s: Vec<RawSample>,
    max_speed_mps: f64,
    null_island_removed: usize,
    warnings: &mut Vec<String>,
) -> Cleaned {
    let samples_read = s.len() + null_island_removed;
    let out_of_order = s.windows(2).filter(|w| w[1].t < w[0].t).count();
    if out_of_order > 0 {
        s.sort_by(|a, b| a.t.total_cmp(&b.t));
        warnings.push(format!(
            "{file}: boat {id} had {out_of_order} samples out of time order; they were sorted"
        ));
    }
    let duplicates_merged = merge_repeated_times(&mut s);
    if duplicates_merged > 0 {
        warnings.push(format!(
            "{file}: boat {id} had {duplicates_merged} samples with a repeated timestamp; they were merged"
        ));
    }
    let frozen_removed = remove_frozen(&mut s);
    let (acc, spikes) = remove_spikes(&s, max_speed_mps);
    drop(s);
    if frozen_removed > 0 {
        warnings.push(format!(
            "{file}: boat {id} had {frozen_removed} frozen fixes (a moving boat's position repeated); they were removed"
        ));
    }
    if !spikes.is_empty() {
        warnings.push(format!(
            "{file}: boat {id} had {} fixes implying over {:.0} kn; they were removed as spikes",
            spikes.len(),
            max_speed_mps / MPS_PER_KNOT
        ));
    }
    let (gap_limit_s, gaps, gap_after) = find_gaps(&acc);
    let max_step = acc
        .windows(2)
        .map(|w| speed(&w[0], &w[1]))
        .fold(0.0, f64::max);
    Cleaned {
        fixes: acc
            .iter()
            .map(|p| Fix {
                t: p.t,
                x: p.x,
                z: p.z,
            })
            .collect(),
        logged: acc.iter().map(|p| p.logged).collect(),
        gap_after,
        report: BoatReport {
            id: id.to_string(),
            file: file.to_string(),
            samples_read,
            samples_kept: acc.len(),
            out_of_order,
            duplicates_merged,
            frozen_removed,
            null_island_removed,
            max_speed_kn: max_speed_mps / MPS_PER_KNOT,
            spikes,
            gap_limit_s,
            gaps,
            max_step_speed_kn: max_step / MPS_PER_KNOT,
        },
    }
}

/// Equal timestamps merged into their mean position, in place (logs hold millions of
/// samples); how many samples were merged away.
fn merge_repeated_times(s: &mut Vec<RawSample>) -> usize {
    let mut duplicates_merged = 0;
    let mut w = 0;
    let mut i = 0;
    while i < s.len() {
        let mut j = i + 1;
        while j < s.len() && s[j].t == s[i].t {
            j += 1;
        }
        let mut m = s[i];
        if j - i > 1 {
            let k = (j - i) as f64;
            duplicates_merged += j - i - 1;
            m.x = s[i..j].iter().map(|p| p.x).sum::<f64>() / k;
            m.z = s[i..j].iter().map(|p| p.z).sum::<f64>() / k;
        }
        s[w] = m;
        w += 1;
        i = j;
    }
    s.truncate(w);
    duplicates_merged
}

/// Frozen fixes removed in place: the exact position of the previous fix while the boat is
/// moving (by its logged speed, else by its previous step); how many.
fn remove_frozen(s: &mut Vec<RawSample>) -> usize {
    let mut frozen_removed = 0;
    let n = s.len();
    let mut w = 0;
    for i in 0..n {
        let p = s[i];
        if w > 0 && p.x == s[w - 1].x && p.z == s[w - 1].z {
            let moving = if p.sog.is_finite() {
                p.sog > FROZEN_MIN_SPEED_MPS
            } else if w >= 2 {
                speed(&s[w - 2], &s[w - 1]) > FROZEN_MIN_SPEED_MPS
            } else {
                false
            };
            // A later fix that moves on: the frozen one is stale, not a stop.
            if moving && i + 1 < n {
                frozen_removed += 1;
                continue;
            }
        }
        s[w] = p;
        w += 1;
    }
    s.truncate(w);
    frozen_removed
}

/// The fixes kept after removing speed spikes (`max_speed_mps`), and the spikes in time order.
/// A stack of accepted fixes: a fix too fast from the last accepted one is either itself a
/// spike (dropped) or proves the last accepted one was (popped, when the fix is reachable from
/// the one before it and the next fix does not vindicate the popped).
fn remove_spikes(kept: &[RawSample], max_speed_mps: f64) -> (Vec<RawSample>, Vec<Spike>) {
    let mut spikes = Vec::new();
    let mut acc: Vec<RawSample> = Vec::with_capacity(kept.len());
    for (i, p) in kept.iter().enumerate() {
        let Some(top) = acc.last() else {
            acc.push(*p);
            continue;
        };
        let v = speed(top, p);
        if v <= max_speed_mps {
            acc.push(*p);
            continue;
        }
        let next_ok_from_top = kept
            .get(i + 1)
            .is_some_and(|q| speed(top, q) <= max_speed_mps);
        if acc.len() >= 2 && !next_ok_from_top && speed(&acc[acc.len() - 2], p) <= max_speed_mps {
            let bad = acc.pop().expect("len >= 2");
            spikes.push(Spike {
                t: bad.t,
                implied_speed_kn: v / MPS_PER_KNOT,
            });
            acc.push(*p);
        } else if acc.len() == 1 && !next_ok_from_top && i + 1 < kept.len() {
            // The very first fix may be the wrong one: trust the pair that agrees.
            let q = &kept[i + 1];
            if speed(p, q) <= max_speed_mps {
                let bad = acc.pop().expect("len 1");
                spikes.push(Spike {
                    t: bad.t,
                    implied_speed_kn: v / MPS_PER_KNOT,
                });
                acc.push(*p);
            } else {
                spikes.push(Spike {
                    t: p.t,
                    implied_speed_kn: v / MPS_PER_KNOT,
                });
            }
        } else {
            spikes.push(Spike {
                t: p.t,
                implied_speed_kn: v / MPS_PER_KNOT,
            });
        }
    }
    spikes.sort_by(|a, b| a.t.total_cmp(&b.t));
    (acc, spikes)
}

/// The track's gap limit ([`gap_limit`]), its gaps ([start, end] race seconds) and, per fix,
/// whether a gap follows it.
fn find_gaps(acc: &[RawSample]) -> (f64, Vec<[f64; 2]>, Vec<bool>) {
    let ts: Vec<f64> = acc.iter().map(|p| p.t).collect();
    let gap_limit_s = gap_limit(&ts);
    let mut gaps = Vec::new();
    let mut gap_after = vec![false; acc.len()];
    for i in 0..acc.len().saturating_sub(1) {
        if acc[i + 1].t - acc[i].t > gap_limit_s {
            gap_after[i] = true;
            gaps.push([acc[i].t, acc[i + 1].t]);
        }
    }
    (gap_limit_s, gaps, gap_after)
}

impl BoatReport {
    /// Samples cleaning dropped (merged, frozen, spikes, at 0° N 0° E).
    pub fn dropped(&self) -> usize {
        self.samples_read - self.samples_kept
    }

    /// Whether cleaning kept fewer than half of the boat's samples: the file does not load
    /// silently then (see `LoadOptions::keep_going`).
    pub fn lost_most(&self) -> bool {
        self.samples_read > 1 && 2 * self.samples_kept < self.samples_read
    }

    /// One clause naming the rule that dropped most and its likeliest cause, e.g.
    /// "11,977 of 11,978 fixes imply over 1,000 kn: is the time column in days?".
    pub fn loss_reason(&self) -> String {
        use crate::text::count;
        let read = count(self.samples_read);
        let rules = [
            (self.spikes.len(), 0),
            (self.duplicates_merged, 1),
            (self.frozen_removed, 2),
            (self.null_island_removed, 3),
        ];
        let (n, rule) = rules.iter().copied().max_by_key(|r| r.0).unwrap_or((0, 0));
        let n_s = count(n);
        match rule {
            0 => {
                let mut v: Vec<f64> = self.spikes.iter().map(|s| s.implied_speed_kn).collect();
                v.sort_by(f64::total_cmp);
                let median = v.get(v.len() / 2).copied().unwrap_or(0.0);
                if median > 1000.0 {
                    format!(
                        "{n_s} of {read} fixes imply over 1,000 kn: is the time column in days?"
                    )
                } else if 5 * n >= 2 * self.samples_read {
                    format!(
                        "{n_s} of {read} fixes imply over {:.0} kn: does the track alternate between two receivers or boats?",
                        self.max_speed_kn
                    )
                } else {
                    format!(
                        "{n_s} of {read} fixes imply over {:.0} kn: is the class's speed limit too low?",
                        self.max_speed_kn
                    )
                }
            }
            1 => format!(
                "{n_s} of {read} samples repeat the timestamp before them: is the time column constant, or rounded to whole days?"
            ),
            2 => format!(
                "{n_s} of {read} fixes repeat the position before them while the boat moves: is the receiver stuck?"
            ),
            _ => format!("{n_s} of {read} fixes are at 0° N 0° E, a receiver's \"no fix\" value"),
        }
    }
}
