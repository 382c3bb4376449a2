//! The embedded races: the generated fleet (default) and Valencia P01.

use race::Race;

#[test]
fn the_fleet_sample_is_a_windward_leeward_race_with_tacks_and_gybes() {
    let r = Race::sample();
    assert_eq!(r.boats.len(), 8);
    let names: Vec<&str> = r.course_marks().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["Start", "W", "L", "W", "Start"]);
    assert!(r.origin.is_some() && r.start_time.is_some());
    let (t0, t1) = r.time_span();
    assert!(t0 < 0.0 && t1 > 1200.0, "{t0} {t1}");
    for b in &r.boats {
        // Every boat sails the whole course, in order.
        let t: Vec<f64> = b
            .roundings()
            .iter()
            .map(|x| x.expect("every mark rounded"))
            .collect();
        assert!(t.windows(2).all(|w| w[0] < w[1]), "{}: {t:?}", b.id);
        assert!(b.has_heel());
        // Tacks and gybes: the smoothed heading turns by more than 60° within 10 s at least
        // four times beyond the four roundings.
        let mut turns = 0;
        let mut t = 0.0;
        while t + 10.0 < b.time_span().1 {
            let (h0, h1) = (b.state_at(t).heading_deg, b.state_at(t + 10.0).heading_deg);
            if ((h1 - h0 + 540.0).rem_euclid(360.0) - 180.0).abs() > 60.0 {
                turns += 1;
                t += 12.0;
            } else {
                t += 1.0;
            }
        }
        assert!(turns >= 8, "{}: {turns} turns", b.id);
    }
    // The file is clean: cleaning removed nothing.
    for rep in &r.report.boats {
        assert_eq!(rep.samples_read, rep.samples_kept, "{rep:?}");
    }
    let size = std::fs::metadata(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/races/fleet.json"
    ))
    .unwrap()
    .len();
    assert!(size < 1_000_000, "{size}");
}

#[test]
fn the_valencia_sample_loads_with_its_marks() {
    let r = Race::valencia();
    assert_eq!(r.boats.len(), 2);
    assert_eq!(r.course.len(), 5);
    assert!(
        r.boats
            .iter()
            .all(|b| b.roundings().iter().all(|x| x.is_some()))
    );
}

#[test]
fn the_committed_fleet_file_is_the_generator_output() {
    let committed = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/races/fleet.json"
    ))
    .unwrap();
    assert!(
        committed == race::synth::fleet_race_json(),
        "assets/races/fleet.json is stale: run scripts/gen-fleet-race.sh"
    );
}
