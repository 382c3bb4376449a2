//! `regatta sea` through the built binary: its output is a sea file that probe accepts.

mod common;

use std::path::PathBuf;

use common::{fails_with, far_race, run};

use ocean::WaveSet;

fn ndbc(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../crates/ocean/tests/data/ndbc")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn jonswap_sea_file_is_valid_and_reports_its_scaling() {
    let out = run(&[
        "sea", "--hs", "3", "--tp", "5", "--waves", "24", "--seed", "7",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let sea = WaveSet::from_json_str(&text, "stdout").unwrap();
    assert_eq!(sea.waves.len(), 24);
    // A steep short sea (Hs 3 m at Tp 5 s) must be scaled to Σ kA = 0.8, and say so.
    assert!((sea.total_steepness() - 0.8).abs() < 1e-9);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("amplitude scale 0."), "{err}");
    // The file feeds probe.
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sea_jonswap.json");
    std::fs::write(&path, &text).unwrap();
    // (With a race far away, so the test does not depend on the embedded sample race.)
    let race = far_race("sea_far_race.json");
    let p = run(&[
        "probe",
        "--t",
        "60",
        "--at",
        "5,5",
        "--sea",
        path.to_str().unwrap(),
        "--race",
        race.to_str().unwrap(),
    ]);
    assert!(p.status.success(), "{}", String::from_utf8_lossy(&p.stderr));
}

#[test]
fn ndbc_sea_file_from_the_buoy() {
    let out = run(&[
        "sea",
        "--ndbc",
        &ndbc("41010.data_spec"),
        "--ndbc-dir",
        &ndbc("41010.swdir"),
        "--ndbc-r1",
        &ndbc("41010.swr1"),
        "--time",
        "2020-06-02 10:50",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let sea = WaveSet::from_json_str(&String::from_utf8(out.stdout).unwrap(), "stdout").unwrap();
    assert!(!sea.waves.is_empty() && sea.total_steepness() <= 0.8 + 1e-9);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("2020-06-02 10:50 with Hs = 2.05 m"), "{err}");
}

#[test]
fn bad_sea_arguments_fail_with_one_sentence() {
    for (args, needle) in [
        (vec!["sea", "--hs", "2"], "either --hs and --tp"),
        (
            vec!["sea", "--hs", "-2", "--tp", "8"],
            "--hs is -2 m, outside (0, 30] m",
        ),
        (
            vec!["sea", "--hs", "2", "--tp", "8", "--gamma", "0.5"],
            "--gamma",
        ),
        (
            vec!["sea", "--hs", "2", "--tp", "8", "--max-steepness", "1"],
            "folds over",
        ),
        (
            vec!["sea", "--ndbc", "/nonexistent/x.data_spec"],
            "could not read /nonexistent/x.data_spec",
        ),
        (
            vec!["sea", "--ndbc", "FILE", "--time", "yesterday"],
            "--time \"yesterday\"",
        ),
    ] {
        let args: Vec<String> = args
            .iter()
            .map(|a| {
                if *a == "FILE" {
                    ndbc("41010.data_spec")
                } else {
                    a.to_string()
                }
            })
            .collect();
        let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        fails_with(&args, needle);
    }
}
