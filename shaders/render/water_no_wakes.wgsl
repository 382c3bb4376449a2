// Vertex stage of the water pass without wakes (adapters with no compute shaders, such as
// OpenGL ES 3.0): each clip-map vertex displaced by the sea in the vertex shader.

struct VertexIn {
    // Rest point in local metres, already morphed towards the next coarser level (CPU side).
    @location(0) rest: vec2<f32>,
    // Weight of the waves that this level has and the next coarser one drops: 1 inside the
    // level, 0 on its outer border, so border vertices evaluate exactly the coarser level's sea.
    @location(1) fade: f32,
    @location(2) level: u32,
}

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    return water_vertex(v);
}

// vs_main's work, for vertex shaders that add to it (entry points cannot be called).
fn water_vertex(v: VertexIn) -> VertexOut {
    let pos = sea_displaced(v.rest, v.fade, v.level);
    var out: VertexOut;
    out.clip = frame.view_proj * vec4<f32>(pos, 1.0);
    out.rest = v.rest;
    out.world = pos;
    out.wake = vec3<f32>(0.0);
    let sums = vertex_sums_out(vertex_slope_sums(v.rest, v.level));
    out.sea_sums = sums[0];
    out.sea_sums_z = sums[1].xy;
    return out;
}
