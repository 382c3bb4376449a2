// Shared by the AR effect passes (background, reflection, refraction, caustics, flow map):
// their uniform and textures (bind group 2; group 1 is unused), the
// full-screen triangle, and the camera image through the camera's intrinsics and pose.
// Appended to common.wgsl and optics.wgsl; mirrored in f64 by crates/effects/src/*.rs.

// Effect bits FX_BACKGROUND, FX_REFLECTION, FX_REFRACTION, FX_CAUSTICS, FX_FLOWMAP (the AR
// water's FX_MASK) and EDGE_FADE: generated from effects::Effect and
// effects::refraction::EDGE_FADE (effects::wgsl::prelude).

struct Effects {
    // Local world -> camera image of the physical camera, its intrinsics folded in on the CPU
    // (render::optics::PinholeCamera::image_projection): (p, 1) -> (u w, v w, w), w the
    // depth in front of the camera, uv as fractions of the image (v grows downwards).
    camera_projection: mat4x3<f32>,
    // The same projection's constant column for points on the table (y = −table depth):
    // camera_projection[1]·y + camera_projection[3], formed in f64 on the CPU (xyz; w unused).
    table_image: vec4<f32>,
    // Screen uv (s, t) -> the camera-image point of the table straight behind it, as columns of
    // a 3×3 map: (s, t, 1) -> (u w, v w, w), the eye's ray met with the table plane and
    // projected, composed in f64 on the CPU (effects::passes::straight_image); all zero when
    // the eye is not above the table.
    straight_image: array<vec4<f32>, 3>,
    // The display's UV transform: screen uv -> camera-image uv, rows of a 2x3 affine map.
    display_u: vec4<f32>,
    display_v: vec4<f32>,
    // Table depth below the rest level (m), ring radius (m), ring centre x, z (local m).
    table: vec4<f32>,
    // Caustic map: min x, min z (local m), side (m), intensity per unit of the texture.
    caustic_region: vec4<f32>,
    // Flow copies A and B: progress, weight, uv offset (reduced on the CPU in f64).
    flow_a: vec4<f32>,
    flow_b: vec4<f32>,
    // Far current x, z (m/s), mark radius (m), detail tile size (m).
    current: vec4<f32>,
    // x = the cover's vertices (0: none), y = marks, zw = the reflected room's grid, columns
    // and rows of cells (effects::reflection::room_grid). Which effects run is each
    // pipeline's constant, FX_MASK.
    flags: vec4<u32>,
    marks: array<vec4<f32>, 8>,
    // The sea's water over the table (water_look.wgsl).
    water: WaterOptics,
    // The screen polygon the water certainly covers (effects::passes::cover), NDC, counter-
    // clockwise, two vertices a vec4: the background pass draws around it.
    cover: array<vec4<f32>, 10>,
    // Its centroid (xy) and the scale (z) about it at which its copy holds the screen.
    cover_shape: vec4<f32>,
}

@group(2) @binding(0) var<uniform> fx: Effects;
@group(2) @binding(1) var camera_image: texture_2d<f32>;
@group(2) @binding(2) var reflection_image: texture_2d<f32>;
@group(2) @binding(3) var caustic_map: texture_2d<f32>;
@group(2) @binding(4) var linear_clamp: sampler;
// Bindings 5 and 6 (the flow map's detail texture and its wrap-around sampler): flowmap.wgsl.

struct ScreenOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

// A triangle that covers the screen at depth z.
fn full_screen(i: u32, z: f32) -> ScreenOut {
    let xy = full_screen_xy(i);
    var out: ScreenOut;
    out.clip = vec4<f32>(xy, z, 1.0);
    out.ndc = xy;
    return out;
}

// Screen uv (0..1, v down) of an NDC point.
fn ndc_to_uv(ndc: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y);
}

// Camera-image uv of a local world point (the pinhole of effects/refraction.rs); z of the
// result is 1 in front of the camera, 0 behind it.
fn camera_uv(p: vec3<f32>) -> vec3<f32> {
    // One exit, no early return: Mesa 22.3's lavapipe crashed drawing some AR water pipelines
    // that inlined this function with an early return (see ar_water.wgsl).
    let h = fx.camera_projection * vec4<f32>(p, 1.0);
    let uv = vec3<f32>(h.xy / h.z, 1.0);
    return select(uv, vec3<f32>(0.5, 0.5, 0.0), h.z <= 0.0);
}

// camera_uv of the table point at local (x, z) (on the plane y = −table depth): the plane's
// height folded into fx.table_image, so two columns and a constant (12 operations) where
// camera_uv's 3×4 product takes 24.
fn table_uv(xz: vec2<f32>) -> vec3<f32> {
    let h = fx.camera_projection[0] * xz.x + fx.camera_projection[2] * xz.y + fx.table_image.xyz;
    let uv = vec3<f32>(h.xy / h.z, 1.0);
    return select(uv, vec3<f32>(0.5, 0.5, 0.0), h.z <= 0.0);
}

// 1 inside the image, falling to 0 at EDGE_FADE outside it by the max-norm distance to the
// image (effects::refraction::edge_weight). Inside, both components of `outside` are negative
// and the clamp makes the weight 1.
fn edge_weight(uv: vec2<f32>) -> f32 {
    let outside = max(-uv, uv - vec2<f32>(1.0));
    return clamp(1.0 - max(outside.x, outside.y) / EDGE_FADE, 0.0, 1.0);
}

// Linear RGB of the camera image at uv, filtered by the sampler, which decodes the sRGB
// texture: the RGBA image as it came, or the YUV planes converted once per camera frame
// (camera_yuv.wgsl). Outside the image the sampler's clamp-to-edge gives the edge texel, what
// clamping uv to [0, 1] first gave (at uv = 1 the linear filter already reads the edge texel
// only).
fn sample_camera(uv: vec2<f32>) -> vec3<f32> {
    return textureSampleLevel(camera_image, linear_clamp, uv, 0.0).rgb;
}
