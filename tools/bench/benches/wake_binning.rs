//! Criterion bench of the CPU's per-frame plan (`frame_plan TIER`: `FrameContext::new`, the
//! clip-map chosen for the view, planned, built and culled, the waves' phases reduced, the
//! frame uniform) and wake work (`render::renderer::bin_wakes`) on the
//! sample race's busiest frame (t = 600 s, 2,033 sources; built as `regatta bench --only
//! budget-model` builds it: `world::scene_at`, the tier's wake and mesh error, the OPPO A54's
//! screen at the tier's render scale), whole and in its three parts: the sources alive and in
//! view (`Wake::gpu_sources`), where each clip-map level's vertices can land
//! (`SampleSpacing::of_mesh`) and the binning within the byte cap (`wake_bins::fit`).
//!
//! `cargo bench -p regatta-bench --bench wake_binning` (release), or with `--profile dev` for
//! the debug build's figures (opt-level 1, as `regatta bench`'s timed column sees it).

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use glam::DVec2;
use quality::Tier;
use regatta::tier_render::TierRender;
use render::frame::FrameContext;
use render::renderer::WAKE_EPSILON_M;
use render::wake_bins::{WAKE_BUFFER_BUDGET_BYTES, WakeBinner};
use render::wake_spacing::SampleSpacing;

/// Race time of the frame, s: the sample race's busiest wakes.
const T: f64 = 600.0;
/// The OPPO A54's screen.
const SCREEN: [u32; 2] = [720, 1600];

fn bench(c: &mut Criterion) {
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), T, None);
    for tier in [Tier::Ultra, Tier::Low] {
        let render = TierRender::of(tier);
        let wake = render.race_wake(&race).expect("the sample race's wake");
        // The size the renderer draws at (`Renderer::render`: the screen at the render scale).
        let scale = render.options.render_scale;
        let drawn = SCREEN.map(|v| ((f64::from(v) * scale).round() as u32).max(1));
        let error_px = render.options.error_px;
        c.bench_function(&format!("frame_plan {tier}"), |b| {
            b.iter(|| {
                black_box(
                    FrameContext::new(&scene, drawn, error_px)
                        .mesh
                        .vertices
                        .len(),
                )
            })
        });
        let mut frame = FrameContext::new(&scene, drawn, error_px);
        let budget = render.wake_source_budget;
        // One binner for every frame, each frame's bins handed back, as the renderer does.
        let mut binner = WakeBinner::default();
        render::renderer::bin_wakes(
            &wake,
            WAKE_BUFFER_BUDGET_BYTES,
            budget,
            &mut binner,
            &mut frame,
        );
        eprintln!(
            "{tier}: {}×{} drawn, {} mesh vertices, {} sources kept ({} dropped), {} bins, \
             {} indices",
            drawn[0],
            drawn[1],
            frame.mesh.vertices.len(),
            frame.wakes.sources.len(),
            frame.wake_drop.dropped,
            frame.wake_bins.bins.len(),
            frame.wake_bins.indices.len()
        );
        c.bench_function(&format!("bin_wakes {tier}"), |b| {
            b.iter(|| {
                binner.recycle(std::mem::take(&mut frame.wake_bins));
                render::renderer::bin_wakes(
                    &wake,
                    WAKE_BUFFER_BUDGET_BYTES,
                    budget,
                    &mut binner,
                    &mut frame,
                );
                black_box(frame.wake_bins.indices.len())
            })
        });
        // The three parts, with the inputs `bin_wakes` gives them.
        let eye = DVec2::new(scene.camera.eye.x, scene.camera.eye.z);
        let reach = frame.clipmap.half_extent(frame.clipmap.levels() - 1);
        let view = ocean::wake::WakeView::around([eye.x, eye.y], reach);
        let origin = [frame.origin.x, frame.origin.y];
        c.bench_function(&format!("gpu_sources {tier}"), |b| {
            b.iter(|| black_box(wake.gpu_sources(T, origin, &view, WAKE_EPSILON_M)))
        });
        let displacement: f64 = scene.sea.waves.iter().map(|w| w.amplitude()).sum();
        c.bench_function(&format!("of_mesh {tier}"), |b| {
            b.iter(|| {
                black_box(SampleSpacing::of_mesh(
                    &frame.clipmap,
                    &frame.mesh,
                    eye,
                    displacement,
                ))
            })
        });
        let sources = wake.gpu_sources(T, origin, &view, WAKE_EPSILON_M);
        let spacing = SampleSpacing::of_mesh(&frame.clipmap, &frame.mesh, eye, displacement);
        let half = reach as f32 * 2.0;
        c.bench_function(&format!("fit {tier}"), |b| {
            b.iter_batched_ref(
                || sources.clone(),
                |wakes| {
                    black_box(render::wake_bins::fit(
                        wakes,
                        half,
                        WAKE_BUFFER_BUDGET_BYTES,
                        budget,
                        &spacing,
                    ))
                },
                BatchSize::SmallInput,
            )
        });
        // `fit` with a binner kept from frame to frame, as the renderer bins.
        let mut binner = WakeBinner::default();
        c.bench_function(&format!("fit kept binner {tier}"), |b| {
            b.iter_batched_ref(
                || sources.clone(),
                |wakes| {
                    let (bins, drop) =
                        binner.fit(wakes, half, WAKE_BUFFER_BUDGET_BYTES, budget, &spacing);
                    let listed = bins.indices.len();
                    binner.recycle(bins);
                    black_box((listed, drop))
                },
                BatchSize::SmallInput,
            )
        });
    }
}

criterion_group! {
    name = benches;
    // Frames of tens of milliseconds in a debug build: a few seconds per figure.
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
