//! The boats' wake sources binned for the water's compute stage (`shaders/water_vertices.wgsl`),
//! within the device's buffer limits and a memory budget.
//!
//! A point sums only the sources listed in its bin. Bunched fleets (hundreds of boats at a
//! start) list tens of millions of (bin, source) pairs, past any device's storage-buffer limit
//! (128 MiB on most GPUs and in `wgpu::Limits::downlevel_defaults`, a phone's) and past what a
//! frame should upload. So the three per-frame buffers (sources, bins, indices) together stay
//! within [`wake_buffer_cap`]: the smaller of the adapter's `max_storage_buffer_binding_size`,
//! its `max_buffer_size` and [`WAKE_BUFFER_BUDGET_BYTES`]. When the sources in view need more,
//! [`fit`] drops the least visible ones (the smallest peak height,
//! `ocean::wake::source_peak_bound`) until the rest fit, and states the error: the height
//! anywhere errs by at most the sum of the dropped sources' peak bounds, and the wake foam by
//! at most the sum of their peak densities (1 − e^{−Σ} is 1-Lipschitz).

use ocean::wake::{GpuWakeFrame, GpuWakeSource, foam_radius2, inner_radius2, source_peak_bound};
use serde::Serialize;

use crate::wake_spacing::{MAX_LEVELS, SampleSpacing};

/// Memory budget of one frame's wake buffers (sources, bins and indices together): 64 MiB,
/// half of the common storage-binding limit (`downlevel_defaults`: 128 MiB), about 16 million
/// (bin, source) pairs. The sample race's busiest frame (t = 600 s, 2,033 sources, the budget
/// model's view) needs 3.4 MB at the OPPO A54's screen and 4.5 MB at the Pixel 2 XL's
/// (`regatta bench --only budget-model`, memory column); phones get less through the quality
/// tiers' source budgets (`Renderer::set_wake_source_budget`), and a byte budget can be set
/// (`Renderer::set_wake_buffer_budget`).
pub const WAKE_BUFFER_BUDGET_BYTES: u64 = 64 << 20;

/// Bins per side of the wake grid and their least side, m.
pub(crate) const WAKE_BINS: u32 = 128;
pub(crate) const WAKE_MIN_CELL_M: f32 = 2.0;

/// How far (m) around a bin its lists reach, at least: the gradient is closed-form (a vertex
/// evaluates every term at the point it looks its bin up with), so the margin covers only the
/// rounding of that look-up and of a term's r² against its radii (see [`lookup_margin`]).
pub(crate) const WAKE_MARGIN_M: f32 = 0.01;

/// The margin for a grid inside [−half, half]²: `wake_bin` finds bin ⌊(p − origin)·inv_cell⌋
/// with two correctly rounded f32 operations on `inv_cell`, itself 1/cell rounded (WGSL's
/// `-` and `*` are correctly rounded), so the point found in a bin lies within
/// 3·2⁻²⁴ · |p − origin| ≤ 1.8·10⁻⁷ · 2·half of its square; r² = |p − pos|² in f32 errs by
/// a few ulps, a relative 10⁻⁶ of the distance. 10⁻⁶ · half, and at least 1 cm, covers both.
pub(crate) fn lookup_margin(half: f32) -> f32 {
    WAKE_MARGIN_M.max(1e-6 * half)
}

/// Bytes of one source in the buffer, one bin entry and one index.
const SOURCE_BYTES: u64 = size_of::<GpuWakeSource>() as u64;
const BIN_BYTES: u64 = 16;
const INDEX_BYTES: u64 = 4;

/// The cap on one frame's wake buffers, bytes: `budget` within the device's limits for one
/// storage binding and one buffer.
pub(crate) fn wake_buffer_cap(limits: &wgpu::Limits, budget: u64) -> u64 {
    budget
        .min(limits.max_storage_buffer_binding_size)
        .min(limits.max_buffer_size)
}

/// What the budget left out of a frame's wakes.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct WakeDrop {
    /// Sources in reach of the view left out to fit the cap.
    pub dropped: usize,
    /// Bound of the wake height error this causes anywhere, m (Σ of their peak bounds).
    pub height_bound_m: f64,
    /// Bound of the wake foam error (Σ of their peak foam densities).
    pub foam_bound: f64,
    /// The cap the frame's wake buffers fit in, bytes.
    pub cap_bytes: u64,
}

/// `WakeGrid` of `shaders/water_vertices.wgsl` (96 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WakeGrid {
    pub origin: [f32; 2],
    pub inv_cell: f32,
    pub margin: f32,
    pub nx: u32,
    pub nz: u32,
    pub _pad: [u32; 2],
    /// Vertex spacing of each clip-map level (16 at most), m: the wake's band limit there.
    pub level_spacing: [[f32; 4]; 4],
}

/// The wake sources binned on a grid: a point looks up its bin and sums only the sources
/// listed there for its clip-map level. Every source whose cull circle, grown by `margin`,
/// touches a bin is listed in the bin's list for level l, unless the whole bin (grown by
/// `margin`) lies inside the source's inner radius for level l's spacing
/// (`ocean::wake::inner_radius2`: its Gaussian cut-off or the band limit, where the term is
/// zero), or no vertex of level l can land in the bin. So a point within `margin` of a bin's
/// points, of a level whose vertices can land there, misses no source that adds to it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WakeBins {
    pub grid: WakeGrid,
    /// Per bin, row-major (x fastest): where its height lists' heads start in `indices`, its
    /// lowest level l₀ and how many levels from there have a list (l₀ | n << 16: the levels
    /// whose vertices can land in the bin, l₀ to its highest; n = 0 where none does), then the
    /// first index and count of its foam list (the sources whose foam strip reaches it: few
    /// do, so a point pays a foam exponential only for those). Level l₀ + k's height list
    /// (the sources whose height term can be non-zero in the bin at the level's spacing) has
    /// its first index and count at `indices[head + 2k]` and `indices[head + 2k + 1]`.
    pub bins: Vec<[u32; 4]>,
    pub indices: Vec<u32>,
}

/// The grid's geometry: corner, bin size and bins per side, the levels whose vertices can land
/// in each bin (bit l: level l; 0: no vertex lands there) and each level's spacing.
#[derive(Debug, Clone, PartialEq)]
struct Layout {
    lo: [f32; 2],
    cell: f32,
    nx: u32,
    nz: u32,
    margin: f32,
    levels_in: Vec<u32>,
    /// Per row of bins and list, the runs of columns whose bins have that list: the binning
    /// lists a source in whole runs.
    slot_runs: runs::SlotRuns,
    /// Each level's vertex spacing, m: one height list per level in each bin.
    spacing: Vec<f32>,
    level_spacing: [[f32; 4]; 4],
}

impl Layout {
    /// Bins of at least [`WAKE_MIN_CELL_M`], at most `max_bins` per side, over [lo, hi],
    /// sampled as `spacing` says.
    fn new(
        lo: [f32; 2],
        hi: [f32; 2],
        max_bins: u32,
        margin: f32,
        spacing: &SampleSpacing,
    ) -> Layout {
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1.0);
        let cell = (size / max_bins as f32).max(WAKE_MIN_CELL_M);
        let nx = (((hi[0] - lo[0]) / cell).ceil() as u32).clamp(1, max_bins);
        let nz = (((hi[1] - lo[1]) / cell).ceil() as u32).clamp(1, max_bins);
        let levels_in = if spacing.vertices.is_empty() {
            (0..nz)
                .flat_map(|j| (0..nx).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let a = [lo[0] + i as f32 * cell, lo[1] + j as f32 * cell];
                    spacing.box_levels_in(a, [a[0] + cell, a[1] + cell], margin)
                })
                .collect()
        } else {
            vertex_levels(lo, cell, [nx, nz], margin, spacing)
        };
        let levels = spacing.levels.len().clamp(1, MAX_LEVELS);
        // A level the spacing does not know has no list (a vertex never carries one).
        let known = u32::MAX >> (32 - levels);
        let levels_in: Vec<u32> = levels_in.into_iter().map(|m| m & known).collect();
        let slot_runs = runs::SlotRuns::of(&levels_in, nx as usize, levels);
        Layout {
            lo,
            cell,
            nx,
            nz,
            margin,
            levels_in,
            slot_runs,
            spacing: (0..levels)
                .map(|l| spacing.levels.get(l).map_or(0.0, |b| b.spacing))
                .collect(),
            level_spacing: spacing.per_level(),
        }
    }

    /// Height lists per bin: one per level.
    fn slots(&self) -> u32 {
        self.spacing.len() as u32
    }

    /// The bins [i0, i1] × [j0, j1] whose lists hold `s` (its cull circle grown by the
    /// margin touches them), or none.
    fn span(&self, s: &GpuWakeSource) -> Option<[u32; 4]> {
        let r = reach_r2(s).sqrt() + self.margin;
        let (x0, x1) = (s.pos[0] - r, s.pos[0] + r);
        let (z0, z1) = (s.pos[1] - r, s.pos[1] + r);
        let (lo, cell) = (self.lo, self.cell);
        if x1 < lo[0]
            || z1 < lo[1]
            || x0 > lo[0] + self.nx as f32 * cell
            || z0 > lo[1] + self.nz as f32 * cell
        {
            return None;
        }
        let bin_of =
            |v: f32, o: f32, n: u32| ((v - o) / cell).floor().clamp(0.0, n as f32 - 1.0) as u32;
        Some([
            bin_of(x0, lo[0], self.nx),
            bin_of(x1, lo[0], self.nx),
            bin_of(z0, lo[1], self.nz),
            bin_of(z1, lo[1], self.nz),
        ])
    }

    /// Lists per bin: its foam list, then one height list per level.
    fn lists_per_bin(&self) -> u32 {
        self.slots() + 1
    }

    /// The distances (m) from coordinate `v` to bin `k`'s interval along the axis whose grid
    /// starts at `lo`: the nearest (0 inside) and the farthest grown by the margin.
    fn distances(&self, v: f64, lo: f32, k: u32) -> [f64; 2] {
        let cell = f64::from(self.cell);
        let a = f64::from(lo) + f64::from(k) * cell;
        let near = (a - v).max(v - (a + cell)).max(0.0);
        let far = (v - a).abs().max((a + cell - v).abs()) + f64::from(self.margin);
        [near, far]
    }

    /// The grid as the shader reads it.
    fn grid(&self) -> WakeGrid {
        WakeGrid {
            origin: self.lo,
            inv_cell: 1.0 / self.cell,
            margin: self.margin,
            nx: self.nx,
            nz: self.nz,
            _pad: [0; 2],
            level_spacing: self.level_spacing,
        }
    }
}

/// Per bin of the grid with corner `lo`, side `cell` and `n` bins per side, the levels whose
/// vertices can land in it: a vertex lands within `spacing.displacement` of its rest point,
/// and its bin is looked up within `margin` of where it lands.
fn vertex_levels(
    lo: [f32; 2],
    cell: f32,
    n: [u32; 2],
    margin: f32,
    spacing: &SampleSpacing,
) -> Vec<u32> {
    let mut levels_in = vec![0u32; (n[0] * n[1]) as usize];
    let reach = f64::from(spacing.displacement) + f64::from(margin);
    let (cell, last) = (f64::from(cell), n.map(|n| f64::from(n) - 1.0));
    for &(rest, level) in &spacing.vertices {
        let bit = 1 << level.min(MAX_LEVELS as u32 - 1);
        let range = |a: usize| {
            let v = f64::from(rest[a]) - f64::from(lo[a]);
            let (b0, b1) = (((v - reach) / cell).floor(), ((v + reach) / cell).floor());
            (b1 >= 0.0 && b0 <= last[a]).then(|| (b0.max(0.0) as u32, b1.min(last[a]) as u32))
        };
        let (Some((i0, i1)), Some((j0, j1))) = (range(0), range(1)) else {
            continue;
        };
        for j in j0..=j1 {
            for i in i0..=i1 {
                levels_in[(j * n[0] + i) as usize] |= bit;
            }
        }
    }
    levels_in
}

/// The squared radius within which a source adds height or foam, m².
fn reach_r2(s: &GpuWakeSource) -> f32 {
    s.cull_r2.max(foam_radius2(s)).max(0.0)
}

/// The rectangle the sources' cull circles (grown by `margin`) cover, clipped to the square
/// [−half, half]²; none when nothing reaches the square.
fn reach(sources: &[GpuWakeSource], half: f32, margin: f32) -> Option<([f32; 2], [f32; 2])> {
    let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
    for s in sources {
        let r = reach_r2(s).sqrt() + margin;
        for a in 0..2 {
            lo[a] = lo[a].min(s.pos[a] - r);
            hi[a] = hi[a].max(s.pos[a] + r);
        }
    }
    let (lo, hi) = (lo.map(|v| v.max(-half)), hi.map(|v| v.min(half)));
    (lo[0] < hi[0] && lo[1] < hi[1]).then_some((lo, hi))
}

impl WakeBins {
    /// Bin `sources` over the rectangle their cull circles (grown by `margin`) cover, clipped
    /// to the square [−half, half]² (local metres).
    #[cfg(any(test, feature = "binning-reference"))]
    pub(crate) fn over_reach(
        sources: &[GpuWakeSource],
        half: f32,
        max_bins: u32,
        margin: f32,
        spacing: &SampleSpacing,
    ) -> WakeBins {
        match reach(sources, half, margin) {
            Some((lo, hi)) => WakeBins::sampled(sources, lo, hi, max_bins, margin, spacing),
            // Nothing reaches the square: one empty bin.
            None => WakeBins::sampled(&[], [-half, -half], [half, half], 1, margin, spacing),
        }
    }

    /// Bin `sources` over the local rectangle [lo, hi] with at most `max_bins` per side, for
    /// points evaluated without a band limit.
    pub fn new(
        sources: &[GpuWakeSource],
        lo: [f32; 2],
        hi: [f32; 2],
        max_bins: u32,
        margin: f32,
    ) -> WakeBins {
        WakeBins::sampled(
            sources,
            lo,
            hi,
            max_bins,
            margin,
            &SampleSpacing::uniform(0.0),
        )
    }

    /// [`WakeBins::new`] for points sampled as `spacing` says (each band limited for its
    /// level's spacing).
    pub fn sampled(
        sources: &[GpuWakeSource],
        lo: [f32; 2],
        hi: [f32; 2],
        max_bins: u32,
        margin: f32,
        spacing: &SampleSpacing,
    ) -> WakeBins {
        WakeBins::on(sources, &Layout::new(lo, hi, max_bins, margin, spacing))
    }

    fn on(sources: &[GpuWakeSource], layout: &Layout) -> WakeBins {
        WakeBinner::default().bin(sources, layout)
    }

    /// The sources whose height local point `p` of clip-map level `level` sums: its bin's
    /// height list for the level, or none outside the grid, exactly as `wake_bin` in
    /// `shaders/render/water_vertices.wgsl` looks it up (f32).
    pub fn listed_at(&self, p: [f32; 2], level: u32) -> &[u32] {
        self.bin_at(p, level).map_or(&[], |[first, count, _, _]| {
            &self.indices[first as usize..(first + count) as usize]
        })
    }

    /// The sources whose foam local point `p` sums: its bin's foam list (one for every level).
    pub fn foam_listed_at(&self, p: [f32; 2]) -> &[u32] {
        self.bin_at(p, 0).map_or(&[], |[_, _, first, count]| {
            &self.indices[first as usize..(first + count) as usize]
        })
    }

    /// The lists of local point `p` of clip-map level `level` as the shader finds them
    /// (height first and count, foam first and count), or none outside the grid.
    pub fn bin_at(&self, p: [f32; 2], level: u32) -> Option<[u32; 4]> {
        let g = self.grid;
        let (x, z) = (
            (p[0] - g.origin[0]) * g.inv_cell,
            (p[1] - g.origin[1]) * g.inv_cell,
        );
        if x < 0.0 || z < 0.0 || x >= g.nx as f32 || z >= g.nz as f32 {
            return None;
        }
        let [head, levels, foam_first, foam_count] =
            self.bins[(z as u32 * g.nx + x as u32) as usize];
        // The bin's pair for `level` (none below its lowest level or past its highest).
        let k = level.wrapping_sub(levels & 0xffff);
        if k >= levels >> 16 {
            return Some([0, 0, foam_first, foam_count]);
        }
        let at = (head + 2 * k) as usize;
        Some([
            self.indices[at],
            self.indices[at + 1],
            foam_first,
            foam_count,
        ])
    }

    /// Bytes of the three buffers with `sources` sources (each at least one entry: the
    /// buffers are never empty).
    pub fn bytes(&self, sources: usize) -> u64 {
        binner::buffer_bytes(sources, self.bins.len(), self.indices.len())
    }
}

/// Bin `wakes.sources` over where they reach inside [−half, half]², the three buffers within
/// `cap` bytes and at most `max_sources` sources (a quality tier's wake source budget): when
/// they would need more, the sources with the smallest peak height are removed from
/// `wakes.sources` until the rest fit (module docs), and the record says how many and the
/// error bound. A renderer binning every frame keeps a [`WakeBinner`] instead, which keeps
/// its memory.
pub fn fit(
    wakes: &mut GpuWakeFrame,
    half: f32,
    cap: u64,
    max_sources: usize,
    spacing: &SampleSpacing,
) -> (WakeBins, WakeDrop) {
    WakeBinner::default().fit(wakes, half, cap, max_sources, spacing)
}

mod binner;
mod listing;
mod runs;
pub use binner::WakeBinner;

#[cfg(any(test, feature = "binning-reference"))]
#[doc(hidden)]
pub mod reference;
#[cfg(test)]
mod tests;
