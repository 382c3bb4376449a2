// The sky pass: one full-screen triangle; each pixel shows the sky along its view ray.
// Appended to common.wgsl.

struct SkyOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> SkyOut {
    let xy = full_screen_xy(i);
    var out: SkyOut;
    out.clip = vec4<f32>(xy, 0.0, 1.0);
    out.ndc = xy;
    return out;
}

@fragment
fn fs_main(in: SkyOut) -> @location(0) vec4<f32> {
    return vec4<f32>(sky_colour(ray_dir(in.ndc)), 1.0);
}
