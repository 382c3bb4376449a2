// Compute pass for the parity test and benches: displacement of the analytic sea at local
// rest points, exactly as the water pass's vertex shader evaluates it (gerstner() of
// common.wgsl). Appended to common.wgsl.

@group(1) @binding(0) var<storage, read> points: array<vec2<f32>>;
@group(1) @binding(1) var<storage, read_write> displaced: array<vec4<f32>>;

@compute @workgroup_size(64)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&points) {
        return;
    }
    let p = points[i];
    var d = vec3<f32>(0.0);
    for (var j = 0u; j < frame.counts.x; j = j + 1u) {
        d += gerstner(waves[j], p);
    }
    displaced[i] = vec4<f32>(d, 0.0);
}
