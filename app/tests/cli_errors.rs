//! Issue 15's command-line cases that need no GPU, through the built binary: every error is one
//! line of safe text (control characters from the input escaped), clap's usage errors are one
//! line, values outside their stated ranges are refused with one sentence, endless inputs are
//! refused at once, and a closed stdout is an error.

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::{fails_with, regatta, regatta_within_a_minute, temp_file};

/// The 41010 buoy files of ../shared/data/waves.
fn buoy(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/waves/ndbc-41010")
        .join(name)
        .display()
        .to_string()
}

/// One line on stderr with no control character in it.
fn assert_one_safe_line(err: &str) {
    let line = err.strip_suffix('\n').unwrap_or(err);
    assert!(!line.chars().any(char::is_control), "{err:?}");
}

#[test]
fn control_characters_in_a_sea_file_key_are_escaped() {
    let sea = temp_file(
        "cli_errors_key.json",
        r#"{"\nname\u001b[2J\u0007": 1, "waves": []}"#,
    );
    let args = [
        "probe",
        "--t",
        "1",
        "--at",
        "0,0",
        "--sea",
        sea.to_str().unwrap(),
    ];
    fails_with(&args, "unknown field `\\nname\\u{1b}[2J\\u{7}`");
    assert_one_safe_line(&regatta(&args).2);
}

#[test]
fn control_characters_in_file_names_and_values_are_escaped() {
    let (code, _, err) = regatta(&[
        "probe",
        "--t",
        "1",
        "--at",
        "0,0",
        "--sea",
        "no\nsuch\u{1b}.json",
    ]);
    assert_ne!(code, 0);
    assert_one_safe_line(&err);
    assert!(err.contains("no\\nsuch\\u{1b}.json"), "{err}");
    let (code, _, err) = regatta(&["probe", "--t", "1", "--at", "\u{7}x\ny"]);
    assert_ne!(code, 0);
    assert_one_safe_line(&err);
    assert!(err.contains("--at \"\\u{7}x\\ny\""), "{err}");
    // Quoted input is cut to a readable length.
    let long = "9".repeat(5000);
    let (_, _, err) = regatta(&["probe", "--t", "1", "--at", &long]);
    assert!(err.len() < 300, "{} bytes: {err}", err.len());
}

/// Clap printed 3 to 6 lines (error, tip, usage, "for more information") for these.
#[test]
fn usage_errors_are_one_line_and_help_is_unchanged() {
    for (args, needle) in [
        (
            vec!["race", "--t", "1", "--t", "2"],
            "cannot be used multiple times",
        ),
        (
            vec!["race", "--bogus"],
            "unexpected argument '--bogus' found",
        ),
        (vec!["render", "--frame", "1", "--out", "a.png"], "--replay"),
        (
            vec!["sea", "--waves", "x"],
            "invalid value 'x' for '--waves",
        ),
        (vec!["nosuch"], "unrecognized subcommand 'nosuch'"),
    ] {
        let (code, out, err) = regatta(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("regatta: ") && err.contains(needle),
            "{args:?}: {err}"
        );
        assert!(err.trim_end().ends_with("(see --help)"), "{err}");
    }
    let (code, out, _) = regatta(&["render", "--help"]);
    assert_eq!(code, 0);
    assert!(
        out.lines().count() > 10 && out.contains("Usage: regatta render"),
        "{out}"
    );
}

/// `render --t -5` was a clap usage error ("unexpected argument '-5'") while race and probe
/// took it: now every subcommand's --t takes a negative time (here render stops later, at its
/// --out, before any GPU work).
#[test]
fn negative_times_are_accepted_everywhere() {
    fails_with(
        &["render", "--t", "-5", "--out", "x.bmp"],
        "--out \"x.bmp\" must name a .png or .jpg file",
    );
    fails_with(
        &["render", "--error-px", "-1", "--out", "x.png"],
        "--error-px -1 is outside 0.1 to 100 pixels",
    );
    let race = common::far_race("cli_errors_far.json");
    let v = common::ok_json(&["race", "--t", "-5", "--race", race.to_str().unwrap()]);
    assert_eq!(v["t"], -5.0);
}

#[test]
fn values_outside_their_ranges_are_one_sentence() {
    fails_with(
        &["probe", "--t", "0", "--at", "1e155,0"],
        "--at \"1e155,0\" lies outside the world: x and z must lie within ±1e6 m",
    );
    fails_with(
        &["sea", "--hs", "1e300", "--tp", "8"],
        "--hs is 1e300 m, outside (0, 30] m",
    );
    fails_with(
        &["sea", "--hs", "2", "--tp", "1e-300"],
        "--tp is 1e-300 s, outside [0.5, 30] s",
    );
    fails_with(
        &["sea", "--hs", "2", "--tp", "8", "--gamma", "1e9"],
        "--gamma is 1e9, outside [1, 10]",
    );
    for (name, l) in [
        ("cli_errors_long.json", "1e300"),
        ("cli_errors_short.json", "1e-300"),
    ] {
        let sea = temp_file(
            name,
            &format!(
                r#"{{"waves": [{{"direction": [1, 0], "steepness": 0.1, "wavelength": {l}}}]}}"#
            ),
        );
        fails_with(
            &[
                "probe",
                "--t",
                "0",
                "--at",
                "0,0",
                "--sea",
                sea.to_str().unwrap(),
            ],
            &format!("wave 0 has \"wavelength\" {l} m, outside 0.01..=5000 m"),
        );
    }
}

#[test]
fn ndbc_files_in_each_others_places_and_bad_times_are_refused() {
    fails_with(
        &["sea", "--ndbc", &buoy("41010.swdir")],
        "41010.swdir holds mean direction (alpha1) values, not spectral density values",
    );
    fails_with(
        &[
            "sea",
            "--ndbc",
            &buoy("41010.data_spec"),
            "--ndbc-r1",
            &buoy("41010.swdir"),
        ],
        "41010.swdir holds mean direction (alpha1) values, not r1 values",
    );
    fails_with(
        &[
            "sea",
            "--ndbc",
            &buoy("41010.data_spec"),
            "--time",
            "2020-13-01 00:50",
        ],
        "--time \"2020-13-01 00:50\" is not a real time: month 13 is not 1–12",
    );
}

/// `--sea /dev/zero` and `--ndbc /dev/zero` read until memory ran out (8.6 GB and growing).
#[test]
fn endless_inputs_are_refused_at_once() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    for (args, needle) in [
        (
            vec!["probe", "--t", "0", "--at", "0,0", "--sea", "/dev/zero"],
            "/dev/zero is not a sea file: it starts with byte 0x00",
        ),
        (
            vec!["sea", "--ndbc", "/dev/zero"],
            "/dev/zero is not an NDBC spectral file: byte 0 is NUL",
        ),
    ] {
        let (code, out, err) = regatta_within_a_minute(&args, &[], &[]);
        assert_ne!(code, 0);
        assert!(
            out.is_empty() && err.lines().count() == 1 && err.contains(needle),
            "{err}"
        );
    }
}

/// `regatta race --t 10 >&-` exited 0 with its JSON lost (Rust's stdout ignores EBADF).
#[test]
fn a_closed_stdout_is_an_error() {
    for sub in ["race --t 10", "sea --hs 2 --tp 8", "probe --t 1 --at 0,0"] {
        let o = Command::new("sh")
            .arg("-c")
            .arg(format!("exec \"$0\" {sub} >&-"))
            .arg(env!("CARGO_BIN_EXE_regatta"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{sub}: {err}");
        assert_eq!(err.lines().count(), 1, "{sub}: {err}");
        assert!(err.contains("stdout is closed"), "{sub}: {err}");
    }
    // Output thrown away on purpose is not a closed stdout.
    let o = Command::new("sh")
        .arg("-c")
        .arg("exec \"$0\" race --t 10 >/dev/null")
        .arg(env!("CARGO_BIN_EXE_regatta"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn contradictory_effect_lists_and_unreachable_error_targets_are_refused() {
    fails_with(
        &["render", "--out", "x.png", "--effects", "all,none"],
        "--effects \"all,none\" is contradictory",
    );
    fails_with(
        &["render", "--out", "x.png", "--error-px", "1e-9"],
        "--error-px 1e-9 is outside 0.1 to 100 pixels",
    );
}

/// A truncated frame passed `replay check`; now every frame is decoded.
#[test]
fn replay_check_decodes_every_frame() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_errors_cut_feed");
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let (code, _, err) = regatta(&[
        "replay", "synth", "--out", d, "--frames", "2", "--size", "160x120",
    ]);
    assert_eq!(code, 0, "{err}");
    let frame = dir.join("frames/000001.jpg");
    let bytes = std::fs::read(&frame).unwrap();
    std::fs::write(&frame, &bytes[..bytes.len() * 9 / 10]).unwrap();
    fails_with(
        &["replay", "check", d],
        "frames/000001.jpg: the JPEG is cut short",
    );
    std::fs::remove_file(&frame).unwrap();
    std::fs::create_dir(&frame).unwrap();
    fails_with(
        &["replay", "check", d],
        "000001.jpg is a directory, not an image file",
    );
}
