//! The race fitted on the table (`core::table`), seen: in the table scene as
//! `regatta render --replay synth` draws it (`TableFrame::draw`), the water reaches the table's
//! edges wherever they are in view (all along the far edge, both far corners included, and
//! the parts of the sides and the near edge the 4:3 frame shows) and stops there. The table
//! comes from the synthetic feed's own table (`ar::SynthConfig::table`), mapped into race
//! metres by the feed's placement; the water's presence is the difference against the same
//! frame with the water cut away entirely (the raw camera image and the marks): at least 2
//! levels (measured about 25) 3 % of the table inside its edges, none 3 % outside. Before the
//! fit to the race's bounds the water covered 61 % of the table's width (no water inside its
//! far corners); without the cut it spills onto the floor.

use std::path::Path;

use glam::{DVec2, DVec3, DVec4};
use regatta::core::feed::TableFrame;
use regatta::core::feed::{FeedView, SYNTH};
use regatta::setup::{Profile, RaceSetup};
use regatta::world::RaceWorld;
use render::Camera;

const SIZE: [u32; 2] = [640, 480];
/// How far inside or outside the table's edges the probed points are, as a share of each side.
const PROBE: f64 = 0.03;

/// Pixel (x, y down) of the race point `p` seen by `cam` in a SIZE frame.
fn project(cam: &Camera, p: DVec3) -> DVec2 {
    let aspect = f64::from(SIZE[0]) / f64::from(SIZE[1]);
    let c = cam.view_proj_local(DVec2::ZERO, aspect) * DVec4::new(p.x, p.y, p.z, 1.0);
    DVec2::new(
        (c.x / c.w + 1.0) * 0.5 * f64::from(SIZE[0]),
        (1.0 - c.y / c.w) * 0.5 * f64::from(SIZE[1]),
    )
}

/// Mean absolute RGB difference of two frames over the 5×5 pixels around `at`.
fn difference_around(a: &image::RgbaImage, b: &image::RgbaImage, at: DVec2) -> f64 {
    let (cx, cy) = (at.x.floor() as i64, at.y.floor() as i64);
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in cy - 2..=cy + 2 {
        for x in cx - 2..=cx + 2 {
            assert!(
                (0..i64::from(SIZE[0])).contains(&x) && (0..i64::from(SIZE[1])).contains(&y),
                "probe {at} is off the frame"
            );
            let (p, q) = (
                a.get_pixel(x as u32, y as u32),
                b.get_pixel(x as u32, y as u32),
            );
            for k in 0..3 {
                sum += (f64::from(p[k]) - f64::from(q[k])).abs();
            }
            n += 3.0;
        }
    }
    sum / n
}

#[test]
fn the_water_covers_the_table_to_its_corners_and_stops_at_its_edges() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let race = race::Race::sample();
    let sea = regatta::setup::inputs::drawable_sea(ocean::WaveSet::default_sea());
    let world = RaceWorld::new(race, sea);
    let table = TableFrame {
        world: &world,
        t: 600.0,
        size: SIZE,
        frame: 0,
        overlays: None,
    };
    let mut feed = FeedView::open(Path::new(SYNTH)).unwrap();
    let mut setup = RaceSetup::new(Profile::Picture);
    setup.options.measure_gpu_time = false;
    let mut renderer = setup.renderer(&gpu, render::OFFSCREEN_FORMAT, None);
    // `water`: false cuts all of it away (a play area far off the table).
    let mut draw = |water: bool| {
        let mut camera = None;
        let (img, _) = table
            .draw(&mut feed, &gpu, &mut renderer, &setup, None, |s| {
                s.boats.clear();
                if !water {
                    s.play_area = [1e7, 1e7, 1e7 + 1.0, 1e7 + 1.0];
                }
                camera = Some(s.camera);
            })
            .unwrap();
        (img, camera.unwrap())
    };
    let (with_water, cam) = draw(true);
    let (without, _) = draw(false);
    let map = feed.placement().expect("a prepared frame has a placement");
    let depth_ar = feed.water().depth_m * map.course_to_table;
    let plane = ar::SynthConfig::default().table();
    let half = DVec2::from(plane.extent) / 2.0;
    let centre = DVec3::from(plane.center);
    let to_race = map.ar_to_race();
    // A point on the water's surface (its depth above the table top) over the table point at
    // (u, v) ∈ [−1, 1]² of its half extents, `share` of each side further in (negative: out).
    let probe = |u: f64, v: f64, share: f64| {
        let ar = centre
            + DVec3::new(
                u * half.x * (1.0 - 2.0 * share),
                depth_ar,
                v * half.y * (1.0 - 2.0 * share),
            );
        project(&cam, to_race.transform_point3(ar))
    };
    let on_frame = |p: DVec2| {
        p.x >= 3.0 && p.y >= 3.0 && p.x < f64::from(SIZE[0]) - 3.0 && p.y < f64::from(SIZE[1]) - 3.0
    };
    // The four edges, each walked from corner to corner (u, v) in 20 steps.
    let edges = [
        ("far (−z)", [-1.0, -1.0], [1.0, -1.0]),
        ("near (+z)", [-1.0, 1.0], [1.0, 1.0]),
        ("left (−x)", [-1.0, -1.0], [-1.0, 1.0]),
        ("right (+x)", [1.0, -1.0], [1.0, 1.0]),
    ];
    let mut far_corners = 0;
    for (name, from, to) in edges {
        let mut seen = 0;
        for k in 0..=20 {
            let [u, v] = [0, 1].map(|i| from[i] + (to[i] - from[i]) * f64::from(k) / 20.0);
            let (inside, outside) = (probe(u, v, PROBE), probe(u, v, -PROBE));
            if !on_frame(inside) || !on_frame(outside) {
                continue;
            }
            seen += 1;
            let d_in = difference_around(&with_water, &without, inside);
            let d_out = difference_around(&with_water, &without, outside);
            if name.starts_with("far") && (k == 0 || k == 20) {
                far_corners += 1;
                eprintln!(
                    "far corner ({u}, {v}): inside at {inside:.0} differs by {d_in:.2}, outside at {outside:.0} by {d_out:.2}"
                );
            }
            assert!(
                d_in >= 2.0,
                "{name} edge at ({u}, {v}): no water just inside ({d_in:.2} levels at {inside:.0})"
            );
            assert!(
                d_out == 0.0,
                "{name} edge at ({u}, {v}): water spills outside ({d_out:.2} levels at {outside:.0})"
            );
        }
        eprintln!("{name} edge: {seen} of 21 points in view");
        assert!(seen >= 5, "{name} edge: only {seen} points in view");
    }
    assert_eq!(far_corners, 2, "both far corners in view");
}
