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
//! texture, the caustic map, a sampler, and the flow map's detail texture (binding 5, baked
//! once from [`super::flow_detail`]) with its wrap-around sampler (binding 6).
//! [`add_effect_passes`] returns an [`EffectsHandle`] that writes each new camera frame into
//! the same textures. The caustic map is the f64
//! area-ratio map of [`super::caustics`] at the frame's race time, uploaded each frame.

mod background;
mod config;
mod cover;
mod pipelines;
mod scissor;
mod shared;
mod table_image;
mod water;

use std::cell::RefCell;
use std::rc::Rc;

use glam::DVec2;

use crate::EffectSet;
use crate::backdrop::Backdrop;
use render::gpu::Gpu;
use render::renderer::Renderer;

pub use background::{BACKGROUND, BackgroundPass};
pub use config::ArConfig;
pub use pipelines::{AR_WATER, AR_WATER_PARTS, CAUSTICS, FLOWMAP, REFLECTION, REFRACTION};
use shared::Shared;
pub use shared::{
    EFFECTS_COMMON, EffectsUniform, FLOW_DETAIL_FORMAT, caustic_region, effect_frame,
    flow_detail_texture, flow_detail_texture_of, linear_repeat_sampler,
};
pub use table_image::{
    screen_projection, straight_columns, straight_image, straight_image_of_clip, table_column,
    table_image,
};
pub use water::{ArWaterPass, OFFSCREEN_REUSED, REFLECTION_ROOM};

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
    pub fn set_backdrop(&self, gpu: &Gpu, frame: Backdrop) {
        let (image, camera) = frame.split();
        let mut shared = self.shared.borrow_mut();
        shared.set_image(gpu, &image);
        shared.camera = camera;
    }

    /// The water's optics from the next frame on, its table `table_depth` scene metres down
    /// (`ArConfig::water`, `ArConfig::table_depth`).
    pub fn set_water(&self, water: render::water_look::WaterLook, table_depth: f64) {
        let mut shared = self.shared.borrow_mut();
        shared.cfg.water = water;
        shared.cfg.table_depth = table_depth;
    }

    /// Draw the next frames with `effects` only (the panel's switches, live): the planner reads
    /// the set every frame, so the passes skip the others as "not requested"; the next frame
    /// is drawn even if the scene stands still.
    pub fn set_effects(&self, effects: EffectSet) {
        let mut shared = self.shared.borrow_mut();
        if shared.cfg.effects != effects {
            shared.cfg.effects = effects;
            shared.revision += 1;
        }
    }

    /// A quality tier's set-up from the next frame on, live: `cfg`'s effects, reflection
    /// texture fraction, caustic tier (cheap or the area-ratio map) and map cells; the rest
    /// (camera image, water, current) kept. The caustic map is made anew at a new size, the AR
    /// water pipelines anew when the caustic tier changes (a shader constant), and the next
    /// frame draws its offscreen targets afresh, so the frame is the one passes built with
    /// `cfg` draw.
    pub fn set_quality(&self, gpu: &Gpu, cfg: &ArConfig) {
        let mut shared = self.shared.borrow_mut();
        let s = &mut *shared;
        let key = |c: &ArConfig| {
            (
                c.effects,
                c.reflection_fraction,
                c.cheap_caustics,
                c.caustic_resolution,
            )
        };
        if key(&s.cfg) == key(cfg) {
            return;
        }
        if s.cfg.caustic_resolution.1 != cfg.caustic_resolution.1 {
            s.caustic_tex = shared::caustic_map_texture(&gpu.device, cfg.caustic_resolution.1);
            s.group = None;
        }
        s.cfg.effects = cfg.effects;
        s.cfg.reflection_fraction = cfg.reflection_fraction;
        s.cfg.cheap_caustics = cfg.cheap_caustics;
        s.cfg.caustic_resolution = cfg.caustic_resolution;
        s.revision += 1;
        s.quality += 1;
    }

    /// The effects the passes draw now.
    pub fn effects(&self) -> EffectSet {
        self.shared.borrow().cfg.effects
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
        let map =
            shared.cfg.effects.contains(crate::Effect::Caustics) && !shared.cfg.cheap_caustics;
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

/// The room's diffuse radiance the AR water takes, per band: the camera's white (the
/// `vec3(1.0)` room of `ar_water.wgsl`, which makes the table's camera colour its albedo).
pub const AR_ROOM_RADIANCE: [f64; 3] = [1.0; 3];

/// Add the background pass for `cfg` over `camera`'s frame to `renderer` and put the AR
/// water pass in the water pass's place. Effects that are not in `cfg.effects` never run (the
/// passes report "not requested"). Later frames go in through the returned handle
/// ([`EffectsHandle::set_backdrop`]).
pub fn add_effect_passes(
    renderer: &mut Renderer,
    gpu: &Gpu,
    cfg: ArConfig,
    camera: Backdrop,
) -> EffectsHandle {
    let targets = renderer.targets;
    let (image, camera) = camera.split();
    let shared = Rc::new(RefCell::new(Shared::new(gpu, targets, cfg, camera, &image)));
    let handle = EffectsHandle {
        shared: shared.clone(),
    };
    let frame_layout = renderer.frame_layout().clone();
    let background = BackgroundPass::new(gpu, &frame_layout, targets, shared.clone());
    let water = ArWaterPass::new(gpu, frame_layout, targets, shared);
    renderer.add_pass(Box::new(background));
    // Over the camera image the AR water takes the room's radiance as the camera's white
    // (`ar_water.wgsl`'s room): the boats take the same light, in each frame that shows the
    // image (the renderer applies it then; switched off live, sun and sky).
    renderer.set_room_light(Some(AR_ROOM_RADIANCE));
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
    scene: &render::Scene,
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
    scene: &render::Scene,
    size: [u32; 2],
    cfg: ArConfig,
) -> EffectsHandle {
    let [ax, az, bx, bz] = scene.play_area;
    let centre = DVec2::new(ax + bx, az + bz) / 2.0;
    let square = ((bx - ax).max(bz - az) / 24.0).max(1e-3);
    // The camera image need not be larger than 640 pixels wide: it is sampled, not shown 1:1.
    let scale = (640.0 / f64::from(size[0].max(1))).min(1.0);
    let frame_size = size.map(|v| ((f64::from(v) * scale).round() as u32).max(1));
    let frame = Backdrop::synthetic(
        &scene.camera,
        frame_size,
        cfg.table_depth,
        centre,
        cfg.ring_radius_for(scene.play_area),
        square,
    );
    add_effect_passes(renderer, gpu, cfg, frame)
}
