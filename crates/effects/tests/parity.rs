//! The effects' mirrored WGSL functions on the GPU (`render::compute::run_kernel`, lavapipe in
//! CI) against their f64 references, each shown to fail on a broken input fed through the same
//! path: `edge_weight`, `overhead_sun`, `ring_hit` and `refracted_table`. (The optics, the
//! current around marks and the caustic map have theirs in the crate's `gpu_tests`.) Skipped
//! without an adapter unless REGATTA_REQUIRE_GPU=true.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_6};

use effects::caustics::{CHEAP_SUN_RADIUS, overhead_sun};
use effects::passes::EffectsUniform;
use effects::reflection::Ring;
use effects::refraction::refract_to_table;
use glam::{DVec2, DVec3};
use render::gpu::{Gpu, test_gpu};
use render::optics::{PinholeCamera, Plane};
use wgpu::util::DeviceExt;

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

// ---- overhead_sun (caustics.wgsl) --------------------------------------------------------------

/// `overhead_sun` of `caustics.wgsl` for each unit normal, with `prelude` as the effects'.
fn wgsl_overhead_sun(gpu: &Gpu, prelude: &str, normals: &[[f32; 4]]) -> Vec<f32> {
    // caustic_light (not called) names the pipeline's constant: declare it.
    let kernel = r#"
const FX_CHEAP_CAUSTICS: bool = true;
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<f32>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        output[id.x] = overhead_sun(input[id.x].xyz);
    }
}
"#;
    let src = render::shader::source(&[
        prelude,
        effects::passes::EFFECTS_COMMON,
        effects::passes::CAUSTICS,
        kernel,
    ]);
    let bytes = render::compute::run_kernel(gpu, "overhead sun parity", &src, normals, 4)
        .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Unit normals tilted 0 to π in steps of 0.01 rad (upside-down ones included), 8 azimuths
/// each, and densely (1e-4 rad) across the critical angle of water (48.6°), beyond which the
/// upward ray is reflected back (total internal reflection: no sun).
fn sun_normals() -> Vec<[f32; 4]> {
    let critical = (1.0 / render::optics::N_WATER).asin();
    let tilts = (0..=314)
        .map(|i| f64::from(i) * 0.01)
        .chain((-50..=50).map(|i| critical + f64::from(i) * 1e-4));
    tilts
        .flat_map(|tilt| {
            (0..8).map(move |k| {
                let az = f64::from(k) * 0.785 + 0.1;
                let n = DVec3::new(tilt.sin() * az.cos(), tilt.cos(), tilt.sin() * az.sin());
                [n.x as f32, n.y as f32, n.z as f32, 0.0]
            })
        })
        .collect()
}

/// Largest difference between the GPU's sun and `effects::caustics::overhead_sun` at the same
/// (f32) normals and the shader's radius.
fn worst_sun_error(got: &[f32], normals: &[[f32; 4]]) -> f64 {
    got.iter()
        .zip(normals)
        .map(|(g, n)| {
            let n = DVec3::new(f64::from(n[0]), f64::from(n[1]), f64::from(n[2]));
            let want = overhead_sun(n, CHEAP_SUN_RADIUS);
            (f64::from(*g) - want).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_wgsl_overhead_sun_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let normals = sun_normals();
    let got = wgsl_overhead_sun(&gpu, &effects::wgsl::prelude(), &normals);
    let worst = worst_sun_error(&got, &normals);
    eprintln!(
        "overhead_sun: {} normals, worst |Δ| {worst:.2e}",
        normals.len()
    );
    // WGSL's acos is only as accurate as atan2 (4096 ulps: the spec's bound), a relative
    // error of 4096 · 2^-23 = 4.9e-4 of the angle a; e^{−x²} (x = a/ρ) then moves by at most
    // 2x² e^{−x²} ≤ 2/e of that: 3.6e-4. The refracted y (≈ 1, a few f32 roundings of 8 ulps,
    // 4.8e-7) moves a by δy/sin a, the sun by 2δy/ρ² ≈ 1e-4 at most. Asserted: 4.6e-4 of the
    // peak 1 (lavapipe's acos is some 3000 ulps off near 0.05 rad: 1.65e-4 measured).
    assert!(worst < 4.6e-4, "worst {worst:e}");
    // The whole range is sampled: the full sun overhead, none under total reflection.
    assert!(got.contains(&1.0) && got.iter().filter(|g| **g == 0.0).count() > 1000);
}

#[test]
fn a_broken_sun_radius_fails_the_overhead_sun_parity() {
    // The same kernel and check with the radius written as its own literal, doubled: at a
    // tilt of the radius the sun differs by e^{−¼} − e^{−1} ≈ 0.41.
    let Some(gpu) = test_gpu() else { return };
    let prelude = effects::wgsl::prelude();
    let line = format!(
        "const CHEAP_SUN_RADIUS: f32 = {:?};",
        CHEAP_SUN_RADIUS as f32
    );
    assert!(prelude.contains(&line), "{prelude}");
    let doubled = format!(
        "const CHEAP_SUN_RADIUS: f32 = {:?};",
        2.0 * CHEAP_SUN_RADIUS as f32
    );
    let normals = sun_normals();
    let got = wgsl_overhead_sun(&gpu, &prelude.replace(&line, &doubled), &normals);
    assert!(worst_sun_error(&got, &normals) > 0.3);
}

// ---- the effects' uniform and camera image, for ring_hit and refracted_table -------------------

/// The effects' test camera: 640×480 px, focal length 500 px, at `eye` looking at `target`.
fn camera(eye: DVec3, target: DVec3) -> PinholeCamera {
    PinholeCamera {
        fx: 500.0,
        fy: 500.0,
        cx: 320.0,
        cy: 240.0,
        width: 640.0,
        height: 480.0,
        pose: glam::dcamera::rh::view::look_at_mat4(eye, target, DVec3::Y).inverse(),
    }
}

/// The `Effects` uniform with `camera` and `table` (depth, ring radius, ring centre x, z) as
/// the passes fill them (local origin 0); the rest zero.
fn effects_uniform(camera: &PinholeCamera, table: [f64; 4]) -> EffectsUniform {
    let mut fx: EffectsUniform = bytemuck::Zeroable::zeroed();
    fx.camera_view = camera.pose.inverse().as_mat4().to_cols_array_2d();
    fx.intrinsics = [
        (camera.fx / camera.width) as f32,
        (camera.fy / camera.height) as f32,
        (camera.cx / camera.width) as f32,
        (camera.cy / camera.height) as f32,
    ];
    fx.table = table.map(|v| v as f32);
    fx
}

fn uniform_buffer(gpu: &Gpu, fx: &EffectsUniform) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("effects uniform"),
            contents: bytemuck::bytes_of(fx),
            usage: wgpu::BufferUsages::UNIFORM,
        })
}

/// f32 of a 3-vector, w = 0.
fn v4(v: DVec3) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

fn dvec(v: [f32; 4]) -> DVec3 {
    DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))
}

/// f32 unit roundoff.
const U: f64 = f32::EPSILON as f64 / 2.0;

// ---- ring_hit (reflection.wgsl) ---------------------------------------------------------------

const RING: Ring = Ring {
    centre: DVec2::new(3.0, -2.0),
    radius: 12.0,
};

/// `ring_hit` of `reflection.wgsl` for each (surface point, reflected direction), the ring
/// given to the GPU as `ring`: vec4(hit, 1), or 0 for none.
fn wgsl_ring_hits(gpu: &Gpu, ring: &Ring, cases: &[[[f32; 4]; 2]]) -> Vec<[f32; 4]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 2>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        output[id.x] = ring_hit(input[id.x][0].xyz, input[id.x][1].xyz);
    }
}
"#;
    let src = effects::wgsl::source(&[
        effects::passes::EFFECTS_COMMON,
        effects::passes::REFLECTION,
        kernel,
    ]);
    let table = [0.0, ring.radius, ring.centre.x, ring.centre.y];
    let uniform = uniform_buffer(gpu, &effects_uniform(&camera(DVec3::Y, DVec3::ZERO), table));
    let fx = [wgpu::BindGroupEntry {
        binding: 0,
        resource: uniform.as_entire_binding(),
    }];
    let bytes =
        render::compute::run_kernel_with(gpu, "ring hit parity", &src, cases, 16, &[&[], &fx])
            .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Points on the water inside the ring (out to 0.999 R, where the exit is close) and rays
/// from each: level, grazing (1e-4 rad up), steep, 1 mrad from vertical, vertical (no
/// horizontal part: never meets the ring) and downwards.
fn ring_cases() -> Vec<[[f32; 4]; 2]> {
    let elevations = [
        0.0,
        1e-4,
        0.01,
        0.3,
        0.8,
        1.2,
        1.5,
        FRAC_PI_2 - 1e-3,
        FRAC_PI_2,
        -0.2,
    ];
    let mut out = Vec::new();
    for (i, frac) in [0.0, 0.3, 0.6, 0.9, 0.999].iter().enumerate() {
        for k in 0..7 {
            let a = f64::from(k) * 0.9 + i as f64;
            let o = RING.centre + DVec2::new(a.cos(), a.sin()) * frac * RING.radius;
            let p = DVec3::new(o.x, 0.05 * (a * 3.0).sin(), o.y);
            for e in elevations {
                for m in 0..12 {
                    let az = f64::from(m) * FRAC_PI_6 + 0.05 * f64::from(k);
                    let r = DVec3::new(e.cos() * az.cos(), e.sin(), e.cos() * az.sin());
                    out.push([v4(p), v4(r)]);
                }
            }
        }
    }
    out
}

/// Against `Ring::hit` at the same (f32) inputs: the largest hit-point error relative to the
/// scale of the computation, (|o| + R)/|r.xz| + |p| (o = p − c: the exit distance is the
/// difference of two terms of up to that size, which cancel when the point is near the ring
/// and heads out), and the cases where one hits and the other does not.
fn compare_ring_hits(got: &[[f32; 4]], cases: &[[[f32; 4]; 2]]) -> (f64, usize, usize) {
    let (mut worst, mut disagree, mut hits) = (0.0f64, 0, 0);
    for (g, [p, r]) in got.iter().zip(cases) {
        let (p, r) = (dvec(*p), dvec(*r));
        match (RING.hit(p, r), g[3] > 0.0) {
            (Some(q), true) => {
                hits += 1;
                let o = DVec2::new(p.x, p.z) - RING.centre;
                let scale = (o.length() + RING.radius) / DVec2::new(r.x, r.z).length() + p.length();
                worst = worst.max((dvec(*g) - q).length() / scale);
            }
            (None, false) => {}
            _ => disagree += 1,
        }
    }
    (worst, disagree, hits)
}

#[test]
fn the_wgsl_ring_hit_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let cases = ring_cases();
    let got = wgsl_ring_hits(&gpu, &RING, &cases);
    let (worst, disagree, hits) = compare_ring_hits(&got, &cases);
    eprintln!(
        "ring_hit: {} rays, {hits} hits, worst |Δq| / scale {worst:.2e} ({:.1} u)",
        cases.len(),
        worst / U
    );
    // Up-going rays with a horizontal part hit (7 of the 10 elevations), the rest miss; the
    // shader's "no horizontal part" (a < 1e-8) and the reference's (a < 1e-16) agree here: no
    // ray of this set has 1e-16 ≤ a < 1e-8.
    assert_eq!(disagree, 0);
    assert_eq!(hits, cases.len() * 7 / 10);
    // About ten f32 operations, each rounding by at most u of the magnitudes involved (b/a
    // and √k/a up to the scale, |p|); the square root halves a relative error, the division
    // keeps it: 16 u of the scale. (Near the ring heading out, b and √k cancel: the hit there
    // is only good to u (|o| + R)/|r.xz|, 0.7 mm for a ray 1 mrad from vertical.)
    assert!(worst < 16.0 * U, "worst {worst:e} of the scale");
}

#[test]
fn a_broken_ring_fails_the_ring_hit_parity() {
    // The same kernel and check, the GPU given a ring 1 % larger than the reference's.
    let Some(gpu) = test_gpu() else { return };
    let cases = ring_cases();
    let broken = Ring {
        radius: RING.radius * 1.01,
        ..RING
    };
    let got = wgsl_ring_hits(&gpu, &broken, &cases);
    let (worst, _, _) = compare_ring_hits(&got, &cases);
    assert!(worst > 1e-3, "worst {worst:e}");
}

// ---- refracted_table (refraction.wgsl) ---------------------------------------------------------

/// Texels per side of the test's camera image, whose texel (i, j) holds its own centre's uv:
/// ((i + ½)/N, (j + ½)/N) in red and green. Filtered linearly (clamped to the edge) it returns
/// the uv it is sampled at, kept to the texel centres' range, so the colour the shader returns
/// is the point it sampled. (2i + 1)/2N has 11 significant bits: exact in a half float.
const UV_IMAGE: u32 = 1024;

/// What the uv image shows at `uv`.
fn uv_image_at(uv: DVec2) -> DVec2 {
    let half = 0.5 / f64::from(UV_IMAGE);
    uv.clamp(DVec2::splat(half), DVec2::splat(1.0 - half))
}

/// The half float of `v`, which it must hold exactly.
fn f16_bits(v: f32) -> u16 {
    let bits = v.to_bits();
    assert!(bits & 0x1fff == 0 && v >= 2f32.powi(-14) && v < 2.0, "{v}");
    let exp = ((bits >> 23) & 0xff) as u16 + 15 - 127;
    (exp << 10) | ((bits >> 13) & 0x3ff) as u16
}

fn uv_image(gpu: &Gpu) -> wgpu::Texture {
    let n = UV_IMAGE;
    let texels: Vec<u16> = (0..n * n)
        .flat_map(|k| {
            let centre = |i: u32| (2 * i + 1) as f32 / (2 * n) as f32;
            [f16_bits(centre(k % n)), f16_bits(centre(k / n))]
        })
        .collect();
    gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("uv image"),
            size: wgpu::Extent3d {
                width: n,
                height: n,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rg16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&texels),
    )
}

/// A view of the water: the camera, the table's depth, and the surface points with normals
/// its pixels see.
struct WaterView {
    camera: PinholeCamera,
    depth: f64,
    /// Surface point, unit view direction, unit normal (f32, as the GPU gets them).
    cases: Vec<[[f32; 4]; 3]>,
}

/// Rays through a 33 × 25 grid of pixels (the image's edges included) to a wavy surface
/// (±0.25 m), normals tilted up to 52° every way; every thirteenth a face overhanging
/// towards the viewer (its normal pointing down), which bends grazing rays up, away from
/// the table.
fn water_view(eye: DVec3, target: DVec3, depth: f64) -> WaterView {
    let camera = camera(eye, target);
    let mut cases = Vec::new();
    for k in 0..33 * 25 {
        let (i, j) = (f64::from(k % 33), f64::from(k / 33));
        let ray = camera.pixel_ray(DVec2::new(i * 20.0, j * 20.0));
        let h = 0.25 * (0.7 * i).sin() * (0.5 * j).cos();
        let Some((_, p)) = Plane::horizontal(h).intersect_ray(eye, ray) else {
            continue;
        };
        let (tilt, az) = (0.1 * f64::from(k % 10), 2.399 * f64::from(k));
        let mut n = DVec3::new(tilt.sin() * az.cos(), tilt.cos(), tilt.sin() * az.sin());
        if k % 13 == 0 {
            n = (-DVec3::new(ray.x, 0.0, ray.z).normalize() - 0.75 * DVec3::Y).normalize();
        }
        let view = (p - eye).normalize();
        cases.push([v4(p), v4(view), v4(n)]);
    }
    WaterView {
        camera,
        depth,
        cases,
    }
}

/// The views: looking down at 30° from 11 m over 3 m of water, and across it from 0.8 m up
/// over 0.5 m (the far pixels grazing at 87° from the vertical).
fn water_views() -> [WaterView; 2] {
    [
        water_view(DVec3::new(0.5, 6.0, 9.0), DVec3::ZERO, 3.0),
        water_view(DVec3::new(0.0, 0.8, 12.0), DVec3::new(0.0, 0.0, -20.0), 0.5),
    ]
}

/// `refracted_table` of `refraction.wgsl` for each case of `view` over the uv image, the GPU
/// given a table `depth` deep: vec4(colour = the uv sampled, path in the water).
fn wgsl_refracted_table(gpu: &Gpu, view: &WaterView, depth: f64) -> Vec<[f32; 4]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 3>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let c = input[id.x];
        output[id.x] = refracted_table(c[0].xyz, c[1].xyz, c[2].xyz);
    }
}
"#;
    let src = effects::wgsl::source(&[
        effects::passes::EFFECTS_COMMON,
        effects::passes::REFRACTION,
        kernel,
    ]);
    let uniform = uniform_buffer(gpu, &effects_uniform(&view.camera, [depth, 0.0, 0.0, 0.0]));
    let image = uv_image(gpu).create_view(&Default::default());
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let fx = [
        wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: wgpu::BindingResource::TextureView(&image),
        },
        wgpu::BindGroupEntry {
            binding: 4,
            resource: wgpu::BindingResource::Sampler(&sampler),
        },
    ];
    let bytes = render::compute::run_kernel_with(
        gpu,
        "refracted table parity",
        &src,
        &view.cases,
        16,
        &[&[], &fx],
    )
    .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// The GPU's samples against `refract_to_table` at the same (f32) surface points and normals:
/// the largest error of the sampled uv (image units) and of the path relative to its
/// length times its condition 1 + 1/|t.y| (t the ray's unit direction: a ray nearly level
/// meets the table far away, where its small t.y, a difference of terms near 1, decides
/// where), and how many samples were refracted inside the image (weight 1), in the fade band
/// (0 < weight < 1), beyond it (weight 0) and not to the table.
struct TableErrors {
    uv: f64,
    path: f64,
    counts: [usize; 4],
}

fn compare_refracted_table(got: &[[f32; 4]], view: &WaterView) -> TableErrors {
    let eye = view.camera.position();
    let table = Plane::horizontal(-view.depth);
    let mut e = TableErrors {
        uv: 0.0,
        path: 0.0,
        counts: [0; 4],
    };
    for (g, [p, _, n]) in got.iter().zip(&view.cases) {
        let (p, n) = (dvec(*p), dvec(*n));
        let s = refract_to_table(eye, p, n, &table, &view.camera);
        let want = uv_image_at(s.sampled_uv());
        e.uv =
            e.uv.max((DVec2::new(f64::from(g[0]), f64::from(g[1])) - want).length());
        let path_error = (f64::from(g[3]) - s.path).abs();
        e.path = e.path.max(match s.path {
            0.0 if path_error == 0.0 => 0.0,
            0.0 => f64::INFINITY,
            path => path_error / (path * (1.0 + path / (p.y + view.depth))),
        });
        let kind = match s.weight {
            _ if s.table_point.is_none() => 3,
            1.0 => 0,
            w if w > 0.0 => 1,
            _ => 2,
        };
        e.counts[kind] += 1;
    }
    e
}

#[test]
fn the_wgsl_refracted_table_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let mut counts = [0; 4];
    for view in water_views() {
        let got = wgsl_refracted_table(&gpu, &view, view.depth);
        let e = compare_refracted_table(&got, &view);
        eprintln!(
            "refracted_table, {} m deep: {} rays (inside, band, outside, no table: {:?}), \
             worst |Δuv| {:.2e}, |Δpath| {:.1} u of the path times its condition",
            view.depth,
            view.cases.len(),
            e.counts,
            e.uv,
            e.path / U
        );
        // The path: the unit direction's t.y carries a few roundings of terms near 1 (≤ 8 u),
        // moving the path by 8 u/|t.y| of it, and the division and the plane's distance a few
        // u more: 16 u of the path times its condition.
        assert!(
            e.path < 16.0 * U,
            "worst |Δpath| {:e} of path × condition",
            e.path
        );
        // The table point, so found (≤ 16 u of the ≤ 30 m from the eye where the condition is
        // near 1), goes through the 4×4 view matrix and the intrinsics: ≤ 1e-5 m at ≥ 5 m
        // from the camera, times the focal length (≤ 1.04 image widths): 2e-6 of the image.
        // The fade band's weight (slope 1/EDGE_FADE = 20 over a segment ≤ 0.3) adds 6 times
        // that near the border, and the image's filtering its sub-texel rounding (≤ 1/512 of
        // a texel, 1.9e-6). Asserted: 1.6e-5.
        assert!(e.uv < 1.6e-5, "worst |Δuv| {:e}", e.uv);
        for (c, n) in counts.iter_mut().zip(e.counts) {
            *c += n;
        }
    }
    // Every branch of the function is taken many times.
    assert!(counts.iter().all(|&c| c >= 20), "{counts:?}");
}

#[test]
fn a_broken_table_depth_fails_the_refracted_table_parity() {
    // The same kernels and checks, the GPU given a table 1 % deeper than the reference's.
    let Some(gpu) = test_gpu() else { return };
    for view in water_views() {
        let got = wgsl_refracted_table(&gpu, &view, view.depth * 1.01);
        let e = compare_refracted_table(&got, &view);
        assert!(
            e.uv > 1e-4 && e.path > 1e-4,
            "{} m: {:e} {:e}",
            view.depth,
            e.uv,
            e.path
        );
    }
}
