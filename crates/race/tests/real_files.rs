//! The importer on the real files of ../shared/data/races (see its README for the quirks
//! asserted here).

mod common;
use common::{hms, load};

const KN: f64 = 1852.0 / 3600.0;

#[test]
fn valencia_p01_two_boats_marks_and_two_laps() {
    let r = load(&[
        "valencia/2025-06-21-ESP29375-P01.gpx",
        "valencia/2025-06-21-ESP30782-P01.gpx",
        "valencia/2025-06-21-ESP30782-P01-meta-data.json",
    ]);
    let ids: Vec<&str> = r.boats.iter().map(|b| b.id.as_str()).collect();
    assert_eq!(ids, ["ESP29375", "ESP30782"]);
    assert_eq!(r.boats[0].fixes().len(), 1913);
    // Start: MINUTO_SALIDA = 5 minutes after ESP30782's first fix (11:18:29).
    assert_eq!(r.report.start_time.as_deref(), Some("2025-06-21T11:23:29Z"));
    assert_eq!(
        r.boats[1].time_span(),
        (-300.0, hms("11:51:29") - hms("11:23:29"))
    );
    assert_eq!(r.boats[0].time_span().0, hms("11:18:34") - hms("11:23:29"));
    // Wind from the meta-data: TWD 110°, TWS 6 kn.
    let w = r.wind.unwrap();
    assert_eq!(w.from_deg, 110.0);
    assert!((w.speed_mps - 6.0 * KN).abs() < 1e-12);
    // The course is S1-B1 twice; both boats round every mark in order.
    let names: Vec<&str> = r.course_marks().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["S1", "B1", "S1", "B1", "S1"]);
    // S1–B1 from the meta-data coordinates: about 697 m (haversine of the published lat/lons).
    for l in r.leg_lengths() {
        assert!((l - 697.0).abs() < 2.0, "leg {l}");
    }
    for b in &r.boats {
        let t: Vec<f64> = b.roundings().iter().map(|x| x.expect("rounded")).collect();
        assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
        // The tracks' closest approaches to B1: ~11:31:59–11:32:04 and ~11:44:29–11:44:35.
        let b1 = t[1] + hms("11:23:29");
        assert!((hms("11:31:30")..hms("11:32:30")).contains(&b1), "{}", b1);
    }
    // Both tracks are clean: nothing removed except (possibly) a frozen fix.
    for rep in &r.report.boats {
        assert!(rep.spikes.is_empty(), "{rep:?}");
        assert!(rep.gaps.is_empty());
    }
}

#[test]
fn gdansk_spike_is_removed() {
    let r = load(&["gdansk/2025-10-26-8_43.gpx"]);
    let rep = &r.report.boats[0];
    // The file has no version attribute: read, with a warning.
    assert!(r.report.warnings.iter().any(|w| w.contains("version")));
    // A single boat's race starts at its first fix (08:43:30).
    assert_eq!(r.boats[0].time_span().0, 0.0);
    // 37.69 kn from 08:46:58.9 to 08:47:00.9 (README): the fix at 08:47:00.9 or the frozen
    // fixes before it must go.
    let spike_t = hms("08:47:00.9") - hms("08:43:30");
    let fixes = r.boats[0].fixes();
    let worst = fixes
        .windows(2)
        .map(|w| (w[1].x - w[0].x).hypot(w[1].z - w[0].z) / (w[1].t - w[0].t))
        .fold(0.0, f64::max);
    assert!(worst <= 20.0 * KN + 1e-9, "max step {} kn", worst / KN);
    assert!(rep.max_step_speed_kn <= 20.0);
    let removed = rep.samples_read - rep.samples_kept;
    assert!((1..=20).contains(&removed), "removed {removed}: {rep:?}");
    // The frozen fixes 08:46:54.9–58.9 or the fix after the jump (08:47:00.9) must go.
    let gone = |t: f64| !fixes.iter().any(|f| (f.t - t).abs() < 0.01);
    assert!(gone(spike_t) || gone(spike_t - 2.0), "{rep:?}");
    let near: Vec<_> = rep
        .spikes
        .iter()
        .filter(|s| (s.t - spike_t).abs() <= 6.0)
        .collect();
    assert!(!near.is_empty() || rep.frozen_removed > 0, "{rep:?}");
    assert_eq!(rep.samples_read, 8650);
}

#[test]
fn gdansk_gaps_are_marked_and_not_interpolated() {
    let r = load(&[
        "gdansk/rerata_26_oct.gpx",
        "gdansk/2025-10-26-boat_three.gpx",
    ]);
    let a = &r.boats[r.boat_index("rerata_26_oct").unwrap()];
    let rep = r
        .report
        .boats
        .iter()
        .find(|b| b.id == "rerata_26_oct")
        .unwrap();
    // Gaps of 122 s, 598 s and 2 h 7 min.
    let lens: Vec<f64> = rep.gaps.iter().map(|g| (g[1] - g[0]).round()).collect();
    assert!(lens.contains(&598.0) && lens.contains(&(hms("14:04:50") - hms("11:57:19"))));
    assert!(lens.contains(&122.0), "{lens:?}");
    let g = rep.gaps.iter().find(|g| g[1] - g[0] > 5000.0).unwrap();
    let s = a.state_at(0.5 * (g[0] + g[1]));
    assert!(s.in_gap && s.racing);
    // The other boat's 99 s gap is marked too.
    let b = r
        .report
        .boats
        .iter()
        .find(|b| b.id != "rerata_26_oct")
        .unwrap();
    assert!(
        b.gaps.iter().any(|g| (g[1] - g[0] - 99.0).abs() < 0.5),
        "{b:?}"
    );
    // Two boats: the start is the later first fix (09:07:31).
    assert_eq!(r.report.start_time.as_deref(), Some("2025-10-26T09:07:31Z"));
}

#[test]
fn sailgp_frozen_fixes_and_spikes_are_removed_and_heel_read() {
    let files: Vec<String> = ["AUS", "ITA", "BRA", "NZL"]
        .iter()
        .map(|b| format!("sailgp-auckland-2025/boat_logs/data_{b}.csv"))
        .collect();
    let refs: Vec<&str> = files.iter().map(|s| s.as_str()).collect();
    let r = load(&refs);
    for (b, rep) in r.boats.iter().zip(&r.report.boats) {
        // The limit is 1.2 × the log's top GPS_SOG (≤ 51 kn): 61 kn at most.
        assert!(
            rep.max_speed_kn < 62.0 && rep.max_speed_kn > 50.0,
            "{rep:?}"
        );
        assert!(rep.max_step_speed_kn <= rep.max_speed_kn + 1e-9);
        assert!(b.has_heel());
        // The inter-race gaps (8–18 min) and the 31–33 s gap are marked.
        assert!(rep.gaps.iter().any(|g| g[1] - g[0] > 400.0), "{rep:?}");
        assert!(
            rep.gaps
                .iter()
                .any(|g| (31.0..=34.0).contains(&(g[1] - g[0]))),
            "{rep:?}"
        );
    }
    let ita = r.report.boats.iter().find(|b| b.id == "ITA").unwrap();
    // ITA: 110 kn and 86 kn from frozen positions (README): gone.
    assert!(ita.frozen_removed >= 3, "{ita:?}");
    assert!(ita.max_step_speed_kn < 62.0);
    let aus = r.report.boats.iter().find(|b| b.id == "AUS").unwrap();
    assert!(aus.frozen_removed >= 1);
    // Removing frozen fixes and spikes costs well under 1 % of the samples.
    for rep in &r.report.boats {
        assert!(
            (rep.samples_read - rep.samples_kept) * 100 < rep.samples_read,
            "{rep:?}"
        );
    }
    // The logged heading is used: at a sample it equals HEADING_deg of that row.
    // data_AUS.csv 03:06:00 row: HEADING_deg 98.95, HEEL_deg 2.21.
    let start = r.start_time.unwrap();
    let t = 3.0 * 3600.0 + 6.0 * 60.0
        - (start.hour() as f64 * 3600.0 + start.minute() as f64 * 60.0 + start.second() as f64);
    let aus_b = &r.boats[r.boat_index("AUS").unwrap()];
    let s = aus_b.state_at(t);
    assert!((s.heading_deg - 98.95).abs() < 1e-3, "{s:?}");
    assert!((s.heel_deg.unwrap() - 2.21).abs() < 1e-5);
}

#[test]
fn files_of_three_kinds_combine() {
    // A GPX boat, a CSV boat and a native JSON boat (with an origin and start) in one race.
    let dir = std::env::temp_dir().join(format!("race-combine-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("extra.json");
    std::fs::write(
        &json,
        r#"{"name": "mixed", "origin": {"lat": 39.408, "lon": -0.3187},
            "start_time": "2025-06-21T11:23:29Z",
            "boats": [{"id": "J1", "track": [[0, 0, 0], [10, 30, 0]]}],
            "marks": [{"name": "M", "position": [100, -50]}]}"#,
    )
    .unwrap();
    let csv = dir.join("log.csv");
    std::fs::write(
        &csv,
        "time,lat,lon,heel\n2025-06-21 11:23:29,39.408,-0.3187,1\n2025-06-21 11:23:39,39.408,-0.3184,3\n",
    )
    .unwrap();
    let r = race::Race::load(&[
        common::data("valencia/2025-06-21-ESP29375-P01.gpx"),
        csv.clone(),
        json.clone(),
    ])
    .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(r.boats.len(), 3);
    assert_eq!(r.name, "mixed");
    // The JSON's origin is the race origin, so its metres are kept exactly.
    let j = &r.boats[r.boat_index("J1").unwrap()];
    assert_eq!(j.fixes()[1].x, 30.0);
    // The CSV boat sits at the JSON origin at t = 0 (same lat/lon), within a millimetre.
    let c = &r.boats[r.boat_index("log").unwrap()];
    let s = c.state_at(0.0);
    assert!(
        s.position[0].abs() < 1e-3 && s.position[1].abs() < 1e-3,
        "{s:?}"
    );
    // 0.0003° of longitude at 39.408° N: 25.8 m east in 10 s.
    let e = c.state_at(10.0).position[0];
    let expect = 0.0003f64.to_radians() * 6_378_137.0 * 39.408f64.to_radians().cos()
        / (1.0 - 0.006_694_38 * 39.408f64.to_radians().sin().powi(2)).sqrt();
    assert!((e - expect).abs() < 1e-3, "{e} vs {expect}");
    assert_eq!(s.heel_deg, Some(1.0));
    assert_eq!(c.state_at(5.0).heel_deg, Some(2.0));
}
