//! Issue 30: silent losses and silent nonsense in import, and refusals that blamed the wrong
//! thing. Every case was reproduced on the old code (where it kept 1 of 600 NMEA fixes, took a
//! 1970 row as the start, or blamed a far mark on a GPX) and stays here. The truth each test
//! checks is built into its input: a boat sailing due east at 5 m/s for 600 s from a known
//! point, with one thing broken.

use race::{LoadOptions, Race};

/// Latitude and longitude of the track's first fix (off Valencia).
const LAT0: f64 = 39.45;
const LON0: f64 = -0.30;
/// Fixes, one a second.
const N: usize = 600;
/// Degrees of longitude per second at 5 m/s east at LAT0 (WGS84 radius of the parallel).
fn dlon_per_s() -> f64 {
    let a = 6_378_137.0f64;
    let e2 = 0.006_694_379_990_14;
    let p = LAT0.to_radians();
    let r = a * p.cos() / (1.0 - e2 * p.sin() * p.sin()).sqrt();
    (5.0 / r).to_degrees()
}

fn lon(i: usize) -> f64 {
    LON0 + dlon_per_s() * i as f64
}

fn load(files: &[(&str, &str)]) -> Result<Race, String> {
    load_with(files, &LoadOptions::default())
}

fn load_with(files: &[(&str, &str)], opts: &LoadOptions) -> Result<Race, String> {
    let f: Vec<(&str, &[u8])> = files.iter().map(|(n, t)| (*n, t.as_bytes())).collect();
    Race::from_files_with(&f, opts).map_err(|e| e.to_string())
}

fn keep_going() -> LoadOptions {
    LoadOptions {
        keep_going: true,
        ..LoadOptions::default()
    }
}

// --- NMEA ------------------------------------------------------------------------------------

/// An NMEA sentence with its checksum (XOR of the bytes between `$` and `*`).
fn sentence(body: &str) -> String {
    format!("${body}*{:02X}", body.bytes().fold(0u8, |a, b| a ^ b))
}

/// `ddmm.mmmm` of a positive angle.
fn dm(deg: f64, width: usize) -> String {
    let d = deg.trunc();
    format!("{:0w$}{:07.4}", d as u32, (deg - d) * 60.0, w = width)
}

/// RMC fix `i` at 11:00:00 + i s on 2025-06-21, with status and latitude as given.
fn rmc(i: usize, status: &str, lat: f64) -> String {
    let t = 11 * 3600 + i;
    sentence(&format!(
        "GPRMC,{:02}{:02}{:02}.00,{status},{},N,{},W,9.7,90.0,210625,,",
        t / 3600,
        t / 60 % 60,
        t % 60,
        dm(lat, 2),
        dm(-lon(i), 3)
    ))
}

fn rmc_log(ending: &str, f: impl Fn(usize) -> String) -> String {
    (0..N).map(f).collect::<Vec<_>>().join(ending) + ending
}

#[test]
fn nmea_lines_ending_in_cr_alone_keep_every_fix() {
    let log = rmc_log("\r", |i| rmc(i, "A", LAT0));
    let r = load(&[("cr.nmea", &log)]).unwrap();
    assert_eq!(r.boats[0].fixes().len(), N);
    assert_eq!(r.time_span(), (0.0, (N - 1) as f64));
}

#[test]
fn nmea_two_sentences_on_one_line_are_both_read() {
    let log: String = (0..N / 2)
        .map(|k| format!("{}{}\r\n", rmc(2 * k, "A", LAT0), rmc(2 * k + 1, "A", LAT0)))
        .collect();
    let r = load(&[("mux.nmea", &log)]).unwrap();
    assert_eq!(r.boats[0].fixes().len(), N);
    assert_eq!(r.report.file_reports[0].records_read, N);
}

#[test]
fn nmea_status_v_losing_most_fixes_is_refused_and_counted_with_keep_going() {
    let log = rmc_log("\n", |i| rmc(i, if i < 10 { "A" } else { "V" }, LAT0));
    let e = load(&[("v.nmea", &log)]).unwrap_err();
    assert_eq!(
        e,
        "v.nmea: reading would keep 10 of 600 positions, because of 590 position sentences the receiver marked as no fix (RMC or GLL status V, GGA quality 0) (--keep-going loads it anyway)."
    );
    let r = load_with(&[("v.nmea", &log)], &keep_going()).unwrap();
    assert_eq!(r.boats[0].fixes().len(), 10);
    assert_eq!(
        r.report.file_reports[0].dropped,
        vec![(
            "position sentences the receiver marked as no fix (RMC or GLL status V, GGA quality 0)"
                .to_string(),
            590
        )]
    );
    assert_eq!(r.report.file_reports[0].fixes_dropped, 590);
}

#[test]
fn nmea_latitude_91_is_counted_not_silently_gone() {
    let log = rmc_log("\n", |i| rmc(i, "A", if i % 60 == 7 { 91.0 } else { LAT0 }));
    let r = load(&[("lat.nmea", &log)]).unwrap();
    assert_eq!(r.boats[0].fixes().len(), N - 10);
    assert_eq!(
        r.report.file_reports[0].dropped,
        vec![(
            "positions with a latitude outside [-90, 90] or a longitude outside [-180, 180]"
                .to_string(),
            10
        )]
    );
    assert!(
        r.report
            .warnings
            .iter()
            .any(|w| w.starts_with("lat.nmea: 10 positions with a latitude outside")),
        "{:?}",
        r.report.warnings
    );
}

#[test]
fn nmea_time_fields_that_are_not_times_refuse_the_log_at_their_line() {
    for bad in ["110000inf", "110000nan", "1100001e300", "11000.5"] {
        let mut lines: Vec<String> = (0..N).map(|i| rmc(i, "A", LAT0)).collect();
        let body = format!(
            "GPRMC,{bad},A,{},N,{},W,9.7,90.0,210625,,",
            dm(LAT0, 2),
            dm(-lon(4), 3)
        );
        lines[4] = sentence(&body);
        let e = load(&[("t.nmea", &(lines.join("\n") + "\n"))]).unwrap_err();
        assert_eq!(
            e,
            format!("t.nmea line 5: RMC time is \"{bad}\", not a time of day hhmmss[.ss].")
        );
    }
}

// --- absurd times ----------------------------------------------------------------------------

/// A CSV log, `time,lat,lon,sog_kts`, row i at 2025-06-21T11:00:00Z + i s.
fn csv_row(i: usize) -> String {
    let t = 11 * 3600 + i;
    format!(
        "2025-06-21T{:02}:{:02}:{:02}Z,{LAT0},{:.8},9.7",
        t / 3600,
        t / 60 % 60,
        t % 60,
        lon(i)
    )
}

fn csv_log(f: impl Fn(usize) -> String) -> String {
    let mut s = String::from("time,lat,lon,sog_kts\n");
    for i in 0..N {
        s.push_str(&f(i));
        s.push('\n');
    }
    s
}

#[test]
fn a_csv_row_dated_1970_or_2100_is_dropped_and_counted_not_the_start() {
    for date in ["1970-01-01T00:00:00Z", "2100-01-01T00:00:00Z"] {
        let log = csv_log(|i| {
            if i == 300 {
                format!("{date},{LAT0},{:.8},9.7", lon(i))
            } else {
                csv_row(i)
            }
        });
        let r = load(&[("b.csv", &log)]).unwrap();
        assert_eq!(r.time_span(), (0.0, (N - 1) as f64), "{date}");
        assert_eq!(r.boats[0].fixes().len(), N - 1);
        assert_eq!(r.report.start_time.as_deref(), Some("2025-06-21T11:00:00Z"));
        assert_eq!(r.report.file_reports[0].fixes_dropped, 1, "{date}");
    }
    // Within the plausible years but a year from the body: isolated, dropped.
    let log = csv_log(|i| {
        if i == 599 {
            format!("2026-06-21T11:09:59Z,{LAT0},{:.8},9.7", lon(i))
        } else {
            csv_row(i)
        }
    });
    let r = load(&[("y.csv", &log)]).unwrap();
    assert_eq!(r.time_span(), (0.0, (N - 2) as f64));
    assert_eq!(
        r.report.file_reports[0].dropped,
        vec![(
            "fixes isolated in time, over a day from the rest of their track".to_string(),
            1
        )]
    );
}

/// An Expedition log (Utc in serial days since 1899-12-30) of the same track: 2025-06-21 is
/// serial day 45829.
fn expedition(f: impl Fn(usize) -> String) -> String {
    let mut s = String::from("Utc,Bsp,Lat,Lon\n");
    for i in 0..N {
        s.push_str(&f(i));
        s.push('\n');
    }
    s
}

fn exp_row(i: usize) -> String {
    format!(
        "{:.8},9.5,{LAT0},{:.8}",
        45829.0 + (11.0 * 3600.0 + i as f64) / 86_400.0,
        lon(i)
    )
}

#[test]
fn expedition_utc_of_minus_5_or_1e300_is_dropped_and_nan_refused_at_its_line() {
    for utc in ["-5", "1e300"] {
        let log = expedition(|i| {
            if i == 100 {
                format!("{utc},9.5,{LAT0},{:.8}", lon(i))
            } else {
                exp_row(i)
            }
        });
        let r = load(&[("e.csv", &log)]).unwrap();
        assert_eq!(r.boats[0].fixes().len(), N - 1, "{utc}");
        let (t0, t1) = r.time_span();
        // Utc is written to 8 decimals of a day (0.9 ms) and read to the millisecond.
        assert!(t0 == 0.0 && (t1 - 599.0).abs() < 2e-3, "{utc}: {t0} {t1}");
        assert_eq!(r.report.file_reports[0].fixes_dropped, 1);
    }
    for utc in ["nan", "inf", "1e306"] {
        let log = expedition(|i| {
            if i == 100 {
                format!("{utc},9.5,{LAT0},{:.8}", lon(i))
            } else {
                exp_row(i)
            }
        });
        assert_eq!(
            load(&[("e.csv", &log)]).unwrap_err(),
            format!("e.csv line 102: Utc is \"{utc}\", not a finite day number.")
        );
    }
}

#[test]
fn a_native_json_time_1e8_s_away_is_dropped_and_counted() {
    let mut track: Vec<String> = (0..N).map(|i| format!("[{i},{},0]", 5 * i)).collect();
    track[N - 1] = format!("[1e8,{},0]", 5 * (N - 1));
    let json = format!(
        "{{\"boats\":[{{\"id\":\"a\",\"track\":[{}]}}]}}",
        track.join(",")
    );
    let r = load(&[("a.json", &json)]).unwrap();
    assert_eq!(r.time_span(), (0.0, (N - 2) as f64));
    assert_eq!(r.report.file_reports[0].fixes_dropped, 1);
}

/// A SailGP race XML with a start time and one mark near the track.
fn race_xml(start: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="utf-8"?>
<Race>
  <RaceStartTime Start="{start}" />
  <Course>
    <CompoundMark CompoundMarkID="1" Name="M1">
      <Mark SeqID="1" Name="M1" TargetLat="{LAT0}" TargetLng="{}" />
    </CompoundMark>
  </Course>
  <CompoundMarkSequence>
    <Corner SeqID="1" CompoundMarkID="1" Rounding="Port" />
  </CompoundMarkSequence>
</Race>
"#,
        lon(300)
    )
}

#[test]
fn a_race_xml_start_10_years_from_the_tracks_is_refused_naming_both() {
    let log = csv_log(csv_row);
    // Six minutes in: fine.
    let r = load(&[
        ("b.csv", &log),
        ("race.xml", &race_xml("2025-06-21T11:06:00Z")),
    ])
    .unwrap();
    assert_eq!(r.time_span(), (-360.0, 239.0));
    let e = load(&[
        ("b.csv", &log),
        ("race.xml", &race_xml("2035-06-21T11:06:00Z")),
    ])
    .unwrap_err();
    assert_eq!(
        e,
        "b.csv: boat \"b\"'s fixes are 10.0 years before the race start (the start comes from start_time of race.xml); the files are not one race, load each on its own."
    );
}

#[test]
fn a_truncated_race_xml_is_refused_at_the_element_it_ends_in() {
    let full = race_xml("2025-06-21T11:06:00Z");
    let cut = &full[..full.find("<Corner").unwrap()];
    let e = load(&[("b.csv", &csv_log(csv_row)), ("race.xml", cut)]).unwrap_err();
    assert_eq!(
        e,
        "race.xml line 9: <CompoundMarkSequence> is never closed: the file ends inside it (a truncated download?) and its course would be incomplete."
    );
}

// --- the spike limit -------------------------------------------------------------------------

#[test]
fn one_garbage_speed_cell_does_not_raise_the_spike_limit() {
    // Row 200 claims 1e300 kn; row 400 jumps 5.6 km north and back (a broken fix).
    let log = csv_log(|i| match i {
        200 => format!("{},1e300", csv_row(i).rsplit_once(',').unwrap().0),
        400 => {
            let t = 11 * 3600 + i;
            format!(
                "2025-06-21T{:02}:{:02}:{:02}Z,{},{:.8},9.7",
                t / 3600,
                t / 60 % 60,
                t % 60,
                LAT0 + 5600.0 / 111_000.0,
                lon(i)
            )
        }
        _ => csv_row(i),
    });
    let r = load(&[("b.csv", &log)]).unwrap();
    let rep = &r.report.boats[0];
    // 1.2 × the 99th percentile of 9.7 kn is under the 20 kn floor.
    assert!(
        (rep.max_speed_kn - 20.0).abs() < 1e-12,
        "{}",
        rep.max_speed_kn
    );
    assert_eq!(rep.spikes.len(), 1);
    assert_eq!(rep.spikes[0].t, 400.0);
    assert_eq!(r.boats[0].fixes().len(), N - 1);
}

// --- units in the time column's name ---------------------------------------------------------

#[test]
fn a_time_column_named_time_ms_is_read_in_milliseconds() {
    let mut log = String::from("time_ms,lat,lon\n");
    for i in 0..=400 {
        log.push_str(&format!("{},{LAT0},{:.8}\n", i * 1000, lon(i)));
    }
    let r = load(&[("ms.csv", &log)]).unwrap();
    assert_eq!(r.time_span(), (0.0, 400.0));
    assert_eq!(r.boats[0].fixes().len(), 401);
    // Unix milliseconds under the same name stay absolute.
    let mut log = String::from("time_ms,lat,lon\n");
    for i in 0..=400 {
        log.push_str(&format!(
            "{},{LAT0},{:.8}\n",
            1_750_503_600_000u64 + i as u64 * 1000,
            lon(i)
        ));
    }
    let r = load(&[("ms.csv", &log)]).unwrap();
    assert_eq!(r.report.start_time.as_deref(), Some("2025-06-21T11:00:00Z"));
    assert_eq!(r.time_span(), (0.0, 400.0));
}

// --- refusals that blamed the wrong thing ----------------------------------------------------

#[test]
fn one_glitch_111_km_off_does_not_refuse_the_track_and_is_cleaned() {
    let log = csv_log(|i| {
        if i == 250 {
            format!(
                "{},{},{:.8},9.7",
                csv_row(i).split(',').next().unwrap(),
                LAT0 + 1.0,
                lon(i)
            )
        } else {
            csv_row(i)
        }
    });
    let r = load(&[("b.csv", &log)]).unwrap();
    assert_eq!(r.report.boats[0].spikes.len(), 1);
    let o = r.origin.unwrap();
    // The middle of the clean track's bounding box.
    assert!((o.lat - LAT0).abs() < 1e-12, "{o:?}");
    // Within the 8 decimals the CSV writes.
    assert!((o.lon - 0.5 * (lon(0) + lon(N - 1))).abs() < 1e-8, "{o:?}");
}

#[test]
fn a_far_mark_is_blamed_on_the_file_that_holds_it() {
    let log = csv_log(csv_row);
    let marks = format!(
        "name,lat,lon\nA,{LAT0},{}\nB,{},{}\n",
        lon(100),
        LAT0 + 1.0,
        lon(100)
    );
    let opts = LoadOptions {
        marks: Some(("marks.csv".into(), marks.into_bytes())),
        ..LoadOptions::default()
    };
    let e = load_with(&[("b.csv", &log)], &opts).unwrap_err();
    assert!(e.starts_with("marks.csv: mark \"B\" (40.4500, "), "{e}");
    assert!(
        e.contains(") is 111 km from the boats' median fix ("),
        "{e}"
    );
    // A race XML's far mark names the XML.
    let xml = race_xml("2025-06-21T11:06:00Z")
        .replace(&format!("TargetLat=\"{LAT0}\""), "TargetLat=\"40.45\"");
    let e = load(&[("b.csv", &log), ("race.xml", &xml)]).unwrap_err();
    assert!(e.starts_with("race.xml: mark \"M1\""), "{e}");
}

#[test]
fn an_absurd_maxsail_start_minute_names_the_maxsail_file() {
    let meta = r#"{"TWD": 200, "TWS": 10, "MINUTO_SALIDA": 1e300, "ARCHIVO_TRACK": "b.csv",
        "BALIZAS": [{"lat": 39.45, "lon": -0.29, "nombre": "S1"}]}"#;
    let e = load(&[("b.csv", &csv_log(csv_row)), ("meta.json", meta)]).unwrap_err();
    assert_eq!(
        e,
        "meta.json: MINUTO_SALIDA is 1e300, not a minute within a day of the track's first fix (-1440 to 1440)."
    );
}

#[test]
fn marks_json_errors_name_the_line_or_the_field() {
    let log = csv_log(csv_row);
    let with = |m: &str| {
        let opts = LoadOptions {
            marks: Some(("m.json".into(), m.as_bytes().to_vec())),
            ..LoadOptions::default()
        };
        load_with(&[("b.csv", &log)], &opts).unwrap_err()
    };
    assert_eq!(
        with("[{\"name\": \"A\", \"lat\": \"x\", \"lon\": -0.29}]"),
        "m.json: marks[0] (\"A\"): \"lat\" is \"x\", not a number."
    );
    assert_eq!(
        with(
            "[\n{\"name\": \"A\", \"lat\": 39.45, \"lon\": -0.29},\n{\"name\": \"B\", \"lat\": 39.45}\n]"
        ),
        "m.json line 3: not a marks file: missing field `lon`."
    );
    assert_eq!(
        with("{\"marks\": [\n{\"name\": \"A\", \"lat\": 39.45, \"lon\": -0.29, \"x\": 1}]}"),
        "m.json line 2: not a marks file: unknown field `x`, expected one of `name`, `lat`, `lon`."
    );
}

#[test]
fn utf16_files_with_a_bom_are_decoded_and_without_one_named() {
    let log = csv_log(csv_row);
    let le: Vec<u8> = [0xFF, 0xFE]
        .into_iter()
        .chain(log.encode_utf16().flat_map(u16::to_le_bytes))
        .collect();
    let be: Vec<u8> = [0xFE, 0xFF]
        .into_iter()
        .chain(log.encode_utf16().flat_map(u16::to_be_bytes))
        .collect();
    let utf8 = load(&[("b.csv", &log)]).unwrap();
    for bytes in [&le, &be] {
        let r = Race::from_files(&[("b.csv", bytes.as_slice())]).unwrap();
        assert_eq!(r.boats[0].fixes(), utf8.boats[0].fixes());
    }
    let bare: Vec<u8> = log.encode_utf16().flat_map(u16::to_le_bytes).collect();
    assert_eq!(
        Race::from_files(&[("b.csv", bare.as_slice())])
            .unwrap_err()
            .to_string(),
        "b.csv: is UTF-16 text without a byte-order mark; save it as UTF-8 (or UTF-16 with a BOM), e.g. iconv -f UTF-16LE -t UTF-8."
    );
}

#[test]
fn a_latitude_of_1e308_is_printed_in_exponent_form() {
    let log = csv_log(|i| {
        if i == 3 {
            format!(
                "{},1e308,{:.8},9.7",
                csv_row(i).split(',').next().unwrap(),
                lon(i)
            )
        } else {
            csv_row(i)
        }
    });
    assert_eq!(
        load(&[("b.csv", &log)]).unwrap_err(),
        "b.csv line 5: latitude 1e308 is not a number in [-90, 90]."
    );
}
