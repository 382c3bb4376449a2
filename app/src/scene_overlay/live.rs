//! The overlays of a window (desktop; the phone's loop can hold one the same way): the user's
//! settings, the overlay passes' layers, this frame's overlay and the labels as last painted,
//! so a click or tap picks what the user saw.

use render::passes::segments::SegmentLayers;

use super::labels::{PlacedLabel, pick};
use super::{OverlayFrame, OverlayKind, OverlaySettings, WindInfo};

#[derive(Default)]
pub struct LiveOverlays {
    pub settings: OverlaySettings,
    layers: SegmentLayers,
    frame: Option<OverlayFrame>,
    placed: Vec<PlacedLabel>,
}

impl LiveOverlays {
    /// Turns the overlay `name` on or off (a name of [`super::OVERLAYS`]).
    pub fn set_overlay(&mut self, name: &str, on: bool) -> Result<(), String> {
        self.settings.set_overlay(name, on)
    }

    /// The Scene panel's overlay switches (by the names of [`super::OVERLAYS`]) onto the
    /// overlays drawn.
    pub fn follow_panel(&mut self, panel: &ui::SceneSettings) {
        for o in &super::OVERLAYS {
            self.settings.set = self.settings.set.with(o.kind, panel.overlay(o.name));
        }
    }

    /// A quality tier's overlay detail (`TierRender::overlay`) onto the overlays drawn.
    pub fn set_detail(&mut self, detail: quality::OverlayDetail) {
        self.settings.detail = detail;
    }

    /// The selected boats (indices into `Race::boats`), oldest first: "compare" takes two.
    pub fn selected(&self) -> &[usize] {
        &self.settings.selected
    }

    /// The wind this frame shows, for the panel.
    pub fn wind(&self) -> Option<WindInfo> {
        self.frame.as_ref().and_then(|f| f.wind)
    }

    /// The debrief the trails' manoeuvre marks read, from the panels' once-per-race cache
    /// (`cache`, which the timeline's tack jumps share): worked out on the first frame that
    /// shows the trails after a race is opened; `None` while the trails are off.
    pub fn debrief<'a>(
        &self,
        cache: &'a mut ui::DebriefView,
        race: &race::Race,
    ) -> Option<&'a race::Debrief> {
        if !self.settings.shows(OverlayKind::Trails) {
            return None;
        }
        cache.update(race);
        cache.debrief()
    }

    /// Before the renderer draws `scene`: makes sure it has the overlay passes and feeds them.
    /// `race` comes with its debrief where the window has it (the panels' `DebriefView`,
    /// once per race): the trails' manoeuvre marks.
    pub fn prepare(
        &mut self,
        gpu: &render::Gpu,
        renderer: &mut render::Renderer,
        (race, debrief): (&race::Race, Option<&race::Debrief>),
        scene: &render::Scene,
        size: [u32; 2],
        pixels_per_point: f64,
    ) {
        super::add_passes(renderer, gpu, &self.layers);
        let f = super::frame(race, scene, size, pixels_per_point, &self.settings, debrief);
        f.push(&self.layers);
        self.frame = Some(f);
    }

    /// Inside the window's egui pass: paints the labels and texts (`size`: the frame, pixels).
    pub fn paint(&mut self, ctx: &egui::Context, size: [u32; 2]) {
        if let Some(f) = &self.frame {
            self.placed = super::paint::paint(ctx, f, size);
        }
    }

    /// A click or tap at framebuffer pixel `p` on the scene: selects the boat there (label or
    /// hull), or clears the selection on the water.
    pub fn click(&mut self, p: [f64; 2]) {
        let boat = self.pick(p);
        self.settings.click(boat);
    }

    /// The boat at framebuffer pixel `p` in the frame last drawn (its label or hull).
    pub fn pick(&self, p: [f64; 2]) -> Option<usize> {
        pick(&self.placed, self.hulls(), p)
    }

    /// The boats on screen in the frame last drawn.
    pub fn hulls(&self) -> &[super::labels::Hull] {
        self.frame.as_ref().map_or(&[][..], |f| &f.hulls[..])
    }

    /// The labels as last painted.
    pub fn placed_labels(&self) -> &[PlacedLabel] {
        &self.placed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_overlay::{OverlayKind, OverlaySet, panel_toggles};

    /// The Scene panel's switches (the desktop's and the phone's) decide the overlays drawn,
    /// and the tier's detail is kept apart from them.
    #[test]
    fn the_panel_switches_and_the_tier_detail_set_the_overlays() {
        let mut live = LiveOverlays::default();
        let mut panel = ui::SceneSettings::new(Vec::new());
        panel.overlays = panel_toggles(OverlaySet::ALL);
        panel
            .overlays
            .iter_mut()
            .filter(|t| t.key == "wind")
            .for_each(|t| t.enabled = false);
        live.follow_panel(&panel);
        assert_eq!(
            live.settings.set,
            OverlaySet::ALL.with(OverlayKind::Wind, false)
        );
        live.set_detail(quality::OverlayDetail::Essential);
        assert_eq!(
            live.settings.shown(),
            [OverlayKind::Course, OverlayKind::Labels]
        );
        live.follow_panel(&panel);
        assert_eq!(live.settings.detail, quality::OverlayDetail::Essential);
    }
}
