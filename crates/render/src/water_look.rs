//! Clear water over a table, from physical optics (docs/water-look.md): the f64 reference of
//! `shaders/water_look.wgsl`, whose constants come from here through the generated prelude
//! ([`crate::shader::prelude`]).
//!
//! What the camera sees of the table through a layer of water `depth_m` deep, per RGB band:
//!
//! - **Absorption** of pure water, Pope & Fry (1997) (380–700 nm, [`POPE_FRY_1997`]), averaged
//!   over box bands B 400–500, G 500–600, R 600–700 nm ([`pure_water_absorption`]);
//!   Beer–Lambert over the optical path.
//! - **Turbidity** (NTU): particles scatter, wavelength-neutral, b_p = [`SCATTERING_PER_NTU`]
//!   per NTU, absorbing nothing. They take light out of the table's image (attenuation
//!   c = a_w + b_p) and scatter room light into the view (single scattering, isotropic,
//!   uniform room radiance L_room): a veil L_room·(1 − R̄)·(b_p/c)·(1 − e^{−c l}).
//! - **The table under water**: room light enters through the surface (diffuse, share
//!   1 − R̄ with R̄ the hemispherical Fresnel reflectance, [`diffuse_entry`]), goes down to
//!   the table (path depth/μ̄, μ̄ the mean cosine of the refracted diffuse light,
//!   [`diffuse_mean_cosine`]), is reflected by the table (albedo ρ: the camera's dry table
//!   colour, white = 1), comes back up (the view path l) and leaves through the surface with
//!   1 − R(θ) (the exact Fresnel factor the shader mixes with, not here) and 1/n² (radiance
//!   in a denser medium). Light reflected back down by the surface from below (r̄_int,
//!   [`diffuse_internal_reflectance`], total internal reflection included) reaches the table
//!   again: a geometric series 1/(1 − ρ r̄_int T_d²). Together:
//!   L = L_dry (1 − R̄) T_d T_v / (n² (1 − ρ r̄_int T_d²)): a white table keeps its radiance
//!   (energy conservation: (1 − R̄)/n² = 1 − r̄_int), a darker one darkens as wet things do.
//! - **Reflection** of the sky and room: the exact unpolarised Fresnel equations
//!   (`optics::fresnel`, `shaders/optics.wgsl`), no Schlick.

use std::f64::consts::FRAC_PI_2;

use crate::optics::{N_AIR, N_WATER, fresnel};

/// The WGSL of the transmitted light (the AR water pass appends it).
pub const WATER_LOOK_WGSL: &str = include_str!("../../../shaders/render/water_look.wgsl");

/// Pure-water absorption coefficient, 1/m, every 10 nm from 380 to 700 nm: Pope & Fry
/// (1997), "Absorption spectrum (380–700 nm) of pure water. II. Integrating cavity
/// measurements", Applied Optics 36(33), 8710–8723, Table 3 (at 10 nm, rounded).
pub const POPE_FRY_1997: [(f64, f64); 33] = [
    (380.0, 0.01137),
    (390.0, 0.00851),
    (400.0, 0.00663),
    (410.0, 0.00473),
    (420.0, 0.00454),
    (430.0, 0.00495),
    (440.0, 0.00635),
    (450.0, 0.00922),
    (460.0, 0.00979),
    (470.0, 0.01060),
    (480.0, 0.01270),
    (490.0, 0.01500),
    (500.0, 0.02040),
    (510.0, 0.03250),
    (520.0, 0.04090),
    (530.0, 0.04340),
    (540.0, 0.04740),
    (550.0, 0.05650),
    (560.0, 0.06190),
    (570.0, 0.06950),
    (580.0, 0.08960),
    (590.0, 0.13510),
    (600.0, 0.22240),
    (610.0, 0.26440),
    (620.0, 0.27550),
    (630.0, 0.29160),
    (640.0, 0.31080),
    (650.0, 0.34000),
    (660.0, 0.41000),
    (670.0, 0.43900),
    (680.0, 0.46500),
    (690.0, 0.51600),
    (700.0, 0.62400),
];

/// The RGB bands, nm (box bands: a camera's channels, approximately).
pub const BANDS_NM: [(f64, f64); 3] = [(600.0, 700.0), (500.0, 600.0), (400.0, 500.0)];

/// Mean of [`POPE_FRY_1997`] over `[lo, hi]` nm (trapezoids on its 10 nm grid; `lo`, `hi` on
/// the grid).
pub fn band_mean_absorption(lo: f64, hi: f64) -> f64 {
    let inside: Vec<(f64, f64)> = POPE_FRY_1997
        .iter()
        .copied()
        .filter(|(l, _)| *l >= lo && *l <= hi)
        .collect();
    let area: f64 = inside
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum();
    area / (hi - lo)
}

/// Pure-water absorption per RGB band, 1/m (R ≈ 0.374, G ≈ 0.070, B ≈ 0.0092).
pub fn pure_water_absorption() -> [f64; 3] {
    BANDS_NM.map(|(lo, hi)| band_mean_absorption(lo, hi))
}

/// Particle scattering per NTU of turbidity, 1/m: the beam attenuation of natural waters is
/// about 1 m⁻¹ per NTU (order of the turbidity–attenuation relations of suspended sediment);
/// taken as pure scattering, the same in every band.
pub const SCATTERING_PER_NTU: f64 = 1.0;

/// Deepest water the settings take, m: the water's surface floats this far above the table
/// (no tank walls are drawn, so a deep layer reads as a floating sheet), and the synthetic
/// feed's camera is 0.55 m above its table (a surface near the camera hides the scene).
pub const MAX_DEPTH_M: f64 = 0.1;
/// Shallowest, m (a film: 0.1 mm).
pub const MIN_DEPTH_M: f64 = 1e-4;
/// Most turbid water the settings take, NTU (muddy river water).
pub const MAX_TURBIDITY_NTU: f64 = 100.0;

/// The water the user chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterLook {
    /// Depth of the water over the table, m (real metres, whatever the scene's scale).
    pub depth_m: f64,
    /// Turbidity, NTU (0: pure water).
    pub turbidity_ntu: f64,
}

impl Default for WaterLook {
    /// 1 cm of clear water (tap water is below 1 NTU; 0.5 here). Deeper, the sea's steep
    /// table-sized waves focus the light into caustic speckles (3 cm: their focal length).
    fn default() -> Self {
        WaterLook {
            depth_m: 0.01,
            turbidity_ntu: 0.5,
        }
    }
}

impl WaterLook {
    /// Checks the ranges: a one-line reason naming the setting.
    pub fn check(&self) -> Result<(), String> {
        if !(self.depth_m.is_finite() && (MIN_DEPTH_M..=MAX_DEPTH_M).contains(&self.depth_m)) {
            return Err(format!(
                "water depth {} m is outside {MIN_DEPTH_M} to {MAX_DEPTH_M} m",
                self.depth_m
            ));
        }
        if !(self.turbidity_ntu.is_finite()
            && (0.0..=MAX_TURBIDITY_NTU).contains(&self.turbidity_ntu))
        {
            return Err(format!(
                "turbidity {} NTU is outside 0 to {MAX_TURBIDITY_NTU} NTU",
                self.turbidity_ntu
            ));
        }
        Ok(())
    }

    /// Particle scattering b_p, 1/m.
    pub fn scattering(&self) -> f64 {
        SCATTERING_PER_NTU * self.turbidity_ntu
    }
}

/// ∫₀^{π/2} f(θ) 2 sin θ cos θ dθ: the cosine-weighted hemispherical mean of f.
fn hemispherical_mean(f: impl Fn(f64) -> f64) -> f64 {
    weighted_integral(&f, 0.0, std::f64::consts::FRAC_PI_2)
}

/// ∫ₐᵇ f(θ) 2 sin θ cos θ dθ by Simpson's rule (200 000 panels: Fresnel's cos θt has an
/// infinite slope at the critical angle, which costs Simpson its order there; computed once).
fn weighted_integral(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 200_000;
    let h = (b - a) / n as f64;
    let g = |th: f64| f(th) * 2.0 * th.sin() * th.cos();
    let mut s = g(a) + g(b);
    for i in 1..n {
        s += g(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// The three diffuse shares, integrated once: (1 − R̄, r̄_int, μ̄).
fn diffuse_shares() -> (f64, f64, f64) {
    static SHARES: std::sync::OnceLock<(f64, f64, f64)> = std::sync::OnceLock::new();
    *SHARES.get_or_init(|| {
        (
            1.0 - hemispherical_mean(|th| fresnel(th.cos(), N_AIR, N_WATER).r),
            {
                // Below the critical angle by Simpson, beyond it all (∫ 2 sin cos = cos² θc).
                let crit = crate::optics::critical_angle(N_WATER, N_AIR).unwrap_or(FRAC_PI_2);
                let r = |th: f64| fresnel(th.cos(), N_WATER, N_AIR).r;
                weighted_integral(&r, 0.0, crit) + crit.cos().powi(2)
            },
            mean_cosine(),
        )
    })
}

/// Share of diffuse (uniform-radiance) room light that enters the water, 1 − R̄ (≈ 0.934).
pub fn diffuse_entry() -> f64 {
    diffuse_shares().0
}

/// Share of Lambertian light from below that the surface reflects back down, r̄_int (total
/// internal reflection included, ≈ 0.47).
pub fn diffuse_internal_reflectance() -> f64 {
    diffuse_shares().1
}

/// Mean cosine (to the vertical, in the water) of diffuse room light after it entered: the
/// downward irradiance falls as e^{−c z/μ̄} (≈ 0.83).
pub fn diffuse_mean_cosine() -> f64 {
    diffuse_shares().2
}

fn mean_cosine() -> f64 {
    // Weight of each air angle: transmitted irradiance; its path cosine: the refracted one.
    let cos_t = |th: f64| fresnel(th.cos(), N_AIR, N_WATER).cos_t;
    let t = |th: f64| fresnel(th.cos(), N_AIR, N_WATER).t;
    let flux = hemispherical_mean(t);
    // Radiance (∝ flux per cos θt) seen along paths: μ̄ = E_d / E_0 = flux / Σ(flux/cos θt).
    flux / hemispherical_mean(|th| t(th) / cos_t(th))
}

impl WaterLook {
    /// The per-frame shader inputs (`water_a`, `water_b` of the effects' uniform):
    /// [T_d (R, G, B): the way down to the table, b_p], [metres of water per scene metre, 0,
    /// 0, 0], for a scene whose table lies `table_depth` scene metres down.
    pub fn gpu_uniform(&self, table_depth: f64) -> [[f32; 4]; 2] {
        let a = pure_water_absorption();
        let b = self.scattering();
        let mu = diffuse_mean_cosine();
        let td = a.map(|a| (-(a + b) * self.depth_m / mu).exp() as f32);
        [
            [td[0], td[1], td[2], b as f32],
            [(self.depth_m / table_depth) as f32, 0.0, 0.0, 0.0],
        ]
    }
}

/// The water's constants as WGSL needs them (name, value), for the generated prelude
/// (`crate::shader::shared_consts`): the band absorption, the diffuse entry share, the mean
/// internal reflectance and n².
pub fn wgsl_values() -> [(&'static str, [f64; 3]); 4] {
    let n2 = (N_WATER / N_AIR).powi(2);
    [
        ("WATER_ABSORPTION", pure_water_absorption()),
        ("WATER_DIFFUSE_ENTRY", [diffuse_entry(); 3]),
        (
            "WATER_INTERNAL_REFLECTANCE",
            [diffuse_internal_reflectance(); 3],
        ),
        ("WATER_N2", [n2; 3]),
    ]
}

/// The light that leaves the water from the table and the particles, before the view
/// direction's 1 − R(θ) (module docs), per band: `table` the dry table's linear colour (the
/// camera's, also its albedo, clamped to [0, 1]), `room` the room's radiance, `path_m` the
/// view ray's path in the water, m.
pub fn transmitted(table: [f64; 3], room: [f64; 3], path_m: f64, look: &WaterLook) -> [f64; 3] {
    let a = pure_water_absorption();
    let b = look.scattering();
    let entry = diffuse_entry();
    let r_int = diffuse_internal_reflectance();
    let mu = diffuse_mean_cosine();
    let n2 = (N_WATER / N_AIR).powi(2);
    std::array::from_fn(|i| {
        let c = a[i] + b;
        let td = (-c * look.depth_m / mu).exp();
        let tv = (-c * path_m).exp();
        let rho = table[i].clamp(0.0, 1.0);
        let through = table[i] * entry * td * tv / (n2 * (1.0 - rho * r_int * td * td));
        let veil = room[i] * entry * (b / c) * (1.0 - tv);
        through + veil
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_absorption_of_pure_water_is_red_first() {
        let [r, g, b] = pure_water_absorption();
        // Hand trapezoids of the table (docs/water-look.md).
        assert!((r - 0.37355).abs() < 1e-5, "{r}");
        assert!((g - 0.06982).abs() < 1e-5, "{g}");
        assert!((b - 0.0091395).abs() < 1e-6, "{b}");
        // Pope & Fry's minimum is near 420 nm and the red end absorbs ~100× more.
        assert!(r > 5.0 * g && g > 5.0 * b);
    }

    #[test]
    fn diffuse_fresnel_shares_match_closed_forms_and_reciprocity() {
        let entry = diffuse_entry();
        let r_int = diffuse_internal_reflectance();
        let n2 = N_WATER * N_WATER;
        // Stokes reciprocity for diffuse light: what leaves from below (air-side measure) is
        // what enters from above, scaled by 1/n²: 1 − r̄_int = (1 − R̄)/n².
        assert!(((1.0 - r_int) - entry / n2).abs() < 1e-6, "{entry} {r_int}");
        // R̄ of water for a uniform sky: 6.6 % (Preisendorfer; Mobley's Light and Water).
        assert!((1.0 - entry - 0.066).abs() < 0.002, "{}", 1.0 - entry);
        // Mean cosine: between the cone's bounds (cos 48.6° = 0.66 and 1), ≈ 0.83.
        let mu = diffuse_mean_cosine();
        assert!(mu > 0.8 && mu < 0.87, "{mu}");
    }

    #[test]
    fn a_white_table_under_pure_water_keeps_its_light_and_a_dark_one_darkens() {
        let pure = WaterLook {
            depth_m: 1e-4,
            turbidity_ntu: 0.0,
        };
        let w = transmitted([1.0; 3], [0.5; 3], 0.0, &pure);
        for c in w {
            assert!((c - 1.0).abs() < 1e-3, "{w:?}");
        }
        // Albedo 0.2: 0.934/(1.777·(1 − 0.2·0.475)) = 0.58 of its dry radiance.
        let d = transmitted([0.2; 3], [0.5; 3], 0.0, &pure);
        assert!(d[0] < 0.2 * 0.59 && d[0] > 0.2 * 0.57, "{d:?}");
    }

    #[test]
    fn deep_water_turns_blue_green_and_turbid_water_veils() {
        let grey = [0.5; 3];
        let clear = WaterLook {
            depth_m: 1.0,
            turbidity_ntu: 0.0,
        };
        // (Deeper than the settings take: the reference holds at any depth.)
        let [r, g, b] = transmitted(grey, grey, 1.1, &clear);
        assert!(r < 0.6 * g && g < b, "{r} {g} {b}");
        // A table 1 m down, seen along 1.1 m: Beer–Lambert by hand for red.
        let a = pure_water_absorption()[0];
        let mu = diffuse_mean_cosine();
        let td = (-a / mu).exp();
        let n2 = N_WATER * N_WATER;
        let want = 0.5 * diffuse_entry() * td * (-a * 1.1).exp()
            / (n2 * (1.0 - 0.5 * diffuse_internal_reflectance() * td * td));
        assert!((r - want).abs() < 1e-12);
        // Turbid: the table fades towards the room's light.
        let murky = WaterLook {
            depth_m: 0.05,
            turbidity_ntu: 100.0,
        };
        let black_table = transmitted([0.0; 3], [0.8; 3], 0.06, &murky);
        assert!(black_table.iter().all(|&c| c > 0.5), "{black_table:?}");
    }

    #[test]
    fn settings_out_of_range_are_refused_with_the_setting_named() {
        assert!(WaterLook::default().check().is_ok());
        for (d, t) in [
            (0.0, 0.0),
            (0.3, 0.0),
            (f64::NAN, 0.0),
            (0.1, -1.0),
            (0.1, 101.0),
        ] {
            let e = WaterLook {
                depth_m: d,
                turbidity_ntu: t,
            }
            .check()
            .unwrap_err();
            assert!(e.contains("depth") || e.contains("turbidity"), "{e}");
        }
    }
}
