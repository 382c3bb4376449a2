//! The phone's frame: the race (plain 3D until the course stands on the table, then over the
//! camera image with the AR camera and light), or the pool, or the camera image alone before
//! anything is placed; then the panels, the bar and the banner. Also the graphics' life: made
//! on the first window, a surface per window, rebuilt on OpenGL ES after a lost device.

use ar::arcore::CoursePlacement;
use effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use pool::{PoolFrame, PoolRenderer, PoolSettings, PoolView};
use render::{Camera, Gpu, Renderer};

use super::PhoneApp;
use crate::core::camera_frame::{backdrop_with_image, display_of};
use crate::core::gfx::{self, Acquired, LostFlag, Window};
use crate::core::table;
use crate::core::vulkan_marker::{FELL_BACK_NOTE, GOOD_FRAMES, VulkanMarker};
use crate::hud::{EguiPainter, SceneChoice, phone_bar, race_panels};
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
    lost: LostFlag,
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

impl PhoneApp {
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
                EguiPainter::for_format(&gpu.device, render::OFFSCREEN_FORMAT.remove_srgb_suffix())
            }
        };
        let format = window.format().unwrap_or(render::OFFSCREEN_FORMAT);
        let setup = RaceSetup::new(Profile::Phone);
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
        if self.graphics.as_ref().is_some_and(|g| g.lost.is_lost()) {
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

    fn draw_race(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) {
        let mut scene = self.world.orbit_scene(self.race_time(), &mut self.orbit);
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

    /// The race with its overlays into `target`; the frame's GPU time kept for the governor.
    fn render_race(
        &mut self,
        g: &mut Graphics,
        target: &wgpu::TextureView,
        size: [u32; 2],
        scene: &render::Scene,
    ) {
        self.prepare_overlays(g, scene, size);
        g.gpu_ms = g
            .race
            .render(&g.gpu, target, size, scene)
            .ok()
            .and_then(|r| r.gpu_ms);
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
        let mut view = PoolView {
            camera: self.pool_orbit.camera(),
            ..PoolView::default_desktop(size)
        };
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
        let frame = PoolFrame::new(&self.pool.scene, self.pool_t, &view, &settings);
        g.pool
            .get_or_insert_with(|| PoolRenderer::new(&g.gpu, format, settings))
            .render(&g.gpu, target, &frame);
        self.pool.view = Some(view);
    }

    /// The panels (race only), the phone's bar and the banner over the frame.
    fn draw_hud(&mut self, g: &mut Graphics, texture: &wgpu::Texture, size: [u32; 2]) {
        let message = self.banner();
        let banner_button = crate::hud::banner::button(self.ar.session);
        let raw = self.touch.take_raw_input(size, self.now);
        let recording = self.ar.recorder.is_some();
        // "Share clip" in the race scene; off while a clip is drawn.
        let share = (self.scene == SceneChoice::Race).then(|| !self.clip_share.busy());
        let mut share_pressed = false;
        let mut choice = self.scene;
        let mut record = false;
        let mut free = self.ui_free;
        let (panels, world, events) = (&mut self.panels, &self.world, &self.events);
        let overlays = &mut self.overlays;
        let races = self.races.panel(&world.race.name);
        let mut open = None;
        let mut clicked = None;
        let mut scene_rect = None;
        let mut bar = None;
        // The phone has no cursor or clipboard to update: the platform output is not needed.
        let _ = g
            .egui
            .paint(&g.gpu.device, &g.gpu.queue, texture, size, raw, |ui| {
                if choice == SceneChoice::Race {
                    overlays.paint(ui.ctx(), size);
                    let r = race_panels(
                        ui,
                        panels,
                        &world.race,
                        events,
                        None,
                        &world.race.name,
                        &overlays.settings.selected,
                        races,
                    );
                    clicked = r.clicked_boat;
                    open = r.open;
                    scene_rect = r.scene_rect;
                }
                let laid = phone_bar(
                    ui.ctx(),
                    &mut choice,
                    (recording, share),
                    message.as_ref(),
                    banner_button,
                );
                record |= laid.record_toggled;
                share_pressed |= laid.share_pressed;
                bar = Some(laid);
                // The scene's part of the screen: what the panels left, else what the bar left.
                free = scene_rect.unwrap_or_else(|| ui.available_rect_before_wrap());
            });
        self.ui_free = free;
        self.bar = bar;
        if bar.is_some_and(|b| b.banner_pressed) {
            // After a refusal: ask for the camera again (Android shows its dialog, or answers
            // at once when the user chose "don't ask again"; the banner then still points to
            // Settings).
            self.session_event(ar::arcore::Event::AskPermissionAgain);
        }
        if let Some(b) = clicked {
            ui::toggle_selection(&mut self.overlays.settings.selected, b);
        }
        if record {
            self.record_button();
        }
        if share_pressed {
            self.share_clip();
        }
        self.races_panel_opened();
        self.races_request(open);
        self.choose_scene(choice);
    }
}
