//! Reading race files (native JSON, GPX, CSV boat logs and instrument exports, Expedition
//! logs, NMEA 0183 logs, SailGP / AC race XML, maxSail meta-data JSON, FIT, TCX, KML / KMZ,
//! NMEA 2000 bus logs: candump, Actisense CSV, canboat JSON) and assembling them into one
//! [`Race`](crate::Race): a common origin and start, cleaning, course and roundings.

use serde::Serialize;
use time::OffsetDateTime;

use crate::Wind;
use crate::clean::MPS_PER_KNOT;
use crate::error::{RaceError, RaceResult};
use crate::geo::GeoPoint;
use crate::text::quote;
use crate::track::Logged;

mod assemble;
mod csv;
mod detect;
mod expedition;
mod fit;
mod gpx;
mod json;
mod kml;
pub(crate) mod marks;
mod maxsail;
mod n2k;
mod n2k_logs;
mod nmea;
mod packed;
mod race_xml;
mod recorder;
mod rules;
mod tcx;
mod timefmt;
mod xml_text;

pub(crate) use assemble::assemble;
pub use detect::Format;
pub(crate) use fit::fit_crc;
pub use rules::{MAX_SAILING_SPEED_KN, TIME_OUTLIER_GAP_S};
pub(crate) use rules::{lines, spike_limit_mps};

/// The default spike limit for a GPS track of unknown class: 20 knots. No dinghy or keelboat
/// of a club fleet sails faster (a planing 470 peaks near 15 kn); the Gdańsk spike is 37.7 kn.
pub const DEFAULT_MAX_SPEED_KN: f64 = 20.0;

/// Coordinates as a file gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Coords {
    /// Degrees.
    Geo,
    /// Race metres in the file's own frame (around its `origin`, if it has one).
    Local,
}

/// Time as a file gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Times {
    /// Seconds since `EPOCH_UNIX` (2020-01-01).
    Absolute,
    /// Seconds since the race start (of the file's `start_time`, if it has one).
    Relative,
}

#[derive(Debug, Clone, Copy)]
pub(crate) struct RawPoint {
    pub t: f64,
    /// lat, lon (Geo) or x, z (Local).
    pub c: [f64; 2],
    pub logged: Logged,
    /// m/s or NaN.
    pub sog: f64,
}

#[derive(Debug, Clone)]
pub(crate) struct RawBoat {
    pub id: String,
    pub name: String,
    pub color: Option<String>,
    pub points: Vec<RawPoint>,
    pub max_speed_mps: f64,
}

#[derive(Debug, Clone)]
pub(crate) struct RawMark {
    pub name: String,
    pub c: [f64; 2],
}

/// A course element as a file states it: one mark, or a gate or line of two marks.
#[derive(Debug, Clone)]
pub(crate) struct RawCourseMark {
    pub name: String,
    /// Names of its marks (one, or two for a gate or a line).
    pub marks: Vec<String>,
    pub kind: crate::course::MarkKind,
    /// "Port", "Starboard", "SP", "PS" as the file says.
    pub rounding: Option<String>,
}

/// A logged channel over time (wind, boat speed, heading, heel): the file's times and units
/// named in `unit`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Series {
    /// The boat it belongs to, or `None` for the race (e.g. a committee boat's wind).
    pub boat: Option<String>,
    /// "tws", "twd", "aws", "awa", "bsp", "heading", "heel".
    pub channel: String,
    pub unit: String,
    /// Race seconds once assembled.
    pub t: Vec<f64>,
    pub v: Vec<f32>,
}

/// What one file gave: its format, what was read and kept, and every rule that dropped data.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct FileReport {
    pub file: String,
    /// The format detected from the content, e.g. "NMEA 0183".
    pub format: String,
    /// Rows, sentences or track points read.
    pub records_read: usize,
    /// Position fixes handed to cleaning (every boat of the file).
    pub fixes: usize,
    /// Channels found besides positions: "heading", "heel", "bsp", "tws", "twd", …
    pub channels: Vec<String>,
    /// Where the calendar date comes from, or why there is none.
    pub date_source: String,
    /// Rule → records it dropped while reading (bad checksums, blank rows, …).
    pub dropped: Vec<(String, usize)>,
    /// Positions among `dropped` (a fix that was in the file and is not in `fixes`): more of
    /// them than `fixes` refuses the file unless `--keep-going` (the silent-loss rule).
    pub fixes_dropped: usize,
}

/// Options for loading races from several files.
#[derive(Debug, Clone, Default)]
pub struct LoadOptions {
    /// Load a boat even when cleaning drops more than half of its samples (with a warning).
    pub keep_going: bool,
    /// For GPX tracks spanning several sessions (days): the session to race, 1-based.
    pub session: Option<usize>,
    /// Course order as mark names; a gate as `G1a/G1b`.
    pub course: Option<Vec<String>>,
    /// Marks for tracks that have none: (file name, contents) of a GPX, JSON or CSV.
    pub marks: Option<(String, Vec<u8>)>,
}

/// Everything one file contributes.
#[derive(Debug, Clone)]
pub(crate) struct Source {
    pub file: String,
    pub coords: Coords,
    pub times: Times,
    pub name: Option<String>,
    /// Local-coordinate files: the geographic point of their (0, 0).
    pub origin: Option<GeoPoint>,
    /// Seconds since `EPOCH_UNIX` of the file's t = 0 (relative times) or of the given start.
    pub start_time: Option<f64>,
    /// maxSail: the start is `minutes` after the first fix of the named track file.
    pub start_after_track: Option<(String, f64)>,
    pub boats: Vec<RawBoat>,
    pub marks: Vec<RawMark>,
    pub course: Option<Vec<String>>,
    /// The course is one lap of an out-and-back: repeat `course[1..]` while the boats sail it.
    pub repeat_laps: bool,
    pub wind: Option<Wind>,
    pub warnings: Vec<String>,
    /// Gates and lines (SailGP race XML, `--course`): the course as compound marks.
    pub compound: Vec<RawCourseMark>,
    /// The course boundary polygon (lat, lon), where a file states one.
    pub boundary: Vec<[f64; 2]>,
    pub series: Vec<Series>,
    pub report: FileReport,
    /// Times of day only (no date): the tracks are aligned by time of day.
    pub time_of_day: bool,
    /// GPX tracks of several sessions: (boat id, index of each session's first point, then
    /// the number of points).
    pub sessions: Vec<(String, Vec<usize>)>,
}

impl Source {
    pub(crate) fn new(file: &str, coords: Coords, times: Times) -> Self {
        Source {
            file: file.to_string(),
            coords,
            times,
            name: None,
            origin: None,
            start_time: None,
            start_after_track: None,
            boats: Vec::new(),
            marks: Vec::new(),
            course: None,
            repeat_laps: false,
            wind: None,
            warnings: Vec::new(),
            compound: Vec::new(),
            boundary: Vec::new(),
            series: Vec::new(),
            report: FileReport {
                file: file.to_string(),
                format: String::new(),
                records_read: 0,
                fixes: 0,
                channels: Vec::new(),
                date_source: String::new(),
                dropped: Vec::new(),
                fixes_dropped: 0,
            },
            time_of_day: false,
            sessions: Vec::new(),
        }
    }

    /// Count `n` records dropped by `rule` (nothing when 0), with a warning.
    pub(crate) fn drop_rule(&mut self, rule: &str, n: usize) {
        if n == 0 {
            return;
        }
        self.warnings.push(format!(
            "{}: {} {rule}; skipped",
            self.file,
            crate::text::count(n)
        ));
        self.report.dropped.push((rule.to_string(), n));
    }

    /// Count `n` positions dropped by `rule`, like [`Source::drop_rule`], and add them to the
    /// positions the silent-loss rule weighs against the fixes kept.
    pub(crate) fn drop_fixes(&mut self, rule: &str, n: usize) {
        self.drop_rule(rule, n);
        self.report.fixes_dropped += n;
    }
}

/// The file name's stem (no folders, no extension).
pub(crate) fn stem(file: &str) -> &str {
    let base = file.rsplit(['/', '\\']).next().unwrap_or(file);
    base.rsplit_once('.').map_or(base, |(s, _)| s)
}

/// A sail number in a file name (`2025-06-21-ESP29375-P01` → `ESP29375`), else the stem.
pub(crate) fn boat_id_from_file(file: &str) -> String {
    let s = stem(file);
    s.split(['-', '_', ' ', '.'])
        .find(|tok| {
            tok.len() >= 5
                && tok[..3].bytes().all(|b| b.is_ascii_uppercase())
                && tok[3..].bytes().all(|b| b.is_ascii_digit())
        })
        .unwrap_or(s)
        .to_string()
}

/// Absolute times are seconds since 2020-01-01T00:00Z inside the importer: a 2025 time is then
/// ~1.7e8 s, resolved to 3e-8 s in f64 (Unix seconds would keep only 2.4e-7 s).
pub(crate) const EPOCH_UNIX: i64 = 1_577_836_800;

pub(crate) fn epoch_seconds(t: OffsetDateTime) -> f64 {
    (t.unix_timestamp() - EPOCH_UNIX) as f64 + t.nanosecond() as f64 * 1e-9
}

/// The largest race file read, bytes (checked before reading to the end, so `/dev/zero` or a
/// mistaken disk image is refused at once): 1 GiB, ten times a long 10 Hz instrument log.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// Parse one file by its content (the extension only breaks ties).
pub(crate) fn parse(file: &str, bytes: &[u8], opts: &LoadOptions) -> RaceResult<Source> {
    // Containers and binary formats, by their magic bytes: gzip (any format inside), KMZ
    // (zipped KML), FIT.
    if packed::is_gzip(bytes) {
        let inner = packed::gunzip(file, bytes)?;
        if packed::is_gzip(&inner) {
            return Err(RaceError::in_file(
                file,
                "is gzip inside gzip; unpack it once",
            ));
        }
        return parse(file, &inner, opts);
    }
    if packed::is_zip(bytes) {
        let kml = packed::kml_of_kmz(file, bytes)?;
        return finish(kml::parse(file, &kml, "KMZ")?, "KMZ");
    }
    if fit::is_fit(bytes) {
        return finish(fit::parse(file, bytes)?, "FIT");
    }
    let decoded = rules::utf8_of(file, bytes)?;
    let bytes = &decoded[..];
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(RaceError::in_file(file, "the file is empty"));
    }
    let format = detect::detect(file, bytes)?;
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        RaceError::at_line(file, line as u64, "the text is not valid UTF-8")
    })?;
    let s = match format {
        Format::MaxSail => maxsail::parse(file, text),
        Format::NativeJson => json::parse(file, text),
        Format::Gpx => gpx::parse(file, text, opts.session),
        Format::Csv => csv::parse(file, text),
        Format::Expedition => expedition::parse(file, text),
        Format::Nmea => nmea::parse(file, text),
        Format::RaceXml => race_xml::parse(file, text),
        Format::Tcx => tcx::parse(file, text),
        Format::Kml => kml::parse(file, text, "KML"),
        Format::N2kCandump => n2k_logs::parse_candump(file, text),
        Format::N2kPlain => n2k_logs::parse_plain(file, text),
        Format::N2kJson => n2k_logs::parse_json(file, text),
    }?;
    finish(s, format.name())
}

/// The report's format (where the reader named none) and fix count.
fn finish(mut s: Source, format: &str) -> RaceResult<Source> {
    if s.report.format.is_empty() {
        s.report.format = format.to_string();
    }
    rules::drop_time_outliers(&mut s);
    s.report.fixes = s.boats.iter().map(|b| b.points.len()).sum();
    Ok(s)
}

/// A boat id or mark name quoted for a message.
pub(crate) fn q(s: &str) -> String {
    quote(s)
}

/// What is wrong with a geographic point read from a file, if anything.
pub(crate) fn geo_problem(lat: f64, lon: f64) -> Option<String> {
    if !(lat.is_finite() && lat.abs() <= 90.0) {
        Some(format!(
            "latitude {} is not a number in [-90, 90]",
            crate::text::number(lat)
        ))
    } else if !(lon.is_finite() && lon.abs() <= 180.0) {
        Some(format!(
            "longitude {} is not a number in [-180, 180]",
            crate::text::number(lon)
        ))
    } else {
        None
    }
}

pub(crate) fn knots_to_mps(v: f64) -> f64 {
    v * MPS_PER_KNOT
}
