//! Issue 30's command-line cases that need no GPU, through the built binary: negative numbers
//! for whole-number options say their range, one range for `sea --depth` both ways, one path
//! for two outputs refused, `--camera` and `--t` capped as `probe` caps them, capped scripts,
//! named pipes refused before they block, an invalid `REGATTA_EXIT_AFTER_FRAMES` refused, and
//! messages without raw paths or Rust Debug text.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{fails_with, regatta, regatta_within_a_minute, temp_file};

fn tmp(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

#[test]
fn negative_whole_numbers_are_values_refused_with_their_range() {
    let out = tmp("cli_rel_neg");
    let out = out.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["sea", "--hs", "2", "--tp", "8", "--waves", "-1"],
            "invalid value '-1' for '--waves <WAVES>': give a whole number from 1 to 4096",
        ),
        (
            vec!["sea", "--hs", "2", "--tp", "8", "--seed", "-1"],
            "invalid value '-1' for '--seed <SEED>': give a whole number from 0 to 18446744073709551615",
        ),
        (
            vec!["replay", "synth", "--out", out, "--frames", "-1"],
            "invalid value '-1' for '--frames <N>': give a whole number from 1 to 100000",
        ),
        (
            vec![
                "render", "--out", "x.png", "--replay", "synth", "--frame", "-1",
            ],
            "invalid value '-1' for '--frame <N>': give a whole number from 0 to the feed's last frame",
        ),
        (
            vec!["race", "--report", "--session", "-1"],
            "invalid value '-1' for '--session <SESSION>': give a whole number from 1 (the first session)",
        ),
        (
            vec!["render", "--out", "x.png", "--size", "-5x3"],
            "--size \"-5x3\" is not WIDTHxHEIGHT",
        ),
        (
            vec!["replay", "synth", "--out", out, "--size", "-5x3"],
            "--size \"-5x3\" is not WxH",
        ),
    ] {
        fails_with(&args, needle);
    }
    assert!(!Path::new(out).exists());
}

#[test]
fn sea_depth_has_one_range_for_writing_and_reading() {
    fails_with(
        &["sea", "--hs", "2", "--tp", "8", "--depth", "20000"],
        "--depth must lie in 0.01..=11000 m",
    );
    // The deepest depth written reads back.
    let (code, sea, err) = regatta(&["sea", "--hs", "2", "--tp", "8", "--depth", "11000"]);
    assert_eq!(code, 0, "{err}");
    let file = temp_file("cli_rel_deep.json", &sea);
    let (code, _, err) = regatta(&[
        "probe",
        "--t",
        "0",
        "--at",
        "0,0",
        "--sea",
        file.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn render_refuses_one_path_for_image_and_record_and_caps_camera_and_time() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let a = dir.join("cli_rel_same.png");
    let b = dir.join(".").join("cli_rel_same.png");
    for report in [&a, &b] {
        fails_with(
            &[
                "render",
                "--out",
                a.to_str().unwrap(),
                "--report",
                report.to_str().unwrap(),
            ],
            "--out and --report are the same file",
        );
    }
    assert!(!a.exists());
    fails_with(
        &["render", "--out", "x.png", "--camera", "1e300,0,0,0,0,0"],
        "--camera \"1e300,0,0,0,0,0\" lies outside the world: every coordinate must lie within ±1e6 m",
    );
    for cmd in [
        vec!["render", "--out", "x.png", "--t", "1e300"],
        vec!["race", "--t", "1e300"],
    ] {
        fails_with(
            &cmd,
            "--t 1e300 is not a finite number of seconds within ±1e9",
        );
    }
}

#[test]
fn scripts_are_capped_and_named_pipes_refused_before_they_block() {
    let out = tmp("cli_rel_sim");
    if Path::new("/dev/zero").exists() {
        let (code, stdout, err) = regatta_within_a_minute(
            &[
                "phone-sim",
                "--script",
                "/dev/zero",
                "--out",
                out.to_str().unwrap(),
            ],
            &[],
            &[],
        );
        assert_ne!(code, 0);
        assert!(stdout.is_empty());
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains("/dev/zero is not a phone-sim script: byte 0 is NUL"),
            "{err}"
        );
    }
    let fifo = tmp("cli_rel_fifo");
    let _ = std::fs::remove_file(&fifo);
    if !Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        eprintln!("mkfifo is not available; the FIFO cases are skipped");
        return;
    }
    let f = fifo.to_str().unwrap();
    for args in [
        vec!["probe", "--t", "0", "--at", "0,0", "--sea", f],
        vec!["sea", "--ndbc", f],
        vec!["phone-sim", "--script", f, "--out", out.to_str().unwrap()],
    ] {
        let (code, _, err) = regatta_within_a_minute(&args, &[], &[]);
        assert_ne!(code, 0, "{args:?}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("is a named pipe (FIFO)"), "{args:?}: {err}");
    }
    let (code, _, err) = regatta_within_a_minute(&["race", "--t", "0", "--race", f], &[], &[]);
    assert_ne!(code, 0);
    assert!(err.contains("is not a regular file"), "{err}");
    std::fs::remove_file(&fifo).unwrap();
}

#[test]
fn an_invalid_exit_after_frames_is_refused_before_a_window_opens() {
    for v in ["-1", "abc", "1e30", "", "0"] {
        let (code, out, err) =
            regatta_within_a_minute(&["run"], &[("REGATTA_EXIT_AFTER_FRAMES", v)], &[]);
        assert_ne!(code, 0, "{v:?}");
        assert!(out.is_empty());
        assert_eq!(err.lines().count(), 1, "{v:?}: {err}");
        assert!(
            err.contains(&format!(
                "REGATTA_EXIT_AFTER_FRAMES is \"{v}\"; give a whole number of frames from 1"
            )),
            "{v:?}: {err}"
        );
    }
}

#[test]
fn run_without_a_display_names_no_source_path() {
    let (code, _, err) = regatta_within_a_minute(
        &["run"],
        &[("REGATTA_EXIT_AFTER_FRAMES", "1")],
        &["DISPLAY", "WAYLAND_DISPLAY"],
    );
    assert_ne!(code, 0);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("cannot open a window"), "{err}");
    assert!(!err.contains(".cargo") && !err.contains(".rs:"), "{err}");
}

#[test]
fn info_lines_escape_the_paths_they_echo_and_bad_intrinsics_are_named_by_field() {
    let out = tmp("cli_rel_feed\nx\u{1b}[2J");
    let _ = std::fs::remove_dir_all(&out);
    let (code, _, err) = regatta(&[
        "replay",
        "synth",
        "--out",
        out.to_str().unwrap(),
        "--frames",
        "2",
        "--size",
        "16x16",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("cli_rel_feed\\nx\\u{1b}[2J"), "{err:?}");
    assert!(!err.contains('\u{1b}'), "{err:?}");
    // The feed's intrinsics with fx = 0: named by field, not as Rust's Debug text.
    let session = out.join("session.json");
    let text = std::fs::read_to_string(&session).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let fx = find_key(&mut v, "fx").expect("session.json has fx");
    *fx = serde_json::json!(0.0);
    std::fs::write(&session, v.to_string()).unwrap();
    let (code, _, err) = regatta(&["replay", "check", out.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("got fx 0, fy "), "{err}");
    assert!(!err.contains("Intrinsics {"), "{err}");
    std::fs::remove_dir_all(&out).unwrap();
}

/// The first value under `key` anywhere in `v`.
fn find_key<'a>(v: &'a mut serde_json::Value, key: &str) -> Option<&'a mut serde_json::Value> {
    match v {
        serde_json::Value::Object(m) => {
            if m.contains_key(key) {
                return m.get_mut(key);
            }
            m.values_mut().find_map(|x| find_key(x, key))
        }
        serde_json::Value::Array(a) => a.iter_mut().find_map(|x| find_key(x, key)),
        _ => None,
    }
}
