//! The clip-map's tests: layout, morph, culling, interpolation and the planner.

use glam::{DVec3, I64Vec2};

use ocean::WaveSet;

use super::plan::{extent_along, lattice_angle, lattice_bound};
use super::*;
use crate::camera::Frustum;

fn config() -> ClipMapConfig {
    ClipMapConfig {
        cells: vec![32, 24, 20, 32],
        base_cell: 0.5,
        ratio: LevelRatio::DOUBLING,
        angle: 0.0,
        morph_band: DEFAULT_MORPH_BAND,
    }
}

/// `config()` for doubling; for the other ratios five levels of 1 m × (p/q)^L cells on a
/// lattice turned by 0.7 rad, each the narrowest that nests the finer one plus two steps
/// (so morph bands are wide).
fn configs() -> Vec<ClipMapConfig> {
    let mut out = vec![config()];
    for ratio in &LEVEL_RATIOS[1..] {
        let step = 2 * ratio.p;
        let mut c = ClipMapConfig {
            cells: vec![4 * step; 5],
            base_cell: 1.0,
            ratio: *ratio,
            angle: 0.7,
            morph_band: DEFAULT_MORPH_BAND,
        };
        for l in 0..c.levels() - 1 {
            while !c.nests(l) {
                c.cells[l as usize + 1] += step;
            }
            c.cells[l as usize + 1] += 2 * step;
        }
        out.push(c);
    }
    out
}

#[test]
fn coarse_index_is_the_nearest_coarse_point_monotone_onto_and_exact_on_shared_points() {
    for r in LEVEL_RATIOS {
        let (p, q) = (i64::from(r.p), i64::from(r.q));
        let mut hit = std::collections::BTreeSet::new();
        for i in -60i64..=60 {
            let c = r.coarse_index(i);
            // Fine point i sits at i q / p coarse cells: c is the nearest (ties lower).
            let x = i as f64 * r.q as f64 / r.p as f64;
            assert!((x - c as f64).abs() <= 0.5, "{r:?} {i} -> {c}");
            assert!(r.coarse_index(i + 1) - c <= 1 && r.coarse_index(i + 1) >= c);
            if i % p == 0 {
                assert_eq!(c, i / p * q, "{r:?} {i}");
            }
            hit.insert(c);
        }
        let (lo, hi) = (r.coarse_index(-60), r.coarse_index(60));
        assert_eq!(hit.len() as i64, hi - lo + 1, "{r:?} not onto");
    }
}

#[test]
fn unculled_mesh_has_the_closed_form_triangle_count() {
    for c in configs() {
        for eye in [
            DVec2::ZERO,
            DVec2::new(3.3, -7.9),
            DVec2::new(-1234.6, 987.2),
        ] {
            let m = c.build(eye, &Culling::default());
            assert_eq!(m.triangles(), c.full_triangles(), "{:?} eye {eye}", c.ratio);
            assert_eq!(c.triangles_drawn(eye, &Culling::default()), m.triangles());
        }
    }
}

#[test]
fn levels_tile_the_plane_without_overlap_or_gap() {
    // Every point of the outermost square is covered by exactly one triangle's cell, and
    // after morphing the triangles still cover it exactly (none flips or overlaps).
    for c in configs() {
        let m = c.build(DVec2::new(5.7, -2.2), &Culling::default());
        let area: f64 = m
            .indices
            .chunks(3)
            .map(|t| {
                // Unmorphed area: use cell size of the level.
                let s = c.cell(m.vertices[t[0] as usize].level);
                s * s / 2.0
            })
            .sum();
        let side = 2.0 * c.half_extent(c.levels() - 1);
        let tol = 1e-9 * side * side;
        assert!(
            (area - side * side).abs() < tol,
            "{:?}: {area} vs {}",
            c.ratio,
            side * side
        );
        let morphed: f64 = m
            .indices
            .chunks(3)
            .map(|t| {
                let p = |k: usize| {
                    let r = m.vertices[t[k] as usize].rest;
                    DVec2::new(f64::from(r[0]), f64::from(r[1]))
                };
                let (a, b) = (p(1) - p(0), p(2) - p(0));
                // Signed: a flipped triangle would subtract.
                (b.x * a.y - a.x * b.y) / 2.0
            })
            .sum();
        assert!(
            (morphed - side * side).abs() < 1e-4 * side * side,
            "{:?}: morphed {morphed} vs {}",
            c.ratio,
            side * side
        );
    }
}

#[test]
fn morphed_border_coincides() {
    // After morphing, every vertex on the outer border of level L is displaced to exactly
    // where a vertex of level L + 1 is: same rest point, same evaluated waves. And every
    // vertex of level L + 1 on the hole's border is met by one: the two borders are the
    // same polyline (no T-junction), for every level ratio.
    let sea = WaveSet::default_sea();
    let target = ErrorTarget::uniform(0.5, 720, 1.0);
    for c in configs() {
        let plan = c.plan(&sea, &target, 8.0);
        assert!(
            plan.windows(2).any(|p| p[1].kept.len() < p[0].kept.len()),
            "{:?}: the test needs a level that drops waves",
            c.ratio
        );
        let eye = DVec2::new(13.2, -4.9);
        let m = c.build(eye, &Culling::default());
        let t = 1234.5;
        let world =
            |v: &ClipVertex| m.origin + DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]));
        let mut checked = 0;
        for l in 0..c.levels() - 1 {
            let centre = c.centre_lattice(l, eye);
            let h = c.half_extent(l);
            // Chebyshev distance in the lattice's frame (rest points are f32).
            let on_border =
                |p: DVec2| ((c.to_lattice(p) - centre).abs().max_element() - h).abs() < 1e-4;
            let coarse: Vec<(DVec2, DVec3, [f32; 2])> = m
                .vertices
                .iter()
                .filter(|v| v.level == l + 1)
                .map(|v| {
                    let d = vertex_displacement(&sea, &plan, v, m.origin, t);
                    (world(v), d, v.rest)
                })
                .collect();
            let mut fine = Vec::new();
            for v in m.vertices.iter().filter(|v| v.level == l) {
                let p = world(v);
                if !on_border(p) {
                    continue;
                }
                assert_eq!(v.fade, 0.0, "border vertex of level {l} not fully morphed");
                let d = vertex_displacement(&sea, &plan, v, m.origin, t);
                let nearest = coarse
                    .iter()
                    .map(|q| (q.1 - d).length())
                    .fold(f64::MAX, f64::min);
                assert!(
                    nearest < 1e-9,
                    "{:?}: level {l} border vertex {p} is {nearest} m off",
                    c.ratio
                );
                fine.push(v.rest);
                checked += 1;
            }
            for (q, _, rest) in coarse.iter().filter(|q| on_border(q.0)) {
                assert!(
                    fine.contains(rest),
                    "{:?}: level {} hole vertex {q} meets no level-{l} vertex",
                    c.ratio,
                    l + 1
                );
            }
        }
        assert!(checked > 100, "only {checked} border vertices checked");
    }
}

#[test]
fn unmorphed_fine_border_would_crack() {
    // Without the morph an odd border vertex of level 0 evaluates all of level 0's waves
    // at its own rest point: it lands metres away from any level-1 vertex. So the test
    // above can fail.
    let sea = WaveSet::default_sea();
    let c = config();
    let target = ErrorTarget::uniform(0.5, 720, 1.0);
    let plan = c.plan(&sea, &target, 8.0);
    let (eye, t) = (DVec2::ZERO, 1234.5);
    let m = c.build(eye, &Culling::default());
    let h = c.half_extent(0);
    let raw = ClipVertex {
        rest: [(0.5 - m.origin.x) as f32, (h - m.origin.y) as f32],
        fade: 1.0,
        level: 0,
    };
    let d = vertex_displacement(&sea, &plan, &raw, m.origin, t);
    let nearest = m
        .vertices
        .iter()
        .filter(|v| v.level == 1)
        .map(|v| (vertex_displacement(&sea, &plan, v, m.origin, t) - d).length())
        .fold(f64::MAX, f64::min);
    assert!(nearest > 1e-3, "{nearest}");
    // Interior vertices never move; border ones slide onto their even neighbour.
    let ci = c.centre_index(0, eye);
    assert_eq!(c.morphed_vertex(0, 1, 0, ci).0, DVec2::new(0.5, 0.0));
    assert_eq!(c.morphed_vertex(0, 1, 16, ci).0, DVec2::new(0.0, 8.0));
    // At ratio 3/2 a border vertex slides onto the nearest coarse point: fine index 4 of
    // 1 m cells (4 m) onto coarse index 3 of 1.5 m cells (4.5 m).
    let c = &configs()[1];
    assert_eq!(c.ratio, LevelRatio { p: 3, q: 2 });
    let h = i64::from(c.cells[0] / 2);
    let (p, fade) = c.morphed_vertex(0, 4, h, I64Vec2::ZERO);
    assert_eq!((p, fade), (DVec2::new(4.5, h as f64 * 1.0), 0.0));
    // Lattice coordinates turn into world ones and back.
    let w = c.to_world(p);
    assert!((w.length() - p.length()).abs() < 1e-12);
    assert!((c.to_lattice(w) - p).length() < 1e-12);
}

#[test]
fn tiles_outside_play_area_and_frustum_are_culled() {
    use crate::camera::Camera;
    let c = config();
    let eye = DVec2::new(0.0, 0.0);
    let origin = c.origin_for(eye);
    let cam = Camera::look_at(DVec3::new(0.0, 5.0, 0.0), DVec3::new(0.0, 0.0, -40.0), 1e3);
    let f = Frustum::from_matrix(cam.view_proj_local(origin, 1.5));
    let culled = c.build(
        eye,
        &Culling {
            frustum: Some(f),
            play_area: Some([-1e4, -1e4, 1e4, 1e4]),
            max_displacement: 1.0,
        },
    );
    let full = c.full_triangles();
    assert!(
        culled.triangles() < full / 2,
        "{} of {full}",
        culled.triangles()
    );
    assert!(culled.levels.iter().any(|l| l.tiles_outside_frustum > 0));
    // Every triangle behind the eye is gone: none lies wholly at z > 1 + tile.
    let small = c.build(
        eye,
        &Culling {
            frustum: None,
            play_area: Some([-3.0, -3.0, 3.0, 3.0]),
            max_displacement: 0.0,
        },
    );
    assert!(small.levels.iter().any(|l| l.tiles_outside_play_area > 0));
    for v in &small.vertices {
        let p = origin + DVec2::new(f64::from(v.rest[0]), f64::from(v.rest[1]));
        // Tiles touching the area keep their vertices: at most one tile beyond it.
        let slack = 3.0 + c.cell(v.level) * f64::from(TILE_CELLS);
        assert!(p.x.abs() <= slack && p.y.abs() <= slack, "{p}");
    }
    // But only the cells that meet the area are drawn, on a turned lattice too: every
    // triangle has a vertex within a cell's diagonal of the area (a morphing level's cell
    // grown by half a coarser cell: what its morph can move into the area), and the cells
    // that cover the area are all there (its area is drawn).
    for angle in [0.0, 0.7] {
        let c = ClipMapConfig { angle, ..config() };
        let culling = Culling {
            frustum: None,
            play_area: Some([-3.0, -3.0, 3.0, 3.0]),
            max_displacement: 0.0,
        };
        let small = c.build(DVec2::new(0.4, -0.3), &culling);
        assert_eq!(
            c.triangles_drawn(DVec2::new(0.4, -0.3), &culling),
            small.triangles()
        );
        // A triangle's corners, world metres.
        let corners = |t: &[u32]| -> Vec<DVec2> {
            t.iter()
                .map(|&k| {
                    let r = small.vertices[k as usize].rest;
                    small.origin + DVec2::new(f64::from(r[0]), f64::from(r[1]))
                })
                .collect()
        };
        let mut area = 0.0;
        for t in small.indices.chunks(3) {
            let level = small.vertices[t[0] as usize].level;
            let p = corners(t);
            let slack = 3.0 + (c.cell(level) + c.cell(level + 1)) * 2f64.sqrt() + 1e-4;
            assert!(
                p.iter().any(|q| q.x.abs() <= slack && q.y.abs() <= slack),
                "{angle}: {p:?}"
            );
            area += (p[1] - p[0]).perp_dot(p[2] - p[0]).abs() / 2.0;
        }
        // Fewer triangles than whole tiles would give, and at least the area's 36 m².
        assert!(area >= 36.0, "{angle}: {area}");
        let whole = small.levels.iter().map(|l| l.tiles_drawn).sum::<u32>();
        assert!(small.triangles() < 2 * 64 * u64::from(whole), "{angle}");
        // Every point of the area lies in a drawn triangle.
        for k in 0..400 {
            let q = DVec2::new(
                -2.99 + 0.015 * f64::from(k % 400),
                2.99 - 0.0149 * f64::from((k * 7) % 400),
            );
            let hit = small.indices.chunks(3).any(|t| {
                let p = corners(t);
                let d = (p[1] - p[0]).perp_dot(p[2] - p[0]);
                let u = (q - p[0]).perp_dot(p[2] - p[0]) / d;
                let v = (p[1] - p[0]).perp_dot(q - p[0]) / d;
                d.abs() > 0.0 && u >= -1e-6 && v >= -1e-6 && u + v <= 1.0 + 1e-6
            });
            assert!(hit, "{angle}: {q} is not drawn");
        }
    }
}

#[test]
fn interpolated_height_is_exact_at_vertices_and_bounded_between() {
    for angle in [0.0, 0.7] {
        let c = ClipMapConfig { angle, ..config() };
        interpolation_within_bound(&c);
    }
}

fn interpolation_within_bound(c: &ClipMapConfig) {
    let sea = WaveSet::default_sea();
    let all: Vec<Vec<usize>> = vec![(0..sea.waves.len()).collect(); c.levels() as usize];
    let (eye, t) = (DVec2::new(0.3, 0.2), 77.0);
    // On a lattice vertex of level 0 the mesh height is the sea's height at that rest point.
    let v = c.to_world(DVec2::new(1.5, -2.0));
    let h = c.interpolated_height(&sea, &all, eye, v, t).unwrap();
    assert!((h - sea.displace([v.x, v.y], t)[1]).abs() < 1e-12);
    // Between vertices the error stays within the stated bound Σ A k² L²/8.
    let s = c.cell(0);
    let bound: f64 = sea
        .waves
        .iter()
        .map(|w| {
            let d = c.to_lattice(DVec2::from(w.direction));
            let l = extent_along([d.x, d.y]) * s;
            w.amplitude() * w.k() * w.k() * l * l / 8.0
        })
        .sum();
    let mut worst: f64 = 0.0;
    for k in 0..2000 {
        let p = DVec2::new(-3.0 + 0.00317 * f64::from(k), 2.9 - 0.00291 * f64::from(k));
        let h = c.interpolated_height(&sea, &all, eye, p, t).unwrap();
        let e = (h - sea.displace([p.x, p.y], t)[1]).abs();
        assert!(e <= bound, "{p}: {e} > {bound}");
        worst = worst.max(e);
    }
    // And it is not vacuous: the worst error seen is a good part of it.
    assert!(worst > 0.1 * bound, "{worst} vs {bound}");
    // Outside the map there is no mesh.
    let far = DVec2::new(1e4, 0.0);
    assert!(c.interpolated_height(&sea, &all, eye, far, t).is_none());
}

#[test]
fn interpolated_height_matches_the_emitted_triangles() {
    // The measure's interpolation and the index buffer split cells the same way: the
    // height at a rest point, barycentric over the emitted triangle that holds it.
    let sea = WaveSet::default_sea();
    let target = ErrorTarget::uniform(0.5, 720, 1.0);
    for angle in [0.0, 0.7] {
        let c = ClipMapConfig { angle, ..config() };
        let plan = c.plan(&sea, &target, 8.0);
        let kept: Vec<Vec<usize>> = plan.iter().map(|p| p.kept.clone()).collect();
        let (eye, t) = (DVec2::ZERO, 55.5);
        let m = c.build(eye, &Culling::default());
        let rest = |k: u32| {
            let r = m.vertices[k as usize].rest;
            m.origin + DVec2::new(f64::from(r[0]), f64::from(r[1]))
        };
        for k in 0..300 {
            // Points well inside level 0's unmorphed part (< 6.4 m from its centre).
            let p = DVec2::new(
                -4.0 + 0.0266 * f64::from(k),
                3.5 - 0.024 * f64::from(k % 97) * 3.0,
            );
            let mine = c.interpolated_height(&sea, &kept, eye, p, t).unwrap();
            let tri = m
                .indices
                .chunks(3)
                .filter(|t| m.vertices[t[0] as usize].level == 0)
                .find_map(|t| {
                    let (a, b, d) = (rest(t[0]), rest(t[1]), rest(t[2]));
                    let det = (b - a).perp_dot(d - a);
                    let u = (p - a).perp_dot(d - a) / det;
                    let v = (b - a).perp_dot(p - a) / det;
                    (u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9).then_some((t, u, v))
                })
                .expect("a level-0 triangle holds the point");
            let y =
                |k: u32| vertex_displacement(&sea, &plan, &m.vertices[k as usize], m.origin, t).y;
            let (t3, u, v) = tri;
            let theirs = y(t3[0]) * (1.0 - u - v) + y(t3[1]) * u + y(t3[2]) * v;
            assert!(
                (mine - theirs).abs() < 1e-5,
                "{angle} {p}: {mine} vs {theirs}"
            );
        }
    }
}

#[test]
fn lattice_turns_its_diagonal_across_the_curved_waves() {
    // One wave: whatever its direction, the chosen lattice crosses it with triangles
    // 1/√2 cells long (the least any direction gets), up to the 1° step.
    for direction in [[1.0, 0.0], [0.6, 0.8], [0.8, -0.6]] {
        let mut sea = WaveSet::default_sea();
        sea.waves.truncate(1);
        sea.waves[0].direction = direction;
        let a = lattice_angle(&sea);
        let c = ClipMapConfig {
            angle: a,
            ..config()
        };
        let d = c.to_lattice(DVec2::from(direction));
        let e = extent_along([d.x, d.y]);
        assert!(
            (std::f64::consts::FRAC_1_SQRT_2 - 1e-12..0.72).contains(&e),
            "{e}"
        );
    }
    // The default sea, against an independent scan (Python, 0.1° steps): Σ A k² extent²
    // is 0.42328 m⁻¹ on the axis-aligned lattice and at least 0.24032 (at 53.2°).
    let sea = WaveSet::default_sea();
    let a = lattice_angle(&sea);
    assert!((lattice_bound(&sea, 0.0) - 0.42328).abs() < 1e-5);
    let best = lattice_bound(&sea, a);
    assert!(
        (0.24031..0.2410).contains(&best),
        "{best} at {}°",
        a.to_degrees()
    );
}

#[test]
fn the_extent_bound_is_sharp_for_one_wave_along_each_axis_and_the_diagonal() {
    assert!((extent_along([1.0, 0.0]) - 1.0).abs() < 1e-15);
    assert!((extent_along([0.0, -1.0]) - 1.0).abs() < 1e-15);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!((extent_along([h, h]) - 2f64.sqrt()).abs() < 1e-15);
    // Across the split diagonal, a triangle spans half of it.
    assert!((extent_along([h, -h]) - h).abs() < 1e-15);
    // A wave along x sampled at s with a crest midway between vertices: the linear
    // interpolation misses it by exactly A(1 − cos(ks/2)) ≈ A k² s²/8.
    let (a, k, s): (f64, f64, f64) = (0.5, 0.4, 0.25);
    let exact = a * (1.0 - (k * s / 2.0).cos());
    let bound = a * k * k * (extent_along([1.0, 0.0]) * s).powi(2) / 8.0;
    assert!(exact <= bound && exact > 0.99 * bound, "{exact} vs {bound}");
}

#[test]
fn graded_target_allows_more_far_away_and_costs_fewer_cells() {
    let sea = WaveSet::default_sea();
    let uniform = ErrorTarget::uniform(0.5, 720, 55f64.to_radians());
    let graded = ErrorTarget {
        distance_exponent: 0.5,
        ..uniform
    };
    // Closed form: pixels · max(1, d / 10 m)^γ.
    assert_eq!(graded.pixels_at(4.0), 0.5);
    assert!((graded.pixels_at(1000.0) - 5.0).abs() < 1e-12);
    assert_eq!(uniform.pixels_at(1000.0), 0.5);
    let c = ClipMapConfig::for_view(&sea, &graded, 12.0, 1000.0);
    assert!(c.half_extent(c.levels() - 1) >= 1000.0);
    for (l, p) in c.plan(&sea, &graded, 12.0).iter().enumerate() {
        let allowed = 0.5 * (p.nearest / GRADED_FROM).max(1.0).sqrt();
        assert!((p.allowed_px - allowed).abs() < 1e-12, "level {l}");
        assert!(
            p.error_px <= allowed,
            "level {l}: {} > {allowed} px",
            p.error_px
        );
    }
    let u = ClipMapConfig::for_view(&sea, &uniform, 12.0, 1000.0);
    assert!(
        c.full_triangles() < u.full_triangles(),
        "{} vs {}",
        c.full_triangles(),
        u.full_triangles()
    );
}

#[test]
fn finer_base_ladders_are_never_worse_than_powers_of_two() {
    let sea = WaveSet::default_sea();
    for px in [0.5, 1.0, 3.0] {
        let target = ErrorTarget::uniform(px, 720, 55f64.to_radians());
        let best = ClipMapConfig::for_view(&sea, &target, 12.0, 1000.0);
        let pow2 = ClipMapConfig::for_view_on_ladder(
            &sea,
            &target,
            12.0,
            1000.0,
            LevelRatio::DOUBLING,
            1.0,
        );
        assert!(best.full_triangles() <= pow2.full_triangles(), "{px} px");
        for p in best.plan(&sea, &target, 12.0) {
            assert!(p.error_px <= px, "{px} px: {}", p.error_px);
        }
    }
}

#[test]
fn chosen_config_meets_its_error_target() {
    let sea = WaveSet::default_sea();
    let target = ErrorTarget::uniform(2.0, 720, 55f64.to_radians());
    let c = ClipMapConfig::for_view(&sea, &target, 12.0, 1000.0);
    let plan = c.plan(&sea, &target, 12.0);
    assert!(c.half_extent(c.levels() - 1) >= 1000.0);
    for (l, p) in plan.iter().enumerate() {
        assert!(p.error_px <= 2.0, "level {l}: {} px", p.error_px);
    }
    // Coarser levels evaluate a subset of the finer one's waves.
    for w in plan.windows(2) {
        assert!(w[1].kept.iter().all(|i| w[0].kept.contains(i)));
    }
}

/// Each vertex the mesh emits is used by a drawn cell and is a distinct lattice vertex of its
/// level (no copy at tile borders), and the mesh draws the triangles the tiles draw when each
/// tile emits its own (t + 1)² vertices (the construction before vertices were shared): the
/// same corners, bit for bit, in the same order. Culled by a frustum and a play area, every
/// ratio, a turned lattice.
#[test]
fn shared_vertices_draw_the_per_tile_triangles_and_each_vertex_once() {
    use crate::camera::Camera;
    for c in configs() {
        let eye = DVec2::new(0.7, -1.3);
        let origin = c.origin_for(eye);
        let cam = Camera::look_at(DVec3::new(0.7, 6.0, -1.3), DVec3::new(5.0, 0.0, -30.0), 1e3);
        let culling = Culling {
            frustum: Some(Frustum::from_matrix(cam.view_proj_local(origin, 1.5))),
            play_area: Some([-20.0, -25.0, 18.0, 10.0]),
            max_displacement: 0.5,
        };
        let mesh = c.build(eye, &culling);
        // The oracle: every tile its own vertices.
        let origin_lattice = c.centre_lattice(c.levels() - 1, eye);
        let mut expected: Vec<[[u32; 2]; 3]> = Vec::new();
        let mut lattice_vertices = std::collections::BTreeSet::new();
        c.visit_tiles(eye, &culling, |l, [i0, i1, j0, j1], cells| {
            let t = i64::from(TILE_CELLS).min(i64::from(c.cells[l as usize]) / 2);
            let centre = c.centre_index(l, eye);
            let corner = |i: i64, j: i64| {
                let (p, _) = c.morphed_vertex(l, i, j, centre);
                let q = c.to_world(p - origin_lattice);
                [(q.x as f32).to_bits(), (q.y as f32).to_bits()]
            };
            for j in j0..j1 {
                for i in i0..i1 {
                    if cells & (1 << ((j - j0) * t + (i - i0))) != 0 {
                        for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                            lattice_vertices.insert((l, i + di, j + dj));
                        }
                        let (a, b) = (corner(i, j), corner(i + 1, j));
                        let (d, e) = (corner(i, j + 1), corner(i + 1, j + 1));
                        expected.extend([[a, d, e], [a, e, b]]);
                    }
                }
            }
        });
        let drawn: Vec<[[u32; 2]; 3]> = mesh
            .indices
            .chunks(3)
            .map(|t| [0, 1, 2].map(|c| mesh.vertices[t[c] as usize].rest.map(f32::to_bits)))
            .collect();
        assert!(!drawn.is_empty());
        assert_eq!(drawn, expected, "{:?}", c.ratio);
        let used: std::collections::BTreeSet<u32> = mesh.indices.iter().copied().collect();
        assert_eq!(used.len(), mesh.vertices.len(), "every vertex is used");
        assert_eq!(
            lattice_vertices.len(),
            mesh.vertices.len(),
            "each lattice vertex of a level once"
        );
        // Shared across tile borders: far fewer vertices than the tiles' own.
        let per_tile: u64 = mesh
            .levels
            .iter()
            .map(|s| u64::from(s.tiles_drawn))
            .sum::<u64>()
            * u64::from((TILE_CELLS + 1) * (TILE_CELLS + 1));
        assert!(
            (mesh.vertices.len() as u64) < per_tile,
            "{} of {per_tile}",
            mesh.vertices.len()
        );
    }
}
