//! Criterion: one boat's state, every boat's state and the leaderboard on the sample race, and
//! loading the sample (parse + clean + derive). The 50-boat scale run is `regatta bench --only race`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use race::Race;

fn bench(c: &mut Criterion) {
    let race = Race::sample();
    let (t0, t1) = race.time_span();
    let mut t = t0;
    let step = (t1 - t0) / 997.0;
    let mut next_t = move || {
        t += step;
        if t > t1 {
            t = t0;
        }
        t
    };
    c.bench_function("boat.state_at", |b| {
        b.iter(|| black_box(race.boats[0].state_at(black_box(next_t()))))
    });
    let mut states = Vec::with_capacity(race.boats.len());
    c.bench_function("race.states_at (8 boats)", |b| {
        b.iter(|| {
            race.states_at(black_box(next_t()), &mut states);
            black_box(&states);
        })
    });
    let mut standings = Vec::with_capacity(race.boats.len());
    c.bench_function("states_at + standings_into (8 boats)", |b| {
        b.iter(|| {
            let t = next_t();
            race.states_at(t, &mut states);
            race.standings_into(t, &states, &mut standings);
            black_box(&standings);
        })
    });
    c.bench_function("Race::sample() load", |b| {
        b.iter(|| black_box(Race::sample()))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
