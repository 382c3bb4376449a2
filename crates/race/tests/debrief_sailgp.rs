//! The debrief against SailGP's own instruments (Auckland 2025, race 25011905): the boats'
//! logs are loaded as positions only (time, latitude, longitude and the GPS's speed over
//! ground; every instrument column cut away: heading, wind, boat speed) with the race XML, and what Regatta derives is compared with what the boats measured:
//! true wind angle sign changes (tacks and gybes), distance to the start line at the gun, and
//! the fleet's estimated wind against the logged true wind direction (TWD).
//!
//! Skips, counted, where ../shared/data is absent (see `debrief_common.rs`).

mod debrief_common;
use debrief_common::{hms, read_shared, skip};

use race::Race;
use race::debrief::manoeuvres::{ManoeuvreKind, Settings, side_of, side_runs};
use race::debrief::wind::{WindSource, angle_diff, circular_mean};
use race::debrief::{Debrief, StartLine};

const BOATS: [&str; 11] = [
    "AUS", "BRA", "CAN", "DEN", "ESP", "GBR", "GER", "ITA", "NZL", "SUI", "USA",
];
const RACE: &str = "25011905.0";
const GUN: &str = "03:08:00";
const XML: &str = "races/sailgp-auckland-2025/race_xmls/25011905_03-13-55.xml";

/// One instrument row of race 25011905: race seconds and the columns compared.
#[derive(Debug, Clone, Copy)]
struct Row {
    t: f64,
    twa: f64,
    twd: f64,
    sog_kmh: f64,
    tts: f64,
    dtl: f64,
}

struct Logs {
    /// Per boat: the positions-only CSV and the instrument rows of race 25011905.
    boats: Vec<(String, String, Vec<Row>)>,
}

fn logs() -> Option<Logs> {
    let mut boats = Vec::new();
    for b in BOATS {
        let text = read_shared(&format!(
            "races/sailgp-auckland-2025/boat_logs/data_{b}.csv"
        ))?;
        // Positions, and the GPS's own speed over ground: the importer sets the class speed
        // limit for spikes from the log's top SOG (without it, 20 kn, and an F50 sails 50).
        let mut csv =
            String::from("BOAT,DATETIME,LATITUDE_GPS_unk,LONGITUDE_GPS_unk,GPS_SOG_km_h_1\n");
        let mut rows = Vec::new();
        for l in text.lines().skip(1) {
            let c: Vec<&str> = l.split(',').collect();
            csv.push_str(&format!("{},{},{},{},{}\n", c[0], c[1], c[3], c[4], c[6]));
            if c[38] != RACE {
                continue;
            }
            let f = |i: usize| c[i].parse::<f64>().unwrap_or(f64::NAN);
            rows.push(Row {
                t: hms(&c[1][11..]) - hms(GUN),
                twa: f(8),
                twd: f(10),
                sog_kmh: f(6),
                tts: f(39),
                dtl: f(43),
            });
        }
        boats.push((b.to_string(), csv, rows));
    }
    Some(Logs { boats })
}

fn load(l: &Logs) -> Race {
    let xml = read_shared(XML).unwrap();
    let mut files: Vec<(String, Vec<u8>)> = vec![("race.xml".into(), xml.into_bytes())];
    for (b, csv, _) in &l.boats {
        files.push((format!("{b}.csv"), csv.clone().into_bytes()));
    }
    let refs: Vec<(&str, &[u8])> = files
        .iter()
        .map(|(n, b)| (n.as_str(), b.as_slice()))
        .collect();
    let r = Race::from_files(&refs).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        r.series.iter().all(|s| s.channel != "twd"),
        "positions only: no wind may come through"
    );
    r
}

/// The instrument's side changes over [from, to]: the same sides and hold rule as the detector
/// (margin, hold, minimum speed) applied to SailGP's own TWA, and the raw sign changes.
fn instrument_changes(rows: &[Row], from: f64, to: f64, st: &Settings) -> (usize, usize, usize) {
    let rows: Vec<&Row> = rows.iter().filter(|r| r.t >= from && r.t <= to).collect();
    let mut sogs: Vec<f64> = rows.iter().map(|r| r.sog_kmh).collect();
    sogs.sort_by(f64::total_cmp);
    let median = sogs.get(sogs.len() / 2).copied().unwrap_or(0.0);
    let times: Vec<f64> = rows.iter().map(|r| r.t).collect();
    let sides: Vec<i8> = rows
        .iter()
        .map(|r| {
            side_of(
                r.twa,
                r.sog_kmh >= st.min_speed_fraction * median,
                st.margin_deg,
            )
        })
        .collect();
    let runs = side_runs(&times, &sides, st.hold_s);
    let (mut tacks, mut gybes) = (0, 0);
    for w in runs.windows(2) {
        let mut a = rows[w[0].last].twa;
        for k in w[0].last + 1..=w[1].first {
            a += angle_diff(rows[k].twa, rows[k - 1].twa);
        }
        if a.abs() < 180.0 {
            tacks += 1;
        } else {
            gybes += 1;
        }
    }
    let raw = rows
        .windows(2)
        .filter(|w| w[0].twa.signum() != w[1].twa.signum())
        .count();
    (tacks, gybes, raw)
}

#[test]
fn manoeuvres_from_positions_match_the_sign_changes_of_sailgp_true_wind_angle() {
    let Some(l) = logs() else {
        return skip(
            "sailgp manoeuvres",
            "../shared/data/races/sailgp-auckland-2025",
        );
    };
    let race = load(&l);
    let d = Debrief::of(&race);
    let wind = d.wind.as_ref().unwrap();
    assert_eq!(wind.source, WindSource::Estimated);
    let st = Settings::default();
    let mut lines = Vec::new();
    let (mut total, mut off_by_more_than_one) = (0, 0);
    let (mut kinds, mut kind_wrong) = (0, Vec::new());
    for bm in &d.manoeuvres {
        let (_, _, rows) = l.boats.iter().find(|b| b.0 == bm.id).unwrap();
        // A log that covers less than 90 % of the boat's racing span is not comparable (CAN's
        // log holds 629 rows of the day): counted and said.
        let covered = rows
            .iter()
            .filter(|r| r.t >= bm.from_s && r.t <= bm.to_s)
            .count() as f64;
        if covered < 0.9 * (bm.to_s - bm.from_s) {
            lines.push(format!(
                "{}: ours {} tacks {} gybes; SailGP's log covers {covered:.0} s of {:.0}: not compared",
                bm.id,
                bm.tacks,
                bm.gybes,
                bm.to_s - bm.from_s
            ));
            continue;
        }
        let (it, ig, raw) = instrument_changes(rows, bm.from_s, bm.to_s, &st);
        lines.push(format!(
            "{}: ours {} tacks {} gybes; SailGP TWA {} tacks {} gybes ({} raw sign changes)",
            bm.id, bm.tacks, bm.gybes, it, ig, raw
        ));
        let (ours, theirs) = (bm.tacks + bm.gybes, it + ig);
        total += 1;
        if ours.abs_diff(theirs) > 1 {
            off_by_more_than_one += 1;
        }
        // Every manoeuvre's kind agrees with what the instrument's TWA did then: a tack
        // passes head to wind (|TWA| < 90° at some row within 8 s), a gybe dead downwind.
        for m in &bm.manoeuvres {
            let near: Vec<f64> = rows
                .iter()
                .filter(|r| (r.t - m.t).abs() <= 8.0)
                .map(|r| r.twa.abs())
                .collect();
            let agrees = match m.kind {
                ManoeuvreKind::Tack => near.iter().any(|a| *a < 90.0),
                ManoeuvreKind::Gybe => near.iter().any(|a| *a > 90.0),
            };
            kinds += 1;
            if !agrees {
                kind_wrong.push(format!("{} {:?} at {:.0} s", bm.id, m.kind, m.t));
            }
        }
    }
    eprintln!("{}", lines.join("\n"));
    assert!(off_by_more_than_one == 0, "{}", lines.join("\n"));
    assert!(kind_wrong.is_empty(), "{kind_wrong:?} of {kinds}");
    assert!(total >= 10, "{total} boats compared");
}

#[test]
fn estimated_wind_from_positions_is_within_its_uncertainty_of_sailgp_twd() {
    let Some(l) = logs() else {
        return skip("sailgp wind", "../shared/data/races/sailgp-auckland-2025");
    };
    let race = load(&l);
    let w = race::debrief::wind::estimate(&race).unwrap();
    // The fleet's TWD over the racing part of race 25011905.
    let twd_at = |t0: f64, t1: f64| {
        circular_mean(
            l.boats
                .iter()
                .flat_map(|b| b.2.iter())
                .filter(|r| r.t >= t0 && r.t < t1 && r.twd.is_finite())
                .map(|r| (r.twd, 1.0)),
        )
        .0
    };
    let (_, end) = race.time_span();
    let mean_twd = twd_at(0.0, end.min(1500.0));
    let err = angle_diff(w.from_deg, mean_twd);
    let mut windows = Vec::new();
    for &(t, from) in &w.samples {
        let m = twd_at(t - 300.0, t + 300.0);
        if m.is_finite() {
            windows.push(angle_diff(from, m));
        }
    }
    let rms = (windows.iter().map(|e| e * e).sum::<f64>() / windows.len() as f64).sqrt();
    eprintln!(
        "estimate {:.1}° ± {:.1}° vs SailGP TWD {mean_twd:.1}°: error {err:.1}°; \
         {} windows, RMS {rms:.1}°, worst {:.1}°",
        w.from_deg,
        w.uncertainty_deg,
        windows.len(),
        windows.iter().fold(0.0f64, |a, e| a.max(e.abs()))
    );
    assert!(err.abs() <= 2.0 * w.uncertainty_deg, "error {err}");
    assert!(err.abs() < 10.0);
}

/// Ignored: it fails, and the cause lies outside the data (the next test). At SailGP's own gun our distance to the
/// race XML's SL1–SL2 segment is 141–191 m with every boat on the course side, against SailGP's
/// DTL of 2–61 m (8 boats with rows at the gun). Ruled out (docs/debrief.md): the gun time,
/// a datum offset, a moved mark, a time lag. SailGP's DTL over the minute before each gun of
/// three races fits the distance to a line 4–5° off SL1–SL2 and 177–185 m further on the
/// course side (median residual 2–3 m), which no point of the XML gives. Run with `--ignored`
/// to see the table.
#[test]
#[ignore = "ours 141-191 m over the XML line vs SailGP DTL 2-61 m: SailGP measures to a line ~180 m upwind of the XML SL1-SL2 (docs/debrief.md)"]
fn distance_to_the_line_at_the_gun_matches_sailgp_dtl() {
    let Some(l) = logs() else {
        return skip("sailgp start", "../shared/data/races/sailgp-auckland-2025");
    };
    let race = load(&l);
    let d = Debrief::of(&race);
    let line = StartLine::of(&race, d.wind.as_ref()).unwrap();
    let mut lines = Vec::new();
    let mut errs = Vec::new();
    for (id, _, rows) in &l.boats {
        // SailGP's own gun: where its countdown (PC_TTS_s) reaches 0; its DTL there, linear
        // between the rows around it.
        let Some(k) = rows
            .iter()
            .position(|r| r.tts <= 0.0 || r.t >= 5.0)
            .filter(|&k| k > 0 && rows[k].t - rows[k - 1].t <= 2.0)
        else {
            lines.push(format!("{id}: no SailGP rows around the gun"));
            continue;
        };
        let (a, b) = (rows[k - 1], rows[k]);
        let t_gun = a.t + a.tts;
        let f = (t_gun - a.t) / (b.t - a.t);
        let dtl = a.dtl + f * (b.dtl - a.dtl);
        let bi = race.boat_index(id).unwrap();
        let ours = line.boat_at(&race.boats[bi], t_gun);
        let at_zero = line.boat_at(&race.boats[bi], 0.0);
        lines.push(format!(
            "{id}: SailGP gun at {t_gun:+.2} s, DTL {dtl:.1} m; ours there {:.1} m to the \
             segment ({:.1} m to the line), at race time 0 {:.1} m, over early {}",
            ours.distance_to_segment_m,
            ours.distance_to_line_m,
            at_zero.distance_to_segment_m,
            at_zero.over_early
        ));
        errs.push(ours.distance_to_segment_m - dtl);
    }
    eprintln!("{}", lines.join("\n"));
    let worst = errs.iter().fold(0.0f64, |a, e| a.max(e.abs()));
    assert!(worst < 25.0, "{}", lines.join("\n"));
}

/// What SailGP's `PC_DTL_m` measures to, found from their own figures: over the minute before
/// the gun (every boat's rows while its countdown still runs) the DTL is the perpendicular
/// distance to one straight line, fitted here (direction by a 0.1° scan, offset by the
/// median; residuals by their median, robust to the few rows where a boat sails past an end).
/// That line is turned 4–5° from the race XML's SL1–SL2 and lies 177–185 m further on the
/// course side: the line the boats started on is about 180 m upwind of the XML's, which is why
/// `distance_to_the_line_at_the_gun_matches_sailgp_dtl` fails. If a later data set's XML
/// agreed with SailGP's line, this test would fail and that one pass.
#[test]
fn sailgp_measures_the_distance_to_a_line_180_m_upwind_of_the_xml_line() {
    let Some(l) = logs() else {
        return skip(
            "sailgp dtl line",
            "../shared/data/races/sailgp-auckland-2025",
        );
    };
    let race = load(&l);
    let d = Debrief::of(&race);
    let line = StartLine::of(&race, d.wind.as_ref()).unwrap();
    // (race metres [x, z] of the boat, SailGP's DTL) before the gun.
    let mut rows: Vec<([f64; 2], f64)> = Vec::new();
    for (id, _, rs) in &l.boats {
        let b = &race.boats[race.boat_index(id).unwrap()];
        let (t0, t1) = b.time_span();
        for r in rs {
            if (-60.0..=0.0).contains(&r.t)
                && r.tts > 0.5
                && r.t >= t0
                && r.t <= t1
                && r.dtl.is_finite()
            {
                rows.push((b.state_at(r.t).position, r.dtl));
            }
        }
    }
    assert!(rows.len() > 300, "{} rows", rows.len());
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    // DTL = c - p.n for the unit normal n towards the course side.
    let mut best = (f64::INFINITY, 0.0, 0.0, [0.0, 0.0]);
    for k in 0..3600 {
        let th = (k as f64 / 10.0).to_radians();
        let n = [th.cos(), th.sin()];
        let v: Vec<f64> = rows
            .iter()
            .map(|(p, dtl)| dtl + p[0] * n[0] + p[1] * n[1])
            .collect();
        let c = median(v.clone());
        let spread = median(v.iter().map(|x| (x - c).abs()).collect());
        if spread < best.0 {
            best = (spread, th, c, n);
        }
    }
    let (spread, _, c, n) = best;
    let turn = (n[0] * line.normal[0] + n[1] * line.normal[1])
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    let offset = c - (line.pin[0] * n[0] + line.pin[1] * n[1]);
    eprintln!(
        "{} rows: SailGP's line is turned {turn:.1}° from SL1-SL2 and {offset:.0} m beyond it on \
         the course side; median residual {spread:.1} m",
        rows.len()
    );
    assert!(
        spread < 4.0,
        "median residual {spread} m: not one straight line"
    );
    assert!((3.0..6.0).contains(&turn), "turned {turn}°");
    assert!(
        (170.0..195.0).contains(&offset),
        "{offset} m beyond the XML line"
    );
}
