//! The WGSL the water pass runs, evaluated by compute shaders (`render::compute`), against
//! ocean's f64 reference: the sea's `gerstner()` sum, the drawn vertex path `sea_displaced()`
//! (level masks and fade), and the foam rule (`regatta probe`'s). Every point is checked
//! against its own bound, what WGSL's accuracy allows a conforming GPU there
//! (`parity/bounds.rs`, from `render::wgsl_accuracy`), and each check is shown to fail on a
//! broken input fed through the same GPU path. Lavapipe in CI; skipped without an adapter
//! unless REGATTA_REQUIRE_GPU=true.

use glam::DVec2;
use ocean::{GpuWave, Wave, WaveSet};
use render::gpu::test_gpu;
use render::wgsl_accuracy::Inexact;

#[path = "parity/bounds.rs"]
mod bounds;

/// A 400 m square of local points (10 m apart) around the origin.
fn square() -> Vec<[f32; 2]> {
    (0..40)
        .flat_map(|i| (0..40).map(move |j| [i as f32 * 10.0 - 200.0, j as f32 * 10.0 - 200.0]))
        .collect()
}

/// GPU displacements of local `points` against `sea.displace` at race time `t`, each
/// component against its bound (`bounds::gerstner` summed): the largest error, metres, the
/// largest bound and the largest error/bound ratio.
fn displacement_errors(
    sea: &WaveSet,
    t: f64,
    origin: DVec2,
    points: &[[f32; 2]],
    gpu_d: &[[f32; 3]],
) -> (f64, f64, f64) {
    let waves = bounds::waves(sea, t, origin.to_array());
    let (mut worst, mut largest_bound, mut ratio) = (0.0f64, 0.0f64, 0.0f64);
    for (p, g) in points.iter().zip(gpu_d) {
        let x0 = [origin.x + f64::from(p[0]), origin.y + f64::from(p[1])];
        let r = sea.displace(x0, t);
        let want = [r[0] - x0[0], r[1], r[2] - x0[1]];
        let at = bounds::point([f64::from(p[0]), f64::from(p[1])], *p);
        let terms: Vec<[Inexact; 3]> = waves.iter().map(|w| bounds::gerstner(w, at)).collect();
        let bound = bounds::accumulate([Inexact::exact(0.0); 3], &terms);
        for c in 0..3 {
            assert!((bound[c].value - want[c]).abs() < 1e-9, "{p:?}");
            let error = (f64::from(g[c]) - want[c]).abs();
            worst = worst.max(error);
            largest_bound = largest_bound.max(bound[c].error);
            ratio = ratio.max(error / bound[c].error);
        }
    }
    (worst, largest_bound, ratio)
}

/// An origin far from the course centre.
const ORIGIN: DVec2 = DVec2::new(-7321.5, 4410.25);

#[test]
fn compute_heights_match_the_f64_reference_within_their_wgsl_bound() {
    let Some(gpu) = test_gpu() else { return };
    let sea = WaveSet::default_sea();
    let points = square();
    for t in [0.0, 1e3, 1e6] {
        let gpu_d = render::compute::gpu_displacements(&gpu, &sea, t, ORIGIN, &points).unwrap();
        let (worst, bound, ratio) = displacement_errors(&sea, t, ORIGIN, &points, &gpu_d);
        eprintln!(
            "gerstner, t = {t} s: worst |Δ| {worst:.2e} m, largest bound {bound:.2e} m, \
             worst error/bound {ratio:.3}"
        );
        // Each point within its bound: per wave A·(2^-11 of sin/cos + the phase's error,
        // beyond ±π plus 2 ULP of the phase for its reduction) and the sum's roundings.
        assert!(ratio <= 1.0, "t = {t}: error/bound {ratio}");
        // And the bound is a few millimetres, not a free pass.
        assert!(bound < 5e-3, "t = {t}: bound {bound} m");
    }
}

#[test]
fn a_broken_phase_reduction_would_fail_the_parity_test() {
    // The same GPU path and check, fed the phase as an f32 sum with absolute time (k D·o + φ
    // − ω t, unreduced): at t = 1e6 s it misses by far more than its bound.
    let Some(gpu) = test_gpu() else { return };
    let sea = WaveSet::default_sea();
    let t = 1e6;
    let broken: Vec<GpuWave> = sea
        .gpu_waves(t, [ORIGIN.x, ORIGIN.y])
        .into_iter()
        .zip(&sea.waves)
        .map(|(mut g, w)| {
            let kx = w.k() as f32 * (w.direction[0] * ORIGIN.x + w.direction[1] * ORIGIN.y) as f32;
            g.phase0 = kx - w.omega(sea.gravity, sea.depth) as f32 * t as f32 + w.phase as f32;
            g
        })
        .collect();
    let points = square();
    let gpu_d = render::compute::wave_displacements(&gpu, &broken, &points).unwrap();
    let (worst, bound, ratio) = displacement_errors(&sea, t, ORIGIN, &points, &gpu_d);
    assert!(
        ratio > 10.0,
        "an unreduced phase passed: {worst} m against {bound} m"
    );
}

/// The f64 reference of `sea_displaced` for a clip-map vertex of level `level`: the waves its
/// level keeps, those the next level drops weighted by `fade`.
fn vertex_reference(
    sea: &WaveSet,
    t: f64,
    levels: &[render::clipmap::LevelPlan],
    x0: [f64; 2],
    fade: f64,
    level: usize,
    masked: bool,
) -> [f64; 3] {
    let mut d = [0.0; 3];
    for (i, w) in sea
        .waves
        .iter()
        .enumerate()
        .take(render::clipmap::MAX_WAVES)
    {
        let kept = |l: usize| levels.get(l).is_some_and(|p| p.kept.contains(&i));
        if masked && !kept(level) {
            continue;
        }
        let weight = if !masked || kept(level + 1) {
            1.0
        } else {
            fade
        };
        let (s, c) = sea.phase_at(w, x0, t).sin_cos();
        let a = w.amplitude() * weight;
        d[0] += w.direction[0] * a * c;
        d[1] += a * s;
        d[2] += w.direction[1] * a * c;
    }
    d
}

#[test]
fn the_drawn_vertices_match_the_f64_sea_with_their_level_masks_and_fade() {
    let Some(gpu) = test_gpu() else { return };
    let mut scene = render::golden::test_scene(1e3, Vec::new());
    // Far from the course centre, looking out to the horizon: many levels, waves dropped.
    let shift = glam::DVec3::new(ORIGIN.x, 0.0, ORIGIN.y);
    scene.camera.eye += shift;
    scene.camera.target = scene.camera.eye + glam::DVec3::new(-1.0, -0.15, -1.0) * 100.0;
    scene.play_area = [-1e5, -1e5, 1e5, 1e5];
    let frame = render::frame::FrameContext::new(&scene, [96, 64], 1.0);
    let gpu_p = render::compute::vertex_positions(&gpu, &frame).unwrap();
    assert_eq!(gpu_p.len(), frame.mesh.vertices.len());
    assert!(frame.levels.len() >= 4, "{} levels", frame.levels.len());
    let waves = bounds::waves(&scene.sea, scene.t, frame.origin.to_array());
    let (mut worst, mut largest_bound) = (0.0f64, 0.0f64);
    let (mut ratio, mut unmasked_ratio) = (0.0f64, 0.0f64);
    let mut faded = 0;
    for (v, g) in frame.mesh.vertices.iter().zip(&gpu_p) {
        let x0 = [
            frame.origin.x + f64::from(v.rest[0]),
            frame.origin.y + f64::from(v.rest[1]),
        ];
        let (fade, level) = (f64::from(v.fade), v.level as usize);
        faded += usize::from(fade < 1.0);
        let r = vertex_reference(&scene.sea, scene.t, &frame.levels, x0, fade, level, true);
        let all = vertex_reference(&scene.sea, scene.t, &frame.levels, x0, fade, level, false);
        let rest = [f64::from(v.rest[0]), 0.0, f64::from(v.rest[1])];
        // The bound: the vertex's rest position plus its kept waves, weighted.
        let at = bounds::point([rest[0], rest[2]], v.rest);
        let terms: Vec<[Inexact; 3]> = waves
            .iter()
            .enumerate()
            .filter_map(|(i, w)| {
                let kept = |l: usize| frame.levels.get(l).is_some_and(|p| p.kept.contains(&i));
                let weight = if kept(level + 1) { 1.0 } else { fade };
                kept(level).then(|| bounds::gerstner(w, at).map(|c| c * Inexact::of(weight as f32)))
            })
            .collect();
        let bound = bounds::accumulate(rest.map(Inexact::exact), &terms);
        for c in 0..3 {
            assert!((bound[c].value - rest[c] - r[c]).abs() < 1e-9);
            let gpu_d = f64::from(g[c]) - rest[c];
            worst = worst.max((gpu_d - r[c]).abs());
            largest_bound = largest_bound.max(bound[c].error);
            ratio = ratio.max((gpu_d - r[c]).abs() / bound[c].error);
            unmasked_ratio = unmasked_ratio.max((gpu_d - all[c]).abs() / bound[c].error);
        }
    }
    eprintln!(
        "sea_displaced: {} vertices, worst |Δ| {worst:.2e} m, largest bound {largest_bound:.2e} \
         m, worst error/bound {ratio:.3}; against the unmasked sea {unmasked_ratio:.0}",
        gpu_p.len()
    );
    assert!(ratio <= 1.0, "error/bound {ratio}");
    // The masks and fades matter here: ignoring them would miss by far more than the bound.
    assert!(faded > 0, "no vertex in a morph band");
    assert!(
        unmasked_ratio > 10.0,
        "the level masks drop nothing: {unmasked_ratio}"
    );
}

/// A steep sea (Σ kA = 0.8) whose crests compress the surface past foam onset.
fn steep_sea() -> WaveSet {
    let wave = |d: [f64; 2], steepness, wavelength, phase| Wave {
        direction: [d[0] / d[0].hypot(d[1]), d[1] / d[0].hypot(d[1])],
        steepness,
        wavelength,
        phase,
    };
    WaveSet {
        gravity: 9.81,
        depth: None,
        waves: vec![
            wave([1.0, 0.2], 0.35, 31.0, 0.0),
            wave([0.7, -0.7], 0.25, 17.0, 1.3),
            wave([-0.2, 1.0], 0.2, 11.0, 4.1),
        ],
    }
}

#[test]
fn the_drawn_foam_is_probes_foam_within_one_level() {
    let Some(gpu) = test_gpu() else { return };
    let sea = steep_sea();
    let t = 500.0;
    // World points on a 60 m square, 0.75 m apart, with wake foam 0, 0.25 or 0.6.
    let mut points = Vec::new();
    let mut exact_points = Vec::new();
    let mut reference = Vec::new();
    let mut partial = 0;
    for i in 0..80i32 {
        for j in 0..80i32 {
            let at = [
                ORIGIN.x + f64::from(i) * 0.75 - 30.0,
                ORIGIN.y + f64::from(j) * 0.75 - 30.0,
            ];
            let s = sea.sample_at(at, t, ocean::DEFAULT_TOLERANCE).unwrap();
            let wake = [0.0, 0.25, 0.6][((i + j) % 3) as usize];
            partial += usize::from(s.foam > 0.0 && s.foam < 1.0);
            // What `regatta probe` reports at `at` with that wake foam.
            reference.push(ocean::foam_coverage(s.foam, wake));
            let rest = s.rest.rest;
            let local = [(rest[0] - ORIGIN.x) as f32, (rest[1] - ORIGIN.y) as f32];
            points.push((local, wake as f32));
            exact_points.push(([rest[0] - ORIGIN.x, rest[1] - ORIGIN.y], wake));
        }
    }
    assert!(partial > 200, "only {partial} points with partial sea foam");
    let drawn = render::compute::gpu_foam(&gpu, &sea, t, ORIGIN, &points).unwrap();
    // Each point against its bound: surface_frame's Jacobian (the sines at 2^-11, beyond ±π
    // with the reduction assumption) through the foam rule.
    let waves = bounds::waves(&sea, t, ORIGIN.to_array());
    let foam_bounds: Vec<Inexact> = points
        .iter()
        .zip(&exact_points)
        .map(|((local, wake), (exact, wake64))| {
            bounds::foam(&waves, bounds::point(*exact, *local), (*wake64, *wake))
        })
        .collect();
    let (mut worst, mut largest_bound, mut ratio) = (0.0f64, 0.0f64, 0.0f64);
    for ((g, r), b) in drawn.iter().zip(&reference).zip(&foam_bounds) {
        assert!((b.value - r).abs() < 1e-6, "{} {r}", b.value);
        let error = (f64::from(g[0]) - r).abs();
        worst = worst.max(error);
        largest_bound = largest_bound.max(b.error);
        ratio = ratio.max(if error == 0.0 { 0.0 } else { error / b.error });
    }
    eprintln!(
        "foam: {} points, worst |Δ| {worst:.2e}, largest bound {largest_bound:.2e}, worst \
         error/bound {ratio:.3}",
        points.len()
    );
    assert!(ratio <= 1.0, "foam error/bound {ratio}");
    // Within a display level anywhere, on any conforming GPU.
    assert!(largest_bound <= 1.0 / 255.0, "bound {largest_bound}");
    // The rule the shaders drew before (onset 0.72 over 0.35, max with the wake) misses the
    // reference by more than the bound at many of these points: the check tells the rules
    // apart.
    let drifted = drawn
        .iter()
        .zip(&points)
        .zip(reference.iter().zip(&foam_bounds))
        .filter(|((g, (_, wake)), (r, b))| {
            let old = ((0.72 - g[1]) / 0.35).clamp(0.0, 1.0).max(*wake);
            (f64::from(old) - **r).abs() > b.error
        })
        .count();
    assert!(drifted > 200, "only {drifted} points tell the rules apart");
}
