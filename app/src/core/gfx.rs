//! The window's drawing target, once for every app (the race renderer is the scene set-up's:
//! `crate::setup::RaceSetup`).
//!
//! [`Window`] is the current window's target: a wgpu surface (desktop, Android) or an
//! offscreen texture standing in for one (`regatta phone-sim`). A window goes away on suspend
//! and a new one comes on resume (wgpu issue 2302: a surface must not outlive its native window);
//! the surface configuration chosen for the first window (the sRGB format, and the non-sRGB view
//! format egui paints through) is kept and reused for every later one, because every renderer and
//! egui's pipelines were built for it (issue 19, defect 3).
//!
//! Devices: Vulkan first; where a Vulkan device cannot be had, or is lost, OpenGL ES
//! ([`open_with_fallback`]), logged and shown on the banner.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use render::Gpu;
use render::gpu::SurfaceTarget;

/// Makes a surface for the current native window on a device's instance (again after the
/// device was lost).
pub type SurfaceMaker =
    Box<dyn FnMut(&wgpu::Instance) -> Result<wgpu::Surface<'static>, String> + Send>;

/// Tries `open` on Vulkan (the primary backends), then on OpenGL ES; the second result is the
/// note to show when it fell back.
pub fn open_with_fallback<T, E: std::fmt::Display>(
    mut open: impl FnMut(wgpu::Backends) -> Result<T, E>,
) -> Result<(T, Option<String>), String> {
    match open(wgpu::Backends::PRIMARY) {
        Ok(t) => Ok((t, None)),
        Err(primary) => {
            let note = format!("Vulkan is not available ({primary}); drawing with OpenGL ES.");
            log::warn!("regatta: {note}");
            open(wgpu::Backends::GL)
                .map(|t| (t, Some(note)))
                .map_err(|gl| format!("no GPU: Vulkan: {primary}; OpenGL ES: {gl}"))
        }
    }
}

/// Whether the device is lost, its lost callback run or not: the app core rebuilds its
/// graphics on OpenGL ES. Before the callback, a refused write says so
/// (`render::gpu::WriteProbe`): egui-wgpu 0.37's `Renderer::update_buffers` panics on a
/// refused staging write, so the app asks first.
#[derive(Clone)]
pub struct LostFlag {
    raised: Arc<AtomicBool>,
    probe: Arc<render::gpu::WriteProbe>,
}

impl LostFlag {
    /// A flag raised when `gpu`'s device is lost.
    pub fn watch(gpu: &Gpu) -> LostFlag {
        let raised = Arc::new(AtomicBool::new(false));
        let by_callback = raised.clone();
        gpu.device.set_device_lost_callback(move |reason, msg| {
            log::error!("regatta: the GPU device was lost ({reason:?}): {msg}");
            by_callback.store(true, Ordering::SeqCst);
        });
        LostFlag {
            raised,
            probe: Arc::new(render::gpu::WriteProbe::new(&gpu.device)),
        }
    }

    /// Raised, or the device refuses a write (lost before its callback ran; raised then).
    pub fn is_lost(&self, queue: &wgpu::Queue) -> bool {
        if !self.is_raised() && !self.probe.device_takes_writes(queue) {
            log::error!("regatta: the GPU device was lost (its lost callback has not run yet)");
            self.raise();
        }
        self.is_raised()
    }

    /// Raised by the lost callback or by [`LostFlag::raise`] (no probe).
    pub fn is_raised(&self) -> bool {
        self.raised.load(Ordering::SeqCst)
    }

    /// The device was found lost elsewhere (egui's painter refused to paint on it).
    pub fn raise(&self) {
        self.raised.store(true, Ordering::SeqCst);
    }
}

/// The surface configuration of the first window, for every later one.
#[derive(Clone, Debug, Default)]
pub struct KeptConfig(Option<wgpu::SurfaceConfiguration>);

impl KeptConfig {
    /// Remembers `config` (after egui added its view format).
    pub fn remember(&mut self, config: &wgpu::SurfaceConfiguration) {
        self.0 = Some(config.clone());
    }

    /// The configuration for a new window of `width` × `height`: the kept one resized, or
    /// `default` (the driver's) for the very first window.
    pub fn for_new_window(
        &self,
        width: u32,
        height: u32,
        default: impl FnOnce() -> Option<wgpu::SurfaceConfiguration>,
    ) -> Option<wgpu::SurfaceConfiguration> {
        let mut config = self.0.clone().or_else(default)?;
        config.width = width.max(1);
        config.height = height.max(1);
        Some(config)
    }

    pub fn get(&self) -> Option<&wgpu::SurfaceConfiguration> {
        self.0.as_ref()
    }
}

/// What the window draws into this frame.
pub enum Frame {
    Surface(wgpu::SurfaceTexture),
    Offscreen(wgpu::Texture),
}

impl Frame {
    pub fn texture(&self) -> &wgpu::Texture {
        match self {
            Frame::Surface(f) => &f.texture,
            Frame::Offscreen(t) => t,
        }
    }
}

/// The outcome of asking the window for a frame.
pub enum Acquired {
    Frame(Frame),
    /// Nothing to draw into this time (surface outdated and reconfigured, occluded, timeout).
    Skip,
    /// The surface failed for good.
    Failed(String),
}

enum Live {
    Surface(SurfaceTarget),
    /// A texture standing in for a window (headless phone sessions).
    Offscreen(wgpu::Texture, wgpu::SurfaceConfiguration),
}

/// The current window's target and the configuration kept across windows.
#[derive(Default)]
pub struct Window {
    kept: KeptConfig,
    live: Option<Live>,
}

impl Window {
    /// The first window's surface, configured by `Gpu::for_window`/`for_surface`; its
    /// configuration is kept.
    pub fn first_surface(&mut self, target: SurfaceTarget) {
        self.kept.remember(&target.config);
        self.live = Some(Live::Surface(target));
    }

    /// A later window's surface, configured as the first one was.
    pub fn attach_surface(
        &mut self,
        gpu: &Gpu,
        surface: wgpu::Surface<'static>,
        width: u32,
        height: u32,
    ) -> Result<(), String> {
        let config = self
            .kept
            .for_new_window(width, height, || {
                surface.get_default_config(&gpu.adapter, width.max(1), height.max(1))
            })
            .ok_or("the adapter cannot present to this window")?;
        surface.configure(&gpu.device, &config);
        self.kept.remember(&config);
        self.live = Some(Live::Surface(SurfaceTarget { surface, config }));
        Ok(())
    }

    /// An offscreen texture as the window (format [`render::OFFSCREEN_FORMAT`] and its non-sRGB
    /// view for egui, as a surface that allows view formats would be; without view formats
    /// (OpenGL ES: a texture asking for them is invalid, and every frame drawn into it fails)
    /// egui paints into the sRGB format itself).
    pub fn attach_offscreen(&mut self, gpu: &Gpu, width: u32, height: u32) {
        let format = render::OFFSCREEN_FORMAT;
        let view_formats = gpu
            .adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::VIEW_FORMATS);
        let config = self
            .kept
            .for_new_window(width, height, || {
                Some(wgpu::SurfaceConfiguration {
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    format,
                    width,
                    height,
                    present_mode: wgpu::PresentMode::AutoVsync,
                    desired_maximum_frame_latency: 2,
                    alpha_mode: wgpu::CompositeAlphaMode::Opaque,
                    view_formats: if view_formats {
                        vec![format.remove_srgb_suffix()]
                    } else {
                        Vec::new()
                    },
                    color_space: wgpu::SurfaceColorSpace::Auto,
                })
            })
            .expect("a default is given");
        self.kept.remember(&config);
        let texture = offscreen_texture(gpu, &config);
        self.live = Some(Live::Offscreen(texture, config));
    }

    /// The surface of the window, to let egui add its view format (then [`Window::remember`]).
    pub fn surface_mut(&mut self) -> Option<&mut SurfaceTarget> {
        match self.live.as_mut()? {
            Live::Surface(s) => Some(s),
            Live::Offscreen(..) => None,
        }
    }

    /// Keeps the live configuration for later windows (after it was changed in place).
    pub fn remember(&mut self) {
        if let Some(c) = self.config().cloned() {
            self.kept.remember(&c);
        }
    }

    /// The window went away: its surface is dropped now, while the native window exists.
    pub fn detach(&mut self) {
        self.live = None;
    }

    pub fn is_attached(&self) -> bool {
        self.live.is_some()
    }

    pub fn config(&self) -> Option<&wgpu::SurfaceConfiguration> {
        match self.live.as_ref()? {
            Live::Surface(s) => Some(&s.config),
            Live::Offscreen(_, c) => Some(c),
        }
    }

    /// The kept configuration (the first window's, with later sizes).
    pub fn kept(&self) -> &KeptConfig {
        &self.kept
    }

    /// The window's size in pixels (1 × 1 without one).
    pub fn size(&self) -> [u32; 2] {
        self.config().map_or([1, 1], |c| [c.width, c.height])
    }

    /// The format egui paints through: the window's non-sRGB view where it has one, else its
    /// own format.
    pub fn egui_view_format(&self) -> Option<wgpu::TextureFormat> {
        let c = self.config().or(self.kept.get())?;
        Some(c.view_formats.first().copied().unwrap_or(c.format))
    }

    /// The format of the window's textures (the kept one without a window).
    pub fn format(&self) -> Option<wgpu::TextureFormat> {
        self.config().or(self.kept.get()).map(|c| c.format)
    }

    /// A new size; a zero size (minimised) is ignored.
    pub fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        match self.live.as_mut() {
            Some(Live::Surface(s)) => s.resize(&gpu.device, width, height),
            Some(Live::Offscreen(t, c)) if [c.width, c.height] != [width, height] => {
                c.width = width;
                c.height = height;
                *t = offscreen_texture(gpu, c);
            }
            _ => return,
        }
        self.remember();
    }

    /// The texture to draw this frame into; an outdated or lost surface is reconfigured and the
    /// frame skipped.
    pub fn acquire(&mut self, gpu: &Gpu) -> Acquired {
        match self.live.as_mut() {
            None => Acquired::Skip,
            Some(Live::Offscreen(t, _)) => Acquired::Frame(Frame::Offscreen(t.clone())),
            Some(Live::Surface(s)) => match s.surface.get_current_texture() {
                wgpu::CurrentSurfaceTexture::Success(f)
                | wgpu::CurrentSurfaceTexture::Suboptimal(f) => Acquired::Frame(Frame::Surface(f)),
                wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                    let (w, h) = (s.config.width, s.config.height);
                    s.resize(&gpu.device, w, h);
                    Acquired::Skip
                }
                wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                    Acquired::Skip
                }
                other => Acquired::Failed(format!("the window surface failed: {other:?}")),
            },
        }
    }

    /// Shows the frame (a surface texture is presented; an offscreen one stays for reading).
    pub fn present(&self, gpu: &Gpu, frame: Frame) {
        match frame {
            Frame::Surface(f) => gpu.queue.present(f),
            Frame::Offscreen(_) => {
                gpu.queue.submit([]);
                // No swapchain asks wgpu to free what was dropped (an old window's texture):
                // the device is polled here, as presenting does for a surface.
                let _ = gpu.device.poll(wgpu::PollType::Poll);
            }
        }
    }

    /// The offscreen window's texture, for screenshots.
    pub fn offscreen_texture(&self) -> Option<&wgpu::Texture> {
        match self.live.as_ref()? {
            Live::Offscreen(t, _) => Some(t),
            Live::Surface(_) => None,
        }
    }
}

fn offscreen_texture(gpu: &Gpu, c: &wgpu::SurfaceConfiguration) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("offscreen window"),
        size: wgpu::Extent3d {
            width: c.width,
            height: c.height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: c.format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &c.view_formats,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(
        format: wgpu::TextureFormat,
        views: Vec<wgpu::TextureFormat>,
    ) -> wgpu::SurfaceConfiguration {
        wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: 1080,
            height: 2160,
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: wgpu::CompositeAlphaMode::Opaque,
            view_formats: views,
            color_space: wgpu::SurfaceColorSpace::Auto,
        }
    }

    #[test]
    fn a_new_window_gets_the_first_windows_configuration_not_the_drivers() {
        // Defect 3: the first window chose sRGB with egui's non-sRGB view; the driver's default
        // for a new window is its first format, without views.
        let chosen = config(
            wgpu::TextureFormat::Rgba8UnormSrgb,
            vec![wgpu::TextureFormat::Rgba8Unorm],
        );
        let driver = config(wgpu::TextureFormat::Rgba8Unorm, vec![]);
        let mut w = Window::default();
        w.kept.remember(&chosen);
        // TerminateWindow: the surface goes; InitWindow in landscape.
        w.detach();
        assert!(!w.is_attached());
        let next = w
            .kept()
            .for_new_window(2160, 1080, || Some(driver.clone()))
            .unwrap();
        assert_eq!(next.format, chosen.format);
        assert_eq!(next.view_formats, chosen.view_formats);
        assert_eq!([next.width, next.height], [2160, 1080]);
        // The very first window takes the driver's.
        let first = KeptConfig::default().for_new_window(10, 20, || Some(driver.clone()));
        assert_eq!(first.unwrap().format, driver.format);
    }

    #[test]
    fn without_vulkan_the_device_comes_from_opengl_es_with_a_note() {
        let tried = std::cell::RefCell::new(Vec::new());
        let (got, note) = open_with_fallback(|b| {
            tried.borrow_mut().push(b);
            if b == wgpu::Backends::GL {
                Ok("gles")
            } else {
                Err("no Vulkan driver")
            }
        })
        .unwrap();
        assert_eq!(got, "gles");
        assert_eq!(
            *tried.borrow(),
            [wgpu::Backends::PRIMARY, wgpu::Backends::GL]
        );
        assert!(note.unwrap().contains("OpenGL ES"));
        let (v, note) = open_with_fallback(|_| Ok::<_, String>(1)).unwrap();
        assert_eq!((v, note), (1, None));
        let e = open_with_fallback(|_| Err::<(), _>("none")).unwrap_err();
        assert!(e.contains("Vulkan") && e.contains("OpenGL ES"), "{e}");
    }
}
