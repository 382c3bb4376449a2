//! NMEA 0183 logs (any talker): positions from RMC, GLL and GGA; the date from RMC or ZDA;
//! heading (HDT, or HDG + variation), boat speed (VHW), speed over ground (RMC, VTG), and wind
//! (MWV true and apparent, MWD, VWT) kept as time series.
//!
//! A small parser rather than the `nmea` crate: on the sample log (plaka.log) nmea 0.8 rejects
//! all 7,250 VWT sentences (the true wind) and all 7,250 GSV sentences for their empty trailing
//! fields, and it gives no access to the fields of sentences it does not model. Here every line
//! is checked against its checksum (XOR of the bytes between `$` and `*`); a bad or missing
//! checksum (a truncated line) skips the line and is counted, never fatal. Lines end in CR, LF
//! or CRLF, and a line may hold several sentences (as some multiplexers write them): each `$`
//! or `!` starts one. Every position dropped is counted by its reason (the receiver's own "no
//! fix" status V or quality 0, a latitude or longitude out of range, no time yet), and a log
//! that would lose most of its positions is refused unless `--keep-going` (the silent-loss
//! rule, see `assemble`). A time field that is not `hhmmss[.s…]` (`110000inf`, `nan`, `1e300`)
//! refuses the log at its line: reading on would shift every later fix.
//!
//! Time: sentences without a time (HDT, MWV, …) take the time of the last timed sentence.
//! Where the log has no date anywhere, times are times of day (a roll-over past midnight adds
//! a day) and the report says the date is missing.

use super::timefmt::{days_in_month, epoch_of};
use super::{Coords, RawBoat, RawPoint, Series, Source, Times};
use crate::clean::MPS_PER_KNOT;
use crate::error::{RaceError, RaceResult};
use crate::track::Logged;

/// A channel while reading: name, unit, (day, time of day, value); 16 bytes a sample.
type Channel = (&'static str, &'static str, Vec<(i32, f32, f64)>);

/// Per-log reading state.
#[derive(Default)]
struct Log {
    /// Days since the log's first timed sentence, and the time of day.
    day: i64,
    tod: Option<f64>,
    /// A date seen (days since 1970 of the day `day` = 0).
    base_day: Option<i64>,
    /// Fixes as (day, time of day, lat, lon, sog, heading).
    fixes: Vec<(i64, f64, f64, f64, f32, f32)>,
    sog: f32,
    heading: f32,
    variation: f64,
    /// Channel → (day, tod, value).
    channels: Vec<Channel>,
    /// Positions dropped: the receiver said "no fix" (status V, quality 0).
    no_fix_status: usize,
    /// Positions dropped: latitude or longitude unreadable or out of range.
    bad_position: usize,
    /// Positions dropped: no timed sentence before them.
    no_time_yet: usize,
    /// The last epoch (day, time of day) that gave a fix or a dropped position: RMC, GGA and
    /// GLL of one epoch are one position, kept or dropped once.
    last_epoch: Option<(i64, f64)>,
}

/// Why a position was dropped.
#[derive(Clone, Copy)]
enum Lost {
    NoFixStatus,
    BadPosition,
}

/// Why a sentence refuses the log.
type SentenceError = String;

fn hex(b: u8) -> Option<u8> {
    (b as char).to_digit(16).map(|d| d as u8)
}

/// The sentence body between `$`/`!` and `*` if its checksum holds; Err(true) if the line
/// has no checksum (truncated), Err(false) if the checksum is wrong.
fn checked(line: &str) -> Result<&str, bool> {
    let start = line.find(['$', '!']).ok_or(true)?;
    let body_end = line[start..].find('*').ok_or(true)? + start;
    let ck = line
        .as_bytes()
        .get(body_end + 1..body_end + 3)
        .ok_or(true)?;
    let want = hex(ck[0])
        .zip(hex(ck[1]))
        .map(|(a, b)| a << 4 | b)
        .ok_or(false)?;
    let body = &line[start + 1..body_end];
    if body.bytes().fold(0u8, |a, b| a ^ b) == want {
        Ok(body)
    } else {
        Err(false)
    }
}

fn f(fields: &[&str], i: usize) -> f64 {
    fields
        .get(i)
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(f64::NAN)
}

fn field<'a>(fields: &[&'a str], i: usize) -> &'a str {
    fields.get(i).copied().unwrap_or("")
}

/// `ddmm.mmmm` / `dddmm.mmmm` with its hemisphere → degrees.
fn coord(v: &str, hemi: &str) -> f64 {
    let Ok(x) = v.parse::<f64>() else {
        return f64::NAN;
    };
    let deg = (x / 100.0).trunc();
    let d = deg + (x - deg * 100.0) / 60.0;
    match hemi {
        "S" | "W" => -d,
        "N" | "E" => d,
        _ => f64::NAN,
    }
}

/// `hhmmss[.ss]` → seconds of the day.
fn hms(v: &str) -> Option<f64> {
    let b = v.as_bytes();
    if b.len() < 6 || !b[..6].iter().all(u8::is_ascii_digit) {
        return None;
    }
    let n = |i: usize| ((b[i] - b'0') * 10 + (b[i + 1] - b'0')) as f64;
    // Only `.` and digits after the seconds: `f64::parse` would take "inf", "nan" or "1e300".
    let frac: f64 = match &b[6..] {
        [] => 0.0,
        [b'.', digits @ ..] if digits.iter().all(u8::is_ascii_digit) => {
            if digits.is_empty() {
                0.0
            } else {
                v[6..].parse().ok()?
            }
        }
        _ => return None,
    };
    let (h, m, s) = (n(0), n(2), n(4));
    (h < 24.0 && m < 60.0 && s < 61.0).then_some(h * 3600.0 + m * 60.0 + s + frac)
}

impl Log {
    /// A timed sentence at `tod`: a roll-over past midnight (time going back by over 12 h)
    /// starts the next day.
    fn at(&mut self, tod: f64) {
        if let Some(prev) = self.tod
            && tod < prev - 43_200.0
        {
            self.day += 1;
        }
        self.tod = Some(tod);
    }

    fn date(&mut self, y: i64, m: u32, d: u32) {
        if self.base_day.is_none() && (1..=12).contains(&m) && d >= 1 && d <= days_in_month(y, m) {
            self.base_day = Some(super::timefmt::days_from_civil(y, m, d) - self.day);
        }
    }

    /// The time field `i` of a timed sentence: read into the log's clock when present;
    /// present but not a time of day refuses the log.
    fn time_field(&mut self, fields: &[&str], i: usize) -> Result<(), SentenceError> {
        let v = field(fields, i).trim();
        if v.is_empty() {
            return Ok(());
        }
        match hms(v) {
            Some(t) => {
                self.at(t);
                Ok(())
            }
            None => Err(format!(
                "{} time is {}, not a time of day hhmmss[.ss]",
                fields[0].get(2..).unwrap_or(""),
                super::q(v)
            )),
        }
    }

    /// Whether the current epoch already gave a fix or a drop; marks it as seen.
    fn seen_epoch(&mut self) -> bool {
        let now = self.tod.map(|t| (self.day, t));
        let seen = now.is_some() && self.last_epoch == now;
        self.last_epoch = now;
        seen
    }

    fn drop_position(&mut self, why: Lost) {
        if self.tod.is_none() {
            self.no_time_yet += 1;
            return;
        }
        let later_fix = self
            .fixes
            .last()
            .is_some_and(|l| Some((l.0, l.1)) == self.tod.map(|t| (self.day, t)));
        if self.seen_epoch() || later_fix {
            return;
        }
        match why {
            Lost::NoFixStatus => self.no_fix_status += 1,
            Lost::BadPosition => self.bad_position += 1,
        }
    }

    fn fix(&mut self, lat: f64, lon: f64) {
        let Some(tod) = self.tod else {
            self.no_time_yet += 1;
            return;
        };
        if !(lat.is_finite() && lon.is_finite()) || super::geo_problem(lat, lon).is_some() {
            self.drop_position(Lost::BadPosition);
            return;
        }
        // RMC, GGA and GLL of one epoch are one fix.
        if let Some(l) = self.fixes.last()
            && l.0 == self.day
            && l.1 == tod
        {
            return;
        }
        self.last_epoch = Some((self.day, tod));
        self.fixes
            .push((self.day, tod, lat, lon, self.sog, self.heading));
    }

    fn put(&mut self, channel: &'static str, unit: &'static str, v: f64) {
        let Some(tod) = self.tod else { return };
        if !v.is_finite() {
            return;
        }
        let k = match self.channels.iter().position(|c| c.0 == channel) {
            Some(k) => k,
            None => {
                self.channels.push((channel, unit, Vec::new()));
                self.channels.len() - 1
            }
        };
        self.channels[k].2.push((self.day as i32, v as f32, tod));
    }

    /// A speed field and its unit letter → m/s.
    fn speed(v: f64, unit: &str) -> f64 {
        match unit {
            "N" => v * MPS_PER_KNOT,
            "K" => v / 3.6,
            "M" => v,
            _ => f64::NAN,
        }
    }

    fn sentence(&mut self, body: &str) -> Result<(), SentenceError> {
        let fields: Vec<&str> = body.split(',').collect();
        let kind = fields[0].get(2..).unwrap_or("");
        match kind {
            "RMC" => {
                self.time_field(&fields, 1)?;
                let d = field(&fields, 9);
                if d.len() == 6 && d.bytes().all(|b| b.is_ascii_digit()) {
                    let n = |i: usize| d[i..i + 2].parse::<u32>().unwrap_or(0);
                    let yy = n(4) as i64;
                    self.date(if yy < 80 { 2000 + yy } else { 1900 + yy }, n(2), n(0));
                }
                let sog = f(&fields, 7) * MPS_PER_KNOT;
                if sog.is_finite() {
                    self.sog = sog as f32;
                }
                if field(&fields, 2) == "A" {
                    let lat = coord(field(&fields, 3), field(&fields, 4));
                    let lon = coord(field(&fields, 5), field(&fields, 6));
                    self.fix(lat, lon);
                } else {
                    self.drop_position(Lost::NoFixStatus);
                }
            }
            "GLL" => {
                self.time_field(&fields, 5)?;
                if field(&fields, 6) != "V" {
                    let lat = coord(field(&fields, 1), field(&fields, 2));
                    let lon = coord(field(&fields, 3), field(&fields, 4));
                    self.fix(lat, lon);
                } else {
                    self.drop_position(Lost::NoFixStatus);
                }
            }
            "GGA" => {
                self.time_field(&fields, 1)?;
                if f(&fields, 6) > 0.0 {
                    let lat = coord(field(&fields, 2), field(&fields, 3));
                    let lon = coord(field(&fields, 4), field(&fields, 5));
                    self.fix(lat, lon);
                } else {
                    self.drop_position(Lost::NoFixStatus);
                }
            }
            "ZDA" => {
                self.time_field(&fields, 1)?;
                let (d, m, y) = (f(&fields, 2), f(&fields, 3), f(&fields, 4));
                if d.is_finite() && m.is_finite() && y.is_finite() {
                    self.date(y as i64, m as u32, d as u32);
                }
            }
            "VTG" => {
                let sog = f(&fields, 5) * MPS_PER_KNOT;
                if sog.is_finite() {
                    self.sog = sog as f32;
                }
            }
            "HDT" => {
                let h = f(&fields, 1);
                if h.is_finite() {
                    self.heading = h as f32;
                    self.put("heading", "deg", h);
                }
            }
            "HDG" => {
                let (h, dev, var) = (f(&fields, 1), f(&fields, 2), f(&fields, 4));
                let sign = |s: &str| if s == "W" { -1.0 } else { 1.0 };
                if var.is_finite() {
                    self.variation = var * sign(field(&fields, 5));
                }
                if h.is_finite() {
                    let dev = if dev.is_finite() {
                        dev * sign(field(&fields, 3))
                    } else {
                        0.0
                    };
                    let t = (h + dev + self.variation).rem_euclid(360.0);
                    self.heading = t as f32;
                    self.put("heading", "deg", t);
                }
            }
            "VHW" => {
                let mut v = Log::speed(f(&fields, 5), "N");
                if !v.is_finite() {
                    v = Log::speed(f(&fields, 7), "K");
                }
                self.put("bsp", "m/s", v);
            }
            "MWV" => {
                let (a, v) = (f(&fields, 1), Log::speed(f(&fields, 3), field(&fields, 4)));
                if field(&fields, 5) == "V" {
                    return Ok(());
                }
                match field(&fields, 2) {
                    "R" => {
                        self.put("awa", "deg", a);
                        self.put("aws", "m/s", v);
                    }
                    "T" => {
                        // 0–360 clockwise from the bow → ±180 (VWT's convention).
                        self.put("twa", "deg", if a > 180.0 { a - 360.0 } else { a });
                        self.put("tws", "m/s", v);
                    }
                    _ => {}
                }
            }
            "MWD" => {
                self.put("twd", "deg", f(&fields, 1));
                let mut v = Log::speed(f(&fields, 5), "N");
                if !v.is_finite() {
                    v = Log::speed(f(&fields, 7), "M");
                }
                self.put("tws", "m/s", v);
            }
            "VWT" => {
                let a = f(&fields, 1);
                let a = if field(&fields, 2) == "L" { -a } else { a };
                self.put("twa", "deg", a);
                self.put("tws", "m/s", Log::speed(f(&fields, 3), "N"));
            }
            _ => {}
        }
        Ok(())
    }
}

/// Whether a sentence (its text from `$`/`!`, checksum or not) carries a position.
fn is_position(sentence: &str) -> bool {
    matches!(sentence.get(3..6), Some("RMC" | "GLL" | "GGA"))
}

/// The sentences of one line: each `$` or `!` starts one (NMEA reserves both characters, so
/// neither appears inside a field); text before the first is not a sentence.
fn sentences_of(line: &str) -> impl Iterator<Item = &str> {
    let starts: Vec<usize> = line.match_indices(['$', '!']).map(|(i, _)| i).collect();
    (0..starts.len()).map(move |k| {
        let end = starts.get(k + 1).copied().unwrap_or(line.len());
        &line[starts[k]..end]
    })
}

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut log = Log {
        sog: f32::NAN,
        heading: f32::NAN,
        variation: 0.0,
        ..Log::default()
    };
    let (mut sentences, mut bad, mut truncated, mut other) = (0usize, 0usize, 0usize, 0usize);
    // Position sentences lost to a wrong or missing checksum (for the silent-loss rule).
    let mut positions_unchecked = 0usize;
    for (line_no, line) in super::lines(text) {
        if line.trim().is_empty() {
            continue;
        }
        if !line.contains(['$', '!']) {
            other += 1;
            continue;
        }
        for one in sentences_of(line) {
            sentences += 1;
            match checked(one) {
                Ok(body) => log
                    .sentence(body)
                    .map_err(|why| RaceError::at_line(file, line_no, why))?,
                Err(broken) => {
                    if broken {
                        truncated += 1;
                    } else {
                        bad += 1;
                    }
                    positions_unchecked += usize::from(is_position(one));
                }
            }
        }
    }
    if log.fixes.is_empty() {
        return Err(RaceError::in_file(
            file,
            format!(
                "the NMEA log has no position with a time (RMC, GLL or GGA) among {} sentences",
                crate::text::count(sentences)
            ),
        ));
    }
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    s.report.records_read = sentences;
    s.drop_rule("sentences with a wrong checksum", bad);
    s.drop_rule("truncated sentences (no checksum)", truncated);
    s.drop_rule("lines that are not NMEA sentences", other);
    s.drop_fixes(
        "position sentences the receiver marked as no fix (RMC or GLL status V, GGA quality 0)",
        log.no_fix_status,
    );
    s.drop_fixes(
        "positions with a latitude outside [-90, 90] or a longitude outside [-180, 180]",
        log.bad_position,
    );
    s.drop_fixes("positions before the log's first time", log.no_time_yet);
    s.report.fixes_dropped += positions_unchecked;
    let base = match log.base_day {
        Some(d) => {
            s.report.date_source = "RMC or ZDA sentences".into();
            d
        }
        None => {
            s.time_of_day = true;
            s.report.date_source =
                "none: the log has no date (no RMC, ZDA without day, month and year); times are times of day, UTC".into();
            s.warnings.push(format!(
                "{file}: the NMEA log has no date; its times are times of day (UTC) on an unknown day"
            ));
            // 2020-01-01, the importer's epoch: times of day then read as seconds of that day.
            super::timefmt::days_from_civil(2020, 1, 1)
        }
    };
    let t_of = |day: i64, tod: f64| {
        let d = base + day;
        epoch_of(1970, 1, 1, 0.0) + d as f64 * 86_400.0 + tod
    };
    let id = super::boat_id_from_file(file);
    let points: Vec<RawPoint> = std::mem::take(&mut log.fixes)
        .into_iter()
        .map(|(day, tod, lat, lon, sog, heading)| RawPoint {
            t: t_of(day, tod),
            c: [lat, lon],
            logged: Logged {
                heading,
                heel: f32::NAN,
            },
            sog: sog as f64,
        })
        .collect();
    s.report.channels = log.channels.iter().map(|c| c.0.to_string()).collect();
    for (channel, unit, v) in log.channels {
        s.series.push(Series {
            boat: Some(id.clone()),
            channel: channel.into(),
            unit: unit.into(),
            t: v.iter().map(|&(d, _, tod)| t_of(d as i64, tod)).collect(),
            v: v.iter().map(|x| x.1).collect(),
        });
    }
    s.boats.push(RawBoat {
        name: id.clone(),
        id,
        color: None,
        max_speed_mps: super::spike_limit_mps(&points),
        points,
    });
    Ok(s)
}
