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
use render::wgsl_accuracy::Inexact;
use wgpu::util::DeviceExt;

#[path = "parity/bounds.rs"]
mod bounds;

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
    let src = render::shader::source(&[
        prelude,
        render::water_look::WATER_LOOK_WGSL,
        effects::passes::EFFECTS_COMMON,
        kernel,
    ]);
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

/// The worst of a set of cases, each an error against its own bound: the largest error, the
/// largest bound and the largest error/bound ratio.
#[derive(Default)]
struct Worst {
    error: f64,
    bound: f64,
    ratio: f64,
}

impl Worst {
    fn add(&mut self, error: f64, bound: f64) {
        self.error = self.error.max(error);
        self.bound = self.bound.max(bound);
        if error != 0.0 {
            self.ratio = self.ratio.max(error / bound);
        }
    }
}

/// The GPU weights against `effects::refraction::edge_weight`, each point against its own
/// bound (`bounds::edge_weight`): the largest error, the largest bound and the largest
/// error/bound ratio.
fn worst_edge_weight_error(got: &[f32], points: &[[f32; 2]]) -> (f64, f64, f64) {
    let mut worst = Worst::default();
    for (g, p) in got.iter().zip(points) {
        let want = effects::refraction::edge_weight(DVec2::new(f64::from(p[0]), f64::from(p[1])));
        let bound = bounds::edge_weight([Inexact::of(p[0]), Inexact::of(p[1])]);
        assert!((bound.value - want).abs() < 1e-12, "{p:?}");
        worst.add((f64::from(*g) - want).abs(), bound.error);
    }
    (worst.error, worst.bound, worst.ratio)
}

#[test]
fn the_wgsl_edge_weight_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let points = points();
    let got = wgsl_edge_weights(&gpu, &effects::wgsl::prelude(), &points);
    let (worst, bound, ratio) = worst_edge_weight_error(&got, &points);
    eprintln!(
        "edge_weight: {} points, worst |Δ| {worst:.2e}, largest bound {bound:.2e}, \
         worst error/bound {ratio:.3}",
        points.len()
    );
    // Each point within its bound: a length (sqrt: 1.0/inverseSqrt, 2 + 2.5 ULP) and a
    // division (2.5 ULP) by the fade, in f32.
    assert!(ratio <= 1.0, "error/bound {ratio:e}");
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
    let (worst, bound, _) = worst_edge_weight_error(&got, &points);
    assert!(
        worst > 0.4 && worst > 100.0 * bound,
        "{worst:e} against {bound:e}"
    );
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
        render::water_look::WATER_LOOK_WGSL,
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

/// The GPU's sun against `effects::caustics::overhead_sun` at the same (f32) normals and the
/// shader's radius, each normal against its own bound (`bounds::overhead_sun`): the largest
/// error, the largest bound, the largest error/bound ratio and the normals at the critical
/// angle that a conforming GPU may put on either side of it (not bounded).
fn worst_sun_error(got: &[f32], normals: &[[f32; 4]]) -> (f64, f64, f64, usize) {
    let (mut worst, mut undecided) = (Worst::default(), 0);
    for (g, n4) in got.iter().zip(normals) {
        let n = dvec(*n4);
        let want = overhead_sun(n, CHEAP_SUN_RADIUS);
        let bounds::Bounded::Decided(bound) = bounds::overhead_sun(*n4, CHEAP_SUN_RADIUS) else {
            undecided += 1;
            continue;
        };
        assert!(
            (bound.value - want).abs() < 1e-9,
            "{n4:?}: {} {want}",
            bound.value
        );
        worst.add((f64::from(*g) - want).abs(), bound.error);
    }
    (worst.error, worst.bound, worst.ratio, undecided)
}

#[test]
fn the_wgsl_overhead_sun_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let normals = sun_normals();
    let got = wgsl_overhead_sun(&gpu, &effects::wgsl::prelude(), &normals);
    let (worst, bound, ratio, undecided) = worst_sun_error(&got, &normals);
    eprintln!(
        "overhead_sun: {} normals ({undecided} at the critical angle undecided), worst |Δ| \
         {worst:.2e}, largest bound {bound:.2e}, worst error/bound {ratio:.3}",
        normals.len()
    );
    // Each normal within its bound: acos is inherited from atan2(sqrt(1 − y²), y) (4096 ULP,
    // and near the zenith sqrt of a difference of terms near 1), exp 3 + 2|x| ULP.
    assert!(ratio <= 1.0, "error/bound {ratio:e}");
    // Only normals within the f32 rounding of the critical angle are undecided.
    assert!(undecided <= 16, "{undecided} undecided");
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
    let (worst, bound, _, _) = worst_sun_error(&got, &normals);
    assert!(
        worst > 0.3 && worst > 100.0 * bound,
        "{worst:e} against {bound:e}"
    );
}

// ---- the effects' uniform and camera image, for ring_hit and refracted_table -------------------

/// The effects' test camera: 640×480 px, focal length 500 px, at `eye` looking at `target`.
fn camera(eye: DVec3, target: DVec3) -> PinholeCamera {
    effects::fixtures::test_camera(
        glam::dcamera::rh::view::look_at_mat4(eye, target, DVec3::Y).inverse(),
    )
}

/// The `Effects` uniform with `camera` and `table` (depth, ring radius, ring centre x, z) as
/// the passes fill them (local origin 0); the rest zero.
fn effects_uniform(camera: &PinholeCamera, table: [f64; 4]) -> EffectsUniform {
    effects_uniform_seen_by(camera, camera, table)
}

/// [`effects_uniform`] for a render camera `render` (the screen's) that is not the physical
/// `camera` (the straight-through map between them).
fn effects_uniform_seen_by(
    camera: &PinholeCamera,
    render: &PinholeCamera,
    table: [f64; 4],
) -> EffectsUniform {
    let mut fx: EffectsUniform = bytemuck::Zeroable::zeroed();
    let image = camera.image_projection(camera.pose.inverse());
    fx.camera_projection = image.as_mat4().to_cols_array_2d();
    fx.table_image = effects::passes::table_image(image, table[0]);
    let screen = render.image_projection(render.pose.inverse());
    fx.straight_image = effects::passes::straight_columns(effects::passes::straight_image(
        screen,
        image,
        table[0],
        render.position().y,
    ));
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

/// Against `Ring::hit` at the same (f32) inputs, each case against its own bound
/// (`bounds::ring_hit`: near the ring heading out, −b and √k cancel, and the bound grows with
/// it): the largest hit-point error, the largest bound, the largest error/bound ratio (per
/// component), the cases where one hits and the other does not, the hits, and the cases a
/// conforming GPU may decide either way (not bounded).
struct RingErrors {
    worst: f64,
    bound: f64,
    ratio: f64,
    disagree: usize,
    hits: usize,
    undecided: usize,
}

fn compare_ring_hits(got: &[[f32; 4]], cases: &[[[f32; 4]; 2]]) -> RingErrors {
    let mut e = RingErrors {
        worst: 0.0,
        bound: 0.0,
        ratio: 0.0,
        disagree: 0,
        hits: 0,
        undecided: 0,
    };
    for (g, [p4, r4]) in got.iter().zip(cases) {
        let (p, r) = (dvec(*p4), dvec(*r4));
        let bound = match bounds::ring_hit(*p4, *r4, RING.centre.to_array(), RING.radius) {
            bounds::Bounded::Decided(b) => Some(b),
            bounds::Bounded::Undecided => {
                e.undecided += 1;
                None
            }
        };
        match (RING.hit(p, r), g[3] > 0.0) {
            (Some(q), true) => {
                e.hits += 1;
                let error = dvec(*g) - q;
                e.worst = e.worst.max(error.length());
                if let Some(Some(b)) = bound {
                    let want = DVec3::new(b[0].value, b[1].value, b[2].value);
                    assert!((want - q).length() < 1e-9, "{want} {q}");
                    let errors = [error.x, error.y, error.z];
                    for (err, c) in errors.iter().zip(b) {
                        e.bound = e.bound.max(c.error);
                        e.ratio = e.ratio.max(err.abs() / c.error);
                    }
                }
            }
            (None, false) => {}
            _ => e.disagree += 1,
        }
    }
    e
}

#[test]
fn the_wgsl_ring_hit_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let cases = ring_cases();
    let got = wgsl_ring_hits(&gpu, &RING, &cases);
    let e = compare_ring_hits(&got, &cases);
    eprintln!(
        "ring_hit: {} rays, {} hits ({} undecided), worst |Δq| {:.2e} m, largest bound \
         {:.2e} m, worst error/bound {:.3}",
        cases.len(),
        e.hits,
        e.undecided,
        e.worst,
        e.bound,
        e.ratio
    );
    // Up-going rays with a horizontal part hit (7 of the 10 elevations), the rest miss; the
    // shader's "no horizontal part" (a < 1e-8) and the reference's (a < 1e-16) agree here: no
    // ray of this set has 1e-16 ≤ a < 1e-8, and no decision is near its threshold.
    assert_eq!((e.disagree, e.undecided), (0, 0));
    assert_eq!(e.hits, cases.len() * 7 / 10);
    // Each hit within its bound: two dot products, a square root (inherited from
    // 1.0/inverseSqrt: 2 + 2.5 ULP) and a division (2.5 ULP) of the case's own magnitudes.
    assert!(e.ratio <= 1.0, "error/bound {:e}", e.ratio);
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
    let e = compare_ring_hits(&got, &cases);
    assert!(e.ratio > 100.0, "error/bound {:e}", e.ratio);
}

// ---- refracted_table (refraction.wgsl) ---------------------------------------------------------

use effects::fixtures::{UV_IMAGE, uv_image, uv_image_at};

/// A view of the water: the camera, the table's depth, and the surface points with normals
/// its pixels see.
struct WaterView {
    camera: PinholeCamera,
    /// The camera the screen is drawn with: at the physical camera's pose but with other
    /// intrinsics (a cropped, zoomed display), so the straight-through map is not the identity.
    render: PinholeCamera,
    depth: f64,
    /// Surface point (w: the screen's u), unit view direction (w: the screen's v), unit normal
    /// (f32, as the GPU gets them).
    cases: Vec<[[f32; 4]; 3]>,
    /// Each case's screen uv in f64 (the render camera's projection of the surface point).
    screens: Vec<DVec2>,
}

/// Rays through a 33 × 25 grid of pixels (the image's edges included) to a wavy surface
/// (±0.25 m), normals tilted up to 52° every way; every thirteenth a face overhanging
/// towards the viewer (its normal pointing down), which bends grazing rays up, away from
/// the table.
fn water_view(eye: DVec3, target: DVec3, depth: f64) -> WaterView {
    let camera = camera(eye, target);
    let render = PinholeCamera {
        fx: 430.0,
        fy: 450.0,
        cx: 300.0,
        cy: 255.0,
        ..camera
    };
    let mut cases = Vec::new();
    let mut screens = Vec::new();
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
        // The screen uv of the surface point as the GPU gets it (its f32), which the
        // reference's straight-through ray passes.
        let screen = render
            .project_uv(dvec(v4(p)))
            .expect("the render camera sees the water");
        let [mut p4, mut view4] = [v4(p), v4(view)];
        (p4[3], view4[3]) = (screen.x as f32, screen.y as f32);
        cases.push([p4, view4, v4(n)]);
        screens.push(screen);
    }
    WaterView {
        camera,
        render,
        depth,
        cases,
        screens,
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

/// How the GPU's `sample_camera` reads the table: through the uv image, or replaced by a spy
/// that returns the (clamped) uv it is asked for, so the parity sees the shader's arithmetic
/// alone, without the texture unit's filtering.
#[derive(Clone, Copy, PartialEq)]
enum Sampling {
    UvImage,
    Spy,
}

/// `effects_common.wgsl` with `sample_camera` renamed away and a spy in its place that returns
/// the clamped uv it is asked for (what the sampler is asked for, exactly).
fn effects_common_with_spy() -> String {
    let signature = "fn sample_camera(uv: vec2<f32>) -> vec3<f32> {";
    let common = effects::passes::EFFECTS_COMMON;
    assert!(
        common.contains(signature),
        "sample_camera changed its signature"
    );
    // The spy still calls the real one (its result times 0), so the pipeline keeps the
    // texture and sampler bindings the test binds.
    let spy = "fn sample_camera(uv: vec2<f32>) -> vec3<f32> {\n    \
               return vec3<f32>(clamp(uv, vec2<f32>(0.0), vec2<f32>(1.0)), \
               0.0 * sample_camera_texture(uv).r);\n}\n";
    format!(
        "{}\n{spy}",
        common.replace(
            signature,
            "fn sample_camera_texture(uv: vec2<f32>) -> vec3<f32> {"
        )
    )
}

/// `refracted_table` of `refraction.wgsl` for each case of `view`, the GPU given a table
/// `depth` deep: vec4(colour = the uv sampled, path in the water).
fn wgsl_refracted_table(
    gpu: &Gpu,
    view: &WaterView,
    depth: f64,
    sampling: Sampling,
) -> Vec<[f32; 4]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 3>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let c = input[id.x];
        output[id.x] = refracted_table(c[0].xyz, c[1].xyz, vec2<f32>(c[0].w, c[1].w), c[2].xyz);
    }
}
"#;
    let common = match sampling {
        Sampling::UvImage => effects::passes::EFFECTS_COMMON.to_string(),
        Sampling::Spy => effects_common_with_spy(),
    };
    let src = effects::wgsl::source(&[&common, effects::passes::REFRACTION, kernel]);
    let uniform = uniform_buffer(
        gpu,
        &effects_uniform_seen_by(&view.camera, &view.render, [depth, 0.0, 0.0, 0.0]),
    );
    let image = uv_image(gpu).create_view(&Default::default());
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let fx = effects::fixtures::camera_entries(&uniform, &image, &sampler);
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

/// What the texture unit may add to a sampled uv, per axis, beyond the uv it is asked for:
/// the filter's weight snapped to Vulkan's least sub-texel precision (1/16 texel) and the
/// filtered value computed and held in half floats (the weight's product and the sum each
/// rounded by ½ f16 ULP: 1 ULP). WGSL states neither; see `render::wgsl_accuracy`. (On an
/// NVIDIA H200 the image path differed by up to 3.34e-4, just under √2 × ½ f16 ULP of a uv in
/// [0.5, 1) = 3.45e-4: both axes rounded to a half float, where the shader's own arithmetic
/// is good to about 1e-6.)
fn sampler_allowance(uv: f64) -> f64 {
    render::wgsl_accuracy::sub_texel_snap_texels() / f64::from(UV_IMAGE)
        + render::wgsl_accuracy::half_float_ulp(uv)
}

/// The GPU's samples against `refract_to_table` at the same (f32) surface points and normals,
/// each case against its own bound (`bounds::refracted_table`: WGSL's accuracy carried through
/// the function): the largest error of the sampled uv (image units) and of the path, the
/// largest bound, the largest error/bound ratio, the cases whose branches a conforming GPU
/// may take either way (not bounded), and how many samples were refracted inside the image
/// (weight 1), in the fade band (0 < weight < 1), beyond it (weight 0) and not to the table.
struct TableErrors {
    uv: f64,
    uv_bound: f64,
    uv_ratio: f64,
    path: f64,
    path_ratio: f64,
    undecided: usize,
    counts: [usize; 4],
}

fn compare_refracted_table(got: &[[f32; 4]], view: &WaterView, sampling: Sampling) -> TableErrors {
    let eye = view.camera.position();
    let table = Plane::horizontal(-view.depth);
    let camera = bounds::CameraBound::seen_by(&view.camera, &view.render);
    let mut e = TableErrors {
        uv: 0.0,
        uv_bound: 0.0,
        uv_ratio: 0.0,
        path: 0.0,
        path_ratio: 0.0,
        undecided: 0,
        counts: [0; 4],
    };
    for ((g, [p4, v4, n4]), screen) in got.iter().zip(&view.cases).zip(&view.screens) {
        let (p, n) = (dvec(*p4), dvec(*n4));
        let s = refract_to_table(eye, p, n, &table, &view.camera);
        let kind = match s.weight {
            _ if s.table_point.is_none() => 3,
            1.0 => 0,
            w if w > 0.0 => 1,
            _ => 2,
        };
        e.counts[kind] += 1;
        let view_ref = (p - eye).normalize();
        let bounds::Bounded::Decided(b) =
            bounds::refracted_table(&camera, view.depth, *p4, *v4, view_ref, *screen, *n4)
        else {
            e.undecided += 1;
            continue;
        };
        let sampled = s.sampled_uv();
        // The bound's own evaluation is the reference's computation: the same path, and the
        // same uv but where a surface point at the image's edge is seen a rounding outside it
        // (the shader blends from its straight uv unclamped, the reference from it clamped):
        // that difference, under 1e-7, is added to the bound.
        let mirrored = DVec2::new(b.at[0].value, b.at[1].value).clamp(DVec2::ZERO, DVec2::ONE);
        let model = (mirrored - sampled.clamp(DVec2::ZERO, DVec2::ONE)).abs();
        assert!(
            model.max_element() < 1e-7 && (b.path.value - s.path).abs() < 1e-9 * s.path.max(1.0),
            "the bound's evaluation left the reference: {mirrored} {sampled} {} {}",
            b.path.value,
            s.path
        );
        let (want, allowance) = match sampling {
            Sampling::Spy => (sampled.clamp(DVec2::ZERO, DVec2::ONE), model),
            Sampling::UvImage => {
                let want = uv_image_at(sampled);
                let texture = DVec2::new(sampler_allowance(want.x), sampler_allowance(want.y));
                (want, model + texture)
            }
        };
        let bound = DVec2::new(b.at[0].error, b.at[1].error) + allowance;
        let error = DVec2::new(f64::from(g[0]), f64::from(g[1])) - want;
        e.uv = e.uv.max(error.length());
        e.uv_bound = e.uv_bound.max(bound.length());
        e.uv_ratio = e
            .uv_ratio
            .max((error.x.abs() / bound.x).max(error.y.abs() / bound.y));
        let path_error = (f64::from(g[3]) - s.path).abs();
        e.path = e.path.max(path_error);
        e.path_ratio = e.path_ratio.max(path_error / b.path.error);
    }
    e
}

#[test]
fn the_wgsl_refracted_table_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let mut counts = [0; 4];
    for view in water_views() {
        for sampling in [Sampling::Spy, Sampling::UvImage] {
            let got = wgsl_refracted_table(&gpu, &view, view.depth, sampling);
            let e = compare_refracted_table(&got, &view, sampling);
            eprintln!(
                "refracted_table, {} m deep, {}: {} rays (inside, band, outside, no table: \
                 {:?}; {} undecided), worst |Δuv| {:.2e} (largest bound {:.2e}, worst \
                 error/bound {:.3}), worst |Δpath| {:.2e} m (error/bound {:.3})",
                view.depth,
                match sampling {
                    Sampling::Spy => "the uv asked of the sampler",
                    Sampling::UvImage => "through the uv image",
                },
                view.cases.len(),
                e.counts,
                e.undecided,
                e.uv,
                e.uv_bound,
                e.uv_ratio,
                e.path,
                e.path_ratio,
            );
            // Every case within its own bound: WGSL's accuracy of each operation carried
            // through the refraction, the plane hit and the projection (and for the image,
            // what the texture unit may add).
            assert!(e.uv_ratio <= 1.0, "|Δuv| over its bound: {:.3}", e.uv_ratio);
            assert!(
                e.path_ratio <= 1.0,
                "|Δpath| over its bound: {:.3}",
                e.path_ratio
            );
            // Branches a conforming GPU may take either way: none in these views.
            assert_eq!(e.undecided, 0);
            if sampling == Sampling::Spy {
                for (c, n) in counts.iter_mut().zip(e.counts) {
                    *c += n;
                }
            }
        }
    }
    // Every branch of the function is taken many times.
    assert!(counts.iter().all(|&c| c >= 20), "{counts:?}");
}

#[test]
fn a_broken_table_depth_fails_the_refracted_table_parity() {
    // The same kernels and checks, the GPU given a table 1 % deeper than the reference's:
    // the uv and the path leave their bounds many times over.
    let Some(gpu) = test_gpu() else { return };
    for view in water_views() {
        let got = wgsl_refracted_table(&gpu, &view, view.depth * 1.01, Sampling::Spy);
        let e = compare_refracted_table(&got, &view, Sampling::Spy);
        eprintln!(
            "refracted_table, a table 1 % deeper under {} m: error/bound {:.1} (uv), {:.1} (path)",
            view.depth, e.uv_ratio, e.path_ratio
        );
        assert!(
            e.uv_ratio > 10.0 && e.path_ratio > 10.0,
            "{} m: {:e} {:e}",
            view.depth,
            e.uv_ratio,
            e.path_ratio
        );
    }
}
