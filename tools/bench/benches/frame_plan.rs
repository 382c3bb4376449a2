//! Criterion bench of the CPU's per-frame plan (`render::frame::FrameContext::new`: the
//! clip-map chosen for the view, planned and built and culled, the waves' phases reduced, each
//! level's vertex waves, the frame uniform) on the budget model's frame: the sample race at
//! t = 600 s, the OPPO A54's screen at each tier's render scale and mesh error. The renderer
//! does this every frame before the wake binning (`wake_binning.rs`).
//!
//! `cargo bench -p regatta-bench --bench frame_plan` (release).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use quality::Tier;
use regatta::tier_render::TierRender;
use render::frame::FrameContext;

/// Race time of the frame, s (the budget model's).
const T: f64 = 600.0;
/// The OPPO A54's screen.
const SCREEN: [u32; 2] = [720, 1600];

fn bench(c: &mut Criterion) {
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), T, None);
    for tier in [Tier::Ultra, Tier::Low] {
        let render = TierRender::of(tier);
        let scale = render.options.render_scale;
        let drawn = SCREEN.map(|v| ((f64::from(v) * scale).round() as u32).max(1));
        let error_px = render.options.error_px;
        let frame = FrameContext::new(&scene, drawn, error_px);
        eprintln!(
            "{tier}: {}×{} drawn, {} levels, {} mesh vertices, {} triangles",
            drawn[0],
            drawn[1],
            frame.levels.len(),
            frame.mesh.vertices.len(),
            frame.mesh.indices.len() / 3
        );
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
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
