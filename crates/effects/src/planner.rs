//! When each effect pass runs: the frame planner's rules for the effects, as pure functions of
//! what the frame shows. Every decision carries its reason, so a report (and a test) can say
//! why a pass did not run.

use super::{Effect, EffectSet};

/// Currents slower than this (m/s) are not drawn: the flow map would move the detail texture
/// by less than a texel over a typical 2 s period.
pub const MIN_VISIBLE_CURRENT: f64 = 0.01;

/// What the planner needs to know about a frame (measured by the renderer from the scene and
/// the camera before drawing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EffectFrame {
    /// The effects asked for (`--effects`, the effects panel).
    pub requested: EffectSet,
    /// A camera frame is available to draw behind the scene.
    pub camera_frame: bool,
    /// Share of the screen covered by water, 0–1.
    pub water_on_screen: f64,
    /// The camera is above the water's rest plane (reflections are seen from above only).
    pub camera_above_water: bool,
    /// Boats, sails or marks above the water whose mirror images fall in the view.
    pub reflectors_in_view: usize,
    /// Size of the reflection texture in pixels (screen size × the configured fraction).
    pub reflection_texture_px: [u32; 2],
    /// Share of the screen where water covers the table, 0–1.
    pub water_over_table: f64,
    /// The sun's elevation above the horizon, radians.
    pub sun_elevation: f64,
    /// The sea has no waves (and no wakes) in view: nothing focuses light.
    pub calm_sea: bool,
    /// Largest current speed over the water in view, m/s.
    pub max_current_in_view: f64,
    /// The timeline is paused (race time not moving).
    pub timeline_paused: bool,
    /// The camera has not moved since the last frame.
    pub camera_still: bool,
    /// The last frame drawn is still on hand and drawn with the same effects.
    pub previous_frame_reusable: bool,
}

/// One pass's decision.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EffectDecision {
    pub effect: Effect,
    pub run: bool,
    /// Why it runs, or why not: a short phrase for the frame report.
    pub reason: String,
}

/// Decide every effect pass for a frame, in draw order.
pub fn plan_effects(f: &EffectFrame) -> Vec<EffectDecision> {
    Effect::ALL.into_iter().map(|e| decide(e, f)).collect()
}

/// The decision for one effect.
pub fn decide(effect: Effect, f: &EffectFrame) -> EffectDecision {
    let (run, reason) = rule(effect, f);
    EffectDecision {
        effect,
        run,
        reason: reason.to_string(),
    }
}

fn rule(effect: Effect, f: &EffectFrame) -> (bool, &'static str) {
    if !f.requested.contains(effect) {
        return (false, "not requested");
    }
    if f.timeline_paused && f.camera_still && f.previous_frame_reusable {
        return (
            false,
            "timeline paused and camera still: previous frame reused",
        );
    }
    match effect {
        Effect::Background => match f.camera_frame {
            true => (true, "camera frame behind the scene"),
            false => (false, "no camera frame"),
        },
        Effect::Reflection => {
            if f.water_on_screen <= 0.0 {
                (false, "water off screen")
            } else if !f.camera_above_water {
                (
                    false,
                    "camera below the water: no reflection seen from under it",
                )
            } else if f.reflection_texture_px[0] == 0 || f.reflection_texture_px[1] == 0 {
                (false, "reflection texture smaller than a pixel")
            } else if f.reflectors_in_view > 0 {
                (true, "boats, sails or marks reflected in visible water")
            } else if f.camera_frame {
                // The room (the camera image on the ring around the water) and the sky are
                // drawn into the same texture: without it the water would mirror the sky
                // alone, and the room would pop in with the first boat.
                (true, "the room and the sky reflected in visible water")
            } else {
                (
                    false,
                    "nothing reflected in view: no boat, sail or mark, no camera image",
                )
            }
        }
        Effect::Refraction => match f.water_over_table > 0.0 {
            true => (true, "water covers the table in view"),
            false => (false, "no water over the table in view"),
        },
        Effect::Caustics => {
            if f.water_over_table <= 0.0 {
                (false, "no water over the table in view")
            } else if f.sun_elevation <= 0.0 {
                (false, "sun below the horizon")
            } else if f.calm_sea {
                (false, "calm sea: light falls evenly")
            } else {
                (true, "waves focus sunlight on the table in view")
            }
        }
        Effect::FlowMap => match f.max_current_in_view >= MIN_VISIBLE_CURRENT {
            true => (true, "current in view"),
            false => (false, "no current in view"),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame that needs every effect.
    fn busy() -> EffectFrame {
        EffectFrame {
            requested: EffectSet::ALL,
            camera_frame: true,
            water_on_screen: 0.6,
            camera_above_water: true,
            reflectors_in_view: 3,
            reflection_texture_px: [320, 180],
            water_over_table: 0.5,
            sun_elevation: 0.8,
            calm_sea: false,
            max_current_in_view: 0.4,
            timeline_paused: false,
            camera_still: false,
            previous_frame_reusable: true,
        }
    }

    fn check(f: &EffectFrame, e: Effect, run: bool, reason: &str) {
        let d = decide(e, f);
        assert_eq!(d.run, run, "{e}: {d:?}");
        assert!(d.reason.contains(reason), "{e}: reason \"{}\"", d.reason);
    }

    #[test]
    fn a_busy_frame_runs_everything_with_reasons() {
        let plan = plan_effects(&busy());
        assert_eq!(plan.len(), 5);
        assert!(
            plan.iter().all(|d| d.run && !d.reason.is_empty()),
            "{plan:?}"
        );
        assert_eq!(
            plan.iter().map(|d| d.effect).collect::<Vec<_>>(),
            Effect::ALL
        );
    }

    #[test]
    fn reflection_needs_a_reflector_and_visible_water_from_above() {
        let f = busy();
        check(&f, Effect::Reflection, true, "reflected");
        check(
            &EffectFrame {
                reflectors_in_view: 0,
                ..f
            },
            Effect::Reflection,
            true,
            "the room",
        );
        check(
            &EffectFrame {
                reflectors_in_view: 0,
                camera_frame: false,
                ..f
            },
            Effect::Reflection,
            false,
            "nothing reflected",
        );
        check(
            &EffectFrame {
                water_on_screen: 0.0,
                ..f
            },
            Effect::Reflection,
            false,
            "water off screen",
        );
        check(
            &EffectFrame {
                camera_above_water: false,
                ..f
            },
            Effect::Reflection,
            false,
            "below the water",
        );
        check(
            &EffectFrame {
                reflection_texture_px: [0, 90],
                ..f
            },
            Effect::Reflection,
            false,
            "smaller than a pixel",
        );
    }

    #[test]
    fn refraction_and_caustics_need_water_over_the_table() {
        let f = busy();
        check(&f, Effect::Refraction, true, "covers the table");
        check(&f, Effect::Caustics, true, "focus");
        let dry = EffectFrame {
            water_over_table: 0.0,
            ..f
        };
        check(&dry, Effect::Refraction, false, "no water over the table");
        check(&dry, Effect::Caustics, false, "no water over the table");
        check(
            &EffectFrame {
                sun_elevation: -0.1,
                ..f
            },
            Effect::Caustics,
            false,
            "sun below",
        );
        check(
            &EffectFrame {
                calm_sea: true,
                ..f
            },
            Effect::Caustics,
            false,
            "calm sea",
        );
        // A calm sea still shows the table through the water.
        check(
            &EffectFrame {
                calm_sea: true,
                ..f
            },
            Effect::Refraction,
            true,
            "covers the table",
        );
    }

    #[test]
    fn flow_maps_only_near_a_current() {
        let f = busy();
        check(&f, Effect::FlowMap, true, "current in view");
        check(
            &EffectFrame {
                max_current_in_view: MIN_VISIBLE_CURRENT,
                ..f
            },
            Effect::FlowMap,
            true,
            "current",
        );
        check(
            &EffectFrame {
                max_current_in_view: 0.005,
                ..f
            },
            Effect::FlowMap,
            false,
            "no current",
        );
    }

    #[test]
    fn the_background_needs_a_camera_frame() {
        check(&busy(), Effect::Background, true, "camera frame");
        check(
            &EffectFrame {
                camera_frame: false,
                ..busy()
            },
            Effect::Background,
            false,
            "no camera frame",
        );
    }

    #[test]
    fn nothing_is_redrawn_while_paused_with_a_still_camera() {
        let still = EffectFrame {
            timeline_paused: true,
            camera_still: true,
            ..busy()
        };
        for d in plan_effects(&still) {
            assert!(
                !d.run && d.reason.contains("previous frame reused"),
                "{d:?}"
            );
        }
        // Paused but the camera moves, or playing with a still camera: redraw.
        for f in [
            EffectFrame {
                camera_still: false,
                ..still
            },
            EffectFrame {
                timeline_paused: false,
                ..still
            },
            EffectFrame {
                previous_frame_reusable: false,
                ..still
            },
        ] {
            assert!(plan_effects(&f).iter().all(|d| d.run), "{f:?}");
        }
    }

    #[test]
    fn unrequested_effects_never_run() {
        let f = EffectFrame {
            requested: EffectSet::only(Effect::Caustics),
            ..busy()
        };
        for d in plan_effects(&f) {
            assert_eq!(d.run, d.effect == Effect::Caustics, "{d:?}");
            if !d.run {
                assert_eq!(d.reason, "not requested");
            }
        }
    }
}
