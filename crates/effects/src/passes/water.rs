//! The AR water pass: the water over the table with reflection, refraction, caustics and
//! flow map, in the water pass's place; its offscreen work (the planar reflection texture and
//! the caustic map) and when it is reused.

use std::cell::RefCell;
use std::rc::Rc;

use glam::{DMat4, DVec3};

use render::frame::{
    FrameBindings, FrameContext, FrameUniform, OffscreenTimestamps, Pass, Targets,
};
use render::gpu::Gpu;
use render::optics::{DepthRange, Plane, oblique_near_plane, reflection_matrix};
use render::passes::boats::BoatsPass;
use render::passes::water::{WaterPass, supports_wakes};

use super::pipelines::{ArPipelines, FxDraw, REFLECTION, fx_pipeline};
use super::scissor::{Scissor, play_area_scissor};
use super::shared::{EFFECTS_COMMON, Shared, effect_frame};
use crate::Effect;
use crate::caustic_map::CausticMapPass;
use crate::planner::{EffectDecision, decide};

/// The room and sky drawn into the reflection texture.
pub const REFLECTION_ROOM: &str = include_str!("../../../../shaders/effects/reflection_room.wgsl");

/// The water over the table with reflection, refraction, caustics and flow map.
pub struct ArWaterPass {
    /// The water pass it replaces: mesh, wakes, and the plain shading when no effect runs.
    water: WaterPass,
    /// The water mesh with `ar_water.wgsl`'s fragment shader, one pipeline per set of
    /// effects, made when first needed.
    pipelines: ArPipelines,
    /// The effect bits of this frame (0: none runs, the plain water shading draws).
    mask: u32,
    shared: Rc<RefCell<Shared>>,
    group: Option<wgpu::BindGroup>,
    /// The planar reflection: its own frame bindings (reflected camera) and boats pass.
    reflection_bindings: FrameBindings,
    /// The room and sky drawn first into the reflection texture, as a grid of triangle
    /// strips, and the grid's columns and rows for this frame's texture
    /// (`reflection::room_grid`, as the effects uniform gives them to the shader).
    room_pipeline: wgpu::RenderPipeline,
    room_grid: [u32; 2],
    /// This frame's offscreen work, prepared, for the renderer to record before the frame.
    offscreen: Offscreen,
    /// The caustic map's pass and its own frame bindings (this frame's waves).
    caustic_map: CausticMapPass,
    caustic_bindings: FrameBindings,
    reflection_boats: BoatsPass,
    /// Effect decisions of the last planned frame.
    pub last_decisions: Vec<EffectDecision>,
    /// What the reflection texture and caustic map on the GPU were made from.
    last_offscreen: Option<OffscreenInputs>,
    /// This frame's target size and the scissor rectangle of the play area in it.
    size: [u32; 2],
    scissor: Option<Scissor>,
}

/// The sky's colour at the horizon (`sky_colour_rough` in shaders/render/common.wgsl`): the reflection
/// texture's clear colour, shown where nothing is mirrored.
const HORIZON_HAZE: wgpu::Color = wgpu::Color {
    r: 0.62,
    g: 0.74,
    b: 0.86,
    a: 1.0,
};

/// What a frame draws offscreen before the water samples it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Offscreen {
    /// The reflection texture: cleared, and `Some(true)` when the room, boats and marks are
    /// drawn into it (the camera is above the water).
    reflection: Option<bool>,
    /// The area-ratio caustic map.
    caustic_map: bool,
}

/// The plan's note when the offscreen work of the last frame is reused.
pub const OFFSCREEN_REUSED: &str =
    "timeline paused and camera still: reflection texture and caustic map of the last frame reused";

/// Everything the reflection texture and the caustic map depend on (the camera image is fixed
/// for the pass's life; a new quality set-up counts in `quality`).
#[derive(Debug, Clone, PartialEq)]
struct OffscreenInputs {
    t: f64,
    sea: std::sync::Arc<ocean::WaveSet>,
    boats: Vec<render::Boat>,
    marks: Vec<render::Mark>,
    play_area: [f64; 4],
    sun: DVec3,
    camera: render::Camera,
    size: [u32; 2],
    mask: u32,
    /// The quality set-up (reflection size, caustic tier and cells) they were drawn with.
    quality: u64,
}

impl OffscreenInputs {
    fn of(frame: &FrameContext, mask: u32, quality: u64) -> OffscreenInputs {
        let s = frame.scene;
        OffscreenInputs {
            t: s.t,
            sea: s.sea.clone(),
            boats: s.boats.clone(),
            marks: s.marks.clone(),
            play_area: s.play_area,
            sun: s.sun,
            camera: s.camera,
            size: frame.size,
            mask,
            quality,
        }
    }
}

const WATER_EFFECTS: [Effect; 4] = [
    Effect::Reflection,
    Effect::Refraction,
    Effect::Caustics,
    Effect::FlowMap,
];

/// The effect bits (`Effects.flags.x`) of the decisions that run.
fn mask_of(ds: &[EffectDecision]) -> u32 {
    ds.iter()
        .filter(|d| d.run)
        .fold(0u32, |m, d| m | 1 << d.effect as u32)
}

impl ArWaterPass {
    /// The AR water over the water pass's mesh, sharing `shared` with the background pass.
    pub(super) fn new(
        gpu: &Gpu,
        frame_layout: wgpu::BindGroupLayout,
        targets: Targets,
        shared: Rc<RefCell<Shared>>,
    ) -> ArWaterPass {
        let fx_layout = shared.borrow().layout.clone();
        let wakes = supports_wakes(&gpu.adapter);
        let water = WaterPass::new(&gpu.device, &frame_layout, targets, wakes);
        let pipelines = ArPipelines {
            frame_layout,
            fx_layout,
            targets,
            wakes,
            cheap_caustics: shared.borrow().cfg.cheap_caustics,
            knockout: u32::from(shared.borrow().cfg.shader_knockout),
            made: Default::default(),
        };
        let reflection_boats = BoatsPass::new(&gpu.device, &pipelines.frame_layout, targets);
        let caustic_map = CausticMapPass::new(gpu, &pipelines.frame_layout);
        let room_layout = shared.borrow().room_layout.clone();
        let room_pipeline = fx_pipeline(
            gpu,
            &pipelines.frame_layout,
            &room_layout,
            targets,
            "reflected room",
            &crate::wgsl::module(
                &gpu.device,
                "reflected room",
                &[EFFECTS_COMMON, REFLECTION, REFLECTION_ROOM],
            ),
            FxDraw {
                buffers: &[],
                vertex: "vs_main",
                fragment: "fs_main",
                depth_write: false,
                depth_compare: wgpu::CompareFunction::Always,
                topology: wgpu::PrimitiveTopology::TriangleStrip,
            },
        );
        ArWaterPass {
            water,
            pipelines,
            mask: 0,
            shared,
            group: None,
            reflection_bindings: FrameBindings::new(&gpu.device),
            caustic_map,
            room_pipeline,
            room_grid: [1, 1],
            offscreen: Offscreen::default(),
            caustic_bindings: FrameBindings::new(&gpu.device),
            reflection_boats,
            last_decisions: Vec::new(),
            last_offscreen: None,
            size: [0, 0],
            scissor: None,
        }
    }

    /// Are `inputs` (this frame's scene and effects) the ones the offscreen textures were
    /// last made from?
    fn reuses(&self, inputs: &OffscreenInputs) -> bool {
        self.last_offscreen.as_ref() == Some(inputs)
    }

    fn decisions(&self, frame: &FrameContext) -> Vec<EffectDecision> {
        let f = effect_frame(frame, &self.shared.borrow().cfg);
        WATER_EFFECTS.iter().map(|&e| decide(e, &f)).collect()
    }

    /// Upload what the reflection texture shows: the room, boats and marks as the water
    /// mirrors them, seen through view × reflection matrix (eq. 1 of the AR water
    /// thesis, 000 in docs/sources.md) with the near plane
    /// moved onto the water (000 eq. 2, wgpu depth). Returns whether anything is mirrored
    /// (not with the camera at or below the water).
    fn prepare_reflection(&mut self, gpu: &Gpu, frame: &FrameContext) -> bool {
        let s = frame.scene;
        let cam = &s.camera;
        // The screen's view, roll included, so the texture lines up with the pixels.
        let view = cam.view_local(frame.origin);
        let water = Plane::horizontal(0.0);
        let refl_view = view * reflection_matrix(&water);
        let aspect = f64::from(frame.size[0]) / f64::from(frame.size[1].max(1));
        let proj =
            glam::dcamera::rh::proj::directx::perspective(cam.fov_y, aspect, cam.near, cam.far);
        let oblique =
            oblique_near_plane(proj, &water.transformed(refl_view), DepthRange::ZeroToOne);
        if let Some(oblique) = oblique {
            let view_proj: DMat4 = oblique * refl_view;
            let mut u: FrameUniform = frame.uniform;
            u.view_proj = view_proj.as_mat4().to_cols_array_2d();
            u.inv_view_proj = view_proj.inverse().as_mat4().to_cols_array_2d();
            u.eye[1] = -u.eye[1];
            self.reflection_bindings
                .upload(&gpu.queue, &u, &frame.waves);
            self.reflection_boats.prepare(gpu, frame);
        }
        let mut shared = self.shared.borrow_mut();
        let size = super::shared::reflection_px(frame.size, &shared.cfg);
        self.room_grid = crate::reflection::room_grid(size);
        shared.reflection_targets(&gpu.device, size);
        shared.room_group(&gpu.device);
        oblique.is_some()
    }

    /// Record the reflection texture as prepared: cleared to the horizon's haze (what shows
    /// where nothing is mirrored); then, where `mirrored`, the room over the sky behind
    /// everything, then boats, sails and marks.
    fn record_reflection(
        &self,
        enc: &mut wgpu::CommandEncoder,
        mirrored: bool,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let shared = self.shared.borrow();
        // prepare_reflection made both this frame.
        let (Some((colour, depth)), Some(room)) = (&shared.reflection, &shared.room_group) else {
            unreachable!("the reflection is recorded only after prepare_reflection");
        };
        let (cv, dv) = (
            colour.create_view(&Default::default()),
            depth.create_view(&Default::default()),
        );
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("planar reflection"),
            color_attachments: &[Some(render::gpu::colour_attachment(
                &cv,
                Some(HORIZON_HAZE),
            ))],
            depth_stencil_attachment: Some(render::gpu::depth_attachment(&dv, true)),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if mirrored {
            pass.set_bind_group(0, &self.reflection_bindings.group, &[]);
            pass.set_pipeline(&self.room_pipeline);
            pass.set_bind_group(2, room, &[]);
            // One strip per row of cells (the instance), two vertices per column line.
            let [cols, rows] = self.room_grid;
            pass.draw(0..2 * (cols + 1), 0..rows);
            self.reflection_boats.draw(&mut pass);
        }
    }
}

impl Pass for ArWaterPass {
    fn name(&self) -> &'static str {
        "ar_water"
    }
    fn condition(&self) -> &'static str {
        "the water is in view (the water pass's condition); each effect by its own rule"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        let water = self.water.plan(frame);
        let ds = self.decisions(frame);
        let text = ds
            .iter()
            .map(|d| {
                let verb = if d.run { "runs" } else { "skipped" };
                format!("{} {verb}: {}", d.effect, d.reason)
            })
            .collect::<Vec<_>>()
            .join("; ");
        match water {
            Ok(w)
                if ds.iter().any(|d| d.run)
                    && self.reuses(&OffscreenInputs::of(
                        frame,
                        mask_of(&ds),
                        self.shared.borrow().quality,
                    )) =>
            {
                Ok(format!("{w}; {text}; {OFFSCREEN_REUSED}"))
            }
            Ok(w) if ds.iter().any(|d| d.run) => Ok(format!("{w}; {text}")),
            Ok(w) => Ok(format!("{w}; plain water shading: {text}")),
            Err(w) => Err(format!("{w}; {text}")),
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        self.water.prepare(gpu, frame);
        let ds = self.decisions(frame);
        let runs = |e: Effect| ds.iter().any(|d| d.effect == e && d.run);
        let mask = mask_of(&ds);
        // Paused timeline, still camera, same scene and effects: the reflection texture and
        // the caustic map on the GPU are this frame's already.
        let (quality, cheap) = {
            let shared = self.shared.borrow();
            (shared.quality, shared.cfg.cheap_caustics)
        };
        // The caustic tier is a shader constant: a new tier makes the pipelines anew.
        if cheap != self.pipelines.cheap_caustics {
            self.pipelines.cheap_caustics = cheap;
            self.pipelines.made = Default::default();
        }
        let inputs = OffscreenInputs::of(frame, mask, quality);
        let reuse = self.reuses(&inputs);
        // The reflected room reads the uniform too.
        self.shared.borrow_mut().write_uniform(gpu, frame);
        self.offscreen = Offscreen::default();
        if !reuse && runs(Effect::Reflection) {
            self.offscreen.reflection = Some(self.prepare_reflection(gpu, frame));
        }
        let mut shared = self.shared.borrow_mut();
        if !reuse && runs(Effect::Caustics) && !shared.cfg.cheap_caustics {
            // The area-ratio map of this frame's sea and time, drawn on the GPU.
            self.caustic_bindings
                .upload(&gpu.queue, &frame.uniform, &frame.waves);
            let region = shared.caustic_region(frame);
            let (depth, src) = (shared.cfg.table_depth, shared.cfg.caustic_resolution.0);
            let side = shared.caustic_tex.width();
            self.caustic_map
                .prepare(gpu, frame, &region, depth, src, side);
            self.offscreen.caustic_map = true;
        }
        self.last_offscreen = Some(inputs);
        self.group = Some(shared.bind_group(&gpu.device));
        if mask != 0 {
            self.pipelines.make(gpu, mask);
        }
        self.mask = mask;
        self.size = frame.size;
        self.scissor = play_area_scissor(frame);
        self.last_decisions = ds;
    }
    fn record_offscreen(
        &mut self,
        enc: &mut wgpu::CommandEncoder,
        timestamps: Option<OffscreenTimestamps<'_>>,
    ) -> bool {
        let Offscreen {
            reflection,
            caustic_map,
        } = std::mem::take(&mut self.offscreen);
        let first_map = usize::from(reflection.is_some());
        let count = first_map
            + if caustic_map {
                self.caustic_map.passes()
            } else {
                0
            };
        if let Some(mirrored) = reflection {
            let writes = OffscreenTimestamps::render(timestamps, 0, count);
            self.record_reflection(enc, mirrored, writes);
        }
        if caustic_map {
            let target = self
                .shared
                .borrow()
                .caustic_tex
                .create_view(&Default::default());
            self.caustic_map.record(
                enc,
                &self.caustic_bindings.group,
                &target,
                timestamps,
                first_map,
                count,
            );
        }
        count > 0
    }
    fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>) {
        self.water.dispatch(pass);
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        match &self.group {
            Some(group) if self.mask != 0 => {
                let Some(pipeline) = &self.pipelines.made[ArPipelines::slot(self.mask)] else {
                    return self.water.draw(pass);
                };
                let Some([x, y, w, h]) = self.scissor else {
                    pass.set_bind_group(2, group, &[]);
                    return self.water.draw_with(pass, pipeline);
                };
                if w == 0 || h == 0 {
                    return 0;
                }
                pass.set_scissor_rect(x, y, w, h);
                pass.set_bind_group(2, group, &[]);
                let triangles = self.water.draw_with(pass, pipeline);
                // The passes after this one draw on the whole target.
                pass.set_scissor_rect(0, 0, self.size[0], self.size[1]);
                triangles
            }
            _ => self.water.draw(pass),
        }
    }
}
