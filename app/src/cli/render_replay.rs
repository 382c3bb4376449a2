//! `regatta render --replay DIR [--frame N]`: the table scene as `regatta run --replay` shows
//! it, headless, over frame N (default 0) of a recorded feed: the race fitted on the feed's
//! table, the feed's camera, `--effects` (all without it, as in the window) over the real
//! image. It goes through the window's own [`FeedView`](crate::desktop::feed::FeedView), so
//! what this draws is what the app draws for that frame. The desktop window module does not
//! exist on Android, and neither does this path there.

use std::path::Path;

use render::effects::EffectSet;

use crate::cli::output::ImageOut;
use crate::cli::render::RenderArgs;
use crate::error::{CliError, CliResult};

#[cfg(not(target_os = "android"))]
pub fn run(
    a: &RenderArgs,
    dir: &Path,
    out: &ImageOut,
    size: [u32; 2],
    effects: Option<EffectSet>,
) -> CliResult {
    use crate::cli::inputs::{drawable_sea, load_race, load_sea};
    use crate::cli::render::{note_unmet_error, print_report};
    use crate::core::scene::{RaceWorld, race_orbit};
    use render::{RenderOptions, Renderer};

    let mut feed = crate::desktop::feed::FeedView::open(dir)?;
    // Without --effects, the window's own set.
    if let Some(effects) = effects {
        feed = feed.with_effects(effects);
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
    let mut scene = world.orbit_scene(t, &mut race_orbit());
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| CliError::new(format!("cannot render: {e}")))?;
    let options = RenderOptions {
        error_px: a.error_px,
        measure_gpu_time: true,
        ..Default::default()
    };
    let mut renderer = Renderer::new(&gpu, render::OFFSCREEN_FORMAT, options);
    let wake = if a.no_wakes {
        None
    } else {
        Some(world.wake()?)
    };
    feed.prepare_frame(
        &gpu,
        &mut renderer,
        render::OFFSCREEN_FORMAT,
        options,
        wake,
        &scene,
        size,
        frame,
    )?;
    feed.apply(&mut scene);
    let (img, report) = render::render_image(&gpu, &mut renderer, &scene, size)
        .map_err(|e| CliError::new(format!("cannot render: {e}")))?;
    out.save(&img)?;
    note_unmet_error(&report);
    print_report(a, &report)
}

#[cfg(target_os = "android")]
pub fn run(
    _a: &RenderArgs,
    _dir: &Path,
    _out: &ImageOut,
    _size: [u32; 2],
    _effects: Option<EffectSet>,
) -> CliResult {
    Err(CliError::new(
        "render --replay draws through the desktop window's feed view, which Android does not build",
    ))
}
