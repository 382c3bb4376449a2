//! `regatta render --effects LIST` through the built binary: bad lists are refused with one
//! sentence naming the effect, and a frame with effects reports each effect's decision.

mod common;

use common::regatta;
use serde_json::Value;

fn out_png(name: &str) -> String {
    std::env::temp_dir()
        .join(format!(
            "regatta-effects-cli-{name}-{}.png",
            std::process::id()
        ))
        .display()
        .to_string()
}

#[test]
fn unknown_effects_are_refused_by_name() {
    let out = out_png("bad");
    for (list, needle) in [("reflection,fog", "\"fog\""), ("caustics,,flowmap", "\"\"")] {
        let (code, stdout, err) = regatta(&["render", "--out", &out, "--effects", list]);
        assert_ne!(code, 0, "{list} succeeded");
        assert!(stdout.is_empty(), "{list}: {stdout}");
        assert_eq!(err.trim_end().lines().count(), 1, "{list}: {err}");
        assert!(
            err.contains("--effects") && err.contains(needle),
            "{list}: {err}"
        );
    }
    let (code, _, err) = regatta(&[
        "render",
        "--out",
        &out,
        "--scene",
        "pool",
        "--effects",
        "all",
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("--effects") && err.contains("pool"), "{err}");
}

/// `regatta render` of a 96 × 64 frame into `out` with `--effects list`.
fn render_effects(out: &str, list: &str) -> (i32, String, String) {
    regatta(&["render", "--out", out, "--size", "96x64", "--effects", list])
}

#[test]
fn a_frame_with_effects_reports_every_decision() {
    // Skip only when this process finds no adapter (counted, and a failure under
    // REGATTA_REQUIRE_GPU); any "cannot render" from the binary is then a real failure.
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let out = out_png("all");
    let (code, stdout, err) = render_effects(&out, "all");
    assert_eq!(code, 0, "{err}");
    let report: Value = serde_json::from_str(&stdout).expect("JSON");
    let passes = report["passes"].as_array().expect("passes");
    let find = |name: &str| {
        passes
            .iter()
            .find(|p| p["name"] == name)
            .unwrap_or_else(|| panic!("no {name} pass in {stdout}"))
    };
    assert_eq!(find("background")["ran"], true);
    let water = find("ar_water");
    let reason = water["reason"].as_str().expect("reason");
    for e in ["reflection", "refraction", "caustics", "flowmap"] {
        assert!(reason.contains(e), "{e} missing from \"{reason}\"");
    }
    assert!(std::path::Path::new(&out).exists());
    let _ = std::fs::remove_file(&out);
    // Only the named effects run; the others say they were not requested.
    let (code, stdout, err) = render_effects(&out, "refraction");
    assert_eq!(code, 0, "{err}");
    let report: Value = serde_json::from_str(&stdout).expect("JSON");
    let passes = report["passes"].as_array().expect("passes");
    let bg = passes
        .iter()
        .find(|p| p["name"] == "background")
        .expect("background");
    assert_eq!(bg["ran"], false);
    assert_eq!(bg["reason"], "not requested");
    let _ = std::fs::remove_file(&out);
}
