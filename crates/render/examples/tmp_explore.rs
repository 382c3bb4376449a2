use glam::DVec2;
use ocean::WaveSet;
use render::clipmap::{ClipMapConfig, ErrorTarget};
use render::mesh_error::*;
fn main() {
    let sea = WaveSet::default_sea();
    let view = bench_view();
    let t = 1234.5;
    let all: Vec<usize> = (0..sea.waves.len()).collect();
    for (levels, res, published) in [(2u32, 50u32, 142820u64), (6, 100, 1541668), (10, 150, 5636516), (6,50,390868), (2,150,1268420)] {
        let cells = 4 * res;
        let src = ClipMapConfig::uniform(levels, cells, view.reach / (f64::from(cells / 2) * f64::from(1u32 << (levels - 1))));
        let s = measure(&sea, &src, &vec![all.clone(); levels as usize], &view, t, 8);
        let target = ErrorTarget { pixels: s.max_px.max(0.05), viewport_height: 720, fov_y: view.camera.fov_y };
        let ours = ClipMapConfig::for_view(&sea, &target, 12.0, view.reach);
        let plan = ours.plan(&sea, &target, 12.0);
        let kept: Vec<Vec<usize>> = plan.iter().map(|p| p.kept.clone()).collect();
        let m = measure(&sea, &ours, &kept, &view, t, 8);
        let tris = regatta_triangles(&sea, &ours, &view);
        println!("src {levels}x{res}: base {:.4} err max {:.3} p99 {:.3} mean {:.3} n {} | ours {:?} full {} drawn {} err max {:.3} p99 {:.3} bound {:.3} ratio {:.4}",
          src.base_cell, s.max_px, s.p99_px, s.mean_px, s.samples, (ours.levels(), &ours.cells, ours.base_cell), ours.full_triangles(), tris, m.max_px, m.p99_px,
          plan.iter().map(|p| p.error_px).fold(0.0, f64::max), tris as f64 / published as f64);
    }
    for px in [0.5, 1.0, 2.0] {
        let target = ErrorTarget { pixels: px, viewport_height: 720, fov_y: view.camera.fov_y };
        let ours = ClipMapConfig::for_view(&sea, &target, 12.0, view.reach);
        let plan = ours.plan(&sea, &target, 12.0);
        let kept: Vec<Vec<usize>> = plan.iter().map(|p| p.kept.clone()).collect();
        let m = measure(&sea, &ours, &kept, &view, t, 8);
        println!("target {px}: {:?} drawn {} meas max {:.3} bound {:?}", (ours.levels(), &ours.cells, ours.base_cell), regatta_triangles(&sea, &ours, &view), m.max_px, plan.iter().map(|p| (p.kept.len(), (p.error_px*100.0).round()/100.0)).collect::<Vec<_>>());
    }
    let _ = DVec2::ZERO;
}
