//! NOAA NDBC buoy spectral files, read into a spectrum and turned into a [`WaveSet`].
//!
//! Two layouts (see ../shared/data/README.md for their quirks):
//! - realtime2 (`.data_spec`, `.swdir`, `.swr1`, ...): one header line, **newest record first**,
//!   each row `YY MM DD hh mm [Sep_Freq] value (freq) value (freq) ...`;
//! - historical (`41010w2019part.txt.gz`, `d`, `j`, ...): a header line naming the date columns
//!   then the frequencies, **oldest first**, one value per frequency; the oldest files have no
//!   minute column (`YYYY MM DD hh`). Historical r1/r2 are integers scaled ×100.
//!
//! Missing values are `999`, `999.0`, `999.00` (or `MM`). Spectral density is m²/Hz;
//! α1 is the direction waves come *from*, degrees clockwise from true north.
//!
//! What a file holds ([`NdbcKind`]) comes from its header (realtime: `spec_1`, `alpha1_1`,
//! `r1_1`, …) or its name (historical: the letter after the station id, `41010w2019`), so a
//! file given in another's place is refused. Values are checked against their kind's range,
//! dates are real dates, and a realtime record with fewer frequencies than the others (a
//! truncated last line) is refused with its line. Files are read up to [`MAX_NDBC_FILE_BYTES`].

use std::fmt;
use std::io::Read;
use std::path::Path;

use crate::spectrum::{
    Band, SpectralOptions, SpectralSea, sea_from_bands, spreading_from_r1,
    travel_direction_from_compass,
};

/// Why an NDBC file was refused: one sentence naming the source and the line.
#[derive(Debug, Clone, PartialEq)]
pub struct NdbcError {
    pub message: String,
}

impl fmt::Display for NdbcError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for NdbcError {}

impl NdbcError {
    /// A message whose text may hold input: made one safe line ([`input::one_line`]).
    fn new(message: impl AsRef<str>) -> NdbcError {
        NdbcError {
            message: input::one_line(message.as_ref()),
        }
    }
}

/// Largest NDBC file read (after decompression), bytes: a year of hourly historical records
/// is about 4 MB, 45 days of realtime records about 100 kB.
pub const MAX_NDBC_FILE_BYTES: u64 = 32 << 20;

/// What an NDBC spectral file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NdbcKind {
    /// Spectral density, m²/Hz (realtime `.data_spec`, historical `w`).
    Density,
    /// α1, mean direction waves come from, degrees (`.swdir`, `d`).
    Alpha1,
    /// α2, principal direction, degrees (`.swdir2`, `i`).
    Alpha2,
    /// r1, first circular moment (`.swr1`, `j`).
    R1,
    /// r2, second circular moment (`.swr2`, `k`).
    R2,
}

impl NdbcKind {
    /// The kind a realtime header names (`spec_1`, `alpha1_1`, `alpha2_1`, `r1_1`, `r2_1`).
    fn from_realtime_header(header: &str) -> Option<NdbcKind> {
        let first = header
            .split_whitespace()
            .find(|t| t.ends_with("_1") && !t.starts_with('('))?;
        Some(match first {
            "spec_1" => NdbcKind::Density,
            "alpha1_1" => NdbcKind::Alpha1,
            "alpha2_1" => NdbcKind::Alpha2,
            "r1_1" => NdbcKind::R1,
            "r2_1" => NdbcKind::R2,
            _ => return None,
        })
    }

    /// The kind a historical file's name says: the letter after the five-character station id
    /// (`41010w2019part.txt.gz`: w, d, i, j, k).
    fn from_historical_name(name: &str) -> Option<NdbcKind> {
        let bytes = name.as_bytes();
        let kind = match *bytes.get(5)? {
            b'w' => NdbcKind::Density,
            b'd' => NdbcKind::Alpha1,
            b'i' => NdbcKind::Alpha2,
            b'j' => NdbcKind::R1,
            b'k' => NdbcKind::R2,
            _ => return None,
        };
        let year_follows = bytes
            .get(6..10)
            .is_some_and(|y| y.iter().all(u8::is_ascii_digit));
        (bytes[..5].iter().all(u8::is_ascii_alphanumeric) && year_follows).then_some(kind)
    }

    /// Words for messages.
    pub fn describe(self) -> &'static str {
        match self {
            NdbcKind::Density => "spectral density",
            NdbcKind::Alpha1 => "mean direction (alpha1)",
            NdbcKind::Alpha2 => "principal direction (alpha2)",
            NdbcKind::R1 => "r1",
            NdbcKind::R2 => "r2",
        }
    }
}

/// Which layout a file had.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NdbcFormat {
    Realtime,
    Historical,
}

/// UTC time of a record (minute 0 where the file has no minute column).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct NdbcTime {
    pub year: u32,
    pub month: u32,
    pub day: u32,
    pub hour: u32,
    pub minute: u32,
}

impl fmt::Display for NdbcTime {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:04}-{:02}-{:02} {:02}:{:02}",
            self.year, self.month, self.day, self.hour, self.minute
        )
    }
}

/// One record: a value per frequency (`None` where missing).
#[derive(Debug, Clone, PartialEq)]
pub struct NdbcRow {
    pub time: NdbcTime,
    /// Hz.
    pub frequencies: Vec<f64>,
    pub values: Vec<Option<f64>>,
}

/// A whole file, records in file order.
#[derive(Debug, Clone, PartialEq)]
pub struct NdbcTable {
    pub format: NdbcFormat,
    /// What the header or the file name says it holds; `None` when neither says (a renamed
    /// historical file).
    pub kind: Option<NdbcKind>,
    /// The file, for messages.
    pub source: String,
    pub rows: Vec<NdbcRow>,
}

/// Days in `month` of `year` (Gregorian), 0 for a month outside 1–12.
fn days_in_month(year: u32, month: u32) -> u32 {
    match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if (year.is_multiple_of(4) && !year.is_multiple_of(100)) || year.is_multiple_of(400) => {
            29
        }
        2 => 28,
        _ => 0,
    }
}

impl NdbcTime {
    /// Why this is not a real UTC time (month 13, 31 June, hour 24, minute 60), if it is not.
    pub fn invalid_because(&self) -> Option<String> {
        if !(1..=12).contains(&self.month) {
            return Some(format!("month {} is not 1–12", self.month));
        }
        let days = days_in_month(self.year, self.month);
        if !(1..=days).contains(&self.day) {
            return Some(format!(
                "day {} is not 1–{days} ({:04}-{:02} has {days} days)",
                self.day, self.year, self.month
            ));
        }
        if self.hour > 23 || self.minute > 59 {
            return Some(format!(
                "{:02}:{:02} is not a time of day",
                self.hour, self.minute
            ));
        }
        None
    }
}

fn missing(v: f64) -> bool {
    (v - 999.0).abs() < 1e-9 || (v - 9999.0).abs() < 1e-9
}

fn parse_value(tok: &str) -> Option<Option<f64>> {
    if tok == "MM" {
        return Some(None);
    }
    let v: f64 = tok.parse().ok()?;
    if !v.is_finite() {
        return None;
    }
    Some(if missing(v) { None } else { Some(v) })
}

/// What a spectral file's header says about its rows.
struct Layout {
    /// A realtime file: "value (frequency)" pairs after the date; else one value per header
    /// frequency.
    realtime: bool,
    /// A realtime row starts with the separation frequency before its pairs.
    with_sep_freq: bool,
    /// Date columns ("#YY MM DD hh mm" or "YYYY MM DD hh"); a realtime header always has 5.
    date_cols: usize,
    /// A historical header's frequencies (Hz).
    header_freqs: Vec<f64>,
}

impl Layout {
    /// The layout of `header` (the first non-blank line), or why it is no spectral header.
    fn of(header: &str) -> Result<Layout, String> {
        let tokens: Vec<&str> = header.split_whitespace().collect();
        let realtime = header.contains('(') || header.contains('<');
        let with_sep_freq = header.contains("Sep_Freq");
        if realtime {
            return Ok(Layout {
                realtime,
                with_sep_freq,
                date_cols: 5,
                header_freqs: Vec::new(),
            });
        }
        // Date columns: header tokens that are not frequencies.
        let date_cols = tokens
            .iter()
            .take_while(|t| t.trim_start_matches('#').parse::<f64>().is_err())
            .count();
        let freqs: Result<Vec<f64>, _> = tokens[date_cols..].iter().map(|t| t.parse()).collect();
        match freqs {
            Ok(f) if (4..=5).contains(&date_cols) && !f.is_empty() => Ok(Layout {
                realtime,
                with_sep_freq,
                date_cols,
                header_freqs: f,
            }),
            _ => {
                Err("the header is neither a realtime nor a historical NDBC spectral header".into())
            }
        }
    }

    /// The time of a row from its date fields (two-digit years are 1950–2049).
    fn time(&self, tok: &[&str]) -> Result<NdbcTime, String> {
        let date_cols = self.date_cols;
        if tok.len() < date_cols {
            return Err(format!("expected {date_cols} date fields"));
        }
        let mut d = [0u32; 5];
        for (j, t) in tok[..date_cols].iter().enumerate() {
            d[j] = t.parse().map_err(|_| {
                format!("date field {} is {}, not a number", j + 1, input::quote(t))
            })?;
        }
        if d[0] < 100 {
            d[0] += if d[0] < 50 { 2000 } else { 1900 };
        }
        let time = NdbcTime {
            year: d[0],
            month: d[1],
            day: d[2],
            hour: d[3],
            minute: if date_cols == 5 { d[4] } else { 0 },
        };
        match time.invalid_because() {
            Some(why) => Err(format!("the date {time} is not a real date: {why}")),
            None => Ok(time),
        }
    }

    /// A row's frequencies (Hz, increasing) and values (`None` where missing), from the
    /// tokens after its date.
    fn spectrum(&self, rest: &[&str]) -> Result<(Vec<f64>, Vec<Option<f64>>), String> {
        let not_a_number = |t: &str| format!("{} is not a number", input::quote(t));
        let (frequencies, values) = if self.realtime {
            let rest = if self.with_sep_freq && !rest.is_empty() {
                &rest[1..]
            } else {
                rest
            };
            if rest.is_empty() || rest.len() % 2 != 0 {
                return Err("expected pairs of \"value (frequency)\" after the date".into());
            }
            let mut f = Vec::with_capacity(rest.len() / 2);
            let mut v = Vec::with_capacity(rest.len() / 2);
            for p in rest.chunks(2) {
                let val = parse_value(p[0]).ok_or_else(|| not_a_number(p[0]))?;
                let fr = p[1]
                    .strip_prefix('(')
                    .and_then(|s| s.strip_suffix(')'))
                    .and_then(|s| s.parse::<f64>().ok())
                    .filter(|f| f.is_finite() && *f > 0.0)
                    .ok_or_else(|| {
                        format!("{} is not a frequency in parentheses", input::quote(p[1]))
                    })?;
                f.push(fr);
                v.push(val);
            }
            (f, v)
        } else {
            if rest.len() != self.header_freqs.len() {
                return Err(format!(
                    "expected {} values (one per header frequency), found {}",
                    self.header_freqs.len(),
                    rest.len()
                ));
            }
            let v: Result<Vec<_>, _> = rest
                .iter()
                .map(|t| parse_value(t).ok_or_else(|| not_a_number(t)))
                .collect();
            (self.header_freqs.clone(), v?)
        };
        if frequencies.windows(2).any(|w| w[1] <= w[0]) {
            return Err("the frequencies are not increasing".into());
        }
        Ok((frequencies, values))
    }
}

impl NdbcTable {
    /// Parse the text of a realtime or historical spectral file. `source` names it in errors
    /// (and, for a historical file, says its kind by its name).
    pub fn parse(text: &str, source: &str) -> Result<NdbcTable, NdbcError> {
        let err = |line: usize, m: String| NdbcError::new(format!("{source}: line {line}: {m}"));
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((_, header)) = lines.next() else {
            return Err(NdbcError::new(format!(
                "{source}: the file is empty, not an NDBC spectral file"
            )));
        };
        // A byte-order mark is text, not part of the first column's name.
        let header = header.strip_prefix('\u{feff}').unwrap_or(header);
        let layout = Layout::of(header).map_err(|m| err(1, m))?;
        let mut rows: Vec<NdbcRow> = Vec::new();
        for (i, line) in lines {
            let n = i + 1;
            let tok: Vec<&str> = line.split_whitespace().collect();
            if tok.first().is_some_and(|t| t.starts_with('#')) {
                continue; // a second header line (units)
            }
            let time = layout.time(&tok).map_err(|m| err(n, m))?;
            let (frequencies, values) = layout
                .spectrum(&tok[layout.date_cols..])
                .map_err(|m| err(n, m))?;
            // Realtime rows carry their own frequencies; a station keeps one set, so a row with
            // fewer is a record cut short (a truncated download's last line), not a new set.
            if let Some(first) = rows.first().map(|r| r.frequencies.len())
                && frequencies.len() != first
            {
                return Err(err(
                    n,
                    format!(
                        "the record has {} frequencies but the first has {first}: a truncated or damaged record",
                        frequencies.len()
                    ),
                ));
            }
            rows.push(NdbcRow {
                time,
                frequencies,
                values,
            });
        }
        if rows.is_empty() {
            return Err(NdbcError::new(format!(
                "{source}: no records after the header"
            )));
        }
        let file_name = source.rsplit('/').next().unwrap_or(source);
        let realtime = layout.realtime;
        Ok(NdbcTable {
            format: if realtime {
                NdbcFormat::Realtime
            } else {
                NdbcFormat::Historical
            },
            kind: if realtime {
                NdbcKind::from_realtime_header(header)
            } else {
                NdbcKind::from_historical_name(file_name)
            },
            source: source.to_string(),
            rows,
        })
    }

    /// Read a file (gzip-compressed when its name ends in `.gz`), at most
    /// [`MAX_NDBC_FILE_BYTES`] compressed and decompressed.
    pub fn read(path: &Path) -> Result<NdbcTable, NdbcError> {
        let name = input::show_path(path);
        let gz = name.ends_with(".gz");
        let sniff = |prefix: &[u8]| {
            if gz {
                (!prefix.starts_with(&[0x1f, 0x8b]))
                    .then(|| "its name ends in .gz but it is not gzip data".to_string())
            } else {
                input::text_sniff(prefix)
            }
        };
        let bytes = input::read_capped(path, MAX_NDBC_FILE_BYTES, "an NDBC spectral file", sniff)
            .map_err(|e| NdbcError::new(e.0))?;
        let bytes = if gz {
            let mut out = Vec::new();
            flate2::read::GzDecoder::new(&bytes[..])
                .take(MAX_NDBC_FILE_BYTES + 1)
                .read_to_end(&mut out)
                .map_err(|e| NdbcError::new(format!("{name}: not a readable gzip file: {e}")))?;
            if out.len() as u64 > MAX_NDBC_FILE_BYTES {
                return Err(NdbcError::new(format!(
                    "{name}: decompresses to more than {} MiB, the most an NDBC file holds",
                    MAX_NDBC_FILE_BYTES >> 20
                )));
            }
            out
        } else {
            bytes
        };
        let text = String::from_utf8(bytes).map_err(|e| {
            NdbcError::new(format!(
                "{name}: byte {} is not UTF-8 text",
                e.utf8_error().valid_up_to()
            ))
        })?;
        NdbcTable::parse(&text, &name)
    }

    fn row_at(&self, time: NdbcTime) -> Option<&NdbcRow> {
        self.rows.iter().find(|r| r.time == time)
    }

    /// Refuses a table whose header or name says it holds something other than `want`.
    pub fn expect_kind(&self, want: NdbcKind) -> Result<(), NdbcError> {
        match self.kind {
            Some(k) if k != want => Err(NdbcError::new(format!(
                "{} holds {} values, not {} values: the files are given in each other's places",
                self.source,
                k.describe(),
                want.describe()
            ))),
            _ => Ok(()),
        }
    }
}

/// One record's directional spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct NdbcSpectrum {
    pub time: NdbcTime,
    /// Hz, increasing.
    pub frequencies: Vec<f64>,
    /// m²/Hz (0 where the file had a missing value).
    pub density: Vec<f64>,
    /// Mean direction waves come from, degrees from north, per frequency.
    pub alpha1_deg: Vec<Option<f64>>,
    /// First circular moment r1 ∈ [0, 1] per frequency.
    pub r1: Vec<Option<f64>>,
}

impl NdbcSpectrum {
    /// The record at `time` (or the first record of the density file) with the direction
    /// (α1) and r1 tables when given; their rows are matched by time and frequency. A table
    /// whose header or name says it holds something else is refused, and so is a value outside
    /// its kind's range (density below 0, α1 outside 0–360°, r1 outside 0–1).
    pub fn from_tables(
        density: &NdbcTable,
        alpha1: Option<&NdbcTable>,
        r1: Option<&NdbcTable>,
        time: Option<NdbcTime>,
    ) -> Result<NdbcSpectrum, NdbcError> {
        density.expect_kind(NdbcKind::Density)?;
        let row = match time {
            Some(t) => density
                .row_at(t)
                .ok_or_else(|| NdbcError::new(format!("{}: no record at {t}", density.source)))?,
            None => &density.rows[0],
        };
        let values = |table: &NdbcTable, kind: NdbcKind| -> Result<Vec<Option<f64>>, NdbcError> {
            table.expect_kind(kind)?;
            let other = table.row_at(row.time).ok_or_else(|| {
                NdbcError::new(format!("{}: no record at {}", table.source, row.time))
            })?;
            if other.frequencies.len() != row.frequencies.len()
                || other
                    .frequencies
                    .iter()
                    .zip(&row.frequencies)
                    .any(|(a, b)| (a - b).abs() > 1e-6)
            {
                return Err(NdbcError::new(format!(
                    "{}: the frequencies at {} differ from those of {}",
                    table.source, row.time, density.source
                )));
            }
            let (scale, range, unit) = match kind {
                NdbcKind::Density => (1.0, 0.0..=f64::MAX, " m²/Hz"),
                NdbcKind::Alpha1 | NdbcKind::Alpha2 => (1.0, 0.0..=360.0, "°"),
                // Historical r1 and r2 are integers scaled ×100.
                NdbcKind::R1 | NdbcKind::R2 if table.format == NdbcFormat::Historical => {
                    (0.01, 0.0..=1.0, "")
                }
                NdbcKind::R1 | NdbcKind::R2 => (1.0, 0.0..=1.0, ""),
            };
            let scaled: Vec<Option<f64>> =
                other.values.iter().map(|v| v.map(|x| x * scale)).collect();
            for (v, f) in scaled.iter().zip(&other.frequencies) {
                if let Some(v) = v
                    && !range.contains(v)
                {
                    return Err(NdbcError::new(format!(
                        "{}: the record at {} has {} {v}{unit} at {f} Hz, outside {}{unit} to {}{unit}",
                        table.source,
                        row.time,
                        kind.describe(),
                        range.start(),
                        if *range.end() == f64::MAX {
                            "∞".to_string()
                        } else {
                            range.end().to_string()
                        },
                    )));
                }
            }
            Ok(scaled)
        };
        let density_values = values(density, NdbcKind::Density)?;
        let optional = |t: Option<&NdbcTable>, kind| match t {
            Some(t) => values(t, kind),
            None => Ok(vec![None; row.frequencies.len()]),
        };
        Ok(NdbcSpectrum {
            time: row.time,
            frequencies: row.frequencies.clone(),
            density: density_values.iter().map(|v| v.unwrap_or(0.0)).collect(),
            alpha1_deg: optional(alpha1, NdbcKind::Alpha1)?,
            r1: optional(r1, NdbcKind::R1)?,
        })
    }

    /// The band [lo, hi] of each frequency: halfway to its neighbours (the end bands mirror).
    pub fn band_edges(&self) -> Vec<(f64, f64)> {
        let f = &self.frequencies;
        let n = f.len();
        (0..n)
            .map(|i| {
                let below = if i > 0 {
                    f[i] - f[i - 1]
                } else if n > 1 {
                    f[1] - f[0]
                } else {
                    0.01
                };
                let above = if i + 1 < n { f[i + 1] - f[i] } else { below };
                (f[i] - 0.5 * below, f[i] + 0.5 * above)
            })
            .collect()
    }

    /// m0 = ∫ S df, m².
    pub fn m0(&self) -> f64 {
        self.band_edges()
            .iter()
            .zip(&self.density)
            .map(|((lo, hi), s)| s * (hi - lo))
            .sum()
    }

    /// Significant wave height 4 sqrt(m0), metres.
    pub fn hs(&self) -> f64 {
        4.0 * self.m0().sqrt()
    }

    /// Bands with their measured direction and spreading. A frequency whose α1 or r1 is
    /// missing gets the energy-weighted mean of the others, or `default_from_deg` and
    /// s = `default_spreading` when the record has none.
    pub fn bands(&self, default_from_deg: f64, default_spreading: f64) -> Vec<Band> {
        let (mut sx, mut sz, mut r1w, mut wsum) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..self.density.len() {
            if let (Some(a), Some(r)) = (self.alpha1_deg[i], self.r1[i]) {
                let d = travel_direction_from_compass(a);
                let e = self.density[i];
                sx += e * d[0];
                sz += e * d[1];
                r1w += e * r;
                wsum += e;
            }
        }
        let (mean_dir, mean_s) = if wsum > 0.0 && sx.hypot(sz) > 0.0 {
            let l = sx.hypot(sz);
            ([sx / l, sz / l], spreading_from_r1(r1w / wsum))
        } else {
            (
                travel_direction_from_compass(default_from_deg),
                default_spreading,
            )
        };
        self.band_edges()
            .iter()
            .enumerate()
            .map(|(i, &(lo, hi))| Band {
                f_lo: lo,
                f_hi: hi,
                energy: self.density[i] * (hi - lo),
                direction: self.alpha1_deg[i]
                    .map(travel_direction_from_compass)
                    .unwrap_or(mean_dir),
                spreading: self.r1[i].map(spreading_from_r1).unwrap_or(mean_s),
            })
            .collect()
    }

    /// The sea of this record: one wave per frequency with energy.
    pub fn to_sea(&self, opts: &SpectralOptions) -> SpectralSea {
        sea_from_bands(&self.bands(0.0, 10.0), opts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn historical_header_without_minutes_and_bad_lines() {
        let text = "YYYY MM DD hh   .030   .040\n2000 01 01 00    .00    .12\n";
        let t = NdbcTable::parse(text, "x.txt").unwrap();
        assert_eq!(t.format, NdbcFormat::Historical);
        assert_eq!(t.rows[0].time.hour, 0);
        assert_eq!(t.rows[0].values, vec![Some(0.0), Some(0.12)]);
        let bad = "YYYY MM DD hh   .030   .040\n2000 01 01 00    .00\n";
        let e = NdbcTable::parse(bad, "x.txt").unwrap_err();
        assert_eq!(
            e.message,
            "x.txt: line 2: expected 2 values (one per header frequency), found 1"
        );
        let e = NdbcTable::parse("hello\n", "y").unwrap_err();
        assert!(e.message.starts_with("y: line 1:"), "{e}");
        let e = NdbcTable::parse(
            "#YY  MM DD hh mm alpha1_1 (freq_1)\n2020 06 08 03 50 1.0 (x)\n",
            "z",
        )
        .unwrap_err();
        assert!(
            e.message.contains("line 2") && e.message.contains("(x)"),
            "{e}"
        );
        let t = NdbcTable::parse(
            "#YY  MM DD hh mm a (freq_1)\n2020 06 08 03 50 999.0 (0.03)\n",
            "w",
        )
        .unwrap();
        assert_eq!(t.rows[0].values, vec![None]);
    }
}
