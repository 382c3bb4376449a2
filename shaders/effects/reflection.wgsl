// Reflection (§ 3.2.1 of the Sailing+ AR water thesis, report 000 in docs/sources.md, improved;
// f64 reference of the ring: effects/reflection.rs):
// what the water mirrors, from the planar reflection texture. The reflection pass draws it at a
// fraction of the screen (000: a quarter) with the reflection matrix (000 eq. 1) and oblique
// near-plane clipping at the water (000 eq. 2), so nothing below the water is in it: first the
// real room over the sky (reflection_room.wgsl: the camera image on a ring around the water,
// drawn as a grid whose corners take ring_hit's exit root, where the camera sees it; the sky
// and the sun elsewhere), then boats, sails and marks. The water samples it at the pixel,
// moved by the surface normal's tilt (000's distortion, which breaks the sun into glints along
// the waves): one texture sample per pixel for everything reflected. (It was drawn over a
// per-pixel sky before: on lavapipe that sky cost about a tenth of a water-only frame.)

fn ring_hit(p: vec3<f32>, r: vec3<f32>) -> vec4<f32> {
    // Solve |(p + s r).xz - c| = R for the exit (s > 0) of the ray from inside the ring; w = 0
    // when the ray runs downwards or misses (one exit: see camera_uv).
    let c = fx.table.zw;
    let o = p.xz - c;
    let d = r.xz;
    let a = dot(d, d);
    let b = dot(o, d);
    let k = b * b - a * (dot(o, o) - fx.table.y * fx.table.y);
    let s = (-b + sqrt(max(k, 0.0))) / max(a, 1e-8);
    let hit = a >= 1e-8 && r.y > 0.0 && k >= 0.0 && s > 0.0;
    return select(vec4<f32>(0.0), vec4<f32>(p + r * s, 1.0), hit);
}

// What the water at this pixel mirrors (with the camera at or below the water nothing is drawn
// into the texture: it keeps its clear colour, the horizon's haze).
fn reflection_colour(screen_uv: vec2<f32>, n: vec3<f32>) -> vec3<f32> {
    // Distort by the normal's horizontal tilt, as the surface does.
    let suv = screen_uv + vec2<f32>(n.x, -n.z) * 0.05;
    return textureSampleLevel(reflection_image, linear_clamp, suv, 0.0).rgb;
}
