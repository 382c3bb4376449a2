// Reflection (source 000 § 3.2.1, improved; f64 reference of the ring: effects/reflection.rs):
// what the water mirrors along the reflected ray r
// from the surface point p.
//
// 1. Boats, sails and marks: the planar reflection texture, drawn by the reflection pass with
//    the reflection matrix (000 eq. 1) and oblique near-plane clipping at the water (000 eq. 2),
//    so nothing below the water is in it; sampled at the pixel, moved by the surface normal.
// 2. Behind them, the real room: the camera image on a vertical ring of radius R around the
//    water (000's background plane on a circle, here a whole cylinder). The ring point that r
//    meets is projected through the camera's pose and intrinsics, so the ring turns with the
//    camera by construction. Only ring points above the water are used, and only where the
//    camera sees them: looking steeply down, the ring leaves the image and the sky is
//    reflected instead of the table (000's "parts below the water" limitation).
// 3. Elsewhere: the sky.

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

fn reflection_colour(p: vec3<f32>, r: vec3<f32>, screen_uv: vec2<f32>, n: vec3<f32>) -> vec3<f32> {
    var colour = sky_colour(r);
    let ring = ring_hit(p, r);
    if ring.w > 0.0 {
        let uv = camera_uv(ring.xyz);
        let w = edge_weight(uv.xy) * uv.z;
        colour = mix(colour, sample_camera(uv.xy), w);
    }
    // Planar reflection: distort by the normal's horizontal tilt, as the surface does. Where
    // nothing was drawn the texture is transparent (the pass clears it every frame the
    // reflection runs, drawn or not), so no flag is needed.
    let suv = screen_uv + vec2<f32>(n.x, -n.z) * 0.05;
    let boats = textureSampleLevel(reflection_image, linear_clamp, suv, 0.0);
    return mix(colour, boats.rgb, boats.a);
}
