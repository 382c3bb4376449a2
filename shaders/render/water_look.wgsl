// The real sea's water over a table by optical similarity (render::water_look is its f64
// reference; docs/water-look.md): the light that leaves the water from the table and from
// the water column, before the view direction's Fresnel transmittance 1 − R(θ). Constants
// (WATER_*) come from the generated prelude; per frame, from the effects' uniform:
//   water_a = (T_d.rgb: the room light's way down to the table, unused)
//   water_c = (κ.rgb = a + b_b of the real sea, 1/m, unused)
//   water_d = (R∞.rgb: the deep water's irradiance reflectance f·b_b/(a + b_b), unused)
//   table  = the dry table's linear colour (also its albedo), room = the room's radiance,
//   path_m = the view ray's path in the water, metres of real sea.
// One vec3 exponential per pixel (the way down is the uniform's).
fn water_transmitted(table: vec3<f32>, room: vec3<f32>, path_m: f32, water_a: vec4<f32>, water_c: vec4<f32>, water_d: vec4<f32>) -> vec3<f32> {
    let td = water_a.xyz;
    let deep = water_d.xyz;
    let t = td * exp(-water_c.xyz * path_m);
    let rho = clamp(table, vec3<f32>(0.0), vec3<f32>(1.0));
    let seen = table * t + room * deep * (vec3<f32>(1.0) - t);
    let albedo = rho * td * td + deep * (vec3<f32>(1.0) - td * td);
    return seen * WATER_DIFFUSE_ENTRY / (WATER_N2 * (vec3<f32>(1.0) - albedo * WATER_INTERNAL_REFLECTANCE));
}

// Infinitely deep water under diffuse light `room` (the open sea: no bottom the camera sees):
// water_transmitted with no table (T_d = T_v = 0), f64 reference water_look::deep_body.
// `deep` = (R∞.rgb, unused).
fn water_deep_body(room: vec3<f32>, deep: vec4<f32>) -> vec3<f32> {
    return water_transmitted(vec3<f32>(0.0), room, 0.0, vec4<f32>(0.0), vec4<f32>(0.0), deep);
}
