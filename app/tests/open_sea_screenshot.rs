//! The open sea's colour follows the water type (docs/water-look.md, "The open sea's colour"):
//! `regatta render` (the orbit view, no `--replay`) with `--water-type pure`, `IB` and `5C`,
//! read back as PNGs. The water body's pixels are those where the three pictures differ (the
//! sky, the boats and the foam do not change with the type). Over them the mean colour's hue
//! moves from blue (pure, oceanic IB) to blue-green (coastal 5), as R∞'s blue/green ratio
//! falls. On a GPU (lavapipe in CI); skipped without one unless REGATTA_REQUIRE_GPU=true.

mod common;

use std::path::{Path, PathBuf};

use common::{differing_pixels, hsv, rendered_png};

/// Hue of the water's mean colour per type, degrees (blue is 240°, cyan 180°), and its HSV
/// saturation: pure water and oceanic IB deep blue, coastal 5 blue-green.
const PURE_HUE: std::ops::RangeInclusive<f64> = 215.0..=240.0;
const IB_HUE: std::ops::RangeInclusive<f64> = 210.0..=235.0;
const COASTAL5_HUE: std::ops::RangeInclusive<f64> = 170.0..=205.0;
const SATURATION: std::ops::RangeInclusive<f64> = 0.35..=0.95;

fn render(out: &Path, water_type: &str) -> image::RgbImage {
    render_with(out, water_type, &[])
}

fn render_with(out: &Path, water_type: &str, extra: &[&str]) -> image::RgbImage {
    let mut args = vec![
        "render",
        "--t",
        "600",
        "--size",
        "480x270",
        "--overlays",
        "none",
        "--water-type",
        water_type,
    ];
    args.extend_from_slice(extra);
    rendered_png(&args, out)
}

#[test]
fn the_open_seas_hue_follows_the_water_type() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("open_sea_screenshot");
    std::fs::create_dir_all(&dir).unwrap();
    let pics: Vec<image::RgbImage> = ["pure", "IB", "5C"]
        .iter()
        .map(|t| render(&dir.join(format!("{t}.png")), t))
        .collect();
    let (w, h) = pics[0].dimensions();
    // The water body: where pure water and coastal 5 differ by more than 30 levels summed.
    let water = differing_pixels(&pics[0], &pics[2], 30.0);
    assert!(
        water.len() as f64 > 0.3 * f64::from(w * h),
        "only {} water pixels",
        water.len()
    );
    let mean = |img: &image::RgbImage| {
        let mut m = [0.0; 3];
        for &(x, y) in &water {
            let p = img.get_pixel(x, y);
            for c in 0..3 {
                m[c] += f64::from(p[c]) / water.len() as f64;
            }
        }
        m
    };
    let got: Vec<(f64, f64, [f64; 3])> = pics
        .iter()
        .map(|p| {
            let m = mean(p);
            let (h, s, _) = hsv(m);
            (h, s, m)
        })
        .collect();
    eprintln!(
        "open sea (hue°, saturation, mean sRGB): pure {:?}, IB {:?}, 5C {:?}",
        got[0], got[1], got[2]
    );
    for ((h, s, m), (name, range)) in
        got.iter()
            .zip([("pure", PURE_HUE), ("IB", IB_HUE), ("5C", COASTAL5_HUE)])
    {
        assert!(
            range.contains(h),
            "{name}: hue {h} outside {range:?} ({m:?})"
        );
        assert!(SATURATION.contains(s), "{name}: saturation {s} ({m:?})");
    }
    // The hue moves towards green in Jerlov's order.
    assert!(
        got[0].0 >= got[1].0 && got[1].0 > got[2].0 + 15.0,
        "{got:?}"
    );
}

/// `--tier` draws the water asked for too: its picture was assembled apart from the still's and
/// drew the default water whatever `--water-type` said (the two pictures were the same). Now
/// the scene set-up gives the tier's renderer the open sea's and the table's water alike, so
/// pure water and coastal 5 differ over the water, as without a tier.
#[test]
fn a_tiers_picture_takes_the_water_type() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("open_sea_screenshot_tier");
    std::fs::create_dir_all(&dir).unwrap();
    let tier = ["--tier", "medium"];
    let pure = render_with(&dir.join("pure.png"), "pure", &tier);
    let coastal = render_with(&dir.join("5C.png"), "5C", &tier);
    let (w, h) = pure.dimensions();
    let water = differing_pixels(&pure, &coastal, 30.0);
    assert!(
        water.len() as f64 > 0.1 * f64::from(w * h),
        "only {} of {} pixels differ between pure water and coastal 5 at --tier medium",
        water.len(),
        w * h
    );
}
