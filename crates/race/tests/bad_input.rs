//! Every bad input gives one sentence naming the file (and the line or field), never a panic.

mod common;
use race::Race;

fn err(files: &[(&str, &str)]) -> String {
    let f: Vec<(&str, &[u8])> = files.iter().map(|(n, t)| (*n, t.as_bytes())).collect();
    match Race::from_files(&f) {
        Ok(_) => panic!("{files:?} was accepted"),
        Err(e) => {
            let m = e.to_string();
            assert!(
                !m.contains('\n') && m.ends_with('.'),
                "not one sentence: {m:?}"
            );
            m
        }
    }
}

fn real(rel: &str) -> String {
    std::fs::read_to_string(common::data(rel)).unwrap()
}

const GPX_HEAD: &str = r#"<?xml version="1.0"?><gpx version="1.1" creator="t" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>"#;

#[test]
fn empty_files() {
    for name in ["a.gpx", "a.csv", "a.json"] {
        let m = err(&[(name, "")]);
        assert!(m.contains(name) && m.contains("empty"), "{m}");
        let m = err(&[(name, " \n\n")]);
        assert!(m.contains("empty"), "{m}");
    }
}

#[test]
fn truncated_files() {
    let gpx = real("valencia/2025-06-21-ESP30782-P01.gpx");
    let m = err(&[("v.gpx", &gpx[..gpx.len() / 2])]);
    // The line where the file ends, and what is missing there.
    let lines = gpx[..gpx.len() / 2].lines().count();
    assert!(
        m.starts_with(&format!("v.gpx line {lines}: not valid GPX: XML error")),
        "{m}"
    );
    let json = r#"{"name": "x", "origin": null, "start_time": null, "boats": [{"id": "A", "track": [[0, 1"#;
    let m = err(&[("r.json", json)]);
    assert!(m.starts_with("r.json line 1:"), "{m}");
    // A CSV cut in the middle of a row: the last row has too few cells (line named).
    let csv = real("sailgp-auckland-2025/boat_logs/data_CAN.csv");
    let cut = &csv[..csv.len() - 300];
    let lines = cut.lines().count();
    let m = err(&[("data_CAN.csv", cut)]);
    assert!(m.starts_with(&format!("data_CAN.csv line {lines}:")), "{m}");
    assert!(m.contains("cells where the header has 45"), "{m}");
}

#[test]
fn malformed_files() {
    let m = err(&[(
        "m.gpx",
        "<gpx version=\"1.1\"><trk><trkseg><trkpt lat=\"1\"></trk></gpx>",
    )]);
    assert_eq!(
        m,
        "m.gpx line 1: not valid GPX: <trkpt> has no lon (longitude)."
    );
    let m = err(&[("m.gpx", "hello")]);
    assert!(m.starts_with("m.gpx: not valid GPX"), "{m}");
    let m = err(&[("m.json", "{\"name\": 3}")]);
    assert!(
        m.starts_with("m.json line 1:") && m.contains("invalid type"),
        "{m}"
    );
    let m = err(&[("m.json", "{\"boats\": []}\n")]);
    assert!(m.contains("m.json") && m.contains("no boats"), "{m}");
    let m = err(&[(
        "m.json",
        "{\n\"boats\": [{\"id\": \"A\", \"track\": [[0, 1]]}]}",
    )]);
    assert!(m.starts_with("m.json line 2:"), "{m}");
    let m = err(&[("m.csv", "a,b,c\n1,2,3\n")]);
    assert!(m.starts_with("m.csv line 1: the header has no time"), "{m}");
    let m = err(&[("m.csv", "time,lat,lon\n2025-13-45 99:00:00,1,2\n")]);
    assert!(
        m.starts_with("m.csv line 2: time is \"2025-13-45 99:00:00\", not a time"),
        "{m}"
    );
    let m = err(&[("m.csv", "time,lat,lon\n0,1,2\n2025-01-01 00:00:00,1,2\n")]);
    assert!(m.starts_with("m.csv line 3:"), "{m}");
}

#[test]
fn gpx_without_times() {
    let g = format!("{GPX_HEAD}<trkpt lat=\"39.4\" lon=\"-0.3\"></trkpt></trkseg></trk></gpx>");
    let m = err(&[("nt.gpx", &g)]);
    assert_eq!(
        m,
        "nt.gpx: track 1 segment 1 point 1 has no <time>; a race track needs a time on every point."
    );
}

#[test]
fn csv_cell_that_is_not_a_number() {
    let mut csv = real("sailgp-auckland-2025/boat_logs/data_NZL.csv");
    // Line 6 (the 5th row): make its latitude a word.
    let mut lines: Vec<String> = csv.lines().map(String::from).collect();
    let mut cells: Vec<&str> = lines[5].split(',').collect();
    cells[3] = "abc";
    lines[5] = cells.join(",");
    csv = lines.join("\n");
    let m = err(&[("data_NZL.csv", &csv)]);
    assert_eq!(
        m,
        "data_NZL.csv line 6: LATITUDE_GPS_unk is \"abc\", not a number."
    );
}

#[test]
fn nan_latitude() {
    let m = err(&[("n.csv", "time,lat,lon\n2025-01-01 00:00:00,NaN,2\n")]);
    assert_eq!(
        m,
        "n.csv line 2: latitude NaN is not a number in [-90, 90]."
    );
    let g = format!(
        "{GPX_HEAD}<trkpt lat=\"NaN\" lon=\"-0.3\"><time>2025-01-01T00:00:00Z</time></trkpt></trkseg></trk></gpx>"
    );
    let m = err(&[("n.gpx", &g)]);
    // The gpx crate refuses it without a line ("error while casting to f64"); the second
    // pass names the line and the field.
    assert_eq!(
        m,
        "n.gpx line 1: not valid GPX: <trkpt> lat is \"NaN\", not a latitude in [-90, 90]."
    );
    let m = err(&[(
        "n.json",
        r#"{"origin": {"lat": 95, "lon": 0}, "boats": [{"id": "A", "track": [[0,0,0]]}]}"#,
    )]);
    assert_eq!(
        m,
        "n.json: \"origin\": latitude 95 is not a number in [-90, 90]."
    );
}

#[test]
fn boat_with_no_points() {
    let m = err(&[("e.json", r#"{"boats": [{"id": "A", "track": []}]}"#)]);
    assert_eq!(m, "e.json: boat \"A\" (boats[0]) has no track points.");
    let g = format!("{GPX_HEAD}</trkseg></trk></gpx>");
    let m = err(&[("e.gpx", &g)]);
    assert_eq!(m, "e.gpx: track 1 (boat e) has no points.");
    let m = err(&[("e.csv", "time,lat,lon\n")]);
    assert!(
        m.starts_with("e.csv: the log has a header but no rows"),
        "{m}"
    );
}

#[test]
fn two_boats_with_the_same_id() {
    let gpx = real("valencia/2025-06-21-ESP30782-P01.gpx");
    let m = err(&[("a/ESP30782-P01.gpx", &gpx), ("b/ESP30782-P02.gpx", &gpx)]);
    assert_eq!(
        m,
        "boat id \"ESP30782\" appears twice (a/ESP30782-P01.gpx and b/ESP30782-P02.gpx); every boat needs its own id."
    );
    let m = err(&[(
        "d.json",
        r#"{"boats": [{"id": "A", "track": [[0,0,0]]}, {"id": "A", "track": [[0,0,0]]}]}"#,
    )]);
    assert!(m.contains("\"A\" appears twice"), "{m}");
}

#[test]
fn unknown_file_extension() {
    let m = err(&[("race.txt", "whatever")]);
    assert_eq!(
        m,
        "race.txt: starts with \"whatever\", which is no race format this program reads; a race file is GPX, FIT, TCX, KML or KMZ, native race JSON, CSV, an Expedition log, an NMEA 0183 or NMEA 2000 log or a SailGP / AC race XML (any of them may be gzipped)."
    );
    let m = err(&[("race", "whatever")]);
    assert!(m.starts_with("race: starts with \"whatever\""), "{m}");
}

#[test]
fn other_bad_fields() {
    let m = err(&[(
        "c.json",
        r##"{"boats": [{"id": "A", "color": "red", "track": [[0,0,0]]}]}"##,
    )]);
    assert!(m.contains("color \"red\""), "{m}");
    let m = err(&[(
        "c.json",
        r#"{"boats": [{"id": "A", "track": [[0,0,0]]}], "course": ["X"]}"#,
    )]);
    assert!(m.contains("the course names the mark \"X\""), "{m}");
    let m = err(&[(
        "c.json",
        r#"{"start_time": "yesterday", "boats": [{"id": "A", "track": [[0,0,0]]}]}"#,
    )]);
    assert!(m.contains("\"start_time\" is \"yesterday\""), "{m}");
    let m = err(&[(
        "c.json",
        r#"{"boats": [{"id": "A", "track": [[0,1e300,0]]}]}"#,
    )]);
    assert!(m.contains("track[0]"), "{m}");
    // Invalid UTF-8: line named.
    let f: Vec<(&str, &[u8])> = vec![("u.csv", b"time,lat,lon\n\xff\xfe,1,2\n")];
    let m = Race::from_files(&f).unwrap_err().to_string();
    assert_eq!(m, "u.csv line 2: the text is not valid UTF-8.");
    assert!(
        Race::load(&["/nonexistent/x.gpx".into()])
            .unwrap_err()
            .to_string()
            .starts_with("/nonexistent/x.gpx: could not be read")
    );
}
