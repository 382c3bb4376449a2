//! Wakes you can see on the table: in the 1280×720 table scene (`regatta render --replay synth`'s
//! path, `TableFrame::draw`), every boat sailing at 2 m/s or more changes the picture visibly
//! behind it over at least twice its own silhouette. Visibly: a Rec. 709 luma difference of at
//! least 3/255 between the picture with that boat's wake and without any wake. The silhouette:
//! the pixels that boat alone changes against an empty scene (no wakes). Behind: pixels whose
//! ray meets the sea's rest plane behind the boat (on the stern side of the line through it
//! across its course made good over the last 10 s: its heading on a straight leg). Before the Froude scaling (docs/wakes.md, "Wakes at table scale") the
//! full-size wakes are far under a pixel there and this fails.

use std::path::Path;
use std::sync::Arc;

use glam::{DVec2, DVec3, DVec4};
use regatta::core::feed::TableFrame;
use regatta::core::feed::{FeedView, SYNTH};
use regatta::setup::{Profile, RaceSetup};
use regatta::world::{middle_time, race_wake};
use render::Camera;

const SIZE: [u32; 2] = [1280, 720];
/// Luma step that counts as visible, of 255.
const VISIBLE: f64 = 3.0;
/// How far back the course made good that says which side is behind a boat reaches, seconds:
/// 30 m at 3 m/s, under one drawn model's length on the table (about 40 m of race).
const TRACK_BACK_S: f64 = 10.0;

fn luma(img: &image::RgbaImage) -> Vec<f64> {
    img.pixels()
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .collect()
}

/// Pixels where the two pictures differ by at least `VISIBLE`.
fn changed(a: &[f64], b: &[f64]) -> Vec<bool> {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() >= VISIBLE)
        .collect()
}

/// Where the ray through pixel (px, py) meets y = 0, world (x, z).
fn on_sea(cam: &Camera, px: u32, py: u32) -> Option<DVec2> {
    let aspect = f64::from(SIZE[0]) / f64::from(SIZE[1]);
    let inv = cam.view_proj_local(DVec2::ZERO, aspect).inverse();
    let x = 2.0 * (f64::from(px) + 0.5) / f64::from(SIZE[0]) - 1.0;
    let y = 1.0 - 2.0 * (f64::from(py) + 0.5) / f64::from(SIZE[1]);
    let p = |z: f64| {
        let v = inv * DVec4::new(x, y, z, 1.0);
        v.truncate() / v.w
    };
    let (a, b): (DVec3, DVec3) = (p(0.0), p(1.0));
    let d = b - a;
    if d.y.abs() < 1e-12 {
        return None;
    }
    let s = -a.y / d.y;
    (s > 0.0).then(|| {
        let q = a + s * d;
        DVec2::new(q.x, q.z)
    })
}

#[test]
fn every_boat_over_2_mps_leaves_a_wake_twice_its_silhouette_behind_it() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let race = race::Race::sample();
    let sea = regatta::setup::inputs::drawable_sea(ocean::WaveSet::default_sea());
    let t = middle_time(&race);
    let world = regatta::world::RaceWorld::new(race.clone(), sea.clone());
    let table = TableFrame {
        world: &world,
        t,
        size: SIZE,
        frame: 0,
        overlays: None,
    };
    let mut feed = FeedView::open(Path::new(SYNTH)).unwrap();
    let mut setup = RaceSetup::new(Profile::Picture);
    setup.options.measure_gpu_time = false;
    let mut renderer = setup.renderer(&gpu, render::OFFSCREEN_FORMAT, None);
    // `keep`: draw only the boat at that position (NaN: none).
    let mut draw = |wake: Option<Arc<ocean::wake::Wake>>, keep: Option<DVec2>| {
        let mut camera = None;
        let (img, _) = table
            .draw(&mut feed, &gpu, &mut renderer, &setup, wake, |s| {
                if let Some(p) = keep {
                    // NaN: no boat.
                    s.boats.retain(|b| b.position == p);
                    assert_eq!(s.boats.len(), usize::from(!p.is_nan()), "boats at {p}");
                }
                camera = Some(s.camera);
            })
            .unwrap();
        (luma(&img), camera.unwrap())
    };
    let mut tested = 0;
    let mut ratios = Vec::new();
    for b in &race.boats {
        let st = b.state_at(t);
        if st.in_gap || !st.racing || st.speed_mps < 2.0 {
            continue;
        }
        let pos = DVec2::from(st.position);
        let mut alone = race.clone();
        alone.boats.retain(|x| x.id == b.id);
        let wake = race_wake(&alone).unwrap();
        // The boat's silhouette: it alone against no boat, no wakes.
        let (no_boat, _) = draw(None, Some(DVec2::splat(f64::NAN)));
        let (boat, cam) = draw(None, Some(pos));
        let silhouette = changed(&no_boat, &boat).iter().filter(|&&c| c).count();
        // Its wake: the boat alone with and without its wake.
        let (with_wake, _) = draw(Some(wake), Some(pos));
        // Which way is ahead: the course made good over the last TRACK_BACK_S (on a straight
        // leg, the heading); during a mark rounding the heading sweeps across the wake just
        // laid, the course made good still points away from it.
        let before = DVec2::from(b.state_at(t - TRACK_BACK_S).position);
        let (sin, cos) = st.heading_deg.to_radians().sin_cos();
        // Compass heading: 0 north (−z), 90 east (+x).
        let heading = DVec2::new(sin, -cos);
        let ahead = (pos - before).try_normalize().unwrap_or(heading);
        // Behind by the course made good (asserted) and by the heading alone (printed).
        let (mut behind, mut behind_heading) = (0usize, 0usize);
        for (i, c) in changed(&boat, &with_wake).into_iter().enumerate() {
            let (px, py) = ((i as u32) % SIZE[0], (i as u32) / SIZE[0]);
            if let (true, Some(q)) = (c, on_sea(&cam, px, py)) {
                behind += usize::from((q - pos).dot(ahead) < 0.0);
                behind_heading += usize::from((q - pos).dot(heading) < 0.0);
            }
        }
        let ratio = behind as f64 / silhouette.max(1) as f64;
        eprintln!(
            "{} at {:.1} m/s: silhouette {silhouette} px, wake behind {behind} px, ratio {ratio:.1} (behind its heading: {behind_heading} px)",
            b.id, st.speed_mps
        );
        assert!(silhouette > 0, "{}: the boat is not in the picture", b.id);
        ratios.push((b.id.clone(), ratio));
        tested += 1;
    }
    assert!(tested >= 4, "too few boats at 2 m/s or more: {tested}");
    for (id, r) in ratios {
        assert!(
            r >= 2.0,
            "{id}: visible wake behind the boat / silhouette = {r:.2}"
        );
    }
}
