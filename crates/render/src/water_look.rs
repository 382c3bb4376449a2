//! The real sea's water over a table, from physical optics (docs/water-look.md): the f64
//! reference of `shaders/render/water_look.wgsl`, whose constants come from here through the
//! generated prelude ([`crate::shader::prelude`]).
//!
//! **Optical similarity** (as Froude scaling is for the wakes): the user states the real sea,
//! a water type ([`WaterType`]: Jerlov's classes, their absorption a and backscattering b_b
//! per RGB band from [`crate::water_types`]) and a depth in metres. On a table of scale s
//! (table metres per race metre) the water is depth·s deep and its coefficients are the real
//! ones ÷ s ([`WaterLook::on_table`]), so every optical depth is the real sea's: 8 m of
//! coastal water over the table looks like 8 m of coastal water over a sandy bottom.
//!
//! What the camera sees of the table and the water, per band (κ = a + b_b, the diffuse
//! attenuation; forward scattering blurs the table's image but does not take light out of it):
//!
//! - **The column's own colour**: deep water reflects R∞ = f · b_b/(a + b_b) of the light
//!   that enters (f = 0.33, [`DEEP_REFLECTANCE_FACTOR`]); over a bottom at depth H the column
//!   shows R∞ (1 − T_d T_v) and the bottom ρ T_d T_v (Maritorena, Morel & Gentili 1994's
//!   shallow-water reflectance, with the view path instead of their vertical one).
//! - **The table under water**: room light enters through the surface (diffuse, share
//!   1 − R̄ with R̄ the hemispherical Fresnel reflectance, [`diffuse_entry`]), goes down to
//!   the table (path depth/μ̄, μ̄ the mean cosine of the refracted diffuse light,
//!   [`diffuse_mean_cosine`]: T_d = e^{−κ H/μ̄}), is reflected by the table (albedo ρ: the
//!   camera's dry table colour, white = 1), comes back up (the view path l: T_v = e^{−κ l})
//!   and leaves through the surface with 1 − R(θ) (the exact Fresnel factor the shader mixes
//!   with, not here) and 1/n² (radiance in a denser medium). Light reflected back down by the
//!   surface from below (r̄_int, [`diffuse_internal_reflectance`], total internal reflection
//!   included) meets the column and the table again: a geometric series 1/(1 − A r̄_int) with
//!   A = ρ T_d² + R∞ (1 − T_d²). Together:
//!   L = (1 − R̄) [L_table T_d T_v + L_room R∞ (1 − T_d T_v)] / (n² (1 − A r̄_int)): a white
//!   table under clear water keeps its radiance (energy conservation:
//!   (1 − R̄)/n² = 1 − r̄_int), a darker one darkens as wet things do.
//! - **Reflection** of the sky and room: the exact unpolarised Fresnel equations
//!   (`optics::fresnel`, `shaders/optics.wgsl`), no Schlick.

use std::f64::consts::FRAC_PI_2;

use crate::optics::{N_AIR, N_WATER, fresnel};
pub use crate::pure_water::{BANDS_NM, POPE_FRY_1997, band_mean_absorption, pure_water_absorption};
pub use crate::water_types::{BandIops, WaterType};

/// The WGSL of the transmitted light (the AR water pass appends it).
pub const WATER_LOOK_WGSL: &str = include_str!("../../../shaders/render/water_look.wgsl");

/// Particle scattering per NTU of turbidity, 1/m: the beam attenuation of natural waters is
/// about 1 m⁻¹ per NTU (order of the turbidity–attenuation relations of suspended sediment);
/// taken as pure scattering with the particles' backscattering ratio
/// ([`crate::water_types::PARTICLE_BACKSCATTER_RATIO`]): it adds b_b, nothing else.
pub const SCATTERING_PER_NTU: f64 = 1.0;

/// Deepest real sea the settings take, m: at the first table's scale (about 1/1000) its
/// water is 10 cm deep (no tank walls are drawn, so a deeper layer reads as a floating sheet).
pub const MAX_DEPTH_M: f64 = 100.0;
/// Shallowest real sea, m.
pub const MIN_DEPTH_M: f64 = 0.5;
/// Most turbid water the settings take, NTU (muddy river water), added to the water type's.
pub const MAX_TURBIDITY_NTU: f64 = 100.0;
/// Irradiance reflectance of deep water per b_b/(a + b_b): R∞ = f · b_b/(a + b_b) with
/// f = 0.33 (Gordon, Brown & Jacobs 1975; Morel & Prieur 1977: R ≈ 0.33 b_b/a).
pub const DEEP_REFLECTANCE_FACTOR: f64 = 0.33;

/// The real sea the user chose; on a table it is drawn by optical similarity
/// ([`WaterLook::on_table`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterLook {
    /// Jerlov's water type (or pure water).
    pub water_type: WaterType,
    /// Depth of the real sea, m (race metres): on a table of scale s (table metres per race
    /// metre) the water is `depth_m · s` deep.
    pub depth_m: f64,
    /// Turbidity added to the type's particles, NTU (0: the type's own water).
    pub turbidity_ntu: f64,
}

impl Default for WaterLook {
    /// 5 m of Jerlov oceanic IB water: over the table it reads as shallow blue-green sea with
    /// the table still seen through it (docs/water-look.md, chosen by the look: 8 m of coastal
    /// 1 hid the table under dark teal), and at the first table's scale it lies about 5 mm
    /// deep, where the sea's table-sized waves ripple the light rather than focus it into
    /// speckles.
    fn default() -> Self {
        WaterLook {
            water_type: WaterType::OceanicIB,
            depth_m: 5.0,
            turbidity_ntu: 0.0,
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

    /// The real sea's absorption and backscattering per band (the type's and the turbidity's),
    /// 1/m.
    pub fn iops(&self) -> BandIops {
        let t = self.water_type.band_iops();
        let bbp = SCATTERING_PER_NTU
            * self.turbidity_ntu
            * crate::water_types::PARTICLE_BACKSCATTER_RATIO;
        BandIops {
            absorption: t.absorption,
            backscattering: t.backscattering.map(|b| b + bbp),
        }
    }

    /// The water on a table of scale `course_to_table` (table metres per race metre), by
    /// optical similarity: depth × s, coefficients ÷ s, so every optical depth (κ·depth, κ·path)
    /// and the deep-water reflectance b_b/(a + b_b) are the real sea's.
    pub fn on_table(&self, course_to_table: f64) -> TableWater {
        let iops = self.iops();
        let kappa: [f64; 3] = std::array::from_fn(|i| iops.absorption[i] + iops.backscattering[i]);
        TableWater {
            depth_m: self.depth_m * course_to_table,
            attenuation: kappa.map(|k| k / course_to_table),
            deep_reflectance: std::array::from_fn(|i| {
                DEEP_REFLECTANCE_FACTOR * iops.backscattering[i] / kappa[i]
            }),
        }
    }
}

/// The water over a table, in the table's own metres ([`WaterLook::on_table`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableWater {
    /// Depth of the water over the table, m.
    pub depth_m: f64,
    /// Diffuse attenuation κ = a + b_b per band, 1/m (forward-scattered light stays in the
    /// table's image, blurred, and is not taken out of it).
    pub attenuation: [f64; 3],
    /// Irradiance reflectance of infinitely deep water R∞ per band.
    pub deep_reflectance: [f64; 3],
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
    /// The per-frame shader inputs (`WaterOptics` of `shaders/render/water_look.wgsl`, in the
    /// effects' uniform) for a scene whose table lies `table_depth` scene metres down:
    /// [T_d (R, G, B): the room light's way down to the table, metres of real sea per scene
    /// metre], [−κ (R, G, B) of the real sea, 1/m, 0], [R∞ (R, G, B), 0] (the shader's
    /// room·R∞ for the AR water's room, the camera's white: 1), [A (R, G, B), 0],
    /// [B (R, G, B), 0], where the transmitted light's denominator
    /// n² (1 − r̄ (ρ T_d² + R∞ (1 − T_d²))) / (1 − R̄) is A − B ρ for a table albedo ρ: the
    /// parts that do not change within a frame formed here in f64, not per pixel. A table
    /// scene in race metres has 1 real metre per scene metre: optical similarity needs no scale
    /// on the GPU.
    pub fn gpu_optics(&self, table_depth: f64) -> [[f32; 4]; 5] {
        let w = self.on_table(1.0);
        let mu = diffuse_mean_cosine();
        let td = w.attenuation.map(|k| (-k * w.depth_m / mu).exp());
        let (entry, r_int) = (diffuse_entry(), diffuse_internal_reflectance());
        let n2 = (N_WATER / N_AIR).powi(2);
        let a: [f64; 3] = std::array::from_fn(|i| {
            n2 * (1.0 - r_int * w.deep_reflectance[i] * (1.0 - td[i] * td[i])) / entry
        });
        let b = td.map(|t| n2 * r_int * t * t / entry);
        let f = |v: [f64; 3], last: f64| [v[0] as f32, v[1] as f32, v[2] as f32, last as f32];
        [
            f(td, self.depth_m / table_depth),
            f(w.attenuation.map(|k| -k), 0.0),
            f(w.deep_reflectance, 0.0),
            f(a, 0.0),
            f(b, 0.0),
        ]
    }
}

/// The light that leaves infinitely deep water of `look`'s type under diffuse light of
/// radiance `room` per band, before the view direction's 1 − R(θ): [`transmitted_on`] with no
/// bottom (T_d = T_v = 0), i.e. (1 − R̄) R∞ L / (n² (1 − R∞ r̄_int)). The open sea's water body
/// (`shaders/render/water.wgsl` calls the same WGSL, `water_deep_body`).
pub fn deep_body(room: [f64; 3], look: &WaterLook) -> [f64; 3] {
    let w = look.on_table(1.0);
    let no_bottom = TableWater {
        depth_m: f64::INFINITY,
        ..w
    };
    transmitted_on([0.0; 3], room, f64::INFINITY, &no_bottom)
}

/// The water's constants as WGSL needs them (name, value), for the generated prelude
/// (`crate::shader::shared_consts`): the diffuse entry share, the mean internal reflectance
/// and n².
pub fn wgsl_values() -> [(&'static str, f64); 3] {
    let n2 = (N_WATER / N_AIR).powi(2);
    [
        ("WATER_DIFFUSE_ENTRY", diffuse_entry()),
        ("WATER_INTERNAL_REFLECTANCE", diffuse_internal_reflectance()),
        ("WATER_N2", n2),
    ]
}

/// The light that leaves the water from the table and from the water column, before the
/// view direction's 1 − R(θ) (module docs), per band: `table` the dry table's linear colour
/// (the camera's, also its albedo, clamped to [0, 1]), `room` the room's radiance, `path_m`
/// the view ray's path in the real sea, m (a table path ÷ the scale: [`transmitted_on`]).
pub fn transmitted(table: [f64; 3], room: [f64; 3], path_m: f64, look: &WaterLook) -> [f64; 3] {
    transmitted_on(table, room, path_m, &look.on_table(1.0))
}

/// [`transmitted`] over a table's water, `path_m` in the table's metres: the table seen
/// through the column (T_d T_v) and the column's own backscattered light where it hides the
/// table (R∞ (1 − T_d T_v), the shallow-water form of Maritorena, Morel & Gentili 1994),
/// through the wet-layer model (module docs) with the column's albedo ρ T_d² + R∞ (1 − T_d²)
/// under the surface.
pub fn transmitted_on(
    table: [f64; 3],
    room: [f64; 3],
    path_m: f64,
    water: &TableWater,
) -> [f64; 3] {
    let entry = diffuse_entry();
    let r_int = diffuse_internal_reflectance();
    let mu = diffuse_mean_cosine();
    let n2 = (N_WATER / N_AIR).powi(2);
    std::array::from_fn(|i| {
        let k = water.attenuation[i];
        let r = water.deep_reflectance[i];
        let td = (-k * water.depth_m / mu).exp();
        let tv = (-k * path_m).exp();
        let rho = table[i].clamp(0.0, 1.0);
        let seen = table[i] * td * tv + room[i] * r * (1.0 - td * tv);
        let albedo = rho * td * td + r * (1.0 - td * td);
        seen * entry / (n2 * (1.0 - albedo * r_int))
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

    fn pure(depth_m: f64) -> WaterLook {
        WaterLook {
            water_type: WaterType::Pure,
            depth_m,
            turbidity_ntu: 0.0,
        }
    }

    #[test]
    fn a_white_table_under_clear_water_keeps_its_light_and_a_dark_one_darkens() {
        // A film of water: T_d = T_v = 1 (to 10⁻⁴), R∞ (1 − T) negligible.
        let film = pure(1e-4).on_table(1.0);
        let w = transmitted_on([1.0; 3], [0.5; 3], 0.0, &film);
        for c in w {
            assert!((c - 1.0).abs() < 1e-3, "{w:?}");
        }
        // Albedo 0.2: 0.934/(1.777·(1 − 0.2·0.475)) = 0.58 of its dry radiance.
        let d = transmitted_on([0.2; 3], [0.5; 3], 0.0, &film);
        assert!(d[0] < 0.2 * 0.59 && d[0] > 0.2 * 0.57, "{d:?}");
    }

    #[test]
    fn deep_water_shows_its_backscatter_and_beer_lambert_holds_by_hand() {
        // So deep the table is gone: L = (1 − R̄) R∞ L_room / (n² (1 − R∞ r̄_int)), R∞ from the
        // type's own band IOPs, by hand.
        let look = WaterLook {
            water_type: WaterType::OceanicIB,
            depth_m: 100.0,
            turbidity_ntu: 0.0,
        };
        let iops = WaterType::OceanicIB.band_iops();
        let n2 = N_WATER * N_WATER;
        let deep = transmitted([0.5; 3], [1.0; 3], 200.0, &look);
        for i in 0..3 {
            let k = iops.absorption[i] + iops.backscattering[i];
            let r = 0.33 * iops.backscattering[i] / k;
            let want = diffuse_entry() * r / (n2 * (1.0 - r * diffuse_internal_reflectance()));
            // Red is fully deep; blue keeps e^{−κ(100/μ̄ + 200)} of the table (< 10⁻³).
            assert!(
                (deep[i] - want).abs() < 1e-3 * want.max(1e-3),
                "{i}: {deep:?}"
            );
        }
        // The open ocean is blue: B > G > R.
        assert!(deep[2] > deep[1] && deep[1] > deep[0], "{deep:?}");
        // 3 m over a grey table seen along 3.3 m: Beer–Lambert in red, by hand.
        let look = WaterLook {
            depth_m: 3.0,
            ..look
        };
        let [r, g, b] = transmitted([0.5; 3], [1.0; 3], 3.3, &look);
        let k = iops.absorption[0] + iops.backscattering[0];
        let rinf = 0.33 * iops.backscattering[0] / k;
        let td = (-k * 3.0 / diffuse_mean_cosine()).exp();
        let tv = (-k * 3.3).exp();
        let albedo = 0.5 * td * td + rinf * (1.0 - td * td);
        let want = diffuse_entry() * (0.5 * td * tv + rinf * (1.0 - td * tv))
            / (n2 * (1.0 - albedo * diffuse_internal_reflectance()));
        assert!((r - want).abs() < 1e-12);
        // Shallow clear water over a grey table: the red goes first, blue-green stays.
        assert!(r < 0.7 * g && r < 0.7 * b, "{r} {g} {b}");
    }

    #[test]
    fn optical_depth_and_the_look_are_invariant_under_the_table_scale() {
        // Closed form: on a table of scale s, depth·s and κ/s: κ_t·H_t = κ·H for every s, and
        // what the camera sees along a table path l·s is what the real sea shows along l.
        for t in [WaterType::Pure, WaterType::OceanicII, WaterType::Coastal5] {
            let look = WaterLook {
                water_type: t,
                depth_m: 12.0,
                turbidity_ntu: 2.0,
            };
            let real = look.on_table(1.0);
            for s in [1.0, 1.0 / 250.0, 0.45e-3, 1e-5] {
                let tw = look.on_table(s);
                for i in 0..3 {
                    let real_od = real.attenuation[i] * real.depth_m;
                    let od = tw.attenuation[i] * tw.depth_m;
                    assert!((od - real_od).abs() < 1e-12 * real_od, "{t} {s}");
                    assert_eq!(tw.deep_reflectance[i], real.deep_reflectance[i]);
                }
                for (table, path) in [([0.6, 0.4, 0.25], 13.0), ([1.0; 3], 30.0)] {
                    let a = transmitted_on(table, [1.0; 3], path * s, &tw);
                    let b = transmitted_on(table, [1.0; 3], path, &real);
                    for i in 0..3 {
                        assert!((a[i] - b[i]).abs() < 1e-12, "{t} {s}: {a:?} {b:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn turbidity_adds_backscatter_and_veils_the_table() {
        let clear = WaterLook {
            water_type: WaterType::Coastal1,
            depth_m: 5.0,
            turbidity_ntu: 0.0,
        };
        let murky = WaterLook {
            turbidity_ntu: 100.0,
            ..clear
        };
        let add = 100.0 * SCATTERING_PER_NTU * crate::water_types::PARTICLE_BACKSCATTER_RATIO;
        for i in 0..3 {
            let d = murky.iops().backscattering[i] - clear.iops().backscattering[i];
            assert!((d - add).abs() < 1e-12);
        }
        // A black table under murky water: the veil, near R∞'s grey, hides it.
        let black = transmitted([0.0; 3], [0.8; 3], 6.0, &murky);
        let white = transmitted([1.0; 3], [0.8; 3], 6.0, &murky);
        for i in 0..3 {
            assert!(
                black[i] > 0.05 && white[i] - black[i] < 0.1,
                "{black:?} {white:?}"
            );
        }
    }

    #[test]
    fn settings_out_of_range_are_refused_with_the_setting_named() {
        assert!(WaterLook::default().check().is_ok());
        for (d, t) in [
            (0.0, 0.0),
            (0.3, 0.0),
            (101.0, 0.0),
            (f64::NAN, 0.0),
            (10.0, -1.0),
            (10.0, 101.0),
        ] {
            let e = WaterLook {
                depth_m: d,
                turbidity_ntu: t,
                ..WaterLook::default()
            }
            .check()
            .unwrap_err();
            assert!(e.contains("depth") || e.contains("turbidity"), "{e}");
        }
    }
}
