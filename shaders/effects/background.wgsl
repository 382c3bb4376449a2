// Camera background pass: the camera frame behind everything, through the display's UV
// transform (screen uv -> camera-image uv, as ARCore's transformCoordinates2d gives it). The
// image is RGBA, or YUV 4:2:0 planes converted to RGBA once per camera frame (camera_yuv.wgsl).
// Drawn at the far plane with depth test LessEqual, so it fills exactly the pixels that no
// water, boat or mark covered; it replaces the sky, which AR does not have. Where the water
// certainly covers a convex polygon of the screen (effects::passes::cover), only the ring
// between that polygon and its copy scaled about its centroid until it holds the screen is
// drawn: two triangles an edge, no pixel inside the polygon.

// The cover's vertex i (NDC).
fn cover_vertex(i: u32) -> vec2<f32> {
    let pair = fx.cover[i / 2u];
    return select(pair.xy, pair.zw, (i % 2u) == 1u);
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> ScreenOut {
    // No cover: one triangle over the whole screen (vertices 0, 1, 2).
    var xy = full_screen_xy(i);
    let n = fx.flags.x;
    if n > 0u {
        // Edge e of the polygon, from vertex e to the next: the quad (inner e, inner e + 1,
        // outer e + 1, outer e) as two triangles, six vertices an edge. (One exit: see
        // camera_uv in effects_common.wgsl.)
        let e = i / 6u;
        let corner = array<u32, 6>(0u, 1u, 3u, 0u, 3u, 2u)[i % 6u];
        let v = cover_vertex((e + (corner & 1u)) % n);
        let c = fx.cover_shape.xy;
        xy = select(v, c + (v - c) * fx.cover_shape.z, corner >= 2u);
    }
    var out: ScreenOut;
    out.clip = vec4<f32>(xy, 1.0, 1.0);
    out.ndc = xy;
    return out;
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let s = vec3<f32>(ndc_to_uv(in.ndc), 1.0);
    let uv = vec2<f32>(dot(fx.display_u.xyz, s), dot(fx.display_v.xyz, s));
    return vec4<f32>(sample_camera(uv), 1.0);
}
