//! Criterion bench of the wake's per-frame work: building the GPU source buffer for a fleet,
//! and evaluating a point in f64 and with the f32 mirror of shaders/wake.wgsl.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use ocean::wake::{TrackSample, Wake, WakeParams, WakeView, wake_height_f32};

/// A fleet of `n` boats sailing circles of 200 m radius at 3–6 m/s for 10 minutes.
fn fleet(n: usize) -> Vec<Vec<TrackSample>> {
    (0..n)
        .map(|b| {
            let u = 3.0 + 3.0 * (b as f64 / n as f64);
            (0..=600)
                .map(|i| {
                    let t = i as f64;
                    let a = u * t / 200.0 + b as f64;
                    TrackSample {
                        t,
                        x: 40.0 * b as f64 + 200.0 * a.cos(),
                        z: -30.0 * b as f64 + 200.0 * a.sin(),
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
    // A 300 m view centred on boat 0 at t (sample 500 of its track).
    let o = [tracks[0][500].x, tracks[0][500].z];
    let view = WakeView::around(o, 150.0);
    c.bench_function("wake gpu_sources, 35 boats", |b| {
        b.iter(|| black_box(wake.gpu_sources(black_box(t), o, &view, 1e-6)))
    });
    let frame = wake.gpu_sources(t, o, &view, 1e-6);
    eprintln!(
        "{} sources alive, {} in view, cull bound {:.1e} m",
        wake.active(t).count(),
        frame.sources.len(),
        frame.cull_bound
    );
    c.bench_function("wake height f32, one point behind boat 0", |b| {
        b.iter(|| black_box(wake_height_f32(&frame.sources, black_box([-10.0, -5.0]))))
    });
    c.bench_function("wake height f64, one point behind boat 0", |b| {
        b.iter(|| black_box(wake.height(black_box([o[0] - 10.0, o[1] - 5.0]), t)))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
