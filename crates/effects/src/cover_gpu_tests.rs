//! The camera background around the water's cover (`passes::cover`) on the GPU: the frame is
//! the one the whole background gives. Lavapipe in CI; skipped without an adapter unless
//! REGATTA_REQUIRE_GPU=true.

use glam::DVec3;

use super::EffectSet;
use super::gpu_tests::{SIZE, config, frame_for, table_scene};
use super::passes::{ArConfig, add_effect_passes};
use render::gpu::test_gpu;
use render::{OFFSCREEN_FORMAT, RenderOptions, Renderer, Scene, render_image};

/// The camera background left out where the water certainly covers the screen
/// (`passes::cover`) changes no pixel: each view, drawn with every effect with and without the
/// cover, is the same image, bit for bit; and where a cover is drawn the background pass
/// shades fewer fragments (the pipeline statistics, where the adapter has them).
#[test]
fn the_background_left_out_under_the_water_changes_no_pixel() {
    let Some(gpu) = test_gpu() else { return };
    let look = |eye: [f64; 3], target: [f64; 3]| {
        render::Camera::look_at(DVec3::from_array(eye), DVec3::from_array(target), 500.0)
    };
    let mut rolled = look([5.0, 9.0, 14.0], [0.0, 0.0, 0.0]);
    rolled.up = DVec3::new(0.6, 1.0, 0.2);
    let views = [
        table_scene(0.0).camera,
        look([0.0, 40.0, 20.0], [0.0, 0.0, 0.0]),
        look([0.0, 4.0, 12.0], [0.0, 0.0, -30.0]),
        look([-3.0, 12.0, 3.0], [2.0, 0.0, -2.0]),
        rolled,
    ];
    let mut fewer = 0;
    for (k, camera) in views.into_iter().enumerate() {
        let scene = Scene {
            camera,
            ..table_scene(40.0 + 7.0 * k as f64)
        };
        let draw = |whole: bool| {
            let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default());
            let cfg = ArConfig {
                background_whole: whole,
                ..config(EffectSet::ALL)
            };
            let frame = frame_for(&scene, &cfg);
            add_effect_passes(&mut r, &gpu, cfg, frame);
            render_image(&gpu, &mut r, &scene, SIZE).expect("render")
        };
        let ((with, with_report), (without, without_report)) = (draw(false), draw(true));
        let differ: Vec<String> = with
            .enumerate_pixels()
            .zip(without.pixels())
            .filter(|((_, _, a), b)| a != b)
            .map(|((x, y, a), b)| format!("({x}, {y}) {a:?} {b:?}"))
            .collect();
        assert!(
            differ.is_empty(),
            "view {k}: {} pixels differ: {}",
            differ.len(),
            differ.join(", ")
        );
        let background = |r: &render::FrameReport| {
            r.shader_invocations
                .iter()
                .find(|i| i.pass == "background")
                .map(|i| i.fragment)
        };
        if let (Some(a), Some(b)) = (background(&with_report), background(&without_report)) {
            assert!(
                a <= b,
                "view {k}: {a} fragments with the cover, {b} without"
            );
            fewer += usize::from(a < b);
        }
    }
    let counted = render_image(
        &gpu,
        &mut Renderer::new(&gpu, OFFSCREEN_FORMAT, RenderOptions::default()),
        &table_scene(0.0),
        SIZE,
    )
    .expect("render")
    .1
    .shader_invocations
    .is_empty();
    assert!(
        counted || fewer >= 3,
        "the cover saved fragments in {fewer} views"
    );
}
