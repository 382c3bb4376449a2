//! The passes of a frame, in drawing order. Each is one WGSL file in `shaders/` and one module
//! here; the renderer runs them through [`crate::frame::Pass`].

pub mod boats;
pub mod sky;
pub mod water;

use crate::frame::Targets;

/// A render pipeline for a pass: bind group 0 (the frame) plus `extra` groups, the shared
/// colour/depth targets, and the given vertex buffers. Boilerplate every pass shares.
pub struct PipelineSpec<'a> {
    pub label: &'a str,
    pub module: &'a wgpu::ShaderModule,
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub depth_write: bool,
    pub depth_test: bool,
    pub cull: Option<wgpu::Face>,
    /// Bind groups 1.. of the pass (group 0 is the frame's).
    pub extra_layouts: &'a [&'a wgpu::BindGroupLayout],
}

pub fn pipeline(
    device: &wgpu::Device,
    frame_layout: &wgpu::BindGroupLayout,
    targets: Targets,
    spec: PipelineSpec,
) -> wgpu::RenderPipeline {
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> = std::iter::once(frame_layout)
        .chain(spec.extra_layouts.iter().copied())
        .map(Some)
        .collect();
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(spec.label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: spec.module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: spec.buffers,
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: spec.cull,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: targets.depth,
            depth_write_enabled: Some(spec.depth_write),
            depth_compare: Some(if spec.depth_test {
                wgpu::CompareFunction::Less
            } else {
                wgpu::CompareFunction::Always
            }),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: spec.module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: targets.colour,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
