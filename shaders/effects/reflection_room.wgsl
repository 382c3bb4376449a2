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
// Drawn as a grid of cells over the texture (at most ROOM_CELL_TEXELS texels a side,
// effects::reflection::room_grid; Effects.flags.zw hold its columns and rows), one triangle
// strip per row of cells: the smooth part of a texel's map (its reflected ray, the water
// crossing, the ring point and that point's homogeneous camera-image point) is evaluated at
// the cell corners and interpolated (error measured against the per-texel f64 map:
// effects::reflection::grid); each texel divides out its uv, takes the edge weight, samples
// the camera image and evaluates the sky and the sun itself, so none of them loses detail.
//
// Appended to effects_common.wgsl and reflection.wgsl; binds only the effects'
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

// sky_colour_texel for a rising direction (dir.y ≥ 0, as every reflected ray is where the
// water samples the texture): sky_gradient's upper half alone (sky_above), its lower half and
// the select left out. At dir.y < 0 (texels above the reflected horizon, which the water does
// not sample) it gives the horizon's haze, the texture's clear colour, where sky_gradient
// darkens to the sea.
fn sky_colour_rising(dir: vec3<f32>) -> vec3<f32> {
    let s = max(dot(dir, frame.sun.xyz), 0.0);
    let sun = pow(s, TEXEL_N64) * TEXEL_W64 + pow(s, TEXEL_N8) * TEXEL_W8 + pow(s, TEXEL_N_DISC) * TEXEL_W_DISC;
    return sky_above(dir.y) + SUN_COLOUR * sun * frame.sun.w;
}

// The sky with the sun at the texel roughness, any direction: sky_colour_rough(dir,
// TEXEL_ROUGHNESS) to rounding (kept for the test of the folded lobes; the pass draws
// sky_colour_rising).
fn sky_colour_texel(dir: vec3<f32>) -> vec3<f32> {
    let s = max(dot(dir, frame.sun.xyz), 0.0);
    let sun = pow(s, TEXEL_N64) * TEXEL_W64 + pow(s, TEXEL_N8) * TEXEL_W8 + pow(s, TEXEL_N_DISC) * TEXEL_W_DISC;
    return sky_gradient(dir) + SUN_COLOUR * sun * frame.sun.w;
}

// The direction of the ray through an NDC point of the texture: far.xyz − eye·far.w, far =
// inv_view_proj·(ndc, ½, 1). That is w·(X − eye) for the point X = far.xyz / far.w, and it
// points the way the view looks wherever X lies: the oblique near plane changes only the
// projection's depth row, so w is the point's depth in front of the eye (> 0 in front) and
// changes sign exactly where X passes behind the eye. It is affine in ndc, so interpolated
// linearly across the screen (w = 1 at every vertex) it stays exact and a texel only
// normalises. (It was multiplied by far.w once more, meant to divide out w's sign: that
// turned the rays of every texel whose X lay behind the eye, a band of the texture across the
// far water in the demo view, so those texels mirrored the sky below the horizon, not the
// room: the_room_ray_is_the_texels_mirrored_ray in effects' room_gpu_tests.rs.)
fn room_ray(ndc: vec2<f32>) -> vec3<f32> {
    let far = frame.inv_view_proj * vec4<f32>(ndc, 0.5, 1.0);
    return far.xyz - frame.eye.xyz * far.w;
}

// The camera-image point of the room the unit reflected direction r meets, homogeneous: (u w,
// v w, w) of camera_projection (w > 0 in front of the camera), linear in the ring point, so
// interpolated over a cell it errs only by the ring point's own curvature (effects::
// reflection::grid). The ray crosses the water at p (it rises from the mirrored eye below)
// and leaves the ring at ring_hit's exit root, taken here wherever the ray rises, also where
// it lies behind p (p outside the ring's circle, off the water): there the map runs on
// smoothly instead of switching to the sky within a cell. Rays that do not rise (texels above
// the reflected horizon, which the water does not sample) get w < 0: the sky.
fn room_image_point(r: vec3<f32>) -> vec3<f32> {
    let eye = frame.eye.xyz;
    let p = eye + r * (-eye.y / max(r.y, 1e-6));
    let o = p.xz - fx.table.zw;
    let d = r.xz;
    let a = max(dot(d, d), 1e-8);
    let b = dot(o, d);
    let k = max(b * b - a * (dot(o, o) - fx.table.y * fx.table.y), 0.0);
    let q = p + r * ((-b + sqrt(k)) / a);
    let h = fx.camera_projection * vec4<f32>(q, 1.0);
    return select(h, vec3<f32>(0.0, 0.0, -1.0), r.y <= 0.0);
}

struct RoomOut {
    @builtin(position) clip: vec4<f32>,
    // room_ray, for the sky at each texel.
    @location(0) ray: vec3<f32>,
    // room_image_point at the cell corners.
    @location(1) image: vec3<f32>,
}

// Corner (column i / 2, row `row` + i % 2) of the grid: vertex i of row `row`'s strip.
@vertex
fn vs_main(@builtin(vertex_index) i: u32, @builtin(instance_index) row: u32) -> RoomOut {
    let corner = vec2<f32>(vec2<u32>(i >> 1u, row + (i & 1u))) / vec2<f32>(fx.flags.zw);
    let ndc = vec2<f32>(2.0 * corner.x - 1.0, 1.0 - 2.0 * corner.y);
    let ray = room_ray(ndc);
    var out: RoomOut;
    out.clip = vec4<f32>(ndc, 1.0, 1.0);
    out.ray = ray;
    out.image = room_image_point(normalize(ray));
    return out;
}

// Per texel: the camera image at the interpolated point (its uv divided out here, so the
// image keeps its full detail and the edge fade its width), weighted by the edge weight where
// the camera sees the point, over the sky and the sun.
@fragment
fn fs_main(in: RoomOut) -> @location(0) vec4<f32> {
    let r = normalize(in.ray);
    let seen = in.image.z > 0.0;
    let uv = select(vec2<f32>(0.5), in.image.xy / in.image.z, seen);
    let w = select(0.0, edge_weight(uv), seen);
    return vec4<f32>(mix(sky_colour_rising(r), sample_camera(uv), w), 1.0);
}
