//! The timeline's events (`race::events`) on the embedded sample race and on a real race of
//! ../shared/data, against what the tracks say independently: who rounds a mark first leads
//! right after it (marks passed rank before distance), and the rounding times are the closest
//! approaches to the marks computed by hand from the GPX.

mod common;

use race::events::LEAD_HOLD_S;
use race::{EventKind, Race, RaceEvent, race_events};

/// The leader the events say holds the lead at `t` (the last lead change before it), if any
/// change happened yet.
fn leader_by_events(events: &[RaceEvent], t: f64) -> Option<usize> {
    events
        .iter()
        .rev()
        .filter(|e| e.t <= t)
        .find_map(|e| match e.kind {
            EventKind::LeadChange { boat, .. } => Some(boat),
            _ => None,
        })
}

/// The first rounding of each course mark (course index ≥ 1): (t, boat).
fn first_roundings(race: &Race, events: &[RaceEvent]) -> Vec<(f64, usize)> {
    (1..race.course.len())
        .filter_map(|k| {
            events.iter().find_map(|e| match e.kind {
                EventKind::Rounding {
                    boat, course_index, ..
                } if course_index == k => Some((e.t, boat)),
                _ => None,
            })
        })
        .collect()
}

/// Lead changes chain (each takes the lead from the previous new leader), are at least the
/// hold time apart, and the events are sorted.
fn assert_consistent(events: &[RaceEvent]) {
    assert!(events.windows(2).all(|w| w[0].t <= w[1].t));
    let changes: Vec<(f64, usize, usize)> = events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::LeadChange { boat, from } => Some((e.t, boat, from)),
            _ => None,
        })
        .collect();
    for w in changes.windows(2) {
        assert_eq!(w[1].2, w[0].1, "{w:?}");
        assert!(w[1].0 - w[0].0 >= LEAD_HOLD_S, "{w:?}");
    }
    assert!(changes.iter().all(|c| c.1 != c.2));
}

#[test]
fn the_sample_race_starts_rounds_and_changes_lead() {
    let race = Race::sample();
    let ev = race_events(&race);
    assert_consistent(&ev);
    assert_eq!(ev[0].kind, EventKind::Start);
    assert_eq!(ev[0].t, 0.0);
    // Eight boats round W, L, W and finish: 4 × 8 roundings.
    let roundings = ev
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Rounding { .. }))
        .count();
    assert_eq!(roundings, 4 * 8);
    // Whoever rounds a mark first leads just after it.
    let firsts = first_roundings(&race, &ev);
    assert_eq!(firsts.len(), 4);
    for (t, boat) in firsts {
        assert_eq!(
            leader_by_events(&ev, t + 1.0),
            Some(boat),
            "{} rounded first at {t}",
            race.boats[boat].id
        );
    }
    let finish = ev
        .iter()
        .rev()
        .find(|e| e.describe(&race).contains("finishes"))
        .unwrap();
    assert!(finish.describe(&race).ends_with("finishes at Start"));
}

/// Valencia 2025-06-21 race P02 (two dinghies, marks S1 and B1 from the maxSail meta-data,
/// start 5 min after the first point, 12:06:29 UTC). The closest approaches to B1 and S1
/// computed by hand from the GPX points (flat earth, 111 320 m per degree) are, in race
/// seconds: ESP29375 562, 891, 1397, 1746; ESP30782 569, 900, 1445, 1803. ESP29375 rounds every
/// mark first, so once it has rounded B1 nobody else can lead.
#[test]
fn valencia_p02_events_match_the_tracks() {
    let race = common::load(&[
        "valencia/2025-06-21-ESP30782-P02.gpx",
        "valencia/2025-06-21-ESP29375-P02.gpx",
        "valencia/2025-06-21-ESP30782-P02-meta-data.json",
    ]);
    let ev = race_events(&race);
    assert_consistent(&ev);
    assert_eq!(ev[0].kind, EventKind::Start);
    let esp29375 = race.boat_index("ESP29375").unwrap();
    let esp30782 = race.boat_index("ESP30782").unwrap();
    let rounding_times = |boat: usize| -> Vec<f64> {
        ev.iter()
            .filter(|e| matches!(e.kind, EventKind::Rounding { .. }) && e.boat() == Some(boat))
            .map(|e| e.t)
            .collect()
    };
    let near = |got: Vec<f64>, want: [f64; 4]| {
        assert_eq!(got.len(), 4, "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() <= 1.0, "{got:?} vs {want:?}");
        }
    };
    near(rounding_times(esp29375), [562.0, 891.0, 1397.0, 1746.0]);
    near(rounding_times(esp30782), [569.0, 900.0, 1445.0, 1803.0]);
    assert_eq!(leader_by_events(&ev, 562.0), Some(esp29375));
    assert!(
        ev.iter()
            .all(|e| !matches!(e.kind, EventKind::LeadChange { .. }) || e.t < 562.0),
        "{ev:?}"
    );
    assert_eq!(
        ev.iter().find(|e| e.t > 1700.0).unwrap().describe(&race),
        "ESP29375 finishes at S1"
    );
}

/// Without a course (the Gdańsk tracks have no marks) there are no ranks and so no lead
/// changes, however the boats' metres sailed cross.
#[test]
fn a_race_without_a_course_has_no_lead_changes() {
    let race = common::load(&[
        "gdansk/2025-10-26-boat_three.gpx",
        "gdansk/2025-10-26-8_43.gpx",
    ]);
    assert_eq!(race.rank_basis(), race::RankBasis::NoCourse);
    let ev = race_events(&race);
    assert!(
        ev.iter()
            .all(|e| !matches!(e.kind, EventKind::LeadChange { .. })),
        "{ev:?}"
    );
}
