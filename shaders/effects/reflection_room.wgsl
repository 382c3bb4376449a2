// The real room in the planar reflection texture (the Sailing+ AR water thesis's § 3.2.1, improved: docs/sources.md; f64 reference
// of the ring: effects/reflection.rs). Drawn first in the planar reflection pass, at the
// texture's fraction of the screen, with the reflection pass's frame bindings: the camera
// mirrored in the water (eq. 1 of the Sailing+ AR water thesis, 000 in docs/sources.md) with its near plane on the water (000 eq. 2). In those
// coordinates a pixel's ray leaves the mirrored eye below the water, crosses the water at p and
// goes on up as the reflected ray of the flat water. The room is the camera image on a vertical
// ring of radius R around the water (000's background plane on a circle, here a whole
// cylinder): the ring point that ray meets is projected through the camera's pose and
// intrinsics, so the ring turns with the camera by construction. Only ring points above the
// water are used, and only where the camera sees them: looking steeply down, the ring leaves
// the image and the sky (with the sun) is reflected instead of the table (000's "parts below
// the water" limitation), blended over the image's edge. Boats, sails and marks are drawn
// over it.
//
// Appended to effects_common.wgsl and reflection.wgsl (ring_hit); binds only the effects'
// uniform and camera image (group 2 without the reflection texture it draws into).

// The sun's disc and glow widened as by a slope variance this large: the disc (about 1.4° at
// the smoothstep's edge) then spans a few texels of a quarter-resolution texture instead of
// flickering between them as the camera moves.
const TEXEL_ROUGHNESS: f32 = 2e-4;

// sky_colour_rough's lobes at that constant variance, evaluated when the shader is compiled
// (const-expressions), so a texel pays the three powers only: sky_colour_texel(dir) is
// sky_colour_rough(dir, TEXEL_ROUGHNESS) to rounding, 27 operations fewer a texel.
const TEXEL_V2: f32 = 2.0 * TEXEL_ROUGHNESS;
const TEXEL_N64: f32 = 64.0 / (1.0 + 64.0 * TEXEL_V2);
const TEXEL_N8: f32 = 8.0 / (1.0 + 8.0 * TEXEL_V2);
const TEXEL_N_DISC: f32 = 1.0 / (3e-4 + TEXEL_V2);
const TEXEL_W64: f32 = 0.6 * (TEXEL_N64 + 1.0) / 65.0;
const TEXEL_W8: f32 = 0.15 * (TEXEL_N8 + 1.0) / 9.0;
const TEXEL_W_DISC: f32 = 30.0 * 3e-4 * (TEXEL_N_DISC + 1.0);

fn sky_colour_texel(dir: vec3<f32>) -> vec3<f32> {
    let s = max(dot(dir, frame.sun.xyz), 0.0);
    let sun = pow(s, TEXEL_N64) * TEXEL_W64 + pow(s, TEXEL_N8) * TEXEL_W8 + pow(s, TEXEL_N_DISC) * TEXEL_W_DISC;
    return sky_gradient(dir) + SUN_COLOUR * sun * frame.sun.w;
}

// The ray of each texel as a varying: with far = inv_view_proj·(ndc, ½, 1) the texel's ray
// is (far.xyz/far.w − eye), whose direction is that of (far.xyz − eye·far.w)·far.w, and both
// far.xyz − eye·far.w and far.w are affine in ndc: interpolated across the full-screen
// triangle (w = 1 at its corners: linear in the screen) they are exact, and a texel only
// normalises (ray_dir's matrix product and division once per corner, not per texel).
struct RoomOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ray_w: vec4<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> RoomOut {
    let corner = full_screen(i, 1.0);
    let far = frame.inv_view_proj * vec4<f32>(corner.ndc, 0.5, 1.0);
    var out: RoomOut;
    out.clip = corner.clip;
    out.ray_w = vec4<f32>(far.xyz - frame.eye.xyz * far.w, far.w);
    return out;
}

@fragment
fn fs_main(in: RoomOut) -> @location(0) vec4<f32> {
    let r = normalize(in.ray_w.xyz * in.ray_w.w);
    let eye = frame.eye.xyz;
    // Where the ray crosses the water (it rises from the mirrored eye below).
    let s = -eye.y / max(r.y, 1e-6);
    let ring = ring_hit(eye + r * s, r);
    let uv = camera_uv(ring.xyz);
    let w = select(0.0, edge_weight(uv.xy) * uv.z, ring.w > 0.0);
    return vec4<f32>(mix(sky_colour_texel(r), sample_camera(uv.xy), w), 1.0);
}
