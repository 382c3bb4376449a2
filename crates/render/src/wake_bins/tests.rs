//! The binning's unit tests: the bins against the sources' own circles and the f32 kernel.

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

/// A seeded generator (SplitMix64): the random fleets below are the same on every run.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [a, b).
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random fleet's wake as the renderer sees it: `boats` boats sailing 600 s at 2–7 m/s
/// from random points within 250 m of the origin, circling (40–350 m radius), their sources
/// alive at t = 500 s in a 600 m view ([`ocean::wake::Wake::gpu_sources`], ε = 0.5 mm).
fn random_fleet(seed: u64, boats: usize) -> Vec<GpuWakeSource> {
    use ocean::wake::{TrackSample, Wake, WakeParams, WakeView};
    let mut rng = SplitMix(seed);
    let tracks: Vec<Vec<TrackSample>> = (0..boats)
        .map(|_| {
            let (mut x, mut z) = (rng.range(-250.0, 250.0), rng.range(-250.0, 250.0));
            let (mut heading, speed) = (rng.range(0.0, std::f64::consts::TAU), rng.range(2.0, 7.0));
            // Circles of 40–350 m radius: the fleet stays around the view.
            let turn = rng.range(0.02, 0.05) * if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
            (0..=600)
                .map(|i| {
                    let sample = TrackSample {
                        t: f64::from(i),
                        x,
                        z,
                    };
                    heading += turn;
                    x += speed * heading.cos();
                    z += speed * heading.sin();
                    sample
                })
                .collect()
        })
        .collect();
    let refs: Vec<&[TrackSample]> = tracks.iter().map(|t| t.as_slice()).collect();
    let wake = Wake::new(&refs, WakeParams::default()).expect("a valid fleet");
    wake.gpu_sources(500.0, [0.0; 2], &WakeView::around([0.0; 2], 300.0), 5e-4)
        .sources
}

/// The sampling of a frame's clip-map mesh: 6 levels of 32 cells from 0.5 m, the eye off the
/// origin, the lattice turned, vertices displaced by up to 1.5 m.
fn mesh_spacing() -> (SampleSpacing, f32) {
    use crate::clipmap::ClipMapConfig;
    let cfg = ClipMapConfig {
        angle: 0.3,
        ..ClipMapConfig::uniform(6, 32, 0.5)
    };
    let eye = glam::DVec2::new(13.7, -21.2);
    let mesh = cfg.build(eye, &Default::default());
    let half = (cfg.half_extent(cfg.levels() - 1) * 2.0) as f32;
    (SampleSpacing::of_mesh(&cfg, &mesh, eye, 1.5), half)
}

/// `fit` equals the straightforward binning (`reference::fit`: a list per bin and level, every
/// pair of a source's bounding square tested on its own) bin for bin and index for index, and
/// drops the same sources, on seeded random fleets over a clip-map mesh and the bunched fleet
/// over three levels, with no cap, with caps and source budgets that force dropping.
#[test]
fn fit_equals_the_reference_binning() {
    let (mesh, mesh_half) = mesh_spacing();
    let mut cases: Vec<(Vec<GpuWakeSource>, f32, SampleSpacing)> = vec![
        (bunched_fleet(), 2000.0, three_levels()),
        (bunched_fleet(), 2000.0, SampleSpacing::uniform(0.0)),
    ];
    for (seed, boats) in [(1, 3), (7, 12), (42, 40)] {
        cases.push((random_fleet(seed, boats), mesh_half, mesh.clone()));
    }
    let mut dropping = 0;
    for (n, (sources, half, spacing)) in cases.iter().enumerate() {
        assert!(!sources.is_empty(), "case {n}");
        let frame = GpuWakeFrame {
            sources: sources.clone(),
            ..Default::default()
        };
        let (all, _) = reference::fit(&mut frame.clone(), *half, u64::MAX, usize::MAX, spacing);
        let need = all.bytes(sources.len());
        assert!(!all.indices.is_empty(), "case {n}: nothing listed");
        eprintln!(
            "case {n}: {} sources, {} indices, {} bins",
            sources.len(),
            all.indices.len(),
            all.bins.len()
        );
        let limits = [
            (u64::MAX, usize::MAX),
            (need / 3, usize::MAX),
            (need * 9 / 10, usize::MAX),
            (u64::MAX, sources.len() / 2),
            (1, usize::MAX),
        ];
        for (cap, max_sources) in limits {
            let (mut fast, mut slow) = (frame.clone(), frame.clone());
            let got = fit(&mut fast, *half, cap, max_sources, spacing);
            let want = reference::fit(&mut slow, *half, cap, max_sources, spacing);
            assert_eq!(got, want, "case {n}, cap {cap}, budget {max_sources}");
            assert_eq!(fast, slow, "case {n}, cap {cap}, budget {max_sources}");
            dropping += usize::from(want.1.dropped > 0);
        }
        // `WakeBins::sampled` (no cap) too, on a grid of its own.
        let lo = [all.grid.origin[0] - 5.0, all.grid.origin[1] + 3.0];
        let hi = [lo[0] + 170.0, lo[1] + 90.0];
        let layout = Layout::new(lo, hi, 64, 0.3, spacing);
        assert_eq!(
            WakeBins::sampled(sources, lo, hi, 64, 0.3, spacing),
            reference::counted(sources, &layout).0,
            "case {n}"
        );
    }
    assert!(dropping >= 12, "{dropping} cases drop sources");
}

/// The entries listed on 1 to 7 threads (chunks of the sources, read in the chunks' order)
/// are those of one pass over the sources, source by source: on the bunched fleet over three
/// levels and a random fleet over a clip-map mesh.
#[test]
fn entries_on_any_number_of_threads_are_those_of_one_pass() {
    let (mesh, mesh_half) = mesh_spacing();
    let cases = [
        (bunched_fleet(), 2000.0, three_levels()),
        (random_fleet(42, 40), mesh_half, mesh),
    ];
    for (n, (sources, half, spacing)) in cases.iter().enumerate() {
        let margin = lookup_margin(*half);
        let (lo, hi) = reach(sources, *half, margin).expect("the fleet is in reach");
        let layout = Layout::new(lo, hi, WAKE_BINS, margin, spacing);
        let listed = |threads: usize| {
            let mut entries = listing::Entries::default();
            layout.entries_on(sources, threads, &mut entries);
            let by_source: Vec<(usize, Vec<u32>)> = entries
                .by_source()
                .map(|(k, lists)| (k, lists.to_vec()))
                .collect();
            (by_source, entries.per_source.clone())
        };
        let one = listed(1);
        assert_eq!(one.0.len(), sources.len(), "case {n}");
        assert!(
            one.0.iter().map(|(_, l)| l.len()).sum::<usize>() > 1000,
            "case {n}"
        );
        for threads in [2, 3, 4, 7] {
            assert!(listed(threads) == one, "case {n}: {threads} threads");
        }
    }
}

/// One binner kept over frames of different fleets, spacings, caps and source budgets, each
/// frame's bins handed back to it, bins every frame as the straightforward binning does
/// (`reference::fit`), whatever it binned before: a big frame, then smaller ones, an empty
/// one, frames that drop sources and one that does not, and the big frame again.
#[test]
fn a_binner_kept_over_frames_bins_each_as_the_reference_does() {
    let (mesh, mesh_half) = mesh_spacing();
    let frames: Vec<(Vec<GpuWakeSource>, f32, SampleSpacing, u64, usize)> = vec![
        (
            bunched_fleet(),
            2000.0,
            three_levels(),
            u64::MAX,
            usize::MAX,
        ),
        (
            random_fleet(7, 12),
            mesh_half,
            mesh.clone(),
            u64::MAX,
            usize::MAX,
        ),
        (
            random_fleet(42, 40),
            mesh_half,
            mesh.clone(),
            60_000,
            usize::MAX,
        ),
        (Vec::new(), mesh_half, mesh.clone(), u64::MAX, usize::MAX),
        (random_fleet(1, 3), mesh_half, mesh.clone(), u64::MAX, 10),
        (
            bunched_fleet(),
            2000.0,
            SampleSpacing::uniform(0.0),
            256 << 10,
            500,
        ),
        (
            bunched_fleet(),
            2000.0,
            three_levels(),
            u64::MAX,
            usize::MAX,
        ),
    ];
    let mut binner = WakeBinner::default();
    let mut dropping = 0;
    for (n, (sources, half, spacing, cap, budget)) in frames.into_iter().enumerate() {
        let frame = GpuWakeFrame {
            sources,
            ..Default::default()
        };
        let (mut kept, mut slow) = (frame.clone(), frame);
        let got = binner.fit(&mut kept, half, cap, budget, &spacing);
        let want = reference::fit(&mut slow, half, cap, budget, &spacing);
        assert_eq!(got, want, "frame {n}");
        assert_eq!(kept, slow, "frame {n}");
        dropping += usize::from(want.1.dropped > 0);
        binner.recycle(got.0);
    }
    assert!(dropping >= 2, "{dropping} frames drop sources");
}
