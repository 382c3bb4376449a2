//! Effect toggles: a named switch per renderer effect. The app owns the list (ui does not know
//! the renderer's types) and reads it back each frame.

use egui::Ui;

/// One switchable effect.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EffectToggle {
    /// The renderer's name for it (e.g. `"reflection"`), for the app to map back.
    pub key: String,
    /// What a person sees, e.g. "Reflections".
    pub label: String,
    pub enabled: bool,
}

impl EffectToggle {
    pub fn new(key: &str, label: &str, enabled: bool) -> Self {
        Self {
            key: key.to_string(),
            label: label.to_string(),
            enabled,
        }
    }
}

/// One checkbox per effect; returns true when any changed.
pub fn effects_ui(ui: &mut Ui, toggles: &mut [EffectToggle]) -> bool {
    let mut changed = false;
    for t in toggles.iter_mut() {
        changed |= ui.checkbox(&mut t.enabled, t.label.as_str()).changed();
    }
    changed
}

/// The keys of the enabled effects, comma-separated (the `--effects LIST` form).
pub fn enabled_list(toggles: &[EffectToggle]) -> String {
    toggles
        .iter()
        .filter(|t| t.enabled)
        .map(|t| t.key.as_str())
        .collect::<Vec<_>>()
        .join(",")
}
