// Compute passes for the parity tests and benches: the WGSL of the water pass at given inputs,
// exactly as the water pass evaluates it. Appended to common.wgsl (render::compute).
//
// One input and one output vec4 per item:
//   cs_main:          (rest x, rest z, -, -)      → (Σ gerstner(): dx, y, dz, 0)
//   cs_sea_displaced: (rest x, rest z, fade, level as bits) → (sea_displaced(), 0), the drawn
//                     vertex path with its level masks and fade (render::clipmap::ClipVertex)
//   cs_foam:          (rest x, rest z, wake foam, -) → (foam as the water pass draws it, J, 0, 0)
//   cs_surface_frame: (rest x, rest z, footprint m, 0 or 1) → (n.x / n.y, n.z / n.y, J, slope
//                     variance) of surface_frame (w = 0), or of the same sums over every
//                     wave without its early stop (w = 1: surface_frame_every_wave)

@group(1) @binding(0) var<storage, read> points: array<vec4<f32>>;
@group(1) @binding(1) var<storage, read_write> displaced: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&points) {
        return;
    }
    let p = points[i].xy;
    var d = vec3<f32>(0.0);
    for (var j = 0u; j < frame.counts.x; j = j + 1u) {
        d += gerstner(waves[j], p);
    }
    displaced[i] = vec4<f32>(d, 0.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_sea_displaced(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&points) {
        return;
    }
    let v = points[i];
    displaced[i] = vec4<f32>(sea_displaced(v.xy, v.z, bitcast<u32>(v.w)), 0.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_foam(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&points) {
        return;
    }
    let v = points[i];
    // A footprint of 0: no wave is band-limited away (the f64 reference keeps every wave).
    let sf = surface_frame(v.xy, frame.counts.x, 0.0);
    displaced[i] = vec4<f32>(foam_coverage(foam_from_jacobian(sf.jacobian), v.z), sf.jacobian, 0.0, 0.0);
}

// surface_frame's sums with no early stop: every wave runs, a faded one adding zero slope
// (the reference its early stop must equal; the frame's waves are sorted by k).
fn surface_frame_every_wave(p: vec2<f32>, n: u32, footprint: f32) -> SurfaceFrame {
    var dxdx = 1.0;
    var dxdz = 0.0;
    var dzdz = 1.0;
    var dydx = 0.0;
    var dydz = 0.0;
    var variance = 0.0;
    for (var i = 0u; i < n; i = i + 1u) {
        let w = waves[i];
        let fade = 1.0 - smoothstep(0.25 * PI, 0.5 * PI, w.k * footprint);
        variance += (1.0 - fade * fade) * w.half_slope2;
        let theta = wave_phase(w, p);
        let s = sin(theta) * fade;
        let c = cos(theta) * fade;
        dxdx -= w.slope_xx * s;
        dxdz -= w.slope_xz * s;
        dzdz -= w.slope_zz * s;
        dydx += w.slope_x * c;
        dydz += w.slope_z * c;
    }
    let tx = vec3<f32>(dxdx, dydx, dxdz);
    let tz = vec3<f32>(dxdz, dydz, dzdz);
    var out: SurfaceFrame;
    out.up = cross(tz, tx);
    out.jacobian = dxdx * dzdz - dxdz * dxdz;
    out.slope_variance = variance;
    return out;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_surface_frame(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&points) {
        return;
    }
    let v = points[i];
    var sf = surface_frame(v.xy, frame.counts.x, v.z);
    if v.w != 0.0 {
        sf = surface_frame_every_wave(v.xy, frame.counts.x, v.z);
    }
    displaced[i] = vec4<f32>(sf.up.x / sf.up.y, sf.up.z / sf.up.y, sf.jacobian, sf.slope_variance);
}
