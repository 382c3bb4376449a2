//! The panels' data against the race crate and closed forms.

use ui::leaderboard::{format_distance, parse_hex_color};
use ui::perf::{FpsMeter, format_count};
use ui::{leaderboard_rows, timeline_events};

#[test]
fn leaderboard_rows_follow_the_race_standings() {
    let race = race::Race::sample();
    let (t0, t1) = race.time_span();
    let t = t0 + 0.6 * (t1 - t0);
    let rows = leaderboard_rows(&race, t);
    let standings = race.standings(t);
    assert_eq!(rows.len(), race.boats.len());
    for (row, s) in rows.iter().zip(&standings) {
        assert_eq!(row.rank, s.rank);
        let boat = &race.boats[s.boat];
        assert!(row.name == boat.name || row.name == boat.id);
        assert_eq!(row.behind_m, s.distance_m);
        let st = boat.state_at(t);
        // 1 knot = 1852 m per hour.
        assert!((row.speed_kn - st.speed_mps * 3600.0 / 1852.0).abs() < 1e-12);
        assert_eq!(row.heading_deg, st.heading_deg);
    }
    assert!(rows.windows(2).all(|w| w[0].rank <= w[1].rank));
    assert_eq!(rows[0].behind_m, 0.0);
}

#[test]
fn a_race_without_marks_is_said_to_have_no_course_rank() {
    use ui::leaderboard::has_no_course;
    let json = br#"{"boats": [{"id": "A", "track": [[0, 0, 0], [10, 20, 0]]}, {"id": "B", "track": [[0, 0, 5], [10, 10, 5]]}]}"#;
    let race = race::Race::from_files(&[("n.json", json)]).unwrap();
    assert_eq!(race.rank_basis(), race::RankBasis::NoCourse);
    assert!(has_no_course(&leaderboard_rows(&race, 5.0)));
    assert!(!has_no_course(&leaderboard_rows(
        &race::Race::sample(),
        5.0
    )));
}

#[test]
fn timeline_events_are_the_start_roundings_and_lead_changes_in_order() {
    let race = race::Race::sample();
    let ev = timeline_events(&race);
    let all = race.rounding_events();
    let roundings = all.iter().filter(|e| e.course_index > 0).count();
    let lead_changes = race::events::lead_changes(&race).len();
    assert_eq!(ev.len(), 1 + roundings + lead_changes);
    assert_eq!(ev[0].label, "Start");
    assert_eq!(ev[0].color, ui::events::START_COLOR);
    assert!(lead_changes > 0, "the sample race's lead changes");
    assert!(ev.windows(2).all(|w| w[0].t <= w[1].t));
}

#[test]
fn fps_meter_averages_over_its_window() {
    let mut m = FpsMeter::new(4);
    assert_eq!(m.fps(), 0.0);
    for _ in 0..4 {
        m.push(0.02);
    }
    assert!((m.fps() - 50.0).abs() < 1e-9);
    // Four frames of 10 ms push the 20 ms ones out of the window.
    for _ in 0..4 {
        m.push(0.01);
    }
    assert!((m.fps() - 100.0).abs() < 1e-9);
    assert!((m.frame_ms() - 10.0).abs() < 1e-9);
    m.push(f64::NAN);
    m.push(0.0);
    assert!((m.fps() - 100.0).abs() < 1e-9);
}

#[test]
fn formats() {
    assert_eq!(
        parse_hex_color("#ff8000"),
        Some(egui::Color32::from_rgb(255, 128, 0))
    );
    assert_eq!(parse_hex_color("ff8000"), None);
    assert_eq!(parse_hex_color("#ff80"), None);
    assert_eq!(format_distance(35.4), "35 m");
    assert_eq!(format_distance(1240.0), "1.24 km");
    assert_eq!(format_count(950), "950");
    assert_eq!(format_count(12_345), "12.3k");
    assert_eq!(format_count(1_250_000), "1.25M");
}
