//! The culled clip-map leaves no hole in the view: every pixel whose ray meets the rest plane
//! inside the play area and within the map's reach lies in one of the frame's triangles
//! (their rest points, morphed, on the rest plane). A culled cell
//! whose morphed triangles reached into the view left such a hole at the screen's edge, where
//! the camera background then showed through the water (docs/quality.md, step 28).

use glam::{DVec2, DVec3, DVec4};
use render::frame::FrameContext;

/// The test views over a play area of ±40 m, over the default sea and over a short three-wave
/// sea on a ±30 m table, with that table's own camera (where the hole was found: effects' demo
/// table).
fn scenes() -> Vec<render::Scene> {
    let cameras = render::golden::test_views(40.0, 0x853c_49e6_748f_ea9b, 12);
    let short_sea = ocean::WaveSet {
        gravity: 9.81,
        depth: None,
        waves: [
            ([1.0, 0.0], 0.12, 14.0, 0.0),
            ([0.6, 0.8], 0.10, 9.0, 1.0),
            ([-0.3, 0.95], 0.08, 6.0, 2.0),
        ]
        .map(|(direction, steepness, wavelength, phase)| ocean::Wave {
            direction,
            steepness,
            wavelength,
            phase,
        })
        .to_vec(),
    };
    let table = render::Scene {
        sea: short_sea.into(),
        play_area: [-30.0, -30.0, 30.0, 30.0],
        camera: render::Camera::look_at(DVec3::new(22.0, 26.0, 48.0), DVec3::ZERO, 500.0),
        ..render::golden::test_scene(40.0, Vec::new())
    };
    let mut scenes = vec![table.clone()];
    for (k, camera) in cameras.into_iter().enumerate() {
        scenes.push(render::Scene {
            camera,
            play_area: [-40.0, -40.0, 40.0, 40.0],
            ..render::golden::test_scene(13.0 * k as f64, Vec::new())
        });
        scenes.push(render::Scene {
            camera,
            ..table.clone()
        });
    }
    scenes
}

#[test]
fn every_pixel_of_the_play_area_in_view_has_a_triangle() {
    let mut checked = 0;
    for (k, (scene, size)) in scenes()
        .iter()
        .flat_map(|s| [(s, [128, 96]), (s, [160, 120])])
        .enumerate()
    {
        let frame = FrameContext::new(scene, size, 1.0);
        // Each triangle's rest points (morphed) on the rest plane, local metres.
        let rest = |i: u32| DVec2::from(frame.mesh.vertices[i as usize].rest.map(f64::from));
        let triangles: Vec<[DVec2; 3]> = frame
            .mesh
            .indices
            .chunks(3)
            .map(|t| [rest(t[0]), rest(t[1]), rest(t[2])])
            .collect();
        // Is the rest-plane point p in some triangle?
        let covered = |p: DVec2| {
            triangles.iter().any(|[a, b, c]| {
                let (s1, s2, s3) = (
                    (*b - *a).perp_dot(p - *a),
                    (*c - *b).perp_dot(p - *b),
                    (*a - *c).perp_dot(p - *c),
                );
                (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
            })
        };
        let inv = frame.view_proj.inverse();
        let eye = scene.camera.eye;
        let eye_local = DVec2::new(eye.x, eye.z) - frame.origin;
        let [ax, az, bx, bz] = scene.play_area;
        // The screen's border pixels (where culling cuts) and a coarse grid inside.
        let border = (0..size[0])
            .flat_map(|x| [(x, 0), (x, size[1] - 1)])
            .chain((0..size[1]).flat_map(|y| [(0, y), (size[0] - 1, y)]));
        let grid = (0..size[0])
            .step_by(8)
            .flat_map(|x| (0..size[1]).step_by(8).map(move |y| (x, y)));
        for (x, y) in border.chain(grid) {
            let q = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
            let ndc = DVec2::new(
                q.x / f64::from(size[0]) * 2.0 - 1.0,
                1.0 - q.y / f64::from(size[1]) * 2.0,
            );
            let near = inv * DVec4::new(ndc.x, ndc.y, 0.0, 1.0);
            let far = inv * DVec4::new(ndc.x, ndc.y, 1.0, 1.0);
            let (a, b) = (near.truncate() / near.w, far.truncate() / far.w);
            if (a.y > 0.0) == (b.y > 0.0) {
                continue;
            }
            let hit = a + (b - a) * (a.y / (a.y - b.y));
            let local = DVec2::new(hit.x, hit.z);
            let world = local + frame.origin;
            // Away from the area's edge and the map's by a few cells (the flat rest points
            // meet those edges only within the sea's displacement).
            let inside = world.x > ax + 2.0
                && world.x < bx - 2.0
                && world.y > az + 2.0
                && world.y < bz - 2.0
                && (local - eye_local).abs().max_element() < 0.95 * frame.reach;
            if inside {
                checked += 1;
                assert!(
                    covered(local),
                    "view {k}: pixel ({x}, {y}) over the water at {world} has no triangle"
                );
            }
        }
    }
    assert!(checked > 5000, "{checked} pixels checked");
}
