//! The AR water's transmitted light (`shaders/render/water_look.wgsl`, run by
//! `render::compute`) against its f64 reference `render::water_look::transmitted`, within a
//! bound derived per output from what WGSL guarantees (not from what one GPU gives), over
//! water types, depths, turbidities, table colours and view paths; and a broken input fed
//! through the same GPU path misses by far more. Lavapipe in CI; skipped without an adapter
//! unless REGATTA_REQUIRE_GPU=true.
//!
//! The bound. Let u = 2⁻²³ (one ULP relative to an f32 in [1, 2)). The shader computes
//! x = −κ·l (κ and l rounded to f32 and one product: |Δx| ≤ 1.5 u |x|), e = exp(x), whose
//! WGSL accuracy is 3 + 2|x| ULP (relative error ≤ (3 + 2|x|) u), and t = T_d·e (T_d rounded,
//! one product: u); so t carries a relative error ε_t = (4 + 3.5|x|) u. The rest is
//! [table t + room R∞ (1 − t)] / (A − B ρ), with R∞, A and B formed in f64 and rounded to f32
//! (½ u relative each; room·R∞ one f32 product, in the uniform the shader reads, as the
//! effects fold the room's white into it) and combined by + − × (correctly rounded, ½ u
//! each) and one division
//! (2.5 ULP): eight operations. The denominator A − B ρ = n²(1 − r̄_int albedo)/(1 − R̄) is at
//! least 0.52 n²/(1 − R̄) while A + B ρ is at most 1.48 n²/(1 − R̄), so A's and B's roundings
//! grow by at most a factor 3 there. With g = (1 − R̄)/(n²(1 − A r̄_int)), the output's
//! sensitivity to t is g·|table − room·R∞| ≤ g·(table + room·R∞), so per channel
//!
//!   |GPU − f64| ≤ g (table + room R∞) t ε_t + 32 u (out + g room R∞) + 10⁻⁹,
//!
//! the 32 u covering the rational part's rounding (at most 2 × 8 half-ULPs, A's and B's 3 × ½,
//! and the division's 2.5: 20 u, rounded up), and 10⁻⁹ the f32 denormal range of outputs near zero.

use render::gpu::test_gpu;
use render::water_look::{
    WaterLook, WaterType, diffuse_entry, diffuse_internal_reflectance, transmitted,
};

const U: f64 = 1.0 / 8_388_608.0; // 2⁻²³

/// Table colours (linear), room radiances and view paths (metres of real sea) to test.
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

/// The bound above for one item and channel, from the f64 quantities.
fn bound(look: &WaterLook, table: f64, room: f64, path: f64, c: usize, out: f64) -> f64 {
    let w = look.on_table(1.0);
    let mu = render::water_look::diffuse_mean_cosine();
    let k = w.attenuation[c];
    let deep = w.deep_reflectance[c];
    let td = (-k * w.depth_m / mu).exp();
    let x = k * path;
    let t = td * (-x).exp();
    let rho = table.clamp(0.0, 1.0);
    let albedo = rho * td * td + deep * (1.0 - td * td);
    let n2 = render::optics::N_WATER.powi(2);
    let g = diffuse_entry() / (n2 * (1.0 - albedo * diffuse_internal_reflectance()));
    let eps_t = (4.0 + 3.5 * x) * U;
    g * (table + room * deep) * t * eps_t + 32.0 * U * (out + g * room * deep) + 1e-9
}

/// The worst |GPU − f64| over the items as a share of its bound, and the worst error.
fn worst(look: &WaterLook, reference: &WaterLook, gpu_out: &[[f32; 3]]) -> (f64, f64) {
    let mut share = 0.0f64;
    let mut err = 0.0f64;
    for ((t, r, p), g) in items(reference).iter().zip(gpu_out) {
        let (t, r, p) = (t.map(f64::from), r.map(f64::from), f64::from(*p));
        let want = transmitted(t, r, p, reference);
        for c in 0..3 {
            let e = (f64::from(g[c]) - want[c]).abs();
            share = share.max(e / bound(look, t[c], r[c], p, c, want[c]));
            err = err.max(e);
        }
    }
    (share, err)
}

fn looks() -> Vec<WaterLook> {
    let mut v = Vec::new();
    for water_type in [
        WaterType::Pure,
        WaterType::OceanicI,
        WaterType::OceanicII,
        WaterType::Coastal1,
        WaterType::Coastal5,
        WaterType::Coastal9,
    ] {
        for depth_m in [0.5, 8.0, 100.0] {
            for turbidity_ntu in [0.0, 20.0] {
                v.push(WaterLook {
                    water_type,
                    depth_m,
                    turbidity_ntu,
                });
            }
        }
    }
    v
}

#[test]
fn the_shaders_sea_water_matches_the_f64_reference_within_the_wgsl_bound() {
    let Some(gpu) = test_gpu() else { return };
    let (mut share, mut err) = (0.0f64, 0.0f64);
    for look in looks() {
        let out = render::compute::gpu_water_transmitted(&gpu, &look, &items(&look)).unwrap();
        let (s, e) = worst(&look, &look, &out);
        assert!(s <= 1.0, "{look:?}: error {e:.2e} is {s:.2} of its bound");
        share = share.max(s);
        err = err.max(e);
    }
    eprintln!("water look: max |GPU − f64| = {err:.2e}, at most {share:.3} of its WGSL bound");
}

#[test]
fn a_wrong_depth_or_type_would_fail_the_parity_check() {
    // The same GPU path with the uniform made for another sea, compared with 8 m of coastal
    // 1's reference: misses by a thousand times its bound and by more than 1/255.
    let Some(gpu) = test_gpu() else { return };
    let one = WaterLook::default();
    for wrong in [
        WaterLook {
            depth_m: 12.0,
            ..one
        },
        WaterLook {
            water_type: WaterType::OceanicII,
            ..one
        },
    ] {
        let out = render::compute::gpu_water_transmitted(&gpu, &wrong, &items(&one)).unwrap();
        let (s, e) = worst(&one, &one, &out);
        assert!(
            s > 1000.0 && e > 1.0 / 255.0,
            "{wrong:?}: only {e} ({s} of the bound)"
        );
    }
}
