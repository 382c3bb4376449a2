//! Roundings, ranks and distance behind the leader on a race whose answers are closed-form.

use race::Race;

/// S at (0, 0), W 1000 m north. A sails 2 m/s, B 1.5 m/s, C 1 m/s straight to W and back;
/// D's log starts at t = 300.
fn race() -> Race {
    let leg = |v: f64, t0: f64| -> Vec<[f64; 3]> {
        let up = 1000.0 / v;
        (0..=(2.0 * up) as usize)
            .map(|i| {
                let t = i as f64;
                let z = if t <= up {
                    -v * t
                } else {
                    -1000.0 + v * (t - up)
                };
                [t0 + t, 0.0, z]
            })
            .collect()
    };
    let json = serde_json::json!({
        "name": "closed form",
        "boats": [
            {"id": "C", "track": leg(1.0, 0.0)},
            {"id": "A", "track": leg(2.0, 0.0)},
            {"id": "B", "track": leg(1.5, 0.0)},
            {"id": "D", "track": leg(2.0, 300.0)},
        ],
        "marks": [{"name": "S", "position": [0, 0]}, {"name": "W", "position": [0, -1000]}],
        "course": ["S", "W", "S"],
    });
    Race::from_files(&[("c.json", json.to_string().as_bytes())]).unwrap()
}

fn ids(r: &Race, t: f64) -> Vec<(String, usize, f64)> {
    r.standings(t)
        .iter()
        .map(|s| {
            (
                r.boats[s.boat].id.clone(),
                s.rank,
                (s.distance_m * 1e6).round() / 1e6,
            )
        })
        .collect()
}

#[test]
fn roundings_are_the_closest_approaches() {
    let r = race();
    let a = &r.boats[r.boat_index("A").unwrap()];
    assert_eq!(a.roundings(), [Some(0.0), Some(500.0), Some(1000.0)]);
    let c = &r.boats[r.boat_index("C").unwrap()];
    assert_eq!(c.roundings(), [Some(0.0), Some(1000.0), Some(2000.0)]);
    let d = &r.boats[r.boat_index("D").unwrap()];
    assert_eq!(d.roundings(), [Some(300.0), Some(800.0), Some(1300.0)]);
    assert_eq!(r.leg_lengths(), [1000.0, 1000.0]);
    // The timeline's jump list: every rounding, in time order.
    let ev = r.rounding_events();
    assert_eq!(ev.len(), 12);
    assert!(ev.windows(2).all(|w| w[0].t <= w[1].t));
    let first_w = ev.iter().find(|e| e.mark == "W").unwrap();
    assert_eq!(
        (
            r.boats[first_w.boat].id.as_str(),
            first_w.t,
            first_w.course_index
        ),
        ("A", 500.0, 1)
    );
}

#[test]
fn ranks_and_distance_behind_the_leader() {
    let r = race();
    // t = 100: A 200 m up (1800 to go), B 150, C 100; D not started: last, at the start
    // line with the whole 2000 m course to go, 200 m behind A.
    let s = ids(&r, 100.0);
    let want: Vec<(String, usize, f64)> = vec![
        ("A".into(), 1, 0.0),
        ("B".into(), 2, 50.0),
        ("C".into(), 3, 100.0),
        ("D".into(), 4, 200.0),
    ];
    assert_eq!(s, want);
    // t = 600: A rounded W and is 200 m back down (800 to go); B at 900 up (1100 to go);
    // D started at 300, 600 m up (1400 to go); C at 600 up (1400 to go: a tie, id order).
    let s = ids(&r, 600.0);
    assert_eq!(s[0], ("A".into(), 1, 0.0));
    assert_eq!(s[1], ("B".into(), 2, 300.0));
    assert_eq!((s[2].2, s[3].2), (600.0, 600.0));
    // t = 1100: A finished (its log ended at 1000: not racing), first with distance 0.
    let st = r.standings(1100.0);
    assert_eq!(r.boats[st[0].boat].id, "A");
    assert!(st[0].finished && !st[0].racing && st[0].distance_m == 0.0);
    // B: rounded W at 666.67 s, then 433.33 s × 1.5 m/s = 650 m back: 350 m to go.
    let b = st.iter().find(|s| r.boats[s.boat].id == "B").unwrap();
    assert_eq!(b.legs_completed, 2);
    assert!((b.remaining_m.unwrap() - 350.0).abs() < 1.0, "{b:?}");
}
