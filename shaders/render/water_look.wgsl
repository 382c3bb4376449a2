// Clear water over a table (render::water_look is its f64 reference; docs/water-look.md): the
// light that leaves the water from the table and from the particles, before the view
// direction's Fresnel transmittance 1 − R(θ). Constants (WATER_*) come from the generated
// prelude; per frame, from the effects' uniform:
//   water_a = (T_d.rgb: the room light's way down to the table, b_p: particle scattering 1/m)
//   table  = the dry table's linear colour (also its albedo), room = the room's radiance,
//   path_m = the view ray's path in the water, metres of water.
// One vec3 exponential per pixel (the way down is the uniform's).
fn water_transmitted(table: vec3<f32>, room: vec3<f32>, path_m: f32, water_a: vec4<f32>) -> vec3<f32> {
    let b = water_a.w;
    let td = water_a.xyz;
    let c = WATER_ABSORPTION + vec3<f32>(b);
    let tv = exp(-c * path_m);
    let rho = clamp(table, vec3<f32>(0.0), vec3<f32>(1.0));
    let through = table * WATER_DIFFUSE_ENTRY * td * tv
        / (WATER_N2 * (vec3<f32>(1.0) - rho * WATER_INTERNAL_REFLECTANCE * td * td));
    let veil = room * WATER_DIFFUSE_ENTRY * (b / c) * (vec3<f32>(1.0) - tv);
    return through + veil;
}
