//! Playing against scrubbing, through the app's real per-frame code: one renderer (the window's,
//! `regatta::setup::RaceSetup::renderer`, or the pool's `PoolPlay::render`) draws frame after frame into one
//! surface-like texture while the timeline plays, pauses (the kept still frame re-presented),
//! jumps back and plays on; a fresh renderer then draws only the last time into a fresh
//! texture. The pixels must be equal: nothing drawn, kept or reused in one frame may leak into
//! another (wake buffers, the kept still frame, the effects' reused offscreen textures, the
//! pool's uniforms and rings).

use effects::EffectSet;
use regatta::hud::initial_clock;
use regatta::pool_play::PoolPlay;
use regatta::setup::{Profile, RaceSetup};
use regatta::world::{RaceWorld, race_orbit, race_wake};
use render::gpu::Gpu;
use render::{FRAME_REUSED, OFFSCREEN_FORMAT, OrbitCamera, Renderer};

const SIZE: [u32; 2] = [96, 64];

/// The scene the window draws at `t` (the app core's, from a world built once per call).
fn race_scene(
    race: &race::Race,
    sea: &ocean::WaveSet,
    t: f64,
    o: &mut OrbitCamera,
) -> render::Scene {
    RaceWorld::new(race.clone(), sea.clone()).orbit_scene(t, o)
}

/// A texture like the window's surface on the desktop: drawn into and copied from and to (the
/// renderer keeps still frames only where the target allows copies).
fn surface_like(gpu: &Gpu) -> wgpu::Texture {
    render::gpu::texture_2d(
        &gpu.device,
        "surface-like target",
        SIZE,
        OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
    )
}

/// The window's race renderer, with `regatta render --effects`' scene effects when `effects`.
fn app_renderer(gpu: &Gpu, race: &race::Race, sea: &ocean::WaveSet, effects: bool) -> Renderer {
    let mut r =
        RaceSetup::new(Profile::Desktop).renderer(gpu, OFFSCREEN_FORMAT, race_wake(race).ok());
    if effects {
        let scene = race_scene(race, sea, race.time_span().0, &mut race_orbit());
        effects::passes::add_scene_effects(&mut r, gpu, &scene, SIZE, EffectSet::ALL);
    }
    r
}

/// Plays the sample race through the app's clock and one renderer (play, pause, jump back,
/// play), then draws the last time with a fresh renderer: the two pictures must be equal.
fn played_equals_scrubbed(effects: bool) {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let race = race::Race::sample();
    let sea = ocean::WaveSet::default_sea();
    // From five minutes into the race, where the boats sail and make wakes.
    let mut clock = initial_clock(&race);
    clock.scrub_to(300.0);
    let mut player = app_renderer(&gpu, &race, &sea, effects);
    let target = surface_like(&gpu);
    let view = target.create_view(&Default::default());
    let mut o = race_orbit();
    let mut draw = |player: &mut Renderer, t: f64| {
        let scene = race_scene(&race, &sea, t, &mut o);
        player
            .render(&gpu, &view, SIZE, &scene)
            .expect("the frame draws")
    };
    // Play 8 frames of a quarter second at the app's 8×.
    for _ in 0..8 {
        clock.advance(0.25);
        draw(&mut player, clock.time());
    }
    // Pause: the second still frame is kept, the later ones re-presented from the copy.
    clock.pause();
    let mut still = None;
    for _ in 0..4 {
        still = Some(draw(&mut player, clock.time()));
    }
    let still = still.unwrap();
    assert!(
        still.passes.iter().all(|p| p.reason == FRAME_REUSED),
        "the paused frames were not re-presented: the test would not cover the kept frame"
    );
    // Jump 60 s back, then play on for 6 frames.
    clock.scrub_to(clock.time() - 60.0);
    draw(&mut player, clock.time());
    clock.play();
    for _ in 0..6 {
        clock.advance(0.25);
        draw(&mut player, clock.time());
    }
    let t = clock.time();
    let played = gpu.read_texture(&target).unwrap();

    // Scrubbing straight to t: a fresh renderer, camera and target draw one frame.
    let mut fresh = app_renderer(&gpu, &race, &sea, effects);
    let target = surface_like(&gpu);
    let scene = race_scene(&race, &sea, t, &mut race_orbit());
    fresh
        .render(&gpu, &target.create_view(&Default::default()), SIZE, &scene)
        .expect("the frame draws");
    let scrubbed = gpu.read_texture(&target).unwrap();
    let differ = played
        .pixels()
        .zip(scrubbed.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differ, 0,
        "effects {effects}: {differ} pixels of the played and scrubbed frames at t = {t} differ"
    );
}

#[test]
fn playing_the_race_equals_scrubbing_to_the_same_time() {
    played_equals_scrubbed(false);
}

#[test]
fn playing_the_race_with_every_effect_equals_scrubbing_to_the_same_time() {
    played_equals_scrubbed(true);
}

/// The app's pool frame (`PoolPlay::render`: frame, rings and uniforms at t, drawn by the
/// pool's renderer, the desktop's orbit view) played at 30 frames a second, back and forth,
/// against a fresh pool drawing only the last time: the same rings and uniforms, the same
/// pixels.
#[test]
fn playing_the_pool_equals_scrubbing_to_the_same_time() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let view = PoolPlay::orbit_view(&PoolPlay::orbit(), SIZE);
    let mut player = PoolPlay::new(None);
    let mut renderer = None;
    let target = surface_like(&gpu);
    let target_view = target.create_view(&Default::default());
    let times: Vec<f64> = (0..60)
        .map(|i| 2.0 + i as f64 / 30.0)
        .chain([9.0, 0.5])
        .chain((0..30).map(|i| 3.0 + i as f64 / 30.0))
        .collect();
    let mut played = None;
    for &t in &times {
        let f = player.render(&mut renderer, &gpu, OFFSCREEN_FORMAT, &target_view, view, t);
        played = Some(f);
    }
    let played = played.unwrap();
    let t = *times.last().unwrap();
    assert!(played.pool.counts[1] > 0, "no ripple rings at t = {t}");
    let played_pixels = gpu.read_texture(&target).unwrap();

    let mut fresh = PoolPlay::new(None);
    let target = surface_like(&gpu);
    let scrubbed = fresh.render(
        &mut None,
        &gpu,
        OFFSCREEN_FORMAT,
        &target.create_view(&Default::default()),
        view,
        t,
    );
    // Debug prints every number in shortest round-trip form: equal strings, equal bits.
    assert_eq!(format!("{played:?}"), format!("{scrubbed:?}"));
    let scrubbed_pixels = gpu.read_texture(&target).unwrap();
    assert!(
        played_pixels == scrubbed_pixels,
        "the pool's played and scrubbed pixels at t = {t} differ"
    );
}
