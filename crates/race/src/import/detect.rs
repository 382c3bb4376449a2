//! Which format a file is, from its content: the first bytes decide, the extension only
//! breaks ties (a file that looks like nothing known is read as its extension says, so the
//! error names what is wrong in the format it claims).

use crate::error::{RaceError, RaceResult};
use crate::text::quote;

/// A race file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    NativeJson,
    MaxSail,
    Gpx,
    /// Boat logs and instrument or tracker exports (SailGP, Vakaros, Velocitek, generic).
    Csv,
    /// Expedition's log CSV (`Utc` in serial days).
    Expedition,
    Nmea,
    /// SailGP / America's Cup race XML (course, marks, start time).
    RaceXml,
    /// Garmin Training Center XML.
    Tcx,
    /// KML (Google Earth) tracks and placemarks.
    Kml,
    /// NMEA 2000 bus log: SocketCAN `candump -l` text.
    N2kCandump,
    /// NMEA 2000 bus log: Actisense / canboat plain CSV.
    N2kPlain,
    /// NMEA 2000 bus log: canboat `analyzer -json` lines.
    N2kJson,
}

impl Format {
    pub fn name(self) -> &'static str {
        match self {
            Format::NativeJson => "native race JSON",
            Format::MaxSail => "maxSail meta-data JSON",
            Format::Gpx => "GPX",
            Format::Csv => "CSV boat log",
            Format::Expedition => "Expedition log",
            Format::Nmea => "NMEA 0183",
            Format::RaceXml => "SailGP race XML",
            Format::Tcx => "TCX",
            Format::Kml => "KML",
            Format::N2kCandump => super::n2k_logs::N2kForm::Candump.name(),
            Format::N2kPlain => super::n2k_logs::N2kForm::Plain.name(),
            Format::N2kJson => super::n2k_logs::N2kForm::Json.name(),
        }
    }
}

/// How much of the file the detection looks at.
const SNIFF_BYTES: usize = 64 * 1024;

const KNOWN: &str = "a race file is GPX, FIT, TCX, KML or KMZ, native race JSON, CSV, an Expedition log, an NMEA 0183 or NMEA 2000 log or a SailGP / AC race XML (any of them may be gzipped)";

pub(crate) fn detect(file: &str, bytes: &[u8]) -> RaceResult<Format> {
    let head = &bytes[..bytes.len().min(SNIFF_BYTES)];
    if head.contains(&0) {
        return Err(RaceError::in_file(
            file,
            format!("holds binary data (a NUL byte), not text; {KNOWN}"),
        ));
    }
    let text = String::from_utf8_lossy(head);
    let t = text.trim_start();
    let base = file.rsplit(['/', '\\']).next().unwrap_or(file);
    let base = base
        .strip_suffix(".gz")
        .or_else(|| base.strip_suffix(".GZ"))
        .unwrap_or(base);
    let ext = Some(base)
        .and_then(|b| b.rsplit_once('.'))
        .map(|(_, e)| e.to_ascii_lowercase());
    // NMEA 2000 logs first: canboat JSON lines start with `{`, plain CSV captures have cells.
    if let Some(form) = super::n2k_logs::sniff(t) {
        return Ok(match form {
            super::n2k_logs::N2kForm::Candump => Format::N2kCandump,
            super::n2k_logs::N2kForm::Plain => Format::N2kPlain,
            super::n2k_logs::N2kForm::Json => Format::N2kJson,
        });
    }
    if t.starts_with('{') || t.starts_with('[') {
        return Ok(if text.contains("\"BALIZAS\"") {
            Format::MaxSail
        } else {
            Format::NativeJson
        });
    }
    if t.starts_with('<') {
        if text.contains("<gpx") {
            return Ok(Format::Gpx);
        }
        if text.contains("<Race") {
            return Ok(Format::RaceXml);
        }
        if text.contains("<TrainingCenterDatabase") {
            return Ok(Format::Tcx);
        }
        if text.contains("<kml") {
            return Ok(Format::Kml);
        }
    }
    let mut lines = t.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines.next().unwrap_or("");
    if is_nmea_line(first)
        || t.lines()
            .take(20)
            .filter(|l| is_nmea_line(l.trim()))
            .count()
            >= 3
    {
        return Ok(Format::Nmea);
    }
    let cells: Vec<&str> = first.split(',').map(str::trim).collect();
    let has = |n: &str| cells.iter().any(|c| c.eq_ignore_ascii_case(n));
    if cells.len() >= 3
        && has("utc")
        && has("lat")
        && has("lon")
        && (has("bsp") || has("tws") || has("awa"))
    {
        return Ok(Format::Expedition);
    }
    match ext.as_deref() {
        Some("json") => return Ok(Format::NativeJson),
        Some("gpx") => return Ok(Format::Gpx),
        Some("xml") => return Ok(Format::RaceXml),
        Some("nmea") => return Ok(Format::Nmea),
        Some("tcx") => return Ok(Format::Tcx),
        Some("kml") => return Ok(Format::Kml),
        _ => {}
    }
    if cells.len() >= 3 && !t.starts_with('<') {
        return Ok(Format::Csv);
    }
    if ext.as_deref() == Some("csv") {
        return Ok(Format::Csv);
    }
    Err(RaceError::in_file(
        file,
        format!(
            "starts with {}, which is no race format this program reads; {KNOWN}",
            quote(first)
        ),
    ))
}

/// `$GPGLL,…` or `!AIVDM,…`: a sentence start, any talker.
fn is_nmea_line(l: &str) -> bool {
    let b = l.as_bytes();
    b.len() > 7
        && (b[0] == b'$' || b[0] == b'!')
        && b[1..6].iter().all(|c| c.is_ascii_alphanumeric())
        && b[6] == b','
}
