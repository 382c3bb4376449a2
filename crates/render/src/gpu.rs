//! Device setup in one place for the three targets: a desktop window (winit), headless
//! (render into a texture and read it back as an image) and an Android surface (a raw window
//! handle from the native activity). Tests get their device from [`test_gpu`].
//!
//! Optional features (timestamp and pipeline-statistics queries) are requested only where the
//! adapter has them; the frame planner reads [`Gpu::features`] to know what it can measure.

use std::fmt;
use std::sync::Arc;

use wgpu::{Backends, Features};

/// Depth buffer format of every pass.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Features Regatta uses when the adapter has them; none is required.
pub(crate) const OPTIONAL_FEATURES: Features = Features::TIMESTAMP_QUERY
    .union(Features::TIMESTAMP_QUERY_INSIDE_ENCODERS)
    .union(Features::PIPELINE_STATISTICS_QUERY);

/// Why no device could be set up: one sentence for a person.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuError(pub String);

impl fmt::Display for GpuError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for GpuError {}

/// A wgpu error message (several indented lines) as one line.
pub fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// An adapter, its device and queue, and what the device can do.
pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// Optional features that this device has enabled (a subset of [`OPTIONAL_FEATURES`]).
    pub features: Features,
}

impl fmt::Debug for Gpu {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let info = self.adapter.get_info();
        write!(f, "Gpu({} on {:?})", info.name, info.backend)
    }
}

/// A window surface with its configuration (desktop or Android).
pub struct SurfaceTarget {
    pub surface: wgpu::Surface<'static>,
    pub config: wgpu::SurfaceConfiguration,
}

impl SurfaceTarget {
    /// Reconfigure after a resize; a zero size (minimised window) is ignored.
    pub fn resize(&mut self, device: &wgpu::Device, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(device, &self.config);
    }
}

fn instance(backends: Backends) -> wgpu::Instance {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle().with_env();
    // The caller's backends win, but WGPU_BACKEND still narrows them.
    desc.backends = if std::env::var_os("WGPU_BACKEND").is_some() {
        desc.backends & backends
    } else {
        backends
    };
    wgpu::Instance::new(desc)
}

impl Gpu {
    /// A device with no surface: for `regatta render`, tests and benches. Among `backends`
    /// the primary ones (Vulkan, Metal, DX12) are tried first, OpenGL only without them.
    pub fn headless(backends: Backends) -> Result<Gpu, GpuError> {
        let primary = backends & Backends::PRIMARY;
        if !primary.is_empty() && primary != backends {
            if let Ok(gpu) = Self::headless(primary) {
                return Ok(gpu);
            }
            return Self::headless(backends - primary);
        }
        let instance = instance(backends);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .map_err(|e| GpuError(format!("no GPU adapter for {backends:?}: {e}")))?;
        Self::from_adapter(instance, adapter)
    }

    /// A device that can present to `window` (a winit window behind an `Arc`), and the
    /// configured surface of `width` × `height` pixels.
    pub fn for_window(
        window: impl Into<wgpu::SurfaceTarget<'static>>,
        width: u32,
        height: u32,
    ) -> Result<(Gpu, SurfaceTarget), GpuError> {
        let instance = instance(Backends::all());
        let surface = instance
            .create_surface(window)
            .map_err(|e| GpuError(format!("could not create a window surface: {e}")))?;
        Self::with_surface(instance, surface, width, height)
    }

    /// A device among `backends` that presents to the surface `make` creates on its instance
    /// (the app core retries with `Backends::GL` where Vulkan cannot be had or was lost).
    pub fn for_surface(
        backends: Backends,
        make: impl FnOnce(&wgpu::Instance) -> Result<wgpu::Surface<'static>, String>,
        width: u32,
        height: u32,
    ) -> Result<(Gpu, SurfaceTarget), GpuError> {
        let instance = instance(backends);
        let surface = make(&instance)
            .map_err(|e| GpuError(format!("could not create a window surface: {e}")))?;
        Self::with_surface(instance, surface, width, height)
    }

    /// A device that presents to a raw native window (the Android `ANativeWindow` of the
    /// native activity).
    ///
    /// # Safety
    /// The handles must stay valid until the returned surface is dropped.
    pub unsafe fn for_raw_window(
        display: wgpu::rwh::RawDisplayHandle,
        window: wgpu::rwh::RawWindowHandle,
        width: u32,
        height: u32,
    ) -> Result<(Gpu, SurfaceTarget), GpuError> {
        let instance = instance(Backends::VULKAN | Backends::GL);
        // SAFETY: the caller guarantees the handles outlive the surface.
        let surface = unsafe {
            instance.create_surface_unsafe(wgpu::SurfaceTargetUnsafe::RawHandle {
                raw_display_handle: Some(display),
                raw_window_handle: window,
            })
        }
        .map_err(|e| GpuError(format!("could not create the native window surface: {e}")))?;
        Self::with_surface(instance, surface, width, height)
    }

    fn with_surface(
        instance: wgpu::Instance,
        surface: wgpu::Surface<'static>,
        width: u32,
        height: u32,
    ) -> Result<(Gpu, SurfaceTarget), GpuError> {
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }))
        .map_err(|e| GpuError(format!("no GPU adapter can present to this window: {e}")))?;
        let gpu = Self::from_adapter(instance, adapter)?;
        let caps = surface.get_capabilities(&gpu.adapter);
        // Shaders write linear colour; an sRGB surface does the encoding.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| GpuError("the window surface offers no texture format".into()))?;
        // Copies to and from the surface let the renderer keep a still frame and re-present
        // it (RenderOptions::keep_still_frames), where the surface allows them. Not on
        // phones: there the camera image changes every frame, and copy usages can cost a
        // tiled GPU its framebuffer compression.
        let copy = if cfg!(target_os = "android") {
            wgpu::TextureUsages::empty()
        } else {
            wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::COPY_DST
        };
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | (caps.usages & copy);
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width: width.max(1),
            height: height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&gpu.device, &config);
        Ok((gpu, SurfaceTarget { surface, config }))
    }

    fn from_adapter(instance: wgpu::Instance, adapter: wgpu::Adapter) -> Result<Gpu, GpuError> {
        let features = adapter.features() & OPTIONAL_FEATURES;
        let info = adapter.get_info();
        log::info!(
            "GPU: {} ({:?}, {:?}), optional features {features:?}",
            info.name,
            info.backend,
            info.device_type
        );
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("regatta"),
            required_features: features,
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| {
            GpuError(format!(
                "the GPU adapter {} refused a device: {e}",
                info.name
            ))
        })?;
        // wgpu's default handler panics: an error outside the renderer's error scopes (a
        // pipeline built at start-up, a resize) is logged instead, and the frame that meets
        // its consequences fails (Renderer::render's scopes).
        device.on_uncaptured_error(Arc::new(|e: wgpu::Error| {
            log::error!("GPU error: {}", one_line(&e.to_string()));
        }));
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
            features,
        })
    }

    /// The adapter's name and backend, for reports.
    pub fn describe(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({:?})", info.name, info.backend)
    }

    /// Block until the GPU has finished all submitted work.
    pub fn wait(&self) {
        // A lost device is reported by the next call that uses it; waiting has nothing to add.
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }

    /// Read a buffer written by the GPU (it must have `MAP_READ`) into bytes.
    pub(crate) fn read_buffer(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
        let (tx, rx) = std::sync::mpsc::channel();
        buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        self.wait();
        rx.recv()
            .map_err(|_| GpuError("the GPU never answered a buffer read".into()))?
            .map_err(|e| GpuError(format!("could not read a GPU buffer: {e}")))?;
        let bytes = buffer
            .get_mapped_range(..)
            .map_err(|e| GpuError(format!("could not map a GPU buffer: {e}")))?
            .to_vec();
        buffer.unmap();
        Ok(bytes)
    }

    /// Run `pipeline` once per item of `items` (its WGSL workgroups hold
    /// `shader::WORKGROUP_SIZE` invocations) with `groups` bound at 0, 1, …, then read
    /// `output` (it must have `COPY_SRC`) back as bytes.
    pub fn dispatch_and_read(
        &self,
        pipeline: &wgpu::ComputePipeline,
        groups: &[&wgpu::BindGroup],
        items: usize,
        output: &wgpu::Buffer,
    ) -> Result<Vec<u8>, GpuError> {
        let read = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("compute read-back"),
            size: output.size(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(pipeline);
            for (i, group) in groups.iter().enumerate() {
                pass.set_bind_group(i as u32, *group, &[]);
            }
            pass.dispatch_workgroups((items as u32).div_ceil(crate::shader::WORKGROUP_SIZE), 1, 1);
        }
        enc.copy_buffer_to_buffer(output, 0, &read, 0, output.size());
        self.queue.submit([enc.finish()]);
        self.read_buffer(&read)
    }

    /// Draw with `draw` into an offscreen `format` texture of `size` pixels and read it back:
    /// the image and what `draw` returned.
    pub fn render_offscreen<R>(
        &self,
        size: [u32; 2],
        format: wgpu::TextureFormat,
        draw: impl FnOnce(&wgpu::TextureView) -> R,
    ) -> Result<(image::RgbaImage, R), GpuError> {
        let tex = texture_2d(
            &self.device,
            "offscreen",
            size,
            format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let drawn = draw(&tex.create_view(&Default::default()));
        Ok((self.read_texture(&tex)?, drawn))
    }

    /// Copy an RGBA8 texture (it must have `COPY_SRC`) into an image.
    pub fn read_texture(&self, texture: &wgpu::Texture) -> Result<image::RgbaImage, GpuError> {
        let pixels = self.read_texture_bytes(texture, 4)?;
        image::RgbaImage::from_raw(texture.width(), texture.height(), pixels)
            .ok_or_else(|| GpuError("a read-back texture had the wrong size".into()))
    }

    /// Copy a texture (it must have `COPY_SRC`) whose texels are `texel_bytes` bytes wide back
    /// to the CPU: its rows packed one after another (the copy's row padding dropped), row 0
    /// first.
    pub fn read_texture_bytes(
        &self,
        texture: &wgpu::Texture,
        texel_bytes: u32,
    ) -> Result<Vec<u8>, GpuError> {
        let (w, h) = (texture.width(), texture.height());
        let row = w * texel_bytes;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded * h),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(h),
                },
            },
            texture.size(),
        );
        self.queue.submit([enc.finish()]);
        let bytes = self.read_buffer(&buffer)?;
        let mut pixels = Vec::with_capacity((row * h) as usize);
        for y in 0..h as usize {
            let start = y * padded as usize;
            pixels.extend_from_slice(&bytes[start..start + row as usize]);
        }
        Ok(pixels)
    }
}

/// `buffers`, each bound whole, as entries at bindings 0, 1, … in order.
pub fn buffer_entries<'a>(buffers: &[&'a wgpu::Buffer]) -> Vec<wgpu::BindGroupEntry<'a>> {
    buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect()
}

/// A bind group of `buffers`, each bound whole, at bindings 0, 1, … in order.
pub fn buffer_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries = buffer_entries(buffers);
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A colour attachment that is stored: cleared to `clear` first, or (`None`) drawn over what is
/// there.
pub fn colour_attachment(
    view: &wgpu::TextureView,
    clear: Option<wgpu::Color>,
) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: clear.map_or(wgpu::LoadOp::Load, wgpu::LoadOp::Clear),
            store: wgpu::StoreOp::Store,
        },
    }
}

/// A render pass into one colour target and no depth, cleared to `clear` first (the
/// full-screen and map passes: upscale, caustic maps, the frame's clear).
pub fn colour_pass<'e>(
    enc: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    clear: wgpu::Color,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(colour_attachment(target, Some(clear)))],
        depth_stencil_attachment: None,
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// A depth attachment without stencil that is stored: cleared to the far plane (1.0) first when
/// `clear`, else tested against what earlier passes wrote.
pub fn depth_attachment(
    view: &wgpu::TextureView,
    clear: bool,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: if clear {
                wgpu::LoadOp::Clear(1.0)
            } else {
                wgpu::LoadOp::Load
            },
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    }
}

/// A plain 2-D texture of `size` pixels (never empty: a zero-sized frame still gets one texel):
/// one mip level, one sample, no extra view formats.
pub fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    texture_2d_with_views(device, label, size, format, usage, &[])
}

/// [`texture_2d`] that may also be viewed as `view_formats` (e.g. the sRGB-less twin of its
/// format, for a painter that writes linear values).
pub fn texture_2d_with_views(
    device: &wgpu::Device,
    label: &str,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size[0].max(1),
            height: size[1].max(1),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

/// A renderer's depth buffer ([`DEPTH_FORMAT`]), kept between frames and made again only when
/// the frame's size changes.
pub struct DepthBuffer {
    label: &'static str,
    texture: Option<(wgpu::Texture, wgpu::TextureView)>,
}

impl DepthBuffer {
    /// No texture yet: the first [`DepthBuffer::view`] makes it.
    pub fn new(label: &'static str) -> DepthBuffer {
        DepthBuffer {
            label,
            texture: None,
        }
    }

    /// A view of a depth buffer of `size` pixels.
    pub fn view(&mut self, gpu: &Gpu, size: [u32; 2]) -> wgpu::TextureView {
        let fits = self
            .texture
            .as_ref()
            .is_some_and(|(t, _)| t.width() == size[0] && t.height() == size[1]);
        if !fits {
            let tex = texture_2d(
                &gpu.device,
                self.label,
                size,
                DEPTH_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            );
            let view = tex.create_view(&Default::default());
            self.texture = Some((tex, view));
        }
        self.texture
            .as_ref()
            .map(|(_, v)| v.clone())
            .expect("set above")
    }
}

/// A 4-byte buffer written to ask whether a device still takes work.
///
/// wgpu marks a lost device invalid at once (`Device::destroy`, or a driver's loss found by a
/// submit or a fence query) but runs its lost callback only from a poll that finds the queue
/// empty. In between, every write is refused: `Queue::write_buffer_with` returns `None`
/// (wgpu-core's `validate_write_buffer` checks the device first, and an error of the device-lost
/// type goes to no error handler: wgpu says it is "surfaced via callback"). A caller that
/// writes through `write_buffer_with` and cannot take a `None` asks first.
pub struct WriteProbe(wgpu::Buffer);

impl WriteProbe {
    const SIZE: wgpu::BufferSize = wgpu::BufferSize::new(wgpu::COPY_BUFFER_ALIGNMENT).unwrap();

    pub fn new(device: &wgpu::Device) -> WriteProbe {
        WriteProbe(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("device write probe"),
            size: Self::SIZE.get(),
            usage: wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }))
    }

    /// Whether `queue`'s device takes a write (false: it is lost). Costs a 4-byte staging
    /// write, carried out with the next submission.
    pub fn device_takes_writes(&self, queue: &wgpu::Queue) -> bool {
        queue.write_buffer_with(&self.0, 0, Self::SIZE).is_some()
    }
}

/// True when the environment demands a GPU (`REGATTA_REQUIRE_GPU=true`, as CI sets it).
pub fn gpu_required() -> bool {
    std::env::var("REGATTA_REQUIRE_GPU").is_ok_and(|v| v == "true" || v == "1")
}

/// The device for a GPU test, on `backends`. Without an adapter the test must not pass
/// silently: under `REGATTA_REQUIRE_GPU=true` this panics with the reason; otherwise it prints
/// "skipped: no GPU adapter" and returns `None`.
pub fn test_gpu_on(backends: Backends) -> Option<Arc<Gpu>> {
    match Gpu::headless(backends) {
        Ok(gpu) => Some(Arc::new(gpu)),
        Err(e) if gpu_required() => {
            panic!("REGATTA_REQUIRE_GPU=true but no GPU adapter was found: {e}")
        }
        Err(e) => {
            record_skip(&format!("no GPU adapter ({e})"));
            None
        }
    }
}

/// Report a test that skips (no adapter, no display server): `skip_log::record`, the protocol
/// scripts/test.sh counts.
pub use skip_log::record as record_skip;

/// The device for a GPU test on any backend (lavapipe in CI); see [`test_gpu_on`].
pub fn test_gpu() -> Option<Arc<Gpu>> {
    test_gpu_on(Backends::all())
}

/// Bind group layout entries, spelt once: a uniform buffer, a storage buffer, a filterable 2-D
/// float texture and a filtering sampler at `binding`, seen by `stages`.
pub mod layout {
    use wgpu::{BindGroupLayoutEntry, BindingType, BufferBindingType, ShaderStages};

    fn buffer(binding: u32, stages: ShaderStages, ty: BufferBindingType) -> BindGroupLayoutEntry {
        BindGroupLayoutEntry {
            binding,
            visibility: stages,
            ty: BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }
    }

    pub fn uniform(binding: u32, stages: ShaderStages) -> BindGroupLayoutEntry {
        buffer(binding, stages, BufferBindingType::Uniform)
    }

    pub fn storage(binding: u32, stages: ShaderStages, read_only: bool) -> BindGroupLayoutEntry {
        buffer(binding, stages, BufferBindingType::Storage { read_only })
    }

    pub fn texture(binding: u32, stages: ShaderStages) -> BindGroupLayoutEntry {
        BindGroupLayoutEntry {
            binding,
            visibility: stages,
            ty: BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        }
    }

    pub fn sampler(binding: u32, stages: ShaderStages) -> BindGroupLayoutEntry {
        BindGroupLayoutEntry {
            binding,
            visibility: stages,
            ty: BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        }
    }
}

/// A uniform buffer of `size` bytes that the queue writes each frame.
pub fn uniform_buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A uniform buffer alone in its own bind group (binding 0), as a pass's per-frame parameters.
pub struct UniformGroup {
    pub layout: wgpu::BindGroupLayout,
    pub buffer: wgpu::Buffer,
    pub group: wgpu::BindGroup,
}

impl UniformGroup {
    /// A uniform of `size` bytes seen by the vertex and fragment stages.
    pub fn new(device: &wgpu::Device, label: &str, size: u64) -> UniformGroup {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &[layout::uniform(0, wgpu::ShaderStages::VERTEX_FRAGMENT)],
        });
        let buffer = uniform_buffer(device, label, size);
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        });
        UniformGroup {
            layout,
            buffer,
            group,
        }
    }
}

/// Grow-only GPU buffer upload: reuse `slot` when it is big enough.
pub(crate) fn upload(
    gpu: &Gpu,
    slot: &mut Option<wgpu::Buffer>,
    usage: wgpu::BufferUsages,
    bytes: &[u8],
) {
    let need = (bytes.len() as u64)
        .max(16)
        .next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
    if slot.as_ref().is_none_or(|b| b.size() < need) {
        // Room to grow, but never past what one binding or buffer may be (a buffer bound
        // whole must fit the binding limit).
        let limits = gpu.device.limits();
        let most = limits
            .max_buffer_size
            .min(limits.max_storage_buffer_binding_size)
            .max(need);
        *slot = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pass data"),
            size: need.next_power_of_two().min(most),
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
    }
    if let Some(b) = slot
        && !bytes.is_empty()
    {
        gpu.queue.write_buffer(b, 0, bytes);
    }
}
