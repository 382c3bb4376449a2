//! `--marks FILE`: course marks for tracks that have none. GPX (its waypoints and route
//! points), a SailGP / AC race XML (its marks, gates and lines in the course's order), JSON
//! (`[{"name", "lat", "lon"}]` or `{"marks": [...]}`) or CSV: columns by header names where
//! the first row names lat and lon (`name,desc,sym,lat,lon` as chart plotters export), else
//! `name,lat,lon` rows.

use serde::Deserialize;

use super::{Coords, RawMark, Source, Times, q};
use crate::error::{RaceError, RaceResult};

#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mark object with name, lat and lon"
)]
struct JsonMark {
    name: String,
    lat: f64,
    lon: f64,
}

#[derive(Deserialize)]
#[serde(untagged, expecting = "a list of marks, or an object with \"marks\"")]
enum JsonMarks {
    List(Vec<JsonMark>),
    Object { marks: Vec<JsonMark> },
}

pub(crate) fn parse(file: &str, bytes: &[u8]) -> RaceResult<Source> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let text = std::str::from_utf8(bytes)
        .map_err(|_| RaceError::in_file(file, "the marks file is not UTF-8 text"))?;
    let t = text.trim_start();
    let mut s = if t.starts_with('<') && t[..t.len().min(64 * 1024)].contains("<Race") {
        // A race XML is a course: its marks, gates, lines and their order.
        super::race_xml::parse(file, text)?
    } else if t.starts_with('<') {
        let mut s = super::gpx::parse(file, text, None)?;
        s.boats.clear();
        s
    } else if t.starts_with('[') || t.starts_with('{') {
        let m: JsonMarks = serde_json::from_str(text)
            .map_err(|e| super::json::json_error(file, "a marks file", &e))?;
        let list = match m {
            JsonMarks::List(l) | JsonMarks::Object { marks: l } => l,
        };
        let mut s = Source::new(file, Coords::Geo, Times::Absolute);
        for (k, m) in list.into_iter().enumerate() {
            if let Some(p) = super::geo_problem(m.lat, m.lon) {
                return Err(RaceError::in_file(
                    file,
                    format!("marks[{k}] ({}): {p}", q(&m.name)),
                ));
            }
            s.marks.push(RawMark {
                name: m.name,
                c: [m.lat, m.lon],
            });
        }
        s
    } else {
        csv_marks(file, text)?
    };
    if s.marks.is_empty() {
        return Err(RaceError::in_file(file, "the marks file has no marks"));
    }
    s.report.format = "marks".into();
    s.report.records_read = s.marks.len();
    s.report.date_source = "none (marks only)".into();
    Ok(s)
}

/// The columns of a marks CSV: by header names where the first row names `lat` and `lon`
/// columns (chart plotters write `name,desc,sym,lat,lon`, …), else `name,lat,lon`.
struct MarkColumns {
    name: usize,
    lat: usize,
    lon: usize,
    /// The first row is the header.
    header: bool,
}

fn mark_columns(first: &[String]) -> MarkColumns {
    let find = |names: &[&str]| {
        first
            .iter()
            .position(|c| names.iter().any(|n| c.eq_ignore_ascii_case(n)))
    };
    match (
        find(&["lat", "latitude"]),
        find(&["lon", "lng", "long", "longitude"]),
    ) {
        (Some(lat), Some(lon)) => MarkColumns {
            name: find(&["name", "mark", "ident", "waypoint", "id"]).unwrap_or(usize::MAX),
            lat,
            lon,
            header: true,
        },
        _ => MarkColumns {
            name: 0,
            lat: 1,
            lon: 2,
            header: first
                .first()
                .is_some_and(|c| c.eq_ignore_ascii_case("name")),
        },
    }
}

fn csv_marks(file: &str, text: &str) -> RaceResult<Source> {
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    let mut rows = ::csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(::csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut cols: Option<MarkColumns> = None;
    for row in rows.records() {
        let row = row.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            RaceError::at_line(file, line, "not a readable CSV row")
        })?;
        let line = row.position().map_or(0, |p| p.line());
        let cells: Vec<String> = row.iter().map(str::to_string).collect();
        if cells.iter().all(String::is_empty) {
            continue;
        }
        let c = match &cols {
            Some(c) => c,
            None => {
                let c = cols.insert(mark_columns(&cells));
                if c.header {
                    continue;
                }
                c
            }
        };
        let need = c
            .lat
            .max(c.lon)
            .max(if c.name == usize::MAX { 0 } else { c.name })
            + 1;
        if cells.len() < need {
            return Err(RaceError::at_line(
                file,
                line,
                if c.header {
                    format!("{} cells; the header names {need} columns", cells.len())
                } else {
                    format!(
                        "{} cells; a marks CSV row is name,lat,lon (or give a header naming lat and lon)",
                        cells.len()
                    )
                },
            ));
        }
        if !c.header && cells.len() != 3 {
            return Err(RaceError::at_line(
                file,
                line,
                format!(
                    "{} cells; a marks CSV row is name,lat,lon (or give a header naming lat and lon)",
                    cells.len()
                ),
            ));
        }
        let num = |k: usize, what: &str| {
            let v = cells[k].as_str();
            v.parse::<f64>().map_err(|_| {
                RaceError::at_line(file, line, format!("{what} is {}, not a number", q(v)))
            })
        };
        let (la, lo) = (num(c.lat, "lat")?, num(c.lon, "lon")?);
        if let Some(p) = super::geo_problem(la, lo) {
            return Err(RaceError::at_line(file, line, p));
        }
        let name = match c.name {
            usize::MAX => format!("mark{}", s.marks.len() + 1),
            k => cells[k].clone(),
        };
        if name.is_empty() {
            return Err(RaceError::at_line(file, line, "the mark has no name"));
        }
        s.marks.push(RawMark { name, c: [la, lo] });
    }
    Ok(s)
}
