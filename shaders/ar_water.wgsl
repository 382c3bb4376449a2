// The AR water pass: the water over the table, shaded again with the effects this frame needs
// (flags.x) and mixed by the full Fresnel equations (source 004): R·reflection + (1 − R)·the
// table seen through the water (refracted, lit by caustics, absorbed along the path).
// A full-screen triangle; each pixel finds the water under it (effects_common.wgsl), so the
// pass needs no mesh. Its depth is pulled towards the eye by a margin that covers the wave
// height, so it passes the depth test over the water pass but not over boats in front.

struct FragOut {
    @location(0) colour: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> ScreenOut {
    return full_screen(i, 0.0);
}

// Light lost per metre of water path, relative to the table's depth (so a scaled table looks
// the same): red goes first.
const ABSORPTION: vec3<f32> = vec3<f32>(0.9, 0.35, 0.25);

@fragment
fn fs_main(in: ScreenOut) -> FragOut {
    let hit = water_hit(in.ndc);
    if hit.w == 0.0 {
        discard;
    }
    let p = hit.xyz;
    let view = normalize(p - frame.eye.xyz);
    let screen_uv = ndc_to_uv(in.ndc);
    let footprint = length(p - frame.eye.xyz) * 2.0 * frame.viewport.w;
    var n = surface_frame(p.xz, frame.counts.x, footprint).normal;
    if fx_on(FX_FLOWMAP) {
        n = flow_normal(p.xz, n);
    }
    let cos_i = max(dot(n, -view), 0.0);
    let r = fresnel_reflectance(cos_i, N_AIR, N_WATER);

    var reflected = sky_colour(reflect_dir(view, n));
    if fx_on(FX_REFLECTION) {
        reflected = reflection_colour(p, reflect_dir(view, n), screen_uv, n);
    }

    // The table under the water (q), straight through or refracted, and its colour and
    // path length in the water (table.w).
    var q = table_point_straight(p, view);
    var table: vec4<f32>;
    if fx_on(FX_REFRACTION) {
        table = refracted_table(p, view, n);
        q = p + refract_dir(view, n, N_AIR, N_WATER).xyz * table.w;
    } else {
        table = vec4<f32>(sample_camera(camera_uv(q).xy), length(q - p));
    }
    var light = 1.0;
    if fx_on(FX_CAUSTICS) {
        light = caustic_light(q, n);
    }
    let depth = max(fx.table.x, 1e-3);
    let transmitted = table.rgb * light * exp(-ABSORPTION * table.w / depth);

    var out: FragOut;
    out.colour = vec4<f32>(r * reflected + (1.0 - r) * transmitted, 1.0);
    // Pull towards the eye by the largest wave height (Σ A) plus 1 % of the distance.
    var amplitude = 0.0;
    for (var i = 0u; i < frame.counts.x; i = i + 1u) {
        amplitude += waves[i].amplitude;
    }
    let margin = amplitude + 0.01 * length(p - frame.eye.xyz);
    let c = frame.view_proj * vec4<f32>(p - view * margin, 1.0);
    out.depth = clamp(c.z / c.w, 0.0, 1.0);
    return out;
}
