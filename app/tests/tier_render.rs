//! Every field of a tier changes the frame the renderer draws: read back from the frame
//! record and the effect passes' offscreen targets of the sample race at 600 s. (Outside the
//! crate: it drives the tier through the scene set-up and the panels, which sit above
//! `tier_render`.)

use effects::passes::EffectsHandle;
use quality::Tier;
use regatta::tier_render::*;
use render::Renderer;

/// The sample race's frame at 600 s at `size` for `tier` (with `budget` wake sources when
/// given instead of the tier's): the record and the offscreen targets' sizes.
fn frame_of(
    tier: &TierRender,
    size: [u32; 2],
) -> (render::FrameReport, effects::passes::OffscreenSizes) {
    let gpu = render::gpu::test_gpu().expect("checked by the caller");
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), 600.0, None);
    let (mut renderer, fx) =
        regatta::setup::RaceSetup::tier_renderer(tier, &gpu, Some(&race), &scene, size)
            .expect("renderer");
    let view = render::gpu::texture_2d(
        &gpu.device,
        "tier test frame",
        size,
        render::OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    )
    .create_view(&Default::default());
    let report = renderer.render(&gpu, &view, size, &scene).expect("frame");
    (report, fx.offscreen_sizes())
}

/// The AR water pass's decision for `effect` in the record: "runs" or "skipped".
fn decision(report: &render::FrameReport, effect: &str) -> bool {
    let water = report
        .passes
        .iter()
        .find(|p| p.name == "ar_water")
        .expect("the AR water pass");
    let runs = water.reason.contains(&format!("{effect} runs"));
    let skipped = water.reason.contains(&format!("{effect} skipped"));
    assert!(runs != skipped, "{effect}: {}", water.reason);
    runs
}

#[test]
fn each_tier_setting_shows_in_the_frame() {
    if render::gpu::test_gpu().is_none() {
        return;
    }
    let size = [240, 160];
    let mut sources = Vec::new();
    for tier in Tier::ALL {
        let t = TierRender::of(tier);
        let s = tier.settings();
        let (report, offscreen) = frame_of(&t, size);
        // Render scale: the record's size is the drawn frame's.
        let drawn = size.map(|v| (f64::from(v) * s.render_scale).round() as u32);
        assert_eq!(report.size, drawn, "{tier}");
        // Clip-map error target, in the drawn frame's pixels.
        assert_eq!(report.clipmap.error_target_px, s.error_px, "{tier}");
        // Which effects run, the flow map among them.
        for e in effects::Effect::ALL {
            if e == effects::Effect::Background {
                let bg = report.passes.iter().find(|p| p.name == "background");
                assert!(bg.is_some_and(|p| p.ran), "{tier}: background");
                continue;
            }
            assert_eq!(
                decision(&report, e.name()),
                s.effects.contains(&e.name()),
                "{tier}: {e}"
            );
        }
        // Reflection texture: the fraction of the drawn frame per side.
        let refl = drawn.map(|v| (f64::from(v) * s.reflection_fraction).round() as u32);
        assert_eq!(offscreen.reflection_px, Some(refl), "{tier}");
        // Caustics: the area-ratio map at the tier's cells, or the cheap tier (no map).
        let map = s.effects.contains(&"caustics") && !s.cheap_caustics;
        assert_eq!(
            offscreen.caustic_map_cells,
            map.then_some(s.caustic_resolution.1 as u32),
            "{tier}"
        );
        // Wake sources: within the tier's budget, and without the budget the count of its
        // spacing.
        let wakes = report.wakes.expect("the race has wakes");
        assert!(wakes.sources <= s.wake_source_budget as usize, "{tier}");
        let unbounded = TierRender {
            wake_source_budget: usize::MAX,
            ..t.clone()
        };
        let all = frame_of(&unbounded, size).0.wakes.expect("wakes");
        assert_eq!(all.dropped, 0);
        assert_eq!(
            wakes.sources,
            all.sources.min(s.wake_source_budget as usize),
            "{tier}"
        );
        assert_eq!(wakes.dropped, all.sources - wakes.sources, "{tier}");
        sources.push((s.wake_spacing_radii, all.sources));
    }
    // Coarser spacing emits fewer sources: about in inverse proportion (a boat's sources are
    // its track length over the spacing, the time rule adding a few at low speed).
    for pair in sources.windows(2) {
        let ((sa, na), (sb, nb)) = (pair[0], pair[1]);
        if sa > sb {
            let ratio = nb as f64 / na as f64;
            assert!(
                ratio > 0.6 * sa / sb && ratio < 1.2 * sa / sb,
                "{sa} R: {na} sources, {sb} R: {nb}"
            );
        } else {
            assert_eq!(na, nb);
        }
    }
}

#[test]
fn a_tier_by_name() {
    assert_eq!(parse_tier("medium").unwrap(), Tier::Medium);
    let e = parse_tier("max\n").unwrap_err().to_string();
    assert!(
        e.contains("low, medium, high, ultra") && !e.contains('\n'),
        "{e}"
    );
}

/// A frame's record without what a run measures (GPU times, shader invocation counts).
fn settled(mut r: render::FrameReport) -> render::FrameReport {
    r.gpu_ms = None;
    r.shader_invocations.clear();
    for p in &mut r.passes {
        p.gpu_ms = None;
        p.offscreen_gpu_ms = None;
    }
    r
}

/// The sample race at 600 s drawn by `renderer` into a fresh texture: record, offscreen
/// targets, pixels.
fn draw(
    gpu: &render::Gpu,
    renderer: &mut Renderer,
    fx: &EffectsHandle,
    scene: &render::Scene,
    size: [u32; 2],
) -> (
    render::FrameReport,
    effects::passes::OffscreenSizes,
    image::RgbaImage,
) {
    let texture = render::gpu::texture_2d(
        &gpu.device,
        "tier frame",
        size,
        render::OFFSCREEN_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let view = texture.create_view(&Default::default());
    let report = renderer.render(gpu, &view, size, scene).expect("frame");
    let img = gpu.read_texture(&texture).expect("read back");
    (settled(report), fx.offscreen_sizes(), img)
}

#[test]
fn a_live_tier_change_draws_the_frame_of_a_renderer_built_at_that_tier() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let size = [240, 160];
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), 600.0, None);
    // Down across every setting, and back up (the caustic tier, map cells, reflection size,
    // effects, spacing and budget all change both ways).
    for (from, to) in [(Tier::Ultra, Tier::Low), (Tier::Low, Tier::High)] {
        let (mut live, live_fx) = regatta::setup::RaceSetup::tier_renderer(
            &TierRender::of(from),
            &gpu,
            Some(&race),
            &scene,
            size,
        )
        .expect("renderer");
        let before = draw(&gpu, &mut live, &live_fx, &scene, size);
        // The phone's way: a Scene panel without switches, through the one tier path.
        let mut settings = ui::SceneSettings::new(Vec::new());
        let mut applier = regatta::panels::SceneApplier::new(live.wake().cloned());
        let fx = Some(&live_fx);
        assert!(
            applier
                .follow_tier(to, &mut settings, &gpu, &mut live, fx, &race)
                .is_some()
        );
        let after = draw(&gpu, &mut live, &live_fx, &scene, size);
        let (mut fresh, fresh_fx) = regatta::setup::RaceSetup::tier_renderer(
            &TierRender::of(to),
            &gpu,
            Some(&race),
            &scene,
            size,
        )
        .expect("renderer");
        let want = draw(&gpu, &mut fresh, &fresh_fx, &scene, size);
        assert_ne!(before.0, want.0, "{from} → {to}: the tiers' frames differ");
        // The record: size (render scale), clip-map error, every pass's decision with its
        // reasons (which effects run), the wake sources drawn and dropped (spacing, budget).
        assert_eq!(after.0, want.0, "{from} → {to}");
        // The reflection texture's size and the caustic map's cells.
        assert_eq!(after.1, want.1, "{from} → {to}");
        // The pixels.
        let differ = after
            .2
            .pixels()
            .zip(want.2.pixels())
            .filter(|(a, b)| a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > 2))
            .count();
        assert_eq!(
            differ, 0,
            "{from} → {to}: pixels differ by more than 2 of 255"
        );
    }
}

/// The window's way: the Scene panel's switches and wakes (`SceneApplier`, applied every frame)
/// over a renderer built at `ultra`; a change to `low` through them draws the frame of a
/// renderer built at `low`, and the switches show `low`'s effects.
#[test]
fn a_tier_through_the_scene_panels_switches_draws_that_tiers_frame() {
    let Some(gpu) = render::gpu::test_gpu() else {
        return;
    };
    let size = [240, 160];
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), 600.0, None);
    let (mut live, fx) = regatta::setup::RaceSetup::tier_renderer(
        &TierRender::of(Tier::Ultra),
        &gpu,
        Some(&race),
        &scene,
        size,
    )
    .expect("renderer");
    let mut settings = ui::SceneSettings::new(regatta::panels::effect_toggles(true));
    let mut applier = regatta::panels::SceneApplier::new(live.wake().cloned());
    applier.apply(&settings, &mut live, Some(&fx));
    draw(&gpu, &mut live, &fx, &scene, size);
    let low = TierRender::of(Tier::Low);
    applier
        .apply_tier(&mut settings, &low, &gpu, &mut live, Some(&fx), &race)
        .expect("the tier applies");
    // The next frame, as the window draws it: the switches applied first.
    applier.apply(&settings, &mut live, Some(&fx));
    let after = draw(&gpu, &mut live, &fx, &scene, size);
    let (mut fresh, fresh_fx) =
        regatta::setup::RaceSetup::tier_renderer(&low, &gpu, Some(&race), &scene, size)
            .expect("renderer");
    let want = draw(&gpu, &mut fresh, &fresh_fx, &scene, size);
    assert_eq!(after.0, want.0);
    assert_eq!(after.1, want.1);
    assert_eq!(after.2.as_raw(), want.2.as_raw());
    for e in effects::Effect::ALL {
        assert_eq!(
            settings.effect(e.name()),
            Tier::Low.settings().effects.contains(&e.name()),
            "{e}"
        );
    }
    assert!(settings.effect("wakes"));
}
