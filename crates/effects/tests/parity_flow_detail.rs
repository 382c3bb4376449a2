//! The flow map's detail texture on the GPU (`detail_slope` of `flowmap.wgsl`: the baked
//! `Rg16Float` texture through the wrap-around bilinear sampler, as the AR water samples it)
//! against the f64 field `effects::flow_detail::detail_slope`, within the bound derived from
//! the field's closed-form derivatives, the half-float texels and the least filtering
//! precision Vulkan allows (`effects::flow_detail::detail_texture_error`), not from what this
//! adapter gives; and the same path failing on a texture baked half a texel off. Skipped
//! without an adapter unless REGATTA_REQUIRE_GPU=true.

use effects::flow_detail::{
    DETAIL_TEXELS, bake_detail, detail_slope, detail_slope_max, detail_texture_error,
};
use glam::DVec2;
use render::gpu::{Gpu, test_gpu};

/// The farthest the sample points reach from the tile's origin, in tiles.
const REACH: f64 = 3.0;

/// `detail_slope` of `flowmap.wgsl` at each point, sampling `texture` (`texels`² f16 pairs).
fn wgsl_detail_slopes(
    gpu: &Gpu,
    texture: &[[u16; 2]],
    texels: u32,
    points: &[[f32; 2]],
) -> Vec<[f32; 2]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<vec2<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec2<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        output[id.x] = detail_slope(input[id.x]);
    }
}
"#;
    let src = effects::wgsl::source(&[
        effects::passes::EFFECTS_COMMON,
        effects::passes::FLOWMAP,
        kernel,
    ]);
    let tex = effects::passes::flow_detail_texture_of(gpu, texture, texels);
    let view = tex.create_view(&Default::default());
    let sampler = effects::passes::linear_repeat_sampler(&gpu.device);
    let fx = [
        wgpu::BindGroupEntry {
            binding: 5,
            resource: wgpu::BindingResource::TextureView(&view),
        },
        wgpu::BindGroupEntry {
            binding: 6,
            resource: wgpu::BindingResource::Sampler(&sampler),
        },
    ];
    let bytes =
        render::compute::run_kernel_with(gpu, "flow detail parity", &src, points, 8, &[&[], &fx])
            .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Points over [−REACH, REACH]² (fixed seed): random, and on texel centres and edges, where
/// the filter's weights are 0, ½ or 1.
fn points() -> Vec<[f32; 2]> {
    let mut seed = 17u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let n = f64::from(DETAIL_TEXELS);
    (0..40_000)
        .map(|k| {
            let (u, v) = (rnd() * 2.0 * REACH - REACH, rnd() * 2.0 * REACH - REACH);
            match k % 4 {
                0 => [
                    ((u * n).round() / n) as f32,
                    ((v * n).round() + 0.5) as f32 / n as f32,
                ],
                1 => [
                    ((u * n).round() + 0.5) as f32 / n as f32,
                    ((v * n).round() + 0.5) as f32 / n as f32,
                ],
                _ => [u as f32, v as f32],
            }
        })
        .collect()
}

/// The largest error per component and the largest error/bound ratio of `got` against the
/// f64 field at the same (f32) points.
fn worst(got: &[[f32; 2]], points: &[[f32; 2]], bound: DVec2) -> (DVec2, f64) {
    let (mut worst, mut ratio) = (DVec2::ZERO, 0.0f64);
    for (g, p) in got.iter().zip(points) {
        let uv = DVec2::new(f64::from(p[0]), f64::from(p[1]));
        let err = (DVec2::new(f64::from(g[0]), f64::from(g[1])) - detail_slope(uv)).abs();
        worst = worst.max(err);
        ratio = ratio.max((err / bound).max_element());
    }
    (worst, ratio)
}

#[test]
fn the_sampled_detail_texture_is_the_f64_field_within_its_bound() {
    let Some(gpu) = test_gpu() else { return };
    let points = points();
    let got = wgsl_detail_slopes(
        &gpu,
        effects::flow_detail::detail_texture(),
        DETAIL_TEXELS,
        &points,
    );
    let e = detail_texture_error(DETAIL_TEXELS, REACH);
    let bound = e.total();
    let (worst, ratio) = worst(&got, &points, bound);
    eprintln!(
        "flow detail on the GPU: {} points, worst |Δ| {:.3e}, {:.3e} against {:.3e}, {:.3e} \
         (exact filter {:.3e}), worst error/bound {ratio:.3}",
        points.len(),
        worst.x,
        worst.y,
        bound.x,
        bound.y,
        e.exact_filter().x,
    );
    assert!(ratio <= 1.0, "error/bound {ratio}");
    // The field is there at all (the samples reach most of its range), and the bound is 1 %
    // of it.
    let largest = got.iter().fold(DVec2::ZERO, |m, g| {
        m.max(DVec2::new(f64::from(g[0]), f64::from(g[1])).abs())
    });
    let m = detail_slope_max();
    assert!(largest.x > 0.5 * m.x && largest.y > 0.5 * m.y, "{largest}");
    assert!(bound.x < 0.011 * m.x && bound.y < 0.011 * m.y, "{bound}");
}

#[test]
fn a_texture_baked_half_a_texel_off_fails_the_gpu_parity() {
    // Texel (i, j) holding the field at (i/N, j/N), not at its centre: the sampled field is
    // shifted by half a texel, up to max|∇f|·h/2 off.
    let Some(gpu) = test_gpu() else { return };
    let n = DETAIL_TEXELS;
    let shifted = effects::flow_detail::bake_detail_at(n, 0.0);
    // The right texture through the same path for comparison: the baked one.
    assert_ne!(shifted, bake_detail(n));
    let points = points();
    let got = wgsl_detail_slopes(&gpu, &shifted, n, &points);
    let bound = detail_texture_error(n, REACH).total();
    let (worst, ratio) = worst(&got, &points, bound);
    assert!(
        ratio > 2.0,
        "a shifted texture passes: worst {worst}, ratio {ratio}"
    );
}
