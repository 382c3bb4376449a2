// The YUV camera image converted to RGBA once per camera frame (BT.601; CPU reference:
// camera_image::Yuv420::to_rgba8, each pixel with its 2×2 block's chroma). Drawn at the camera
// image's size into a texture that the effect passes then sample like an RGBA camera image,
// through an sRGB view, the sampler decoding: a camera frame is converted once, not once per
// screen pixel that samples it (the background, the water, the reflected room; on lavapipe
// that per-sample conversion cost 0.75–1.2 ms of a 12 ms frame). Appended to common.wgsl
// (full_screen_xy); its own bindings are group 1.

// YUV -> gamma-encoded R'G'B': rgb = (to_rgb * vec4(y, u, v, 1)).rgb, the BT.601 matrix of
// camera_image::YuvToRgb::to_gpu_columns (offset in the last column).
struct CameraFormat {
    to_rgb: mat4x4<f32>,
}

@group(1) @binding(0) var luma: texture_2d<f32>;
// (U, V) at half resolution.
@group(1) @binding(1) var chroma: texture_2d<f32>;
@group(1) @binding(2) var<uniform> format: CameraFormat;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(full_screen_xy(i), 0.5, 1.0);
}

// The sRGB transfer function's inverse (IEC 61966-2-1), for an sRGB target, which encodes it
// again on write. ENCODED_TARGET (a constant the pass appends): the target is Rgba8Unorm,
// sampled through an sRGB view, and takes R'G'B' as they are. Either way the texture holds
// R'G'B' rounded to 8 bits, as the CPU reference does.
fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
}

@fragment
fn fs_main(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(at.xy);
    let y = textureLoad(luma, pixel, 0).r;
    let uv = textureLoad(chroma, pixel / 2u, 0).rg;
    let rgb = (format.to_rgb * vec4<f32>(y, uv, 1.0)).rgb;
    let encoded = clamp(rgb, vec3<f32>(0.0), vec3<f32>(1.0));
    return vec4<f32>(select(srgb_to_linear(encoded), encoded, ENCODED_TARGET), 1.0);
}
