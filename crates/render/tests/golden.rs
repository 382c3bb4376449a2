//! Golden-image tests on lavapipe: a fixed scene rendered small and compared with a PNG in
//! `tests/golden/`. The tolerance lets driver rounding through and catches a broken shader:
//! mean absolute difference ≤ 2 levels (of 255) per channel, and ≤ 1 % of pixels off by more
//! than 24 levels in any channel.
//!
//! Regenerate after an intended change of the picture:
//! `REGATTA_UPDATE_GOLDEN=1 cargo test -p render --test golden`, then look at the PNGs.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use ocean::WaveSet;
use render::gpu::test_gpu;
use render::{Boat, Camera, Mark, RenderOptions, Renderer, Scene};

const MEAN_TOLERANCE: f64 = 2.0;
const PIXEL_TOLERANCE: u8 = 24;
const MAX_OFF_FRACTION: f64 = 0.01;

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(format!("{name}.png"))
}

/// Mean absolute difference per channel (levels) and the fraction of pixels off by more than
/// `PIXEL_TOLERANCE` in some channel.
fn compare(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, f64) {
    assert_eq!(a.dimensions(), b.dimensions());
    let (mut sum, mut off) = (0.0, 0usize);
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d: Vec<u8> = (0..3).map(|c| p[c].abs_diff(q[c])).collect();
        sum += d.iter().map(|&x| f64::from(x)).sum::<f64>();
        off += usize::from(d.iter().any(|&x| x > PIXEL_TOLERANCE));
    }
    let n = (a.width() * a.height()) as f64;
    (sum / (3.0 * n), off as f64 / n)
}

fn check(name: &str, scene: &Scene, size: [u32; 2]) {
    let Some(gpu) = test_gpu() else { return };
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let (img, _) = render::render_image(&gpu, &mut r, scene, size).unwrap();
    let path = golden_path(name);
    if std::env::var_os("REGATTA_UPDATE_GOLDEN").is_some() {
        img.save(&path).unwrap();
        eprintln!("wrote {}", path.display());
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e}; regenerate with REGATTA_UPDATE_GOLDEN=1",
                path.display()
            )
        })
        .to_rgba8();
    let (mean, off) = compare(&img, &golden);
    if mean > MEAN_TOLERANCE || off > MAX_OFF_FRACTION {
        let got = std::env::temp_dir().join(format!("regatta-{name}-got.png"));
        let _ = img.save(&got);
        panic!(
            "{name}: mean difference {mean:.2} levels, {:.2} % pixels off (limits {MEAN_TOLERANCE}, {:.0} %); got {}",
            off * 100.0,
            MAX_OFF_FRACTION * 100.0,
            got.display()
        );
    }
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
    Scene {
        t,
        sea: WaveSet::default_sea(),
        boats,
        marks: vec![Mark {
            position: DVec2::new(20.0, -25.0),
        }],
        play_area: [-2000.0, -2000.0, 2000.0, 2000.0],
        sun: Scene::default_sun(),
        camera: Camera::look_at(
            DVec3::new(25.0, 14.0, 45.0),
            DVec3::new(-2.0, 0.0, -5.0),
            5000.0,
        ),
    }
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
    for w in &mut flat.sea.waves {
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
