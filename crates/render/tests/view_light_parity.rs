//! The open sea's water body (`water_look.wgsl`'s `water_deep_body`) and the boats' room light
//! (`boats.wgsl`'s `boat_in_room`) on the GPU against their f64 references
//! (`water_look::deep_body`, `view_light::boat_in_room`), within bounds derived from what WGSL
//! guarantees. Lavapipe in CI; skipped without an adapter unless REGATTA_REQUIRE_GPU=true.
//!
//! Let u = 2⁻²³. **Deep body**: with no table the shader's T_d·exp(0) is exactly 0, so the
//! output is E R∞ L / (N² (1 − R∞ r̄)): five inputs and constants rounded to f32 (½ u each),
//! four products and one subtraction (½ u each, 1 − R∞ r̄ ≥ 0.97 cancels nothing) and one
//! division (2.5 ULP): |GPU − f64| ≤ 8 u · out + 10⁻⁹ (rounded up from 7 u).
//! **Boat**: shade = (1 − D)·½·(1 + n_y) + D·max(n·l, 0), out = c·L·shade. The dot product's
//! error is at most 3 u Σ|n_i l_i| (three products and two sums, inputs rounded), the rest six
//! roundings of positive terms: |GPU − f64| ≤ c L (6 u shade + 4 u D Σ|n_i l_i|) + 10⁻⁹.

use glam::DVec3;
use render::gpu::test_gpu;
use render::view_light::{ROOM_DIRECTIONAL_SHARE, boat_in_room, water_body_uniform};
use render::water_look::{WaterLook, WaterType, deep_body};

const U: f64 = 1.0 / 8_388_608.0;

fn f32s(v: [f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
}
fn f64s(v: [f32; 3]) -> [f64; 3] {
    v.map(f64::from)
}

#[test]
fn the_open_seas_body_matches_the_f64_deep_body_within_the_wgsl_bound() {
    let Some(gpu) = test_gpu() else { return };
    let lights = [[0.24, 0.40, 0.70], [1.0, 1.0, 1.0], [0.05, 0.03, 0.01]];
    let mut items = Vec::new();
    let mut want = Vec::new();
    for t in WaterType::ALL {
        for turbidity in [0.0, 20.0] {
            let look = WaterLook {
                water_type: t,
                depth_m: 5.0,
                turbidity_ntu: turbidity,
            };
            for l in lights {
                let l32 = f32s(l);
                items.push((l32, water_body_uniform(&look)));
                want.push(deep_body(f64s(l32), &look));
            }
        }
    }
    let out = render::compute::gpu_water_deep_body(&gpu, &items).unwrap();
    let mut share = 0.0f64;
    for (o, w) in out.iter().zip(&want) {
        for c in 0..3 {
            let bound = 8.0 * U * w[c] + 1e-9;
            let e = (f64::from(o[c]) - w[c]).abs();
            assert!(e <= bound, "{c}: {o:?} {w:?}");
            share = share.max(e / bound);
        }
    }
    eprintln!("deep body: at most {share:.3} of the WGSL bound");
    // Another type's R∞ misses by far more than the bound.
    let wrong = water_body_uniform(&WaterLook {
        water_type: WaterType::Coastal5,
        ..WaterLook::default()
    });
    let o = render::compute::gpu_water_deep_body(&gpu, &[([1.0; 3], wrong)]).unwrap()[0];
    let w = deep_body([1.0; 3], &WaterLook::default());
    assert!((f64::from(o[2]) - w[2]).abs() > 1000.0 * (8.0 * U * w[2] + 1e-9));
}

#[test]
fn the_boats_room_light_matches_the_f64_formula_within_the_wgsl_bound() {
    let Some(gpu) = test_gpu() else { return };
    let normals = [
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::X,
        DVec3::new(-0.6, 0.2, 0.77).normalize(),
        DVec3::new(0.1, -0.7, 0.7).normalize(),
    ];
    let lights = [
        DVec3::Y,
        DVec3::new(0.3, 0.9, 0.2).normalize(),
        DVec3::new(-0.55, 0.57, 0.6).normalize(),
    ];
    let rooms = [[1.0, 1.0, 1.0], [0.30, 0.20, 0.10]];
    let albedos = [[0.8, 0.1, 0.1], [0.92, 0.92, 0.88], [0.12, 0.12, 0.13]];
    let mut items = Vec::new();
    let mut cases = Vec::new();
    for n in normals {
        for l in lights {
            for r in rooms {
                for c in albedos {
                    let n32 = f32s(n.to_array());
                    let l32 = f32s(l.to_array());
                    items.push((f32s(c), n32, l32, f32s(r)));
                    let (n, l) = (DVec3::from_array(f64s(n32)), DVec3::from_array(f64s(l32)));
                    cases.push((c, n, l, r));
                }
            }
        }
    }
    let out = render::compute::gpu_boat_in_room(&gpu, &items).unwrap();
    let mut share = 0.0f64;
    for (o, &(c, n, l, r)) in out.iter().zip(&cases) {
        let c = f64s(f32s(c));
        let r = f64s(f32s(r));
        let want = boat_in_room(c, n, l, r);
        let d = ROOM_DIRECTIONAL_SHARE;
        let shade = (1.0 - d) * 0.5 * (1.0 + n.y) + d * n.dot(l).max(0.0);
        let dot_abs = (n * l).abs().element_sum();
        for i in 0..3 {
            let bound = c[i] * r[i] * (6.0 * U * shade + 4.0 * U * d * dot_abs) + 1e-9;
            let e = (f64::from(o[i]) - want[i]).abs();
            assert!(e <= bound, "{n} {l} {i}: {o:?} {want:?}");
            share = share.max(e / bound);
        }
    }
    eprintln!("boat in room: at most {share:.3} of the WGSL bound");
}
