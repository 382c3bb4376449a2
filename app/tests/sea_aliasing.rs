//! The water's shading is band-limited: waves whose wavelength on screen is a few pixels or
//! less fade out of the per-pixel normals (common.wgsl's `surface_frame`) instead of aliasing
//! into moiré. Measured on a far, grazing view of the open sea at a small size, where most of
//! the sea's waves are finer than a pixel.

mod common;

use common::regatta;

/// Mean absolute difference between horizontally and vertically neighbouring pixels, over the
/// RGB channels, in 8-bit levels: the image's high-frequency energy.
fn neighbour_difference(img: &image::RgbaImage) -> f64 {
    let (w, h) = img.dimensions();
    let (mut sum, mut n) = (0.0, 0u64);
    for y in 0..h - 1 {
        for x in 0..w - 1 {
            let p = img.get_pixel(x, y);
            for q in [img.get_pixel(x + 1, y), img.get_pixel(x, y + 1)] {
                for c in 0..3 {
                    sum += f64::from(p[c].abs_diff(q[c]));
                }
                n += 3;
            }
        }
    }
    sum / n as f64
}

#[test]
fn a_far_grazing_sea_has_no_moire() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let out = std::env::temp_dir()
        .join(format!("regatta-sea-aliasing-{}.png", std::process::id()))
        .display()
        .to_string();
    // 300 m up, looking 800 m ahead (20° below the horizon): a pixel spans metres, so the
    // sea's short waves are far below a pixel.
    let (code, _, err) = regatta(&[
        "render",
        "--out",
        &out,
        "--size",
        "128x96",
        "--t",
        "700",
        "--no-wakes",
        // The sea alone: labels and lines would add edges of their own.
        "--overlays",
        "none",
        "--camera=0,300,0,0,0,-800",
    ]);
    assert_eq!(code, 0, "{err}");
    let img = image::open(&out).expect("a PNG").to_rgba8();
    let _ = std::fs::remove_file(&out);
    let hf = neighbour_difference(&img);
    // Measured on lavapipe: 1.10 levels band-limited; the unfiltered shading (waves faded
    // only from k·footprint = π to 2π) gave 1.92, its sub-pixel waves aliasing into stripes.
    assert!(
        hf < 1.5,
        "neighbouring pixels differ by {hf:.2} levels on average: sub-pixel waves alias"
    );
    // Not a flat image either: the resolved swell and the sky gradient remain.
    assert!(hf > 0.3, "{hf:.2}: the sea lost its resolved waves");
}
