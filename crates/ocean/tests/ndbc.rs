//! NDBC spectral files (real buoy data, tests/data/ndbc) into spectra and seas.

use std::path::PathBuf;

use ocean::ndbc::{NdbcFormat, NdbcSpectrum, NdbcTable, NdbcTime};
use ocean::spectrum::{SpectralOptions, travel_direction_from_compass};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/ndbc")
        .join(name)
}

fn table(name: &str) -> NdbcTable {
    NdbcTable::read(&data(name)).unwrap()
}

#[test]
fn realtime_hs_matches_the_buoys_own_wvht_in_every_record() {
    let density = table("41010.data_spec");
    assert_eq!(density.format, NdbcFormat::Realtime);
    assert_eq!(density.rows.len(), 149);
    // Newest record first.
    let first = density.rows[0].time;
    assert_eq!(
        first,
        NdbcTime {
            year: 2020,
            month: 6,
            day: 8,
            hour: 3,
            minute: 50
        }
    );
    assert!(density.rows[148].time < first);
    assert_eq!(density.rows[0].frequencies.len(), 46);
    assert_eq!(density.rows[0].frequencies[0], 0.033);
    // The .spec summary (written 10 minutes earlier in each hour) states WVHT, rounded to
    // 0.1 m: 4 sqrt(m0) of our integration must agree with it.
    let spec = std::fs::read_to_string(data("41010.spec")).unwrap();
    let mut worst: f64 = 0.0;
    let mut sum = 0.0;
    let mut n = 0;
    for line in spec.lines().filter(|l| !l.starts_with('#')) {
        let tok: Vec<&str> = line.split_whitespace().collect();
        let d: Vec<u32> = tok[..4].iter().map(|t| t.parse().unwrap()).collect();
        let time = NdbcTime {
            year: d[0],
            month: d[1],
            day: d[2],
            hour: d[3],
            minute: 50,
        };
        let wvht: f64 = tok[5].parse().unwrap();
        let s = NdbcSpectrum::from_tables(&density, None, None, Some(time)).unwrap();
        let diff = (s.hs() - wvht).abs();
        worst = worst.max(diff);
        sum += diff;
        n += 1;
    }
    assert_eq!(n, 149);
    assert!(worst <= 0.12, "worst |Hs − WVHT| = {worst}");
    assert!(
        sum / n as f64 <= 0.04,
        "mean |Hs − WVHT| = {}",
        sum / n as f64
    );
}

#[test]
fn realtime_directions_become_a_sea() {
    let density = table("41010.data_spec");
    let alpha1 = table("41010.swdir");
    let r1 = table("41010.swr1");
    let s = NdbcSpectrum::from_tables(&density, Some(&alpha1), Some(&r1), None).unwrap();
    // The first record: missing (999) directions at the lowest frequencies, present above.
    assert_eq!(s.alpha1_deg[0], None);
    assert_eq!(s.alpha1_deg[6], Some(36.0));
    assert!(s.r1.iter().flatten().all(|r| (0.0..=1.0).contains(r)));
    let bands = s.bands(0.0, 10.0);
    assert_eq!(bands[6].direction, travel_direction_from_compass(36.0));
    let total: f64 = bands.iter().map(|b| b.energy).sum();
    assert!((total - s.m0()).abs() < 1e-12);
    let g = s.to_sea(&SpectralOptions::default());
    let nonzero = s.density.iter().filter(|d| **d > 0.0).count();
    assert_eq!(g.sea.waves.len(), nonzero);
    assert!((g.hs_spectrum - s.hs()).abs() < 1e-12);
    assert!(g.sea.total_steepness() <= 0.8 + 1e-12);
    assert!((g.hs_waves - g.hs_spectrum * g.amplitude_scale).abs() < 1e-9);
    // Each wave's frequency lies in its band: its wavelength g/(2π f²) is within the band's.
    for w in &g.sea.waves {
        let f = (9.81 / (std::f64::consts::TAU * w.wavelength)).sqrt();
        assert!(
            bands
                .iter()
                .any(|b| f >= b.f_lo - 1e-12 && f <= b.f_hi + 1e-12)
        );
    }
}

#[test]
fn historical_gz_files_with_scaled_r1() {
    let density = table("41010w2019part.txt.gz");
    assert_eq!(density.format, NdbcFormat::Historical);
    assert_eq!(density.rows.len(), 99);
    assert_eq!(
        density.rows[0].time,
        NdbcTime {
            year: 2019,
            month: 2,
            day: 6,
            hour: 0,
            minute: 40
        }
    );
    assert_eq!(density.rows[0].frequencies.len(), 47);
    assert_eq!(density.rows[0].values[15], Some(5.80));
    let d = table("41010d2019part.txt.gz");
    let j = table("41010j2019part.txt.gz");
    let t = NdbcTime {
        year: 2019,
        month: 2,
        day: 10,
        hour: 10,
        minute: 40,
    };
    let s = NdbcSpectrum::from_tables(&density, Some(&d), Some(&j), Some(t)).unwrap();
    // Historical r1 is written ×100 (integers 1–100): read as 0.01–1.
    assert!(s.r1.iter().flatten().all(|r| *r > 0.0 && *r <= 1.0));
    let first_j = NdbcSpectrum::from_tables(&density, None, Some(&j), None).unwrap();
    assert!((first_j.r1[0].unwrap() - 0.59).abs() < 1e-12);
    assert!(s.hs() > 0.5 && s.hs() < 10.0, "{}", s.hs());
}

#[test]
fn old_layout_without_minutes() {
    let t = table("44004w2000.txt");
    assert_eq!(t.rows.len(), 3);
    assert_eq!(
        t.rows[2].time,
        NdbcTime {
            year: 2000,
            month: 1,
            day: 1,
            hour: 2,
            minute: 0
        }
    );
    assert_eq!(t.rows[0].frequencies.len(), 38);
    assert_eq!(t.rows[0].values[5], Some(0.12));
}

#[test]
fn mismatched_or_missing_files_are_named() {
    let e = NdbcTable::read(&data("nope.data_spec")).unwrap_err();
    assert!(e.message.starts_with("could not read ") && e.message.contains("nope.data_spec"));
    let density = table("41010.data_spec");
    let hist_dir = table("41010d2019part.txt.gz");
    let e = NdbcSpectrum::from_tables(&density, Some(&hist_dir), None, None).unwrap_err();
    assert!(
        e.message
            .ends_with("41010d2019part.txt.gz: no record at 2020-06-08 03:50"),
        "{e}"
    );
    let t = NdbcTime {
        year: 1999,
        month: 1,
        day: 1,
        hour: 0,
        minute: 0,
    };
    let e = NdbcSpectrum::from_tables(&density, None, None, Some(t)).unwrap_err();
    assert!(e.message.contains("1999-01-01 00:00"), "{e}");
}
