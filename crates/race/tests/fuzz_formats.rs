//! Fuzz-style: mutations of the watch, tracker and bus formats (FIT, TCX, KML, KMZ, NMEA 2000
//! candump / canboat plain / canboat JSON, gzip, Expedition sparse rows, AC35 race XML) never
//! panic the importer: each loads or gives one printable sentence. 1,000 mutated cases per
//! seed in the default run (fixed seed); `REGATTA_FUZZ_SEED` / `REGATTA_FUZZ_CASES` for long
//! runs (scripts/fuzz.sh). The byte mutations are those of fuzz.rs: flips, deletions,
//! insertions of syntax, truncation, duplication, digit changes, swapped and repeated lines.

mod common;
mod mutation;

use mutation::{apply, edit};
mod format_fixtures;

use std::io::Write;

use format_fixtures::*;
use proptest::prelude::*;
use proptest::test_runner::TestRunner;
use race::Race;

/// The fixed seed of this file (any u64, chosen once).
const FORMAT_MUTATIONS_SEED: u64 = 0x5EED_0029_0001;

fn kmz() -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    zip.start_file("doc.kml", zip::write::SimpleFileOptions::default())
        .unwrap();
    zip.write_all(kml_track_fixture().as_bytes()).unwrap();
    zip.finish().unwrap().into_inner()
}

fn sparse_expedition() -> String {
    let mut s = String::from("!Boat,Utc,Bsp,Hdg,Lat,Lon\n");
    for k in 0..10 {
        let (lat, lon) = fix(k);
        let days = 45_829.458_333 + k as f64 / 86_400.0;
        s += &format!("0,{days:.7},1,5.2,2,{},3,{lat},4,{lon}\n", 10 + k);
    }
    s
}

fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    vec![
        ("bus.log", candump_fixture().into_bytes()),
        ("capture.csv", plain_fixture().into_bytes()),
        ("analyzer.json", json_fixture().into_bytes()),
        ("bus.log.gz", gzip(candump_fixture().as_bytes())),
        ("w.tcx", tcx_fixture().into_bytes()),
        ("p.kml", kml_points_fixture().into_bytes()),
        ("t.kmz", kmz()),
        ("a.fit", fit_fixture()),
        ("exp.csv", sparse_expedition().into_bytes()),
    ]
}

/// What the insertions put into a file: this test's formats' syntax.
const SYNTAX: &[&[u8]] = &[
    b"NaN",
    b"-",
    b"1e999",
    b",",
    b"<",
    b"#",
    b"\"",
    b"\n",
    b"FF",
    b"<Placemark>",
    b"9",
    b"}",
];

/// Loads (and answers a query) or fails with one printable sentence.
fn exercise(name: &str, bytes: &[u8], with_xml: bool) {
    let xml = ac35_xml();
    let mut files: Vec<(&str, &[u8])> = vec![(name, bytes)];
    if with_xml {
        files.push(("race.xml", xml.as_bytes()));
    }
    match Race::from_files(&files) {
        Ok(r) => {
            let (t0, t1) = r.time_span();
            let mut s = Vec::new();
            r.states_at(0.5 * (t0 + t1), &mut s);
        }
        Err(e) => {
            let m = e.to_string();
            assert!(
                !m.chars().any(char::is_control) && m.ends_with('.'),
                "not one printable sentence: {m:?}"
            );
        }
    }
}

#[test]
fn mutated_watch_tracker_and_bus_files_never_panic() {
    let seeds = seeds();
    // Every seed loads unmutated (the mutations start from files that work).
    for (name, b) in &seeds {
        Race::from_files(&[(name, b)]).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    let cfg = common::fuzz_config(
        "mutated_watch_tracker_and_bus_files_never_panic",
        FORMAT_MUTATIONS_SEED,
        1000 * seeds.len() as u32,
    );
    let mut runner = TestRunner::new(cfg);
    runner
        .run(
            &(
                0..seeds.len(),
                prop::collection::vec(edit(SYNTAX), 1..4),
                any::<bool>(),
            ),
            |(k, edits, with_xml)| {
                let (name, b) = &seeds[k];
                exercise(name, &apply(b.clone(), &edits), with_xml);
                Ok(())
            },
        )
        .unwrap();
}
