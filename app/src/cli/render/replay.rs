//! `regatta render --replay DIR [--frame N]`: the table scene as `regatta run --replay` shows
//! it, headless, over frame N (default 0) of a recorded feed: the race fitted on the feed's
//! table, the feed's camera, `--effects` (all without it, as in the window) over the real
//! image. It goes through the window's own [`FeedView`](crate::feed::FeedView) (and
//! [`TableFrame`](crate::feed::TableFrame)), so what this draws is what the app draws for that
//! frame.

use std::path::Path;

use effects::EffectSet;

use crate::cli::render::{RenderArgs, note_unmet_error, print_report};
use crate::core::scene::RaceWorld;
use crate::error::{CliError, CliResult};
use crate::feed::{FeedView, TableFrame};
use crate::setup::inputs::{drawable_sea, load_race, load_sea};
use crate::setup::output::ImageOut;

pub fn run(
    a: &RenderArgs,
    dir: &Path,
    out: &ImageOut,
    size: [u32; 2],
    effects: Option<EffectSet>,
    tier: Option<quality::Tier>,
    overlays: &crate::scene_overlay::OverlaySettings,
) -> CliResult {
    use render::{RenderOptions, Renderer};

    let mut feed = FeedView::open(dir)?;
    feed.set_water(a.water.look(feed.water())?);
    // Without --effects, the window's own set; with --tier, the tier's effects and sizes.
    if let Some(effects) = effects {
        feed = feed.with_effects(effects);
    }
    let tier = tier.map(crate::tier_render::TierRender::of);
    if let Some(tier) = &tier {
        feed = feed.with_quality(&tier.ar);
    }
    let frame = a.frame.unwrap_or(0);
    if frame >= feed.len() {
        return Err(CliError::new(format!(
            "--frame {frame} is past the feed's last frame: {} has frames 0 to {}",
            input::show_path(dir),
            feed.len() - 1
        )));
    }
    let world = RaceWorld::new(load_race(&a.race)?, drawable_sea(load_sea(a.sea.as_ref())?));
    let t = a.t.unwrap_or_else(|| world.middle_time());
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| CliError::new(format!("cannot render: {e}")))?;
    let options = match &tier {
        Some(tier) => RenderOptions {
            measure_gpu_time: true,
            ..tier.options
        },
        None => RenderOptions {
            error_px: a.error_px,
            measure_gpu_time: true,
            ..Default::default()
        },
    };
    let mut renderer = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, options);
    let wake = match (&tier, a.no_wakes) {
        (_, true) => None,
        (Some(tier), false) => Some(tier.race_wake(&world.race)?),
        (None, false) => Some(world.wake()?),
    };
    if let Some(tier) = &tier {
        // The feed builds its renderer on the first frame: build it, then set the tier's
        // options and wake source budget on it (the draw below keeps that renderer).
        feed.prepare_frame(
            &gpu,
            &mut renderer,
            render::OFFSCREEN_FORMAT,
            options,
            wake.clone(),
            world.race_bounds,
            size,
            frame,
        )?;
        tier.apply_to(&mut renderer);
    }
    let table = TableFrame {
        world: &world,
        t,
        size,
        frame,
        overlays: Some(overlays),
    };
    let (img, report) = table.draw(&mut feed, &gpu, &mut renderer, options, wake, |_| {})?;
    out.save(&img)?;
    note_unmet_error(&report);
    print_report(a, &report)
}
