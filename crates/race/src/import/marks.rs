//! `--marks FILE`: course marks for tracks that have none. GPX (its waypoints and route
//! points), JSON (`[{"name", "lat", "lon"}]` or `{"marks": [...]}`) or CSV (`name,lat,lon`,
//! with or without that header).

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
    let mut s = if t.starts_with('<') {
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

fn csv_marks(file: &str, text: &str) -> RaceResult<Source> {
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    for (i, l) in text.lines().enumerate() {
        let l = l.trim();
        if l.is_empty() {
            continue;
        }
        let cells: Vec<&str> = l.split(',').map(str::trim).collect();
        let line = i as u64 + 1;
        if i == 0
            && cells
                .first()
                .is_some_and(|c| c.eq_ignore_ascii_case("name"))
        {
            continue;
        }
        let [name, lat, lon] = cells[..] else {
            return Err(RaceError::at_line(
                file,
                line,
                format!("{} cells; a marks CSV row is name,lat,lon", cells.len()),
            ));
        };
        let num = |c: &str, what: &str| {
            c.parse::<f64>().map_err(|_| {
                RaceError::at_line(file, line, format!("{what} is {}, not a number", q(c)))
            })
        };
        let (la, lo) = (num(lat, "lat")?, num(lon, "lon")?);
        if let Some(p) = super::geo_problem(la, lo) {
            return Err(RaceError::at_line(file, line, p));
        }
        if name.is_empty() {
            return Err(RaceError::at_line(file, line, "the mark has no name"));
        }
        s.marks.push(RawMark {
            name: name.to_string(),
            c: [la, lo],
        });
    }
    Ok(s)
}
