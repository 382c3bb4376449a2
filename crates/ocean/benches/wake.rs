//! Criterion bench of the wake's per-frame work: building the GPU source buffer for a fleet,
//! and evaluating a point in f64 and with the f32 mirror of shaders/wake.wgsl.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use ocean::wake::{TrackSample, Wake, WakeParams, WakeView, wake_height_f32};

/// A fleet of `n` boats sailing curved courses at 3–6 m/s for 10 minutes.
fn fleet(n: usize) -> Vec<Vec<TrackSample>> {
    (0..n)
        .map(|b| {
            let u = 3.0 + 3.0 * (b as f64 / n as f64);
            (0..=600)
                .map(|i| {
                    let t = i as f64;
                    let a = 0.002 * t * (1.0 + b as f64 * 0.1);
                    TrackSample {
                        t,
                        x: 30.0 * b as f64 + u * t * a.cos(),
                        z: -20.0 * b as f64 + u * t * a.sin(),
                    }
                })
                .collect()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let tracks = fleet(35);
    let refs: Vec<&[TrackSample]> = tracks.iter().map(|t| t.as_slice()).collect();
    let wake = Wake::new(&refs, WakeParams::default()).expect("valid fleet");
    let t = 500.0;
    let view = WakeView::around([1500.0, -300.0], 300.0);
    c.bench_function("wake gpu_sources, 35 boats", |b| {
        b.iter(|| black_box(wake.gpu_sources(black_box(t), [1500.0, -300.0], &view, 1e-6)))
    });
    let frame = wake.gpu_sources(t, [1500.0, -300.0], &view, 1e-6);
    c.bench_function("wake height f32, one point", |b| {
        b.iter(|| black_box(wake_height_f32(&frame.sources, black_box([10.0, -20.0]))))
    });
    c.bench_function("wake height f64, one point", |b| {
        b.iter(|| black_box(wake.height(black_box([1510.0, -320.0]), t)))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
