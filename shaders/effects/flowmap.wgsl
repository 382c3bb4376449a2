// Flow-map distortion with the UV jump (the Sailing+ AR water thesis's § 3.1, docs/sources.md; f64 reference: effects/flowmap.rs):
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

// The detail field's slopes (∂/∂u, ∂/∂v of a tiling height field on the unit square, f64
// reference effects::flow_detail::detail_slope: three rounded triangle waves with integer
// frequencies), baked once on the CPU into a DETAIL_TEXELS² Rg16Float texture and sampled
// bilinearly with wrap-around: one texture sample where evaluating the waves took 50 ALU
// operations. Within effects::flow_detail::detail_texture_error of the field (about 1.0e-3
// of slopes up to 0.156, under the weakest filtering Vulkan allows).
@group(2) @binding(5) var flow_detail: texture_2d<f32>;
@group(2) @binding(6) var linear_repeat: sampler;

fn detail_slope(uv: vec2<f32>) -> vec2<f32> {
    return textureSampleLevel(flow_detail, linear_repeat, uv, 0.0).xy;
}

// The two copies' sample points in the detail tile at local point p where the water runs at
// `current` (m/s): xy copy A's, zw copy B's, each uv − flow·progress + offset (effects::flowmap::
// flow_uv). Affine in p and the current, so the vertex shader forms them and the rasteriser
// interpolates them as it would p and the current (exact up to rounding).
fn flow_sample_points(p: vec2<f32>, current: vec2<f32>) -> vec4<f32> {
    // Flow in tiles per period: current (m/s) x period (s, folded into the tile size).
    let flow = current / fx.current.w;
    let uv = p / fx.current.w;
    return vec4<f32>(uv - flow * fx.flow_a.x + fx.flow_a.zw, uv - flow * fx.flow_b.x + fx.flow_b.zw);
}

// The flow-advected detail's slopes at the copies' sample `points` (flow_sample_points) where
// the water runs at `current` (m/s, interpolated from the vertices): the gradient (∂/∂x, ∂/∂z)
// of a height field that adds to the sea's and the wake's, so the caller forms one normal from
// their summed slopes (f64 reference: effects::flowmap::flow_slope and normal_of_slopes).
fn flow_slope(points: vec4<f32>, current: vec2<f32>) -> vec2<f32> {
    let sa = detail_slope(points.xy) * fx.flow_a.y;
    let sb = detail_slope(points.zw) * fx.flow_b.y;
    // Stronger where the current runs faster (still water shows no flow pattern): 4 × the
    // flow in tiles per period.
    let k = clamp(length(current) * 4.0 / fx.current.w, 0.0, 1.0);
    return (sa + sb) * k;
}
