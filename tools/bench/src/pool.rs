//! Bench section `pool`: the pool scene's frame cost as a ratio to the race scene's water-only
//! frame (same GPU, same size, measured interleaved in one run), and the caustics map's
//! resolution against the light it conserves and its GPU f32 error against the f64 reference.

use std::time::Instant;

use pool::caustics::CausticMap;
use pool::{PoolFrame, PoolRenderer, PoolScene, PoolSettings, PoolView, render_pool_image};
use render::{Gpu, OFFSCREEN_FORMAT, RenderOptions, Renderer, Scene};
use serde_json::json;

use crate::{BenchContext, Table, offscreen};
use regatta::error::{AppError, AppResult};

/// The race scene with nothing but its sea: no boats, no marks, a camera over the water.
fn water_only_scene(t: f64) -> Scene {
    Scene {
        marks: vec![],
        ..render::golden::test_scene(t, vec![])
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ratio_table(ctx: &BenchContext, gpu: &Gpu) -> Table {
    let sizes: &[[u32; 2]] = if ctx.quick {
        &[[320, 180]]
    } else {
        &[[640, 360], [1280, 720]]
    };
    let reps = if ctx.quick { 5 } else { 21 };
    let mut table = Table::new(
        "pool_frame_ratio",
        "Pool frame cost relative to the race scene's water-only frame",
        &[
            "size",
            "race water frame ms",
            "pool frame ms",
            "ratio pool / race",
        ],
    );
    let settings = PoolSettings::default();
    let scene = PoolScene::default();
    for &size in sizes {
        ctx.progress(format!("pool: {}x{} frames", size[0], size[1]));
        let target = offscreen(gpu, size);
        let mut race = Renderer::new(
            gpu,
            OFFSCREEN_FORMAT,
            RenderOptions {
                measure_gpu_time: false,
                ..Default::default()
            },
        );
        let mut pool = PoolRenderer::new(gpu, OFFSCREEN_FORMAT, settings);
        let view = PoolView::default_desktop(size);
        let (mut race_ms, mut pool_ms) = (Vec::new(), Vec::new());
        // Interleaved, after one warm-up frame each, so both see the same machine state.
        for i in 0..=reps {
            let t = 100.0 + i as f64 * 0.04;
            let water = water_only_scene(t);
            let t0 = Instant::now();
            // A failed frame is logged by the renderer (and would show in the times).
            let _ = race.render(gpu, &target, size, &water);
            gpu.wait();
            let r = t0.elapsed().as_secs_f64() * 1e3;
            let t0 = Instant::now();
            let frame = PoolFrame::new(&scene, t, &view, &settings);
            pool.render(gpu, &target, &frame);
            gpu.wait();
            let p = t0.elapsed().as_secs_f64() * 1e3;
            if i > 0 {
                race_ms.push(r);
                pool_ms.push(p);
            }
        }
        let (r, p) = (median(race_ms), median(pool_ms));
        table.row(vec![
            json!(format!("{}x{}", size[0], size[1])),
            json!(r),
            json!(p),
            json!(p / r),
        ]);
    }
    table.note(format!(
        "Wall time per frame (CPU planning + GPU, waiting for the GPU), median of {reps} \
         interleaved frames on {}. The pool frame is: the caustics map ({}² surface cells into \
         {}² texels), the full-screen ray trace of spheres and box, and the {}² water mesh \
         whose fragments trace reflection and refraction.",
        gpu.describe(),
        settings.caustic_grid,
        settings.caustic_size,
        settings.water_grid,
    ));
    table
}

fn caustics_table(ctx: &BenchContext, gpu: &Gpu) -> AppResult<Table> {
    let mut table = Table::new(
        "pool_caustics",
        "Caustics map: resolution against conserved light and GPU f32 error",
        &[
            "surface cells per side",
            "texels per side",
            "entered / flat-water light (f64)",
            "landed / entered light (f64)",
            "GPU flux error vs f64",
            "GPU L1 error / flux",
        ],
    );
    let scene = PoolScene::default();
    let t = 3.0;
    let rings = scene.rings(t);
    let entered = {
        // Flux through the flat surface: T(θ) cos θ times the pool's area (E = 1).
        let f = render::optics::fresnel(scene.to_light.y, 1.0, scene.ior);
        f.t * scene.to_light.y * 4.0 * scene.pool.half_x * scene.pool.half_z
    };
    let grids: &[(u32, u32)] = if ctx.quick {
        &[(64, 128), (160, 256)]
    } else {
        &[(32, 64), (64, 128), (128, 256), (160, 256), (256, 512)]
    };
    for &(grid, texels) in grids {
        let settings = PoolSettings {
            caustic_grid: grid,
            caustic_size: texels,
            ..PoolSettings::default()
        };
        let reference = CausticMap::compute(
            &scene,
            t,
            &rings,
            grid as usize,
            texels as usize,
            texels as usize,
        );
        let mut r = PoolRenderer::new(gpu, OFFSCREEN_FORMAT, settings);
        let frame = PoolFrame::new(&scene, t, &PoolView::default_desktop([64, 64]), &settings);
        render_pool_image(gpu, &mut r, &frame)
            .map_err(|e| AppError::new(format!("the pool bench could not render: {e}")))?;
        let got = r.read_caustics(gpu).map_err(|e| {
            AppError::new(format!("the pool bench could not read the caustics: {e}"))
        })?;
        let texel = reference.texel_size(0) * reference.texel_size(1);
        let flux = reference.total_flux();
        let gpu_flux = got.iter().map(|&v| f64::from(v)).sum::<f64>() * texel;
        let l1 = got
            .iter()
            .zip(&reference.texels)
            .map(|(&g, &w)| (f64::from(g) - w).abs())
            .sum::<f64>()
            * texel;
        table.row(vec![
            json!(grid),
            json!(texels),
            json!(reference.entered / entered),
            json!(flux / reference.entered),
            json!((gpu_flux / flux - 1.0).abs()),
            json!(l1 / flux),
        ]);
    }
    table.note(
        "Entered light is Σ T·A⊥ over the surface triangles; flat water lets in \
         T(θ)·cos θ·(pool area). Landed light is the map's integral: texel centres sample the \
         landing triangles, so near a focus (triangles smaller than a texel) it keeps the light \
         only on average; triangles whose corners land on two walls are dropped. The GPU draws \
         the same triangles in f32 into a half-float map (area ratio from the screen \
         derivatives of the surface position, exact for a triangle); its error against the f64 \
         reference is texels whose centre an f32 edge puts on the other side.",
    );
    Ok(table)
}

/// The `pool` section.
pub fn run(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let gpu = match Gpu::headless(wgpu::Backends::all()) {
        Ok(g) => g,
        Err(e) => {
            let mut t = Table::new("pool_frame_ratio", "Pool frame cost (no GPU)", &["note"]);
            t.row(vec![json!(format!("skipped: {e}"))]);
            return Ok(vec![t]);
        }
    };
    Ok(vec![ratio_table(ctx, &gpu), caustics_table(ctx, &gpu)?])
}
