//! Caustics on the pool's floor and walls from the moving surface, by the area ratio.
//!
//! The water surface is a grid of triangles. Sunlight of irradiance E (normal to the sun)
//! crossing one triangle carries the flux Φ = E · T · A⊥, with A⊥ the triangle's area projected
//! onto a plane perpendicular to the light and T the Fresnel transmittance (full equations, from
//! [`render::optics`]). Each vertex's ray is refracted (Snell, [`render::optics::refract`]) and
//! followed to the face of the box it lands on; the three landing points span the receiving
//! triangle of area A_r. That triangle receives irradiance Φ / A_r, spread evenly over it:
//! where the surface focuses light the receiving triangle is small and bright, where it spreads
//! light it is large and dim. The light that enters through the surface is the light that lands
//! on the box: energy is conserved by construction, up to the triangles lost at the box's edges
//! (a triangle whose corners land on two different walls is dropped; the test bounds the loss).
//!
//! Landing points are laid out on the box's unfolded net ([`PoolBox::net_coords`]): the floor
//! and the four walls in one texture, continuous across the floor's edges and isometric, so
//! A_r measured in the net is the true receiving area. A texel's value is irradiance / E: for
//! flat water, the floor reads T(θ) cos θ of the sun's angle θ, the same factor a Phong diffuse
//! term max(N·L, 0) gives a surface in the open, times the transmittance. Absorption along the
//! light's path through the water and the spheres' shadows are not in the map (the shader
//! applies absorption along the view path).
//!
//! The GPU pass does the same: it draws the same triangles into the same net with additive
//! blending, each fragment adding Φ / A_r (A⊥/A_r from the screen derivatives of the surface
//! position, exact because it is affine within a triangle); this is its f64 reference.

use glam::DVec3;

use super::geometry::{Face, PoolBox, Ray};
use super::scene::PoolScene;
use super::water::Ring;
use render::optics::{N_AIR, fresnel, refract};

/// The caustics texture: irradiance / E over the unfolded net of the box, row-major, row 0 at
/// the net's −z edge, column 0 at its −x edge.
#[derive(Debug, Clone, PartialEq)]
pub struct CausticMap {
    /// Texels along x and z.
    pub width: usize,
    pub height: usize,
    /// Half extents of the net (x, z), metres.
    pub half_extent: [f64; 2],
    pub texels: Vec<f64>,
    /// Σ T · A⊥ over the surface triangles: the light that entered the water, E · m².
    pub entered: f64,
}

/// Where one surface grid vertex's refracted ray lands.
#[derive(Debug, Clone, Copy)]
struct Landing {
    surface: DVec3,
    transmittance: f64,
    face: Face,
    net: [f64; 2],
}

impl CausticMap {
    /// The map of `scene` at time `t` (with its ripple `rings`), refracting a grid of
    /// `grid × grid` surface cells into a `width × height` texture.
    pub fn compute(
        scene: &PoolScene,
        t: f64,
        rings: &[Ring],
        grid: usize,
        width: usize,
        height: usize,
    ) -> CausticMap {
        let pool = &scene.pool;
        let half_extent = pool.net_half_extent();
        let mut map = CausticMap {
            width,
            height,
            half_extent,
            texels: vec![0.0; width * height],
            entered: 0.0,
        };
        let n = grid.max(1);
        let landing = |i: usize, j: usize| -> Option<Landing> {
            let x0 = [
                -pool.half_x + 2.0 * pool.half_x * i as f64 / n as f64,
                -pool.half_z + 2.0 * pool.half_z * j as f64 / n as f64,
            ];
            land(scene, pool, scene.mesh_point(x0, t, rings))
        };
        let verts: Vec<Option<Landing>> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i, j)))
            .map(|(i, j)| landing(i, j))
            .collect();
        let at = |i: usize, j: usize| verts[j * (n + 1) + i];
        for j in 0..n {
            for i in 0..n {
                let quad = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                for tri in [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]] {
                    if let [Some(a), Some(b), Some(c)] = tri {
                        map.add_triangle(scene.to_light, [a, b, c]);
                    }
                }
            }
        }
        map
    }

    /// Splat one surface triangle's light onto the texels whose centres its landing triangle
    /// covers (half-open edge rule, so a tiling of triangles covers each centre once).
    fn add_triangle(&mut self, to_light: DVec3, v: [Landing; 3]) {
        let cross = (v[1].surface - v[0].surface).cross(v[2].surface - v[0].surface);
        let a_perp = 0.5 * cross.dot(to_light).abs();
        let transmittance = (v[0].transmittance + v[1].transmittance + v[2].transmittance) / 3.0;
        let flux = transmittance * a_perp;
        self.entered += flux;
        // Two different walls: the landing triangle would cut across the net's empty corner.
        let walls: Vec<Face> = v
            .iter()
            .map(|l| l.face)
            .filter(|f| *f != Face::Floor)
            .collect();
        if walls.windows(2).any(|w| w[0] != w[1]) {
            return;
        }
        let [p0, p1, p2] = [v[0].net, v[1].net, v[2].net];
        let area2 = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
        if area2 == 0.0 {
            return;
        }
        let irradiance = flux / (0.5 * area2.abs());
        // Texel bounds of the triangle.
        let (tx, tz) = (self.texel_size(0), self.texel_size(1));
        let to_col = |x: f64| (x + self.half_extent[0]) / tx - 0.5;
        let to_row = |z: f64| (z + self.half_extent[1]) / tz - 0.5;
        let xs = [p0[0], p1[0], p2[0]];
        let zs = [p0[1], p1[1], p2[1]];
        let c0 = to_col(xs.iter().copied().fold(f64::MAX, f64::min))
            .ceil()
            .max(0.0) as usize;
        let c1 = to_col(xs.iter().copied().fold(f64::MIN, f64::max)).floor();
        let r0 = to_row(zs.iter().copied().fold(f64::MAX, f64::min))
            .ceil()
            .max(0.0) as usize;
        let r1 = to_row(zs.iter().copied().fold(f64::MIN, f64::max)).floor();
        if c1 < 0.0 || r1 < 0.0 {
            return;
        }
        let c1 = (c1 as usize).min(self.width - 1);
        let r1 = (r1 as usize).min(self.height - 1);
        // Orient counter-clockwise so "inside" is "all edge functions ≥ 0".
        let (p1, p2) = if area2 > 0.0 { (p1, p2) } else { (p2, p1) };
        let edge = |a: [f64; 2], b: [f64; 2], p: [f64; 2]| {
            (b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])
        };
        // Top-left style tie rule: a centre exactly on an edge belongs to one side only.
        let owns = |e: f64, a: [f64; 2], b: [f64; 2]| {
            e > 0.0 || (e == 0.0 && (b[1] < a[1] || (b[1] == a[1] && b[0] > a[0])))
        };
        for row in r0..=r1 {
            let z = -self.half_extent[1] + (row as f64 + 0.5) * tz;
            for col in c0..=c1 {
                let p = [-self.half_extent[0] + (col as f64 + 0.5) * tx, z];
                let inside = owns(edge(p0, p1, p), p0, p1)
                    && owns(edge(p1, p2, p), p1, p2)
                    && owns(edge(p2, p0, p), p2, p0);
                if inside {
                    self.texels[row * self.width + col] += irradiance;
                }
            }
        }
    }

    /// Texel size along x (axis 0) or z (axis 1), metres.
    pub fn texel_size(&self, axis: usize) -> f64 {
        let n = if axis == 0 { self.width } else { self.height };
        2.0 * self.half_extent[axis] / n as f64
    }

    /// The texel value at net point `q` (nearest texel; 0 outside the net).
    pub fn at_net(&self, q: [f64; 2]) -> f64 {
        let col = ((q[0] + self.half_extent[0]) / self.texel_size(0)).floor();
        let row = ((q[1] + self.half_extent[1]) / self.texel_size(1)).floor();
        if col < 0.0 || row < 0.0 || col >= self.width as f64 || row >= self.height as f64 {
            return 0.0;
        }
        self.texels[row as usize * self.width + col as usize]
    }

    /// Light landed on the whole box: Σ texel · texel area, in units of E · m².
    pub fn total_flux(&self) -> f64 {
        self.texels.iter().sum::<f64>() * self.texel_size(0) * self.texel_size(1)
    }
}

/// Refract the sunlight at one surface point and follow it to the box.
fn land(scene: &PoolScene, pool: &PoolBox, p: super::water::WaterPoint) -> Option<Landing> {
    let surface = p.position;
    let cos_i = p.normal.dot(scene.to_light);
    if cos_i <= 0.0 {
        // The sun is behind this facet: no direct light enters here.
        return None;
    }
    let transmittance = fresnel(cos_i, N_AIR, scene.ior).t;
    let dir = refract(-scene.to_light, p.normal, N_AIR, scene.ior)?;
    let hit = pool.hit_inside(&Ray::new(surface, dir))?;
    Some(Landing {
        surface,
        transmittance,
        face: hit.face,
        net: pool.net_coords(hit.face, hit.point),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::water::{PoolWater, RippleModel};
    use ocean::{Wave, WaveSet};
    use render::optics::N_WATER;

    fn scene_with(waves: Vec<Wave>, to_light: DVec3) -> PoolScene {
        PoolScene {
            water: PoolWater {
                waves: WaveSet {
                    gravity: 9.81,
                    depth: Some(1.0),
                    waves,
                },
                ripples: RippleModel::default(),
            },
            floaters: vec![],
            movers: vec![],
            to_light: to_light.normalize(),
            ..PoolScene::default()
        }
    }

    #[test]
    fn flat_water_lights_the_floor_with_t_cos_theta() {
        let to_light = DVec3::new(0.2, 1.0, -0.1).normalize();
        let scene = scene_with(vec![], to_light);
        let map = CausticMap::compute(&scene, 0.0, &[], 64, 128, 96);
        let cos = to_light.y;
        let expected = fresnel(cos, N_AIR, N_WATER).t * cos;
        // Away from the edges every floor texel reads the same value.
        for q in [[0.0, 0.0], [0.5, -0.3], [-0.6, 0.4]] {
            let v = map.at_net(q);
            assert!((v - expected).abs() < 1e-9, "{v} vs {expected} at {q:?}");
        }
    }

    #[test]
    fn light_entering_equals_light_landing() {
        // Energy: the flux through the surface, E · T · cos θ · (pool area) to first order in the
        // slopes, is what the box receives in the net (floor and walls).
        let to_light = DVec3::new(-0.35, 1.0, 0.45).normalize();
        let scene = PoolScene {
            to_light,
            ..PoolScene::default()
        };
        let t = 2.0;
        let rings = scene.rings(t);
        // Texel centres sample the landing triangles: near a focus a triangle is smaller than
        // a texel and lands on one centre or none, so a coarse map keeps the light only on
        // average (±3 % at 256², ±0.5 % at 1024² for this sea; the bench tabulates it).
        let map = CausticMap::compute(&scene, t, &rings, 160, 1024, 1024);
        let area = 4.0 * scene.pool.half_x * scene.pool.half_z;
        let expected = fresnel(to_light.y, N_AIR, N_WATER).t * to_light.y * area;
        let got = map.total_flux();
        // The rasterised map keeps what entered, less the corner triangles and texel sampling.
        assert!(
            (got / map.entered - 1.0).abs() < 0.01,
            "landed {got}, entered {}",
            map.entered
        );
        // What entered is the flat-water flux up to the slopes' second-order effects and the
        // waves' heights along the walls (a few per cent for this sea).
        assert!(
            (map.entered / expected - 1.0).abs() < 0.03,
            "entered {}, flat water {expected}",
            map.entered
        );
        // And it is not uniform: the moving surface focuses light.
        let max = map.texels.iter().copied().fold(0.0, f64::max);
        assert!(max > 2.0 * expected / area, "max {max}");
    }

    #[test]
    fn small_wave_matches_linear_lens_formula() {
        // A single gentle wave along x and the sun overhead: to first order the floor (depth D)
        // sees I / I_flat = 1 / (1 + D (1 − 1/n) h''(x)), h = A sin(k x), at the x whose ray
        // lands at X = x + D (1 − 1/n) h'(x) (so a crest, h'' < 0, focuses light).
        let wave = Wave {
            direction: [1.0, 0.0],
            steepness: 0.02,
            wavelength: 0.5,
            phase: 0.0,
        };
        let scene = scene_with(vec![wave], DVec3::Y);
        let map = CausticMap::compute(&scene, 0.0, &[], 400, 800, 8);
        let flat = fresnel(1.0, N_AIR, N_WATER).t;
        let (k, a) = (wave.k(), wave.amplitude());
        let d = -scene.pool.floor_y;
        let eta = 1.0 - 1.0 / N_WATER;
        let eps = d * eta * a * k * k;
        assert!(eps > 0.05, "the test needs a visible effect: {eps}");
        let mut worst: f64 = 0.0;
        for col in 0..map.width {
            let x_net = -map.half_extent[0] + (col as f64 + 0.5) * map.texel_size(0);
            if x_net.abs() > 0.8 {
                continue; // off the floor, or near its edges
            }
            // Invert X = x + D η A k cos(k x) by fixed-point iteration.
            let mut x = x_net;
            for _ in 0..50 {
                x = x_net - d * eta * a * k * (k * x).cos();
            }
            let expected = 1.0 / (1.0 - eps * (k * x).sin());
            let got = map.at_net([x_net, 0.0]) / flat;
            worst = worst.max((got - expected).abs());
        }
        // The first-order formula leaves O(ε², kA) errors.
        assert!(worst < 0.25 * eps, "worst {worst}, effect size {eps}");
    }
}
