//! Reading race files (native JSON, GPX, CSV boat logs, maxSail meta-data JSON) and assembling
//! them into one [`Race`]: a common origin and start, cleaning, course and roundings.

use time::OffsetDateTime;

use crate::clean::{self, BoatReport, MPS_PER_KNOT, RawSample};
use crate::course::Mark;
use crate::error::{RaceError, RaceResult};
use crate::geo::{GeoPoint, LocalFrame};
use crate::track::{Boat, Logged};
use crate::{LoadReport, Race, Wind};

mod csv;
mod gpx;
mod json;
mod maxsail;

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
        }
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

/// Parse one file by its extension.
pub(crate) fn parse(file: &str, bytes: &[u8]) -> RaceResult<Source> {
    let ext = file
        .rsplit(['/', '\\'])
        .next()
        .and_then(|b| b.rsplit_once('.'))
        .map(|(_, e)| e.to_ascii_lowercase());
    let Some(ext) = ext else {
        return Err(RaceError::in_file(
            file,
            "no file extension; a race file is .json, .gpx or .csv",
        ));
    };
    if !matches!(ext.as_str(), "json" | "gpx" | "csv") {
        return Err(RaceError::in_file(
            file,
            format!("unknown file extension \".{ext}\"; a race file is .json, .gpx or .csv"),
        ));
    }
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(RaceError::in_file(file, "the file is empty"));
    }
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        RaceError::at_line(file, line as u64, "the text is not valid UTF-8")
    })?;
    match ext.as_str() {
        "json" if maxsail::is_maxsail(text) => maxsail::parse(file, text),
        "json" => json::parse(file, text),
        "gpx" => gpx::parse(file, text),
        _ => csv::parse(file, text),
    }
}

/// Assemble parsed files into one race.
pub(crate) fn assemble(sources: Vec<Source>) -> RaceResult<Race> {
    if sources.is_empty() {
        return Err(RaceError::new("no race files were given"));
    }
    let mut warnings: Vec<String> = Vec::new();
    // Unique boat ids across all files.
    let mut seen: Vec<(&str, &str)> = Vec::new();
    for s in &sources {
        for b in &s.boats {
            if let Some((_, other)) = seen.iter().find(|(id, _)| *id == b.id) {
                return Err(RaceError::new(format!(
                    "boat id \"{}\" appears twice ({} and {}); every boat needs its own id",
                    b.id, other, s.file
                )));
            }
            seen.push((&b.id, &s.file));
        }
    }
    if seen.is_empty() {
        let files: Vec<&str> = sources.iter().map(|s| s.file.as_str()).collect();
        return Err(RaceError::new(format!(
            "{} contain no boats",
            files.join(", ")
        )));
    }

    // --- origin: the first file that states one, else the course centre -------------------
    let any_geo = sources.iter().any(|s| s.coords == Coords::Geo);
    let stated = sources.iter().find_map(|s| s.origin);
    let origin = match stated {
        Some(o) => Some(o),
        None if any_geo => Some(geo_centre(&sources)),
        None => None,
    };
    if origin.is_some()
        && let Some(s) = sources
            .iter()
            .find(|s| s.coords == Coords::Local && s.origin.is_none())
        && sources.len() > 1
    {
        return Err(RaceError::in_file(
            &s.file,
            "has no \"origin\", so its metres cannot be placed beside GPS tracks; add an origin",
        ));
    }
    let frame = origin.map(LocalFrame::new);
    let to_race = |s: &Source, c: [f64; 2]| -> [f64; 2] {
        match (s.coords, &frame) {
            (Coords::Geo, Some(f)) => f.to_local(GeoPoint::new(c[0], c[1])),
            (Coords::Local, Some(f)) => match s.origin {
                Some(o) if o == f.origin() => c,
                Some(o) => f.to_local(LocalFrame::new(o).to_geo(c)),
                None => c,
            },
            _ => c,
        }
    };

    // --- start: stated, else maxSail's minute after its track's first fix, else the earliest
    // time at which every boat with absolute times has a fix ---------------------------------
    let first_abs = |file: &str| -> Option<f64> {
        sources
            .iter()
            .filter(|s| s.times == Times::Absolute && stem(&s.file) == stem(file))
            .flat_map(|s| s.boats.iter())
            .filter_map(|b| b.points.iter().map(|p| p.t).min_by(f64::total_cmp))
            .min_by(f64::total_cmp)
    };
    let mut start_how = String::new();
    let mut start: Option<f64> = None;
    if let Some(s) = sources.iter().find(|s| s.start_time.is_some()) {
        start = s.start_time;
        start_how = format!("start_time of {}", s.file);
    }
    if start.is_none() {
        for s in &sources {
            if let Some((track, minutes)) = &s.start_after_track {
                if let Some(t0) = first_abs(track) {
                    start = Some(t0 + minutes * 60.0);
                    start_how =
                        format!("{minutes} min after the first fix of {track} ({})", s.file);
                    break;
                }
                warnings.push(format!(
                    "{}: its start refers to {track}, which was not loaded; the start is taken from the tracks",
                    s.file
                ));
            }
        }
    }
    if start.is_none() {
        start = sources
            .iter()
            .filter(|s| s.times == Times::Absolute)
            .flat_map(|s| s.boats.iter())
            .filter_map(|b| b.points.iter().map(|p| p.t).min_by(f64::total_cmp))
            .max_by(f64::total_cmp);
        if start.is_some() {
            start_how = "the earliest time at which every boat has a fix".into();
        } else {
            start_how = "the files' own race time".into();
        }
    }

    // --- boats -------------------------------------------------------------------------------
    let mut boats = Vec::new();
    let mut reports: Vec<BoatReport> = Vec::new();
    for s in &sources {
        warnings.extend(s.warnings.iter().cloned());
        let shift = match (s.times, start, s.start_time) {
            (Times::Absolute, Some(st), _) => -st,
            (Times::Relative, Some(st), Some(own)) => own - st,
            _ => 0.0,
        };
        for b in &s.boats {
            let raw: Vec<RawSample> = b
                .points
                .iter()
                .map(|p| {
                    let xz = to_race(s, p.c);
                    RawSample {
                        t: p.t + shift,
                        x: xz[0],
                        z: xz[1],
                        logged: p.logged,
                        sog: p.sog,
                    }
                })
                .collect();
            let c = clean::clean(&b.id, &s.file, raw, b.max_speed_mps, &mut warnings);
            let color = b
                .color
                .clone()
                .unwrap_or_else(|| PALETTE[boats.len() % PALETTE.len()].to_string());
            boats.push(Boat::build(
                b.id.clone(),
                b.name.clone(),
                color,
                c.fixes,
                c.gap_after,
                c.logged,
            ));
            reports.push(c.report);
        }
    }

    // --- marks and course ---------------------------------------------------------------------
    let mut marks: Vec<Mark> = Vec::new();
    for s in &sources {
        for m in &s.marks {
            let position = to_race(s, m.c);
            match marks.iter().find(|k| k.name == m.name) {
                Some(k)
                    if (k.position[0] - position[0]).hypot(k.position[1] - position[1]) > 1.0 =>
                {
                    warnings.push(format!(
                        "{}: mark {} is given again {:.0} m away; the first position is kept",
                        s.file,
                        m.name,
                        (k.position[0] - position[0]).hypot(k.position[1] - position[1])
                    ));
                }
                Some(_) => {}
                None => marks.push(Mark {
                    name: m.name.clone(),
                    position,
                }),
            }
        }
    }
    let course_names = sources.iter().find_map(|s| s.course.clone());
    let course = match course_names {
        Some(names) => {
            let mut c = Vec::new();
            for n in &names {
                let Some(i) = marks.iter().position(|m| &m.name == n) else {
                    let file = &sources
                        .iter()
                        .find(|s| s.course.is_some())
                        .expect("found")
                        .file;
                    return Err(RaceError::in_file(
                        file,
                        format!("the course names the mark \"{n}\", which no file defines"),
                    ));
                };
                c.push(i);
            }
            c
        }
        None => (0..marks.len()).collect(),
    };
    let course = if sources.iter().any(|s| s.repeat_laps) {
        repeat_laps(&boats, &marks, course)
    } else {
        course
    };

    let name = sources
        .iter()
        .find_map(|s| s.name.clone())
        .unwrap_or_else(|| race_name(&sources));
    let wind = sources.iter().find_map(|s| s.wind);
    let start_time = start.and_then(|s| {
        let whole = s.floor();
        let nanos = ((s - whole) * 1e9).round() as i128;
        OffsetDateTime::from_unix_timestamp_nanos(
            (whole as i128 + EPOCH_UNIX as i128) * 1_000_000_000 + nanos,
        )
        .ok()
    });
    let report = LoadReport {
        files: sources.iter().map(|s| s.file.clone()).collect(),
        origin,
        start_time: start_time.and_then(|t| {
            t.format(&time::format_description::well_known::Rfc3339)
                .ok()
        }),
        start_from: start_how,
        boats: reports,
        warnings,
    };
    Ok(Race::new(
        name, origin, start_time, boats, marks, course, wind, report,
    ))
}

/// Add laps (`course[1..]` again) while at least half the boats sail them: the maxSail files
/// give the marks of an out-and-back but not the number of laps.
fn repeat_laps(boats: &[Boat], marks: &[Mark], course: Vec<usize>) -> Vec<usize> {
    if course.len() < 2 {
        return course;
    }
    let lap: Vec<usize> = course[1..].to_vec();
    let radius = crate::course::rounding_radius(marks, &course);
    let mut best = course;
    for _ in 0..20 {
        let mut next = best.clone();
        next.extend_from_slice(&lap);
        let done = boats
            .iter()
            .filter(|b| {
                crate::course::detect_roundings(b, marks, &next, radius)
                    .last()
                    .is_some_and(|r| r.is_some())
            })
            .count();
        if 2 * done < boats.len().max(1) || done == 0 {
            break;
        }
        best = next;
    }
    best
}

/// Boat colours when a file gives none: distinct on water blue, in a fixed order.
pub const PALETTE: [&str; 10] = [
    "#e6194b", "#ffe119", "#f58231", "#f032e6", "#ffffff", "#3cb44b", "#911eb4", "#bcf60c",
    "#fabebe", "#9a6324",
];

/// Centre of everything geographic: the marks' mean if any file has marks, else the middle of
/// the tracks' bounding box.
fn geo_centre(sources: &[Source]) -> GeoPoint {
    let geo = || sources.iter().filter(|s| s.coords == Coords::Geo);
    let marks: Vec<[f64; 2]> = geo().flat_map(|s| s.marks.iter().map(|m| m.c)).collect();
    if !marks.is_empty() {
        let k = marks.len() as f64;
        return GeoPoint::new(
            marks.iter().map(|c| c[0]).sum::<f64>() / k,
            marks.iter().map(|c| c[1]).sum::<f64>() / k,
        );
    }
    let (mut lat0, mut lat1, mut lon0, mut lon1) = (90.0f64, -90.0f64, 180.0f64, -180.0f64);
    for p in geo().flat_map(|s| s.boats.iter().flat_map(|b| b.points.iter())) {
        lat0 = lat0.min(p.c[0]);
        lat1 = lat1.max(p.c[0]);
        lon0 = lon0.min(p.c[1]);
        lon1 = lon1.max(p.c[1]);
    }
    GeoPoint::new(0.5 * (lat0 + lat1), 0.5 * (lon0 + lon1))
}

/// A name from the files: their common stem prefix, else the first stem.
fn race_name(sources: &[Source]) -> String {
    let stems: Vec<&str> = sources.iter().map(|s| stem(&s.file)).collect();
    let first = stems[0];
    let mut n = first.len();
    for s in &stems[1..] {
        n = n.min(
            first
                .bytes()
                .zip(s.bytes())
                .take_while(|(a, b)| a == b)
                .count(),
        );
    }
    let common = first[..n].trim_end_matches(['-', '_', ' ', '.']);
    if common.len() >= 4 {
        common.to_string()
    } else {
        first.to_string()
    }
}

/// What is wrong with a geographic point read from a file, if anything.
pub(crate) fn geo_problem(lat: f64, lon: f64) -> Option<String> {
    if !(lat.is_finite() && lat.abs() <= 90.0) {
        Some(format!("latitude {lat} is not a number in [-90, 90]"))
    } else if !(lon.is_finite() && lon.abs() <= 180.0) {
        Some(format!("longitude {lon} is not a number in [-180, 180]"))
    } else {
        None
    }
}

pub(crate) fn knots_to_mps(v: f64) -> f64 {
    v * MPS_PER_KNOT
}
