//! GPU tests of the pool passes on lavapipe (small sizes): the caustics map against its f64
//! reference, and golden images. Without an adapter they skip, unless `REGATTA_REQUIRE_GPU`
//! demands one ([`render::gpu::test_gpu`]).
//!
//! Regenerate the golden images after an intended change of the picture:
//! `REGATTA_UPDATE_GOLDEN=1 cargo test -p pool --lib gpu_tests`, then look at them.

use std::path::PathBuf;

use super::caustics::CausticMap;
use super::gpu::{PoolFrame, PoolRenderer, PoolSettings, PoolView, render_pool_image};
use super::scene::PoolScene;
use render::gpu::test_gpu;
use render::renderer::OFFSCREEN_FORMAT;

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
        .join("golden")
        .join(format!("{name}.png"));
    render::golden::check(&path, &img).unwrap_or_else(|e| panic!("{e}"));
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
fn over_the_camera_image_only_the_pool_is_drawn() {
    let Some(gpu) = test_gpu() else { return };
    let scene = PoolScene::default();
    let settings = small_settings();
    let mut r = PoolRenderer::new(&gpu, OFFSCREEN_FORMAT, settings);
    let mut view = PoolView::default_desktop([48, 32]);
    let desktop = PoolFrame::new(&scene, 1.0, &view, &settings);
    let (img, _) = render_pool_image(&gpu, &mut r, &desktop).unwrap();
    // The corner shows ground or sky on the desktop, and the pool's centre shows water.
    assert_eq!(img.get_pixel(0, 0)[3], 255);
    view.over_camera_image = true;
    let ar = PoolFrame::new(&scene, 1.0, &view, &settings);
    let (img_ar, _) = render_pool_image(&gpu, &mut r, &ar).unwrap();
    // Over the camera image (here the zeroed new texture) the corner is left alone...
    assert_eq!(img_ar.get_pixel(0, 0).0, [0, 0, 0, 0]);
    // ...and the pool is drawn as on the desktop.
    assert_eq!(img_ar.get_pixel(24, 16), img.get_pixel(24, 16));
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

#[test]
fn gpu_water_matches_the_f64_trace_on_still_water() {
    // Still water (no waves, no balls): the view ray of a pixel meets the surface where it
    // crosses y = 0, so the f64 reference can shade exactly the point the GPU shades.
    let Some(gpu) = test_gpu() else { return };
    let mut scene = PoolScene::default();
    scene.water.waves.waves.clear();
    scene.floaters.clear();
    scene.movers.clear();
    let settings = small_settings();
    let size = [64, 64];
    let mut view = PoolView::default_desktop(size);
    view.camera = render::camera::Camera::look_at(
        glam::DVec3::new(0.1, 2.0, 0.4),
        glam::DVec3::new(0.0, -1.0, 0.0),
        super::FAR_M,
    );
    let mut r = PoolRenderer::new(&gpu, OFFSCREEN_FORMAT, settings);
    let frame = PoolFrame::new(&scene, 1.0, &view, &settings);
    let (img, _) = render_pool_image(&gpu, &mut r, &frame).unwrap();
    let n = settings.caustic_size as usize;
    let map = CausticMap::compute(&scene, 1.0, &[], settings.caustic_grid as usize, n, n);
    let linear = |c: u8| {
        let s = f64::from(c) / 255.0;
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    let mut diffs = Vec::new();
    for py in (2..64).step_by(5) {
        for px in (2..64).step_by(5) {
            let ray = super::interact::pointer_ray(&view, [px as f64 + 0.5, py as f64 + 0.5]);
            let s = -ray.origin.y / ray.dir.y;
            let p = ray.at(s);
            // Away from the walls (the caustics map's edge texels blend with the walls').
            if p.x.abs() > scene.pool.half_x - 0.15 || p.z.abs() > scene.pool.half_z - 0.15 {
                continue;
            }
            let want = super::trace::shade_water(&scene, &[], &map, p, glam::DVec3::Y, ray.dir);
            let got = img.get_pixel(px, py);
            let d = (0..3)
                .map(|c| (linear(got[c]) - want[c]).abs())
                .fold(0.0, f64::max);
            diffs.push(d);
        }
    }
    assert!(diffs.len() > 40, "only {} pixels on the water", diffs.len());
    diffs.sort_by(f64::total_cmp);
    let median = diffs[diffs.len() / 2];
    let within = diffs.iter().filter(|&&d| d < 0.02).count() as f64 / diffs.len() as f64;
    // 8-bit output, f32 shading, and the reflected sky (R ≈ 2 % here) drawn by the renderer's
    // sky rather than the reference's gradient: within 0.02. A few pixels sit on a grout line
    // or on the edge of a wall's shadow in the caustics map (sampled bilinearly on the GPU,
    // nearest on the CPU) and flip between the two sides.
    assert!(median < 0.01, "median channel difference {median}");
    assert!(
        within > 0.85,
        "only {:.0} % of pixels within 0.02: {diffs:?}",
        within * 100.0
    );
}
