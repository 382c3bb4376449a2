//! The race scene at time t: boats with data at t, the course marks, the play area and the sun,
//! for every entry point (desktop window, phone, `regatta render`, benches).
//!
//! [`RaceWorld`] holds what does not change during a race: the marks and the play area (one
//! scan of every fix, made once) and the sea behind an `Arc`, so a frame costs the boats' states
//! and nothing else.
//!
//! Invariant: the bottom of the app's folders: it names only `error` and `wakes` of the app
//! (the race overlays, the set-up, the feed and the core all stand on it; the folder-level
//! module test, `tools/module_cycles`, holds it).

use std::sync::Arc;

use glam::{DVec2, DVec3};
use render::{Boat, Camera, Mark, OrbitCamera, Scene};

use crate::error::AppResult;

/// Hull length drawn for every boat, metres (the tracks do not say).
pub const BOAT_LENGTH_M: f64 = 10.0;
/// Water reaches this far beyond every track and mark, metres.
pub const PLAY_AREA_MARGIN_M: f64 = 1500.0;
/// Far clip distance, metres.
pub const FAR_M: f64 = 20_000.0;

/// A race on a sea, with what every frame shares.
#[derive(Clone, Debug)]
pub struct RaceWorld {
    pub race: race::Race,
    /// The sea drawn: the one given, or the embedded default sea turned to the race's wind
    /// ([`sea_for_race`]).
    pub sea: Arc<ocean::WaveSet>,
    /// The sea as given, which a new race on this world starts from ([`RaceWorld::with_race`]).
    pub given_sea: Arc<ocean::WaveSet>,
    /// Every buoy once: single marks and both ends of gates and lines.
    pub marks: Vec<Mark>,
    /// Min x, min z, max x, max z (race metres): every track and mark, what the table
    /// scenes fit onto the table (`core::table`).
    pub race_bounds: [f64; 4],
    /// The sea: the race's bounds plus [`PLAY_AREA_MARGIN_M`] on every side (the orbit view's
    /// water; the table scenes cut it to the table).
    pub play_area: [f64; 4],
}

impl RaceWorld {
    /// A race on `sea`; where `sea` is the embedded default sea (no `--sea` given), its waves
    /// are turned to run with the race's wind ([`sea_for_race`]).
    pub fn new(race: race::Race, sea: ocean::WaveSet) -> Self {
        let drawn = sea_for_race(&race, &sea);
        let marks: Vec<Mark> = race
            .buoys()
            .into_iter()
            .map(|p| Mark {
                position: DVec2::from(p),
            })
            .collect();
        let track_points = race
            .boats
            .iter()
            .flat_map(|b| b.fixes().iter().map(|f| DVec2::from(f.pos())));
        let race_bounds =
            Scene::play_area_around(track_points.chain(marks.iter().map(|m| m.position)), 0.0);
        let [ax, az, bx, bz] = race_bounds;
        let m = PLAY_AREA_MARGIN_M;
        RaceWorld {
            race,
            sea: Arc::new(drawn.unwrap_or_else(|| sea.clone())),
            given_sea: Arc::new(sea),
            marks,
            race_bounds,
            play_area: [ax - m, az - m, bx + m, bz + m],
        }
    }

    /// Another race on the sea this world was given (the default sea turns to the new race's
    /// wind; a sea file stays as it is).
    pub fn with_race(&self, race: race::Race) -> RaceWorld {
        RaceWorld::new(race, (*self.given_sea).clone())
    }

    /// The scene at race time `t`: boats that have data at t (not inside a gap), the marks, the
    /// play area, and `camera` (or one framing the fleet).
    pub fn scene_at(&self, t: f64, camera: Option<Camera>) -> Scene {
        let boats: Vec<Boat> = self
            .race
            .boats
            .iter()
            .filter(|b| !b.fixes().is_empty())
            .map(|b| (b, b.state_at(t)))
            .filter(|(_, s)| !s.in_gap)
            .map(|(b, s)| Boat {
                position: DVec2::from(s.position),
                heading: s.heading_deg.to_radians(),
                colour: linear_colour(&b.color),
                length: BOAT_LENGTH_M,
            })
            .collect();
        let camera = camera.unwrap_or_else(|| Scene::framing_camera(&boats, &[], FAR_M));
        Scene {
            t,
            sea: Arc::clone(&self.sea),
            boats,
            marks: self.marks.clone(),
            play_area: self.play_area,
            sun: Scene::default_sun(),
            camera,
        }
    }

    /// The scene the race views draw at `t`: the camera orbiting the fleet's centre (`orbit`
    /// keeps the user's angle and distance; its target follows the fleet). A function of `t`
    /// and the orbit alone, so playing to t and scrubbing to t draw the same frame.
    pub fn orbit_scene(&self, t: f64, orbit: &mut OrbitCamera) -> Scene {
        let mut scene = self.scene_at(t, None);
        follow_fleet(orbit, &scene);
        scene.camera = orbit.camera();
        scene
    }

    /// The middle of the race's time span.
    pub fn middle_time(&self) -> f64 {
        middle_time(&self.race)
    }

    /// The race's wakes (default parameters), for `Renderer::set_wake`.
    pub fn wake(&self) -> AppResult<Arc<ocean::wake::Wake>> {
        race_wake(&self.race)
    }
}

/// The sea a race is drawn on when no sea was chosen: `Some(the default sea turned so its
/// dominant wave runs downwind of the race's wind)` where `sea` is the embedded default sea and
/// the race has a wind (stated, logged or estimated: [`race::Race::wind_model`]); `None` (draw
/// `sea` as it is) for a sea from a file, or a race without wind.
pub fn sea_for_race(race: &race::Race, sea: &ocean::WaveSet) -> Option<ocean::WaveSet> {
    if *sea != ocean::WaveSet::default_sea() {
        return None;
    }
    let from = match race.wind {
        Some(w) => w.from_deg,
        None => race.wind_model()?.from_deg,
    };
    Some(turned_to_wind(sea, from))
}

/// `sea` turned about the vertical so its dominant wave (largest amplitude) travels downwind
/// of a wind from `from_deg` (compass); every wave turns by the same angle, so the spectrum's
/// spread and phases are kept.
pub fn turned_to_wind(sea: &ocean::WaveSet, from_deg: f64) -> ocean::WaveSet {
    let amplitude = |w: &ocean::Wave| w.steepness * w.wavelength;
    let Some(dominant) = sea
        .waves
        .iter()
        .filter(|w| w.steepness > 0.0)
        .max_by(|a, b| amplitude(a).total_cmp(&amplitude(b)))
    else {
        return sea.clone();
    };
    let d = dominant.direction;
    let n = d[0].hypot(d[1]);
    let c = [d[0] / n, d[1] / n];
    // Downwind in race metres [east, south]: the bearing from + 180°.
    let b = (from_deg + 180.0).to_radians();
    let t = [b.sin(), -b.cos()];
    let (cos, sin) = (c[0] * t[0] + c[1] * t[1], c[0] * t[1] - c[1] * t[0]);
    let mut out = sea.clone();
    for w in &mut out.waves {
        let v = w.direction;
        w.direction = [v[0] * cos - v[1] * sin, v[0] * sin + v[1] * cos];
    }
    out
}

/// [`RaceWorld::scene_at`] for one frame (a command, a bench): builds the world once.
pub fn scene_at(race: &race::Race, sea: &ocean::WaveSet, t: f64, camera: Option<Camera>) -> Scene {
    RaceWorld::new(race.clone(), sea.clone()).scene_at(t, camera)
}

/// Points `orbit` at the centre of the scene's boats (kept where it was without boats).
pub fn follow_fleet(orbit: &mut OrbitCamera, scene: &Scene) {
    if !scene.boats.is_empty() {
        let c = scene.boats.iter().map(|b| b.position).sum::<DVec2>() / scene.boats.len() as f64;
        orbit.target = DVec3::new(c.x, 0.0, c.y);
    }
}

/// The orbit the race views open with, before the course is framed or dragged: 90 m from the
/// course origin, from the north-west, 20° up.
pub fn race_orbit() -> OrbitCamera {
    OrbitCamera {
        target: DVec3::ZERO,
        distance: 90.0,
        yaw: 2.4,
        pitch: 0.35,
        far: FAR_M,
    }
}

/// The wakes of every boat of `race` (default wake parameters), for `Renderer::set_wake`.
pub fn race_wake(race: &race::Race) -> AppResult<Arc<ocean::wake::Wake>> {
    crate::wakes::race_wake(race, ocean::wake::WakeParams::default()).map(Arc::new)
}

/// The middle of the race's time span.
pub fn middle_time(race: &race::Race) -> f64 {
    let (a, b) = race.time_span();
    (a + b) / 2.0
}

/// Linear RGB of `#rrggbb` (sRGB decoded); grey when the string is not a colour.
pub fn linear_colour(hex: &str) -> [f32; 3] {
    let h = hex.trim_start_matches('#');
    let c = |i: usize| {
        h.get(i..i + 2)
            .and_then(|x| u8::from_str_radix(x, 16).ok())
            .map(|b| {
                let s = f32::from(b) / 255.0;
                if s <= 0.04045 {
                    s / 12.92
                } else {
                    ((s + 0.055) / 1.055).powf(2.4)
                }
            })
    };
    match (h.len(), c(0), c(2), c(4)) {
        (6, Some(r), Some(g), Some(b)) => [r, g, b],
        _ => [0.5, 0.5, 0.5],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_decode_srgb() {
        assert_eq!(linear_colour("#ffffff"), [1.0, 1.0, 1.0]);
        assert_eq!(linear_colour("#000000"), [0.0, 0.0, 0.0]);
        // sRGB 0.5 (0x80) is 0.2158 linear.
        assert!((linear_colour("#808080")[0] - 0.2158).abs() < 1e-3);
        assert_eq!(linear_colour("oops"), [0.5, 0.5, 0.5]);
    }

    #[test]
    fn the_race_bounds_and_the_play_area_cover_every_fix_and_mark_and_the_sea_is_shared() {
        let race = race::Race::sample();
        let world = RaceWorld::new(race.clone(), ocean::WaveSet::default_sea());
        // Independent truth: the bounding box of every fix and buoy, scanned here.
        let mut b = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        let pts = race
            .boats
            .iter()
            .flat_map(|bt| bt.fixes().iter().map(|f| f.pos()))
            .chain(race.buoys());
        for [x, z] in pts.map(|p| DVec2::from(p).to_array()) {
            b = [b[0].min(x), b[1].min(z), b[2].max(x), b[3].max(z)];
        }
        let m = PLAY_AREA_MARGIN_M;
        let sea = [b[0] - m, b[1] - m, b[2] + m, b[3] + m];
        for (got, want) in [(world.race_bounds, b), (world.play_area, sea)] {
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() < 1e-6, "{got:?} vs {want:?}");
            }
        }
        let s1 = world.scene_at(world.middle_time(), None);
        let s2 = world.scene_at(world.middle_time() + 5.0, None);
        assert!(Arc::ptr_eq(&s1.sea, &s2.sea) && Arc::ptr_eq(&s1.sea, &world.sea));
        assert_eq!(s1.play_area, world.play_area);
    }

    /// The compass direction a sea's dominant wave comes from (against its travel).
    fn dominant_from(sea: &ocean::WaveSet) -> f64 {
        let w = sea
            .waves
            .iter()
            .max_by(|a, b| (a.steepness * a.wavelength).total_cmp(&(b.steepness * b.wavelength)))
            .unwrap();
        race::track::bearing_deg([-w.direction[0], -w.direction[1]])
    }

    #[test]
    fn the_default_sea_turns_to_the_race_wind_and_a_sea_file_stays() {
        let default = ocean::WaveSet::default_sea();
        // The default sea alone comes from about 289° (its dominant wave runs east-south-east).
        assert!(
            (dominant_from(&default) - 289.3).abs() < 0.1,
            "{}",
            dominant_from(&default)
        );
        // Valencia's metadata state a wind from 110°; the sample's file from 0°.
        for (race, from) in [(race::Race::valencia(), 110.0), (race::Race::sample(), 0.0)] {
            let world = RaceWorld::new(race, default.clone());
            let got = dominant_from(&world.sea);
            assert!(
                race::debrief::wind::angle_diff(got, from).abs() < 1e-9,
                "{got} vs {from}"
            );
            // Every wave turned by the same angle: the angles between waves are kept.
            for (a, b) in default.waves.iter().zip(&world.sea.waves) {
                let turn = |v: [f64; 2]| race::track::bearing_deg(v);
                let d = race::debrief::wind::angle_diff(turn(b.direction), turn(a.direction));
                let d0 = race::debrief::wind::angle_diff(
                    turn(world.sea.waves[0].direction),
                    turn(default.waves[0].direction),
                );
                assert!((d - d0).abs() < 1e-9);
                assert!(
                    (a.direction[0].hypot(a.direction[1]) - b.direction[0].hypot(b.direction[1]))
                        .abs()
                        < 1e-12
                );
            }
            // A new race on the same world turns the given sea again, not the turned one.
            let next = world.with_race(race::Race::sample());
            assert!(race::debrief::wind::angle_diff(dominant_from(&next.sea), 0.0).abs() < 1e-9);
        }
        // A sea from a file is drawn as given.
        let mut file_sea = default.clone();
        file_sea.waves[0].phase += 0.5;
        let world = RaceWorld::new(race::Race::valencia(), file_sea.clone());
        assert_eq!(*world.sea, file_sea);
    }
}
