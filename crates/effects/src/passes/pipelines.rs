//! The effects' render pipelines: bind groups 0 and 2 ([`fx_pipeline`]) and the AR water's
//! pipeline cache, one per set of water effects ([`ArPipelines`]), with the WGSL they assemble.

use render::frame::Targets;
use render::gpu::Gpu;
use render::passes::water::vertex_stage;
use render::shader;

use super::shared::EFFECTS_COMMON;

/// The effects in the AR water's fragment shader (`ar_water.wgsl` and what it calls).
pub const REFLECTION: &str = include_str!("../../../../shaders/effects/reflection.wgsl");
pub const REFRACTION: &str = include_str!("../../../../shaders/effects/refraction.wgsl");
pub const CAUSTICS: &str = include_str!("../../../../shaders/effects/caustics.wgsl");
pub const FLOWMAP: &str = include_str!("../../../../shaders/effects/flowmap.wgsl");
pub const AR_WATER: &str = include_str!("../../../../shaders/effects/ar_water.wgsl");

/// The AR water's shader after its vertex stage and before its pipeline's `FX_MASK` /
/// `FX_CHEAP_CAUSTICS` constants: the water pass's shading, then every effect. One list for
/// the pipelines and for the budget model, which counts the same shader's work.
pub const AR_WATER_PARTS: [&str; 7] = [
    shader::WATER,
    EFFECTS_COMMON,
    REFLECTION,
    REFRACTION,
    CAUSTICS,
    FLOWMAP,
    AR_WATER,
];

/// How an effect pipeline draws: a full-screen triangle (the background), the water mesh, or
/// the reflected room's grid of triangle strips.
pub(super) struct FxDraw<'a> {
    pub(super) buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub(super) vertex: &'a str,
    pub(super) fragment: &'a str,
    pub(super) depth_write: bool,
    pub(super) depth_compare: wgpu::CompareFunction,
    pub(super) topology: wgpu::PrimitiveTopology,
}

/// A pipeline of bind groups 0 (frame) and 2 (effects); group 1 is unused (it was the water's
/// wake sources, which its compute stage now reads).
pub(super) fn fx_pipeline(
    gpu: &Gpu,
    frame_layout: &wgpu::BindGroupLayout,
    fx_layout: &wgpu::BindGroupLayout,
    targets: Targets,
    label: &str,
    module: &wgpu::ShaderModule,
    draw: FxDraw,
) -> wgpu::RenderPipeline {
    render::passes::render_pipeline(
        &gpu.device,
        label,
        module,
        &[Some(frame_layout), None, Some(fx_layout)],
        targets,
        render::passes::Raster {
            buffers: draw.buffers,
            vertex: draw.vertex,
            fragment: draw.fragment,
            depth_write: draw.depth_write,
            depth_compare: draw.depth_compare,
            cull: None,
            blend: None,
            topology: draw.topology,
        },
    )
}

/// The AR water's pipelines, one per set of water effects (`mask`, at most 16), made when first
/// needed. Each module ends with the set as constants (`FX_MASK`, `FX_CHEAP_CAUSTICS`), so the
/// effects that do not run are constant-false branches the driver removes: lavapipe runs both
/// sides of every branch of a fragment shader under execution masks, so with a uniform flag
/// one effect costs about as much as all. (The effects uniform could not carry the flags
/// anyway: the background pass, prepared after this one, writes it with none set.)
///
/// Mesa 22.3's lavapipe crashes (SIGSEGV in its queue thread; by the disassembly at the fault,
/// its uniform inlining reading `const_buffer[slot − 1]` with slot 0) drawing some of these
/// pipelines when an inlined function returns early; the effect shaders are written with one exit per function, and
/// `gpu_tests::every_set_of_water_effects_draws_and_each_effect_shows` draws all 16.
pub(super) struct ArPipelines {
    pub(super) frame_layout: wgpu::BindGroupLayout,
    pub(super) fx_layout: wgpu::BindGroupLayout,
    pub(super) targets: Targets,
    pub(super) wakes: bool,
    /// The overhead-sun caustics instead of the area-ratio map (a new caustic tier makes the
    /// pipelines anew).
    pub(super) cheap_caustics: bool,
    /// [`ArConfig::shader_knockout`].
    pub(super) knockout: u32,
    /// Indexed by [`ArPipelines::slot`].
    pub(super) made: [Option<wgpu::RenderPipeline>; 16],
}

impl ArPipelines {
    /// The index of the water effects `mask` (FX_* bits; the background's bit 0 is not the
    /// water's).
    pub(super) fn slot(mask: u32) -> usize {
        ((mask >> 1) & 15) as usize
    }

    /// Make the pipeline for the water effects `mask` unless it exists.
    pub(super) fn make(&mut self, gpu: &Gpu, mask: u32) {
        let key = Self::slot(mask);
        if self.made[key].is_some() {
            return;
        }
        let label = format!("ar_water {mask:#x}");
        // The water pass's own files first (its vs_main, VertexOut, foam colour), then the
        // effects, then this pipeline's constants.
        let (stage, buffer) = vertex_stage(self.wakes);
        let constants = format!(
            "const FX_MASK: u32 = {}u;\nconst FX_CHEAP_CAUSTICS: bool = {};",
            mask & 0b1_1110 & !self.knockout,
            self.cheap_caustics,
        );
        let effects: Vec<&str> = AR_WATER_PARTS
            .into_iter()
            .chain(std::iter::once(constants.as_str()))
            .collect();
        let parts: Vec<&str> = std::iter::once(&stage).chain(&effects).copied().collect();
        self.made[key] = Some(fx_pipeline(
            gpu,
            &self.frame_layout,
            &self.fx_layout,
            self.targets,
            &label,
            &crate::wgsl::module(&gpu.device, &label, &parts),
            FxDraw {
                buffers: &[Some(buffer)],
                vertex: "vs_ar",
                fragment: "fs_ar",
                depth_write: true,
                depth_compare: wgpu::CompareFunction::Less,
                topology: wgpu::PrimitiveTopology::TriangleList,
            },
        ));
    }
}
