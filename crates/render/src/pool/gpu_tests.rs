//! GPU tests of the pool passes on lavapipe (small sizes): the caustics map against its f64
//! reference, and golden images. Without an adapter they skip, unless `REGATTA_REQUIRE_GPU`
//! demands one ([`crate::gpu::test_gpu`]).
//!
//! Regenerate the golden images after an intended change of the picture:
//! `REGATTA_UPDATE_GOLDEN=1 cargo test -p render --lib pool::gpu_tests`, then look at them.

use std::path::PathBuf;

use super::caustics::CausticMap;
use super::gpu::{PoolFrame, PoolRenderer, PoolSettings, PoolView, render_pool_image};
use super::scene::PoolScene;
use crate::gpu::test_gpu;
use crate::renderer::OFFSCREEN_FORMAT;

/// Same limits as the race scene's golden images: mean difference ≤ 2 levels per channel and
/// ≤ 1 % of pixels off by more than 24 levels.
const MEAN_TOLERANCE: f64 = 2.0;
const PIXEL_TOLERANCE: u8 = 24;
const MAX_OFF_FRACTION: f64 = 0.01;

fn small_settings() -> PoolSettings {
    PoolSettings {
        caustic_grid: 96,
        caustic_size: 128,
        water_grid: 64,
        ..PoolSettings::default()
    }
}

fn golden(name: &str, t: f64, size: [u32; 2]) {
    let Some(gpu) = test_gpu() else { return };
    let scene = PoolScene::default();
    let settings = small_settings();
    let mut r = PoolRenderer::new(&gpu, OFFSCREEN_FORMAT, settings);
    let frame = PoolFrame::new(&scene, t, &PoolView::default_desktop(size), &settings);
    let (img, report) = render_pool_image(&gpu, &mut r, &frame).unwrap();
    assert_eq!(report.spheres, 4);
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("src/pool/golden")
        .join(format!("{name}.png"));
    if std::env::var_os("REGATTA_UPDATE_GOLDEN").is_some() {
        img.save(&path).unwrap();
        eprintln!("wrote {}", path.display());
        return;
    }
    let want = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e}; regenerate with REGATTA_UPDATE_GOLDEN=1",
                path.display()
            )
        })
        .to_rgba8();
    assert_eq!(img.dimensions(), want.dimensions());
    let (mut sum, mut off) = (0.0, 0usize);
    for (p, q) in img.pixels().zip(want.pixels()) {
        let d = [0, 1, 2].map(|c| p[c].abs_diff(q[c]));
        sum += d.iter().map(|&x| f64::from(x)).sum::<f64>();
        off += usize::from(d.iter().any(|&x| x > PIXEL_TOLERANCE));
    }
    let n = f64::from(img.width() * img.height());
    let (mean, off) = (sum / (3.0 * n), off as f64 / n);
    if mean > MEAN_TOLERANCE || off > MAX_OFF_FRACTION {
        let got = std::env::temp_dir().join(format!("regatta-pool-{name}-got.png"));
        let _ = img.save(&got);
        panic!(
            "{name}: mean difference {mean:.2} levels, {:.2} % pixels off; got {}",
            off * 100.0,
            got.display()
        );
    }
}

#[test]
fn golden_pool() {
    golden("pool_t3", 3.0, [160, 120]);
}

#[test]
fn golden_pool_after_ten_hours() {
    // Phases and ring ages are reduced on the CPU: ten hours in, the picture is as sharp.
    golden("pool_t36000", 36_000.0, [160, 120]);
}

#[test]
fn gpu_caustics_match_the_f64_area_ratio() {
    let Some(gpu) = test_gpu() else { return };
    let scene = PoolScene::default();
    let settings = small_settings();
    let t = 3.0;
    let mut r = PoolRenderer::new(&gpu, OFFSCREEN_FORMAT, settings);
    let frame = PoolFrame::new(&scene, t, &PoolView::default_desktop([32, 32]), &settings);
    render_pool_image(&gpu, &mut r, &frame).unwrap();
    let got = r.read_caustics(&gpu).unwrap();
    let n = settings.caustic_size as usize;
    let want = CausticMap::compute(
        &scene,
        t,
        &scene.rings(t),
        settings.caustic_grid as usize,
        n,
        n,
    );
    // The same light lands (f32 and half-float storage against f64).
    let texel = want.texel_size(0) * want.texel_size(1);
    let got_flux: f64 = got.iter().map(|&v| f64::from(v)).sum::<f64>() * texel;
    let want_flux = want.total_flux();
    assert!(
        (got_flux / want_flux - 1.0).abs() < 0.01,
        "GPU {got_flux}, f64 {want_flux}"
    );
    // Texel by texel, where the light is (a triangle edge falling on the other side of a texel
    // centre in f32 moves a whole texel's worth: allow a few such texels).
    let diff: f64 = got
        .iter()
        .zip(&want.texels)
        .map(|(&g, &w)| (f64::from(g) - w).abs())
        .sum::<f64>()
        * texel;
    assert!(
        diff < 0.05 * want_flux,
        "L1 difference {diff} of {want_flux}"
    );
}
