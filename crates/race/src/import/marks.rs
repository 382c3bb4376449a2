//! `--marks FILE`: course marks for tracks that have none. GPX (its waypoints and route
//! points), JSON (`[{"name", "lat", "lon"}]` or `{"marks": [...]}`) or CSV (`name,lat,lon`,
//! with or without that header).

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
    let mut s = if t.starts_with('<') {
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
