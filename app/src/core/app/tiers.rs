//! The quality governor of both profiles (docs/quality.md; the phone starts at
//! [`PHONE_START_TIER`], the desktop at ultra or its `--tier`): each drawn frame feeds the phone's
//! [`TierControl`] its GPU time where the renderer measured one, else the present interval on
//! the phone's own clock (the time its events carry, so a `phone-sim` session replays to the
//! same decisions); nothing changes while a finger is down (scrubbing the timeline, turning the
//! view). The tier drawn is applied to the race renderer live, every setting, as the window
//! applies it (`crate::panels::SceneApplier::follow_tier`), and again when the renderer or its
//! effect passes are built anew or a new race opens. The Scene panel's tier control shows the tier; a pin or target set there is answered
//! here. The tier also bounds the camera image ARCore delivers, from the next resume on
//! ([`App::camera_budget`]).

use ar::arcore::ffi::CameraBudget;
use quality::Tier;

use super::App;
use crate::tier_control::TierControl;

/// The tier the phone starts at before any frame is measured: the Pixel 2 XL's goal (every
/// effect at ¾ size); a slower phone steps down within its first second or two.
pub const PHONE_START_TIER: Tier = Tier::High;

/// The phone's governor, auto, at [`PHONE_START_TIER`].
pub(super) fn phone_tiers() -> TierControl {
    TierControl::new(PHONE_START_TIER, false)
}

impl App {
    /// After a drawn frame: the panel's pin or target, the frame to the governor, the tier
    /// applied, and the panel told the tier drawn.
    pub(super) fn govern(&mut self) {
        if let Some(panel) = self.panels.settings.tier {
            let now = self.tiers.panel();
            if panel.pinned != now.pinned {
                self.tiers.answer(ui::TierChange::Pin(panel.pinned));
            }
            if panel.target != now.target {
                self.tiers.answer(ui::TierChange::Target(panel.target));
            }
        }
        let scrubbing = self.touch.owner().is_some();
        let gpu_ms = self.graphics.as_ref().and_then(|g| g.gpu_ms);
        if let Some(t) = self.tiers.frame(self.now, gpu_ms, scrubbing) {
            log::info!("regatta: quality tier {}", t.tier);
        }
        self.apply_tier();
        self.panels.settings.tier = Some(self.tiers.panel());
        self.follow_water();
    }

    /// The Scene panel's sea onto the table's effects when it changed: its type and turbidity,
    /// and its depth as the optical depth over the placed table (the table stays where it was
    /// placed, `table::table_depth()` down, as `regatta render --effects` keeps its table).
    fn follow_water(&mut self) {
        let Some(g) = self.graphics.as_mut() else {
            return;
        };
        let look = crate::panels::water_look(&self.panels.settings);
        // The open (orbit) sea's body colour follows the water type too.
        if look.check().is_ok() {
            g.race.set_water_look(look);
        }
        // The desktop's feed refits its table to the new depth at its next frame.
        if let Some(feed) = self.desktop.as_mut().and_then(|d| d.feed.as_mut()) {
            if feed.water() != look {
                feed.set_water(look);
            }
            return;
        }
        let Some(fx) = g.race_effects.as_ref() else {
            return;
        };
        if g.water != Some(look) && look.check().is_ok() {
            fx.set_water(look, crate::core::table::table_depth());
            g.water = Some(look);
        }
    }

    /// The governor's tier onto the race renderer, when it or the renderer's effect passes
    /// changed since it was last applied.
    fn apply_tier(&mut self) {
        if let Some(mut g) = self.graphics.take() {
            self.apply_tier_to(&mut g);
            self.graphics = Some(g);
        }
    }

    /// [`App::apply_tier`] onto `g` (the frame's graphics, taken out of the app while it draws):
    /// the one tier path of both profiles, with the effect passes' handle of the profile.
    pub(super) fn apply_tier_to(&mut self, g: &mut super::Graphics) {
        let tier = self.tiers.tier();
        let fx = self.effects_handle(g).cloned();
        let settings = &mut self.panels.settings;
        let race = &self.world.race;
        if let Some(t) = g
            .scene
            .follow_tier(tier, settings, &g.gpu, &mut g.race, fx.as_ref(), race)
        {
            self.overlays.set_detail(t.overlay);
        }
    }

    /// What the camera image may cost at the governor's tier: the tier's
    /// `camera_image_max_px`, and the window's size for the shape tie-break (when there is a
    /// window).
    pub(super) fn camera_budget(&self) -> CameraBudget {
        let screen = self.graphics.as_ref().map(|g| g.window.size());
        CameraBudget {
            max_image_px: self.tiers.tier().settings().camera_image_max_px,
            screen: screen.filter(|s| s[0] > 1 && s[1] > 1),
        }
    }

    /// The race renderer (`None` before the first window): what a tier set on it.
    pub fn race_renderer(&self) -> Option<&render::Renderer> {
        self.graphics.as_ref().map(|g| &g.race)
    }

    /// The tier the race renderer draws at (`None` before the first frame).
    pub fn tier_drawn(&self) -> Option<Tier> {
        self.graphics.as_ref().and_then(|g| g.scene.tier_applied())
    }
}
