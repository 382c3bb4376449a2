//! The HUD: the egui layer both apps draw over the scene (not the race overlays, which are
//! drawn in the scene: `scene_overlay`): the race panels of `crates/ui` (timeline
//! scrubber, leaderboard, performance), painted with egui-wgpu after the scene into the same
//! surface texture ([`EguiPainter`]). The desktop feeds egui from winit (egui-winit); the phone
//! from its touch events ([`touch`]), with the AR session's messages on a banner ([`banner`]).

pub mod banner;
pub mod touch;

use render::FrameReport;

use render::gpu::WriteProbe;
use ui::{FpsMeter, PassStat, PerfStats, RaceClock, RegattaUi, TimelineEvent, UiFrame, UiResponse};

/// The race clock the app starts with: paused at the start signal would show an empty sea, so
/// it plays at 8× from the span's start (or from the start signal when the data begin earlier).
pub fn initial_clock(race: &race::Race) -> RaceClock {
    let mut clock = RaceClock::new(race.time_span());
    clock.looping = true;
    clock.jump_to_start();
    clock.set_speed(8.0);
    clock.play();
    clock
}

/// The panels for a newly shown race, on the desktop and the phone alike: a fresh clock, no
/// plots, no following, the race's timeline events and no boat selected (the panels that were
/// open stay open, the switches as they were).
pub fn panels_for_new_race(
    race: &race::Race,
    panels: &mut RegattaUi,
    events: &mut Vec<TimelineEvent>,
    selected: &mut Vec<usize>,
) {
    panels.clock = initial_clock(race);
    panels.plots.clear();
    panels.follow = false;
    *events = ui::timeline_events(race);
    selected.clear();
}

/// The performance panel's numbers from the renderer's frame record and the app's frame meter.
pub fn perf_stats(report: &FrameReport, fps: &FpsMeter) -> PerfStats {
    PerfStats {
        fps: fps.fps(),
        frame_ms: fps.frame_ms(),
        triangles: report.triangles,
        adapter: report.adapter.clone(),
        passes: report
            .passes
            .iter()
            .map(|p| PassStat {
                name: p.name.clone(),
                ran: p.ran,
                reason: p.reason.clone(),
                triangles: p.triangles,
                gpu_ms: p.total_gpu_ms(),
            })
            .collect(),
    }
}

/// Lays out the race panels (`crates/ui`'s [`RegattaUi`]) at the panels' race time, with the
/// app's boat `selection` and, where the platform opens races, the Races panel.
#[allow(clippy::too_many_arguments)]
pub fn race_panels(
    ui: &mut egui::Ui,
    panels: &mut RegattaUi,
    race: &race::Race,
    events: &[TimelineEvent],
    perf: Option<&PerfStats>,
    title: &str,
    selection: &[usize],
    races: Option<ui::RacesPanel<'_>>,
) -> UiResponse {
    let rows = ui::leaderboard_rows(race, panels.clock.time());
    panels.show(
        ui,
        &UiFrame {
            rows: &rows,
            events,
            perf,
            title,
            race: Some(race),
            selection,
            races,
        },
    )
}

/// An egui context and the egui-wgpu renderer that paints its output over a surface texture.
///
/// egui blends in gamma space, so where the surface allows views of another format
/// (`DownlevelFlags::SURFACE_VIEW_FORMATS`; Vulkan's `VK_KHR_swapchain_mutable_format`) it paints
/// through a `*Unorm` view of the `*UnormSrgb` surface texture; elsewhere (some phones) it paints
/// into the sRGB texture itself and translucent panels come out a little lighter.
pub struct EguiPainter {
    pub ctx: egui::Context,
    renderer: egui_wgpu::Renderer,
    /// The format egui's views of the surface texture have.
    view_format: wgpu::TextureFormat,
    /// Asks the device before egui's upload (egui-wgpu panics on a lost device's refusal).
    probe: WriteProbe,
}

/// One egui pass: what egui asks of the platform, and whether it was painted (not on a
/// lost device: the widgets ran, the picture was left as it was).
pub struct EguiPass {
    pub platform: egui::PlatformOutput,
    pub painted: bool,
}

impl EguiPainter {
    /// A painter for `surface`; adds the non-sRGB view format to its configuration (and
    /// reconfigures it) when `view_formats_allowed`.
    pub fn new(
        device: &wgpu::Device,
        surface: &mut render::gpu::SurfaceTarget,
        view_formats_allowed: bool,
    ) -> Self {
        let format = surface.config.format;
        let mut view_format = format;
        if view_formats_allowed && format.remove_srgb_suffix() != format {
            view_format = format.remove_srgb_suffix();
            if !surface.config.view_formats.contains(&view_format) {
                surface.config.view_formats.push(view_format);
                surface.surface.configure(device, &surface.config);
            }
        }
        Self::for_format(device, view_format)
    }

    /// A painter that paints into textures viewed as `view_format`.
    pub fn for_format(device: &wgpu::Device, view_format: wgpu::TextureFormat) -> Self {
        Self {
            ctx: egui::Context::default(),
            renderer: egui_wgpu::Renderer::new(
                device,
                view_format,
                egui_wgpu::RendererOptions::default(),
            ),
            view_format,
            probe: WriteProbe::new(device),
        }
    }

    /// The format of egui's views (the surface's, or its non-sRGB twin).
    pub fn view_format(&self) -> wgpu::TextureFormat {
        self.view_format
    }

    /// Runs one egui pass over `raw` with `build` laying out the widgets, and paints the
    /// result over `texture` (`size` pixels; its format or [`Self::view_format`] among its view
    /// formats). Returns what egui asks of the platform (cursor, clipboard, …), and whether it
    /// painted: not on a lost device, where egui-wgpu 0.37's `Renderer::update_buffers` panics
    /// ("Failed to create staging buffer", its `Queue::write_buffer_with` refused); the
    /// widgets still ran (a click in this frame counts).
    pub fn paint(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        texture: &wgpu::Texture,
        size: [u32; 2],
        raw: egui::RawInput,
        build: impl FnMut(&mut egui::Ui),
    ) -> EguiPass {
        let view = &texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(self.view_format),
            ..Default::default()
        });
        let out = self.ctx.run_ui(raw, build);
        let jobs = self.ctx.tessellate(out.shapes, out.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: size,
            pixels_per_point: out.pixels_per_point,
        };
        // Every frame's texture changes are applied and freed (and the delta marked handled),
        // or egui's font atlas goes stale.
        let mut delta = out.textures_delta;
        for (id, image_delta) in &delta.set {
            for d in image_delta {
                self.renderer.update_texture(device, queue, *id, d);
            }
        }
        // Asked after the texture uploads (a lost device takes them as no-ops), right before
        // the buffers': nothing between can find a loss (buffer creation reports only
        // running out of memory).
        if !self.probe.device_takes_writes(queue) {
            delta.clear();
            return EguiPass {
                platform: out.platform_output,
                painted: false,
            };
        }
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("egui"),
        });
        let extra = self
            .renderer
            .update_buffers(device, queue, &mut encoder, &jobs, &screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            self.renderer
                .render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        queue.submit(extra.into_iter().chain(std::iter::once(encoder.finish())));
        for id in &delta.free {
            self.renderer.free_texture(id);
        }
        delta.clear();
        EguiPass {
            platform: out.platform_output,
            painted: true,
        }
    }
}

/// Which scene the phone shows on the table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SceneChoice {
    #[default]
    Race,
    Pool,
}

impl SceneChoice {
    /// What a tap on the table places.
    pub fn noun(self) -> &'static str {
        match self {
            SceneChoice::Race => "course",
            SceneChoice::Pool => "pool",
        }
    }
}

/// Points the phone's bar (and a one-line banner) takes at the top of the screen, kept free
/// by the panels' column.
pub const PHONE_BAR_HEIGHT: f32 = 90.0;

/// What the phone's bar did this frame, and where its buttons are (points).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhoneBar {
    /// The record button was pressed (start or stop).
    pub record_toggled: bool,
    pub race_button: egui::Rect,
    pub pool_button: egui::Rect,
    pub record_button: egui::Rect,
    /// The banner's button ([`banner::button`]), where one is shown, and whether it was
    /// pressed.
    pub banner_button: Option<egui::Rect>,
    pub banner_pressed: bool,
    /// The "Share clip" button, where shown, and whether it was pressed.
    pub share_button: Option<egui::Rect>,
    pub share_pressed: bool,
}

/// The phone's bar along the top: the scene toggle (race | pool), the record button, and
/// under them the session's banner ([`banner::banner`]), if any, with its button
/// (`banner_button`: the label). Laid out inside egui's content rect, below the status bar and
/// the cutout. `share`: the "Share clip" button after Record, enabled or not; `None` hides it.
pub fn phone_bar(
    ctx: &egui::Context,
    scene: &mut SceneChoice,
    (recording, share): (bool, Option<bool>),
    banner: Option<&(String, banner::Tone)>,
    banner_button: Option<&str>,
) -> PhoneBar {
    let glass = egui::Frame::window(&ctx.global_style())
        .fill(egui::Color32::from_black_alpha(170))
        .corner_radius(6.0);
    egui::Area::new(egui::Id::unique("phone-bar"))
        .anchor(egui::Align2::CENTER_TOP, [0.0, 10.0])
        .show(ctx, |ui| {
            glass
                .show(ui, |ui| {
                    // Long banners wrap inside the screen rather than run off its edges.
                    ui.set_max_width((ctx.content_rect().width() - 40.0).max(120.0));
                    let big = |s: &str| egui::RichText::new(s).size(18.0);
                    let (race, pool, record, share) = ui
                        .horizontal(|ui| {
                            let race = ui.selectable_value(scene, SceneChoice::Race, big("Race"));
                            let pool = ui.selectable_value(scene, SceneChoice::Pool, big("Pool"));
                            ui.separator();
                            let label = if recording { "⏹ Stop" } else { "⏺ Record" };
                            let record = ui.button(big(label));
                            let share = share.map(|enabled| {
                                ui.add_enabled(enabled, egui::Button::new(big("Share clip")))
                            });
                            (race, pool, record, share)
                        })
                        .inner;
                    if let Some((text, tone)) = banner {
                        let colour = match tone {
                            banner::Tone::Hint => egui::Color32::from_rgb(210, 230, 255),
                            banner::Tone::Warning => egui::Color32::from_rgb(255, 200, 90),
                        };
                        ui.add(
                            egui::Label::new(egui::RichText::new(text).color(colour).size(16.0))
                                .wrap(),
                        );
                    }
                    let button = banner_button.map(|label| ui.button(big(label)));
                    PhoneBar {
                        record_toggled: record.clicked(),
                        race_button: race.rect,
                        pool_button: pool.rect,
                        record_button: record.rect,
                        banner_button: button.as_ref().map(|b| b.rect),
                        banner_pressed: button.is_some_and(|b| b.clicked()),
                        share_button: share.as_ref().map(|b| b.rect),
                        share_pressed: share.is_some_and(|b| b.clicked()),
                    }
                })
                .inner
        })
        .inner
}

#[cfg(test)]
mod tests {
    use super::touch::{Finger, Touch, TouchAction, TouchInput, over_egui};
    use super::*;

    /// A finger tap on "Pool" switches the scene and never reaches the table; a tap on
    /// "Record" reports the toggle; the banner text is laid out under the buttons.
    #[test]
    fn tapping_the_bar_switches_the_scene_and_records() {
        let ctx = egui::Context::default();
        let mut scene = SceneChoice::Race;
        let mut touch = TouchInput::new(3.0);
        let note = (
            "Tap the table to place the course.".to_string(),
            banner::Tone::Hint,
        );
        let frame = |touch: &mut TouchInput, scene: &mut SceneChoice, now: f64| {
            let mut bar = None;
            let mut free = egui::Rect::NOTHING;
            let out = ctx.run_ui(touch.take_raw_input([1080, 2340], now), |ui| {
                bar = Some(phone_bar(ui.ctx(), scene, (false, None), Some(&note), None));
                free = ui.available_rect_before_wrap();
            });
            out.drop_without_applying_deltas();
            (bar.unwrap(), free)
        };
        frame(&mut touch, &mut scene, 0.0);
        let (bar, free) = frame(&mut touch, &mut scene, 0.02);
        let tap = |touch: &mut TouchInput, at: egui::Pos2| {
            let f = [Finger {
                id: 0,
                px: [at.x * 3.0, at.y * 3.0],
            }];
            let over = |p| over_egui(&ctx, free, p);
            let a = touch.on_touch(
                &Touch {
                    action: TouchAction::Down(0),
                    fingers: f.to_vec(),
                },
                over,
            );
            let b = touch.on_touch(
                &Touch {
                    action: TouchAction::Up(0),
                    fingers: f.to_vec(),
                },
                over,
            );
            a || b
        };
        assert!(!tap(&mut touch, bar.pool_button.center()));
        frame(&mut touch, &mut scene, 0.04);
        assert_eq!(scene, SceneChoice::Pool);
        assert!(!tap(&mut touch, bar.record_button.center()));
        let (bar2, _) = frame(&mut touch, &mut scene, 0.06);
        assert!(bar2.record_toggled);
        // Far below the bar the tap belongs to the table.
        assert!(tap(&mut touch, egui::pos2(180.0, 600.0)));
        let (bar3, _) = frame(&mut touch, &mut scene, 0.08);
        assert!(!bar3.record_toggled);
        assert_eq!(scene, SceneChoice::Pool);
    }

    /// The phone's painting path on the GPU (lavapipe in CI): the bar and banner painted over a
    /// grey "scene" of 480×300 pixels at 1.2 pixels per point, through a `Unorm` view of an sRGB
    /// texture (desktop, phones with mutable swapchain formats) and straight into the sRGB
    /// texture (other phones). Away from the bar the scene is untouched; under it the glass
    /// darkens the grey; the selected "Race" button's fill comes out the same both ways.
    #[test]
    fn the_bar_is_painted_over_the_scene_on_the_gpu() {
        let Some(gpu) = render::gpu::test_gpu() else {
            return;
        };
        let size = [480u32, 300];
        let format = wgpu::TextureFormat::Rgba8UnormSrgb;
        let grey = 128u8;
        let mut fills = Vec::new();
        for unorm_view in [true, false] {
            let texture = render::gpu::texture_2d_with_views(
                &gpu.device,
                "scene",
                size,
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST,
                &[format.remove_srgb_suffix()],
            );
            gpu.queue.write_texture(
                texture.as_image_copy(),
                &vec![grey; (size[0] * size[1] * 4) as usize],
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(size[0] * 4),
                    rows_per_image: None,
                },
                texture.size(),
            );
            let view_format = if unorm_view {
                format.remove_srgb_suffix()
            } else {
                format
            };
            let mut painter = EguiPainter::for_format(&gpu.device, view_format);
            let mut touch = TouchInput::new(1.2);
            let mut scene = SceneChoice::Race;
            let note = (
                ar::arcore::Unavailable::PermissionRefused.message(),
                banner::Tone::Warning,
            );
            let mut bar = None;
            // egui sizes its areas in the first pass and fades them in over a few tenths of a
            // second: paint a second's worth of frames.
            for i in 0..10 {
                let raw = touch.take_raw_input(size, 0.1 * f64::from(i));
                painter.paint(&gpu.device, &gpu.queue, &texture, size, raw, |ui| {
                    bar = Some(phone_bar(
                        ui.ctx(),
                        &mut scene,
                        (false, None),
                        Some(&note),
                        None,
                    ));
                });
            }
            let img = gpu.read_texture(&texture).unwrap();
            let bar = bar.unwrap();
            // A pixel between the buttons' row and the edge of the glass, and one far below.
            let inside = bar.race_button.left_top() - egui::vec2(3.0, 3.0);
            let px = |p: egui::Pos2| img.get_pixel((p.x * 1.2) as u32, (p.y * 1.2) as u32).0;
            assert_eq!(px(egui::pos2(30.0, 240.0)), [grey, grey, grey, grey]);
            let g = px(inside);
            assert!(g[0] < grey - 20, "{g:?}");
            let fill = px(bar.race_button.left_center() + egui::vec2(3.0, 0.0));
            assert!(
                fill[2] > fill[0] + 40,
                "the selected button is blue: {fill:?}"
            );
            fills.push(fill);
        }
        let d = (0..3).map(|c| fills[0][c].abs_diff(fills[1][c])).max();
        assert!(d <= Some(2), "{fills:?}");
    }

    /// A device lost before its lost callback ran (destroyed here, not polled: wgpu runs the
    /// callback only from a poll) refuses every write, and egui-wgpu 0.37's buffer upload
    /// panicked on the refusal. The painter runs the widgets (a tap in that frame counts)
    /// and paints nothing.
    #[test]
    fn on_a_device_lost_before_its_callback_the_widgets_run_and_nothing_is_painted() {
        let Some(gpu) = render::gpu::test_gpu() else {
            return;
        };
        let size = [64u32, 48];
        let format = wgpu::TextureFormat::Rgba8UnormSrgb;
        let texture = render::gpu::texture_2d_with_views(
            &gpu.device,
            "scene",
            size,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            &[],
        );
        let mut painter = EguiPainter::for_format(&gpu.device, format);
        let raw = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(64.0, 48.0),
            )),
            ..Default::default()
        };
        let mut ran = 0;
        let pass = painter.paint(&gpu.device, &gpu.queue, &texture, size, raw.clone(), |ui| {
            ran += 1;
            ui.label("Boreas");
        });
        assert!(pass.painted, "not painted on a working device");
        gpu.device.destroy();
        let pass = painter.paint(&gpu.device, &gpu.queue, &texture, size, raw, |ui| {
            ran += 1;
            ui.label("Boreas");
        });
        assert!(!pass.painted, "painted on a lost device");
        assert_eq!(ran, 2, "the widgets did not run on the lost device");
    }
}
