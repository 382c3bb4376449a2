//! The water pass (`shaders/water.wgsl`): the clip-map displaced by the analytic sea and the
//! boats' wakes (shaders/ocean/wake.wgsl`, sources from `ocean::wake`), with Fresnel-mixed sky
//! reflection, water-body light, Jacobian foam and wake foam.
//!
//! Where the adapter has compute shaders, a compute stage (`shaders/water_vertices.wgsl`)
//! displaces every clip-map vertex by the sea and the wakes (their kernel's sin and cos from
//! the table of one turn, [`crate::turn_table`]) once per frame into a vertex buffer, and the
//! vertex shader (`shaders/water_displaced.wgsl`) only projects it: a vertex shader summing
//! hundreds of wake sources starves a GPU's vertex pipeline (13× the water pass on an H200)
//! and runs on one thread in lavapipe. Without compute (OpenGL ES 3.0) the
//! vertex shader displaces by the sea alone (`shaders/water_no_wakes.wgsl`) and the report
//! says that wakes are skipped.

use crate::clipmap::ClipVertex;
use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::{Gpu, upload};
use crate::passes::{PipelineSpec, pipeline};
use crate::shader;
use crate::turn_table::TurnTable;

/// The water pass's compute stage: its pipeline and bind group 1.
struct VertexCompute {
    pipeline: wgpu::ComputePipeline,
    /// Wake sources, bins, indices, grid, the clip-map vertices and the displaced vertices.
    buffers: [Option<wgpu::Buffer>; 6],
    /// The wake kernel's table of one turn (bindings 6 and 7), uploaded on the first frame.
    turn_table: Option<TurnTable>,
    group: Option<wgpu::BindGroup>,
    /// Vertices to displace this frame.
    vertex_count: u32,
    /// This frame's wake sources as the kernel reads them (kept to reuse its allocation).
    kernel_sources: Vec<ocean::wake::WakeKernelSource>,
}

/// Bytes of one displaced vertex (`DisplacedVertex` of `shaders/water_vertices.wgsl`): position
/// and rest point, wake, and the slope sums the vertex carries to the pixels.
pub const DISPLACED_VERTEX_BYTES: u64 = 64;

pub struct WaterPass {
    pipeline: wgpu::RenderPipeline,
    /// The clip-map vertices (drawn directly without the compute stage).
    vertices: Option<wgpu::Buffer>,
    indices: Option<wgpu::Buffer>,
    index_count: u32,
    compute: Option<VertexCompute>,
}

/// Can this adapter run the water's compute stage (sea and wakes per vertex)?
pub fn supports_wakes(adapter: &wgpu::Adapter) -> bool {
    adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        && adapter.limits().max_storage_buffers_per_shader_stage >= 5
}

/// The vertex stage of a pipeline that draws the water mesh: the WGSL file that defines
/// `vs_main` and its vertex buffer layout. `wakes`: the compute stage's displaced vertices.
pub fn vertex_stage(wakes: bool) -> (&'static str, wgpu::VertexBufferLayout<'static>) {
    if wakes {
        (
            shader::WATER_DISPLACED,
            wgpu::VertexBufferLayout {
                array_stride: DISPLACED_VERTEX_BYTES,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &DISPLACED_ATTRIBUTES,
            },
        )
    } else {
        (shader::WATER_NO_WAKES, vertex_layout())
    }
}

const DISPLACED_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Float32x4];

impl WaterPass {
    /// The water pass; `wakes` builds it with the wake hook (see [`supports_wakes`]).
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        t: Targets,
        wakes: bool,
    ) -> Self {
        let compute = wakes.then(|| {
            use crate::gpu::layout;
            let cs = wgpu::ShaderStages::COMPUTE;
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("water vertices"),
                entries: &[0, 1, 2, 3, 4, 5, 6, 7].map(|binding| match binding {
                    3 => layout::uniform(binding, cs),
                    6 | 7 => TurnTable::layout_entries(6, cs)[binding as usize - 6],
                    _ => layout::storage(binding, cs, binding != 5),
                }),
            });
            let module = shader::module(
                device,
                "water vertices",
                &[&shader::wake(), shader::WATER_VERTICES],
            );
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("water vertices"),
                bind_group_layouts: &[Some(frame_layout), Some(&layout)],
                immediate_size: 0,
            });
            VertexCompute {
                pipeline: device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("water vertices"),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some("cs_displace"),
                    compilation_options: Default::default(),
                    cache: None,
                }),
                buffers: Default::default(),
                turn_table: None,
                group: None,
                vertex_count: 0,
                kernel_sources: Vec::new(),
            }
        });
        let (stage, buffer) = vertex_stage(wakes);
        let module = shader::module(
            device,
            "water",
            &[stage, shader::WATER, crate::water_look::WATER_LOOK_WGSL],
        );
        let spec = PipelineSpec {
            label: "water",
            module: &module,
            buffers: &[Some(buffer)],
            depth_write: true,
            depth_test: true,
            cull: None,
            extra_layouts: &[],
        };
        WaterPass {
            pipeline: pipeline(device, frame_layout, t, spec),
            vertices: None,
            indices: None,
            index_count: 0,
            compute,
        }
    }
}

/// The clip-map vertex attributes of `shaders/water.wgsl`'s `VertexIn`.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32, 2 => Uint32];

/// The clip-map vertex buffer layout, for pipelines that draw the water mesh with another
/// fragment shader (the AR effects' `ArWaterPass`).
pub(crate) fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: size_of::<ClipVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

impl WaterPass {
    /// Draw this frame's mesh with `pipeline`, which shares the water's vertex stage
    /// ([`vertex_stage`]); returns the triangles drawn.
    pub fn draw_with(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        pipeline: &wgpu::RenderPipeline,
    ) -> u64 {
        let drawn = match &self.compute {
            Some(c) => c.buffers[5].as_ref(),
            None => self.vertices.as_ref(),
        };
        let (Some(v), Some(i)) = (drawn, &self.indices) else {
            return 0;
        };
        pass.set_pipeline(pipeline);
        pass.set_vertex_buffer(0, v.slice(..));
        pass.set_index_buffer(i.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
        u64::from(self.index_count / 3)
    }
}

impl Pass for WaterPass {
    fn name(&self) -> &'static str {
        "water"
    }
    fn condition(&self) -> &'static str {
        "some clip-map tile survives frustum and play-area culling"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        let drawn: u32 = frame.mesh.levels.iter().map(|l| l.tiles_drawn).sum();
        let wakes = match (&self.compute, frame.wakes.sources.len()) {
            (None, n) if n > 0 => "; wakes skipped: the adapter has no compute shaders".into(),
            (_, 0) => String::new(),
            (_, n) => {
                let d = &frame.wake_drop;
                let dropped = if d.dropped > 0 {
                    format!(
                        "; {} dropped over the {:.1} MiB wake buffer cap (height error ≤ {:.2e} m, \
                         foam ≤ {:.2e})",
                        d.dropped,
                        d.cap_bytes as f64 / f64::from(1 << 20),
                        d.height_bound_m,
                        d.foam_bound
                    )
                } else {
                    String::new()
                };
                format!(
                    "; {n} wake sources ({} culled{dropped})",
                    frame.wakes.culled
                )
            }
        };
        if drawn > 0 {
            Ok(format!("{drawn} clip-map tiles in view{wakes}"))
        } else {
            Err("water off screen: every clip-map tile is outside the view or the play area".into())
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let vertex_bytes: &[u8] = bytemuck::cast_slice(&frame.mesh.vertices);
        upload(
            gpu,
            &mut self.indices,
            wgpu::BufferUsages::INDEX,
            bytemuck::cast_slice(&frame.mesh.indices),
        );
        self.index_count = frame.mesh.indices.len() as u32;
        let Some(c) = self.compute.as_mut() else {
            upload(
                gpu,
                &mut self.vertices,
                wgpu::BufferUsages::VERTEX,
                vertex_bytes,
            );
            return;
        };
        // Binned by the renderer (`wake_bins::fit`), within the buffer limits and budget.
        let bins = &frame.wake_bins;
        // Each source as the kernel reads it (its constants formed once a frame). Buffers
        // are never empty (a zeroed entry is never read: counts say what is live).
        let zero = [ocean::wake::GpuWakeSource::default()];
        let sources: &[ocean::wake::GpuWakeSource] = if frame.wakes.sources.is_empty() {
            &zero
        } else {
            &frame.wakes.sources
        };
        c.kernel_sources.clear();
        c.kernel_sources
            .extend(sources.iter().map(ocean::wake::WakeKernelSource::from));
        let indices: &[u32] = if bins.indices.is_empty() {
            &[0]
        } else {
            &bins.indices
        };
        let n = frame.mesh.vertices.len();
        let storage = wgpu::BufferUsages::STORAGE;
        let data: [(&[u8], wgpu::BufferUsages); 5] = [
            (bytemuck::cast_slice(&c.kernel_sources), storage),
            (bytemuck::cast_slice(&bins.bins), storage),
            (bytemuck::cast_slice(indices), storage),
            (bytemuck::bytes_of(&bins.grid), wgpu::BufferUsages::UNIFORM),
            (vertex_bytes, storage),
        ];
        for (slot, (bytes, usage)) in c.buffers.iter_mut().zip(data) {
            upload(gpu, slot, usage, bytes);
        }
        // The displaced vertices: written by the compute stage, drawn as a vertex buffer.
        let need = (n as u64 * DISPLACED_VERTEX_BYTES).max(DISPLACED_VERTEX_BYTES);
        if c.buffers[5].as_ref().is_none_or(|b| b.size() < need) {
            c.buffers[5] = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("displaced water vertices"),
                size: need.next_power_of_two(),
                usage: storage | wgpu::BufferUsages::VERTEX,
                mapped_at_creation: false,
            }));
        }
        let table = c
            .turn_table
            .get_or_insert_with(|| TurnTable::new(&gpu.device, &gpu.queue));
        // Made each frame: the vertex bindings are sized to this frame's mesh, so the
        // shader's arrayLength is the vertex count.
        let mut entries: Vec<wgpu::BindGroupEntry> = c
            .buffers
            .iter()
            .enumerate()
            .filter_map(|(i, b)| {
                let size = match i {
                    4 => std::num::NonZeroU64::new(vertex_bytes.len() as u64),
                    5 => std::num::NonZeroU64::new(n as u64 * DISPLACED_VERTEX_BYTES),
                    _ => None,
                };
                b.as_ref().map(|buffer| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer,
                        offset: 0,
                        size,
                    }),
                })
            })
            .collect();
        entries.extend(table.entries(6));
        c.vertex_count = 0;
        if n == 0 {
            return;
        }
        c.group = Some(gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("water vertices"),
            layout: &c.pipeline.get_bind_group_layout(1),
            entries: &entries,
        }));
        c.vertex_count = n as u32;
    }
    fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>) {
        if let Some(c) = &self.compute
            && let Some(group) = &c.group
            && c.vertex_count > 0
        {
            pass.set_pipeline(&c.pipeline);
            pass.set_bind_group(1, group, &[]);
            pass.dispatch_workgroups(c.vertex_count.div_ceil(crate::shader::WORKGROUP_SIZE), 1, 1);
        }
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        self.draw_with(pass, &self.pipeline)
    }
}
