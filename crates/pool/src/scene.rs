//! The pool scene's contents at a time t: the box, the water, the spheres that float and the
//! spheres that move, the sun. Everything is a closed-form function of t and of the moving
//! spheres' paths (a drag is recorded as a path), so any frame can be drawn on its own.

use glam::DVec3;
use ocean::WaveSet;

use super::geometry::{PoolBox, Ray, Sphere};
use super::water::{PoolWater, Ring, RippleModel, SpherePath, WaterPoint, rings_of};

/// The pool's own sea: short, steep-ish waves sized to a 2 m pool, finite depth 1 m (Σ kA =
/// 0.43). They focus light at about 1–2 m depth, so the floor shows a caustic network.
pub const POOL_SEA_JSON: &str = r#"{"gravity": 9.81, "depth": 1.0, "waves": [
  {"direction": [1.0, 0.3], "steepness": 0.08, "wavelength": 0.9, "phase": 0.0},
  {"direction": [-0.4, 1.0], "steepness": 0.08, "wavelength": 0.55, "phase": 1.9},
  {"direction": [0.7, -0.7], "steepness": 0.09, "wavelength": 0.37, "phase": 4.1},
  {"direction": [0.2, 1.0], "steepness": 0.10, "wavelength": 0.23, "phase": 2.6},
  {"direction": [-1.0, -0.5], "steepness": 0.08, "wavelength": 0.16, "phase": 0.8}
]}"#;

/// A sphere that floats: it rides the water particle of rest point `rest` (small floating
/// bodies follow the orbital motion of the water), with its centre `lift` metres above the
/// surface there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floater {
    /// (x, z) rest point, metres.
    pub rest: [f64; 2],
    /// Metres.
    pub radius: f64,
    /// Height of the centre above the surface, metres (negative: more than half submerged).
    pub lift: f64,
    /// Linear RGB albedo.
    pub color: [f64; 3],
}

/// A sphere that moves along a path (scripted, or dragged with the mouse or a finger). Where it
/// cuts the surface it leaves ripples.
#[derive(Debug, Clone, PartialEq)]
pub struct Mover {
    pub path: SpherePath,
    /// Metres.
    pub radius: f64,
    /// Linear RGB albedo.
    pub color: [f64; 3],
}

impl Mover {
    /// Record a drag sample: the sphere is at horizontal point `to` (x, z) at time `t`, its
    /// centre at height `y`. The path becomes a track that starts where the sphere was; samples
    /// not later than the last one are ignored (a track is strictly increasing in time).
    pub fn drag_to(&mut self, t: f64, to: [f64; 2], y: f64) {
        let target = DVec3::new(to[0], y, to[1]);
        match &mut self.path {
            SpherePath::Track(samples) => {
                if samples.last().is_none_or(|(tl, _)| t > *tl) {
                    samples.push((t, target));
                }
            }
            SpherePath::Orbit { .. } => {
                // Keep where the sphere was, so the jump to the pointer (if any) is motion
                // that makes ripples, capped by the ripple model like any fast move.
                let here = self.path.position(t);
                self.path = SpherePath::Track(vec![(t, here), (t + DRAG_START_S, target)]);
            }
        }
    }
}

/// How long the sphere takes to reach the pointer when a drag starts, seconds.
pub const DRAG_START_S: f64 = 0.05;

/// A sphere of the scene at a moment, with its albedo.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneSphere {
    pub sphere: Sphere,
    pub color: [f64; 3],
}

/// The whole pool scene.
#[derive(Debug, Clone, PartialEq)]
pub struct PoolScene {
    pub pool: PoolBox,
    pub water: PoolWater,
    pub floaters: Vec<Floater>,
    pub movers: Vec<Mover>,
    /// Unit vector towards the sun.
    pub to_light: DVec3,
    /// Refractive index of the water (air = 1).
    pub ior: f64,
}

impl Default for PoolScene {
    /// The scene of the CS114 WebGL pool report (2018, report 004 in docs/sources.md), with moving water: a 2 m × 1.6 m pool, 1 m deep; a red
    /// and a yellow ball floating, a blue ball swimming below the surface, a green ball moving
    /// through the surface (the one a drag moves), the sun high in the south-west.
    fn default() -> Self {
        let waves = WaveSet::from_json_str(POOL_SEA_JSON, "the pool sea")
            .expect("the pool sea is valid (checked by a test)");
        PoolScene {
            pool: PoolBox {
                half_x: 1.0,
                half_z: 0.8,
                floor_y: -1.0,
                rim_y: 0.15,
            },
            water: PoolWater {
                waves,
                ripples: RippleModel::default(),
            },
            floaters: vec![
                Floater {
                    rest: [-0.45, -0.3],
                    radius: 0.12,
                    lift: 0.03,
                    color: [0.8, 0.06, 0.05],
                },
                Floater {
                    rest: [0.5, 0.35],
                    radius: 0.1,
                    lift: 0.02,
                    color: [0.9, 0.7, 0.05],
                },
            ],
            movers: vec![
                Mover {
                    path: SpherePath::Orbit {
                        center: DVec3::new(0.0, -0.55, 0.0),
                        radii: [0.45, 0.3],
                        period_s: 9.0,
                        phase: 0.0,
                    },
                    radius: 0.18,
                    color: [0.05, 0.2, 0.8],
                },
                Mover {
                    path: SpherePath::Orbit {
                        center: DVec3::new(0.05, 0.0, 0.05),
                        radii: [0.6, 0.45],
                        period_s: 7.0,
                        phase: 2.0,
                    },
                    radius: 0.09,
                    color: [0.1, 0.7, 0.2],
                },
            ],
            to_light: DVec3::new(-0.35, 1.0, 0.45).normalize(),
            ior: 1.333,
        }
    }
}

impl PoolScene {
    /// The surface mesh's vertex for rest point `x0` (inside the pool's footprint): the water
    /// point, held inside the walls, and pinned to a wall when `x0` lies on it. Free edge
    /// vertices would open a gap where the waves pull the surface away from a wall (up to
    /// Σ A); pinned ones keep the mesh's footprint exactly the pool's. The shader does the same.
    pub fn mesh_point(&self, x0: [f64; 2], t: f64, rings: &[Ring]) -> WaterPoint {
        let mut p = self.water.point(x0, t, rings);
        let pin = |rest: f64, at: f64, half: f64| {
            if rest.abs() >= half * (1.0 - 1e-9) {
                half.copysign(rest)
            } else {
                at.clamp(-half, half)
            }
        };
        p.position.x = pin(x0[0], p.position.x, self.pool.half_x);
        p.position.z = pin(x0[1], p.position.z, self.pool.half_z);
        p
    }

    /// The ripple rings alive at time `t`, from every moving sphere.
    pub fn rings(&self, t: f64) -> Vec<Ring> {
        self.movers
            .iter()
            .flat_map(|m| rings_of(&self.water.ripples, &m.path, m.radius, t))
            .collect()
    }

    /// Every sphere at time `t` (floaters first, then movers). `rings` are [`Self::rings`]
    /// at `t`: the floaters ride the ripples too.
    pub fn spheres(&self, t: f64, rings: &[Ring]) -> Vec<SceneSphere> {
        let floating = self.floaters.iter().map(|f| {
            let p = self.water.point(f.rest, t, rings).position;
            SceneSphere {
                sphere: Sphere {
                    center: p + DVec3::Y * f.lift,
                    radius: f.radius,
                },
                color: f.color,
            }
        });
        let moving = self.movers.iter().map(|m| SceneSphere {
            sphere: Sphere {
                center: m.path.position(t),
                radius: m.radius,
            },
            color: m.color,
        });
        floating.chain(moving).collect()
    }

    /// Where a drag ray (from the camera through the pointer, in pool space) meets the water's
    /// rest plane y = 0, kept `margin` metres inside the walls; `None` when the ray does not
    /// come down onto the plane.
    pub fn drag_point(&self, ray: &Ray, margin: f64) -> Option<[f64; 2]> {
        if ray.dir.y >= 0.0 || ray.origin.y <= 0.0 {
            return None;
        }
        let s = -ray.origin.y / ray.dir.y;
        let p = ray.at(s);
        let mx = (self.pool.half_x - margin).max(0.0);
        let mz = (self.pool.half_z - margin).max(0.0);
        Some([p.x.clamp(-mx, mx), p.z.clamp(-mz, mz)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pool_sea_is_valid_and_does_not_fold() {
        let s = WaveSet::from_json_str(POOL_SEA_JSON, "the pool sea").unwrap();
        assert!(s.total_steepness() < 1.0);
        let scene = PoolScene::default();
        assert_eq!(scene.water.waves, s);
        // The highest crest stays below the rim, the lowest trough above the floor.
        let amp = s.total_amplitude();
        assert!(amp < scene.pool.rim_y && -amp > scene.pool.floor_y);
    }

    #[test]
    fn floaters_ride_the_surface_point_of_their_rest_point() {
        let scene = PoolScene::default();
        let t = 3.7;
        let rings = scene.rings(t);
        let spheres = scene.spheres(t, &rings);
        assert_eq!(spheres.len(), scene.floaters.len() + scene.movers.len());
        for (s, f) in spheres.iter().zip(&scene.floaters) {
            let [x, y, z] = scene.water.waves.displace(f.rest, t);
            let (eta, _) = super::super::water::ripple_height(&scene.water.ripples, &rings, [x, z]);
            let c = s.sphere.center;
            assert!((c - DVec3::new(x, y + eta + f.lift, z)).length() < 1e-12);
        }
    }

    #[test]
    fn mesh_edges_stay_on_the_walls_and_inside_points_inside() {
        let scene = PoolScene::default();
        let (hx, hz) = (scene.pool.half_x, scene.pool.half_z);
        for t in [0.0, 1.3, 7.7] {
            let rings = scene.rings(t);
            for u in [-1.0, -0.5, 0.0, 0.999, 1.0] {
                let e = scene.mesh_point([hx, u * hz], t, &rings).position;
                assert_eq!(e.x, hx);
                let w = scene.mesh_point([u * hx, -hz], t, &rings).position;
                assert_eq!(w.z, -hz);
                let i = scene
                    .mesh_point([u * hx * 0.99, u * hz * 0.99], t, &rings)
                    .position;
                assert!(i.x.abs() <= hx && i.z.abs() <= hz);
            }
        }
    }

    #[test]
    fn drag_ray_meets_the_rest_plane_where_the_line_crosses_y_zero() {
        let scene = PoolScene::default();
        // From (0.3, 2, 1) towards (0.1, 0, 0.2): the crossing is that point.
        let from = DVec3::new(0.3, 2.0, 1.0);
        let to = DVec3::new(0.1, 0.0, 0.2);
        let ray = Ray::new(from, to - from);
        let p = scene.drag_point(&ray, 0.1).unwrap();
        assert!((p[0] - 0.1).abs() < 1e-12 && (p[1] - 0.2).abs() < 1e-12);
        // Far outside the pool: held 0.1 m inside the east wall.
        let ray = Ray::new(from, DVec3::new(5.0, 0.0, 0.2) - from);
        assert!((scene.drag_point(&ray, 0.1).unwrap()[0] - 0.9).abs() < 1e-12);
        // Looking up: no drag.
        assert!(scene.drag_point(&Ray::new(from, DVec3::Y), 0.1).is_none());
    }

    #[test]
    fn drag_turns_an_orbit_into_a_track_that_makes_ripples() {
        let mut scene = PoolScene::default();
        let m = &mut scene.movers[1];
        let start = m.path.position(2.0);
        m.drag_to(2.0, [0.5, 0.5], 0.0);
        m.drag_to(2.5, [-0.5, 0.5], 0.0);
        m.drag_to(2.4, [9.0, 9.0], 0.0); // out of order: ignored
        assert_eq!(m.path.position(2.0), start);
        assert_eq!(m.path.position(3.0), DVec3::new(-0.5, 0.0, 0.5));
        let rings = scene.rings(2.6);
        assert!(rings.iter().any(|r| (r.center[0] + 0.5).abs() < 0.3));
    }
}
