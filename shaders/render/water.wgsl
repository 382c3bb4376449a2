// The water pass: the clip-map mesh displaced by the analytic Gerstner sea and the boats'
// wakes, shaded with per-pixel analytic normals, the full Fresnel equations (optics.wgsl), sky
// and sun reflection, Jacobian foam and wake foam. Appended to common.wgsl, optics.wgsl and a
// vertex stage that defines vs_main: water_displaced.wgsl (the vertices were displaced by the
// pass's compute stage, water_vertices.wgsl, sea and wakes) or water_no_wakes.wgsl (the sea
// displaced in the vertex shader, no wakes: adapters without compute). The wake is evaluated
// per vertex (it sums many sources; the clip-map's cells near the boats are finer than the
// wake's waves) and interpolated to the pixels.

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) rest: vec2<f32>,
    @location(1) world: vec3<f32>,
    // Wake slope (∂w/∂x, ∂w/∂z) and foam at this vertex.
    @location(2) wake: vec3<f32>,
    // The slope sums of the sea's longest waves, summed per vertex (vertex_sums_out):
    // interpolated, where the pixel's own wave loops start (render::vertex_slopes).
    @location(3) sea_sums: vec4<f32>,
    @location(4) sea_sums_z: vec2<f32>,
}

const FOAM: vec3<f32> = vec3<f32>(0.85, 0.88, 0.9);

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let pa = frame.play_area;
    if in.rest.x < pa.x || in.rest.y < pa.y || in.rest.x > pa.z || in.rest.y > pa.w {
        discard;
    }
    // Footprint of this pixel on the rest plane, metres: waves shorter than four footprints fade.
    let across = dpdx(in.rest);
    let down = dpdy(in.rest);
    let footprint = sqrt(max(dot(across, across), dot(down, down)));
    let sf = surface_frame_from(in.rest, frame.counts.x, footprint, vertex_sums_in(in.sea_sums, in.sea_sums_z));
    // Total surface y = h_sea(X) + w(X): add the wake's slope to the sea's.
    let n = normalize(vec3<f32>(sf.up.x / sf.up.y - in.wake.x, 1.0, sf.up.z / sf.up.y - in.wake.y));
    let wfoam = in.wake.z;
    let to_eye = normalize(frame.eye.xyz - in.world);
    let cos_i = max(dot(n, to_eye), 0.0);
    let r = fresnel_reflectance(cos_i, N_AIR, N_WATER);
    let reflected = sky_colour_rough(reflect_dir(-to_eye, n), sf.slope_variance);
    // Light from the water body: infinitely deep water of the chosen type (water_look.wgsl)
    // under the sky's and sun's diffuse light (frame.light), times the open sea's exposure.
    let sun_in = max(dot(n, frame.sun.xyz), 0.0);
    let body = water_deep_body(frame.light.rgb, frame.water_body) * frame.water_body.w;
    var colour = r * reflected + (1.0 - r) * body;
    // Foam where the horizontal map compresses, with the wake's: ocean's rule (common.wgsl).
    let foam = foam_coverage(foam_from_jacobian(sf.jacobian), wfoam);
    colour = mix(colour, FOAM * (0.6 + 0.4 * sun_in), foam);
    return vec4<f32>(colour, 1.0);
}
