//! Race files of the watch, tracker and bus formats written from their published layouts:
//! one boat, 10 fixes 1 s apart going north from (LAT0, LON0), shared by the format tests and
//! the fuzz seeds.
#![allow(dead_code)]

use std::io::Write;

pub const T0_UNIX: i64 = 1_750_503_600;
pub const LAT0: f64 = 39.42;
pub const LON0: f64 = -0.31;
pub const STEP_DEG: f64 = 1e-5;

pub fn fix(k: usize) -> (f64, f64) {
    (LAT0 + k as f64 * STEP_DEG, LON0)
}

pub fn can_id(priority: u32, pgn: u32, source: u32) -> u32 {
    priority << 26 | pgn << 8 | source
}

pub fn n2k_messages(k: usize) -> Vec<(u32, Vec<u8>)> {
    let (lat, lon) = fix(k);
    let mut pos = Vec::new();
    pos.extend_from_slice(&((lat * 1e7).round() as i32).to_le_bytes());
    pos.extend_from_slice(&((lon * 1e7).round() as i32).to_le_bytes());
    // 130306: apparent wind 5.12 m/s at 1.0000 rad (57.2958°).
    let wind = vec![0, 0x00, 0x02, 0x10, 0x27, 2, 0xFF, 0xFF];
    // 127250: heading 1.5708 rad true (90.0002°); deviation, variation not available.
    let mut hdg = vec![0];
    hdg.extend_from_slice(&15_708u16.to_le_bytes());
    hdg.extend_from_slice(&[0xFF, 0x7F, 0xFF, 0x7F, 0xFC]);
    // 128259: 3.00 m/s through the water.
    let mut stw = vec![0];
    stw.extend_from_slice(&300u16.to_le_bytes());
    stw.extend_from_slice(&[0xFF, 0xFF, 0, 0xFF, 0xFF]);
    // 129026: COG 0 rad true, SOG 1.11 m/s.
    let mut cog = vec![0, 0xFC, 0, 0];
    cog.extend_from_slice(&111u16.to_le_bytes());
    cog.extend_from_slice(&[0xFF, 0xFF]);
    vec![
        (129_026, cog),
        (127_250, hdg),
        (130_306, wind),
        (128_259, stw),
        (129_025, pos),
    ]
}

pub fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02X}")).collect()
}

pub fn gnss_message() -> Vec<u8> {
    let mut d = vec![0u8; 43];
    d[1..3].copy_from_slice(&((T0_UNIX / 86_400) as u16).to_le_bytes());
    d[3..7].copy_from_slice(&(((T0_UNIX % 86_400) * 10_000) as u32).to_le_bytes());
    d[7..15].copy_from_slice(&(((LAT0 + 0.09) * 1e16) as i64).to_le_bytes());
    d[15..23].copy_from_slice(&((LON0 * 1e16) as i64).to_le_bytes());
    d
}

pub fn fast_frames(msg: &[u8]) -> Vec<Vec<u8>> {
    let mut frames = vec![{
        let mut f = vec![0x40, msg.len() as u8];
        f.extend_from_slice(&msg[..6]);
        f
    }];
    for (k, chunk) in msg[6..].chunks(7).enumerate() {
        let mut f = vec![0x40 | (k as u8 + 1)];
        f.extend_from_slice(chunk);
        f.resize(8, 0xFF);
        frames.push(f);
    }
    frames
}

pub fn candump_fixture() -> String {
    let mut s = String::from("# candump -l of a fixture bus\n");
    for k in 0..10 {
        let t = T0_UNIX as f64 + k as f64;
        for (pgn, d) in n2k_messages(k) {
            s += &format!("({t:.6}) can0 {:08X}#{}\n", can_id(2, pgn, 0x2B), hex(&d));
        }
    }
    for f in fast_frames(&gnss_message()) {
        s += &format!(
            "({:.6}) can0 {:08X}#{}\n",
            T0_UNIX as f64 + 9.5,
            can_id(3, 129_029, 0x10),
            hex(&f)
        );
    }
    s
}

pub fn canboat_time(k: f64) -> String {
    let t = time::OffsetDateTime::from_unix_timestamp_nanos(((T0_UNIX as f64 + k) * 1e9) as i128)
        .unwrap();
    format!(
        "{:04}-{:02}-{:02}-{:02}:{:02}:{:02}.{:03}",
        t.year(),
        t.month() as u8,
        t.day(),
        t.hour(),
        t.minute(),
        t.second(),
        t.millisecond()
    )
}

pub fn plain_fixture() -> String {
    let mut s = String::new();
    for k in 0..10 {
        for (pgn, d) in n2k_messages(k) {
            let bytes: Vec<String> = d.iter().map(|b| format!("{b:02x}")).collect();
            s += &format!(
                "{},2,{pgn},43,255,{},{}\n",
                canboat_time(k as f64),
                d.len(),
                bytes.join(",")
            );
        }
    }
    // The gateway's reassembled 129029 (length 43) from another source.
    let g: Vec<String> = gnss_message().iter().map(|b| format!("{b:02x}")).collect();
    s += &format!("{},3,129029,16,255,43,{}\n", canboat_time(9.5), g.join(","));
    s
}

pub fn json_fixture() -> String {
    let mut s = String::new();
    for k in 0..10 {
        let (lat, lon) = fix(k);
        let ts = canboat_time(k as f64);
        s += &format!(
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":129026,"description":"COG & SOG, Rapid Update","fields":{{"SID":0,"COG Reference":"True","COG":0.0,"SOG":1.11}}}}"#
        );
        s += "\n";
        s += &format!(
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":127250,"description":"Vessel Heading","fields":{{"SID":0,"Heading":90.0,"Reference":"True"}}}}"#
        );
        s += "\n";
        s += &format!(
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":130306,"description":"Wind Data","fields":{{"SID":0,"Wind Speed":5.12,"Wind Angle":57.3,"Reference":"Apparent"}}}}"#
        );
        s += "\n";
        s += &format!(
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":128259,"description":"Speed","fields":{{"SID":0,"Speed Water Referenced":3.0}}}}"#
        );
        s += "\n";
        s += &format!(
            r#"{{"timestamp":"{ts}","prio":2,"src":43,"dst":255,"pgn":129025,"description":"Position, Rapid Update","fields":{{"Latitude":{lat},"Longitude":{lon}}}}}"#
        );
        s += "\n";
    }
    s
}

pub fn gzip(b: &[u8]) -> Vec<u8> {
    let mut z = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    z.write_all(b).unwrap();
    z.finish().unwrap()
}

pub fn iso(k: usize) -> String {
    let t = time::OffsetDateTime::from_unix_timestamp(T0_UNIX + k as i64).unwrap();
    t.format(&time::format_description::well_known::Rfc3339)
        .unwrap()
}

pub fn tcx_fixture() -> String {
    let mut s = String::from(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<TrainingCenterDatabase xmlns="http://www.garmin.com/xmlschemas/TrainingCenterDatabase/v2" xmlns:ns3="http://www.garmin.com/xmlschemas/ActivityExtension/v2">
 <Activities><Activity Sport="Other"><Id>2025-06-21T11:00:00Z</Id>
"#,
    );
    for lap in 0..2 {
        s += "<Lap StartTime=\"x\"><Track>\n";
        if lap == 0 {
            // A trackpoint before the GPS fix: counted, not a fix.
            s += "<Trackpoint><Time>2025-06-21T10:59:59Z</Time><HeartRateBpm><Value>90</Value></HeartRateBpm></Trackpoint>\n";
        }
        for k in lap * 5..lap * 5 + 5 {
            let (lat, lon) = fix(k);
            s += &format!(
                "<Trackpoint><Time>{}</Time><Position><LatitudeDegrees>{lat}</LatitudeDegrees><LongitudeDegrees>{lon}</LongitudeDegrees></Position><Extensions><ns3:TPX><ns3:Speed>1.11</ns3:Speed></ns3:TPX></Extensions></Trackpoint>\n",
                iso(k)
            );
        }
        s += "</Track></Lap>\n";
    }
    s += "</Activity></Activities><Creator><Name>Instinct 2</Name></Creator></TrainingCenterDatabase>\n";
    s
}

pub fn kml_points_fixture() -> String {
    let mut s = String::from(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document><name>Regatta</name>
<Placemark><name>Windward</name><Point><coordinates>-0.31,39.43,0</coordinates></Point></Placemark>
"#,
    );
    for boat in ["Alpha", "Bravo"] {
        s += &format!("<Folder><name>{boat}</name>\n");
        for k in 0..10 {
            let (lat, lon) = fix(k);
            let lon = if boat == "Bravo" { lon + 0.001 } else { lon };
            s += &format!(
                "<Placemark><TimeStamp><when>{}</when></TimeStamp><Point><coordinates>{lon},{lat},0</coordinates></Point></Placemark>\n",
                iso(k)
            );
        }
        s += "</Folder>\n";
    }
    s += "</Document></kml>\n";
    s
}

pub fn kml_track_fixture() -> String {
    let mut s = String::from(
        r#"<kml xmlns="http://www.opengis.net/kml/2.2" xmlns:gx="http://www.google.com/kml/ext/2.2"><Document>
<Placemark><name>ESP30782</name><gx:Track>
"#,
    );
    for k in 0..10 {
        s += &format!("<when>{}</when>\n", iso(k));
    }
    for k in 0..10 {
        let (lat, lon) = fix(k);
        s += &format!("<gx:coord>{lon} {lat} 0</gx:coord>\n");
    }
    s += "</gx:Track></Placemark>\n<Placemark><LineString><coordinates>-0.31,39.42 -0.30,39.43</coordinates></LineString></Placemark>\n</Document></kml>\n";
    s
}

pub fn fit_crc(bytes: &[u8]) -> u16 {
    const T: [u16; 16] = [
        0x0000, 0xCC01, 0xD801, 0x1400, 0xF001, 0x3C00, 0x2800, 0xE401, 0xA001, 0x6C00, 0x7800,
        0xB401, 0x5000, 0x9C01, 0x8801, 0x4400,
    ];
    let mut crc = 0u16;
    for &b in bytes {
        let tmp = T[(crc & 0xF) as usize];
        crc = (crc >> 4) & 0x0FFF;
        crc = crc ^ tmp ^ T[(b & 0xF) as usize];
        let tmp = T[(crc & 0xF) as usize];
        crc = (crc >> 4) & 0x0FFF;
        crc = crc ^ tmp ^ T[(b >> 4) as usize];
    }
    crc
}

pub fn fit_fixture() -> Vec<u8> {
    const FIT_EPOCH_UNIX: i64 = 631_065_600;
    let mut d = Vec::new();
    let def = |d: &mut Vec<u8>, local: u8, global: u16, fields: &[(u8, u8, u8)]| {
        d.extend_from_slice(&[0x40 | local, 0, 0]);
        d.extend_from_slice(&global.to_le_bytes());
        d.push(fields.len() as u8);
        for f in fields {
            d.extend_from_slice(&[f.0, f.1, f.2]);
        }
    };
    // file_id: type (enum) = 4 activity, manufacturer (uint16) = 1 garmin.
    def(&mut d, 0, 0, &[(0, 1, 0x00), (1, 2, 0x84)]);
    d.extend_from_slice(&[0, 4, 1, 0]);
    // user_profile: friendly_name, 16-byte string.
    def(&mut d, 1, 3, &[(0, 16, 0x07)]);
    d.push(1);
    let mut name = b"Ana Vela".to_vec();
    name.resize(16, 0);
    d.extend_from_slice(&name);
    // record: timestamp uint32, position_lat sint32, position_long sint32, speed uint16.
    def(
        &mut d,
        2,
        20,
        &[(253, 4, 0x86), (0, 4, 0x85), (1, 4, 0x85), (6, 2, 0x84)],
    );
    // lap: timestamp.
    def(&mut d, 3, 19, &[(253, 4, 0x86)]);
    let sc = |deg: f64| (deg * 2_147_483_648.0 / 180.0).round() as i32;
    for k in 0..10 {
        let (lat, lon) = fix(k);
        let ts = (T0_UNIX - FIT_EPOCH_UNIX + k as i64) as u32;
        d.push(2);
        d.extend_from_slice(&ts.to_le_bytes());
        d.extend_from_slice(&sc(lat).to_le_bytes());
        d.extend_from_slice(&sc(lon).to_le_bytes());
        d.extend_from_slice(&1110u16.to_le_bytes());
        if k == 4 || k == 9 {
            d.push(3);
            d.extend_from_slice(&ts.to_le_bytes());
        }
    }
    // session: sport (enum) = 32 sailing.
    def(&mut d, 4, 18, &[(5, 1, 0x00)]);
    d.extend_from_slice(&[4, 32]);
    let mut f = vec![14, 0x20];
    f.extend_from_slice(&2132u16.to_le_bytes());
    f.extend_from_slice(&(d.len() as u32).to_le_bytes());
    f.extend_from_slice(b".FIT");
    let hc = fit_crc(&f);
    f.extend_from_slice(&hc.to_le_bytes());
    f.extend_from_slice(&d);
    let c = fit_crc(&f);
    f.extend_from_slice(&c.to_le_bytes());
    f
}

pub fn ac35_xml() -> String {
    let (lat, lon) = (LAT0, LON0);
    format!(
        r#"<Race><RaceID>11080703</RaceID><RaceType>Fleet</RaceType>
<RaceStartTime Time="2025-06-21T04:00:05-0700" Postpone="false"/>
<Participants><Yacht SourceID="101"/></Participants>
<Course>
 <CompoundMark CompoundMarkID="1" Name="StartLine">
  <Mark SeqID="1" Name="PRO" TargetLat="{lat}" TargetLng="{w}" SourceID="122"/>
  <Mark SeqID="2" Name="PIN" TargetLat="{lat}" TargetLng="{e}" SourceID="123"/>
 </CompoundMark>
 <CompoundMark CompoundMarkID="2" Name="Mark1">
  <Mark SeqID="1" Name="M1" TargetLat="{n}" TargetLng="{lon}" SourceID="131"/>
 </CompoundMark>
</Course>
<CompoundMarkSequence>
 <Corner SeqID="1" CompoundMarkID="1" Rounding="SP" ZoneSize="3"/>
 <Corner SeqID="2" CompoundMarkID="2" Rounding="Port" ZoneSize="3"/>
</CompoundMarkSequence>
<CourseLimit>
 <Limit SeqID="1" Lat="{s}" Lon="{w}"/><Limit SeqID="2" Lat="{n}" Lon="{w}"/><Limit SeqID="3" Lat="{n}" Lon="{e}"/>
</CourseLimit>
</Race>"#,
        w = lon - 0.001,
        e = lon + 0.001,
        n = lat + 0.002,
        s = lat - 0.001,
    )
}
