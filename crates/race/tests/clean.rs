//! Cleaning rules on small tracks whose right answer is known by construction.

use race::Race;

fn race(track: serde_json::Value, max_speed_kn: Option<f64>) -> Race {
    let mut boat = serde_json::json!({"id": "A", "track": track});
    if let Some(k) = max_speed_kn {
        boat["max_speed_kn"] = k.into();
    }
    let json = serde_json::json!({"boats": [boat]});
    Race::from_files(&[("c.json", json.to_string().as_bytes())]).unwrap()
}

#[test]
fn out_of_order_samples_are_sorted_with_a_warning() {
    let r = race(
        serde_json::json!([[0, 0, 0], [2, 2, 0], [1, 1, 0], [3, 3, 0]]),
        None,
    );
    let t: Vec<f64> = r.boats[0].fixes().iter().map(|f| f.t).collect();
    assert_eq!(t, [0.0, 1.0, 2.0, 3.0]);
    assert_eq!(r.report.boats[0].out_of_order, 1);
    assert!(
        r.report.warnings[0].contains("1 samples out of time order"),
        "{:?}",
        r.report.warnings
    );
}

#[test]
fn equal_timestamps_are_merged_into_their_mean() {
    let r = race(
        serde_json::json!([[0, 0, 0], [1, 1, 0], [1, 3, 2], [2, 2, 0]]),
        None,
    );
    let f = r.boats[0].fixes();
    assert_eq!(f.len(), 3);
    assert_eq!((f[1].t, f[1].x, f[1].z), (1.0, 2.0, 1.0));
    assert_eq!(r.report.boats[0].duplicates_merged, 1);
}

#[test]
fn a_spike_above_the_class_limit_is_removed_and_reported() {
    // 2 m/s east; the fix at t = 5 jumps 100 m north (≈ 97 kn), limit 10 kn.
    let track: Vec<[f64; 3]> = (0..11)
        .map(|i| [i as f64, 2.0 * i as f64, if i == 5 { -100.0 } else { 0.0 }])
        .collect();
    let r = race(serde_json::json!(track), Some(10.0));
    let rep = &r.report.boats[0];
    assert_eq!(rep.spikes.len(), 1);
    assert_eq!(rep.spikes[0].t, 5.0);
    assert!(rep.spikes[0].implied_speed_kn > 90.0);
    assert!(r.boats[0].fixes().iter().all(|f| f.z == 0.0));
    // Between t = 4 and 6 the boat now goes straight through, at 2 m/s.
    let s = r.boats[0].state_at(5.0);
    assert!((s.position[0] - 10.0).abs() < 1e-6 && s.position[1] == 0.0);
}

#[test]
fn a_bad_first_fix_is_the_one_removed() {
    let mut track: Vec<[f64; 3]> = (0..10).map(|i| [i as f64, 2.0 * i as f64, 0.0]).collect();
    track[0] = [0.0, 500.0, 500.0];
    let r = race(serde_json::json!(track), Some(10.0));
    assert_eq!(r.report.boats[0].spikes.len(), 1);
    assert_eq!(r.report.boats[0].spikes[0].t, 0.0);
    assert_eq!(r.boats[0].fixes()[0].t, 1.0);
}

#[test]
fn a_frozen_fix_of_a_moving_boat_is_removed_but_a_stopped_boat_stays() {
    // Moving at 3 m/s, the receiver repeats the fix at t = 4 for t = 5, then jumps 6 m.
    let mut track: Vec<[f64; 3]> = (0..10).map(|i| [i as f64, 3.0 * i as f64, 0.0]).collect();
    track[5] = [5.0, 12.0, 0.0];
    let r = race(serde_json::json!(track), None);
    assert_eq!(r.report.boats[0].frozen_removed, 1);
    assert!(!r.boats[0].fixes().iter().any(|f| f.t == 5.0));
    // A boat at rest repeats its position legitimately.
    let still: Vec<[f64; 3]> = (0..10).map(|i| [i as f64, 7.0, 7.0]).collect();
    let r = race(serde_json::json!(still), None);
    assert_eq!(r.report.boats[0].frozen_removed, 0);
    assert_eq!(r.boats[0].fixes().len(), 10);
}
