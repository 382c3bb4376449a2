//! The f64 reference of what the pool shader computes per fragment of the water surface: the
//! view ray splits at the surface into a reflected and a refracted ray (Snell; total internal
//! reflection from below past the critical angle), each is traced against the analytic spheres
//! and the pool box, the hits are Phong-shaded (the CS114 WebGL pool report's coefficients, 2018: docs/sources.md), and the full
//! Fresnel equations weigh the two. Under the water, light is lit by the caustics map and
//! absorbed along the view path (Beer–Lambert, red first).

use glam::DVec3;

use super::caustics::CausticMap;
use super::geometry::{Face, Ray};
use super::scene::{PoolScene, SceneSphere};
use render::optics::{N_AIR, fresnel, reflect, refract};

/// Absorption coefficients of clear pool water for red, green and blue, 1/m: light loses
/// e^(−μ s) over a path of s metres (pure water absorbs red most).
pub const WATER_ABSORPTION: [f64; 3] = [0.45, 0.09, 0.06];

/// Phong coefficients of the CS114 pool report: diffuse 0.8, specular 0.4, plus an ambient term.
pub const AMBIENT: f64 = 0.25;
pub const DIFFUSE: f64 = 0.8;
pub const SPECULAR: f64 = 0.4;
/// Specular exponent of tiles and balls.
pub const SHININESS: f64 = 60.0;

/// Edge of a square tile, metres, and the width of the grout between tiles.
pub const TILE: f64 = 0.1;
pub const GROUT: f64 = 0.007;

/// How a view ray divides at the water surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Split {
    /// Mirror direction and the share of light it carries (Fresnel R).
    pub reflected: (DVec3, f64),
    /// Transmitted direction and its share (1 − R); `None` under total internal reflection.
    pub refracted: Option<(DVec3, f64)>,
    /// True when the ray arrives from the water side.
    pub from_below: bool,
}

/// Split the unit view direction `d` at a surface point with upward unit normal `normal`,
/// between air and water of index `ior`.
pub fn split(d: DVec3, normal: DVec3, ior: f64) -> Split {
    let from_below = d.dot(normal) > 0.0;
    let (n1, n2) = if from_below {
        (ior, N_AIR)
    } else {
        (N_AIR, ior)
    };
    let f = fresnel(d.dot(normal), n1, n2);
    let refracted = refract(d, normal, n1, n2).map(|t| (t, f.t));
    Split {
        reflected: (reflect(d, normal), f.r),
        refracted: if f.total_internal { None } else { refracted },
        from_below,
    }
}

/// Tile albedo (linear RGB) at a point of a face of the box: pale aqua tiles with light grout,
/// a dark-blue band along the top of the walls and a dark lane line down the floor.
pub fn tile_albedo(scene: &PoolScene, face: Face, p: DVec3) -> [f64; 3] {
    let (u, v) = match face {
        Face::Floor => (p.x, p.z),
        Face::East | Face::West => (p.z, p.y),
        Face::North | Face::South => (p.x, p.y),
    };
    let grout = |c: f64| (c / TILE).rem_euclid(1.0) * TILE < GROUT;
    if grout(u) || grout(v) {
        return [0.75, 0.78, 0.76];
    }
    let band = face != Face::Floor && p.y > scene.pool.rim_y - 2.0 * TILE;
    let lane = face == Face::Floor && p.z.abs() < TILE && p.x.abs() < scene.pool.half_x - TILE;
    if band || lane {
        [0.03, 0.12, 0.35]
    } else {
        [0.55, 0.78, 0.82]
    }
}

/// Sky seen along `d` (a simple gradient; the AR build shows the camera image instead).
pub fn sky(d: DVec3) -> [f64; 3] {
    let up = d.y.max(0.0);
    [0.6 - 0.35 * up, 0.75 - 0.25 * up, 0.95]
}

fn phong(
    albedo: [f64; 3],
    diffuse_light: f64,
    n: DVec3,
    to_light: DVec3,
    to_eye: DVec3,
    spec: f64,
) -> [f64; 3] {
    let r = reflect(-to_light, n);
    let s = if diffuse_light > 0.0 {
        SPECULAR * spec * r.dot(to_eye).max(0.0).powf(SHININESS)
    } else {
        0.0
    };
    albedo.map(|a| a * (AMBIENT + DIFFUSE * diffuse_light) + s)
}

/// The nearest sphere along a ray, with its distance.
fn nearest_sphere<'a>(spheres: &'a [SceneSphere], ray: &Ray) -> Option<(f64, &'a SceneSphere)> {
    spheres
        .iter()
        .filter_map(|s| s.sphere.hit(ray).map(|d| (d, s)))
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// Colour seen along a ray in the air (a reflection off the water, or a refraction out of it):
/// a sphere, a wall above the water, or the sky.
pub fn trace_air(scene: &PoolScene, spheres: &[SceneSphere], ray: &Ray) -> [f64; 3] {
    let wall = scene.pool.hit_inside(ray);
    let ball = nearest_sphere(spheres, ray);
    let l = scene.to_light;
    match (ball, wall) {
        (Some((s, b)), w) if w.is_none_or(|w| s < w.s) => {
            let p = ray.at(s);
            let n = b.sphere.normal_at(p);
            phong(b.color, n.dot(l).max(0.0), n, l, -ray.dir, 1.0)
        }
        (_, Some(w)) => {
            let albedo = tile_albedo(scene, w.face, w.point);
            phong(albedo, w.normal.dot(l).max(0.0), w.normal, l, -ray.dir, 0.3)
        }
        _ => sky(ray.dir),
    }
}

/// Colour seen along a ray under the water: a sphere or the tiled box, lit by the caustics map
/// (balls by the refracted sun with the flat-water transmittance), absorbed along the path.
pub fn trace_water(
    scene: &PoolScene,
    spheres: &[SceneSphere],
    caustics: &CausticMap,
    ray: &Ray,
) -> [f64; 3] {
    let Some(wall) = scene.pool.hit_inside(ray) else {
        // Only a ray heading up out of the pool gets here; treat it as reaching the sky.
        return sky(ray.dir);
    };
    let (s, color) = match nearest_sphere(spheres, ray) {
        Some((s, b)) if s < wall.s => {
            let p = ray.at(s);
            let n = b.sphere.normal_at(p);
            let sun = refract(-scene.to_light, DVec3::Y, N_AIR, scene.ior).unwrap_or(DVec3::NEG_Y);
            let t = fresnel(scene.to_light.y, N_AIR, scene.ior).t;
            let light = t * n.dot(-sun).max(0.0);
            (s, phong(b.color, light, n, -sun, -ray.dir, 1.0))
        }
        _ => {
            let albedo = tile_albedo(scene, wall.face, wall.point);
            let light = caustics.at_net(scene.pool.net_coords(wall.face, wall.point));
            (wall.s, albedo.map(|a| a * (AMBIENT + DIFFUSE * light)))
        }
    };
    let mut out = color;
    for (c, mu) in out.iter_mut().zip(WATER_ABSORPTION) {
        *c *= (-mu * s).exp();
    }
    out
}

/// Colour of the water surface at `point` (unit upward `normal`) seen along the unit view
/// direction `d`: Fresnel-weighted reflection plus refraction, each traced.
pub fn shade_water(
    scene: &PoolScene,
    spheres: &[SceneSphere],
    caustics: &CausticMap,
    point: DVec3,
    normal: DVec3,
    d: DVec3,
) -> [f64; 3] {
    let sp = split(d, normal, scene.ior);
    let (rdir, r) = sp.reflected;
    let rray = Ray::new(point, rdir);
    let reflected = if sp.from_below {
        trace_water(scene, spheres, caustics, &rray)
    } else {
        trace_air(scene, spheres, &rray)
    };
    let mut out = reflected.map(|c| c * r);
    if let Some((tdir, t)) = sp.refracted {
        let tray = Ray::new(point, tdir);
        let transmitted = if sp.from_below {
            trace_air(scene, spheres, &tray)
        } else {
            trace_water(scene, spheres, caustics, &tray)
        };
        for (o, c) in out.iter_mut().zip(transmitted) {
            *o += t * c;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use render::optics::N_WATER;

    fn sin_angle(a: DVec3, n: DVec3) -> f64 {
        a.cross(n).length()
    }

    #[test]
    fn refraction_obeys_snells_sine_ratio_both_ways() {
        let n = DVec3::new(0.1, 1.0, -0.2).normalize();
        for d in [
            DVec3::new(0.5, -1.0, 0.2),
            DVec3::new(-1.0, -0.3, 0.4),
            DVec3::new(0.0, -1.0, 0.0),
        ] {
            let d = d.normalize();
            let sp = split(d, n, N_WATER);
            assert!(!sp.from_below);
            let (t, _) = sp.refracted.unwrap();
            // sin θi / sin θt = n2 / n1, and the ray keeps going down (into the water).
            let (si, st) = (sin_angle(d, n), sin_angle(t, n));
            if si > 1e-9 {
                assert!((si / st - N_WATER).abs() < 1e-12);
            }
            assert!(t.dot(n) < 0.0);
            // The three directions lie in one plane.
            assert!(d.cross(n).dot(t).abs() < 1e-12);
        }
        // From below at 30°: sin θt = 1.333 · sin 30°.
        let d = DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0);
        let sp = split(d, DVec3::Y, N_WATER);
        assert!(sp.from_below);
        let (t, _) = sp.refracted.unwrap();
        assert!((t.x - N_WATER * 0.5).abs() < 1e-12 && t.y > 0.0);
    }

    #[test]
    fn shares_sum_to_one_and_match_normal_incidence() {
        let sp = split(DVec3::NEG_Y, DVec3::Y, N_WATER);
        let r0 = ((N_WATER - 1.0) / (N_WATER + 1.0)).powi(2);
        assert!((sp.reflected.1 - r0).abs() < 1e-12);
        assert!((sp.reflected.1 + sp.refracted.unwrap().1 - 1.0).abs() < 1e-15);
        assert_eq!(sp.reflected.0, DVec3::Y);
    }

    #[test]
    fn ray_from_below_beyond_the_critical_angle_only_reflects() {
        // Critical angle asin(1/1.333) = 48.6°; at 60° from the normal the surface is a mirror.
        let crit = (1.0 / N_WATER).asin();
        for deg in [49.0f64, 60.0, 85.0] {
            assert!(deg.to_radians() > crit);
            let a = deg.to_radians();
            let d = DVec3::new(a.sin(), a.cos(), 0.0);
            let sp = split(d, DVec3::Y, N_WATER);
            assert!(sp.from_below && sp.refracted.is_none());
            assert_eq!(sp.reflected.1, 1.0);
            assert!((sp.reflected.0 - DVec3::new(a.sin(), -a.cos(), 0.0)).length() < 1e-12);
        }
        // Just inside the critical angle, light still gets out.
        let a = crit - 1e-3;
        let sp = split(DVec3::new(a.sin(), a.cos(), 0.0), DVec3::Y, N_WATER);
        assert!(sp.refracted.is_some() && sp.reflected.1 < 1.0);
    }

    #[test]
    fn water_seen_from_below_past_critical_angle_shows_only_the_pool() {
        let scene = PoolScene::default();
        let map = CausticMap::compute(&scene, 0.0, &[], 32, 64, 64);
        let point = DVec3::new(0.0, 0.0, 0.0);
        let a = 70f64.to_radians();
        let d = DVec3::new(a.sin(), a.cos(), 0.0);
        let seen = shade_water(&scene, &[], &map, point, DVec3::Y, d);
        let mirror = trace_water(&scene, &[], &map, &Ray::new(point, reflect(d, DVec3::Y)));
        assert_eq!(seen, mirror);
        assert_ne!(seen, trace_air(&scene, &[], &Ray::new(point, DVec3::Y)));
    }

    #[test]
    fn underwater_colour_is_absorbed_by_beer_lambert() {
        // Straight down from the surface to the floor: 1 m of water, no caustic light beyond
        // the ambient term in an empty map.
        let scene = PoolScene::default();
        let map = CausticMap {
            width: 1,
            height: 1,
            half_extent: scene.pool.net_half_extent(),
            texels: vec![0.0],
            entered: 0.0,
        };
        let p = DVec3::new(0.33, 0.0, 0.33);
        let c = trace_water(&scene, &[], &map, &Ray::new(p, DVec3::NEG_Y));
        let albedo = tile_albedo(&scene, Face::Floor, DVec3::new(0.33, -1.0, 0.33));
        for i in 0..3 {
            let expected = albedo[i] * AMBIENT * (-WATER_ABSORPTION[i] * 1.0).exp();
            assert!((c[i] - expected).abs() < 1e-12);
        }
    }

    #[test]
    fn tiles_have_grout_every_tile_length() {
        let scene = PoolScene::default();
        let grout = tile_albedo(&scene, Face::Floor, DVec3::new(0.302, -1.0, 0.55));
        let tile = tile_albedo(&scene, Face::Floor, DVec3::new(0.35, -1.0, 0.55));
        assert_ne!(grout, tile);
        assert_eq!(
            grout,
            tile_albedo(&scene, Face::Floor, DVec3::new(0.402, -1.0, 0.65))
        );
    }
}
