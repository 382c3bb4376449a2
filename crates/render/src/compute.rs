//! The sea evaluated by a compute shader (`shaders/wave_heights.wgsl`) with the same WGSL
//! `gerstner()` the water pass's vertices use: the GPU side of the parity test against ocean's
//! f64 reference, and of the benches.

use glam::DVec2;
use ocean::WaveSet;
use wgpu::util::DeviceExt;

use crate::clipmap::MAX_WAVES;
use crate::frame::{FrameBindings, FrameUniform};
use crate::gpu::{Gpu, GpuError};
use crate::shader;

/// Displacements (dx, y, dz), metres, of the local rest points `points` (metres from
/// `origin`) at race time `t`, evaluated on the GPU with every wave of `sea` (at most 64).
pub fn gpu_displacements(
    gpu: &Gpu,
    sea: &WaveSet,
    t: f64,
    origin: DVec2,
    points: &[[f32; 2]],
) -> Result<Vec<[f32; 3]>, GpuError> {
    if points.is_empty() {
        return Ok(Vec::new());
    }
    let device = &gpu.device;
    let bindings = FrameBindings::new(device);
    let mut waves = sea.gpu_waves(t, [origin.x, origin.y]);
    waves.truncate(MAX_WAVES);
    let uniform = FrameUniform {
        counts: [waves.len() as u32, 0, 0, 0],
        ..bytemuck::Zeroable::zeroed()
    };
    bindings.upload(&gpu.queue, &uniform, &waves);
    let io_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("wave heights io"),
        entries: &[
            crate::gpu::layout::storage(0, wgpu::ShaderStages::COMPUTE, true),
            crate::gpu::layout::storage(1, wgpu::ShaderStages::COMPUTE, false),
        ],
    });
    let module = shader::module(device, "wave heights", &[shader::WAVE_HEIGHTS]);
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("wave heights"),
        bind_group_layouts: &[Some(&bindings.layout), Some(&io_layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("wave heights"),
        layout: Some(&layout),
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("points"),
        contents: bytemuck::cast_slice(points),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let out_size = (points.len() * 16) as u64;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("displaced"),
        size: out_size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let io = crate::gpu::buffer_group(device, "wave heights io", &io_layout, &[&input, &output]);
    let bytes = gpu.dispatch_and_read(&pipeline, &[&bindings.group, &io], points.len(), &output)?;
    let v: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    Ok(v.iter().map(|d| [d[0], d[1], d[2]]).collect())
}
