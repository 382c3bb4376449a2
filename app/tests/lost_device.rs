//! A device lost before its lost callback ran, on both profiles (the desktop's `App::desktop`
//! and the phone's `App::phone`), headless on lavapipe with offscreen windows.
//!
//! wgpu runs a device's lost callback only from a poll (`Device::destroy` marks the device
//! invalid and the callback waits for a maintenance with the queue empty; a loss the driver
//! reports to a submit runs it there, in the middle of a frame). Until then every write to
//! the device is refused: `Queue::write_buffer_with` returns `None`, and egui-wgpu's
//! `Renderer::update_buffers` panicked on that `None` ("Failed to create staging buffer for
//! index data"), killing the app with the race the user watched. On Android the callback
//! comes only from a poll, and a device can be lost at any time (a driver reset, the app in
//! the background under memory pressure).
//!
//! Each test draws the race paused with a boat selected, loses the device without a poll,
//! and draws on: no frame panics, the device is rebuilt on OpenGL ES (the banner's note says
//! the GPU was lost), the race time and the selection are kept, and the rebuilt frame shows
//! the same race: the labels and hulls are placed where they were (the same boats at the
//! same time under the same camera), as many labels show their team's colour bar (the race
//! file's colour) as before the loss, and where the boats are the picture is the one before
//! the loss (lavapipe's Vulkan then, llvmpipe's OpenGL ES now: a mean difference of 0.00 of
//! 255 measured), within a quarter of what the race 30 s later differs by (61 of 255).

mod common;

use regatta::core::app::{App, DesktopStart};
use regatta::hud::SceneChoice;
use regatta::scene_overlay::labels::{BAR_PT, Hull};
use regatta::scene_overlay::paint::colour32;
use regatta::setup::RaceSetup;

const SIZE: [u32; 2] = [360, 480];

fn world() -> regatta::world::RaceWorld {
    RaceSetup::world(race::Race::sample(), ocean::WaveSet::default_sea())
}

/// The app in an offscreen window at one pixel per point, the side panels off (the scene
/// free for the labels).
fn shown(mut app: App) -> App {
    app.panels.show_leaderboard = false;
    app.panels.show_perf = false;
    common::shown(app, SIZE)
}

fn desktop() -> App {
    shown(App::desktop(
        world(),
        DesktopStart {
            feed: None,
            water: render::water_look::WaterLook::default(),
            tier: Some(quality::Tier::Low),
            scene: SceneChoice::Race,
            pool_sea: None,
        },
    ))
}

fn phone() -> App {
    let mut app = App::phone(world(), Box::new(regatta::core::ar::NoAr));
    app.tiers = regatta::tier_control::TierControl::new(quality::Tier::Low, true);
    shown(app)
}

fn screenshot(app: &App) -> image::RgbaImage {
    app.screenshot()
        .expect("an offscreen window")
        .expect("the frame reads back")
}

/// Mean absolute difference of the colour channels over the boats (the pixels within each
/// hull's pick circle, where the race renderer drew the hulls and sails), in 8-bit steps.
fn difference_on_boats(hulls: &[Hull], a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let (mut sum, mut n) = (0u64, 0u64);
    for (x, y, p) in a.enumerate_pixels() {
        let c = [f64::from(x) + 0.5, f64::from(y) + 0.5];
        if hulls
            .iter()
            .any(|h| (h.centre[0] - c[0]).hypot(h.centre[1] - c[1]) <= h.radius)
        {
            let q = b.get_pixel(x, y);
            sum += (0..3)
                .map(|k| u64::from(p.0[k].abs_diff(q.0[k])))
                .sum::<u64>();
            n += 3;
        }
    }
    assert!(n > 0, "no boat in the frame");
    sum as f64 / n as f64
}

/// How many of the placed labels show their team's colour bar (egui's sRGB of the race
/// file's linear colour) at their left edge in `img`.
fn team_bars_seen(app: &App, img: &image::RgbaImage) -> usize {
    app.overlays
        .placed_labels()
        .iter()
        .filter(|l| {
            let x = (l.rect[0] + 0.5 * BAR_PT) as u32;
            let y = (0.5 * (l.rect[1] + l.rect[3])) as u32;
            if x >= img.width() || y >= img.height() {
                return false;
            }
            let want = colour32(l.colour, 255).to_array();
            let got = img.get_pixel(x, y).0;
            (0..3).all(|k| (i32::from(got[k]) - i32::from(want[k])).abs() <= 12)
        })
        .count()
}

fn label_rects(app: &App) -> Vec<(usize, [f64; 4])> {
    let labels = app.overlays.placed_labels();
    labels.iter().map(|l| (l.boat, l.rect)).collect()
}

fn a_device_lost_before_its_callback_draws_on_and_comes_back(mut app: App) {
    let dt = 1.0 / 30.0;
    app.frame(dt);
    let later = app.race_time() + 30.0;
    // The race 30 s on, for scale: what another race picture differs by.
    app.panels.clock.pause();
    let t = app.race_time();
    app.panels.clock.scrub_to(later);
    app.frame(dt);
    let other = screenshot(&app);
    app.panels.clock.scrub_to(t);
    app.frame(dt);
    let hull = app.overlays.hulls()[0];
    app.overlays.click(hull.centre);
    assert_eq!(app.overlays.selected(), [hull.boat]);
    app.frame(dt);
    let before = screenshot(&app);
    let labels = label_rects(&app);
    let hulls = app.overlays.hulls().to_vec();
    assert!(!labels.is_empty(), "no label placed before the loss");
    let bars_before = team_bars_seen(&app, &before);
    assert!(bars_before > 0, "no team bar before the loss");
    assert_eq!(app.graphics_note(), None, "{:?}", app.describe_gpu());

    app.lose_device_unpolled();
    // A second of frames: egui fades the new context's areas in over a few tenths.
    for _ in 0..30 {
        app.frame(dt);
    }
    assert_eq!(
        app.graphics_note(),
        Some("The GPU was lost; drawing with OpenGL ES."),
        "not rebuilt: {:?}",
        app.describe_gpu()
    );
    assert!(
        app.describe_gpu().is_some_and(|d| d.contains("Gl")),
        "{:?}",
        app.describe_gpu()
    );
    assert_eq!(app.race_time(), t, "the race time was lost with the device");
    assert_eq!(
        app.overlays.selected(),
        [hull.boat],
        "the selection was lost"
    );
    let after = screenshot(&app);
    assert_eq!(
        label_rects(&app),
        labels,
        "the labels moved: not the same boats at the same time under the same camera"
    );
    let centres = |h: &[Hull]| h.iter().map(|h| (h.boat, h.centre)).collect::<Vec<_>>();
    assert_eq!(
        centres(app.overlays.hulls()),
        centres(&hulls),
        "the hulls moved"
    );
    let bars = team_bars_seen(&app, &after);
    assert_eq!(
        bars,
        bars_before,
        "of the {} labels' team bars, {bars_before} were in the frame before the loss, \
         {bars} in the rebuilt one",
        labels.len()
    );
    // The panels are laid out anew on the new egui context (their heights may differ by a
    // few points); the race under them is compared where the boats are.
    let same = difference_on_boats(&hulls, &after, &before);
    let moved = difference_on_boats(&hulls, &other, &before);
    assert!(
        same < 0.25 * moved,
        "on the boats the rebuilt frame differs from the frame before the loss by {same:.2} \
         (the race 30 s later by {moved:.2})"
    );
    eprintln!("on the boats: rebuilt vs before {same:.2}, 30 s later vs before {moved:.2}");
}

#[test]
fn desktop_a_device_lost_before_its_callback_draws_on_and_comes_back() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    a_device_lost_before_its_callback_draws_on_and_comes_back(desktop());
}

#[test]
fn phone_a_device_lost_before_its_callback_draws_on_and_comes_back() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    a_device_lost_before_its_callback_draws_on_and_comes_back(phone());
}
