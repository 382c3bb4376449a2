//! `regatta render --replay DIR [--frame N]`: the table scene as `regatta run --replay` shows
//! it, headless, over frame N (default 0) of a recorded feed: the race fitted on the feed's
//! table, the feed's camera, `--effects` (all without it, as in the window) over the real
//! image. It goes through the window's own [`FeedView`](crate::core::feed::FeedView) (and
//! [`TableFrame`](crate::core::feed::TableFrame)), so what this draws is what the app draws for that
//! frame.

use std::path::Path;

use crate::cli::render::{RenderArgs, note_unmet_error, print_report};
use crate::core::feed::{FeedView, TableFrame};
use crate::error::{AppError, AppResult};
use crate::setup::RaceSetup;
use crate::setup::output::ImageOut;

pub fn run(
    a: &RenderArgs,
    dir: &Path,
    out: &ImageOut,
    size: [u32; 2],
    setup: RaceSetup,
) -> AppResult {
    let mut feed = FeedView::open(dir)?;
    feed.set_water(a.water.look(feed.water())?);
    // Without --effects, the window's own set; with --tier, the tier's effects and sizes.
    if let Some(effects) = setup.effects {
        feed = feed.with_effects(effects);
    }
    if let Some(tier) = &setup.tier {
        feed = feed.with_quality(&tier.ar);
    }
    let frame = a.frame.unwrap_or(0);
    if frame >= feed.len() {
        return Err(AppError::new(format!(
            "--frame {frame} is past the feed's last frame: {} has frames 0 to {}",
            input::show_path(dir),
            feed.len() - 1
        )));
    }
    let world = RaceSetup::load_world(&a.race, a.sea.as_ref())?;
    let t = a.t.unwrap_or_else(|| world.middle_time());
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("cannot render: {e}")))?;
    // The feed builds the renderer through the set-up on its first frame.
    let mut renderer = setup.renderer(&gpu, render::OFFSCREEN_FORMAT, None);
    let wake = setup.wake(&world.race)?;
    let table = TableFrame {
        world: &world,
        t,
        size,
        frame,
        overlays: Some(&setup.overlays),
    };
    let (img, report) = table.draw(&mut feed, &gpu, &mut renderer, &setup, wake, |_| {})?;
    out.save(&img)?;
    note_unmet_error(&report);
    print_report(a, &report)
}
