//! shaders/ocean/wake.wgsl on a real GPU (lavapipe in CI) against its CPU mirror and the f64 terms:
//! a compute pass sums `wake_source_height`, `wake_source_height_grad` and `wake_source_foam`
//! over a frame's source buffer at a grid of local points.

use ocean::wake::{
    GpuWakeSource, TrackSample, WGSL_SIN_ERROR, Wake, WakeParams, WakeView,
    f32_height_error_bound, wake_height_f32, wake_height_grad_f32, wake_wgsl,
};
use wgpu::util::DeviceExt;

#[path = "wake_gpu/bounds.rs"]
mod bounds;

/// The value of `const NAME: f32 = …;` in the wake's WGSL (its generated constants).
fn wgsl_const(name: &str) -> f32 {
    let wgsl = wake_wgsl();
    let line = wgsl
        .lines()
        .find(|l| l.starts_with(&format!("const {name}: f32 = ")))
        .unwrap_or_else(|| panic!("{name} not in the wake's WGSL"));
    let value = line.rsplit("= ").next().unwrap().trim_end_matches(';');
    value.parse().unwrap_or_else(|e| panic!("{line}: {e}"))
}

const MAIN: &str = r#"
@group(0) @binding(0) var<storage, read> wake_sources: array<WakeSource>;
@group(0) @binding(1) var<storage, read> points: array<vec2<f32>>;
@group(0) @binding(2) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&points)) {
        return;
    }
    let p = points[i];
    var h = 0.0;
    var grad = vec3<f32>(0.0);
    var foam = 0.0;
    for (var j = 0u; j < arrayLength(&wake_sources); j++) {
        h += wake_source_height(wake_sources[j], p);
        grad += wake_source_height_grad(wake_sources[j], p);
        foam += wake_source_foam(wake_sources[j], p);
    }
    out[i] = vec4<f32>(h, grad.yz, wake_foam_from_density(foam));
}
"#;

/// The test kernel over `sources` (a frame's source buffer) at local `points`: per point
/// (height, ∂h/∂x, ∂h/∂z, foam) as the GPU sums them.
fn gpu_wake(gpu: &render::gpu::Gpu, sources: &[GpuWakeSource], points: &[[f32; 2]]) -> Vec<[f32; 4]> {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("wake test"),
        // The core's prelude for WORKGROUP_SIZE (the size dispatch_and_read divides by).
        source: wgpu::ShaderSource::Wgsl(
            format!("{}{}\n{MAIN}", render::shader::prelude(), wake_wgsl()).into(),
        ),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("wake test"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let storage = |label, bytes: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage: wgpu::BufferUsages::STORAGE,
        })
    };
    let source_bytes: Vec<u8> = ocean::wake::GpuWakeFrame {
        sources: sources.to_vec(),
        ..Default::default()
    }
    .bytes()
    .to_vec();
    let sources = storage("sources", &source_bytes);
    let point_bytes: Vec<u8> = points
        .iter()
        .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
        .collect();
    let pts = storage("points", &point_bytes);
    let size = (points.len() * 16) as u64;
    let out = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("out"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let bind = render::gpu::buffer_group(
        device,
        "wake test",
        &pipeline.get_bind_group_layout(0),
        &[&sources, &pts, &out],
    );
    let bytes = gpu
        .dispatch_and_read(&pipeline, &[&bind], points.len(), &out)
        .unwrap();
    bytes
        .chunks_exact(16)
        .map(|c| {
            std::array::from_fn(|k| f32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap()))
        })
        .collect()
}

/// A boat turning at 5 m/s, 10 h into a race and 4 km from the course origin: the frame's
/// wake sources around (3990, −1000) and a grid of local points over them.
fn turning_boat() -> (ocean::wake::GpuWakeFrame, Vec<[f32; 2]>) {
    let t_end = 36_000.0;
    let track: Vec<TrackSample> = (0..=120)
        .map(|i| {
            let t = t_end - 60.0 + 0.5 * i as f64;
            let a = 5.0 * (t - t_end) / 80.0;
            TrackSample {
                t,
                x: 4000.0 + 80.0 * a.sin(),
                z: -1000.0 + 80.0 * (1.0 - a.cos()),
            }
        })
        .collect();
    let wake = Wake::new(&[&track], WakeParams::default()).unwrap();
    let origin = [3990.0, -1000.0];
    let view = WakeView::around([3990.0, -1000.0], 40.0);
    let frame = wake.gpu_sources(t_end, origin, &view, 1e-6);
    assert!(frame.sources.len() > 50);
    let points: Vec<[f32; 2]> = (0..64 * 16)
        .map(|i| [-40.0 + 2.5 * (i % 32) as f32, -40.0 + 2.5 * (i / 32) as f32])
        .collect();
    (frame, points)
}

#[test]
fn wake_wgsl_matches_its_cpu_mirror_on_the_gpu() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let (frame, points) = turning_boat();
    let got = gpu_wake(&gpu, &frame.sources, &points);
    let slopes: Vec<[f32; 3]> = points
        .iter()
        .map(|p| wake_height_grad_f32(&frame.sources, *p))
        .collect();
    let peak_slope = slopes
        .iter()
        .map(|g| f64::from(g[1].hypot(g[2])))
        .fold(0.0, f64::max);

    let constants = wake_constants();
    let mut worst = 0.0f64;
    let mut peak = 0.0f64;
    let mut worst_slope = 0.0f64;
    let (mut largest_bound, mut ratio) = (0.0f64, 0.0f64);
    for ((p, g), cpu_slope) in points.iter().zip(&got).zip(&slopes) {
        // Each output against its bound: the exact value of the shader's formula at the
        // GPU's own (f32) inputs, and WGSL's accuracy of each operation
        // (bounds::height_and_gradient). The CPU mirror lies within the same bound.
        let b = bounds::height_and_gradient(&frame.sources, *p, &constants);
        let cpu_h = wake_height_f32(&frame.sources, *p) as f64;
        assert!(
            (cpu_h - b[0].value).abs() <= b[0].error,
            "{p:?}: the CPU mirror {cpu_h} outside {:?}",
            b[0]
        );
        for (c, bc) in b.iter().enumerate() {
            let gpu_value = f64::from(g[c.min(2)]);
            let error = (gpu_value - bc.value).abs();
            ratio = ratio.max(if error == 0.0 { 0.0 } else { error / bc.error });
            assert!(
                error <= bc.error,
                "{p:?}: output {c}: GPU {gpu_value} vs {} ± {:e}",
                bc.value,
                bc.error
            );
        }
        largest_bound = largest_bound.max(b[0].error);
        let ds = f64::from(g[1] - cpu_slope[1]).hypot(f64::from(g[2] - cpu_slope[2]));
        worst_slope = worst_slope.max(ds);
        let foam = bounds::foam(&frame.sources, *p);
        let foam_error = (f64::from(g[3]) - foam.value).abs();
        assert!(
            foam_error <= foam.error && (0.0..=1.0).contains(&g[3]),
            "{p:?}: foam {} vs {} ± {:e}",
            g[3],
            foam.value,
            foam.error
        );
        ratio = ratio.max(if foam_error == 0.0 { 0.0 } else { foam_error / foam.error });
        // The old per-point bound of ocean::wake (first order, 2^-11 sin) still holds too.
        let bound = f32_height_error_bound(&frame.sources, *p, WGSL_SIN_ERROR);
        assert!((g[0] as f64 - cpu_h).abs() <= 2.0 * bound + 1e-7);
        worst = worst.max((g[0] as f64 - cpu_h).abs());
        peak = peak.max(cpu_h.abs());
    }
    eprintln!(
        "{}: wake.wgsl vs CPU mirror, {} sources, max |Δh| {worst:.2e} m (peak {peak:.3} m, \
         largest WGSL bound {largest_bound:.2e} m), max |Δ∇h| {worst_slope:.2e} (peak \
         {peak_slope:.3}); worst error/bound over height, gradient and foam {ratio:.3}",
        gpu.describe(),
        frame.sources.len()
    );
    assert!(peak > 1e-2, "no wake in the test field");
    // A wake that is not the mirror's would leave the bound: the bound is far below the peak.
    assert!(largest_bound < 1e-3 * peak, "bound {largest_bound:e} m");
}

#[test]
fn a_wrong_source_age_fails_the_wake_parity() {
    // The same kernel and check, the GPU given every source's q = g s²/4 1 % larger (an age
    // 0.5 % off): the heights leave their bounds many times over.
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let (frame, points) = turning_boat();
    let broken: Vec<GpuWakeSource> = frame
        .sources
        .iter()
        .map(|s| GpuWakeSource { q: s.q * 1.01, ..*s })
        .collect();
    let got = gpu_wake(&gpu, &broken, &points);
    let constants = wake_constants();
    let ratio = points
        .iter()
        .zip(&got)
        .map(|(p, g)| {
            let b = bounds::height_and_gradient(&frame.sources, *p, &constants);
            (f64::from(g[0]) - b[0].value).abs() / b[0].error
        })
        .fold(0.0, f64::max);
    assert!(ratio > 100.0, "error/bound {ratio:e}");
}

/// The wake's generated constants as the GPU gets them.
fn wake_constants() -> bounds::Constants {
    bounds::Constants {
        min_r2: wgsl_const("WAKE_MIN_R2"),
        gauss_cutoff: wgsl_const("WAKE_GAUSS_CUTOFF"),
        tau: wgsl_const("WAKE_TAU"),
    }
}
