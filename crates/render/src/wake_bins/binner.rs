//! A frame's list entries sorted into their lists and laid out for the GPU, within the buffer
//! cap and the source budget: [`WakeBinner`], which the renderer keeps from frame to frame.

use super::listing::Entries;
use super::*;

/// Bins a frame's wake sources ([`WakeBinner::fit`]). It keeps its working memory from
/// frame to frame, and the buffers of a frame's bins handed back ([`WakeBinner::recycle`]),
/// so a frame like the last allocates nothing. Its bins depend only on the frame's inputs,
/// never on the frames before.
#[derive(Debug, Default)]
pub struct WakeBinner {
    entries: Entries,
    /// Entries per list.
    counts: Vec<u32>,
    /// Where each list's next entry goes in the index buffer.
    next: Vec<u32>,
    /// The buffers of a frame's bins handed back, refilled by the next frame.
    spare: WakeBins,
    /// Each source's peak height bound, the sources from the least visible, which are kept
    /// and their new numbers ([`u32::MAX`]: dropped), for a frame that drops sources.
    peak: Vec<f64>,
    order: Vec<usize>,
    keep: Vec<bool>,
    rank: Vec<u32>,
}

impl WakeBinner {
    /// [`fit`], with this binner's memory.
    pub fn fit(
        &mut self,
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
            // Nothing reaches the square: one empty bin.
            let layout = Layout::new([-half; 2], [half; 2], 1, margin, spacing);
            return (self.bin(&[], &layout), drop);
        };
        // The grid stays the one of all sources in reach, so every count below is exact.
        let layout = Layout::new(lo, hi, WAKE_BINS, margin, spacing);
        // The bytes of all sources' bins, from their lists' lengths (laid out as they would
        // be, none filled).
        let (mut bins, len) = self.lay_out(&wakes.sources, &layout);
        let mut bytes = buffer_bytes(wakes.sources.len(), bins.bins.len(), len);
        let mut kept = wakes.sources.len();
        if bytes <= cap && kept <= max_sources {
            self.fill(&layout, false, len, &mut bins);
            return (bins, drop);
        }
        let sources = &wakes.sources;
        self.peak.clear();
        self.peak.extend(sources.iter().map(source_peak_bound));
        let peak = &self.peak;
        self.order.clear();
        self.order.extend(0..sources.len());
        self.order
            .sort_by(|&a, &b| peak[a].total_cmp(&peak[b]).then(a.cmp(&b)));
        self.keep.clear();
        self.keep.resize(sources.len(), true);
        let listed = &self.entries.per_source;
        for &k in &self.order {
            if bytes <= cap && kept <= max_sources {
                break;
            }
            self.keep[k] = false;
            kept -= 1;
            bytes -= SOURCE_BYTES + INDEX_BYTES * u64::from(listed[k]);
            drop.dropped += 1;
            drop.height_bound_m += peak[k];
            drop.foam_bound += f64::from(sources[k].foam);
        }
        // The kept sources' lists are the lists of all less the dropped ones (a source's
        // entries depend only on it and the grid): their entries, renumbered, rather than
        // the kept sources binned again.
        self.rank.clear();
        let mut next = 0;
        for &k in &self.keep {
            self.rank.push(if k { next } else { u32::MAX });
            next += u32::from(k);
        }
        for (k, lists) in self.entries.by_source() {
            if !self.keep[k] {
                for &list in lists {
                    self.counts[list as usize] -= 1;
                }
            }
        }
        let len = layout.plan(&self.counts, &mut self.next, &mut bins.bins);
        self.fill(&layout, true, len, &mut bins);
        let mut keep = self.keep.iter();
        wakes
            .sources
            .retain(|_| keep.next().copied().unwrap_or(true));
        (bins, drop)
    }

    /// Hand a frame's bins back once uploaded: the next frame fills their buffers.
    pub fn recycle(&mut self, bins: WakeBins) {
        self.spare = bins;
    }

    /// Every source of `sources` binned on `layout` (no cap).
    pub(super) fn bin(&mut self, sources: &[GpuWakeSource], layout: &Layout) -> WakeBins {
        let (mut bins, len) = self.lay_out(sources, layout);
        self.fill(layout, false, len, &mut bins);
        bins
    }

    /// The entries of `sources` on `layout`, counted per list, and their bins laid out in the
    /// spare buffers (none filled): the bins and the index buffer's length.
    fn lay_out(&mut self, sources: &[GpuWakeSource], layout: &Layout) -> (WakeBins, usize) {
        layout.entries(sources, &mut self.entries);
        self.count(layout);
        let mut bins = std::mem::take(&mut self.spare);
        let len = layout.plan(&self.counts, &mut self.next, &mut bins.bins);
        (bins, len)
    }

    /// Fill `bins` as laid out (`len` indices), each source by its number, or by its new
    /// number in `rank` when `renumbered` (a frame that dropped sources).
    fn fill(&mut self, layout: &Layout, renumbered: bool, len: usize, bins: &mut WakeBins) {
        let rank = renumbered.then_some(self.rank.as_slice());
        layout.fill(&self.entries, &self.counts, &mut self.next, rank, len, bins);
    }

    /// The entries of each list: the sum of the chunks' counts (each counted on its thread).
    fn count(&mut self, layout: &Layout) {
        self.counts.clear();
        let lists = layout.levels_in.len() * layout.lists_per_bin() as usize;
        self.counts.resize(lists, 0);
        for chunk in &self.entries.counts {
            for (count, &n) in self.counts.iter_mut().zip(chunk) {
                *count += n;
            }
        }
    }
}

/// Bytes of the three buffers with `sources` sources, `bins` bins and `indices` indices (each
/// at least one entry: the buffers are never empty).
pub(super) fn buffer_bytes(sources: usize, bins: usize, indices: usize) -> u64 {
    SOURCE_BYTES * sources.max(1) as u64
        + BIN_BYTES * bins as u64
        + INDEX_BYTES * indices.max(1) as u64
}

/// The levels whose height lists a bin lays out, those of `mask` from the lowest to the
/// highest whose list is not empty (`count`: a level's entries; an empty list and none read
/// alike): [lowest, how many], or none.
fn level_span(mask: u32, count: impl Fn(u32) -> u32) -> Option<[u32; 2]> {
    let (mut lowest, mut highest) = (None, 0);
    // Only the levels of `mask`, one bit at a time (a bin has one or two).
    let mut levels = mask;
    while levels != 0 {
        let l = levels.trailing_zeros();
        if count(l) != 0 {
            lowest.get_or_insert(l);
            highest = l;
        }
        levels &= levels - 1;
    }
    lowest.map(|lowest| [lowest, highest - lowest + 1])
}

impl Layout {
    /// The bins of lists `counts` long (their entries sorted into lists by a counting sort,
    /// which keeps each list in the sources' order), laid out per bin (`WakeBins::bins`): each
    /// bin's entry in `bins`, where each list laid out starts in the index buffer in
    /// `starts`. Returns the index buffer's length. Both the bytes a frame needs and the
    /// layout it gets come from here.
    fn plan(&self, counts: &[u32], starts: &mut Vec<u32>, bins: &mut Vec<[u32; 4]>) -> usize {
        let per_bin = self.lists_per_bin() as usize;
        starts.resize(counts.len(), 0);
        bins.clear();
        let mut len = 0u32;
        for (b, &mask) in self.levels_in.iter().enumerate() {
            let first = b * per_bin;
            let foam_count = counts[first];
            let foam_first = len;
            starts[first] = len;
            len += foam_count;
            let head = len;
            let height = |l: u32| counts[first + 1 + l as usize];
            let Some([lowest, span]) = level_span(mask, height) else {
                bins.push([head, 0, foam_first, foam_count]);
                continue;
            };
            // Their (first, count) pairs, then their lists.
            len += 2 * span;
            for l in lowest..lowest + span {
                starts[first + 1 + l as usize] = len;
                len += height(l);
            }
            bins.push([head, lowest | span << 16, foam_first, foam_count]);
        }
        len as usize
    }

    /// Lay out `entries` in `out` as `plan` planned (`len` indices, each list at `starts`):
    /// the heads, then every entry's source (`rank`: its new number, [`u32::MAX`] for a
    /// dropped source whose entries `counts` no longer holds) in its place.
    fn fill(
        &self,
        entries: &Entries,
        counts: &[u32],
        starts: &mut [u32],
        rank: Option<&[u32]>,
        len: usize,
        out: &mut WakeBins,
    ) {
        out.grid = self.grid();
        let per_bin = self.lists_per_bin() as usize;
        let indices = &mut out.indices;
        indices.clear();
        indices.resize(len, 0);
        for (b, &[head, levels, _, _]) in out.bins.iter().enumerate() {
            let (lowest, span) = (levels & 0xffff, levels >> 16);
            for k in 0..span {
                let list = b * per_bin + 1 + (lowest + k) as usize;
                let at = (head + 2 * k) as usize;
                indices[at] = starts[list];
                indices[at + 1] = counts[list];
            }
        }
        for (k, lists) in entries.by_source() {
            let k = rank.map_or(k as u32, |rank| rank[k]);
            if k == u32::MAX {
                continue;
            }
            for &list in lists {
                let at = &mut starts[list as usize];
                indices[*at as usize] = k;
                *at += 1;
            }
        }
    }
}
