// The water pass: the clip-map mesh displaced by the analytic Gerstner sea and the boats'
// wakes, shaded with per-pixel analytic normals, the full Fresnel equations (optics.wgsl), sky
// and sun reflection, Jacobian foam and wake foam. Appended to common.wgsl, optics.wgsl and a
// wake hook (water_wakes.wgsl after wake.wgsl, or water_no_wakes.wgsl) that defines
// wake_at(p). The wake is evaluated per vertex (it sums many sources; the clip-map's cells
// near the boats are finer than the wake's waves) and interpolated to the pixels.

struct VertexIn {
    // Rest point in local metres, already morphed towards the next coarser level (CPU side).
    @location(0) rest: vec2<f32>,
    // Weight of the waves that this level has and the next coarser one drops: 1 inside the
    // level, 0 on its outer border, so border vertices evaluate exactly the coarser level's sea.
    @location(1) fade: f32,
    @location(2) level: u32,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) rest: vec2<f32>,
    @location(1) world: vec3<f32>,
    // Wake slope (∂w/∂x, ∂w/∂z) and foam at this vertex.
    @location(2) wake: vec3<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var pos = vec3<f32>(v.rest.x, 0.0, v.rest.y);
    for (var i = 0u; i < frame.counts.x; i = i + 1u) {
        if wave_in_level(i, v.level) {
            let weight = select(v.fade, 1.0, wave_in_level(i, v.level + 1u));
            pos += gerstner(waves[i], v.rest) * weight;
        }
    }
    // The wake is a height at a world point: where this vertex has gone.
    var out: VertexOut;
    out.wake = vec3<f32>(0.0);
    if frame.counts.z > 0u {
        let w = wake_at(pos.xz);
        pos.y += w.x;
        out.wake = w.yzw;
    }
    out.clip = frame.view_proj * vec4<f32>(pos, 1.0);
    out.rest = v.rest;
    out.world = pos;
    return out;
}

// Colour of light scattered up out of the water body (what refraction shows in open water).
const DEEP_WATER: vec3<f32> = vec3<f32>(0.004, 0.035, 0.07);
const SHALLOW_SCATTER: vec3<f32> = vec3<f32>(0.02, 0.16, 0.17);
const FOAM: vec3<f32> = vec3<f32>(0.85, 0.88, 0.9);

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let pa = frame.play_area;
    if in.rest.x < pa.x || in.rest.y < pa.y || in.rest.x > pa.z || in.rest.y > pa.w {
        discard;
    }
    // Footprint of this pixel on the rest plane, metres: waves shorter than four footprints fade.
    let footprint = max(length(dpdx(in.rest)), length(dpdy(in.rest)));
    let sf = surface_frame(in.rest, frame.counts.x, footprint);
    // Total surface y = h_sea(X) + w(X): add the wake's slope to the sea's.
    let n = normalize(vec3<f32>(sf.normal.x / sf.normal.y - in.wake.x, 1.0, sf.normal.z / sf.normal.y - in.wake.y));
    let wfoam = in.wake.z;
    let to_eye = normalize(frame.eye.xyz - in.world);
    let cos_i = max(dot(n, to_eye), 0.0);
    let r = fresnel_reflectance(cos_i, N_AIR, N_WATER);
    let reflected = sky_colour_rough(reflect_dir(-to_eye, n), sf.slope_variance);
    // Light from the water body: more scatter where the sun lights a facet facing the eye.
    let sun_in = max(dot(n, frame.sun.xyz), 0.0);
    let body = DEEP_WATER + SHALLOW_SCATTER * (0.25 + 0.75 * sun_in) * (1.0 - cos_i * 0.5);
    var colour = r * reflected + (1.0 - r) * body;
    // Foam where the horizontal map compresses (Jacobian below FOAM_ONSET, ocean crate).
    let foam = max(clamp((0.72 - sf.jacobian) / 0.35, 0.0, 1.0), wfoam);
    colour = mix(colour, FOAM * (0.6 + 0.4 * sun_in), foam);
    return vec4<f32>(colour, 1.0);
}
