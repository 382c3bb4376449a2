//! `regatta bench --only overlays`: what the race overlays cost. The frame `regatta render`
//! draws by default (the sample race at t = 600 s framed from above, sky, water, boats, no
//! wakes) against the same frame with every overlay: the overlay passes (trails with their
//! manoeuvre marks, course,
//! ahead/behind lines, wind, team rings), the CPU work that builds them (sea heights under
//! every point, the standings, the label projection) and egui's labels painted over the frame.
//! The two cases are interleaved frame by frame in one run, so a busy moment of the machine
//! falls on both alike; the ratio is the figure (goal ≤ 1.10).

use std::time::Instant;

use render::passes::segments::SegmentLayers;
use render::{OFFSCREEN_FORMAT, RenderOptions, Renderer};
use serde_json::json;

use crate::{BenchContext, Table};
use regatta::error::{AppError, AppResult};
use regatta::scene_overlay::{self, OverlaySettings};

/// Goal: all overlays together cost at most this fraction over the water-only frame.
pub const GOAL_RATIO: f64 = 1.10;

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Section `overlays`.
pub fn run(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("the overlays bench needs a GPU adapter: {e}")))?;
    let size = [1280u32, 720];
    let frames = if ctx.quick { 6 } else { 20 };
    let race = race::Race::sample();
    // Worked out once per race, as the windows do (not a per-frame cost).
    let debrief = race::Debrief::of(&race);
    let sea = regatta::setup::inputs::drawable_sea(ocean::WaveSet::default_sea());
    let options = RenderOptions::default();
    let mut plain = Renderer::new(&gpu, OFFSCREEN_FORMAT, options);
    let mut with = Renderer::new(&gpu, OFFSCREEN_FORMAT, options);
    let handle = SegmentLayers::default();
    scene_overlay::add_passes(&mut with, &gpu, &handle);
    let texture = render::gpu::texture_2d_with_views(
        &gpu.device,
        "bench overlays",
        size,
        OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
        &[OFFSCREEN_FORMAT.remove_srgb_suffix()],
    );
    let view = texture.create_view(&Default::default());
    let mut painter =
        regatta::hud::EguiPainter::for_format(&gpu.device, OFFSCREEN_FORMAT.remove_srgb_suffix());
    let settings = OverlaySettings::default();
    let ppp = scene_overlay::paint::headless_pixels_per_point(size);
    let (mut wall, mut gpu_ms) = ([Vec::new(), Vec::new()], [Vec::new(), Vec::new()]);
    let mut overlay_gpu = Vec::new();
    let fail = |e: render::GpuError| AppError::new(e.to_string());
    for i in 0..frames + 2 {
        ctx.progress(format!("overlays: frame {i} of {}", frames + 2));
        // Race time moves 1/30 s per frame, as in a playing race.
        let t = 600.0 + f64::from(i) / 30.0;
        let scene = regatta::world::scene_at(&race, &sea, t, None);
        let t0 = Instant::now();
        let water = plain.render(&gpu, &view, size, &scene).map_err(fail)?;
        gpu.wait();
        let water_s = t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        let f = scene_overlay::frame(&race, &scene, size, ppp, &settings, Some(&debrief));
        f.push(&handle);
        let all = with.render(&gpu, &view, size, &scene).map_err(fail)?;
        scene_overlay::paint::paint_over(&mut painter, &gpu, &texture, size, &f, ppp);
        gpu.wait();
        let all_s = t0.elapsed().as_secs_f64();
        if i >= 2 {
            wall[0].push(water_s * 1e3);
            wall[1].push(all_s * 1e3);
            gpu_ms[0].extend(water.gpu_ms);
            gpu_ms[1].extend(all.gpu_ms);
            overlay_gpu.push(
                all.passes
                    .iter()
                    .filter(|p| p.name.starts_with("overlay-"))
                    .filter_map(|p| p.gpu_ms)
                    .sum::<f64>(),
            );
        }
    }
    let mut t = Table::new(
        "overlays_cost",
        "Race overlays: all of them against the water-only frame",
        &[
            "frame",
            "median ms/frame",
            "ratio",
            "median GPU ms",
            "GPU ratio",
        ],
    );
    let water_ms = median(&mut wall[0]);
    let all_ms = median(&mut wall[1]);
    let (g0, g1) = (median(&mut gpu_ms[0]), median(&mut gpu_ms[1]));
    t.row(vec![
        json!("water only"),
        json!(water_ms),
        json!(1.0),
        json!(g0),
        json!(1.0),
    ]);
    let ratio = all_ms / water_ms;
    t.row(vec![
        json!("all overlays (passes + CPU + egui labels)"),
        json!(all_ms),
        json!(ratio),
        json!(g1),
        json!(g1 / g0),
    ]);
    t.note(format!(
        "{frames} frames per case of the sample race at t = 600 s (the `regatta render` view) at \
         {}×{} on {}, the two cases interleaved frame by frame in one run; each frame planned, \
         drawn and waited for. The overlay passes' own GPU time: median {:.3} ms.",
        size[0],
        size[1],
        gpu.describe(),
        median(&mut overlay_gpu)
    ));
    t.note(format!(
        "Goal: all overlays ≤ {GOAL_RATIO}× the water-only frame. Measured: {ratio:.3}× wall \
         clock ({}).",
        if ratio <= GOAL_RATIO {
            "met"
        } else {
            "NOT met"
        }
    ));
    Ok(vec![t])
}
