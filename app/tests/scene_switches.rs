//! Every switch of the Scene panel's Effects changes what is drawn, live, in one renderer (the
//! window's way): with all effects on, switching any one off through the panel's settings
//! (`regatta::panels::SceneApplier`, what the window calls each frame) changes the picture and
//! the frame report says the effect was "not requested"; switching it back on gives the first
//! picture again. Before, only the wakes' switch acted: the effect passes took their set once.
//!
//! Needs a GPU (lavapipe in CI); skipped without one unless `REGATTA_REQUIRE_GPU=true`.

use effects::{EffectSet, demo_table_scene, passes::add_scene_effects};
use regatta::panels::{SceneApplier, effect_toggles};
use regatta::setup::{Profile, RaceSetup};
use regatta::world::RaceWorld;
use render::{OFFSCREEN_FORMAT, OrbitCamera, Renderer, Scene};
use ui::SceneSettings;

const SIZE: [u32; 2] = [320, 240];

fn draw(gpu: &render::Gpu, r: &mut Renderer, scene: &Scene) -> (image::RgbaImage, String) {
    let (img, report) = gpu
        .render_offscreen(SIZE, OFFSCREEN_FORMAT, |view| {
            r.render(gpu, view, SIZE, scene).expect("the frame draws")
        })
        .unwrap();
    let reasons = report
        .passes
        .iter()
        .map(|p| p.reason.clone())
        .collect::<Vec<_>>()
        .join("; ");
    (img, reasons)
}

fn differing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 2))
        .count()
}

fn set(settings: &mut SceneSettings, key: &str, on: bool) {
    for t in &mut settings.effects {
        if t.key == key {
            t.enabled = on;
        }
    }
}

#[test]
fn every_effect_switch_changes_the_picture() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let scene = demo_table_scene(1.0);
    let mut r = Renderer::new(&gpu, OFFSCREEN_FORMAT, Default::default());
    let handle = add_scene_effects(&mut r, &gpu, &scene, SIZE, EffectSet::ALL);
    let mut settings = SceneSettings::new(effect_toggles(true));
    let mut applier = SceneApplier::new(None);
    applier.apply(&settings, &mut r, Some(&handle));
    let (all_on, reasons) = draw(&gpu, &mut r, &scene);
    assert!(!reasons.contains("not requested"), "{reasons}");
    for e in effects::Effect::ALL {
        set(&mut settings, e.name(), false);
        applier.apply(&settings, &mut r, Some(&handle));
        let (off, reasons) = draw(&gpu, &mut r, &scene);
        assert!(
            reasons.contains(&format!("{e} skipped: not requested"))
                || (e == effects::Effect::Background && reasons.contains("not requested")),
            "{e}: {reasons}"
        );
        let d = differing_pixels(&all_on, &off);
        assert!(d > 50, "switching {e} off changed only {d} pixels");
        set(&mut settings, e.name(), true);
        applier.apply(&settings, &mut r, Some(&handle));
        let (back, _) = draw(&gpu, &mut r, &scene);
        assert_eq!(differing_pixels(&all_on, &back), 0, "{e} back on");
    }
}

#[test]
fn the_wakes_switch_changes_the_picture() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let race = race::Race::sample();
    let sea = ocean::WaveSet::default_sea();
    let mut orbit = OrbitCamera {
        target: glam::DVec3::ZERO,
        distance: 90.0,
        yaw: 2.4,
        pitch: 0.5,
        far: regatta::world::FAR_M,
    };
    let world = RaceWorld::new(race.clone(), sea);
    let scene = world.orbit_scene(300.0, &mut orbit);
    let mut r =
        RaceSetup::new(Profile::Desktop).renderer(&gpu, OFFSCREEN_FORMAT, world.wake().ok());
    let mut settings = SceneSettings::new(effect_toggles(false));
    let mut applier = SceneApplier::new(regatta::world::race_wake(&race).ok());
    let (on, _) = draw(&gpu, &mut r, &scene);
    set(&mut settings, "wakes", false);
    applier.apply(&settings, &mut r, None);
    let (off, _) = draw(&gpu, &mut r, &scene);
    let d = differing_pixels(&on, &off);
    assert!(d > 50, "switching the wakes off changed only {d} pixels");
}
