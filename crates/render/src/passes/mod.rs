//! The passes of a frame, in drawing order. Each is one WGSL file in `shaders/` and one module
//! here; the renderer runs them through [`crate::frame::Pass`].

pub mod boats;
pub mod segments;
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
    render_pipeline(
        device,
        spec.label,
        spec.module,
        &layouts,
        targets,
        Raster {
            buffers: spec.buffers,
            vertex: "vs_main",
            fragment: "fs_main",
            depth_write: spec.depth_write,
            depth_compare: if spec.depth_test {
                wgpu::CompareFunction::Less
            } else {
                wgpu::CompareFunction::Always
            },
            cull: spec.cull,
            blend: None,
            topology: wgpu::PrimitiveTopology::TriangleList,
        },
    )
}

/// A pipeline's vertex input, entry points and depth/cull state.
pub struct Raster<'a> {
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub vertex: &'a str,
    pub fragment: &'a str,
    pub depth_write: bool,
    pub depth_compare: wgpu::CompareFunction,
    pub cull: Option<wgpu::Face>,
    /// Colour blending (`None`: replace; segment layers blend over the scene).
    pub blend: Option<wgpu::BlendState>,
    /// How the vertices make triangles: a list, or a strip (the reflected room's grid rows,
    /// each interior vertex shaded twice rather than six times).
    pub topology: wgpu::PrimitiveTopology,
}

/// A render pipeline with bind groups `layouts` (a `None` is an unused slot) into the shared
/// colour/depth `targets`: the one place the descriptor is spelt.
pub fn render_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    layouts: &[Option<&wgpu::BindGroupLayout>],
    targets: Targets,
    raster: Raster,
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: layouts,
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(raster.vertex),
            compilation_options: Default::default(),
            buffers: raster.buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: raster.topology,
            cull_mode: raster.cull,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: targets.depth,
            depth_write_enabled: Some(raster.depth_write),
            depth_compare: Some(raster.depth_compare),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(raster.fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: targets.colour,
                blend: raster.blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Light added up where triangles overlap (caustic maps): one + one.
pub const ADDITIVE: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// A pipeline whose vertex shader makes its positions from the vertex index (no vertex
/// buffers), into one colour target: full-screen and grid passes (the
/// upscale, the caustic maps, the pool).
pub struct BufferlessPipeline<'a> {
    pub label: &'a str,
    pub module: &'a wgpu::ShaderModule,
    /// Entry points.
    pub vertex: &'a str,
    pub fragment: &'a str,
    /// Bind groups 0.. (a `None` is an unused slot); `None`: derived from the shader.
    pub layouts: Option<&'a [Option<&'a wgpu::BindGroupLayout>]>,
    pub format: wgpu::TextureFormat,
    pub blend: Option<wgpu::BlendState>,
    pub depth: Option<wgpu::DepthStencilState>,
}

pub fn bufferless_pipeline(device: &wgpu::Device, p: BufferlessPipeline) -> wgpu::RenderPipeline {
    let layout = p.layouts.map(|layouts| {
        device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(p.label),
            bind_group_layouts: layouts,
            immediate_size: 0,
        })
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(p.label),
        layout: layout.as_ref(),
        vertex: wgpu::VertexState {
            module: p.module,
            entry_point: Some(p.vertex),
            compilation_options: Default::default(),
            buffers: &[],
        },
        // No culling: a caustic map's folded triangles face the other way.
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: p.depth,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: p.module,
            entry_point: Some(p.fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: p.format,
                blend: p.blend,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}
