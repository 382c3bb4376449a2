//! The AR water's transmitted light (`shaders/water_look.wgsl`, run by `render::compute`)
//! against its f64 reference `render::water_look::transmitted`: each channel within its own
//! bound, what WGSL's accuracy allows a conforming GPU there (`transmitted_bound`, from
//! `render::wgsl_accuracy`), itself under one display level (1/255), over table colours, view
//! paths, depths and turbidities; and a broken input fed through the same GPU path misses.
//! Lavapipe in CI; skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use render::gpu::test_gpu;
use render::water_look::{WaterLook, transmitted};
use render::wgsl_accuracy::Inexact;

/// One display level: what every bound must stay under.
const TOLERANCE: f64 = 1.0 / 255.0;

/// `water_transmitted` of `water_look.wgsl` evaluated with WGSL's accuracy of each operation
/// (exp 3 + 2|x| ULP, division 2.5 ULP, the rest correctly rounded), the constants and the
/// uniform the f32 of the reference's f64: per channel, the value and its bound.
fn transmitted_bound(
    table: [f32; 3],
    room: [f32; 3],
    path_m: f32,
    look: &WaterLook,
) -> [Inexact; 3] {
    let constant = |name: &str, i: usize| {
        let (_, v) = render::water_look::wgsl_values()
            .into_iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("{name}"));
        Inexact::input(v[i], v[i] as f32)
    };
    let b64 = look.scattering();
    let [water_a, _] = look.gpu_uniform(look.depth_m);
    let mu = render::water_look::diffuse_mean_cosine();
    let absorption = render::water_look::pure_water_absorption();
    let one = Inexact::exact(1.0);
    std::array::from_fn(|i| {
        let b = Inexact::input(b64, water_a[3]);
        let td = Inexact::input(
            (-(absorption[i] + b64) * look.depth_m / mu).exp(),
            water_a[i],
        );
        let c = constant("WATER_ABSORPTION", i) + b;
        let tv = (-c * Inexact::of(path_m)).exp();
        let t = Inexact::of(table[i]);
        let rho = t.clamp(0.0, 1.0);
        let entry = constant("WATER_DIFFUSE_ENTRY", i);
        let through = t * entry * td * tv
            / (constant("WATER_N2", i)
                * (one - rho * constant("WATER_INTERNAL_REFLECTANCE", i) * td * td));
        let veil = Inexact::of(room[i]) * entry * (b / c) * (one - tv);
        through + veil
    })
}

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

/// The largest error of the GPU's channels against the reference, the largest bound and the
/// largest error/bound ratio.
fn worst_error(look: &WaterLook, gpu_out: &[[f32; 3]]) -> (f64, f64, f64) {
    let (mut worst, mut largest_bound, mut ratio) = (0.0f64, 0.0f64, 0.0f64);
    for ((t, r, p), g) in items(look).iter().zip(gpu_out) {
        let want = transmitted(t.map(f64::from), r.map(f64::from), f64::from(*p), look);
        let bound = transmitted_bound(*t, *r, *p, look);
        for c in 0..3 {
            assert!((bound[c].value - want[c]).abs() < 1e-9, "{look:?}");
            let error = (f64::from(g[c]) - want[c]).abs();
            worst = worst.max(error);
            largest_bound = largest_bound.max(bound[c].error);
            ratio = ratio.max(if error == 0.0 {
                0.0
            } else {
                error / bound[c].error
            });
        }
    }
    (worst, largest_bound, ratio)
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
    let (mut worst, mut largest_bound, mut worst_ratio) = (0.0f64, 0.0f64, 0.0f64);
    for look in looks() {
        let out = render::compute::gpu_water_transmitted(&gpu, &look, &items(&look)).unwrap();
        let (e, bound, ratio) = worst_error(&look, &out);
        assert!(ratio <= 1.0, "{look:?}: error {e:e}, error/bound {ratio}");
        worst = worst.max(e);
        largest_bound = largest_bound.max(bound);
        worst_ratio = worst_ratio.max(ratio);
    }
    eprintln!(
        "water look: max |GPU − f64| = {worst:.2e}, largest WGSL bound {largest_bound:.2e}, \
         worst error/bound {worst_ratio:.3}"
    );
    // On any conforming GPU, within a display level.
    assert!(largest_bound < TOLERANCE, "bound {largest_bound:e}");
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
    let (e, bound, ratio) = worst_error(&one, &out);
    assert!(
        e > 10.0 * TOLERANCE && ratio > 100.0,
        "only {e} (bound {bound})"
    );
}
