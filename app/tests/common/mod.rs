//! What the app's integration tests share: running the built `regatta` binary and checking the
//! command-line contract of docs/command-line.md (JSON on stdout; bad input is one sentence on stderr,
//! nothing on stdout, a non-zero exit and no panic).

// Each test file is its own crate and uses only some of these helpers.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

/// Runs the built binary with `args` and returns its raw output.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args(args)
        .output()
        .expect("the regatta binary runs")
}

/// Runs the built binary: (exit code, -1 when killed by a signal; stdout; stderr).
pub fn regatta(args: &[&str]) -> (i32, String, String) {
    let o = run(args);
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// A good input: exit 0 and a JSON document on stdout.
pub fn ok_json(args: &[&str]) -> Value {
    let (code, out, err) = regatta(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {out}"))
}

/// A bad input: non-zero exit, nothing on stdout, one line on stderr containing `needle`, and
/// no panic.
pub fn fails_with(args: &[&str], needle: &str) {
    let (code, out, err) = regatta(args);
    assert_ne!(code, 0, "{args:?} should fail");
    assert!(out.is_empty(), "{args:?} printed to stdout: {out}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: not one line: {err}"
    );
    assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
}

/// A JSON number.
pub fn f(v: &Value) -> f64 {
    v.as_f64().expect("a number")
}

/// Writes `text` to `name` in the test target's temporary directory.
pub fn temp_file(name: &str, text: &str) -> PathBuf {
    let p = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// A race (written to `name`) whose only boat sails 50 km away: its wakes are negligible
/// (< 1e-9 m) near the origin, so the sea's own values can be checked exactly there.
pub fn far_race(name: &str) -> PathBuf {
    temp_file(
        name,
        r##"{"name": "far away", "origin": null, "start_time": null,
            "boats": [{"id": "FAR", "name": "Far", "color": "#ff0000",
                       "track": [[0, 50000, 0], [1000, 50000, 5000]]}],
            "marks": []}"##,
    )
}

/// Runs the built binary with stdout on a pipe whose reading end is already closed (as
/// `regatta … | head` after head exits): (exit code, stderr).
pub fn into_closed_pipe(args: &[&str]) -> (i32, String) {
    let (reader, writer) = std::io::pipe().expect("a pipe");
    drop(reader);
    let o = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args(args)
        .stdout(writer)
        .output()
        .expect("the regatta binary runs");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Runs the binary with `env` set (and `unset` removed); a run still going after 60 s (an open
/// that blocks, a wait on input) is killed and fails the test. Returns (exit code, stdout,
/// stderr).
pub fn regatta_within_a_minute(
    args: &[&str],
    env: &[(&str, &str)],
    unset: &[&str],
) -> (i32, String, String) {
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_regatta"));
    cmd.args(args).stdout(Stdio::piped()).stderr(Stdio::piped());
    for (k, v) in env {
        cmd.env(k, v);
    }
    for k in unset {
        cmd.env_remove(k);
    }
    let mut child = cmd.spawn().unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("{args:?} still ran after 60 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Hue (degrees), saturation and value of an sRGB colour (0–255 per channel).
pub fn hsv(c: [f64; 3]) -> (f64, f64, f64) {
    let max = c[0].max(c[1]).max(c[2]);
    let min = c[0].min(c[1]).min(c[2]);
    let d = max - min;
    let s = if max > 0.0 { d / max } else { 0.0 };
    let h = if d == 0.0 {
        0.0
    } else if max == c[0] {
        60.0 * ((c[1] - c[2]) / d).rem_euclid(6.0)
    } else if max == c[1] {
        60.0 * ((c[2] - c[0]) / d + 2.0)
    } else {
        60.0 * ((c[0] - c[1]) / d + 4.0)
    };
    (h, s, max / 255.0)
}

/// `regatta render ARGS --out OUT` (a PNG): exit 0, and the picture read back.
pub fn rendered_png(args: &[&str], out: &std::path::Path) -> image::RgbImage {
    let out_arg = out.to_str().expect("a UTF-8 path");
    let args: Vec<&str> = args.iter().copied().chain(["--out", out_arg]).collect();
    let (code, _, err) = regatta(&args);
    assert_eq!(code, 0, "{args:?}: {err}");
    image::open(out).unwrap().to_rgb8()
}

/// The pixels where two pictures of the same size differ by more than `levels`, summed over
/// the three channels (0–255 each).
pub fn differing_pixels(a: &image::RgbImage, b: &image::RgbImage, levels: f64) -> Vec<(u32, u32)> {
    let (w, h) = a.dimensions();
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
            (0..3)
                .map(|c| (f64::from(p[c]) - f64::from(q[c])).abs())
                .sum::<f64>()
                > levels
        })
        .collect()
}

/// The timeline's scrub track as egui laid it out in `ctx`'s last pass (points): the widest
/// drag-sensing widget of the track's height, 26 points.
pub fn scrub_track(ctx: &egui::Context) -> Option<egui::Rect> {
    ctx.viewport(|v| {
        v.prev_pass
            .widgets
            .layers()
            .flat_map(|(_, w)| w.iter())
            .filter(|w| w.sense == egui::Sense::click_and_drag())
            .filter(|w| (w.rect.height() - 26.0).abs() < 0.5)
            .map(|w| w.rect)
            .max_by(|a, b| a.width().total_cmp(&b.width()))
    })
}

/// `app` in an offscreen window of `size` pixels at one pixel per point, in the foreground.
pub fn shown(mut app: regatta::core::app::App, size: [u32; 2]) -> regatta::core::app::App {
    use regatta::core::app::AppEvent;
    app.on_all([
        AppEvent::Density(1.0),
        AppEvent::Resumed,
        AppEvent::WindowCreated {
            surface: None,
            size,
        },
    ]);
    app
}
