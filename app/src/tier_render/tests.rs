//! Every field of a tier changes the frame the renderer draws: read back from the frame
//! record and the effect passes' offscreen targets of the sample race at 600 s.

use super::*;

/// The sample race's frame at 600 s at `size` for `tier` (with `budget` wake sources when
/// given instead of the tier's): the record and the offscreen targets' sizes.
fn frame_of(
    tier: &TierRender,
    size: [u32; 2],
) -> (render::FrameReport, effects::passes::OffscreenSizes) {
    let gpu = render::gpu::test_gpu().expect("checked by the caller");
    let race = race::Race::sample();
    let scene = crate::core::scene::scene_at(&race, &ocean::WaveSet::default_sea(), 600.0, None);
    let (mut renderer, fx) = tier
        .renderer(&gpu, Some(&race), &scene, size)
        .expect("renderer");
    let view = crate::bench::offscreen(&gpu, size);
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
