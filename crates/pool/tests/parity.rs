//! The pool's mirrored WGSL ray functions on the GPU (`render::compute::run_kernel`, lavapipe
//! in CI) against the f64 references of `pool::geometry` and `pool::trace` (`hit_sphere`,
//! `box_inside`, `tile_albedo`), each shown to fail on a broken input fed through the same
//! path. (The water trace and the caustics have theirs in the crate's
//! `gpu_tests`.) Skipped without an adapter unless REGATTA_REQUIRE_GPU=true.

use glam::DVec3;
use pool::PoolScene;
use pool::geometry::{Face, PoolBox, Ray, Sphere};
use pool::gpu::PoolUniform;
use pool::trace::{GROUT, TILE, tile_albedo};
use render::gpu::{Gpu, test_gpu};
use wgpu::util::DeviceExt;

#[path = "parity/bounds.rs"]
mod bounds;

/// One ray against one sphere: origin, direction (unit), sphere centre and radius.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Case {
    origin: [f32; 4],
    dir: [f32; 4],
    sphere: [f32; 4],
}

/// `hit_sphere` of `pool_common.wgsl` for each case (NO_HIT = −1 for a miss).
fn wgsl_hits(gpu: &Gpu, cases: &[Case]) -> Vec<f32> {
    let kernel = r#"
struct Case { origin: vec4<f32>, dir: vec4<f32>, sphere: vec4<f32> }
@group(0) @binding(10) var<storage, read> input: array<Case>;
@group(0) @binding(11) var<storage, read_write> output: array<f32>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let c = input[id.x];
        output[id.x] = hit_sphere(c.origin.xyz, c.dir.xyz, PoolSphere(c.sphere, vec4<f32>(0.0)));
    }
}
"#;
    let prelude = pool::wgsl::prelude();
    let src = render::shader::source(&[&prelude, pool::gpu::POOL_COMMON, kernel]);
    let bytes = render::compute::run_kernel(gpu, "sphere hit parity", &src, cases, 4)
        .expect("the kernel runs");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Rays from a ring of origins 1–3 m from spheres of 0.1–0.3 m, aimed at, beside and away
/// from them: hits, grazes and misses.
fn rays() -> Vec<(Ray, Sphere)> {
    let mut out = Vec::new();
    for k in 0..400 {
        let a = f64::from(k) * 0.157;
        let sphere = Sphere {
            center: DVec3::new(0.2 * a.sin(), -0.3 + 0.1 * (k % 5) as f64, 0.1 * a.cos()),
            radius: 0.1 + 0.05 * (k % 5) as f64,
        };
        let origin = sphere.center
            + DVec3::new(a.cos(), 0.3 * (k % 3) as f64, a.sin()) * (1.0 + 0.005 * (k % 400) as f64);
        let aim = sphere.center + DVec3::new(0.0, 0.0, 0.01 * (k % 100) as f64 - 0.5);
        out.push((Ray::new(origin, aim - origin), sphere));
    }
    out
}

fn cases(rays: &[(Ray, Sphere)]) -> Vec<Case> {
    let v = |d: DVec3, w: f64| [d.x as f32, d.y as f32, d.z as f32, w as f32];
    rays.iter()
        .map(|(r, s)| Case {
            origin: v(r.origin, 0.0),
            dir: v(r.dir, 0.0),
            sphere: v(s.center, s.radius),
        })
        .collect()
}

/// The GPU hits against `Sphere::hit`, each against its own bound (`bounds::hit_sphere`: near
/// grazing the discriminant is small and its square root magnifies its error): the largest
/// distance error, metres, the largest bound, the largest error/bound ratio, how many hits or
/// misses disagree, and the rays a conforming GPU may decide either way (not bounded).
struct SphereErrors {
    worst: f64,
    bound: f64,
    ratio: f64,
    disagree: usize,
    undecided: usize,
}

fn compare(got: &[f32], rays: &[(Ray, Sphere)]) -> SphereErrors {
    let mut e = SphereErrors {
        worst: 0.0,
        bound: 0.0,
        ratio: 0.0,
        disagree: 0,
        undecided: 0,
    };
    let truth = cases(rays);
    for ((g, (ray, sphere)), c) in got.iter().zip(rays).zip(&truth) {
        let bound = bounds::hit_sphere(
            (ray.origin, c.origin),
            (ray.dir, c.dir),
            (sphere.center, sphere.radius, c.sphere),
        );
        let bound = match bound {
            bounds::Bounded::Decided(b) => b,
            bounds::Bounded::Undecided => {
                e.undecided += 1;
                continue;
            }
        };
        match (sphere.hit(ray), bound) {
            (Some(s), Some(b)) if *g >= 0.0 => {
                assert!((b.value - s).abs() < 1e-9, "{} {s}", b.value);
                let error = (f64::from(*g) - s).abs();
                e.worst = e.worst.max(error);
                e.bound = e.bound.max(b.error);
                e.ratio = e.ratio.max(error / b.error);
            }
            (None, None) if *g < 0.0 => {}
            _ => e.disagree += 1,
        }
    }
    e
}

#[test]
fn the_wgsl_sphere_hit_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let rays = rays();
    let cases = cases(&rays);
    let got = wgsl_hits(&gpu, &cases);
    let e = compare(&got, &rays);
    let hits = got.iter().filter(|g| **g >= 0.0).count();
    eprintln!(
        "hit_sphere: {} rays, {hits} hits ({} undecided), worst |Δs| {:.2e} m, largest bound \
         {:.2e} m, worst error/bound {:.3}",
        rays.len(),
        e.undecided,
        e.worst,
        e.bound,
        e.ratio
    );
    assert!(
        hits > 50 && hits < rays.len() - 50,
        "{hits} hits of {}",
        rays.len()
    );
    // Grazing rays (a discriminant within its bound of 0) may go either way on a conforming
    // GPU: 2 of these 400; every other hit or miss agrees.
    assert_eq!(e.disagree, 0);
    assert!(e.undecided <= 4, "{} undecided", e.undecided);
    // Each distance within its bound: two dot products, sqrt (1.0/inverseSqrt: 2 + 2.5 ULP)
    // of the discriminant, inputs rounded to f32.
    assert!(e.ratio <= 1.0, "error/bound {:e}", e.ratio);
}

#[test]
fn a_broken_sphere_fails_the_sphere_hit_parity() {
    // The same kernel and check, the GPU given spheres 1 cm larger than the reference's.
    let Some(gpu) = test_gpu() else { return };
    let rays = rays();
    let mut broken = cases(&rays);
    for c in &mut broken {
        c.sphere[3] += 0.01;
    }
    let got = wgsl_hits(&gpu, &broken);
    let e = compare(&got, &rays);
    assert!(
        e.ratio > 100.0 || e.disagree > 0,
        "error/bound {:e}, {} disagree",
        e.ratio,
        e.disagree
    );
}

// ---- the box (box_inside, tile_albedo): the pool uniform's box bound as group 1 ----------------

/// The default pool's box as the GPU gets it (f32), and the same values as the reference's.
fn pool_box() -> ([f32; 4], PoolBox) {
    let b = PoolScene::default().pool;
    let gpu = [b.half_x, b.half_z, b.floor_y, b.rim_y].map(|v| v as f32);
    let [half_x, half_z, floor_y, rim_y] = gpu.map(f64::from);
    let reference = PoolBox {
        half_x,
        half_z,
        floor_y,
        rim_y,
    };
    (gpu, reference)
}

/// Run `kernel` (after the pool's shared WGSL, with `prelude` as the pool's) on `input` with
/// the pool uniform's box `box_` bound, `out` bytes per item.
fn run_on_box<In: bytemuck::Pod>(
    gpu: &Gpu,
    prelude: &str,
    kernel: &str,
    box_: [f32; 4],
    input: &[In],
    out: usize,
) -> Vec<u8> {
    let mut pool: PoolUniform = bytemuck::Zeroable::zeroed();
    pool.box_ = box_;
    let uniform = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("pool uniform"),
            contents: bytemuck::bytes_of(&pool),
            usage: wgpu::BufferUsages::UNIFORM,
        });
    let group = [wgpu::BindGroupEntry {
        binding: 0,
        resource: uniform.as_entire_binding(),
    }];
    let src = render::shader::source(&[prelude, pool::gpu::POOL_COMMON, kernel]);
    render::compute::run_kernel_with(gpu, "pool box parity", &src, input, out, &[&group])
        .expect("the kernel runs")
}

/// `box_inside` for each (origin, unit direction): ((point, s), (normal, face)).
fn wgsl_box_exits(gpu: &Gpu, box_: [f32; 4], rays: &[[[f32; 4]; 2]]) -> Vec<[[f32; 4]; 2]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 2>>;
@group(0) @binding(11) var<storage, read_write> output: array<array<vec4<f32>, 2>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let h = box_inside(input[id.x][0].xyz, input[id.x][1].xyz);
        output[id.x] = array<vec4<f32>, 2>(vec4<f32>(h.point, h.s), vec4<f32>(h.normal, f32(h.face)));
    }
}
"#;
    let bytes = run_on_box(gpu, &pool::wgsl::prelude(), kernel, box_, rays, 32);
    bytemuck::cast_slice(&bytes).to_vec()
}

/// Origins on a 5 × 5 × 5 grid through the box (its walls, floor and rim included), each with
/// 64 directions spread over the sphere (a Fibonacci lattice), the six axes and the level
/// diagonals (no vertical part: neither the floor nor the top is a candidate).
fn box_rays(b: &PoolBox) -> Vec<[[f32; 4]; 2]> {
    let mut dirs: Vec<DVec3> = (0..64)
        .map(|k| {
            let y = 1.0 - (f64::from(k) + 0.5) / 32.0;
            let a = 2.399_963 * f64::from(k);
            let r = (1.0 - y * y).sqrt();
            DVec3::new(r * a.cos(), y, r * a.sin())
        })
        .collect();
    dirs.extend([
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ]);
    dirs.extend((0..4).map(|k| {
        let a = 0.785 + 1.571 * f64::from(k);
        DVec3::new(a.cos(), 0.0, a.sin())
    }));
    let lerp = |lo: f64, hi: f64, i: i32| lo + (hi - lo) * f64::from(i) / 4.0;
    let mut out = Vec::new();
    for k in 0..125 {
        let o = DVec3::new(
            lerp(-b.half_x, b.half_x, k % 5),
            lerp(b.floor_y, b.rim_y, k / 5 % 5),
            lerp(-b.half_z, b.half_z, k / 25),
        );
        let v = |d: DVec3| [d.x as f32, d.y as f32, d.z as f32, 0.0];
        out.extend(dirs.iter().map(|d| [v(o), v(*d)]));
    }
    out
}

/// The face number `box_inside` gives the open top (`FACE_NONE` of the pool's prelude).
fn face_none() -> f32 {
    match pool::wgsl::shared_consts()
        .iter()
        .find(|(n, _)| *n == "FACE_NONE")
    {
        Some((_, render::shader::WgslValue::U32(v))) => *v as f32,
        other => panic!("FACE_NONE: {other:?}"),
    }
}

/// The face numbers of `box_inside`: west, east, north, south, floor, and the open top.
fn face_numbers() -> [u32; 6] {
    [
        Face::West as u32,
        Face::East as u32,
        Face::North as u32,
        Face::South as u32,
        Face::Floor as u32,
        face_none() as u32,
    ]
}

/// Against `PoolBox::hit_inside` at the same (f32) rays, each against its own bound
/// (`bounds::box_exits`): the GPU's face must be one a conforming GPU may pick (an exit whose
/// distance lies within the errors of the smallest: at an edge, either face), its distance
/// and point within that exit's bound of the reference's. Returns the largest error of the
/// exit point and distance, metres, the largest bound, the largest error/bound ratio, the
/// rays that left through another face that a conforming GPU may pick (at an edge), and the
/// rays whose face no conforming GPU picks.
struct BoxErrors {
    worst: f64,
    bound: f64,
    ratio: f64,
    at_edges: usize,
    disagree: usize,
}

fn compare_box_exits(got: &[[[f32; 4]; 2]], rays: &[[[f32; 4]; 2]], b: &PoolBox) -> BoxErrors {
    let dvec = |v: [f32; 4]| DVec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
    let box_ = pool_box().0;
    let mut e = BoxErrors {
        worst: 0.0,
        bound: 0.0,
        ratio: 0.0,
        at_edges: 0,
        disagree: 0,
    };
    let none = face_none();
    for ([hit, normal], [o4, d4]) in got.iter().zip(rays) {
        let (o, d) = (dvec(*o4), dvec(*d4));
        let want = b.hit_inside(&Ray { origin: o, dir: d });
        let face = normal[3];
        let exits = bounds::box_exits(box_, *o4, *d4, face_numbers());
        let Some(exit) = exits.iter().find(|x| x.face as f32 == face) else {
            e.disagree += 1;
            continue;
        };
        let want_face = want.map_or(none, |h| h.face as u32 as f32);
        if face != want_face {
            e.at_edges += 1;
        }
        let Some(h) = want else { continue };
        if face == want_face && normal[..3] != h.normal.as_vec3().to_array() {
            e.disagree += 1;
        }
        // The reference's distance against the picked exit's bound (its value differs from
        // the reference's by the distance between the two candidates at an edge).
        let s_bound = (exit.s.value.max(0.0) - h.s).abs() + exit.s.error;
        let point = bounds::exit_point(*o4, *d4, exit.s);
        let errors = [
            (f64::from(hit[3]) - h.s).abs() / s_bound,
            (f64::from(hit[0]) - h.point.x).abs()
                / ((point[0].value - h.point.x).abs() + point[0].error),
            (f64::from(hit[1]) - h.point.y).abs()
                / ((point[1].value - h.point.y).abs() + point[1].error),
            (f64::from(hit[2]) - h.point.z).abs()
                / ((point[2].value - h.point.z).abs() + point[2].error),
        ];
        e.worst = e
            .worst
            .max((dvec(*hit) - h.point).length())
            .max((f64::from(hit[3]) - h.s).abs());
        e.bound = e.bound.max(s_bound);
        e.ratio = errors
            .iter()
            .map(|r| if r.is_nan() { 0.0 } else { *r })
            .fold(e.ratio, f64::max);
    }
    e
}

#[test]
fn the_wgsl_box_exit_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let (box_, b) = pool_box();
    let rays = box_rays(&b);
    let got = wgsl_box_exits(&gpu, box_, &rays);
    let e = compare_box_exits(&got, &rays, &b);
    let faces: Vec<usize> = (0..6)
        .map(|f| got.iter().filter(|g| g[1][3] == f as f32).count())
        .collect();
    eprintln!(
        "box_inside: {} rays (floor, west, east, north, south, top: {faces:?}), worst |Δ| \
         {:.2e} m, largest bound {:.2e} m, worst error/bound {:.3}, {} at an edge on another \
         face",
        rays.len(),
        e.worst,
        e.bound,
        e.ratio,
        e.at_edges
    );
    assert_eq!(e.disagree, 0);
    assert!(faces.iter().all(|&n| n > 100), "{faces:?}");
    // s = (bound − o)/d: a subtraction and a division (2.5 ULP), the point o + d·s.
    assert!(e.ratio <= 1.0, "error/bound {:e}", e.ratio);
}

#[test]
fn a_broken_box_fails_the_box_exit_parity() {
    // The same kernel and check, the GPU's box 1 cm wider (x) than the reference's.
    let Some(gpu) = test_gpu() else { return };
    let (mut box_, b) = pool_box();
    box_[0] += 0.01;
    let rays = box_rays(&b);
    let got = wgsl_box_exits(&gpu, box_, &rays);
    let e = compare_box_exits(&got, &rays, &b);
    assert!(
        e.ratio > 100.0 || e.disagree > 0,
        "error/bound {:e}, {} disagree",
        e.ratio,
        e.disagree
    );
}

/// `tile_albedo` for each (point, face as w), with `prelude` as the pool's.
fn wgsl_albedos(gpu: &Gpu, prelude: &str, points: &[[f32; 4]]) -> Vec<[f32; 4]> {
    let kernel = r#"
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&input) {
        let p = input[id.x];
        output[id.x] = vec4<f32>(tile_albedo(u32(p.w), p.xyz), 0.0);
    }
}
"#;
    let bytes = run_on_box(gpu, prelude, kernel, pool_box().0, points, 16);
    bytemuck::cast_slice(&bytes).to_vec()
}

/// The width, metres, within which a conforming GPU may put a point on either side of a tile
/// edge: `bounds::tile_edge_width` at the box's largest coordinate.
fn tile_border() -> f64 {
    let b = pool_box().1;
    let extent = b
        .half_x
        .max(b.half_z)
        .max(b.rim_y.abs())
        .max(b.floor_y.abs());
    let border = bounds::tile_edge_width(extent, TILE, GROUT, b.rim_y);
    // Far below the grout (a broken grout moves edges by a whole grout width).
    assert!(border < GROUT / 100.0, "{border}");
    border
}

const FACES: [Face; 5] = [
    Face::Floor,
    Face::West,
    Face::East,
    Face::North,
    Face::South,
];

/// Points on each face: a 97 × 61 grid over it (a step that no tile divides), and lines along
/// the tile borders (k·TILE), the grout's inner edges (k·TILE + GROUT), the band's lower edge
/// (TILE·2 below the rim) and the floor's lane (|z| = TILE, |x| = half_x − TILE).
fn tile_points(b: &PoolBox) -> Vec<[f32; 4]> {
    let mut edges: Vec<f64> = (-12..=12).map(|k| f64::from(k) * TILE).collect();
    edges.extend((-12..=12).map(|k| f64::from(k) * TILE + GROUT));
    edges.extend([b.rim_y - 2.0 * TILE, b.half_x - TILE, TILE - b.half_x]);
    let mut out = Vec::new();
    for face in FACES {
        // (u, v) over the face, and the point.
        let (u_range, v_range) = match face {
            Face::Floor => ((-b.half_x, b.half_x), (-b.half_z, b.half_z)),
            Face::West | Face::East => ((-b.half_z, b.half_z), (b.floor_y, b.rim_y)),
            Face::North | Face::South => ((-b.half_x, b.half_x), (b.floor_y, b.rim_y)),
        };
        let point = |u: f64, v: f64| match face {
            Face::Floor => DVec3::new(u, b.floor_y, v),
            Face::West => DVec3::new(-b.half_x, v, u),
            Face::East => DVec3::new(b.half_x, v, u),
            Face::North => DVec3::new(u, v, -b.half_z),
            Face::South => DVec3::new(u, v, b.half_z),
        };
        let at = |r: (f64, f64), i: usize, n: usize| r.0 + (r.1 - r.0) * i as f64 / n as f64;
        let mut uv: Vec<(f64, f64)> = (0..97 * 61)
            .map(|k| (at(u_range, k % 97, 96), at(v_range, k / 97, 60)))
            .collect();
        for &e in &edges {
            for i in 0..=40 {
                uv.push((e, at(v_range, i, 40)));
                uv.push((at(u_range, i, 40), e));
            }
        }
        for (u, v) in uv {
            let p = point(u, v);
            if b.contains(p, 1e-9) {
                out.push([p.x as f32, p.y as f32, p.z as f32, face as u32 as f32]);
            }
        }
    }
    out
}

/// Against `trace::tile_albedo` at the same (f32) points: how many colours differ where the
/// reference is the same within `border` metres every way, and how many points lie within
/// `border` of a tile, grout, band or lane edge (there either neighbour's colour is right).
fn compare_albedos(got: &[[f32; 4]], points: &[[f32; 4]], border: f64) -> (usize, usize) {
    let scene = PoolScene {
        pool: pool_box().1,
        ..PoolScene::default()
    };
    let (mut wrong, mut at_borders) = (0, 0);
    for (g, p) in got.iter().zip(points) {
        let face = FACES[p[3] as usize];
        let q = DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
        let colour = |q: DVec3| tile_albedo(&scene, face, q).map(|c| c as f32);
        let near: Vec<[f32; 3]> = (0..27)
            .map(|k| {
                let step = |i: i32| f64::from(i % 3 - 1) * border;
                colour(q + DVec3::new(step(k), step(k / 3), step(k / 9)))
            })
            .collect();
        let unique = near.iter().all(|c| *c == near[0]);
        at_borders += usize::from(!unique);
        if !near.contains(&[g[0], g[1], g[2]]) || (unique && [g[0], g[1], g[2]] != colour(q)) {
            wrong += 1;
        }
    }
    (wrong, at_borders)
}

#[test]
fn the_wgsl_tile_albedo_is_the_f64_one() {
    let Some(gpu) = test_gpu() else { return };
    let points = tile_points(&pool_box().1);
    let got = wgsl_albedos(&gpu, &pool::wgsl::prelude(), &points);
    // Within `border` of a tile, grout, band or lane edge either colour is right: how far a
    // conforming GPU may move an edge at the pool's largest coordinate (bounds::tile_edge_width).
    let border = tile_border();
    let (wrong, at_borders) = compare_albedos(&got, &points, border);
    let colours: std::collections::HashSet<[u32; 3]> = got
        .iter()
        .map(|g| [g[0], g[1], g[2]].map(f32::to_bits))
        .collect();
    eprintln!(
        "tile_albedo: {} points, {at_borders} within {border:.2e} m of an edge, {wrong} wrong",
        points.len()
    );
    assert_eq!(wrong, 0);
    // Tiles, grout, band and lane all appear; the border lines are in the set.
    assert_eq!(colours.len(), 3);
    assert!(at_borders > 1000, "{at_borders}");
}

#[test]
fn a_broken_grout_fails_the_tile_albedo_parity() {
    // The same kernel and check with the grout written as its own literal, doubled.
    let Some(gpu) = test_gpu() else { return };
    let prelude = pool::wgsl::prelude();
    let line = format!("const GROUT: f32 = {:?};", GROUT as f32);
    assert!(prelude.contains(&line), "{prelude}");
    let broken = prelude.replace(
        &line,
        &format!("const GROUT: f32 = {:?};", 2.0 * GROUT as f32),
    );
    let points = tile_points(&pool_box().1);
    let got = wgsl_albedos(&gpu, &broken, &points);
    let (wrong, _) = compare_albedos(&got, &points, tile_border());
    assert!(wrong > 1000, "{wrong} wrong");
}
