//! The proptest configuration every property test of this crate uses (see docs/testing.md).
//!
//! Under `cargo test` (scripts/test.sh, CI) a test runs a fixed case count from a fixed seed, so
//! CI is deterministic. scripts/fuzz.sh sets `REGATTA_FUZZ_SEED` (u64) and `REGATTA_FUZZ_CASES`
//! (u32) to run the same properties long with random seeds. The seed and case count go to
//! stderr, which the test harness shows only for a failing test: a failure names its seed.
//! Failure-persistence files are off: a case a fuzz run finds becomes a plain `#[test]`.

use proptest::test_runner::{Config, RngSeed};

/// `fixed_seed` and `cases` apply unless the environment overrides them.
pub fn fuzz_config(fixed_seed: u64, cases: u32) -> Config {
    let seed = env_number("REGATTA_FUZZ_SEED").unwrap_or(fixed_seed);
    let cases = env_number("REGATTA_FUZZ_CASES").map_or(cases, |n: u64| {
        u32::try_from(n).expect("REGATTA_FUZZ_CASES exceeds u32")
    });
    eprintln!(
        "proptest: seed {seed}, {cases} cases (replay: REGATTA_FUZZ_SEED={seed} REGATTA_FUZZ_CASES={cases})"
    );
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

fn env_number(name: &str) -> Option<u64> {
    let value = std::env::var(name).ok()?;
    Some(
        value
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("{name}={value:?} is not an unsigned integer")),
    )
}
