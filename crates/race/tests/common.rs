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
