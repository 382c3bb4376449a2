//! Bench section `budget`: the phones' frame budget on paper (issue: the APK).
//!
//! No phone is reachable from these machines, so the budget is an estimate with its method in
//! the open: the frame of the embedded race with wakes and every AR effect is drawn at the
//! phones' screen sizes and at render scales of ¾ and ½ (what the phone's compositor would
//! stretch to the screen) on the adapter at hand, each pass timed with GPU timestamps, and the
//! times are scaled by the ratio of the adapter's *measured* FP32 throughput (an FMA-chain
//! compute kernel, [`measure_gflops`]) to each phone GPU's spec-sheet FP32 peak. That assumes
//! the passes are arithmetic-bound (Gerstner sums, wake sources, optics) and that a phone GPU
//! reaches the same fraction of its peak as the kernel does here; neither is measured on a
//! phone.

use std::time::Instant;

use effects::EffectSet;
use render::{OFFSCREEN_FORMAT, RenderOptions, Renderer};
use serde_json::json;
use wgpu::util::DeviceExt;

use crate::bench::{BenchContext, Table};
use crate::error::{CliError, CliResult};

/// A phone the product targets: its GPU's FP32 peak and screen, and the frame rate goal.
struct Phone {
    name: &'static str,
    gpu: &'static str,
    /// Spec-sheet FP32 peak, GFLOP/s.
    gflops: f64,
    /// Screen, pixels (portrait).
    screen: [u32; 2],
    goal_fps: f64,
}

/// Adreno 540: 567 GFLOP/s FP32 at 710 MHz. PowerVR GE8320 (MediaTek Helio P35): 64 FP32
/// FLOP per clock at 680 MHz = 43.5 GFLOP/s.
const PHONES: [Phone; 2] = [
    Phone {
        name: "Pixel 2 XL",
        gpu: "Adreno 540",
        gflops: 567.0,
        screen: [1440, 2880],
        goal_fps: 60.0,
    },
    Phone {
        name: "OPPO A54",
        gpu: "PowerVR GE8320",
        gflops: 43.5,
        screen: [720, 1600],
        goal_fps: 52.0,
    },
];

/// Independent FMA chains per invocation, 4 lanes each: 32 FLOP per loop iteration.
const FMA_KERNEL: &str = r#"
struct Params { iterations: u32, pad0: u32, pad1: u32, pad2: u32 }
@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = f32(id.x) * 1e-7;
    var a = vec4<f32>(s, s + 0.1, s + 0.2, s + 0.3);
    var b = a + 0.5;
    var c = a + 0.7;
    var d = a + 0.9;
    let m = vec4<f32>(0.9999);
    let k = vec4<f32>(1e-4);
    for (var i = 0u; i < params.iterations; i = i + 1u) {
        a = fma(a, m, k);
        b = fma(b, m, k);
        c = fma(c, m, k);
        d = fma(d, m, k);
    }
    out[id.x] = a + b + c + d;
}
"#;
const FLOP_PER_ITERATION: f64 = 32.0;

/// The FMA kernel compiled on an adapter, with its output buffer.
struct FmaKernel<'a> {
    gpu: &'a render::Gpu,
    pipeline: wgpu::ComputePipeline,
    out: wgpu::Buffer,
}

impl<'a> FmaKernel<'a> {
    /// Invocations per dispatch.
    const INVOCATIONS: u32 = 1 << 20;

    fn new(gpu: &'a render::Gpu) -> Self {
        let device = &gpu.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("fma throughput"),
            source: wgpu::ShaderSource::Wgsl(FMA_KERNEL.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("fma throughput"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let out = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("fma out"),
            size: u64::from(Self::INVOCATIONS) * 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        FmaKernel { gpu, pipeline, out }
    }

    /// The kernel's parameters and output bound for `iterations` loop turns.
    fn group(&self, iterations: u32) -> wgpu::BindGroup {
        let device = &self.gpu.device;
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("fma params"),
            contents: &[iterations.to_le_bytes(), [0; 4], [0; 4], [0; 4]].concat(),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        render::gpu::buffer_group(
            device,
            "fma",
            &self.pipeline.get_bind_group_layout(0),
            &[&params, &self.out],
        )
    }

    /// One dispatch of `iterations` loop turns: wall seconds until the GPU finished it.
    fn time(&self, iterations: u32) -> f64 {
        let group = self.group(iterations);
        let t0 = Instant::now();
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(Self::INVOCATIONS / 64, 1, 1);
        }
        self.gpu.queue.submit([enc.finish()]);
        self.gpu.wait();
        t0.elapsed().as_secs_f64()
    }
}

/// The adapter's FP32 throughput, GFLOP/s: the FMA kernel over 2²⁰ invocations, its loop
/// doubled until one dispatch takes ≥ `min_s` seconds, then the median of three.
pub fn measure_gflops(gpu: &render::Gpu, min_s: f64) -> Result<f64, render::GpuError> {
    let kernel = FmaKernel::new(gpu);
    kernel.time(1); // compile and warm up
    let mut iterations = 16u32;
    while kernel.time(iterations) < min_s && iterations < 1 << 24 {
        iterations *= 2;
    }
    let mut times: Vec<f64> = (0..3).map(|_| kernel.time(iterations)).collect();
    times.sort_by(f64::total_cmp);
    let flop = f64::from(FmaKernel::INVOCATIONS) * f64::from(iterations) * FLOP_PER_ITERATION;
    let gflops = flop / times[1] / 1e9;
    if gflops.is_finite() && gflops > 0.0 {
        Ok(gflops)
    } else {
        Err(render::GpuError(format!(
            "the FMA kernel gave no throughput ({gflops} GFLOP/s)"
        )))
    }
}

/// The passes that ran, each with its median GPU milliseconds where measured.
type PassTimes = Vec<(String, Option<f64>)>;

/// Per-pass GPU milliseconds (median over `frames`) of the sample race at `size` with wakes
/// and every effect, and the median wall milliseconds of a frame.
fn pass_times(gpu: &render::Gpu, size: [u32; 2], frames: usize) -> CliResult<(PassTimes, f64)> {
    use crate::core::scene::{race_wake, scene_at};
    let race = race::Race::sample();
    let sea = ocean::WaveSet::default_sea();
    let t = 600.0;
    let scene = scene_at(&race, &sea, t, None);
    let mut renderer = Renderer::new(gpu, OFFSCREEN_FORMAT, RenderOptions::default());
    renderer.set_wake(Some(race_wake(&race)?));
    effects::passes::add_scene_effects(&mut renderer, gpu, &scene, size, EffectSet::ALL);
    let view = crate::bench::offscreen(gpu, size);
    let failed = |e: render::GpuError| CliError(e.to_string());
    renderer.render(gpu, &view, size, &scene).map_err(failed)?; // warm-up: pipelines, buffers
    let mut runs = Vec::new();
    let mut wall = Vec::new();
    for _ in 0..frames {
        let t0 = Instant::now();
        let report = renderer.render(gpu, &view, size, &scene).map_err(failed)?;
        gpu.wait();
        wall.push(t0.elapsed().as_secs_f64() * 1e3);
        runs.push(report.passes);
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let passes = runs[0]
        .iter()
        .enumerate()
        .filter(|(_, p)| p.ran)
        .map(|(i, p)| {
            let ms: Vec<f64> = runs.iter().filter_map(|r| r[i].total_gpu_ms()).collect();
            (p.name.clone(), median(ms))
        })
        .collect();
    Ok((passes, median(wall).unwrap_or(f64::NAN)))
}

/// Section `budget`.
pub fn run(ctx: &BenchContext) -> CliResult<Vec<Table>> {
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| CliError::new(format!("the budget bench needs a GPU adapter: {e}")))?;
    ctx.progress("budget: measuring the adapter's FP32 throughput");
    let gflops = measure_gflops(&gpu, if ctx.quick { 0.05 } else { 0.25 })
        .map_err(|e| CliError::new(format!("budget: {e}")))?;
    // Render scales: the frame drawn at a fraction of the screen per side, which the phone's
    // compositor stretches to the screen (the clip-map's pixel error target follows the
    // render size). Quick: the half scale only, so small machines finish in seconds.
    let scales: &[f64] = if ctx.quick { &[0.5] } else { &[1.0, 0.75, 0.5] };
    let frames = if ctx.quick { 2 } else { 5 };
    let mut passes_table = Table::new(
        "budget_passes",
        "Frame of the sample race with wakes and every AR effect: GPU ms per pass on this adapter",
        &["pass", "size", "GPU ms (median)"],
    );
    let mut phones = Table::new(
        "budget_phones",
        "Phone frame budget on paper: this adapter's times scaled by measured FP32 throughput to each phone's peak",
        &[
            "phone",
            "GPU",
            "FP32 peak GFLOP/s",
            "screen",
            "render scale",
            "render size",
            "measured here ms",
            "estimated phone ms",
            "estimated fps",
            "goal fps",
            "speed-up still needed",
        ],
    );
    for (phone, &scale) in PHONES
        .iter()
        .flat_map(|p| scales.iter().map(move |s| (p, s)))
    {
        let size = phone
            .screen
            .map(|v| ((f64::from(v) * scale).round() as u32).max(1));
        ctx.progress(format!(
            "budget: {} frame at {}×{}",
            phone.name, size[0], size[1]
        ));
        let (passes, wall_ms) = pass_times(&gpu, size, frames)?;
        let gpu_total: Option<f64> = passes.iter().map(|(_, ms)| *ms).sum();
        for (name, ms) in &passes {
            passes_table.row(vec![
                json!(name),
                json!(format!("{}×{}", size[0], size[1])),
                json!(ms),
            ]);
        }
        // GPU timestamps where the adapter has them, else the frame's wall time.
        let here = gpu_total.unwrap_or(wall_ms);
        let est = here * gflops / phone.gflops;
        let budget_ms = 1e3 / phone.goal_fps;
        phones.row(vec![
            json!(phone.name),
            json!(phone.gpu),
            json!(phone.gflops),
            json!(format!("{}×{}", phone.screen[0], phone.screen[1])),
            json!(scale),
            json!(format!("{}×{}", size[0], size[1])),
            json!(here),
            json!(est),
            json!(1e3 / est),
            json!(phone.goal_fps),
            json!((est / budget_ms).max(1.0)),
        ]);
    }
    let adapter = gpu.describe();
    passes_table.note(format!(
        "{adapter}; race time 600 s, the default camera, {frames} frames after one warm-up, \
         median GPU time per pass from timestamp queries (empty where the adapter has none)."
    ));
    phones.note(format!(
        "This adapter's measured FP32 throughput: {gflops:.1} GFLOP/s (an FMA-chain compute \
         kernel, 2^20 invocations). Estimated phone ms = measured ms at the render size × \
         {gflops:.1} / the phone's FP32 peak. Assumes arithmetic-bound passes and the same \
         fraction of peak on the phone as here (a big GPU that a phone-sized frame cannot fill \
         makes the estimate pessimistic); bandwidth, tiling and thermal limits are not \
         modelled, and no phone was measured."
    ));
    Ok(vec![phones, passes_table])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FLOP the throughput is credited with, counted independently from the kernel's
    /// text: the `fma` calls in its loop body, each on a `vec4<f32>` (4 lanes, 2 FLOP each).
    #[test]
    fn the_kernel_does_the_flop_it_is_credited_with() {
        let body_start = FMA_KERNEL.find("for (").expect("a loop");
        let open = body_start + FMA_KERNEL[body_start..].find('{').unwrap();
        let close = open + FMA_KERNEL[open..].find('}').unwrap();
        let body = &FMA_KERNEL[open + 1..close];
        let fmas = body.matches("fma(").count();
        assert!(
            !body.contains('{'),
            "nested block in the loop: count by hand"
        );
        // Each chain is a vec4 (a declared as one; b, c, d are a plus a scalar).
        assert!(FMA_KERNEL.contains("var a = vec4<f32>("));
        for v in ["b", "c", "d"] {
            assert!(FMA_KERNEL.contains(&format!("var {v} = a + ")), "{v}");
        }
        assert_eq!(
            fmas as f64 * 4.0 * 2.0,
            FLOP_PER_ITERATION,
            "{fmas} fma per turn"
        );
    }

    /// The kernel really runs `iterations` turns on the GPU (a dropped parameter or a loop
    /// optimised away would credit FLOP never done): its output against the chain in f32.
    #[test]
    fn the_kernel_computes_the_chain_it_is_timed_for() {
        let Some(gpu) = render::gpu::test_gpu() else {
            return;
        };
        let kernel = FmaKernel::new(&gpu);
        let iterations = 1000u32;
        let bytes = gpu
            .dispatch_and_read(
                &kernel.pipeline,
                &[&kernel.group(iterations)],
                FmaKernel::INVOCATIONS as usize,
                &kernel.out,
            )
            .expect("read back");
        for id in [0u32, 1, 4097, FmaKernel::INVOCATIONS - 1] {
            let s = id as f32 * 1e-7;
            // Lane l of chain a starts at s + l/10; b, c, d at a + 0.5, 0.7, 0.9; out = a+b+c+d.
            let want: [f32; 4] = std::array::from_fn(|lane| {
                let a0 = s + [0.0, 0.1, 0.2, 0.3][lane];
                [0.0f32, 0.5, 0.7, 0.9]
                    .iter()
                    .map(|offset| (0..iterations).fold(a0 + offset, |x, _| x.mul_add(0.9999, 1e-4)))
                    .sum()
            });
            let at = id as usize * 16;
            for (lane, w) in want.iter().enumerate() {
                let got =
                    f32::from_le_bytes(bytes[at + 4 * lane..at + 4 * lane + 4].try_into().unwrap());
                // Fused or not, f32 rounding over 1000 turns stays below 1e-4; half the turns
                // would be off by about 0.1.
                assert!(
                    (got - w).abs() < 1e-4,
                    "invocation {id} lane {lane}: {got} vs {w}"
                );
            }
        }
    }

    /// The measured rate is plausible for the adapter: on a CPU adapter (lavapipe in CI) no more
    /// than its cores can do (6 GHz, two 16-lane FMA units: 64 FLOP per cycle per core), on a
    /// GPU below 500 TFLOP/s FP32; above 1 GFLOP/s everywhere (lavapipe on one core does
    /// several).
    #[test]
    fn the_throughput_kernel_measures_a_plausible_rate() {
        let Some(gpu) = render::gpu::test_gpu() else {
            return;
        };
        let g = measure_gflops(&gpu, 0.02).expect("a rate");
        let info = gpu.adapter.get_info();
        let ceiling = if info.device_type == wgpu::DeviceType::Cpu {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            cores as f64 * 6.0 * 64.0
        } else {
            5e5
        };
        eprintln!("{}: {g:.1} GFLOP/s (ceiling {ceiling:.0})", gpu.describe());
        assert!(g > 1.0 && g < ceiling, "{g} GFLOP/s (ceiling {ceiling})");
    }
}
