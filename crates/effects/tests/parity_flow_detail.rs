//! The flow map's detail texture on the GPU (`detail_slope` of `flowmap.wgsl`: the baked
//! `Rg16Float` texture through the wrap-around bilinear sampler, as the AR water samples it)
//! against the f64 field `effects::flow_detail::detail_slope`, within the bound derived from
//! the field's closed-form derivatives, the half-float texels and the least filtering
//! precision Vulkan allows (`effects::flow_detail::detail_texture_error`), not from what this
//! adapter gives; and the same path failing on a texture baked half a texel off. Then the
//! flow's whole share, `flow_slope` (two advected copies of that texture, weighted and scaled
//! by the current's speed), against `effects::flowmap::flow_slope`, within a bound carried
//! through its arithmetic by `render::wgsl_accuracy::Inexact`, and failing on a copy a quarter
//! period off. Skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use effects::flow_detail::{
    DETAIL_TEXELS, bake_detail, detail_gradient_max, detail_slope, detail_slope_max,
    detail_texture_error,
};
use effects::flowmap::{DEFAULT_JUMP, FlowPhase, flow_phases, flow_slope};
use effects::passes::EffectsUniform;
use glam::DVec2;
use render::gpu::{Gpu, test_gpu};
use render::wgsl_accuracy::{Inexact, length};
use wgpu::util::DeviceExt;

/// The detail texture of `texture` (`texels`² f16 pairs) and the wrap-around sampler, as the
/// AR water binds them.
fn detail_binding(
    gpu: &Gpu,
    texture: &[[u16; 2]],
    texels: u32,
) -> (wgpu::TextureView, wgpu::Sampler) {
    let tex = effects::passes::flow_detail_texture_of(gpu, texture, texels);
    (
        tex.create_view(&Default::default()),
        effects::passes::linear_repeat_sampler(&gpu.device),
    )
}

/// Bindings 5 and 6 of the effects' group: the detail texture and its sampler.
fn detail_entries<'a>(
    view: &'a wgpu::TextureView,
    sampler: &'a wgpu::Sampler,
) -> [wgpu::BindGroupEntry<'a>; 2] {
    [
        wgpu::BindGroupEntry {
            binding: 5,
            resource: wgpu::BindingResource::TextureView(view),
        },
        wgpu::BindGroupEntry {
            binding: 6,
            resource: wgpu::BindingResource::Sampler(sampler),
        },
    ]
}

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
    let (view, sampler) = detail_binding(gpu, texture, texels);
    let fx = detail_entries(&view, &sampler);
    let bytes =
        render::compute::run_kernel_with(gpu, "flow detail parity", &src, points, 8, &[&[], &fx])
            .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Points over [−REACH, REACH]² (fixed seed): random, and on texel centres and edges, where
/// the filter's weights are 0, ½ or 1.
fn points() -> Vec<[f32; 2]> {
    let mut rnd = render::golden::fixed_seed_uniform(17);
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

/// The detail tile (m per flow period) of the parity cases: `ArConfig`'s default.
const TILE: f64 = 12.0;

/// The farthest a flow case's sample point reaches from the tile's origin, in tiles: points
/// within 40 m (3.4 tiles), currents to 2 m/s (0.17 tiles per period), offsets below 1.
const FLOW_REACH: f64 = 5.0;

/// `flow_slope` of `flowmap.wgsl` at each case (xy: the local point, m; zw: the current, m/s)
/// with the two copies `phases` in the effects' uniform, at the sample points
/// `flow_sample_points` forms there (in the AR water the vertices form them and the rasteriser
/// interpolates them; `flowmap::tests` checks that interpolating is forming them).
fn wgsl_flow_slopes(gpu: &Gpu, phases: [[f32; 4]; 2], cases: &[[f32; 4]]) -> Vec<[f32; 2]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec2<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let current = input[id.x].zw;
        output[id.x] = flow_slope(flow_sample_points(input[id.x].xy, current), current);
    }
}
"#;
    let src = effects::wgsl::source(&[
        effects::passes::EFFECTS_COMMON,
        effects::passes::FLOWMAP,
        kernel,
    ]);
    let mut fx: EffectsUniform = bytemuck::Zeroable::zeroed();
    [fx.flow_a, fx.flow_b] = phases;
    fx.current = [0.0, 0.0, 1.0, TILE as f32];
    let uniform = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("flow slope parity"),
            contents: bytemuck::bytes_of(&fx),
            usage: wgpu::BufferUsages::UNIFORM,
        });
    let (view, sampler) =
        detail_binding(gpu, effects::flow_detail::detail_texture(), DETAIL_TEXELS);
    let [texture, filter] = detail_entries(&view, &sampler);
    let fx = [
        wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        },
        texture,
        filter,
    ];
    let bytes =
        render::compute::run_kernel_with(gpu, "flow slope parity", &src, cases, 8, &[&[], &fx])
            .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// The uniform's copy (progress, weight, offset) of a phase, in f32.
fn gpu_phase(phase: &FlowPhase) -> [f32; 4] {
    [
        phase.progress as f32,
        phase.weight as f32,
        phase.offset.x as f32,
        phase.offset.y as f32,
    ]
}

/// The phase the GPU is given, as the reference reads it (the same f32 numbers).
fn phase_of(gpu: [f32; 4]) -> FlowPhase {
    let f = |k: usize| f64::from(gpu[k]);
    FlowPhase {
        progress: f(0),
        weight: f(1),
        offset: DVec2::new(f(2), f(3)),
    }
}

/// What a conforming GPU's `flow_slope` may err by at `case` with the copies `phases`, per
/// component: its arithmetic in `Inexact` numbers, each sample point's error moving the
/// sample by up to the field's largest gradient times it, on top of the sampled texture's own
/// bound (`detail_texture_error` at FLOW_REACH tiles).
fn flow_slope_bound(case: [f32; 4], phases: [[f32; 4]; 2]) -> DVec2 {
    let tile = Inexact::of(TILE as f32);
    let flow = [Inexact::of(case[2]) / tile, Inexact::of(case[3]) / tile];
    let uv = [Inexact::of(case[0]) / tile, Inexact::of(case[1]) / tile];
    let texture = detail_texture_error(DETAIL_TEXELS, FLOW_REACH).total();
    let g = detail_gradient_max();
    let copy = |phase: [f32; 4]| {
        let progress = Inexact::of(phase[0]);
        let point = [0, 1].map(|a| uv[a] - flow[a] * progress + Inexact::of(phase[2 + a]));
        assert!(
            point.iter().all(|c| c.magnitude() <= FLOW_REACH),
            "{point:?}"
        );
        let at = detail_slope(DVec2::new(point[0].value, point[1].value));
        [0, 1].map(|j| {
            let sample = Inexact {
                value: at[j],
                error: texture[j] + g[j][0] * point[0].error + g[j][1] * point[1].error,
            };
            sample * Inexact::of(phase[1])
        })
    };
    let (a, b) = (copy(phases[0]), copy(phases[1]));
    let current = [Inexact::of(case[2]), Inexact::of(case[3])];
    let k = (length(&current) * Inexact::exact(4.0) / tile).clamp(0.0, 1.0);
    let s = [0, 1].map(|j| (a[j] + b[j]) * k);
    DVec2::new(s[0].error, s[1].error)
}

/// Points within 40 m and currents to 2 m/s (fixed seed), still water and the speeds where
/// k = 4·|current|/tile saturates (3 m/s) among them.
fn flow_cases() -> Vec<[f32; 4]> {
    let mut rnd = render::golden::fixed_seed_uniform(29);
    (0..20_000)
        .map(|k| {
            let p = DVec2::new(rnd() * 80.0 - 40.0, rnd() * 80.0 - 40.0) / 2f64.sqrt();
            let speed = match k % 5 {
                0 => 0.0,
                1 => 0.75,
                _ => 2.0 * rnd(),
            };
            let c = DVec2::from_angle(rnd() * std::f64::consts::TAU) * speed;
            [p.x as f32, p.y as f32, c.x as f32, c.y as f32]
        })
        .collect()
}

/// The largest error per component and the largest error/bound ratio of the GPU's flow slopes
/// `got` (given `given` copies) against `effects::flowmap::flow_slope` with the copies `want`.
fn worst_flow(
    got: &[[f32; 2]],
    cases: &[[f32; 4]],
    given: [[f32; 4]; 2],
    want: [[f32; 4]; 2],
) -> (DVec2, f64) {
    let phases = want.map(phase_of);
    let (mut worst, mut ratio) = (DVec2::ZERO, 0.0f64);
    for (g, c) in got.iter().zip(cases) {
        let f = |k: usize| f64::from(c[k]);
        let reference = flow_slope(
            DVec2::new(f(0), f(1)),
            DVec2::new(f(2), f(3)),
            TILE,
            &phases,
        );
        let err = (DVec2::new(f64::from(g[0]), f64::from(g[1])) - reference).abs();
        let bound = flow_slope_bound(*c, given);
        worst = worst.max(err);
        ratio = ratio.max((err / bound).max_element());
    }
    (worst, ratio)
}

#[test]
fn the_flow_slope_on_the_gpu_is_the_f64_reference_within_its_bound() {
    let Some(gpu) = test_gpu() else { return };
    let cases = flow_cases();
    let mut largest = DVec2::ZERO;
    // Three moments: mid-period, near A's restart (its weight small), and hours into a race.
    for t in [0.6, 3.98, 36_000.3] {
        let phases = flow_phases(t, 2.0, DEFAULT_JUMP).map(|p| gpu_phase(&p));
        let got = wgsl_flow_slopes(&gpu, phases, &cases);
        let (worst, ratio) = worst_flow(&got, &cases, phases, phases);
        eprintln!(
            "flow slope on the GPU at t = {t} s: {} cases, worst |Δ| {:.3e}, {:.3e}, worst \
             error/bound {ratio:.3}",
            cases.len(),
            worst.x,
            worst.y,
        );
        assert!(ratio <= 1.0, "t = {t}: error/bound {ratio}");
        largest = got.iter().fold(largest, |m, g| {
            m.max(DVec2::new(f64::from(g[0]), f64::from(g[1])).abs())
        });
    }
    // The detail is there at all: the fast cases reach half the field's largest slope.
    let m = detail_slope_max();
    assert!(largest.x > 0.5 * m.x && largest.y > 0.5 * m.y, "{largest}");
}

#[test]
fn a_flow_copy_a_quarter_period_off_fails_the_gpu_parity() {
    // The GPU's copy A a quarter period further on than the reference's: its sample points
    // move by a quarter of the flow, up to 0.04 tiles at 2 m/s.
    let Some(gpu) = test_gpu() else { return };
    let cases = flow_cases();
    let phases = flow_phases(0.6, 2.0, DEFAULT_JUMP).map(|p| gpu_phase(&p));
    let mut off = phases;
    off[0][0] += 0.25;
    let got = wgsl_flow_slopes(&gpu, off, &cases);
    let (worst, ratio) = worst_flow(&got, &cases, off, phases);
    eprintln!("flow slope with copy A a quarter period off: worst error/bound {ratio:.1}");
    assert!(
        ratio > 2.0,
        "a copy off by a quarter period passes: worst {worst}, ratio {ratio}"
    );
}
