// The caustic map by compute (appended to caustic_map.wgsl: its grid, grid_point, and the
// f64 reference it follows, effects::caustics::area_ratio and splat_triangle, step by step):
//
// 1. cs_points: every grid point's footprint and landing point, once.
// 2. cs_triangles: every grid cell's two triangles: irradiance I = A_source / A_table
//    (capped at grid.light.w), added to every map texel whose centre the landed triangle
//    covers, with the reference's rule for centres on a shared edge (counted once). Texels
//    add up in fixed point (LIGHT_SCALE) with atomics: integer sums do not depend on the order
//    the triangles arrive in, so the map is the same on every run and every GPU.
// 3. vs_resolve / fs_resolve: the fixed-point sums into the half-float map caustics.wgsl
//    samples with filtering.

// Units of light per 1 (flat water) in the fixed-point sums: 2^16, so one triangle's share
// is rounded by at most 7.6e-6 and a texel can hold 65,535 (over a thousand overlapping
// triangles at the cap of 50).
const LIGHT_SCALE: f32 = 65536.0;

// Per grid point: footprint (local m) and landing point (map texels).
@group(1) @binding(1) var<storage, read_write> points: array<vec4<f32>>;
// Per map texel, row-major from the region's −z edge: light × LIGHT_SCALE.
@group(1) @binding(2) var<storage, read_write> light_sum: array<atomic<u32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_points(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < grid.side * grid.side {
        let g = grid_point(id.x);
        points[id.x] = vec4<f32>(g.foot, g.uv * grid.map.y);
    }
}

fn cross2(a: vec2<f32>, b: vec2<f32>) -> f32 {
    return a.x * b.y - a.y * b.x;
}

// Add irradiance `value` to the texels whose centres landed triangle (a, b, c) covers: grid
// indices ia, ib, ic, counter-clockwise in map texels. An edge is evaluated from its lower
// grid index to its higher, so both triangles sharing it compute the same number (with
// opposite signs), and a centre exactly on it goes to the triangle that runs it that way.
fn splat(ia: u32, ib: u32, ic: u32, value: u32) {
    let n = u32(grid.map.y);
    let a = points[ia].zw;
    let b = points[ib].zw;
    let c = points[ic].zw;
    let lo = min(min(a, b), c);
    let hi = max(max(a, b), c);
    // Texel centres i + 0.5 inside the bounding box, cut to the map before the conversion to
    // integers, so no point far off (or not finite: it fails the test) can make a long loop.
    let finite = all(abs(lo) < vec2<f32>(1e6)) && all(abs(hi) < vec2<f32>(1e6));
    let size = f32(select(0u, n, finite));
    let first = vec2<i32>(clamp(ceil(lo - 0.5), vec2<f32>(0.0), vec2<f32>(size)));
    let last = vec2<i32>(clamp(floor(hi - 0.5), vec2<f32>(-1.0), vec2<f32>(size - 1.0)));
    for (var j = first.y; j <= last.y; j = j + 1) {
        for (var i = first.x; i <= last.x; i = i + 1) {
            let p = vec2<f32>(f32(i) + 0.5, f32(j) + 0.5);
            if covers(ia, a, ib, b, p) && covers(ib, b, ic, c, p) && covers(ic, c, ia, a, p) {
                atomicAdd(&light_sum[u32(j) * n + u32(i)], value);
            }
        }
    }
}

// Is p on the inner (left) side of edge u → v, ties as in splat?
fn covers(iu: u32, u: vec2<f32>, iv: u32, v: vec2<f32>, p: vec2<f32>) -> bool {
    let forward = iu < iv;
    let s = select(v, u, forward);
    let e = select(u, v, forward);
    let side = cross2(e - s, p - s) * select(-1.0, 1.0, forward);
    return side > 0.0 || (side == 0.0 && forward);
}

// One landed triangle of grid indices (i0, i1, i2).
fn triangle(i0: u32, i1: u32, i2: u32) {
    let p0 = points[i0];
    let p1 = points[i1];
    let p2 = points[i2];
    let source = 0.5 * abs(cross2(p1.xy - p0.xy, p2.xy - p0.xy));
    let signed = 0.5 * cross2(p1.zw - p0.zw, p2.zw - p0.zw);
    if signed != 0.0 {
        let texel = grid.map.x * grid.map.x;
        let ratio = min(source / (abs(signed) * texel), grid.light.w);
        let value = u32(round(ratio * LIGHT_SCALE));
        if signed > 0.0 {
            splat(i0, i1, i2, value);
        } else {
            splat(i0, i2, i1, value);
        }
    }
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_triangles(@builtin(global_invocation_id) id: vec3<u32>) {
    let cells = grid.side - 1u;
    if id.x < cells * cells {
        // As area_ratio splits a cell: (k, k+1, k+side+1), (k, k+side+1, k+side).
        let k = (id.x / cells) * grid.side + id.x % cells;
        triangle(k, k + 1u, k + grid.side + 1u);
        triangle(k, k + grid.side + 1u, k + grid.side);
    }
}

// The resolve: the fixed-point sums read back as a storage buffer, with the grid, in a group of
// their own (group 2: the same buffer may not be bound for writing in the same pass).
@group(2) @binding(0) var<storage, read> resolved_sum: array<u32>;
@group(2) @binding(1) var<uniform> resolved_grid: CausticGrid;

struct ResolveOut {
    @builtin(position) clip: vec4<f32>,
}

@vertex
fn vs_resolve(@builtin(vertex_index) i: u32) -> ResolveOut {
    var out: ResolveOut;
    out.clip = vec4<f32>(full_screen_xy(i), 0.5, 1.0);
    return out;
}

@fragment
fn fs_resolve(in: ResolveOut) -> @location(0) vec4<f32> {
    let n = u32(resolved_grid.map.y);
    let texel = vec2<u32>(in.clip.xy);
    let sum = resolved_sum[texel.y * n + texel.x];
    return vec4<f32>(f32(sum) / LIGHT_SCALE, 0.0, 0.0, 1.0);
}
