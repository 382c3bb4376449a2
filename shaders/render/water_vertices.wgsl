// Compute stage of the water pass: displaces every clip-map vertex by the sea and the boats'
// wakes (shaders/ocean/wake.wgsl, bind group 1) once per frame into the vertex buffer the water's
// vertex shader (water_displaced.wgsl) draws, with the slope sums of the sea's longest waves
// that the pixels interpolate (vertex_slope_sums). The wake at a vertex is band limited for its
// level's vertex spacing, as the sea's waves are per level: a level cannot carry a wave
// shorter than π cells (render::clipmap::plan). The CPU bins the wake sources on a grid over
// where they reach (render::wake_bins): a point sums only the sources listed for its bin, in
// two lists: for the height, one list per clip-map level, every source whose cull circle,
// grown by the grid's margin, reaches the bin and whose term band limited for the level's
// spacing is not zero over the whole bin (empty where no vertex of the level can land); for
// the foam, every source whose foam strip reaches the bin.
// Appended to common.wgsl, optics.wgsl and wake.wgsl.

struct WakeGrid {
    // Local (x, z) of the grid's corner, m.
    origin: vec2<f32>,
    // 1 / bin size, 1/m.
    inv_cell: f32,
    // Points within this distance of p may use p's bin, m.
    margin: f32,
    nx: u32,
    nz: u32,
    _pad0: u32,
    _pad1: u32,
    // Vertex spacing of clip-map level l at [l / 4][l % 4], m.
    level_spacing: array<vec4<f32>, 4>,
}

@group(1) @binding(0) var<storage, read> wake_sources: array<WakeSource>;
// Per bin: where its height lists' (first, count) pairs start in wake_index, its lowest level
// l0 | the number of levels from there with a list << 16, then its foam list's first index
// and count. Level l0 + k's height list: first and count at wake_index[head + 2k], [+ 1].
@group(1) @binding(1) var<storage, read> wake_bins: array<vec4<u32>>;
@group(1) @binding(2) var<storage, read> wake_index: array<u32>;
@group(1) @binding(3) var<uniform> wake_grid: WakeGrid;
// The kernel's table of (sin 2πu, cos 2πu) (ocean::turn_table) and its linear, repeating sampler.
@group(1) @binding(6) var turn_table: texture_2d<f32>;
@group(1) @binding(7) var turn_sampler: sampler;

// The lists of the sources that can reach local point p of clip-map level `level`: the
// level's height list (first, count), then the foam list (first, count).
fn wake_bin(p: vec2<f32>, level: u32) -> vec4<u32> {
    let g = (p - wake_grid.origin) * wake_grid.inv_cell;
    if frame.counts.z == 0u || g.x < 0.0 || g.y < 0.0 || g.x >= f32(wake_grid.nx) || g.y >= f32(wake_grid.nz) {
        return vec4<u32>(0u);
    }
    let bin = wake_bins[u32(g.y) * wake_grid.nx + u32(g.x)];
    // None below the bin's lowest level or past its highest (no such vertex lands there).
    let k = level - (bin.y & 0xffffu);
    if k >= (bin.y >> 16u) {
        return vec4<u32>(0u, 0u, bin.zw);
    }
    return vec4<u32>(wake_index[bin.x + 2u * k], wake_index[bin.x + 2u * k + 1u], bin.zw);
}

// The wake at local point p of clip-map level `level`, sampled every `spacing` metres (the
// level's spacing): (height m, ∂w/∂x, ∂w/∂z, foam in [0, 1]), one pass over p's list for
// the level with each source's closed-form gradient, band limited.
fn wake_at(p: vec2<f32>, level: u32, spacing: f32) -> vec4<f32> {
    let bin = wake_bin(p, level);
    var grad = vec3<f32>(0.0);
    // The list's index range, its end formed once; the band limit's edges once.
    let end = bin.x + bin.y;
    let band = wake_band_edges(spacing);
    for (var i = bin.x; i < end; i = i + 1u) {
        let s = wake_sources[wake_index[i]];
        let d = p - s.pos;
        grad += wake_source_height_grad_at(s, d, dot(d, d), band);
    }
    return vec4<f32>(grad, wake_foam_from_density(wake_foam_at(p, bin)));
}

// The foam density at local point p: the sources of its bin's foam list (`bin` from wake_bin).
fn wake_foam_at(p: vec2<f32>, bin: vec4<u32>) -> f32 {
    var density = 0.0;
    for (var i = 0u; i < bin.w; i = i + 1u) {
        density += wake_source_foam(wake_sources[wake_index[bin.z + i]], p);
    }
    return density;
}

// A clip-map vertex as the CPU builds it (render::clipmap::ClipVertex, 16 bytes).
struct ClipVertex {
    rest: vec2<f32>,
    fade: f32,
    level: u32,
}

// What the vertex shader draws (water_displaced.wgsl's VertexIn, 64 bytes): the position and
// rest point, the wake, and the slope sums of the waves the vertex carries to the pixels
// (vertex_slope_sums, as vertex_sums_out packs them).
struct DisplacedVertex {
    pos_rest_x: vec4<f32>,
    rest_z_wake: vec4<f32>,
    sea_sums: vec4<f32>,
    sea_sums_z: vec4<f32>,
}

@group(1) @binding(4) var<storage, read> clip_vertices: array<ClipVertex>;
@group(1) @binding(5) var<storage, read_write> displaced: array<DisplacedVertex>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_displace(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&clip_vertices) {
        return;
    }
    let v = clip_vertices[i];
    var pos = sea_displaced(v.rest, v.fade, v.level);
    // The wake is a height at a world point: where this vertex has gone.
    var wake = vec3<f32>(0.0);
    if frame.counts.z > 0u {
        let w = wake_at(pos.xz, v.level, wake_grid.level_spacing[v.level / 4u][v.level % 4u]);
        pos.y += w.x;
        wake = w.yzw;
    }
    let sums = vertex_sums_out(vertex_slope_sums(v.rest, v.level));
    displaced[i] = DisplacedVertex(vec4<f32>(pos, v.rest.x), vec4<f32>(v.rest.y, wake), sums[0], sums[1]);
}
