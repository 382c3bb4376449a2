//! `regatta probe --race`: the boats' Kelvin wakes in the probe's JSON, checked against the
//! independent Havelock reference through the built binary.

mod common;

use std::path::PathBuf;

use common::{f, fails_with, ok_json, temp_file};
use ocean::wake::{SteadyPatch, WakeParams, kelvin_reference};

/// Relative RMS of the sample race's wake against the steady reference: measured 0.29 (the
/// boat's speed and course vary, the reference's do not), asserted at 1.5x. A zero wake is
/// 1.0; one of half the size about 0.55.
const REL_TOL: f64 = 1.5 * 0.29;

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

/// Without `--race` the probe uses the embedded sample race, and its wakes have the size the
/// Havelock reference gives: on the centreline 4–5 wavelengths behind the boat whose course
/// has been steadiest, the probe's wake height against `kelvin_reference` for that boat's speed
/// (a zero or a wrong-sized wake fails; `is_finite` alone let a zero wake pass).
#[test]
fn the_sample_race_makes_wakes_without_race_files() {
    let race = race::Race::sample();
    let t = 300.0;
    // The boat whose velocity changed least over the last 30 s (a steady, straight run).
    let steadiness = |b: &race::Boat| {
        let now = b.state_at(t).velocity;
        (1..=30)
            .map(|k| {
                let v = b.state_at(t - k as f64).velocity;
                (v[0] - now[0]).hypot(v[1] - now[1])
            })
            .fold(0.0, f64::max)
    };
    let boat = race
        .boats
        .iter()
        .min_by(|a, b| steadiness(a).total_cmp(&steadiness(b)))
        .unwrap();
    let state = boat.state_at(t);
    let u = state.speed_mps;
    let dir = [state.velocity[0] / u, state.velocity[1] / u];
    let prm = WakeParams::default();
    let patch = SteadyPatch {
        speed: u,
        force: prm.force,
        hull_radius: prm.hull_radius,
        gravity: prm.gravity,
    };
    let lam = patch.wavelength();
    let behind: Vec<f64> = (0..8).map(|i| (4.0 + 0.125 * i as f64) * lam).collect();
    let mut args = vec!["probe".to_string(), "--t".into(), format!("{t}")];
    for d in &behind {
        let p = [
            state.position[0] - d * dir[0],
            state.position[1] - d * dir[1],
        ];
        args.push("--at".into());
        args.push(format!("{},{}", p[0], p[1]));
    }
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let v = ok_json(&argv);
    let points = v["points"].as_array().unwrap();
    let (mut err2, mut ref2) = (0.0, 0.0);
    for (o, d) in points.iter().zip(&behind) {
        let got = f(&o["wake_height"]);
        let (want, _) = kelvin_reference(&patch, -d, 0.0);
        eprintln!(
            "{} at {u:.2} m/s, {:.2} λ behind: wake {got:.5} m, reference {want:.5} m",
            boat.id,
            d / lam
        );
        err2 += (got - want).powi(2);
        ref2 += want * want;
    }
    let rel = (err2 / ref2).sqrt();
    let a_t = prm.transverse_amplitude(u, behind[0]);
    eprintln!("relative RMS {rel:.3}, A_T {a_t:.4} m");
    assert!(
        a_t > 1e-3,
        "test geometry: A_T {a_t} m is too small to tell a wake from none"
    );
    assert!(
        rel < REL_TOL,
        "{}: relative RMS {rel} against the reference",
        boat.id
    );
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
