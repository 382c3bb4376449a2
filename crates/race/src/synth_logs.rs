//! Generated instrument logs of a given size, for the import benchmark (`regatta bench --only
//! race`) and its tests: one boat off Valencia sailing a looping track (under 5 kn) at 10 Hz, as an
//! NMEA 0183 log (RMC, HDT and MWV each tenth of a second, CRLF) or as a CSV export (time, lat,
//! lon, sog_kts, hdg, heel). Deterministic.

use std::fmt::Write;

/// Position of the generated boat at tenth-second `i`: loops of 500 m and 600 m, at most
/// 1.7 m/s north-south and 1.5 m/s east-west (86 km per degree of longitude at 39.4° N).
fn position(i: usize) -> (f64, f64) {
    let t = i as f64 / 10.0;
    let lat = 39.40 + 500.0 * (t / 300.0).sin() / 111_195.0;
    let lon = -0.30 + 600.0 * (t / 400.0).cos() / 86_000.0;
    (lat, lon)
}

/// Time of day of tenth-second `i`: (hours, minutes, seconds, tenths), and the day offset.
fn clock(i: usize) -> (usize, usize, usize, usize, usize) {
    let secs = i / 10;
    (
        (secs / 3600) % 24,
        (secs / 60) % 60,
        secs % 60,
        i % 10,
        secs / 86_400,
    )
}

fn sentence(out: &mut String, body: &str) {
    let ck = body.bytes().fold(0u8, |a, b| a ^ b);
    let _ = write!(out, "${body}*{ck:02X}\r\n");
}

/// An NMEA 0183 log of at least `bytes` bytes; one RMC fix per 0.1 s.
pub fn nmea_log(bytes: usize) -> String {
    let mut s = String::with_capacity(bytes + 256);
    let mut i = 0usize;
    while s.len() < bytes {
        let (lat, lon) = position(i);
        let (h, m, sec, tenth, day) = clock(i);
        let (d, ld) = (lat.trunc(), lon.abs().trunc());
        let body = format!(
            "GPRMC,{h:02}{m:02}{sec:02}.{tenth}0,A,{:02}{:08.5},N,{:03}{:08.5},W,4.1,45.0,{:02}0625,,,A",
            d as u32,
            (lat - d) * 60.0,
            ld as u32,
            (lon.abs() - ld) * 60.0,
            21 + day
        );
        sentence(&mut s, &body);
        sentence(
            &mut s,
            &format!("IIHDT,{:.1},T", 40.0 + (i % 50) as f64 * 0.2),
        );
        sentence(
            &mut s,
            &format!("IIMWV,{:.1},T,{:.1},N,A", 40.0 + (i % 30) as f64, 12.0),
        );
        i += 1;
    }
    s
}

/// A CSV export of at least `bytes` bytes; one row per 0.1 s.
pub fn csv_log(bytes: usize) -> String {
    let mut s = String::with_capacity(bytes + 256);
    s.push_str("time,lat,lon,sog_kts,hdg,heel\n");
    let mut i = 0usize;
    while s.len() < bytes {
        let (lat, lon) = position(i);
        let (h, m, sec, tenth, day) = clock(i);
        let _ = writeln!(
            s,
            "2025-06-{:02} {h:02}:{m:02}:{sec:02}.{tenth},{lat:.7},{lon:.7},6.1,{:.1},{:.1}",
            21 + day,
            40.0 + (i % 50) as f64 * 0.2,
            10.0 + (i % 7) as f64
        );
        i += 1;
    }
    s
}

/// A fleet tracker's CSV export (`boat,time,lat,lon`) of `boats` boats with `fixes` fixes each,
/// 1 s apart, rows in time order (every boat's fix of one second, then the next second's), as a
/// tracking provider writes a whole fleet into one file. Boat `k` starts on a 200-wide grid of
/// 11 m × 8.6 m cells off Valencia and sails east at 2 m/s. Deterministic.
pub fn fleet_csv(boats: usize, fixes: usize) -> String {
    let mut s = String::with_capacity(boats * fixes * 48 + 32);
    s.push_str("boat,time,lat,lon\n");
    for i in 0..fixes {
        for k in 0..boats {
            let lat = 39.40 + (k % 200) as f64 * 1e-4;
            let lon = -0.30 + (k / 200) as f64 * 1e-4 + 2.0 * i as f64 / 86_000.0;
            let _ = writeln!(
                s,
                "B{k},2025-06-21 11:{:02}:{:02},{lat:.7},{lon:.7}",
                i / 60,
                i % 60
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_logs_load_with_every_fix_kept() {
        // 2 MB: half an hour at 10 Hz, a full loop of the track.
        for (name, text) in [
            ("g.nmea", nmea_log(2_000_000)),
            ("g.csv", csv_log(2_000_000)),
        ] {
            let r = crate::Race::from_files(&[(name, text.as_bytes())]).unwrap();
            let rep = &r.report.boats[0];
            assert_eq!(rep.samples_kept, rep.samples_read, "{name}");
            assert!(rep.samples_read > 1000, "{name}");
            // 0.1 s apart throughout.
            let f = r.boats[0].fixes();
            assert!(
                f.windows(2).all(|w| (w[1].t - w[0].t - 0.1).abs() < 1e-6),
                "{name}"
            );
        }
    }

    #[test]
    fn a_generated_fleet_loads_every_boat_and_fix() {
        let r = crate::Race::from_files(&[("fleet.csv", fleet_csv(1000, 5).as_bytes())]).unwrap();
        assert_eq!(r.boats.len(), 1000);
        assert!(r.boats.iter().all(|b| b.fixes().len() == 5));
        assert_eq!(r.time_span(), (0.0, 4.0));
    }
}
