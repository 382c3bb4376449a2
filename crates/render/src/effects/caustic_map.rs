//! The area-ratio caustic map on the GPU (`shaders/caustic_map.wgsl`): the surface grid of
//! [`super::caustics::area_ratio`] (the f64 reference), displaced by the frame's waves,
//! refracted onto the table and drawn into a half-float map with additive blending, once per
//! frame that needs it. It replaces the f64 map computed on the CPU every frame (1–2 ms, more
//! than a whole frame on a fast GPU).

use glam::{DVec2, DVec3};

use super::caustics::{CausticRegion, MAX_INTENSITY};
use crate::frame::FrameContext;
use crate::gpu::Gpu;
use crate::shader;

/// The caustic map's texel format: additive, filterable, values well above 1.
pub const CAUSTIC_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

/// `CausticGrid` of `shaders/caustic_map.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
struct CausticGrid {
    origin: [f32; 2],
    step: f32,
    side: u32,
    region: [f32; 4],
    light: [f32; 4],
    map: [f32; 4],
}

/// The pass's pipeline, its uniform and the grid's index buffer (remade when the grid's side
/// changes).
pub struct CausticMapPass {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    group: wgpu::BindGroup,
    indices: Option<(u32, wgpu::Buffer, u32)>,
}

/// The surface grid of `area_ratio` for `region`: its first rest point (world), step and
/// points per side, with the same margin for light bent in from outside the square.
pub fn surface_grid(
    region: &CausticRegion,
    waves: &ocean::WaveSet,
    depth: f64,
    src_res: usize,
) -> (DVec2, f64, usize) {
    let src_res = src_res.max(1);
    let step = region.size / src_res as f64;
    let travel = depth.abs() * 1.5 + waves.waves.iter().map(|w| w.amplitude()).sum::<f64>();
    let margin = if region.periodic {
        0
    } else {
        (travel / step).ceil() as usize + 1
    };
    let origin = DVec2::from(region.min) - DVec2::splat(margin as f64 * step);
    (origin, step, src_res + 2 * margin + 1)
}

impl CausticMapPass {
    pub fn new(gpu: &Gpu, frame_layout: &wgpu::BindGroupLayout) -> CausticMapPass {
        let device = &gpu.device;
        let crate::gpu::UniformGroup {
            layout,
            buffer: uniform,
            group,
        } = crate::gpu::UniformGroup::new(device, "caustic grid", size_of::<CausticGrid>() as u64);
        let module = shader::module(device, "caustic map", &[super::passes::CAUSTIC_MAP]);
        let pipeline = crate::passes::bufferless_pipeline(
            device,
            crate::passes::BufferlessPipeline {
                label: "caustic map",
                module: &module,
                layouts: Some(&[Some(frame_layout), Some(&layout)]),
                format: CAUSTIC_MAP_FORMAT,
                blend: Some(crate::passes::ADDITIVE),
                depth: None,
            },
        );
        CausticMapPass {
            pipeline,
            uniform,
            group,
            indices: None,
        }
    }

    /// Record the caustics of `frame`'s sea on a table `depth` metres down over `region`
    /// (world metres) into `target` (a [`CAUSTIC_MAP_FORMAT`] map), from a `src_res`² surface
    /// grid, for submission with the frame. `frame_group` is bind group 0 with this frame's
    /// waves.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        &mut self,
        gpu: &Gpu,
        frame: &FrameContext,
        frame_group: &wgpu::BindGroup,
        region: &CausticRegion,
        depth: f64,
        src_res: usize,
        target: &wgpu::Texture,
    ) -> Option<wgpu::CommandBuffer> {
        let s = frame.scene;
        let (origin, step, side) = surface_grid(region, &s.sea, depth, src_res);
        let o = frame.origin;
        let light = (-s.sun).normalize_or(DVec3::NEG_Y);
        let f = |v: f64| v as f32;
        let grid = CausticGrid {
            origin: [f(origin.x - o.x), f(origin.y - o.y)],
            step: f(step),
            side: side as u32,
            region: [
                f(region.min[0] - o.x),
                f(region.min[1] - o.y),
                f(region.size),
                f(depth),
            ],
            light: [f(light.x), f(light.y), f(light.z), f(MAX_INTENSITY)],
            map: [
                f(region.size / f64::from(target.width().max(1))),
                0.0,
                0.0,
                0.0,
            ],
        };
        gpu.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&grid));
        let side = side as u32;
        if self.indices.as_ref().is_none_or(|(n, _, _)| *n != side) {
            // Each cell as area_ratio splits it: (k, k+1, k+side+1), (k, k+side+1, k+side).
            let mut idx = Vec::with_capacity(((side - 1) * (side - 1) * 6) as usize);
            for j in 0..side - 1 {
                for i in 0..side - 1 {
                    let k = j * side + i;
                    idx.extend_from_slice(&[k, k + 1, k + side + 1, k, k + side + 1, k + side]);
                }
            }
            let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("caustic grid indices"),
                size: (idx.len() * 4).max(4) as u64,
                usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            gpu.queue
                .write_buffer(&buffer, 0, bytemuck::cast_slice(&idx));
            self.indices = Some((side, buffer, idx.len() as u32));
        }
        let (_, indices, count) = self.indices.as_ref()?;
        let view = target.create_view(&Default::default());
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("caustic map"),
                color_attachments: &[Some(crate::gpu::colour_attachment(
                    &view,
                    Some(wgpu::Color::TRANSPARENT),
                ))],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, frame_group, &[]);
            pass.set_bind_group(1, &self.group, &[]);
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..*count, 0, 0..1);
        }
        Some(enc.finish())
    }
}
