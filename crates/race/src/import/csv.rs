//! Boat logs and instrument or tracker exports as CSV: SailGP boat logs, Vakaros Atlas,
//! Velocitek, and any log with a time, a latitude and a longitude column. Columns are found by
//! name (case-insensitive, synonyms below), units from the name (`_kts`, `km_h`, `m_s`, `mph`;
//! knots otherwise). Times: `YYYY-MM-DD[T ]HH:MM:SS[.f]` with an optional zone (`Z`, `-0500`,
//! `+05:30`; none = UTC), Unix seconds or milliseconds (values near 1e9 or 1e12), else plain
//! seconds since the race start. Blank rows and rows without a position are skipped and
//! counted; a `boat` column that names several boats splits the file into one boat per id.
//! A time column's name may state its unit (`time_ms`, `t_us`, `elapsed_min`; seconds
//! otherwise), like the speed columns. The spike limit is 1.2 × the log's own top speed over
//! ground within twice its 99th percentile (the instrument knows what the class can do; one
//! garbage cell does not), from 20 kn to 80 kn.

use super::timefmt::parse_datetime;
use super::{Coords, RawBoat, RawPoint, Series, Source, Times, q};
use crate::Wind;
use crate::error::{RaceError, RaceResult};
use crate::text::plain;
use crate::track::Logged;

/// A column and the factor from its unit to SI (m/s for speeds, 1 for degrees).
type Col = Option<(usize, f64)>;

struct Columns {
    time: usize,
    /// Seconds per unit of a plain-number time column, from its name (`time_ms` → 0.001).
    time_unit_s: f64,
    lat: usize,
    lon: usize,
    sog: Col,
    heading: Col,
    heel: Col,
    trim: Col,
    bsp: Col,
    tws: Col,
    twd: Col,
    boat: Option<usize>,
}

/// Metres per second per unit named in a column name.
fn unit_of(name: &str) -> f64 {
    if name.contains("km_h")
        || name.contains("kmh")
        || name.contains("km/h")
        || name.contains("kph")
    {
        1.0 / 3.6
    } else if name.contains("m_s") || name.contains("mps") || name.contains("m/s") {
        1.0
    } else if name.contains("mph") {
        0.447_04
    } else {
        super::knots_to_mps(1.0)
    }
}

/// Seconds per unit named at the end of a time column's name: `_ms`, `_millis`, `_msec` →
/// 0.001; `_us`, `_usec`, `_micros` → 1e-6; `_ns`, `_nanos` → 1e-9; `_min` → 60; `_h`, `_hours`
/// → 3600; else seconds.
fn time_unit_of(name: &str) -> f64 {
    let last = name.rsplit('_').next().unwrap_or("");
    if name == last {
        return 1.0;
    }
    match last {
        "ms" | "millis" | "msec" | "milliseconds" => 1e-3,
        "us" | "usec" | "micros" | "microseconds" => 1e-6,
        "ns" | "nanos" | "nanoseconds" => 1e-9,
        "min" | "mins" | "minutes" => 60.0,
        "h" | "hr" | "hours" => 3600.0,
        _ => 1.0,
    }
}

/// A header name reduced to letters and digits joined by `_`: "Speed (kts)" → "speed_kts".
fn norm(h: &str) -> String {
    let mut out = String::with_capacity(h.len());
    for c in h.trim().chars() {
        if c.is_ascii_alphanumeric() || c == '/' {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') && !out.is_empty() {
            out.push('_');
        }
    }
    out.trim_end_matches('_').to_string()
}

fn detect(file: &str, header: &csv::StringRecord) -> RaceResult<Columns> {
    let names: Vec<String> = header.iter().map(norm).collect();
    let find = |pred: &dyn Fn(&str) -> bool| names.iter().position(|n| pred(n));
    let starts = |ps: &'static [&'static str]| {
        move |n: &str| {
            ps.iter()
                .any(|p| n == *p || n.starts_with(&format!("{p}_")))
        }
    };
    let need = |i: Option<usize>, what: &str| {
        i.ok_or_else(|| RaceError::at_line(file, 1, format!("the header has no {what} column")))
    };
    let time = find(&starts(&[
        "datetime",
        "date/time",
        "date_time",
        "timestamp",
        "time",
        "utc",
        "time_utc",
        "t",
        "gps_time",
        "iso_time",
    ]));
    let speed = |i: Option<usize>| i.map(|i| (i, unit_of(&names[i])));
    let deg = |i: Option<usize>| i.map(|i| (i, 1.0));
    let sog = find(&|n| n.contains("sog") && !n.contains("vmg"))
        .or_else(|| find(&starts(&["speed", "speed_over_ground"])));
    let time = need(time, "time (DATETIME, time, timestamp or utc)")?;
    Ok(Columns {
        time,
        time_unit_s: time_unit_of(&names[time]),
        lat: need(
            find(&starts(&["lat", "latitude", "latitude_gps"])),
            "latitude (LAT…)",
        )?,
        lon: need(
            find(&starts(&[
                "lon",
                "lng",
                "long",
                "longitude",
                "longitude_gps",
            ])),
            "longitude (LON…)",
        )?,
        sog: speed(sog),
        heading: deg(find(&starts(&[
            "heading",
            "hdg",
            "hdg_true",
            "heading_true",
            "hdt",
        ]))),
        heel: deg(find(&starts(&["heel", "roll"]))),
        trim: deg(find(&starts(&["trim", "pitch"]))),
        bsp: speed(find(&starts(&["bsp", "boat_speed", "boatspeed", "stw"]))),
        tws: speed(find(&|n| n.starts_with("tws"))),
        twd: deg(find(&|n| n.starts_with("twd"))),
        boat: find(&|n| n == "boat" || n == "boat_id" || n == "boat_name" || n == "sail_number"),
    })
}

/// A time cell: (seconds, kind). Calendar times and Unix times are absolute. `unit_s`: the
/// seconds per unit of a plain number, as the column's name says (1 when it says nothing).
fn parse_time(cell: &str, unit_s: f64) -> Option<(f64, Times)> {
    if let Some(t) = parse_datetime(cell) {
        return Some((t, Times::Absolute));
    }
    let v: f64 = cell.trim().parse().ok().filter(|v: &f64| v.is_finite())?;
    let unix = |s: f64| s - super::EPOCH_UNIX as f64;
    let secs = v * unit_s;
    Some(if (1e9..4e9).contains(&secs) {
        (unix(secs), Times::Absolute)
    } else if unit_s == 1.0 && (1e12..4e12).contains(&v) {
        (unix(v / 1000.0), Times::Absolute)
    } else {
        (secs, Times::Relative)
    })
}

/// One boat's rows while reading.
struct Track {
    id: String,
    points: Vec<RawPoint>,
    series: Vec<Series>,
}

/// The instrument channels kept as series, in the order their values are read.
type Channels = [(&'static str, Col); 4];

/// One data row's values: NaN where the log has no such column or the cell is empty.
struct Row<'r> {
    t: f64,
    lat: f64,
    lon: f64,
    sog: f64,
    heading: f64,
    heel: f64,
    tws: f64,
    twd: f64,
    /// The channels' values, in [`Channels`]' order.
    channel_values: [f64; 4],
    /// The boat column's id; empty when the log has none or the cell is blank.
    boat: &'r str,
}

/// The mean wind over the rows that give both TWS and TWD (directions averaged as vectors).
#[derive(Default)]
struct WindMean {
    east: f64,
    north: f64,
    tws_sum: f64,
    rows: usize,
}

impl WindMean {
    fn add(&mut self, tws: f64, twd: f64) {
        if tws.is_finite() && twd.is_finite() {
            self.east += twd.to_radians().sin();
            self.north += twd.to_radians().cos();
            self.tws_sum += tws;
            self.rows += 1;
        }
    }

    fn mean(&self) -> Option<Wind> {
        (self.rows > 0).then(|| Wind {
            from_deg: self.east.atan2(self.north).to_degrees().rem_euclid(360.0),
            speed_mps: self.tws_sum / self.rows as f64,
        })
    }
}

pub(crate) fn parse(file: &str, text: &str) -> RaceResult<Source> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = rdr
        .headers()
        .map_err(|e| RaceError::at_line(file, 1, format!("unreadable header ({e})")))?
        .clone();
    let cols = detect(file, &header)?;
    let names: Vec<&str> = header.iter().map(str::trim).collect();
    let mut tracks: Vec<Track> = Vec::new();
    // Boat id → index in `tracks`: a fleet file of 40,000 boats looked up by scanning was
    // quadratic in the boat count.
    let mut track_of: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    let mut times: Option<Times> = None;
    let mut wind = WindMean::default();
    let (mut rows, mut blank, mut no_fix) = (0usize, 0usize, 0usize);
    let mut rec = csv::StringRecord::new();
    let file_id = super::boat_id_from_file(file);
    let channels: Channels = [
        ("bsp", cols.bsp),
        ("tws", cols.tws),
        ("twd", cols.twd),
        ("trim", cols.trim),
    ];
    while next_record(file, &mut rdr, &mut rec)? {
        rows += 1;
        let line = rec.position().map_or(0, |p| p.line());
        if rec.iter().all(|c| c.trim().is_empty()) {
            blank += 1;
            continue;
        }
        let Some(row) = read_row(file, line, &rec, &names, &cols, &channels, &mut times)? else {
            no_fix += 1;
            continue;
        };
        wind.add(row.tws, row.twd);
        let id = if row.boat.is_empty() {
            &file_id
        } else {
            row.boat
        };
        let k = match track_of.get(id) {
            Some(&k) => k,
            None => {
                track_of.insert(id.to_string(), tracks.len());
                tracks.push(Track::new(id, &channels));
                tracks.len() - 1
            }
        };
        tracks[k].push(&row, &channels);
    }
    if tracks.is_empty() {
        return Err(RaceError::in_file(
            file,
            "the log has a header but no rows with a position: a boat needs points",
        ));
    }
    Ok(into_source(
        file,
        &cols,
        tracks,
        times,
        wind.mean(),
        [rows, blank, no_fix],
    ))
}

/// The next record into `rec`: false at the end, or the reader's error naming the line.
fn next_record(
    file: &str,
    rdr: &mut csv::Reader<&[u8]>,
    rec: &mut csv::StringRecord,
) -> RaceResult<bool> {
    rdr.read_record(rec).map_err(|e| {
        let line = e.position().map_or(0, |p| p.line());
        let what = match e.kind() {
            csv::ErrorKind::Utf8 { .. } => "text that is not UTF-8".to_string(),
            _ => format!("unreadable row ({})", crate::text::escape(&e.to_string())),
        };
        RaceError::at_line(file, line, what)
    })
}

/// A non-blank row's values; `None` for a row without a position; an error naming the line
/// for a short or long row, a bad number, time or position, or a time of the other kind than
/// the rows before (`times`: the kind the first row set).
fn read_row<'r>(
    file: &str,
    line: u64,
    rec: &'r csv::StringRecord,
    names: &[&str],
    cols: &Columns,
    channels: &Channels,
    times: &mut Option<Times>,
) -> RaceResult<Option<Row<'r>>> {
    if rec.len() != names.len() {
        return Err(RaceError::at_line(
            file,
            line,
            format!("{} cells where the header has {}", rec.len(), names.len()),
        ));
    }
    let cell = |i: usize| rec.get(i).unwrap_or("").trim();
    let num = |i: usize| number_cell(file, line, names[i], cell(i));
    let opt = |c: Col| -> RaceResult<f64> {
        match c {
            Some((i, u)) => Ok(num(i)? * u),
            None => Ok(f64::NAN),
        }
    };
    let (lat, lon) = (num(cols.lat)?, num(cols.lon)?);
    if lat.is_nan() && cell(cols.lat).is_empty() || lon.is_nan() && cell(cols.lon).is_empty() {
        return Ok(None);
    }
    let Some((t, kind)) = parse_time(cell(cols.time), cols.time_unit_s) else {
        return Err(RaceError::at_line(
            file,
            line,
            format!(
                "{} is {}, not a time (YYYY-MM-DD HH:MM:SS with an optional zone, RFC 3339 or seconds)",
                plain(names[cols.time]),
                q(cell(cols.time))
            ),
        ));
    };
    match times {
        None => *times = Some(kind),
        Some(k) if *k != kind => {
            return Err(RaceError::at_line(
                file,
                line,
                "mixes calendar times and plain seconds in the time column",
            ));
        }
        _ => {}
    }
    if let Some(msg) = super::geo_problem(lat, lon) {
        return Err(RaceError::at_line(file, line, msg));
    }
    let (sog, heading, heel) = (opt(cols.sog)?, opt(cols.heading)?, opt(cols.heel)?);
    let (tws, twd) = (opt(cols.tws)?, opt(cols.twd)?);
    let mut channel_values = [f64::NAN; 4];
    for (v, (_, c)) in channel_values.iter_mut().zip(channels) {
        *v = opt(*c)?;
    }
    Ok(Some(Row {
        t,
        lat,
        lon,
        sog,
        heading,
        heel,
        tws,
        twd,
        channel_values,
        boat: cols.boat.map(cell).unwrap_or(""),
    }))
}

impl Track {
    /// A row's fix, and its channels' values where the row has them.
    fn push(&mut self, row: &Row, channels: &Channels) {
        let present = row
            .channel_values
            .iter()
            .zip(channels)
            .filter(|(_, (_, c))| c.is_some());
        for (ser, (&v, _)) in self.series.iter_mut().zip(present) {
            if v.is_finite() {
                ser.t.push(row.t);
                ser.v.push(v as f32);
            }
        }
        self.points.push(RawPoint {
            t: row.t,
            c: [row.lat, row.lon],
            logged: Logged {
                heading: row.heading as f32,
                heel: row.heel as f32,
            },
            sog: row.sog,
        });
    }

    /// A boat's track with one empty series per instrument channel the log has.
    fn new(id: &str, channels: &[(&str, Col)]) -> Track {
        Track {
            id: id.to_string(),
            points: Vec::new(),
            series: channels
                .iter()
                .filter(|(_, c)| c.is_some())
                .map(|(name, _)| Series {
                    boat: None,
                    channel: name.to_string(),
                    unit: if matches!(*name, "bsp" | "tws") {
                        "m/s"
                    } else {
                        "deg"
                    }
                    .into(),
                    t: Vec::new(),
                    v: Vec::new(),
                })
                .collect(),
        }
    }
}

/// The file's source from its tracks: the report's counts (`[rows, blank, without a
/// position]`), channels and date source, the mean wind, and the boats with their series.
fn into_source(
    file: &str,
    cols: &Columns,
    tracks: Vec<Track>,
    times: Option<Times>,
    wind: Option<Wind>,
    [rows, blank, no_fix]: [usize; 3],
) -> Source {
    let mut s = Source::new(file, Coords::Geo, times.unwrap_or(Times::Absolute));
    s.report.records_read = rows;
    s.drop_rule("blank rows", blank);
    s.drop_rule("rows without a position", no_fix);
    s.report.date_source = match times {
        Some(Times::Absolute) => "the time column (calendar or Unix times)".into(),
        _ => "none: the time column is seconds since the race start".into(),
    };
    let found = [
        ("sog", cols.sog.is_some()),
        ("heading", cols.heading.is_some()),
        ("heel", cols.heel.is_some()),
        ("trim", cols.trim.is_some()),
        ("bsp", cols.bsp.is_some()),
        ("tws", cols.tws.is_some()),
        ("twd", cols.twd.is_some()),
    ];
    s.report.channels = found
        .iter()
        .filter(|f| f.1)
        .map(|f| f.0.to_string())
        .collect();
    s.wind = wind;
    if tracks.len() > 1 {
        s.warnings.push(format!(
            "{file}: the boat column names {} boats; the rows were split by boat",
            tracks.len()
        ));
    }
    for tr in tracks {
        for mut ser in tr.series {
            ser.boat = Some(tr.id.clone());
            s.series.push(ser);
        }
        s.boats.push(RawBoat {
            name: tr.id.clone(),
            id: tr.id,
            color: None,
            max_speed_mps: super::spike_limit_mps(&tr.points),
            points: tr.points,
        });
    }
    s
}

/// A numeric cell of a log (CSV export or Expedition): NaN when empty (a sparse row), else the
/// number, or one sentence naming the file, line and column.
pub(super) fn number_cell(file: &str, line: u64, column: &str, cell: &str) -> RaceResult<f64> {
    let c = cell.trim();
    if c.is_empty() {
        return Ok(f64::NAN);
    }
    c.parse::<f64>().map_err(|_| {
        RaceError::at_line(
            file,
            line,
            format!("{} is {}, not a number", plain(column), q(c)),
        )
    })
}
