//! The effect passes on the GPU, added to a [`Renderer`] by [`add_effect_passes`]:
//!
//! - [`BackgroundPass`] (`shaders/background.wgsl`): the camera frame behind everything.
//! - [`ArWaterPass`] (`shaders/ar_water.wgsl` with `reflection.wgsl`, `refraction.wgsl`,
//!   `caustics.wgsl`, `flowmap.wgsl`): takes the water pass's place and draws its mesh (waves
//!   and wakes, `water.wgsl`'s vertex shader) with a fragment shader that shades each water
//!   pixel once with the effects the planner chose, mixed by the full Fresnel equations, and
//!   the sea's and wakes' normals and foam; when no effect runs it draws the plain water. When
//!   boats or marks are reflected, its `prepare` first draws them into the planar reflection
//!   texture (a fraction of the screen) with the reflection matrix and oblique near-plane
//!   clipping at the water.
//!
//! Both share bind group 2 (`shaders/effects_common.wgsl`; group 1 is unused): the [`EffectsUniform`], the camera image (binding 1: an sRGB RGBA view, YUV
//! 4:2:0 converted into it once per camera frame, [`super::camera_upload`]), the reflection
//! texture, the caustic map and a sampler. [`add_effect_passes`] returns an [`EffectsHandle`]
//! that writes each new camera frame into the same textures. The caustic map is the f64
//! area-ratio map of [`super::caustics`] at the frame's race time, uploaded each frame.

use std::cell::RefCell;
use std::rc::Rc;

use glam::{DMat4, DVec2, DVec3};

use super::camera_frame::{CameraFrame, CameraImage};
use super::camera_upload::{CameraTextures, YuvConversion};
use super::caustic_map::{CAUSTIC_MAP_FORMAT, CausticMapPass};
use super::caustics::CausticRegion;
use super::flowmap::{DEFAULT_JUMP, flow_phases};
use super::planner::{EffectDecision, EffectFrame, decide};
use super::{Effect, EffectSet};
use crate::frame::{FrameBindings, FrameContext, FrameUniform, OffscreenTimestamps, Pass, Targets};
use crate::gpu::Gpu;
use crate::optics::{DepthRange, Plane, oblique_near_plane, reflection_matrix};
use crate::passes::boats::BoatsPass;
use crate::passes::water::{WaterPass, supports_wakes, vertex_stage};
use crate::renderer::{DEPTH_FORMAT, Renderer};
use crate::shader;

pub const EFFECTS_COMMON: &str = include_str!("../../../../shaders/effects_common.wgsl");
pub const BACKGROUND: &str = include_str!("../../../../shaders/background.wgsl");
pub const REFLECTION: &str = include_str!("../../../../shaders/reflection.wgsl");
pub const REFRACTION: &str = include_str!("../../../../shaders/refraction.wgsl");
pub const CAUSTICS: &str = include_str!("../../../../shaders/caustics.wgsl");
pub const FLOWMAP: &str = include_str!("../../../../shaders/flowmap.wgsl");
pub const AR_WATER: &str = include_str!("../../../../shaders/ar_water.wgsl");
pub const CAUSTIC_MAP: &str = include_str!("../../../../shaders/caustic_map.wgsl");
pub const CAUSTIC_SCATTER: &str = include_str!("../../../../shaders/caustic_scatter.wgsl");
pub const REFLECTION_ROOM: &str = include_str!("../../../../shaders/reflection_room.wgsl");

/// How the effects are set up.
#[derive(Debug, Clone, PartialEq)]
pub struct ArConfig {
    /// Effects asked for.
    pub effects: EffectSet,
    /// Depth of the water over the table, metres of the scene (table units × scale).
    pub table_depth: f64,
    /// Radius of the ring the camera image is reflected on; `None`: 1.05 × half the play
    /// area's diagonal (000: at least half the water's diagonal).
    pub ring_radius: Option<f64>,
    /// Reflection texture size as a fraction of the screen's (000 uses a quarter).
    pub reflection_fraction: f64,
    /// Far tidal current, m/s (x, z).
    pub current: DVec2,
    /// Radius of a course mark in the current, metres.
    pub mark_radius: f64,
    /// Flow-map restart period, seconds.
    pub flow_period: f64,
    /// Side of one tile of the flow-distorted detail texture, metres.
    pub detail_tile: f64,
    /// Use the cheap overhead-sun caustics instead of the area-ratio map.
    pub cheap_caustics: bool,
    /// Surface grid and output cells per side of the area-ratio caustic map.
    pub caustic_resolution: (usize, usize),
    /// Test hook, 0 in use: these effects' bits (`1 << Effect as u8`) are left out of the AR
    /// water shader's `FX_MASK` while every pass still runs, so the effect's term is dead (the
    /// golden tests prove they catch that).
    #[doc(hidden)]
    pub shader_knockout: u8,
}

impl Default for ArConfig {
    fn default() -> Self {
        ArConfig {
            effects: EffectSet::ALL,
            table_depth: 3.0,
            ring_radius: None,
            reflection_fraction: 0.25,
            current: DVec2::new(0.6, 0.2),
            mark_radius: 4.0,
            flow_period: 2.0,
            detail_tile: 12.0,
            cheap_caustics: false,
            caustic_resolution: (48, 64),
            shader_knockout: 0,
        }
    }
}

impl ArConfig {
    /// The ring radius for a scene's play area.
    pub fn ring_radius_for(&self, play_area: [f64; 4]) -> f64 {
        let [ax, az, bx, bz] = play_area;
        self.ring_radius
            .unwrap_or_else(|| 1.05 * 0.5 * DVec2::new(bx - ax, bz - az).length())
    }
}

/// The per-frame uniform of the effects, `Effects` in `shaders/effects_common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EffectsUniform {
    pub camera_view: [[f32; 4]; 4],
    pub intrinsics: [f32; 4],
    pub display_u: [f32; 4],
    pub display_v: [f32; 4],
    pub table: [f32; 4],
    pub caustic_region: [f32; 4],
    pub flow_a: [f32; 4],
    pub flow_b: [f32; 4],
    pub current: [f32; 4],
    pub flags: [u32; 4],
    pub marks: [[f32; 4]; 8],
}

/// What the planner needs, measured from the frame: water coverage from a 9×9 grid of view
/// rays, reflectors from the frustum test the boats pass uses.
pub fn effect_frame(frame: &FrameContext, cfg: &ArConfig) -> EffectFrame {
    let s = frame.scene;
    let n = 9;
    let hits = (0..n * n)
        .filter(|k| {
            let (i, j) = (k % n, k / n);
            let ndc = [
                i as f64 / (n - 1) as f64 * 2.0 - 1.0,
                j as f64 / (n - 1) as f64 * 2.0 - 1.0,
            ];
            frame.ray_hits_water(ndc)
        })
        .count();
    let water = hits as f64 / (n * n) as f64;
    let in_view = |p: DVec2, r: f64| frame.sphere_in_view(DVec3::new(p.x, 0.0, p.y), r);
    let reflectors = s
        .boats
        .iter()
        .filter(|b| in_view(b.position, b.length))
        .count()
        + s.marks.iter().filter(|m| in_view(m.position, 2.0)).count();
    let px = |v: u32| (f64::from(v) * cfg.reflection_fraction).round() as u32;
    EffectFrame {
        requested: cfg.effects,
        camera_frame: true,
        water_on_screen: water,
        camera_above_water: s.camera.eye.y > 0.0,
        reflectors_in_view: reflectors,
        reflection_texture_px: [px(frame.size[0]), px(frame.size[1])],
        water_over_table: water,
        sun_elevation: s.sun.y.clamp(-1.0, 1.0).asin(),
        calm_sea: s.sea.waves.is_empty(),
        max_current_in_view: if water > 0.0 {
            cfg.current.length()
        } else {
            0.0
        },
        // Frame reuse is the renderer's: it does not keep frames yet.
        timeline_paused: false,
        camera_still: false,
        previous_frame_reusable: false,
    }
}

/// Resources shared by the effect passes.
struct Shared {
    cfg: ArConfig,
    /// The current frame's camera and display transform (its image is on the GPU).
    camera: CameraFrame<()>,
    layout: wgpu::BindGroupLayout,
    /// Group 2 of the room in the reflection texture: the uniform and the camera image, not
    /// the reflection texture it draws into.
    room_layout: wgpu::BindGroupLayout,
    room_group: Option<wgpu::BindGroup>,
    uniform: wgpu::Buffer,
    camera_image: CameraTextures,
    yuv_conversion: YuvConversion,
    caustic_tex: wgpu::Texture,
    reflection: Option<(wgpu::Texture, wgpu::Texture)>,
    sampler: wgpu::Sampler,
    group: Option<wgpu::BindGroup>,
    colour_format: wgpu::TextureFormat,
    /// Camera frames set so far: the background pass's revision, so that the renderer draws
    /// a still scene again over a new image.
    revision: u64,
    /// The uniform last written.
    written: Option<EffectsUniform>,
}

impl Shared {
    fn new(
        gpu: &Gpu,
        targets: Targets,
        cfg: ArConfig,
        camera: CameraFrame<()>,
        image: &CameraImage,
    ) -> Shared {
        let device = &gpu.device;
        use crate::gpu::layout;
        let fs = wgpu::ShaderStages::FRAGMENT;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("effects"),
            entries: &[
                layout::uniform(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                layout::texture(1, fs),
                layout::texture(2, fs),
                layout::texture(3, fs),
                layout::sampler(4, fs),
            ],
        });
        let room_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reflected room"),
            entries: &[
                layout::uniform(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                layout::texture(1, fs),
                layout::sampler(4, fs),
            ],
        });
        let uniform = crate::gpu::uniform_buffer(
            device,
            "effects uniform",
            size_of::<EffectsUniform>() as u64,
        );
        let yuv_conversion = YuvConversion::new(gpu);
        let n = cfg.caustic_resolution.1 as u32;
        let caustic_tex = crate::gpu::texture_2d(
            device,
            "caustic map",
            [n, n],
            CAUSTIC_MAP_FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC,
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("effects linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let mut shared = Shared {
            cfg,
            camera,
            layout,
            room_layout,
            room_group: None,
            uniform,
            camera_image: CameraTextures::new(device, image, &yuv_conversion),
            yuv_conversion,
            caustic_tex,
            reflection: None,
            sampler,
            group: None,
            colour_format: targets.colour,
            revision: 0,
            written: None,
        };
        shared.set_image(gpu, image);
        shared
    }

    /// Write `image` into the camera textures, made anew (and the bind group dropped) only
    /// when its kind or size differs from the last image's.
    fn set_image(&mut self, gpu: &Gpu, image: &CameraImage) {
        if !self.camera_image.fits(image) {
            self.camera_image = CameraTextures::new(&gpu.device, image, &self.yuv_conversion);
            self.group = None;
            self.room_group = None;
        }
        self.camera_image.write(gpu, image, &self.yuv_conversion);
        self.revision += 1;
    }

    /// The reflection textures (colour, depth) at `size`, made when the size changes.
    fn reflection_targets(&mut self, device: &wgpu::Device, size: [u32; 2]) {
        let fits = self
            .reflection
            .as_ref()
            .is_some_and(|(c, _)| c.width() == size[0].max(1) && c.height() == size[1].max(1));
        if fits {
            return;
        }
        let colour = crate::gpu::texture_2d(
            device,
            "planar reflection",
            size,
            self.colour_format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let depth = crate::gpu::texture_2d(
            device,
            "planar reflection depth",
            size,
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        self.reflection = Some((colour, depth));
        // The water's group binds the reflection texture; the room's does not (it draws
        // into it), so only the first is made again.
        self.group = None;
    }

    fn bind_group(&mut self, device: &wgpu::Device) -> wgpu::BindGroup {
        if self.reflection.is_none() {
            self.reflection_targets(device, [1, 1]);
        }
        if self.group.is_none() {
            self.group = Some(self.make_group(device, false));
        }
        self.group.clone().expect("made above")
    }

    /// Group 2 of the reflected room: the uniform and the camera image.
    fn room_group(&mut self, device: &wgpu::Device) -> wgpu::BindGroup {
        if self.room_group.is_none() {
            self.room_group = Some(self.make_group(device, true));
        }
        self.room_group.clone().expect("made above")
    }

    /// Group 2: the uniform, the camera image and the sampler, and unless `room` (the group of
    /// the reflected room, which draws into the reflection texture) the reflection texture and
    /// the caustic map.
    fn make_group(&self, device: &wgpu::Device, room: bool) -> wgpu::BindGroup {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (main, caustic) = (self.camera_image.sampled_view(), view(&self.caustic_tex));
        let reflection = self.reflection.as_ref().map(|(c, _)| view(c));
        let texture = |binding, v| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(v),
        };
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: self.uniform.as_entire_binding(),
            },
            texture(1, &main),
            wgpu::BindGroupEntry {
                binding: 4,
                resource: wgpu::BindingResource::Sampler(&self.sampler),
            },
        ];
        if !room && let Some(reflection) = &reflection {
            entries.push(texture(2, reflection));
            entries.push(texture(3, &caustic));
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(if room { "reflected room" } else { "effects" }),
            layout: if room {
                &self.room_layout
            } else {
                &self.layout
            },
            entries: &entries,
        })
    }

    /// Write this frame's uniform, unless it holds it already (both effect passes prepare
    /// with it; a still frame leaves it as it is).
    fn write_uniform(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let u = self.uniform(frame);
        if self.written != Some(u) {
            gpu.queue
                .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&u));
            self.written = Some(u);
        }
    }

    /// The uniform for a frame (the effects that run are the pipelines' constants).
    fn uniform(&self, frame: &FrameContext) -> EffectsUniform {
        let s = frame.scene;
        let o = frame.origin;
        let cam = &self.camera.camera;
        let f = |v: f64| v as f32;
        let view = self.camera.view_local(o).as_mat4().to_cols_array_2d();
        let d = self.camera.display;
        let ring = self.cfg.ring_radius_for(s.play_area);
        let [ax, az, bx, bz] = s.play_area;
        let centre = DVec2::new(ax + bx, az + bz) / 2.0 - o;
        let region = self.caustic_region(frame);
        let [a, b] = flow_phases(s.t, self.cfg.flow_period, DEFAULT_JUMP);
        let mut marks = [[0.0f32; 4]; 8];
        let mut near: Vec<DVec2> = s.marks.iter().map(|m| m.position - o).collect();
        let target = DVec2::new(s.camera.target.x, s.camera.target.z) - o;
        near.sort_by(|p, q| (*p - target).length().total_cmp(&(*q - target).length()));
        for (slot, p) in marks.iter_mut().zip(&near) {
            *slot = [f(p.x), f(p.y), 0.0, 0.0];
        }
        EffectsUniform {
            camera_view: view,
            intrinsics: [
                f(cam.fx / cam.width),
                f(cam.fy / cam.height),
                f(cam.cx / cam.width),
                f(cam.cy / cam.height),
            ],
            display_u: [f(d[0][0]), f(d[0][1]), f(d[0][2]), 0.0],
            display_v: [f(d[1][0]), f(d[1][1]), f(d[1][2]), 0.0],
            table: [f(self.cfg.table_depth), f(ring), f(centre.x), f(centre.y)],
            caustic_region: [
                f(region.min[0] - o.x),
                f(region.min[1] - o.y),
                f(region.size),
                1.0,
            ],
            flow_a: [f(a.progress), f(a.weight), f(a.offset.x), f(a.offset.y)],
            flow_b: [f(b.progress), f(b.weight), f(b.offset.x), f(b.offset.y)],
            current: [
                f(self.cfg.current.x),
                f(self.cfg.current.y),
                f(self.cfg.mark_radius),
                f(self.cfg.detail_tile),
            ],
            flags: [0, near.len().min(8) as u32, 0, 0],
            marks,
        }
    }

    fn caustic_region(&self, frame: &FrameContext) -> CausticRegion {
        caustic_region(frame.scene, frame.size, &self.cfg)
    }
}

/// The square of the table the caustic map covers for `scene` seen at `size` pixels: around
/// the point looked at, as wide as the view there (world metres), cut to the water (the play
/// area and a margin of twice the depth: table points seen through the water's edge at up to
/// 63° from straight down).
pub fn caustic_region(scene: &crate::Scene, size: [u32; 2], cfg: &ArConfig) -> CausticRegion {
    let cam = &scene.camera;
    let dist = (cam.target - cam.eye).length();
    let aspect = f64::from(size[0]) / f64::from(size[1].max(1));
    let width = 2.0 * dist * (0.5 * cam.fov_y).tan() * aspect.max(1.0) * 1.5;
    CausticRegion::in_view(
        [cam.target.x, cam.target.z],
        width,
        scene.play_area,
        2.0 * cfg.table_depth,
    )
}

/// How an effect pipeline draws: a full-screen triangle (the background) or the water mesh.
struct FxDraw<'a> {
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    vertex: &'a str,
    fragment: &'a str,
    depth_write: bool,
    depth_compare: wgpu::CompareFunction,
}

/// A pipeline of bind groups 0 (frame) and 2 (effects); group 1 is unused (it was the water's
/// wake sources, which its compute stage now reads).
fn fx_pipeline(
    gpu: &Gpu,
    frame_layout: &wgpu::BindGroupLayout,
    fx_layout: &wgpu::BindGroupLayout,
    targets: Targets,
    label: &str,
    module: &wgpu::ShaderModule,
    draw: FxDraw,
) -> wgpu::RenderPipeline {
    crate::passes::render_pipeline(
        &gpu.device,
        label,
        module,
        &[Some(frame_layout), None, Some(fx_layout)],
        targets,
        crate::passes::Raster {
            buffers: draw.buffers,
            vertex: draw.vertex,
            fragment: draw.fragment,
            depth_write: draw.depth_write,
            depth_compare: draw.depth_compare,
            cull: None,
        },
    )
}

/// The camera frame behind everything.
pub struct BackgroundPass {
    pipeline: wgpu::RenderPipeline,
    shared: Rc<RefCell<Shared>>,
    group: Option<wgpu::BindGroup>,
}

impl Pass for BackgroundPass {
    fn name(&self) -> &'static str {
        "background"
    }
    fn fills_background(&self) -> bool {
        true
    }
    fn condition(&self) -> &'static str {
        "a camera frame is available (it fills every pixel no water, boat or mark covers)"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        let shared = self.shared.borrow();
        result(decide(
            Effect::Background,
            &effect_frame(frame, &shared.cfg),
        ))
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let mut shared = self.shared.borrow_mut();
        shared.write_uniform(gpu, frame);
        self.group = Some(shared.bind_group(&gpu.device));
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        let Some(group) = &self.group else { return 0 };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(2, group, &[]);
        pass.draw(0..3, 0..1);
        1
    }
    fn revision(&self) -> u64 {
        self.shared.borrow().revision
    }
}

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
    /// The room and sky drawn first into the reflection texture.
    room_pipeline: wgpu::RenderPipeline,
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

/// The sky's colour at the horizon (`sky_colour_rough` in `shaders/common.wgsl`): the reflection
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

/// A scissor rectangle, pixels: x, y, width, height.
type Scissor = [u32; 4];

/// Largest height of the boats' wakes above or below the sea surface that the scissor allows
/// for, metres (a Kelvin wake of a keelboat stays well under this).
const WAKE_HEIGHT_MARGIN: f64 = 1.0;

/// The screen rectangle that holds every pixel of the water inside the play area, or `None`
/// when that is the whole screen. Every fragment outside the play area is discarded by the
/// shader anyway, but lavapipe runs the whole fragment shader for it first (measured: a shader
/// that discards every fragment costs as much as the full one), so the AR water draws only
/// inside this rectangle (in the bench's view it cuts 30 % of the rows, about 5 % of the
/// pass's time): the play area grown by the waves' largest displacement (Σ amplitudes,
/// horizontally and vertically, plus WAKE_HEIGHT_MARGIN vertically) as a box, its eight
/// corners projected.
/// Exact culling, no approximation: a corner behind the camera gives the whole screen.
fn play_area_scissor(frame: &FrameContext) -> Option<Scissor> {
    let s = frame.scene;
    let reach: f64 = s.sea.waves.iter().map(|w| w.amplitude()).sum();
    let [ax, az, bx, bz] = s.play_area;
    let o = frame.origin;
    let (w, h) = (f64::from(frame.size[0]), f64::from(frame.size[1]));
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for k in 0..8 {
        let x = if k & 1 == 0 { ax - reach } else { bx + reach } - o.x;
        let z = if k & 2 == 0 { az - reach } else { bz + reach } - o.y;
        let y = if k & 4 == 0 { -1.0 } else { 1.0 } * (reach + WAKE_HEIGHT_MARGIN);
        let c = frame.view_proj * glam::DVec4::new(x, y, z, 1.0);
        if c.w <= 1e-9 {
            return None;
        }
        let px = DVec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h);
        lo = lo.min(px);
        hi = hi.max(px);
    }
    let x0 = lo.x.floor().clamp(0.0, w) as u32;
    let y0 = lo.y.floor().clamp(0.0, h) as u32;
    let x1 = hi.x.ceil().clamp(0.0, w) as u32;
    let y1 = hi.y.ceil().clamp(0.0, h) as u32;
    let rect = [x0, y0, x1 - x0, y1 - y0];
    (rect != [0, 0, frame.size[0], frame.size[1]]).then_some(rect)
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
struct ArPipelines {
    frame_layout: wgpu::BindGroupLayout,
    fx_layout: wgpu::BindGroupLayout,
    targets: Targets,
    wakes: bool,
    /// The overhead-sun caustics instead of the area-ratio map (fixed for the pass's life).
    cheap_caustics: bool,
    /// [`ArConfig::shader_knockout`].
    knockout: u32,
    /// Indexed by [`ArPipelines::slot`].
    made: [Option<wgpu::RenderPipeline>; 16],
}

impl ArPipelines {
    /// The index of the water effects `mask` (FX_* bits; the background's bit 0 is not the
    /// water's).
    fn slot(mask: u32) -> usize {
        ((mask >> 1) & 15) as usize
    }

    /// Make the pipeline for the water effects `mask` unless it exists.
    fn make(&mut self, gpu: &Gpu, mask: u32) {
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
        let effects = [
            shader::WATER,
            EFFECTS_COMMON,
            REFLECTION,
            REFRACTION,
            CAUSTICS,
            FLOWMAP,
            AR_WATER,
            &constants,
        ];
        let parts: Vec<&str> = std::iter::once(&stage).chain(&effects).copied().collect();
        self.made[key] = Some(fx_pipeline(
            gpu,
            &self.frame_layout,
            &self.fx_layout,
            self.targets,
            &label,
            &shader::module(&gpu.device, &label, &parts),
            FxDraw {
                buffers: &[Some(buffer)],
                vertex: "vs_ar",
                fragment: "fs_ar",
                depth_write: true,
                depth_compare: wgpu::CompareFunction::Less,
            },
        ));
    }
}

/// The plan's note when the offscreen work of the last frame is reused.
pub const OFFSCREEN_REUSED: &str =
    "timeline paused and camera still: reflection texture and caustic map of the last frame reused";

/// Everything the reflection texture and the caustic map depend on (the camera image and the
/// configuration are fixed for the pass's life).
#[derive(Debug, Clone, PartialEq)]
struct OffscreenInputs {
    t: f64,
    sea: ocean::WaveSet,
    boats: Vec<crate::Boat>,
    marks: Vec<crate::Mark>,
    play_area: [f64; 4],
    sun: DVec3,
    camera: crate::Camera,
    size: [u32; 2],
    mask: u32,
}

impl OffscreenInputs {
    fn of(frame: &FrameContext, mask: u32) -> OffscreenInputs {
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

fn result(d: EffectDecision) -> Result<String, String> {
    if d.run { Ok(d.reason) } else { Err(d.reason) }
}

impl ArWaterPass {
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
    /// mirrors them, seen through view × reflection matrix (000 eq. 1) with the near plane
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
        let frac = shared.cfg.reflection_fraction;
        let size = frame
            .size
            .map(|v| ((f64::from(v) * frac).round() as u32).max(1));
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
            color_attachments: &[Some(crate::gpu::colour_attachment(&cv, Some(HORIZON_HAZE)))],
            depth_stencil_attachment: Some(crate::gpu::depth_attachment(&dv, true)),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if mirrored {
            pass.set_bind_group(0, &self.reflection_bindings.group, &[]);
            pass.set_pipeline(&self.room_pipeline);
            pass.set_bind_group(2, room, &[]);
            pass.draw(0..3, 0..1);
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
                    && self.reuses(&OffscreenInputs::of(frame, mask_of(&ds))) =>
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
        let inputs = OffscreenInputs::of(frame, mask);
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

/// The camera frame of the effect passes, for their owner to change: from
/// [`add_effect_passes`]. Cheap to clone; it outlives the passes harmlessly.
#[derive(Clone)]
pub struct EffectsHandle {
    shared: Rc<RefCell<Shared>>,
}

impl EffectsHandle {
    /// Draw the next frames over `frame`: its image is written into the textures the passes
    /// already bind (made anew only when the image's kind (RGBA or YUV) or size changes), its
    /// camera and display transform go into the next frame's uniform, and the renderer draws
    /// the next frame even if the scene stands still. No pass or pipeline is rebuilt.
    pub fn set_camera_frame(&self, gpu: &Gpu, frame: CameraFrame) {
        let (image, camera) = frame.split();
        let mut shared = self.shared.borrow_mut();
        shared.set_image(gpu, &image);
        shared.camera = camera;
    }

    /// Size of the camera image now on the GPU, pixels.
    pub fn camera_image_size(&self) -> [u32; 2] {
        self.shared.borrow().camera_image.size
    }

    /// The offscreen targets the passes draw into: the reflection texture's size (once a
    /// frame has drawn one) and the area-ratio caustic map's cells per side (none with the
    /// cheap caustics or without caustics). The budget bench and the tier tests read them.
    pub fn offscreen_sizes(&self) -> OffscreenSizes {
        let shared = self.shared.borrow();
        let map = shared.cfg.effects.contains(Effect::Caustics) && !shared.cfg.cheap_caustics;
        OffscreenSizes {
            reflection_px: shared
                .reflection
                .as_ref()
                .map(|(t, _)| [t.width(), t.height()]),
            caustic_map_cells: map.then(|| shared.caustic_tex.width()),
        }
    }
}

/// [`EffectsHandle::offscreen_sizes`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OffscreenSizes {
    pub reflection_px: Option<[u32; 2]>,
    pub caustic_map_cells: Option<u32>,
}

/// Add the background pass for `cfg` over `camera`'s frame to `renderer` and put the AR
/// water pass in the water pass's place. Effects that are not in `cfg.effects` never run (the
/// passes report "not requested"). Later frames go in through the returned handle
/// ([`EffectsHandle::set_camera_frame`]).
pub fn add_effect_passes(
    renderer: &mut Renderer,
    gpu: &Gpu,
    cfg: ArConfig,
    camera: CameraFrame,
) -> EffectsHandle {
    let targets = renderer.targets;
    let (image, camera) = camera.split();
    let shared = Rc::new(RefCell::new(Shared::new(gpu, targets, cfg, camera, &image)));
    let handle = EffectsHandle {
        shared: shared.clone(),
    };
    let frame_layout = renderer.frame_layout().clone();
    let fx_layout = shared.borrow().layout.clone();
    let background = BackgroundPass {
        pipeline: fx_pipeline(
            gpu,
            &frame_layout,
            &fx_layout,
            targets,
            "background",
            &shader::module(&gpu.device, "background", &[EFFECTS_COMMON, BACKGROUND]),
            FxDraw {
                buffers: &[],
                vertex: "vs_main",
                fragment: "fs_main",
                depth_write: false,
                depth_compare: wgpu::CompareFunction::LessEqual,
            },
        ),
        shared: shared.clone(),
        group: None,
    };
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
        &shader::module(
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
        },
    );
    let water = ArWaterPass {
        water,
        pipelines,
        mask: 0,
        shared,
        group: None,
        reflection_bindings: FrameBindings::new(&gpu.device),
        caustic_map,
        room_pipeline,
        offscreen: Offscreen::default(),
        caustic_bindings: FrameBindings::new(&gpu.device),
        reflection_boats,
        last_decisions: Vec::new(),
        last_offscreen: None,
        size: [0, 0],
        scissor: None,
    };
    renderer.add_pass(Box::new(background));
    if !renderer.replace_pass("water", Box::new(water)) {
        log::warn!("no water pass to shade with the effects: the renderer has none");
    }
    handle
}

/// The effects for a scene without a frame source yet: the default [`ArConfig`] with
/// `effects`, over a synthetic camera frame of `size` pixels seen from the scene's camera
/// (checkers of 1/24 of the play area's width). `regatta render --effects` uses this.
pub fn add_scene_effects(
    renderer: &mut Renderer,
    gpu: &Gpu,
    scene: &crate::Scene,
    size: [u32; 2],
    effects: EffectSet,
) -> EffectsHandle {
    let cfg = ArConfig {
        effects,
        ..ArConfig::default()
    };
    add_scene_effects_with(renderer, gpu, scene, size, cfg)
}

/// [`add_scene_effects`] with a whole [`ArConfig`] (a quality tier's reflection size and
/// caustic tier).
pub fn add_scene_effects_with(
    renderer: &mut Renderer,
    gpu: &Gpu,
    scene: &crate::Scene,
    size: [u32; 2],
    cfg: ArConfig,
) -> EffectsHandle {
    let [ax, az, bx, bz] = scene.play_area;
    let centre = DVec2::new(ax + bx, az + bz) / 2.0;
    let square = ((bx - ax).max(bz - az) / 24.0).max(1e-3);
    // The camera image need not be larger than 640 pixels wide: it is sampled, not shown 1:1.
    let scale = (640.0 / f64::from(size[0].max(1))).min(1.0);
    let frame_size = size.map(|v| ((f64::from(v) * scale).round() as u32).max(1));
    let frame = CameraFrame::synthetic(
        &scene.camera,
        frame_size,
        cfg.table_depth,
        centre,
        cfg.ring_radius_for(scene.play_area),
        square,
    );
    add_effect_passes(renderer, gpu, cfg, frame)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scissor_holds_every_water_point_of_the_play_area() {
        // The demo table seen from its camera: the rectangle is smaller than the screen (so it
        // saves work) and holds the projection of the f64 sea surface over the whole play
        // area, including its displaced edges, at any race time.
        let size = [640, 480];
        for t in [0.0, 40.0, 1234.5] {
            let scene = super::super::demo_table_scene(t);
            let frame = FrameContext::new(&scene, size, 1.0);
            let [x, y, w, h] = play_area_scissor(&frame).expect("the play area is not all");
            assert!(w * h < size[0] * size[1] * 9 / 10, "{:?}", [x, y, w, h]);
            let [ax, az, bx, bz] = scene.play_area;
            let n = 40;
            for i in 0..=n {
                for j in 0..=n {
                    let rest = [
                        ax + (bx - ax) * f64::from(i) / f64::from(n),
                        az + (bz - az) * f64::from(j) / f64::from(n),
                    ];
                    let p = scene.sea.surface(rest, t).position;
                    let local =
                        glam::DVec4::new(p[0] - frame.origin.x, p[1], p[2] - frame.origin.y, 1.0);
                    let c = frame.view_proj * local;
                    let px = (c.x / c.w + 1.0) * 0.5 * f64::from(size[0]);
                    let py = (1.0 - c.y / c.w) * 0.5 * f64::from(size[1]);
                    let inside_screen = (0.0..f64::from(size[0])).contains(&px)
                        && (0.0..f64::from(size[1])).contains(&py);
                    if inside_screen {
                        assert!(
                            px >= f64::from(x)
                                && px <= f64::from(x + w)
                                && py >= f64::from(y)
                                && py <= f64::from(y + h),
                            "t = {t}: water at ({px:.1}, {py:.1}) outside {:?}",
                            [x, y, w, h]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_camera_inside_the_grown_play_area_box_gets_the_whole_screen() {
        // Eye below the box's top (a corner behind the camera): no scissor.
        let mut scene = super::super::demo_table_scene(40.0);
        scene.camera = crate::Camera::look_at(
            glam::DVec3::new(0.0, 0.5, 0.0),
            glam::DVec3::new(10.0, 0.0, 0.0),
            500.0,
        );
        let frame = FrameContext::new(&scene, [320, 240], 1.0);
        assert_eq!(play_area_scissor(&frame), None);
    }
}
