//! Which lists of which bins hold each source: the (list, source) entries of a frame's sources,
//! listed on up to [`ENTRY_THREADS`] threads, before they are sorted into lists
//! (`binner.rs`).

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
        for lists in &mut out.chunks {
            lists.clear();
        }
        let work = sources
            .chunks(chunk)
            .zip(out.per_source.chunks_mut(chunk))
            .zip(out.chunks.iter_mut().zip(out.scratch.iter_mut()));
        if parts == 1 {
            for ((part, listed), (lists, scratch)) in work {
                self.entries_from(part, lists, listed, scratch);
            }
            return;
        }
        std::thread::scope(|scope| {
            for ((part, listed), (lists, scratch)) in work {
                scope.spawn(move || self.entries_from(part, lists, listed, scratch));
            }
        });
    }

    /// [`Layout::entries`] of `sources`: their lists appended to `lists`, each source's count
    /// in `listed_per_source` (one slot a source).
    ///
    /// The squared distances are separable: a bin's nearest (and farthest) squared distance
    /// is its column's plus its row's, so each column's and row's are worked out once per
    /// source. Along a row the nearest and the farthest squared distances only fall up to one
    /// column and only grow past it, so the columns within a radius are one run: a row
    /// walks only the columns within the larger of the cull and foam radii, and within
    /// those, where the whole bin lies inside the source's least inner radius of the row's
    /// levels (no level lists it), only the ones its foam reaches (`Run::within`, each run's
    /// ends moved from the last row's). Every comparison is the one of a test per bin, on the
    /// same f64 values; a source's entries come out in another order than bin by bin, which
    /// the lists do not see (each holds a source at most once, in the sources' order).
    fn entries_from(
        &self,
        sources: &[GpuWakeSource],
        lists: &mut Vec<u32>,
        listed_per_source: &mut [u32],
        columns: &mut Distances,
    ) {
        let margin = f64::from(self.margin);
        for (n, s) in sources.iter().enumerate() {
            let Some([i0, i1, j0, j1]) = self.span(s) else {
                continue;
            };
            let cull = f64::from(s.cull_r2.max(0.0)).sqrt() + margin;
            let foam = f64::from(foam_radius2(s)).sqrt() + margin;
            let mut radii = Radii2 {
                cull: cull * cull,
                foam: foam * foam,
                inner: [0.0; MAX_LEVELS],
            };
            // Beyond both radii a bin lists nothing. Neither this nor a nearest distance is
            // NaN (`f64::max` drops a NaN operand, and `cull2` is of a NaN-free radius).
            let either2 = radii.cull.max(radii.foam);
            for (r2, &spacing) in radii.inner.iter_mut().zip(&self.spacing) {
                *r2 = f64::from(inner_radius2(s, spacing));
            }
            let (x, z) = (f64::from(s.pos[0]), f64::from(s.pos[1]));
            columns.of(self, x, self.lo[0], i0..=i1);
            let mut reach = Run::new(columns.near_least);
            let mut hole = Run::new(columns.far_least);
            let mut foamed = Run::new(columns.near_least);
            let before = lists.len();
            for j in j0..=j1 {
                let [near, far] = self.distances(z, self.lo[1], j);
                let row = Row {
                    bin: j * self.nx + i0,
                    near2: near * near,
                    far2: far * far,
                };
                if row.near2 > either2 {
                    continue;
                }
                // The row's columns where some level lands, as offsets into the span.
                let [first, end] = self.rows[j as usize];
                let (first, end) = (first.max(i0) - i0, end.min(i1 + 1).saturating_sub(i0));
                let [a0, a1] = reach.within(&columns.near2, row.near2, either2, false);
                let (a0, a1) = (a0.max(first as usize), a1.min(end as usize));
                if a0 >= a1 {
                    continue;
                }
                // No level lists a bin wholly inside the least inner radius of the row's
                // levels; such a bin lists the source only when its foam reaches it.
                let mut least_inner2 = f64::INFINITY;
                let mut row_levels = self.row_levels[j as usize];
                while row_levels != 0 {
                    let l = row_levels.trailing_zeros() as usize;
                    least_inner2 = least_inner2.min(radii.inner[l]);
                    row_levels &= row_levels - 1;
                }
                let [h0, h1] = hole.within(&columns.far2, row.far2, least_inner2, true);
                let (h0, h1) = (h0.clamp(a0, a1), h1.clamp(a0, a1));
                self.list_bins(&radii, columns, &row, [a0, h0], lists);
                self.list_bins(&radii, columns, &row, [h1.max(h0), a1], lists);
                if h0 < h1 {
                    let [f0, f1] = foamed.within(&columns.near2, row.near2, radii.foam, false);
                    let per_bin = self.lists_per_bin();
                    for c in f0.max(h0)..f1.min(h1) {
                        let b = row.bin + c as u32;
                        if self.levels_in[b as usize] != 0 {
                            lists.push(b * per_bin);
                        }
                    }
                }
            }
            listed_per_source[n] = (lists.len() - before) as u32;
        }
    }

    /// The lists of the bins of columns [from, to) of `row` (offsets into the source's span)
    /// that hold the source, appended to `lists`: each bin tested on its own.
    fn list_bins(
        &self,
        radii: &Radii2,
        columns: &Distances,
        row: &Row,
        [from, to]: [usize; 2],
        lists: &mut Vec<u32>,
    ) {
        let per_bin = self.lists_per_bin();
        for c in from..to {
            let b = row.bin + c as u32;
            let levels_in = self.levels_in[b as usize];
            if levels_in == 0 {
                continue;
            }
            let near2 = columns.near2[c] + row.near2;
            let head = b * per_bin;
            if near2 <= radii.foam {
                lists.push(head);
            }
            if near2 > radii.cull {
                continue;
            }
            // Only the levels that land here (a bin has one or two of them).
            let far2 = columns.far2[c] + row.far2;
            let mut levels = levels_in;
            while levels != 0 {
                let l = levels.trailing_zeros();
                if far2 >= radii.inner[l as usize] {
                    lists.push(head + 1 + l);
                }
                levels &= levels - 1;
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

/// A row of a source's span: its first column's bin and its squared distances to the
/// source along z, m² (the nearest, and the farthest grown by the margin).
struct Row {
    bin: u32,
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

/// A run of columns [start, end) along a row within a radius, tracked from row to row.
#[derive(Debug, Clone, Copy)]
struct Run {
    /// Where the distances are least: inside every run that is not empty.
    valley: usize,
    ends: [usize; 2],
}

impl Run {
    fn new(valley: usize) -> Run {
        Run {
            valley,
            ends: [valley, valley + 1],
        }
    }

    /// The columns c with d[c] + `offset` ≤ `limit` (< where `strict`), where `d` falls up
    /// to `self.valley` and grows past it (a bin's squared distance to the source along the
    /// row): one run [start, end) around the valley (a rounded sum grows with its operand),
    /// or an empty one. Each end moves from where the last row's was, so a source's rows
    /// together take a few turns a column, not one a bin.
    fn within(&mut self, d: &[f64], offset: f64, limit: f64, strict: bool) -> [usize; 2] {
        // A function, not a closure: the debug build (opt-level 1) calls a closure here.
        #[inline(always)]
        fn holds(d: f64, offset: f64, limit: f64, strict: bool) -> bool {
            let v = d + offset;
            if strict { v < limit } else { v <= limit }
        }
        let v = self.valley;
        if v >= d.len() || !holds(d[v], offset, limit, strict) {
            return [v, v];
        }
        // d[start..=v] all inside (d falls to v), d[start − 1] not.
        let mut start = self.ends[0].min(v);
        if holds(d[start], offset, limit, strict) {
            while start > 0 && holds(d[start - 1], offset, limit, strict) {
                start -= 1;
            }
        } else {
            while !holds(d[start], offset, limit, strict) {
                start += 1;
            }
        }
        // d[v..end] all inside (d grows from v), d[end] not.
        let mut end = self.ends[1].clamp(v + 1, d.len());
        if holds(d[end - 1], offset, limit, strict) {
            while end < d.len() && holds(d[end], offset, limit, strict) {
                end += 1;
            }
        } else {
            while !holds(d[end - 1], offset, limit, strict) {
                end -= 1;
            }
        }
        self.ends = [start, end];
        self.ends
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Run::within` finds the same columns as testing each one, on seeded sequences that
    /// fall to a valley and grow past it (with flat stretches), for thresholds met nowhere,
    /// everywhere and in between, with the last row's run as the start anywhere.
    #[test]
    fn a_run_is_the_columns_a_test_per_column_finds() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for case in 0..2000 {
            let n = 1 + (next() % 40) as usize;
            let valley = (next() % n as u64) as usize;
            // Falls (steps of 0, 1 or 2) to the valley, grows past it.
            let mut d = vec![0.0f64; n];
            for c in (0..valley).rev() {
                d[c] = d[c + 1] + (next() % 3) as f64;
            }
            for c in valley + 1..n {
                d[c] = d[c - 1] + (next() % 3) as f64;
            }
            let mut run = Run::new(valley);
            for row in 0..12 {
                let limit = (next() % 50) as f64 - 3.0;
                let offset = (next() % 4) as f64;
                let strict = next() & 1 == 0;
                run.ends = [
                    (next() % (n as u64 + 1)) as usize,
                    (next() % (n as u64 + 2)) as usize,
                ];
                if row % 3 == 0 {
                    run.ends = [valley, valley + 1];
                }
                let [a, b] = run.within(&d, offset, limit, strict);
                let inside = |x: f64| if strict { x < limit } else { x <= limit };
                let want: Vec<usize> = (0..n).filter(|&c| inside(d[c] + offset)).collect();
                let got: Vec<usize> = (a..b).collect();
                assert_eq!(
                    got, want,
                    "case {case} row {row}: {d:?} + {offset} ≤ {limit}"
                );
            }
        }
    }
}
