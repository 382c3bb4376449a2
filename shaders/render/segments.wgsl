// Segment layers (crates/render/src/passes/segments.rs): world-space segments drawn as
// screen-space capsules `width` pixels wide (a segment of length 0 is a disc).
// Depth-tested against the water and boats, not written; alpha-blended. Appended to
// common.wgsl: `frame.view_proj` (local metres) and `frame.viewport`.

struct Segment {
    // Local metres; a.w = width in pixels.
    @location(0) a: vec4<f32>,
    @location(1) b: vec4<f32>,
    @location(2) colour_a: vec4<f32>,
    @location(3) colour_b: vec4<f32>,
}

struct SegmentOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) colour: vec4<f32>,
    // The segment's ends in framebuffer pixels (y down).
    @location(1) @interpolate(flat) ends: vec4<f32>,
    @location(2) @interpolate(flat) half_width: f32,
}

// Framebuffer pixel (y down) of a clip-space point in front of the near plane.
fn to_pixels(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>((ndc.x * 0.5 + 0.5) * frame.viewport.x, (0.5 - ndc.y * 0.5) * frame.viewport.y);
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, s: Segment) -> SegmentOut {
    var out: SegmentOut;
    var ca = frame.view_proj * vec4<f32>(s.a.xyz, 1.0);
    var cb = frame.view_proj * vec4<f32>(s.b.xyz, 1.0);
    // Clip against the near plane (z = 0 in wgpu's clip space): a segment wholly behind it
    // draws nothing; one crossing it is cut where it crosses.
    if ca.z < 0.0 && cb.z < 0.0 {
        out.clip = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        return out;
    }
    if ca.z < 0.0 {
        ca = mix(ca, cb, (0.0 - ca.z) / (cb.z - ca.z) + 1e-4);
    } else if cb.z < 0.0 {
        cb = mix(cb, ca, (0.0 - cb.z) / (ca.z - cb.z) + 1e-4);
    }
    let pa = to_pixels(ca);
    let pb = to_pixels(cb);
    let d = pb - pa;
    let len = length(d);
    let dir = select(vec2<f32>(1.0, 0.0), d / max(len, 1e-6), len > 1e-3);
    let n = vec2<f32>(-dir.y, dir.x);
    // One pixel beyond the half width for the anti-aliased edge.
    let hw = 0.5 * s.a.w + 1.0;
    // Two triangles: corners (end, side).
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(0.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
        vec2<f32>(0.0, -1.0), vec2<f32>(1.0, 1.0), vec2<f32>(0.0, 1.0),
    );
    let corner = corners[vi % 6u];
    let at_b = corner.x > 0.5;
    let end = select(pa - dir * hw, pb + dir * hw, at_b);
    let p = end + n * corner.y * hw;
    let depth = select(ca.z / ca.w, cb.z / cb.w, at_b);
    out.clip = vec4<f32>(
        p.x / frame.viewport.x * 2.0 - 1.0,
        1.0 - p.y / frame.viewport.y * 2.0,
        clamp(depth, 0.0, 1.0),
        1.0,
    );
    out.colour = select(s.colour_a, s.colour_b, at_b);
    out.ends = vec4<f32>(pa, pb);
    out.half_width = 0.5 * s.a.w;
    return out;
}

@fragment
fn fs_main(in: SegmentOut) -> @location(0) vec4<f32> {
    let p = in.clip.xy;
    let a = in.ends.xy;
    let ab = in.ends.zw - a;
    let h = clamp(dot(p - a, ab) / max(dot(ab, ab), 1e-6), 0.0, 1.0);
    let dist = length(p - a - ab * h);
    let coverage = clamp(in.half_width + 0.5 - dist, 0.0, 1.0);
    return vec4<f32>(in.colour.rgb, in.colour.a * coverage);
}
