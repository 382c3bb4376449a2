//! The default table sea reads as sea (docs/water-look.md): `regatta render --replay synth` at
//! the default look (5 m of Jerlov oceanic IB by optical similarity), read back as a PNG, is
//! blue-green over the water's pixels, while the table's texture still shows through. The dry
//! table is the same frame with the background effect alone (the camera image). On a GPU
//! (lavapipe in CI); skipped without one unless REGATTA_REQUIRE_GPU=true.

mod common;

use std::path::{Path, PathBuf};

use common::{differing_pixels, hsv, rendered_png};

/// Hue of the water's mean colour, degrees: blue-green (cyan is 180°; green 120°, blue 240°).
const HUE_DEG: std::ops::RangeInclusive<f64> = 160.0..=200.0;
/// Share of the water's pixels whose own hue is blue-green (the range above widened to
/// 120°–230°: green-cyan to azure).
const MIN_BLUE_GREEN_SHARE: f64 = 0.8;
/// HSV saturation of the water's mean colour: a coloured sea, not a grey or milky sheet.
const SATURATION: std::ops::RangeInclusive<f64> = 0.3..=0.7;
/// The table's texture through the water: the regression slope of the wet picture's luminance
/// on the dry table's, over 4×4 blocks of the water (the share of the table's contrast that
/// survives the water), and their correlation.
const MIN_CONTRAST_SHARE: f64 = 0.5;
const MIN_CORRELATION: f64 = 0.5;

fn tmp_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn render(out: &Path, extra: &[&str]) -> image::RgbImage {
    let mut args = vec![
        "render",
        "--replay",
        "synth",
        "--t",
        "600",
        "--size",
        "480x270",
        "--overlays",
        "none",
    ];
    args.extend_from_slice(extra);
    rendered_png(&args, out)
}

fn luma(p: &image::Rgb<u8>) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

#[test]
fn the_default_table_sea_is_blue_green_and_the_table_shows_through() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let dir = tmp_dir("water_look_screenshot");
    let wet = render(&dir.join("wet.png"), &[]);
    let dry = render(&dir.join("dry.png"), &["--effects", "background"]);
    let (w, h) = wet.dimensions();
    // The water: where the picture is no longer the camera's table.
    let water = differing_pixels(&wet, &dry, 45.0);
    assert!(
        water.len() as f64 > 0.2 * f64::from(w * h),
        "only {} water pixels",
        water.len()
    );
    let mut mean = [0.0; 3];
    let mut blue_green = 0usize;
    for &(x, y) in &water {
        let p = wet.get_pixel(x, y);
        for c in 0..3 {
            mean[c] += f64::from(p[c]) / water.len() as f64;
        }
        let (hue, s, _) = hsv([0, 1, 2].map(|c| f64::from(p[c])));
        if (120.0..=230.0).contains(&hue) && s > 0.1 {
            blue_green += 1;
        }
    }
    let (hue, sat, val) = hsv(mean);
    let share = blue_green as f64 / water.len() as f64;
    // The table's texture through the water, over 4×4 blocks wholly in the water.
    let in_water: std::collections::HashSet<(u32, u32)> = water.iter().copied().collect();
    let mut blocks = Vec::new();
    for by in 0..h / 4 {
        for bx in 0..w / 4 {
            let px: Vec<(u32, u32)> = (0..16).map(|i| (bx * 4 + i % 4, by * 4 + i / 4)).collect();
            if px.iter().all(|p| in_water.contains(p)) {
                let m = |img: &image::RgbImage| {
                    px.iter()
                        .map(|&(x, y)| luma(img.get_pixel(x, y)))
                        .sum::<f64>()
                        / 16.0
                };
                blocks.push((m(&dry), m(&wet)));
            }
        }
    }
    let n = blocks.len() as f64;
    let (md, mw) = blocks
        .iter()
        .fold((0.0, 0.0), |(a, b), (d, w)| (a + d / n, b + w / n));
    let cov = blocks.iter().map(|(d, w)| (d - md) * (w - mw)).sum::<f64>() / n;
    let var_d = blocks.iter().map(|(d, _)| (d - md).powi(2)).sum::<f64>() / n;
    let var_w = blocks.iter().map(|(_, w)| (w - mw).powi(2)).sum::<f64>() / n;
    let slope = cov / var_d;
    let corr = cov / (var_d * var_w).sqrt();
    eprintln!(
        "water: {} px, mean sRGB ({:.0}, {:.0}, {:.0}), hue {hue:.1}°, saturation {sat:.3}, value {val:.3}, blue-green share {share:.3}; table contrast share {slope:.3}, correlation {corr:.3} over {} blocks",
        water.len(),
        mean[0],
        mean[1],
        mean[2],
        blocks.len()
    );
    assert!(HUE_DEG.contains(&hue), "hue {hue:.1}°");
    assert!(SATURATION.contains(&sat), "saturation {sat:.3}");
    assert!(share >= MIN_BLUE_GREEN_SHARE, "blue-green share {share:.3}");
    assert!(slope >= MIN_CONTRAST_SHARE, "contrast share {slope:.3}");
    assert!(corr >= MIN_CORRELATION, "correlation {corr:.3}");
}
