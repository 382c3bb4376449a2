// Camera background pass: the camera frame behind everything, through the display's UV
// transform (screen uv -> camera-image uv, as ARCore's transformCoordinates2d gives it). The
// image is RGBA, or YUV 4:2:0 planes converted to RGBA once per camera frame (camera_yuv.wgsl).
// Drawn at the far plane with depth test LessEqual, so it fills exactly the pixels that no
// water, boat or mark covered; it replaces the sky, which AR does not have.

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> ScreenOut {
    return full_screen(i, 1.0);
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let s = vec3<f32>(ndc_to_uv(in.ndc), 1.0);
    let uv = vec2<f32>(dot(fx.display_u.xyz, s), dot(fx.display_v.xyz, s));
    return vec4<f32>(sample_camera(uv), 1.0);
}
