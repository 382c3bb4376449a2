// The AR caustic map pass: the area-ratio caustics of the actual wave surface at this frame's
// race time, drawn on the GPU into the caustic map that caustics.wgsl samples (f64 reference:
// crates/effects/src/caustics.rs, area_ratio, which this follows step by step).
//
// A grid over the map's region plus a margin: grid point v is rest point (v mod side,
// v div side). Each point is displaced by the sea, the sunlight is refracted through its
// normal and lands on the table (grid_point). Two ways to add up the landed triangles (light
// folds over in a caustic):
//
// - here, for adapters without compute shaders: the grid drawn as indexed triangles with
//   additive blending. Inside a triangle the footprint — where that light crossed the rest
//   level y = 0 — is an affine function of the map position, so its screen derivatives are
//   the map's exact Jacobian: one texel of table receives the light of |det| of footprint,
//   and the irradiance relative to flat water is that area over the texel's.
// - caustic_scatter.wgsl (appended to this file): compute shaders. A grid's triangles are
//   about a texel each, and a rasteriser pays per triangle (lavapipe: ~0.1 µs, on one thread
//   for a one-tile map): a compute pass finds each triangle's covered texel centres itself.

struct CausticGrid {
    // Local (x, z) of the first rest point, m; step between rest points, m; points per side.
    origin: vec2<f32>,
    step: f32,
    side: u32,
    // The map: local (x, z) of its min corner, its side (m), the table's depth (m).
    region: vec4<f32>,
    // Direction the sunlight travels (downwards, unit); w: the cap of one triangle's irradiance.
    light: vec4<f32>,
    // x: side of one map texel, m; y: texels per side of the map.
    map: vec4<f32>,
}

@group(1) @binding(0) var<uniform> grid: CausticGrid;

struct MapOut {
    @builtin(position) clip: vec4<f32>,
    // Where this vertex's light crossed y = 0, local metres.
    @location(0) foot: vec2<f32>,
}

// Grid point v: where its light crossed y = 0 (foot, local metres) and where it lands on the
// table (uv: 0..1 across the map's region).
struct GridPoint {
    foot: vec2<f32>,
    uv: vec2<f32>,
}

fn grid_point(v: u32) -> GridPoint {
    let rest = grid.origin + vec2<f32>(f32(v % grid.side), f32(v / grid.side)) * grid.step;
    var s = vec3<f32>(rest.x, 0.0, rest.y);
    for (var i = 0u; i < frame.counts.x; i = i + 1u) {
        s += gerstner(waves[i], rest);
    }
    let n = normalize(surface_frame(rest, frame.counts.x, 0.0).up);
    let l = grid.light.xyz;
    // Light goes from air into water: no total internal reflection is possible.
    let t = refract_dir(l, n, N_AIR, N_WATER);
    let dir = select(l, t.xyz, t.w > 0.0);
    let q = s + ((-grid.region.w - s.y) / dir.y) * dir;
    var out: GridPoint;
    out.foot = (s - (s.y / l.y) * l).xz;
    out.uv = (q.xz - grid.region.xy) / grid.region.z;
    return out;
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> MapOut {
    let g = grid_point(v);
    var out: MapOut;
    // Map row 0 is the region's −z edge, the top of the texture.
    out.clip = vec4<f32>(2.0 * g.uv.x - 1.0, 1.0 - 2.0 * g.uv.y, 0.5, 1.0);
    out.foot = g.foot;
    return out;
}

@fragment
fn fs_main(in: MapOut) -> @location(0) vec4<f32> {
    let fx = dpdx(in.foot);
    let fy = dpdy(in.foot);
    let texel = grid.map.x * grid.map.x;
    let ratio = abs(fx.x * fy.y - fx.y * fy.x) / texel;
    return vec4<f32>(min(ratio, grid.light.w), 0.0, 0.0, 1.0);
}
