//! The wake's band limit per clip-map level and the bins it allows: at every vertex of a real
//! frame, the sum over the vertex's bin equals, bit for bit, the sum over every source the
//! frame sent (each term band limited for the vertex's level spacing), so a bin leaves out only
//! sources whose term is exactly zero there; and the band limit lists fewer (bin, source)
//! pairs than binning without it. On the CPU: the f32 mirror of shaders/ocean/wake.wgsl; and on
//! the GPU (lavapipe in CI), `wake_bin` of shaders/render/water_vertices.wgsl finds, for each
//! vertex and its level, exactly the lists the CPU's `WakeBins::bin_at` finds.

use glam::{DVec2, DVec3};
use ocean::wake::{
    FOAM_EPSILON, TrackSample, Wake, WakeParams, source_height_grad_f32,
    source_height_grad_sampled_f32,
};
use render::Camera;
use render::frame::FrameContext;
use render::wake_bins::{WAKE_BUFFER_BUDGET_BYTES, WakeBins};
use wgpu::util::DeviceExt;

/// Three boats sailing curved courses for 70 s at 4–7 m/s around the origin.
fn fleet_wake() -> (Wake, f64) {
    let t_end = 70.0;
    let tracks: Vec<Vec<TrackSample>> = (0..3)
        .map(|b| {
            let speed = 4.0 + 1.5 * f64::from(b);
            (0..=140)
                .map(|i| {
                    let t = 0.5 * f64::from(i);
                    let a = 0.01 * t * (1.0 + f64::from(b)) + f64::from(b);
                    TrackSample {
                        t,
                        x: -150.0 + 40.0 * f64::from(b) + speed * t * a.cos(),
                        z: -100.0 + speed * t * a.sin(),
                    }
                })
                .collect()
        })
        .collect();
    let refs: Vec<&[TrackSample]> = tracks.iter().map(Vec::as_slice).collect();
    (Wake::new(&refs, WakeParams::default()).unwrap(), t_end)
}

/// The fleet's water at race time `t` through a camera 70 m up.
fn fleet_scene(t: f64) -> render::Scene {
    let mut scene = render::golden::test_scene(t, Vec::new());
    scene.camera = Camera::look_at(
        DVec3::new(-60.0, 70.0, 120.0),
        DVec3::new(-40.0, 0.0, 40.0),
        5000.0,
    );
    scene
}

/// The scene's frame, its wakes binned as the renderer bins them.
fn fleet_frame<'a>(scene: &'a render::Scene, wake: &Wake) -> FrameContext<'a> {
    let mut frame = FrameContext::new(scene, SIZE, 1.0);
    let mut binner = render::wake_bins::WakeBinner::default();
    render::renderer::bin_wakes(
        wake,
        WAKE_BUFFER_BUDGET_BYTES,
        usize::MAX,
        &mut binner,
        &mut frame,
    );
    frame
}

const SIZE: [u32; 2] = [360, 640];

#[test]
fn a_vertex_sums_over_its_bin_exactly_what_it_sums_over_every_source() {
    let (wake, t) = fleet_wake();
    let scene = fleet_scene(t);
    let frame = fleet_frame(&scene, &wake);
    let (sources, bins) = (&frame.wakes.sources, &frame.wake_bins);
    assert!(sources.len() > 500, "{}", sources.len());
    assert_eq!(frame.wake_drop.dropped, 0);
    let o = frame.origin;
    let (mut checked, mut nonzero, mut foamy) = (0usize, 0usize, 0usize);
    for v in frame.mesh.vertices.iter().step_by(3) {
        // Where the compute stage evaluates it: the vertex displaced by the sea.
        let d = scene
            .sea
            .displace([f64::from(v.rest[0]) + o.x, f64::from(v.rest[1]) + o.y], t);
        let p = [(d[0] - o.x) as f32, (d[2] - o.y) as f32];
        let spacing = frame.clipmap.cell(v.level) as f32;
        let listed = bins.listed_at(p, v.level);
        let mut binned = [0.0f32; 3];
        for &k in listed {
            let g = source_height_grad_sampled_f32(&sources[k as usize], p, spacing);
            binned = [binned[0] + g[0], binned[1] + g[1], binned[2] + g[2]];
        }
        let mut every = [0.0f32; 3];
        for (k, s) in sources.iter().enumerate() {
            let g = source_height_grad_sampled_f32(s, p, spacing);
            if g != [0.0; 3] {
                assert!(
                    listed.contains(&(k as u32)),
                    "source {k} adds {g:?} at {p:?} (level {}) but is not in its bin",
                    v.level
                );
            }
            every = [every[0] + g[0], every[1] + g[1], every[2] + g[2]];
        }
        // Terms left out are exact zeros, and x + 0 = x: the sums agree bit for bit.
        assert_eq!(binned, every, "{p:?}");
        // Foam (not band limited): every strip denser than FOAM_EPSILON at p is in the
        // bin's foam list, near the track too, where the height term is nothing; and what
        // the list leaves out is under FOAM_EPSILON per source.
        let foam_listed = bins.foam_listed_at(p);
        let (mut listed_foam, mut every_foam) = (0.0f64, 0.0f64);
        for (k, s) in sources.iter().enumerate() {
            let d2 = (p[0] - s.pos[0]).powi(2) + (p[1] - s.pos[1]).powi(2);
            let density = s.foam * (-d2 / s.foam_w2).exp();
            every_foam += f64::from(density);
            if foam_listed.contains(&(k as u32)) {
                listed_foam += f64::from(density);
            }
            if density > FOAM_EPSILON {
                assert!(
                    foam_listed.contains(&(k as u32)),
                    "source {k}'s foam {density} at {p:?} but not in its bin's foam list"
                );
                foamy += 1;
            }
        }
        assert!(
            every_foam - listed_foam <= f64::from(FOAM_EPSILON) * sources.len() as f64,
            "{every_foam} vs {listed_foam}"
        );
        checked += 1;
        nonzero += usize::from(every[0] != 0.0);
    }
    assert!(
        checked > 1000 && nonzero > checked / 10,
        "{checked} {nonzero}"
    );
    assert!(foamy > 0, "the frame's vertices see some foam");
}

#[test]
fn the_band_limit_lists_fewer_pairs_and_drops_only_sub_mesh_waves() {
    let (wake, t) = fleet_wake();
    let scene = fleet_scene(t);
    let frame = fleet_frame(&scene, &wake);
    let limited = frame.wake_bins.indices.len();
    let g = frame.wake_bins.grid;
    let lo = g.origin;
    let side = 1.0 / g.inv_cell;
    let hi = [lo[0] + g.nx as f32 * side, lo[1] + g.nz as f32 * side];
    let plain = WakeBins::new(&frame.wakes.sources, lo, hi, g.nx.max(g.nz), g.margin);
    assert!(
        (limited as f64) < 0.9 * plain.indices.len() as f64,
        "band limited {limited} vs {}",
        plain.indices.len()
    );
    // What the band limit removes at a vertex is the sources' waves shorter than π vertex
    // spacings: each term it zeroes has k·spacing ≥ 2, each it keeps whole k·spacing ≤ 1.
    let s = &frame.wakes.sources;
    let eye = DVec2::new(scene.camera.eye.x, scene.camera.eye.z) - frame.origin;
    let p = [eye.x as f32, eye.y as f32];
    for src in s.iter().take(400) {
        let full = source_height_grad_f32(src, p);
        let lim = source_height_grad_sampled_f32(src, p, 1.0);
        let d = [p[0] - src.pos[0], p[1] - src.pos[1]];
        let k = src.q / (d[0] * d[0] + d[1] * d[1]);
        if lim == [0.0; 3] && full != [0.0; 3] {
            assert!(k >= 2.0 * 0.999, "k {k}");
        }
        if k <= 1.0 {
            assert_eq!(lim, full);
        }
    }
}

/// The culling tolerance the renderer uses (`WAKE_EPSILON_M`, per source) is below what the
/// screen shows: at every fifth vertex of a frame the wake with the culled sources differs
/// from the wake with every source alive (ε = 1e-9 m) by under a quarter of a pixel in height
/// (the clip-map's own error target is 1 px) and by under 5·10⁻³ in slope: 0.3° of normal
/// tilt, 0.6° of the reflected ray, under one 8-bit level of the sky's colour ramp (0.5 over
/// 90°). The frame's stated bound (`cull_bound`, every culled tail in phase) is far looser.
#[test]
fn culling_errs_by_less_than_the_screen_shows() {
    let (wake, t) = fleet_wake();
    let scene = fleet_scene(t);
    let frame = fleet_frame(&scene, &wake);
    let size = SIZE;
    let eye = DVec2::new(scene.camera.eye.x, scene.camera.eye.z);
    let view = ocean::wake::WakeView::around(
        [eye.x, eye.y],
        frame.clipmap.half_extent(frame.clipmap.levels() - 1),
    );
    let o = frame.origin;
    let all = wake.gpu_sources(t, [o.x, o.y], &view, 1e-9);
    let px_angle = 2.0 * (scene.camera.fov_y / 2.0).tan() / f64::from(size[1]);
    let (mut worst_px, mut worst_slope, mut peak) = (0.0f64, 0.0f64, 0.0f64);
    let mut steepest = 0.0f64;
    for v in frame.mesh.vertices.iter().step_by(5) {
        let spacing = frame.clipmap.cell(v.level) as f32;
        let a = ocean::wake::wake_height_grad_sampled_f32(&all.sources, v.rest, spacing);
        let b = ocean::wake::wake_height_grad_sampled_f32(&frame.wakes.sources, v.rest, spacing);
        let p = DVec3::new(f64::from(v.rest[0]) + o.x, 0.0, f64::from(v.rest[1]) + o.y);
        let pixel = (p - scene.camera.eye).length() * px_angle;
        worst_px = worst_px.max(f64::from((a[0] - b[0]).abs()) / pixel);
        worst_slope = worst_slope.max(f64::from(a[1] - b[1]).hypot(f64::from(a[2] - b[2])));
        peak = peak.max(f64::from(a[0].abs()));
        steepest = steepest.max(f64::from(a[1]).hypot(f64::from(a[2])));
    }
    eprintln!(
        "ε {} m: worst {worst_px:.3} px, slope {worst_slope:.2e} of {steepest:.3}; wake peak \
         {peak:.3} m; stated bound {:.3} m",
        render::renderer::WAKE_EPSILON_M,
        frame.wakes.cull_bound
    );
    assert!(peak > 0.01, "the frame shows a wake: {peak}");
    assert!(worst_px < 0.25, "{worst_px} px");
    assert!(worst_slope < 5e-3, "{worst_slope} of {steepest}");
}

/// `wake_bin(p, level)` on the GPU, one vec4<u32> per input (x, z, level, unused).
const WAKE_BIN_KERNEL: &str = r#"
@group(0) @binding(10) var<storage, read> input: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<u32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&input) {
        return;
    }
    let i = input[id.x];
    output[id.x] = wake_bin(i.xy, u32(i.z));
}
"#;

/// The shader looks a vertex's lists up where the CPU's mirror does: for every third vertex of
/// the frame (displaced by the sea), points around it and outside the grid, each at its level
/// or another level, `wake_bin` returns the same (first, count) of the level's height
/// list and of the foam list as `WakeBins::bin_at` (zeros outside the grid), u32 for u32. The
/// CPU tests above prove those lists lossless, so this carries it to what the GPU sums.
#[test]
fn the_gpu_finds_the_lists_the_cpu_finds() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let (wake, t) = fleet_wake();
    let scene = fleet_scene(t);
    let frame = fleet_frame(&scene, &wake);
    let bins = &frame.wake_bins;
    // Some bins hold more than one level's list.
    assert!(bins.bins.iter().any(|b| b[1] >> 16 > 1));
    let o = frame.origin;
    let levels = frame.clipmap.levels();
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    for (n, v) in frame.mesh.vertices.iter().enumerate().step_by(3) {
        let d = scene
            .sea
            .displace([f64::from(v.rest[0]) + o.x, f64::from(v.rest[1]) + o.y], t);
        let p = [(d[0] - o.x) as f32, (d[2] - o.y) as f32];
        inputs.push([p[0], p[1], v.level as f32, 0.0]);
        // Another level's list at the same point (the slot arithmetic), and a point nudged.
        let other = (v.level + 1 + n as u32) % levels;
        inputs.push([p[0] + 0.37, p[1] - 0.21, other as f32, 0.0]);
    }
    let g = bins.grid;
    let side = 1.0 / g.inv_cell;
    let far = [g.origin[0] + g.nx as f32 * side + 1.0, g.origin[1] - 1.0];
    inputs.push([far[0], far[1], 0.0, 0.0]);
    let device = &gpu.device;
    let buffer = |label, usage, contents: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let uniform = wgpu::BufferUsages::UNIFORM;
    let frame_buffer = buffer("frame", uniform, bytemuck::bytes_of(&frame.uniform));
    let bins_buffer = buffer(
        "wake bins",
        wgpu::BufferUsages::STORAGE,
        bytemuck::cast_slice(&bins.bins),
    );
    let index_buffer = buffer(
        "wake index",
        wgpu::BufferUsages::STORAGE,
        bytemuck::cast_slice(&bins.indices),
    );
    let grid_buffer = buffer("wake grid", uniform, bytemuck::bytes_of(&bins.grid));
    let source = render::shader::source(&[&render::shader::wake(), render::shader::WATER_VERTICES])
        + WAKE_BIN_KERNEL;
    let out = render::compute::run_kernel_in(
        &gpu,
        "wake_bin",
        &source,
        &inputs,
        16,
        &[wgpu::BindGroupEntry {
            binding: 0,
            resource: frame_buffer.as_entire_binding(),
        }],
        &[&[
            wgpu::BindGroupEntry {
                binding: 1,
                resource: bins_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: index_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: grid_buffer.as_entire_binding(),
            },
        ]],
    )
    .expect("the kernel runs");
    let found: &[[u32; 4]] = bytemuck::cast_slice(&out);
    let mut listed = 0usize;
    for (i, gpu_lists) in inputs.iter().zip(found) {
        let cpu = bins.bin_at([i[0], i[1]], i[2] as u32).unwrap_or([0; 4]);
        assert_eq!(*gpu_lists, cpu, "at {:?} level {}", [i[0], i[1]], i[2]);
        listed += cpu[1] as usize;
    }
    assert_eq!(found.last(), Some(&[0; 4]), "outside the grid");
    assert!(
        listed > inputs.len(),
        "the frame's vertices list sources: {listed}"
    );
}
