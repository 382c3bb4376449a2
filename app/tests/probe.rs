//! `regatta probe` through the built binary: the JSON contract of docs/command-line.md and its errors.

mod common;

use common::{f, fails_with, far_race, ok_json, temp_file};
use ocean::WaveSet;

#[test]
fn default_sea_points_obey_the_contract() {
    let race = far_race("probe_far_race.json");
    let v = ok_json(&[
        "probe",
        "--t",
        "125.5",
        "--at",
        "10,-20",
        "--at",
        "-3000.5,4000",
        "--race",
        race.to_str().unwrap(),
    ]);
    assert_eq!(f(&v["t"]), 125.5);
    let sea = WaveSet::default_sea();
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 2);
    for (p, at) in pts.iter().zip([[10.0, -20.0], [-3000.5, 4000.0]]) {
        assert_eq!(f(&p["at"][0]), at[0]);
        assert_eq!(f(&p["at"][1]), at[1]);
        // `rest` is carried to `at` by the waves, and `sea_height` is the height there.
        let rest = [f(&p["rest"][0]), f(&p["rest"][1])];
        let d = sea.displace(rest, 125.5);
        assert!((d[0] - at[0]).hypot(d[2] - at[1]) <= 1e-6, "{p}");
        assert!((f(&p["sea_height"]) - d[1]).abs() < 1e-9);
        assert!(f(&p["wake_height"]).abs() < 1e-9, "{p}");
        let sum = f(&p["sea_height"]) + f(&p["wake_height"]);
        assert!((f(&p["height"]) - sum).abs() < 1e-12);
        // The normal is the analytic one of the surface at the rest point.
        let sp = sea.surface(rest, 125.5);
        for i in 0..3 {
            assert!((f(&p["normal"][i]) - sp.normal[i]).abs() < 1e-8, "{p}");
        }
        assert!((f(&p["foam"]) - ocean::foam_from_jacobian(sp.jacobian)).abs() < 1e-9);
    }
}

#[test]
fn sea_file_with_one_wave_against_the_closed_form() {
    // One wave along +x, kA = 0.5, λ = 20 m: height at X solves X = x0 + A cos θ(x0) with
    // θ = k x0 − ω t; found here independently by bisection.
    let sea = temp_file(
        "probe_one_wave.json",
        r#"{"gravity": 9.81, "depth": null,
            "waves": [{"direction": [2.0, 0.0], "steepness": 0.5, "wavelength": 20.0}]}"#,
    );
    let t = 3.0;
    let race = far_race("probe_far_race.json");
    let v = ok_json(&[
        "probe",
        "--t",
        "3",
        "--at",
        "7.25,100",
        "--sea",
        sea.to_str().unwrap(),
        "--race",
        race.to_str().unwrap(),
    ]);
    let k = std::f64::consts::TAU / 20.0;
    let (a, w) = (0.5 / k, (9.81 * k).sqrt());
    let x_of = |x0: f64| x0 + a * (k * x0 - w * t).cos();
    let (mut lo, mut hi) = (7.25 - 2.0 * a, 7.25 + 2.0 * a);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if x_of(m) < 7.25 { lo = m } else { hi = m }
    }
    let th = k * lo - w * t;
    let p = &v["points"][0];
    assert!((f(&p["rest"][0]) - lo).abs() < 1e-5, "{p}");
    assert_eq!(f(&p["rest"][1]), 100.0);
    assert!((f(&p["height"]) - a * th.sin()).abs() < 1e-6);
    // Slope dh/dX = (dy/dx0) / (dX/dx0) = kA cos θ / (1 − kA sin θ).
    let slope = 0.5 * th.cos() / (1.0 - 0.5 * th.sin());
    let n = [-slope, 1.0, 0.0];
    let len = (1.0 + slope * slope).sqrt();
    for i in 0..3 {
        assert!((f(&p["normal"][i]) - n[i] / len).abs() < 1e-6, "{p}");
    }
    let jac = 1.0 - 0.5 * th.sin();
    assert!((f(&p["foam"]) - ((0.6 - jac) / 0.6).clamp(0.0, 1.0)).abs() < 1e-6);
}

#[test]
fn bad_arguments_give_one_sentence_and_fail() {
    fails_with(&["probe", "--at", "1,2"], "--t SECONDS is missing");
    fails_with(&["probe", "--t", "5"], "--at X,Z is missing");
    fails_with(&["probe", "--t", "5", "--at", "1"], "--at \"1\"");
    fails_with(&["probe", "--t", "5", "--at", "1,2,3"], "--at \"1,2,3\"");
    fails_with(&["probe", "--t", "5", "--at", "1,NaN"], "--at \"1,NaN\"");
    fails_with(&["probe", "--t", "5", "--at", "inf,0"], "not a point");
    fails_with(&["probe", "--t", "NaN", "--at", "1,2"], "--t \"NaN\"");
    fails_with(
        &["probe", "--t", "soon", "--at", "1,2"],
        "not a finite number",
    );
    fails_with(
        &[
            "probe",
            "--t",
            "1",
            "--at",
            "1,2",
            "--sea",
            "/nonexistent/sea.json",
        ],
        "could not read /nonexistent/sea.json",
    );
}

/// Writes `text` as sea file `name`, probes with it and expects a one-sentence failure naming
/// `needle`; returns the file's path.
fn sea_file_fails(name: &str, text: &str, needle: &str) -> std::path::PathBuf {
    let sea = temp_file(name, text);
    let s = sea.to_str().unwrap();
    fails_with(&["probe", "--t", "1", "--at", "0,0", "--sea", s], needle);
    sea
}

#[test]
fn invalid_sea_files_are_refused_naming_file_and_wave() {
    let steep = sea_file_fails(
        "probe_steep.json",
        r#"{"waves": [{"direction": [1, 0], "steepness": 0.6, "wavelength": 30},
                      {"direction": [0, 1], "steepness": 1.5, "wavelength": 10}]}"#,
        "wave 1",
    );
    let s = steep.to_str().unwrap();
    fails_with(&["probe", "--t", "1", "--at", "0,0", "--sea", s], s);
    sea_file_fails(
        "probe_fold.json",
        r#"{"waves": [{"direction": [1, 0], "steepness": 0.6, "wavelength": 30},
                      {"direction": [0, 1], "steepness": 0.5, "wavelength": 10}]}"#,
        "folds over",
    );
    sea_file_fails(
        "probe_zero_dir.json",
        r#"{"waves": [{"direction": [0, 0], "steepness": 0.1, "wavelength": 30}]}"#,
        "wave 0 has a zero \"direction\"",
    );
    sea_file_fails("probe_junk.json", "{\"waves\": [ oops ]}", "line 1");
}
