//! The plots' numbers (`ui::series`) and the race folder listing (`ui::open`), against
//! independent truth: the gap in seconds at a mark equals the difference of the two boats'
//! rounding times, computed by hand from the Valencia P02 GPX (see race's tests/events.rs).

use std::path::PathBuf;

use ui::series::{gap_near, gap_series, vmg_mps};
use ui::{list_races, open::RaceEntry};

fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/races")
        .join(rel)
}

/// VMG is the velocity's part along the wind's axis: closed form for a boat beating at 45°
/// to a north wind, running dead downwind, and reaching across it.
#[test]
fn vmg_is_the_speed_along_the_wind_axis() {
    let s = 5.0;
    let k = std::f64::consts::FRAC_1_SQRT_2;
    // North-east at 5 m/s ([east, south] = [5k, −5k]) against a wind from 0°.
    assert!((vmg_mps([s * k, -s * k], 0.0) - s * k).abs() < 1e-12);
    // Running south before a north wind: all of it.
    assert!((vmg_mps([0.0, s], 0.0) - s).abs() < 1e-12);
    // Reaching east across a north wind: none.
    assert!(vmg_mps([s, 0.0], 0.0).abs() < 1e-12);
    // A wind from 90° (east), the boat sailing east: all of it.
    assert!((vmg_mps([s, 0.0], 90.0) - s).abs() < 1e-12);
}

/// At the moment the leader rounds a mark, the trailing boat is exactly its rounding-time
/// difference behind: ESP29375 rounds B1, S1, B1, S1 at 562, 891, 1397, 1746 s and ESP30782
/// at 569, 900, 1445, 1803 s (closest approaches from the GPX), so 7, 9, 48 and 57 s. The
/// plot samples every ~4 s, so each is read at the sample nearest the rounding (±4 s of
/// race, the trailing boat's gap changes by < 2 s in that time), and compared within 3 s.
#[test]
fn the_gap_at_a_mark_is_the_rounding_time_difference() {
    let paths: Vec<PathBuf> = [
        "valencia/2025-06-21-ESP30782-P02.gpx",
        "valencia/2025-06-21-ESP29375-P02.gpx",
        "valencia/2025-06-21-ESP30782-P02-meta-data.json",
    ]
    .iter()
    .map(|r| data(r))
    .collect();
    let race = race::Race::load(&paths).unwrap();
    let lead = race.boat_index("ESP29375").unwrap();
    let trail = race.boat_index("ESP30782").unwrap();
    let gaps = gap_series(&race, lead, trail);
    assert!(!gaps.is_empty());
    for (t, want) in [(562.0, 7.0), (891.0, 9.0), (1397.0, 48.0), (1746.0, 57.0)] {
        let g = gap_near(&gaps, t, 5.0).unwrap();
        let s = g.seconds.unwrap();
        assert!(g.metres > 0.0, "{g:?}");
        assert!(
            (s - want).abs() <= 3.0,
            "at {t}: {s} s, want {want} s ({g:?})"
        );
    }
    // Seen from the other side the gap is the same, negative.
    let back = gap_series(&race, trail, lead);
    let g = gap_near(&back, 1397.0, 5.0).unwrap();
    assert!(
        g.metres < 0.0 && (g.seconds.unwrap() + 48.0).abs() <= 3.0,
        "{g:?}"
    );
}

/// A race without a course has no gap to compare (nothing to measure it along).
#[test]
fn no_course_no_gap() {
    let paths = vec![
        data("gdansk/2025-10-26-boat_three.gpx"),
        data("gdansk/2025-10-26-8_43.gpx"),
    ];
    let race = race::Race::load(&paths).unwrap();
    assert!(gap_series(&race, 0, 1).is_empty());
}

/// The phone's race folder: loose files are races of their own, each sub-folder one race of
/// its race files; hidden files, other extensions and empty folders are left out; a missing
/// folder is an empty list.
#[test]
fn the_race_folder_lists_files_and_folders_as_races() {
    let dir = std::env::temp_dir().join(format!("regatta-ui-races-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("valencia-p02")).unwrap();
    std::fs::create_dir_all(dir.join("empty")).unwrap();
    for f in [
        "fleet.json",
        "notes.pdf",
        ".hidden.gpx",
        "valencia-p02/a.gpx",
        "valencia-p02/b.GPX",
        "valencia-p02/marks.json",
        "valencia-p02/photo.jpg",
    ] {
        std::fs::write(dir.join(f), b"x").unwrap();
    }
    let got = list_races(&dir).unwrap();
    let want = vec![
        RaceEntry {
            name: "fleet.json".into(),
            files: vec![dir.join("fleet.json")],
        },
        RaceEntry {
            name: "valencia-p02".into(),
            files: vec![
                dir.join("valencia-p02/a.gpx"),
                dir.join("valencia-p02/b.GPX"),
                dir.join("valencia-p02/marks.json"),
            ],
        },
    ];
    assert_eq!(got, want);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(list_races(&dir).unwrap(), Vec::new());
}
