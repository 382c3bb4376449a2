//! The quality tiers: named, documented sets of renderer settings.

use std::fmt;

/// How many of the race overlays a tier draws (of those the user chose); the app's overlay
/// table says which overlay needs which detail (docs/overlays.md, "Tiers").
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum OverlayDetail {
    /// Boat labels and the course.
    Essential,
    /// Adds the trails (with their manoeuvre marks) and the wind.
    Standard,
    /// Every overlay: adds the ahead/behind lines.
    Full,
}

/// A quality tier, cheapest first. Each is one row of [`TierSettings`]; the app maps the row
/// onto its renderer options (`RenderOptions`, `ArConfig`, the wake parameters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Tier {
    /// A PowerVR GE8320 class phone (OPPO A54) at 30 fps: half-size frame, coarse mesh,
    /// background, reflection and refraction only, the reflection at ⅙ of the screen per side.
    Low,
    /// Adds the cheap overhead-sun caustics (the Sailing+ AR water thesis's, TU Delft 2022: docs/sources.md) and a finer mesh.
    Medium,
    /// Every effect, the area-ratio caustic map at its default grid, ¾-size frame (the Pixel 2
    /// XL at 60 fps is the goal here).
    High,
    /// Every effect at full size, the finest mesh and wakes.
    Ultra,
}

/// What one tier sets. Units in the field docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TierSettings {
    /// Fraction of the target's size per side the scene is drawn at (`RenderOptions::render_scale`).
    pub render_scale: f64,
    /// Clip-map screen-space error target, pixels of the drawn frame (`RenderOptions::error_px`).
    pub error_px: f64,
    /// AR effects that run, by their command-line names (`--effects`).
    pub effects: &'static [&'static str],
    /// Reflection texture size as a fraction of the screen per side (`ArConfig::reflection_fraction`).
    pub reflection_fraction: f64,
    /// Caustics by the AR water thesis's overhead-sun formula (GPU Gems ch. 2) instead of the area-ratio map.
    pub cheap_caustics: bool,
    /// Surface grid and output cells per side of the area-ratio caustic map
    /// (`ArConfig::caustic_resolution`).
    pub caustic_resolution: (usize, usize),
    /// Wake source spacing as a multiple of the hull radius (the wake model's default is 0.5:
    /// larger spacing emits fewer sources at a stated error, see docs/wakes.md).
    pub wake_spacing_radii: f64,
    /// Most wake sources drawn per frame (the least visible beyond it are dropped, with a bound).
    pub wake_source_budget: u32,
    /// How much of the race overlay is drawn.
    pub overlay: OverlayDetail,
    /// The largest camera CPU image, pixels, the session asks ARCore for: its upload and
    /// YUV → RGB conversion cost at most [`CAMERA_IMAGE_SHARE`] of the frame of the phone the
    /// tier is made for (the OPPO A54 at 30 fps for `low` and `medium`, the Pixel 2 XL at
    /// 60 fps for `high` and `ultra`) on the budget model, rounded down to 1,000 pixels
    /// (docs/quality.md, "The camera image"; checked against the model by the bench's
    /// `budget_camera` tests).
    pub camera_image_max_px: u64,
}

/// The share of a frame the camera image's upload and conversion may take. 5 %: the governor
/// steps a tier down only when its median frame exceeds 1.05 × the budget, so a tier that fits
/// its frame before the camera image cannot be pushed past that threshold by the image alone.
pub const CAMERA_IMAGE_SHARE: f64 = 0.05;

impl Tier {
    /// Every tier, cheapest first.
    pub const ALL: [Tier; 4] = [Tier::Low, Tier::Medium, Tier::High, Tier::Ultra];

    /// The name used in the panel, on the command line and in `budget.json`.
    pub fn name(self) -> &'static str {
        match self {
            Tier::Low => "low",
            Tier::Medium => "medium",
            Tier::High => "high",
            Tier::Ultra => "ultra",
        }
    }

    /// The tier named `name` (as [`Tier::name`] writes it).
    pub fn from_name(name: &str) -> Option<Tier> {
        Tier::ALL.into_iter().find(|t| t.name() == name)
    }

    /// Position in [`Tier::ALL`] (0 = cheapest).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The next cheaper tier, if any.
    pub fn cheaper(self) -> Option<Tier> {
        self.index().checked_sub(1).map(|i| Tier::ALL[i])
    }

    /// The next richer tier, if any.
    pub fn richer(self) -> Option<Tier> {
        Tier::ALL.get(self.index() + 1).copied()
    }

    /// This tier's settings.
    pub fn settings(self) -> TierSettings {
        const LOW_FX: &[&str] = &["background", "reflection", "refraction"];
        const ALL_FX: &[&str] = &[
            "background",
            "reflection",
            "refraction",
            "caustics",
            "flowmap",
        ];
        match self {
            Tier::Low => TierSettings {
                render_scale: 0.5,
                error_px: 2.0,
                effects: LOW_FX,
                reflection_fraction: 1.0 / 6.0,
                cheap_caustics: true,
                caustic_resolution: (32, 32),
                wake_spacing_radii: 1.0,
                wake_source_budget: 512,
                camera_image_max_px: 925_000,
                overlay: OverlayDetail::Essential,
            },
            Tier::Medium => TierSettings {
                render_scale: 0.5,
                error_px: 1.5,
                effects: &["background", "reflection", "refraction", "caustics"],
                reflection_fraction: 0.25,
                cheap_caustics: true,
                caustic_resolution: (32, 48),
                wake_spacing_radii: 0.75,
                wake_source_budget: 1_024,
                camera_image_max_px: 925_000,
                overlay: OverlayDetail::Standard,
            },
            Tier::High => TierSettings {
                render_scale: 0.75,
                error_px: 1.0,
                effects: ALL_FX,
                reflection_fraction: 0.25,
                cheap_caustics: false,
                caustic_resolution: (48, 64),
                wake_spacing_radii: 0.5,
                wake_source_budget: 4_096,
                camera_image_max_px: 3_333_000,
                overlay: OverlayDetail::Full,
            },
            Tier::Ultra => TierSettings {
                render_scale: 1.0,
                // The mesh's error on the screen as `high`'s (1 px at ¾ scale): the finer
                // mesh of 1 px cost the A54 a quarter more wake work for a third of a pixel.
                error_px: 4.0 / 3.0,
                effects: ALL_FX,
                reflection_fraction: 0.5,
                cheap_caustics: false,
                caustic_resolution: (48, 64),
                wake_spacing_radii: 0.5,
                wake_source_budget: 65_536,
                camera_image_max_px: 3_333_000,
                overlay: OverlayDetail::Full,
            },
        }
    }

    /// This tier's frame cost relative to `ultra`, before anything is measured: the fraction
    /// of ultra's shaded pixels (render scale squared) weighted by the effects' share of a
    /// frame. A first guess only: the governor replaces it by the ratios it measures.
    pub fn prior_cost(self) -> f64 {
        match self {
            Tier::Low => 0.22,
            Tier::Medium => 0.30,
            Tier::High => 0.60,
            Tier::Ultra => 1.0,
        }
    }
}

impl fmt::Display for Tier {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiers_grow_in_every_setting_from_low_to_ultra() {
        for pair in Tier::ALL.windows(2) {
            let (a, b) = (pair[0].settings(), pair[1].settings());
            assert!(
                a.render_scale <= b.render_scale,
                "{} → {}",
                pair[0],
                pair[1]
            );
            // The mesh's error in screen pixels (the drawn frame's over the render scale).
            assert!(a.error_px / a.render_scale >= b.error_px / b.render_scale - 1e-12);
            assert!(a.effects.len() <= b.effects.len());
            assert!(a.effects.iter().all(|e| b.effects.contains(e)));
            assert!(a.reflection_fraction <= b.reflection_fraction);
            assert!(a.wake_spacing_radii >= b.wake_spacing_radii);
            assert!(a.wake_source_budget < b.wake_source_budget);
            assert!(a.overlay <= b.overlay);
            assert!(a.camera_image_max_px <= b.camera_image_max_px);
            assert!(pair[0].prior_cost() < pair[1].prior_cost());
        }
    }

    #[test]
    fn the_low_tier_runs_the_effects_of_the_phone_goal() {
        // The OPPO A54 goal: background, reflection and refraction at 30 fps.
        let low = Tier::Low.settings();
        for e in ["background", "reflection", "refraction"] {
            assert!(low.effects.contains(&e));
        }
        // The Pixel 2 XL goal: every effect at render scale ≥ ¾.
        let high = Tier::High.settings();
        assert_eq!(high.effects.len(), 5);
        assert!(high.render_scale >= 0.75);
    }

    #[test]
    fn names_round_trip() {
        for t in Tier::ALL {
            assert_eq!(Tier::from_name(t.name()), Some(t));
        }
        assert_eq!(Tier::from_name("max"), None);
        assert_eq!(Tier::Low.cheaper(), None);
        assert_eq!(Tier::Ultra.richer(), None);
        assert_eq!(Tier::Medium.richer(), Some(Tier::High));
    }
}
