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

// A smooth periodic bump per component: 1 at whole x, −1 at half; a triangle wave with its
// corners rounded by s (3 − s²)/2 (continuous slope), within 0.021 of cos(2π x) everywhere at
// a few multiply-adds instead of a cosine's range reduction and polynomial (lavapipe pays for
// every instruction of every pixel).
fn periodic_bump(x: vec3<f32>) -> vec3<f32> {
    let s = 4.0 * abs(fract(x) - 0.5) - 1.0;
    return s * (1.5 - 0.5 * s * s);
}

// Slopes (d/dx, d/dz) of a tiling detail height field on the unit square (a stand-in for a
// normal map texture: three bumps with integer frequencies, so it tiles).
fn detail_slope(uv: vec2<f32>) -> vec2<f32> {
    let b = periodic_bump(vec3<f32>(3.0 * uv.x + 2.0 * uv.y, -2.0 * uv.x + 5.0 * uv.y, 7.0 * uv.x + 1.0 * uv.y));
    return vec2<f32>(3.0 * b.x - 2.0 * b.y + 7.0 * b.z * 0.4, 2.0 * b.x + 5.0 * b.y + 1.0 * b.z * 0.4) * 0.02;
}

// The surface normal n at local point p tilted by the flow-advected detail, where the water
// runs at `current` (m/s, current_at interpolated from the vertices).
fn flow_normal(p: vec2<f32>, current: vec2<f32>, n: vec3<f32>) -> vec3<f32> {
    // Flow in tiles per period: current (m/s) x period (s, folded into the tile size).
    let flow = current / fx.current.w;
    let uv = p / fx.current.w;
    let sa = detail_slope(uv - flow * fx.flow_a.x + fx.flow_a.zw) * fx.flow_a.y;
    let sb = detail_slope(uv - flow * fx.flow_b.x + fx.flow_b.zw) * fx.flow_b.y;
    let s = sa + sb;
    // Stronger where the current runs faster (still water shows no flow pattern).
    let k = clamp(length(flow) * 4.0, 0.0, 1.0);
    return normalize(n + vec3<f32>(-s.x, 0.0, -s.y) * k);
}
