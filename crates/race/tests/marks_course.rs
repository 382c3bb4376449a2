//! GPX sessions, routes as marks, `--marks FILE` and `--course A,B,C` (a gate as `A/B`).

mod common;
use race::{LoadOptions, MarkKind, Race};

const HEAD: &str = r#"<?xml version="1.0"?><gpx version="1.0" creator="GPSBabel" xmlns="http://www.topografix.com/GPX/1/0">"#;

/// A track point every second for `n` s from `start` (RFC 3339 without the seconds'
/// fraction), sailing north at 2 m/s from `lat`, `lon`.
fn points(start: &str, n: usize, lat: f64, lon: f64) -> String {
    let t0 =
        time::OffsetDateTime::parse(start, &time::format_description::well_known::Rfc3339).unwrap();
    (0..n)
        .map(|i| {
            let t = t0 + time::Duration::seconds(i as i64);
            let t = t
                .format(&time::format_description::well_known::Rfc3339)
                .unwrap();
            let la = lat + 2.0 * i as f64 / 111_195.0;
            format!("<trkpt lat=\"{la:.7}\" lon=\"{lon}\"><time>{t}</time></trkpt>")
        })
        .collect()
}

/// Boat A: sessions on 2024-06-01 and 2024-06-02 (one track, two segments); boat B on 06-02.
fn two_days() -> (String, String) {
    let a = format!(
        "{HEAD}<trk><trkseg>{}</trkseg><trkseg>{}</trkseg></trk></gpx>",
        points("2024-06-01T10:00:00Z", 600, 39.40, -0.30),
        points("2024-06-02T10:00:00Z", 900, 39.41, -0.30)
    );
    let b = format!(
        "{HEAD}<trk><trkseg>{}</trkseg></trk></gpx>",
        points("2024-06-02T10:00:30Z", 600, 39.41, -0.301)
    );
    (a, b)
}

fn files<'a>(list: &'a [(&'a str, &'a str)]) -> Vec<(&'a str, &'a [u8])> {
    list.iter().map(|(n, t)| (*n, t.as_bytes())).collect()
}

#[test]
fn a_track_of_several_days_races_the_session_that_overlaps_the_others() {
    let (a, b) = two_days();
    let r = Race::from_files(&files(&[("A.gpx", &a), ("B.gpx", &b)])).unwrap();
    let ia = r.boat_index("A").unwrap();
    assert_eq!(r.boats[ia].fixes().len(), 900);
    assert_eq!(r.report.start_time.as_deref(), Some("2024-06-02T10:00:30Z"));
    assert!(
        r.report
            .warnings
            .iter()
            .any(|w| w.contains("boat \"A\" has 2 sessions") && w.contains("session 2 was raced"))
    );
    assert_eq!(r.report.file_reports[0].format, "GPX 1.0");
    // --session 1: the first day.
    let opts = LoadOptions {
        session: Some(1),
        ..LoadOptions::default()
    };
    let r = Race::from_files_with(&files(&[("A.gpx", &a)]), &opts).unwrap();
    assert_eq!(r.boats[0].fixes().len(), 600);
    assert_eq!(r.report.start_time.as_deref(), Some("2024-06-01T10:00:00Z"));
    let opts = LoadOptions {
        session: Some(3),
        ..LoadOptions::default()
    };
    let e = Race::from_files_with(&files(&[("A.gpx", &a)]), &opts)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "A.gpx: --session 3: boat \"A\" has sessions 1 to 2.");
}

#[test]
fn routes_and_waypoints_become_marks() {
    let (_, b) = two_days();
    let route = b.replace(
        "</gpx>",
        r#"<rte><rtept lat="39.42" lon="-0.30"><name>W</name></rtept><rtept lat="39.41" lon="-0.29"></rtept></rte></gpx>"#,
    );
    let r = Race::from_files(&files(&[("B.gpx", &route)])).unwrap();
    let names: Vec<&str> = r.course_marks().map(|m| m.name.as_str()).collect();
    assert_eq!(names, vec!["fleet at the start", "W", "RT1-2"]);
}

#[test]
fn marks_files_in_three_formats_and_a_course_with_a_gate() {
    let (_, b) = two_days();
    let csv = "name,lat,lon\nS,39.4100,-0.3005\nG1a,39.4150,-0.3010\nG1b,39.4150,-0.3000\nF,39.4110,-0.3005\n";
    let json = r#"[{"name": "S", "lat": 39.41, "lon": -0.3005}, {"name": "G1a", "lat": 39.415, "lon": -0.301},
        {"name": "G1b", "lat": 39.415, "lon": -0.3}, {"name": "F", "lat": 39.411, "lon": -0.3005}]"#;
    let gpx = format!(
        "{HEAD}<wpt lat=\"39.41\" lon=\"-0.3005\"><name>S</name></wpt><wpt lat=\"39.415\" lon=\"-0.301\"><name>G1a</name></wpt>\
         <wpt lat=\"39.415\" lon=\"-0.3\"><name>G1b</name></wpt><wpt lat=\"39.411\" lon=\"-0.3005\"><name>F</name></wpt></gpx>"
    );
    let course: Vec<String> = ["S", "G1a/G1b", "F"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut positions = Vec::new();
    for (name, text) in [("m.csv", csv), ("m.json", json), ("m.gpx", gpx.as_str())] {
        let opts = LoadOptions {
            marks: Some((name.to_string(), text.as_bytes().to_vec())),
            course: Some(course.clone()),
            ..LoadOptions::default()
        };
        let r = Race::from_files_with(&files(&[("B.gpx", &b)]), &opts)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let c: Vec<(&str, MarkKind)> = r
            .course_marks()
            .map(|m| (m.name.as_str(), m.kind))
            .collect();
        assert_eq!(
            c,
            vec![
                ("S", MarkKind::Mark),
                ("G1a/G1b", MarkKind::Gate),
                ("F", MarkKind::Mark)
            ],
            "{name}"
        );
        let gate = r.course_marks().nth(1).unwrap();
        // Its middle is 0.005° north of S: 556 m (1° of latitude = 111.2 km near 39° N).
        let s = r.course_marks().next().unwrap().position;
        assert!(
            ((s[1] - gate.position[1]) - 556.0).abs() < 2.0,
            "{:?}",
            gate.position
        );
        positions.push(gate.ends.unwrap());
        // Boat B (the start: its first fix) sails north at 2 m/s from 39.41: through the gate
        // 556 m on, at 278 s.
        let t = r.boats[0].roundings()[1].unwrap();
        assert!((t - 278.0).abs() < 2.0, "{t}");
    }
    assert_eq!(positions[0], positions[1]);
    assert_eq!(positions[0], positions[2]);
    // An unknown mark in --course names it.
    let opts = LoadOptions {
        marks: Some(("m.csv".into(), csv.as_bytes().to_vec())),
        course: Some(vec!["S".into(), "X\n".into()]),
        ..LoadOptions::default()
    };
    let e = Race::from_files_with(&files(&[("B.gpx", &b)]), &opts)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "--course: the course names the mark \"X\\n\", which no file defines."
    );
    // A bad marks row names its line.
    let opts = LoadOptions {
        marks: Some(("m.csv".into(), b"S,39.4,abc\n".to_vec())),
        ..LoadOptions::default()
    };
    let e = Race::from_files_with(&files(&[("B.gpx", &b)]), &opts)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "m.csv line 1: lon is \"abc\", not a number.");
}
