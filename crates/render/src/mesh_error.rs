//! Measured screen-space height error of a clip-map against the analytic f64 sea, and the
//! triangles it draws at a view: what the `mesh` bench compares with the clip-maps measured in the Sailing+ wave-model thesis
//! (TU Delft 2022; docs/sources.md).
//!
//! Error: for a ray through every `stride`-th pixel that meets the sea's rest plane inside the
//! play area, the height the (unmorphed) mesh draws at that rest point, linear over its
//! triangle, against the f64 sea's height there, divided by the metres one pixel spans at that
//! distance. It measures the vertical error at rest points (the horizontal displacement is
//! interpolated alike and not counted).

use glam::{DVec2, DVec3, DVec4};
use ocean::WaveSet;

use crate::camera::{Camera, Frustum};
use crate::clipmap::{ClipMapConfig, Culling};

/// The bench view.
pub struct View {
    pub camera: Camera,
    pub size: [u32; 2],
    pub play_area: [f64; 4],
    /// Distance from the eye (x, z) to the farthest play-area edge, metres.
    pub reach: f64,
}

/// The bench's standard view: an eye 12 m up looking 150 m ahead, 1280 × 720 px, over a 2 km
/// play area.
pub fn bench_view() -> View {
    let camera = Camera::look_at(
        DVec3::new(0.0, 12.0, 0.0),
        DVec3::new(0.0, 0.0, -150.0),
        20_000.0,
    );
    View {
        camera,
        size: [1280, 720],
        play_area: [-1000.0, -1000.0, 1000.0, 1000.0],
        reach: 1000.0,
    }
}

/// Measured error of a mesh: max, 99th percentile and mean in pixels over the sample rays.
#[derive(Debug, Clone, Copy)]
pub struct Measured {
    pub max_px: f64,
    pub p99_px: f64,
    pub mean_px: f64,
    pub samples: usize,
    /// Distance from the eye of the sample with the largest error, metres.
    pub worst_distance: f64,
    /// Rays that meet the play area where the map has no mesh (a hole in the water; not in
    /// the statistics above, so a map is only comparable when this is 0).
    pub uncovered: usize,
}

/// Measure the height error of `cfg` (waves `kept[level]` per level) at `view`, at time `t`.
pub fn measure(
    sea: &WaveSet,
    cfg: &ClipMapConfig,
    kept: &[Vec<usize>],
    view: &View,
    t: f64,
    stride: u32,
) -> Measured {
    let cam = &view.camera;
    let eye = DVec2::new(cam.eye.x, cam.eye.z);
    let aspect = f64::from(view.size[0]) / f64::from(view.size[1]);
    let inv = cam.view_proj_local(DVec2::ZERO, aspect).inverse();
    let [ax, az, bx, bz] = view.play_area;
    let mut errs = Vec::new();
    let mut uncovered = 0;
    for py in (0..view.size[1]).step_by(stride as usize) {
        for px in (0..view.size[0]).step_by(stride as usize) {
            let ndc = [
                (f64::from(px) + 0.5) / f64::from(view.size[0]) * 2.0 - 1.0,
                1.0 - (f64::from(py) + 0.5) / f64::from(view.size[1]) * 2.0,
            ];
            let n = inv * DVec4::new(ndc[0], ndc[1], 0.0, 1.0);
            let f = inv * DVec4::new(ndc[0], ndc[1], 1.0, 1.0);
            let (a, b) = (n.truncate() / n.w, f.truncate() / f.w);
            if b.y >= a.y || a.y <= 0.0 {
                continue;
            }
            let p = a + (b - a) * (a.y / (a.y - b.y));
            let x0 = DVec2::new(p.x, p.z);
            if x0.x < ax || x0.x > bx || x0.y < az || x0.y > bz {
                continue;
            }
            let Some(h) = cfg.interpolated_height(sea, kept, eye, x0, t) else {
                uncovered += 1;
                continue;
            };
            let truth = sea.displace([x0.x, x0.y], t)[1];
            let d = (p - cam.eye).length();
            errs.push(((h - truth).abs() * cam.pixels_per_metre(d, view.size[1]), d));
        }
    }
    errs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let worst_distance = errs.last().map_or(0.0, |e| e.1);
    let errs: Vec<f64> = errs.into_iter().map(|e| e.0).collect();
    let n = errs.len();
    Measured {
        max_px: errs.last().copied().unwrap_or(0.0),
        p99_px: errs.get(n * 99 / 100).copied().unwrap_or(0.0),
        mean_px: errs.iter().sum::<f64>() / n.max(1) as f64,
        samples: n,
        worst_distance,
        uncovered,
    }
}

/// Triangles Regatta draws for `cfg` at `view` (frustum and play-area culling).
pub fn regatta_triangles(sea: &WaveSet, cfg: &ClipMapConfig, view: &View) -> u64 {
    let cam = &view.camera;
    let eye = DVec2::new(cam.eye.x, cam.eye.z);
    let origin = cfg.origin_for(eye);
    let aspect = f64::from(view.size[0]) / f64::from(view.size[1]);
    let culling = Culling {
        frustum: Some(Frustum::from_matrix(cam.view_proj_local(origin, aspect))),
        play_area: Some(view.play_area),
        max_displacement: sea.total_amplitude(),
    };
    cfg.triangles_drawn(eye, &culling)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clipmap::{ErrorTarget, LevelRatio};

    #[test]
    fn chosen_maps_cover_every_sample_of_the_play_area() {
        // The lattice is turned (the default sea's is), so covering the play area's corners
        // takes a wider map than the world-axis reach: a hole would hide error from `measure`.
        let sea = WaveSet::default_sea();
        let view = bench_view();
        for px in [0.3, 1.0, 4.0] {
            let target = ErrorTarget::uniform(px, view.size[1], view.camera.fov_y);
            let cfg = ClipMapConfig::for_view(&sea, &target, view.camera.eye.y, view.reach);
            assert!(cfg.angle != 0.0, "the test needs a turned lattice");
            let kept: Vec<Vec<usize>> = cfg
                .plan(&sea, &target, view.camera.eye.y)
                .into_iter()
                .map(|p| p.kept)
                .collect();
            let m = measure(&sea, &cfg, &kept, &view, 10.0, 16);
            assert_eq!(m.uncovered, 0, "{px} px: {cfg:?}");
            assert!(m.samples > 1000);
            // The map's error is measured against the sea: within a few times the target.
            assert!(
                m.max_px > 0.05 * px && m.max_px < 4.0 * px,
                "{px}: {}",
                m.max_px
            );
        }
        // A map that stops short of the play area leaves uncovered rays, and says so.
        let short = ClipMapConfig {
            ratio: LevelRatio::DOUBLING,
            ..ClipMapConfig::uniform(3, 64, 1.0)
        };
        let kept = vec![(0..sea.waves.len()).collect::<Vec<_>>(); 3];
        let m = measure(&sea, &short, &kept, &view, 10.0, 16);
        assert!(
            m.uncovered > 100 && m.samples > 0,
            "{} / {}",
            m.uncovered,
            m.samples
        );
    }
}
