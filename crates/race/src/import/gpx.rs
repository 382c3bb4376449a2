//! GPX 1.0/1.1 with the `gpx` crate: one boat per track (all its segments), waypoints and
//! route points as marks. A `<gpx>` element without the `version` attribute (the Gdańsk file)
//! is read as GPX 1.1, with a warning, instead of refused. A track whose points have a gap of
//! more than [`SESSION_GAP_S`] (a GPSBabel dump of many days) is split into sessions; the race
//! picks one (see `assemble`). Where the `gpx` crate refuses a file, a second pass with an XML
//! reader finds the line and the field at fault.

use super::{
    Coords, DEFAULT_MAX_SPEED_KN, RawBoat, RawMark, RawPoint, Source, Times, epoch_seconds, q,
};
use crate::error::{RaceError, RaceResult};
use crate::track::Logged;

/// Insert `version="1.1"` into a `<gpx ...>` start tag that lacks it.
fn with_version(text: &str) -> Option<String> {
    let start = text.find("<gpx")?;
    let after = &text[start + 4..];
    if !after.starts_with([' ', '>', '\n', '\r', '\t', '/']) {
        return None;
    }
    let end = after.find('>')?;
    if after[..end].contains("version") {
        return None;
    }
    let mut s = String::with_capacity(text.len() + 16);
    s.push_str(&text[..start + 4]);
    s.push_str(" version=\"1.1\"");
    s.push_str(after);
    Some(s)
}

/// A pause longer than this (seconds) between two points of a track starts a new session: 4 h,
/// longer than any pause inside a day's racing (Gdańsk has one of 2 h 7 min between races),
/// shorter than a night.
pub const SESSION_GAP_S: f64 = 4.0 * 3600.0;

pub(crate) fn parse(file: &str, text: &str, session: Option<usize>) -> RaceResult<Source> {
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    let patched = with_version(text);
    if patched.is_some() {
        s.warnings.push(format!(
            "{file}: the <gpx> element has no version attribute; it was read as GPX 1.1"
        ));
    }
    let g = gpx::read(patched.as_deref().unwrap_or(text).as_bytes()).map_err(|e| {
        if let Some((line, what)) = diagnose(text) {
            return RaceError::at_line(file, line, format!("not valid GPX: {what}"));
        }
        let detail = match &e {
            gpx::errors::GpxError::XmlParseError(x) => {
                format!("XML error {x}")
            }
            other => other.to_string(),
        };
        RaceError::in_file(
            file,
            format!("not valid GPX: {}", crate::text::cut(&detail, 120)),
        )
    })?;
    s.report.format = match g.version {
        gpx::GpxVersion::Gpx10 => "GPX 1.0",
        _ => "GPX 1.1",
    }
    .into();
    s.report.date_source = "<time> of every point (UTC)".into();
    let base_id = super::boat_id_from_file(file);
    let n_tracks = g.tracks.len();
    for (ti, trk) in g.tracks.iter().enumerate() {
        let id = if n_tracks > 1 {
            format!("{base_id}-{}", ti + 1)
        } else {
            base_id.clone()
        };
        let mut points = Vec::new();
        for (si, seg) in trk.segments.iter().enumerate() {
            for (pi, w) in seg.points.iter().enumerate() {
                let at = || format!("track {} segment {} point {}", ti + 1, si + 1, pi + 1);
                let p = w.point();
                let (lat, lon) = (p.y(), p.x());
                if let Some(msg) = super::geo_problem(lat, lon) {
                    return Err(RaceError::in_file(file, format!("{}: {msg}", at())));
                }
                let Some(t) = w.time else {
                    return Err(RaceError::in_file(
                        file,
                        format!(
                            "{} has no <time>; a race track needs a time on every point",
                            at()
                        ),
                    ));
                };
                points.push(RawPoint {
                    t: epoch_seconds(t.into()),
                    c: [lat, lon],
                    logged: Logged {
                        heading: f32::NAN,
                        heel: f32::NAN,
                    },
                    sog: w.speed.unwrap_or(f64::NAN),
                });
            }
        }
        if points.is_empty() {
            return Err(RaceError::in_file(
                file,
                format!("track {} (boat {id}) has no points", ti + 1),
            ));
        }
        s.report.records_read += points.len();
        let points = pick_session(&mut s, &id, points, session)?;
        s.boats.push(RawBoat {
            name: id.clone(),
            id,
            color: None,
            points,
            max_speed_mps: super::knots_to_mps(DEFAULT_MAX_SPEED_KN),
        });
    }
    for (k, w) in g.waypoints.iter().enumerate() {
        let p = w.point();
        if let Some(msg) = super::geo_problem(p.y(), p.x()) {
            return Err(RaceError::in_file(
                file,
                format!("waypoint {}: {msg}", k + 1),
            ));
        }
        s.marks.push(RawMark {
            name: w.name.clone().unwrap_or_else(|| format!("WP{}", k + 1)),
            c: [p.y(), p.x()],
        });
    }
    for (ri, r) in g.routes.iter().enumerate() {
        for (k, w) in r.points.iter().enumerate() {
            let p = w.point();
            if let Some(msg) = super::geo_problem(p.y(), p.x()) {
                return Err(RaceError::in_file(
                    file,
                    format!("route {} point {}: {msg}", ri + 1, k + 1),
                ));
            }
            s.marks.push(RawMark {
                name: w
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("RT{}-{}", ri + 1, k + 1)),
                c: [p.y(), p.x()],
            });
        }
    }
    if s.boats.is_empty() && s.marks.is_empty() {
        return Err(RaceError::in_file(
            file,
            "the GPX has no tracks and no waypoints",
        ));
    }
    Ok(s)
}

/// Split a track at pauses over [`SESSION_GAP_S`]; keep the session asked for (`--session N`),
/// else all of them for now: `assemble` picks the one that overlaps the other boats.
fn pick_session(
    s: &mut Source,
    id: &str,
    mut points: Vec<RawPoint>,
    session: Option<usize>,
) -> RaceResult<Vec<RawPoint>> {
    points.sort_by(|a, b| a.t.total_cmp(&b.t));
    let mut bounds = vec![0];
    bounds.extend((1..points.len()).filter(|&i| points[i].t - points[i - 1].t > SESSION_GAP_S));
    bounds.push(points.len());
    let n = bounds.len() - 1;
    if n == 1 {
        return Ok(points);
    }
    let k = match session {
        Some(k) if (1..=n).contains(&k) => k,
        Some(k) => {
            return Err(RaceError::in_file(
                &s.file,
                format!("--session {k}: boat {} has sessions 1 to {n}", q(id)),
            ));
        }
        None => {
            s.sessions.push((id.to_string(), bounds));
            return Ok(points);
        }
    };
    let kept: Vec<RawPoint> = points[bounds[k - 1]..bounds[k]].to_vec();
    s.warnings.push(format!(
        "{}: boat {} has {n} sessions (pauses over {:.0} h); session {k} was raced (--session)",
        s.file,
        q(id),
        SESSION_GAP_S / 3600.0
    ));
    s.report
        .dropped
        .push(("points of other sessions".into(), points.len() - kept.len()));
    Ok(kept)
}

/// The first line and field of a GPX that the `gpx` crate refuses for a value: a coordinate
/// attribute or a `<time>`, `<ele>` or `<speed>` that is not what it should be.
fn diagnose(text: &str) -> Option<(u64, String)> {
    use quick_xml::events::Event;
    let mut r = quick_xml::Reader::from_str(text);
    let mut open: Option<String> = None;
    loop {
        let pos = r.buffer_position() as usize;
        let line = || {
            text.as_bytes()[..pos.min(text.len())]
                .iter()
                .filter(|&&b| b == b'\n')
                .count() as u64
                + 1
        };
        match r.read_event() {
            Err(e) => {
                return Some((
                    line(),
                    format!("XML error ({})", crate::text::cut(&e.to_string(), 80)),
                ));
            }
            Ok(Event::Eof) => return None,
            Ok(Event::Start(e)) | Ok(Event::Empty(e)) => {
                let name = e.local_name().as_ref().to_string();
                if matches!(name.as_str(), "trkpt" | "wpt" | "rtept") {
                    for (key, word, lim) in [("lat", "latitude", 90.0), ("lon", "longitude", 180.0)]
                    {
                        let v = e
                            .attributes()
                            .flatten()
                            .find(|a| a.key.as_ref() == key)
                            .map(|a| a.value.to_string());
                        match v {
                            None => {
                                return Some((line(), format!("<{name}> has no {key} ({word})")));
                            }
                            Some(v) => match v.trim().parse::<f64>() {
                                Ok(x) if x.is_finite() && x.abs() <= lim => {}
                                _ => {
                                    return Some((
                                        line(),
                                        format!(
                                            "<{name}> {key} is {}, not a {word} in [-{lim}, {lim}]",
                                            q(&v)
                                        ),
                                    ));
                                }
                            },
                        }
                    }
                }
                open = matches!(name.as_str(), "time" | "ele" | "speed").then_some(name);
            }
            Ok(Event::Text(t)) => {
                if let Some(name) = open.take() {
                    let v = AsRef::<str>::as_ref(&t).trim().to_string();
                    let ok = match name.as_str() {
                        "time" => {
                            time::OffsetDateTime::parse(
                                &v,
                                &time::format_description::well_known::Rfc3339,
                            )
                            .is_ok()
                                || super::timefmt::parse_datetime(&v).is_some()
                        }
                        _ => v.parse::<f64>().is_ok_and(f64::is_finite),
                    };
                    if !ok {
                        let want = if name == "time" {
                            "an ISO 8601 time"
                        } else {
                            "a number"
                        };
                        return Some((line(), format!("<{name}> is {}, not {want}", q(&v))));
                    }
                }
            }
            Ok(_) => open = None,
        }
    }
}
