//! Generated logs of the watch and bus formats for the import benchmark (`regatta bench --only
//! race`): one boat off Valencia sailing loops (under 5 kn) at 10 Hz, as a SocketCAN candump
//! (PGNs 129025, 129026, 127250, 130306 each tenth of a second), canboat analyzer JSON lines
//! (the same messages), a TCX file and a FIT file (records with position and speed).
//! Deterministic.

use std::fmt::Write;

/// Unix seconds of the first fix: 2025-06-21T11:00:00Z.
const T0_UNIX: i64 = 1_750_503_600;

/// Position at tenth-second `i`: loops of 500 m and 600 m.
fn position(i: usize) -> (f64, f64) {
    let t = i as f64 / 10.0;
    let lat = 39.40 + 500.0 * (t / 300.0).sin() / 111_195.0;
    let lon = -0.30 + 600.0 * (t / 400.0).cos() / 86_000.0;
    (lat, lon)
}

/// The calendar time of tenth-second `i` from 2025-06-21T11:00Z: (day of June, hour, minute,
/// second, millisecond).
fn stamp(i: usize) -> (usize, usize, usize, usize, usize) {
    let ms = 11 * 3_600_000 + i * 100;
    let s = ms / 1000;
    (
        21 + s / 86_400,
        s / 3600 % 24,
        s / 60 % 60,
        s % 60,
        ms % 1000,
    )
}

/// The NMEA 2000 payloads of tenth-second `i` (canboat layouts; see `import::n2k`).
fn n2k_payloads(i: usize) -> [(u32, [u8; 8]); 4] {
    let (lat, lon) = position(i);
    let mut pos = [0u8; 8];
    pos[..4].copy_from_slice(&((lat * 1e7).round() as i32).to_le_bytes());
    pos[4..].copy_from_slice(&((lon * 1e7).round() as i32).to_le_bytes());
    let cog = ((i % 600) as u16 * 10).to_le_bytes();
    let hdg = ((i % 600) as u16 * 10 + 100).to_le_bytes();
    [
        (129_025, pos),
        (129_026, [i as u8, 0xFC, cog[0], cog[1], 200, 0, 0xFF, 0xFF]),
        (
            127_250,
            [i as u8, hdg[0], hdg[1], 0xFF, 0x7F, 0xFF, 0x7F, 0xFC],
        ),
        (130_306, [i as u8, 0x00, 0x02, 0x10, 0x27, 2, 0xFF, 0xFF]),
    ]
}

/// A candump -l log of at least `bytes` bytes.
pub fn candump_log(bytes: usize) -> String {
    let mut s = String::with_capacity(bytes + 256);
    let mut i = 0usize;
    while s.len() < bytes {
        let t = T0_UNIX as f64 + i as f64 / 10.0;
        for (pgn, d) in n2k_payloads(i) {
            let _ = write!(s, "({t:.6}) can0 {:08X}#", 2 << 26 | pgn << 8 | 0x2B);
            for b in d {
                let _ = write!(s, "{b:02X}");
            }
            s.push('\n');
        }
        i += 1;
    }
    s
}

/// canboat analyzer JSON lines of at least `bytes` bytes (the candump's messages decoded).
pub fn canboat_json_log(bytes: usize) -> String {
    let mut s = String::with_capacity(bytes + 512);
    let mut i = 0usize;
    while s.len() < bytes {
        let (lat, lon) = position(i);
        let (d, h, m, sec, ms) = stamp(i);
        let ts = format!("2025-06-{d:02}-{h:02}:{m:02}:{sec:02}.{ms:03}");
        let a = (i % 600) as f64 * 0.0573;
        let _ = writeln!(
            s,
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":129025,"description":"Position, Rapid Update","fields":{{"Latitude":{lat:.7},"Longitude":{lon:.7}}}}}"#
        );
        let _ = writeln!(
            s,
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":129026,"description":"COG & SOG, Rapid Update","fields":{{"SID":{},"COG Reference":"True","COG":{a:.1},"SOG":2.00}}}}"#,
            i % 250
        );
        let _ = writeln!(
            s,
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":127250,"description":"Vessel Heading","fields":{{"SID":{},"Heading":{:.1},"Reference":"True"}}}}"#,
            i % 250,
            a + 0.6
        );
        let _ = writeln!(
            s,
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":130306,"description":"Wind Data","fields":{{"SID":{},"Wind Speed":5.12,"Wind Angle":57.3,"Reference":"Apparent"}}}}"#,
            i % 250
        );
        i += 1;
    }
    s
}

/// A TCX file of at least `bytes` bytes (one lap).
pub fn tcx_log(bytes: usize) -> String {
    let mut s = String::with_capacity(bytes + 512);
    s.push_str(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<TrainingCenterDatabase xmlns=\"http://www.garmin.com/xmlschemas/TrainingCenterDatabase/v2\"><Activities><Activity Sport=\"Other\"><Lap><Track>\n",
    );
    let mut i = 0usize;
    while s.len() < bytes {
        let (lat, lon) = position(i);
        let (d, h, m, sec, ms) = stamp(i);
        let _ = writeln!(
            s,
            "<Trackpoint><Time>2025-06-{d:02}T{h:02}:{m:02}:{sec:02}.{ms:03}Z</Time><Position><LatitudeDegrees>{lat:.7}</LatitudeDegrees><LongitudeDegrees>{lon:.7}</LongitudeDegrees></Position></Trackpoint>"
        );
        i += 1;
    }
    s.push_str("</Track></Lap></Activity></Activities></TrainingCenterDatabase>\n");
    s
}

/// A FIT activity of `fixes` records at 1 Hz (FIT timestamps are whole seconds): file_id,
/// then `record` messages (timestamp, position_lat, position_long in semicircles, speed in
/// mm/s).
pub fn fit_log(fixes: usize) -> Vec<u8> {
    const FIT_EPOCH_UNIX: i64 = 631_065_600;
    let mut d = Vec::with_capacity(fixes * 15 + 64);
    // Definition, local 0 = file_id: type (enum) = 4 activity, manufacturer (uint16) = 1.
    d.extend_from_slice(&[0x40, 0, 0, 0, 0, 2, 0, 1, 0x00, 1, 2, 0x84]);
    d.extend_from_slice(&[0, 4, 1, 0]);
    // Definition, local 1 = record: timestamp, position_lat, position_long, speed.
    d.extend_from_slice(&[
        0x41, 0, 0, 20, 0, 4, 253, 4, 0x86, 0, 4, 0x85, 1, 4, 0x85, 6, 2, 0x84,
    ]);
    let sc = |deg: f64| (deg * 2_147_483_648.0 / 180.0).round() as i32;
    for k in 0..fixes {
        let (lat, lon) = position(k * 10);
        d.push(1);
        d.extend_from_slice(&((T0_UNIX - FIT_EPOCH_UNIX + k as i64) as u32).to_le_bytes());
        d.extend_from_slice(&sc(lat).to_le_bytes());
        d.extend_from_slice(&sc(lon).to_le_bytes());
        d.extend_from_slice(&2000u16.to_le_bytes());
    }
    let mut f = vec![14, 0x20];
    f.extend_from_slice(&2132u16.to_le_bytes());
    f.extend_from_slice(&(d.len() as u32).to_le_bytes());
    f.extend_from_slice(b".FIT");
    let hc = crate::import::fit_crc(&f);
    f.extend_from_slice(&hc.to_le_bytes());
    f.extend_from_slice(&d);
    let c = crate::import::fit_crc(&f);
    f.extend_from_slice(&c.to_le_bytes());
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stamps_roll_over_midnight() {
        // 13 h after 11:00 is 00:00 of the next day.
        assert_eq!(stamp(13 * 36_000), (22, 0, 0, 0, 0));
        assert_eq!(stamp(1), (21, 11, 0, 0, 100));
    }

    #[test]
    fn generated_logs_load_with_every_fix() {
        for (name, bytes, fixes) in [
            ("b.log", candump_log(100_000).into_bytes(), None),
            ("b.json", canboat_json_log(100_000).into_bytes(), None),
            ("b.tcx", tcx_log(100_000).into_bytes(), None),
            ("b.fit", fit_log(500), Some(500)),
        ] {
            let r = crate::Race::from_files(&[(name, &bytes)]).unwrap_or_else(|e| panic!("{e}"));
            let rep = &r.report.file_reports[0];
            assert!(rep.fixes > 100, "{name}: {rep:?}");
            if let Some(n) = fixes {
                assert_eq!(rep.fixes, n);
            }
            assert!(rep.dropped.is_empty(), "{name}: {:?}", rep.dropped);
        }
    }
}
