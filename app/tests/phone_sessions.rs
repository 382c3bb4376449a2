//! Phone sessions on the host (issue 19): the phone app of the app core, headless on lavapipe,
//! with the simulated ARCore, driven by the scripts in tests/phone/ (through `regatta
//! phone-sim`) or step by step (through `regatta::phone_sim::PhoneSim`). Each asserts against a
//! truth computed here: the session machine's published messages, the table hit computed from
//! the synthetic camera's pose and intrinsics by hand, the gesture's finger geometry, the
//! timeline track's rectangle as egui laid it out, the replay reader.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use ar::arcore::Unavailable;
use ar::arcore::session::tracking_hint;
use glam::{DVec2, DVec3};
use regatta::core::feed::CameraFeed;
use regatta::core::table::{course_pivot, table_depth};
use regatta::phone_sim::PhoneSim;
use regatta::sim_phone::device::Device;
use serde_json::Value;

/// The A54's layout (360 × 800 dp) on a quarter of its pixels: quick on lavapipe.
const SIZE: [u32; 2] = [180, 400];

fn gpu_present() -> bool {
    render::gpu::test_gpu().is_some()
}

fn out_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("phone_sessions")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn script(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/phone")
        .join(name)
}

/// Runs `regatta phone-sim` on a script of tests/phone/: exit status, log lines, out folder.
fn phone_sim(name: &str, extra: &[&str]) -> (std::process::Output, Vec<Value>, PathBuf) {
    let out = out_dir(name);
    let o = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args([
            "phone-sim",
            "--device",
            "a54",
            "--size",
            "180x400",
            "--script",
        ])
        .arg(script(name))
        .arg("--out")
        .arg(&out)
        .args(extra)
        .output()
        .unwrap();
    let log = std::fs::read_to_string(out.join("log.jsonl")).unwrap_or_default();
    let lines = log
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    (o, lines, out)
}

fn last(lines: &[Value]) -> &Value {
    lines.last().expect("the log has a line per step")
}

/// A one-frame synthetic feed: the camera stands still, so a tap's frame is known.
fn still_feed() -> CameraFeed {
    CameraFeed::synth(still_config())
}

fn still_config() -> ar::SynthConfig {
    ar::SynthConfig {
        frames: 1,
        width: 320,
        height: 240,
        supersample: 1,
        ..ar::SynthConfig::default()
    }
}

fn launch(feed: CameraFeed, data: Option<PathBuf>) -> PhoneSim {
    PhoneSim::launch(feed, SIZE, Device::A54.pixels_per_point(SIZE), data)
}

#[test]
fn permission_denied_shows_why_and_the_race_runs_in_3d() {
    if !gpu_present() {
        return;
    }
    let (o, lines, out) = phone_sim("permission_denied.txt", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let end = last(&lines);
    assert_eq!(end["session"], "Unavailable(PermissionRefused)");
    assert_eq!(end["banner"], Unavailable::PermissionRefused.message());
    assert!(end["banner"].as_str().unwrap().contains("camera"));
    assert!(end["frames_drawn"].as_u64().unwrap() >= 3, "{end}");
    assert_eq!(end["placed"], false);
    assert!(out.join("denied.png").is_file());
    // One line per step, with the step's line number.
    let numbers: Vec<u64> = lines.iter().map(|l| l["line"].as_u64().unwrap()).collect();
    assert_eq!(numbers, [2, 3, 4]);
}

#[test]
fn arcore_missing_and_unsupported_each_say_so() {
    if !gpu_present() {
        return;
    }
    for (name, session, why) in [
        (
            "arcore_missing.txt",
            "Unavailable(LibraryMissing)",
            Unavailable::LibraryMissing,
        ),
        (
            "arcore_unsupported.txt",
            "Unavailable(DeviceNotSupported)",
            Unavailable::DeviceNotSupported,
        ),
    ] {
        let (o, lines, _) = phone_sim(name, &[]);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let end = last(&lines);
        assert_eq!(end["session"], session, "{name}");
        assert_eq!(end["banner"], why.message(), "{name}");
        assert!(
            end["frames_drawn"].as_u64().unwrap() > 0,
            "{name}: the 3D view draws"
        );
    }
}

#[test]
fn tracking_lost_shows_arcores_hint_and_regained_clears_it() {
    if !gpu_present() {
        return;
    }
    let (o, lines, _) = phone_sim("tracking.txt", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // AR_TRACKING_STATE_PAUSED (1) for AR_TRACKING_FAILURE_REASON_EXCESSIVE_MOTION (3).
    let lost = tracking_hint(1, 3).unwrap();
    assert_eq!(lines[1]["banner"], lost);
    assert_eq!(lines[2]["banner"], lost);
    assert_eq!(lines[4]["banner"], "Tap the table to place the course.");
    assert!(lines.iter().all(|l| l["session"] == "Running"));
}

#[test]
fn a_bad_script_line_is_one_line_naming_file_and_line_exit_2() {
    let (o, lines, _) = phone_sim("bad_line.txt", &[]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains("bad_line.txt:2:") && err.contains("tap 0.5"),
        "{err}"
    );
    assert!(
        lines.is_empty(),
        "nothing runs before the script is read whole"
    );
}

/// Where the ray through the screen point `s` (0–1) of a `SIZE` view showing `cfg`'s frame 0
/// (cropped to the view's aspect, centred) meets the table top (y = 0), computed by hand.
fn table_hit_by_hand(cfg: &ar::SynthConfig, s: DVec2) -> DVec3 {
    let k = cfg.intrinsics();
    let (iw, ih) = (f64::from(k.width), f64::from(k.height));
    let shown = (f64::from(SIZE[0]) / f64::from(SIZE[1])) / (iw / ih);
    let u = shown * s.x + 0.5 * (1.0 - shown);
    let (px, py) = (u * iw, s.y * ih);
    let dir_cam = DVec3::new((px - k.cx) / k.fx, -(py - k.cy) / k.fy, -1.0);
    let pose = cfg.pose(0).to_mat4().as_dmat4();
    let origin = pose.transform_point3(DVec3::ZERO);
    let dir = pose.transform_vector3(dir_cam);
    origin + dir * (-origin.y / dir.y)
}

/// The screen point a tap at `s` really touches: the finger's pixel as the touch carries it (f32).
fn touched(s: [f64; 2]) -> DVec2 {
    let px = [
        (s[0] * f64::from(SIZE[0])) as f32,
        (s[1] * f64::from(SIZE[1])) as f32,
    ];
    DVec2::new(f64::from(px[0]), f64::from(px[1]))
        / DVec2::new(f64::from(SIZE[0]), f64::from(SIZE[1]))
}

fn pivot_on_table(sim: &PhoneSim) -> DVec3 {
    let world = regatta::world::RaceWorld::new(race::Race::sample(), ocean::WaveSet::default_sea());
    let p = sim.app.course().expect("the course stands on the table");
    p.race_to_ar()
        .transform_point3(course_pivot(world.play_area, table_depth()))
}

#[test]
fn tap_places_the_course_on_the_hit_and_pinch_and_twist_scale_and_turn_it() {
    if !gpu_present() {
        return;
    }
    let mut sim = launch(still_feed(), None);
    sim.frame(0.1);
    assert!(sim.app.course().is_none());
    let s = [0.55, 0.62];
    sim.tap(s);
    let want = table_hit_by_hand(&still_config(), touched(s));
    let got = pivot_on_table(&sim);
    assert!(
        (got - want).length() < 1e-4,
        "course at {got}, table hit at {want}"
    );
    let before = sim.app.course().unwrap();
    // Fingers spread to twice their distance and turned 30° counter-clockwise on screen.
    sim.pinch(2.0, 30.0);
    let after = sim.app.course().unwrap();
    let ratio = after.course_to_table / before.course_to_table;
    assert!((ratio - 2.0).abs() < 1e-3, "scaled by {ratio}");
    let turned = (after.yaw - before.yaw).rem_euclid(std::f64::consts::TAU);
    assert!(
        (turned - 30f64.to_radians()).abs() < 1e-3,
        "turned by {turned} rad"
    );
    // The course scaled and turned about its centre: the centre stays on the tapped point.
    assert!((pivot_on_table(&sim) - want).length() < 1e-4);
    // The status says so.
    assert!(sim.app.status().placed);
}

#[test]
fn one_finger_on_the_timeline_scrubs_to_the_time_under_it() {
    if !gpu_present() {
        return;
    }
    let mut sim = launch(still_feed(), None);
    sim.app.panels.clock.pause();
    sim.frame(0.1);
    let ctx = sim.app.egui_context().unwrap();
    // The scrub track as egui laid it out in the last frame: the widest drag-sensing widget of
    // the track's height.
    let track = common::scrub_track(&ctx);
    let track = track.expect("the timeline's scrub track is on screen");
    let ppp = f64::from(Device::A54.pixels_per_point(SIZE));
    let to_screen = |x: f32, y: f32| {
        [
            f64::from(x) * ppp / f64::from(SIZE[0]),
            f64::from(y) * ppp / f64::from(SIZE[1]),
        ]
    };
    let y = track.center().y;
    let from = to_screen(track.left() + 0.2 * track.width(), y);
    let to = to_screen(track.left() + 0.63 * track.width(), y);
    sim.drag(from, to, 0.4);
    // The time under the finger: its pixel in points along the track.
    let finger_x = f64::from((to[0] * f64::from(SIZE[0])) as f32) / ppp;
    let s = (finger_x - f64::from(track.left())) / f64::from(track.width());
    let (a, b) = sim.app.panels.clock.span();
    let want = a + s * (b - a);
    let got = sim.app.race_time();
    assert!(
        (got - want).abs() < 0.05,
        "race time {got}, finger at {want}"
    );
    assert!(
        sim.app.course().is_none(),
        "a drag on the panel is not a tap on the table"
    );
}

#[test]
fn rotation_turns_the_view_and_tells_arcore() {
    if !gpu_present() {
        return;
    }
    let mut sim = launch(still_feed(), None);
    sim.tap([0.5, 0.6]);
    let drawn = sim.app.status().frames_drawn;
    sim.rotate(90);
    assert_eq!(sim.app.view_size(), [SIZE[1], SIZE[0]]);
    assert_eq!(sim.scripted().lock().geometry, (1, SIZE[1], SIZE[0]));
    sim.frame(0.1);
    assert!(sim.app.status().frames_drawn > drawn);
    let img = sim.app.screenshot().unwrap().unwrap();
    assert_eq!(img.dimensions(), (SIZE[1], SIZE[0]));
    // The course stays where it stood.
    assert!(sim.app.status().placed);
    sim.rotate(0);
    assert_eq!(sim.scripted().lock().geometry, (0, SIZE[0], SIZE[1]));
}

#[test]
fn a_recording_passes_replay_check_and_plays_back_with_its_table() {
    if !gpu_present() {
        return;
    }
    let out = out_dir("record");
    let feed = CameraFeed::synth(ar::SynthConfig {
        frames: 8,
        ..still_config()
    });
    let mut sim = launch(feed, Some(out.clone()));
    sim.frame(0.1);
    sim.step(&regatta::phone_sim::script::Step::Record(true), &out)
        .unwrap();
    for _ in 0..8 {
        sim.frame(0.1);
    }
    sim.step(&regatta::phone_sim::script::Step::Record(false), &out)
        .unwrap();
    let dir = sim
        .app
        .last_recording
        .clone()
        .expect("a folder was written");
    let o = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args(["replay", "check"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(summary["frames"].as_u64().unwrap() >= 4, "{summary}");
    // Played back through the simulated ARCore: the recorded table is detected again, and a
    // tap stands the course on it.
    let feed = CameraFeed::Replay(ar::ReplayFeed::open(&dir).unwrap());
    let mut replay = launch(feed, None);
    replay.frame(0.1);
    replay.tap([0.5, 0.6]);
    assert!(
        replay.app.status().placed,
        "no table in the played-back recording"
    );
}

#[test]
fn the_scripted_tour_runs_every_step() {
    if !gpu_present() {
        return;
    }
    let (o, lines, out) = phone_sim("tour.txt", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(lines.iter().all(|l| l["ok"] == true), "{lines:?}");
    let by_step = |s: &str| lines.iter().find(|l| l["step"] == s).unwrap();
    assert_eq!(by_step("tap 0.5 0.6")["placed"], true);
    assert_eq!(by_step("scene pool")["scene"], "pool");
    assert_eq!(by_step("record start")["recording"], true);
    assert_eq!(by_step("record stop")["recording"], false);
    for shot in ["race", "pool", "landscape"] {
        let img = image::open(out.join(format!("{shot}.png"))).unwrap();
        let want = if shot == "landscape" {
            (400, 180)
        } else {
            (180, 400)
        };
        assert_eq!((img.width(), img.height()), want, "{shot}");
    }
    assert!(out.join("recordings").read_dir().unwrap().count() == 1);
}

/// A races folder in the test's out folder `name`: the Valencia sample (a folder: its two
/// boats' GPX and the metadata JSON) and a broken GPX file.
fn races_folder(name: &str) -> PathBuf {
    let races = out_dir(name).join("races");
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/races/valencia");
    std::fs::create_dir_all(races.join("valencia")).unwrap();
    for f in std::fs::read_dir(&sample).unwrap() {
        let f = f.unwrap().path();
        std::fs::copy(&f, races.join("valencia").join(f.file_name().unwrap())).unwrap();
    }
    std::fs::write(races.join("broken.gpx"), "<gpx><trk><trkseg><trkpt lat=\"x").unwrap();
    races
}

/// The Valencia race of `races` as the importer reads its race files (the truth).
fn valencia(races: &Path) -> race::Race {
    let mut files: Vec<PathBuf> = std::fs::read_dir(races.join("valencia"))
        .unwrap()
        .map(|f| f.unwrap().path())
        .filter(|f| f.extension().is_some_and(|e| e == "gpx" || e == "json"))
        .collect();
    files.sort();
    race::Race::load(&files).unwrap()
}

/// Whether pixel `p` (framebuffer) is inside label box `r` or a hull's pick circle.
fn on_a_boat(sim: &PhoneSim, p: [f64; 2]) -> bool {
    let o = &sim.app.overlays;
    o.placed_labels().iter().any(|l| {
        let r = l.rect;
        (r[0]..=r[2]).contains(&p[0]) && (r[1]..=r[3]).contains(&p[1])
    }) || o
        .hulls()
        .iter()
        .any(|h| (h.centre[0] - p[0]).hypot(h.centre[1] - p[1]) <= h.radius)
}

#[test]
fn the_overlays_are_drawn_on_the_phone_and_a_tap_on_a_boat_selects_it() {
    if !gpu_present() {
        return;
    }
    let mut sim = launch(still_feed(), None);
    // The race stands still: the boats are where the last frame drew them.
    sim.app.panels.clock.pause();
    sim.frame(0.1);
    sim.tap([0.5, 0.45]);
    assert!(sim.app.course().is_some());
    sim.frame(0.1);
    // Drawn: the labels were painted, each with its team-colour bar at its left edge; the
    // screenshot has that colour there (egui's sRGB of the team's linear colour).
    let img = sim.app.screenshot().unwrap().unwrap();
    let ppp = f64::from(Device::A54.pixels_per_point(SIZE));
    let labels = sim.app.overlays.placed_labels().to_vec();
    assert!(!labels.is_empty(), "no label painted on the phone");
    let bars_seen = labels
        .iter()
        .filter(|l| {
            let x = l.rect[0] + 0.5 * regatta::scene_overlay::labels::BAR_PT * ppp;
            let y = 0.5 * (l.rect[1] + l.rect[3]);
            let (x, y) = (x as u32, y as u32);
            if x >= SIZE[0] || y >= SIZE[1] {
                return false;
            }
            let want = regatta::scene_overlay::paint::colour32(l.colour, 255);
            let got = img.get_pixel(x, y).0;
            (0..3).all(|k| (i32::from(got[k]) - i32::from(want.to_array()[k])).abs() <= 12)
        })
        .count();
    assert!(
        bars_seen > 0,
        "none of the {} labels' team bars is in the screenshot",
        labels.len()
    );
    // A tap on a label selects its boat; a tap on a hull (off every label) selects the
    // boat nearest to the finger: the one tapped.
    let size = SIZE.map(f64::from);
    let in_label = |p: [f64; 2]| {
        labels.iter().any(|l| {
            let r = l.rect;
            (r[0]..=r[2]).contains(&p[0]) && (r[1]..=r[3]).contains(&p[1])
        })
    };
    let label = &labels[0];
    let course = sim.app.course();
    let r = label.rect;
    sim.tap([0.5 * (r[0] + r[2]) / size[0], 0.5 * (r[1] + r[3]) / size[1]]);
    assert_eq!(sim.app.overlays.selected(), [label.boat]);
    let hull = *sim
        .app
        .overlays
        .hulls()
        .iter()
        .find(|h| h.boat != label.boat && !in_label(h.centre))
        .expect("a hull off the labels");
    sim.tap([hull.centre[0] / size[0], hull.centre[1] / size[1]]);
    assert_eq!(sim.app.overlays.selected(), [label.boat, hull.boat]);
    assert_eq!(
        sim.app.course(),
        course,
        "a tap on a boat does not move the course"
    );
    // A tap on open table (off every boat and label) moves the course there; the selection
    // stays.
    let open = [6, 5, 4]
        .into_iter()
        .flat_map(|j| [5, 3, 7, 2, 8].map(|i| [f64::from(i) / 10.0, f64::from(j) / 10.0]))
        .find(|s| !on_a_boat(&sim, [s[0] * size[0], s[1] * size[1]]))
        .expect("open table somewhere");
    sim.tap(open);
    let want = table_hit_by_hand(&still_config(), touched(open));
    let got = pivot_on_table(&sim);
    assert!(
        (got - want).length() < 1e-4,
        "a tap at {open:?} put the course at {got}, not at the table hit {want}"
    );
    assert_eq!(sim.app.overlays.selected(), [label.boat, hull.boat]);
}

#[test]
fn the_races_folder_is_listed_and_a_chosen_race_loads_or_says_why_in_one_sentence() {
    if !gpu_present() {
        return;
    }
    let races = races_folder("races_folder");
    let mut sim = launch(still_feed(), None);
    // The course placed on the table (before the panel covers it): a new race stands where it
    // stood, fitted anew.
    sim.tap([0.5, 0.6]);
    sim.app.set_races_dir(Some(races.clone()));
    sim.app.panels.show_races = true;
    sim.frame(0.1);
    assert_eq!(sim.app.listed_races(), ["broken.gpx", "valencia"]);
    let names = |sim: &PhoneSim| -> Vec<String> {
        sim.app
            .race()
            .boats
            .iter()
            .map(|b| b.name.clone())
            .collect()
    };
    let before = names(&sim);
    let placed = sim.app.course().expect("the course placed");
    let pivot = |p: &ar::arcore::CoursePlacement, bounds| {
        p.race_to_ar()
            .transform_point3(course_pivot(bounds, table_depth()))
    };
    let sample_pivot = pivot(
        &placed,
        regatta::world::RaceWorld::new(race::Race::sample(), ocean::WaveSet::default_sea())
            .race_bounds,
    );
    // The broken file: one sentence naming it, the race stays.
    let e = sim.app.choose_race("broken.gpx").unwrap_err();
    sim.frame(0.1);
    assert!(e.contains("broken.gpx") && !e.contains('\n'), "{e}");
    assert_eq!(sim.app.race_error(), Some(e.as_str()));
    assert_eq!(names(&sim), before);
    // Valencia: its boats, as the importer reads the files (the truth), replace the sample's.
    sim.app.choose_race("valencia").unwrap();
    sim.frame(0.1);
    let want: Vec<String> = valencia(&races)
        .boats
        .iter()
        .map(|b| b.name.clone())
        .collect();
    assert_eq!(names(&sim), want);
    assert_ne!(want, before);
    assert_eq!(sim.app.race_error(), None);
    // Valencia's own bounds (every fix and mark, read here from the importer's race) fill
    // 90 % of the room on the tapped table along the side that binds (the race turned a
    // quarter where that draws it larger), pivot on the same table point.
    let truth = valencia(&races);
    let points = truth
        .boats
        .iter()
        .flat_map(|b| b.fixes().iter().map(|f| f.pos()))
        .chain(truth.buoys());
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for [x, z] in points {
        b = [b[0].min(x), b[1].min(z), b[2].max(x), b[3].max(z)];
    }
    let course = sim.app.course().expect("still placed");
    let (w, h) = (b[2] - b[0], b[3] - b[1]);
    let room = sim.app.table_room().extent;
    assert!(
        room.min_element() < regatta::core::table::FIRST_TABLE_M,
        "{room}"
    );
    let race_per_table = (w / room.x)
        .max(h / room.y)
        .min((w / room.y).max(h / room.x));
    let want_scale = (1.0 - regatta::core::table::RACE_MARGIN) / race_per_table;
    assert!(
        (course.course_to_table / want_scale - 1.0).abs() < 1e-9,
        "{} vs {want_scale}",
        course.course_to_table
    );
    assert!((pivot(&course, b) - sample_pivot).length() < 1e-9);
    // A file pushed while the app was away is listed after resume.
    sim.pause();
    std::fs::copy(races.join("broken.gpx"), races.join("later.gpx")).unwrap();
    sim.resume();
    assert_eq!(
        sim.app.listed_races(),
        ["broken.gpx", "later.gpx", "valencia"]
    );
}

#[test]
fn a_script_chooses_a_race_in_the_folder_regatta_races_dir_names() {
    if !gpu_present() {
        return;
    }
    let races = races_folder("races_script");
    let out = races.parent().unwrap().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_regatta"))
        .args([
            "phone-sim",
            "--device",
            "a54",
            "--size",
            "180x400",
            "--script",
        ])
        .arg(script("races.txt"))
        .arg("--out")
        .arg(&out)
        .env("REGATTA_RACES_DIR", &races)
        .output()
        .unwrap();
    assert!(
        !o.status.success(),
        "a step failed: the exit status says so"
    );
    let log = std::fs::read_to_string(out.join("log.jsonl")).unwrap();
    let lines: Vec<Value> = log
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let sample = race::Race::sample().name;
    assert_eq!(lines[0]["race"], sample.as_str());
    assert_eq!(lines[1]["ok"], true, "{}", lines[1]);
    assert_eq!(lines[1]["race"], valencia(&races).name.as_str());
    assert_eq!(lines[2]["ok"], false);
    let e = lines[2]["error"].as_str().unwrap();
    assert!(e.contains("broken.gpx") && !e.contains('\n'), "{e}");
    assert_eq!(
        lines[2]["race"], lines[1]["race"],
        "the race shown before stays"
    );
}
