//! The water pass (`shaders/water.wgsl`): the clip-map displaced by the analytic sea, with
//! Fresnel-mixed sky reflection, water-body light and Jacobian foam.

use crate::clipmap::ClipVertex;
use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::passes::{PipelineSpec, pipeline};
use crate::shader;

pub struct WaterPass {
    pipeline: wgpu::RenderPipeline,
    vertices: Option<wgpu::Buffer>,
    indices: Option<wgpu::Buffer>,
    index_count: u32,
}

impl WaterPass {
    pub fn new(device: &wgpu::Device, frame_layout: &wgpu::BindGroupLayout, t: Targets) -> Self {
        let module = shader::module(device, "water", &[shader::WATER]);
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
        };
        WaterPass {
            pipeline: pipeline(device, frame_layout, t, spec),
            vertices: None,
            indices: None,
            index_count: 0,
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
        if drawn > 0 {
            Ok(format!("{drawn} clip-map tiles in view"))
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
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        let (Some(v), Some(i)) = (&self.vertices, &self.indices) else {
            return 0;
        };
        pass.set_pipeline(&self.pipeline);
        pass.set_vertex_buffer(0, v.slice(..));
        pass.set_index_buffer(i.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
        u64::from(self.index_count / 3)
    }
}
