//! The phone's frame: the race (plain 3D until the course stands on the table, then over the
//! camera image with the AR camera and light), or the pool, or the camera image alone before
//! anything is placed; then the panels, the bar and the banner. Also the graphics' life: made
//! on the first window, a surface per window, rebuilt on OpenGL ES after a lost device.

use ar::arcore::CoursePlacement;
use effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use pool::{PoolRenderer, PoolSettings, PoolView};
use render::{Camera, Gpu, Renderer};

use super::App;
use crate::core::camera_frame::{backdrop_with_image, display_of};
use crate::core::gfx::{self, Acquired, LostFlag, Window};
use crate::core::table;
use crate::core::vulkan_marker::{FELL_BACK_NOTE, GOOD_FRAMES, VulkanMarker};
use crate::hud::{EguiPainter, SceneChoice};
use crate::pool_play::PoolPlay;
use crate::setup::{Profile, RaceSetup};

/// The device, the window, and what draws into it.
pub struct Graphics {
    pub gpu: Gpu,
    pub window: Window,
    /// The race: plain 3D until the course stands on the table, then with the effect passes
    /// over the camera image (`race_effects`, built on the first such frame).
    pub(super) race: Renderer,
    pub(super) race_effects: Option<EffectsHandle>,
    /// The camera image alone (effect passes, the sea taken out): behind the pool, and before
    /// anything is placed.
    backdrop: Option<(Renderer, EffectsHandle)>,
    pool: Option<PoolRenderer>,
    /// (frame, placement) last uploaded to `race_effects`, and frame to `backdrop`.
    race_upload: Option<(u64, CoursePlacement)>,
    backdrop_upload: Option<u64>,
    pub egui: EguiPainter,
    pub(super) lost: LostFlag,
    /// Said on the banner: the device came from OpenGL ES because Vulkan could not be had.
    pub note: Option<String>,
    pub frames_drawn: u64,
    /// The race renderer's GPU time of the last frame, where measured; the quality tier it
    /// draws at and whether its effect passes were there then (`tiers.rs`).
    pub(super) gpu_ms: Option<f64>,
    /// The Scene panel's switches and the quality tier on `race`, as the window applies them
    /// (`crate::panels::SceneApplier`; `tiers.rs`).
    pub(super) scene: crate::panels::SceneApplier,
    /// The Vulkan crash marker, armed until [`GOOD_FRAMES`] frames were presented.
    marker: Option<VulkanMarker>,
    /// The sea last handed to `race_effects` (`tiers.rs`, `follow_water`); `None` after they
    /// were built anew.
    pub(super) water: Option<render::water_look::WaterLook>,
}

/// Takes the sea's place in the backdrop renderer: only the camera image is drawn.
struct NoSea;

impl render::Pass for NoSea {
    fn name(&self) -> &'static str {
        "water"
    }
    fn condition(&self) -> &'static str {
        "never: the camera image alone, behind the pool or before anything is placed"
    }
    fn plan(&self, _: &render::frame::FrameContext) -> Result<String, String> {
        Err("no sea in the camera-image backdrop".into())
    }
    fn prepare(&mut self, _: &render::Gpu, _: &render::frame::FrameContext) {}
    fn draw(&self, _: &mut wgpu::RenderPass<'_>) -> u64 {
        0
    }
}

impl Graphics {
    /// The wakes of a newly opened race (and nothing kept of the last one's frames).
    pub(super) fn set_race_wake(&mut self, wake: Option<std::sync::Arc<ocean::wake::Wake>>) {
        self.scene.set_race_wake(wake, &mut self.race);
        self.race_upload = None;
    }
}

impl App {
    /// A new window: the first makes the device (Vulkan, else OpenGL ES); later ones only a
    /// surface with the kept configuration.
    pub(super) fn attach_window(&mut self, size: [u32; 2]) {
        let [w, h] = [size[0].max(1), size[1].max(1)];
        if let Some(g) = self.graphics.as_mut() {
            let attached = match self.maker.as_mut() {
                Some(make) => {
                    make(&g.gpu.instance).and_then(|s| g.window.attach_surface(&g.gpu, s, w, h))
                }
                None => {
                    g.window.attach_offscreen(&g.gpu, w, h);
                    Ok(())
                }
            };
            if let Err(e) = attached {
                log::error!("regatta: cannot draw into the new window: {e}");
            }
            return;
        }
        match self.open_graphics(None, w, h) {
            Ok(g) => {
                self.backend
                    .limit_image_side(g.gpu.device.limits().max_texture_dimension_2d);
                self.graphics = Some(g);
            }
            Err(e) => log::error!("regatta: {e}"),
        }
    }

    /// Makes the device and the first window's target on `only` (or Vulkan, then OpenGL ES).
    fn open_graphics(
        &mut self,
        only: Option<wgpu::Backends>,
        w: u32,
        h: u32,
    ) -> Result<Graphics, String> {
        let maker = &mut self.maker;
        let open = |b: wgpu::Backends| match maker.as_mut() {
            Some(make) => Gpu::for_surface(b, |i| make(i), w, h).map(|(gpu, s)| (gpu, Some(s))),
            None => Gpu::headless(b).map(|gpu| (gpu, None)),
        };
        // A launch that stopped on its first Vulkan frames left the marker: OpenGL ES now.
        let marker = self.data_dir.as_deref().map(VulkanMarker::in_dir);
        let crashed = only.is_none() && marker.as_ref().is_some_and(|m| m.left_by_a_crash());
        let mut open = open;
        let ((gpu, surface), note) = match only {
            Some(b) => open(b).map(|x| (x, None)).map_err(|e| e.to_string())?,
            None if crashed => {
                log::warn!("regatta: {FELL_BACK_NOTE}");
                match open(wgpu::Backends::GL) {
                    Ok(x) => (x, Some(FELL_BACK_NOTE.to_string())),
                    Err(e) => {
                        log::error!("regatta: no OpenGL ES ({e}); trying Vulkan again");
                        gfx::open_with_fallback(open)?
                    }
                }
            }
            None => gfx::open_with_fallback(open)?,
        };
        log::info!("regatta: drawing on {}", gpu.describe());
        // Armed before anything is submitted on Vulkan; cleared after GOOD_FRAMES frames.
        let marker = marker.filter(|_| gpu.adapter.get_info().backend == wgpu::Backend::Vulkan);
        if let Some(m) = &marker {
            m.arm();
        }
        let mut window = Window::default();
        let egui = match surface {
            Some(mut s) => {
                let view_formats = gpu
                    .adapter
                    .get_downlevel_capabilities()
                    .flags
                    .contains(wgpu::DownlevelFlags::SURFACE_VIEW_FORMATS);
                let egui = EguiPainter::new(&gpu.device, &mut s, view_formats);
                window.first_surface(s);
                egui
            }
            None => {
                window.attach_offscreen(&gpu, w, h);
                let view = window
                    .egui_view_format()
                    .unwrap_or(render::OFFSCREEN_FORMAT);
                EguiPainter::for_format(&gpu.device, view)
            }
        };
        let format = window.format().unwrap_or(render::OFFSCREEN_FORMAT);
        let setup = self.race_setup();
        let wake = setup.wake_or_none(&self.world.race);
        Ok(Graphics {
            scene: crate::panels::SceneApplier::new(wake.clone()),
            race: setup.renderer(&gpu, format, wake),
            race_effects: None,
            backdrop: None,
            pool: None,
            race_upload: None,
            backdrop_upload: None,
            egui,
            lost: LostFlag::watch(&gpu),
            note,
            frames_drawn: 0,
            water: None,
            gpu_ms: None,
            marker,
            gpu,
            window,
        })
    }

    /// The device was lost: everything on it goes; a new one on OpenGL ES takes the window.
    fn rebuild_after_loss(&mut self) {
        let Some(old) = self.graphics.take() else {
            return;
        };
        let [w, h] = old.window.size();
        drop(old);
        match self.open_graphics(Some(wgpu::Backends::GL), w, h) {
            Ok(mut g) => {
                g.note = Some("The GPU was lost; drawing with OpenGL ES.".to_string());
                log::warn!("regatta: the GPU was lost; drawing with OpenGL ES");
                self.graphics = Some(g);
            }
            Err(e) => log::error!("regatta: no GPU after the device was lost: {e}"),
        }
    }

    pub(super) fn draw(&mut self) {
        // Lost, its callback run or not (wgpu runs it only from a poll; drawing on a device
        // lost before it panicked in egui-wgpu): rebuilt before anything is drawn.
        if self
            .graphics
            .as_ref()
            .is_some_and(|g| g.lost.is_lost(&g.gpu.queue))
        {
            self.rebuild_after_loss();
        }
        if let Some(mut g) = self.graphics.take() {
            self.draw_with(&mut g);
            self.graphics = Some(g);
        }
    }

    fn draw_with(&mut self, g: &mut Graphics) {
        let frame = match g.window.acquire(&g.gpu) {
            Acquired::Frame(f) => f,
            Acquired::Skip => return,
            Acquired::Failed(e) => {
                log::error!("regatta: {e}");
                return;
            }
        };
        let size = g.window.size();
        let format = g.window.format().unwrap_or(render::OFFSCREEN_FORMAT);
        let target = frame.texture().create_view(&wgpu::TextureViewDescriptor {
            format: Some(format),
            ..Default::default()
        });
        match self.scene {
            SceneChoice::Race => self.draw_race(g, &target, size, format),
            SceneChoice::Pool => self.draw_pool(g, &target, size, format),
        }
        self.draw_hud(g, frame.texture(), size);
        if g.lost.is_raised() {
            // Lost within this frame (found by a submit or by egui's painter): nothing is
            // shown (polling a lost device, as an offscreen window's present does, can panic
            // in wgpu); the next frame rebuilds.
            return;
        }
        g.window.present(&g.gpu, frame);
        g.frames_drawn += 1;
        if g.frames_drawn >= GOOD_FRAMES
            && let Some(m) = g.marker.take()
        {
            m.clear();
        }
    }

    /// The camera image alone into `target`; false when there is none.
    fn draw_backdrop(
        &self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) -> bool {
        let Some((view, frame)) = self.ar.view() else {
            return false;
        };
        let seq = self.ar.frame_seq;
        if g.backdrop_upload != Some(seq) {
            let background = match backdrop_with_image(frame, &table::AR_AS_IS, display_of(frame)) {
                Ok(b) => b,
                Err(e) => {
                    log::warn!("regatta: {e}");
                    return false;
                }
            };
            match &g.backdrop {
                Some((_, handle)) => handle.set_backdrop(&g.gpu, background),
                None => {
                    let mut r = RaceSetup::new(Profile::Phone).renderer(&g.gpu, format, None);
                    let handle = add_effect_passes(&mut r, &g.gpu, ArConfig::default(), background);
                    r.replace_pass("water", Box::new(NoSea));
                    g.backdrop = Some((r, handle));
                }
            }
            g.backdrop_upload = Some(seq);
        }
        let mut scene = self.world.scene_at(self.race_time(), None);
        scene.boats.clear();
        scene.marks.clear();
        scene.camera = Camera::from_view_projection(view.view, view.projection_gl);
        if let Some((r, _)) = g.backdrop.as_mut() {
            // A failed frame is logged by the renderer; the next one tries again.
            let _ = r.render(&g.gpu, target, size, &scene);
        }
        true
    }

    /// How the race renderer is built for this profile (the desktop's with the command
    /// line's water).
    fn race_setup(&self) -> RaceSetup {
        let mut setup = RaceSetup::new(self.profile());
        if let Some(d) = &self.desktop {
            setup.sea_water = d.sea_water;
        }
        setup
    }

    fn draw_race(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) {
        let t = self.race_time();
        let mut scene = self.world.orbit_scene(t, &mut self.orbit);
        // "Follow": the orbit turns about the first selected boat instead of the fleet.
        if self.panels.follow
            && let Some(target) =
                crate::panels::follow_target(&self.world.race, self.overlays.selected(), t)
        {
            self.orbit.target = target;
            scene.camera = self.orbit.camera();
        }
        if self.desktop.is_some() {
            // The desktop: the orbit view, or the feed's camera and table.
            if self.put_on_feed(g, &mut scene, size, format) {
                self.render_race(g, target, size, &scene);
            }
            return;
        }
        let Some(p) = self.course else {
            // Not placed: the camera image where AR runs (to see the table), else 3D.
            if !self.draw_backdrop(g, target, size, format) {
                self.render_race(g, target, size, &scene);
            }
            return;
        };
        // On the table: the AR camera and light, the camera image behind.
        if let Some((view, frame)) = self.ar.view() {
            scene.camera = table::display_camera(&p, view);
            if let Some(l) = view.light_towards {
                scene.sun = table::sun(&p, l);
            }
            table::boats_as_models(&mut scene, &p);
            scene.play_area = self.table_room.area(self.world.race_bounds);
            let upload = (self.ar.frame_seq, p);
            if g.race_upload != Some(upload) {
                match backdrop_with_image(frame, &p, display_of(frame)) {
                    Ok(background) => match &g.race_effects {
                        Some(handle) => handle.set_backdrop(&g.gpu, background),
                        None => {
                            // The table's sea; the Scene panel's water follows (`follow_water`).
                            let cfg = ArConfig::on_table(render::water_look::WaterLook::default());
                            let fx = add_effect_passes(&mut g.race, &g.gpu, cfg, background);
                            g.water = None;
                            g.race_effects = Some(fx);
                        }
                    },
                    Err(e) => log::warn!("regatta: {e}"),
                }
                g.race_upload = Some(upload);
            }
        }
        self.render_race(g, target, size, &scene);
    }

    /// With the desktop's feed, puts `scene` on its table (the feed's frame for the app's
    /// seconds handed to the effects, the renderer built with the effect passes the first
    /// time); false when the feed failed (the app cannot go on: `App::take_failure`).
    fn put_on_feed(
        &mut self,
        g: &mut Graphics,
        scene: &mut render::Scene,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) -> bool {
        let Some(d) = self.desktop.as_mut() else {
            return true;
        };
        let Some(feed) = d.feed.as_mut() else {
            return true;
        };
        let wake = g.scene.current_wake();
        let bounds = self.world.race_bounds;
        if let Err(e) = feed.prepare(&g.gpu, &mut g.race, format, wake, bounds, size, self.now) {
            d.failure = Some(e.to_string());
            return false;
        }
        feed.apply(scene);
        true
    }

    /// The race with its overlays into `target`, the Scene panel's switches and the tier
    /// applied first (the same path on both profiles); the frame's GPU time kept for the
    /// governor.
    fn render_race(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        scene: &render::Scene,
    ) {
        let fx = self.effects_handle(g).cloned();
        g.scene
            .apply(&self.panels.settings, &mut g.race, fx.as_ref());
        self.apply_tier_to(g);
        self.prepare_overlays(g, scene, size);
        let report = g.race.render(&g.gpu, target, size, scene).ok();
        g.gpu_ms = report.as_ref().and_then(|r| r.gpu_ms);
        if let Some(r) = &report {
            self.record(r);
        }
    }

    /// The effect passes' handle of the race renderer: the feed's on the desktop, the camera
    /// image's on the phone.
    pub(super) fn effects_handle<'a>(&'a self, g: &'a Graphics) -> Option<&'a EffectsHandle> {
        match &self.desktop {
            Some(d) => d.feed.as_ref().and_then(|f| f.effects_handle()),
            None => g.race_effects.as_ref(),
        }
    }

    /// The overlays over the race as the desktop draws them (labels at the phone's density):
    /// their layers into `g.race`'s overlay passes; the labels are painted in the egui pass.
    fn prepare_overlays(&mut self, g: &mut Graphics, scene: &render::Scene, size: [u32; 2]) {
        let ppp = f64::from(self.touch.pixels_per_point);
        let race = &self.world.race;
        self.overlays.follow_panel(&self.panels.settings);
        let debrief = self.overlays.debrief(&mut self.panels.debrief, race);
        self.overlays
            .prepare(&g.gpu, &mut g.race, (race, debrief), scene, size, ppp);
    }

    fn draw_pool(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) {
        let settings = PoolSettings::default();
        let mut view = PoolPlay::orbit_view(&self.pool_orbit, size);
        let backdrop = self.draw_backdrop(g, target, size, format);
        if let (true, Some(place), Some((display, _))) =
            (backdrop, self.pool_placement, self.ar.view())
        {
            view = PoolView {
                camera: Camera::from_view_projection(display.view, display.projection_gl),
                model: PoolView::standing_on(place.race_to_ar(), &self.pool.scene, &settings),
                size,
                over_camera_image: true,
            };
        } else if backdrop {
            // The camera image is shown until the pool is placed.
            self.pool.view = None;
            return;
        }
        self.pool
            .render(&mut g.pool, &g.gpu, format, target, view, self.pool_t);
    }
}
