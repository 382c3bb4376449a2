//! `regatta race` through the built binary: the docs/command-line.md JSON, the report, and bad input
//! (one sentence on stderr naming the file, non-zero exit, nothing on stdout).

mod common;

use std::path::PathBuf;

use common::{fails_with, ok_json};

fn data(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/races")
        .join(rel)
        .display()
        .to_string()
}

#[test]
fn sample_race_json_matches_the_contract_and_the_library() {
    let v = ok_json(&["race", "--t", "300"]);
    assert_eq!(v["t"], 300.0);
    assert_eq!(v["rank_basis"], "course");
    let boats = v["boats"].as_array().unwrap();
    let race = race::Race::sample();
    assert_eq!(boats.len(), race.boats.len());
    let mut keys: Vec<&str> = boats[0]
        .as_object()
        .unwrap()
        .keys()
        .map(|k| k.as_str())
        .collect();
    keys.sort();
    assert_eq!(
        keys,
        [
            "distance_m",
            "heading_deg",
            "id",
            "lat",
            "lon",
            "name",
            "position",
            "racing",
            "rank",
            "speed_mps"
        ]
    );
    for (i, b) in boats.iter().enumerate() {
        assert_eq!(b["rank"], i + 1, "sorted by rank");
        let lib = race.boats[race.boat_index(b["id"].as_str().unwrap()).unwrap()].state_at(300.0);
        assert_eq!(b["position"][0].as_f64().unwrap(), lib.position[0]);
        assert_eq!(b["position"][1].as_f64().unwrap(), lib.position[1]);
        assert_eq!(b["racing"], true);
        let h = b["heading_deg"].as_f64().unwrap();
        assert!((0.0..360.0).contains(&h));
    }
    assert_eq!(boats[0]["distance_m"], 0.0);
    assert!(
        boats
            .iter()
            .all(|b| b["distance_m"].as_f64().unwrap() >= 0.0)
    );
    // Before anyone's first fix, nobody is racing.
    let v = ok_json(&["race", "--t", "-1000"]);
    assert!(
        v["boats"]
            .as_array()
            .unwrap()
            .iter()
            .all(|b| b["racing"] == false)
    );
}

#[test]
fn valencia_lat_lon_round_trip_to_the_gpx_point() {
    let files = [
        data("valencia/2025-06-21-ESP29375-P01.gpx"),
        data("valencia/2025-06-21-ESP30782-P01.gpx"),
        data("valencia/2025-06-21-ESP30782-P01-meta-data.json"),
    ];
    // t = 600 is 11:33:29 (start 11:23:29); ESP30782 logs a point at exactly that second.
    let mut args = vec!["race", "--t", "600", "--race"];
    args.extend(files.iter().map(|s| s.as_str()));
    let v = ok_json(&args);
    let b = v["boats"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["id"] == "ESP30782")
        .unwrap()
        .clone();
    let gpx = std::fs::read_to_string(&files[1]).unwrap();
    let at = gpx.find("<time>2025-06-21T11:33:29.000Z</time>").unwrap();
    let tag = &gpx[gpx[..at].rfind("<trkpt").unwrap()..at];
    let attr = |n: &str| -> f64 {
        let s = &tag[tag.find(&format!("{n}=\"")).unwrap() + n.len() + 2..];
        s[..s.find('"').unwrap()].parse().unwrap()
    };
    assert!(
        (b["lat"].as_f64().unwrap() - attr("lat")).abs() < 1e-9,
        "{b}"
    );
    assert!(
        (b["lon"].as_f64().unwrap() - attr("lon")).abs() < 1e-9,
        "{b}"
    );
}

#[test]
fn report_names_the_gdansk_spike() {
    let v = ok_json(&[
        "race",
        "--report",
        "--race",
        &data("gdansk/2025-10-26-8_43.gpx"),
    ]);
    let rep = &v["import"]["boats"][0];
    assert_eq!(rep["samples_read"], 8650);
    assert!(rep["max_step_speed_kn"].as_f64().unwrap() <= 20.0);
    assert!(
        !rep["spikes"].as_array().unwrap().is_empty()
            || rep["frozen_removed"].as_u64().unwrap() > 0
    );
    assert!(
        v["import"]["warnings"][0]
            .as_str()
            .unwrap()
            .contains("version")
    );
}

#[test]
fn bad_input_is_one_sentence_and_a_failure() {
    let dir = std::env::temp_dir().join(format!("race-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let w = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    // Writes a race file and expects `race` to refuse it with one sentence naming `needle`.
    let refused = |name: &str, text: &str, needle: &str| {
        fails_with(&["race", "--t", "0", "--race", &w(name, text)], needle);
    };
    refused("empty.gpx", "", "empty.gpx: the file is empty.");
    refused(
        "race.txt",
        "x",
        "race.txt: starts with \"x\", which is no race format",
    );
    refused(
        "log.csv",
        "time,lat,lon\n2025-01-01 00:00:00,39.4,-0.3\n2025-01-01 00:00:01,abc,-0.3\n",
        "log.csv line 3: lat is \"abc\", not a number.",
    );
    refused(
        "nan.csv",
        "time,lat,lon\n2025-01-01 00:00:00,NaN,-0.3\n",
        "nan.csv line 2: latitude NaN",
    );
    refused(
        "nt.gpx",
        r#"<gpx version="1.1" creator="x"><trk><trkseg><trkpt lat="1" lon="2"></trkpt></trkseg></trk></gpx>"#,
        "nt.gpx: track 1 segment 1 point 1 has no <time>",
    );
    refused("bad.json", "{\"boats\": [", "bad.json line 1:");
    refused(
        "nb.json",
        r#"{"boats": [{"id": "A", "track": []}]}"#,
        "has no track points",
    );
    let g = data("valencia/2025-06-21-ESP30782-P01.gpx");
    fails_with(&["race", "--t", "0", "--race", &g, &g], "appears twice");
    fails_with(
        &["race", "--t", "0", "--race", "/nonexistent/r.gpx"],
        "/nonexistent/r.gpx: could not be read",
    );
    fails_with(&["race"], "needs --t");
    fails_with(&["race", "--t", "nan"], "--t NaN is not a finite number");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_race_without_origin_has_no_lat_lon() {
    let dir = std::env::temp_dir().join(format!("race-cli-local-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("local.json");
    std::fs::write(
        &p,
        r#"{"name": "local", "origin": null, "start_time": null,
            "boats": [{"id": "A", "track": [[0, 0, 0], [10, 30, -40]]}], "marks": []}"#,
    )
    .unwrap();
    let v = ok_json(&["race", "--t", "5", "--race", &p.display().to_string()]);
    std::fs::remove_dir_all(&dir).ok();
    let b = &v["boats"][0];
    assert!(b.get("lat").is_none() && b.get("lon").is_none(), "{b}");
    // Halfway along a straight 50 m in 10 s: (15, -20), 5 m/s, bearing atan2(3, 4) = 36.87°.
    assert_eq!(b["position"][0], 15.0);
    assert_eq!(b["position"][1], -20.0);
    assert!((b["speed_mps"].as_f64().unwrap() - 5.0).abs() < 1e-5);
    assert!((b["heading_deg"].as_f64().unwrap() - 36.869_897_6).abs() < 1e-4);
    assert_eq!(b["rank"], 1);
}

#[test]
fn a_closed_stdout_is_one_clear_error_not_a_panic() {
    for args in [
        &["race", "--t", "300"][..],
        &["probe", "--t", "1", "--at", "0,0"][..],
    ] {
        let (code, err) = common::into_closed_pipe(args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(err.contains("could not write"), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn keep_going_loads_what_would_be_refused_and_says_so_on_stderr() {
    // The Expedition log's day count read as seconds by a generic CSV.
    let text = std::fs::read_to_string(data("expedition/expedition-valencia.csv")).unwrap();
    let mut csv = String::from("t,lat,lon\n");
    for l in text.lines().skip(1).take(200) {
        let c: Vec<&str> = l.split(',').collect();
        csv.push_str(&format!("{},{},{}\n", c[0], c[37], c[38]));
    }
    let p = common::temp_file("days.csv", &csv);
    let p = p.display().to_string();
    fails_with(
        &["race", "--t", "0", "--race", &p],
        "cleaning would keep 1 of 200 samples, because",
    );
    let (code, out, err) = common::regatta(&["race", "--report", "--keep-going", "--race", &p]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("regatta: warning: ") && err.contains("loaded anyway (--keep-going)"),
        "{err}"
    );
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["import"]["boats"][0]["samples_kept"], 1);
    assert_eq!(v["rank_basis"], "no_course");
}

#[test]
fn new_formats_report_their_format_channels_and_date_source() {
    let v = ok_json(&[
        "race",
        "--report",
        "--race",
        &data("nmea-signalk/plaka.log"),
    ]);
    let f = &v["import"]["file_reports"][0];
    assert_eq!(f["format"], "NMEA 0183");
    assert_eq!(f["fixes"], 7250);
    assert!(
        f["date_source"]
            .as_str()
            .unwrap()
            .starts_with("none: the log has no date")
    );
    assert!(f["channels"].as_array().unwrap().iter().any(|c| c == "tws"));
    let v = ok_json(&[
        "race",
        "--report",
        "--race",
        &data("sailgp-auckland-2025/race_xmls/25011905_03-13-55.xml"),
        &data("sailgp-auckland-2025/boat_logs/data_NZL.csv"),
    ]);
    assert_eq!(v["course"][2], "LG1/LG2");
    assert_eq!(v["rank_basis"], "course");
    assert_eq!(v["boundary"].as_array().unwrap().len(), 12);
}

#[test]
fn marks_and_course_flags_give_a_course() {
    let marks = common::temp_file(
        "marks.csv",
        "name,lat,lon\nS1,39.40921,-0.32253\nB1,39.40691,-0.315\n",
    );
    let g = data("valencia/2025-06-21-ESP29375-P01.gpx");
    let m = marks.display().to_string();
    let v = ok_json(&[
        "race", "--report", "--race", &g, "--marks", &m, "--course", "S1,B1,S1",
    ]);
    assert_eq!(v["course"], serde_json::json!(["S1", "B1", "S1"]));
    fails_with(
        &[
            "race", "--t", "0", "--race", &g, "--marks", &m, "--course", "S1,X",
        ],
        "--course: the course names the mark \"X\", which no file defines.",
    );
    fails_with(
        &["race", "--t", "0", "--race", &g, "--session", "0"],
        "--session counts from 1",
    );
}

/// A race XML is a course: `--marks RACE.xml` and `--course RACE.xml` both race its sequence
/// (Auckland race 25011905: start line SL1/SL2, M1, the gates, finish FL1/FL2), where `--marks`
/// used to read it as GPX ("invalid child element `Race` in `gpx`").
#[test]
fn a_race_xml_is_a_course_for_marks_and_course() {
    let log = data("sailgp-auckland-2025/boat_logs/data_NZL.csv");
    let xml = data("sailgp-auckland-2025/race_xmls/25011905_03-13-55.xml");
    let beside = ok_json(&["race", "--report", "--race", &log, &xml]);
    for flag in ["--marks", "--course"] {
        let v = ok_json(&["race", "--report", "--race", &log, flag, &xml]);
        assert_eq!(v["course"], beside["course"], "{flag}");
        assert_eq!(v["course"][0], "SL1/SL2", "{flag}");
    }
}

#[test]
fn a_device_is_refused_at_once() {
    fails_with(
        &["race", "--t", "0", "--race", "/dev/zero"],
        "/dev/zero: is not a regular file",
    );
}

/// `--race`'s help names every format the importer detects (`race::import::detect::Format`:
/// native JSON, maxSail, GPX, CSV, Expedition, NMEA 0183, race XML, FIT, TCX, KML and the three
/// NMEA 2000 logs), on each command that takes race files; it once named 6 of them.
#[test]
fn race_help_names_every_format_the_importer_reads() {
    let formats = [
        "native race JSON",
        "maxSail JSON",
        "GPX",
        "CSV logs",
        "Expedition",
        "NMEA 0183",
        "race XML",
        "FIT",
        "TCX",
        "KML / KMZ",
        "candump",
        "Actisense CSV",
        "canboat JSON",
    ];
    for command in ["race", "render", "run"] {
        let (code, help, err) = common::regatta(&[command, "--help"]);
        assert_eq!(code, 0, "{err}");
        // clap wraps the help; the words are compared with the line breaks as spaces.
        let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
        for f in formats {
            assert!(
                help.contains(f),
                "regatta {command} --help lacks {f:?}: {help}"
            );
        }
    }
}
