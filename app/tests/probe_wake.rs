//! `regatta probe --race`: the boats' Kelvin wakes in the probe's JSON, checked against the
//! independent Havelock reference through the built binary.

mod common;

use std::path::PathBuf;

use common::{f, fails_with, ok_json, temp_file};
use ocean::wake::{SteadyPatch, WakeParams, kelvin_reference};

/// One boat sailing +x at 5 m/s, reaching (0, 0) at t = 200 s, fixes every second.
fn straight_race() -> PathBuf {
    let track: Vec<String> = (0..=200)
        .map(|i| format!("[{i}, {}, 0.0]", 5.0 * (i as f64 - 200.0)))
        .collect();
    let json = format!(
        "{{\"name\": \"straight\", \"origin\": null, \"start_time\": null, \"boats\": \
         [{{\"id\": \"ONE\", \"name\": \"One\", \"color\": \"#ff0000\", \"track\": [{}]}}], \
         \"marks\": []}}",
        track.join(", ")
    );
    temp_file("probe_wake_straight.json", &json)
}

#[test]
fn wake_height_matches_the_havelock_reference_and_adds_to_height() {
    let race = straight_race();
    let prm = WakeParams::default();
    let patch = SteadyPatch {
        speed: 5.0,
        force: prm.force,
        hull_radius: prm.hull_radius,
        gravity: prm.gravity,
    };
    let lam = patch.wavelength();
    let pts: Vec<[f64; 2]> = [(4.0, 0.0), (4.3, 0.0), (4.6, 0.0), (5.0, 0.8), (6.0, 1.2)]
        .iter()
        .map(|(a, b)| [-a * lam, b * lam])
        .collect();
    let mut args = vec![
        "probe".to_string(),
        "--t".into(),
        "200".into(),
        "--race".into(),
        race.display().to_string(),
    ];
    for p in &pts {
        args.push("--at".into());
        args.push(format!("{},{}", p[0], p[1]));
    }
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let v = ok_json(&argv);
    let out = v["points"].as_array().unwrap();
    for (o, p) in out.iter().zip(&pts) {
        let w = f(&o["wake_height"]);
        let (want, _) = kelvin_reference(&patch, p[0], p[1]);
        let scale = prm.transverse_amplitude(5.0, -p[0]);
        assert!(
            (w - want).abs() <= 0.2 * scale,
            "{p:?}: {w} vs {want} (A_T {scale})"
        );
        assert!((f(&o["height"]) - f(&o["sea_height"]) - w).abs() < 1e-12);
        let n = &o["normal"];
        let len = f(&n[0]).hypot(f(&n[1])).hypot(f(&n[2]));
        assert!((len - 1.0).abs() < 1e-12);
        let foam = f(&o["foam"]);
        assert!((0.0..=1.0).contains(&foam));
    }
    // Right behind the boat the foam strip is white; ahead of it there is no wake.
    let v = ok_json(&[
        "probe",
        "--t",
        "200",
        "--race",
        race.to_str().unwrap(),
        "--at",
        "-3,0",
        "--at",
        "200,0",
    ]);
    let p = v["points"].as_array().unwrap();
    assert!(f(&p[0]["foam"]) > 0.3, "{}", p[0]);
    assert!(f(&p[1]["wake_height"]).abs() < 1e-4, "{}", p[1]);
}

#[test]
fn the_sample_race_makes_wakes_without_race_files() {
    let v = ok_json(&["probe", "--t", "300", "--at", "0,0", "--at", "-100,200"]);
    for p in v["points"].as_array().unwrap() {
        assert!(f(&p["wake_height"]).is_finite());
    }
}

#[test]
fn a_missing_race_file_is_one_clear_error() {
    fails_with(
        &[
            "probe",
            "--t",
            "1",
            "--at",
            "0,0",
            "--race",
            "/nonexistent/race.json",
        ],
        "/nonexistent/race.json",
    );
}
