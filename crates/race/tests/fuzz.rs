//! Fuzz-style: random bytes and mutations of the real files never panic the importer (they
//! load or give a one-line error without control characters). 10,000+ cases in the default
//! run: 4,000 random byte strings under each extension mix and 6,000 mutations of real files
//! of every format (cut to keep each case fast). Fixed seeds under `cargo test`;
//! `REGATTA_FUZZ_SEED` / `REGATTA_FUZZ_CASES` for long random runs (scripts/fuzz.sh).

mod common;
mod mutation;

use mutation::{apply, edit};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;
use race::Race;

fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    // The first n bytes, ended after the last complete element or row.
    let cut = |rel: &str, n: usize| {
        let b = std::fs::read(common::data(rel)).unwrap();
        let b = &b[..b.len().min(n)];
        let end = if rel.ends_with(".gpx") {
            b"</trkpt>".as_slice()
        } else {
            b"\n"
        };
        let at = b.windows(end.len()).rposition(|w| w == end).unwrap() + end.len();
        b[..at].to_vec()
    };
    let mut gpx = cut("valencia/2025-06-21-ESP29375-P01.gpx", 6000);
    gpx.extend_from_slice(b"</trkseg></trk></gpx>");
    let mut gdansk = cut("gdansk/2025-10-26-8_43.gpx", 5000);
    gdansk.extend_from_slice(b"</trkseg></trk></gpx>");
    let xml = std::fs::read(common::data(
        "sailgp-auckland-2025/race_xmls/25011905_03-13-55.xml",
    ))
    .unwrap();
    vec![
        ("v.gpx", gpx),
        ("g.gpx", gdansk),
        ("data_ITA.csv", cut("sailgp-auckland-2025/boat_logs/data_ITA.csv", 6000)),
        (
            "m.json",
            std::fs::read(common::data("valencia/2025-06-21-ESP30782-P01-meta-data.json")).unwrap(),
        ),
        (
            "r.json",
            br##"{"name": "x", "origin": {"lat": 39.4, "lon": -0.3}, "start_time": "2025-06-21T11:23:29Z",
                "boats": [{"id": "A", "color": "#ff0000", "track": [[0, 0, 0], [1, 2, 3], [2, 4, 1], [3, 5, 5]]},
                          {"id": "B", "track": [[0, 10, 0], [2, 12, 3]], "heel": [1, 2]}],
                "marks": [{"name": "S", "position": [0, 0]}, {"name": "W", "position": [3, 3]}],
                "course": ["S", "W", "S"], "wind": {"from_deg": 10, "speed_mps": 4}}"##
                .to_vec(),
        ),
        ("plaka.log", cut("nmea-signalk/plaka.log", 6000)),
        ("expedition.csv", cut("expedition/expedition-valencia.csv", 6000)),
        ("race.xml", xml),
    ]
}

/// Seeds that hold no boat load beside a track of their racing area (an index into seeds()).
fn companion(name: &str) -> Option<usize> {
    match name {
        "m.json" => Some(0),
        "race.xml" => Some(2),
        _ => None,
    }
}

/// Load (if the bytes are a race) and query; returns whether it loaded.
fn exercise(files: &[(&str, &[u8])]) -> bool {
    match Race::from_files(files) {
        Ok(r) => {
            // A race that loads answers queries anywhere without panicking.
            let (t0, t1) = r.time_span();
            let mut s = Vec::new();
            for t in [t0 - 1.0, t0, 0.5 * (t0 + t1), t1, t1 + 1.0, f64::NAN] {
                r.states_at(t, &mut s);
                let _ = r.standings(t);
            }
            true
        }
        Err(e) => {
            let m = e.to_string();
            assert!(
                !m.chars().any(char::is_control) && m.ends_with('.'),
                "not one printable sentence: {m:?}"
            );
            false
        }
    }
}

/// The fixed seeds of this file (SEEDS.md): any u64, chosen once.
const RANDOM_BYTES_SEED: u64 = 0x5EED_0017_0001;
const MUTATIONS_SEED: u64 = 0x5EED_0017_0002;

/// What the insertions put into a file: this test's formats' syntax.
const SYNTAX: &[&[u8]] = &[
    b"NaN",
    b"-",
    b"1e999",
    b",",
    b"<",
    b"\"",
    b"]",
    b"\n",
    b"<trkpt lat=\"1\" lon=\"2\">",
    b"9",
    b"0",
    b"}",
];

#[test]
fn random_bytes_never_panic() {
    let cfg = common::fuzz_config("random_bytes_never_panic", RANDOM_BYTES_SEED, 4000);
    let cases = cfg.cases as usize;
    let mut runner = TestRunner::new(cfg);
    let n = std::cell::Cell::new(0);
    runner
        .run(
            &(
                prop::collection::vec(any::<u8>(), 0..400),
                prop::sample::select(vec![
                    "a.gpx", "a.csv", "a.json", "a.txt", "a", "a.log", "a.xml",
                ]),
            ),
            |(bytes, ext)| {
                n.set(n.get() + 1);
                exercise(&[(ext, &bytes)]);
                Ok(())
            },
        )
        .unwrap();
    assert_eq!(n.get(), cases);
}

#[test]
fn mutated_real_files_never_panic() {
    let seeds = seeds();
    for (name, bytes) in &seeds {
        // The meta-data file has marks but no boats: it loads beside a track.
        let k = companion(name).unwrap_or(0);
        let with: &[(&str, &[u8])] = &[(name, bytes), (seeds[k].0, &seeds[k].1)];
        let files = if companion(name).is_some() {
            with
        } else {
            &with[..1]
        };
        assert!(exercise(files), "seed {name} must load");
    }
    let cfg = common::fuzz_config("mutated_real_files_never_panic", MUTATIONS_SEED, 6000);
    let cases = cfg.cases as usize;
    let mut runner = TestRunner::new(cfg);
    let (n, loaded) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
    runner
        .run(
            &(
                0usize..seeds.len(),
                prop::option::of(0usize..seeds.len()),
                prop::collection::vec(edit(SYNTAX), 1..4),
            ),
            |(which, also, edits)| {
                let (name, bytes) = &seeds[which];
                let m = apply(bytes.clone(), &edits);
                let mut files: Vec<(&str, &[u8])> = vec![(name, &m)];
                if let Some(k) = also.filter(|k| *k != which) {
                    files.push((seeds[k].0, &seeds[k].1));
                }
                n.set(n.get() + 1);
                loaded.set(loaded.get() + exercise(&files) as usize);
                Ok(())
            },
        )
        .unwrap();
    let (n, loaded) = (n.get(), loaded.get());
    eprintln!("{loaded} of {n} mutated races loaded");
    assert_eq!(n, cases);
    // Enough mutations survive parsing to reach cleaning, interpolation and ranking.
    assert!(10 * loaded > cases, "{loaded}");
}

/// The case a random seed found on CI (issue 15): a JSON key `"\name"` (a real newline once
/// decoded) was echoed by serde's "unknown field" message, so the error spanned two lines.
#[test]
fn regression_json_key_with_a_newline_is_escaped() {
    let json = br#"{"\name": "x", "boats": [{"id": "A", "track": [[0, 0, 0]]}]}"#;
    let m = Race::from_files(&[("r.json", json)])
        .unwrap_err()
        .to_string();
    assert_eq!(
        m,
        "r.json line 1: not a race file: unknown field `\\name`, expected one of `name`, `origin`, `start_time`, `boats`, `marks`, `course`, `wind`."
    );
}
