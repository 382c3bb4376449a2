//! Bench section `budget`: the phones' frame budget per quality tier, two ways
//! ([`super::budget_run`] runs it):
//!
//! - timed: the frame is drawn on the adapter at hand and timed (GPU timestamps), and the FP32
//!   throughput of the adapter is measured with an FMA-chain kernel ([`FmaKernel`]) *in the
//!   same run, alternating with the frame*: each repetition gives one ratio frame time ×
//!   measured GFLOP/s ÷ the phone's FP32 peak, and the estimate is the median of the ratios, so
//!   a load that slows the machine slows both and cancels;
//! - modelled: the work of each pass counted in its shaders and invocations against the
//!   phone's published rates ([`super::budget_model`]), machine-independent.

use wgpu::util::DeviceExt;

use super::work_clock::WorkClock;

/// Independent FMA chains per invocation, 4 lanes each: 32 FLOP per loop iteration. Sized by
/// the core prelude's `WORKGROUP_SIZE` ([`FmaKernel::new`] prepends it).
const FMA_KERNEL: &str = r#"
struct Params { iterations: u32, pad0: u32, pad1: u32, pad2: u32 }
@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP_SIZE)
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
pub(crate) const FLOP_PER_ITERATION: f64 = 32.0;

/// The FMA kernel compiled on an adapter, with its output buffer.
pub(crate) struct FmaKernel<'a> {
    gpu: &'a render::Gpu,
    pipeline: wgpu::ComputePipeline,
    out: wgpu::Buffer,
    /// How its dispatches are timed: the adapter's [`WorkClock`], as the frames they pace.
    pub(crate) clock: WorkClock,
}

impl<'a> FmaKernel<'a> {
    /// Invocations per dispatch.
    pub(crate) const INVOCATIONS: u32 = 1 << 20;

    pub(crate) fn new(gpu: &'a render::Gpu) -> Self {
        let device = &gpu.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("fma throughput"),
            source: wgpu::ShaderSource::Wgsl(
                format!("{}{FMA_KERNEL}", render::shader::prelude()).into(),
            ),
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
        FmaKernel {
            gpu,
            pipeline,
            out,
            clock: WorkClock::for_adapter(&gpu.adapter.get_info()),
        }
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

    /// Loop turns for one dispatch of at least `min_s` seconds (doubled from 16; compiles
    /// and warms up first).
    pub(crate) fn calibrate(&self, min_s: f64) -> u32 {
        self.time(1);
        let mut iterations = 16u32;
        while self.time(iterations) < min_s && iterations < 1 << 24 {
            iterations *= 2;
        }
        iterations
    }

    /// GFLOP/s of one dispatch of `iterations` turns.
    pub(crate) fn gflops(&self, iterations: u32) -> f64 {
        let flop = f64::from(Self::INVOCATIONS) * f64::from(iterations) * FLOP_PER_ITERATION;
        flop / self.time(iterations) / 1e9
    }

    /// One dispatch of `iterations` loop turns: seconds of work until the GPU finished it, on
    /// the kernel's [`WorkClock`].
    pub(crate) fn time(&self, iterations: u32) -> f64 {
        let group = self.group(iterations);
        let t0 = self.clock.now();
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(Self::INVOCATIONS / render::shader::WORKGROUP_SIZE, 1, 1);
        }
        self.gpu.queue.submit([enc.finish()]);
        self.gpu.wait();
        self.clock.since(t0)
    }
}

/// The adapter's FP32 throughput, GFLOP/s: the FMA kernel over 2²⁰ invocations, its loop
/// doubled until one dispatch takes ≥ `min_s` seconds, then the median of three.
pub fn measure_gflops(gpu: &render::Gpu, min_s: f64) -> Result<f64, render::GpuError> {
    let kernel = FmaKernel::new(gpu);
    let iterations = kernel.calibrate(min_s);
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
