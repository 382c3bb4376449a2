//! Assembling parsed files into one race: unique boat ids, a common origin and start,
//! cleaning with the silent-loss rule, the racing-area check, marks and the course.

use std::collections::HashMap;

use time::OffsetDateTime;

use super::{Coords, EPOCH_UNIX, Source, Times, q, stem};
use crate::clean::{self, BoatReport, RawSample};
use crate::course::{Mark, MarkKind};
use crate::error::{RaceError, RaceResult};
use crate::geo::{GeoPoint, LocalFrame};
use crate::text::count;
use crate::track::Boat;
use crate::{LoadOptions, LoadReport, Race};

/// Assemble parsed files into one race.
/// Boats further than this from the race's origin (their median fix) are refused: the files
/// mix two racing areas, and one flat projection cannot hold both (a 50 km radius keeps the
/// projection's distance error under 0.1 %, see geo.rs).
pub const MAX_RACE_RADIUS_M: f64 = 50_000.0;

pub(crate) fn assemble(mut sources: Vec<Source>, opts: &LoadOptions) -> RaceResult<Race> {
    if sources.is_empty() {
        return Err(RaceError::new("no race files were given"));
    }
    let mut warnings: Vec<String> = Vec::new();
    check_boats(&sources)?;
    refuse_lost_reading(&sources, opts, &mut warnings)?;
    for s in &mut sources {
        merge_duplicate_tracks(s);
    }
    pick_sessions(&mut sources);
    let null_island = drop_null_island(&mut sources);
    let place = Placement::of(&sources)?;
    let (start, start_how) = race_start(&sources, &mut warnings);
    if let Some(st) = start {
        check_one_time(&sources, st, &start_how)?;
    }
    let (boats, reports, series) = build_boats(
        &mut sources,
        &place,
        start,
        &null_island,
        opts,
        &mut warnings,
    )?;
    let (mut marks, mut mark_of) = build_marks(&sources, &place, &mut warnings);
    let course = build_course(&sources, opts, &mut marks, &mut mark_of, &boats)?;
    let course = if sources.iter().any(|s| s.repeat_laps) && opts.course.is_none() {
        repeat_laps(&boats, &marks, course)
    } else {
        course
    };

    let name = sources
        .iter()
        .find_map(|s| s.name.clone())
        .unwrap_or_else(|| race_name(&sources));
    let wind = sources.iter().find_map(|s| s.wind);
    let time_of_day = sources.iter().any(|s| s.time_of_day);
    let (start_time, start_text) = start_words(start, time_of_day);
    let boundary: Vec<[f64; 2]> = sources
        .iter()
        .flat_map(|s| s.boundary.iter().map(|c| place.to_race(s, *c)))
        .collect();
    let origin = place.origin();
    let report = LoadReport {
        files: sources.iter().map(|s| s.file.clone()).collect(),
        origin,
        start_time: start_text,
        start_from: start_how,
        boats: reports,
        file_reports: sources.iter().map(|s| s.report.clone()).collect(),
        warnings,
    };
    let mut race = Race::new(name, origin, start_time, boats, marks, course, wind, report);
    race.series = series;
    race.boundary = boundary;
    Ok(race)
}

/// Every boat id once across the files, and some boat at all.
fn check_boats(sources: &[Source]) -> RaceResult<()> {
    // Unique boat ids across all files (a map: fleets of 40,000 boats are read).
    let mut seen: HashMap<&str, &str> = HashMap::new();
    for s in sources {
        for b in &s.boats {
            if let Some(other) = seen.insert(&b.id, &s.file) {
                return Err(RaceError::new(format!(
                    "boat id {} appears twice ({} and {}); every boat needs its own id",
                    q(&b.id),
                    other,
                    s.file
                )));
            }
        }
    }
    if seen.is_empty() {
        let files: Vec<&str> = sources.iter().map(|s| s.file.as_str()).collect();
        if sources
            .iter()
            .all(|s| s.course.is_some() || !s.marks.is_empty())
        {
            // A race XML (or a marks file) alone: a course without boats.
            return Err(RaceError::new(format!(
                "{} hold a course but no boats: load the boats' tracks beside it (or give it to --marks or --course)",
                files.join(", ")
            )));
        }
        return Err(RaceError::new(format!(
            "{} contain no boats",
            files.join(", ")
        )));
    }
    Ok(())
}

/// Fixes at exactly (0, 0): a receiver's "no fix", never a race. Dropped; the count per file
/// and boat is returned for the boats' reports.
fn drop_null_island(sources: &mut [Source]) -> Vec<Vec<usize>> {
    sources
        .iter_mut()
        .map(|s| {
            let geo = s.coords == Coords::Geo;
            s.boats
                .iter_mut()
                .map(|b| {
                    let n = b.points.len();
                    if geo {
                        b.points.retain(|p| p.c != [0.0, 0.0]);
                    }
                    n - b.points.len()
                })
                .collect()
        })
        .collect()
}

/// Where the race's metres are: the origin (the first file that states one, else the centre
/// of the GPS tracks) and each file's coordinates carried into that frame.
struct Placement {
    frame: Option<LocalFrame>,
}

impl Placement {
    fn of(sources: &[Source]) -> RaceResult<Placement> {
        let any_geo = sources.iter().any(|s| s.coords == Coords::Geo);
        let stated = sources.iter().find_map(|s| s.origin);
        let origin = match stated {
            Some(o) => Some(o),
            None if any_geo => Some(geo_centre(sources)?),
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
        if let Some(o) = origin {
            check_racing_area(sources, o)?;
        }
        Ok(Placement {
            frame: origin.map(LocalFrame::new),
        })
    }

    fn origin(&self) -> Option<GeoPoint> {
        self.frame.as_ref().map(LocalFrame::origin)
    }

    /// A point of file `s` (its own coordinates) in the race's metres.
    fn to_race(&self, s: &Source, c: [f64; 2]) -> [f64; 2] {
        match (s.coords, &self.frame) {
            (Coords::Geo, Some(f)) => f.to_local(GeoPoint::new(c[0], c[1])),
            (Coords::Local, Some(f)) => match s.origin {
                Some(o) if o == f.origin() => c,
                Some(o) => f.to_local(LocalFrame::new(o).to_geo(c)),
                None => c,
            },
            _ => c,
        }
    }
}

type Boats = (Vec<Boat>, Vec<BoatReport>, Vec<crate::Series>);

/// Each file's boats in the race's metres and seconds from `start`, cleaned (the silent-loss
/// rule), with their reports, and the files' instrument series on the same clock.
fn build_boats(
    sources: &mut [Source],
    place: &Placement,
    start: Option<f64>,
    null_island: &[Vec<usize>],
    opts: &LoadOptions,
    warnings: &mut Vec<String>,
) -> RaceResult<Boats> {
    let mut boats = Vec::new();
    let mut reports: Vec<BoatReport> = Vec::new();
    let mut series = Vec::new();
    for si in 0..sources.len() {
        // The raw points are taken, not copied: a 100 MB log holds millions of them.
        let taken: Vec<Vec<super::RawPoint>> = sources[si]
            .boats
            .iter_mut()
            .map(|b| std::mem::take(&mut b.points))
            .collect();
        let s = &sources[si];
        warnings.extend(s.warnings.iter().cloned());
        let shift = match (s.times, start, s.start_time) {
            (Times::Absolute, Some(st), _) => -st,
            (Times::Relative, Some(st), Some(own)) => own - st,
            _ => 0.0,
        };
        for ser in &s.series {
            let mut ser = ser.clone();
            ser.t.iter_mut().for_each(|t| *t += shift);
            series.push(ser);
        }
        for (bi, (b, points)) in s.boats.iter().zip(taken).enumerate() {
            let raw: Vec<RawSample> = points
                .into_iter()
                .map(|p| {
                    let xz = place.to_race(s, p.c);
                    RawSample {
                        t: p.t + shift,
                        x: xz[0],
                        z: xz[1],
                        logged: p.logged,
                        sog: p.sog,
                    }
                })
                .collect();
            let c = clean::clean(
                &b.id,
                &s.file,
                raw,
                b.max_speed_mps,
                null_island[si][bi],
                warnings,
            );
            if c.report.lost_most() {
                let what = format!(
                    "{}: boat {}: cleaning would keep {} of {} samples, because {}",
                    s.file,
                    q(&b.id),
                    count(c.report.samples_kept),
                    count(c.report.samples_read),
                    c.report.loss_reason()
                );
                if !opts.keep_going {
                    return Err(RaceError::new(format!(
                        "{what} (--keep-going loads it anyway)"
                    )));
                }
                warnings.push(format!("{what}; loaded anyway (--keep-going)"));
            }
            if c.fixes.is_empty() {
                return Err(RaceError::in_file(
                    &s.file,
                    format!("boat {} has no fix left to race", q(&b.id)),
                ));
            }
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
    Ok((boats, reports, series))
}

/// The files' marks in the race's metres (a name given twice keeps its first position) and
/// their gates and lines, with each name's index.
fn build_marks(
    sources: &[Source],
    place: &Placement,
    warnings: &mut Vec<String>,
) -> (Vec<Mark>, HashMap<String, usize>) {
    let mut marks: Vec<Mark> = Vec::new();
    // Mark name → index in `marks` (100,000 marks were quadratic by scanning).
    let mut mark_of: HashMap<String, usize> = HashMap::new();
    for s in sources {
        for m in &s.marks {
            let position = place.to_race(s, m.c);
            match mark_of.get(&m.name).map(|&i| &marks[i]) {
                Some(k) if dist(k.position, position) > 1.0 => {
                    warnings.push(format!(
                        "{}: mark {} is given again {:.0} m away; the first position is kept",
                        s.file,
                        q(&m.name),
                        dist(k.position, position)
                    ));
                }
                Some(_) => {}
                None => {
                    mark_of.insert(m.name.clone(), marks.len());
                    marks.push(Mark::buoy(m.name.clone(), position));
                }
            }
        }
    }
    for s in sources {
        let by_name: HashMap<&str, &super::RawMark> =
            s.marks.iter().rev().map(|m| (m.name.as_str(), m)).collect();
        for cm in &s.compound {
            if let Some(k) = mark_of.get(&cm.name).map(|&i| &mut marks[i]) {
                // A compound of one mark is that buoy: it only adds the rounding side.
                if k.rounding.is_none() {
                    k.rounding = cm.rounding.clone();
                }
                continue;
            }
            let ends: Vec<[f64; 2]> = cm
                .marks
                .iter()
                .filter_map(|n| by_name.get(n.as_str()))
                .map(|m| place.to_race(s, m.c))
                .collect();
            mark_of.insert(cm.name.clone(), marks.len());
            marks.push(compound_mark(
                cm.name.clone(),
                cm.kind,
                &ends,
                cm.rounding.clone(),
            ));
        }
    }
    (marks, mark_of)
}

/// The start as a UTC time (none when only the time of day is known) and as the report's
/// words.
fn start_words(start: Option<f64>, time_of_day: bool) -> (Option<OffsetDateTime>, Option<String>) {
    let start_time = start.filter(|_| !time_of_day).and_then(|s| {
        let whole = s.floor();
        // To the microsecond: an f64 of ~1e8 s holds 3e-8 s, so finer digits are noise.
        let nanos = ((s - whole) * 1e6).round() as i128 * 1000;
        OffsetDateTime::from_unix_timestamp_nanos(
            (whole as i128 + EPOCH_UNIX as i128) * 1_000_000_000 + nanos,
        )
        .ok()
    });
    let start_text = match (start_time, start) {
        (Some(t), _) => t
            .format(&time::format_description::well_known::Rfc3339)
            .ok(),
        (None, Some(s)) if time_of_day => {
            let d = s.rem_euclid(86_400.0);
            Some(format!(
                "{:02}:{:02}:{:06.3} UTC (time of day; no file gives the date)",
                (d / 3600.0) as u32,
                (d % 3600.0 / 60.0) as u32,
                d % 60.0
            ))
        }
        _ => None,
    };
    (start_time, start_text)
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A gate or line from its buoys (a single buoy when only one was found).
fn compound_mark(
    name: String,
    kind: MarkKind,
    ends: &[[f64; 2]],
    rounding: Option<String>,
) -> Mark {
    let mut m = Mark::buoy(name, ends.first().copied().unwrap_or([0.0, 0.0]));
    m.rounding = rounding;
    if let [a, b] = ends {
        m.position = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        m.ends = Some([*a, *b]);
        m.kind = kind;
    }
    m
}

/// The same track twice in one file (a GPX exported twice into one): the copy is merged
/// into the first, with a warning.
fn merge_duplicate_tracks(s: &mut Source) {
    // Candidates by length and first point (a map: comparing every pair of a 40,000-boat
    // fleet was quadratic), then compared point for point.
    type Key = (usize, u64, u64, u64);
    let key = |b: &super::RawBoat| -> Key {
        let p = b.points.first();
        (
            b.points.len(),
            p.map_or(0, |p| p.t.to_bits()),
            p.map_or(0, |p| p.c[0].to_bits()),
            p.map_or(0, |p| p.c[1].to_bits()),
        )
    };
    let mut first_of: HashMap<Key, Vec<usize>> = HashMap::new();
    let mut merged_into: Vec<Option<usize>> = vec![None; s.boats.len()];
    for (k, merged) in merged_into.iter_mut().enumerate() {
        let same = first_of.entry(key(&s.boats[k])).or_default();
        let dup = same.iter().copied().find(|&j| {
            let (a, b) = (&s.boats[j].points, &s.boats[k].points);
            a.iter().zip(b).all(|(p, r)| p.t == r.t && p.c == r.c)
        });
        match dup {
            Some(j) => *merged = Some(j),
            None => same.push(k),
        }
    }
    if merged_into.iter().all(Option::is_none) {
        return;
    }
    let boats = std::mem::take(&mut s.boats);
    let ids: Vec<String> = boats.iter().map(|b| b.id.clone()).collect();
    for (k, gone) in boats.into_iter().enumerate() {
        let Some(j) = merged_into[k] else {
            s.boats.push(gone);
            continue;
        };
        let msg = format!(
            "boat {} repeats the track of boat {} point for point; it was merged into it",
            q(&gone.id),
            q(&ids[j])
        );
        s.warnings.push(format!("{}: {msg}", s.file));
        s.report
            .dropped
            .push(("duplicate track".into(), gone.points.len()));
    }
}

/// For each track of several sessions: the session that overlaps the other boats' time spans
/// most, else the longest; the others are dropped with a warning naming `--session`.
fn pick_sessions(sources: &mut [Source]) {
    let spans: Vec<(String, f64, f64)> = sources
        .iter()
        .flat_map(|s| s.boats.iter())
        .filter(|b| !b.points.is_empty())
        .map(|b| {
            let (a, z) = b
                .points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), p| {
                    (a.min(p.t), z.max(p.t))
                });
            (b.id.clone(), a, z)
        })
        .collect();
    for s in sources.iter_mut() {
        for (id, bounds) in std::mem::take(&mut s.sessions) {
            let Some(b) = s.boats.iter_mut().find(|b| b.id == id) else {
                continue;
            };
            let n = bounds.len() - 1;
            let score = |k: usize| -> (f64, f64) {
                let (a, z) = (b.points[bounds[k]].t, b.points[bounds[k + 1] - 1].t);
                let overlap: f64 = spans
                    .iter()
                    .filter(|o| o.0 != id)
                    .map(|o| (z.min(o.2) - a.max(o.1)).max(0.0))
                    .sum();
                (overlap, z - a)
            };
            let k = (0..n)
                .max_by(|&i, &j| {
                    let (x, y) = (score(i), score(j));
                    x.0.total_cmp(&y.0)
                        .then(x.1.total_cmp(&y.1))
                        .then(j.cmp(&i))
                })
                .unwrap_or(0);
            let how = if score(k).0 > 0.0 {
                "it overlaps the other boats"
            } else {
                "the longest; no other boat overlaps any"
            };
            let total = b.points.len();
            b.points = b.points[bounds[k]..bounds[k + 1]].to_vec();
            s.warnings.push(format!(
                "{}: boat {} has {n} sessions (pauses over 4 h); session {} was raced ({how}); choose another with --session N",
                s.file,
                q(&id),
                k + 1
            ));
            s.report
                .dropped
                .push(("points of other sessions".into(), total - b.points.len()));
        }
    }
}

/// The silent-loss rule for what the readers dropped: a file whose dropped positions outnumber
/// the fixes it kept is refused with the rule that dropped most, unless `keep_going`.
fn refuse_lost_reading(
    sources: &[Source],
    opts: &LoadOptions,
    warnings: &mut Vec<String>,
) -> RaceResult<()> {
    for s in sources {
        let (lost, kept) = (s.report.fixes_dropped, s.report.fixes);
        if lost <= kept {
            continue;
        }
        let (rule, n) = s
            .report
            .dropped
            .iter()
            .max_by_key(|d| d.1)
            .map_or(("dropped positions", lost), |d| (d.0.as_str(), d.1));
        let what = format!(
            "{}: reading would keep {} of {} positions, because of {} {rule}",
            s.file,
            count(kept),
            count(kept + lost),
            count(n)
        );
        if !opts.keep_going {
            return Err(RaceError::new(format!(
                "{what} (--keep-going loads it anyway)"
            )));
        }
        warnings.push(format!("{what}; loaded anyway (--keep-going)"));
    }
    Ok(())
}

/// Refuse boats whose median fix is further than [`MAX_RACE_RADIUS_M`] from the origin.
fn check_racing_area(sources: &[Source], origin: GeoPoint) -> RaceResult<()> {
    let mut far = Vec::new();
    for s in sources.iter().filter(|s| s.coords == Coords::Geo) {
        for b in s.boats.iter().filter(|b| !b.points.is_empty()) {
            let median = |k: usize| {
                let mut v: Vec<f64> = b.points.iter().map(|p| p.c[k]).collect();
                let mid = v.len() / 2;
                *v.select_nth_unstable_by(mid, f64::total_cmp).1
            };
            let d = great_circle_m(origin, GeoPoint::new(median(0), median(1)));
            if d > MAX_RACE_RADIUS_M {
                far.push(format!("{} ({}, {:.0} km)", q(&b.id), s.file, d / 1000.0));
            }
        }
    }
    if far.is_empty() {
        return Ok(());
    }
    Err(RaceError::new(format!(
        "boats further than {:.0} km from the race's origin ({:.4}, {:.4}): {}; the files mix racing areas, load each race on its own",
        MAX_RACE_RADIUS_M / 1000.0,
        origin.lat,
        origin.lon,
        far.join(", ")
    )))
}

/// Haversine distance on a sphere of the mean Earth radius, metres.
fn great_circle_m(a: GeoPoint, b: GeoPoint) -> f64 {
    let (p1, p2) = (a.lat.to_radians(), b.lat.to_radians());
    let dp = p2 - p1;
    let dl = (b.lon - a.lon).to_radians();
    let h = (dp / 2.0).sin().powi(2) + p1.cos() * p2.cos() * (dl / 2.0).sin().powi(2);
    2.0 * 6_371_008.8 * h.sqrt().min(1.0).asin()
}

/// Refuse pieces of a race that are far apart in time: every boat's fixes must come within
/// [`super::TIME_OUTLIER_GAP_S`] (a day) of the start (`st`, seconds since the epoch for
/// absolute times); a race XML whose start is 10 years from the tracks, or two years' logs
/// loaded together, say so instead of drawing boats that never meet.
fn check_one_time(sources: &[Source], st: f64, start_how: &str) -> RaceResult<()> {
    let day = super::TIME_OUTLIER_GAP_S;
    for s in sources {
        let shift = match (s.times, s.start_time) {
            (Times::Absolute, _) => -st,
            (Times::Relative, Some(own)) => own - st,
            (Times::Relative, None) => 0.0,
        };
        for b in &s.boats {
            let (lo, hi) = b
                .points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), p| {
                    (a.min(p.t + shift), z.max(p.t + shift))
                });
            if lo > hi || (lo - day..=hi + day).contains(&0.0) {
                continue;
            }
            let away = if lo > 0.0 { lo } else { -hi };
            let undated = sources
                .iter()
                .find(|s| s.time_of_day)
                .map(|s| {
                    format!(
                        " ({} has no date: its times of day were read as 2020-01-01)",
                        s.file
                    )
                })
                .unwrap_or_default();
            return Err(RaceError::in_file(
                &s.file,
                format!(
                    "boat {}'s fixes are {} {} the race start (the start comes from {start_how}){undated}; the files are not one race, load each on its own",
                    q(&b.id),
                    span_words(away.abs()),
                    if lo > 0.0 { "after" } else { "before" },
                ),
            ));
        }
    }
    Ok(())
}

/// A long duration in words: "3.2 days", "10.0 years" (times are at most 120 years apart:
/// absolute times lie in 1980–2099, relative ones within ±1e9 s).
fn span_words(s: f64) -> String {
    const YEAR: f64 = 365.25 * 86_400.0;
    if s >= YEAR {
        format!("{:.1} years", s / YEAR)
    } else {
        format!("{:.1} days", s / 86_400.0)
    }
}

/// The start: stated, else maxSail's minute after its track's first fix, else the earliest
/// time at which every boat with absolute times has a fix. Also the phrase saying which.
fn race_start(sources: &[Source], warnings: &mut Vec<String>) -> (Option<f64>, String) {
    let first_abs = |file: &str| -> Option<f64> {
        sources
            .iter()
            .filter(|s| s.times == Times::Absolute && stem(&s.file) == stem(file))
            .flat_map(|s| s.boats.iter())
            .filter_map(|b| b.points.iter().map(|p| p.t).min_by(f64::total_cmp))
            .min_by(f64::total_cmp)
    };
    if let Some(s) = sources.iter().find(|s| s.start_time.is_some()) {
        return (s.start_time, format!("start_time of {}", s.file));
    }
    for s in sources {
        if let Some((track, minutes)) = &s.start_after_track {
            if let Some(t0) = first_abs(track) {
                return (
                    Some(t0 + minutes * 60.0),
                    format!("{minutes} min after the first fix of {track} ({})", s.file),
                );
            }
            warnings.push(format!(
                "{}: its start refers to {track}, which was not loaded; the start is taken from the tracks",
                s.file
            ));
        }
    }
    let start = sources
        .iter()
        .filter(|s| s.times == Times::Absolute)
        .flat_map(|s| s.boats.iter())
        .filter_map(|b| b.points.iter().map(|p| p.t).min_by(f64::total_cmp))
        .max_by(f64::total_cmp);
    match start {
        Some(_) => (
            start,
            "the earliest time at which every boat has a fix".into(),
        ),
        None => (None, "the files' own race time".into()),
    }
}

/// The course: `--course`, else a file's course, else the marks in file order from the fleet's
/// position at the start (a file with marks but no course races to them in order).
fn build_course(
    sources: &[Source],
    opts: &LoadOptions,
    marks: &mut Vec<Mark>,
    mark_of: &mut HashMap<String, usize>,
    boats: &[Boat],
) -> RaceResult<Vec<usize>> {
    let stated = opts
        .course
        .clone()
        .map(|c| (c, "--course".to_string()))
        .or_else(|| {
            sources
                .iter()
                .find_map(|s| s.course.clone().map(|c| (c, s.file.clone())))
        });
    if let Some((names, from)) = stated {
        let mut c = Vec::with_capacity(names.len());
        for n in &names {
            c.push(resolve_mark(marks, mark_of, n).ok_or_else(|| {
                RaceError::new(format!(
                    "{from}: the course names the mark {}, which no file defines",
                    q(n)
                ))
            })?);
        }
        return Ok(c);
    }
    if marks.is_empty() {
        return Ok(Vec::new());
    }
    // From the fleet's mean position at the start signal, to each mark in the order listed.
    let at_start: Vec<[f64; 2]> = boats
        .iter()
        .filter(|b| !b.fixes().is_empty())
        .map(|b| b.state_at(0.0).position)
        .collect();
    let k = at_start.len().max(1) as f64;
    let centre = [
        at_start.iter().map(|p| p[0]).sum::<f64>() / k,
        at_start.iter().map(|p| p[1]).sum::<f64>() / k,
    ];
    let mut start = Mark::buoy("fleet at the start", centre);
    start.kind = MarkKind::FleetStart;
    let n = marks.len();
    marks.push(start);
    let mut c = vec![n];
    c.extend(0..n);
    Ok(c)
}

/// A course name: a mark, or `A/B` (a gate between the marks A and B, added to `marks`).
/// `mark_of`: mark name → index in `marks`, kept in step.
fn resolve_mark(
    marks: &mut Vec<Mark>,
    mark_of: &mut HashMap<String, usize>,
    name: &str,
) -> Option<usize> {
    if let Some(&i) = mark_of.get(name) {
        return Some(i);
    }
    let (a, b) = name.split_once('/')?;
    let pa = marks[*mark_of.get(a.trim())?].position;
    let pb = marks[*mark_of.get(b.trim())?].position;
    mark_of.insert(name.to_string(), marks.len());
    marks.push(compound_mark(
        name.to_string(),
        MarkKind::Gate,
        &[pa, pb],
        None,
    ));
    Some(marks.len() - 1)
}

/// Add laps (`course[1..]` again) while at least half the boats sail them: the maxSail files
/// give the marks of an out-and-back but not the number of laps.
fn repeat_laps(boats: &[Boat], marks: &[Mark], course: Vec<usize>) -> Vec<usize> {
    if course.len() < 2 {
        return course;
    }
    let lap: Vec<usize> = course[1..].to_vec();
    let radius = crate::course::rounding_radius(marks, &course, crate::course::typical_step(boats));
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

/// The fleet's median fix (the medians of every geographic fix's latitude and longitude):
/// where the racing is, whatever a few glitches say. `None` without geographic fixes.
fn fleet_median(sources: &[Source]) -> Option<GeoPoint> {
    let fixes = || {
        sources
            .iter()
            .filter(|s| s.coords == Coords::Geo)
            .flat_map(|s| s.boats.iter().flat_map(|b| b.points.iter()))
    };
    let median = |k: usize| {
        let mut v: Vec<f64> = fixes().map(|p| p.c[k]).collect();
        if v.is_empty() {
            return None;
        }
        let mid = v.len() / 2;
        Some(*v.select_nth_unstable_by(mid, f64::total_cmp).1)
    };
    Some(GeoPoint::new(median(0)?, median(1)?))
}

/// Centre of everything geographic: the marks' mean if any file has marks, else the middle of
/// the bounding box of the tracks' fixes within [`MAX_RACE_RADIUS_M`] of the fleet's median
/// fix (a glitch 100 km off, which cleaning drops as a spike, does not move the origin). A mark
/// that far from the fleet is refused, naming its file.
fn geo_centre(sources: &[Source]) -> RaceResult<GeoPoint> {
    let geo = || sources.iter().filter(|s| s.coords == Coords::Geo);
    let fleet = fleet_median(sources);
    if let Some(f) = fleet {
        for s in geo() {
            for m in &s.marks {
                let d = great_circle_m(f, GeoPoint::new(m.c[0], m.c[1]));
                if d > MAX_RACE_RADIUS_M {
                    return Err(RaceError::in_file(
                        &s.file,
                        format!(
                            "mark {} ({:.4}, {:.4}) is {:.0} km from the boats' median fix ({:.4}, {:.4}), more than {:.0} km: it belongs to another racing area",
                            q(&m.name),
                            m.c[0],
                            m.c[1],
                            d / 1000.0,
                            f.lat,
                            f.lon,
                            MAX_RACE_RADIUS_M / 1000.0
                        ),
                    ));
                }
            }
        }
    }
    let marks: Vec<[f64; 2]> = geo().flat_map(|s| s.marks.iter().map(|m| m.c)).collect();
    if !marks.is_empty() {
        let k = marks.len() as f64;
        return Ok(GeoPoint::new(
            marks.iter().map(|c| c[0]).sum::<f64>() / k,
            marks.iter().map(|c| c[1]).sum::<f64>() / k,
        ));
    }
    let near = |p: &super::RawPoint| {
        fleet.is_none_or(|f| great_circle_m(f, GeoPoint::new(p.c[0], p.c[1])) <= MAX_RACE_RADIUS_M)
    };
    let (mut lat0, mut lat1, mut lon0, mut lon1) = (90.0f64, -90.0f64, 180.0f64, -180.0f64);
    for p in geo()
        .flat_map(|s| s.boats.iter().flat_map(|b| b.points.iter()))
        .filter(|p| near(p))
    {
        lat0 = lat0.min(p.c[0]);
        lat1 = lat1.max(p.c[0]);
        lon0 = lon0.min(p.c[1]);
        lon1 = lon1.max(p.c[1]);
    }
    Ok(GeoPoint::new(0.5 * (lat0 + lat1), 0.5 * (lon0 + lon1)))
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
