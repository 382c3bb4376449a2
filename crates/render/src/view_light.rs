//! The light a view's water takes, and the boats with it (docs/water-look.md, "The open sea's
//! colour" and "The boats' light"): the f64 reference of the frame uniform's `light` and
//! `water_body` and of the boats' shading in `shaders/render/boats.wgsl`.
//!
//! - **Open sea** (orbit view): the sky and the sun light the sea. The water body shows
//!   infinitely deep water of the chosen type ([`crate::water_look::deep_body`]) under the
//!   diffuse radiance of that light, [`open_sea_light`]; the boats keep the sun's Phong.
//! - **Room** (the table, over the camera image): the AR water takes the room's radiance (the
//!   camera's white, `vec3(1.0)` in `ar_water.wgsl`, the assumption that makes the table's
//!   colour its albedo); the boats take the same radiance ([`boat_in_room`]), so a boat's
//!   colour and the water's around it scale together with the room's light.

use glam::DVec3;

use crate::water_look::{WaterLook, deep_body};

/// The sky of `shaders/render/common.wgsl`'s `sky_colour_rough` at the zenith and the horizon
/// (linear RGB radiance, the renderer's units); a test checks the WGSL spells the same.
pub const SKY_ZENITH: [f64; 3] = [0.10, 0.28, 0.62];
/// See [`SKY_ZENITH`].
pub const SKY_HORIZON: [f64; 3] = [0.62, 0.74, 0.86];
/// The sky's blend exponent: mix(horizon, zenith, up^0.45).
pub const SKY_EXPONENT: f64 = 0.45;
/// Colour of the sun's glow and disc in `sky_colour_rough`.
pub const SUN_COLOUR: [f64; 3] = [1.0, 0.92, 0.78];

/// Irradiance of the sun's glow lobes and disc on a surface facing it, per unit `sun.w`:
/// ∫ radiance dω of `sky_colour_rough`'s terms (variance 0): 0.6·2π/65 (pow(s, 64)) +
/// 0.15·2π/9 (pow(s, 8)) + 30·2π·(1 − 0.99965) (the disc, its smoothstep's midpoint) ≈ 0.23.
pub fn sun_irradiance() -> f64 {
    use std::f64::consts::TAU;
    0.6 * TAU / 65.0 + 0.15 * TAU / 9.0 + 30.0 * TAU * (1.0 - 0.99965)
}

/// The diffuse radiance that lights the open sea's water, per band: the cosine-weighted mean
/// of the sky over the upper hemisphere (closed form: horizon + (zenith − horizon)·2/(2 +
/// 0.45), since ∫₀¹ u^0.45·2u du = 2/2.45) plus the sun's irradiance on the level sea ÷ π
/// (E = π L for uniform radiance L). `sun`: unit vector towards the sun, `sun_scale` its
/// `frame.sun.w`.
pub fn open_sea_light(sun: DVec3, sun_scale: f64) -> [f64; 3] {
    let w = 2.0 / (2.0 + SKY_EXPONENT);
    let e_sun = sun_irradiance() * sun_scale * sun.y.max(0.0) / std::f64::consts::PI;
    std::array::from_fn(|i| {
        SKY_HORIZON[i] + (SKY_ZENITH[i] - SKY_HORIZON[i]) * w + e_sun * SUN_COLOUR[i]
    })
}

/// Today's (hand-picked, before the water type) open-sea body in blue at the reference view
/// that [`open_sea_exposure`] keeps: a level facet (sun_in = sun.y of the default sun) seen at
/// 60° from the vertical: DEEP.b + SHALLOW.b·(0.25 + 0.75·sun_in)·(1 − 0.5·cos 60°).
fn hand_picked_blue(sun: DVec3) -> f64 {
    0.07 + 0.17 * (0.25 + 0.75 * sun.y) * (1.0 - 0.5 * 0.5)
}

/// The open sea's exposure: one factor for all bands and types, the ratio of the hand-picked
/// body's blue to the physical default's (oceanic IB under the default sun) in blue. The
/// renderer's sky is a display's (its zenith is 0.62 in blue where a real clear sky is some
/// 20–50 times the deep sea's water-leaving radiance), so the physical body, in the sky's units,
/// is about 13× darker than the picture was tuned to; the factor keeps the default sea's
/// brightness and lets the type set its colour.
pub fn open_sea_exposure() -> f64 {
    let sun = crate::Scene::default_sun();
    let body = deep_body(open_sea_light(sun, 1.0), &WaterLook::default());
    hand_picked_blue(sun) / body[2]
}

/// The frame uniform's `water_body`: R∞ per band of `look`'s type and the exposure.
pub fn water_body_uniform(look: &WaterLook) -> [f32; 4] {
    let r = look.on_table(1.0).deep_reflectance;
    [
        r[0] as f32,
        r[1] as f32,
        r[2] as f32,
        open_sea_exposure() as f32,
    ]
}

/// The open sea's body colour as `water.wgsl` draws it: the exposure times the deep water's
/// light under [`open_sea_light`].
pub fn open_sea_body(look: &WaterLook, sun: DVec3, sun_scale: f64) -> [f64; 3] {
    deep_body(open_sea_light(sun, sun_scale), look).map(|c| c * open_sea_exposure())
}

/// Share of the room's light that comes from its main light's direction (the rest from the
/// whole upper hemisphere): enough for a hull's sides and a sail's two faces to differ.
pub const ROOM_DIRECTIONAL_SHARE: f64 = 0.5;

/// A boat's colour in a room of diffuse radiance `room` per band, `albedo` its colour, `n` the
/// surface's unit normal and `to_light` the room's main light direction (unit):
/// albedo·room·((1 − D)·(1 + n_y)/2 + D·max(n·l, 0)) with D = [`ROOM_DIRECTIONAL_SHARE`]. A
/// level surface under an overhead light gets albedo·room: the table's camera colour for the
/// same albedo, as the water's model assumes. Linear in `room`, as the water's light is.
pub fn boat_in_room(albedo: [f64; 3], n: DVec3, to_light: DVec3, room: [f64; 3]) -> [f64; 3] {
    let d = ROOM_DIRECTIONAL_SHARE;
    let shade = (1.0 - d) * 0.5 * (1.0 + n.y) + d * n.dot(to_light).max(0.0);
    std::array::from_fn(|i| albedo[i] * room[i] * shade)
}

/// The constants the boats' WGSL needs, for the generated prelude.
pub fn wgsl_values() -> [(&'static str, f64); 1] {
    [("ROOM_DIRECTIONAL_SHARE", ROOM_DIRECTIONAL_SHARE)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::N_WATER;
    use crate::water_look::{WaterType, diffuse_entry, diffuse_internal_reflectance, transmitted};

    fn deep(t: WaterType) -> WaterLook {
        WaterLook {
            water_type: t,
            depth_m: 5.0,
            turbidity_ntu: 0.0,
        }
    }

    #[test]
    fn deep_body_is_morel_prieur_from_the_tabulated_iops() {
        // R∞ = 0.33 b_b/(a + b_b) (Morel & Prieur 1977) from the type's band a and b_b, by hand,
        // through the surface: (1 − R̄) R∞ L / (n² (1 − R∞ r̄_int)).
        for t in WaterType::ALL {
            let iops = t.band_iops();
            let body = deep_body([0.3, 0.5, 0.7], &deep(t));
            for i in 0..3 {
                let (a, bb) = (iops.absorption[i], iops.backscattering[i]);
                let r = 0.33 * bb / (a + bb);
                let l = [0.3, 0.5, 0.7][i];
                let want = diffuse_entry() * r * l
                    / (N_WATER * N_WATER * (1.0 - r * diffuse_internal_reflectance()));
                assert!((body[i] - want).abs() <= 1e-12 * want, "{t} {i}");
            }
        }
    }

    #[test]
    fn oceanic_waters_are_bluest_and_coastal_ones_greener_in_jerlovs_order() {
        // The blue/green ratio of R∞ falls from oceanic I to coastal 9 (Jerlov's classes are
        // ordered by turbidity, yellow substance shifting the colour to green), and pure water
        // is bluer than all of them.
        let ratio = |t: WaterType| {
            let r = deep(t).on_table(1.0).deep_reflectance;
            r[2] / r[1]
        };
        let order = &WaterType::ALL[1..];
        for w in order.windows(2) {
            assert!(
                ratio(w[0]) > ratio(w[1]),
                "{} {}: {} {}",
                w[0],
                w[1],
                ratio(w[0]),
                ratio(w[1])
            );
        }
        assert!(ratio(WaterType::Pure) > ratio(WaterType::OceanicI));
        // Oceanic water is blue (B > G > R), coastal 5 green (G the largest band).
        let ib = deep(WaterType::OceanicIB).on_table(1.0).deep_reflectance;
        assert!(ib[2] > ib[1] && ib[1] > ib[0], "{ib:?}");
        let c5 = deep(WaterType::Coastal5).on_table(1.0).deep_reflectance;
        assert!(c5[1] > c5[2] && c5[1] > c5[0], "{c5:?}");
        // Magnitudes: open-ocean blue R∞ of a few per cent (Morel & Prieur's 0.02–0.05 in the
        // blue for oceanic waters).
        assert!(ib[2] > 0.02 && ib[2] < 0.06, "{ib:?}");
    }

    /// ∫ over the upper hemisphere of f(direction) cos θ dω, numerically (midpoint rule).
    fn cosine_integral(f: impl Fn(DVec3) -> f64) -> f64 {
        let (nt, np) = (2000, 400);
        let mut s = 0.0;
        for i in 0..nt {
            let th = (i as f64 + 0.5) / nt as f64 * std::f64::consts::FRAC_PI_2;
            for j in 0..np {
                let ph = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                let d = DVec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin());
                s += f(d) * th.cos() * th.sin();
            }
        }
        s * (std::f64::consts::FRAC_PI_2 / nt as f64) * (std::f64::consts::TAU / np as f64)
    }

    #[test]
    fn the_open_sea_light_is_the_skys_cosine_weighted_mean_numerically() {
        // Sky only (sun below the horizon): the closed form against a quadrature of the WGSL's
        // mix(horizon, zenith, up^0.45), E/π.
        let below = DVec3::new(0.0, -1.0, 0.0);
        let l = open_sea_light(below, 1.0);
        for i in 0..3 {
            let e = cosine_integral(|d| {
                let w = d.y.max(0.0).powf(SKY_EXPONENT);
                SKY_HORIZON[i] + (SKY_ZENITH[i] - SKY_HORIZON[i]) * w
            });
            assert!(
                (l[i] - e / std::f64::consts::PI).abs() < 1e-4,
                "{i}: {l:?} {e}"
            );
        }
        // The sun overhead: its lobes' irradiance by quadrature (no disc: its edge is finer
        // than the grid; the disc's share, 30·2π·3.5e-4, is added by hand).
        let up = DVec3::Y;
        let lobes = cosine_integral(|d| {
            let s = d.dot(up).max(0.0);
            s.powi(64) * 0.6 + s.powi(8) * 0.15
        });
        // With the sun overhead, ∫ L cos θ dω = ∫ s^n·s dω: compare ∫ s^n dω = 2π/(n + 1).
        let lobes_flat = 0.6 * std::f64::consts::TAU / 66.0 + 0.15 * std::f64::consts::TAU / 10.0;
        assert!((lobes - lobes_flat).abs() < 1e-4, "{lobes} {lobes_flat}");
        let disc = 30.0 * std::f64::consts::TAU * 3.5e-4;
        let e_lobes = 0.6 * std::f64::consts::TAU / 65.0 + 0.15 * std::f64::consts::TAU / 9.0;
        assert!((sun_irradiance() - (e_lobes + disc)).abs() < 1e-12);
    }

    #[test]
    fn the_wgsl_sky_is_the_one_the_open_sea_light_integrates() {
        let wgsl = include_str!("../../../shaders/render/common.wgsl");
        assert!(wgsl.contains("const SKY_ZENITH: vec3<f32> = vec3<f32>(0.10, 0.28, 0.62);"));
        assert!(wgsl.contains("const SKY_HORIZON: vec3<f32> = vec3<f32>(0.62, 0.74, 0.86);"));
        assert!(wgsl.contains("pow(max(up, 0.0), 0.45)"));
        assert!(wgsl.contains("vec3<f32>(1.0, 0.92, 0.78)"));
    }

    #[test]
    fn the_default_open_sea_keeps_todays_blue_and_is_deep_blue() {
        let sun = crate::Scene::default_sun();
        let body = open_sea_body(&WaterLook::default(), sun, 1.0);
        assert!((body[2] - hand_picked_blue(sun)).abs() < 1e-12);
        // Deep blue: B > G > R, hue between 200° and 240°.
        assert!(body[2] > body[1] && body[1] > body[0], "{body:?}");
        let hue = {
            let (r, g, b) = (body[0], body[1], body[2]);
            let (mx, mn) = (b, r.min(g));
            240.0 + 60.0 * (r - g) / (mx - mn)
        };
        assert!((200.0..240.0).contains(&hue), "{hue} {body:?}");
        // The exposure is one factor, order 10 (module docs).
        let k = open_sea_exposure();
        eprintln!("open sea: exposure {k:.2}, default body {body:?}");
        assert!(k > 3.0 && k < 30.0, "{k}");
    }

    #[test]
    fn a_boat_and_the_water_around_it_scale_together_with_the_room_light() {
        // A dim warm room against a bright neutral one: the water's light (a table of albedo
        // ρ seen through the sea, the camera showing ρ·room) and a boat's colour change by the
        // same factor per band.
        let dim_warm = [0.30, 0.20, 0.10];
        let bright = [1.0, 1.0, 1.0];
        let table = [0.55, 0.40, 0.25];
        let look = WaterLook::default();
        let water = |room: [f64; 3]| {
            let seen: [f64; 3] = std::array::from_fn(|i| table[i] * room[i]);
            transmitted(seen, room, 6.0, &look)
        };
        let to_light = DVec3::new(0.3, 0.9, 0.2).normalize();
        for n in [DVec3::Y, DVec3::X, DVec3::new(-0.6, 0.2, 0.77).normalize()] {
            for albedo in [[0.8, 0.1, 0.1], [0.92, 0.92, 0.88]] {
                let b1 = boat_in_room(albedo, n, to_light, dim_warm);
                let b2 = boat_in_room(albedo, n, to_light, bright);
                let (w1, w2) = (water(dim_warm), water(bright));
                for i in 0..3 {
                    let boat_ratio = b1[i] / b2[i];
                    let water_ratio = w1[i] / w2[i];
                    // The water's model takes the camera's colour as the table's albedo
                    // (exact under the camera's white): in the dim room the albedo under the
                    // surface, ρ T_d², is read dimmer, which moves the internal reflections'
                    // 1/(1 − A r̄_int) by at most r̄_int ρ (1 − room) T_d² / (1 − r̄_int).
                    let w = look.on_table(1.0);
                    let td = (-w.attenuation[i] * w.depth_m
                        / crate::water_look::diffuse_mean_cosine())
                    .exp();
                    let r_int = diffuse_internal_reflectance();
                    let tol = r_int * table[i] * (1.0 - dim_warm[i]) * td * td / (1.0 - r_int);
                    assert!(
                        (boat_ratio - water_ratio).abs() <= tol * water_ratio + 1e-12,
                        "{n} {i}: {boat_ratio} {water_ratio} {tol}"
                    );
                    assert!((boat_ratio - dim_warm[i]).abs() < 1e-12);
                }
            }
        }
        // A level surface under an overhead light: albedo × room, the table's own colour.
        let b = boat_in_room([0.5, 0.4, 0.3], DVec3::Y, DVec3::Y, [0.8, 0.7, 0.6]);
        for (i, c) in b.iter().enumerate() {
            assert!((c - [0.5 * 0.8, 0.4 * 0.7, 0.3 * 0.6][i]).abs() < 1e-12);
        }
    }
}
