//! `regatta replay`: JSON on stdout, one sentence on stderr and a non-zero exit for bad input.

mod common;

use std::path::PathBuf;

use common::{fails_with, regatta};

#[test]
fn synth_writes_a_feed_that_check_reads_back() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("replay_cli_synth");
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let (code, out, err) = regatta(&[
        "replay", "synth", "--out", d, "--frames", "3", "--size", "64x48",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["frames"], 3);
    assert_eq!(v["intrinsics"]["width"], 64);
    assert_eq!(v["intrinsics"]["height"], 48);
    // 65° horizontal field of view: fx = 32 / tan(32.5°).
    let fx = v["intrinsics"]["fx"].as_f64().unwrap();
    assert!((fx - 32.0 / 32.5f64.to_radians().tan()).abs() < 1e-9);
    assert_eq!(v["planes"][0]["extent"][0].as_f64().unwrap() as f32, 1.2f32);
    let (code, out2, _) = regatta(&["replay", "check", d]);
    assert_eq!(code, 0);
    assert_eq!(out, out2);
}

#[test]
fn bad_input_is_one_sentence_and_a_non_zero_exit() {
    fails_with(
        &["replay", "synth", "--out", "/tmp/never", "--size", "64by48"],
        "--size \"64by48\"",
    );

    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("replay_cli_bad");
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let (code, _, err) = regatta(&[
        "replay", "synth", "--out", d, "--frames", "2", "--size", "32x24",
    ]);
    assert_eq!(code, 0, "{err}");
    std::fs::write(dir.join("frames.txt"), "0 frames/000000.jpg 0 0 1 0 0 0\n").unwrap();
    let (code, _, err) = regatta(&["replay", "check", d]);
    assert_ne!(code, 0);
    assert!(
        err.contains("frames.txt line 1") && err.contains("found 8"),
        "{err}"
    );

    let (code, _, err) = regatta(&["run", "--replay", "/nonexistent/feed"]);
    assert_ne!(code, 0);
    assert!(
        err.contains("/nonexistent/feed") && err.contains("is not a feed"),
        "{err}"
    );
}
