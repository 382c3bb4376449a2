// Flow-map distortion with the UV jump (source 000 § 3.1; f64 reference: effects/flowmap.rs):
// a detail normal texture advected by the current around the marks, two copies half a period
// apart blended with triangle weights, each jumping at its restart. The current is the
// potential flow past each mark (a cylinder) in the far current; progress and offsets come
// reduced from the CPU.

fn current_at(p: vec2<f32>) -> vec2<f32> {
    // In complex numbers (x + i z) the field past a mark at offset ζ is v = U − a² conj(U) ζ²/|ζ|⁴,
    // the same as effects::flowmap::current_at without turning into the current's frame (no
    // square root, no division by the speed) and without an early return (see camera_uv).
    let u = fx.current.xy;
    let a2 = fx.current.z * fx.current.z;
    var v = u;
    var inside = false;
    for (var i = 0u; i < min(fx.flags.y, 8u); i = i + 1u) {
        let d = p - fx.marks[i].xy;
        let r2 = dot(d, d);
        inside = inside || r2 <= a2;
        let d2 = vec2<f32>(d.x * d.x - d.y * d.y, 2.0 * d.x * d.y);
        v -= a2 / (r2 * r2) * vec2<f32>(u.x * d2.x + u.y * d2.y, u.x * d2.y - u.y * d2.x);
    }
    return select(v, vec2<f32>(0.0), inside);
}

// Slopes (d/dx, d/dz) of a tiling detail height field on the unit square (a stand-in for a
// normal map texture: a few sines with integer frequencies, so it tiles).
fn detail_slope(uv: vec2<f32>) -> vec2<f32> {
    let t = 2.0 * PI;
    let a = cos(t * (3.0 * uv.x + 2.0 * uv.y));
    let b = cos(t * (-2.0 * uv.x + 5.0 * uv.y));
    let c = cos(t * (7.0 * uv.x + 1.0 * uv.y));
    return vec2<f32>(3.0 * a - 2.0 * b + 7.0 * c * 0.4, 2.0 * a + 5.0 * b + 1.0 * c * 0.4) * 0.02;
}

fn flow_normal(p: vec2<f32>, n: vec3<f32>) -> vec3<f32> {
    // Flow in tiles per period: current (m/s) x period (s, folded into the tile size).
    let flow = current_at(p) / fx.current.w;
    let uv = p / fx.current.w;
    let sa = detail_slope(uv - flow * fx.flow_a.x + fx.flow_a.zw) * fx.flow_a.y;
    let sb = detail_slope(uv - flow * fx.flow_b.x + fx.flow_b.zw) * fx.flow_b.y;
    let s = sa + sb;
    // Stronger where the current runs faster (still water shows no flow pattern).
    let k = clamp(length(flow) * 4.0, 0.0, 1.0);
    return normalize(n + vec3<f32>(-s.x, 0.0, -s.y) * k);
}
