//! `regatta replay`: JSON on stdout, one sentence on stderr and a non-zero exit for bad input.

use std::path::PathBuf;
use std::process::Command;

fn regatta(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn synth_writes_a_feed_that_check_reads_back() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("replay_cli_synth");
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let (ok, out, err) = regatta(&[
        "replay", "synth", "--out", d, "--frames", "3", "--size", "64x48",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["frames"], 3);
    assert_eq!(v["intrinsics"]["width"], 64);
    assert_eq!(v["intrinsics"]["height"], 48);
    // 65° horizontal field of view: fx = 32 / tan(32.5°).
    let fx = v["intrinsics"]["fx"].as_f64().unwrap();
    assert!((fx - 32.0 / 32.5f64.to_radians().tan()).abs() < 1e-9);
    assert_eq!(v["planes"][0]["extent"][0].as_f64().unwrap() as f32, 1.2f32);
    let (ok, out2, _) = regatta(&["replay", "check", d]);
    assert!(ok);
    assert_eq!(out, out2);
}

#[test]
fn bad_input_is_one_sentence_and_a_non_zero_exit() {
    let (ok, out, err) = regatta(&["replay", "synth", "--out", "/tmp/never", "--size", "64by48"]);
    assert!(!ok && out.is_empty());
    assert!(err.contains("--size \"64by48\""), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");

    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("replay_cli_bad");
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    assert!(
        regatta(&[
            "replay", "synth", "--out", d, "--frames", "2", "--size", "32x24"
        ])
        .0
    );
    std::fs::write(dir.join("frames.txt"), "0 frames/000000.jpg 0 0 1 0 0 0\n").unwrap();
    let (ok, _, err) = regatta(&["replay", "check", d]);
    assert!(!ok);
    assert!(
        err.contains("frames.txt line 1") && err.contains("found 8"),
        "{err}"
    );

    let (ok, _, err) = regatta(&["run", "--replay", "/nonexistent/feed"]);
    assert!(!ok);
    assert!(
        err.contains("/nonexistent/feed") && err.contains("is not a feed"),
        "{err}"
    );
}
