//! `regatta bench --only budget`: per phone and quality tier, the timed estimate (interleaved
//! with the throughput kernel, [`super::budget`]) and the machine-independent one
//! ([`super::budget_model`]), each tier's accuracy ([`super::budget_accuracy`]), the goals,
//! the effects' cost with a YUV camera image on the model, and `budget.json`.

use quality::Tier;
use serde_json::json;

use super::budget::FmaKernel;
use super::budget_model::{FrameInputs, PHONES, PassWork, PhoneGpu, frame_ms, frame_work};
use super::shader_cost::Trips;
use super::work_clock::WorkClock;
use crate::{Axes, BenchContext, Series, Table};
use regatta::error::{AppError, AppResult};
use regatta::tier_render::TierRender;

/// Race time of the budget's frame, s: the sample race's busiest wakes.
const T: f64 = 600.0;

/// One phone and tier: both estimates and the frame behind them.
pub(crate) struct Row {
    pub(crate) phone: &'static PhoneGpu,
    pub(crate) tier: Tier,
    /// Phone ms per repetition (timed, interleaved).
    timed_ms: Vec<f64>,
    /// Model ms: at the spec sheets' high rates, and at their low rates with the phone's own
    /// hidden surface removal (the phone's figure).
    pub(crate) model_ms: (f64, f64),
    /// Model ms range: fast spec with all occluded fragments removed, slow spec with none.
    pub(crate) model_range: (f64, f64),
    pub(crate) work: Vec<PassWork>,
    pub(crate) report: render::FrameReport,
    /// The loops' trip counts the model used for this frame.
    pub(crate) trips: Trips,
    /// This CPU's time to cull and bin the frame's wake sources (`bin_wakes`), ms: median
    /// and relative interquartile range of [`BINNING_REPS`] runs.
    pub(crate) binning_ms: (f64, f64),
}

/// Runs of `bin_wakes` timed per row.
const BINNING_REPS: usize = 7;

/// Median and relative interquartile range of `v`.
fn median_iqr(v: &[f64]) -> (f64, f64) {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let q = |p: f64| s[((s.len() - 1) as f64 * p).round() as usize];
    let m = q(0.5);
    (m, (q(0.75) - q(0.25)) / m)
}

/// Trip counts of the frame's loops: the sea's waves (all of them, and a fragment's), the
/// marks, and the wake sources a clip-map vertex sums (binned as the renderer bins them); the
/// bytes of the frame's wake buffers; and the clip-map's vertices (the compute stage's
/// invocations).
fn trips(
    scene: &render::Scene,
    tier: &TierRender,
    wake: &ocean::wake::Wake,
    drawn: [u32; 2],
) -> (Trips, f64, f64) {
    let mut frame = render::frame::FrameContext::new(scene, drawn, tier.options.error_px);
    render::renderer::bin_wakes(
        wake,
        render::wake_bins::WAKE_BUFFER_BUDGET_BYTES,
        tier.wake_source_budget,
        &mut Default::default(),
        &mut frame,
    );
    let [height, foam] = wake_sources_per_vertex(&frame);
    let [resolved, fading] = waves_in_pixel(&frame);
    let vertex_waves = vertex_waves_per_vertex(&frame);
    let trips = Trips {
        waves: scene.sea.waves.len() as f64,
        resolved_waves_in_pixel: resolved,
        fading_waves_in_pixel: fading,
        wake_sources_per_vertex: height,
        wake_foam_sources_per_vertex: foam,
        vertex_waves_per_vertex: vertex_waves,
        marks: scene.marks.len() as f64,
    };
    let bytes = frame.wake_bins.bytes(frame.wakes.sources.len()) as f64;
    (trips, bytes, frame.mesh.vertices.len() as f64)
}

/// The wake sources the compute stage sums per clip-map vertex, the means over the vertices
/// of its bin's height list and foam list: each vertex looks up the bin its displaced position
/// falls in as `wake_at` in `shaders/render/water_vertices.wgsl` does (`WakeBins::bin_at`),
/// none outside the grid or without wakes. The position is the f64 sea's displacement (the
/// shader's f32 one can fall in a neighbouring bin within a few millimetres of a bin's edge).
fn wake_sources_per_vertex(frame: &render::frame::FrameContext) -> [f64; 2] {
    let vertices = &frame.mesh.vertices;
    if frame.uniform.counts[2] == 0 || vertices.is_empty() {
        return [0.0; 2];
    }
    let surface = sea_surface(frame);
    let mut listed = [0.0; 2];
    for v in vertices {
        let d = surface([f64::from(v.rest[0]), f64::from(v.rest[1])]);
        if let Some([_, height, _, foam]) =
            frame.wake_bins.bin_at([d[0] as f32, d[2] as f32], v.level)
        {
            listed[0] += f64::from(height);
            listed[1] += f64::from(foam);
        }
    }
    listed.map(|n| n / vertices.len() as f64)
}

/// The frame's sea surface in its local coordinates: a rest point (x, z, metres from the
/// origin) to its displaced position (x, y, z), as the f64 sea has it at the frame's time.
fn sea_surface<'a>(frame: &'a render::frame::FrameContext) -> impl Fn([f64; 2]) -> [f64; 3] + 'a {
    let (o, sea, t) = (frame.origin, &frame.scene.sea, frame.scene.t);
    move |p| {
        let d = sea.displace([p[0] + o.x, p[1] + o.y], t);
        [d[0] - o.x, d[1], d[2] - o.y]
    }
}

/// The waves whose slope sums a clip-map vertex carries to the pixels (`vertex_slope_sums`,
/// its level's first pixel wave), the mean over the vertices.
fn vertex_waves_per_vertex(frame: &render::frame::FrameContext) -> f64 {
    let vertices = &frame.mesh.vertices;
    let sum: f64 = vertices
        .iter()
        .map(|v| f64::from(first_pixel_wave(frame, v.level)))
        .sum();
    sum / vertices.len().max(1) as f64
}

/// The first wave a pixel of clip-map level `level` sums (its vertices sum those before).
fn first_pixel_wave(frame: &render::frame::FrameContext, level: u32) -> u32 {
    frame
        .vertex_waves
        .get(level as usize)
        .map_or(0, |v| v.first_pixel_wave)
}

/// The turns of a water fragment's two wave loops in `surface_frame_from`, the means over the
/// fragments a GPU shading 2×2 quads runs for the frame's clip-map: `resolved_waves` runs the
/// waves sorted by wavenumber from the first its triangle's vertices did not sum
/// (`render::vertex_slopes`) while k·footprint < π/4 (the pixel filter leaves them whole),
/// `fading_waves` from there while k·footprint < π/2 (the filter fades them). Each loop's
/// turn that meets its limit runs its test too: counted as a turn.
fn waves_in_pixel(frame: &render::frame::FrameContext) -> [f64; 2] {
    let footprints = frame
        .mesh
        .footprints(frame.view_proj, frame.size, sea_surface(frame));
    let quarter = 0.25 * std::f64::consts::PI;
    let n = frame.waves.len();
    let below = |limit: f64, footprint: f64| {
        frame
            .waves
            .iter()
            .take_while(|w| f64::from(w.k) * footprint < limit)
            .count()
    };
    let (mut turns, mut fragments) = ([0.0; 2], 0.0);
    for (footprint, quads, level) in footprints {
        let first = (first_pixel_wave(frame, level) as usize).min(n);
        let whole = below(quarter, footprint).max(first);
        let fading = below(2.0 * quarter, footprint).max(whole) - whole;
        let resolved_turns = (whole - first + 1).min(n - first);
        let fading_turns = (fading + 1).min(n - whole);
        turns[0] += (resolved_turns * quads as usize) as f64;
        turns[1] += (fading_turns * quads as usize) as f64;
        fragments += quads as f64;
    }
    if fragments == 0.0 {
        [n as f64, 0.0]
    } else {
        turns.map(|t| t / fragments)
    }
}

/// The fragments a GPU shading 2×2 quads runs for the frame's clip-map at `drawn` pixels:
/// 4 per quad each triangle covers a pixel of (`render::clipmap::ScreenCoverage`).
fn water_quad_fragments(scene: &render::Scene, tier: &TierRender, drawn: [u32; 2]) -> u64 {
    let frame = render::frame::FrameContext::new(scene, drawn, tier.options.error_px);
    frame
        .mesh
        .screen_coverage(frame.view_proj, drawn, sea_surface(&frame))
        .quad_fragments
}

/// `report` with the water's fragments as a phone GPU shades them, 4 per 2×2 quad each
/// clip-map triangle covers: lavapipe counts 16 per 4×4 block (docs/quality.md, "Goals").
fn as_phone_shades(
    report: &render::FrameReport,
    scene: &render::Scene,
    tier: &TierRender,
) -> render::FrameReport {
    let quads = water_quad_fragments(scene, tier, report.size);
    let mut shaded = report.clone();
    for inv in &mut shaded.shader_invocations {
        if inv.pass == "water" || inv.pass == "ar_water" {
            inv.fragment = quads;
        }
    }
    shaded
}

/// Draw `tier` on `phone`'s screen `reps` times alternating with the kernel (none without
/// one: the model alone); model its work.
pub(crate) fn measure(
    ctx: &BenchContext,
    gpu: &render::Gpu,
    kernel: Option<(&FmaKernel, u32)>,
    phone: &'static PhoneGpu,
    tier: Tier,
    reps: usize,
) -> AppResult<Row> {
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), T, None);
    let t = TierRender::of(tier);
    let size = phone.screen;
    ctx.progress(format!(
        "budget: {} {tier} at {}×{}",
        phone.phone, size[0], size[1]
    ));
    let (mut renderer, fx) =
        regatta::setup::RaceSetup::tier_renderer(&t, gpu, Some(&race), &scene, size)?;
    let view = crate::offscreen(gpu, size);
    let failed = |e: render::GpuError| AppError(e.to_string());
    let report = renderer.render(gpu, &view, size, &scene).map_err(failed)?; // warm-up
    let mut timed_ms = Vec::with_capacity(reps);
    for k in 0..kernel.map_or(0, |_| reps) {
        let Some((kernel, iterations)) = kernel else {
            break;
        };
        // The kernel before and after the frame: the load the frame saw lies between.
        let before = kernel.gflops(iterations);
        // The frame: GPU timestamps on a GPU that has them, else the kernel's clock (on a CPU
        // adapter the driver threads' CPU time). The frames of a 60 fps playback, so that no
        // offscreen work is reused.
        let playing = render::Scene {
            t: T + (k + 1) as f64 / 60.0,
            ..scene.clone()
        };
        let clock = kernel.clock;
        let t0 = clock.now();
        let r = renderer
            .render(gpu, &view, size, &playing)
            .map_err(failed)?;
        gpu.wait();
        let here = match (clock, r.gpu_ms) {
            (WorkClock::Wall, Some(gpu_ms)) => gpu_ms,
            _ => clock.since(t0) * 1e3,
        };
        let gflops = (before * kernel.gflops(iterations)).sqrt();
        timed_ms.push(here * gflops / phone.gflops[1]);
    }
    let wake = t.race_wake(&race)?;
    let (trips, wake_buffer_bytes, clipmap_vertices) = trips(&scene, &t, &wake, report.size);
    let binning_ms = binning_ms(&scene, &t, &wake, report.size);
    let shaded = as_phone_shades(&report, &scene, &t);
    let inputs = FrameInputs {
        report: &shaded,
        offscreen: fx.offscreen_sizes(),
        ar: &t.ar,
        trips,
        wake_buffer_bytes,
        clipmap_vertices,
        screen: size,
        yuv: None,
    };
    let (full, unmodelled) = frame_work(&inputs, false).map_err(AppError::new)?;
    let (hsr, _) = frame_work(&inputs, true).map_err(AppError::new)?;
    // The range: fast spec with every occluded fragment removed, to slow spec shading all
    // the depth test lets through; the phone's own figure: slow spec, its architecture.
    let range = (frame_ms(&hsr, phone).0, frame_ms(&full, phone).1);
    let work = if phone.hidden_surface_removal {
        hsr
    } else {
        full
    };
    if !unmodelled.is_empty() {
        ctx.progress(format!(
            "budget: passes not modelled: {}",
            unmodelled.join(", ")
        ));
    }
    if report.shader_invocations.is_empty() {
        return Err(AppError::new(
            "budget: the adapter counts no shader invocations (pipeline-statistics queries): \
             the model needs them",
        ));
    }
    Ok(Row {
        phone,
        tier,
        timed_ms,
        model_ms: (range.0, frame_ms(&work, phone).1),
        model_range: range,
        work,
        report,
        trips,
        binning_ms,
    })
}

/// This CPU's time to cull and bin the frame's wake sources as the renderer does every frame
/// (`bin_wakes`, the tier's source budget), ms: median and relative interquartile range of
/// [`BINNING_REPS`] runs.
fn binning_ms(
    scene: &render::Scene,
    tier: &TierRender,
    wake: &ocean::wake::Wake,
    drawn: [u32; 2],
) -> (f64, f64) {
    let mut frame = render::frame::FrameContext::new(scene, drawn, tier.options.error_px);
    // One binner for every run, each run's bins handed back to it, as the renderer does
    // from frame to frame.
    let mut binner = render::wake_bins::WakeBinner::default();
    let runs: Vec<f64> = (0..BINNING_REPS)
        .map(|_| {
            let t0 = std::time::Instant::now();
            render::renderer::bin_wakes(
                wake,
                render::wake_bins::WAKE_BUFFER_BUDGET_BYTES,
                tier.wake_source_budget,
                &mut binner,
                &mut frame,
            );
            let ms = t0.elapsed().as_secs_f64() * 1e3;
            binner.recycle(std::mem::take(&mut frame.wake_bins));
            ms
        })
        .collect();
    median_iqr(&runs)
}

/// The goal a tier is held to on a phone, if any: (fps, what the goal asks).
pub(crate) fn goal(phone: &PhoneGpu, tier: Tier) -> Option<(f64, &'static str)> {
    match (phone.phone, tier) {
        ("OPPO A54", Tier::Low) => Some((30.0, "≥ 30 fps, background + reflection + refraction")),
        ("Pixel 2 XL", Tier::High) => Some((60.0, "≥ 60 fps, every effect, render scale ≥ ¾")),
        _ => None,
    }
}

/// Section `budget`.
pub fn run(ctx: &BenchContext) -> AppResult<Vec<Table>> {
    let gpu = render::Gpu::headless(wgpu::Backends::all())
        .map_err(|e| AppError::new(format!("the budget bench needs a GPU adapter: {e}")))?;
    let kernel = FmaKernel::new(&gpu);
    // A dispatch of about a tenth of a second: long enough that a scheduling blip of the
    // shared machine is a small part of it, like the frame's.
    let iterations = kernel.calibrate(if ctx.quick { 0.03 } else { 0.1 });
    let reps = if ctx.quick { 3 } else { 9 };
    let mut rows = Vec::new();
    for phone in &PHONES {
        for tier in Tier::ALL {
            rows.push(measure(
                ctx,
                &gpu,
                Some((&kernel, iterations)),
                phone,
                tier,
                reps,
            )?);
        }
    }
    let mut tiers = Table::new(
        "budget_tiers",
        "Phone frame budget per quality tier: timed (interleaved with the FP32 kernel) and modelled (shader work × invocations against published rates)",
        &[
            "phone",
            "tier",
            "effects",
            "render scale",
            "timed ms",
            "timed fps",
            "timed spread (IQR/median)",
            "model ms (slow spec, the phone's HSR)",
            "model ms range",
            "model fps (slow spec, the phone's HSR)",
            "goal",
            "goal met on the model (slow spec)",
        ],
    );
    let mut json_rows = Vec::new();
    for r in &rows {
        let s = r.tier.settings();
        let (timed, spread) = median_iqr(&r.timed_ms);
        let model_fps = 1e3 / r.model_ms.1;
        let g = goal(r.phone, r.tier);
        tiers.row(vec![
            json!(r.phone.phone),
            json!(r.tier.name()),
            json!(s.effects.join(",")),
            json!(s.render_scale),
            json!(timed),
            json!(1e3 / timed),
            json!(spread),
            json!(r.model_ms.1),
            json!(format!("{:.1}–{:.1}", r.model_range.0, r.model_range.1)),
            json!(model_fps),
            json!(g.map(|(_, what)| what)),
            json!(g.map(|(fps, _)| if model_fps >= fps {
                "yes".to_string()
            } else {
                format!("no: needs {:.2}× less work", fps / model_fps)
            })),
        ]);
        json_rows.push(json!({
            "phone": r.phone.phone,
            "tier": r.tier.name(),
            "effects": s.effects,
            "render_scale": s.render_scale,
            "model_fps": model_fps,
            "model_fps_range": [1e3 / r.model_range.1, 1e3 / r.model_range.0],
            "timed_fps": 1e3 / timed,
            "timed_spread": spread,
        }));
    }
    tiers.note(format!(
        "{}; the sample race at {T} s with wakes, the default camera, each phone's screen. \
         Timed on {}: {reps} repetitions, each the FMA kernel (2^20 invocations × \
         {iterations} turns), the frame, the kernel again; phone ms = frame ms × the geometric \
         mean of the two kernels' GFLOP/s ÷ \
         the phone's FP32 peak (Adreno 540: {}, GE8320: {} GFLOP/s); the median of the \
         repetitions. Model: see budget_passes; the phone's figure at the slow end of the spec \
         sheets with its own hidden surface removal (PowerVR: each pixel shaded once; Adreno: \
         every fragment the depth test passes, as counted); the range from the fast end with \
         each pixel shaded once to the slow end with every counted fragment.",
        gpu.describe(),
        kernel.clock.describe(),
        PHONES[1].gflops[1],
        PHONES[0].gflops[1],
    ));
    for p in &PHONES {
        tiers.note(format!("{} ({}) rates: {}", p.phone, p.gpu, p.sources));
    }
    let path = ctx.out_dir.join("budget.json");
    regatta::setup::output::write_text(&path, &serde_json::to_string_pretty(&json_rows)?)?;
    let passes = passes_table(&rows);
    let accuracy = accuracy_table(ctx, &rows)?;
    let yuv = yuv_table(ctx, &gpu)?;
    Ok(vec![tiers, accuracy, passes, yuv])
}

/// Per pass of every row: the model's ms at the slow spec and what bounds it.
pub(crate) fn passes_table(rows: &[Row]) -> Table {
    let mut t = Table::new(
        "budget_passes",
        "Machine-independent model per pass: invocations × shader work against the phone's rates",
        &[
            "phone",
            "tier",
            "pass",
            "vertex + compute invocations",
            "fragment invocations",
            "GFLOP",
            "Gtexel",
            "memory MB",
            "storage loads MB (cache)",
            "model ms (slow spec)",
            "bound by",
            "timed here ms",
        ],
    );
    for r in rows {
        for w in &r.work {
            let here = r
                .report
                .passes
                .iter()
                .find(|p| p.name == w.pass)
                .and_then(|p| p.gpu_ms);
            t.row(vec![
                json!(r.phone.phone),
                json!(r.tier.name()),
                json!(w.pass),
                json!(w.invocations[0]),
                json!(w.invocations[1]),
                json!(w.cost.alu * 1e-9),
                json!(w.cost.tex * 1e-9),
                json!(w.target_bytes * 1e-6),
                json!(w.cost.storage_bytes * 1e-6),
                json!(w.ms(r.phone, false)),
                json!(w.bound(r.phone, false).0),
                json!(here),
            ]);
        }
    }
    t.note(
        "Vertex and fragment invocations of the frame's passes from pipeline-statistics \
         queries (this adapter's rasteriser); the water's compute stage once per clip-map vertex \
         (half its triangles); the reflection texture's grid twice per corner of its cells (up to 8 texels a side) \
         (one triangle strip per row of cells) and once per texel; the caustic map once per \
         surface grid point, twice per grid cell and once per map cell; the upscale once per \
         screen pixel. Work per invocation: naga's IR of each entry point (tools/bench/src/\
         shader_cost.rs), loops × trip counts known on the CPU (waves, marks, wake sources per \
         bin). A pass takes the longest of ALU ÷ FP32 rate, texels ÷ texture rate and memory \
         bytes ÷ bandwidth (render targets, vertices, the wake buffers once: the sources a bin \
         lists are read by all its vertices from the cache). Timed here: this adapter's GPU timestamps of the pass (its offscreen work \
         apart), to compare rankings.",
    );
    t
}

/// Each tier's accuracy against its cost on both phones, and the plot.
fn accuracy_table(ctx: &BenchContext, rows: &[Row]) -> AppResult<Table> {
    let mut t = Table::new(
        "budget_accuracy",
        "Quality tiers: run time against error (f64 references)",
        &[
            "tier",
            "mesh error px (screen)",
            "wake RMS / reference RMS",
            "wake budget drop bound m",
            "caustic RMS error",
            "OPPO A54 model ms",
            "OPPO A54 timed ms",
            "Pixel 2 XL model ms",
            "Pixel 2 XL timed ms",
        ],
    );
    let mut series: Vec<Series> = PHONES
        .iter()
        .flat_map(|p| {
            ["model", "timed"].map(|k| Series {
                label: format!("{} {k}", p.phone),
                points: Vec::new(),
            })
        })
        .collect();
    for tier in Tier::ALL {
        let of = |phone: &str| {
            rows.iter()
                .find(|r| r.tier == tier && r.phone.phone == phone)
        };
        let (Some(a54), Some(p2)) = (of("OPPO A54"), of("Pixel 2 XL")) else {
            continue;
        };
        let acc = super::budget_accuracy::tier_accuracy(ctx, tier, &a54.report)?;
        let timed = |r: &Row| median_iqr(&r.timed_ms).0;
        for (k, r) in [a54, p2].iter().enumerate() {
            series[2 * k].points.push((acc.mesh_px, r.model_ms.1));
            series[2 * k + 1].points.push((acc.mesh_px, timed(r)));
        }
        t.row(vec![
            json!(tier.name()),
            json!(acc.mesh_px),
            json!(acc.wake_rel_rms),
            json!(acc.wake_drop_bound_m),
            json!(acc.caustic_rms),
            json!(a54.model_ms.1),
            json!(timed(a54)),
            json!(p2.model_ms.1),
            json!(timed(p2)),
        ]);
    }
    t.note(
        "Mesh: the clip-map's worst level error bound (f64) in screen pixels. Wakes: RMS \
         height error against the Havelock integral at the tier's source spacing (one boat at \
         5 m/s), and the bound of the height error of the sources the tier's budget dropped in \
         the OPPO A54 frame. Caustics: RMS error of the light on the demo table against the \
         512² area-ratio reference (1 = flat water): the tier's map, the cheap overhead-sun \
         formula, or flat light where caustics are off.",
    );
    t.plots.push(ctx.plot(
        "tiers.svg",
        &Axes {
            title: "Quality tiers: frame ms against mesh error (low → ultra: right → left)",
            x_label: "mesh error bound, screen px",
            y_label: "frame ms",
            log_x: true,
            log_y: true,
        },
        &series,
    )?);
    Ok(t)
}

/// The AR effects' cost over water only on the model, with a 640×480 YUV camera image
/// converted for every frame and at 30 Hz into a 60 fps frame.
fn yuv_table(ctx: &BenchContext, gpu: &render::Gpu) -> AppResult<Table> {
    let mut t = Table::new(
        "budget_yuv",
        "All effects with a YUV camera image against water only, on the machine-independent model",
        &["phone", "case", "model ms (slow spec)", "× water only"],
    );
    let race = race::Race::sample();
    let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), T, None);
    let ultra = TierRender::of(Tier::Ultra);
    let wake = ultra.race_wake(&race)?;
    for phone in &PHONES {
        let size = phone.screen;
        ctx.progress(format!(
            "budget: {} water only and all effects",
            phone.phone
        ));
        let view = crate::offscreen(gpu, size);
        let failed = |e: render::GpuError| AppError(e.to_string());
        let mut water = render::Renderer::new(gpu, render::OFFSCREEN_FORMAT, ultra.options);
        water.set_wake(Some(wake.clone()));
        let water_report = water.render(gpu, &view, size, &scene).map_err(failed)?;
        let water_report = as_phone_shades(&water_report, &scene, &ultra);
        let (mut all, fx) =
            regatta::setup::RaceSetup::tier_renderer(&ultra, gpu, Some(&race), &scene, size)?;
        let all_report = all.render(gpu, &view, size, &scene).map_err(failed)?;
        let all_report = as_phone_shades(&all_report, &scene, &ultra);
        let (trips, wake_buffer_bytes, clipmap_vertices) = trips(&scene, &ultra, &wake, size);
        let none = effects::passes::ArConfig {
            effects: effects::EffectSet::NONE,
            ..ultra.ar.clone()
        };
        let no_offscreen = effects::passes::OffscreenSizes {
            reflection_px: None,
            caustic_map_cells: None,
        };
        let ms = |report, offscreen, ar, yuv| -> AppResult<f64> {
            let i = FrameInputs {
                report,
                offscreen,
                ar,
                trips,
                wake_buffer_bytes,
                clipmap_vertices,
                screen: size,
                yuv,
            };
            let work = frame_work(&i, phone.hidden_surface_removal).map_err(AppError::new)?;
            Ok(frame_ms(&work.0, phone).1)
        };
        let fx_sizes = fx.offscreen_sizes();
        let base = ms(&water_report, no_offscreen, &none, None)?;
        let cam = Some(([640, 480], 1.0));
        let half = Some(([640, 480], 0.5));
        for (case, v) in [
            ("water only", base),
            ("all effects", ms(&all_report, fx_sizes, &ultra.ar, None)?),
            (
                "all effects + YUV every frame",
                ms(&all_report, fx_sizes, &ultra.ar, cam)?,
            ),
            (
                "all effects + YUV at 30 Hz, 60 fps",
                ms(&all_report, fx_sizes, &ultra.ar, half)?,
            ),
        ] {
            t.row(vec![
                json!(phone.phone),
                json!(case),
                json!(v),
                json!(v / base),
            ]);
        }
    }
    t.note(
        "The ultra tier's frame (every effect, full screen) of the sample race with wakes. \
         The camera image: 640×480 YUV 4:2:0 uploaded and converted to RGBA \
         (shaders/camera_yuv.wgsl) once per camera frame. Goal: at most 1.6× water only.",
    );
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AR water's fragments as a phone shades them lie between a quarter of lavapipe's
    /// count (16 per 4×4 block, and each block a triangle touches holds at least one of its 2×2
    /// quads) and that count (a quad touched lies in a block touched); the CPU's block count
    /// agrees with lavapipe's within 8 % (render's `fragment_count` test), hence the 10 %
    /// margins. Every other pass keeps lavapipe's figures.
    #[test]
    fn the_water_is_counted_in_quads_between_a_quarter_and_all_of_lavapipes_blocks() {
        let Some(gpu) = render::gpu::test_gpu() else {
            return;
        };
        let race = race::Race::sample();
        let scene = regatta::world::scene_at(&race, &ocean::WaveSet::default_sea(), T, None);
        let t = TierRender::of(Tier::High);
        let size = [270, 540];
        let (mut renderer, _) =
            regatta::setup::RaceSetup::tier_renderer(&t, &gpu, Some(&race), &scene, size)
                .expect("renderer");
        let view = crate::offscreen(&gpu, size);
        let report = renderer.render(&gpu, &view, size, &scene).expect("frame");
        if report.shader_invocations.is_empty() {
            return; // no pipeline statistics on this adapter: nothing to replace
        }
        let shaded = as_phone_shades(&report, &scene, &t);
        let water = |r: &render::FrameReport| {
            r.shader_invocations
                .iter()
                .find(|i| i.pass == "ar_water")
                .map(|i| i.fragment as f64)
                .expect("the AR water pass")
        };
        let (blocks, quads) = (water(&report), water(&shaded));
        assert!(
            quads >= blocks / 4.0 / 1.1 && quads <= blocks * 1.1,
            "{quads} quad lanes against lavapipe's {blocks}"
        );
        for (a, b) in report
            .shader_invocations
            .iter()
            .zip(&shaded.shader_invocations)
        {
            if a.pass != "ar_water" && a.pass != "water" {
                assert_eq!(format!("{a:?}"), format!("{b:?}"));
            }
        }
    }
}
