// Caustics on the table (f64 reference: effects/caustics.rs).
//
// Area-ratio tier: the irradiance map of the actual wave surface at this race time, computed on
// the CPU by the area ratio (light conserved; 1 = flat water) and sampled at the table point.
// Cheap tier (the Sailing+ AR water thesis's, after GPU Gems; docs/sources.md): sun straight overhead; the vertical ray from the table
// meets the surface above, is bent out by its normal and looks up a sun disc; the source's
// alpha = clamp(r + g + b, 0, 1) makes the dark parts transparent. The sun disc's radius
// CHEAP_SUN_RADIUS and the blend CHEAP_SUN_GAIN come from the prelude (f64 reference:
// effects::caustics::cheap_caustic_light).

fn overhead_sun(n: vec3<f32>) -> f32 {
    let up = refract_dir(vec3<f32>(0.0, 1.0, 0.0), n, N_WATER, N_AIR);
    let angle = acos(clamp(up.y, -1.0, 1.0));
    let x = angle / CHEAP_SUN_RADIUS;
    return select(0.0, exp(-x * x), up.w > 0.0);
}

// Light on the table point whose (x, z) is q (local metres: the table's height is the
// plane's) relative to flat water; n is the surface normal above it (cheap tier only).
// FX_CHEAP_CAUSTICS is a constant of the pipeline (ar_water.wgsl).
fn caustic_light(q: vec2<f32>, n: vec3<f32>) -> f32 {
    if FX_CHEAP_CAUSTICS {
        let rgb = vec3<f32>(overhead_sun(n));
        let alpha = clamp(rgb.r + rgb.g + rgb.b, 0.0, 1.0);
        return 1.0 + CHEAP_SUN_GAIN * alpha * rgb.r;
    }
    // Outside the map: the light of flat water. (The early return above is on a constant; the
    // map's test is a select: see camera_uv.)
    let uv = (q - fx.caustic_region.xy) / fx.caustic_region.z;
    let light = textureSampleLevel(caustic_map, linear_clamp, uv, 0.0).r * fx.caustic_region.w;
    return select(light, 1.0, any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)));
}
