//! SailGP / America's Cup (AC35 data feed) race XML (`<Race>`): the course as compound marks in sequence
//! (`CompoundMarkSequence/Corner`), each one mark or two (a gate, or the start or finish line),
//! their rounding sides, the `Boundary` course limit and the race start time. Boats come from
//! the boat logs loaded beside it (the XML names yachts only by a SourceID).
//!
//! Names: a compound of one mark is that mark's name ("M1"); of two it is "A/B" ("LG1/LG2"),
//! the same spelling `--course` uses for a gate. The first compound of the sequence with two
//! marks is the start line, the last the finish line, the others gates.

use quick_xml::XmlVersion;
use quick_xml::events::{BytesStart, Event};

use super::xml_text::{line_of, next_event};
use super::{Coords, RawCourseMark, RawMark, Source, Times, epoch_seconds, q};
use crate::course::MarkKind;
use crate::error::{RaceError, RaceResult};

struct Compound {
    id: String,
    marks: Vec<String>,
}

fn attr(e: &BytesStart, name: &str) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == name)
        .and_then(|a| {
            a.normalized_value(XmlVersion::Implicit1_0)
                .ok()
                .map(|v| v.into_owned())
        })
}

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    let mut r = quick_xml::Reader::from_str(text);
    let mut compounds: Vec<Compound> = Vec::new();
    let mut sequence: Vec<(String, Option<String>)> = Vec::new();
    let mut in_boundary = false;
    let mut saw_race = false;
    let mut path: Vec<String> = Vec::new();
    // The line of each open element, to name where a truncated file stops.
    let mut opened_at: Vec<u64> = Vec::new();
    loop {
        let pos = r.buffer_position();
        let ev = next_event(&mut r, file, text)?;
        let line = || line_of(text, pos);
        let num = |e: &BytesStart, name: &str| -> RaceResult<f64> {
            let v = attr(e, name).ok_or_else(|| {
                RaceError::at_line(
                    file,
                    line(),
                    format!("<{}> has no {name}", AsRef::<str>::as_ref(&e.name())),
                )
            })?;
            v.trim().parse::<f64>().map_err(|_| {
                RaceError::at_line(file, line(), format!("{name} is {}, not a number", q(&v)))
            })
        };
        let (e, empty) = match &ev {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                opened_at.pop();
                if path.pop().as_deref() == Some("CourseLimit") {
                    in_boundary = false;
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let name = AsRef::<str>::as_ref(&e.name()).to_string();
        match name.as_str() {
            "Race" => saw_race = true,
            "RaceStartTime" => {
                // SailGP writes `Start` (RFC 3339); the AC35 feed `Time` ("…T13:30:00-0700").
                if let Some(v) = attr(e, "Start").or_else(|| attr(e, "Time")) {
                    let t = time::OffsetDateTime::parse(
                        &v,
                        &time::format_description::well_known::Rfc3339,
                    )
                    .ok()
                    .map(epoch_seconds)
                    .or_else(|| super::timefmt::parse_datetime(&v))
                    .ok_or_else(|| {
                        RaceError::at_line(
                            file,
                            line(),
                            format!("RaceStartTime is {}, not an ISO 8601 time", q(&v)),
                        )
                    })?;
                    s.start_time = Some(t);
                }
            }
            "RaceID" => {}
            "CompoundMark" => compounds.push(Compound {
                id: attr(e, "CompoundMarkID").unwrap_or_default(),
                marks: Vec::new(),
            }),
            "Mark" if path.last().map(String::as_str) == Some("CompoundMark") => {
                let mark = attr(e, "Name").unwrap_or_else(|| format!("mark{}", s.marks.len() + 1));
                let (lat, lon) = (num(e, "TargetLat")?, num(e, "TargetLng")?);
                if let Some(p) = super::geo_problem(lat, lon) {
                    return Err(RaceError::at_line(
                        file,
                        line(),
                        format!("mark {}: {p}", q(&mark)),
                    ));
                }
                if !s.marks.iter().any(|m| m.name == mark) {
                    s.marks.push(RawMark {
                        name: mark.clone(),
                        c: [lat, lon],
                    });
                }
                if let Some(c) = compounds.last_mut() {
                    c.marks.push(mark);
                }
            }
            "Corner" => sequence.push((
                attr(e, "CompoundMarkID").unwrap_or_default(),
                attr(e, "Rounding"),
            )),
            // SailGP names its limits (`Boundary`, `Exclusion Zone`, …); AC35 has one, unnamed.
            "CourseLimit" => {
                in_boundary = matches!(attr(e, "name").as_deref(), Some("Boundary") | None)
            }
            "Limit" if in_boundary => {
                let (lat, lon) = (num(e, "Lat")?, num(e, "Lon")?);
                if let Some(p) = super::geo_problem(lat, lon) {
                    return Err(RaceError::at_line(file, line(), format!("boundary: {p}")));
                }
                s.boundary.push([lat, lon]);
            }
            _ => {}
        }
        if !empty {
            path.push(name);
            opened_at.push(line());
        }
    }
    // quick-xml reports no error for elements left open at the end: a file cut short (a
    // partial download) would load a partial course, its finish gone.
    if let (Some(open), Some(at)) = (path.last(), opened_at.last()) {
        return Err(RaceError::at_line(
            file,
            *at,
            format!(
                "<{}> is never closed: the file ends inside it (a truncated download?) and its course would be incomplete",
                crate::text::cut(open, 40)
            ),
        ));
    }
    if !saw_race {
        return Err(RaceError::in_file(
            file,
            "has no <Race> element: not a race XML",
        ));
    }
    let mut course = Vec::with_capacity(sequence.len());
    let n = sequence.len();
    for (k, (id, rounding)) in sequence.iter().enumerate() {
        let Some(c) = compounds.iter().find(|c| &c.id == id) else {
            return Err(RaceError::in_file(
                file,
                format!(
                    "the CompoundMarkSequence names CompoundMarkID {}, which the Course does not define",
                    q(id)
                ),
            ));
        };
        if c.marks.is_empty() {
            return Err(RaceError::in_file(
                file,
                format!("CompoundMark {} has no marks", q(id)),
            ));
        }
        let name = c.marks.join("/");
        let kind = match (c.marks.len(), k) {
            (1, _) => MarkKind::Mark,
            (_, 0) => MarkKind::StartLine,
            (_, k) if k + 1 == n => MarkKind::FinishLine,
            _ => MarkKind::Gate,
        };
        if !s.compound.iter().any(|m| m.name == name) {
            s.compound.push(RawCourseMark {
                name: name.clone(),
                marks: c.marks.clone(),
                kind,
                rounding: rounding.clone(),
            });
        }
        course.push(name);
    }
    if !course.is_empty() {
        s.course = Some(course);
    }
    s.report.records_read = compounds.len() + sequence.len();
    s.report.date_source = "RaceStartTime".into();
    s.report.channels = vec!["course".into(), "boundary".into(), "start time".into()];
    Ok(s)
}
