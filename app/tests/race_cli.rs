//! `regatta race` through the built binary: the DESIGN.md JSON, the report, and bad input
//! (one sentence on stderr naming the file, non-zero exit, nothing on stdout).

use std::path::PathBuf;
use std::process::Command;

use serde_json::Value;

fn data(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/races")
        .join(rel)
        .display()
        .to_string()
}

fn regatta(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args(args)
        .output()
        .expect("run regatta");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn ok_json(args: &[&str]) -> Value {
    let (code, out, err) = regatta(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {out}"))
}

fn fails(args: &[&str], needle: &str) {
    let (code, out, err) = regatta(args);
    assert_ne!(code, 0, "{args:?} succeeded");
    assert!(out.is_empty(), "{args:?} wrote to stdout: {out}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
    assert!(!err.contains("panicked"));
}

#[test]
fn sample_race_json_matches_the_contract_and_the_library() {
    let v = ok_json(&["race", "--t", "300"]);
    assert_eq!(v["t"], 300.0);
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
    let empty = w("empty.gpx", "");
    fails(
        &["race", "--t", "0", "--race", &empty],
        "empty.gpx: the file is empty.",
    );
    let txt = w("race.txt", "x");
    fails(
        &["race", "--t", "0", "--race", &txt],
        "unknown file extension \".txt\"",
    );
    let csv = w(
        "log.csv",
        "time,lat,lon\n2025-01-01 00:00:00,39.4,-0.3\n2025-01-01 00:00:01,abc,-0.3\n",
    );
    fails(
        &["race", "--t", "0", "--race", &csv],
        "log.csv line 3: lat is \"abc\", not a number.",
    );
    let nan = w("nan.csv", "time,lat,lon\n2025-01-01 00:00:00,NaN,-0.3\n");
    fails(
        &["race", "--t", "0", "--race", &nan],
        "nan.csv line 2: latitude NaN",
    );
    let notime = w(
        "nt.gpx",
        r#"<gpx version="1.1" creator="x"><trk><trkseg><trkpt lat="1" lon="2"></trkpt></trkseg></trk></gpx>"#,
    );
    fails(
        &["race", "--t", "0", "--race", &notime],
        "nt.gpx: track 1 segment 1 point 1 has no <time>",
    );
    let json = w("bad.json", "{\"boats\": [");
    fails(&["race", "--t", "0", "--race", &json], "bad.json line 1:");
    let noboat = w("nb.json", r#"{"boats": [{"id": "A", "track": []}]}"#);
    fails(
        &["race", "--t", "0", "--race", &noboat],
        "has no track points",
    );
    let g = data("valencia/2025-06-21-ESP30782-P01.gpx");
    fails(&["race", "--t", "0", "--race", &g, &g], "appears twice");
    fails(
        &["race", "--t", "0", "--race", "/nonexistent/r.gpx"],
        "/nonexistent/r.gpx: could not be read",
    );
    fails(&["race"], "needs --t");
    fails(&["race", "--t", "nan"], "--t is NaN");
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
