//! Boat logs as CSV (SailGP style), one boat per file. The header is detected by name
//! (case-insensitive): time `DATETIME`/`time`/`timestamp`/`utc`; `LAT…`; `LON…`/`LNG…`;
//! speed over ground `…SOG…` (else `…SPEED…`) with the unit from the name (`km_h`, `m_s`,
//! else knots); `HEADING…`; `HEEL…`; true wind `TWS…`/`TWD…`; the boat `BOAT`. Times are
//! `YYYY-MM-DD HH:MM:SS[.f]` (UTC), RFC 3339, or plain seconds since the race start.
//! The spike limit is 1.2 × the log's own top speed over ground (the instrument knows what the
//! class can do), at least 20 kn.

use time::PrimitiveDateTime;
use time::format_description::well_known::Rfc3339;
use time::macros::format_description;

use super::{Coords, DEFAULT_MAX_SPEED_KN, RawBoat, RawPoint, Source, Times, epoch_seconds};
use crate::Wind;
use crate::error::{RaceError, RaceResult};
use crate::track::Logged;

struct Columns {
    time: usize,
    lat: usize,
    lon: usize,
    sog: Option<(usize, f64)>,
    heading: Option<usize>,
    heel: Option<usize>,
    tws: Option<(usize, f64)>,
    twd: Option<usize>,
    boat: Option<usize>,
}

/// Metres per second per unit named in a column name.
fn unit_of(name: &str) -> f64 {
    if name.contains("km_h") || name.contains("kmh") || name.contains("km/h") {
        1.0 / 3.6
    } else if name.contains("m_s") || name.contains("mps") || name.contains("m/s") {
        1.0
    } else {
        super::knots_to_mps(1.0)
    }
}

fn detect(file: &str, header: &csv::StringRecord) -> RaceResult<Columns> {
    let names: Vec<String> = header
        .iter()
        .map(|h| h.trim().to_ascii_lowercase())
        .collect();
    let find = |pred: &dyn Fn(&str) -> bool| names.iter().position(|n| pred(n));
    let need = |i: Option<usize>, what: &str| {
        i.ok_or_else(|| RaceError::at_line(file, 1, format!("the header has no {what} column")))
    };
    let time = [
        "datetime",
        "time",
        "timestamp",
        "utc",
        "time_utc",
        "date_time",
        "t",
    ]
    .iter()
    .find_map(|w| names.iter().position(|n| n == w));
    let sog = find(&|n| n.contains("sog"))
        .or_else(|| find(&|n| n.contains("speed") && !n.starts_with("tw") && !n.starts_with("aw")));
    let tws = find(&|n| n.starts_with("tws"));
    Ok(Columns {
        time: need(time, "time (DATETIME, time, timestamp or utc)")?,
        lat: need(find(&|n| n.starts_with("lat")), "latitude (LAT…)")?,
        lon: need(
            find(&|n| n.starts_with("lon") || n.starts_with("lng")),
            "longitude (LON…)",
        )?,
        sog: sog.map(|i| (i, unit_of(&names[i]))),
        heading: find(&|n| n.starts_with("heading") || n == "hdg"),
        heel: find(&|n| n.starts_with("heel")),
        tws: tws.map(|i| (i, unit_of(&names[i]))),
        twd: find(&|n| n.starts_with("twd")),
        boat: find(&|n| n == "boat" || n == "boat_id"),
    })
}

/// Absolute (unix seconds) or relative seconds.
fn parse_time(cell: &str) -> Option<(f64, Times)> {
    let c = cell.trim();
    let fmt_frac = format_description!("[year]-[month]-[day] [hour]:[minute]:[second].[subsecond]");
    let fmt = format_description!("[year]-[month]-[day] [hour]:[minute]:[second]");
    if let Ok(t) =
        PrimitiveDateTime::parse(c, fmt).or_else(|_| PrimitiveDateTime::parse(c, fmt_frac))
    {
        return Some((epoch_seconds(t.assume_utc()), Times::Absolute));
    }
    if let Ok(t) = time::OffsetDateTime::parse(c, &Rfc3339) {
        return Some((epoch_seconds(t), Times::Absolute));
    }
    c.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .map(|v| (v, Times::Relative))
}

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header = rdr
        .headers()
        .map_err(|e| RaceError::at_line(file, 1, format!("unreadable header ({e})")))?
        .clone();
    let cols = detect(file, &header)?;
    let names: Vec<&str> = header.iter().collect();
    let mut points = Vec::new();
    let mut times: Option<Times> = None;
    let mut boat: Option<String> = None;
    let (mut wind_e, mut wind_n, mut tws_sum, mut n_wind) = (0.0, 0.0, 0.0, 0usize);
    let mut max_sog: f64 = 0.0;
    for rec in rdr.records() {
        let rec = rec.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            let what = match e.kind() {
                csv::ErrorKind::UnequalLengths {
                    expected_len, len, ..
                } => {
                    format!("{len} cells where the header has {expected_len}")
                }
                csv::ErrorKind::Utf8 { .. } => "text that is not UTF-8".into(),
                _ => format!("unreadable row ({e})"),
            };
            RaceError::at_line(file, line, what)
        })?;
        let line = rec.position().map_or(0, |p| p.line());
        let cell = |i: usize| rec.get(i).unwrap_or("");
        let num = |i: usize| -> RaceResult<f64> {
            let c = cell(i);
            c.parse::<f64>().map_err(|_| {
                RaceError::at_line(file, line, format!("{} is \"{c}\", not a number", names[i]))
            })
        };
        let opt = |i: Option<usize>| -> RaceResult<f64> {
            match i {
                Some(i) => num(i),
                None => Ok(f64::NAN),
            }
        };
        let Some((t, kind)) = parse_time(cell(cols.time)) else {
            return Err(RaceError::at_line(
                file,
                line,
                format!(
                    "{} is \"{}\", not a time (YYYY-MM-DD HH:MM:SS, RFC 3339 or seconds)",
                    names[cols.time],
                    cell(cols.time)
                ),
            ));
        };
        match times {
            None => times = Some(kind),
            Some(k) if k != kind => {
                return Err(RaceError::at_line(
                    file,
                    line,
                    "mixes calendar times and plain seconds in the time column",
                ));
            }
            _ => {}
        }
        let (lat, lon) = (num(cols.lat)?, num(cols.lon)?);
        if let Some(msg) = super::geo_problem(lat, lon) {
            return Err(RaceError::at_line(file, line, msg));
        }
        let sog = match cols.sog {
            Some((i, u)) => num(i)? * u,
            None => f64::NAN,
        };
        if sog.is_finite() {
            max_sog = max_sog.max(sog);
        }
        let heading = opt(cols.heading)?;
        let heel = opt(cols.heel)?;
        if let (Some((i, u)), Some(j)) = (cols.tws, cols.twd) {
            let (s, d) = (num(i)? * u, num(j)?);
            if s.is_finite() && d.is_finite() {
                wind_e += d.to_radians().sin();
                wind_n += d.to_radians().cos();
                tws_sum += s;
                n_wind += 1;
            }
        }
        if boat.is_none()
            && let Some(b) = cols.boat
        {
            boat = Some(cell(b).to_string()).filter(|b| !b.is_empty());
        }
        points.push(RawPoint {
            t,
            c: [lat, lon],
            logged: Logged {
                heading: heading as f32,
                heel: heel as f32,
            },
            sog,
        });
    }
    if points.is_empty() {
        return Err(RaceError::in_file(
            file,
            "the log has a header but no rows: a boat needs points",
        ));
    }
    let mut s = Source::new(file, Coords::Geo, times.unwrap_or(Times::Absolute));
    if n_wind > 0 {
        s.wind = Some(Wind {
            from_deg: wind_e.atan2(wind_n).to_degrees().rem_euclid(360.0),
            speed_mps: tws_sum / n_wind as f64,
        });
    }
    let id = boat.unwrap_or_else(|| super::boat_id_from_file(file));
    s.boats.push(RawBoat {
        name: id.clone(),
        id,
        color: None,
        points,
        max_speed_mps: (1.2 * max_sog).max(super::knots_to_mps(DEFAULT_MAX_SPEED_KN)),
    });
    Ok(s)
}
