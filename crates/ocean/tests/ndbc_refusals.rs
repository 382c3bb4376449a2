//! NDBC files that used to give silent nonsense (issue 15), made from the real buoy 41010
//! files of ../shared/data/waves: swapped files, values outside their range, impossible dates,
//! a truncated last record, and a device that never ends.

use std::path::{Path, PathBuf};

use ocean::ndbc::{NdbcKind, NdbcSpectrum, NdbcTable};

fn real(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/waves/ndbc-41010")
        .join(name)
}

fn table(name: &str) -> NdbcTable {
    NdbcTable::read(&real(name)).unwrap()
}

/// The real file `name` with `edit` applied to its text, parsed under the same name.
fn edited(name: &str, edit: impl Fn(&str) -> String) -> Result<NdbcTable, String> {
    let text = std::fs::read_to_string(real(name)).unwrap();
    NdbcTable::parse(&edit(&text), name).map_err(|e| e.message)
}

/// `41010.swdir` in the density's place gave Hs = 31.7 m (directions read as m²/Hz).
#[test]
fn swapped_files_are_refused_by_their_headers_and_names() {
    let density = table("41010.data_spec");
    let dir = table("41010.swdir");
    let r1 = table("41010.swr1");
    assert_eq!(
        (density.kind, dir.kind, r1.kind),
        (
            Some(NdbcKind::Density),
            Some(NdbcKind::Alpha1),
            Some(NdbcKind::R1)
        )
    );
    let e = NdbcSpectrum::from_tables(&dir, None, None, None).unwrap_err();
    assert!(
        e.message.ends_with(
            "41010.swdir holds mean direction (alpha1) values, not spectral density values: the files are given in each other's places"
        ),
        "{e}"
    );
    let e = NdbcSpectrum::from_tables(&density, Some(&r1), Some(&dir), None).unwrap_err();
    assert!(e.message.contains("41010.swr1 holds r1 values"), "{e}");
    // Historical files say their kind by name: `w` density, `d` α1, `j` r1.
    let w = table("41010w2019part.txt.gz");
    let j = table("41010j2019part.txt.gz");
    assert_eq!(
        (w.kind, j.kind),
        (Some(NdbcKind::Density), Some(NdbcKind::R1))
    );
    let e = NdbcSpectrum::from_tables(&j, None, None, None).unwrap_err();
    assert!(
        e.message.contains("41010j2019part.txt.gz holds r1 values"),
        "{e}"
    );
    // The right files still make the buoy's sea.
    let s = NdbcSpectrum::from_tables(&density, Some(&dir), Some(&r1), None).unwrap();
    assert!((s.hs() - 2.0).abs() < 1.0, "{}", s.hs());
}

#[test]
fn values_outside_their_range_are_refused() {
    let density = table("41010.data_spec");
    // The first record's r1 at 0.063 Hz is 0.37: make it 1.37.
    let r1 = edited("41010.swr1", |t| {
        t.replacen("0.37 (0.063)", "1.37 (0.063)", 1)
    })
    .unwrap();
    let e = NdbcSpectrum::from_tables(&density, None, Some(&r1), None).unwrap_err();
    assert_eq!(
        e.message,
        "41010.swr1: the record at 2020-06-08 03:50 has r1 1.37 at 0.063 Hz, outside 0 to 1"
    );
    // A negative density was clamped to 0 before, losing what the file said.
    let neg = edited("41010.data_spec", |t| {
        t.replacen("0.060 (0.063)", "-0.060 (0.063)", 1)
    })
    .unwrap();
    let e = NdbcSpectrum::from_tables(&neg, None, None, None).unwrap_err();
    assert!(
        e.message
            .contains("spectral density -0.06 m²/Hz at 0.063 Hz"),
        "{e}"
    );
    let dir = edited("41010.swdir", |t| {
        t.replacen("36.0 (0.063)", "361.0 (0.063)", 1)
    })
    .unwrap();
    let e = NdbcSpectrum::from_tables(&density, Some(&dir), None, None).unwrap_err();
    assert!(
        e.message
            .contains("(alpha1) 361° at 0.063 Hz, outside 0° to 360°"),
        "{e}"
    );
}

#[test]
fn impossible_dates_are_refused_with_their_line() {
    let e = edited("41010.data_spec", |t| {
        t.replacen("\n2020 06 08 03 50", "\n2020 13 08 03 50", 1)
    })
    .unwrap_err();
    assert_eq!(
        e,
        "41010.data_spec: line 2: the date 2020-13-08 03:50 is not a real date: month 13 is not 1–12"
    );
    let e = edited("41010.data_spec", |t| {
        t.replacen("\n2020 06 08 03 50", "\n2020 06 31 03 50", 1)
    })
    .unwrap_err();
    assert!(e.contains("day 31 is not 1–30"), "{e}");
    let e = edited("41010.data_spec", |t| {
        t.replacen("\n2020 06 08 03 50", "\n2020 06 08 24 50", 1)
    })
    .unwrap_err();
    assert!(e.contains("24:50 is not a time of day"), "{e}");
}

/// A download cut short ends inside its last (oldest) record: that record used to load with
/// fewer frequencies and so a lower Hs, silently.
#[test]
fn a_truncated_last_record_is_reported() {
    let text = std::fs::read_to_string(real("41010.data_spec")).unwrap();
    let lines = text.lines().count();
    // Cut the last line after its 20th "value (frequency)" pair.
    let cut = |t: &str| {
        let body = t.trim_end();
        let start = body.rfind('\n').unwrap() + 1;
        let last: Vec<&str> = body[start..].split_whitespace().collect();
        format!("{}{}", &body[..start], last[..6 + 40].join(" "))
    };
    let e = edited("41010.data_spec", cut).unwrap_err();
    assert_eq!(
        e,
        format!(
            "41010.data_spec: line {lines}: the record has 20 frequencies but the first has 46: a truncated or damaged record"
        )
    );
}

#[test]
fn endless_and_binary_files_are_refused_before_reading_them() {
    if Path::new("/dev/zero").exists() {
        let e = NdbcTable::read(Path::new("/dev/zero")).unwrap_err();
        assert_eq!(
            e.message,
            "/dev/zero is not an NDBC spectral file: byte 0 is NUL, so it is binary, not text"
        );
    }
    // A .gz name on text is refused by its first bytes, not after a failed inflate.
    let p = std::env::temp_dir().join(format!("ndbc-refusals-{}.txt.gz", std::process::id()));
    std::fs::write(&p, "#YY MM DD hh mm\n").unwrap();
    let e = NdbcTable::read(&p).unwrap_err();
    assert!(
        e.message
            .ends_with("its name ends in .gz but it is not gzip data"),
        "{e}"
    );
    let _ = std::fs::remove_file(p);
}

#[test]
fn control_characters_in_a_value_are_escaped() {
    let e = edited("41010.data_spec", |t| {
        t.replacen("0.060 (0.063)", "0.0\u{1b}[2J6 (0.063)", 1)
    })
    .unwrap_err();
    assert_eq!(
        e,
        "41010.data_spec: line 2: \"0.0\\u{1b}[2J6\" is not a number"
    );
}
