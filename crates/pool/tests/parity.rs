//! The pool's mirrored WGSL ray functions on the GPU (`render::compute::run_kernel`, lavapipe
//! in CI) against the f64 references of `pool::geometry`, each shown to fail on a broken input
//! fed through the same path. (The water trace and the caustics have theirs in the crate's
//! `gpu_tests`.) Skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use glam::DVec3;
use pool::geometry::{Ray, Sphere};
use render::gpu::{Gpu, test_gpu};

/// One ray against one sphere: origin, direction (unit), sphere centre and radius.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Case {
    origin: [f32; 4],
    dir: [f32; 4],
    sphere: [f32; 4],
}

/// `hit_sphere` of `pool_common.wgsl` for each case (NO_HIT = −1 for a miss).
fn wgsl_hits(gpu: &Gpu, cases: &[Case]) -> Vec<f32> {
    let kernel = r#"
struct Case { origin: vec4<f32>, dir: vec4<f32>, sphere: vec4<f32> }
@group(0) @binding(10) var<storage, read> input: array<Case>;
@group(0) @binding(11) var<storage, read_write> output: array<f32>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let c = input[id.x];
        output[id.x] = hit_sphere(c.origin.xyz, c.dir.xyz, PoolSphere(c.sphere, vec4<f32>(0.0)));
    }
}
"#;
    let prelude = pool::wgsl::prelude();
    let src = render::shader::source(&[&prelude, pool::gpu::POOL_COMMON, kernel]);
    let bytes = render::compute::run_kernel(gpu, "sphere hit parity", &src, cases, 4)
        .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Rays from a ring of origins 1–3 m from spheres of 0.1–0.3 m, aimed at, beside and away
/// from them: hits, grazes and misses.
fn rays() -> Vec<(Ray, Sphere)> {
    let mut out = Vec::new();
    for k in 0..400 {
        let a = f64::from(k) * 0.157;
        let sphere = Sphere {
            center: DVec3::new(0.2 * a.sin(), -0.3 + 0.1 * (k % 5) as f64, 0.1 * a.cos()),
            radius: 0.1 + 0.05 * (k % 5) as f64,
        };
        let origin = sphere.center
            + DVec3::new(a.cos(), 0.3 * (k % 3) as f64, a.sin()) * (1.0 + 0.005 * (k % 400) as f64);
        let aim = sphere.center + DVec3::new(0.0, 0.0, 0.01 * (k % 100) as f64 - 0.5);
        out.push((Ray::new(origin, aim - origin), sphere));
    }
    out
}

fn cases(rays: &[(Ray, Sphere)]) -> Vec<Case> {
    let v = |d: DVec3, w: f64| [d.x as f32, d.y as f32, d.z as f32, w as f32];
    rays.iter()
        .map(|(r, s)| Case {
            origin: v(r.origin, 0.0),
            dir: v(r.dir, 0.0),
            sphere: v(s.center, s.radius),
        })
        .collect()
}

/// The largest distance error of the GPU hits, metres, and whether every hit or miss agrees.
fn compare(got: &[f32], rays: &[(Ray, Sphere)]) -> (f64, usize) {
    let mut worst = 0.0f64;
    let mut disagree = 0;
    for (g, (ray, sphere)) in got.iter().zip(rays) {
        match sphere.hit(ray) {
            Some(s) if *g >= 0.0 => worst = worst.max((f64::from(*g) - s).abs()),
            None if *g < 0.0 => {}
            _ => disagree += 1,
        }
    }
    (worst, disagree)
}

#[test]
fn the_wgsl_sphere_hit_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let rays = rays();
    let got = wgsl_hits(&gpu, &cases(&rays));
    let (worst, disagree) = compare(&got, &rays);
    let hits = got.iter().filter(|g| **g >= 0.0).count();
    assert!(
        hits > 50 && hits < rays.len() - 50,
        "{hits} hits of {}",
        rays.len()
    );
    // Grazing rays may disagree in f32; none here comes within a micrometre of grazing.
    assert_eq!(disagree, 0);
    // Distances of 1–3 m in f32; near-grazing rays lose most (the square root of a small
    // discriminant): under a millimetre, a tenth of what a 1 cm larger sphere moves.
    assert!(worst < 1e-3, "worst {worst:e} m");
}

#[test]
fn a_broken_sphere_fails_the_sphere_hit_parity() {
    // The same kernel and check, the GPU given spheres 1 cm larger than the reference's.
    let Some(gpu) = test_gpu() else { return };
    let rays = rays();
    let mut broken = cases(&rays);
    for c in &mut broken {
        c.sphere[3] += 0.01;
    }
    let got = wgsl_hits(&gpu, &broken);
    let (worst, disagree) = compare(&got, &rays);
    assert!(
        worst > 5e-3 || disagree > 0,
        "worst {worst:e} m, {disagree} disagree"
    );
}
