//! The AR water's transmitted light (`shaders/water_look.wgsl`, run by `render::compute`)
//! against its f64 reference `render::water_look::transmitted`: within 1/255 over table
//! colours, view paths, depths and turbidities, and a broken input fed through the same GPU
//! path misses. Lavapipe in CI; skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use render::gpu::test_gpu;
use render::water_look::{WaterLook, transmitted};

const TOLERANCE: f64 = 1.0 / 255.0;

/// Table colours (linear), room radiances and view paths (metres of water) to test.
fn items(look: &WaterLook) -> Vec<([f32; 3], [f32; 3], f32)> {
    let mut v = Vec::new();
    for (i, t) in [
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
        [0.6, 0.35, 0.15],
        [0.9, 0.1, 0.5],
    ]
    .into_iter()
    .enumerate()
    {
        for path in [0.0, 1.0, 1.3, 3.0] {
            let room = [1.0, 0.8 - 0.1 * i as f32, 0.6];
            v.push((t, room, path * look.depth_m as f32));
        }
    }
    v
}

fn worst_error(look: &WaterLook, gpu_out: &[[f32; 3]]) -> f64 {
    items(look)
        .iter()
        .zip(gpu_out)
        .map(|((t, r, p), g)| {
            let want = transmitted(t.map(f64::from), r.map(f64::from), f64::from(*p), look);
            (0..3)
                .map(|c| (f64::from(g[c]) - want[c]).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

fn looks() -> Vec<WaterLook> {
    let mut v = Vec::new();
    for depth_m in [1e-4, 0.01, 0.1] {
        for turbidity_ntu in [0.0, 0.5, 20.0, 100.0] {
            v.push(WaterLook {
                depth_m,
                turbidity_ntu,
            });
        }
    }
    v
}

#[test]
fn the_shaders_clear_water_matches_the_f64_reference_within_1_of_255() {
    let Some(gpu) = test_gpu() else { return };
    let mut worst = 0.0f64;
    for look in looks() {
        let out = render::compute::gpu_water_transmitted(&gpu, &look, &items(&look)).unwrap();
        let e = worst_error(&look, &out);
        assert!(e < TOLERANCE, "{look:?}: max error {e}");
        worst = worst.max(e);
    }
    eprintln!("water look: max |GPU − f64| = {worst:.2e} (tolerance {TOLERANCE:.2e})");
}

#[test]
fn a_wrong_depth_would_fail_the_parity_check() {
    // The same GPU path, the uniform made for 3 cm of water, compared with 1 cm's reference.
    let Some(gpu) = test_gpu() else { return };
    let one = WaterLook {
        depth_m: 0.01,
        turbidity_ntu: 20.0,
    };
    let three = WaterLook {
        depth_m: 0.03,
        ..one
    };
    let out = render::compute::gpu_water_transmitted(&gpu, &three, &items(&one)).unwrap();
    let e = worst_error(&one, &out);
    assert!(e > 10.0 * TOLERANCE, "only {e}");
}
