//! Error messages quote input escaped and cut (issue 15): no raw newline, CR, ESC, BEL or NUL
//! from a file reaches the terminal, and internal type names do not either. Also the hangs
//! and the clearer messages: `/dev/zero`, folders, a byte-order mark, a huge track point.

mod common;
use race::{LoadOptions, Race};

fn err(name: &str, text: &[u8]) -> String {
    let m = Race::from_files(&[(name, text)]).unwrap_err().to_string();
    assert!(
        !m.chars().any(char::is_control),
        "raw control character in {m:?}"
    );
    assert!(m.ends_with('.'), "{m:?}");
    m
}

#[test]
fn quoted_input_is_escaped_and_cut() {
    // start_time with ESC and a terminal colour sequence.
    let m = err(
        "r.json",
        br#"{"start_time": "\u001b[31mred\u0007", "boats": [{"id": "A", "track": [[0,0,0]]}]}"#,
    );
    assert!(m.contains(r#""start_time" is "\u{1b}[31mred\u{7}""#), "{m}");
    // A colour with a newline, a boat id with CR, a mark name with NUL.
    let m = err(
        "r.json",
        br##"{"boats": [{"id": "A\r", "color": "#ff\n00", "track": [[0,0,0]]}]}"##,
    );
    assert_eq!(
        m,
        r##"r.json: boat "A\r" has color "#ff\n00", not #rrggbb."##
    );
    let m = err(
        "r.json",
        br#"{"boats": [{"id": "A", "track": [[0,0,0]]}], "marks": [{"name": "M\u0000", "position": [1e300, 0]}]}"#,
    );
    assert!(
        m.starts_with(r#"r.json: marks[0] ("M\u{0}"): x = 1e300 is beyond"#),
        "{m}"
    );
    // A long value is cut to 40 characters.
    let long = "x".repeat(500);
    let json =
        format!(r#"{{"start_time": "{long}", "boats": [{{"id": "A", "track": [[0,0,0]]}}]}}"#);
    let m = err("r.json", json.as_bytes());
    assert!(
        m.contains(&format!("\"{}…\"", "x".repeat(40))) && m.len() < 200,
        "{m}"
    );
    // A quoted CSV cell with a newline inside.
    let m = err("c.csv", b"time,lat,lon\n2025-01-01 00:00:00,\"4\n5\",1\n");
    assert_eq!(m, r#"c.csv line 2: lat is "4\n5", not a number."#);
    // A file name with a newline and an escape.
    let m = err(
        "a\nb\u{1b}.gpx",
        b"<gpx version=\"1.1\"><trk><trkseg><trkpt lat=\"1\"></trk></gpx>",
    );
    assert!(m.starts_with(r"a\nb\u{1b}.gpx line 1:"), "{m}");
}

#[test]
fn messages_name_things_in_the_domain_not_rust_types() {
    // Before: "invalid type: integer `3`, expected struct JsonRace".
    let m = err("r.json", b"3");
    assert_eq!(
        m,
        "r.json line 1: not a race file: invalid type: integer `3`, expected a race object with \"boats\"."
    );
    let m = err("r.json", br#"{"boats": [3]}"#);
    assert!(
        m.contains("expected a boat object with \"id\" and \"track\""),
        "{m}"
    );
    assert!(!m.contains("struct"), "{m}");
}

#[test]
fn a_byte_order_mark_before_json_is_accepted() {
    let mut json = b"\xEF\xBB\xBF".to_vec();
    json.extend_from_slice(br#"{"boats": [{"id": "A", "track": [[0,0,0],[1,1,0]]}]}"#);
    let r = Race::from_files(&[("bom.json", &json)]).unwrap();
    assert_eq!(r.boats[0].fixes().len(), 2);
}

#[test]
fn a_finite_but_huge_track_point_is_called_what_it_is() {
    let m = err(
        "h.json",
        br#"{"boats": [{"id": "A", "track": [[0,1e200,0]]}]}"#,
    );
    assert_eq!(
        m,
        "h.json: boat \"A\" track[0]: x = 1e200 is beyond ±1e9 (metres from the origin, or seconds): no race is that large."
    );
}

#[test]
fn devices_and_folders_are_refused_before_reading() {
    // /dev/zero never ends: refused from its metadata, at once.
    let e = Race::load(&["/dev/zero".into()]).unwrap_err().to_string();
    assert_eq!(
        e,
        "/dev/zero: is not a regular file (a folder or a device); a race file is a file."
    );
    let dir = std::env::temp_dir();
    let e = Race::load(std::slice::from_ref(&dir))
        .unwrap_err()
        .to_string();
    assert!(
        e.ends_with("is not a regular file (a folder or a device); a race file is a file."),
        "{e}"
    );
    // Binary content is refused by its first bytes, whatever the extension.
    let m = err("x.gpx", b"\x7fELF\x00\x01\x02");
    assert!(
        m.contains("holds binary data (a NUL byte), not text"),
        "{m}"
    );
    assert_eq!(race::MAX_FILE_BYTES, 1 << 30);
    let _ = LoadOptions::default();
}
