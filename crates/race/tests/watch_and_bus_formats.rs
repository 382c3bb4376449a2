//! The readers of watch, tracker and bus files (FIT, TCX, KML/KMZ, NMEA 2000 in three text
//! forms, gzip around any of them), Expedition's sparse rows, AC35 race XML and header-named
//! marks CSV: fixtures written here from each format's published layout (the values they must
//! give are the ones written), real files where a licence allows, and the report each fills.

mod common;
mod format_fixtures;

use std::io::Write;

use format_fixtures::*;
use race::{LoadOptions, Race};

/// Unix seconds of the fixtures' first fix: 2025-06-21T11:00:00Z.
/// The fixtures' boat: 10 fixes, 1 s apart, going north at 1e-5 ° (1.11 m) a second from here.
/// The first fix's position and absolute time (Unix s) of a loaded boat.
fn first_fix(r: &Race, boat: usize) -> (f64, f64, f64) {
    let f = r.boats[boat].fixes()[0];
    let g = r.to_geo(f.pos()).expect("geographic race");
    let start = r.start_time.expect("an absolute start");
    (
        g.lat,
        g.lon,
        start.unix_timestamp() as f64 + start.nanosecond() as f64 * 1e-9 + f.t,
    )
}

fn report(r: &Race) -> &race::FileReport {
    &r.report.file_reports[0]
}

fn assert_fixture_track(r: &Race, boat: usize) {
    let (lat, lon, t) = first_fix(r, boat);
    assert!((lat - LAT0).abs() < 1e-6, "lat {lat}");
    assert!((lon - LON0).abs() < 1e-6, "lon {lon}");
    assert!((t - T0_UNIX as f64).abs() < 1e-3, "t {t}");
    assert_eq!(r.boats[boat].fixes().len(), 10);
}

// ---------------------------------------------------------------- NMEA 2000

/// A CAN id from its parts (ISO 11783: priority << 26 | PGN << 8 | source).
/// The fixture's messages at second k, as (PGN, payload), from the canboat layouts.
/// A 129029 GNSS message (43 bytes) whose position is 10 km off the track: it must be read
/// (fast-packet reassembly) and, from a second source address, counted and not kept.
/// Fast-packet frames of a message (sequence 2): frame 0 = counter, length, 6 bytes; then 7.
fn series_value(r: &Race, channel: &str) -> f32 {
    let s = r
        .series
        .iter()
        .find(|s| s.channel == channel)
        .unwrap_or_else(|| panic!("no {channel} series"));
    assert_eq!(s.v.len(), 10, "{channel}");
    s.v[0]
}

fn assert_n2k_fixture(r: &Race, format: &str) {
    assert_fixture_track(r, 0);
    let rep = report(r);
    assert_eq!(rep.format, format);
    assert_eq!(rep.fixes, 10);
    // Published resolutions: 0.01 m/s and 1e-4 rad.
    assert!((series_value(r, "aws") - 5.12).abs() < 1e-5);
    assert!((series_value(r, "awa") - 57.2958).abs() < 0.01);
    assert!((series_value(r, "heading") - 90.0).abs() < 0.01);
    assert!((series_value(r, "bsp") - 3.0).abs() < 1e-5);
    assert!((series_value(r, "sog") - 1.11).abs() < 1e-5);
    for c in ["sog", "heading", "awa", "aws", "bsp"] {
        assert!(
            rep.channels.iter().any(|x| x == c),
            "{c}: {:?}",
            rep.channels
        );
    }
}

#[test]
fn candump_fixture_decodes_each_pgn_at_its_resolution() {
    let text = candump_fixture();
    let r = Race::from_files(&[("bus.log", text.as_bytes())]).unwrap();
    assert_n2k_fixture(&r, "NMEA 2000 (SocketCAN candump)");
    // 50 single frames + 7 fast-packet frames.
    assert_eq!(report(&r).records_read, 57);
    // The reassembled 129029 was decoded: its position came from a second source, counted.
    assert!(
        report(&r)
            .dropped
            .contains(&("positions from a second GNSS source address".into(), 1)),
        "{:?}",
        report(&r).dropped
    );
}

#[test]
fn candump_with_a_lost_fast_packet_frame_counts_it() {
    let text = candump_fixture();
    // Drop frame 3 of the 129029 message.
    let lines: Vec<&str> = text.lines().collect();
    let n = lines.len();
    let kept: Vec<&str> = lines
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != n - 4)
        .map(|(_, l)| *l)
        .collect();
    let r = Race::from_files(&[("bus.log", kept.join("\n").as_bytes())]).unwrap();
    let d = &report(&r).dropped;
    assert!(
        d.contains(&("fast-packet messages with a missing frame".into(), 1)),
        "{d:?}"
    );
    assert!(!d.iter().any(|x| x.0.contains("second GNSS")), "{d:?}");
}

#[test]
fn canboat_plain_and_json_give_the_candump_track() {
    let r = Race::from_files(&[("capture.csv", plain_fixture().as_bytes())]).unwrap();
    assert_n2k_fixture(&r, "NMEA 2000 (Actisense / canboat plain CSV)");
    let r = Race::from_files(&[("analyzer.json", json_fixture().as_bytes())]).unwrap();
    assert_n2k_fixture(&r, "NMEA 2000 (canboat analyzer JSON)");
}

#[test]
fn a_log_of_mostly_unreadable_lines_is_refused() {
    let mut text = candump_fixture();
    for _ in 0..100 {
        text += "(1750503600.000000) can0 09F8012B#ZZ\n";
    }
    let e = Race::from_files(&[("bus.log", text.as_bytes())]).unwrap_err();
    assert!(
        e.to_string().contains("100 of 157 lines are not NMEA 2000"),
        "{e}"
    );
}

#[test]
fn gzip_loads_as_its_content() {
    let gz = gzip(candump_fixture().as_bytes());
    let r = Race::from_files(&[("bus.log.gz", &gz)]).unwrap();
    assert_n2k_fixture(&r, "NMEA 2000 (SocketCAN candump)");
    let gz = gzip(tcx_fixture().as_bytes());
    let r = Race::from_files(&[("watch.tcx.gz", &gz)]).unwrap();
    assert_fixture_track(&r, 0);
    // A cut gzip is one sentence, not a panic or a partial load.
    let e = Race::from_files(&[("bus.log.gz", &gz[..gz.len() / 2])]).unwrap_err();
    assert!(e.to_string().contains("gzip"), "{e}");
}

/// The real candump capture (canboat's candumpSample3.txt, Apache-2.0): a moored boat.
#[test]
fn real_candump_capture_decodes() {
    let path = common::data("../nmea2000/candumpSample3.txt");
    let Ok(bytes) = std::fs::read(&path) else {
        common::skip("../shared/data/nmea2000/candumpSample3.txt is absent");
        return;
    };
    let opts = LoadOptions {
        keep_going: true,
        ..LoadOptions::default()
    };
    let r = Race::from_files_with(&[("candumpSample3.txt", &bytes)], &opts).unwrap();
    let rep = report(&r);
    // 2,378 lines: 10 comment or blank, 2,368 frames; 165 of them PGN 129025 from 0x2B.
    assert_eq!(rep.records_read, 2_368);
    assert_eq!(rep.fixes, 165);
    assert!(rep.dropped.iter().all(|(k, _)| k != "unreadable lines"));
    // The first 129025 frame, F12B6B1B 8E5E36FF, is 46.0008433 N, 1.3214066 W.
    let (lat, lon, t) = first_fix(&r, 0);
    assert!((lat - 46.000_843_3).abs() < 1e-6 && (lon + 1.321_406_6).abs() < 1e-6);
    assert!((t - 1_502_984_866.429).abs() < 0.01, "{t}");
    // AIS reports of other vessels (fast packets 129038/129039 reassembled) are counted.
    let ais = rep
        .dropped
        .iter()
        .find(|(k, _)| k == "AIS reports of other vessels")
        .map_or(0, |x| x.1);
    assert!(ais > 0, "{:?}", rep.dropped);
    for c in ["heading_magnetic", "bsp", "sog", "awa", "aws"] {
        assert!(
            rep.channels.iter().any(|x| x == c),
            "{c}: {:?}",
            rep.channels
        );
    }
    // The EV-1's 127250 frames (09F112CC#FF725AFF7FFF7FFD): heading 0x5A72 × 1e-4 rad =
    // 132.662°, reference bits 01 = magnetic, variation 0x7FFF = not available: kept apart
    // from true headings.
    let h = r
        .series
        .iter()
        .find(|s| s.channel == "heading_magnetic")
        .unwrap();
    assert!(
        (h.v[0] as f64 - 2.3154f64.to_degrees()).abs() < 1e-3,
        "{}",
        h.v[0]
    );
    assert!(!rep.channels.iter().any(|x| x == "heading"));
}

// ---------------------------------------------------------------- TCX, KML, KMZ

#[test]
fn tcx_laps_are_one_track_named_by_the_device() {
    let r = Race::from_files(&[("2025-06-21-ESP1234.tcx", tcx_fixture().as_bytes())]).unwrap();
    assert_eq!(r.boats.len(), 1);
    assert_fixture_track(&r, 0);
    assert_eq!(r.boats[0].name, "Instinct 2");
    assert_eq!(r.boats[0].id, "ESP1234");
    let rep = report(&r);
    assert_eq!(
        rep.format,
        "TCX (Instinct 2, sport Other, 2 laps in one track)"
    );
    assert_eq!(rep.records_read, 11);
    assert!(
        rep.dropped
            .contains(&("trackpoints without a position".into(), 1))
    );
}

#[test]
fn kml_placemarks_per_fix_make_a_boat_per_folder_and_untimed_points_marks() {
    let r = Race::from_files(&[("tracker.kml", kml_points_fixture().as_bytes())]).unwrap();
    let names: Vec<&str> = r.boats.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["Alpha", "Bravo"]);
    assert_fixture_track(&r, 0);
    // The untimed placemark is a mark (the race adds its start element after it).
    let marks: Vec<&str> = r.marks.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(marks, ["Windward", "fleet at the start"]);
    assert_eq!(report(&r).fixes, 20);
}

#[test]
fn kml_gx_track_and_kmz() {
    let r = Race::from_files(&[("t.kml", kml_track_fixture().as_bytes())]).unwrap();
    assert_eq!(r.boats[0].name, "ESP30782");
    assert_fixture_track(&r, 0);
    assert!(
        report(&r)
            .dropped
            .contains(&("line points without times".into(), 2))
    );
    // The same KML zipped as a KMZ's doc.kml.
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    zip.start_file("doc.kml", zip::write::SimpleFileOptions::default())
        .unwrap();
    zip.write_all(kml_track_fixture().as_bytes()).unwrap();
    let kmz = zip.finish().unwrap().into_inner();
    let r = Race::from_files(&[("t.kmz", &kmz)]).unwrap();
    assert_fixture_track(&r, 0);
    assert_eq!(report(&r).format, "KMZ");
}

// ---------------------------------------------------------------- FIT

/// FIT CRC-16 (FIT SDK, "FIT File Protocol", CRC section: the nibble table below).
/// A FIT activity from the FIT protocol: definition messages (header 0x40 | local type,
/// reserved, little-endian, global message number, fields as number/size/base type) and data
/// messages. file_id (0), user_profile (3) friendly_name, session (18) sport = 32 (sailing),
/// two laps (19), ten records (20): timestamp (s since 1989-12-31), position in semicircles
/// (2³¹ / 180 per degree), speed in mm/s.
#[test]
fn fit_sailing_session_is_one_track_named_by_the_athlete() {
    let fit = fit_fixture();
    let r = Race::from_files(&[("2025-06-21-ESP29375.fit", &fit)]).unwrap();
    assert_eq!(r.boats.len(), 1);
    // Semicircles resolve 8.4e-8 °.
    assert_fixture_track(&r, 0);
    assert_eq!(r.boats[0].name, "Ana Vela");
    assert_eq!(r.boats[0].id, "ESP29375");
    let rep = report(&r);
    assert_eq!(
        rep.format,
        "FIT (garmin, sport sailing, 2 laps in one track)"
    );
    assert_eq!(rep.records_read, 10);
    assert!((series_value(&r, "sog") - 1.11).abs() < 1e-6);
    // Gzipped, the same.
    let r = Race::from_files(&[("a.fit.gz", &gzip(&fit))]).unwrap();
    assert_fixture_track(&r, 0);
}

/// fitparser's own test file garmin-fenix-5-bike.fit (MIT, fitparse-rs; copied into
/// tests/data with its licence): a real watch recording with GPS.
#[test]
fn real_fit_file_from_a_garmin_watch() {
    let bytes = std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/garmin-fenix-5-bike.fit"),
    )
    .unwrap();
    let opts = LoadOptions {
        keep_going: true,
        ..LoadOptions::default()
    };
    let r = Race::from_files_with(&[("garmin-fenix-5-bike.fit", &bytes)], &opts).unwrap();
    let rep = report(&r);
    assert_eq!(
        rep.format,
        "FIT (garmin fenix5, sport cycling, 1 laps in one track)"
    );
    assert_eq!((rep.records_read, rep.fixes), (19, 19));
    // The watch's own summary (the session message: start position and time, written by the
    // device apart from the records) is where the track starts.
    let session = fitparser::from_bytes(&bytes)
        .unwrap()
        .into_iter()
        .find(|m| m.kind() == fitparser::profile::MesgNum::Session)
        .unwrap();
    let get = |name: &str| {
        session
            .fields()
            .iter()
            .find(|f| f.name() == name)
            .map(|f| f.value().clone())
            .unwrap_or_else(|| panic!("session has no {name}"))
    };
    let semi = |v: fitparser::Value| match v {
        fitparser::Value::SInt32(x) => x as f64 * 180.0 / 2_147_483_648.0,
        v => panic!("{v:?}"),
    };
    let (lat, lon, t) = first_fix(&r, 0);
    assert!(
        (lat - semi(get("start_position_lat"))).abs() < 1e-6,
        "{lat}"
    );
    assert!(
        (lon - semi(get("start_position_long"))).abs() < 1e-6,
        "{lon}"
    );
    let fitparser::Value::Timestamp(start) = get("start_time") else {
        panic!()
    };
    assert!((t - start.timestamp() as f64).abs() < 1.5, "{t}");
}

// ---------------------------------------------------------------- Expedition sparse rows

/// The real dense Expedition log rewritten in the sparse form (`!Boat,Utc,…` header, rows
/// `0,utc,id,value,…` of the non-empty cells, id = column after Utc) loads to the same boat.
#[test]
fn expedition_sparse_rows_equal_the_dense_log() {
    let Ok(dense) = std::fs::read_to_string(common::data("expedition/expedition-valencia.csv"))
    else {
        common::skip("../shared/data/races/expedition/expedition-valencia.csv is absent");
        return;
    };
    let dense: String = dense.lines().take(2001).map(|l| format!("{l}\n")).collect();
    let mut lines = dense.lines();
    let header = lines.next().unwrap();
    let mut sparse = format!("!Boat,{header}\n");
    for l in lines {
        let cells: Vec<&str> = l.split(',').collect();
        let mut row = format!("0,{}", cells[0]);
        for (k, c) in cells.iter().enumerate().skip(1) {
            if !c.is_empty() {
                row += &format!(",{k},{c}");
            }
        }
        sparse += &row;
        sparse += "\n";
    }
    let a = Race::from_files(&[("exp.csv", dense.as_bytes())]).unwrap();
    let b = Race::from_files(&[("exp.csv", sparse.as_bytes())]).unwrap();
    assert_eq!(report(&b).format, "Expedition log (sparse rows)");
    assert_eq!(a.boats[0].fixes(), b.boats[0].fixes());
    assert_eq!(a.series, b.series);
    assert_eq!(report(&a).fixes, report(&b).fixes);
}

// ---------------------------------------------------------------- race XML and marks

/// An AC35-feed race XML as the feed's published example writes it: `RaceStartTime Time`
/// with a `-0700` offset, marks by SeqID, one unnamed `CourseLimit`.
#[test]
fn ac35_race_xml_is_a_course_beside_tracks_and_as_marks() {
    let xml = ac35_xml();
    let tcx = tcx_fixture();
    let r = Race::from_files(&[("w.tcx", tcx.as_bytes()), ("race.xml", xml.as_bytes())]).unwrap();
    let start = r.start_time.unwrap();
    assert_eq!(start.unix_timestamp(), T0_UNIX + 5);
    assert_eq!(r.boundary.len(), 3);
    let course: Vec<&str> = r.course_marks().map(|m| m.name.as_str()).collect();
    assert_eq!(course, ["PRO/PIN", "M1"]);
    // The same file given to --marks.
    let opts = LoadOptions {
        marks: Some(("race.xml".into(), xml.into_bytes())),
        ..LoadOptions::default()
    };
    let r = Race::from_files_with(&[("w.tcx", tcx.as_bytes())], &opts).unwrap();
    let course: Vec<&str> = r.course_marks().map(|m| m.name.as_str()).collect();
    assert_eq!(course, ["PRO/PIN", "M1"]);
    // Alone, it says what it is (it used to say only "contain no boats").
    let e = Race::from_files(&[("race.xml", ac35_xml().as_bytes())]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "race.xml hold a course but no boats: load the boats' tracks beside it (or give it to --marks or --course)."
    );
}

#[test]
fn marks_csv_columns_by_header_names() {
    let csv = "name,desc,sym,lat,lon\nW,\"windward, yellow\",Buoy,39.4300,-0.3100\nL,leeward,Buoy,39.4200,-0.3100\n";
    let opts = LoadOptions {
        marks: Some(("plotter.csv".into(), csv.as_bytes().to_vec())),
        ..LoadOptions::default()
    };
    let r = Race::from_files_with(&[("w.tcx", tcx_fixture().as_bytes())], &opts).unwrap();
    let names: Vec<&str> = r.marks.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["W", "L", "fleet at the start"]);
    let w = r.to_geo(r.marks[0].position).unwrap();
    assert!((w.lat - 39.43).abs() < 1e-9 && (w.lon + 0.31).abs() < 1e-9);
    // The old form still loads; a 5-cell row without a header is one clear sentence.
    let e = race::Race::from_files_with(
        &[("w.tcx", tcx_fixture().as_bytes())],
        &LoadOptions {
            marks: Some(("m.csv".into(), b"W,x,y,39.43,-0.31\n".to_vec())),
            ..LoadOptions::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("5 cells"), "{e}");
}

/// Found by fuzzing: fitparser's header reader overflows (a panic) on a FIT file shorter than
/// its header; a damaged byte is caught by the FIT CRC before decoding.
#[test]
fn damaged_fit_files_are_one_sentence() {
    let fit = fit_fixture();
    for (bytes, want) in [
        (fit[..13].to_vec(), "the FIT file is cut"),
        (fit[..fit.len() - 20].to_vec(), "the FIT file is cut"),
        (
            {
                let mut b = fit.clone();
                b[40] ^= 0x10;
                b
            },
            "checksum does not match",
        ),
    ] {
        let e = Race::from_files(&[("a.fit", &bytes)])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("a.fit: ") && e.contains(want), "{e}");
    }
}

/// Outside folders, repeating Placemark names are boats; a name per fix (a time label) is not.
#[test]
fn kml_placemark_names_name_boats_only_when_they_repeat() {
    let doc = |name: &dyn Fn(usize, usize) -> String| {
        let mut s = String::from("<kml><Document>\n");
        for boat in 0..2 {
            for k in 0..10 {
                let (lat, lon) = fix(k);
                s += &format!(
                    "<Placemark><name>{}</name><TimeStamp><when>{}</when></TimeStamp><Point><coordinates>{},{lat}</coordinates></Point></Placemark>\n",
                    name(boat, k),
                    iso(k),
                    lon + boat as f64 * 0.001
                );
            }
        }
        s + "</Document></kml>\n"
    };
    let named = doc(&|b, _| ["Alpha", "Bravo"][b].to_string());
    let r = Race::from_files(&[("t.kml", named.as_bytes())]).unwrap();
    let names: Vec<&str> = r.boats.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["Alpha", "Bravo"]);
    assert_fixture_track(&r, 0);
    // Time labels: one boat of the file; its 20 fixes share 10 timestamps, which cleaning
    // merges with a warning (never silently).
    let labels = doc(&|b, k| format!("{b}-{k}"));
    let r = Race::from_files(&[("t.kml", labels.as_bytes())]).unwrap();
    assert_eq!(r.boats.len(), 1);
    assert_eq!(r.boats[0].name, "t");
    assert_eq!(r.report.boats[0].duplicates_merged, 10);
}
