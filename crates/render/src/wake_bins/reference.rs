//! The binning as it was first written (a `Vec` per list, every (bin, source) pair of a
//! source's bounding square tested in f64 on its own): the reference the faster binning in
//! the parent module must equal, bin for bin and index for index (`tests.rs`, and the sample
//! race's frame in `app/tests/wake_bins_race.rs` through the `binning-reference` feature).

use super::*;

impl Layout {
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

/// [`WakeBins::on`], and how many list entries each source takes.
pub(super) fn counted(sources: &[GpuWakeSource], layout: &Layout) -> (WakeBins, Vec<u64>) {
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
    let (all, listed) = counted(&wakes.sources, &layout);
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
    (counted(&wakes.sources, &layout).0, drop)
}
