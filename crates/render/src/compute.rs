//! The water pass's WGSL evaluated by compute shaders (`shaders/wave_heights.wgsl`) at given
//! inputs: the GPU side of the parity tests against ocean's f64 reference (the sea's
//! `gerstner()`, the drawn vertex path `sea_displaced()` with its level masks and fade, and
//! the foam rule), and of the benches.

use glam::DVec2;
use ocean::{GpuWave, WaveSet};
use wgpu::util::DeviceExt;

use crate::clipmap::{ClipVertex, MAX_WAVES};
use crate::frame::{FrameBindings, FrameContext, FrameUniform};
use crate::gpu::{Gpu, GpuError};
use crate::shader;

/// Run `entry` of `wave_heights.wgsl` once per item of `inputs`, with `uniform` and `waves`
/// bound as the water pass binds them (group 0); one vec4 out per item.
fn evaluate(
    gpu: &Gpu,
    uniform: &FrameUniform,
    waves: &[GpuWave],
    entry: &str,
    inputs: &[[f32; 4]],
) -> Result<Vec<[f32; 4]>, GpuError> {
    if inputs.is_empty() {
        return Ok(Vec::new());
    }
    let device = &gpu.device;
    let bindings = FrameBindings::new(device);
    bindings.upload(&gpu.queue, uniform, &waves[..waves.len().min(MAX_WAVES)]);
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
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("points"),
        contents: bytemuck::cast_slice(inputs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("displaced"),
        size: (inputs.len() * 16) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let io = crate::gpu::buffer_group(device, "wave heights io", &io_layout, &[&input, &output]);
    let bytes = gpu.dispatch_and_read(&pipeline, &[&bindings.group, &io], inputs.len(), &output)?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}

/// A uniform that only says how many waves there are (what `gerstner` sums need).
fn waves_uniform(waves: &[GpuWave]) -> FrameUniform {
    FrameUniform {
        counts: [waves.len().min(MAX_WAVES) as u32, 0, 0, 0],
        ..bytemuck::Zeroable::zeroed()
    }
}

/// Displacements (dx, y, dz), metres, of the local rest points `points` (metres from
/// `origin`) at race time `t`, evaluated on the GPU with every wave of `sea` (at most 64).
pub fn gpu_displacements(
    gpu: &Gpu,
    sea: &WaveSet,
    t: f64,
    origin: DVec2,
    points: &[[f32; 2]],
) -> Result<Vec<[f32; 3]>, GpuError> {
    wave_displacements(gpu, &sea.gpu_waves(t, [origin.x, origin.y]), points)
}

/// Displacements (dx, y, dz) of the local rest points `points` by `waves` as the GPU gets
/// them (phases already reduced by the caller: the parity test also feeds broken ones).
pub fn wave_displacements(
    gpu: &Gpu,
    waves: &[GpuWave],
    points: &[[f32; 2]],
) -> Result<Vec<[f32; 3]>, GpuError> {
    let inputs: Vec<[f32; 4]> = points.iter().map(|p| [p[0], p[1], 0.0, 0.0]).collect();
    let out = evaluate(gpu, &waves_uniform(waves), waves, "cs_main", &inputs)?;
    Ok(out.iter().map(|d| [d[0], d[1], d[2]]).collect())
}

/// Every clip-map vertex of `frame` displaced by the sea as the water pass draws it
/// (`sea_displaced`: its level's wave mask, the next level's dropped waves faded): local
/// (x, y, z), metres.
pub fn vertex_positions(gpu: &Gpu, frame: &FrameContext) -> Result<Vec<[f32; 3]>, GpuError> {
    let inputs: Vec<[f32; 4]> = frame
        .mesh
        .vertices
        .iter()
        .map(|v: &ClipVertex| [v.rest[0], v.rest[1], v.fade, f32::from_bits(v.level)])
        .collect();
    let out = evaluate(
        gpu,
        &frame.uniform,
        &frame.waves,
        "cs_sea_displaced",
        &inputs,
    )?;
    Ok(out.iter().map(|d| [d[0], d[1], d[2]]).collect())
}

/// `surface_frame` of the frame's waves (sorted by wavenumber) at local rest points with a
/// pixel footprint (m): (slope x, slope z, Jacobian, slope variance) per point; with
/// `every_wave`, the same sums run over every wave without the early stop.
pub fn gpu_surface_frames(
    gpu: &Gpu,
    frame: &FrameContext,
    points: &[([f32; 2], f32)],
    every_wave: bool,
) -> Result<Vec<[f32; 4]>, GpuError> {
    let flag = if every_wave { 1.0 } else { 0.0 };
    let inputs: Vec<[f32; 4]> = points
        .iter()
        .map(|(p, fp)| [p[0], p[1], *fp, flag])
        .collect();
    evaluate(
        gpu,
        &frame.uniform,
        &frame.waves,
        "cs_surface_frame",
        &inputs,
    )
}

/// The foam the water pass draws (footprint 0: no wave band-limited) at local rest points
/// (metres from `origin`) with the given wake foam, at race time `t`: (foam, Jacobian).
pub fn gpu_foam(
    gpu: &Gpu,
    sea: &WaveSet,
    t: f64,
    origin: DVec2,
    points: &[([f32; 2], f32)],
) -> Result<Vec<[f32; 2]>, GpuError> {
    let waves = sea.gpu_waves(t, [origin.x, origin.y]);
    let inputs: Vec<[f32; 4]> = points.iter().map(|(p, w)| [p[0], p[1], *w, 0.0]).collect();
    let out = evaluate(gpu, &waves_uniform(&waves), &waves, "cs_foam", &inputs)?;
    Ok(out.iter().map(|d| [d[0], d[1]]).collect())
}

/// Run `cs_main` of the WGSL `source` (assembled by its owner, e.g. with
/// [`shader::source`]) once per item of `input`: the kernel reads
/// `@group(0) @binding(10) var<storage, read> input` and writes
/// `@group(0) @binding(11) var<storage, read_write> output`, `output_item_bytes` per item
/// (bindings 0 and 1 of group 0 are the frame's in the shared files). Returns the output.
/// The GPU side of the mirrored functions' parity tests.
pub fn run_kernel<In: bytemuck::Pod>(
    gpu: &Gpu,
    label: &str,
    source: &str,
    input: &[In],
    output_item_bytes: usize,
) -> Result<Vec<u8>, GpuError> {
    run_kernel_with(gpu, label, source, input, output_item_bytes, &[])
}

/// [`run_kernel`] for a function that reads more than its input: `groups[i]` holds the
/// entries of bind group `i + 1` (a uniform, a texture, a sampler, as the function's shared
/// file declares them; empty for a group it does not use).
pub fn run_kernel_with<In: bytemuck::Pod>(
    gpu: &Gpu,
    label: &str,
    source: &str,
    input: &[In],
    output_item_bytes: usize,
    groups: &[&[wgpu::BindGroupEntry]],
) -> Result<Vec<u8>, GpuError> {
    run_kernel_in(gpu, label, source, input, output_item_bytes, &[], groups)
}

/// [`run_kernel_with`] for a function that also reads group 0's own bindings (the frame's
/// uniform at binding 0, as the shared files declare it): `frame_entries` go into group 0
/// beside the input and output.
pub fn run_kernel_in<In: bytemuck::Pod>(
    gpu: &Gpu,
    label: &str,
    source: &str,
    input: &[In],
    output_item_bytes: usize,
    frame_entries: &[wgpu::BindGroupEntry],
    groups: &[&[wgpu::BindGroupEntry]],
) -> Result<Vec<u8>, GpuError> {
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some("cs_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let input_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::cast_slice(input),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: (input.len() * output_item_bytes).max(16) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut io = vec![
        wgpu::BindGroupEntry {
            binding: 10,
            resource: input_buffer.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 11,
            resource: output.as_entire_binding(),
        },
    ];
    io.extend(frame_entries.iter().cloned());
    let bound: Vec<wgpu::BindGroup> = std::iter::once(&io[..])
        .chain(groups.iter().copied())
        .enumerate()
        .map(|(index, entries)| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &pipeline.get_bind_group_layout(index as u32),
                entries,
            })
        })
        .collect();
    let bound: Vec<&wgpu::BindGroup> = bound.iter().collect();
    let mut bytes = gpu.dispatch_and_read(&pipeline, &bound, input.len(), &output)?;
    bytes.truncate(input.len() * output_item_bytes);
    Ok(bytes)
}

/// The AR water's transmitted light (`shaders/water_look.wgsl`'s `water_transmitted`) on the
/// GPU, per item: (dry table colour, room radiance, view path in metres of real sea) for
/// `look`, its uniform made as the effects make it (`WaterLook::gpu_optics`, a scene in real
/// metres), with the item's room radiance folded into R∞ as the effects fold the camera's
/// white. The parity test's GPU side of `water_look::transmitted`.
pub fn gpu_water_transmitted(
    gpu: &Gpu,
    look: &crate::water_look::WaterLook,
    items: &[([f32; 3], [f32; 3], f32)],
) -> Result<Vec<[f32; 3]>, GpuError> {
    const ENTRY: &str = "
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 7>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&input) { return; }
    let a = input[i][0];
    let b = input[i][1];
    let w = WaterOptics(input[i][2], input[i][3], input[i][4], input[i][5], input[i][6]);
    output[i] = vec4<f32>(water_transmitted(a.xyz, a.w * w.down_scale.w, w), 0.0);
}";
    if items.is_empty() {
        return Ok(Vec::new());
    }
    // The scene in real metres: the table lies the water's depth down.
    let [down, neg_k, deep, a, b] = look.gpu_optics(look.depth_m);
    let inputs: Vec<[[f32; 4]; 7]> = items
        .iter()
        .map(|(t, r, path)| {
            // The room's radiance folded into R∞ as the uniform carries it: the f32 product
            // the shader formed before.
            let room_deep = [deep[0] * r[0], deep[1] * r[1], deep[2] * r[2], deep[3]];
            [
                [t[0], t[1], t[2], *path],
                [0.0; 4],
                down,
                neg_k,
                room_deep,
                a,
                b,
            ]
        })
        .collect();
    let src = format!(
        "{}{}\n{ENTRY}",
        shader::prelude(),
        crate::water_look::WATER_LOOK_WGSL
    );
    let bytes = run_kernel(gpu, "water look", &src, &inputs, 16)?;
    let out: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    Ok(out.iter().map(|o| [o[0], o[1], o[2]]).collect())
}

/// The open sea's water body (`water_look.wgsl`'s `water_deep_body`) on the GPU, per item:
/// (diffuse radiance per band, the frame uniform's `water_body`: R∞ and the exposure). The
/// parity test's GPU side of `water_look::deep_body`.
pub fn gpu_water_deep_body(
    gpu: &Gpu,
    items: &[([f32; 3], [f32; 4])],
) -> Result<Vec<[f32; 3]>, GpuError> {
    const ENTRY: &str = "
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 2>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&input) { return; }
    output[i] = vec4<f32>(water_deep_body(input[i][0].xyz, input[i][1]), 0.0);
}";
    if items.is_empty() {
        return Ok(Vec::new());
    }
    let inputs: Vec<[[f32; 4]; 2]> = items
        .iter()
        .map(|(l, w)| [[l[0], l[1], l[2], 0.0], *w])
        .collect();
    let src = format!(
        "{}{}\n{ENTRY}",
        shader::prelude(),
        crate::water_look::WATER_LOOK_WGSL
    );
    let bytes = run_kernel(gpu, "water deep body", &src, &inputs, 16)?;
    let out: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    Ok(out.iter().map(|o| [o[0], o[1], o[2]]).collect())
}

/// One case of [`gpu_boat_in_room`]: albedo, unit normal, unit direction to the room's main
/// light, room radiance.
pub type BoatLightCase = ([f32; 3], [f32; 3], [f32; 3], [f32; 3]);

/// The boats' room lighting (`boats.wgsl`'s `boat_in_room`) on the GPU, per item
/// ([`BoatLightCase`]). The parity test's GPU side
/// of `view_light::boat_in_room`.
pub fn gpu_boat_in_room(gpu: &Gpu, items: &[BoatLightCase]) -> Result<Vec<[f32; 3]>, GpuError> {
    const ENTRY: &str = "
@group(0) @binding(10) var<storage, read> input: array<array<vec4<f32>, 4>>;
@group(0) @binding(11) var<storage, read_write> output: array<vec4<f32>>;
@compute @workgroup_size(WORKGROUP_SIZE)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&input) { return; }
    let v = input[i];
    output[i] = vec4<f32>(boat_in_room(v[0].xyz, v[1].xyz, v[2].xyz, v[3].xyz), 0.0);
}";
    if items.is_empty() {
        return Ok(Vec::new());
    }
    let v4 = |a: [f32; 3]| [a[0], a[1], a[2], 0.0];
    let inputs: Vec<[[f32; 4]; 4]> = items
        .iter()
        .map(|(c, n, l, r)| [v4(*c), v4(*n), v4(*l), v4(*r)])
        .collect();
    let src = format!("{}\n{ENTRY}", shader::source(&[shader::BOATS]));
    let bytes = run_kernel(gpu, "boat in room", &src, &inputs, 16)?;
    let out: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    Ok(out.iter().map(|o| [o[0], o[1], o[2]]).collect())
}
