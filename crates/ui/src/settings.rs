//! The "Scene" panel: one switch per renderer effect and the quality tier control
//! ([`crate::tier::tier_ui`]), one switch per race overlay (the app gives them, named as
//! `regatta render --overlays` names them: ui keeps no list of its own), and the
//! real sea shown on the table (water type, depth, turbidity). ui knows none of the renderer's types: the panel
//! returns what changed as [`SettingChange`]s named as on the command line, and the app maps
//! each name onto its renderer (and says which it cannot apply, [`SceneSettings::unavailable`]).

use egui::{RichText, Ui};

use crate::effects::{EffectToggle, effects_ui};
use crate::tier::{TierChange, TierPanel, tier_ui};

/// What the water sliders span and start at, in real units (the app gives the renderer's own
/// ranges: ui keeps no copy of them).
#[derive(Clone, Debug, PartialEq)]
pub struct WaterRanges {
    /// Depth of the real sea, metres.
    pub depth_m: std::ops::RangeInclusive<f64>,
    /// Turbidity, NTU.
    pub turbidity_ntu: std::ops::RangeInclusive<f64>,
    /// The water types' names (`--water-type`), in the order offered.
    pub water_types: Vec<String>,
}

impl Default for WaterRanges {
    /// A stand-in for panels drawn without a renderer (tests): 0.5 to 100 m, 0 to 100 NTU,
    /// two types.
    fn default() -> Self {
        Self {
            depth_m: 0.5..=100.0,
            turbidity_ntu: 0.0..=100.0,
            water_types: vec!["pure".to_string(), "IB".to_string()],
        }
    }
}

/// One thing the user changed this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum SettingChange {
    /// An effect (`background`, `reflection`, …, `wakes`) on or off.
    Effect { key: String, enabled: bool },
    /// A race overlay (its `--overlays` name) on or off.
    Overlay { key: String, enabled: bool },
    /// The real sea's water type (`--water-type` name).
    WaterType(String),
    /// Depth of the real sea, metres.
    WaterDepth(f64),
    /// Turbidity, NTU.
    Turbidity(f64),
    /// The quality tier pinned (or auto) or the frame-rate target.
    Tier(TierChange),
}

/// Everything the Scene panel shows.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneSettings {
    pub effects: Vec<EffectToggle>,
    pub overlays: Vec<EffectToggle>,
    /// The real sea's water type (`--water-type` name).
    pub water_type: String,
    /// Depth of the real sea, metres.
    pub water_depth_m: f64,
    /// Turbidity, NTU.
    pub turbidity: f64,
    /// What the water sliders span.
    pub water_ranges: WaterRanges,
    /// Keys the app cannot apply in this build or scene (e.g. an overlay without its pass, or
    /// the water sliders without a table): shown disabled, with why on hover.
    pub unavailable: Vec<(String, String)>,
    /// The quality tier control under the effects (the app sets the tier drawn each frame);
    /// `None`: not shown (no governor).
    pub tier: Option<TierPanel>,
}

impl SceneSettings {
    /// `effects` as the app offers them, no overlay switches (the app sets its own), 5 m of
    /// oceanic IB water (the app sets the renderer's own defaults and ranges).
    pub fn new(effects: Vec<EffectToggle>) -> Self {
        Self {
            effects,
            overlays: Vec::new(),
            water_type: "IB".to_string(),
            water_depth_m: 5.0,
            turbidity: 0.0,
            water_ranges: WaterRanges::default(),
            unavailable: Vec::new(),
            tier: None,
        }
    }

    /// Why `key` cannot be applied, if it cannot.
    pub fn why_unavailable(&self, key: &str) -> Option<&str> {
        self.unavailable
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, why)| why.as_str())
    }

    /// Whether overlay `key` is on.
    pub fn overlay(&self, key: &str) -> bool {
        self.overlays.iter().any(|o| o.key == key && o.enabled)
    }

    /// Whether effect `key` is on.
    pub fn effect(&self, key: &str) -> bool {
        self.effects.iter().any(|o| o.key == key && o.enabled)
    }
}

/// The panel; returns what the user changed this frame, in the order shown.
pub fn scene_settings_ui(ui: &mut Ui, s: &mut SceneSettings) -> Vec<SettingChange> {
    let mut out = Vec::new();
    ui.label(RichText::new("Effects").strong());
    let before = s.effects.clone();
    toggles_ui(ui, &mut s.effects, &s.unavailable);
    for (b, a) in before.iter().zip(&s.effects) {
        if b.enabled != a.enabled {
            out.push(SettingChange::Effect {
                key: a.key.clone(),
                enabled: a.enabled,
            });
        }
    }
    if let Some(panel) = s.tier.as_mut()
        && let Some(change) = tier_ui(ui, panel)
    {
        out.push(SettingChange::Tier(change));
    }
    ui.separator();
    ui.label(RichText::new("Overlays").strong());
    let before = s.overlays.clone();
    toggles_ui(ui, &mut s.overlays, &s.unavailable);
    for (b, a) in before.iter().zip(&s.overlays) {
        if b.enabled != a.enabled {
            out.push(SettingChange::Overlay {
                key: a.key.clone(),
                enabled: a.enabled,
            });
        }
    }
    ui.separator();
    ui.label(RichText::new("Water").strong());
    let type_why = s.why_unavailable("type").map(str::to_string);
    let depth_why = s.why_unavailable("depth").map(str::to_string);
    let before = s.water_type.clone();
    ui.add_enabled_ui(type_why.is_none(), |ui| {
        egui::ComboBox::from_label("Water type")
            .selected_text(s.water_type.as_str())
            .show_ui(ui, |ui| {
                for name in &s.water_ranges.water_types {
                    ui.selectable_value(&mut s.water_type, name.clone(), name.as_str());
                }
            })
    })
    .response
    .on_disabled_hover_text(type_why.unwrap_or_default());
    if s.water_type != before {
        out.push(SettingChange::WaterType(s.water_type.clone()));
    }
    let turbidity_why = s.why_unavailable("turbidity").map(str::to_string);
    let depth = ui
        .add_enabled(
            depth_why.is_none(),
            egui::Slider::new(&mut s.water_depth_m, s.water_ranges.depth_m.clone())
                .logarithmic(true)
                .text("Sea depth")
                .suffix(" m")
                .max_decimals(1),
        )
        .on_disabled_hover_text(depth_why.unwrap_or_default());
    if depth.changed() {
        out.push(SettingChange::WaterDepth(s.water_depth_m));
    }
    let turbidity = ui
        .add_enabled(
            turbidity_why.is_none(),
            egui::Slider::new(&mut s.turbidity, s.water_ranges.turbidity_ntu.clone())
                .logarithmic(true)
                .text("Turbidity")
                .suffix(" NTU")
                .max_decimals(1),
        )
        .on_disabled_hover_text(turbidity_why.unwrap_or_default());
    if turbidity.changed() {
        out.push(SettingChange::Turbidity(s.turbidity));
    }
    out
}

/// Checkboxes, the unavailable ones greyed out with their reason on hover.
fn toggles_ui(ui: &mut Ui, toggles: &mut [EffectToggle], unavailable: &[(String, String)]) {
    for t in toggles.iter_mut() {
        match unavailable.iter().find(|(k, _)| *k == t.key) {
            Some((_, why)) => {
                ui.add_enabled(false, egui::Checkbox::new(&mut t.enabled, t.label.as_str()))
                    .on_disabled_hover_text(why);
            }
            None => {
                effects_ui(ui, std::slice::from_mut(t));
            }
        }
    }
}
