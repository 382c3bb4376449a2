//! FIT activity files (Garmin, Suunto, Coros, Wahoo watches and plotters), decoded by the
//! `fitparser` crate (the FIT SDK's profile, compressed timestamps, developer fields).
//!
//! A FIT file is binary: a 12- or 14-byte header whose bytes 8–11 are `.FIT`, then records.
//! The track is every `record` message with a timestamp and `position_lat`/`position_long`
//! (semicircles: degrees = value × 180 / 2³¹); `enhanced_speed` or `speed` (m/s) is the speed
//! over ground, `heading` where the device logs it. The file's `session`/`sport` names the
//! activity (a sailing watch profile says "sailing") and its `lap` messages split it into laps:
//! a sailing session's laps are marks of the day, not races, so all laps make one track. The
//! boat is named from the athlete (`user_profile.friendly_name`), else the device
//! (`file_id` manufacturer and product), else the file name; its id is always from the file
//! name, so two sailors with the same watch stay two boats.

use fitparser::de::{FitObject, FitStreamProcessor};
use fitparser::profile::MesgNum;
use fitparser::{FitDataField, Value};

use super::recorder::{Recorder, source};
use super::{EPOCH_UNIX, Source, boat_id_from_file};
use crate::error::{RaceError, RaceResult};

/// Degrees per semicircle: 180 / 2³¹ (FIT profile, `position_lat` units).
const DEG_PER_SEMICIRCLE: f64 = 180.0 / 2_147_483_648.0;

/// A FIT file's header: size 12 or 14, `.FIT` at bytes 8–11.
pub(crate) fn is_fit(bytes: &[u8]) -> bool {
    bytes.len() >= 12 && matches!(bytes[0], 12 | 14) && &bytes[8..12] == b".FIT"
}

fn number(v: &Value) -> Option<f64> {
    Some(match v {
        Value::Byte(x) | Value::Enum(x) | Value::UInt8(x) | Value::UInt8z(x) => *x as f64,
        Value::SInt8(x) => *x as f64,
        Value::SInt16(x) => *x as f64,
        Value::UInt16(x) | Value::UInt16z(x) => *x as f64,
        Value::SInt32(x) => *x as f64,
        Value::UInt32(x) | Value::UInt32z(x) => *x as f64,
        Value::SInt64(x) => *x as f64,
        Value::UInt64(x) | Value::UInt64z(x) => *x as f64,
        Value::Float32(x) => *x as f64,
        Value::Float64(x) => *x,
        _ => return None,
    })
    .filter(|x| x.is_finite())
}

fn text(v: &Value) -> Option<String> {
    match v {
        Value::String(s) if !s.trim().is_empty() => Some(s.trim().to_string()),
        _ => None,
    }
}

fn field<'a>(fields: &'a [FitDataField], name: &str) -> Option<&'a Value> {
    fields.iter().find(|f| f.name() == name).map(|f| f.value())
}

/// FIT CRC-16 (FIT SDK, "FIT File Protocol": the nibble table below, register from 0).
pub(crate) fn fit_crc(bytes: &[u8]) -> u16 {
    const T: [u16; 16] = [
        0x0000, 0xCC01, 0xD801, 0x1400, 0xF001, 0x3C00, 0x2800, 0xE401, 0xA001, 0x6C00, 0x7800,
        0xB401, 0x5000, 0x9C01, 0x8801, 0x4400,
    ];
    let mut crc = 0u16;
    for &b in bytes {
        for nibble in [b & 0xF, b >> 4] {
            let tmp = T[(crc & 0xF) as usize];
            crc = ((crc >> 4) & 0x0FFF) ^ tmp ^ T[nibble as usize];
        }
    }
    crc
}

/// Every FIT file of the chain (a file may hold several, back to back) complete and matching
/// its CRC: header size, `.FIT`, the declared data size present, and the 2-byte CRC after the
/// data equal to the CRC of header and data (0 = not computed). Checked before decoding
/// because the decoder panics on some damaged files (found by fuzzing: an arithmetic overflow
/// on a header longer than the rest of the file).
fn check_chain(bytes: &[u8]) -> Result<(), String> {
    let mut at = 0usize;
    while at < bytes.len() {
        let b = &bytes[at..];
        if !is_fit(b) {
            return Err(format!(
                "{} bytes after the FIT data are not another FIT file",
                crate::text::count(b.len())
            ));
        }
        let header = b[0] as usize;
        let data = u32::from_le_bytes([b[4], b[5], b[6], b[7]]) as usize;
        let end = header.saturating_add(data).saturating_add(2);
        if b.len() < end {
            return Err(format!(
                "the FIT file is cut: its header declares {} bytes of records, {} are present",
                crate::text::count(data),
                crate::text::count(b.len().saturating_sub(header + 2))
            ));
        }
        let want = u16::from_le_bytes([b[end - 2], b[end - 1]]);
        if want != 0 && fit_crc(&b[..end - 2]) != want {
            return Err("the FIT file's checksum does not match its content (damaged)".into());
        }
        at += end;
    }
    Ok(())
}

pub(crate) fn parse(file: &str, bytes: &[u8]) -> RaceResult<Source> {
    check_chain(bytes).map_err(|m| RaceError::in_file(file, m))?;
    let mut rec = Recorder::new();
    let (mut records_read, mut no_position, mut laps) = (0usize, 0usize, 0usize);
    let (mut sport, mut athlete, mut maker, mut product) = (None, None, None, None);
    let mut handle = |r: fitparser::FitDataRecord| {
        let f = r.fields();
        match r.kind() {
            MesgNum::Record => {
                records_read += 1;
                let Some(Value::Timestamp(ts)) = field(f, "timestamp") else {
                    no_position += 1;
                    return;
                };
                let t = (ts.timestamp() - EPOCH_UNIX) as f64
                    + ts.timestamp_subsec_nanos() as f64 * 1e-9;
                let speed = field(f, "enhanced_speed")
                    .or_else(|| field(f, "speed"))
                    .and_then(number);
                if let Some(v) = speed {
                    rec.set_sog(v);
                    rec.put("sog", "m/s", t, v);
                }
                if let Some(h) = field(f, "heading").and_then(number) {
                    rec.put("heading", "deg", t, h);
                }
                match (
                    field(f, "position_lat").and_then(number),
                    field(f, "position_long").and_then(number),
                ) {
                    (Some(la), Some(lo)) => {
                        rec.fix(t, la * DEG_PER_SEMICIRCLE, lo * DEG_PER_SEMICIRCLE)
                    }
                    _ => no_position += 1,
                }
            }
            MesgNum::Lap => laps += 1,
            MesgNum::Session | MesgNum::Sport if sport.is_none() => {
                sport = field(f, "sport").and_then(text);
            }
            MesgNum::UserProfile if athlete.is_none() => {
                athlete = field(f, "friendly_name").and_then(text);
            }
            MesgNum::FileId if maker.is_none() && product.is_none() => {
                maker = field(f, "manufacturer").and_then(text);
                product = field(f, "product_name")
                    .or_else(|| field(f, "garmin_product"))
                    .and_then(text);
            }
            _ => {}
        }
    };
    // Message by message (fitparser's stream decoder), so no list of every decoded record is
    // held: the FIT decoder's records are several times the size of the fixes they carry.
    // A second guard: a file crafted to pass the CRC can still reach a panic in the decoder.
    let handle = &mut handle;
    let decoded = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let mut processor = FitStreamProcessor::new();
        let mut input = bytes;
        while !input.is_empty() {
            let (rest, obj) = processor.deserialize_next(input)?;
            input = rest;
            match obj {
                FitObject::Header(_) => processor.reset(),
                FitObject::DataMessage(m) => handle(processor.decode_message(m)?),
                FitObject::DefinitionMessage(_) | FitObject::Crc(_) => {}
            }
        }
        Ok::<(), fitparser::Error>(())
    }))
    .map_err(|_| RaceError::in_file(file, "is not a readable FIT file (the FIT decoder failed)"))?;
    decoded.map_err(|e| {
        RaceError::in_file(
            file,
            format!(
                "is not a readable FIT file ({})",
                crate::text::cut(&crate::text::escape(&e.to_string()), 80)
            ),
        )
    })?;
    if rec.points.is_empty() {
        return Err(RaceError::in_file(
            file,
            format!(
                "the FIT file has no record with a time and a position among {} records (an activity without GPS, or not an activity)",
                crate::text::count(records_read)
            ),
        ));
    }
    let device = match (maker, product) {
        (Some(m), Some(p)) => Some(format!("{m} {p}")),
        (m, p) => m.or(p),
    };
    let mut format = String::from("FIT");
    let about: Vec<String> = [
        device.clone(),
        sport.as_ref().map(|s| format!("sport {s}")),
        (laps > 0).then(|| format!("{laps} laps in one track")),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !about.is_empty() {
        format = format!("FIT ({})", about.join(", "));
    }
    let mut s = source(file, &format);
    s.report.records_read = records_read;
    s.report.date_source = "FIT timestamps (seconds since 1989-12-31T00:00Z, UTC)".into();
    s.drop_rule("records without a position", no_position);
    let id = boat_id_from_file(file);
    let name = athlete.or(device).unwrap_or_else(|| id.clone());
    rec.finish(&mut s, id, name);
    Ok(s)
}
