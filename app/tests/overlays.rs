//! The race overlays (docs/overlays.md): label anchors against an independent f64 projection
//! of each masthead, decluttering on the real sample fleet, trail breaks at the gaps of a real
//! Garmin track, `--overlays` errors, and golden images of the orbit and table scenes with every
//! overlay (`REGATTA_UPDATE_GOLDEN=1 cargo test -p regatta --test overlays` rewrites them).

mod common;

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use regatta::scene_overlay::OverlayKind;
use regatta::scene_overlay::{self, OverlaySet, OverlaySettings, labels};
use regatta::setup::{Profile, RaceSetup};
use render::Scene;
use render::golden::{Region, differing};
use render::passes::segments::Layer;

fn sea() -> ocean::WaveSet {
    regatta::setup::inputs::drawable_sea(regatta::setup::inputs::load_sea(None).unwrap())
}

/// The desktop's orbit view of `race` at `t`.
fn orbit_scene(race: &race::Race, t: f64) -> Scene {
    let mut orbit = regatta::world::race_orbit();
    regatta::world::RaceWorld::new(race.clone(), sea()).orbit_scene(t, &mut orbit)
}

/// A pinhole projection written out from the camera's definition (eye, target, up, vertical
/// field of view), in f64: framebuffer pixels, y down.
fn project_independently(scene: &Scene, size: [u32; 2], p: DVec3) -> [f64; 2] {
    let c = &scene.camera;
    let forward = (c.target - c.eye).normalize();
    let right = forward.cross(c.up).normalize();
    let up = right.cross(forward);
    let d = p - c.eye;
    let (x, y, z) = (d.dot(right), d.dot(up), d.dot(forward));
    let [w, h] = size.map(f64::from);
    let f = (h / 2.0) / (c.fov_y / 2.0).tan();
    [w / 2.0 + f * x / z, h / 2.0 - f * y / z]
}

/// Where the boats pass puts boat `b`'s masthead: its own float pose and model matrix.
fn masthead_as_drawn(scene: &Scene, position: [f64; 2], heading_deg: f64, length: f64) -> DVec3 {
    let p = DVec2::from(position);
    let heading = heading_deg.to_radians();
    let pose = render::scene::float_pose(&scene.sea, scene.t, p, heading, length, 0.32 * length);
    render::scene::float_matrix(p, heading, &pose, DVec2::ZERO)
        .transform_point3(DVec3::from(render::passes::boats::MASTHEAD) * length)
}

#[test]
fn every_label_anchor_is_within_two_pixels_of_its_masthead() {
    let race = race::Race::sample();
    // The desktop's orbit view, and `regatta render`'s framing view at phone size.
    let framing = |t| regatta::world::scene_at(&race, &sea(), t, None);
    for (t, size, scene) in [
        (600.0, [1280, 720], orbit_scene(&race, 600.0)),
        (300.0, [720, 1600], framing(300.0)),
    ] {
        let f = scene_overlay::frame(&race, &scene, size, 1.0, &OverlaySettings::default(), None);
        assert!(
            f.hulls.len() >= 2,
            "t = {t}: {} boats on screen",
            f.hulls.len()
        );
        for h in &f.hulls {
            let s = race.boats[h.boat].state_at(t);
            let top = masthead_as_drawn(&scene, s.position, s.heading_deg, 10.0);
            let want = project_independently(&scene, size, top);
            let off = (h.anchor[0] - want[0]).hypot(h.anchor[1] - want[1]);
            assert!(off <= 2.0, "boat {} at t = {t}: {off:.3} px", h.boat);
        }
    }
}

/// Label sizes as a proportional font of `px` pixels lays them out, near enough.
fn measure(text: &str, px: f64) -> [f64; 2] {
    [0.55 * px * text.chars().count() as f64, 1.2 * px]
}

#[test]
fn the_sample_fleets_labels_never_overlap_and_the_leader_is_labelled() {
    let race = race::Race::sample();
    // At the start the fleet is bunched on the line.
    for t in [0.0, 60.0, 600.0] {
        let scene = orbit_scene(&race, t);
        let size = [1280, 720];
        let f = scene_overlay::frame(&race, &scene, size, 1.0, &OverlaySettings::default(), None);
        let placed = labels::place(&f.labels, [1280.0, 720.0], 1.0, &measure);
        for (i, a) in placed.iter().enumerate() {
            for b in &placed[i + 1..] {
                let apart = a.rect[2] <= b.rect[0]
                    || b.rect[2] <= a.rect[0]
                    || a.rect[3] <= b.rect[1]
                    || b.rect[3] <= a.rect[1];
                assert!(apart, "t = {t}: {} and {} overlap", a.text, b.text);
            }
        }
        let leader = race.standings(t).into_iter().find(|s| s.rank == 1).unwrap();
        if f.labels.iter().any(|c| c.boat == leader.boat) {
            assert!(
                placed.iter().any(|l| l.boat == leader.boat),
                "t = {t}: the leader's label was hidden"
            );
        }
        // A tap on a label selects that label's boat.
        for l in &placed {
            let centre = [(l.rect[0] + l.rect[2]) / 2.0, (l.rect[1] + l.rect[3]) / 2.0];
            assert_eq!(labels::pick(&placed, &f.hulls, centre), Some(l.boat));
        }
    }
}

#[test]
fn a_selected_boat_gets_a_white_ring_and_its_label_first() {
    let race = race::Race::sample();
    let scene = orbit_scene(&race, 600.0);
    let layer = |selected: Vec<usize>| {
        let settings = OverlaySettings {
            selected,
            ..Default::default()
        };
        let f = scene_overlay::frame(&race, &scene, [1280, 720], 1.0, &settings, None);
        let (_, layer) = f
            .layers
            .into_iter()
            .find(|(k, _)| *k == OverlayKind::Labels)
            .unwrap();
        let Layer::Draw(segments) = layer else {
            panic!("{layer:?}")
        };
        let white = segments.iter().filter(|s| s.colour_a == [1.0; 4]).count();
        (f.labels, white)
    };
    let (_, none) = layer(Vec::new());
    let (labels, one) = layer(vec![5]);
    assert_eq!(none, 0);
    assert!(one >= 24, "a full white ring: {one} segments");
    let placed = labels::place(&labels, [1280.0, 720.0], 1.0, &measure);
    assert!(placed[0].boat == 5 && placed[0].selected, "{:?}", placed[0]);
}

#[test]
fn phone_labels_are_at_least_twelve_points() {
    for size in [[720, 1600], [1080, 2400]] {
        let ppp = scene_overlay::paint::headless_pixels_per_point(size);
        // A phone is ~360 dp wide: pixels per dp.
        let dp = f64::from(size[0]) / 360.0;
        assert!(labels::LABEL_TEXT_PT * ppp / dp >= 12.0, "{size:?}");
    }
}

fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../shared/data/races")
        .join(rel)
}

#[test]
fn trails_break_at_the_gaps_of_a_real_garmin_track() {
    // rerata_26_oct.gpx: gaps of 122 s (09:55:10→09:57:12) and 598 s (10:55:24→11:05:22), per
    // ../shared/data/README.md.
    let race = race::Race::load(&[data("gdansk/rerata_26_oct.gpx")]).unwrap();
    let boat = &race.boats[0];
    let (t0, t1) = boat.time_span();
    let mut seen = Vec::new();
    // Twenty-minute trails every five minutes over the whole track.
    const WINDOW_S: f64 = 1200.0;
    let mut t = t0;
    while t <= t1 {
        let lines = regatta::scene_overlay::geometry::trail_polylines(boat, t, WINDOW_S);
        for line in &lines {
            for w in line.windows(2) {
                assert!(
                    w[1].0 - w[0].0 < 60.0,
                    "a trail spans {:.0} s",
                    w[1].0 - w[0].0
                );
            }
        }
        for pair in lines.windows(2) {
            seen.push(pair[1][0].0 - pair[0].last().unwrap().0);
        }
        t += 300.0;
    }
    for gap in [122.0, 598.0] {
        assert!(
            seen.iter().any(|g| (g - gap).abs() <= 1.0),
            "a trail breaks across the {gap} s gap: {seen:?}"
        );
    }
}

#[test]
fn the_frame_reports_each_overlay_and_why_it_was_skipped() {
    let race = race::Race::sample();
    let scene = orbit_scene(&race, 600.0);
    let f = scene_overlay::frame(
        &race,
        &scene,
        [640, 360],
        1.0,
        &OverlaySettings::default(),
        None,
    );
    for (kind, layer) in &f.layers {
        assert!(matches!(layer, Layer::Draw(_)), "{kind:?}: {layer:?}");
    }
    // The race's file states its wind: the label says it is the race's data.
    assert!(
        f.texts
            .iter()
            .any(|t| t.text.ends_with("(from the race's data)")),
        "{:?}",
        f.texts
    );
    let mut no_wind = race.clone();
    no_wind.wind = None;
    let calm = Scene {
        sea: ocean::WaveSet {
            waves: Vec::new(),
            ..sea()
        }
        .into(),
        ..scene.clone()
    };
    let settings = OverlaySettings {
        set: OverlaySet::parse("wind,lines").unwrap(),
        ..Default::default()
    };
    let f = scene_overlay::frame(&no_wind, &calm, [640, 360], 1.0, &settings, None);
    let layer = |k| {
        f.layers
            .iter()
            .find(|(kind, _)| *kind == k)
            .unwrap()
            .1
            .clone()
    };
    // No wind in the race's files and a calm sea: the wind drawn is the fleet's estimate
    // (race::debrief::wind), and its label on the water says so, with its uncertainty.
    assert!(
        matches!(layer(OverlayKind::Wind), Layer::Draw(_)),
        "the estimated wind is drawn"
    );
    let sigma = no_wind.wind_model().unwrap().uncertainty_deg;
    let said = format!("(estimated from the fleet ±{sigma:.1}°)");
    assert!(
        f.texts.iter().any(|t| t.text.ends_with(&said)),
        "no wind label ending {said}: {:?}",
        f.texts
    );
    assert_eq!(
        layer(OverlayKind::Trails),
        Layer::Hidden("turned off (\"trails\" not in --overlays)".into())
    );
    assert!(f.labels.is_empty(), "labels off: none placed");
}

#[test]
fn bad_overlay_lists_are_one_line_errors() {
    let out = std::env::temp_dir().join("regatta-overlays-never.png");
    let out = out.to_str().unwrap();
    common::fails_with(
        &["render", "--out", out, "--overlays", "labels,wakes"],
        "--overlays names the unknown overlay \"wakes\"",
    );
    common::fails_with(
        &["render", "--out", out, "--overlays", "none,course"],
        "contradictory",
    );
    common::fails_with(
        &[
            "render",
            "--out",
            out,
            "--scene",
            "pool",
            "--overlays",
            "all",
        ],
        "--overlays",
    );
}

// ---- golden images ----

const GOLDEN_SIZE: [u32; 2] = [384, 216];

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(format!("{name}.png"))
}

/// The scene drawn as `regatta render` draws it, with `set`; `table`: over the synthetic
/// feed's table with its effects (`regatta render --replay synth`). No wakes: the goldens
/// show the overlays, not the wake model.
fn draw(race: &race::Race, t: f64, set: OverlaySet, table: bool) -> image::RgbaImage {
    let gpu = render::gpu::test_gpu().expect("checked by the caller");
    let setup = RaceSetup::new(Profile::Picture);
    let mut renderer = setup.renderer(&gpu, render::OFFSCREEN_FORMAT, None);
    let mut scene = orbit_scene(race, t);
    if table {
        let mut feed = regatta::core::feed::FeedView::open(Path::new("synth")).unwrap();
        feed.prepare_frame(
            &gpu,
            &mut renderer,
            render::OFFSCREEN_FORMAT,
            &setup,
            None,
            regatta::world::RaceWorld::new(race.clone(), sea()).race_bounds,
            GOLDEN_SIZE,
            0,
        )
        .unwrap();
        feed.apply(&mut scene);
    }
    let settings = OverlaySettings {
        set,
        ..Default::default()
    };
    // The goldens show the overlays without the manoeuvre marks (tests/manoeuvre_marks.rs).
    let drawn = (race, None);
    scene_overlay::render_headless(&gpu, &mut renderer, drawn, &scene, GOLDEN_SIZE, &settings)
        .unwrap()
        .0
}

/// The golden `name` of the sample race at t = 600 s with every overlay; the pixels the
/// overlays change (against the same frame without them) are a region with its own limit.
fn golden(name: &str, table: bool) {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let race = race::Race::sample();
    let with = draw(&race, 600.0, OverlaySet::ALL, table);
    let without = draw(&race, 600.0, OverlaySet::NONE, table);
    let mask = differing(&with, &without);
    let changed = mask.iter().filter(|&&m| m).count();
    assert!(
        changed > (GOLDEN_SIZE[0] * GOLDEN_SIZE[1]) as usize / 50,
        "the overlays change only {changed} pixels"
    );
    let regions = [Region {
        name: "overlays".into(),
        mask,
        mean_tolerance: 3.0,
    }];
    render::golden::check_regions(&golden_path(name), &with, &regions)
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn golden_orbit_scene_with_overlays() {
    golden("overlays_orbit", false);
}

#[test]
fn golden_table_scene_with_overlays() {
    golden("overlays_table", true);
}

/// `regatta render --tier` draws the overlays of the tier's detail (quality's tier table:
/// low is essential, medium standard), and the frame report says why the others are not
/// drawn; without `--tier` every overlay the user chose is drawn.
#[test]
fn render_at_a_tier_draws_the_overlays_of_its_detail() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let out =
        std::env::temp_dir().join(format!("regatta-tier-overlays-{}.png", std::process::id()));
    let out = out.to_str().unwrap();
    let passes = |tier: Option<&str>| -> Vec<(String, bool, String)> {
        let mut args = vec!["render", "--out", out, "--size", "320x180", "--t", "600"];
        if let Some(t) = tier {
            args.extend(["--tier", t]);
        }
        let v = common::ok_json(&args);
        v["passes"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| p["name"].as_str().unwrap().starts_with("overlay-"))
            .map(|p| {
                let s = |k: &str| p[k].as_str().unwrap().to_string();
                (s("name"), p["ran"].as_bool().unwrap(), s("reason"))
            })
            .collect()
    };
    let hidden_by_tier = |passes: &[(String, bool, String)]| -> Vec<String> {
        passes
            .iter()
            .filter(|(_, _, why)| why.starts_with("the tier's overlay detail"))
            .map(|(name, _, _)| name.clone())
            .collect()
    };
    let low = passes(Some("low"));
    assert_eq!(low.len(), 5, "{low:?}");
    assert_eq!(
        hidden_by_tier(&low),
        ["overlay-trails", "overlay-lines", "overlay-wind"],
        "{low:?}"
    );
    let course = low.iter().find(|p| p.0 == "overlay-course").unwrap();
    assert!(course.1, "the course is drawn at low: {course:?}");
    let medium = passes(Some("medium"));
    assert_eq!(hidden_by_tier(&medium), ["overlay-lines"], "{medium:?}");
    assert!(hidden_by_tier(&passes(None)).is_empty());
    assert!(hidden_by_tier(&passes(Some("high"))).is_empty());
    let _ = std::fs::remove_file(out);
}
