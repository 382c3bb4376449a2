//! `regatta render` through the built binary: a frame of the sample race is written as a PNG
//! and its planner record is JSON on stdout; bad inputs exit non-zero with one sentence naming
//! the flag or file.

mod common;

use common::{fails_with, regatta};
use serde_json::Value;

fn tmp(name: &str) -> String {
    std::env::temp_dir()
        .join(format!("regatta-render-cli-{}-{name}", std::process::id()))
        .display()
        .to_string()
}

#[test]
fn a_frame_of_the_sample_race_is_a_png_and_a_json_record() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let (out, rep) = (tmp("frame.png"), tmp("frame.json"));
    let (code, stdout, err) = regatta(&[
        "render", "--out", &out, "--size", "96x64", "--t", "700", "--report", &rep,
    ]);
    assert_eq!(code, 0, "{err}");
    let json: Value = serde_json::from_str(&stdout).expect("JSON on stdout");
    assert_eq!(json["t"], 700.0);
    assert_eq!(json["size"], serde_json::json!([96, 64]));
    let names: Vec<&str> = json["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert!(names.starts_with(&["sky", "water", "boats"]), "{names:?}");
    for p in json["passes"].as_array().unwrap() {
        assert!(p["reason"].as_str().is_some_and(|r| !r.is_empty()), "{p}");
    }
    assert!(
        json["wakes"]["sources"].as_u64().unwrap() > 0,
        "{}",
        json["wakes"]
    );
    let img = image::open(&out).expect("a PNG").to_rgba8();
    assert_eq!(img.dimensions(), (96, 64));
    // The same record went to --report.
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&rep).unwrap()).unwrap();
    assert_eq!(file, json);
    let _ = (std::fs::remove_file(&out), std::fs::remove_file(&rep));
}

#[test]
fn bad_inputs_are_one_sentence_naming_what_is_wrong() {
    let out = tmp("bad.png");
    let missing = tmp("no-such-sea.json");
    for (args, needle) in [
        (vec!["--size", "0x10"], "--size"),
        (vec!["--camera", "1,2,3"], "--camera"),
        (vec!["--error-px", "0"], "--error-px"),
        (vec!["--t", "NaN"], "--t"),
        (vec!["--sea", missing.as_str()], "no-such-sea.json"),
    ] {
        let mut all = vec!["render", "--out", out.as_str()];
        all.extend(args.iter().copied());
        fails_with(&all, needle);
    }
}
