//! What lavapipe's fragment invocation count measures (the budget model's input,
//! `FrameReport::shader_invocations`): 16 per 4×4 block that a triangle touches, before the
//! depth test, so on the clip-map's small far-field triangles it is several times the pixels
//! shaded; `ClipMesh::screen_coverage` counts the same blocks on the CPU, and the 2×2 quads a
//! phone GPU shades.

use render::frame::FrameContext;
use render::gpu::test_gpu;
use render::{RenderOptions, Renderer};

#[test]
fn lavapipe_counts_sixteen_fragments_per_four_by_four_block_a_triangle_touches() {
    let Some(gpu) = test_gpu() else { return };
    let mut r = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, RenderOptions::default());
    let scene = render::golden::test_scene(100.0, Vec::new());
    let size = [360, 640];
    let (_, report) = render::render_image(&gpu, &mut r, &scene, size).unwrap();
    let Some(water) = report.shader_invocations.iter().find(|i| i.pass == "water") else {
        eprintln!("skipped: no pipeline statistics on {}", report.adapter);
        return;
    };
    let frame = FrameContext::new(&scene, report.size, r.options.error_px);
    let (o, sea, t) = (frame.origin, &scene.sea, scene.t);
    let c = frame
        .mesh
        .screen_coverage(frame.view_proj, report.size, |p| {
            let d = sea.displace([p[0] + o.x, p[1] + o.y], t);
            [d[0] - o.x, d[1], d[2] - o.y]
        });
    if !report.adapter.contains("llvmpipe") {
        eprintln!("skipped: {} is not lavapipe", report.adapter);
        return;
    }
    // Whole 4×4 blocks: 16 a block, never a pixel at a time.
    assert_eq!(water.fragment % 16, 0, "{water:?}");
    // The blocks the CPU finds, up to the displacement the GPU draws with fewer waves in
    // the far levels (4.8 % apart when written: 815,232 counted, 854,224 found).
    let blocks = c.block_fragments as f64;
    let counted = water.fragment as f64;
    assert!((counted - blocks).abs() < 0.08 * counted, "{water:?} {c:?}");
    // Not the pixels shaded: 4.8 times the water's pixels, 2.2 times a phone's 2×2 quads.
    assert!(counted > 3.0 * c.pixels as f64, "{water:?} {c:?}");
    assert!(counted > 1.8 * c.quad_fragments as f64, "{water:?} {c:?}");
}
