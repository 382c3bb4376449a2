//! The background pass: the camera frame behind everything.

use std::cell::RefCell;
use std::rc::Rc;

use render::frame::{FrameContext, Pass, Targets};
use render::gpu::Gpu;

use super::pipelines::{FxDraw, fx_pipeline};
use super::shared::{EFFECTS_COMMON, Shared, effect_frame};
use crate::Effect;
use crate::planner::{EffectDecision, decide};

pub const BACKGROUND: &str = include_str!("../../../../shaders/effects/background.wgsl");

/// The camera frame behind everything.
pub struct BackgroundPass {
    pipeline: wgpu::RenderPipeline,
    shared: Rc<RefCell<Shared>>,
    group: Option<wgpu::BindGroup>,
    /// Vertices of this frame's draw: 3 for the whole screen, six an edge of the water's
    /// cover around it (`background.wgsl`).
    vertices: u32,
}

impl Pass for BackgroundPass {
    fn name(&self) -> &'static str {
        "background"
    }
    fn fills_background(&self) -> bool {
        true
    }
    fn condition(&self) -> &'static str {
        "a camera frame is available (it fills every pixel no water, boat or mark covers, \
         outside the part of the screen the water certainly covers)"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        let shared = self.shared.borrow();
        decision_result(decide(
            Effect::Background,
            &effect_frame(frame, &shared.cfg),
        ))
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let mut shared = self.shared.borrow_mut();
        shared.write_uniform(gpu, frame);
        self.group = Some(shared.bind_group(&gpu.device));
        let cover = shared.written.map_or(0, |u| u.flags[0]);
        self.vertices = if cover == 0 { 3 } else { 6 * cover };
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        let Some(group) = &self.group else { return 0 };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(2, group, &[]);
        pass.draw(0..self.vertices, 0..1);
        1
    }
    fn revision(&self) -> u64 {
        self.shared.borrow().revision
    }
}

impl BackgroundPass {
    pub(super) fn new(
        gpu: &Gpu,
        frame_layout: &wgpu::BindGroupLayout,
        targets: Targets,
        shared: Rc<RefCell<Shared>>,
    ) -> BackgroundPass {
        let fx_layout = shared.borrow().layout.clone();
        BackgroundPass {
            pipeline: fx_pipeline(
                gpu,
                frame_layout,
                &fx_layout,
                targets,
                "background",
                &crate::wgsl::module(&gpu.device, "background", &[EFFECTS_COMMON, BACKGROUND]),
                FxDraw {
                    buffers: &[],
                    vertex: "vs_main",
                    fragment: "fs_main",
                    depth_write: false,
                    depth_compare: wgpu::CompareFunction::LessEqual,
                    topology: wgpu::PrimitiveTopology::TriangleList,
                },
            ),
            shared,
            group: None,
            vertices: 3,
        }
    }
}

/// A planner decision as a pass's plan: `Ok(why)` when it runs, `Err(why not)`.
fn decision_result(d: EffectDecision) -> Result<String, String> {
    if d.run { Ok(d.reason) } else { Err(d.reason) }
}
