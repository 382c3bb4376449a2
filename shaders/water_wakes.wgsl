// Wake hook of the water pass, with wakes: the boats' wakes of shaders/wake.wgsl (bind group 1).
// The CPU bins the sources on a grid over the view (render::passes::water::WakeBins): a point
// sums only the sources listed for its bin, which holds every source whose cull circle, grown
// by the grid's margin, reaches the bin. Appended after wake.wgsl and before water.wgsl.

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
}

@group(1) @binding(0) var<storage, read> wake_sources: array<WakeSource>;
// Per bin: (first index into wake_index, count).
@group(1) @binding(1) var<storage, read> wake_bins: array<vec2<u32>>;
@group(1) @binding(2) var<storage, read> wake_index: array<u32>;
@group(1) @binding(3) var<uniform> wake_grid: WakeGrid;

// The (first, count) of the sources that can reach local point p.
fn wake_bin(p: vec2<f32>) -> vec2<u32> {
    let g = (p - wake_grid.origin) * wake_grid.inv_cell;
    if frame.counts.z == 0u || g.x < 0.0 || g.y < 0.0 || g.x >= f32(wake_grid.nx) || g.y >= f32(wake_grid.nz) {
        return vec2<u32>(0u, 0u);
    }
    return wake_bins[u32(g.y) * wake_grid.nx + u32(g.x)];
}

// The wake at local point p: (height m, ∂w/∂x, ∂w/∂z, foam in [0, 1]), one pass over p's bin
// with each source's closed-form gradient.
fn wake_at(p: vec2<f32>) -> vec4<f32> {
    let bin = wake_bin(p);
    var h = vec3<f32>(0.0);
    var f = 0.0;
    for (var i = 0u; i < bin.y; i = i + 1u) {
        let s = wake_sources[wake_index[bin.x + i]];
        h += wake_source_height_grad(s, p);
        f += wake_source_foam(s, p);
    }
    return vec4<f32>(h, wake_foam_from_density(f));
}
