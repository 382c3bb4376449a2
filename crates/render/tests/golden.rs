//! Golden-image tests on lavapipe: a fixed scene rendered small and compared with a PNG in
//! `tests/golden/` by the crate's shared check (`render::golden`, which states the limits).
//!
//! Regenerate after an intended change of the picture:
//! `REGATTA_UPDATE_GOLDEN=1 cargo test -p render --test golden`, then look at the PNGs.

use std::path::PathBuf;

use glam::DVec2;
use render::golden::{MAX_OFF_FRACTION, MEAN_TOLERANCE, compare};
use render::gpu::test_gpu;
use render::{Boat, RenderOptions, Renderer, Scene};

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(format!("{name}.png"))
}

fn check(name: &str, scene: &Scene, size: [u32; 2]) {
    let Some(gpu) = test_gpu() else { return };
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (img, _) = render::render_image(&gpu, &mut r, scene, size).unwrap();
    render::golden::check(&golden_path(name), &img).unwrap_or_else(|e| panic!("{e}"));
}

fn race_scene(t: f64) -> Scene {
    let boats = [
        (0.0, 0.0, 0.6, [0.8, 0.05, 0.05]),
        (-18.0, 12.0, 0.9, [0.05, 0.1, 0.7]),
        (10.0, 22.0, 0.7, [0.9, 0.75, 0.05]),
    ]
    .iter()
    .map(|&(x, z, h, c)| Boat {
        position: DVec2::new(x, z),
        heading: h,
        colour: c,
        length: 10.0,
    })
    .collect();
    render::golden::test_scene(t, boats)
}

#[test]
fn golden_sea_with_boats() {
    check("sea_with_boats", &race_scene(100.0), [192, 128]);
}

#[test]
fn golden_sea_after_a_long_race() {
    // Ten hours in: the phases are reduced on the CPU, so the picture is as sharp as at t = 0.
    check("sea_after_ten_hours", &race_scene(36_000.0), [192, 128]);
}

#[test]
fn the_tolerance_catches_a_broken_shader() {
    // A frame with the sea's waves gone (what a shader that drops its displacement draws)
    // differs from the real one by more than the tolerance.
    let Some(gpu) = test_gpu() else { return };
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let good = race_scene(100.0);
    let mut flat = good.clone();
    for w in &mut std::sync::Arc::make_mut(&mut flat.sea).waves {
        w.steepness = 0.0;
    }
    let (a, _) = render::render_image(&gpu, &mut r, &good, [192, 128]).unwrap();
    let (b, _) = render::render_image(&gpu, &mut r, &flat, [192, 128]).unwrap();
    let (mean, off) = compare(&a, &b);
    assert!(
        mean > MEAN_TOLERANCE || off > MAX_OFF_FRACTION,
        "mean {mean}, off {off}"
    );
    // And the same frame twice is within it.
    let (c, _) = render::render_image(&gpu, &mut r, &good, [192, 128]).unwrap();
    assert_eq!(compare(&a, &c), (0.0, 0.0));
}
