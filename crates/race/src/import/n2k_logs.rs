//! NMEA 2000 bus logs in the three text forms sailors have: SocketCAN `candump -l`
//! (`(1502984866.421964) can0 09F8012B#F12B6B1B8E5E36FF`: Unix time, interface, 29-bit id,
//! frame bytes), Actisense NGT-1 / canboat plain CSV (`2011-11-24-22:42:04.388,2,129025,36,
//! 255,8,…`: time, priority, PGN, source, destination, length, bytes; fast packets either
//! reassembled by the gateway, length > 8, or frame by frame) and canboat `analyzer -json`
//! lines (`{"timestamp":…,"src":…,"pgn":129025,"fields":{"Latitude":…}}`: decoded fields,
//! angles in degrees, speeds in m/s).
//!
//! One boat per file (named from the file). Positions come from the first source address that
//! sends one (PGN 129025 or 129029); other sources' positions, AIS reports of other vessels,
//! fast packets with a missing frame and unreadable lines are counted. A log whose unreadable
//! lines outnumber its messages is refused, not loaded with what little was left.

use serde::Deserialize;

use super::n2k::{CanId, Decoded, FastPackets, decode, is_fast_packet};
use super::recorder::{Recorder, source};
use super::{EPOCH_UNIX, Source, boat_id_from_file, q};
use crate::error::{RaceError, RaceResult};

/// The three text forms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum N2kForm {
    Candump,
    /// Actisense / canboat plain CSV.
    Plain,
    /// canboat analyzer JSON lines.
    Json,
}

impl N2kForm {
    pub(crate) fn name(self) -> &'static str {
        match self {
            N2kForm::Candump => "NMEA 2000 (SocketCAN candump)",
            N2kForm::Plain => "NMEA 2000 (Actisense / canboat plain CSV)",
            N2kForm::Json => "NMEA 2000 (canboat analyzer JSON)",
        }
    }
}

/// Reading state: decoded values applied to one boat.
struct Bus {
    rec: Recorder,
    fast: FastPackets,
    decoded: Vec<Decoded>,
    /// The source address whose positions make the track.
    gnss_source: Option<u8>,
    other_gnss: usize,
    ais: usize,
    variation: f64,
    messages: usize,
    bad_lines: usize,
    first_bad: Option<(u64, String)>,
}

impl Bus {
    fn new() -> Self {
        Bus {
            rec: Recorder::new(),
            fast: FastPackets::default(),
            decoded: Vec::new(),
            gnss_source: None,
            other_gnss: 0,
            ais: 0,
            variation: f64::NAN,
            messages: 0,
            bad_lines: 0,
            first_bad: None,
        }
    }

    fn bad(&mut self, line: u64, text: &str) {
        self.bad_lines += 1;
        if self.first_bad.is_none() {
            self.first_bad = Some((line, text.to_string()));
        }
    }

    /// One frame (≤ 8 bytes) or one reassembled message at `t` (seconds since EPOCH_UNIX).
    fn message(&mut self, t: f64, id: CanId, data: &[u8]) {
        self.messages += 1;
        let mut out = std::mem::take(&mut self.decoded);
        out.clear();
        if is_fast_packet(id.pgn) && data.len() <= 8 {
            if let Some(msg) = self.fast.frame(id, data) {
                decode(id.pgn, &msg, &mut out);
            }
        } else {
            decode(id.pgn, data, &mut out);
        }
        for d in &out {
            self.apply(t, id.source, *d);
        }
        self.decoded = out;
    }

    fn apply(&mut self, t: f64, source: u8, d: Decoded) {
        let r = &mut self.rec;
        match d {
            Decoded::Position { lat, lon } => {
                if *self.gnss_source.get_or_insert(source) == source {
                    r.fix(t, lat, lon);
                } else {
                    self.other_gnss += 1;
                }
            }
            Decoded::GnssTime { .. } => {}
            Decoded::CogSog { sog, .. } => {
                r.set_sog(sog);
                r.put("sog", "m/s", t, sog);
            }
            Decoded::Heading {
                heading,
                deviation,
                variation,
                magnetic,
            } => {
                if variation.is_finite() {
                    self.variation = variation;
                }
                if !magnetic {
                    r.put("heading", "deg", t, heading);
                } else if self.variation.is_finite() {
                    let dev = if deviation.is_finite() {
                        deviation
                    } else {
                        0.0
                    };
                    r.put(
                        "heading",
                        "deg",
                        t,
                        (heading + dev + self.variation).rem_euclid(360.0),
                    );
                } else {
                    // No variation anywhere yet: kept apart rather than passed off as true.
                    r.put("heading_magnetic", "deg", t, heading);
                }
            }
            Decoded::Wind {
                speed,
                angle,
                reference,
            } => {
                let signed = if angle > 180.0 { angle - 360.0 } else { angle };
                match reference {
                    0 => {
                        r.put("twd", "deg", t, angle);
                        r.put("tws", "m/s", t, speed);
                    }
                    1 if self.variation.is_finite() => {
                        r.put("twd", "deg", t, (angle + self.variation).rem_euclid(360.0));
                        r.put("tws", "m/s", t, speed);
                    }
                    2 => {
                        r.put("awa", "deg", t, signed);
                        r.put("aws", "m/s", t, speed);
                    }
                    3 | 4 => {
                        r.put("twa", "deg", t, signed);
                        r.put("tws", "m/s", t, speed);
                    }
                    _ => {}
                }
            }
            Decoded::Stw { speed } => r.put("bsp", "m/s", t, speed),
            Decoded::Ais { .. } => self.ais += 1,
        }
    }

    fn finish(mut self, file: &str, form: N2kForm, date_source: &str) -> RaceResult<Source> {
        if self.bad_lines > self.messages {
            let (line, text) = self.first_bad.take().unwrap_or_default();
            return Err(RaceError::at_line(
                file,
                line,
                format!(
                    "{} of {} lines are not {} messages, e.g. {}",
                    crate::text::count(self.bad_lines),
                    crate::text::count(self.bad_lines + self.messages),
                    form.name(),
                    q(&text)
                ),
            ));
        }
        if self.rec.points.is_empty() {
            return Err(RaceError::in_file(
                file,
                format!(
                    "the NMEA 2000 log has no position (PGN 129025 or 129029) among {} messages",
                    crate::text::count(self.messages)
                ),
            ));
        }
        let mut s = source(file, form.name());
        s.report.records_read = self.messages;
        s.report.date_source = date_source.to_string();
        s.drop_rule("unreadable lines", self.bad_lines);
        s.drop_rule(
            "positions from a second GNSS source address",
            self.other_gnss,
        );
        s.drop_rule("AIS reports of other vessels", self.ais);
        s.drop_rule(
            "fast-packet messages with a missing frame",
            self.fast.broken,
        );
        let id = boat_id_from_file(file);
        self.rec.finish(&mut s, id.clone(), id);
        Ok(s)
    }
}

fn unix_to_epoch(unix: f64) -> f64 {
    unix - EPOCH_UNIX as f64
}

fn hex_byte(s: &str) -> Option<u8> {
    (s.len() <= 2).then(|| u8::from_str_radix(s, 16).ok())?
}

/// `(1502984866.421964) can0 09F8012B#F12B…` or `(…) can0 09F8012B [8] F1 2B …`.
fn candump_line(l: &str, data: &mut Vec<u8>) -> Option<(f64, u32)> {
    let rest = l.strip_prefix('(')?;
    let (ts, rest) = rest.split_once(')')?;
    let t: f64 = ts.trim().parse().ok().filter(|t: &f64| t.is_finite())?;
    let mut words = rest.split_whitespace();
    let _iface = words.next()?;
    let frame = words.next()?;
    data.clear();
    let id_hex = if let Some((id, bytes)) = frame.split_once('#') {
        if bytes.len() % 2 != 0 || bytes.len() > 16 {
            return None;
        }
        for k in (0..bytes.len()).step_by(2) {
            data.push(hex_byte(bytes.get(k..k + 2)?)?);
        }
        id
    } else {
        let n: usize = words.next()?.trim_matches(['[', ']']).parse().ok()?;
        for w in words.by_ref().take(n) {
            data.push(hex_byte(w)?);
        }
        if data.len() != n {
            return None;
        }
        frame
    };
    // NMEA 2000 uses extended (29-bit) identifiers, written with 8 hex digits.
    if id_hex.len() != 8 {
        return None;
    }
    let id = u32::from_str_radix(id_hex, 16).ok()?;
    (id < 1 << 29).then_some((t, id))
}

pub(crate) fn parse_candump(file: &str, text: &str) -> RaceResult<Source> {
    let mut bus = Bus::new();
    let mut data = Vec::with_capacity(8);
    for (i, l) in text.lines().enumerate() {
        let l = l.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        match candump_line(l, &mut data) {
            Some((t, id)) => bus.message(unix_to_epoch(t), CanId::from_raw(id), &data),
            None => bus.bad(i as u64 + 1, l),
        }
    }
    bus.finish(
        file,
        N2kForm::Candump,
        "candump timestamps (the logging computer's clock, Unix seconds, UTC)",
    )
}

/// canboat's `2011-11-24-22:42:04.388` (or ISO 8601) → seconds since EPOCH_UNIX, UTC.
fn canboat_time(s: &str) -> Option<f64> {
    let s = s.trim();
    if s.len() > 10 && s.as_bytes()[10] == b'-' {
        let fixed = format!("{}T{}", &s[..10], &s[11..]);
        super::timefmt::parse_datetime(&fixed)
    } else {
        super::timefmt::parse_datetime(s)
    }
}

fn plain_line(l: &str, data: &mut Vec<u8>) -> Option<(f64, CanId)> {
    let mut cells = l.split(',');
    let t = canboat_time(cells.next()?)?;
    let priority: u8 = cells.next()?.trim().parse().ok()?;
    let pgn: u32 = cells.next()?.trim().parse().ok()?;
    let source: u8 = cells.next()?.trim().parse().ok()?;
    let _dst: u8 = cells.next()?.trim().parse().ok()?;
    let len: usize = cells.next()?.trim().parse().ok()?;
    data.clear();
    for c in cells {
        data.push(hex_byte(c.trim())?);
    }
    (data.len() == len && pgn < 1 << 18).then_some((
        t,
        CanId {
            priority,
            pgn,
            source,
        },
    ))
}

pub(crate) fn parse_plain(file: &str, text: &str) -> RaceResult<Source> {
    let mut bus = Bus::new();
    let mut data = Vec::with_capacity(8);
    for (i, l) in text.lines().enumerate() {
        let l = l.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        match plain_line(l, &mut data) {
            Some((t, id)) => bus.message(t, id, &data),
            None => bus.bad(i as u64 + 1, l),
        }
    }
    bus.finish(
        file,
        N2kForm::Plain,
        "the capture's timestamps (taken as UTC)",
    )
}

/// A lookup field as canboat writes it: its name, its number, or both.
#[derive(Deserialize)]
#[serde(untagged)]
enum Lookup {
    Name(String),
    Number(f64),
    Both {
        name: Option<String>,
        value: Option<f64>,
    },
}

impl Lookup {
    fn name(&self) -> Option<&str> {
        match self {
            Lookup::Name(n) => Some(n),
            Lookup::Both { name, .. } => name.as_deref(),
            Lookup::Number(_) => None,
        }
    }

    fn number(&self) -> Option<f64> {
        match self {
            Lookup::Number(v) => Some(*v),
            Lookup::Both { value, .. } => *value,
            Lookup::Name(_) => None,
        }
    }

    fn is_magnetic(&self) -> bool {
        self.name() == Some("Magnetic") || self.number() == Some(1.0)
    }

    /// 130306's reference as its number (see `n2k`).
    fn wind_reference(&self) -> Option<u8> {
        if let Some(v) = self.number() {
            return Some(v as u8);
        }
        let n = self.name()?;
        Some(if n.contains("Apparent") {
            2
        } else if n.contains("boat") {
            3
        } else if n.contains("water") {
            4
        } else if n.contains("Magnetic") {
            1
        } else if n.contains("True") {
            0
        } else {
            return None;
        })
    }
}

#[derive(Deserialize, Default)]
struct JsonFields {
    #[serde(rename = "Latitude")]
    latitude: Option<f64>,
    #[serde(rename = "Longitude")]
    longitude: Option<f64>,
    #[serde(rename = "COG")]
    cog: Option<f64>,
    #[serde(rename = "SOG")]
    sog: Option<f64>,
    #[serde(rename = "COG Reference")]
    cog_reference: Option<Lookup>,
    #[serde(rename = "Heading")]
    heading: Option<f64>,
    #[serde(rename = "Deviation")]
    deviation: Option<f64>,
    #[serde(rename = "Variation")]
    variation: Option<f64>,
    #[serde(rename = "Reference")]
    reference: Option<Lookup>,
    #[serde(rename = "Wind Speed")]
    wind_speed: Option<f64>,
    #[serde(rename = "Wind Angle")]
    wind_angle: Option<f64>,
    #[serde(rename = "Speed Water Referenced")]
    stw: Option<f64>,
    #[serde(rename = "User ID")]
    user_id: Option<f64>,
}

#[derive(Deserialize)]
struct JsonMessage {
    timestamp: String,
    #[serde(default)]
    src: u8,
    pgn: u32,
    #[serde(default)]
    fields: JsonFields,
}

fn json_decoded(m: &JsonMessage, out: &mut Vec<Decoded>) {
    let f = &m.fields;
    let nan = |v: Option<f64>| v.unwrap_or(f64::NAN);
    match m.pgn {
        129025 | 129029 => {
            if let (Some(lat), Some(lon)) = (f.latitude, f.longitude) {
                out.push(Decoded::Position { lat, lon });
            }
        }
        129026 => out.push(Decoded::CogSog {
            cog: nan(f.cog),
            sog: nan(f.sog),
            magnetic: f.cog_reference.as_ref().is_some_and(Lookup::is_magnetic),
        }),
        127250 => {
            if let Some(heading) = f.heading {
                out.push(Decoded::Heading {
                    heading,
                    deviation: nan(f.deviation),
                    variation: nan(f.variation),
                    magnetic: f.reference.as_ref().is_some_and(Lookup::is_magnetic),
                });
            }
        }
        130306 => {
            if let (Some(speed), Some(angle), Some(reference)) = (
                f.wind_speed,
                f.wind_angle,
                f.reference.as_ref().and_then(Lookup::wind_reference),
            ) {
                out.push(Decoded::Wind {
                    speed,
                    angle,
                    reference,
                });
            }
        }
        128259 => {
            if let Some(speed) = f.stw {
                out.push(Decoded::Stw { speed });
            }
        }
        129038 | 129039 => {
            if let (Some(lat), Some(lon)) = (f.latitude, f.longitude) {
                out.push(Decoded::Ais {
                    mmsi: f.user_id.unwrap_or(0.0) as u32,
                    lat,
                    lon,
                });
            }
        }
        _ => {}
    }
}

pub(crate) fn parse_json(file: &str, text: &str) -> RaceResult<Source> {
    let mut bus = Bus::new();
    let mut out = Vec::new();
    for (i, l) in text.lines().enumerate() {
        let l = l.trim();
        if l.is_empty() {
            continue;
        }
        let m = serde_json::from_str::<JsonMessage>(l)
            .ok()
            .and_then(|m| canboat_time(&m.timestamp).map(|t| (t, m)));
        let Some((t, m)) = m else {
            bus.bad(i as u64 + 1, l);
            continue;
        };
        bus.messages += 1;
        out.clear();
        json_decoded(&m, &mut out);
        for d in &out {
            bus.apply(t, m.src, *d);
        }
    }
    bus.finish(
        file,
        N2kForm::Json,
        "the analyzer's timestamps (taken as UTC)",
    )
}

/// Which form a text is, from its first lines (None: not NMEA 2000).
pub(crate) fn sniff(text: &str) -> Option<N2kForm> {
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))?;
    let mut data = Vec::new();
    if first.starts_with('(') {
        return candump_line(first, &mut data).map(|_| N2kForm::Candump);
    }
    if first.starts_with('{') {
        return (first.contains("\"pgn\"") && first.contains("\"timestamp\""))
            .then_some(N2kForm::Json);
    }
    plain_line(first, &mut data).map(|_| N2kForm::Plain)
}
