//! Garmin Training Center XML (TCX, schema `TrainingCenterDatabase/v2`): watches and Garmin
//! Connect export it. `Activities/Activity[@Sport]/Lap/Track/Trackpoint` with `Time` (ISO 8601,
//! UTC), `Position/LatitudeDegrees`, `Position/LongitudeDegrees` and, in the `TPX` extension
//! (ActivityExtension/v2), `Speed` in m/s. Trackpoints without a position (a watch before its
//! GPS fix, or pauses) are counted. Laps are the watch's laps, not races: every lap of the
//! file is one track. The boat is named from the device (`Creator/Name`), else the file.

use super::recorder::{Recorder, source};
use super::timefmt::parse_datetime;
use super::xml_text::{Node, last, parent, walk};
use super::{Source, boat_id_from_file, q};
use crate::error::{RaceError, RaceResult};

#[derive(Default)]
struct Point {
    time: Option<f64>,
    lat: Option<f64>,
    lon: Option<f64>,
}

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut rec = Recorder::new();
    let mut p = Point::default();
    let (mut points, mut no_position, mut laps) = (0usize, 0usize, 0usize);
    let mut sport: Option<String> = None;
    let mut device: Option<String> = None;
    let num = |v: &str, what: &str| {
        v.parse::<f64>()
            .map_err(|_| format!("{what} is {}, not a number", q(v)))
    };
    walk(file, text, |node| {
        match node {
            Node::Open(path, attrs) => match last(path) {
                "Trackpoint" => p = Point::default(),
                "Lap" => laps += 1,
                "Activity" if sport.is_none() => {
                    sport = attrs
                        .iter()
                        .find(|(k, _)| k == "Sport")
                        .map(|(_, v)| v.clone());
                }
                _ => {}
            },
            Node::Text(path, v) => match (parent(path), last(path)) {
                ("Trackpoint", "Time") => {
                    p.time = Some(
                        parse_datetime(v)
                            .ok_or_else(|| format!("Time is {}, not an ISO 8601 time", q(v)))?,
                    )
                }
                ("Position", "LatitudeDegrees") => p.lat = Some(num(v, "LatitudeDegrees")?),
                ("Position", "LongitudeDegrees") => p.lon = Some(num(v, "LongitudeDegrees")?),
                ("TPX", "Speed") => {
                    let s = num(v, "Speed")?;
                    rec.set_sog(s);
                    if let Some(t) = p.time {
                        rec.put("sog", "m/s", t, s);
                    }
                }
                ("Creator", "Name") if device.is_none() => device = Some(v.to_string()),
                _ => {}
            },
            Node::Close(path) => {
                if last(path) == "Trackpoint" {
                    points += 1;
                    match (p.time, p.lat, p.lon) {
                        (Some(t), Some(la), Some(lo)) => rec.fix(t, la, lo),
                        _ => no_position += 1,
                    }
                }
            }
        }
        Ok(())
    })?;
    if rec.points.is_empty() {
        return Err(RaceError::in_file(
            file,
            format!(
                "the TCX file has no trackpoint with a time and a position among {}",
                crate::text::count(points)
            ),
        ));
    }
    let about: Vec<String> = [
        device.clone(),
        sport.as_ref().map(|s| format!("sport {s}")),
        (laps > 0).then(|| format!("{laps} laps in one track")),
    ]
    .into_iter()
    .flatten()
    .collect();
    let format = if about.is_empty() {
        "TCX".to_string()
    } else {
        format!("TCX ({})", about.join(", "))
    };
    let mut s = source(file, &format);
    s.report.records_read = points;
    s.report.date_source = "Trackpoint Time (ISO 8601, UTC)".into();
    s.drop_rule("trackpoints without a position", no_position);
    let id = boat_id_from_file(file);
    let name = device.unwrap_or_else(|| id.clone());
    rec.finish(&mut s, id, name);
    Ok(s)
}
