//! The pass framework and the frame planner.
//!
//! A frame starts from a [`Scene`]; [`FrameContext::new`] turns it into everything the passes
//! share: the local origin (the clip-map centre), the camera matrices in local f32, the
//! clip-map's plan and mesh, the reduced wave phases and the [`FrameUniform`] (bind group 0).
//! Then each [`Pass`] states whether it is needed ([`Pass::plan`]), prepares its buffers
//! ([`Pass::prepare`]) and draws into its own render pass ([`Pass::draw`]); the renderer
//! records every decision, the triangles and the GPU time per pass in a [`FrameReport`].

use glam::{DMat4, DVec2, DVec3, DVec4};
use serde::Serialize;

use crate::camera::Frustum;
use crate::clipmap::{ClipMapConfig, ClipMesh, Culling, ErrorTarget, LevelPlan, MAX_WAVES};
use crate::gpu::Gpu;
use crate::scene::Scene;

/// The plan's reason for every pass when the last frame is re-presented.
pub const FRAME_REUSED: &str =
    "timeline paused and camera still: the last frame is re-presented (a copy), nothing is drawn";
/// The per-frame uniform, `Frame` in `shaders/common.wgsl` (bind group 0, binding 0).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniform {
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    pub eye: [f32; 4],
    pub sun: [f32; 4],
    pub play_area: [f32; 4],
    pub viewport: [f32; 4],
    pub counts: [u32; 4],
    pub level_masks: [[u32; 4]; 8],
    /// The diffuse radiance of the sun and sky that the open sea's body takes, per band (rgb;
    /// `view_light::open_sea_light`), w unused.
    pub light: [f32; 4],
    /// Over the camera image, the room's diffuse radiance that the AR water takes (rgb), which
    /// the boats take too; w = 1 then, 0 in the open sea (the boats keep the sun and sky).
    pub room_light: [f32; 4],
    /// R∞ of the chosen water type per band (rgb) and the open sea's exposure (w)
    /// (`view_light::water_body_uniform`).
    pub water_body: [f32; 4],
    /// Per clip-map level, the waves whose slope sums its vertices carry to the pixels:
    /// level l's first pixel wave at [l / 4][l % 4] (`vertex_slopes`).
    pub vertex_waves: [[u32; 4]; 4],
}

/// Everything the passes of one frame share, computed once on the CPU.
pub struct FrameContext<'a> {
    pub scene: &'a Scene,
    /// Viewport, pixels.
    pub size: [u32; 2],
    /// World (x, z) of the local origin: the clip-map centre. Shaders see world − origin.
    pub origin: DVec2,
    /// View-projection for local coordinates, f64.
    pub view_proj: DMat4,
    pub frustum: Frustum,
    pub clipmap: ClipMapConfig,
    pub error_target: ErrorTarget,
    pub levels: Vec<LevelPlan>,
    pub mesh: ClipMesh,
    /// Half the side of the square around the eye (world axes) the clip-map covers, m: as far
    /// as the play area's farthest corner, or the far plane if nearer.
    pub reach: f64,
    /// The sea's waves as the GPU gets them (the first 64 of `scene.sea.waves`), sorted by
    /// wavenumber, longest first (`ocean::sort_by_wavenumber`).
    pub waves: Vec<ocean::GpuWave>,
    /// Per clip-map level, the waves its vertices sum for the pixels and the error bound
    /// ([`crate::vertex_slopes`]).
    pub vertex_waves: Vec<crate::vertex_slopes::VertexWaves>,
    pub uniform: FrameUniform,
    /// The wake sources that can reach the view (empty without wakes); the renderer fills
    /// them and `uniform.counts[2]` from its wake.
    pub wakes: ocean::wake::GpuWakeFrame,
    /// `wakes.sources` binned for the water's compute stage, and what the wake buffer cap
    /// left out ([`crate::wake_bins::fit`]; the renderer fills both with `wakes`).
    pub wake_bins: crate::wake_bins::WakeBins,
    pub wake_drop: crate::wake_bins::WakeDrop,
}

impl<'a> FrameContext<'a> {
    /// Plan the frame: choose the clip-map for the view, build and cull its mesh, reduce the
    /// wave phases at the origin and fill the uniform.
    pub fn new(scene: &'a Scene, size: [u32; 2], error_px: f64) -> FrameContext<'a> {
        let cam = &scene.camera;
        let aspect = f64::from(size[0]) / f64::from(size[1].max(1));
        let error_target = ErrorTarget::uniform(error_px, size[1].max(1), cam.fov_y);
        let eye_xz = DVec2::new(cam.eye.x, cam.eye.z);
        // The map must reach the farthest corner of the play area that the far plane allows.
        let [ax, az, bx, bz] = scene.play_area;
        let corner = [(ax, az), (ax, bz), (bx, az), (bx, bz)]
            .iter()
            .map(|&(x, z)| (DVec2::new(x, z) - eye_xz).abs().max_element())
            .fold(0.0, f64::max);
        let reach = corner.min(cam.far).max(10.0);
        let clipmap = ClipMapConfig::for_view(&scene.sea, &error_target, cam.eye.y, reach);
        let levels = clipmap.plan(&scene.sea, &error_target, cam.eye.y);
        let origin = clipmap.origin_for(eye_xz);
        let view_proj = cam.view_proj_local(origin, aspect);
        let frustum = Frustum::from_matrix(view_proj);
        let max_displacement = scene.sea.total_amplitude();
        let mesh = clipmap.build(
            eye_xz,
            &Culling {
                frustum: Some(frustum),
                play_area: Some(scene.play_area),
                max_displacement,
            },
        );
        let mut waves = scene.sea.gpu_waves(scene.t, [origin.x, origin.y]);
        if waves.len() > MAX_WAVES {
            log::warn!(
                "the sea has {} waves; the GPU draws the first {MAX_WAVES}",
                waves.len()
            );
            waves.truncate(MAX_WAVES);
        }
        // Longest first, so that a pixel's wave loop stops at its first filtered-out wave;
        // `slot_of` maps the sea's wave index to its place in the GPU's list.
        let order = ocean::sort_by_wavenumber(&mut waves);
        let mut slot_of = vec![usize::MAX; scene.sea.waves.len()];
        for (slot, &i) in order.iter().enumerate() {
            slot_of[i] = slot;
        }
        let mut level_masks = [[0u32; 4]; 8];
        for (l, p) in levels.iter().enumerate() {
            for &i in p.kept.iter().filter(|&&i| i < MAX_WAVES) {
                let slot = slot_of[i];
                let word = (l % 2) * 2 + slot / 32;
                level_masks[l / 2][word] |= 1 << (slot % 32);
            }
        }
        let eye = cam.eye - DVec3::new(origin.x, 0.0, origin.y);
        let footprints = crate::vertex_slopes::level_footprints(
            &clipmap,
            &levels,
            &error_target,
            cam.eye,
            max_displacement,
        );
        let vertex_waves =
            crate::vertex_slopes::vertex_waves(&clipmap, &levels, &footprints, &waves);
        let uniform = FrameUniform {
            view_proj: view_proj.as_mat4().to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().as_mat4().to_cols_array_2d(),
            eye: [eye.x as f32, eye.y as f32, eye.z as f32, 0.0],
            sun: [
                scene.sun.x as f32,
                scene.sun.y as f32,
                scene.sun.z as f32,
                1.0,
            ],
            play_area: [
                (ax - origin.x) as f32,
                (az - origin.y) as f32,
                (bx - origin.x) as f32,
                (bz - origin.y) as f32,
            ],
            viewport: [
                size[0] as f32,
                size[1] as f32,
                1.0 / size[0].max(1) as f32,
                1.0 / size[1].max(1) as f32,
            ],
            counts: [waves.len() as u32, levels.len() as u32, 0, 0],
            level_masks,
            light: {
                let l = crate::view_light::open_sea_light(scene.sun, 1.0);
                [l[0] as f32, l[1] as f32, l[2] as f32, 0.0]
            },
            room_light: [0.0; 4],
            water_body: crate::view_light::water_body_uniform(
                &crate::water_look::WaterLook::default(),
            ),
            vertex_waves: crate::vertex_slopes::uniform_counts(&vertex_waves),
        };
        FrameContext {
            scene,
            size,
            origin,
            view_proj,
            frustum,
            clipmap,
            error_target,
            levels,
            mesh,
            reach,
            waves,
            vertex_waves,
            uniform,
            wakes: Default::default(),
            wake_bins: Default::default(),
            wake_drop: Default::default(),
        }
    }

    /// Does the ray through NDC point (x, y) meet the sea's rest plane inside the play area?
    pub fn ray_hits_water(&self, ndc: [f64; 2]) -> bool {
        let inv = self.view_proj.inverse();
        let near = inv * DVec4::new(ndc[0], ndc[1], 0.0, 1.0);
        let far = inv * DVec4::new(ndc[0], ndc[1], 1.0, 1.0);
        let (a, b) = (near.truncate() / near.w, far.truncate() / far.w);
        if (a.y > 0.0) == (b.y > 0.0) {
            return false;
        }
        let p = a + (b - a) * (a.y / (a.y - b.y));
        let w = DVec2::new(p.x, p.z) + self.origin;
        let [ax, az, bx, bz] = self.scene.play_area;
        w.x >= ax && w.x <= bx && w.y >= az && w.y <= bz
    }

    /// Is a sphere of `radius` metres at world `centre` inside the view frustum?
    pub fn sphere_in_view(&self, centre: DVec3, radius: f64) -> bool {
        let c = centre - DVec3::new(self.origin.x, 0.0, self.origin.y);
        self.frustum
            .planes
            .iter()
            .all(|p| p.truncate().dot(c) + p.w >= -radius)
    }
}

/// Bind group 0, shared by every pass: the frame uniform and the waves.
pub struct FrameBindings {
    pub layout: wgpu::BindGroupLayout,
    pub group: wgpu::BindGroup,
    pub uniform: wgpu::Buffer,
    pub waves: wgpu::Buffer,
}

impl FrameBindings {
    pub fn new(device: &wgpu::Device) -> FrameBindings {
        let entry = |binding| {
            crate::gpu::layout::uniform(
                binding,
                wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
            )
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("frame"),
            entries: &[entry(0), entry(1)],
        });
        let buffer = |label, size| crate::gpu::uniform_buffer(device, label, size);
        let uniform = buffer("frame uniform", size_of::<FrameUniform>() as u64);
        let waves = buffer("waves", (MAX_WAVES * size_of::<ocean::GpuWave>()) as u64);
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: waves.as_entire_binding(),
                },
            ],
        });
        FrameBindings {
            layout,
            group,
            uniform,
            waves,
        }
    }

    /// Upload the uniform and the waves (the rest of the 64 slots stays as it was: unread).
    pub fn upload(&self, queue: &wgpu::Queue, uniform: &FrameUniform, waves: &[ocean::GpuWave]) {
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(uniform));
        if !waves.is_empty() {
            queue.write_buffer(&self.waves, 0, bytemuck::cast_slice(waves));
        }
    }
}

/// The formats a pass draws into.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Targets {
    pub colour: wgpu::TextureFormat,
    pub depth: wgpu::TextureFormat,
}

/// A render pass of the frame. See the crate docs for how to add one.
pub trait Pass {
    /// Short name, used in the frame report.
    fn name(&self) -> &'static str;
    /// The condition under which this pass is needed, in words (for the report and docs).
    fn condition(&self) -> &'static str;
    /// Decide for this frame: `Ok(why it runs)` or `Err(why it is skipped)`.
    fn plan(&self, frame: &FrameContext) -> Result<String, String>;
    /// Upload what the pass draws (only called when it runs).
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext);
    /// True for a pass that draws every pixel nothing else covers (the camera image): the
    /// backdrop passes are then skipped.
    fn fills_background(&self) -> bool {
        false
    }
    /// True for a pass that only draws behind everything (the sky).
    fn is_backdrop(&self) -> bool {
        false
    }
    /// Record this frame's offscreen work (a reflection texture, a caustic map: what
    /// `prepare` found needed) into the frame's encoder, before any pass draws. `timestamps`,
    /// where the renderer measures, go on the first and last of those render passes. Returns
    /// whether anything was recorded (the timestamps were written).
    fn record_offscreen(
        &mut self,
        _enc: &mut wgpu::CommandEncoder,
        _timestamps: Option<OffscreenTimestamps<'_>>,
    ) -> bool {
        false
    }
    /// Record compute work that must run before the pass draws (e.g. displacing vertices);
    /// bind group 0 is already set. Timed with the pass. Most passes have none.
    fn dispatch(&self, _pass: &mut wgpu::ComputePass<'_>) {}
    /// Record the draw calls; bind group 0 is already set. Returns triangles submitted.
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64;
    /// Changes whenever an input of this pass outside the [`Scene`] changes (e.g. a new
    /// camera image), so that the renderer does not re-present a stale frame.
    fn revision(&self) -> u64 {
        0
    }
}

/// Where a pass's offscreen render passes write their GPU timestamps: `begin` at the start of
/// the first, `end` at the end of the last (the same pass where there is one).
#[derive(Clone, Copy)]
pub struct OffscreenTimestamps<'a> {
    pub queries: &'a wgpu::QuerySet,
    pub begin: u32,
    pub end: u32,
}

impl<'a> OffscreenTimestamps<'a> {
    /// The query set and the begin and end slots of pass `index` of `count` offscreen
    /// passes, where it writes any.
    fn slots(
        t: Option<Self>,
        index: usize,
        count: usize,
    ) -> Option<(Self, Option<u32>, Option<u32>)> {
        let t = t?;
        let (first, last) = (index == 0, index + 1 == count);
        (first || last).then_some((t, first.then_some(t.begin), last.then_some(t.end)))
    }

    /// The timestamp writes of offscreen pass `index` of `count`, a render pass.
    pub fn render(
        t: Option<Self>,
        index: usize,
        count: usize,
    ) -> Option<wgpu::RenderPassTimestampWrites<'a>> {
        Self::slots(t, index, count).map(|(t, begin, end)| wgpu::RenderPassTimestampWrites {
            query_set: t.queries,
            beginning_of_pass_write_index: begin,
            end_of_pass_write_index: end,
        })
    }

    /// The timestamp writes of offscreen pass `index` of `count`, a compute pass.
    pub fn compute(
        t: Option<Self>,
        index: usize,
        count: usize,
    ) -> Option<wgpu::ComputePassTimestampWrites<'a>> {
        Self::slots(t, index, count).map(|(t, begin, end)| wgpu::ComputePassTimestampWrites {
            query_set: t.queries,
            beginning_of_pass_write_index: begin,
            end_of_pass_write_index: end,
        })
    }
}

/// One pass's entry in the frame record.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassRecord {
    pub name: String,
    pub condition: String,
    pub ran: bool,
    /// Why it ran, or why it was skipped.
    pub reason: String,
    pub triangles: u64,
    /// GPU time from timestamp queries (its compute stage and render pass); absent where the
    /// adapter has none.
    pub gpu_ms: Option<f64>,
    /// GPU time of its offscreen render passes (reflection texture, caustic map), where it
    /// had any and the adapter measures.
    pub offscreen_gpu_ms: Option<f64>,
}

impl PassRecord {
    /// The pass's whole GPU time: its own and its offscreen work's, where measured.
    pub fn total_gpu_ms(&self) -> Option<f64> {
        self.gpu_ms
            .map(|ms| ms + self.offscreen_gpu_ms.unwrap_or(0.0))
    }
}

/// A pass's shader invocations in one frame (pipeline-statistics queries).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ShaderInvocations {
    pub pass: String,
    pub vertex: u64,
    pub fragment: u64,
}

/// One clip-map level's line in the frame record.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelRecord {
    pub cell_m: f64,
    pub half_extent_m: f64,
    pub waves: usize,
    pub error_bound_px: f64,
    #[serde(flatten)]
    pub stats: crate::clipmap::LevelStats,
}

/// What the planner decided and measured for one frame (`regatta render --report`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameReport {
    pub t: f64,
    pub size: [u32; 2],
    pub adapter: String,
    pub passes: Vec<PassRecord>,
    /// Per pass that ran, its shader invocations from pipeline-statistics queries (its main
    /// render pass, not its offscreen work); empty where the adapter does not count them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub shader_invocations: Vec<ShaderInvocations>,
    pub triangles: u64,
    /// "pipeline_statistics" where the adapter counts primitives, else "counted".
    pub triangles_source: String,
    /// Sum of the passes' GPU times, offscreen work included, where measured.
    pub gpu_ms: Option<f64>,
    pub clipmap: ClipMapRecord,
    /// The wakes of this frame, where the renderer has a wake.
    pub wakes: Option<WakeRecord>,
    /// Metres the camera was raised because its eye was under the sea surface
    /// ([`crate::Scene::camera_above_water`]); absent when it was above.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera_raised_m: Option<f64>,
    /// True when nothing was drawn: the last frame was re-presented (paused and still).
    pub reused_last_frame: bool,
}

impl FrameReport {
    /// The record of re-presenting the frame this one recorded: nothing ran, nothing drawn.
    pub fn reused(&self) -> FrameReport {
        let mut r = self.clone();
        for p in &mut r.passes {
            p.ran = false;
            p.reason = FRAME_REUSED.into();
            p.triangles = 0;
            p.gpu_ms = None;
            p.offscreen_gpu_ms = None;
        }
        r.triangles = 0;
        r.shader_invocations.clear();
        r.gpu_ms = None;
        r.reused_last_frame = true;
        r
    }
}

/// The wake sources of a frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WakeRecord {
    /// Sources sent to the GPU.
    pub sources: usize,
    /// Alive sources left out because they cannot reach the view.
    pub culled: usize,
    /// Bound of the wake height error from culling anywhere in view, metres.
    pub cull_bound_m: f64,
    /// Sources in reach left out to fit the wake buffer cap (the least visible), the bound
    /// of the height (m) and foam error that causes anywhere, and the cap (bytes).
    pub dropped: usize,
    pub drop_bound_m: f64,
    pub drop_foam_bound: f64,
    pub buffer_cap_bytes: u64,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClipMapRecord {
    pub levels: u32,
    /// Cells per side of each level.
    pub cells: Vec<u32>,
    pub base_cell_m: f64,
    pub error_target_px: f64,
    pub origin: [f64; 2],
    pub per_level: Vec<LevelRecord>,
}

impl ClipMapRecord {
    pub fn of(frame: &FrameContext) -> ClipMapRecord {
        ClipMapRecord {
            levels: frame.clipmap.levels(),
            cells: frame.clipmap.cells.clone(),
            base_cell_m: frame.clipmap.base_cell,
            error_target_px: frame.error_target.pixels,
            origin: [frame.origin.x, frame.origin.y],
            per_level: frame
                .levels
                .iter()
                .zip(&frame.mesh.levels)
                .map(|(p, s)| LevelRecord {
                    cell_m: p.cell,
                    half_extent_m: p.half_extent,
                    waves: p.kept.len(),
                    error_bound_px: p.error_px,
                    stats: *s,
                })
                .collect(),
        }
    }
}
