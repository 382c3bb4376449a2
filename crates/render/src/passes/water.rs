//! The water pass (`shaders/water.wgsl`): the clip-map displaced by the analytic sea and the
//! boats' wakes (`shaders/wake.wgsl`, sources from `ocean::wake`), with Fresnel-mixed sky
//! reflection, water-body light, Jacobian foam and wake foam.
//!
//! Wakes need storage buffers in vertex shaders; on an adapter without them (OpenGL ES 3.0)
//! the pass is built with the no-wake hook and the report says so.

use crate::clipmap::ClipVertex;
use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::passes::{PipelineSpec, pipeline};
use crate::shader;

/// The wake sources' bind group (group 1) of the water pass.
struct WakeBinding {
    layout: wgpu::BindGroupLayout,
    buffer: Option<wgpu::Buffer>,
    group: Option<wgpu::BindGroup>,
}

pub struct WaterPass {
    pipeline: wgpu::RenderPipeline,
    vertices: Option<wgpu::Buffer>,
    indices: Option<wgpu::Buffer>,
    index_count: u32,
    wakes: Option<WakeBinding>,
}

/// Can this adapter read storage buffers in vertex shaders (what wakes need)?
pub fn supports_wakes(adapter: &wgpu::Adapter) -> bool {
    adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::VERTEX_STORAGE)
        && adapter.limits().max_storage_buffers_per_shader_stage > 0
}

impl WaterPass {
    /// The water pass; `wakes` builds it with the wake hook (see [`supports_wakes`]).
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        t: Targets,
        wakes: bool,
    ) -> Self {
        let wakes = wakes.then(|| WakeBinding {
            layout: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("wake sources"),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                }],
            }),
            buffer: None,
            group: None,
        });
        let module = match wakes {
            Some(_) => shader::module(
                device,
                "water",
                &[shader::WAKE, shader::WATER_WAKES, shader::WATER],
            ),
            None => shader::module(device, "water", &[shader::WATER_NO_WAKES, shader::WATER]),
        };
        let extra: Vec<&wgpu::BindGroupLayout> = wakes.iter().map(|w| &w.layout).collect();
        let attrs = wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32, 2 => Uint32];
        let spec = PipelineSpec {
            label: "water",
            module: &module,
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<ClipVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &attrs,
            })],
            depth_write: true,
            depth_test: true,
            cull: None,
            extra_layouts: &extra,
        };
        WaterPass {
            pipeline: pipeline(device, frame_layout, t, spec),
            vertices: None,
            indices: None,
            index_count: 0,
            wakes,
        }
    }
}

/// Grow-only GPU buffer upload: reuse `slot` when it is big enough.
pub(crate) fn upload(
    gpu: &Gpu,
    slot: &mut Option<wgpu::Buffer>,
    usage: wgpu::BufferUsages,
    bytes: &[u8],
) {
    let need = (bytes.len() as u64)
        .max(16)
        .next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
    if slot.as_ref().is_none_or(|b| b.size() < need) {
        *slot = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pass data"),
            size: need.next_power_of_two(),
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    if let Some(b) = slot
        && !bytes.is_empty()
    {
        gpu.queue.write_buffer(b, 0, bytes);
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
        let wakes = match (&self.wakes, frame.wakes.sources.len()) {
            (None, n) if n > 0 => "; wakes skipped: no storage buffers in vertex shaders".into(),
            (_, 0) => String::new(),
            (_, n) => format!("; {n} wake sources ({} culled)", frame.wakes.culled),
        };
        if drawn > 0 {
            Ok(format!("{drawn} clip-map tiles in view{wakes}"))
        } else {
            Err("water off screen: every clip-map tile is outside the view or the play area".into())
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        upload(
            gpu,
            &mut self.vertices,
            wgpu::BufferUsages::VERTEX,
            bytemuck::cast_slice(&frame.mesh.vertices),
        );
        upload(
            gpu,
            &mut self.indices,
            wgpu::BufferUsages::INDEX,
            bytemuck::cast_slice(&frame.mesh.indices),
        );
        self.index_count = frame.mesh.indices.len() as u32;
        if let Some(w) = self.wakes.as_mut() {
            // At least one (zeroed, never read: counts.z says how many are live) source, so
            // the binding is never empty.
            let sources = &frame.wakes.sources;
            let zero = [ocean::wake::GpuWakeSource::default()];
            let data: &[ocean::wake::GpuWakeSource] =
                if sources.is_empty() { &zero } else { sources };
            let old = w.buffer.as_ref().map(|b| b.size());
            upload(
                gpu,
                &mut w.buffer,
                wgpu::BufferUsages::STORAGE,
                bytemuck::cast_slice(data),
            );
            if w.group.is_none() || w.buffer.as_ref().map(|b| b.size()) != old {
                let buffer = w.buffer.as_ref().expect("uploaded above");
                w.group = Some(gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("wake sources"),
                    layout: &w.layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: buffer.as_entire_binding(),
                    }],
                }));
            }
        }
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        let (Some(v), Some(i)) = (&self.vertices, &self.indices) else {
            return 0;
        };
        pass.set_pipeline(&self.pipeline);
        if let Some(g) = self.wakes.as_ref().and_then(|w| w.group.as_ref()) {
            pass.set_bind_group(1, g, &[]);
        }
        pass.set_vertex_buffer(0, v.slice(..));
        pass.set_index_buffer(i.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
        u64::from(self.index_count / 3)
    }
}
