//! Each new format against the real sample files: counts, spans and positions checked against
//! an independent reading (hand-decoded sentences and rows, the data README, SailGP's own leg
//! numbers).

mod common;
use common::{data, hms};
use race::{MarkKind, Race};

fn read(rel: &str) -> String {
    std::fs::read_to_string(data(rel)).unwrap()
}

fn from(files: &[(&str, &str)]) -> Race {
    let f: Vec<(&str, &[u8])> = files.iter().map(|(n, t)| (*n, t.as_bytes())).collect();
    Race::from_files(&f).unwrap_or_else(|e| panic!("{e}"))
}

/// An NMEA sentence with its checksum (XOR of the bytes between `$` and `*`).
fn sentence(body: &str) -> String {
    format!("${body}*{:02X}", body.bytes().fold(0u8, |a, b| a ^ b))
}

#[test]
fn nmea_log_without_a_date_gives_times_of_day_and_the_wind() {
    let r = common::load(&["nmea-signalk/plaka.log"]);
    let rep = &r.report.file_reports[0];
    assert_eq!(rep.format, "NMEA 0183");
    // 7,250 GLL fixes every 2 s, 09:55:59–14:03:24 (data README).
    assert_eq!(r.boats[0].fixes().len(), 7250);
    assert_eq!(r.time_span(), (0.0, hms("14:03:24") - hms("09:55:59")));
    assert!(
        rep.date_source.starts_with("none: the log has no date"),
        "{}",
        rep.date_source
    );
    assert!(r.start_time.is_none());
    assert!(
        r.report
            .start_time
            .as_deref()
            .unwrap()
            .starts_with("09:55:59.000 UTC (time of day")
    );
    // The first fix, decoded by hand: $GPGLL,6005.071,N,02332.346,E,095559,A,D*43 is
    // 60° 5.071' N, 23° 32.346' E.
    let f = r.boats[0].fixes()[0];
    let g = r.to_geo(f.pos()).unwrap();
    assert!((g.lat - (60.0 + 5.071 / 60.0)).abs() < 1e-9, "{g:?}");
    assert!((g.lon - (23.0 + 32.346 / 60.0)).abs() < 1e-9, "{g:?}");
    for c in ["tws", "twa", "bsp", "awa", "aws"] {
        assert!(
            rep.channels.iter().any(|x| x == c),
            "{c} in {:?}",
            rep.channels
        );
    }
    // Boat speed: the first VHW after the first time is 06.12 kn; the true wind of the first
    // MWD (speed only: its direction fields are empty) is 08.16 kn.
    let bsp = r.series.iter().find(|s| s.channel == "bsp").unwrap();
    assert!((bsp.v[0] as f64 - 6.12 * 1852.0 / 3600.0).abs() < 1e-5);
    let tws = r.series.iter().find(|s| s.channel == "tws").unwrap();
    assert!(
        (tws.v[0] as f64 - 8.16 * 1852.0 / 3600.0).abs() < 1e-5,
        "{}",
        tws.v[0]
    );
    assert_eq!(tws.t[0], 0.0);
}

#[test]
fn nmea_bad_and_truncated_sentences_are_counted_and_skipped_and_crlf_or_lf_is_the_same() {
    let text = read("nmea-signalk/plaka.log");
    let lf = text.replace("\r\n", "\n");
    let mut lines: Vec<String> = lf.lines().map(String::from).collect();
    // Line 11 is the first GLL: a wrong checksum; line 27 (the second GLL) truncated.
    assert!(lines[10].starts_with("$GPGLL") && lines[26].starts_with("$GPGLL"));
    lines[10] = lines[10].replace("*43", "*44");
    lines[26].truncate(20);
    let bad = lines.join("\n");
    let r = from(&[("p.log", &bad)]);
    assert_eq!(r.boats[0].fixes().len(), 7248);
    let d = &r.report.file_reports[0].dropped;
    assert!(
        d.contains(&("sentences with a wrong checksum".into(), 1)),
        "{d:?}"
    );
    assert!(
        d.contains(&("truncated sentences (no checksum)".into(), 1)),
        "{d:?}"
    );
    let a = from(&[("p.log", &lf)]);
    let b = common::load(&["nmea-signalk/plaka.log"]);
    assert_eq!(a.boats[0].fixes(), b.boats[0].fixes());
}

#[test]
fn nmea_dates_from_rmc_and_zda_with_midnight_roll_over() {
    // A talker "GN" log crossing midnight: RMC gives 2024-12-31; the fix after midnight is on
    // 2025-01-01 (no date sentence after it). HDG 100° magnetic, variation 5° E: 105° true.
    let log = [
        sentence("GNRMC,235958.00,A,3947.000,N,00018.000,W,5.0,90.0,311224,,,A"),
        sentence("HCHDG,100.0,,,5.0,E"),
        sentence("GNGGA,235959.00,3947.001,N,00018.000,W,1,08,1.0,0.0,M,0.0,M,,"),
        sentence("GNGLL,3947.002,N,00018.000,W,000001.00,A,A"),
        sentence("IIMWV,045.0,T,12.0,N,A"),
    ]
    .join("\r\n");
    let r = from(&[("x.nmea", &log)]);
    let rep = &r.report.file_reports[0];
    assert_eq!(rep.date_source, "RMC or ZDA sentences");
    assert_eq!(r.report.start_time.as_deref(), Some("2024-12-31T23:59:58Z"));
    let t: Vec<f64> = r.boats[0].fixes().iter().map(|f| f.t).collect();
    assert_eq!(t, vec![0.0, 1.0, 3.0]);
    // 0.002' of latitude north = 3.704 m north (z negative is north).
    let z = r.boats[0].fixes()[2].z - r.boats[0].fixes()[0].z;
    assert!((z + 0.002 * 1852.0).abs() < 0.02, "{z}");
    let h = r.series.iter().find(|s| s.channel == "heading").unwrap();
    assert_eq!(h.v, vec![105.0]);
    // ZDA alone dates a GLL log.
    let log = [
        sentence("GPZDA,120000.00,15,06,2024,00,00"),
        sentence("GPGLL,3947.000,N,00018.000,W,120000.00,A,A"),
        sentence("GPGLL,3947.001,N,00018.000,W,120001.00,A,A"),
    ]
    .join("\n");
    let r = from(&[("z.txt", &log)]);
    assert_eq!(r.report.start_time.as_deref(), Some("2024-06-15T12:00:00Z"));
}

#[test]
fn expedition_log_days_sparse_rows_and_synonyms() {
    let r = common::load(&["expedition/expedition-valencia.csv"]);
    let rep = &r.report.file_reports[0];
    assert_eq!(rep.format, "Expedition log");
    assert_eq!(rep.records_read, 11_978);
    // Utc 38516.38857 days since 1899-12-30 = 2005-06-13 + 0.38857 × 86,400 s = 09:19:32.448.
    assert_eq!(
        r.report.start_time.as_deref(),
        Some("2005-06-13T09:19:32.448Z")
    );
    // The last row, 38516.5305: 12:43:55.2 (the README's 12:43:55).
    let (_, end) = r.time_span();
    assert!((end - (0.5305 - 0.38857) * 86_400.0).abs() < 2e-3, "{end}");
    let g = r.to_geo(r.boats[0].fixes()[0].pos()).unwrap();
    assert!(
        (g.lat - 39.400246).abs() < 1e-9 && (g.lon + 0.299097).abs() < 1e-9,
        "{g:?}"
    );
    for c in ["bsp", "heading", "heel", "tws", "twd", "set"] {
        assert!(
            rep.channels.iter().any(|x| x == c),
            "{c} in {:?}",
            rep.channels
        );
    }
    // Most fixes are kept (frozen and quantised-time spikes are reported, not hidden).
    let b = &r.report.boats[0];
    assert!(b.samples_kept > 11_000, "{b:?}");

    // Sparse rows, as Expedition writes when only some channels changed: row 3 writes only
    // Bsp; the fix count drops by one, Bsp still has a sample there, and `Set` (not `iSet`)
    // is read too.
    let text = read("expedition/expedition-valencia.csv");
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[0] = lines[0].replace(",iSet,", ",Set,");
    let cells: Vec<&str> = lines[3].split(',').collect();
    let sparse: Vec<&str> = cells
        .iter()
        .enumerate()
        .map(|(i, c)| if i <= 1 { *c } else { "" })
        .collect();
    lines[3] = sparse.join(",");
    let r = from(&[("e.csv", &lines.join("\n"))]);
    let rep = &r.report.file_reports[0];
    assert_eq!(rep.fixes, 11_977);
    assert!(rep.channels.iter().any(|c| c == "set"));
    let bsp = r.series.iter().find(|s| s.channel == "bsp").unwrap();
    assert_eq!(bsp.t.len(), 11_978);
    let hdg = r.series.iter().find(|s| s.channel == "heading").unwrap();
    assert_eq!(hdg.t.len(), 11_977);
}

/// (time of the change, new leg) of SailGP's own `TRK_LEG_NUM_unk` for race 25011905.
fn sailgp_legs(boat: &str) -> Vec<(f64, usize)> {
    let text = read(&format!("sailgp-auckland-2025/boat_logs/data_{boat}.csv"));
    let mut out = Vec::new();
    let mut prev = 0usize;
    for l in text.lines().skip(1) {
        let c: Vec<&str> = l.split(',').collect();
        if c[38] != "25011905.0" {
            continue;
        }
        let leg = c[37].parse::<f64>().unwrap() as usize;
        if leg != prev {
            out.push((hms(&c[1][11..]) - hms("03:08:00"), leg));
            prev = leg;
        }
    }
    out
}

#[test]
fn sailgp_race_xml_gives_the_course_with_gates_and_the_roundings_match_sailgp() {
    let boats = [
        "AUS", "BRA", "CAN", "DEN", "ESP", "GBR", "GER", "ITA", "NZL", "SUI", "USA",
    ];
    let mut files = vec!["sailgp-auckland-2025/race_xmls/25011905_03-13-55.xml".to_string()];
    files.extend(
        boats
            .iter()
            .map(|b| format!("sailgp-auckland-2025/boat_logs/data_{b}.csv")),
    );
    let rels: Vec<&str> = files.iter().map(String::as_str).collect();
    let r = common::load(&rels);
    let course: Vec<(&str, MarkKind)> = r
        .course_marks()
        .map(|m| (m.name.as_str(), m.kind))
        .collect();
    assert_eq!(
        course,
        vec![
            ("SL1/SL2", MarkKind::StartLine),
            ("M1", MarkKind::Mark),
            ("LG1/LG2", MarkKind::Gate),
            ("WG1/WG2", MarkKind::Gate),
            ("LG1/LG2", MarkKind::Gate),
            ("WG1/WG2", MarkKind::Gate),
            ("LG1", MarkKind::Mark),
            ("FL1/FL2", MarkKind::FinishLine),
        ]
    );
    let roundings: Vec<Option<&str>> = r.course_marks().map(|m| m.rounding.as_deref()).collect();
    assert_eq!(
        roundings,
        vec![
            Some("SP"),
            Some("Port"),
            Some("PS"),
            Some("SP"),
            Some("PS"),
            Some("SP"),
            Some("Port"),
            Some("PS")
        ]
    );
    // Start 16:08+13:00; the boundary has 12 corners; the gate LG1/LG2's ends are its buoys.
    assert_eq!(r.report.start_time.as_deref(), Some("2025-01-19T03:08:00Z"));
    assert_eq!(r.boundary.len(), 12);
    let lg = r.marks.iter().find(|m| m.name == "LG1/LG2").unwrap();
    let lg1 = r.marks.iter().find(|m| m.name == "LG1").unwrap();
    assert_eq!(lg.ends.unwrap()[0], lg1.position);
    assert_eq!(r.rank_basis(), race::RankBasis::Course);
    // Every mark rounding (legs 2–7) at most 25 s before the change of SailGP's own leg
    // counter, for every boat that sailed the leg.
    let mut compared = 0;
    for (bi, b) in r.boats.iter().enumerate() {
        for (t, leg) in sailgp_legs(&b.id) {
            if (2..=7).contains(&leg) {
                let ours = r.boats[bi].roundings()[leg - 1].unwrap_or(f64::NAN);
                // Ours is the closest approach (or the passage through a gate); SailGP's
                // counter changes once the boat is on the next leg: 0–23 s later here.
                assert!(
                    (-25.0..=1.0).contains(&(ours - t)),
                    "{} leg {leg}: ours {ours}, SailGP {t}",
                    b.id
                );
                compared += 1;
            }
        }
    }
    assert!(compared >= 50, "{compared}");
}

#[test]
fn instrument_csv_exports_offsets_blank_rows_synonyms_and_units() {
    // Vakaros Atlas style: ISO times with a -0500 offset, sog in knots, hdg_true, heel, trim,
    // and a blank row in the middle.
    let vakaros = "timestamp,latitude,longitude,sog_kts,cog,hdg_true,heel,trim\n\
        2024-07-20T10:00:00.000-0500,41.500000,-71.300000,6.0,45.0,44.0,12.5,-1.0\n\
        ,,,,,,,\n\
        2024-07-20T10:00:01.000-0500,41.500030,-71.299960,6.1,45.0,44.5,13.0,-1.2\n\
        2024-07-20T10:00:02.000-0500,41.500060,-71.299920,6.2,45.0,45.0,13.5,-1.1\n";
    let r = from(&[("atlas.csv", vakaros)]);
    assert_eq!(r.report.start_time.as_deref(), Some("2024-07-20T15:00:00Z"));
    let rep = &r.report.file_reports[0];
    assert_eq!(rep.dropped, vec![("blank rows".to_string(), 1)]);
    assert_eq!(rep.records_read, 4);
    for c in ["sog", "heading", "heel", "trim"] {
        assert!(
            rep.channels.iter().any(|x| x == c),
            "{c} in {:?}",
            rep.channels
        );
    }
    assert_eq!(r.boats[0].fixes().len(), 3);
    assert_eq!(r.boats[0].state_at(1.0).heel_deg, Some(13.0));
    // Velocitek style: "Date/Time", "Latitude", "Longitude", "Speed (km/h)".
    let velocitek = "Date/Time,Latitude,Longitude,Speed (km/h),Heading\n\
        2024-07-20 15:00:00,41.5,-71.3,18.0,44\n\
        2024-07-20 15:00:01,41.50003,-71.29996,18.0,44\n";
    let r = from(&[("v.csv", velocitek)]);
    assert_eq!(r.report.start_time.as_deref(), Some("2024-07-20T15:00:00Z"));
    assert_eq!(r.report.boats[0].max_speed_kn, 20.0);
}
