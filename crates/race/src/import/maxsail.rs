//! maxSail's `*-meta-data.json` (Valencia sample): marks (`BALIZAS`), wind (`TWD`, `TWS` in
//! knots) and the start (`MINUTO_SALIDA` minutes after the first fix of `ARCHIVO_TRACK`).
//! The course is the start mark (`S…`, salida) then the others in file order, then back to the
//! start mark: an out-and-back sausage, repeated for as many laps as the boats sail (the
//! Valencia races sail it twice; the file does not say).

use serde::Deserialize;

use super::{Coords, RawMark, Source, Times};
use crate::Wind;
use crate::error::{RaceError, RaceResult};

#[derive(Deserialize)]
#[allow(non_snake_case)]
#[serde(expecting = "a maxSail meta-data object with BALIZAS")]
struct Meta {
    TWD: Option<f64>,
    TWS: Option<f64>,
    MINUTO_SALIDA: Option<f64>,
    BALIZAS: Vec<Baliza>,
    ARCHIVO_TRACK: Option<String>,
}

#[derive(Deserialize)]
#[serde(expecting = "a mark object with lat, lon and nombre")]
struct Baliza {
    lat: f64,
    lon: f64,
    nombre: String,
}

/// The largest start minute after the track's first fix: a day (the Valencia files say 5 to
/// 12 minutes; a race starts the day its boats are out).
const MAX_START_MINUTE: f64 = 1440.0;

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let m: Meta = serde_json::from_str(text)
        .map_err(|e| super::json::json_error(file, "a maxSail meta-data file", &e))?;
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    for (k, b) in m.BALIZAS.iter().enumerate() {
        if let Some(p) = super::geo_problem(b.lat, b.lon) {
            return Err(RaceError::in_file(
                file,
                format!("BALIZAS[{k}] ({}): {p}", super::q(&b.nombre)),
            ));
        }
        s.marks.push(RawMark {
            name: b.nombre.clone(),
            c: [b.lat, b.lon],
        });
    }
    if let (Some(d), Some(k)) = (m.TWD, m.TWS)
        && d.is_finite()
        && k.is_finite()
        && k >= 0.0
    {
        s.wind = Some(Wind {
            from_deg: d.rem_euclid(360.0),
            speed_mps: super::knots_to_mps(k),
        });
    }
    if let Some(min) = m.MINUTO_SALIDA
        && !(min.is_finite() && min.abs() <= MAX_START_MINUTE)
    {
        return Err(RaceError::in_file(
            file,
            format!(
                "MINUTO_SALIDA is {}, not a minute within a day of the track's first fix (-1440 to 1440)",
                crate::text::number(min)
            ),
        ));
    }
    if let (Some(min), Some(track)) = (m.MINUTO_SALIDA, m.ARCHIVO_TRACK) {
        s.start_after_track = Some((track, min));
    }
    let start = s.marks.iter().position(|b| b.name.starts_with('S'));
    if let Some(st) = start {
        let mut course = vec![s.marks[st].name.clone()];
        course.extend(
            s.marks
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != st)
                .map(|(_, b)| b.name.clone()),
        );
        course.push(s.marks[st].name.clone());
        s.course = Some(course);
        s.repeat_laps = true;
    }
    Ok(s)
}
