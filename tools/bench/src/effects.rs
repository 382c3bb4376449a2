//! Bench sections of the AR water effects:
//!
//! - `effects`: the cost of each AR effect alone and of all of them against a water-only
//!   frame, in the form of Table 1 of the Sailing+ AR water thesis (TU Delft 2022, report 000
//!   in docs/sources.md: min / max / average frames per second) plus
//!   the ratios, measured in one run on the adapter at hand (lavapipe in CI); each pass's GPU
//!   time in the same run; and the area-ratio caustic map's CPU time against its error per
//!   resolution (against a 512² f64 reference).
//! - `fresnel`: the error Schlick's approximation would make against the full Fresnel
//!   equations at each angle, air → water and water → air, and what each costs.

use std::collections::BTreeMap;
use std::hint::black_box;
use std::time::Instant;

use effects::backdrop::{Backdrop, CameraImage, Yuv420, YuvRange};
use effects::passes::{ArConfig, EffectsHandle, add_effect_passes};
use effects::{Effect, EffectSet, demo_table_scene};
use render::optics::{N_AIR, N_WATER, brewster_angle, critical_angle, fresnel, schlick};
use render::{OFFSCREEN_FORMAT, RenderOptions, Renderer};
use serde_json::json;

use crate::{Axes, BenchContext, Series, Table, time_ns};
use regatta::error::{AppError, AppResult};

/// Goal of the issue: every effect on costs at most this much of a water-only frame.
const GOAL_RATIO: f64 = 1.6;

/// A renderer drawing the demo table scene at `size` with `effects` (`None`: without effect
/// passes) into its own texture.
struct Case {
    renderer: Renderer,
    view: wgpu::TextureView,
    /// A camera frame handed over before every frame (the YUV case: as ARCore does), with
    /// the handle that takes it.
    new_frames: Option<(EffectsHandle, Backdrop)>,
}

/// The kind of camera image a case draws over.
#[derive(Clone, Copy, PartialEq)]
enum CameraKind {
    Rgba,
    /// YUV 4:2:0 planes, as ARCore hands them over: a new camera frame every frame, uploaded
    /// and converted.
    Yuv,
}

impl Case {
    fn new(
        gpu: &render::Gpu,
        size: [u32; 2],
        effects: Option<EffectSet>,
        camera: CameraKind,
    ) -> Case {
        let mut new_frames = None;
        let mut renderer = Renderer::new(
            gpu,
            OFFSCREEN_FORMAT,
            RenderOptions {
                measure_gpu_time: true,
                ..RenderOptions::default()
            },
        );
        let scene = demo_table_scene(40.0);
        if let Some(effects) = effects {
            let cfg = ArConfig {
                effects,
                ..ArConfig::default()
            };
            let [ax, az, bx, bz] = scene.play_area;
            let frame = Backdrop::synthetic(
                &scene.camera,
                size,
                cfg.table_depth,
                glam::DVec2::new(ax + bx, az + bz) / 2.0,
                cfg.ring_radius_for(scene.play_area),
                4.0,
            );
            let frame = match (camera, &frame.image) {
                (CameraKind::Yuv, CameraImage::Rgba(rgba)) => {
                    let yuv = Yuv420::from_rgba(rgba, YuvRange::Full)
                        .expect("a synthetic frame has a size");
                    frame.with_image(CameraImage::Yuv420(yuv))
                }
                _ => frame,
            };
            let again = (camera == CameraKind::Yuv).then(|| frame.clone());
            let handle = add_effect_passes(&mut renderer, gpu, cfg, frame);
            new_frames = again.map(|frame| (handle, frame));
        }
        let view = crate::offscreen(gpu, size);
        Case {
            renderer,
            view,
            new_frames,
        }
    }

    /// Plan, draw and wait for one frame at race time `t`: wall seconds, and the passes'
    /// GPU milliseconds (all, and each pass's) from timestamp queries where the adapter has
    /// them.
    fn frame(&mut self, gpu: &render::Gpu, size: [u32; 2], t: f64) -> AppResult<Timing> {
        let scene = demo_table_scene(t);
        let t0 = Instant::now();
        if let Some((handle, frame)) = &self.new_frames {
            handle.set_backdrop(gpu, frame.clone());
        }
        let report = self
            .renderer
            .render(gpu, &self.view, size, &scene)
            .map_err(|e| AppError(e.to_string()))?;
        gpu.wait();
        Ok(Timing {
            wall_s: t0.elapsed().as_secs_f64(),
            gpu_ms: report.gpu_ms,
            // A pass's offscreen work (reflection texture, caustic map) as its own column.
            passes: report
                .passes
                .iter()
                .flat_map(|p| {
                    [
                        p.gpu_ms.map(|ms| (p.name.clone(), ms)),
                        p.offscreen_gpu_ms
                            .map(|ms| (format!("{} offscreen", p.name), ms)),
                    ]
                })
                .flatten()
                .collect(),
        })
    }
}

/// One frame's times.
struct Timing {
    wall_s: f64,
    gpu_ms: Option<f64>,
    passes: Vec<(String, f64)>,
}

/// Section `effects`.
pub fn effects_section(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("the effects bench needs a GPU adapter: {e}")))?;
    let (size, frames) = if ctx.quick {
        ([320, 240], 8usize)
    } else {
        ([640, 480], 30)
    };
    let base = EffectSet::NONE;
    let mut cases: Vec<(String, Option<EffectSet>, CameraKind)> =
        vec![("water only".into(), None, CameraKind::Rgba)];
    for e in Effect::ALL {
        cases.push((format!("{e} alone"), Some(base.with(e)), CameraKind::Rgba));
    }
    cases.push(("all effects".into(), Some(EffectSet::ALL), CameraKind::Rgba));
    // The phone's case: the camera image as YUV planes (the bench's others are RGBA).
    cases.push((
        "all effects, YUV camera, a new frame each frame".into(),
        Some(EffectSet::ALL),
        CameraKind::Yuv,
    ));
    let mut t = Table::new(
        "effects_cost",
        "AR effects: frame cost of each effect against water only (after the AR water thesis, Table 1)",
        &[
            "effects",
            "min fps",
            "max fps",
            "average fps",
            "median ms/frame",
            "ratio to water only",
            "median GPU ms",
            "GPU ratio",
        ],
    );
    let mut water_ms = f64::NAN;
    let mut worst: (f64, String) = (0.0, String::new());
    // Frame by frame, every case in turn: a busy moment of the machine falls on all cases
    // alike. Race time advances 1/30 s per frame, so caustics and flow are recomputed every
    // frame as in a playing race. Two warm-up frames are dropped.
    let mut runs: Vec<Case> = cases
        .iter()
        .map(|(_, fx, camera)| Case::new(&gpu, size, *fx, *camera))
        .collect();
    let mut pooled: Vec<Vec<f64>> = vec![Vec::new(); cases.len()];
    let mut gpu_ms: Vec<Vec<f64>> = vec![Vec::new(); cases.len()];
    let mut pass_ms: Vec<BTreeMap<String, Vec<f64>>> = vec![BTreeMap::new(); cases.len()];
    for i in 0..frames + 2 {
        if i % 10 == 0 {
            ctx.progress(format!("effects: frame {i} of {}", frames + 2));
        }
        for (k, case) in runs.iter_mut().enumerate() {
            let f = case.frame(&gpu, size, 40.0 + i as f64 / 30.0)?;
            if i >= 2 {
                pooled[k].push(f.wall_s);
                gpu_ms[k].extend(f.gpu_ms);
                for (name, ms) in f.passes {
                    pass_ms[k].entry(name).or_default().push(ms);
                }
            }
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let mut water_gpu = None;
    let mut worst_gpu = 0.0f64;
    for (((name, _, _), times), g) in cases.iter().zip(&mut pooled).zip(&mut gpu_ms) {
        let g = median(g);
        if water_gpu.is_none() {
            water_gpu = g;
        }
        let g_ratio = g.zip(water_gpu).map(|(a, b)| a / b);
        worst_gpu = worst_gpu.max(g_ratio.unwrap_or(0.0));
        times.sort_by(f64::total_cmp);
        let median = times[times.len() / 2] * 1e3;
        let mean = times.iter().sum::<f64>() / times.len() as f64;
        if water_ms.is_nan() {
            water_ms = median;
        }
        let ratio = median / water_ms;
        if ratio > worst.0 {
            worst = (ratio, name.clone());
        }
        t.row(vec![
            json!(name),
            json!(1.0 / times[times.len() - 1]),
            json!(1.0 / times[0]),
            json!(1.0 / mean),
            json!(median),
            json!(ratio),
            json!(g),
            json!(g_ratio),
        ]);
    }
    t.note(format!(
        "{} frames per case of the demo table scene (60 m of water, two boats, a mark, three \
         waves) at {}×{} on {}, measured in one run, the cases interleaved frame by frame; each frame planned, \
         drawn and waited for (CPU planning included; the area-ratio caustic map is drawn on \
         the GPU every frame the race time moves). fps is 1 / frame time, as in the AR water thesis's Table 1.",
        frames,
        size[0],
        size[1],
        gpu.describe()
    ));
    t.note(format!(
        "Goal: every case ≤ {GOAL_RATIO}× water only. Largest frame-time ratio: {:.2} ({}), \
         {}; largest GPU-time ratio (sum of the passes' timestamps, the offscreen reflection \
         texture and caustic map included): {:.2}. Each water pixel is shaded once, by a \
         pipeline made for the set of effects that runs (the effects as WGSL constants: \
         lavapipe runs both sides of every branch, so a uniform flag \
         made one effect cost as much as all). The sky is not drawn under the camera \
         background; under the reflection the water mirrors the reflection texture alone \
         (room over sky, drawn at a quarter of the resolution). On lavapipe each camera-image \
         or texture sample and each transcendental function per water pixel shows in the \
         pass table below. The YUV case hands over a new camera frame (as big as the screen \
         here) before every frame: its upload and its conversion to RGBA count in its frame \
         time; the conversion is submitted on its own, so not in its GPU time.",
        worst.0,
        worst.1,
        if worst.0 <= GOAL_RATIO {
            "goal met"
        } else {
            "goal NOT met"
        },
        worst_gpu
    ));
    // Where the time goes: each pass's median GPU time per case.
    let names: Vec<String> = pass_ms
        .iter()
        .flat_map(|m| m.keys().cloned())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let mut columns = vec!["effects".to_string()];
    columns.extend(names.iter().map(|n| format!("{n} GPU ms")));
    let cols: Vec<&str> = columns.iter().map(String::as_str).collect();
    let mut p = Table::new(
        "effects_passes",
        "AR effects: median GPU time of each pass (timestamp queries), same run; ar_water \
         shades the water with the effects (the plain water shader when none runs); ar_water \
         offscreen draws the reflection texture and the caustic map before the frame",
        &cols,
    );
    for ((name, _, _), m) in cases.iter().zip(&mut pass_ms) {
        let mut row = vec![json!(name)];
        for n in &names {
            row.push(json!(m.get_mut(n).and_then(&median)));
        }
        p.row(row);
    }
    let methods = caustic_method_table(ctx, &gpu, size, frames);
    Ok(vec![t, p, methods, caustic_resolution_table(ctx, size)])
}

/// The caustic map drawn both ways (compute scatter, and the rasterised triangles kept for
/// adapters without compute shaders), interleaved frame by frame in one run: each map's
/// median time from submission to completion, race time moving 1/30 s per frame.
fn caustic_method_table(
    ctx: &BenchContext,
    gpu: &render::Gpu,
    size: [u32; 2],
    frames: usize,
) -> Table {
    use effects::caustic_map::{CAUSTIC_MAP_FORMAT, CausticMapPass, CausticMethod};
    use effects::passes::caustic_region;
    use render::frame::{FrameBindings, FrameContext};
    ctx.progress("effects: caustic map methods");
    let cfg = ArConfig::default();
    let (src, out) = cfg.caustic_resolution;
    let bindings = FrameBindings::new(&gpu.device);
    let target = render::gpu::texture_2d(
        &gpu.device,
        "caustic map",
        [out as u32; 2],
        CAUSTIC_MAP_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    );
    let view = target.create_view(&Default::default());
    let methods = [CausticMethod::Scatter, CausticMethod::Raster];
    let mut passes: Vec<CausticMapPass> = methods
        .iter()
        .map(|&m| CausticMapPass::with_method(gpu, &bindings.layout, m))
        .collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); methods.len()];
    for i in 0..frames + 2 {
        let scene = demo_table_scene(40.0 + i as f64 / 30.0);
        let frame = FrameContext::new(&scene, size, 1.0);
        let region = caustic_region(&scene, size, &cfg);
        bindings.upload(&gpu.queue, &frame.uniform, &frame.waves);
        gpu.wait();
        for (pass, t) in passes.iter_mut().zip(&mut times) {
            pass.prepare(gpu, &frame, &region, cfg.table_depth, src, out as u32);
            let mut enc = gpu.device.create_command_encoder(&Default::default());
            pass.record(&mut enc, &bindings.group, &view, None, 0, pass.passes());
            let t0 = Instant::now();
            gpu.queue.submit([enc.finish()]);
            gpu.wait();
            if i >= 2 {
                t.push(t0.elapsed().as_secs_f64() * 1e3);
            }
        }
    }
    let mut table = Table::new(
        "caustic_methods",
        "Area-ratio caustic map on the GPU: compute scatter against rasterised triangles",
        &["method", "median ms per map", "ratio to scatter"],
    );
    let medians: Vec<f64> = times
        .iter_mut()
        .map(|v| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        })
        .collect();
    for (m, ms) in methods.iter().zip(&medians) {
        table.row(vec![
            json!(format!("{m:?}")),
            json!(ms),
            json!(ms / medians[0]),
        ]);
    }
    table.note(format!(
        "{frames} maps each of the demo scene ({src}² surface cells, {out}² texels) on {}, \
         interleaved in one run; submission to completion, wall clock. The renderer uses the \
         scatter wherever the adapter runs compute shaders (CausticMethod::for_adapter). Both \
         match the f64 reference (test gpu_caustic_map_matches_the_f64_area_ratio).",
        gpu.describe()
    ));
    table
}

/// The area-ratio caustic map's cost on the CPU against its error, per resolution (surface
/// grid, output cells), for the demo scene's view at `size`: the error is that of the
/// displayed light (clamped to the texture's range, 1 = flat water) against the f64 map of a
/// 512² surface grid on the same output cells.
fn caustic_resolution_table(ctx: &BenchContext, size: [u32; 2]) -> Table {
    use effects::caustics::MAX_INTENSITY;
    use effects::caustics::area_ratio;
    use effects::passes::caustic_region;
    let scene = demo_table_scene(40.0);
    let cfg = ArConfig::default();
    let region = caustic_region(&scene, size, &cfg);
    let map = |src: usize, out: usize| {
        area_ratio(
            &scene.sea,
            scene.t,
            -scene.sun,
            cfg.table_depth,
            region,
            src,
            out,
        )
    };
    let mut t = Table::new(
        "caustic_resolution",
        "Area-ratio caustic map: CPU time per frame against error, per resolution",
        &[
            "surface grid",
            "output cells",
            "ms per map",
            "RMS error",
            "99th percentile error",
            "in use",
        ],
    );
    let reps = if ctx.quick { 3 } else { 9 };
    let mut references: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
    let shown = |v: f64| v.clamp(0.0, MAX_INTENSITY);
    for (src, out) in [(32, 48), (48, 64), (64, 64), (64, 96), (96, 96), (128, 128)] {
        let reference = references.entry(out).or_insert_with(|| {
            ctx.progress(format!("effects: caustic reference map, {out}² cells"));
            map(512, out).intensity
        });
        let m = map(src, out);
        let mut err: Vec<f64> = m
            .intensity
            .iter()
            .zip(reference.iter())
            .map(|(a, b)| (shown(*a) - shown(*b)).abs())
            .collect();
        let rms = (err.iter().map(|e| e * e).sum::<f64>() / err.len() as f64).sqrt();
        err.sort_by(f64::total_cmp);
        let p99 = err[(err.len() * 99 / 100).min(err.len() - 1)];
        let ns = time_ns(reps, 1, || {
            black_box(map(src, out));
        });
        t.row(vec![
            json!(src),
            json!(out),
            json!(ns * 1e-6),
            json!(rms),
            json!(p99),
            json!((src, out) == cfg.caustic_resolution),
        ]);
    }
    t.note(format!(
        "The demo table scene at race time {} s; the map covers the view cut to the water, a \
         square {:.1} m wide (a surface grid of N² cells on it, plus a margin for light bent \
         in from outside). Error: |map light − reference| per output cell (1 = flat water; \
         each triangle's light capped at {MAX_INTENSITY} as in the shader). ms per map is the \
         f64 reference on one CPU core; the renderer draws the same triangles on the GPU \
         (shaders/effects/caustic_map.wgsl) into a half-float map every frame the race time moves.",
        scene.t, region.size,
    ));
    t
}

/// Section `fresnel`.
pub fn fresnel_section(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let mut t = Table::new(
        "fresnel_schlick",
        "Fresnel: Schlick's approximation against the full equations (n = 1.333)",
        &[
            "angle (°)",
            "R full, air→water",
            "Schlick",
            "error",
            "relative error",
            "R full, water→air",
            "Schlick",
            "error",
        ],
    );
    let mut angles: Vec<f64> = (0..=90).step_by(5).map(f64::from).collect();
    let extra = [
        brewster_angle(N_AIR, N_WATER).to_degrees(),
        critical_angle(N_WATER, N_AIR).unwrap_or(90.0).to_degrees(),
        84.0,
        89.0,
    ];
    angles.extend(extra);
    angles.sort_by(f64::total_cmp);
    let (mut worst_in, mut worst_in_at, mut worst_out) = (0.0f64, 0.0, 0.0f64);
    for &deg in &angles {
        let c = deg.to_radians().cos();
        let full_in = fresnel(c, N_AIR, N_WATER).r;
        let sch_in = schlick(c, N_AIR, N_WATER);
        let full_out = fresnel(c, N_WATER, N_AIR).r;
        let sch_out = schlick(c, N_WATER, N_AIR);
        if (sch_in - full_in).abs() > worst_in {
            worst_in = (sch_in - full_in).abs();
            worst_in_at = deg;
        }
        worst_out = worst_out.max((sch_out - full_out).abs());
        t.row(vec![
            json!((deg * 100.0).round() / 100.0),
            json!(full_in),
            json!(sch_in),
            json!(sch_in - full_in),
            json!((sch_in - full_in) / full_in),
            json!(full_out),
            json!(sch_out),
            json!(sch_out - full_out),
        ]);
    }
    // Dense sweep for the plot and the worst case.
    let sweep: Vec<f64> = (0..=900).map(|i| i as f64 * 0.1).collect();
    let err = |n1: f64, n2: f64| -> Vec<(f64, f64)> {
        sweep
            .iter()
            .map(|&deg| {
                let c = deg.to_radians().cos();
                (deg, schlick(c, n1, n2) - fresnel(c, n1, n2).r)
            })
            .collect()
    };
    let (e_in, e_out) = (err(N_AIR, N_WATER), err(N_WATER, N_AIR));
    for &(deg, e) in &e_in {
        if e.abs() > worst_in {
            worst_in = e.abs();
            worst_in_at = deg;
        }
    }
    worst_out = e_out.iter().fold(worst_out, |w, &(_, e)| w.max(e.abs()));

    let reps = if ctx.quick { 5 } else { 31 };
    let cosines: Vec<f64> = sweep.iter().map(|d| d.to_radians().cos()).collect();
    let per = cosines.len();
    let ns_full = time_ns(reps, per, || {
        for &c in &cosines {
            black_box(fresnel(black_box(c), N_AIR, N_WATER).r);
        }
    });
    let ns_schlick = time_ns(reps, per, || {
        for &c in &cosines {
            black_box(schlick(black_box(c), N_AIR, N_WATER));
        }
    });
    t.note(format!(
        "Brewster's angle {:.2}° (Rp = 0), critical angle from inside the water {:.2}° (total \
         internal reflection above it: both give R = 1 there).",
        brewster_angle(N_AIR, N_WATER).to_degrees(),
        critical_angle(N_WATER, N_AIR).unwrap_or(90.0).to_degrees()
    ));
    t.note(format!(
        "Worst |Schlick − full| over 0–90° in 0.1° steps: {worst_in:.4} at {worst_in_at:.1}° \
         looking into the water, {worst_out:.4} looking up from under it (Schlick there uses \
         the transmitted angle). At 50° Schlick is {:.0} % low: the water mixes reflection and \
         refraction by the full equations.",
        100.0
            * (1.0
                - schlick(50f64.to_radians().cos(), N_AIR, N_WATER)
                    / fresnel(50f64.to_radians().cos(), N_AIR, N_WATER).r)
    ));
    t.note(format!(
        "Cost on this CPU (f64, median of {reps} sweeps of {per} angles): full equations \
         {ns_full:.1} ns, Schlick {ns_schlick:.1} ns per evaluation, ratio {:.2}; on the GPU \
         the difference is a few ALU operations per water pixel.",
        ns_full / ns_schlick.max(1e-9)
    ));
    t.plots.push(ctx.plot(
        "fresnel_schlick_error.svg",
        &Axes {
            title: "Schlick's error against the full Fresnel equations (n = 1.333)",
            x_label: "angle of incidence (°)",
            y_label: "R Schlick − R full",
            log_x: false,
            log_y: false,
        },
        &[
            Series {
                label: "air → water".into(),
                points: e_in,
            },
            Series {
                label: "water → air".into(),
                points: e_out,
            },
        ],
    )?);
    Ok(vec![t])
}
