//! The race scene at time t: boats with data at t, the course marks, the play area and the sun,
//! for every entry point (desktop window, phone, `regatta render`, benches).
//!
//! [`RaceWorld`] holds what does not change during a race: the marks and the play area (one
//! scan of every fix, made once) and the sea behind an `Arc`, so a frame costs the boats' states
//! and nothing else.

use std::sync::Arc;

use glam::{DVec2, DVec3};
use render::{Boat, Camera, Mark, OrbitCamera, Scene};

use crate::error::CliResult;

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
    pub sea: Arc<ocean::WaveSet>,
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
    pub fn new(race: race::Race, sea: ocean::WaveSet) -> Self {
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
            sea: Arc::new(sea),
            marks,
            race_bounds,
            play_area: [ax - m, az - m, bx + m, bz + m],
        }
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
    pub fn wake(&self) -> CliResult<Arc<ocean::wake::Wake>> {
        race_wake(&self.race)
    }
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
pub fn race_wake(race: &race::Race) -> CliResult<Arc<ocean::wake::Wake>> {
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
        let race = crate::cli::inputs::load_race(&[]).unwrap();
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
}
