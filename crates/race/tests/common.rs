// Shared helpers for the race crate's tests (included with `mod common;`).
#![allow(dead_code)]

use std::path::PathBuf;

/// `../shared/data/races/<rel>` relative to the workspace root.
pub fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/races")
        .join(rel)
}

pub fn load(rels: &[&str]) -> race::Race {
    let paths: Vec<PathBuf> = rels.iter().map(|r| data(r)).collect();
    race::Race::load(&paths).unwrap_or_else(|e| panic!("{rels:?}: {e}"))
}

/// Seconds between two UTC times of the same day, "HH:MM:SS.fff".
pub fn hms(s: &str) -> f64 {
    let v: Vec<f64> = s.split(':').map(|p| p.parse().unwrap()).collect();
    v[0] * 3600.0 + v[1] * 60.0 + v[2]
}

/// The proptest configuration of a fuzz or property test: a fixed seed and case count under
/// `cargo test` (deterministic), overridden by `REGATTA_FUZZ_SEED` (u64) and
/// `REGATTA_FUZZ_CASES` (u32) for long random runs (scripts/fuzz.sh). The seed is printed so
/// a failure can be replayed.
pub fn fuzz_config(name: &str, seed: u64, cases: u32) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, RngSeed};
    let env = |k: &str| std::env::var(k).ok().filter(|v| !v.trim().is_empty());
    let seed = env("REGATTA_FUZZ_SEED").map_or(seed, |v| {
        v.trim()
            .parse()
            .unwrap_or_else(|_| panic!("REGATTA_FUZZ_SEED={v:?} is not a u64"))
    });
    let cases = env("REGATTA_FUZZ_CASES").map_or(cases, |v| {
        v.trim()
            .parse()
            .unwrap_or_else(|_| panic!("REGATTA_FUZZ_CASES={v:?} is not a u32"))
    });
    eprintln!("{name}: REGATTA_FUZZ_SEED={seed} REGATTA_FUZZ_CASES={cases}");
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

/// A test whose input (a file of `../shared/data`) is missing: under CI (`CI=true`) it fails;
/// elsewhere it skips and is counted (`skip_log::unless_ci`, docs/testing.md).
pub fn skip(reason: &str) {
    skip_log::unless_ci(reason);
}
