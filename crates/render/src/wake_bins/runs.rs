//! Runs of columns along a row of bins: the columns within a radius of a source
//! ([`Run`], tracked from row to row), and the columns whose bins have a given list
//! ([`SlotRuns`], per row of the grid). The listing (`listing.rs`) lists a source in whole
//! runs, their intersections, rather than testing bin by bin.

/// Per row of bins and list slot (0: the foam list, which a bin has where any level lands;
/// 1 + l: level l's height list, where level l lands), the runs of columns [first, end) whose
/// bins have that list, left to right. A clip-map level lands in a ring, so a row crosses it in
/// one or two runs.
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct SlotRuns {
    slots: usize,
    /// Per row and slot (row · slots + slot), its runs' range [first, end) in `runs`.
    at: Vec<[u32; 2]>,
    runs: Vec<[u32; 2]>,
    /// The bins where any level lands, [i0, i1, j0, j1] (inclusive), or none.
    landing: Option<[u32; 4]>,
}

impl SlotRuns {
    /// The runs of the grid whose bins have the levels `levels_in` (row-major, `nx` a row;
    /// bit l: level l lands there), for `levels` levels.
    pub(super) fn of(levels_in: &[u32], nx: usize, levels: usize) -> SlotRuns {
        let slots = levels + 1;
        let mut out = SlotRuns {
            slots,
            at: Vec::with_capacity(levels_in.len() / nx.max(1) * slots),
            runs: Vec::new(),
            landing: None,
        };
        for row in levels_in.chunks(nx.max(1)) {
            for slot in 0..slots {
                let has = |mask: u32| match slot {
                    0 => mask != 0,
                    s => mask >> (s - 1) & 1 != 0,
                };
                let first = out.runs.len() as u32;
                let mut start = None;
                for (i, &mask) in row.iter().enumerate() {
                    match (has(mask), start) {
                        (true, None) => start = Some(i as u32),
                        (false, Some(s)) => {
                            out.runs.push([s, i as u32]);
                            start = None;
                        }
                        _ => {}
                    }
                }
                if let Some(s) = start {
                    out.runs.push([s, row.len() as u32]);
                }
                out.at.push([first, out.runs.len() as u32]);
            }
        }
        for j in 0..(out.at.len() / slots) as u32 {
            let landing = out.of_row(j, 0);
            let (Some(&[first, _]), Some(&[_, end])) = (landing.first(), landing.last()) else {
                continue;
            };
            // Rows come in order: the first one found is the lowest.
            let [i0, i1, _, j1] = out.landing.get_or_insert([first, end - 1, j, j]);
            (*i0, *i1, *j1) = ((*i0).min(first), (*i1).max(end - 1), j);
        }
        out
    }

    /// The bins where any level lands, [i0, i1, j0, j1] (inclusive), or none: no list holds
    /// a source outside them.
    pub(super) fn landing(&self) -> Option<[u32; 4]> {
        self.landing
    }

    /// The runs of row `j` whose bins have list `slot`.
    pub(super) fn of_row(&self, j: u32, slot: u32) -> &[[u32; 2]] {
        let [first, end] = self.at[j as usize * self.slots + slot as usize];
        &self.runs[first as usize..end as usize]
    }
}

/// A run of columns [start, end) along a row within a radius, tracked from row to row.
#[derive(Debug, Clone, Copy)]
pub(super) struct Run {
    /// Where the distances are least: inside every run that is not empty.
    valley: usize,
    ends: [usize; 2],
}

impl Run {
    pub(super) fn new(valley: usize) -> Run {
        Run {
            valley,
            ends: [valley, valley + 1],
        }
    }

    /// The columns c with d[c] + `offset` ≤ `limit` (where `strict`: not ≥ `limit`, < for
    /// every limit but a NaN, where it holds everywhere, as the per-bin test "≥ the inner
    /// radius" it stands for fails everywhere; `d` and `offset` are never NaN), where `d` falls up
    /// to `self.valley` and grows past it (a bin's squared distance to the source along the
    /// row): one run [start, end) around the valley (a rounded sum grows with its operand),
    /// or an empty one. Each end moves from where the last row's was, so a source's rows
    /// together take a few turns a column, not one a bin.
    #[inline(always)]
    pub(super) fn within(
        &mut self,
        d: &[f64],
        offset: f64,
        limit: f64,
        strict: bool,
    ) -> [usize; 2] {
        // A function, not a closure: the debug build (opt-level 1) calls a closure here.
        #[inline(always)]
        fn holds(d: f64, offset: f64, limit: f64, strict: bool) -> bool {
            let v = d + offset;
            if strict {
                v < limit || limit.is_nan()
            } else {
                v <= limit
            }
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

    /// A fixed-seed xorshift64 stream.
    fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        }
    }

    /// `Run::within` finds the same columns as testing each one, on seeded sequences that
    /// fall to a valley and grow past it (with flat stretches), for thresholds met nowhere,
    /// everywhere and in between, with the last row's run as the start anywhere.
    #[test]
    fn a_run_is_the_columns_a_test_per_column_finds() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1du64);
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

    /// A row's runs of a slot are exactly the columns whose bins have that list, and the
    /// landing box is the bounding box of the bins with a level, on seeded random grids of
    /// level masks (runs of each length, empty rows, full rows, grids with no level).
    #[test]
    fn slot_runs_are_the_columns_with_the_list() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15u64);
        let mut empty_grids = 0;
        for case in 0..200 {
            let (nx, nz, levels) = (
                1 + (next() % 20) as usize,
                1 + (next() % 6) as usize,
                1 + (next() % 4) as usize,
            );
            // Masks with long stretches: each bin keeps the last one's mask three times in four.
            let mut mask = 0u32;
            let levels_in: Vec<u32> = (0..nx * nz)
                .map(|_| {
                    if next().is_multiple_of(4) {
                        mask = (next() as u32) & ((1 << levels) - 1);
                    }
                    mask
                })
                .collect();
            let runs = SlotRuns::of(&levels_in, nx, levels);
            // The landing box: the least and greatest column and row of a bin with a level.
            let landed = (0..nx * nz).filter(|&b| levels_in[b] != 0);
            let want_box = landed.clone().next().map(|_| {
                let (cols, rows) = (landed.clone().map(|b| b % nx), landed.map(|b| b / nx));
                [
                    cols.clone().min(),
                    cols.max(),
                    rows.clone().min(),
                    rows.max(),
                ]
                .map(|v| v.unwrap_or(0) as u32)
            });
            assert_eq!(runs.landing(), want_box, "case {case}: {levels_in:?}");
            empty_grids += usize::from(want_box.is_none());
            for j in 0..nz {
                let row = &levels_in[j * nx..(j + 1) * nx];
                for slot in 0..=levels {
                    let want: Vec<usize> = (0..nx)
                        .filter(|&i| match slot {
                            0 => row[i] != 0,
                            s => row[i] & 1 << (s - 1) != 0,
                        })
                        .collect();
                    let of_row = runs.of_row(j as u32, slot as u32);
                    let got: Vec<usize> = of_row
                        .iter()
                        .flat_map(|&[a, b]| a as usize..b as usize)
                        .collect();
                    assert_eq!(got, want, "case {case} row {j} slot {slot}: {row:?}");
                    // Maximal runs: none empty, none touching the next.
                    assert!(
                        of_row.windows(2).all(|w| w[0][1] < w[1][0]),
                        "case {case}: {of_row:?}"
                    );
                    assert!(of_row.iter().all(|&[a, b]| a < b), "case {case}");
                }
            }
        }
        assert!(empty_grids > 0, "no grid without a level");
    }
}
