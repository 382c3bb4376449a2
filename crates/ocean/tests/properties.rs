//! Property tests over random valid seas, points within ±10 km and t in [0, 1e7] s.

use ocean::{Wave, WaveSet, displace_f32, f32_error_bound};
use proptest::prelude::*;

#[path = "support/fuzz_config.rs"]
mod fuzz_config;

/// A valid sea: 1–12 waves, λ in [1, 300] m (log-uniform), Σ kA in [0, 0.9], deep or finite
/// depth in [1, 200] m.
fn sea() -> impl Strategy<Value = WaveSet> {
    let wave = (
        0.0..std::f64::consts::TAU,
        0.0f64..5.7,
        0.01f64..1.0,
        0.0..std::f64::consts::TAU,
    );
    (
        prop::collection::vec(wave, 1..12),
        0.0f64..0.9,
        prop::option::of(1.0f64..200.0),
    )
        .prop_map(|(raw, total, depth)| {
            let wsum: f64 = raw.iter().map(|w| w.2).sum();
            WaveSet {
                gravity: 9.81,
                depth,
                waves: raw
                    .iter()
                    .map(|&(ang, lnl, w, phase)| Wave {
                        direction: [ang.cos(), ang.sin()],
                        steepness: total * w / wsum,
                        wavelength: lnl.exp(),
                        phase,
                    })
                    .collect(),
            }
        })
}

fn point() -> impl Strategy<Value = [f64; 2]> {
    [-10_000.0f64..10_000.0, -10_000.0f64..10_000.0]
}

fn time() -> impl Strategy<Value = f64> {
    0.0f64..1e7
}

proptest! {
    // 256 cases from a fixed seed; scripts/fuzz.sh overrides both.
    #![proptest_config(fuzz_config::fuzz_config(0x5EA5_0F1A_7E00, 256))]
    #[test]
    fn surface_is_finite_with_unit_normals(s in sea(), x0 in point(), t in time()) {
        let sp = s.surface(x0, t);
        prop_assert!(sp.position.iter().all(|v| v.is_finite()));
        let n = sp.normal;
        prop_assert!(((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() - 1.0).abs() < 1e-12);
        prop_assert!(n[1] > 0.0);
        prop_assert!(sp.jacobian >= 1.0 - s.total_steepness() - 1e-12);
        // Every point stays within Σ A of its rest point.
        let d = [sp.position[0] - x0[0], sp.position[1], sp.position[2] - x0[1]];
        prop_assert!((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() <= s.total_amplitude() + 1e-9);
    }

    #[test]
    fn inverse_then_forward_is_within_tolerance(s in sea(), at in point(), t in time()) {
        let w = s.sample_at(at, t, ocean::DEFAULT_TOLERANCE).unwrap();
        let p = s.displace(w.rest.rest, t);
        prop_assert!((p[0] - at[0]).hypot(p[2] - at[1]) <= ocean::DEFAULT_TOLERANCE);
        prop_assert!(w.rest.residual <= ocean::DEFAULT_TOLERANCE);
        prop_assert!((w.height - p[1]).abs() < 1e-12);
        prop_assert!(w.height.is_finite() && w.normal.iter().all(|v| v.is_finite()));
        prop_assert!(w.rest.iterations <= 20, "{:?}", w.rest);
    }

    #[test]
    fn f32_path_is_within_its_stated_bound(
        s in sea(),
        origin in point(),
        p in [-500.0f64..500.0, -500.0f64..500.0],
        t in time(),
    ) {
        let g = s.gpu_waves(t, origin);
        let pf = [p[0] as f32, p[1] as f32];
        let d = displace_f32(&g, pf);
        // The f64 reference at the same rest point the f32 path sees.
        let x0 = [origin[0] + pf[0] as f64, origin[1] + pf[1] as f64];
        let r = s.displace(x0, t);
        let radius = (pf[0] as f64).hypot(pf[1] as f64);
        let bound = f32_error_bound(&g, radius);
        let err = [
            (d[0] as f64 - (r[0] - x0[0])).abs(),
            (d[1] as f64 - r[1]).abs(),
            (d[2] as f64 - (r[2] - x0[1])).abs(),
        ];
        for e in err {
            prop_assert!(e <= bound, "error {e} > bound {bound}");
        }
    }

    #[test]
    fn culling_error_never_exceeds_its_bound(
        s in sea(),
        frac in 0.0f64..1.0,
        min_wavelength in 0.0f64..20.0,
        x0 in point(),
        t in time(),
    ) {
        let c = s.cull(frac * s.total_amplitude(), min_wavelength);
        prop_assert!(c.displacement_bound <= frac * s.total_amplitude() + 1e-12 || c.below_grid > 0);
        // Displacement at a rest point.
        let a = s.displace(x0, t);
        let b = c.sea.displace(x0, t);
        let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
        prop_assert!(d <= c.displacement_bound + 1e-9, "{d} > {}", c.displacement_bound);
        // Height at a world point (both inverses to 1e-10 m).
        let h = s.sample_at(x0, t, 1e-10).unwrap().height;
        let hk = c.sea.sample_at(x0, t, 1e-10).unwrap().height;
        prop_assert!((h - hk).abs() <= c.height_bound + 1e-8, "{} > {}", (h - hk).abs(), c.height_bound);
    }
}
