//! Which lists of which bins hold each source: the (list, source) entries of a frame's sources,
//! listed on up to [`ENTRY_THREADS`] threads, before they are sorted into lists
//! (`binner.rs`).

use super::runs::Run;
use super::*;

/// Most threads that list a frame's entries.
const ENTRY_THREADS: usize = 4;
/// The fewest sources worth a thread of their own (a thread costs tens of microseconds; a
/// source's entries about ten).
const MIN_SOURCES_A_THREAD: usize = 256;

/// The list entries of a frame's sources before they are sorted into lists, kept from frame
/// to frame for their allocations.
#[derive(Debug, Default)]
pub(super) struct Entries {
    /// Per chunk of `chunk` consecutive sources (one a thread), the lists its sources are
    /// entered in, in the sources' order: source k's entries are the `per_source[k]` after
    /// those of the sources before it in its chunk. List b·(levels + 1) is bin b's foam list
    /// and b·(levels + 1) + 1 + l its level-l height list.
    pub(super) chunks: Vec<Vec<u32>>,
    /// Sources a chunk.
    pub(super) chunk: usize,
    /// List entries per source.
    pub(super) per_source: Vec<u32>,
    /// Per chunk, its entries per list (counted on its thread; empty for a chunk with no
    /// sources this frame).
    pub(super) counts: Vec<Vec<u32>>,
    /// Each thread's distances (scratch).
    scratch: Vec<Distances>,
}

impl Entries {
    /// Each source's index with its lists, in the sources' order.
    pub(super) fn by_source(&self) -> impl Iterator<Item = (usize, &[u32])> {
        let chunk = self.chunk.max(1);
        self.chunks
            .iter()
            .zip(self.per_source.chunks(chunk))
            .enumerate()
            .flat_map(move |(c, (lists, counts))| {
                counts
                    .iter()
                    .enumerate()
                    .scan(0usize, move |at, (n, &count)| {
                        let from = *at;
                        *at += count as usize;
                        Some((c * chunk + n, &lists[from..*at]))
                    })
            })
    }
}

/// A source's squared distances to the columns (or rows) of its span, m²: per column the
/// nearest (0 inside) and the farthest grown by the margin, and the column where each is
/// least.
#[derive(Debug, Default)]
struct Distances {
    near2: Vec<f64>,
    far2: Vec<f64>,
    near_least: usize,
    far_least: usize,
}

impl Layout {
    /// Every list entry of `sources`, in the sources' order: which bins list each source and
    /// in which of their lists. Bin (i, j) lists source `s` in its foam list when its foam
    /// strip (grown by the margin) reaches the bin's square, and in level l's height list
    /// when level l's vertices can land in the bin and its cull circle (grown by the margin)
    /// reaches the square with some point of the square outside the source's inner radius
    /// for level l's spacing (a bin in a corner of the circle's bounding square is out of
    /// reach of every point of the circle, and listing it would only add loop turns to the
    /// bin's points).
    pub(super) fn entries(&self, sources: &[GpuWakeSource], out: &mut Entries) {
        let threads = std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .min(ENTRY_THREADS)
            .min(sources.len().div_ceil(MIN_SOURCES_A_THREAD));
        self.entries_on(sources, threads, out);
    }

    /// [`Layout::entries`] on `threads` threads.
    pub(super) fn entries_on(&self, sources: &[GpuWakeSource], threads: usize, out: &mut Entries) {
        out.per_source.clear();
        out.per_source.resize(sources.len(), 0);
        // A source's entries depend only on it and the grid: chunks of sources on threads of
        // their own (a phone has 8 cores), their entries read in the chunks' order, are the
        // entries of one pass over all of them, in the same order.
        let threads = threads.max(1);
        let chunk = sources.len().div_ceil(threads).max(1);
        out.chunk = chunk;
        let parts = sources.len().div_ceil(chunk).max(1);
        out.chunks
            .resize_with(parts.max(out.chunks.len()), Vec::new);
        out.scratch
            .resize_with(parts.max(out.scratch.len()), Default::default);
        out.counts
            .resize_with(parts.max(out.counts.len()), Vec::new);
        for (lists, counts) in out.chunks.iter_mut().zip(&mut out.counts) {
            lists.clear();
            counts.clear();
        }
        let work = sources
            .chunks(chunk)
            .zip(out.per_source.chunks_mut(chunk))
            .zip(out.chunks.iter_mut().zip(out.scratch.iter_mut()))
            .zip(out.counts.iter_mut());
        if parts == 1 {
            for (((part, listed), (lists, scratch)), counts) in work {
                self.entries_from_owned(part, lists, listed, scratch, counts);
            }
            return;
        }
        std::thread::scope(|scope| {
            for (((part, listed), (lists, scratch)), counts) in work {
                scope.spawn(move || self.entries_from_owned(part, lists, listed, scratch, counts));
            }
        });
    }

    /// [`Layout::entries_from`] on the thread's own copies of the chunk's list and scratch
    /// headers, put back after: the threads' `Vec` headers sit side by side in one cache
    /// line, and each entry written updates its list's length, so on the shared headers the
    /// threads took the line from each other at every entry (a third of the listing's time
    /// on two threads). And the chunk's entries counted per list in `counts`, on the same
    /// thread, while they are in its cache.
    fn entries_from_owned(
        &self,
        sources: &[GpuWakeSource],
        lists: &mut Vec<u32>,
        listed_per_source: &mut [u32],
        scratch: &mut Distances,
        counts: &mut Vec<u32>,
    ) {
        let (mut own_lists, mut own_scratch) = (std::mem::take(lists), std::mem::take(scratch));
        self.entries_from(sources, &mut own_lists, listed_per_source, &mut own_scratch);
        counts.resize(self.levels_in.len() * self.lists_per_bin() as usize, 0);
        let counted = counts.as_mut_slice();
        for &list in &own_lists {
            counted[list as usize] += 1;
        }
        (*lists, *scratch) = (own_lists, own_scratch);
    }

    /// [`Layout::entries`] of `sources`: their lists appended to `lists`, each source's count
    /// in `listed_per_source` (one slot a source).
    ///
    /// The squared distances are separable: a bin's nearest (and farthest) squared distance
    /// is its column's plus its row's, so each column's and row's are worked out once per
    /// source. Along a row the nearest and the farthest squared distances only fall up to one
    /// column and only grow past it, so the columns within a radius are one run, and so are
    /// the columns wholly inside a level's inner radius (`Run::within`, each run's ends moved
    /// from the last row's). A row lists the source in whole runs: in the foam lists of the
    /// columns its foam reaches, and in level l's lists of the columns its cull circle
    /// reaches less those wholly inside its inner radius for level l, each intersected with
    /// the row's runs of bins that have the list (`SlotRuns`). Every comparison is the one of
    /// a test per bin, on the same f64 values (`reference.rs`); a source's entries come out
    /// in another order than bin by bin, which the lists do not see (each holds a source at
    /// most once, in the sources' order).
    fn entries_from(
        &self,
        sources: &[GpuWakeSource],
        lists: &mut Vec<u32>,
        listed_per_source: &mut [u32],
        columns: &mut Distances,
    ) {
        let margin = f64::from(self.margin);
        for (n, s) in sources.iter().enumerate() {
            // Only the part of its span where some level lands: no list elsewhere.
            let (Some([i0, i1, j0, j1]), Some([l0, l1, m0, m1])) =
                (self.span(s), self.slot_runs.landing())
            else {
                continue;
            };
            let ([i0, i1], [j0, j1]) = ([i0.max(l0), i1.min(l1)], [j0.max(m0), j1.min(m1)]);
            if i0 > i1 || j0 > j1 {
                continue;
            }
            let cull = f64::from(s.cull_r2.max(0.0)).sqrt() + margin;
            let foam = f64::from(foam_radius2(s)).sqrt() + margin;
            let mut radii = Radii2 {
                cull: cull * cull,
                foam: foam * foam,
                inner: [0.0; MAX_LEVELS],
            };
            // Beyond both radii a row lists nothing. Neither this nor a nearest distance is
            // NaN (`f64::max` drops a NaN operand, and `cull2` is of a NaN-free radius).
            let either2 = radii.cull.max(radii.foam);
            for (r2, &spacing) in radii.inner.iter_mut().zip(&self.spacing) {
                *r2 = f64::from(inner_radius2(s, spacing));
            }
            let (x, z) = (f64::from(s.pos[0]), f64::from(s.pos[1]));
            columns.of(self, x, self.lo[0], i0..=i1);
            let mut foamed = Run::new(columns.near_least);
            let mut culled = Run::new(columns.near_least);
            let mut holes = [Run::new(columns.far_least); MAX_LEVELS];
            let before = lists.len();
            for j in j0..=j1 {
                let [near, far] = self.distances(z, self.lo[1], j);
                let row = Row {
                    j,
                    i0: i0 as usize,
                    near2: near * near,
                    far2: far * far,
                };
                // Beyond both radii, or no level lands in the row's columns of the span.
                let landing = self.slot_runs.of_row(j, 0);
                let (Some(&[first, _]), Some(&[_, end])) = (landing.first(), landing.last()) else {
                    continue;
                };
                if row.near2 > either2 || end <= i0 || first > i1 {
                    continue;
                }
                let foamed = foamed.within(&columns.near2, row.near2, radii.foam, false);
                self.list_runs(&row, 0, &[foamed], lists);
                let [c0, c1] = culled.within(&columns.near2, row.near2, radii.cull, false);
                if c0 >= c1 {
                    continue;
                }
                // Only the levels that land in the columns the cull circle reaches (one to
                // three of the ten: a clip-map level lands in a ring).
                let first_bin = (j * self.nx) as usize + row.i0;
                let mut levels = self.levels_in[first_bin + c0..first_bin + c1]
                    .iter()
                    .fold(0, |m, &l| m | l);
                while levels != 0 {
                    let l = levels.trailing_zeros();
                    levels &= levels - 1;
                    let inner = radii.inner[l as usize];
                    let [h0, h1] = holes[l as usize].within(&columns.far2, row.far2, inner, true);
                    // The culled columns less the hole (both runs, the hole around the
                    // farthest distances' valley): a left and a right run, one of them empty
                    // when the hole is.
                    let outside = [[c0, c1.min(h0)], [c0.max(h1), c1]];
                    self.list_runs(&row, 1 + l, &outside, lists);
                }
            }
            listed_per_source[n] = (lists.len() - before) as u32;
        }
    }

    /// The source listed in list `slot` of the bins of `row` in the columns `parts` (runs of
    /// offsets into the source's span) whose bins have that list, appended to `lists`.
    fn list_runs(&self, row: &Row, slot: u32, parts: &[[usize; 2]], lists: &mut Vec<u32>) {
        let per_bin = self.lists_per_bin();
        let first_bin = row.j * self.nx;
        let runs = self.slot_runs.of_row(row.j, slot);
        for &[c0, c1] in parts {
            let (from, to) = ((c0 + row.i0) as u32, (c1 + row.i0) as u32);
            if from >= to {
                continue;
            }
            // The row's runs are in order, and where few vertices land (a coarse level over
            // small bins) a row has dozens: only those that overlap [from, to).
            let first = runs.partition_point(|&[_, end]| end <= from);
            for &[r0, r1] in runs[first..].iter().take_while(|&&[r0, _]| r0 < to) {
                let bins = first_bin + from.max(r0)..first_bin + to.min(r1);
                lists.extend(bins.map(|b| b * per_bin + slot));
            }
        }
    }
}

/// A source's squared radii, m², grown by the margin: its cull circle's and its foam
/// strip's, and its inner radius for each level's spacing.
struct Radii2 {
    cull: f64,
    foam: f64,
    inner: [f64; MAX_LEVELS],
}

/// A row `j` of a source's span, whose first column is `i0`, and its squared distances to
/// the source along z, m² (the nearest, and the farthest grown by the margin).
struct Row {
    j: u32,
    i0: usize,
    near2: f64,
    far2: f64,
}

impl Distances {
    /// The distances from coordinate `v` to the columns `span` of the axis whose grid starts
    /// at `lo` (`Layout::distances`, squared).
    fn of(&mut self, layout: &Layout, v: f64, lo: f32, span: std::ops::RangeInclusive<u32>) {
        self.near2.clear();
        self.far2.clear();
        for i in span {
            let [near, far] = layout.distances(v, lo, i);
            self.near2.push(near * near);
            self.far2.push(far * far);
        }
        self.near_least = least(&self.near2);
        self.far_least = least(&self.far2);
    }
}

/// Where `v` is least (the first such place; 0 when empty).
fn least(v: &[f64]) -> usize {
    (0..v.len()).fold(0, |m, i| if v[i] < v[m] { i } else { m })
}
