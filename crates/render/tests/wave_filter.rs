//! The pixel filter's early stop (`surface_frame` in `shaders/render/common.wgsl`): the
//! frame's waves go to the GPU sorted by wavenumber, longest first, so a fragment's loop stops
//! at the first wave its footprint fades out entirely and adds the rest's slope variance in
//! one sum. What must hold: the sort keeps each clip-map level's waves (the level masks follow
//! the waves to their new places), and the early stop sums what running every wave sums.
//! The sea here lists its waves shortest first, so the sort moves every one of them. GPU parts
//! on lavapipe in CI; skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use ocean::{Wave, WaveSet};
use render::frame::FrameContext;
use render::gpu::test_gpu;

/// The default sea, its waves listed shortest first.
fn shuffled_sea() -> WaveSet {
    let mut sea = WaveSet::default_sea();
    sea.waves.reverse();
    assert!(sea.waves[0].k() > sea.waves[sea.waves.len() - 1].k());
    sea
}

/// A view out to the horizon over the shuffled sea: many levels, short waves dropped far out.
fn scene() -> render::Scene {
    let mut scene = render::golden::test_scene(1e3, Vec::new());
    scene.sea = shuffled_sea().into();
    scene.camera.target = scene.camera.eye + glam::DVec3::new(-1.0, -0.15, -1.0) * 100.0;
    scene.play_area = [-1e5, -1e5, 1e5, 1e5];
    scene
}

fn is_kept(frame: &FrameContext, level: usize, slot: usize) -> bool {
    let m = frame.uniform.level_masks[level / 2];
    let word = m[(level % 2) * 2 + slot / 32];
    word >> (slot % 32) & 1 == 1
}

#[test]
fn the_frames_waves_are_sorted_longest_first_and_each_level_keeps_its_own() {
    let scene = scene();
    let frame = FrameContext::new(&scene, [96, 64], 1.0);
    let k: Vec<f32> = frame.waves.iter().map(|w| w.k).collect();
    assert!(k.windows(2).all(|p| p[0] <= p[1]), "{k:?}");
    assert!(frame.levels.len() >= 4, "{} levels", frame.levels.len());
    let mut dropped = 0;
    for (l, plan) in frame.levels.iter().enumerate() {
        for (slot, w) in frame.waves.iter().enumerate() {
            // The sea's wave in this slot: the one of the same wavenumber.
            let i = scene
                .sea
                .waves
                .iter()
                .position(|s: &Wave| s.k() as f32 == w.k)
                .unwrap();
            assert_eq!(
                is_kept(&frame, l, slot),
                plan.kept.contains(&i),
                "level {l} slot {slot}"
            );
            dropped += usize::from(!plan.kept.contains(&i));
        }
    }
    // Far levels drop short waves, so the masks are not all ones.
    assert!(dropped > 0);
    // The tail sums: Σ (k a)²/2 from each slot on, against the f64 waves.
    for slot in 0..frame.waves.len() {
        let want: f64 = frame.waves[slot..]
            .iter()
            .map(|w| {
                let s = scene
                    .sea
                    .waves
                    .iter()
                    .find(|s| s.k() as f32 == w.k)
                    .unwrap();
                0.5 * (s.k() * s.amplitude()).powi(2)
            })
            .sum();
        let got = f64::from(frame.waves[slot].tail_half_slope2);
        assert!(
            (got - want).abs() <= 1e-6 * want,
            "slot {slot}: {got} vs {want}"
        );
    }
}

/// Points over a few wavelengths, each at footprints from none to past every wave's cut-off
/// (k·footprint ≥ π/2 for the longest wave, 60 m: footprint ≥ 15 m).
fn points() -> Vec<([f32; 2], f32)> {
    let footprints = [
        0.0, 0.3, 0.6, 0.95, 1.4, 2.0, 3.1, 4.5, 7.0, 9.9, 14.0, 16.0, 40.0,
    ];
    (0..24)
        .flat_map(|i| {
            let p = [i as f32 * 7.3 - 80.0, i as f32 * -4.1 + 35.0];
            footprints.iter().map(move |&f| (p, f))
        })
        .collect()
}

#[test]
fn the_early_stop_sums_what_every_wave_sums() {
    let Some(gpu) = test_gpu() else { return };
    let scene = scene();
    let frame = FrameContext::new(&scene, [96, 64], 1.0);
    let points = points();
    let stopped = render::compute::gpu_surface_frames(&gpu, &frame, &points, false).unwrap();
    let every = render::compute::gpu_surface_frames(&gpu, &frame, &points, true).unwrap();
    let mut stops = 0;
    for ((p, fp), (a, b)) in points.iter().zip(stopped.iter().zip(&every)) {
        // Slopes and Jacobian: a faded wave adds fade·k·a·sin… with fade = 1 − smoothstep = 0
        // from k·footprint = π/2 on (a GPU's division may leave 1 − t of a few ULP in the
        // smoothstep, whose slope there is 0: a fade of 3(1 − t)² < 1e-12).
        for c in 0..3 {
            assert!(
                (a[c] - b[c]).abs() <= 1e-6,
                "{p:?} footprint {fp}: {a:?} vs {b:?}"
            );
        }
        // The variance: one f32 tail sum against a running sum of the same terms.
        assert!(
            (a[3] - b[3]).abs() <= 1e-6 * b[3].max(1e-3),
            "{p:?} {fp}: {a:?} vs {b:?}"
        );
        stops += usize::from(
            frame
                .waves
                .iter()
                .any(|w| w.k * fp >= std::f32::consts::FRAC_PI_2),
        );
    }
    // Many of the points stop early, and at the largest footprints every wave is faded out:
    // flat water with all of the sea's slope variance.
    assert!(stops > points.len() / 2, "{stops} of {}", points.len());
    let all = frame.waves[0].tail_half_slope2;
    let last = stopped[stopped.len() - 1];
    assert_eq!([last[0], last[1], last[2]], [0.0, 0.0, 1.0]);
    assert!((last[3] - all).abs() <= 1e-6 * all);
}

/// The check above fails when the waves are not sorted (the loop then stops at a short wave
/// with longer, unfaded waves after it): the GPU path fed the shortest wave first.
#[test]
fn unsorted_waves_would_fail_the_early_stop_check() {
    let Some(gpu) = test_gpu() else { return };
    let scene = scene();
    let mut frame = FrameContext::new(&scene, [96, 64], 1.0);
    frame.waves.reverse();
    let points = points();
    let stopped = render::compute::gpu_surface_frames(&gpu, &frame, &points, false).unwrap();
    let every = render::compute::gpu_surface_frames(&gpu, &frame, &points, true).unwrap();
    let worst = stopped
        .iter()
        .zip(&every)
        .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst > 1e-2, "worst slope difference {worst}");
}

/// `resolved_waves` takes a wave whole while k < π/(4·footprint), the cut-off wavenumber
/// formed once per pixel, where it tested k·footprint < π/4 per wave. The two tests disagree
/// only for k·footprint within a few ULP of π/4, and there the wave's fade,
/// 1 − smoothstep(π/4, π/2, k·footprint), rounds to exactly 1, so `fading_waves` adds the same
/// terms (sin θ·1, a variance of 0) as `resolved_waves`: the sums do not change. Checked in
/// f32 as WGSL computes it, for every wave of the default sea at footprints up to 64 ULP either
/// side of its cut-off, with every value WGSL's division (2.5 ULP) may give for the cut-off.
#[test]
fn the_cut_off_wavenumber_moves_only_waves_whose_fade_is_exactly_one() {
    // common.wgsl's PI, as its f32.
    let pi = std::f64::consts::PI as f32;
    let (fading, faded) = (0.25 * pi, 0.5 * pi);
    let step = |x: f32, ulps: i32| f32::from_bits(x.to_bits().wrapping_add_signed(ulps));
    let (mut tests, mut disagreements) = (0, 0);
    for w in WaveSet::default_sea().gpu_waves(0.0, [0.0, 0.0]) {
        let k = w.k;
        let cut = fading / k;
        for ulps in -64..=64 {
            let footprint = step(cut, ulps);
            let kf = k * footprint;
            let whole_before = kf < fading;
            let quotient = fading / footprint.max(1e-30);
            for error in -3..=3 {
                let k_fading = step(quotient, error);
                tests += 1;
                if (k < k_fading) == whole_before {
                    continue;
                }
                disagreements += 1;
                // smoothstep's t, with its division's 2.5 ULP, and t²(3 − 2t) ≤ 3t²: at most
                // half an ULP below 1 (2⁻²⁵), which 1 − s rounds back to 1 (to even).
                let t = f64::from((kf - fading).max(0.0) / (faded - fading))
                    * (1.0 + 3.0 * f64::from(f32::EPSILON));
                let s = 3.0 * t * t;
                assert!(
                    s <= 2f64.powi(-25),
                    "k {k} footprint {footprint}: smoothstep {s}"
                );
                assert_eq!(1.0 - s as f32, 1.0);
            }
        }
        // A footprint of 0 cuts no wave, as k·0 < π/4 faded none.
        assert!(k < fading / 0f32.max(1e-30));
    }
    eprintln!("{disagreements} of {tests} (wave, footprint, cut-off) cases disagree");
    // The check is not empty: the tests do disagree near each cut-off.
    assert!(disagreements > 0);
}
