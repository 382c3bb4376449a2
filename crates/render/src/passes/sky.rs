//! The sky pass (`shaders/sky.wgsl`): the sky gradient and the sun wherever the water does not
//! cover the screen.

use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::passes::{PipelineSpec, pipeline};
use crate::shader;

pub(crate) struct SkyPass {
    pipeline: wgpu::RenderPipeline,
}

impl SkyPass {
    pub fn new(device: &wgpu::Device, frame_layout: &wgpu::BindGroupLayout, t: Targets) -> Self {
        let module = shader::module(device, "sky", &[shader::SKY]);
        let spec = PipelineSpec {
            label: "sky",
            module: &module,
            buffers: &[],
            depth_write: false,
            depth_test: false,
            cull: None,
            extra_layouts: &[],
        };
        SkyPass {
            pipeline: pipeline(device, frame_layout, t, spec),
        }
    }
}

impl Pass for SkyPass {
    fn name(&self) -> &'static str {
        "sky"
    }
    fn is_backdrop(&self) -> bool {
        true
    }
    fn condition(&self) -> &'static str {
        "some pixel's view ray misses the water of the play area (horizon or beyond the area in view)"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        // Sample a 5×5 grid of screen points, corners included.
        let grid =
            (0..5).flat_map(|i| (0..5).map(move |j| [i as f64 / 2.0 - 1.0, j as f64 / 2.0 - 1.0]));
        let misses = grid.filter(|p| !frame.ray_hits_water(*p)).count();
        if misses > 0 {
            Ok(format!("{misses} of 25 sample rays see sky"))
        } else {
            Err("water covers the whole screen".into())
        }
    }
    fn prepare(&mut self, _gpu: &Gpu, _frame: &FrameContext) {}
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        pass.set_pipeline(&self.pipeline);
        pass.draw(0..3, 0..1);
        1
    }
}
