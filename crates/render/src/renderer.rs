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

/// Depth buffer format of every pass.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Default screen-space error target of the clip-map, pixels.
pub const DEFAULT_ERROR_PX: f64 = 1.0;
/// Wake culling tolerance: height error allowed per left-out wake source, metres.
pub const WAKE_EPSILON_M: f64 = 1e-4;

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

/// Pipeline-statistics queries, one per pass: vertex shader invocations, primitives entering
/// the clipper and fragment shader invocations, in that order (wgpu writes a query's counters
/// in the order of their bits).
struct Stats {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    capacity: u32,
}

/// Passes a frame can time.
const TIMED_PASSES: u32 = 16;
/// Counters each pipeline-statistics query writes ([`Stats`]).
const STATS_PER_QUERY: u64 = 3;
/// Timestamp slots of pass k: 4k.. begin and end of its render pass and its compute stage.
/// The passes with offscreen work follow from OFFSCREEN_SLOTS, two each, in order: only
/// written slots are resolved (a query never written has no defined value), and a resolve
/// lands at a multiple of 256 bytes (wgpu::QUERY_RESOLVE_BUFFER_ALIGNMENT).
const OFFSCREEN_SLOTS: u32 = 4 * TIMED_PASSES;

struct Timer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
}

/// The plan's reason for every pass when the last frame is re-presented.
pub const FRAME_REUSED: &str =
    "timeline paused and camera still: the last frame is re-presented (a copy), nothing is drawn";

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
    timer: Option<Timer>,
    stats: Option<Stats>,
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
        let timer = gpu
            .features
            .contains(wgpu::Features::TIMESTAMP_QUERY)
            .then(|| {
                // Per pass: begin and end of its render pass, its compute stage and its
                // offscreen passes (OFFSCREEN_SLOTS).
                let capacity = 6 * TIMED_PASSES;
                let size = u64::from(capacity) * 8;
                Timer {
                    queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                        label: Some("pass timestamps"),
                        ty: wgpu::QueryType::Timestamp,
                        count: capacity,
                    }),
                    resolve: device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("timestamps"),
                        size,
                        usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                        mapped_at_creation: false,
                    }),
                    read: device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("timestamps read"),
                        size,
                        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    }),
                }
            });
        let stats = gpu
            .features
            .contains(wgpu::Features::PIPELINE_STATISTICS_QUERY)
            .then(|| {
                let capacity = 16;
                let size = u64::from(capacity) * 8 * STATS_PER_QUERY;
                let buffer = |label, usage| {
                    device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(label),
                        size,
                        usage,
                        mapped_at_creation: false,
                    })
                };
                Stats {
                    queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                        label: Some("pass primitives"),
                        ty: wgpu::QueryType::PipelineStatistics(
                            wgpu::PipelineStatisticsTypes::VERTEX_SHADER_INVOCATIONS
                                | wgpu::PipelineStatisticsTypes::CLIPPER_INVOCATIONS
                                | wgpu::PipelineStatisticsTypes::FRAGMENT_SHADER_INVOCATIONS,
                        ),
                        count: capacity,
                    }),
                    resolve: buffer(
                        "primitives",
                        wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                    ),
                    read: buffer(
                        "primitives read",
                        wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    ),
                    capacity,
                }
            });
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

    /// Add a pass (effects, wakes, pool) after the built-in ones; it draws in that order.
    pub fn add_pass(&mut self, pass: Box<dyn Pass>) {
        self.invalidate();
        self.passes.push(pass);
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
    /// re-presented, every pass recorded as skipped with [`FRAME_REUSED`].
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

    /// Plan and draw one frame.
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
        if let Some(w) = &self.wake {
            // Sources that can reach any water the clip-map draws.
            let eye = DVec2::new(scene.camera.eye.x, scene.camera.eye.z);
            let reach = frame.clipmap.half_extent(frame.clipmap.levels() - 1);
            let view = ocean::wake::WakeView::around([eye.x, eye.y], reach);
            frame.wakes = w.gpu_sources(
                scene.t,
                [frame.origin.x, frame.origin.y],
                &view,
                WAKE_EPSILON_M,
            );
            let half = frame.clipmap.half_extent(frame.clipmap.levels() - 1) as f32 * 2.0;
            let cap = crate::wake_bins::wake_buffer_cap(&gpu.device.limits(), self.wake_budget);
            (frame.wake_bins, frame.wake_drop) =
                crate::wake_bins::fit(&mut frame.wakes, half, cap, self.wake_sources);
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
            frame.uniform.counts[2] = frame.wakes.sources.len() as u32;
        }
        self.bindings
            .upload(&gpu.queue, &frame.uniform, &frame.waves);
        let depth = self.depth.view(gpu, size);
        let mut records = Vec::new();
        let mut run = Vec::new();
        let mut decisions: Vec<Result<String, String>> =
            self.passes.iter().map(|p| p.plan(&frame)).collect();
        // A pass that fills every pixel behind the scene (the camera image) hides the sky.
        if let Some(cover) = self
            .passes
            .iter()
            .zip(&decisions)
            .find(|(p, d)| p.fills_background() && d.is_ok())
            .map(|(p, _)| p.name())
        {
            for (p, d) in self.passes.iter().zip(&mut decisions) {
                if p.is_backdrop() && d.is_ok() {
                    *d = Err(format!(
                        "hidden: the {cover} pass fills every pixel behind the scene"
                    ));
                }
            }
        }
        for ((i, p), decision) in self.passes.iter_mut().enumerate().zip(decisions) {
            if decision.is_ok() {
                p.prepare(gpu, &frame);
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
        let timer = self
            .timer
            .as_ref()
            .filter(|_| self.options.measure_gpu_time && run.len() <= TIMED_PASSES as usize);
        // Pipeline statistics block on a read-back too: only when measuring.
        let stats = self
            .stats
            .as_ref()
            .filter(|s| self.options.measure_gpu_time && run.len() <= s.capacity as usize);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        // The passes' offscreen work first (reflection texture, caustic map), in the frame's
        // encoder: one command buffer, one submission.
        let slot = |k: usize, i: u32| 4 * k as u32 + i;
        // For each pass that recorded offscreen work, its index among those.
        let mut offscreen: Vec<Option<u32>> = Vec::with_capacity(run.len());
        let mut timed_offscreen = 0;
        for &i in &run {
            let timestamps = timer.map(|t| crate::frame::OffscreenTimestamps {
                queries: &t.queries,
                begin: OFFSCREEN_SLOTS + 2 * timed_offscreen,
                end: OFFSCREEN_SLOTS + 2 * timed_offscreen + 1,
            });
            let recorded = self.passes[i].record_offscreen(&mut enc, timestamps);
            offscreen.push(recorded.then_some(timed_offscreen));
            timed_offscreen += u32::from(recorded);
        }
        if run.is_empty() {
            // Nothing is needed: still clear, so the frame shows no stale image.
            crate::gpu::colour_pass(&mut enc, "clear", target, wgpu::Color::BLACK, None);
        }
        for (k, &i) in run.iter().enumerate() {
            let first = k == 0;
            {
                // The pass's compute stage (empty for most; always begun, so that its
                // timestamps are written).
                let mut compute = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(self.passes[i].name()),
                    timestamp_writes: timer.map(|t| wgpu::ComputePassTimestampWrites {
                        query_set: &t.queries,
                        beginning_of_pass_write_index: Some(slot(k, 2)),
                        end_of_pass_write_index: Some(slot(k, 3)),
                    }),
                });
                compute.set_bind_group(0, &self.bindings.group, &[]);
                self.passes[i].dispatch(&mut compute);
            }
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(self.passes[i].name()),
                color_attachments: &[Some(crate::gpu::colour_attachment(
                    target,
                    first.then_some(wgpu::Color::BLACK),
                ))],
                depth_stencil_attachment: Some(crate::gpu::depth_attachment(&depth, first)),
                timestamp_writes: timer.map(|t| wgpu::RenderPassTimestampWrites {
                    query_set: &t.queries,
                    beginning_of_pass_write_index: Some(slot(k, 0)),
                    end_of_pass_write_index: Some(slot(k, 1)),
                }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.bindings.group, &[]);
            if let Some(st) = stats {
                pass.begin_pipeline_statistics_query(&st.queries, k as u32);
            }
            records[i].triangles = self.passes[i].draw(&mut pass);
            if stats.is_some() {
                pass.end_pipeline_statistics_query();
            }
        }
        if let Some(st) = stats
            && !run.is_empty()
        {
            let n = run.len() as u32;
            enc.resolve_query_set(&st.queries, 0..n, &st.resolve, 0);
            enc.copy_buffer_to_buffer(
                &st.resolve,
                0,
                &st.read,
                0,
                u64::from(n) * 8 * STATS_PER_QUERY,
            );
        }
        if let Some(t) = timer
            && !run.is_empty()
        {
            let n = 4 * run.len() as u32;
            enc.resolve_query_set(&t.queries, 0..n, &t.resolve, 0);
            let m = 2 * timed_offscreen;
            let at = u64::from(OFFSCREEN_SLOTS) * 8;
            if m > 0 {
                enc.resolve_query_set(
                    &t.queries,
                    OFFSCREEN_SLOTS..OFFSCREEN_SLOTS + m,
                    &t.resolve,
                    at,
                );
            }
            enc.copy_buffer_to_buffer(&t.resolve, 0, &t.read, 0, at + u64::from(m) * 8);
        }
        gpu.queue.submit([enc.finish()]);
        if let Some(t) = timer
            && !run.is_empty()
        {
            match gpu.read_buffer(&t.read) {
                Ok(bytes) => {
                    let ticks: &[u64] = bytemuck::cast_slice(&bytes);
                    let period_ns = f64::from(gpu.queue.get_timestamp_period());
                    let ms = |ticks: u64| ticks as f64 * period_ns * 1e-6;
                    for (k, &i) in run.iter().enumerate() {
                        let q = &ticks[slot(k, 0) as usize..slot(k + 1, 0) as usize];
                        let own = q[1].saturating_sub(q[0]) + q[3].saturating_sub(q[2]);
                        records[i].gpu_ms = Some(ms(own));
                        records[i].offscreen_gpu_ms = offscreen[k].map(|m| {
                            let o = (OFFSCREEN_SLOTS + 2 * m) as usize;
                            ms(ticks[o + 1].saturating_sub(ticks[o]))
                        });
                    }
                }
                Err(e) => log::warn!("no GPU timings this frame: {e}"),
            }
        }
        let mut triangles_source = "counted";
        let mut shader_invocations = Vec::new();
        if let Some(st) = stats
            && !run.is_empty()
        {
            match gpu.read_buffer(&st.read) {
                Ok(bytes) => {
                    let counts: &[u64] = bytemuck::cast_slice(&bytes);
                    for (k, &i) in run.iter().enumerate() {
                        let [vertex, prims, fragment] = std::array::from_fn(|c| counts[3 * k + c]);
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
        let gpu_ms = records
            .iter()
            .filter_map(PassRecord::total_gpu_ms)
            .reduce(|a, b| a + b);
        FrameReport {
            t: scene.t,
            size,
            adapter: gpu.describe(),
            triangles: records.iter().map(|r| r.triangles).sum(),
            triangles_source: triangles_source.into(),
            passes: records,
            shader_invocations,
            gpu_ms,
            clipmap: ClipMapRecord::of(&frame),
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
            camera_raised_m: raised.as_ref().map(|(_, m)| *m),
        }
    }
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
