//! Never lose data silently (issues 15 and 17): a boat that would lose more than half of its
//! samples refuses the file with one sentence (count and likeliest reason) unless keep_going;
//! every drop is a warning in the report. Also: the racing-area check, boats split by id,
//! duplicate tracks merged, and the native JSON spike rule.

mod common;
use race::{LoadOptions, Race, RankBasis};

fn read(rel: &str) -> String {
    std::fs::read_to_string(common::data(rel)).unwrap()
}

fn load(files: &[(&str, &str)], keep_going: bool) -> Result<Race, String> {
    let f: Vec<(&str, &[u8])> = files.iter().map(|(n, t)| (*n, t.as_bytes())).collect();
    let opts = LoadOptions {
        keep_going,
        ..LoadOptions::default()
    };
    Race::from_files_with(&f, &opts).map_err(|e| e.to_string())
}

/// The Expedition log's Utc, Lat, Lon as a generic CSV: the day count read as seconds.
fn days_as_seconds() -> String {
    let text = read("expedition/expedition-valencia.csv");
    let mut out = String::from("t,lat,lon\n");
    for l in text.lines().skip(1) {
        let c: Vec<&str> = l.split(',').collect();
        out.push_str(&format!("{},{},{}\n", c[0], c[37], c[38]));
    }
    out
}

#[test]
fn a_day_count_read_as_seconds_is_refused_with_the_reason() {
    let e = load(&[("days.csv", &days_as_seconds())], false).unwrap_err();
    assert_eq!(
        e,
        "days.csv: boat \"days\": cleaning would keep 1 of 11,978 samples, because 11,416 of 11,978 fixes imply over 1,000 kn: is the time column in days? (--keep-going loads it anyway)."
    );
    // --keep-going loads it, and says so in the report.
    let r = load(&[("days.csv", &days_as_seconds())], true).unwrap();
    assert_eq!(r.report.boats[0].samples_kept, 1);
    assert!(
        r.report
            .warnings
            .iter()
            .any(|w| w.contains("loaded anyway (--keep-going)")),
        "{:?}",
        r.report.warnings
    );
}

/// Valencia P01 of ESP29375 (1,913 points) with every point edited by `f(index, line)`.
fn valencia_edited(f: impl Fn(usize, &str) -> String) -> String {
    let text = read("valencia/2025-06-21-ESP29375-P01.gpx");
    let mut k = 0;
    let mut out = String::new();
    for l in text.split_inclusive('\n') {
        if l.contains("<trkpt") {
            out.push_str(&f(k, l));
            k += 1;
        } else {
            out.push_str(l);
        }
    }
    assert_eq!(k, 1913);
    out
}

#[test]
fn all_equal_timestamps_are_refused() {
    // Every <time> the same: 1,913 samples would merge into 1.
    let text = read("valencia/2025-06-21-ESP29375-P01.gpx");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(a) = rest.find("<time>") {
        out.push_str(&rest[..a]);
        out.push_str("<time>2025-06-21T11:18:34Z");
        let b = rest[a..].find("</time>").unwrap() + a;
        rest = &rest[b..];
    }
    out.push_str(rest);
    let e = load(&[("same.gpx", &out)], false).unwrap_err();
    assert!(
        e.contains("cleaning would keep 1 of 1,913 samples, because 1,912 of 1,913 samples repeat the timestamp before them"),
        "{e}"
    );
}

#[test]
fn rows_at_zero_zero_are_refused_and_never_move_the_origin() {
    // CAN: 628 rows; 622 of them at (0, 0) as a receiver without a fix writes.
    let text = read("sailgp-auckland-2025/boat_logs/data_CAN.csv");
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for l in lines.iter_mut().skip(7) {
        let mut c: Vec<&str> = l.split(',').collect();
        c[3] = "0";
        c[4] = "0";
        *l = c.join(",");
    }
    let csv = lines.join("\n");
    let e = load(&[("data_CAN.csv", &csv)], false).unwrap_err();
    assert!(
        e.contains(
            "cleaning would keep 6 of 628 samples, because 622 of 628 fixes are at 0° N 0° E"
        ),
        "{e}"
    );
    let r = load(&[("data_CAN.csv", &csv)], true).unwrap();
    let o = r.origin.unwrap();
    assert!(
        (o.lat + 36.83).abs() < 0.05 && (o.lon - 174.76).abs() < 0.05,
        "{o:?}"
    );
    assert_eq!(r.report.boats[0].null_island_removed, 622);
}

/// Valencia with every other point moved 0.01° (1.1 km) north.
fn shifted() -> String {
    valencia_edited(|k, l| {
        if k % 2 != 0 {
            let a = l.find("lat=\"").unwrap() + 5;
            let b = l[a..].find('"').unwrap() + a;
            let lat: f64 = l[a..b].parse().unwrap();
            format!("{}{}{}", &l[..a], lat + 0.01, &l[b..])
        } else {
            l.to_string()
        }
    })
}

#[test]
fn alternating_spikes_are_reported_and_refused_past_half() {
    // Every other point off (issue 15: 954 of 1,913 dropped with nothing said): under half,
    // so it loads, and the report says how many fixes were removed and why.
    let r = load(&[("alt.gpx", &shifted())], false).unwrap();
    let kept = r.report.boats[0].samples_kept;
    assert_eq!(kept, 957);
    assert!(
        r.report.warnings.iter().any(|w| w
            == "alt.gpx: boat alt had 956 fixes implying over 20 kn; they were removed as spikes"),
        "{:?}",
        r.report.warnings
    );
    // The reason a refusal would give for it: spikes near half of the fixes, at boat-like
    // speeds (not days read as seconds), point at two sources mixed.
    let mut rep = r.report.boats[0].clone();
    rep.spikes
        .iter_mut()
        .for_each(|s| s.implied_speed_kn = 50.0);
    assert_eq!(
        rep.loss_reason(),
        "956 of 1,913 fixes imply over 20 kn: does the track alternate between two receivers or boats?"
    );
}

#[test]
fn every_drop_is_a_warning_in_the_report() {
    // The SailGP ITA log: 4 frozen fixes and 5 spikes (data README), each rule a warning.
    let r = common::load(&["sailgp-auckland-2025/boat_logs/data_ITA.csv"]);
    let w = &r.report.warnings;
    assert!(w.iter().any(|w| w.contains("4 frozen fixes")), "{w:?}");
    assert!(
        w.iter().any(|w| w.contains("5 fixes implying over 60 kn")),
        "{w:?}"
    );
}

#[test]
fn native_json_tracks_get_the_spike_rule() {
    // A 100 km step in one second (194,000 kn) in the middle of a 3 m/s track.
    let mut track: Vec<[f64; 3]> = (0..20).map(|i| [i as f64, 3.0 * i as f64, 0.0]).collect();
    track[10][1] = 100_000.0;
    let json = serde_json::json!({"boats": [{"id": "A", "track": track}]}).to_string();
    let r = load(&[("s.json", &json)], false).unwrap();
    assert_eq!(r.boats[0].fixes().len(), 19);
    let spike = &r.report.boats[0].spikes[0];
    assert_eq!(spike.t, 10.0);
    assert!(spike.implied_speed_kn > 190_000.0, "{spike:?}");
}

#[test]
fn boats_from_two_racing_areas_are_refused_by_name() {
    let ita = read("sailgp-auckland-2025/boat_logs/data_ITA.csv");
    let val = read("valencia/2025-06-21-ESP29375-P01.gpx");
    let e = load(&[("data_ITA.csv", &ita), ("ESP29375.gpx", &val)], false).unwrap_err();
    assert!(
        e.starts_with("boats further than 50 km from the race's origin"),
        "{e}"
    );
    // The origin follows the fleet's median fix (issue 30: a glitch or a far file no longer
    // drags it between the areas): ITA's 10 Hz log outweighs the GPX, so the origin is in the
    // Hauraki Gulf and the file named is the one far from it, Valencia (19,500 km: nearly
    // antipodal).
    assert!(e.contains("race's origin (-36.8"), "{e}");
    assert!(
        e.contains("\"ESP29375\" (ESP29375.gpx, 19498 km)") && !e.contains("\"ITA\""),
        "{e}"
    );
    // Within the area, nothing is refused.
    let nzl = read("sailgp-auckland-2025/boat_logs/data_NZL.csv");
    assert!(load(&[("data_ITA.csv", &ita), ("data_NZL.csv", &nzl)], false).is_ok());
}

#[test]
fn a_csv_whose_boat_column_alternates_is_split_by_id() {
    let csv = "boat,time,lat,lon\n\
        A,2025-01-01 00:00:00,39.40000,-0.30000\n\
        B,2025-01-01 00:00:00,39.41000,-0.30000\n\
        A,2025-01-01 00:00:01,39.40001,-0.30000\n\
        B,2025-01-01 00:00:01,39.41001,-0.30000\n\
        A,2025-01-01 00:00:02,39.40002,-0.30000\n\
        B,2025-01-01 00:00:02,39.41002,-0.30000\n";
    let r = load(&[("two.csv", csv)], false).unwrap();
    let ids: Vec<&str> = r.boats.iter().map(|b| b.id.as_str()).collect();
    assert_eq!(ids, vec!["A", "B"]);
    assert!(r.boats.iter().all(|b| b.fixes().len() == 3));
    assert!(
        r.report
            .warnings
            .iter()
            .any(|w| w.contains("names 2 boats"))
    );
}

#[test]
fn the_same_track_twice_in_a_gpx_is_merged_and_reported() {
    let gpx = read("valencia/2025-06-21-ESP29375-P01.gpx");
    let a = gpx.find("<trk>").unwrap();
    let b = gpx.find("</trk>").unwrap() + "</trk>".len();
    let twice = format!("{}{}{}", &gpx[..b], &gpx[a..b], &gpx[b..]);
    let r = load(&[("twice.gpx", &twice)], false).unwrap();
    assert_eq!(r.boats.len(), 1);
    assert!(
        r.report
            .warnings
            .iter()
            .any(|w| w.contains("repeats the track of boat") && w.contains("merged")),
        "{:?}",
        r.report.warnings
    );
    assert_eq!(
        r.report.file_reports[0].dropped,
        vec![("duplicate track".to_string(), 1913)]
    );
}

#[test]
fn marks_without_a_course_race_in_the_order_listed_from_the_start() {
    // Boat A sails 60 m north toward mark N (100 m north); boat B sails 200 m south, away.
    // Before: N was taken as the start and B, with more metres sailed, led.
    let a: Vec<[f64; 3]> = (0..=60).map(|i| [i as f64, 0.0, -(i as f64)]).collect();
    let b: Vec<[f64; 3]> = (0..=60).map(|i| [i as f64, 10.0, 3.0 * i as f64]).collect();
    let json = serde_json::json!({
        "boats": [{"id": "A", "track": a}, {"id": "B", "track": b, "max_speed_kn": 30}],
        "marks": [{"name": "N", "position": [0, -100]}, {"name": "E", "position": [100, -100]}]
    })
    .to_string();
    let r = load(&[("m.json", &json)], false).unwrap();
    let names: Vec<&str> = r.course_marks().map(|m| m.name.as_str()).collect();
    assert_eq!(names, vec!["fleet at the start", "N", "E"]);
    assert_eq!(r.rank_basis(), RankBasis::Course);
    let s = r.standings(60.0);
    assert_eq!(r.boats[s[0].boat].id, "A");
    // With no marks at all there is no course rank.
    let json = serde_json::json!({"boats": [{"id": "A", "track": a}]}).to_string();
    assert_eq!(
        load(&[("n.json", &json)], false).unwrap().rank_basis(),
        RankBasis::NoCourse
    );
}
