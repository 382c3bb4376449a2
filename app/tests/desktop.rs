//! The desktop app: the timeline's determinism (a frame reached by playing to t equals the frame
//! reached by scrubbing to t) and a smoke test of the real window under Xvfb.

use std::path::PathBuf;
use std::process::Command;
use std::time::{Duration, Instant};

use glam::DVec3;
use regatta::cli::render::{FAR_M, race_wake};
use regatta::desktop::overlay::initial_clock;
use regatta::desktop::race_scene;
use render::{OrbitCamera, RenderOptions, Renderer};

fn orbit() -> OrbitCamera {
    OrbitCamera {
        target: DVec3::ZERO,
        distance: 90.0,
        yaw: 2.4,
        pitch: 0.35,
        far: FAR_M,
    }
}

/// Plays the app's clock for `frames` frames of `dt` wall seconds; returns the race times seen.
fn play(race: &race::Race, frames: usize, dt: f64) -> Vec<f64> {
    let mut clock = initial_clock(race);
    (0..frames)
        .map(|_| {
            clock.advance(dt);
            clock.time()
        })
        .collect()
}

#[test]
fn playing_to_t_and_scrubbing_to_t_give_the_same_scene() {
    let race = race::Race::sample();
    let sea = ocean::WaveSet::default_sea();
    let times = play(&race, 240, 1.0 / 60.0);
    let t = *times.last().unwrap();
    // Playing: the scene of every frame in turn (the orbit's target follows the fleet).
    let mut played_orbit = orbit();
    let mut played = None;
    for &ti in &times {
        played = Some(race_scene(&race, &sea, ti, &mut played_orbit));
    }
    // Scrubbing: one jump from a fresh clock and a fresh orbit.
    let mut clock = initial_clock(&race);
    clock.pause();
    clock.scrub_to(t);
    let scrubbed = race_scene(&race, &sea, clock.time(), &mut orbit());
    assert_eq!(clock.time(), t);
    // Debug prints every f64 in shortest round-trip form: equal strings are bit-equal scenes.
    assert_eq!(format!("{:?}", played.unwrap()), format!("{scrubbed:?}"));
}

#[test]
fn playing_to_t_and_scrubbing_to_t_give_the_same_pixels() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let race = race::Race::sample();
    let sea = ocean::WaveSet::default_sea();
    let size = [96, 64];
    let wake = race_wake(&race).unwrap();
    let new_renderer = || {
        let mut r = Renderer::new(
            &gpu,
            render::OFFSCREEN_FORMAT,
            RenderOptions {
                measure_gpu_time: false,
                ..Default::default()
            },
        );
        r.set_wake(Some(wake.clone()));
        r
    };
    // Playing: one renderer draws 12 frames at 8× (its per-frame state, if it had any, would
    // carry from frame to frame); scrubbing: a fresh renderer draws only the last time.
    let times = play(&race, 12, 0.25);
    let mut player = new_renderer();
    let mut o = orbit();
    let mut last = None;
    for &t in &times {
        let scene = race_scene(&race, &sea, t, &mut o);
        last = Some(
            render::render_image(&gpu, &mut player, &scene, size)
                .unwrap()
                .0,
        );
    }
    let t = *times.last().unwrap();
    let scene = race_scene(&race, &sea, t, &mut orbit());
    let scrubbed = render::render_image(&gpu, &mut new_renderer(), &scene, size)
        .unwrap()
        .0;
    assert!(
        last.unwrap() == scrubbed,
        "the played and scrubbed frames at t = {t} differ"
    );
}

/// Runs the real app under Xvfb for a few frames; it exits by itself and writes a screenshot.
/// Needs xvfb-run and a Vulkan driver: skips without them unless `REGATTA_REQUIRE_GPU=true`.
#[test]
fn the_window_opens_draws_the_race_and_exits_cleanly() {
    let required = render::gpu::gpu_required();
    let has_xvfb = Command::new("xvfb-run").arg("--help").output().is_ok();
    if !has_xvfb {
        assert!(
            !required,
            "REGATTA_REQUIRE_GPU=true but xvfb-run is not installed"
        );
        eprintln!("skipped: xvfb-run is not installed");
        return;
    }
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("desktop_smoke");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let shot = dir.join("window.png");
    let start = Instant::now();
    let mut child = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 640x400x24"])
        .arg(env!("CARGO_BIN_EXE_regatta"))
        .arg("run")
        .env("REGATTA_WINDOW_SIZE", "480x270")
        .env("REGATTA_EXIT_AFTER_FRAMES", "6")
        .env("REGATTA_SCREENSHOT", &shot)
        .env("XDG_RUNTIME_DIR", &dir)
        .spawn()
        .expect("xvfb-run starts");
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(180) {
            let _ = child.kill();
            panic!("the app did not exit by itself within 180 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    assert!(status.success(), "the app exited with {status}");
    let img = image::open(&shot)
        .expect("the app wrote its screenshot")
        .to_rgba8();
    assert_eq!(img.dimensions(), (480, 270));
    // Not blank: many colours, and the picture has structure (luminance spread).
    let lum: Vec<f64> = img
        .pixels()
        .map(|p| 0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2]))
        .collect();
    let mean = lum.iter().sum::<f64>() / lum.len() as f64;
    let sd = (lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64).sqrt();
    let mut colours: Vec<[u8; 3]> = img.pixels().map(|p| [p[0], p[1], p[2]]).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() > 500 && sd > 10.0,
        "a blank-looking screenshot: {} colours, luminance sd {sd:.1}",
        colours.len()
    );
    // The sea fills the middle of the picture: more blue than red there.
    let (mut r, mut b) = (0.0, 0.0);
    for y in 110..150 {
        for x in 100..380 {
            let p = img.get_pixel(x, y);
            r += f64::from(p[0]);
            b += f64::from(p[2]);
        }
    }
    assert!(
        b > r,
        "the middle of the window is not sea-coloured (red {r}, blue {b})"
    );
    // The timeline panel along the bottom is dark and opaque.
    let bottom = (0..480).map(|x| lum[(265 * 480 + x) as usize]).sum::<f64>() / 480.0;
    assert!(
        bottom < 60.0,
        "no timeline panel along the bottom (mean luminance {bottom:.0})"
    );
}
