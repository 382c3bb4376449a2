//! The egui layer over the app's frame: the race panels (both profiles; the desktop's with the
//! performance panel and the Races panel's file dialog), the phone's bar and banner, the
//! desktop's "Share clip" button; then what they asked for (a boat selected, a race to open,
//! a recording, a clip, the scene switched).

use super::App;
use super::draw::Graphics;
use crate::hud::{SceneChoice, phone_bar, race_panels};

impl App {
    /// The panels (race only), the phone's bar and banner or the desktop's clip button, over
    /// the frame in `texture` (`size` pixels). The desktop's pool has none.
    pub(super) fn draw_hud(&mut self, g: &mut Graphics, texture: &wgpu::Texture, size: [u32; 2]) {
        let desktop = self.desktop.is_some();
        if desktop && self.scene == SceneChoice::Pool {
            return;
        }
        let message = self.banner();
        let banner_button = crate::hud::banner::button(self.ar.session);
        let raw = self.take_panel_input(size);
        let recording = self.ar.recorder.is_some();
        // "Share clip" in the race scene; off while a clip is drawn.
        let share = (self.scene == SceneChoice::Race).then(|| !self.clip.busy());
        let mut share_pressed = false;
        let mut choice = self.scene;
        let mut record = false;
        let mut free = self.ui_free;
        let (panels, world, events) = (&mut self.panels, &self.world, &self.events);
        let overlays = &mut self.overlays;
        let races = self.races.panel(&world.race.name);
        let perf = self.desktop.as_ref().map(|d| &d.perf);
        let desktop_clip = self.desktop.as_ref().map(|_| &self.clip);
        let mut response = None;
        let mut scene_rect = None;
        let mut bar = None;
        let pass = g
            .egui
            .paint(&g.gpu.device, &g.gpu.queue, texture, size, raw, |ui| {
                if choice == SceneChoice::Race {
                    overlays.paint(ui.ctx(), size);
                    let r = race_panels(
                        ui,
                        panels,
                        &world.race,
                        events,
                        perf,
                        &world.race.name,
                        &overlays.settings.selected,
                        races,
                    );
                    scene_rect = r.scene_rect;
                    response = Some(r);
                }
                if let Some(clip) = desktop_clip {
                    // Bottom right, above the timeline's panel (about 92 points tall in a
                    // 1280x720 window; a window narrow enough to wrap the panel's rows makes it
                    // taller).
                    egui::Area::new(egui::Id::unique("share-clip"))
                        .anchor(egui::Align2::RIGHT_BOTTOM, egui::vec2(-8.0, -100.0))
                        .show(ui.ctx(), |ui| {
                            egui::Frame::popup(ui.style())
                                .show(ui, |ui| share_pressed |= clip.ui(ui));
                        });
                } else {
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
                }
                // The scene's part of the screen: what the panels left, else what the bar left.
                free = scene_rect.unwrap_or_else(|| ui.available_rect_before_wrap());
            });
        if !pass.painted {
            // A lost device whose callback has not run: the next frame rebuilds.
            g.lost.raise();
        }
        self.ui_free = free;
        self.bar = bar;
        // The phone has no cursor or clipboard to update.
        if let Some(d) = self.desktop.as_mut() {
            d.platform_output = Some(pass.platform);
        }
        if bar.is_some_and(|b| b.banner_pressed) {
            // After a refusal: ask for the camera again (Android shows its dialog, or answers
            // at once when the user chose "don't ask again"; the banner then still points to
            // Settings).
            self.session_event(ar::arcore::Event::AskPermissionAgain);
        }
        let mut open = None;
        if let Some(r) = response {
            if let Some(b) = r.clicked_boat {
                ui::toggle_selection(&mut self.overlays.settings.selected, b);
            }
            if r.clear_selection {
                self.overlays.settings.selected.clear();
            }
            open = r.open;
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
