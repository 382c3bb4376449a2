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
        let levels_in = levels_in.into_iter().map(|m| m & known).collect();
        Layout {
            lo,
            cell,
            nx,
            nz,
            margin,
            levels_in,
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

    /// Which of bin (i, j)'s lists hold `s`, whose cull circle and foam strip reach `radii`
    /// (m, grown by the margin): the foam list when its foam strip reaches the bin's square;
    /// level l's height list when level l's vertices can land in the bin and its cull circle
    /// reaches the square with some point of the square outside the source's inner radius
    /// for level l's spacing. (A bin in a corner of the circle's bounding square is out of
    /// reach of every point of the circle, and listing it would only add loop turns to the
    /// bin's points.)
    fn reaches(&self, s: &GpuWakeSource, radii: &Radii, i: u32, j: u32) -> Listing {
        let none = Listing {
            heights: 0,
            foam: false,
        };
        let levels_in = self.levels_in[(j * self.nx + i) as usize];
        if levels_in == 0 {
            return none;
        }
        let cell = f64::from(self.cell);
        let gap = |v: f32, lo: f32, k: u32| {
            let a = f64::from(lo) + f64::from(k) * cell;
            (a - f64::from(v)).max(f64::from(v) - (a + cell)).max(0.0)
        };
        let (dx, dz) = (gap(s.pos[0], self.lo[0], i), gap(s.pos[1], self.lo[1], j));
        let near2 = dx * dx + dz * dz;
        let foam = near2 <= radii.foam * radii.foam;
        if near2 > radii.cull * radii.cull {
            return Listing { foam, ..none };
        }
        // The height term: the bin's farthest point from the source (grown by the margin)
        // must lie outside the source's inner radius for the level's spacing.
        let far = |v: f32, lo: f32, k: u32| {
            let a = f64::from(lo) + f64::from(k) * cell;
            (f64::from(v) - a)
                .abs()
                .max((a + cell - f64::from(v)).abs())
                + f64::from(self.margin)
        };
        let (fx, fz) = (far(s.pos[0], self.lo[0], i), far(s.pos[1], self.lo[1], j));
        let far2 = fx * fx + fz * fz;
        let heights = (0..self.slots())
            .filter(|&l| levels_in & (1 << l) != 0 && far2 >= radii.inner2[l as usize])
            .fold(0, |m, l| m | 1 << l);
        Listing { heights, foam }
    }

    /// The bins that list `s` (row-major indices) and in which of their lists.
    fn bins_of<'a>(&'a self, s: &'a GpuWakeSource) -> impl Iterator<Item = (u32, Listing)> + 'a {
        let [i0, i1, j0, j1] = self.span(s).unwrap_or([1, 0, 1, 0]);
        // Once per source, not per bin of its span.
        let margin = f64::from(self.margin);
        let mut inner2 = [0.0; MAX_LEVELS];
        for (r2, &spacing) in inner2.iter_mut().zip(&self.spacing) {
            *r2 = f64::from(inner_radius2(s, spacing));
        }
        let radii = Radii {
            cull: f64::from(s.cull_r2.max(0.0)).sqrt() + margin,
            foam: f64::from(foam_radius2(s)).sqrt() + margin,
            inner2,
        };
        (j0..=j1).flat_map(move |j| {
            (i0..=i1)
                .map(move |i| (j * self.nx + i, self.reaches(s, &radii, i, j)))
                .filter(|(_, l)| l.heights != 0 || l.foam)
        })
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

/// The lists of one bin that hold a source.
#[derive(Debug, Clone, Copy)]
struct Listing {
    /// Bit l: its height term can be non-zero at a point of the bin sampled at level l's
    /// spacing, and level l's vertices can land in the bin.
    heights: u32,
    /// Its foam strip reaches the bin.
    foam: bool,
}

/// How far a source's cull circle and foam strip reach, grown by the grid's margin, m, and
/// its inner radius for each level's spacing, m².
#[derive(Debug, Clone, Copy)]
struct Radii {
    cull: f64,
    foam: f64,
    inner2: [f64; MAX_LEVELS],
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
        WakeBins::counted(sources, layout).0
    }

    /// [`WakeBins::on`], and how many list entries each source takes.
    fn counted(sources: &[GpuWakeSource], layout: &Layout) -> (WakeBins, Vec<u64>) {
        let mut entries = vec![0u64; sources.len()];
        let (nx, nz, slots) = (layout.nx, layout.nz, layout.slots());
        let mut heights: Vec<Vec<u32>> = vec![Vec::new(); (nx * nz * slots) as usize];
        let mut foams: Vec<Vec<u32>> = vec![Vec::new(); (nx * nz) as usize];
        for (k, s) in sources.iter().enumerate() {
            for (b, l) in layout.bins_of(s) {
                let mut levels = l.heights;
                while levels != 0 {
                    let level = levels.trailing_zeros();
                    heights[(b * slots + level) as usize].push(k as u32);
                    levels &= levels - 1;
                }
                if l.foam {
                    foams[b as usize].push(k as u32);
                }
                entries[k] += u64::from(l.heights.count_ones()) + u64::from(l.foam);
            }
        }
        let mut bins = Vec::with_capacity(foams.len());
        let mut indices = Vec::new();
        for ((f, levels), &mask) in foams
            .iter()
            .zip(heights.chunks(slots as usize))
            .zip(&layout.levels_in)
        {
            let foam_first = indices.len() as u32;
            indices.extend_from_slice(f);
            let head = indices.len() as u32;
            // The levels from the lowest to the highest with a list that is not empty (each
            // level that lands here; an empty list and none read alike): their (first, count)
            // pairs, then their lists.
            let mut listed =
                (0..slots).filter(|&l| mask & 1 << l != 0 && !levels[l as usize].is_empty());
            let Some(lowest) = listed.clone().next() else {
                bins.push([head, 0, foam_first, f.len() as u32]);
                continue;
            };
            let highest = listed.next_back().unwrap_or(lowest);
            let span = highest - lowest + 1;
            indices.resize(indices.len() + 2 * span as usize, 0);
            for (k, h) in levels[lowest as usize..=highest as usize]
                .iter()
                .enumerate()
            {
                let at = head as usize + 2 * k;
                indices[at] = indices.len() as u32;
                indices[at + 1] = h.len() as u32;
                indices.extend_from_slice(h);
            }
            bins.push([head, lowest | span << 16, foam_first, f.len() as u32]);
        }
        let bins = WakeBins {
            grid: WakeGrid {
                origin: layout.lo,
                inv_cell: 1.0 / layout.cell,
                margin: layout.margin,
                nx,
                nz,
                _pad: [0; 2],
                level_spacing: layout.level_spacing,
            },
            bins,
            indices,
        };
        (bins, entries)
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
        SOURCE_BYTES * sources.max(1) as u64
            + BIN_BYTES * self.bins.len() as u64
            + INDEX_BYTES * self.indices.len().max(1) as u64
    }
}

/// Bin `wakes.sources` over where they reach inside [−half, half]², the three buffers within
/// `cap` bytes and at most `max_sources` sources (a quality tier's wake source budget): when
/// they would need more, the sources with the smallest peak height are removed from
/// `wakes.sources` until the rest fit (module docs), and the record says how many and the
/// error bound.
pub fn fit(
    wakes: &mut GpuWakeFrame,
    half: f32,
    cap: u64,
    max_sources: usize,
    spacing: &SampleSpacing,
) -> (WakeBins, WakeDrop) {
    let mut drop = WakeDrop {
        cap_bytes: cap,
        ..Default::default()
    };
    let margin = lookup_margin(half);
    let Some((lo, hi)) = reach(&wakes.sources, half, margin) else {
        let bins = WakeBins::over_reach(&[], half, WAKE_BINS, margin, spacing);
        return (bins, drop);
    };
    // The grid stays the one of all sources in reach, so every count below is exact.
    let layout = Layout::new(lo, hi, WAKE_BINS, margin, spacing);
    let (all, listed) = WakeBins::counted(&wakes.sources, &layout);
    let mut bytes = all.bytes(wakes.sources.len());
    let mut kept = wakes.sources.len();
    if bytes <= cap && kept <= max_sources {
        return (all, drop);
    }
    let peak: Vec<f64> = wakes.sources.iter().map(source_peak_bound).collect();
    let mut order: Vec<usize> = (0..wakes.sources.len()).collect();
    order.sort_by(|&a, &b| peak[a].total_cmp(&peak[b]).then(a.cmp(&b)));
    let mut keep = vec![true; wakes.sources.len()];
    for k in order {
        if bytes <= cap && kept <= max_sources {
            break;
        }
        keep[k] = false;
        kept -= 1;
        bytes -= SOURCE_BYTES + INDEX_BYTES * listed[k];
        drop.dropped += 1;
        drop.height_bound_m += peak[k];
        drop.foam_bound += f64::from(wakes.sources[k].foam);
    }
    let mut kept = keep.into_iter();
    wakes.sources.retain(|_| kept.next().unwrap_or(true));
    (WakeBins::on(&wakes.sources, &layout), drop)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_source_reaching_a_point_is_in_its_bin() {
        // Sources scattered over a square, each reaching a different radius.
        let sources: Vec<GpuWakeSource> = (0..300)
            .map(|k| {
                let f = k as f32;
                GpuWakeSource {
                    pos: [(f * 37.3) % 400.0 - 200.0, (f * 91.7) % 400.0 - 200.0],
                    cull_r2: (1.0 + (f * 13.1) % 30.0).powi(2),
                    ..Default::default()
                }
            })
            .collect();
        let bins = WakeBins::new(&sources, [-250.0, -250.0], [250.0, 250.0], 32, 2.0);
        let mut listed = 0usize;
        for a in 0..97 {
            for b in 0..89 {
                let p = [-249.0 + a as f32 * 5.13, -249.0 + b as f32 * 5.59];
                let list = bins.listed_at(p, 0);
                listed += list.len();
                // Any stencil point within the margin: every source whose cull circle holds
                // it is listed.
                for q in [p, [p[0] + 1.9, p[1]], [p[0], p[1] - 1.9]] {
                    for (k, s) in sources.iter().enumerate() {
                        let d2 = (q[0] - s.pos[0]).powi(2) + (q[1] - s.pos[1]).powi(2);
                        if d2 <= s.cull_r2 {
                            assert!(list.contains(&(k as u32)), "source {k} missing at {q:?}");
                        }
                    }
                }
            }
        }
        // And binning saves work: far fewer than all sources per point on average.
        assert!(listed < 97 * 89 * sources.len() / 5, "{listed}");
    }

    /// A bin lists a source exactly when the source's cull circle grown by the margin
    /// reaches some point of the bin's square (the square's nearest point to the source, by
    /// clamping, within the grown radius), so a large circle is listed in about its Minkowski
    /// sum with a bin over a bin's area, (πr² + 4rc + c²)/c², not its bounding square's
    /// (2r/c + 1)² bins: π/4 of them and less.
    #[test]
    fn a_bin_lists_the_sources_whose_circle_reaches_it_and_no_other() {
        // 2 m bins over [−100, 100]²; a source at the origin reaching 39.5 m (+ 0.5 margin).
        let big = GpuWakeSource {
            pos: [0.0, 0.0],
            cull_r2: 39.5 * 39.5,
            ..Default::default()
        };
        let mut sources = vec![big];
        sources.extend((0..60).map(|k| {
            let f = k as f32;
            GpuWakeSource {
                pos: [(f * 37.3) % 180.0 - 90.0, (f * 91.7) % 180.0 - 90.0],
                cull_r2: (0.3 + (f * 13.1) % 25.0).powi(2),
                ..Default::default()
            }
        }));
        let bins = WakeBins::new(&sources, [-100.0; 2], [100.0; 2], 100, 0.5);
        let g = bins.grid;
        let cell = 1.0 / f64::from(g.inv_cell);
        assert!((cell - 2.0).abs() < 1e-6, "{g:?}");
        let mut big_bins = 0usize;
        for j in 0..g.nz {
            for i in 0..g.nx {
                let (x0, z0) = (
                    f64::from(g.origin[0]) + f64::from(i) * cell,
                    f64::from(g.origin[1]) + f64::from(j) * cell,
                );
                let middle = [(x0 + 0.5 * cell) as f32, (z0 + 0.5 * cell) as f32];
                let list = bins.listed_at(middle, 0);
                for (k, s) in sources.iter().enumerate() {
                    let (px, pz) = (f64::from(s.pos[0]), f64::from(s.pos[1]));
                    let near = [px.clamp(x0, x0 + cell), pz.clamp(z0, z0 + cell)];
                    let d = (near[0] - px).hypot(near[1] - pz);
                    let r = f64::from(s.cull_r2).sqrt() + 0.5;
                    let listed = list.contains(&(k as u32));
                    if d <= r - 1e-4 {
                        assert!(listed, "source {k} reaches bin ({i}, {j}) at {d} m < {r}");
                    }
                    if d > r + 1e-4 {
                        assert!(!listed, "source {k} listed in bin ({i}, {j}) {d} m away");
                    }
                    if k == 0 && listed {
                        big_bins += 1;
                    }
                }
            }
        }
        let (r, c) = (40.0, 2.0);
        let minkowski = (std::f64::consts::PI * r * r + 4.0 * r * c + c * c) / (c * c);
        assert!(
            (big_bins as f64 - minkowski).abs() < 0.03 * minkowski,
            "{big_bins} bins against {minkowski:.0}"
        );
        let square = (2.0 * r / c + 1.0).powi(2);
        assert!((big_bins as f64) < 0.82 * square, "{big_bins} of {square}");
    }

    fn listed_at(bins: &WakeBins, p: [f32; 2]) -> &[u32] {
        bins.listed_at(p, 0)
    }

    #[test]
    fn bins_cover_only_where_the_sources_reach() {
        // A fleet's wake 120 m across, 900 m from the origin of a 4 km clip-map.
        let sources: Vec<GpuWakeSource> = (0..200)
            .map(|k| {
                let f = k as f32;
                GpuWakeSource {
                    pos: [900.0 + (f * 37.3) % 120.0, -300.0 + (f * 91.7) % 80.0],
                    cull_r2: (2.0 + (f * 13.1) % 20.0).powi(2),
                    ..Default::default()
                }
            })
            .collect();
        let bins = WakeBins::over_reach(&sources, 2000.0, 128, 0.5, &SampleSpacing::uniform(0.0));
        let whole = WakeBins::new(&sources, [-2000.0; 2], [2000.0; 2], 128, 0.5);
        // The grid spans the reach (≤ 164 m) in the smallest bins (2 m), not the whole
        // square's 31 m bins.
        let g = bins.grid;
        let cell = 1.0 / g.inv_cell;
        assert!(cell <= 2.0 + 1e-3, "{g:?}");
        assert!(
            g.nx as f32 * cell <= 166.0 && g.nz as f32 * cell <= 166.0,
            "{g:?}"
        );
        let (mut fine, mut coarse) = (0usize, 0usize);
        for a in 0..200 {
            for b in 0..150 {
                let p = [860.0 + a as f32 * 1.01, -340.0 + b as f32 * 1.07];
                let list = listed_at(&bins, p);
                for (k, s) in sources.iter().enumerate() {
                    let d2 = (p[0] - s.pos[0]).powi(2) + (p[1] - s.pos[1]).powi(2);
                    if d2 <= s.cull_r2 {
                        assert!(list.contains(&(k as u32)), "source {k} missing at {p:?}");
                    }
                }
                fine += list.len();
                coarse += listed_at(&whole, p).len();
            }
        }
        // Far fewer sources to loop over per point than with bins over the whole square.
        assert!(fine * 3 < coarse, "{fine} vs {coarse}");
        assert!(listed_at(&bins, [0.0, 0.0]).is_empty());
        // No source in reach: an empty grid.
        let none = WakeBins::over_reach(&sources, 100.0, 128, 0.5, &SampleSpacing::uniform(0.0));
        assert!(none.indices.is_empty() && listed_at(&none, [0.0, 0.0]).is_empty());
    }

    /// 600 sources bunched in 100 m, of growing strength (source k: 1e-3 × (k + 1)).
    fn bunched_fleet() -> Vec<GpuWakeSource> {
        (0..600)
            .map(|k| {
                let f = k as f32;
                GpuWakeSource {
                    pos: [(f * 37.3) % 100.0 - 50.0, (f * 91.7) % 100.0 - 50.0],
                    dx: [1.0, 0.0],
                    q: 50.0,
                    strength: 1e-3 * (1.0 + f),
                    gauss: 0.25,
                    cull_r2: 30.0 * 30.0,
                    foam: 0.01,
                    foam_w2: 1.0,
                    _pad: [0.0; 2],
                }
            })
            .collect()
    }

    #[test]
    fn a_source_budget_keeps_exactly_that_many_of_the_most_visible() {
        // A quality tier's wake source budget: 150 of 600 kept, well within the byte cap.
        let mut frame = GpuWakeFrame {
            sources: bunched_fleet(),
            ..Default::default()
        };
        let (_, drop) = fit(
            &mut frame,
            2000.0,
            u64::MAX,
            150,
            &SampleSpacing::uniform(0.0),
        );
        assert_eq!((frame.sources.len(), drop.dropped), (150, 450));
        // The weakest 450 went: the kept ones are sources 450..600.
        let weakest_kept = frame
            .sources
            .iter()
            .map(|s| s.strength)
            .fold(f32::MAX, f32::min);
        assert_eq!(weakest_kept, 1e-3 * 451.0);
        assert!(drop.height_bound_m > 0.0);
        // A budget above the count drops nothing.
        let mut all = GpuWakeFrame {
            sources: bunched_fleet(),
            ..Default::default()
        };
        assert_eq!(
            fit(
                &mut all,
                2000.0,
                u64::MAX,
                600,
                &SampleSpacing::uniform(0.0)
            )
            .1
            .dropped,
            0
        );
    }

    #[test]
    fn a_fleet_over_the_cap_drops_its_least_visible_sources_and_states_the_bound() {
        // The bunched fleet: far more (bin, source) pairs than a 256 KiB cap holds.
        let sources = bunched_fleet();
        let mut all = GpuWakeFrame {
            sources: sources.clone(),
            ..Default::default()
        };
        let (bins, drop) = fit(
            &mut all,
            2000.0,
            u64::MAX,
            usize::MAX,
            &SampleSpacing::uniform(0.0),
        );
        assert_eq!((drop.dropped, all.sources.len()), (0, 600));
        let need = bins.bytes(600);
        let cap = 256 << 10;
        assert!(need > 4 * cap, "{need}");
        let mut frame = GpuWakeFrame {
            sources,
            ..Default::default()
        };
        let (bins, drop) = fit(
            &mut frame,
            2000.0,
            cap,
            usize::MAX,
            &SampleSpacing::uniform(0.0),
        );
        // Fits, and drops no more than it must (one more source would not fit).
        assert!(bins.bytes(frame.sources.len()) <= cap);
        assert!(drop.dropped > 0 && drop.dropped + frame.sources.len() == 600);
        // The dropped ones are the weakest: every kept source is at least as strong.
        let weakest_kept = frame
            .sources
            .iter()
            .map(|s| s.strength)
            .fold(f32::MAX, f32::min);
        assert_eq!(weakest_kept, 1e-3 * (1.0 + drop.dropped as f32));
        // The bound is the sum of the dropped sources' peak bounds and foam densities.
        let bound: f64 = all.sources[..drop.dropped]
            .iter()
            .map(source_peak_bound)
            .sum();
        assert!((drop.height_bound_m - bound).abs() <= 1e-12 * bound);
        assert!((drop.foam_bound - 0.01 * drop.dropped as f64).abs() < 1e-6);
        assert_eq!(drop.cap_bytes, cap);
    }

    /// Three levels (0.5, 1 and 2 m) of vertices on the west half of [−60, 60]², finest in
    /// the middle: the sampling of a frame's mesh.
    fn three_levels() -> SampleSpacing {
        use crate::wake_spacing::LevelBox;
        let levels = [0.5f32, 1.0, 2.0]
            .iter()
            .enumerate()
            .map(|(l, &spacing)| LevelBox {
                centre: [0.0; 2],
                half: 20.0 * (l + 1) as f32,
                spacing,
            })
            .collect();
        let mut vertices = Vec::new();
        for a in 0..120 {
            for b in 0..240 {
                let p = [-60.0 + a as f32 * 0.5, -60.0 + b as f32 * 0.5];
                let r = p[0].abs().max(p[1].abs());
                let level = if r < 20.0 {
                    0
                } else if r < 40.0 {
                    1
                } else {
                    2
                };
                vertices.push((p, level));
            }
        }
        SampleSpacing {
            levels,
            vertices,
            displacement: 1.0,
        }
    }

    /// With a list per level, the cap still holds: `fit` counts every level's entries and
    /// every bin's entry per level (a count of one entry per bin let a tight cap be
    /// overrun).
    #[test]
    fn a_fleet_over_the_cap_fits_with_a_list_per_level() {
        let spacing = three_levels();
        let mut all = GpuWakeFrame {
            sources: bunched_fleet(),
            ..Default::default()
        };
        let (bins, drop) = fit(&mut all, 2000.0, u64::MAX, usize::MAX, &spacing);
        assert_eq!(drop.dropped, 0);
        // Bins on a ring's edge hold two levels' lists.
        assert!(bins.bins.iter().any(|b| b[1] >> 16 == 2));
        let need = bins.bytes(600);
        for cap in [need / 2, need / 4, need * 9 / 10] {
            let mut frame = GpuWakeFrame {
                sources: bunched_fleet(),
                ..Default::default()
            };
            let (bins, drop) = fit(&mut frame, 2000.0, cap, usize::MAX, &spacing);
            let bytes = bins.bytes(frame.sources.len());
            assert!(bytes <= cap, "{bytes} > {cap}");
            assert!(drop.dropped > 0 && drop.dropped + frame.sources.len() == 600);
        }
    }

    /// A bin lists a source for a level only where that level's vertices can land: east of
    /// x = 1 m (the west half's vertices, displaced by up to 1 m) and a bin nothing is listed;
    /// at each vertex moved by up to 1 m, its level's list holds every source whose term at
    /// the level's spacing is not zero (the f32 kernel over every source).
    #[test]
    fn a_bin_lists_a_source_for_the_levels_that_land_there() {
        let spacing = three_levels();
        let mut frame = GpuWakeFrame {
            sources: bunched_fleet(),
            ..Default::default()
        };
        let (bins, _) = fit(&mut frame, 2000.0, u64::MAX, usize::MAX, &spacing);
        let sources = &frame.sources;
        let cell = 1.0 / bins.grid.inv_cell;
        let mut east = 0usize;
        for a in 0..100 {
            for b in 0..241 {
                let p = [
                    1.0 + cell + 0.01 + a as f32 * 0.59,
                    -60.0 + b as f32 * 0.4993,
                ];
                east += (0..3).map(|l| bins.listed_at(p, l).len()).sum::<usize>();
            }
        }
        assert_eq!(east, 0);
        let (mut listed, mut terms) = (0usize, 0usize);
        for &(rest, level) in spacing.vertices.iter().step_by(7) {
            let s_l = spacing.levels[level as usize].spacing;
            for (dx, dz) in [(0.0, 0.0), (0.7, -0.7), (-0.99, 0.0), (0.0, 0.99)] {
                let p = [rest[0] + dx, rest[1] + dz];
                let list = bins.listed_at(p, level);
                for (k, s) in sources.iter().enumerate() {
                    let g = ocean::wake::source_height_grad_sampled_f32(s, p, s_l);
                    if g != [0.0; 3] {
                        assert!(list.contains(&(k as u32)), "{k} at {p:?} level {level}");
                        terms += 1;
                    }
                }
                listed += list.len();
            }
        }
        assert!(terms > 1000 && listed >= terms, "{terms} {listed}");
    }
}
