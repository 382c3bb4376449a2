//! GPX 1.0/1.1 with the `gpx` crate: one boat per track (all its segments), waypoints as marks.
//! A `<gpx>` element without the `version` attribute (the Gdańsk file) is read as GPX 1.1,
//! with a warning, instead of refused.

use super::{
    Coords, DEFAULT_MAX_SPEED_KN, RawBoat, RawMark, RawPoint, Source, Times, epoch_seconds,
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

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    let patched = with_version(text);
    if patched.is_some() {
        s.warnings.push(format!(
            "{file}: the <gpx> element has no version attribute; it was read as GPX 1.1"
        ));
    }
    let g = gpx::read(patched.as_deref().unwrap_or(text).as_bytes()).map_err(|e| {
        let detail = match &e {
            gpx::errors::GpxError::XmlParseError(x) => {
                format!("XML error {x}")
            }
            other => other.to_string(),
        };
        RaceError::in_file(file, format!("not valid GPX: {detail}"))
    })?;
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
    if s.boats.is_empty() && s.marks.is_empty() {
        return Err(RaceError::in_file(
            file,
            "the GPX has no tracks and no waypoints",
        ));
    }
    Ok(s)
}
