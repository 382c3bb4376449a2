//! The renderer: owns the shared frame bindings, the depth buffer and the passes, plans each
//! frame and draws it into a colour view (a window's surface texture or an offscreen texture).

use std::sync::Arc;

use glam::DVec2;

use crate::frame::{
    ClipMapRecord, FrameBindings, FrameContext, FrameReport, Pass, PassRecord, ShaderInvocations,
    Targets, WakeRecord,
};
use crate::gpu::{Gpu, GpuError};
use crate::passes::{boats::BoatsPass, sky::SkyPass, water::WaterPass};
use crate::scene::Scene;
use crate::timing::{GpuTimer, PassStats};

/// Depth buffer format of every pass (defined beside the device helpers that make depth
/// buffers; named here too for the passes that plug into the renderer).
pub use crate::gpu::DEPTH_FORMAT;
/// Default screen-space error target of the clip-map, pixels.
pub const DEFAULT_ERROR_PX: f64 = 1.0;
/// Wake culling tolerance: height error allowed per left-out wake source, metres (half a
/// millimetre at the race's scale). Measured against every source alive
/// (`tests/wake_band_limit.rs`): under 0.04 px of height and 2·10⁻³ of slope (0.1°) at every
/// vertex of a three-boat frame; 1 mm erred there by 4.6·10⁻³ of slope, 14 % of that weak
/// wake's steepest (docs/wakes.md).
pub const WAKE_EPSILON_M: f64 = 5e-4;

/// Options of a [`Renderer`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Clip-map error target in pixels.
    pub error_px: f64,
    /// Read back GPU timestamps after each frame (blocks until the GPU is done: for headless
    /// frames and benches; the window app leaves it off).
    pub measure_gpu_time: bool,
    /// Keep a copy of a frame drawn twice in a row (timeline paused, camera still) and
    /// re-present it instead of drawing it again while nothing changes. Costs one texture of
    /// the target's size and one copy per re-presented frame; needs a target with `COPY_SRC |
    /// COPY_DST` (otherwise every frame is drawn).
    pub keep_still_frames: bool,
    /// Draw the frame at this fraction of the target's size per side and stretch it onto the
    /// target (bilinear): 0.5 shades a quarter of the pixels. 1: the target's size. The
    /// clip-map's pixel error target is in the drawn frame's pixels. (Phones: see the budget
    /// bench.)
    pub render_scale: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            error_px: DEFAULT_ERROR_PX,
            measure_gpu_time: true,
            keep_still_frames: false,
            render_scale: 1.0,
        }
    }
}

/// What a frame was drawn from, to tell whether the next one would look the same.
#[derive(Debug, Clone, PartialEq)]
struct FrameKey {
    scene: Scene,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    /// [`Renderer::revision`] and the passes' own revisions (e.g. a new camera image).
    revision: u64,
}

/// The frame drawn at [`RenderOptions::render_scale`] and the pass that stretches it onto the
/// target (`shaders/upscale.wgsl`).
struct Upscale {
    pipeline: wgpu::RenderPipeline,
    sampler: wgpu::Sampler,
    /// The smaller frame and its bind group, remade when its size changes.
    frame: Option<(wgpu::Texture, wgpu::BindGroup)>,
}

impl Upscale {
    fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Upscale {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("upscale"),
            source: wgpu::ShaderSource::Wgsl(crate::shader::UPSCALE.into()),
        });
        let pipeline = crate::passes::bufferless_pipeline(
            device,
            crate::passes::BufferlessPipeline {
                label: "upscale",
                module: &module,
                vertex: "vs_main",
                fragment: "fs_main",
                layouts: None,
                format,
                blend: None,
                depth: None,
            },
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("upscale"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Upscale {
            pipeline,
            sampler,
            frame: None,
        }
    }

    /// The smaller frame's view and bind group at `size`.
    fn frame(
        &mut self,
        device: &wgpu::Device,
        size: [u32; 2],
        format: wgpu::TextureFormat,
    ) -> (wgpu::TextureView, wgpu::BindGroup) {
        let fits = self
            .frame
            .as_ref()
            .is_some_and(|(t, _)| [t.width(), t.height()] == size);
        if !fits {
            let texture = crate::gpu::texture_2d(
                device,
                "scaled frame",
                size,
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            );
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("upscale"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(
                            &texture.create_view(&Default::default()),
                        ),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                ],
            });
            self.frame = Some((texture, group));
        }
        let (texture, group) = self.frame.as_ref().expect("made above");
        (texture.create_view(&Default::default()), group.clone())
    }
}

/// The last frame drawn twice in a row, kept for re-presenting.
struct StillFrame {
    key: FrameKey,
    texture: wgpu::Texture,
    report: FrameReport,
}

pub struct Renderer {
    pub targets: Targets,
    pub options: RenderOptions,
    bindings: FrameBindings,
    passes: Vec<Box<dyn Pass>>,
    depth: crate::gpu::DepthBuffer,
    timer: Option<GpuTimer>,
    stats: Option<PassStats>,
    wake: Option<Arc<ocean::wake::Wake>>,
    /// Bumped when an input outside the [`Scene`] changes (wakes, passes).
    revision: u64,
    /// The key of the last frame drawn, and the kept copy of a still frame.
    last: Option<FrameKey>,
    still: Option<StillFrame>,
    upscale: Option<Upscale>,
    /// Memory budget of a frame's wake buffers, bytes (within the device's limits).
    wake_budget: u64,
    /// Most wake sources a frame draws (a quality tier's budget; default unlimited).
    wake_sources: usize,
    /// Bins every frame's wake sources, its memory and the last frame's buffers kept.
    wake_binner: crate::wake_bins::WakeBinner,
    /// The real sea's water (its type colours the open sea's body).
    water_look: crate::water_look::WaterLook,
    /// The room's diffuse radiance over the camera image (the AR water's and the boats'), in
    /// the frames where a pass draws the camera image; none: the open sea under the sun and
    /// sky.
    room_light: Option<[f64; 3]>,
}

impl Renderer {
    /// A renderer drawing into `colour` textures (linear shader output; use an sRGB format).
    pub fn new(gpu: &Gpu, colour: wgpu::TextureFormat, options: RenderOptions) -> Renderer {
        let device = &gpu.device;
        let targets = Targets {
            colour,
            depth: DEPTH_FORMAT,
        };
        let bindings = FrameBindings::new(device);
        let passes: Vec<Box<dyn Pass>> = vec![
            Box::new(SkyPass::new(device, &bindings.layout, targets)),
            Box::new(WaterPass::new(
                device,
                &bindings.layout,
                targets,
                crate::passes::water::supports_wakes(&gpu.adapter),
            )),
            Box::new(BoatsPass::new(device, &bindings.layout, targets)),
        ];
        let timer = GpuTimer::new(gpu);
        let stats = PassStats::new(gpu);
        Renderer {
            targets,
            options,
            bindings,
            passes,
            depth: crate::gpu::DepthBuffer::new("depth"),
            timer,
            stats,
            wake: None,
            revision: 0,
            last: None,
            still: None,
            upscale: None,
            wake_budget: crate::wake_bins::WAKE_BUFFER_BUDGET_BYTES,
            wake_sources: usize::MAX,
            wake_binner: Default::default(),
            water_look: Default::default(),
            room_light: None,
        }
    }

    /// Something the frame depends on changed outside the [`Scene`] (a camera image, a
    /// setting): the next frame is drawn, not re-presented.
    pub fn invalidate(&mut self) {
        self.revision += 1;
    }

    /// The boats' wakes to draw (built once per race by the caller), or none.
    pub fn set_wake(&mut self, wake: Option<Arc<ocean::wake::Wake>>) {
        self.wake = wake;
        self.invalidate();
    }

    /// The wakes drawn now (a quality tier's spacing is read from them).
    pub fn wake(&self) -> Option<&Arc<ocean::wake::Wake>> {
        self.wake.as_ref()
    }

    /// The memory budget of a frame's wake buffers, bytes (default
    /// [`crate::wake_bins::WAKE_BUFFER_BUDGET_BYTES`]; the device's limits cap it too).
    pub fn set_wake_buffer_budget(&mut self, bytes: u64) {
        self.wake_budget = bytes;
        self.invalidate();
    }

    /// The most wake sources a frame draws (a quality tier's budget): beyond it the least
    /// visible are left out, with the error bound in the frame report (`wake_bins::fit`).
    pub fn set_wake_source_budget(&mut self, sources: usize) {
        self.wake_sources = sources;
        self.invalidate();
    }

    /// The most wake sources a frame draws ([`Renderer::set_wake_source_budget`]).
    pub fn wake_source_budget(&self) -> usize {
        self.wake_sources
    }

    /// The real sea's water: its type sets the open sea's body colour (`view_light`).
    /// Unchanged, nothing happens (callers may hand it every frame).
    pub fn set_water_look(&mut self, look: crate::water_look::WaterLook) {
        if self.water_look != look {
            self.water_look = look;
            self.invalidate();
        }
    }

    /// The room's diffuse radiance per band that the water over the camera image takes, so the
    /// boats take it too (`view_light::boat_in_room`), in each frame where a pass that fills
    /// the background (the camera image) runs; none: the open sea's sun and sky.
    pub fn set_room_light(&mut self, radiance: Option<[f64; 3]>) {
        self.room_light = radiance;
        self.invalidate();
    }

    /// Add a pass (effects, wakes, pool) after the built-in ones; it draws in that order.
    pub fn add_pass(&mut self, pass: Box<dyn Pass>) {
        self.invalidate();
        self.passes.push(pass);
    }

    /// Whether a pass named `name` is registered (the app adds its segment passes once).
    pub fn has_pass(&self, name: &str) -> bool {
        self.passes.iter().any(|p| p.name() == name)
    }

    /// Put `pass` in the place of the pass named `name` (the AR effects replace "water" with
    /// a pass that draws the same mesh shaded once with the effects); false if there is none.
    pub fn replace_pass(&mut self, name: &str, pass: Box<dyn Pass>) -> bool {
        self.invalidate();
        match self.passes.iter_mut().find(|p| p.name() == name) {
            Some(slot) => {
                *slot = pass;
                true
            }
            None => false,
        }
    }

    /// The layout of bind group 0, for passes built outside this crate's `passes` module.
    pub fn frame_layout(&self) -> &wgpu::BindGroupLayout {
        &self.bindings.layout
    }

    /// Plan and draw `scene` into `target` (`size` pixels); returns the frame's record.
    ///
    /// With [`RenderOptions::keep_still_frames`], a frame that looks like the last one (same
    /// scene, size and inputs: the timeline paused and the camera still) is not drawn again:
    /// the second identical frame is kept, and from the third on the kept copy is
    /// re-presented, every pass recorded as skipped with [`crate::frame::FRAME_REUSED`].
    ///
    /// A device error while the frame is recorded (validation, out of memory, internal) is
    /// caught in error scopes, logged, and fails this frame with one line; the renderer and
    /// the device stay usable for the next frame.
    pub fn render(
        &mut self,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        size: [u32; 2],
        scene: &Scene,
    ) -> Result<FrameReport, GpuError> {
        let scopes = [
            wgpu::ErrorFilter::Validation,
            wgpu::ErrorFilter::OutOfMemory,
            wgpu::ErrorFilter::Internal,
        ]
        .map(|f| gpu.device.push_error_scope(f));
        let report = self.render_unchecked(gpu, target, size, scene);
        // Popped in reverse order of pushing, as a stack.
        let [a, b, c] = scopes;
        let errors = [c, b, a].map(|s| pollster::block_on(s.pop()));
        let Some(error) = errors.into_iter().flatten().next() else {
            return Ok(report);
        };
        // Nothing of a failed frame is kept for re-presenting.
        self.last = None;
        self.still = None;
        let line = crate::gpu::one_line(&error.to_string());
        log::error!("frame at t = {} s failed: {line}", scene.t);
        Err(GpuError(format!("the GPU refused this frame: {line}")))
    }

    fn render_unchecked(
        &mut self,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        size: [u32; 2],
        scene: &Scene,
    ) -> FrameReport {
        let texture = target.texture();
        let copy = wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST;
        if !self.options.keep_still_frames || !texture.usage().contains(copy) {
            self.last = None;
            self.still = None;
            return self.draw_scaled(gpu, target, size, scene);
        }
        let key = FrameKey {
            scene: scene.clone(),
            size,
            format: texture.format(),
            revision: self.revision + self.passes.iter().map(|p| p.revision()).sum::<u64>(),
        };
        if let Some(still) = self.still.as_ref().filter(|s| s.key == key) {
            copy_whole(gpu, &still.texture, texture);
            return still.report.reused();
        }
        self.still = None;
        let report = self.draw_scaled(gpu, target, size, scene);
        if self.last.as_ref() == Some(&key) {
            // Drawn twice alike: keep it for the frames to come.
            let kept = crate::gpu::texture_2d(&gpu.device, "still frame", size, key.format, copy);
            copy_whole(gpu, texture, &kept);
            self.still = Some(StillFrame {
                key: key.clone(),
                texture: kept,
                report: report.clone(),
            });
        }
        self.last = Some(key);
        report
    }

    /// Draw one frame at [`RenderOptions::render_scale`] of `size` and stretch it onto
    /// `target`; the record's size is the drawn frame's.
    fn draw_scaled(
        &mut self,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        size: [u32; 2],
        scene: &Scene,
    ) -> FrameReport {
        let scale = self.options.render_scale;
        if !(scale > 0.0 && scale < 1.0) {
            return self.draw(gpu, target, size, scene);
        }
        let inner = size.map(|v| ((f64::from(v) * scale).round() as u32).max(1));
        let format = self.targets.colour;
        let up = self
            .upscale
            .get_or_insert_with(|| Upscale::new(&gpu.device, format));
        let (view, group) = up.frame(&gpu.device, inner, format);
        let pipeline = up.pipeline.clone();
        let report = self.draw(gpu, &view, inner, scene);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass =
                crate::gpu::colour_pass(&mut enc, "upscale", target, wgpu::Color::BLACK, None);
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([enc.finish()]);
        report
    }

    /// Plan, record and measure one frame.
    fn draw(
        &mut self,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        size: [u32; 2],
        scene: &Scene,
    ) -> FrameReport {
        let raised = scene.camera_above_water();
        if let Some((_, m)) = &raised {
            log::warn!(
                "the camera eye is under the sea surface (or within {} m of it): raised by \
                 {m:.2} m; the water is not drawn from below",
                crate::scene::CAMERA_CLEARANCE_M
            );
        }
        let scene = raised.as_ref().map_or(scene, |(s, _)| s);
        let mut frame = FrameContext::new(scene, size, self.options.error_px);
        frame.uniform.water_body = crate::view_light::water_body_uniform(&self.water_look);
        if let Some(w) = &self.wake {
            let limits = (self.wake_budget, self.wake_sources);
            gather_wakes(gpu, w, limits, &mut self.wake_binner, &mut frame);
        }
        let depth = self.depth.view(gpu, size);
        // Plan.
        let (run, mut records) = self.plan(gpu, &frame);
        // The room's light only in a frame that shows the camera image: a switch of the
        // image, live, relights the boats from the next frame on.
        let image_shown = run.iter().any(|&i| self.passes[i].fills_background());
        if let Some(l) = self.room_light.filter(|_| image_shown) {
            frame.uniform.room_light = [l[0] as f32, l[1] as f32, l[2] as f32, 1.0];
        }
        self.bindings
            .upload(&gpu.queue, &frame.uniform, &frame.waves);
        // Record.
        let measure = self.options.measure_gpu_time;
        let timer = self
            .timer
            .as_ref()
            .filter(|_| measure && GpuTimer::fits(run.len()));
        // Pipeline statistics block on a read-back too: only when measuring.
        let stats = self.stats.as_ref().filter(|s| measure && s.fits(run.len()));
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        // The passes' offscreen work first (reflection texture, caustic map), in the frame's
        // encoder: one command buffer, one submission.
        let offscreen = record_offscreen(&mut self.passes, &mut enc, &run, timer);
        if run.is_empty() {
            // Nothing is needed: still clear, so the frame shows no stale image.
            crate::gpu::colour_pass(&mut enc, "clear", target, wgpu::Color::BLACK, None);
        }
        let recording = Recording {
            target,
            depth: &depth,
            frame_group: &self.bindings.group,
            timer,
            stats,
        };
        recording.passes(&mut enc, &self.passes, &run, &mut records);
        if !run.is_empty() {
            if let Some(st) = stats {
                st.resolve(&mut enc, run.len());
            }
            if let Some(t) = timer {
                let timed_offscreen = offscreen.iter().flatten().count() as u32;
                t.resolve(&mut enc, run.len(), timed_offscreen);
            }
        }
        gpu.queue.submit([enc.finish()]);
        // Measure.
        let (triangles_source, shader_invocations) =
            measure_frame(gpu, timer, stats, &run, &offscreen, &mut records);
        let report = self.report(
            gpu,
            &frame,
            records,
            (triangles_source, shader_invocations),
            raised.as_ref().map(|(_, m)| *m),
        );
        // The wake bins are uploaded: their buffers serve the next frame's.
        self.wake_binner
            .recycle(std::mem::take(&mut frame.wake_bins));
        report
    }

    /// Plan the frame: each pass's decision (with the backdrop rule), the passes that run
    /// prepared. Returns their indices and every pass's record.
    fn plan(&mut self, gpu: &Gpu, frame: &FrameContext) -> (Vec<usize>, Vec<PassRecord>) {
        let mut records = Vec::new();
        let mut run = Vec::new();
        let mut decisions: Vec<Result<String, String>> =
            self.passes.iter().map(|p| p.plan(frame)).collect();
        hide_backdrops(&self.passes, &mut decisions);
        for ((i, p), decision) in self.passes.iter_mut().enumerate().zip(decisions) {
            if decision.is_ok() {
                p.prepare(gpu, frame);
                run.push(i);
            }
            let ran = decision.is_ok();
            records.push(PassRecord {
                name: p.name().into(),
                condition: p.condition().into(),
                ran,
                reason: decision.unwrap_or_else(|e| e),
                triangles: 0,
                gpu_ms: None,
                offscreen_gpu_ms: None,
            });
        }
        (run, records)
    }

    /// The frame's report from the passes' records.
    fn report(
        &self,
        gpu: &Gpu,
        frame: &FrameContext,
        records: Vec<PassRecord>,
        (triangles_source, shader_invocations): (&str, Vec<ShaderInvocations>),
        camera_raised_m: Option<f64>,
    ) -> FrameReport {
        let gpu_ms = records
            .iter()
            .filter_map(PassRecord::total_gpu_ms)
            .reduce(|a, b| a + b);
        FrameReport {
            t: frame.scene.t,
            size: frame.size,
            adapter: gpu.describe(),
            triangles: records.iter().map(|r| r.triangles).sum(),
            triangles_source: triangles_source.into(),
            passes: records,
            shader_invocations,
            gpu_ms,
            clipmap: ClipMapRecord::of(frame),
            wakes: self.wake.as_ref().map(|_| WakeRecord {
                sources: frame.wakes.sources.len(),
                culled: frame.wakes.culled,
                cull_bound_m: frame.wakes.cull_bound,
                dropped: frame.wake_drop.dropped,
                drop_bound_m: frame.wake_drop.height_bound_m,
                drop_foam_bound: frame.wake_drop.foam_bound,
                buffer_cap_bytes: frame.wake_drop.cap_bytes,
            }),
            reused_last_frame: false,
            camera_raised_m,
        }
    }
}

/// The wake sources of `wake` that can reach any water the clip-map draws, binned for the GPU
/// within `budget` bytes and at most `max_sources` sources, into `frame`.
fn gather_wakes(
    gpu: &Gpu,
    wake: &ocean::wake::Wake,
    (budget, max_sources): (u64, usize),
    binner: &mut crate::wake_bins::WakeBinner,
    frame: &mut FrameContext,
) {
    let cap = crate::wake_bins::wake_buffer_cap(&gpu.device.limits(), budget);
    bin_wakes(wake, cap, max_sources, binner, frame);
    if frame.wake_drop.dropped > 0 {
        // Every frame of a bunched fleet drops some: the frame report carries it, the
        // log only at info (a warning per frame would flood the terminal).
        log::info!(
            "{} wake sources dropped to fit the {} byte wake buffer cap: height error \
             ≤ {:.2e} m",
            frame.wake_drop.dropped,
            cap,
            frame.wake_drop.height_bound_m
        );
    }
}

/// The frame's wake sources (culled to the clip-map's reach with [`WAKE_EPSILON_M`]) binned
/// for the clip-map's vertices, each band limited for its level's spacing, within `cap` bytes
/// and `max_sources` sources: `frame.wakes`, `frame.wake_bins`, `frame.wake_drop`. What the
/// renderer uploads, and what the budget model counts. `binner` is the renderer's, kept from
/// frame to frame (the bins do not depend on it).
pub fn bin_wakes(
    wake: &ocean::wake::Wake,
    cap: u64,
    max_sources: usize,
    binner: &mut crate::wake_bins::WakeBinner,
    frame: &mut FrameContext,
) {
    let scene = frame.scene;
    let eye = DVec2::new(scene.camera.eye.x, scene.camera.eye.z);
    let reach = frame.clipmap.half_extent(frame.clipmap.levels() - 1);
    let view = ocean::wake::WakeView::around([eye.x, eye.y], reach);
    frame.wakes = wake.gpu_sources(
        scene.t,
        [frame.origin.x, frame.origin.y],
        &view,
        WAKE_EPSILON_M,
    );
    let displacement = scene.sea.total_amplitude();
    let spacing =
        crate::wake_spacing::SampleSpacing::of_mesh(&frame.clipmap, &frame.mesh, eye, displacement);
    let half = reach as f32 * 2.0;
    (frame.wake_bins, frame.wake_drop) =
        binner.fit(&mut frame.wakes, half, cap, max_sources, &spacing);
    frame.uniform.counts[2] = frame.wakes.sources.len() as u32;
}

/// The backdrop rule: a pass that fills every pixel behind the scene (the camera image) hides
/// the sky, so a backdrop pass planned to run is skipped with the reason.
fn hide_backdrops(passes: &[Box<dyn Pass>], decisions: &mut [Result<String, String>]) {
    let Some(cover) = passes
        .iter()
        .zip(decisions.iter())
        .find(|(p, d)| p.fills_background() && d.is_ok())
        .map(|(p, _)| p.name())
    else {
        return;
    };
    for (p, d) in passes.iter().zip(decisions.iter_mut()) {
        if p.is_backdrop() && d.is_ok() {
            *d = Err(format!(
                "hidden: the {cover} pass fills every pixel behind the scene"
            ));
        }
    }
}

/// Record the offscreen work of the passes that run (`run`). Returns, for each, its index
/// among the passes that recorded any (their timestamp slots), or `None`.
fn record_offscreen(
    passes: &mut [Box<dyn Pass>],
    enc: &mut wgpu::CommandEncoder,
    run: &[usize],
    timer: Option<&GpuTimer>,
) -> Vec<Option<u32>> {
    let mut offscreen = Vec::with_capacity(run.len());
    let mut timed_offscreen = 0;
    for &i in run {
        let timestamps = timer.map(|t| t.offscreen(timed_offscreen));
        let recorded = passes[i].record_offscreen(enc, timestamps);
        offscreen.push(recorded.then_some(timed_offscreen));
        timed_offscreen += u32::from(recorded);
    }
    offscreen
}

/// Where and with what the passes of a frame record.
struct Recording<'a> {
    target: &'a wgpu::TextureView,
    depth: &'a wgpu::TextureView,
    frame_group: &'a wgpu::BindGroup,
    timer: Option<&'a GpuTimer>,
    stats: Option<&'a PassStats>,
}

impl Recording<'_> {
    /// Record the compute stage and the render pass of every pass that runs (`run`), in order;
    /// the first clears the targets. The triangles each draws go into its record.
    fn passes(
        &self,
        enc: &mut wgpu::CommandEncoder,
        passes: &[Box<dyn Pass>],
        run: &[usize],
        records: &mut [PassRecord],
    ) {
        for (k, &i) in run.iter().enumerate() {
            let first = k == 0;
            {
                // The pass's compute stage (empty for most; always begun, so that its
                // timestamps are written).
                let mut compute = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(passes[i].name()),
                    timestamp_writes: self.timer.map(|t| t.compute(k)),
                });
                compute.set_bind_group(0, self.frame_group, &[]);
                passes[i].dispatch(&mut compute);
            }
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(passes[i].name()),
                color_attachments: &[Some(crate::gpu::colour_attachment(
                    self.target,
                    first.then_some(wgpu::Color::BLACK),
                ))],
                depth_stencil_attachment: Some(crate::gpu::depth_attachment(self.depth, first)),
                timestamp_writes: self.timer.map(|t| t.render(k)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, self.frame_group, &[]);
            if let Some(st) = self.stats {
                st.begin(&mut pass, k);
            }
            records[i].triangles = passes[i].draw(&mut pass);
            if self.stats.is_some() {
                PassStats::end(&mut pass);
            }
        }
    }
}

/// Read the submitted frame's measurements into the records of the passes that ran (`run`):
/// GPU milliseconds and, with pipeline statistics, the primitives drawn. Returns where the
/// triangle counts come from and each pass's shader invocations (with pipeline statistics).
fn measure_frame(
    gpu: &Gpu,
    timer: Option<&GpuTimer>,
    stats: Option<&PassStats>,
    run: &[usize],
    offscreen: &[Option<u32>],
    records: &mut [PassRecord],
) -> (&'static str, Vec<ShaderInvocations>) {
    let mut shader_invocations = Vec::new();
    if run.is_empty() {
        return ("counted", shader_invocations);
    }
    if let Some(t) = timer {
        match t.read(gpu, offscreen) {
            Ok(durations) => {
                for (&i, (own, off)) in run.iter().zip(durations) {
                    records[i].gpu_ms = Some(own);
                    records[i].offscreen_gpu_ms = off;
                }
            }
            Err(e) => log::warn!("no GPU timings this frame: {e}"),
        }
    }
    let mut triangles_source = "counted";
    if let Some(st) = stats {
        match st.read(gpu, run.len()) {
            Ok(counts) => {
                for (&i, [vertex, prims, fragment]) in run.iter().zip(counts) {
                    records[i].triangles = prims;
                    shader_invocations.push(ShaderInvocations {
                        pass: records[i].name.clone(),
                        vertex,
                        fragment,
                    });
                }
                triangles_source = "pipeline_statistics";
            }
            Err(e) => log::warn!("no pipeline statistics this frame: {e}"),
        }
    }
    (triangles_source, shader_invocations)
}

/// Copy all of `from` into `to` (same size and format).
fn copy_whole(gpu: &Gpu, from: &wgpu::Texture, to: &wgpu::Texture) {
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    enc.copy_texture_to_texture(from.as_image_copy(), to.as_image_copy(), from.size());
    gpu.queue.submit([enc.finish()]);
}

/// Render `scene` offscreen at `size` and read it back: the image and the frame's record.
pub fn render_image(
    gpu: &Gpu,
    renderer: &mut Renderer,
    scene: &Scene,
    size: [u32; 2],
) -> Result<(image::RgbaImage, FrameReport), crate::gpu::GpuError> {
    let (image, report) = gpu.render_offscreen(size, renderer.targets.colour, |view| {
        renderer.render(gpu, view, size, scene)
    })?;
    Ok((image, report?))
}

/// The offscreen colour format: 8-bit sRGB, what PNGs hold.
pub const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
