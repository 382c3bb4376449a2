//! `regatta render`: one frame, headless, to a PNG (or JPEG); the frame planner's record as
//! JSON on stdout (and in `--report FILE.json`). With `--replay DIR [--frame N]`, the race on
//! the table of a recorded feed, drawn over that frame ([`replay`]).

use std::path::PathBuf;

use clap::Args;
use glam::{DVec2, DVec3};
use render::Camera;

use crate::setup::inputs::{drawable_sea, load_sea, parse_size_in};
use crate::setup::output::{ImageOut, write_text};
use crate::setup::{Profile, RaceSetup};

pub mod clip;
pub mod replay;
use crate::error::{AppError, AppResult};
use crate::world::FAR_M;

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Image file to write: .png or .jpg; or a clip, .gif, with --from and --to (written whole
    /// or not at all; .mp4 is refused: no encoder in this build).
    #[arg(long)]
    pub out: PathBuf,
    /// Race files (native race JSON, maxSail JSON, GPX, CSV logs and exports, Expedition, NMEA
    /// 0183, SailGP / AC race XML, FIT, TCX, KML / KMZ, NMEA 2000 logs: candump, Actisense CSV,
    /// canboat JSON; several combine into one race); the embedded sample race without it.
    #[arg(long, num_args = 1..)]
    pub race: Vec<PathBuf>,
    /// Sea file (JSON); the embedded default sea without it.
    #[arg(long)]
    pub sea: Option<PathBuf>,
    /// Race time in seconds since the start; the middle of the race without it.
    #[arg(long, allow_negative_numbers = true)]
    pub t: Option<f64>,
    /// Image size, WIDTHxHEIGHT pixels.
    #[arg(long, default_value = "1280x720", allow_hyphen_values = true)]
    pub size: String,
    /// Camera: EYE_X,EYE_Y,EYE_Z,TARGET_X,TARGET_Y,TARGET_Z in race metres (y up); without
    /// it the camera frames the fleet.
    #[arg(long, allow_hyphen_values = true)]
    pub camera: Option<String>,
    /// Clip-map screen-space error target, pixels (0.1 to 100).
    #[arg(long, default_value_t = render::renderer::DEFAULT_ERROR_PX, allow_negative_numbers = true)]
    pub error_px: f64,
    /// Also write the frame record (JSON) to this file.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// AR effects over a (synthetic) camera frame: a comma-separated list of background,
    /// reflection, refraction, caustics, flowmap, or all / none; without it, the water only.
    #[arg(long)]
    pub effects: Option<String>,
    /// Which scene: the race, or the tiled pool after a 2018 WebGL pool project (CS114) (`--camera` then in pool
    /// metres, `--sea` replacing the pool's waves).
    #[arg(long, value_enum, default_value_t = SceneKind::Race)]
    pub scene: SceneKind,
    /// Draw no boat wakes.
    #[arg(long)]
    pub no_wakes: bool,
    /// Race overlays: a comma-separated list of labels, trails, course, lines, wind, or all /
    /// none; all without it (docs/overlays.md).
    #[arg(long, value_name = "LIST")]
    pub overlays: Option<String>,
    /// The real sea's water type, depth and turbidity (the AR effects' water: `--replay`,
    /// `--effects`).
    #[command(flatten)]
    pub water: crate::water::WaterArgs,
    /// A recorded camera feed (replay folder, TUM RGB-D folder, or `synth`): the race fitted on
    /// its table and drawn over one of its frames, as `regatta run --replay` shows it.
    #[arg(long, value_name = "DIR")]
    pub replay: Option<PathBuf>,
    /// Which frame of `--replay`, from 0.
    #[arg(long, value_name = "N", requires = "replay", allow_negative_numbers = true,
        value_parser = crate::cli::inputs::whole_number::<usize>("from 0 to the feed's last frame"))]
    pub frame: Option<usize>,
    /// A quality tier (low, medium, high, ultra; docs/quality.md): its render scale, clip-map
    /// error target, AR effects and their sizes, wake spacing and budget, and which of the
    /// race overlays it draws (its overlay detail; docs/overlays.md, "Tiers").
    #[arg(long, conflicts_with_all = ["effects", "error_px"])]
    pub tier: Option<String>,
    /// A clip's first race time, seconds since the start (with --to and a .gif --out).
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub from: Option<f64>,
    /// A clip's last race time, seconds since the start.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    pub to: Option<f64>,
    /// A clip's frames per second of race time (0.1 to 50; 15 without it).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub fps: Option<f64>,
}

/// Finest clip-map error target `--error-px` accepts, pixels. Finer targets are invisible
/// (a tenth of a pixel moves no pixel centre's sample by more than a tenth of its footprint)
/// and the clip-map's finest cells cannot meet them: 1e-9 px took 38 s and met 0.059 px.
pub const MIN_ERROR_PX: f64 = 0.1;
/// Coarsest `--error-px`, pixels: a mesh 100 pixels off is no longer the sea.
pub const MAX_ERROR_PX: f64 = 100.0;

/// `--error-px` within [`MIN_ERROR_PX`, `MAX_ERROR_PX`].
pub fn check_error_px(px: f64) -> AppResult {
    if (MIN_ERROR_PX..=MAX_ERROR_PX).contains(&px) {
        Ok(())
    } else {
        Err(AppError::new(format!(
            "--error-px {} is outside {MIN_ERROR_PX} to {MAX_ERROR_PX} pixels: finer targets are invisible and beyond what the clip-map can meet",
            input::show_number(px)
        )))
    }
}

/// The clip-map's worst level error against the target: a note on stderr when the map could
/// not meet it (too few levels or cells for the view), so the record is not taken as met.
pub fn note_unmet_error(report: &render::FrameReport) {
    let asked = report.clipmap.error_target_px;
    let met = report
        .clipmap
        .per_level
        .iter()
        .map(|l| l.error_bound_px)
        .fold(0.0, f64::max);
    if met > asked * (1.0 + 1e-9) {
        eprintln!(
            "regatta render: the clip-map meets {met:.3} px, not the {asked} px asked (its levels and cells do not reach further for this view)"
        );
    }
}

pub use crate::setup::SceneKind;

/// Parse `WIDTHxHEIGHT` (each 1..=8192).
pub fn parse_size(s: &str) -> AppResult<[u32; 2]> {
    parse_size_in(
        s,
        1..=8192,
        "WIDTHxHEIGHT with each between 1 and 8192 pixels",
    )
}

/// Whether two output paths name one file: equal as given, or equal once their folders are
/// resolved (`x.png` and `./x.png`; a file that does not exist yet has no canonical path).
fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    let resolved = |p: &std::path::Path| {
        let dir = p.parent().filter(|d| !d.as_os_str().is_empty());
        let dir = dir.map_or_else(|| std::path::PathBuf::from("."), |d| d.to_path_buf());
        std::fs::canonicalize(dir)
            .ok()
            .zip(p.file_name())
            .map(|(d, f)| d.join(f))
    };
    a == b || matches!((resolved(a), resolved(b)), (Some(x), Some(y)) if x == y)
}

/// Parse `--camera` (six finite numbers; the eye must differ from the target and not look
/// straight down the vertical).
pub fn parse_camera(s: &str, far: f64) -> AppResult<Camera> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            AppError::new(format!(
                "--camera \"{s}\" is not six numbers EYE_X,EYE_Y,EYE_Z,TARGET_X,TARGET_Y,TARGET_Z"
            ))
        })?;
    if v.len() != 6 || v.iter().any(|x| !x.is_finite()) {
        return Err(AppError::new(format!(
            "--camera \"{s}\" needs exactly six finite numbers EYE_X,EYE_Y,EYE_Z,TARGET_X,TARGET_Y,TARGET_Z"
        )));
    }
    let max = crate::cli::probe::MAX_WORLD_M;
    if v.iter().any(|x| x.abs() > max) {
        return Err(AppError::new(format!(
            "--camera \"{s}\" lies outside the world: every coordinate must lie within ±{max:e} m, as probe's --at"
        )));
    }
    let eye = DVec3::new(v[0], v[1], v[2]);
    let target = DVec3::new(v[3], v[4], v[5]);
    let d = target - eye;
    if d.length() < 1e-6 || DVec2::new(d.x, d.z).length() < 1e-6 * d.length() {
        return Err(AppError::new(format!(
            "--camera \"{s}\": the eye must differ from the target and not look straight up or down"
        )));
    }
    Ok(Camera::look_at(eye, target, far))
}

pub fn run(a: RenderArgs) -> AppResult {
    if let Some(format) = clip::clip_format(&a.out) {
        return clip::run(&a, format);
    }
    if a.from.is_some() || a.to.is_some() || a.fps.is_some() {
        return Err(AppError::new(
            "--from, --to and --fps make a clip: --out must name a .gif file",
        ));
    }
    let size = parse_size(&a.size)?;
    let out = ImageOut::new(&a.out, "--out")?;
    let effects = a
        .effects
        .as_deref()
        .map(effects::EffectSet::parse)
        .transpose()
        .map_err(AppError::new)?;
    if let Some(t) = a.t {
        crate::cli::inputs::check_race_time(t)?;
    }
    if let Some(report) = &a.report
        && same_file(&a.out, report)
    {
        return Err(AppError::new(format!(
            "--out and --report are the same file ({}): the frame record would overwrite the image; give two paths",
            input::show_path(&a.out)
        )));
    }
    let mut overlays = overlay_settings(&a)?;
    let tier = a
        .tier
        .as_deref()
        .map(crate::tier_render::parse_tier)
        .transpose()?;
    if let Some(tier) = tier {
        // A tier draws the overlays its detail has (docs/overlays.md, "Tiers").
        overlays.detail = crate::tier_render::TierRender::of(tier).overlay;
    }
    if tier.is_some() && effects.is_some() {
        return Err(AppError::new(
            "--tier chooses the effects itself: give --tier or --effects, not both",
        ));
    }
    if a.scene == SceneKind::Pool {
        if effects.is_some() || a.replay.is_some() || a.overlays.is_some() || tier.is_some() {
            return Err(AppError::new(
                "--effects, --overlays, --tier and --replay have no meaning with --scene pool (the pool traces its own)",
            ));
        }
        return run_pool(&a, &out, size);
    }
    check_error_px(a.error_px)?;
    if let Some(dir) = &a.replay {
        if a.camera.is_some() {
            return Err(AppError::new(
                "--camera has no meaning with --replay: the feed's camera draws",
            ));
        }
        return replay::run(
            &a,
            dir,
            &out,
            size,
            race_setup(&a, tier, effects, overlays)?,
        );
    }
    let camera = a
        .camera
        .as_deref()
        .map(|c| parse_camera(c, FAR_M))
        .transpose()?;
    let setup = race_setup(&a, tier, effects, overlays)?;
    let world = RaceSetup::load_world(&a.race, a.sea.as_ref())?;
    let t = a.t.unwrap_or_else(|| world.middle_time());
    let scene = world.scene_at(t, camera);
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("cannot render: {e}")))?;
    let mut renderer = setup.renderer(&gpu, render::OFFSCREEN_FORMAT, setup.wake(&world.race)?);
    let _effects = setup.scene_effects(&mut renderer, &gpu, &scene, size);
    let (img, report) = setup.picture(&gpu, &mut renderer, &world, &scene, size)?;
    out.save(&img)?;
    note_unmet_error(&report);
    print_report(&a, &report)
}

/// The race scene's set-up the flags ask for: a picture's options with `--error-px` (or the
/// tier's), the effects, `--no-wakes`, the water flags over the open sea's and the table's
/// water, and the overlays.
pub fn race_setup(
    a: &RenderArgs,
    tier: Option<quality::Tier>,
    effects: Option<effects::EffectSet>,
    overlays: crate::scene_overlay::OverlaySettings,
) -> AppResult<RaceSetup> {
    let mut setup = RaceSetup::new(Profile::Picture);
    setup.options.error_px = a.error_px;
    if let Some(tier) = tier {
        setup = setup.with_tier(tier);
    }
    setup.effects = effects;
    setup.wakes = !a.no_wakes;
    setup.sea_water = a.water.look(setup.sea_water)?;
    setup.table_water = a.water.look(setup.table_water)?;
    setup.overlays = overlays;
    Ok(setup)
}

/// The overlays `--overlays` asks for (all without it).
pub fn overlay_settings(a: &RenderArgs) -> AppResult<crate::scene_overlay::OverlaySettings> {
    let set = match a.overlays.as_deref() {
        Some(list) => crate::scene_overlay::OverlaySet::parse(list).map_err(AppError::new)?,
        None => crate::scene_overlay::OverlaySet::ALL,
    };
    Ok(crate::scene_overlay::OverlaySettings {
        set,
        ..Default::default()
    })
}

/// Print the frame record and write it to `--report`.
pub fn print_report(a: &RenderArgs, report: &impl serde::Serialize) -> AppResult {
    let json = serde_json::to_string_pretty(report)?;
    if let Some(p) = &a.report {
        write_text(p, &json)?;
    }
    crate::terminal::print_stdout("the frame record", &json)
}

/// `--scene pool`: the pool at `--t` (default [`pool::DEFAULT_T`]).
fn run_pool(a: &RenderArgs, out: &ImageOut, size: [u32; 2]) -> AppResult {
    use pool::{PoolFrame, PoolRenderer, PoolScene, PoolSettings, PoolView};
    if !a.race.is_empty() {
        return Err(AppError::new("--race has no meaning with --scene pool"));
    }
    let t = a.t.unwrap_or(pool::DEFAULT_T);
    let mut scene = PoolScene::default();
    if let Some(p) = &a.sea {
        scene.water.waves = drawable_sea(load_sea(Some(p))?);
    }
    let mut view = PoolView::default_desktop(size);
    if let Some(c) = &a.camera {
        view.camera = parse_camera(c, pool::FAR_M)?;
    }
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("cannot render: {e}")))?;
    let settings = PoolSettings::default();
    let mut renderer = PoolRenderer::new(&gpu, render::OFFSCREEN_FORMAT, settings);
    let frame = PoolFrame::new(&scene, t, &view, &settings);
    let (img, report) = pool::render_pool_image(&gpu, &mut renderer, &frame)
        .map_err(|e| AppError::new(format!("cannot render: {e}")))?;
    out.save(&img)?;
    print_report(a, &report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_sizes_are_refused_with_the_flag_named() {
        for s in ["", "640", "0x480", "640x", "axb", "9000x10", "-5x5"] {
            let e = parse_size(s).unwrap_err().to_string();
            assert!(e.contains("--size") && e.contains(s), "{s}: {e}");
        }
        assert_eq!(parse_size("64x48").unwrap(), [64, 48]);
    }

    #[test]
    fn bad_cameras_are_refused() {
        for s in [
            "1,2,3",
            "1,2,3,4,5,x",
            "0,10,0,0,0,0",
            "1,1,1,1,1,1",
            "1,2,3,4,5,NaN",
        ] {
            let e = parse_camera(s, 1e3).unwrap_err().to_string();
            assert!(e.contains("--camera"), "{s}: {e}");
        }
        let c = parse_camera("0,10,50,0,0,0", 1e3).unwrap();
        assert_eq!(c.eye, DVec3::new(0.0, 10.0, 50.0));
    }

    fn pool_args(extra: &[&str]) -> RenderArgs {
        use clap::Parser;
        let base = [
            "regatta",
            "render",
            "--scene",
            "pool",
            "--out",
            "/nonexistent/p.png",
        ];
        match crate::cli::Cli::try_parse_from(base.iter().chain(extra))
            .unwrap()
            .command
        {
            Some(crate::cli::Command::Render(a)) => a,
            other => panic!("not a render command: {other:?}"),
        }
    }

    #[test]
    fn pool_scene_refuses_a_race_and_a_bad_time() {
        let e = run(pool_args(&["--race", "r.json"]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("--race") && e.contains("--scene pool"), "{e}");
        let e = run(pool_args(&["--t", "inf"])).unwrap_err().to_string();
        assert!(e.contains("--t"), "{e}");
        let e = run(pool_args(&["--camera", "1,2"]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("--camera"), "{e}");
    }
}
