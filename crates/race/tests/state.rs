//! Interpolation, heading smoothing and the not-racing ends, on races built from native JSON.

mod common;
use proptest::prelude::*;
use race::Race;

fn race_json(track: &[[f64; 3]]) -> Race {
    let json = serde_json::json!({
        "name": "t", "origin": null, "start_time": null,
        "boats": [{"id": "A", "track": track, "max_speed_kn": 1e6}], "marks": []
    });
    Race::from_files(&[("t.json", json.to_string().as_bytes())]).unwrap()
}

proptest! {
    #![proptest_config(common::fuzz_config("no_overshoot_past_samples", 0x5EED_0017_0003, 300))]
    /// PCHIP never leaves the box of an interval's two samples (no overshoot), and passes
    /// through every sample exactly.
    #[test]
    fn no_overshoot_past_samples(
        steps in prop::collection::vec((0.2f64..5.0, -30.0f64..30.0, -30.0f64..30.0), 2..60),
        probes in prop::collection::vec(0.0f64..1.0, 20),
    ) {
        let mut t = 0.0;
        let (mut x, mut z) = (0.0, 0.0);
        let mut track = vec![[0.0, 0.0, 0.0]];
        for (dt, dx, dz) in &steps {
            t += dt;
            // Some flat runs too: equal values must stay exactly flat.
            if *dx > 20.0 { } else { x += dx; }
            z += dz;
            track.push([t, x, z]);
        }
        let r = race_json(&track);
        let b = &r.boats[0];
        let f = b.fixes();
        prop_assert_eq!(f.len(), track.len());
        for w in f.windows(2) {
            for p in &probes {
                let tt = w[0].t + p * (w[1].t - w[0].t);
                let s = b.state_at(tt);
                prop_assert!(s.position[0] >= w[0].x.min(w[1].x) && s.position[0] <= w[0].x.max(w[1].x));
                prop_assert!(s.position[1] >= w[0].z.min(w[1].z) && s.position[1] <= w[0].z.max(w[1].z));
            }
        }
        for p in f {
            let s = b.state_at(p.t);
            prop_assert_eq!(s.position, [p.x, p.z]);
        }
    }
}

#[test]
fn straight_line_at_constant_speed_is_reproduced() {
    // 3 m/s on a bearing of 60°: x = 3 sin60 t, z = -3 cos60 t.
    let (sx, sz) = (
        3.0 * 60f64.to_radians().sin(),
        -3.0 * 60f64.to_radians().cos(),
    );
    let track: Vec<[f64; 3]> = (0..30)
        .map(|i| [i as f64, sx * i as f64, sz * i as f64])
        .collect();
    let r = race_json(&track);
    let s = r.boats[0].state_at(12.37);
    // Slopes are stored in f32 (track.rs): a micrometre is the bound that allows.
    assert!((s.position[0] - sx * 12.37).abs() < 1e-6);
    assert!((s.position[1] - sz * 12.37).abs() < 1e-6);
    assert!((s.speed_mps - 3.0).abs() < 1e-5);
    assert!((s.heading_deg - 60.0).abs() < 1e-4, "{}", s.heading_deg);
    assert!((s.sailed_m - 3.0 * 12.37).abs() < 1e-6);
    assert!(s.racing && !s.in_gap);
}

#[test]
fn gps_jitter_does_not_spin_the_boat() {
    // Northbound at 2 m/s with ±1.5 m of alternating sideways jitter at 1 Hz: raw successive
    // bearings swing by ±56°; the smoothed heading stays within 25° of north.
    let track: Vec<[f64; 3]> = (0..60)
        .map(|i| {
            let j = if i % 2 == 0 { 1.5 } else { -1.5 };
            [i as f64, j, -2.0 * i as f64]
        })
        .collect();
    let r = race_json(&track);
    for k in 10..500 {
        let t = 5.0 + k as f64 * 0.1;
        let h = r.boats[0].state_at(t).heading_deg;
        let off = (h + 180.0).rem_euclid(360.0) - 180.0;
        assert!(off.abs() < 25.0, "t {t}: heading {h}");
    }
}

#[test]
fn outside_the_track_the_boat_is_held_and_not_racing() {
    let r = race_json(&[[10.0, 1.0, 2.0], [20.0, 11.0, 2.0], [30.0, 21.0, 2.0]]);
    let b = &r.boats[0];
    let before = b.state_at(0.0);
    assert!(!before.racing && before.position == [1.0, 2.0] && before.speed_mps == 0.0);
    let after = b.state_at(99.0);
    assert!(!after.racing && after.position == [21.0, 2.0]);
    assert!(!b.state_at(f64::NAN).racing);
    assert!(b.state_at(10.0).racing && b.state_at(30.0).racing);
    assert_eq!(r.time_span(), (10.0, 30.0));
    // Heading east at the ends too.
    assert!((before.heading_deg - 90.0).abs() < 1e-4);
}

#[test]
fn a_gap_is_crossed_straight_and_flagged() {
    // 1 Hz for 10 s, then nothing for 60 s (> 20 s limit), then 1 Hz again.
    let mut track: Vec<[f64; 3]> = (0..10).map(|i| [i as f64, i as f64, 0.0]).collect();
    track.extend((0..10).map(|i| [70.0 + i as f64, 100.0 + i as f64, 50.0]));
    let r = race_json(&track);
    let b = &r.boats[0];
    assert_eq!(b.gaps().collect::<Vec<_>>(), [9]);
    let s = b.state_at(39.5);
    assert!(s.in_gap);
    assert!(
        (s.position[0] - (9.0 + 0.5 * 91.0)).abs() < 1e-9 && (s.position[1] - 25.0).abs() < 1e-9
    );
    assert!(!b.state_at(5.0).in_gap && !b.state_at(75.0).in_gap);
}

#[test]
fn states_at_fills_every_boat_without_reallocating() {
    let r = Race::sample();
    let mut v = Vec::with_capacity(r.boats.len());
    let cap = v.capacity();
    let ptr = v.as_ptr();
    for k in 0..100 {
        r.states_at(k as f64 * 7.0, &mut v);
        assert_eq!(v.len(), r.boats.len());
    }
    assert_eq!((v.capacity(), v.as_ptr()), (cap, ptr));
}

#[test]
fn fixes_between_and_bounds() {
    let r = race_json(&[
        [0.0, 1.0, 2.0],
        [1.0, 5.0, -3.0],
        [2.0, 9.0, 4.0],
        [3.0, -2.0, 0.0],
    ]);
    let b = &r.boats[0];
    let ts = |s: &[race::Fix]| s.iter().map(|f| f.t).collect::<Vec<_>>();
    assert_eq!(ts(b.fixes_between(0.5, 2.0)), [1.0, 2.0]);
    assert_eq!(ts(b.fixes_between(-9.0, 0.0)), [0.0]);
    assert!(b.fixes_between(3.5, 9.0).is_empty());
    assert!(b.fixes_between(2.0, 1.0).is_empty());
    assert_eq!(r.bounds(), Some([[-2.0, -3.0], [9.0, 4.0]]));
}
