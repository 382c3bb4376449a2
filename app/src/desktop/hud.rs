//! The desktop's HUD: the egui panels over the window: the race-timeline scrubber (which owns race time),
//! the leaderboard, effect toggles and the performance panel of `crates/ui`, wired to winit
//! through egui-winit and painted after the scene, into the same surface texture, by the
//! painter the phone uses too ([`crate::hud::EguiPainter`]).

use std::sync::Arc;
use std::time::Instant;

use ocean::wake::Wake;

use render::FrameReport;
use ui::{FpsMeter, OpenRequest, PerfStats, RegattaUi, TimelineEvent};
use winit::event::WindowEvent;
use winit::window::Window;

use crate::hud::EguiPainter;
pub use crate::hud::{initial_clock, perf_stats};

/// The panels, their egui-winit input and painter.
pub struct Hud {
    input: egui_winit::State,
    painter: EguiPainter,
    pub panels: RegattaUi,
    events: Vec<TimelineEvent>,
    fps: FpsMeter,
    perf: PerfStats,
    last: Instant,
    title: String,
    /// The Scene panel's switches applied to the renderer (the wakes kept while off).
    scene: crate::panels::SceneApplier,
    /// The last race that failed to open, as one sentence (the race shown stays).
    pub load_error: Option<String>,
    /// What the Races panel asked for this frame, for the app to do.
    pub open_request: Option<OpenRequest>,
    /// What the tier control changed this frame, for the app's governor.
    pub tier_change: Option<ui::TierChange>,
    /// When the app exits by itself (`REGATTA_EXIT_AFTER_FRAMES`, for the smoke test).
    exit_after: super::smoke::ExitAfter,
    /// The surface's colour format (the screenshot texture uses it too).
    format: wgpu::TextureFormat,
    /// The race overlays in the scene (labels, trails, course, lines, wind).
    pub scene_overlays: crate::scene_overlay::live::LiveOverlays,
    /// The "Share clip" button and its worker (`share_clip.rs`).
    pub share_clip: super::share_clip::ShareClip,
    /// The button was pressed this frame: the app starts the clip (it holds the world).
    pub share_requested: bool,
}

/// The window's first size: 1280×720 points, or `REGATTA_WINDOW_SIZE=WxH` (physical pixels;
/// the smoke test keeps lavapipe's frames small with it).
pub fn window_size() -> winit::dpi::Size {
    let env = std::env::var("REGATTA_WINDOW_SIZE").ok();
    match env.as_deref().map(crate::setup::inputs::parse_frame_size) {
        Some(Ok((w, h))) => winit::dpi::PhysicalSize::new(w, h).into(),
        Some(Err(e)) => {
            log::warn!("REGATTA_WINDOW_SIZE: {e}; opening 1280x720");
            winit::dpi::LogicalSize::new(1280.0, 720.0).into()
        }
        None => winit::dpi::LogicalSize::new(1280.0, 720.0).into(),
    }
}

impl Hud {
    /// Panels for `race` in `window`. The surface gets a non-sRGB view format: egui blends in
    /// gamma space, so it paints through a `*Unorm` view of the `*UnormSrgb` surface texture
    /// (through an sRGB view its translucent panels come out washed out).
    pub fn new(
        window: &Window,
        device: &wgpu::Device,
        surface: &mut render::gpu::SurfaceTarget,
        race: &race::Race,
        title: String,
        with_effect_passes: bool,
    ) -> Self {
        let format = surface.config.format;
        // Desktop Vulkan, Metal and DX12 all take other view formats of the surface.
        let painter = EguiPainter::new(device, surface, true);
        let input = egui_winit::State::new(
            painter.ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(device.limits().max_texture_dimension_2d as usize),
        );
        let mut panels = RegattaUi::new(
            initial_clock(race),
            crate::panels::effect_toggles(with_effect_passes),
        );
        panels.settings.overlays = crate::scene_overlay::panel_toggles(Default::default());
        crate::panels::set_water_ranges(&mut panels.settings, with_effect_passes);
        let mut scene_overlays = crate::scene_overlay::live::LiveOverlays::default();
        // The selected boats (at most two: follow, the plots, compare, the highlighted labels).
        crate::panels::panels_from_env(&mut panels, &mut scene_overlays.settings.selected, race);
        Self {
            input,
            painter,
            panels,
            events: ui::timeline_events(race),
            fps: FpsMeter::new(30),
            perf: PerfStats::default(),
            last: Instant::now(),
            title,
            scene: crate::panels::SceneApplier::new(crate::world::race_wake(race).ok()),
            load_error: None,
            open_request: None,
            tier_change: None,
            format,
            exit_after: super::smoke::ExitAfter::from_env(),
            scene_overlays,
            share_clip: Default::default(),
            share_requested: false,
        }
    }

    /// Hands a window event to egui; true when egui used it (the pointer is over a panel), so
    /// the app does not orbit the camera with it.
    pub fn on_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        self.input.on_window_event(window, event).consumed
    }

    /// True while the pointer is over a panel or egui has the keyboard.
    pub fn wants_pointer(&self) -> bool {
        self.painter.ctx.egui_wants_pointer_input()
    }

    pub fn wants_keyboard(&self) -> bool {
        self.painter.ctx.egui_wants_keyboard_input()
    }

    /// Advances the clock by the wall time since the last call; returns the race time to draw.
    pub fn tick(&mut self) -> f64 {
        let now = Instant::now();
        let dt = now.duration_since(self.last).as_secs_f64();
        self.last = now;
        self.fps.push(dt);
        self.panels.clock.advance(dt);
        self.panels.clock.time()
    }

    /// Takes the renderer's record of the frame for the performance panel.
    pub fn record(&mut self, report: &FrameReport) {
        self.perf = perf_stats(report, &self.fps);
    }

    /// Applies the Scene panel's switches to the renderer (before it draws the frame): the
    /// wakes, and the AR effects through `effects` where the effect passes draw.
    pub fn apply_effects(
        &mut self,
        renderer: &mut render::Renderer,
        effects: Option<&effects::passes::EffectsHandle>,
    ) {
        let settings = &self.panels.settings;
        self.scene.apply(settings, renderer, effects);
        self.scene_overlays.follow_panel(settings);
    }

    /// The quality tier on the running renderer when it changed, every setting, through the
    /// Scene panel's switches, and its overlay detail onto the race overlays: the phone's path
    /// too
    /// ([`crate::panels::SceneApplier::follow_tier`]).
    pub fn follow_tier(
        &mut self,
        tier: quality::Tier,
        gpu: &render::Gpu,
        renderer: &mut render::Renderer,
        effects: Option<&effects::passes::EffectsHandle>,
        race: &race::Race,
    ) {
        let settings = &mut self.panels.settings;
        let applied = self
            .scene
            .follow_tier(tier, settings, gpu, renderer, effects, race);
        if let Some(t) = applied {
            // The tier's overlay detail onto the race overlays drawn.
            self.scene_overlays.set_detail(t.overlay);
        }
    }

    /// The water the Scene panel asks for (the feed applies it on the table).
    pub fn water_look(&self) -> render::water_look::WaterLook {
        crate::panels::water_look(&self.panels.settings)
    }

    /// The race's wakes when the "Wakes" toggle is on (for a renderer built afresh).
    pub fn wake(&self) -> Option<Arc<Wake>> {
        self.scene.current_wake()
    }

    /// Shows `race` from now on: a fresh timeline, events, selection and plots; its wakes in
    /// `renderer`. The title names it.
    pub fn set_race(&mut self, race: &race::Race, renderer: &mut render::Renderer) {
        crate::hud::panels_for_new_race(
            race,
            &mut self.panels,
            &mut self.events,
            &mut self.scene_overlays.settings.selected,
        );
        self.load_error = None;
        self.title = race.name.clone();
        self.scene
            .set_race_wake(crate::world::race_wake(race).ok(), renderer);
    }

    /// Counts a drawn frame; true when the app should exit (`REGATTA_EXIT_AFTER_FRAMES`).
    pub fn frame_done(&mut self) -> bool {
        self.exit_after.frame_done()
    }

    /// Lays out the panels and paints them over `texture` (`size` pixels; its format, or its
    /// non-sRGB twin among its view formats).
    pub fn paint(
        &mut self,
        window: &Window,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        texture: &wgpu::Texture,
        size: [u32; 2],
        race: &race::Race,
    ) {
        let raw = self.input.take_egui_input(window);
        let (panels, events, perf, title, scene) = (
            &mut self.panels,
            &self.events,
            &self.perf,
            &self.title,
            &mut self.scene_overlays,
        );
        let races = ui::RacesPanel {
            current: &race.name,
            error: self.load_error.as_deref(),
            dialog: true,
            ..Default::default()
        };
        let mut response = None;
        let (share, mut share_pressed) = (&self.share_clip, false);
        let platform = self.painter.paint(device, queue, texture, size, raw, |ui| {
            scene.paint(ui.ctx(), size);
            response = Some(crate::hud::race_panels(
                ui,
                panels,
                race,
                events,
                Some(perf),
                title,
                &scene.settings.selected,
                Some(races),
            ));
            // Bottom right, above the timeline's panel (about 92 points tall in a 1280x720
            // window; a window narrow enough to wrap the panel's rows makes it taller).
            egui::Area::new(egui::Id::unique("share-clip"))
                .anchor(egui::Align2::RIGHT_BOTTOM, egui::vec2(-8.0, -100.0))
                .show(ui.ctx(), |ui| {
                    egui::Frame::popup(ui.style()).show(ui, |ui| share_pressed = share.ui(ui));
                });
        });
        self.input.handle_platform_output(window, platform);
        self.share_requested |= share_pressed;
        if let Some(r) = response {
            if let Some(b) = r.clicked_boat {
                ui::toggle_selection(&mut self.scene_overlays.settings.selected, b);
            }
            if r.clear_selection {
                self.scene_overlays.settings.selected.clear();
            }
            if r.open.is_some() {
                self.open_request = r.open;
            }
            if r.tier.is_some() {
                self.tier_change = r.tier;
            }
        }
    }
}

impl Hud {
    /// With `REGATTA_SCREENSHOT=FILE.png`, draws `scene` and the panels once more into an
    /// offscreen texture of the surface's format and writes it as PNG (surface textures cannot
    /// be read back). Errors are one sentence naming the file.
    pub fn save_screenshot(
        &mut self,
        window: &Window,
        gpu: &render::Gpu,
        renderer: &mut render::Renderer,
        scene: &render::Scene,
        size: [u32; 2],
        race: &race::Race,
    ) -> Result<(), String> {
        let Some(path) = super::smoke::screenshot_path() else {
            return Ok(());
        };
        let format = self.format;
        let texture = render::gpu::texture_2d_with_views(
            &gpu.device,
            "screenshot",
            size,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            &[self.painter.view_format()],
        );
        let view = texture.create_view(&Default::default());
        renderer
            .render(gpu, &view, size, scene)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        self.paint(window, &gpu.device, &gpu.queue, &texture, size, race);
        let img = gpu
            .read_texture(&texture)
            .map_err(|e| format!("{}: {e}", input::show_path(&path)))?;
        super::smoke::write_screenshot(img, format, &path)
    }
}

/// Gives `event` to the panels first: true when they used it (a click on a panel, or the
/// timeline's keys: space plays and pauses, ←/→ step, Home jumps to the start, PgUp/PgDn jump
/// between events, R plays the other way, [ and ] halve and double the speed, F follows the
/// selected boat), so the app must not use it too.
pub fn handle_event(o: &mut Hud, window: &Window, event: &WindowEvent) -> bool {
    use winit::event::ElementState;
    use winit::keyboard::{Key, NamedKey};
    let consumed = o.on_event(window, event);
    match event {
        WindowEvent::CloseRequested
        | WindowEvent::Resized(_)
        | WindowEvent::RedrawRequested
        | WindowEvent::DroppedFile(_) => false,
        WindowEvent::KeyboardInput { event, .. }
            if event.state == ElementState::Pressed && !o.wants_keyboard() =>
        {
            let times: Vec<f64> = o.events.iter().map(|e| e.t).collect();
            let clock = &mut o.panels.clock;
            match event.logical_key {
                Key::Named(NamedKey::Space) => clock.toggle(),
                Key::Named(NamedKey::ArrowRight) => clock.step(1),
                Key::Named(NamedKey::ArrowLeft) => clock.step(-1),
                Key::Named(NamedKey::Home) => clock.jump_to_start(),
                Key::Named(NamedKey::PageDown) => {
                    clock.jump_to_next(&times);
                }
                Key::Named(NamedKey::PageUp) => {
                    clock.jump_to_previous(&times);
                }
                Key::Character(ref c) => match c.as_str() {
                    "r" | "R" => clock.reverse(),
                    "[" => clock.slower(),
                    "]" => clock.faster(),
                    "f" | "F" => {
                        o.panels.follow =
                            !o.panels.follow && !o.scene_overlays.selected().is_empty()
                    }
                    _ => return consumed,
                },
                _ => return consumed,
            }
            true
        }
        WindowEvent::MouseInput { .. }
        | WindowEvent::MouseWheel { .. }
        | WindowEvent::CursorMoved { .. } => {
            // Pointer events over a panel belong to the panel; elsewhere they orbit the camera
            // (cursor moves always reach the app, so a drag that leaves a panel ends cleanly).
            !matches!(event, WindowEvent::CursorMoved { .. }) && (consumed || o.wants_pointer())
        }
        _ => consumed,
    }
}
