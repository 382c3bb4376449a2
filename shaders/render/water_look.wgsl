// The real sea's water over a table by optical similarity (render::water_look is its f64
// reference; docs/water-look.md): the light that leaves the water from the table and from
// the water column, before the view direction's Fresnel transmittance 1 − R(θ). Constants
// (WATER_*) come from the generated prelude; per frame, from the effects' uniform, the
// optics of the chosen sea (render::water_look::WaterLook::gpu_optics):
//   table  = the dry table's linear colour (also its albedo),
//   path_m = the view ray's path in the water, metres of real sea,
// and the room's radiance folded into the uniform's R∞ (the AR water's room is the camera's
// white, 1: the product costs a pixel nothing).
// L = (1 − R̄)[table T_d T_v + room R∞ (1 − T_d T_v)] / (n² (1 − r̄ (ρ T_d² + R∞ (1 − T_d²)))):
// the denominator is A − B ρ with A and B per-frame constants (formed in f64 on the CPU),
// one vec3 exponential per pixel (the way down is the uniform's).
struct WaterOptics {
    // T_d.rgb: the room light's way down to the table; w: metres of real sea per scene metre.
    down_scale: vec4<f32>,
    // −κ.rgb, κ = a + b_b of the real sea, 1/m.
    neg_attenuation: vec4<f32>,
    // room·R∞.rgb: the room's radiance times the deep water's irradiance reflectance
    // f·b_b/(a + b_b) (the column's own light in that room).
    deep: vec4<f32>,
    // A.rgb = n² (1 − r̄ R∞ (1 − T_d²)) / (1 − R̄).
    denominator: vec4<f32>,
    // B.rgb = n² r̄ T_d² / (1 − R̄): the table albedo's weight in the denominator.
    albedo_weight: vec4<f32>,
}

fn water_transmitted(table: vec3<f32>, path_m: f32, w: WaterOptics) -> vec3<f32> {
    let t = w.down_scale.xyz * exp(w.neg_attenuation.xyz * path_m);
    let rho = clamp(table, vec3<f32>(0.0), vec3<f32>(1.0));
    // table·t + room·R∞·(1 − t) as one mix (WGSL defines mix by that expression).
    let seen = mix(w.deep.xyz, table, t);
    return seen / (w.denominator.xyz - w.albedo_weight.xyz * rho);
}

// Infinitely deep water under diffuse light `room` (the open sea: no bottom the camera sees):
// water_transmitted with no table (T_d = T_v = 0: the column's albedo is R∞), f64 reference
// water_look::deep_body. `deep` = (R∞.rgb, unused).
fn water_deep_body(room: vec3<f32>, deep: vec4<f32>) -> vec3<f32> {
    let r = deep.xyz;
    return room * r * WATER_DIFFUSE_ENTRY / (WATER_N2 * (vec3<f32>(1.0) - r * WATER_INTERNAL_REFLECTANCE));
}
