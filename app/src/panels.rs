//! The panels' wiring shared by the desktop window and the phone: which effect switches a
//! scene offers, how the Scene panel's named settings reach the renderer, the camera that
//! follows a selected boat, opening race files (one-sentence errors; the race shown before
//! stays), and the phone's race folder.
//!
//! The panels themselves (and their tests) are `crates/ui`; this module only maps their plain
//! names and values onto the renderer's types.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use effects::{Effect, EffectSet, passes::EffectsHandle};
use glam::DVec3;
use ui::{EffectToggle, SceneSettings};

/// What a person sees for each AR effect (`effects::Effect::name`).
fn effect_label(e: Effect) -> &'static str {
    match e {
        Effect::Background => "Camera image",
        Effect::Reflection => "Reflections",
        Effect::Refraction => "Refraction of the table",
        Effect::Caustics => "Caustics",
        Effect::FlowMap => "Current around marks",
    }
}

/// The effect switches of a scene: the AR effects where the effect passes draw (a camera feed
/// or the synthetic table), and the wakes everywhere.
pub fn effect_toggles(with_effect_passes: bool) -> Vec<EffectToggle> {
    let mut v: Vec<EffectToggle> = if with_effect_passes {
        Effect::ALL
            .iter()
            .map(|e| EffectToggle::new(e.name(), effect_label(*e), true))
            .collect()
    } else {
        Vec::new()
    };
    v.push(EffectToggle::new("wakes", "Wakes", true));
    v
}

/// Why the water sliders are greyed out without a table.
pub const NO_TABLE: &str =
    "the sea's water type, depth and turbidity are the table's: open a camera feed (--replay)";

/// Gives the Scene panel the renderer's water ranges and defaults, and greys the water sliders
/// out where no table is shown (`has_table`: a camera feed or the synthetic table).
pub fn set_water_ranges(settings: &mut SceneSettings, has_table: bool) {
    use render::water_look::{MAX_DEPTH_M, MAX_TURBIDITY_NTU, MIN_DEPTH_M, WaterLook, WaterType};
    let look = WaterLook::default();
    settings.water_ranges = ui::settings::WaterRanges {
        depth_m: MIN_DEPTH_M..=MAX_DEPTH_M,
        turbidity_ntu: 0.0..=MAX_TURBIDITY_NTU,
        water_types: WaterType::ALL.map(|t| t.name().to_string()).to_vec(),
    };
    settings.water_type = look.water_type.name().to_string();
    settings.water_depth_m = look.depth_m;
    settings.turbidity = look.turbidity_ntu;
    settings.unavailable = if has_table {
        Vec::new()
    } else {
        ["type", "depth", "turbidity"]
            .map(|k| (k.to_string(), NO_TABLE.to_string()))
            .to_vec()
    };
}

/// The water the Scene panel asks for.
pub fn water_look(settings: &SceneSettings) -> render::water_look::WaterLook {
    render::water_look::WaterLook {
        water_type: render::water_look::WaterType::from_name(&settings.water_type)
            .unwrap_or_default(),
        depth_m: settings.water_depth_m,
        turbidity_ntu: settings.turbidity,
    }
}

/// The AR effects switched on in `settings`.
pub fn effect_set(settings: &SceneSettings) -> EffectSet {
    Effect::ALL
        .into_iter()
        .filter(|e| settings.effect(e.name()))
        .fold(EffectSet::NONE, EffectSet::with)
}

/// Turns the AR effect switches to `effects` (a quality tier's), the others (wakes) as they
/// were.
pub fn set_effect_switches(settings: &mut SceneSettings, effects: EffectSet) {
    for t in &mut settings.effects {
        if let Some(e) = Effect::from_name(&t.key) {
            t.enabled = effects.contains(e);
        }
    }
}

/// Applies the Scene panel's switches and the quality tier to the race renderer: the one way
/// the desktop window and the phone core change them. The switches every frame (cheap when
/// nothing changed; a switch the panel does not offer, as the phone's effect switches, acts on
/// nothing): the AR effects through the effect passes' handle, the wakes by taking the race's
/// wake out of the renderer and putting it back. The tier when it or the renderer's effect
/// passes changed ([`SceneApplier::follow_tier`]).
pub struct SceneApplier {
    /// The race's wakes, kept while the "Wakes" switch is off.
    pub wake: Option<Arc<ocean::wake::Wake>>,
    wakes_shown: bool,
    /// The tier last applied, and whether the renderer had its effect passes then.
    tier: Option<(quality::Tier, bool)>,
}

/// Whether the panel offers the switch `key`.
fn offers(settings: &SceneSettings, key: &str) -> bool {
    settings.effects.iter().any(|t| t.key == key)
}

impl SceneApplier {
    pub fn new(wake: Option<Arc<ocean::wake::Wake>>) -> Self {
        Self {
            wake,
            wakes_shown: true,
            tier: None,
        }
    }

    /// The wakes the renderer should have now (for a renderer built afresh).
    pub fn current_wake(&self) -> Option<Arc<ocean::wake::Wake>> {
        if self.wakes_shown {
            self.wake.clone()
        } else {
            None
        }
    }

    /// A new race's wakes (shown or not as the switch says).
    pub fn set_race_wake(
        &mut self,
        wake: Option<Arc<ocean::wake::Wake>>,
        renderer: &mut render::Renderer,
    ) {
        self.wake = wake;
        renderer.set_wake(self.current_wake());
        // The tier applies again at the next frame: the new race's wakes at its spacing.
        self.tier = None;
    }

    /// `tier` onto the running renderer when it, or whether the renderer has its effect
    /// passes (`effects`), changed since it was last applied ([`SceneApplier::apply_tier`]);
    /// what the tier set when it was applied (the caller hands its overlay detail to the race
    /// overlays). A failure (the respaced wakes) is logged and the tier counts as applied: the
    /// next change tries again.
    #[allow(clippy::too_many_arguments)]
    pub fn follow_tier(
        &mut self,
        tier: quality::Tier,
        settings: &mut SceneSettings,
        gpu: &render::Gpu,
        renderer: &mut render::Renderer,
        effects: Option<&EffectsHandle>,
        race: &race::Race,
    ) -> Option<crate::tier_render::TierRender> {
        let key = Some((tier, effects.is_some()));
        if self.tier == key {
            return None;
        }
        let t = crate::tier_render::TierRender::of(tier);
        if let Err(e) = self.apply_tier(settings, &t, gpu, renderer, effects, race) {
            log::warn!("regatta: quality tier {tier}: {e}");
        }
        self.tier = key;
        Some(t)
    }

    /// The tier last applied by [`SceneApplier::follow_tier`] (`None` before the first).
    pub fn tier_applied(&self) -> Option<quality::Tier> {
        self.tier.map(|(t, _)| t)
    }

    /// A quality tier on the running renderer (docs/quality.md), the same on the desktop and
    /// the phone: the AR effect switches of `settings` turned to the tier's effects (applied as
    /// a click would, and the user may still turn one off after), the race's wakes emitted
    /// again at the tier's spacing (kept behind the Wakes switch), the rest through
    /// `TierRender::apply_live`.
    pub fn apply_tier(
        &mut self,
        settings: &mut SceneSettings,
        tier: &crate::tier_render::TierRender,
        gpu: &render::Gpu,
        renderer: &mut render::Renderer,
        effects: Option<&EffectsHandle>,
        race: &race::Race,
    ) -> crate::error::AppResult {
        set_effect_switches(settings, tier.ar.effects);
        if let Some(w) = tier.respaced_wake(race, self.wake.as_deref())? {
            self.set_race_wake(Some(w), renderer);
        }
        tier.apply_live(gpu, renderer, effects);
        self.apply(settings, renderer, effects);
        Ok(())
    }

    pub fn apply(
        &mut self,
        settings: &SceneSettings,
        renderer: &mut render::Renderer,
        effects: Option<&EffectsHandle>,
    ) {
        let wakes = !offers(settings, "wakes") || settings.effect("wakes");
        if wakes != self.wakes_shown {
            self.wakes_shown = wakes;
            renderer.set_wake(self.current_wake());
        }
        let offers_effects = Effect::ALL.iter().any(|e| offers(settings, e.name()));
        if let Some(h) = effects
            && offers_effects
        {
            h.set_effects(effect_set(settings));
        }
    }
}

/// Where the orbit camera looks when it follows the first selected boat at race time `t`
/// (race metres, on the water); `None` without a selection.
pub fn follow_target(race: &race::Race, selection: &[usize], t: f64) -> Option<DVec3> {
    let b = race.boats.get(*selection.first()?)?;
    let p = b.state_at(t).position;
    Some(DVec3::new(p[0], 0.0, p[1]))
}

/// Loads `paths` as one race. The error is the importer's one sentence (file and line named,
/// control characters escaped), for the panel; the caller keeps the race it showed.
pub fn load_race_files(paths: &[PathBuf]) -> Result<race::Race, String> {
    if paths.is_empty() {
        return Err("no files were given".to_string());
    }
    let race = race::Race::load(paths).map_err(|e| input::one_line(&e.to_string()))?;
    if race.boats.is_empty() {
        return Err(format!(
            "{}: no boat tracks in it (only marks or a course?); add the boats' files",
            paths
                .iter()
                .map(|p| input::show_path(p))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    for w in &race.report.warnings {
        log::warn!("{}", input::escape_controls(w));
    }
    Ok(race)
}

/// For screenshots and the smoke test: `REGATTA_PANELS=boats,events,scene,races` opens those
/// panels at start, `REGATTA_SELECT=EOS,GAL` selects those boats (by id; unknown ids are
/// ignored, with a warning).
pub fn panels_from_env(panels: &mut ui::RegattaUi, selection: &mut Vec<usize>, race: &race::Race) {
    if let Ok(list) = std::env::var("REGATTA_PANELS") {
        for name in list.split(',').map(str::trim) {
            match name {
                "boats" => panels.show_boats = true,
                "events" => panels.show_events = true,
                "scene" => panels.show_scene = true,
                "races" => panels.show_races = true,
                "" => {}
                other => log::warn!("REGATTA_PANELS: no panel {}", input::quote(other)),
            }
        }
    }
    if let Ok(list) = std::env::var("REGATTA_SELECT") {
        for id in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            match race.boat_index(id) {
                Some(b) => ui::toggle_selection(selection, b),
                None => log::warn!("REGATTA_SELECT: no boat {}", input::quote(id)),
            }
        }
    }
}

/// The phone's race folder inside the app's external files folder
/// (`/sdcard/Android/data/org.regatta.app/files/races`, where `adb push` can write without
/// root; docs/panels.md).
pub fn phone_race_folder(external_files: &Path) -> PathBuf {
    external_files.join("races")
}

/// The desktop's file dialog for race files (rfd through the XDG desktop portal on Linux);
/// `None` when cancelled or when no portal answers.
#[cfg(not(target_os = "android"))]
pub fn pick_race_files() -> Option<Vec<PathBuf>> {
    rfd::FileDialog::new()
        .set_title("Open race files (tracks, marks, course)")
        .add_filter("Race files", &ui::open::RACE_EXTENSIONS)
        .pick_files()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The effect set follows the switches by name, whatever their order.
    #[test]
    fn the_effect_set_follows_the_switches() {
        let mut s = SceneSettings::new(effect_toggles(true));
        assert_eq!(effect_set(&s), EffectSet::ALL);
        for t in &mut s.effects {
            t.enabled = matches!(t.key.as_str(), "caustics" | "wakes");
        }
        assert_eq!(effect_set(&s), EffectSet::only(Effect::Caustics));
        assert!(effect_toggles(false).iter().all(|t| t.key == "wakes"));
        // A tier's effects turn the AR switches; the wakes' switch stays.
        let low = EffectSet::only(Effect::Background).with(Effect::Reflection);
        set_effect_switches(&mut s, low);
        assert_eq!(effect_set(&s), low);
        assert!(s.effect("wakes"));
    }

    /// A bad file is one sentence naming it, and nothing else is loaded.
    #[test]
    fn a_bad_race_file_is_one_sentence() {
        let dir = std::env::temp_dir().join(format!("regatta-panels-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("bad.gpx");
        std::fs::write(&bad, "<gpx><trk><trkseg><trkpt lat=\"95\" lon=\"0\">\n").unwrap();
        let e = load_race_files(std::slice::from_ref(&bad)).unwrap_err();
        assert!(e.contains("bad.gpx"), "{e}");
        assert!(!e.contains('\n'), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Following puts the camera's target on the selected boat.
    #[test]
    fn following_targets_the_selected_boat() {
        let race = race::Race::sample();
        let t = 600.0;
        let p = race.boats[3].state_at(t).position;
        assert_eq!(
            follow_target(&race, &[3, 5], t),
            Some(DVec3::new(p[0], 0.0, p[1]))
        );
        assert_eq!(follow_target(&race, &[], t), None);
    }
}
