//! `regatta render` on a GPU (skipped without one unless REGATTA_REQUIRE_GPU=true): outputs
//! written whole or not at all, a 10,000-wave sea drawn from its largest waves with the bound
//! said, and `render --replay DIR --frame N`, the table scene over a recorded frame.

mod common;

use std::path::PathBuf;

use common::{fails_with, regatta};
use serde_json::Value;

fn tmp_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gpu() -> bool {
    render::gpu::test_gpu().is_some()
}

/// `--out x.jpg` left a 0-byte file (the PNG-only encoder refused RGBA for JPEG after the file
/// was created).
#[test]
fn a_jpeg_output_is_a_whole_jpeg_and_failures_leave_no_file() {
    if !gpu() {
        return;
    }
    let dir = tmp_dir("render_outputs_jpeg");
    let out = dir.join("frame.jpg");
    let (code, _, err) = regatta(&[
        "render",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "64x48",
        "--t",
        "700",
    ]);
    assert_eq!(code, 0, "{err}");
    let img = image::open(&out).expect("a decodable JPEG");
    assert_eq!((img.width(), img.height()), (64, 48));
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "a temporary file was left"
    );
    // A folder that does not exist: nothing is written, nothing is left.
    let missing = dir.join("no/such/frame.png");
    fails_with(
        &[
            "render",
            "--out",
            missing.to_str().unwrap(),
            "--size",
            "64x48",
        ],
        "could not write",
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

/// A 10,000-wave sea froze `regatta run` (2 frames in 60 s): the renderers draw its 64 largest
/// waves and say what the rest could move.
#[test]
fn a_sea_of_ten_thousand_waves_draws_its_largest() {
    if !gpu() {
        return;
    }
    let dir = tmp_dir("render_outputs_big_sea");
    // Amplitudes A = s λ / 2π fall with the index: the 64 largest are waves 0 to 63.
    let waves: Vec<String> = (0..10_000)
        .map(|i| {
            let l = 50.0 / (1.0 + f64::from(i) * 0.01);
            format!(
                r#"{{"direction": [{}, {}], "steepness": 0.00005, "wavelength": {l}, "phase": {}}}"#,
                (f64::from(i) * 0.7).cos(),
                (f64::from(i) * 0.7).sin(),
                f64::from(i) * 0.3
            )
        })
        .collect();
    let sea = dir.join("sea.json");
    std::fs::write(&sea, format!(r#"{{"waves": [{}]}}"#, waves.join(",\n"))).unwrap();
    let dropped: f64 = (64..10_000)
        .map(|i| 0.00005 * 50.0 / (1.0 + f64::from(i) * 0.01) / std::f64::consts::TAU)
        .sum();
    let out = dir.join("frame.png");
    let (code, stdout, err) = regatta(&[
        "render",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "64x48",
        "--t",
        "700",
        "--sea",
        sea.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let want = format!(
        "the sea has 10000 waves; drawing the 64 largest, the 9936 dropped move the surface by at most {dropped:.3e} m"
    );
    assert!(err.contains(&want), "{err}\nwanted: {want}");
    let json: Value = serde_json::from_str(&stdout).unwrap();
    for l in json["clipmap"]["per_level"].as_array().unwrap() {
        assert!(l["waves"].as_u64().unwrap() <= 64, "{l}");
    }
}

/// The contract's `render --replay DIR [--frame N]`: the race on the feed's table over frame N.
/// With the background effect alone, the picture's corners (outside the table's water) are the
/// camera image itself.
#[test]
fn render_replay_draws_the_table_scene_over_a_feed_frame() {
    if !gpu() {
        return;
    }
    let dir = tmp_dir("render_outputs_replay");
    let feed = dir.join("feed");
    let (code, _, err) = regatta(&[
        "replay",
        "synth",
        "--out",
        feed.to_str().unwrap(),
        "--frames",
        "3",
        "--size",
        "160x120",
        "--quality",
        "100",
    ]);
    assert_eq!(code, 0, "{err}");
    let out = dir.join("over.png");
    let (code, stdout, err) = regatta(&[
        "render",
        "--replay",
        feed.to_str().unwrap(),
        "--frame",
        "2",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "160x120",
        "--effects",
        "background",
    ]);
    assert_eq!(code, 0, "{err}");
    let json: Value = serde_json::from_str(&stdout).unwrap();
    let names: Vec<&str> = json["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert!(names.iter().any(|n| n.contains("background")), "{names:?}");
    let drawn = image::open(&out).unwrap().to_rgb8();
    let camera = image::open(feed.join("frames/000002.jpg"))
        .unwrap()
        .to_rgb8();
    assert_eq!(drawn.dimensions(), camera.dimensions());
    // The top-left corner: the room behind the table in the feed.
    let mut diff = 0.0;
    let mut n = 0.0;
    for y in 0..12 {
        for x in 0..16 {
            for c in 0..3 {
                diff += (f64::from(drawn.get_pixel(x, y)[c])
                    - f64::from(camera.get_pixel(x, y)[c]))
                .abs();
                n += 1.0;
            }
        }
    }
    assert!(
        diff / n < 6.0,
        "the corner differs from the camera image by {:.1} levels",
        diff / n
    );
    // And the water is drawn over the table: the centre is not the camera image.
    let centre = |img: &image::RgbImage| img.get_pixel(80, 70).0;
    assert_ne!(centre(&drawn), centre(&camera));
    fails_with(
        &[
            "render",
            "--replay",
            feed.to_str().unwrap(),
            "--frame",
            "3",
            "--out",
            out.to_str().unwrap(),
        ],
        "--frame 3 is past the feed's last frame",
    );
}
