//! Criterion benches of the hot f64 functions: forward displacement, surface (normal and
//! Jacobian), the inverse (height at a world point) and the f32 GPU path, on the default sea
//! and on a 64-wave JONSWAP sea.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use ocean::spectrum::{SeaState, SpectralOptions};
use ocean::{WaveSet, displace_f32};

fn seas() -> Vec<(&'static str, WaveSet)> {
    let jonswap = SeaState {
        hs: 2.0,
        tp: 8.0,
        gamma: 3.3,
        direction: [1.0, 0.3],
        spreading: 8.0,
    }
    .to_sea(64, &SpectralOptions::default())
    .sea;
    vec![("default6", WaveSet::default_sea()), ("jonswap64", jonswap)]
}

fn bench(c: &mut Criterion) {
    let (p, t) = ([1234.5, -876.25], 4321.0);
    for (name, sea) in seas() {
        c.bench_function(&format!("displace/{name}"), |b| {
            b.iter(|| sea.displace(black_box(p), black_box(t)))
        });
        c.bench_function(&format!("surface/{name}"), |b| {
            b.iter(|| sea.surface(black_box(p), black_box(t)))
        });
        c.bench_function(&format!("height_at/{name}"), |b| {
            b.iter(|| sea.height_at(black_box(p), black_box(t)))
        });
        let g = sea.gpu_waves(t, [1200.0, -900.0]);
        c.bench_function(&format!("displace_f32/{name}"), |b| {
            b.iter(|| displace_f32(black_box(&g), black_box([34.5, 23.75])))
        });
        c.bench_function(&format!("gpu_waves/{name}"), |b| {
            b.iter(|| sea.gpu_waves(black_box(t), black_box([1200.0, -900.0])))
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
