//! Caustics on the table under the water (f64 reference of `shaders/caustics.wgsl`).
//!
//! **Area-ratio method.** Sunlight crossing a small patch of the wave surface is refracted
//! (Snell, n = 1.333) through the surface's actual normal at race time t and lands on the table
//! plane `depth` below the rest level. Light is conserved, so the irradiance on the table is the
//! area the patch takes in the sunlight (its footprint along the sun direction on a horizontal
//! plane) divided by the area it lands on: I = A_source / A_table, 1 for flat water. Because the
//! waves are a closed-form function of t (`ocean::WaveSet::surface`), the caustics scrub with
//! the timeline like everything else.
//!
//! **Cheap tier (the Sailing+ AR water thesis's, TU Delft 2022, docs/sources.md; after GPU Gems ch. 2).** The sun straight overhead, the flat water
//! plane, one lookup of a sun map in the direction the surface normal bends the vertical ray,
//! and alpha = clamp(r + g + b, 0, 1) so black means transparent. It ignores the sun's
//! direction and the real focusing distance; it costs one normal per pixel.

use glam::{DVec2, DVec3};
use ocean::WaveSet;

use render::optics::{N_AIR, N_WATER, refract};

/// Where to compute caustics: a square of the table, in the waves' horizontal coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CausticRegion {
    /// Lower corner (x, z), metres.
    pub min: [f64; 2],
    /// Side length, metres.
    pub size: f64,
    /// True when the sea repeats with this period in x and z: light leaving one side enters
    /// the other. Otherwise a margin of surface around the square is traced so that light
    /// bent into the square from outside is counted.
    pub periodic: bool,
}

impl CausticRegion {
    /// The square of the table whose caustics can be seen in a view: around `target` (the point
    /// looked at, world x, z), `view_width` metres wide, cut to the `play_area` (min x, min z,
    /// max x, max z) grown by `margin` metres, since light only reaches the table under the
    /// water (the margin covers table points seen through the water near its edge, and light
    /// bent out past it). Without an overlap, the play area's square.
    pub fn in_view(
        target: [f64; 2],
        view_width: f64,
        play_area: [f64; 4],
        margin: f64,
    ) -> CausticRegion {
        let half = view_width / 2.0;
        let lo = [
            (target[0] - half).max(play_area[0] - margin),
            (target[1] - half).max(play_area[1] - margin),
        ];
        let hi = [
            (target[0] + half).min(play_area[2] + margin),
            (target[1] + half).min(play_area[3] + margin),
        ];
        if hi[0] > lo[0] && hi[1] > lo[1] {
            CausticRegion {
                min: lo,
                size: (hi[0] - lo[0]).max(hi[1] - lo[1]),
                periodic: false,
            }
        } else {
            CausticRegion {
                min: [play_area[0] - margin, play_area[1] - margin],
                size: (play_area[2] - play_area[0]).max(play_area[3] - play_area[1]) + 2.0 * margin,
                periodic: false,
            }
        }
    }
}

/// Caustic irradiance on a regular grid over a [`CausticRegion`] of the table; 1 is the
/// irradiance under flat water.
#[derive(Debug, Clone, PartialEq)]
pub struct CausticMap {
    pub region: CausticRegion,
    /// Cells per side.
    pub n: usize,
    /// Row-major (z rows, x columns) irradiance per cell.
    pub intensity: Vec<f64>,
}

impl CausticMap {
    /// Mean irradiance over the map.
    pub fn mean(&self) -> f64 {
        self.intensity.iter().sum::<f64>() / self.intensity.len() as f64
    }
    /// Largest irradiance.
    pub fn max(&self) -> f64 {
        self.intensity.iter().copied().fold(0.0, f64::max)
    }
    /// Irradiance of the cell containing (x, z), or `None` outside the map.
    pub fn at(&self, x: f64, z: f64) -> Option<f64> {
        let cell = self.region.size / self.n as f64;
        let i = ((x - self.region.min[0]) / cell).floor();
        let j = ((z - self.region.min[1]) / cell).floor();
        let inside = (0.0..self.n as f64).contains(&i) && (0.0..self.n as f64).contains(&j);
        inside.then(|| self.intensity[j as usize * self.n + i as usize])
    }
}

/// Area-ratio caustics of `waves` at race time `t` on a table `depth` metres below the rest
/// level, lit by a sun whose light travels along `sun_dir` (pointing down, normalised here).
/// The surface is sampled on a `src_res`² grid of rest points (plus margin), the result binned
/// on an `out_res`² grid.
///
/// Each grid cell of the surface is split into two triangles; each triangle's light (its
/// footprint area along the sun on the plane y = 0) spreads evenly over the triangle it lands on,
/// with irradiance A_source / A_table. An output cell's value is the sum of the irradiances of
/// the landed triangles covering its centre (more than one where the light folds over, as in a
/// real caustic): exactly what the GPU pass does when it rasterises the landed triangles with
/// additive blending. Light is conserved up to the sampling of the landed triangles by the
/// output cells (a periodic patch keeps its mean within about 1 % at the sizes tested).
pub fn area_ratio(
    waves: &WaveSet,
    t: f64,
    sun_dir: DVec3,
    depth: f64,
    region: CausticRegion,
    src_res: usize,
    out_res: usize,
) -> CausticMap {
    let sun = sun_dir.normalize();
    let src_res = src_res.max(1);
    let out_res = out_res.max(1);
    let step = region.size / src_res as f64;
    // Margin (in source cells) so light bent in from outside a non-periodic square is traced:
    // the largest horizontal travel is about the depth times the ray's slope plus the wave's
    // horizontal displacement.
    let travel = depth.abs() * 1.5 + waves.waves.iter().map(|w| w.amplitude()).sum::<f64>();
    let margin = if region.periodic {
        0
    } else {
        (travel / step).ceil() as usize + 1
    };
    let n = src_res + 2 * margin + 1;
    let origin = [
        region.min[0] - margin as f64 * step,
        region.min[1] - margin as f64 * step,
    ];
    // Footprint (where the sunlight crosses y = 0 before reaching this surface point) and
    // landing point on the table, for every rest-grid point.
    let mut foot = Vec::with_capacity(n * n);
    let mut land = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let x0 = [origin[0] + i as f64 * step, origin[1] + j as f64 * step];
            let sp = waves.surface(x0, t);
            let s = DVec3::from(sp.position);
            let f = s - (s.y / sun.y) * sun;
            foot.push(DVec2::new(f.x, f.z));
            // Light goes from air into water: no total internal reflection possible.
            let dir = refract(sun, DVec3::from(sp.normal), N_AIR, N_WATER).unwrap_or(sun);
            let l = s + ((-depth - s.y) / dir.y) * dir;
            land.push(DVec2::new(l.x, l.z));
        }
    }
    let cell = region.size / out_res as f64;
    let mut intensity = vec![0.0; out_res * out_res];
    let tri_area = |a: DVec2, b: DVec2, c: DVec2| 0.5 * (b - a).perp_dot(c - a);
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let k = j * n + i;
            for tri in [[k, k + 1, k + n + 1], [k, k + n + 1, k + n]] {
                let src = tri_area(foot[tri[0]], foot[tri[1]], foot[tri[2]]).abs();
                let signed = tri_area(land[tri[0]], land[tri[1]], land[tri[2]]);
                if signed == 0.0 {
                    continue;
                }
                let ratio = (src / signed.abs()).min(MAX_INTENSITY);
                // Counter-clockwise order, so that "inside" is the left of every edge.
                let tri = if signed > 0.0 {
                    tri
                } else {
                    [tri[0], tri[2], tri[1]]
                };
                splat_triangle(&land, tri, ratio, &region, out_res, cell, &mut intensity);
            }
        }
    }
    CausticMap {
        region,
        n: out_res,
        intensity,
    }
}

/// Irradiance is capped here (times the flat-water value): at an exact focus the area ratio is
/// infinite, and a real sun (0.53° wide) and the water's own blur keep caustics finite.
pub const MAX_INTENSITY: f64 = 50.0;

/// Add `value` to every output cell whose centre lies inside the triangle `tri` (indices into
/// `pts`, counter-clockwise). A centre on an edge shared by two triangles counts once: each edge
/// is evaluated in one canonical direction (lower vertex index first), so both triangles see the
/// same number with opposite signs, and a tie goes to the triangle that traverses the edge in the
/// canonical direction.
fn splat_triangle(
    pts: &[DVec2],
    tri: [usize; 3],
    value: f64,
    region: &CausticRegion,
    out_res: usize,
    cell: f64,
    out: &mut [f64],
) {
    let [a, b, c] = tri.map(|q| pts[q]);
    let lo = a.min(b).min(c);
    let hi = a.max(b).max(c);
    let min = DVec2::from(region.min);
    // Cell-centre indices (unwrapped) whose centres fall in the bounding box.
    let i0 = ((lo.x - min.x) / cell - 0.5).ceil() as i64;
    let i1 = ((hi.x - min.x) / cell - 0.5).floor() as i64;
    let j0 = ((lo.y - min.y) / cell - 0.5).ceil() as i64;
    let j1 = ((hi.y - min.y) / cell - 0.5).floor() as i64;
    let edges = [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])];
    let n = out_res as i64;
    for j in j0..=j1 {
        for i in i0..=i1 {
            let (wi, wj) = if region.periodic {
                (i.rem_euclid(n), j.rem_euclid(n))
            } else if (0..n).contains(&i) && (0..n).contains(&j) {
                (i, j)
            } else {
                continue;
            };
            let p = min + DVec2::new(i as f64 + 0.5, j as f64 + 0.5) * cell;
            let inside = edges.iter().all(|&(u, v)| {
                let (s, e, forward) = if u < v { (u, v, true) } else { (v, u, false) };
                let side = (pts[e] - pts[s]).perp_dot(p - pts[s]);
                let side = if forward { side } else { -side };
                side > 0.0 || (side == 0.0 && forward)
            });
            if inside {
                out[wj as usize * out_res + wi as usize] += value;
            }
        }
    }
}

/// Angular radius of the cheap tier's sun disc, radians (`CHEAP_SUN_RADIUS` in WGSL, which
/// `caustics.wgsl`'s `overhead_sun` uses).
pub const CHEAP_SUN_RADIUS: f64 = 0.1;

/// The cheap tier's brightness at a table point under flat water lit from straight above
/// (the AR water thesis's, after GPU Gems): the vertical ray from the table meets the water plane directly
/// above, is bent by the surface normal there, and looks up a sun map: here a Gaussian disc
/// of angular radius `sun_radius` (radians; the shader's is [`CHEAP_SUN_RADIUS`]) around the
/// zenith, standing in for the thesis's sun texture. Under total internal reflection (the normal tilted
/// beyond the critical angle, 48.6°) no sun is seen: 0 up to e^{−(π/2)²/ρ²}.
pub fn overhead_sun(normal: DVec3, sun_radius: f64) -> f64 {
    // Looking up from below the water: refract the upward ray out into the air.
    let up = refract(DVec3::Y, normal, N_WATER, N_AIR).unwrap_or(DVec3::ZERO);
    let angle = up.y.clamp(-1.0, 1.0).acos();
    (-(angle / sun_radius).powi(2)).exp()
}

/// The AR water thesis's trick to make the black of the caustic texture transparent without a branch:
/// alpha = clamp(r + g + b, 0, 1).
pub fn caustic_alpha(rgb: [f64; 3]) -> f64 {
    (rgb[0] + rgb[1] + rgb[2]).clamp(0.0, 1.0)
}

/// How much the cheap tier's sun adds to flat water's light at full alpha (`CHEAP_SUN_GAIN` in
/// WGSL, which `caustics.wgsl`'s `caustic_light` uses): the AR water thesis's blend strength.
pub const CHEAP_SUN_GAIN: f64 = 0.8;

/// The cheap tier's light on a table point relative to flat water, `normal` the surface normal
/// above it: 1 + gain · alpha · sun, the grey sun map's alpha by [`caustic_alpha`].
pub fn cheap_caustic_light(normal: DVec3) -> f64 {
    let sun = overhead_sun(normal, CHEAP_SUN_RADIUS);
    1.0 + CHEAP_SUN_GAIN * caustic_alpha([sun; 3]) * sun
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean::{Wave, WaveSet};

    fn sea(waves: &[([f64; 2], f64, f64)]) -> WaveSet {
        WaveSet {
            gravity: 9.81,
            depth: None,
            waves: waves
                .iter()
                .map(|&(direction, steepness, wavelength)| Wave {
                    direction,
                    steepness,
                    wavelength,
                    phase: 0.3,
                })
                .collect(),
        }
    }

    #[test]
    fn the_view_region_is_cut_to_the_water() {
        let water = [-30.0, -30.0, 30.0, 30.0];
        // A view 136 m wide around the middle: the play area and its margin, no more.
        let r = CausticRegion::in_view([0.0, 0.0], 136.0, water, 6.0);
        assert_eq!((r.min, r.size), ([-36.0, -36.0], 72.0));
        // A narrow view inside the water keeps its own square.
        let r = CausticRegion::in_view([10.0, -5.0], 20.0, water, 6.0);
        assert_eq!((r.min, r.size), ([0.0, -15.0], 20.0));
        // A view over the edge: from the view's side to the grown edge.
        let r = CausticRegion::in_view([30.0, 0.0], 40.0, water, 6.0);
        assert_eq!((r.min, r.size), ([10.0, -20.0], 40.0));
        // A view beside the water: the whole play area.
        let r = CausticRegion::in_view([200.0, 0.0], 20.0, water, 6.0);
        assert_eq!((r.min, r.size), ([-36.0, -36.0], 72.0));
    }

    #[test]
    fn flat_water_gives_uniform_unit_light_from_any_sun_angle() {
        let flat = sea(&[]);
        let region = CausticRegion {
            min: [-1.0, -1.0],
            size: 2.0,
            periodic: true,
        };
        for sun in [DVec3::NEG_Y, DVec3::new(0.5, -1.0, 0.2)] {
            let map = area_ratio(&flat, 12.0, sun, 0.4, region, 32, 16);
            for v in &map.intensity {
                assert!((v - 1.0).abs() < 1e-9, "{v}");
            }
        }
    }

    #[test]
    fn light_is_conserved_over_a_periodic_patch_at_any_race_time() {
        // Waves whose wavelengths divide the 8 m patch: the sea repeats, so no light is lost.
        let waves = sea(&[([1.0, 0.0], 0.25, 4.0), ([0.0, 1.0], 0.2, 8.0 / 3.0)]);
        let region = CausticRegion {
            min: [0.0, 0.0],
            size: 8.0,
            periodic: true,
        };
        let sun = DVec3::new(0.3, -1.0, 0.1);
        for t in [0.0, 7.3, 3600.0] {
            let map = area_ratio(&waves, t, sun, 1.5, region, 96, 32);
            assert!(
                (map.mean() - 1.0).abs() < 0.01,
                "t = {t}: mean {}",
                map.mean()
            );
            // And the waves really focus light: bright lines and dark gaps.
            assert!(map.max() > 1.5, "t = {t}: max {}", map.max());
            let min = map.intensity.iter().copied().fold(f64::MAX, f64::min);
            assert!(min < 0.9, "t = {t}: min {min}");
        }
    }

    #[test]
    fn caustics_match_linear_theory_for_a_gentle_swell() {
        // A small sinusoid y = A sin(kx) lit from straight above bends each ray towards the
        // nearer crest by about (1 − 1/n) times the slope, so the light on the table at depth D
        // moves by δ(x) = D (1 − 1/n) A k cos(kx) and its irradiance is 1 / (1 + δ'(x)) =
        // 1 / (1 − D (1 − 1/n) A k² sin(kx)): each crest focuses like a convex lens, each
        // trough spreads the light, to first order in the slope.
        let lambda = 8.0;
        let k = std::f64::consts::TAU / lambda;
        let steep = 0.01; // kA
        let focus = 0.5; // D (1 − 1/n) A k²
        let depth = focus / ((1.0 - 1.0 / N_WATER) * steep * k);
        let waves = WaveSet {
            gravity: 9.81,
            depth: None,
            waves: vec![Wave {
                direction: [1.0, 0.0],
                steepness: steep,
                wavelength: lambda,
                phase: 0.0,
            }],
        };
        let region = CausticRegion {
            min: [0.0, 0.0],
            size: lambda,
            periodic: true,
        };
        let map = area_ratio(&waves, 0.0, DVec3::NEG_Y, depth, region, 512, 64);
        let predicted_max = 1.0 / (1.0 - focus);
        let predicted_min = 1.0 / (1.0 + focus);
        let (lo, hi) = map
            .intensity
            .iter()
            .fold((f64::MAX, 0.0f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        assert!(
            (hi / predicted_max - 1.0).abs() < 0.05,
            "max {hi} vs {predicted_max}"
        );
        assert!(
            (lo / predicted_min - 1.0).abs() < 0.05,
            "min {lo} vs {predicted_min}"
        );
        // The bright line sits under the crest (x = λ/4 at t = 0, where δ = 0), the dark one
        // under the trough.
        let crest = map.at(0.25 * lambda, 1.0).unwrap();
        assert!(crest > 0.97 * predicted_max, "{crest}");
        let trough = map.at(0.75 * lambda, 1.0).unwrap();
        assert!(trough < 1.03 * predicted_min, "{trough}");
    }

    #[test]
    fn caustics_scrub_with_race_time() {
        let waves = sea(&[([1.0, 0.0], 0.2, 4.0)]);
        let region = CausticRegion {
            min: [0.0, 0.0],
            size: 4.0,
            periodic: true,
        };
        let at = |t| area_ratio(&waves, t, DVec3::NEG_Y, 0.8, region, 64, 16).intensity;
        let period = std::f64::consts::TAU / waves.waves[0].omega(9.81, None);
        let (a, b, c) = (at(100.0), at(100.0 + period), at(100.0 + period / 3.0));
        let diff = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max)
        };
        assert!(
            diff(&a, &b) < 1e-6,
            "one wave period later the caustics repeat"
        );
        assert!(
            diff(&a, &c) > 0.1,
            "a third of a period later they have moved"
        );
    }

    #[test]
    fn a_non_periodic_region_counts_light_bent_in_from_outside() {
        let waves = sea(&[([0.8, 0.6], 0.15, 3.0), ([-0.6, 0.8], 0.1, 2.0)]);
        let region = CausticRegion {
            min: [-2.0, -2.0],
            size: 4.0,
            periodic: false,
        };
        let map = area_ratio(&waves, 5.0, DVec3::new(0.2, -1.0, 0.0), 1.0, region, 96, 24);
        // Not exactly 1 (the square is not a period) but no dark rim from lost light.
        assert!((map.mean() - 1.0).abs() < 0.05, "{}", map.mean());
        let rim: f64 = (0..24).map(|i| map.intensity[i]).sum::<f64>() / 24.0;
        assert!(rim > 0.7, "rim {rim}");
    }

    #[test]
    fn cheap_tier_is_brightest_under_a_level_surface_and_alpha_clamps() {
        assert!((overhead_sun(DVec3::Y, 0.1) - 1.0).abs() < 1e-12);
        let tilted = (DVec3::Y + DVec3::X * 0.1).normalize();
        let a = overhead_sun(tilted, 0.1);
        // A normal tilted by θ sends the vertical ray out at asin(n sin θ) from the normal,
        // i.e. asin(n sin θ) − θ from the zenith.
        let th = 0.1f64.atan();
        let off = (N_WATER * th.sin()).asin() - th;
        assert!((a - (-(off / 0.1).powi(2)).exp()).abs() < 1e-12, "{a}");
        assert_eq!(caustic_alpha([0.0, 0.0, 0.0]), 0.0);
        assert!((caustic_alpha([0.1, 0.2, 0.3]) - 0.6).abs() < 1e-12);
        assert_eq!(caustic_alpha([0.5, 0.5, 0.5]), 1.0);
        // The light: level water sees the whole sun at full alpha, 1 + gain; a facet tilted past
        // the critical angle (48.6°) sees none, 1.
        assert!((cheap_caustic_light(DVec3::Y) - (1.0 + CHEAP_SUN_GAIN)).abs() < 1e-12);
        let steep = (DVec3::Y + DVec3::X * 60f64.to_radians().tan()).normalize();
        assert!((cheap_caustic_light(steep) - 1.0).abs() < 1e-12);
        // Between: alpha = 3·sun below a third.
        let s = overhead_sun(tilted, CHEAP_SUN_RADIUS);
        let want = 1.0 + CHEAP_SUN_GAIN * (3.0 * s).min(1.0) * s;
        assert!((cheap_caustic_light(tilted) - want).abs() < 1e-12);
    }
}
