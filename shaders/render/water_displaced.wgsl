// Vertex stage of the water pass with its compute stage (water_vertices.wgsl): every clip-map
// vertex was displaced by the sea and the wakes this frame, once, in a compute pass; the vertex
// shader only projects it. (A vertex shader summing hundreds of wake sources starves a GPU's
// vertex pipeline and runs on one thread in lavapipe; a compute pass runs at full width.)

struct VertexIn {
    // Displaced position (local metres) and the rest point's x.
    @location(0) pos_rest_x: vec4<f32>,
    // The rest point's z, the wake slope (∂w/∂x, ∂w/∂z) and wake foam.
    @location(1) rest_z_wake: vec4<f32>,
    // The slope sums of the waves the vertex carries to the pixels (vertex_sums_out).
    @location(2) sea_sums: vec4<f32>,
    @location(3) sea_sums_z: vec4<f32>,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return water_vertex(v);
}

// vs_main's work, for vertex shaders that add to it (entry points cannot be called).
fn water_vertex(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = frame.view_proj * vec4<f32>(v.pos_rest_x.xyz, 1.0);
    out.rest = vec2<f32>(v.pos_rest_x.w, v.rest_z_wake.x);
    out.world = v.pos_rest_x.xyz;
    out.wake = v.rest_z_wake.yzw;
    out.sea_sums = v.sea_sums;
    out.sea_sums_z = v.sea_sums_z.xy;
    return out;
}
