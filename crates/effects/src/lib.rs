//! `effects`: the AR water effects of the Sailing+ AR water thesis (TU Delft 2022; what it says:
//! docs/sources.md), made physical where the thesis names its own limitations: camera
//! background, planar reflection, refraction of the real table, caustics and flow-map
//! distortion, mixed by the full Fresnel equations, not Schlick's approximation
//! ([`render::optics`]). A crate on the render
//! core (`render`): its passes implement [`render::Pass`] and draw with the core's helpers.
//!
//! Invariant: it knows nothing of ARCore (a camera image arrives as a [`backdrop`] value),
//! egui, the command line, races or the pool scene; `render` knows nothing of it.
//!
//! Each effect has a pure, host-tested model here (f64, no GPU): the GPU passes follow these
//! models, and their tests compare against them.
//!
//! - [`refraction`]: the view ray through the wave surface onto the table, into the camera image.
//! - [`caustics`]: the area-ratio caustics of the actual wave surface at race time t, and the
//!   source's cheap overhead-sun tier.
//! - [`flowmap`]: current around a mark and the two-phase flow-map blend with the UV jump.
//! - [`flow_detail`]: the detail field the flow map advects, its baked texture and its bound.
//! - [`planner`]: when each effect pass runs, and why it does not.

pub mod backdrop;
#[cfg(test)]
mod camera_gpu_tests;
pub mod camera_upload;
pub mod caustic_map;
pub mod caustics;
#[cfg(test)]
mod cover_gpu_tests;
#[doc(hidden)]
pub mod fixtures;
pub mod flow_detail;
pub mod flowmap;
#[cfg(test)]
mod gpu_tests;
pub mod passes;
pub mod planner;
pub mod reflection;
pub mod refraction;
#[cfg(test)]
mod room_gpu_tests;
pub mod wgsl;

use std::fmt;

/// The effects' test camera: a 640×480 pinhole at `eye` looking at `target`, focal length
/// `focal` px. Looking straight down, "up" in the image is north.
#[cfg(test)]
fn test_camera(eye: glam::DVec3, target: glam::DVec3, focal: f64) -> render::optics::PinholeCamera {
    use glam::DVec3;
    let up = if (target - eye).normalize().y.abs() > 0.999 {
        DVec3::NEG_Z
    } else {
        DVec3::Y
    };
    render::optics::PinholeCamera {
        fx: focal,
        fy: focal,
        cx: 320.0,
        cy: 240.0,
        width: 640.0,
        height: 480.0,
        pose: glam::dcamera::rh::view::look_at_mat4(eye, target, up).inverse(),
    }
}

use glam::{DVec2, DVec3};
use ocean::{Wave, WaveSet};

use render::{Boat, Camera, Mark, Scene};

/// One effect pass, in draw order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Effect {
    /// The camera frame behind everything.
    Background,
    /// Planar reflection of boats, sails, marks and the camera image.
    Reflection,
    /// The real table seen through the water.
    Refraction,
    /// Light focused by the waves onto the table.
    Caustics,
    /// Flow-map texture distortion for current around marks.
    FlowMap,
}

impl Effect {
    /// Every effect, in draw order.
    pub const ALL: [Effect; 5] = [
        Effect::Background,
        Effect::Reflection,
        Effect::Refraction,
        Effect::Caustics,
        Effect::FlowMap,
    ];

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Effect::Background => "background",
            Effect::Reflection => "reflection",
            Effect::Refraction => "refraction",
            Effect::Caustics => "caustics",
            Effect::FlowMap => "flowmap",
        }
    }

    /// The effect named `name` (as [`Effect::name`] writes it).
    pub fn from_name(name: &str) -> Option<Effect> {
        Effect::ALL.into_iter().find(|e| e.name() == name)
    }
}

impl fmt::Display for Effect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A set of effects, e.g. from `--effects reflection,caustics`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EffectSet(u8);

impl EffectSet {
    /// No effects: water only.
    pub const NONE: EffectSet = EffectSet(0);
    /// Every effect.
    pub const ALL: EffectSet = EffectSet(0b1_1111);

    pub fn only(e: Effect) -> EffectSet {
        EffectSet(1 << e as u8)
    }
    pub fn with(self, e: Effect) -> EffectSet {
        EffectSet(self.0 | 1 << e as u8)
    }
    pub fn contains(self, e: Effect) -> bool {
        self.0 & (1 << e as u8) != 0
    }
    pub fn iter(self) -> impl Iterator<Item = Effect> {
        Effect::ALL.into_iter().filter(move |e| self.contains(*e))
    }

    /// Parse a comma-separated list: effect names, or `all` or `none` (water only) alone.
    /// Whitespace around names is ignored; an unknown or empty name is refused with a sentence
    /// that names it and lists the valid names, and `all` or `none` beside other names (`all,none`
    /// was taken as `all`) is refused as a contradiction.
    pub fn parse(list: &str) -> Result<EffectSet, String> {
        let names: Vec<&str> = list.split(',').map(str::trim).collect();
        if names.len() > 1
            && let Some(whole) = names.iter().find(|n| matches!(**n, "all" | "none"))
        {
            return Err(format!(
                "--effects \"{}\" is contradictory: \"{whole}\" stands alone, not in a list",
                names.join(",")
            ));
        }
        let mut set = EffectSet::NONE;
        for name in names {
            match name {
                "all" => set = EffectSet::ALL,
                "none" => {}
                _ => match Effect::from_name(name) {
                    Some(e) => set = set.with(e),
                    None => {
                        let valid: Vec<&str> = Effect::ALL.iter().map(|e| e.name()).collect();
                        return Err(format!(
                            "--effects names the unknown effect \"{name}\"; the effects are: {}, all, none",
                            valid.join(", ")
                        ));
                    }
                },
            }
        }
        Ok(set)
    }
}

impl fmt::Display for EffectSet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == EffectSet::NONE {
            return f.write_str("none");
        }
        let names: Vec<&str> = self.iter().map(Effect::name).collect();
        f.write_str(&names.join(","))
    }
}

/// A table-sized scene for the effects' golden images and bench: 60 m of water (table units ×
/// scale) with three short waves, two boats and a mark, seen obliquely from above, at race
/// time `t`.
pub fn demo_table_scene(t: f64) -> Scene {
    let wave = |direction: [f64; 2], steepness: f64, wavelength: f64, phase: f64| Wave {
        direction,
        steepness,
        wavelength,
        phase,
    };
    let boat = |x: f64, z: f64, heading: f64, colour: [f32; 3]| Boat {
        position: DVec2::new(x, z),
        heading,
        colour,
        length: 8.0,
    };
    Scene {
        t,
        sea: WaveSet {
            gravity: 9.81,
            depth: None,
            waves: vec![
                wave([1.0, 0.0], 0.12, 14.0, 0.0),
                wave([0.6, 0.8], 0.10, 9.0, 1.0),
                wave([-0.3, 0.95], 0.08, 6.0, 2.0),
            ],
        }
        .into(),
        boats: vec![
            boat(-6.0, 4.0, 0.7, [0.8, 0.05, 0.05]),
            boat(8.0, -6.0, 2.0, [0.05, 0.1, 0.7]),
        ],
        marks: vec![Mark {
            position: DVec2::new(2.0, 10.0),
        }],
        play_area: [-30.0, -30.0, 30.0, 30.0],
        sun: Scene::default_sun(),
        camera: Camera::look_at(DVec3::new(22.0, 26.0, 48.0), DVec3::ZERO, 500.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn effect_lists_parse_and_print() {
        let s = EffectSet::parse("reflection, caustics").unwrap();
        assert!(s.contains(Effect::Reflection) && s.contains(Effect::Caustics));
        assert!(!s.contains(Effect::Background) && !s.contains(Effect::FlowMap));
        assert_eq!(s.to_string(), "reflection,caustics");
        assert_eq!(EffectSet::parse("all").unwrap(), EffectSet::ALL);
        assert_eq!(EffectSet::parse("none").unwrap(), EffectSet::NONE);
        assert_eq!(EffectSet::ALL.iter().count(), 5);
        for e in Effect::ALL {
            assert_eq!(EffectSet::parse(e.name()).unwrap(), EffectSet::only(e));
        }
    }

    #[test]
    fn unknown_effects_are_refused_by_name() {
        let err = EffectSet::parse("reflection,fog").unwrap_err();
        assert!(err.contains("\"fog\"") && err.contains("caustics"), "{err}");
        let err = EffectSet::parse("reflection,,caustics").unwrap_err();
        assert!(err.contains("\"\""), "{err}");
    }

    /// `all,none` was taken as `all`.
    #[test]
    fn all_or_none_in_a_list_is_a_contradiction() {
        for list in ["all,none", "none, reflection", "caustics,all"] {
            let err = EffectSet::parse(list).unwrap_err();
            assert!(err.contains("is contradictory"), "{list}: {err}");
        }
        assert_eq!(
            EffectSet::parse("all, none").unwrap_err(),
            "--effects \"all,none\" is contradictory: \"all\" stands alone, not in a list"
        );
    }
}
