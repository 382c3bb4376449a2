// Compute passes for the parity tests and benches: the WGSL of the water pass at given inputs,
// exactly as the water pass evaluates it. Appended to common.wgsl (render::compute).
//
// One input and one output vec4 per item:
//   cs_main:          (rest x, rest z, -, -)      → (Σ gerstner(): dx, y, dz, 0)
//   cs_sea_displaced: (rest x, rest z, fade, level as bits) → (sea_displaced(), 0), the drawn
//                     vertex path with its level masks and fade (render::clipmap::ClipVertex)
//   cs_foam:          (rest x, rest z, wake foam, -) → (foam as the water pass draws it, J, 0, 0)

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
