// The upscale pass: the frame drawn at a fraction of the screen (RenderOptions::render_scale),
// stretched onto the screen with bilinear filtering. The phones' budget: shading half the
// pixels per side costs a quarter; the stretch costs one texture sample per screen pixel.

@group(0) @binding(0) var frame_image: texture_2d<f32>;
@group(0) @binding(1) var linear_clamp: sampler;

struct StretchOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> StretchOut {
    let xy = vec2<f32>(f32((i << 1u) & 2u) * 2.0 - 1.0, f32(i & 2u) * 2.0 - 1.0);
    var out: StretchOut;
    out.clip = vec4<f32>(xy, 0.0, 1.0);
    out.uv = vec2<f32>(0.5 * xy.x + 0.5, 0.5 - 0.5 * xy.y);
    return out;
}

@fragment
fn fs_main(in: StretchOut) -> @location(0) vec4<f32> {
    return textureSampleLevel(frame_image, linear_clamp, in.uv, 0.0);
}
