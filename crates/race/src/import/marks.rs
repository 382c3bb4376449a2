//! `--marks FILE`: course marks for tracks that have none. GPX (its waypoints and route
//! points), a SailGP / AC race XML (its marks, gates and lines in the course's order), JSON
//! (`[{"name", "lat", "lon"}]` or `{"marks": [...]}`) or CSV: columns by header names where
//! the first row names lat and lon (`name,desc,sym,lat,lon` as chart plotters export), else
//! `name,lat,lon` rows.

use serde::Deserialize;

use super::{Coords, RawMark, Source, Times, q};
use crate::error::{RaceError, RaceResult};

/// A mark as written: its fields' types are checked by hand, so a message names the field
/// (serde names the type it expected, not the field), and the shape by serde, which gives the
/// line (an untagged enum of list and object gave only "line 0").
#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mark object with name, lat and lon"
)]
struct JsonMark {
    name: serde_json::Value,
    lat: serde_json::Value,
    lon: serde_json::Value,
}

#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "an object with \"marks\", a list of marks"
)]
struct JsonMarksObject {
    marks: Vec<JsonMark>,
}

/// Mark `k`'s name, latitude and longitude, or what is wrong, naming the field.
fn mark_fields(k: usize, m: &JsonMark) -> Result<(String, f64, f64), String> {
    let name = m
        .name
        .as_str()
        .ok_or_else(|| format!("marks[{k}]: \"name\" is {}, not a string", shown(&m.name)))?;
    let num = |v: &serde_json::Value, field: &str| {
        v.as_f64().ok_or_else(|| {
            format!(
                "marks[{k}] ({}): \"{field}\" is {}, not a number",
                q(name),
                shown(v)
            )
        })
    };
    Ok((name.to_string(), num(&m.lat, "lat")?, num(&m.lon, "lon")?))
}

/// A JSON value for a message, escaped and cut.
fn shown(v: &serde_json::Value) -> String {
    crate::text::cut(&v.to_string(), crate::text::QUOTE_MAX_CHARS)
}

pub(crate) fn parse(file: &str, bytes: &[u8]) -> RaceResult<Source> {
    let decoded = super::rules::utf8_of(file, bytes)?;
    let bytes = &decoded[..];
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
        let wrong = |e: serde_json::Error| super::json::json_error(file, "a marks file", &e);
        let list: Vec<JsonMark> = if t.starts_with('[') {
            serde_json::from_str(text).map_err(wrong)?
        } else {
            serde_json::from_str::<JsonMarksObject>(text)
                .map_err(wrong)?
                .marks
        };
        let mut s = Source::new(file, Coords::Geo, Times::Absolute);
        for (k, m) in list.iter().enumerate() {
            let (name, lat, lon) =
                mark_fields(k, m).map_err(|what| RaceError::in_file(file, what))?;
            if let Some(p) = super::geo_problem(lat, lon) {
                return Err(RaceError::in_file(
                    file,
                    format!("marks[{k}] ({}): {p}", q(&name)),
                ));
            }
            s.marks.push(RawMark {
                name,
                c: [lat, lon],
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
