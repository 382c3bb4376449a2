//! KML (Google Earth; OGC KML 2.2) and KMZ (the same, zipped: its first `.kml` entry) as race
//! trackers and phone apps export them. Two shapes carry time:
//!
//! - one `Placemark` per fix: `<TimeStamp><when>` and `<Point><coordinates>lon,lat[,alt]`;
//!   the fixes of one boat share a `Folder`, whose `name` names the boat; outside folders,
//!   Placemark names name the boats when they repeat (each name on at least two fixes on
//!   average), else the file is one boat (names that are time labels);
//! - `gx:Track` (KML 2.2 extension): `when` and `gx:coord` (`lon lat alt`, space-separated)
//!   lists paired in order, one track per `Placemark`, named by the Placemark (else its folder,
//!   else the file).
//!
//! A `Placemark` with a `Point` and no time is a course mark, named by its `name`. Lines
//! (`LineString`) have no times and cannot be raced: their points are counted as dropped.

use super::recorder::{Recorder, source};
use super::timefmt::parse_datetime;
use super::xml_text::{Node, last, parent, walk};
use super::{RawMark, Source, boat_id_from_file, q};
use crate::error::{RaceError, RaceResult};

/// The Placemark being read.
#[derive(Default)]
struct Placemark {
    name: Option<String>,
    when: Option<f64>,
    point: Option<(f64, f64)>,
    track_when: Vec<f64>,
    track_coord: Vec<(f64, f64)>,
}

/// `lon,lat[,alt]` (coordinates) or `lon lat [alt]` (gx:coord) → (lat, lon).
fn lon_lat(v: &str, sep: char) -> Result<(f64, f64), String> {
    let mut it = v.split(sep).map(str::trim).filter(|s| !s.is_empty());
    let n = |s: Option<&str>, what: &str| {
        let s = s.ok_or_else(|| format!("{} has no {what}", q(v)))?;
        s.parse::<f64>()
            .map_err(|_| format!("{what} is {}, not a number", q(s)))
    };
    let lon = n(it.next(), "longitude")?;
    let lat = n(it.next(), "latitude")?;
    Ok((lat, lon))
}

/// A timed Point placemark: (folder, placemark name, t, lat, lon), grouped into boats once
/// the whole file is read.
type PointFix = (Option<String>, Option<String>, f64, f64, f64);

/// The index of the boat `name`, added if new.
fn boat(boats: &mut Vec<(String, Recorder)>, name: &str) -> usize {
    match boats.iter().position(|(n, _)| n == name) {
        Some(k) => k,
        None => {
            boats.push((name.to_string(), Recorder::new()));
            boats.len() - 1
        }
    }
}

fn time(v: &str) -> Result<f64, String> {
    parse_datetime(v).ok_or_else(|| format!("when is {}, not an ISO 8601 time", q(v)))
}

pub(crate) fn parse(file: &str, text: &str, format: &str) -> RaceResult<Source> {
    let mut boats: Vec<(String, Recorder)> = Vec::new();
    let mut point_fixes: Vec<PointFix> = Vec::new();
    let mut marks: Vec<RawMark> = Vec::new();
    let mut folders: Vec<Option<String>> = Vec::new();
    let mut pm: Option<Placemark> = None;
    let (mut records, mut line_points, mut unpaired) = (0usize, 0usize, 0usize);
    let file_id = boat_id_from_file(file);
    let mut bad = 0usize;
    walk(file, text, |node| {
        match node {
            Node::Open(path, _) => match last(path) {
                "Folder" => folders.push(None),
                "Placemark" => pm = Some(Placemark::default()),
                _ => {}
            },
            Node::Text(path, v) => {
                let (up, here) = (parent(path), last(path));
                match (&mut pm, up, here) {
                    (Some(p), "Placemark", "name") => p.name = Some(v.to_string()),
                    (None, "Folder", "name") => {
                        if let Some(f) = folders.last_mut() {
                            *f = Some(v.to_string());
                        }
                    }
                    (Some(p), "TimeStamp", "when") => p.when = Some(time(v)?),
                    (Some(p), "Point", "coordinates") => p.point = Some(lon_lat(v, ',')?),
                    (Some(p), "Track", "when") => p.track_when.push(time(v)?),
                    (Some(p), "Track", "coord") => p.track_coord.push(lon_lat(v, ' ')?),
                    (Some(_), "LineString", "coordinates") => {
                        line_points += v.split_whitespace().count()
                    }
                    _ => {}
                }
            }
            Node::Close(path) => match last(path) {
                "Folder" => {
                    folders.pop();
                }
                "Placemark" => {
                    let Some(p) = pm.take() else { return Ok(()) };
                    let folder = folders.iter().rev().flatten().next().cloned();
                    if !p.track_when.is_empty() || !p.track_coord.is_empty() {
                        let name = p.name.or(folder).unwrap_or_else(|| file_id.clone());
                        let k = boat(&mut boats, &name);
                        let n = p.track_when.len().min(p.track_coord.len());
                        unpaired += p.track_when.len().max(p.track_coord.len()) - n;
                        records += n;
                        for (t, (la, lo)) in p.track_when.iter().zip(&p.track_coord) {
                            boats[k].1.fix(*t, *la, *lo);
                        }
                    } else if let Some((la, lo)) = p.point {
                        match p.when {
                            Some(t) => {
                                records += 1;
                                point_fixes.push((folder, p.name, t, la, lo));
                            }
                            None => {
                                if super::geo_problem(la, lo).is_some() {
                                    bad += 1;
                                } else {
                                    marks.push(RawMark {
                                        name: p
                                            .name
                                            .unwrap_or_else(|| format!("mark{}", marks.len() + 1)),
                                        c: [la, lo],
                                    });
                                }
                            }
                        }
                    }
                }
                _ => {}
            },
        }
        Ok(())
    })?;
    // One boat per folder. Outside folders, placemark names name boats when they repeat (a
    // tracker writing the boat's name on each fix); names that do not (a time label per fix)
    // leave the file as one boat.
    let unfoldered: Vec<&str> = point_fixes
        .iter()
        .filter(|f| f.0.is_none())
        .filter_map(|f| f.1.as_deref())
        .collect();
    let mut distinct = unfoldered.clone();
    distinct.sort_unstable();
    distinct.dedup();
    let names_are_boats = !unfoldered.is_empty() && 2 * distinct.len() <= unfoldered.len();
    for (folder, name, t, la, lo) in point_fixes {
        let boat_name = match (folder, name) {
            (Some(f), _) => f,
            (None, Some(n)) if names_are_boats => n,
            _ => file_id.clone(),
        };
        let k = boat(&mut boats, &boat_name);
        boats[k].1.fix(t, la, lo);
    }
    // A boat all of whose fixes had impossible positions: counted, not a boat.
    bad += boats
        .iter()
        .filter(|(_, r)| r.points.is_empty())
        .map(|(_, r)| r.bad_positions)
        .sum::<usize>();
    boats.retain(|(_, r)| !r.points.is_empty());
    if boats.is_empty() {
        return Err(RaceError::in_file(
            file,
            format!(
                "the {format} file has no timed position (a Placemark with TimeStamp and Point, or a gx:Track){}",
                if line_points > 0 {
                    format!(
                        "; its {} line points have no times",
                        crate::text::count(line_points)
                    )
                } else {
                    String::new()
                }
            ),
        ));
    }
    let mut s = source(file, format);
    s.report.records_read = records;
    s.report.date_source = "when (ISO 8601, UTC unless an offset is given)".into();
    s.drop_rule("line points without times", line_points);
    s.drop_rule("gx:Track when or coord without its pair", unpaired);
    s.drop_rule("placemarks with an impossible position", bad);
    s.marks = marks;
    for (name, rec) in boats {
        rec.finish(&mut s, name.clone(), name);
    }
    Ok(s)
}
