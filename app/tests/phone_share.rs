//! Races opened the Android way (issue 26): a race file shared with the phone app ("Share": an
//! `ACTION_SEND` intent with a `content://` URI) is read through the ContentResolver of the
//! host's scripted JNI, loaded, fitted to the table and kept in the races folder; the other
//! boat of the same race joins it, asking nothing; a file of another place and day opens as its
//! own race; a broken file is one sentence on the banner and the race shown stays. The truth is
//! the importer reading the same files from disk (`race::Race::load`) and the table fit computed
//! here from those races' own fixes and marks.

use std::path::{Path, PathBuf};
use std::process::Command;

use regatta::core::app::Opened;
use regatta::core::feed::CameraFeed;
use regatta::phone_sim::PhoneSim;
use regatta::sim_phone::device::Device;
use serde_json::Value;

/// The A54's layout (360 × 800 dp) on a quarter of its pixels: quick on lavapipe.
const SIZE: [u32; 2] = [180, 400];

fn out_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("phone_share")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn launch() -> PhoneSim {
    let feed = CameraFeed::synth(ar::SynthConfig {
        frames: 1,
        width: 320,
        height: 240,
        supersample: 1,
        ..ar::SynthConfig::default()
    });
    PhoneSim::launch(feed, SIZE, Device::A54.pixels_per_point(SIZE), None)
}

/// A Valencia 2025-06-21 race P01 boat's GPX (MIT, in the repository).
fn valencia(boat: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/races/valencia")
        .join(format!("2025-06-21-{boat}-P01.gpx"))
}

/// A track of another place and day: Gdańsk, 2025-10-26 (../shared/data; `None` without it).
fn gdansk() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/races/gdansk/rerata_26_oct.gpx");
    p.is_file().then_some(p)
}

fn boats(race: &race::Race) -> Vec<String> {
    race.boats.iter().map(|b| b.name.clone()).collect()
}

/// The course-to-table scale that fits `truth` (its every fix and mark) into 90 % of the room
/// on the tapped table along the side that binds, turned a quarter where that draws it larger.
fn fitted_scale(truth: &race::Race, room: glam::DVec2) -> f64 {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    let points = truth
        .boats
        .iter()
        .flat_map(|b| b.fixes().iter().map(|f| f.pos()))
        .chain(truth.buoys());
    for [x, z] in points {
        b = [b[0].min(x), b[1].min(z), b[2].max(x), b[3].max(z)];
    }
    let (w, h) = (b[2] - b[0], b[3] - b[1]);
    let race_per_table = (w / room.x)
        .max(h / room.y)
        .min((w / room.y).max(h / room.x));
    (1.0 - regatta::core::table::RACE_MARGIN) / race_per_table
}

fn assert_fitted(sim: &PhoneSim, truth: &race::Race) {
    let course = sim.app.course().expect("the course stands on the table");
    let want = fitted_scale(truth, sim.app.table_room().extent);
    assert!(
        (course.course_to_table / want - 1.0).abs() < 1e-9,
        "scale {} vs {want}",
        course.course_to_table
    );
}

#[test]
fn shared_files_open_a_race_join_it_or_stand_alone_and_are_kept() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let races = out_dir("share").join("races");
    let mut sim = launch();
    sim.app.set_races_dir(Some(races.clone()));
    sim.tap([0.5, 0.6]);
    assert!(sim.app.course().is_some(), "the course placed first");

    // One boat of Valencia P01: its own race, read through the ContentResolver, fitted, kept.
    let a = valencia("ESP29375");
    assert_eq!(sim.open(&a), Ok(Opened::Race));
    let truth = race::Race::load(std::slice::from_ref(&a)).unwrap();
    assert_eq!(boats(sim.app.race()), boats(&truth));
    assert_fitted(&sim, &truth);
    let calls: Vec<&str> = sim.intents().calls().iter().map(|c| c.method).collect();
    assert!(
        calls.contains(&"getIntent") && calls.contains(&"getContentResolver().openInputStream"),
        "{calls:?}"
    );
    let kept = races.join("2025-06-21-ESP29375-P01/2025-06-21-ESP29375-P01.gpx");
    assert_eq!(std::fs::read(&kept).unwrap(), std::fs::read(&a).unwrap());
    assert_eq!(sim.app.listed_races(), ["2025-06-21-ESP29375-P01"]);
    assert_eq!(
        sim.app.status().banner.as_deref(),
        Some("Opened \"2025-06-21-ESP29375-P01.gpx\".")
    );

    // The other boat of the same race, shared later: each share starts a new Activity on
    // Android, so a fresh app (showing the embedded race) with the same races folder. It joins
    // the race: one race, two boats, as the importer reads both files together.
    drop(sim);
    let mut sim = launch();
    sim.app.set_races_dir(Some(races.clone()));
    sim.tap([0.5, 0.6]);
    let b = valencia("ESP30782");
    assert_eq!(sim.open(&b), Ok(Opened::BoatsAdded(1)));
    let both = race::Race::load(&[a.clone(), b.clone()]).unwrap();
    assert_eq!(both.boats.len(), 2);
    assert_eq!(boats(sim.app.race()), boats(&both));
    assert_eq!(sim.app.race().time_span(), both.time_span());
    assert_fitted(&sim, &both);
    assert_eq!(
        sim.app.listed_races(),
        ["2025-06-21-ESP29375-P01"],
        "still one race in the folder"
    );
    let folder = races.join("2025-06-21-ESP29375-P01");
    assert_eq!(
        std::fs::read(folder.join("2025-06-21-ESP30782-P01.gpx")).unwrap(),
        std::fs::read(&b).unwrap()
    );
    // The same file shared again adds nothing and keeps no copy.
    assert_eq!(sim.open(&b), Ok(Opened::BoatsAdded(0)));
    assert_eq!(std::fs::read_dir(&folder).unwrap().count(), 2);
    assert_eq!(
        sim.app.status().banner.as_deref(),
        Some("\"2025-06-21-ESP30782-P01.gpx\" is in this race already.")
    );

    // A track of another place and day: its own race, its own folder.
    let Some(g) = gdansk() else {
        render::gpu::record_skip("no ../shared/data/races/gdansk for the race of another place");
        return;
    };
    assert_eq!(sim.open(&g), Ok(Opened::Race));
    let gdansk_race = race::Race::load(std::slice::from_ref(&g)).unwrap();
    assert_eq!(boats(sim.app.race()), boats(&gdansk_race));
    assert_fitted(&sim, &gdansk_race);
    assert_eq!(
        sim.app.listed_races(),
        ["2025-06-21-ESP29375-P01", "rerata_26_oct"]
    );

    // The same place 10 minutes after P01 ended (race P02, 12:01–12:41): another race too.
    let p02 = g
        .parent()
        .unwrap()
        .join("../valencia/2025-06-21-ESP29375-P02.gpx");
    assert_eq!(sim.open(&p02), Ok(Opened::Race));
    assert_eq!(sim.app.listed_races().len(), 3);
    assert_eq!(sim.app.race().boats.len(), 1);

    // A broken file: one sentence naming it on the banner and in the Races panel; the race
    // stays; nothing is kept.
    let shown = boats(sim.app.race());
    let broken = out_dir("share-broken").join("broken.gpx");
    std::fs::write(&broken, "<gpx><trk><trkseg><trkpt lat=\"x").unwrap();
    let e = sim.open(&broken).unwrap_err();
    assert!(e.contains("broken.gpx") && !e.contains('\n'), "{e}");
    assert_eq!(sim.app.status().banner.as_deref(), Some(e.as_str()));
    assert_eq!(sim.app.race_error(), Some(e.as_str()));
    assert_eq!(boats(sim.app.race()), shown);
    assert_eq!(
        sim.app.listed_races().len(),
        3,
        "the broken file is not kept"
    );
}

#[test]
fn a_file_the_provider_cannot_open_is_one_sentence_and_the_race_stays() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let mut sim = launch();
    let before = boats(sim.app.race());
    // A share whose grant was revoked: the provider no longer holds the URI.
    sim.intents().script_content(|c| {
        c.intent = Some(ar::arcore::ffi::IntentFile {
            action: ar::arcore::ffi::intent::ACTION_SEND.into(),
            uri: "content://org.example.mail/attachments/7".into(),
            mime: Some("application/gpx+xml".into()),
        });
    });
    let e = sim
        .open_intent()
        .expect("the intent carries a file")
        .unwrap_err();
    assert!(
        e.starts_with("\"7.gpx\" could not be read (java.io.FileNotFoundException"),
        "{e}"
    );
    assert_eq!(sim.app.status().banner.as_deref(), Some(e.as_str()));
    assert_eq!(boats(sim.app.race()), before);
}

#[test]
fn a_script_shares_files_with_open() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let out = out_dir("share-script");
    let races = out.join("races");
    let o = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args([
            "phone-sim",
            "--device",
            "a54",
            "--size",
            "180x400",
            "--script",
        ])
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/phone/share.txt"))
        .arg("--out")
        .arg(out.join("out"))
        .env("REGATTA_RACES_DIR", &races)
        .output()
        .unwrap();
    assert!(
        !o.status.success(),
        "the broken file's step fails: the exit says so"
    );
    let log = std::fs::read_to_string(out.join("out/log.jsonl")).unwrap();
    let lines: Vec<Value> = log
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let both = race::Race::load(&[valencia("ESP29375"), valencia("ESP30782")]).unwrap();
    let one = race::Race::load(&[valencia("ESP29375")]).unwrap();
    assert_eq!(lines[1]["ok"], true, "{}", lines[1]);
    assert_eq!(lines[1]["race"], one.name.as_str());
    assert_eq!(lines[1]["boats"], 1);
    assert_eq!(lines[2]["ok"], true, "{}", lines[2]);
    assert_eq!(lines[2]["race"], both.name.as_str());
    assert_eq!(lines[2]["boats"], 2);
    assert_eq!(lines[3]["ok"], false);
    let e = lines[3]["error"].as_str().unwrap();
    assert!(e.contains("not-a-race.gpx") && !e.contains('\n'), "{e}");
    assert_eq!(lines[3]["banner"], e);
    assert_eq!(lines[3]["boats"], 2, "the race shown stays");
    assert!(
        races
            .join("2025-06-21-ESP29375-P01/2025-06-21-ESP30782-P01.gpx")
            .is_file()
    );
}
