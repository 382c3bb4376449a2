//! The effects' mirrored WGSL functions on the GPU (`render::compute::run_kernel`, lavapipe in
//! CI) against their f64 references, each shown to fail on a broken input fed through the same
//! path. (The optics, the current around marks and the caustic map have theirs in the crate's
//! `gpu_tests`.) Skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use glam::DVec2;
use render::gpu::{Gpu, test_gpu};

/// `edge_weight` of `effects_common.wgsl` at each point, with `prelude` as the effects' prelude.
fn wgsl_edge_weights(gpu: &Gpu, prelude: &str, points: &[[f32; 2]]) -> Vec<f32> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<vec2<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<f32>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        output[id.x] = edge_weight(input[id.x]);
    }
}
"#;
    let src = render::shader::source(&[prelude, effects::passes::EFFECTS_COMMON, kernel]);
    let bytes = render::compute::run_kernel(gpu, "edge weight parity", &src, points, 4)
        .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// UV points inside, on and around the image border (out to twice the fade).
fn points() -> Vec<[f32; 2]> {
    (0..61 * 61)
        .map(|k| {
            let (i, j) = (k % 61, k / 61);
            [-0.12 + i as f32 * 0.0204, -0.12 + j as f32 * 0.0204]
        })
        .collect()
}

/// Largest difference between the GPU weights and `effects::refraction::edge_weight`.
fn worst_edge_weight_error(got: &[f32], points: &[[f32; 2]]) -> f64 {
    got.iter()
        .zip(points)
        .map(|(g, p)| {
            let want =
                effects::refraction::edge_weight(DVec2::new(f64::from(p[0]), f64::from(p[1])));
            (f64::from(*g) - want).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_wgsl_edge_weight_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let points = points();
    let got = wgsl_edge_weights(&gpu, &effects::wgsl::prelude(), &points);
    let worst = worst_edge_weight_error(&got, &points);
    // f32 of a length and a division of numbers ≤ 1: a few ulps.
    assert!(worst < 1e-5, "worst {worst:e}");
    // Both ends are reached: 1 inside, 0 beyond the fade.
    assert!(got.contains(&1.0) && got.contains(&0.0));
}

#[test]
fn a_broken_edge_fade_fails_the_edge_weight_parity() {
    // The same kernel and check with the fade written as its own literal, doubled: the
    // weights between the border and twice the fade then miss by up to a half.
    let Some(gpu) = test_gpu() else { return };
    let prelude = effects::wgsl::prelude();
    let line = format!(
        "const EDGE_FADE: f32 = {:?};",
        effects::refraction::EDGE_FADE as f32
    );
    assert!(prelude.contains(&line), "{prelude}");
    let broken = prelude.replace(
        &line,
        &format!(
            "const EDGE_FADE: f32 = {:?};",
            2.0 * effects::refraction::EDGE_FADE as f32
        ),
    );
    let points = points();
    let got = wgsl_edge_weights(&gpu, &broken, &points);
    assert!(worst_edge_weight_error(&got, &points) > 0.4);
}
