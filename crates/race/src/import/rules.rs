//! Rules every reader shares, so that a new format gets them by calling one function: lines
//! with any ending, the spike limit from a log's own speeds, and times that cannot belong to the
//! race (isolated far from the body of a track, or dated outside the years GPS has existed).
//! `parse` applies [`drop_time_outliers`] to every file after its reader; a reader calls
//! [`lines`] and [`spike_limit_mps`] itself, and counts every position it drops with
//! [`Source::drop_fixes`](super::Source::drop_fixes) so the silent-loss rule can weigh them.

use std::borrow::Cow;

use super::{DEFAULT_MAX_SPEED_KN, RawPoint, Source, Times, knots_to_mps};
use crate::error::{RaceError, RaceResult};

/// The fastest a spike limit derived from a log may be: 80 kn, 1.2 × the outright sailing
/// speed record (Sailrocket 2, 65.45 kn over 500 m, 2012). A logged speed over ground beyond it
/// is a broken cell, not a boat.
pub const MAX_SAILING_SPEED_KN: f64 = 80.0;

/// The quantile of a log's speeds over ground that bounds the speeds believed: those up to
/// twice the 99th percentile, so one garbage cell in a hundred cannot raise the limit while an
/// F50's brief top speed (51 kn in a log whose 99th percentile is ~46 kn) still sets it.
const SPIKE_LIMIT_QUANTILE: f64 = 0.99;

/// Times further than this from every other fix of their track, seconds, split it into runs;
/// a run holding few of the track's fixes is an outlier in time (a receiver's 1970 before its
/// first fix, a clock reset): one day, longer than any night between two racing days' sessions
/// is not, but a file then holds sessions large enough to be kept.
pub const TIME_OUTLIER_GAP_S: f64 = 86_400.0;

/// Absolute times must lie from 1980-01-06 (the GPS epoch: no receiver logs earlier) to
/// 2100-01-01, seconds since the importer's epoch (2020-01-01).
const FIRST_PLAUSIBLE_T: f64 = -1_261_872_000.0;
const LAST_PLAUSIBLE_T: f64 = 2_524_608_000.0;

/// Lines ending in CR, LF or CRLF (old Mac tools and some loggers end lines in CR alone), with
/// their 1-based numbers.
pub(crate) fn lines(text: &str) -> impl Iterator<Item = (u64, &str)> {
    text.split('\n')
        .flat_map(|l| l.strip_suffix('\r').unwrap_or(l).split('\r'))
        .zip(1u64..)
        .map(|(l, n)| (n, l))
}

/// The spike limit of a log from its own speeds over ground (m/s in `sog`, NaN where none):
/// 1.2 × the fastest of them within twice their 99th percentile, at least
/// [`DEFAULT_MAX_SPEED_KN`] and at most [`MAX_SAILING_SPEED_KN`]. The instrument knows what the
/// class can do; one garbage cell (1e300 kn) does not.
pub(crate) fn spike_limit_mps(points: &[RawPoint]) -> f64 {
    let mut v: Vec<f64> = points
        .iter()
        .map(|p| p.sog)
        .filter(|v| v.is_finite() && *v >= 0.0)
        .collect();
    let floor = knots_to_mps(DEFAULT_MAX_SPEED_KN);
    if v.is_empty() {
        return floor;
    }
    let k = ((v.len() - 1) as f64 * SPIKE_LIMIT_QUANTILE).floor() as usize;
    let (_, q, above) = v.select_nth_unstable_by(k, f64::total_cmp);
    let believed = 2.0 * *q;
    let top = above
        .iter()
        .copied()
        .filter(|s| *s <= believed)
        .fold(*q, f64::max);
    (1.2 * top).clamp(floor, knots_to_mps(MAX_SAILING_SPEED_KN))
}

/// Time intervals `[lo, hi]` of the runs of `ts` (sorted) that are outliers: runs split at gaps
/// over [`TIME_OUTLIER_GAP_S`], each holding at most max(2, 1 %) of the fixes and at most a
/// fifth of the largest run's.
fn outlier_runs(ts: &[f64]) -> Vec<[f64; 2]> {
    let n = ts.len();
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut a = 0;
    for i in 1..=n {
        if i == n || ts[i] - ts[i - 1] > TIME_OUTLIER_GAP_S {
            runs.push((a, i));
            a = i;
        }
    }
    let body = runs.iter().map(|r| r.1 - r.0).max().unwrap_or(0);
    let small = (n / 100).max(2);
    runs.iter()
        .filter(|r| {
            let k = r.1 - r.0;
            k <= small && 5 * k <= body
        })
        .map(|r| [ts[r.0], ts[r.1 - 1]])
        .collect()
}

/// Drop fixes whose times cannot belong to the race, counted as positions dropped: absolute
/// times before 1980-01-06 or from 2100 on, then isolated runs of a track far in time from its
/// body ([`outlier_runs`]). Channel samples of the file outside what is left of its tracks (by
/// more than [`TIME_OUTLIER_GAP_S`]) go too. A track of several sessions (GPX pauses) is left
/// to the session choice, which drops the sessions not raced.
pub(crate) fn drop_time_outliers(s: &mut Source) {
    let (mut undated, mut isolated) = (0usize, 0usize);
    let mut windows: Vec<(String, [f64; 2])> = Vec::new();
    for b in &mut s.boats {
        if s.sessions.iter().any(|(id, _)| *id == b.id) || b.points.is_empty() {
            continue;
        }
        let n = b.points.len();
        if s.times == Times::Absolute {
            b.points
                .retain(|p| (FIRST_PLAUSIBLE_T..LAST_PLAUSIBLE_T).contains(&p.t));
            undated += n - b.points.len();
        }
        let mut ts: Vec<f64> = b.points.iter().map(|p| p.t).collect();
        ts.sort_by(f64::total_cmp);
        let out = outlier_runs(&ts);
        if !out.is_empty() {
            let before = b.points.len();
            b.points
                .retain(|p| !out.iter().any(|r| (r[0]..=r[1]).contains(&p.t)));
            isolated += before - b.points.len();
        }
        let (lo, hi) = b
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), p| {
                (a.min(p.t), z.max(p.t))
            });
        if lo <= hi {
            windows.push((b.id.clone(), [lo, hi]));
        }
    }
    s.drop_fixes(
        "fixes dated before 1980-01-06 (the GPS epoch) or after 2099",
        undated,
    );
    s.drop_fixes(
        "fixes isolated in time, over a day from the rest of their track",
        isolated,
    );
    if undated + isolated == 0 || windows.is_empty() {
        return;
    }
    let all = windows
        .iter()
        .fold([f64::INFINITY, f64::NEG_INFINITY], |w, b| {
            [w[0].min(b.1[0]), w[1].max(b.1[1])]
        });
    let mut channel = 0usize;
    for ser in &mut s.series {
        let w = ser
            .boat
            .as_ref()
            .and_then(|id| windows.iter().find(|b| &b.0 == id).map(|b| b.1))
            .unwrap_or(all);
        let keep = |t: f64| t >= w[0] - TIME_OUTLIER_GAP_S && t <= w[1] + TIME_OUTLIER_GAP_S;
        let n = ser.t.len();
        let mut k = 0;
        for i in 0..n {
            if keep(ser.t[i]) {
                ser.t[k] = ser.t[i];
                ser.v[k] = ser.v[i];
                k += 1;
            }
        }
        ser.t.truncate(k);
        ser.v.truncate(k);
        channel += n - k;
    }
    s.drop_rule("channel samples at the times of dropped fixes", channel);
}

/// The bytes of a file as UTF-8: UTF-16 with a byte-order mark (what Windows tools write for
/// "Unicode" CSV and XML) decoded, UTF-8 as it is. UTF-16 without a mark (every other byte NUL
/// in ASCII text) is refused with how to convert it, rather than called binary.
pub(crate) fn utf8_of<'a>(file: &str, bytes: &'a [u8]) -> RaceResult<Cow<'a, [u8]>> {
    let (le, body) = match bytes {
        [0xFF, 0xFE, rest @ ..] => (true, rest),
        [0xFE, 0xFF, rest @ ..] => (false, rest),
        _ => {
            let head = &bytes[..bytes.len().min(512)];
            let at = |k: usize| head.iter().skip(k).step_by(2);
            // ASCII text as UTF-16: one byte of each pair NUL, the other never.
            let utf16 = |k: usize| at(k).all(|&b| b == 0) && at(1 - k).all(|&b| b != 0);
            if head.len() >= 8 && (utf16(0) || utf16(1)) {
                return Err(RaceError::in_file(
                    file,
                    "is UTF-16 text without a byte-order mark; save it as UTF-8 (or UTF-16 with a BOM), e.g. iconv -f UTF-16LE -t UTF-8",
                ));
            }
            return Ok(Cow::Borrowed(bytes));
        }
    };
    let units = body.chunks(2).map(|c| match (c, le) {
        ([a, b], true) => u16::from_le_bytes([*a, *b]),
        ([a, b], false) => u16::from_be_bytes([*a, *b]),
        _ => 0xFFFF,
    });
    let mut out = String::with_capacity(body.len() / 2);
    let mut line = 1u64;
    for c in char::decode_utf16(units) {
        match c {
            Ok(c) => {
                line += u64::from(c == '\n');
                out.push(c);
            }
            Err(_) => {
                return Err(RaceError::at_line(
                    file,
                    line,
                    "the UTF-16 text has a broken character (an unpaired surrogate)",
                ));
            }
        }
    }
    if body.len() % 2 == 1 {
        return Err(RaceError::in_file(
            file,
            "the UTF-16 text ends in half a character (an odd number of bytes): is it truncated?",
        ));
    }
    Ok(Cow::Owned(out.into_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_end_in_cr_lf_or_crlf() {
        let got: Vec<(u64, &str)> = lines("a\rb\r\nc\nd").collect();
        assert_eq!(got, vec![(1, "a"), (2, "b"), (3, "c"), (4, "d")]);
    }

    #[test]
    fn a_lone_far_time_is_an_outlier_and_a_second_session_is_not() {
        let mut ts: Vec<f64> = (0..600).map(f64::from).collect();
        ts.push(1e8);
        assert_eq!(outlier_runs(&ts), vec![[1e8, 1e8]]);
        // Two racing days of 300 fixes each: both kept.
        let two: Vec<f64> = (0..600)
            .map(|i| f64::from(i) + if i >= 300 { 3.0 * 86_400.0 } else { 0.0 })
            .collect();
        assert!(outlier_runs(&two).is_empty());
    }
}
