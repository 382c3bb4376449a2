use glam::{DVec2, DVec3};

use super::*;
use crate::frame::FrameContext;

/// Views of the golden scene's sea: the test camera 14 m up, a fan's view from 80 m, and a
/// low, grazing one.
fn views() -> Vec<(crate::Scene, [u32; 2])> {
    let mut out = Vec::new();
    for (eye, target, size) in [
        (
            DVec3::new(25.0, 14.0, 45.0),
            DVec3::new(-2.0, 0.0, -5.0),
            [360, 640],
        ),
        (
            DVec3::new(120.0, 80.0, 80.0),
            DVec3::new(0.0, 0.0, 0.0),
            [720, 1600],
        ),
        (
            DVec3::new(0.0, 4.0, 60.0),
            DVec3::new(0.0, 0.0, -200.0),
            [640, 360],
        ),
    ] {
        let mut scene = crate::golden::test_scene(600.0, Vec::new());
        scene.camera = crate::Camera::look_at(eye, target, 5000.0);
        out.push((scene, size));
    }
    out
}

fn rest(v: &crate::clipmap::ClipVertex) -> DVec2 {
    DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]))
}

/// Every triangle's three vertices are of one level, so the pixels' first wave, interpolated
/// from them, is that level's.
#[test]
fn a_triangle_is_of_one_level() {
    for (scene, size) in views() {
        let frame = FrameContext::new(&scene, size, 4.0 / 3.0);
        let v = &frame.mesh.vertices;
        for t in frame.mesh.indices.chunks_exact(3) {
            let l = v[t[0] as usize].level;
            assert!(t.iter().all(|&i| v[i as usize].level == l), "{t:?}");
        }
    }
}

/// The sums interpolated from a triangle's vertices, against the sums at the interpolated rest
/// point (f64), at points across each triangle of every level of three views: within the
/// level's bound, and the bound within 8× of the worst error met (so a bound a quarter as large
/// fails: the test can tell a wrong bound from a right one).
#[test]
fn the_interpolated_sums_stay_within_their_bound() {
    let weights = [
        [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
        [0.5, 0.5, 0.0],
        [0.0, 0.5, 0.5],
        [0.5, 0.0, 0.5],
        [0.7, 0.2, 0.1],
        [0.1, 0.7, 0.2],
        [0.2, 0.1, 0.7],
    ];
    let mut worst_ratio = 0.0f64;
    let mut levels_with_waves = 0;
    for (scene, size) in views() {
        let frame = FrameContext::new(&scene, size, 4.0 / 3.0);
        let v = &frame.mesh.vertices;
        for (l, vw) in frame.vertex_waves.iter().enumerate() {
            assert!(vw.bound <= VERTEX_SLOPE_BOUND, "{vw:?}");
            let m = vw.first_pixel_wave as usize;
            if m == 0 {
                continue;
            }
            levels_with_waves += 1;
            let mut worst = 0.0f64;
            for t in frame.mesh.indices.chunks_exact(3) {
                if v[t[0] as usize].level as usize != l {
                    continue;
                }
                let corners = [0, 1, 2].map(|k| rest(&v[t[k] as usize]));
                let sums = corners.map(|p| slope_sums(&frame.waves, m, p));
                for b in &weights {
                    let p = corners[0] * b[0] + corners[1] * b[1] + corners[2] * b[2];
                    let exact = slope_sums(&frame.waves, m, p);
                    for c in 0..5 {
                        let interpolated =
                            b[0] * sums[0][c] + b[1] * sums[1][c] + b[2] * sums[2][c];
                        worst = worst.max((interpolated - exact[c]).abs());
                    }
                }
            }
            assert!(
                worst <= vw.bound * (1.0 + 1e-9) + 1e-12,
                "level {l}: {worst} > {}",
                vw.bound
            );
            worst_ratio = worst_ratio.max(worst / vw.bound);
        }
    }
    assert!(levels_with_waves >= 3, "{levels_with_waves}");
    assert!(
        worst_ratio > 0.125,
        "the bound is loose: worst / bound = {worst_ratio}"
    );
}

/// One wave along a lattice axis: its bound is c k² s²/8 with c = k A (the height's gradient
/// along the axis) and s the cell of the next coarser level (the morph band's triangles reach
/// it; the coarsest level's own), by hand, and a level takes it only while that is within
/// VERTEX_SLOPE_BOUND.
#[test]
fn a_level_takes_a_wave_while_its_bound_holds() {
    let (k, a) = (0.2f32, 0.5f32);
    let wave = ocean::GpuWave {
        wavevector: [k, 0.0],
        k,
        amplitude_direction: [a, 0.0],
        amplitude: a,
        slope_xx: k * a,
        slope_x: k * a,
        ..bytemuck::Zeroable::zeroed()
    };
    let clipmap = ClipMapConfig::uniform(2, 8, 1.0);
    let plan = |cell: f64| LevelPlan {
        cell,
        half_extent: 4.0 * cell,
        nearest: 1.0,
        kept: vec![0],
        dropped_bound: 0.0,
        interpolation_bound: 0.0,
        error_px: 0.0,
        allowed_px: 1.0,
    };
    // c k² s²/8 = 0.1 · 0.04 · s²/8 = s²/2000: within 0.01 up to s = √20 ≈ 4.47 m.
    let small = [0.1; 3];
    let got = vertex_waves(
        &clipmap,
        &[plan(3.0), plan(4.0), plan(5.0)],
        &small,
        &[wave],
    );
    assert_eq!(got[1].first_pixel_wave, 0, "{:?}", got[1]);
    assert_eq!(got[0].first_pixel_wave, 1);
    assert!((got[0].bound - 16.0 / 2000.0).abs() < 1e-9, "{:?}", got[0]);
    assert_eq!(got[2].first_pixel_wave, 0);
    assert_eq!(got[2].bound, 0.0);
    // A level whose pixels span π/(4k) ≈ 3.93 m or more keeps the wave for its pixels.
    let wide = [3.9, 3.95, 0.1];
    let got = vertex_waves(&clipmap, &[plan(3.0), plan(3.0), plan(3.0)], &wide, &[wave]);
    let firsts: Vec<u32> = got.iter().map(|v| v.first_pixel_wave).collect();
    assert_eq!(firsts, [1, 0, 1]);
}

/// The pixel filter would fade a wave the vertices sum (k·footprint ≥ π/4) in under 1 % of
/// the water's fragments: facets the waves turn away from the eye, which span more of the rest
/// plane than `footprint_bound`'s flat sea.
#[test]
fn few_pixels_lose_the_filter_of_the_vertex_waves() {
    for (scene, size) in views() {
        let frame = FrameContext::new(&scene, size, 4.0 / 3.0);
        let (o, t) = (frame.origin, scene.t);
        let surface = |p: [f64; 2]| {
            let d = scene.sea.displace([p[0] + o.x, p[1] + o.y], t);
            [d[0] - o.x, d[1], d[2] - o.y]
        };
        let (mut unfiltered, mut all) = (0u64, 0u64);
        for (footprint, quads, level) in frame.mesh.footprints(frame.view_proj, size, surface) {
            let first = frame.vertex_waves[level as usize].first_pixel_wave as usize;
            all += quads;
            let shortest = frame.waves[..first]
                .iter()
                .map(|w| f64::from(w.k))
                .fold(0.0, f64::max);
            if shortest * footprint >= std::f64::consts::FRAC_PI_4 {
                unfiltered += quads;
            }
        }
        let share = unfiltered as f64 / all.max(1) as f64;
        eprintln!("{size:?}: {share:.4} of {all} fragments");
        // Measured: 0.21 %, 0.29 % and 0.004 % (facets turned away from the eye).
        assert!(share < 0.01, "{share}");
    }
}
