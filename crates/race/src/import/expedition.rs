//! Expedition's log CSV: `Utc` is a serial day number (days since 1899-12-30, as spreadsheets
//! count them). Expedition writes only the channels that changed, so every channel carries
//! forward from the row that last wrote it, and a fix exists only on a row that wrote a
//! position. `Set`/`iSet` and `Drift`/`iDrift` are synonyms.
//!
//! Sparse form: when many channels are logged Expedition writes the header `!Boat,Utc,Bsp,…`
//! and each row as `boat,utc` followed by `channel id,value` pairs, only for the channels that
//! changed. A channel's id is its place in the header counted from `Utc` (Utc = 0, the next
//! column 1, …), as in the dense form where `Utc` is the first column. Such rows are spread
//! back into the header's columns before reading; pairs naming no column are counted.
//!
//! Resolution: the times are kept as written, in f64 seconds; Expedition writes `Utc` with 5
//! decimals, so the file's own resolution is 1e-5 day = 0.864 s (f64 holds 38516.38857 days to
//! 1e-11 day, about a microsecond).

use super::csv::number_cell;
use super::{Coords, RawBoat, RawPoint, Series, Source, Times};
use crate::error::{RaceError, RaceResult};
use crate::track::Logged;

/// Days from 1899-12-30 (the spreadsheet epoch) to 1970-01-01.
const SERIAL_DAY_OF_UNIX_EPOCH: f64 = 25_569.0;

/// The channels kept as time series: (header, channel, unit, factor to SI).
const CHANNELS: [(&str, &str, &str, f64); 7] = [
    ("bsp", "bsp", "m/s", super::super::clean::MPS_PER_KNOT),
    ("hdg", "heading", "deg", 1.0),
    ("heel", "heel", "deg", 1.0),
    ("tws", "tws", "m/s", super::super::clean::MPS_PER_KNOT),
    ("twd", "twd", "deg", 1.0),
    ("aws", "aws", "m/s", super::super::clean::MPS_PER_KNOT),
    ("awa", "awa", "deg", 1.0),
];

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut lines = text.lines().enumerate();
    let header: Vec<String> = lines
        .next()
        .map(|(_, h)| {
            h.split(',')
                .map(|c| c.trim().to_ascii_lowercase())
                .collect()
        })
        .unwrap_or_default();
    let col = |names: &[&str]| header.iter().position(|h| names.contains(&h.as_str()));
    let need = |i: Option<usize>, what: &str| {
        i.ok_or_else(|| {
            RaceError::at_line(
                file,
                1,
                format!("the Expedition header has no {what} column"),
            )
        })
    };
    let utc = need(col(&["utc"]), "Utc")?;
    let lat = need(col(&["lat"]), "Lat")?;
    let lon = need(col(&["lon"]), "Lon")?;
    let sog = col(&["sog"]);
    let chans: Vec<(usize, &str, &str, f64)> = CHANNELS
        .iter()
        .filter_map(|(h, c, u, f)| col(&[h]).map(|i| (i, *c, *u, *f)))
        .collect();
    let set_col = col(&["iset", "set"]);
    // The sparse form: `!Boat` first in the header.
    let sparse = header.first().is_some_and(|h| h.starts_with('!'));
    let mut dense: Vec<&str> = Vec::new();
    let mut bad_pairs = 0usize;
    let mut series: Vec<Series> = chans
        .iter()
        .map(|(_, c, u, _)| Series {
            boat: None,
            channel: c.to_string(),
            unit: u.to_string(),
            t: Vec::new(),
            v: Vec::new(),
        })
        .collect();
    // The latest value of each channel (carried forward).
    let mut last: Vec<f64> = vec![f64::NAN; chans.len()];
    let mut last_sog = f64::NAN;
    let mut points = Vec::new();
    let (mut rows, mut no_time, mut no_fix) = (0usize, 0usize, 0usize);
    let mut cells: Vec<&str> = Vec::with_capacity(header.len());
    for (i, l) in lines {
        let l = l.trim_end_matches('\r');
        if l.trim().is_empty() || (sparse && l.starts_with('!')) {
            continue;
        }
        rows += 1;
        let line = i as u64 + 1;
        cells.clear();
        cells.extend(l.split(','));
        if sparse {
            bad_pairs += spread_pairs(&cells, utc, header.len(), &mut dense);
            std::mem::swap(&mut cells, &mut dense);
        }
        let num = |k: usize| number_cell(file, line, &header[k], cells.get(k).map_or("", |c| c));
        let days = num(utc)?;
        if days.is_nan() && cells.get(utc).is_none_or(|c| c.trim().is_empty()) {
            no_time += 1;
            continue;
        }
        if !(days.is_finite() && (days * 86_400.0).is_finite()) {
            return Err(RaceError::at_line(
                file,
                line,
                format!(
                    "Utc is {}, not a finite day number",
                    super::q(cells.get(utc).map_or("", |c| c.trim()))
                ),
            ));
        }
        // To the millisecond: the file's 5 decimals of a day are 0.864 s steps, and the
        // product's last bits are noise (…32.448000193 s).
        let t = (((days - SERIAL_DAY_OF_UNIX_EPOCH) * 86_400.0 - super::EPOCH_UNIX as f64) * 1e3)
            .round()
            / 1e3;
        for (k, (c, _, _, f)) in chans.iter().enumerate() {
            let v = num(*c)?;
            if v.is_finite() {
                last[k] = v * f;
                series[k].t.push(t);
                series[k].v.push(last[k] as f32);
            }
        }
        if let Some(c) = set_col {
            num(c)?;
        }
        if let Some(c) = sog {
            let v = num(c)?;
            if v.is_finite() {
                last_sog = v * super::super::clean::MPS_PER_KNOT;
            }
        }
        let (la, lo) = (num(lat)?, num(lon)?);
        if !(la.is_finite() && lo.is_finite()) {
            no_fix += 1;
            continue;
        }
        if let Some(p) = super::geo_problem(la, lo) {
            return Err(RaceError::at_line(file, line, p));
        }
        let at = |name: &str| {
            chans
                .iter()
                .position(|c| c.1 == name)
                .map_or(f64::NAN, |k| last[k])
        };
        points.push(RawPoint {
            t,
            c: [la, lo],
            logged: Logged {
                heading: at("heading") as f32,
                heel: at("heel") as f32,
            },
            sog: last_sog,
        });
    }
    if points.is_empty() {
        return Err(RaceError::in_file(
            file,
            "the Expedition log has no row with a position",
        ));
    }
    let mut s = Source::new(file, Coords::Geo, Times::Absolute);
    s.report.format = "Expedition log".into();
    s.report.records_read = rows;
    s.report.date_source =
        "Utc (serial days since 1899-12-30, resolution 1e-5 day = 0.864 s)".into();
    s.drop_rule("rows without a Utc time", no_time);
    s.drop_rule("rows without a position (channels carried forward)", no_fix);
    s.drop_rule("sparse channel pairs naming no header column", bad_pairs);
    if sparse {
        s.report.format = "Expedition log (sparse rows)".into();
    }
    let id = super::boat_id_from_file(file);
    s.report.channels = series
        .iter()
        .filter(|x| !x.t.is_empty())
        .map(|x| x.channel.clone())
        .collect();
    if set_col.is_some() {
        s.report.channels.push("set".into());
    }
    for mut x in series.into_iter().filter(|x| !x.t.is_empty()) {
        x.boat = Some(id.clone());
        s.series.push(x);
    }
    s.boats.push(RawBoat {
        name: id.clone(),
        id,
        color: None,
        max_speed_mps: super::spike_limit_mps(&points),
        points,
    });
    Ok(s)
}

/// A sparse row (`boat,utc,id,value,id,value,…`) spread into `dense` by header column: the
/// column of channel `id` is `utc + id`. Returns the pairs that name no column.
fn spread_pairs<'a>(
    cells: &[&'a str],
    utc: usize,
    columns: usize,
    dense: &mut Vec<&'a str>,
) -> usize {
    dense.clear();
    dense.resize(columns, "");
    for (k, c) in cells.iter().take(utc + 1).enumerate() {
        dense[k] = c;
    }
    let mut bad = 0;
    for pair in cells.get(utc + 1..).unwrap_or(&[]).chunks(2) {
        match (pair[0].trim().parse::<usize>(), pair.get(1)) {
            (Ok(id), Some(v)) if id > 0 && utc + id < columns => dense[utc + id] = v,
            _ => bad += 1,
        }
    }
    bad
}
