//! The native race JSON of docs/command-line.md, plus two optional fields: `"course"` (mark names in
//! rounding order; default: the marks in file order) and `"wind"` (`{"from_deg", "speed_mps"}`).
//! A boat may give `"max_speed_kn"` (its class's spike limit; default 20 kn, the same rule as
//! GPX: a 388,775 kn step is a broken fix, not a boat).

use serde::Deserialize;

use super::{
    Coords, DEFAULT_MAX_SPEED_KN, RawBoat, RawMark, RawPoint, Source, Times, epoch_seconds, q,
};
use crate::Wind;
use crate::error::{RaceError, RaceResult};
use crate::geo::GeoPoint;
use crate::track::Logged;

#[derive(Deserialize)]
#[serde(deny_unknown_fields, expecting = "a race object with \"boats\"")]
struct JsonRace {
    name: Option<String>,
    origin: Option<GeoPoint>,
    start_time: Option<String>,
    boats: Vec<JsonBoat>,
    #[serde(default)]
    marks: Vec<JsonMark>,
    course: Option<Vec<String>>,
    wind: Option<Wind>,
}

#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a boat object with \"id\" and \"track\""
)]
struct JsonBoat {
    id: String,
    name: Option<String>,
    color: Option<String>,
    track: Vec<[f64; 3]>,
    /// Degrees, one per track point, where logged.
    heel: Option<Vec<f64>>,
    max_speed_kn: Option<f64>,
}

#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mark object with \"name\" and \"position\""
)]
struct JsonMark {
    name: String,
    position: [f64; 2],
}

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let r: JsonRace =
        serde_json::from_str(text).map_err(|e| json_error(file, "a race file", &e))?;
    let mut s = Source::new(file, Coords::Local, Times::Relative);
    s.name = r.name;
    if let Some(o) = r.origin {
        if let Some(p) = super::geo_problem(o.lat, o.lon) {
            return Err(RaceError::in_file(file, format!("\"origin\": {p}")));
        }
        s.origin = Some(o);
    }
    if let Some(st) = &r.start_time {
        let t = time::OffsetDateTime::parse(st, &time::format_description::well_known::Rfc3339)
            .map_err(|_| {
                RaceError::in_file(
                    file,
                    format!(
                        "\"start_time\" is {}, not an RFC 3339 time such as 2025-06-21T11:23:29Z",
                        q(st)
                    ),
                )
            })?;
        s.start_time = Some(epoch_seconds(t));
    }
    s.course = r.course;
    if let Some(w) = r.wind {
        if !(w.from_deg.is_finite() && w.speed_mps.is_finite() && w.speed_mps >= 0.0) {
            return Err(RaceError::in_file(
                file,
                "\"wind\" needs a finite from_deg and a speed_mps ≥ 0",
            ));
        }
        s.wind = Some(w);
    }
    for (bi, b) in r.boats.into_iter().enumerate() {
        if b.track.is_empty() {
            return Err(RaceError::in_file(
                file,
                format!("boat {} (boats[{bi}]) has no track points", q(&b.id)),
            ));
        }
        if b.id.trim().is_empty() {
            return Err(RaceError::in_file(
                file,
                format!("boats[{bi}] has an empty \"id\""),
            ));
        }
        if let Some(c) = &b.color
            && !(c.len() == 7
                && c.starts_with('#')
                && c[1..].bytes().all(|x| x.is_ascii_hexdigit()))
        {
            return Err(RaceError::in_file(
                file,
                format!("boat {} has color {}, not #rrggbb", q(&b.id), q(c)),
            ));
        }
        if let Some(h) = &b.heel
            && h.len() != b.track.len()
        {
            return Err(RaceError::in_file(
                file,
                format!(
                    "boat {} has {} heel values for {} track points",
                    q(&b.id),
                    h.len(),
                    b.track.len()
                ),
            ));
        }
        let max_speed_mps = match b.max_speed_kn {
            Some(k) if k.is_finite() && k > 0.0 => super::knots_to_mps(k),
            Some(k) => {
                return Err(RaceError::in_file(
                    file,
                    format!(
                        "boat {} has max_speed_kn {k}; it must be positive",
                        q(&b.id)
                    ),
                ));
            }
            None => super::knots_to_mps(DEFAULT_MAX_SPEED_KN),
        };
        let mut points = Vec::with_capacity(b.track.len());
        for (k, p) in b.track.iter().enumerate() {
            if let Some(what) = point_problem(p) {
                return Err(RaceError::in_file(
                    file,
                    format!("boat {} track[{k}]: {what}", q(&b.id)),
                ));
            }
            let heel = b.heel.as_ref().map_or(f32::NAN, |h| h[k] as f32);
            points.push(RawPoint {
                t: p[0],
                c: [p[1], p[2]],
                logged: Logged {
                    heading: f32::NAN,
                    heel,
                },
                sog: f64::NAN,
            });
        }
        s.boats.push(RawBoat {
            name: b.name.unwrap_or_else(|| b.id.clone()),
            id: b.id,
            color: b.color,
            points,
            max_speed_mps,
        });
    }
    for (k, m) in r.marks.into_iter().enumerate() {
        if let Some(what) = coordinate_problem("x", m.position[0])
            .or_else(|| coordinate_problem("z", m.position[1]))
        {
            return Err(RaceError::in_file(
                file,
                format!("marks[{k}] ({}): {what}", q(&m.name)),
            ));
        }
        s.marks.push(RawMark {
            name: m.name,
            c: m.position,
        });
    }
    Ok(s)
}

/// The largest race coordinate or time accepted, metres or seconds: 1e9 (a million km, or 31
/// years). Beyond it f64 metres lose the centimetre and the value is certainly a broken field.
const MAX_COORDINATE: f64 = 1e9;

fn coordinate_problem(what: &str, v: f64) -> Option<String> {
    if !v.is_finite() {
        Some(format!("{what} is {v}, not a finite number"))
    } else if v.abs() >= MAX_COORDINATE {
        Some(format!(
            "{what} = {v:e} is beyond ±1e9 (metres from the origin, or seconds): no race is that large"
        ))
    } else {
        None
    }
}

/// What is wrong with a track point `[t, x, z]`, if anything.
fn point_problem(p: &[f64; 3]) -> Option<String> {
    coordinate_problem("t", p[0])
        .or_else(|| coordinate_problem("x", p[1]))
        .or_else(|| coordinate_problem("z", p[2]))
}

/// A serde_json error as one line: where, and what, in the words of the format.
pub(crate) fn json_error(file: &str, what: &str, e: &serde_json::Error) -> RaceError {
    let msg = e.to_string();
    let msg = msg
        .rsplit_once(" at line ")
        .map_or(msg.as_str(), |(m, _)| m);
    let msg = crate::text::serde_message(
        msg,
        &[
            ("a sequence", "a list"),
            ("a map", "an object"),
            ("struct Meta", "a maxSail meta-data object"),
            ("struct GeoPoint", "an object with lat and lon"),
            ("struct Wind", "an object with from_deg and speed_mps"),
            ("struct Baliza", "a mark object with lat, lon and nombre"),
        ],
    );
    RaceError::at_line(file, e.line() as u64, format!("not {what}: {msg}"))
}
