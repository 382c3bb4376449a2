//! What the effect passes share: the effects uniform and bind group 2 (`Shared`, behind an
//! `Rc<RefCell>` held by both passes and the handle), the planner's view of a frame and the
//! caustic map's region.

use glam::{DVec2, DVec3};

use super::config::ArConfig;
use super::table_image::{screen_projection, straight_columns, straight_image, table_image};
use crate::backdrop::{Backdrop, CameraImage};
use crate::camera_upload::{CameraTextures, YuvConversion};
use crate::caustic_map::CAUSTIC_MAP_FORMAT;
use crate::caustics::CausticRegion;
use crate::flow_detail::{DETAIL_TEXELS, detail_texture};
use crate::flowmap::{DEFAULT_JUMP, flow_phases};
use crate::planner::EffectFrame;
use render::frame::{FrameContext, Targets};
use render::gpu::DEPTH_FORMAT;
use render::gpu::Gpu;

/// Bind group 2 of both effect passes and the effects' shared WGSL (the `Effects` uniform).
pub const EFFECTS_COMMON: &str = include_str!("../../../../shaders/effects/effects_common.wgsl");

/// The per-frame uniform of the effects, `Effects` in `shaders/effects_common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EffectsUniform {
    /// `PinholeCamera::image_projection` for local points: columns of WGSL's mat4x3 (each
    /// padded to 4).
    pub camera_projection: [[f32; 4]; 4],
    /// [`table_image`]: the projection's constant column for table points.
    pub table_image: [f32; 4],
    /// [`straight_columns`]: screen uv → the camera-image point of the table behind it.
    pub straight_image: [[f32; 4]; 3],
    pub display_u: [f32; 4],
    pub display_v: [f32; 4],
    pub table: [f32; 4],
    pub caustic_region: [f32; 4],
    pub flow_a: [f32; 4],
    pub flow_b: [f32; 4],
    pub current: [f32; 4],
    pub flags: [u32; 4],
    pub marks: [[f32; 4]; 8],
    /// `WaterLook::gpu_optics`: the sea's water over the table (`WaterOptics`).
    pub water: [[f32; 4]; 5],
    /// [`super::cover::water_cover`]: the screen polygon the water certainly covers (NDC, two
    /// vertices a vec4; `flags[0]` of them, 0 for none), where the background is not drawn.
    pub cover: [[f32; 4]; super::cover::MAX_COVER_VERTICES / 2],
    /// The polygon's centroid (xy) and the scale (z) of the copy that holds the screen.
    pub cover_shape: [f32; 4],
}

/// What the planner needs, measured from the frame: water coverage from a 9×9 grid of view
/// rays, reflectors from the frustum test the boats pass uses.
pub fn effect_frame(frame: &FrameContext, cfg: &ArConfig) -> EffectFrame {
    let s = frame.scene;
    let n = 9;
    let hits = (0..n * n)
        .filter(|k| {
            let (i, j) = (k % n, k / n);
            let ndc = [
                i as f64 / (n - 1) as f64 * 2.0 - 1.0,
                j as f64 / (n - 1) as f64 * 2.0 - 1.0,
            ];
            frame.ray_hits_water(ndc)
        })
        .count();
    let water = hits as f64 / (n * n) as f64;
    let in_view = |p: DVec2, r: f64| frame.sphere_in_view(DVec3::new(p.x, 0.0, p.y), r);
    let reflectors = s
        .boats
        .iter()
        .filter(|b| in_view(b.position, b.length))
        .count()
        + s.marks.iter().filter(|m| in_view(m.position, 2.0)).count();
    EffectFrame {
        requested: cfg.effects,
        camera_frame: true,
        water_on_screen: water,
        camera_above_water: s.camera.eye.y > 0.0,
        reflectors_in_view: reflectors,
        reflection_texture_px: reflection_px(frame.size, cfg),
        water_over_table: water,
        sun_elevation: s.sun.y.clamp(-1.0, 1.0).asin(),
        calm_sea: s.sea.waves.is_empty(),
        max_current_in_view: if water > 0.0 {
            cfg.current.length()
        } else {
            0.0
        },
        // Frame reuse is the renderer's: it does not keep frames yet.
        timeline_paused: false,
        camera_still: false,
        previous_frame_reusable: false,
    }
}

/// The planar reflection texture's size for a target of `size` pixels: the configured
/// fraction of each side, at least 1.
pub(crate) fn reflection_px(size: [u32; 2], cfg: &ArConfig) -> [u32; 2] {
    size.map(|v| ((f64::from(v) * cfg.reflection_fraction).round() as u32).max(1))
}

/// Resources shared by the effect passes.
pub(super) struct Shared {
    pub(super) cfg: ArConfig,
    /// The current frame's camera and display transform (its image is on the GPU).
    pub(super) camera: Backdrop<()>,
    pub(super) layout: wgpu::BindGroupLayout,
    /// Group 2 of the room in the reflection texture: the uniform and the camera image, not
    /// the reflection texture it draws into.
    pub(super) room_layout: wgpu::BindGroupLayout,
    pub(super) room_group: Option<wgpu::BindGroup>,
    pub(super) uniform: wgpu::Buffer,
    pub(super) camera_image: CameraTextures,
    pub(super) yuv_conversion: YuvConversion,
    pub(super) caustic_tex: wgpu::Texture,
    pub(super) reflection: Option<(wgpu::Texture, wgpu::Texture)>,
    pub(super) sampler: wgpu::Sampler,
    /// The flow map's detail texture (made once) and its wrap-around sampler.
    pub(super) flow_detail: wgpu::Texture,
    pub(super) repeat_sampler: wgpu::Sampler,
    pub(super) group: Option<wgpu::BindGroup>,
    pub(super) colour_format: wgpu::TextureFormat,
    /// Camera frames set so far: the background pass's revision, so that the renderer draws
    /// a still scene again over a new image.
    pub(super) revision: u64,
    /// Quality set-ups set so far ([`super::EffectsHandle::set_quality`]): the offscreen
    /// targets of an earlier one are not reused.
    pub(super) quality: u64,
    /// The uniform last written.
    pub(super) written: Option<EffectsUniform>,
}

/// The area-ratio caustic map's texture, `cells` per side.
pub(super) fn caustic_map_texture(device: &wgpu::Device, cells: usize) -> wgpu::Texture {
    let n = cells as u32;
    render::gpu::texture_2d(
        device,
        "caustic map",
        [n, n],
        CAUSTIC_MAP_FORMAT,
        wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC,
    )
}

/// The flow map's detail texture format: two 16-bit floats, filterable everywhere.
pub const FLOW_DETAIL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg16Float;

/// The flow map's detail texture (`flow_detail` of `shaders/effects/flowmap.wgsl`):
/// [`crate::flow_detail::detail_texture`] uploaded, [`DETAIL_TEXELS`]² texels.
pub fn flow_detail_texture(gpu: &Gpu) -> wgpu::Texture {
    flow_detail_texture_of(gpu, detail_texture(), DETAIL_TEXELS)
}

/// A detail texture of `texels`² f16 pairs (`texels` rows of `texels`).
pub fn flow_detail_texture_of(gpu: &Gpu, texture: &[[u16; 2]], texels: u32) -> wgpu::Texture {
    use wgpu::util::DeviceExt;
    gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("flow detail"),
            size: wgpu::Extent3d {
                width: texels,
                height: texels,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FLOW_DETAIL_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(texture),
    )
}

/// The flow detail's sampler (`linear_repeat`): bilinear, wrapping around the tile.
pub fn linear_repeat_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("effects linear repeat"),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

impl Shared {
    pub(super) fn new(
        gpu: &Gpu,
        targets: Targets,
        cfg: ArConfig,
        camera: Backdrop<()>,
        image: &CameraImage,
    ) -> Shared {
        let device = &gpu.device;
        use render::gpu::layout;
        let fs = wgpu::ShaderStages::FRAGMENT;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("effects"),
            entries: &[
                layout::uniform(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                layout::texture(1, fs),
                layout::texture(2, fs),
                layout::texture(3, fs),
                layout::sampler(4, fs),
                layout::texture(5, fs),
                layout::sampler(6, fs),
            ],
        });
        let room_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("reflected room"),
            entries: &[
                layout::uniform(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                layout::texture(1, fs),
                layout::sampler(4, fs),
            ],
        });
        let uniform = render::gpu::uniform_buffer(
            device,
            "effects uniform",
            size_of::<EffectsUniform>() as u64,
        );
        let yuv_conversion = YuvConversion::new(gpu);
        let caustic_tex = caustic_map_texture(device, cfg.caustic_resolution.1);
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("effects linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let flow_detail = flow_detail_texture(gpu);
        let repeat_sampler = linear_repeat_sampler(device);
        let mut shared = Shared {
            cfg,
            camera,
            layout,
            room_layout,
            room_group: None,
            uniform,
            camera_image: CameraTextures::new(device, image, &yuv_conversion),
            yuv_conversion,
            caustic_tex,
            reflection: None,
            sampler,
            flow_detail,
            repeat_sampler,
            group: None,
            colour_format: targets.colour,
            revision: 0,
            quality: 0,
            written: None,
        };
        shared.set_image(gpu, image);
        shared
    }

    /// Write `image` into the camera textures, made anew (and the bind group dropped) only
    /// when its kind or size differs from the last image's.
    pub(super) fn set_image(&mut self, gpu: &Gpu, image: &CameraImage) {
        if !self.camera_image.fits(image) {
            self.camera_image = CameraTextures::new(&gpu.device, image, &self.yuv_conversion);
            self.group = None;
            self.room_group = None;
        }
        self.camera_image.write(gpu, image, &self.yuv_conversion);
        self.revision += 1;
    }

    /// The reflection textures (colour, depth) at `size`, made when the size changes.
    pub(super) fn reflection_targets(&mut self, device: &wgpu::Device, size: [u32; 2]) {
        let fits = self
            .reflection
            .as_ref()
            .is_some_and(|(c, _)| c.width() == size[0].max(1) && c.height() == size[1].max(1));
        if fits {
            return;
        }
        let colour = render::gpu::texture_2d(
            device,
            "planar reflection",
            size,
            self.colour_format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let depth = render::gpu::texture_2d(
            device,
            "planar reflection depth",
            size,
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        self.reflection = Some((colour, depth));
        // The water's group binds the reflection texture; the room's does not (it draws
        // into it), so only the first is made again.
        self.group = None;
    }

    pub(super) fn bind_group(&mut self, device: &wgpu::Device) -> wgpu::BindGroup {
        if self.reflection.is_none() {
            self.reflection_targets(device, [1, 1]);
        }
        if self.group.is_none() {
            self.group = Some(self.make_group(device, false));
        }
        self.group.clone().expect("made above")
    }

    /// Group 2 of the reflected room: the uniform and the camera image.
    pub(super) fn room_group(&mut self, device: &wgpu::Device) -> wgpu::BindGroup {
        if self.room_group.is_none() {
            self.room_group = Some(self.make_group(device, true));
        }
        self.room_group.clone().expect("made above")
    }

    /// Group 2: the uniform, the camera image and the sampler, and unless `room` (the group of
    /// the reflected room, which draws into the reflection texture) the reflection texture,
    /// the caustic map and the flow detail with its sampler.
    pub(super) fn make_group(&self, device: &wgpu::Device, room: bool) -> wgpu::BindGroup {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (main, caustic) = (self.camera_image.sampled_view(), view(&self.caustic_tex));
        let reflection = self.reflection.as_ref().map(|(c, _)| view(c));
        let detail = view(&self.flow_detail);
        let texture = |binding, v| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(v),
        };
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: self.uniform.as_entire_binding(),
            },
            texture(1, &main),
            wgpu::BindGroupEntry {
                binding: 4,
                resource: wgpu::BindingResource::Sampler(&self.sampler),
            },
        ];
        if !room && let Some(reflection) = &reflection {
            entries.push(texture(2, reflection));
            entries.push(texture(3, &caustic));
            entries.push(texture(5, &detail));
            entries.push(wgpu::BindGroupEntry {
                binding: 6,
                resource: wgpu::BindingResource::Sampler(&self.repeat_sampler),
            });
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(if room { "reflected room" } else { "effects" }),
            layout: if room {
                &self.room_layout
            } else {
                &self.layout
            },
            entries: &entries,
        })
    }

    /// Write this frame's uniform, unless it holds it already (both effect passes prepare
    /// with it; a still frame leaves it as it is).
    pub(super) fn write_uniform(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let u = self.uniform(frame);
        if self.written != Some(u) {
            gpu.queue
                .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&u));
            self.written = Some(u);
        }
    }

    /// The uniform for a frame (the effects that run are the pipelines' constants).
    pub(super) fn uniform(&self, frame: &FrameContext) -> EffectsUniform {
        let s = frame.scene;
        let o = frame.origin;
        let cam = &self.camera.camera;
        let f = |v: f64| v as f32;
        let image = cam.image_projection(self.camera.view_local(o));
        let projection = image.as_mat4().to_cols_array_2d();
        let d = self.camera.display;
        let ring = self.cfg.ring_radius_for(s.play_area);
        let [ax, az, bx, bz] = s.play_area;
        let centre = DVec2::new(ax + bx, az + bz) / 2.0 - o;
        let region = self.caustic_region(frame);
        let [a, b] = flow_phases(s.t, self.cfg.flow_period, DEFAULT_JUMP);
        let water = self.cfg.water.gpu_optics(self.cfg.table_depth);
        let room_grid = crate::reflection::room_grid(reflection_px(frame.size, &self.cfg));
        let mut marks = [[0.0f32; 4]; 8];
        let mut near: Vec<DVec2> = s.marks.iter().map(|m| m.position - o).collect();
        let target = DVec2::new(s.camera.target.x, s.camera.target.z) - o;
        near.sort_by(|p, q| (*p - target).length().total_cmp(&(*q - target).length()));
        for (slot, p) in marks.iter_mut().zip(&near) {
            *slot = [f(p.x), f(p.y), 0.0, 0.0];
        }
        let cover = (!self.cfg.background_whole)
            .then(|| super::cover::water_cover(frame))
            .flatten();
        let (cover, cover_shape, cover_vertices) = super::cover::cover_uniform(cover.as_ref());
        EffectsUniform {
            camera_projection: projection,
            table_image: table_image(image, self.cfg.table_depth),
            straight_image: straight_columns(straight_image(
                screen_projection(frame.view_proj),
                image,
                self.cfg.table_depth,
                s.camera.eye.y,
            )),
            display_u: [f(d[0][0]), f(d[0][1]), f(d[0][2]), 0.0],
            display_v: [f(d[1][0]), f(d[1][1]), f(d[1][2]), 0.0],
            table: [f(self.cfg.table_depth), f(ring), f(centre.x), f(centre.y)],
            caustic_region: [
                f(region.min[0] - o.x),
                f(region.min[1] - o.y),
                f(region.size),
                1.0,
            ],
            flow_a: [f(a.progress), f(a.weight), f(a.offset.x), f(a.offset.y)],
            flow_b: [f(b.progress), f(b.weight), f(b.offset.x), f(b.offset.y)],
            current: [
                f(self.cfg.current.x),
                f(self.cfg.current.y),
                f(self.cfg.mark_radius),
                f(self.cfg.detail_tile),
            ],
            flags: [
                cover_vertices,
                near.len().min(8) as u32,
                room_grid[0],
                room_grid[1],
            ],
            marks,
            water,
            cover,
            cover_shape,
        }
    }

    pub(super) fn caustic_region(&self, frame: &FrameContext) -> CausticRegion {
        caustic_region(frame.scene, frame.size, &self.cfg)
    }
}

/// The square of the table the caustic map covers for `scene` seen at `size` pixels: around
/// the point looked at, as wide as the view there (world metres), cut to the water (the play
/// area and a margin of twice the depth: table points seen through the water's edge at up to
/// 63° from straight down).
pub fn caustic_region(scene: &render::Scene, size: [u32; 2], cfg: &ArConfig) -> CausticRegion {
    let cam = &scene.camera;
    let dist = (cam.target - cam.eye).length();
    let aspect = f64::from(size[0]) / f64::from(size[1].max(1));
    let width = 2.0 * dist * (0.5 * cam.fov_y).tan() * aspect.max(1.0) * 1.5;
    CausticRegion::in_view(
        [cam.target.x, cam.target.z],
        width,
        scene.play_area,
        2.0 * cfg.table_depth,
    )
}
