//! Calendar timestamps as the logs write them, parsed by hand (the CSV and NMEA importers
//! read millions of them; a format-description parser per row would dominate the import).

/// Days from 1970-01-01 to the civil date (proleptic Gregorian; H. Hinnant's algorithm).
pub(crate) fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m as i64 + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d as i64 - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// Seconds since [`super::EPOCH_UNIX`] of a UTC date and a time of day in seconds.
pub(crate) fn epoch_of(y: i64, m: u32, d: u32, day_seconds: f64) -> f64 {
    ((days_from_civil(y, m, d) * 86_400 - super::EPOCH_UNIX) as f64) + day_seconds
}

fn digits(b: &[u8]) -> Option<u32> {
    if b.is_empty() || !b.iter().all(u8::is_ascii_digit) {
        return None;
    }
    Some(b.iter().fold(0u32, |a, c| a * 10 + (c - b'0') as u32))
}

/// `HH:MM:SS[.f]` → seconds of the day.
pub(crate) fn time_of_day(b: &[u8]) -> Option<f64> {
    if b.len() < 8 || b[2] != b':' || b[5] != b':' {
        return None;
    }
    let (h, m) = (digits(&b[0..2])?, digits(&b[3..5])?);
    let s = digits(&b[6..8])?;
    if h > 23 || m > 59 || s > 60 {
        return None;
    }
    let mut frac = 0.0;
    if b.len() > 8 {
        if b[8] != b'.' && b[8] != b',' {
            return None;
        }
        let f = &b[9..];
        if f.is_empty() || f.len() > 9 || !f.iter().all(u8::is_ascii_digit) {
            return None;
        }
        frac = digits(f)? as f64 / 10f64.powi(f.len() as i32);
    }
    Some(h as f64 * 3600.0 + m as f64 * 60.0 + s as f64 + frac)
}

/// `YYYY-MM-DD[T ]HH:MM:SS[.f][Z|±HH[:]MM]` (no zone = UTC) → seconds since the epoch.
pub(crate) fn parse_datetime(s: &str) -> Option<f64> {
    let b = s.trim().as_bytes();
    if b.len() < 19 || b[4] != b'-' || b[7] != b'-' || !(b[10] == b' ' || b[10] == b'T') {
        return None;
    }
    let y = digits(&b[0..4])? as i64;
    let (mo, d) = (digits(&b[5..7])?, digits(&b[8..10])?);
    if !(1..=12).contains(&mo) || d == 0 || d > days_in_month(y, mo) {
        return None;
    }
    let rest = &b[11..];
    // The zone: Z, or a sign after the seconds.
    let (clock, offset_s) = match rest
        .iter()
        .rposition(|&c| c == b'+' || c == b'-' || c == b'Z')
    {
        Some(i) if i >= 8 => {
            let z = &rest[i..];
            let off = if z == b"Z" {
                0.0
            } else {
                let sign = if z[0] == b'-' { -1.0 } else { 1.0 };
                let hm: Vec<u8> = z[1..].iter().copied().filter(|&c| c != b':').collect();
                if hm.len() != 4 {
                    return None;
                }
                let (oh, om) = (digits(&hm[0..2])?, digits(&hm[2..4])?);
                if oh > 23 || om > 59 {
                    return None;
                }
                sign * (oh as f64 * 3600.0 + om as f64 * 60.0)
            };
            (&rest[..i], off)
        }
        _ => (rest, 0.0),
    };
    let day_s = time_of_day(clock)?;
    Some(epoch_of(y, mo, d, day_s) - offset_s)
}

pub(crate) fn days_in_month(y: i64, m: u32) -> u32 {
    match m {
        2 if (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn datetimes_with_zones_match_the_time_crate() {
        use time::format_description::well_known::Rfc3339;
        for (s, rfc) in [
            ("2025-01-19 03:06:00", "2025-01-19T03:06:00Z"),
            ("2023-06-10T14:05:22.100-0500", "2023-06-10T19:05:22.100Z"),
            ("2024-02-29T23:30:00+05:30", "2024-02-29T18:00:00Z"),
            ("2005-06-13T09:19:32Z", "2005-06-13T09:19:32Z"),
        ] {
            let t = time::OffsetDateTime::parse(rfc, &Rfc3339).unwrap();
            let want = super::super::epoch_seconds(t);
            assert!((parse_datetime(s).unwrap() - want).abs() < 1e-6, "{s}");
        }
        for bad in [
            "2025-13-01 00:00:00",
            "2025-02-30 00:00:00",
            "2025-01-01 25:00:00",
            "x",
        ] {
            assert!(parse_datetime(bad).is_none(), "{bad}");
        }
    }
}
