//! The pool scene on the GPU: three passes, one WGSL file each (`shaders/pool_*.wgsl`, sharing
//! `shaders/pool_common.wgsl`).
//!
//! 1. **caustics**: the water grid's triangles refracted onto the box's unfolded net, drawn with
//!    additive blending into the caustics map (area ratio; f64 reference [`super::caustics`]).
//! 2. **scene**: a full-screen triangle that ray-traces the spheres, the tub and the tiled
//!    inside of the pool, writing depth.
//! 3. **water**: the surface grid displaced by the waves and ripples; each fragment splits the
//!    view ray by the full Fresnel equations and traces both halves against the spheres and the
//!    box (f64 reference [`super::trace::shade_water`]).
//!
//! Inputs are f32-safe: bind group 0 is the renderer's [`FrameUniform`] (in pool space, the
//! waves' phases reduced in f64 by `WaveSet::gpu_waves`), bind group 1 the [`PoolUniform`]
//! (sphere centres, ripple rings with their ages: never an absolute time), bind group 2 the
//! caustics map.
//!
//! **The pool in AR.** [`PoolView::model`] maps pool space into the world, the same similarity
//! (table anchor pose times `course_to_table` scale) that stands the race course on the
//! detected table ([`PoolView::standing_on`]). The frame uniform's view-projection is `camera · model`, and the eye and the
//! sun are taken into pool space by `model⁻¹`, so every shader works in pool metres whatever
//! the table's pose and scale.

use glam::{DMat4, DVec2};
use ocean::GpuWave;
use serde::Serialize;

use super::scene::PoolScene;
use render::camera::Camera;
use render::clipmap::MAX_WAVES;
use render::frame::{FrameBindings, FrameUniform, PassRecord};
use render::gpu::DEPTH_FORMAT;
use render::gpu::{DepthBuffer, Gpu, GpuError, texture_2d};
use render::shader;

/// Spheres and ripple rings the shader holds (defined with the constants WGSL shares).
pub use crate::wgsl::{MAX_RINGS, MAX_SPHERES};

/// The pool's shared WGSL (structs, water, rays, shading): every pool pass file follows it.
pub const POOL_COMMON: &str = include_str!("../../../shaders/pool/pool_common.wgsl");
const POOL_CAUSTICS: &str = include_str!("../../../shaders/pool/pool_caustics.wgsl");
const POOL_SCENE: &str = include_str!("../../../shaders/pool/pool_scene.wgsl");
const POOL_WATER: &str = include_str!("../../../shaders/pool/pool_water.wgsl");

/// The caustics map's format: blendable and filterable everywhere (WebGPU core).
pub const CAUSTIC_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

/// `PoolSphere` in `pool_common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuSphere {
    pub center_radius: [f32; 4],
    pub colour: [f32; 4],
}

/// `PoolRing` in `pool_common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuRing {
    /// Centre x, z (m), age (s), amplitude (m).
    pub center_age_amp: [f32; 4],
    /// x: radius of the sphere that made the ring (m).
    pub source: [f32; 4],
}

/// `Pool` in `pool_common.wgsl` (bind group 1).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PoolUniform {
    /// half_x, half_z, floor_y, rim_y.
    pub box_: [f32; 4],
    /// Ripple k, ω, group speed, 1/τ.
    pub ripple: [f32; 4],
    /// Ripple σ, ε, refractive index, wall thickness.
    pub ripple2: [f32; 4],
    /// Net half extents x, z; caustics map texels along x, z.
    pub net: [f32; 4],
    /// Rest-point grid half extents x, z (the pool's); caustic grid cells; water grid cells.
    pub grid: [f32; 4],
    /// Spheres, rings, waves, 1 when drawn over the camera image (AR).
    pub counts: [u32; 4],
    pub spheres: [GpuSphere; MAX_SPHERES],
    pub rings: [GpuRing; MAX_RINGS],
}

/// Resolutions of the pool's GPU work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoolSettings {
    /// Surface cells per side refracted into the caustics map.
    pub caustic_grid: u32,
    /// Caustics map texels per side.
    pub caustic_size: u32,
    /// Surface cells per side of the drawn water mesh.
    pub water_grid: u32,
    /// Thickness of the tub's walls, metres.
    pub wall: f64,
}

impl Default for PoolSettings {
    fn default() -> Self {
        PoolSettings {
            caustic_grid: 160,
            caustic_size: 256,
            water_grid: 128,
            wall: 0.08,
        }
    }
}

/// How the pool is seen: a camera in the world, and where pool space lies in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoolView {
    pub camera: Camera,
    /// Pool space → world: a rotation about y, a uniform scale and a translation (identity on
    /// the desktop; the table anchor and `course_to_table` in AR).
    pub model: DMat4,
    /// Viewport, pixels.
    pub size: [u32; 2],
    /// AR: draw only the pool (and what it reflects and refracts) over the camera image already
    /// in the target; no ground, no sky behind it.
    pub over_camera_image: bool,
}

impl PoolView {
    /// The model matrix that stands the tub on a table: `table` maps a table frame (y up, its
    /// origin the tapped point on the detected plane, metres scaled as the user pinched) into
    /// the AR world; in the app it is the race course's own `CoursePlacement::race_to_ar()`.
    /// Pool space is lifted so that the bottom of the tub (floor minus wall thickness) rests
    /// on the table's origin.
    pub fn standing_on(table: DMat4, scene: &PoolScene, settings: &PoolSettings) -> DMat4 {
        let bottom = scene.pool.floor_y - settings.wall;
        table * DMat4::from_translation(glam::DVec3::new(0.0, -bottom, 0.0))
    }

    /// The desktop default: looking into the pool from the south-east and above.
    pub fn default_desktop(size: [u32; 2]) -> PoolView {
        PoolView {
            camera: Camera::look_at(
                glam::DVec3::new(1.0, 1.55, 2.0),
                glam::DVec3::new(-0.05, -0.4, -0.1),
                super::FAR_M,
            ),
            model: DMat4::IDENTITY,
            size,
            over_camera_image: false,
        }
    }
}

/// Everything one pool frame uploads, computed on the CPU in f64 and handed over in f32.
#[derive(Debug, Clone)]
pub struct PoolFrame {
    pub t: f64,
    pub size: [u32; 2],
    pub frame: FrameUniform,
    pub waves: Vec<GpuWave>,
    pub pool: Box<PoolUniform>,
    /// Keep the target's contents (the AR camera image) instead of clearing it.
    pub over_camera_image: bool,
    /// Spheres and rings that did not fit the shader's arrays (logged; 0 for the default scene).
    pub dropped: usize,
}

impl PoolFrame {
    /// The frame of `scene` at time `t` seen through `view`.
    pub fn new(scene: &PoolScene, t: f64, view: &PoolView, settings: &PoolSettings) -> PoolFrame {
        let aspect = f64::from(view.size[0]) / f64::from(view.size[1].max(1));
        let view_proj = view.camera.view_proj_local(DVec2::ZERO, aspect) * view.model;
        let to_pool = view.model.inverse();
        let eye = to_pool.transform_point3(view.camera.eye);
        let sun = scene.to_light;
        // The pool is small and centred on its origin: its waves' local origin is (0, 0).
        let mut waves = scene.water.waves.gpu_waves(t, [0.0, 0.0]);
        let mut dropped = waves.len().saturating_sub(MAX_WAVES);
        waves.truncate(MAX_WAVES);
        let rings = scene.rings(t);
        let spheres = scene.spheres(t, &rings);
        dropped +=
            rings.len().saturating_sub(MAX_RINGS) + spheres.len().saturating_sub(MAX_SPHERES);
        if dropped > 0 {
            log::warn!(
                "the pool frame has {dropped} waves, rings or spheres beyond what the shader holds"
            );
        }
        let f = |x: f64| x as f32;
        let m = &scene.water.ripples;
        let mut pool = Box::new(PoolUniform {
            box_: [
                f(scene.pool.half_x),
                f(scene.pool.half_z),
                f(scene.pool.floor_y),
                f(scene.pool.rim_y),
            ],
            ripple: [
                f(m.k()),
                f(m.omega()),
                f(m.group_speed()),
                f(1.0 / m.decay_s),
            ],
            ripple2: [f(m.packet_width), f(m.core), f(scene.ior), f(settings.wall)],
            net: {
                let [nx, nz] = scene.pool.net_half_extent();
                let texels = settings.caustic_size as f32;
                [f(nx), f(nz), texels, texels]
            },
            grid: {
                [
                    f(scene.pool.half_x),
                    f(scene.pool.half_z),
                    settings.caustic_grid as f32,
                    settings.water_grid as f32,
                ]
            },
            counts: [
                spheres.len().min(MAX_SPHERES) as u32,
                rings.len().min(MAX_RINGS) as u32,
                waves.len() as u32,
                u32::from(view.over_camera_image),
            ],
            spheres: [GpuSphere::default(); MAX_SPHERES],
            rings: [GpuRing::default(); MAX_RINGS],
        });
        for (g, s) in pool.spheres.iter_mut().zip(&spheres) {
            let c = s.sphere.center;
            g.center_radius = [f(c.x), f(c.y), f(c.z), f(s.sphere.radius)];
            g.colour = [f(s.color[0]), f(s.color[1]), f(s.color[2]), 1.0];
        }
        for (g, r) in pool.rings.iter_mut().zip(&rings) {
            g.center_age_amp = [f(r.center[0]), f(r.center[1]), f(r.age), f(r.amplitude)];
            g.source = [f(r.source_radius), 0.0, 0.0, 0.0];
        }
        let frame = FrameUniform {
            view_proj: view_proj.as_mat4().to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().as_mat4().to_cols_array_2d(),
            eye: [f(eye.x), f(eye.y), f(eye.z), 0.0],
            sun: [f(sun.x), f(sun.y), f(sun.z), 1.0],
            play_area: [
                f(-scene.pool.half_x),
                f(-scene.pool.half_z),
                f(scene.pool.half_x),
                f(scene.pool.half_z),
            ],
            viewport: [
                view.size[0] as f32,
                view.size[1] as f32,
                1.0 / view.size[0].max(1) as f32,
                1.0 / view.size[1].max(1) as f32,
            ],
            counts: [waves.len() as u32, 0, 0, 0],
            level_masks: [[0; 4]; 8],
            // The pool draws no boats and no open-sea body: the renderer's defaults.
            light: [1.0, 1.0, 1.0, 0.0],
            room_light: [0.0; 4],
            water_body: [0.0; 4],
            // The pool has no clip-map: no vertex carries slope sums.
            vertex_waves: [[0; 4]; 4],
        };
        PoolFrame {
            t,
            size: view.size,
            frame,
            waves,
            pool,
            over_camera_image: view.over_camera_image,
            dropped,
        }
    }
}

/// What one pool frame did (`regatta render --scene pool --report`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoolReport {
    pub t: f64,
    pub size: [u32; 2],
    pub adapter: String,
    pub passes: Vec<PassRecord>,
    pub triangles: u64,
    pub spheres: u32,
    pub rings: u32,
}

/// The pool's pipelines, bindings and caustics map.
pub struct PoolRenderer {
    pub settings: PoolSettings,
    colour_format: wgpu::TextureFormat,
    bindings: FrameBindings,
    pool_buffer: wgpu::Buffer,
    pool_group: wgpu::BindGroup,
    caustic_texture: wgpu::Texture,
    caustic_view: wgpu::TextureView,
    caustic_group: wgpu::BindGroup,
    caustics: wgpu::RenderPipeline,
    scene: wgpu::RenderPipeline,
    water: wgpu::RenderPipeline,
    /// Indices of the caustic and water grids' triangles over their (n + 1)² vertices.
    caustic_indices: (wgpu::Buffer, u32),
    water_indices: (wgpu::Buffer, u32),
    depth: DepthBuffer,
}

struct PipelineParts<'a> {
    label: &'a str,
    pass_wgsl: &'a str,
    layouts: &'a [Option<&'a wgpu::BindGroupLayout>],
    format: wgpu::TextureFormat,
    blend: Option<wgpu::BlendState>,
    depth: Option<wgpu::DepthStencilState>,
}

fn build_pipeline(device: &wgpu::Device, p: PipelineParts) -> wgpu::RenderPipeline {
    let prelude = crate::wgsl::prelude();
    let module = shader::module(device, p.label, &[&prelude, POOL_COMMON, p.pass_wgsl]);
    render::passes::bufferless_pipeline(
        device,
        render::passes::BufferlessPipeline {
            label: p.label,
            module: &module,
            vertex: "vs_main",
            fragment: "fs_main",
            layouts: Some(p.layouts),
            format: p.format,
            blend: p.blend,
            depth: p.depth,
        },
    )
}

fn depth_state(compare: wgpu::CompareFunction) -> Option<wgpu::DepthStencilState> {
    Some(wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    })
}

impl PoolRenderer {
    /// Pipelines drawing into `colour` textures (linear shader output; use an sRGB format).
    pub fn new(gpu: &Gpu, colour: wgpu::TextureFormat, settings: PoolSettings) -> PoolRenderer {
        use render::gpu::layout;
        let device = &gpu.device;
        let bindings = FrameBindings::new(device);
        let render::gpu::UniformGroup {
            layout: pool_layout,
            buffer: pool_buffer,
            group: pool_group,
        } = render::gpu::UniformGroup::new(device, "pool", size_of::<PoolUniform>() as u64);
        let caustic_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("pool caustics map"),
            entries: &[
                layout::texture(0, wgpu::ShaderStages::FRAGMENT),
                layout::sampler(1, wgpu::ShaderStages::FRAGMENT),
            ],
        });
        let n = settings.caustic_size.max(1);
        let caustic_texture = texture_2d(
            device,
            "pool caustics map",
            [n, n],
            CAUSTIC_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let caustic_view = caustic_texture.create_view(&Default::default());
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("pool caustics"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let caustic_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("pool caustics map"),
            layout: &caustic_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&caustic_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
            ],
        });
        let caustics = build_pipeline(
            device,
            PipelineParts {
                label: "pool caustics",
                pass_wgsl: POOL_CAUSTICS,
                layouts: &[Some(&bindings.layout), Some(&pool_layout)],
                format: CAUSTIC_FORMAT,
                blend: Some(render::passes::ADDITIVE),
                depth: None,
            },
        );
        let all = [
            Some(&bindings.layout),
            Some(&pool_layout),
            Some(&caustic_layout),
        ];
        let scene = build_pipeline(
            device,
            PipelineParts {
                label: "pool scene",
                pass_wgsl: POOL_SCENE,
                layouts: &all,
                format: colour,
                blend: None,
                depth: depth_state(wgpu::CompareFunction::Always),
            },
        );
        let water = build_pipeline(
            device,
            PipelineParts {
                label: "pool water",
                pass_wgsl: POOL_WATER,
                layouts: &all,
                format: colour,
                blend: None,
                depth: depth_state(wgpu::CompareFunction::Less),
            },
        );
        let index_buffer = |label, n| {
            let indices = grid_indices(n);
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (indices.len() * 4) as u64,
                usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            gpu.queue
                .write_buffer(&buffer, 0, bytemuck::cast_slice(&indices));
            (buffer, indices.len() as u32)
        };
        PoolRenderer {
            caustic_indices: index_buffer("pool caustic indices", settings.caustic_grid),
            water_indices: index_buffer("pool water indices", settings.water_grid),
            settings,
            colour_format: colour,
            bindings,
            pool_buffer,
            pool_group,
            caustic_texture,
            caustic_view,
            caustic_group,
            caustics,
            scene,
            water,
            depth: DepthBuffer::new("pool depth"),
        }
    }

    /// The colour format the pipelines draw into.
    pub fn colour_format(&self) -> wgpu::TextureFormat {
        self.colour_format
    }

    /// Draw `frame` into `target` (its size is `frame.size`).
    pub fn render(
        &mut self,
        gpu: &Gpu,
        target: &wgpu::TextureView,
        frame: &PoolFrame,
    ) -> PoolReport {
        self.bindings.upload(&gpu.queue, &frame.frame, &frame.waves);
        gpu.queue.write_buffer(
            &self.pool_buffer,
            0,
            bytemuck::bytes_of(frame.pool.as_ref()),
        );
        let depth = self.depth.view(gpu, frame.size);
        let sun_up = frame.frame.sun[1] > 0.0;
        let caustic_cells = u64::from(self.settings.caustic_grid).pow(2);
        let water_cells = u64::from(self.settings.water_grid).pow(2);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = render::gpu::colour_pass(
                &mut enc,
                "pool caustics",
                &self.caustic_view,
                wgpu::Color::TRANSPARENT,
                None,
            );
            if sun_up {
                pass.set_pipeline(&self.caustics);
                pass.set_bind_group(0, &self.bindings.group, &[]);
                pass.set_bind_group(1, &self.pool_group, &[]);
                let (indices, count) = &self.caustic_indices;
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..*count, 0, 0..1);
            }
        }
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("pool scene and water"),
                color_attachments: &[Some(render::gpu::colour_attachment(
                    target,
                    (!frame.over_camera_image).then_some(wgpu::Color::BLACK),
                ))],
                depth_stencil_attachment: Some(render::gpu::depth_attachment(&depth, true)),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.bindings.group, &[]);
            pass.set_bind_group(1, &self.pool_group, &[]);
            pass.set_bind_group(2, &self.caustic_group, &[]);
            pass.set_pipeline(&self.scene);
            pass.draw(0..3, 0..1);
            pass.set_pipeline(&self.water);
            let (indices, count) = &self.water_indices;
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..*count, 0, 0..1);
        }
        gpu.queue.submit([enc.finish()]);
        let record =
            |name: &str, condition: &str, ran: bool, reason: String, triangles| PassRecord {
                name: name.into(),
                condition: condition.into(),
                ran,
                reason,
                triangles,
                gpu_ms: None,
                offscreen_gpu_ms: None,
            };
        let passes = vec![
            record(
                "pool caustics",
                "the sun is above the water",
                sun_up,
                if sun_up {
                    format!("{caustic_cells} surface cells refracted into the map")
                } else {
                    "the sun is below the horizon: no caustics".into()
                },
                if sun_up { 2 * caustic_cells } else { 0 },
            ),
            record(
                "pool scene",
                "always: the spheres and the pool",
                true,
                "full-screen ray trace".into(),
                1,
            ),
            record(
                "pool water",
                "always: the water fills the pool",
                true,
                format!("{water_cells} surface cells"),
                2 * water_cells,
            ),
        ];
        PoolReport {
            t: frame.t,
            size: frame.size,
            adapter: gpu.describe(),
            triangles: passes.iter().map(|p| p.triangles).sum(),
            passes,
            spheres: frame.pool.counts[0],
            rings: frame.pool.counts[1],
        }
    }

    /// Read the caustics map back as f32 (irradiance / E), row-major, row 0 at the net's −z edge.
    pub fn read_caustics(&self, gpu: &Gpu) -> Result<Vec<f32>, GpuError> {
        // `CAUSTIC_FORMAT` texels are one f16: two bytes each.
        let bytes = gpu.read_texture_bytes(&self.caustic_texture, 2)?;
        Ok(bytes
            .chunks_exact(2)
            .map(|b| f16_to_f32(u16::from_le_bytes([b[0], b[1]])))
            .collect())
    }
}

/// Two triangles per cell of an n × n grid whose (n + 1)² vertices are numbered row by row:
/// (00, 10, 11) and (00, 11, 01), counter-clockwise seen from above.
fn grid_indices(n: u32) -> Vec<u32> {
    let row = n + 1;
    (0..n * n)
        .flat_map(|c| {
            let v = (c / n) * row + c % n;
            [v, v + 1, v + row + 1, v, v + row + 1, v + row]
        })
        .collect()
}

/// IEEE 754 half → single precision.
fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = i32::from((h >> 10) & 0x1f);
    let frac = f32::from(h & 0x3ff);
    sign * match exp {
        0 => frac * 2f32.powi(-24),
        31 => {
            if frac == 0.0 {
                f32::INFINITY
            } else {
                f32::NAN
            }
        }
        e => (1.0 + frac / 1024.0) * 2f32.powi(e - 15),
    }
}

/// Render `frame` offscreen and read it back as an image.
pub fn render_pool_image(
    gpu: &Gpu,
    renderer: &mut PoolRenderer,
    frame: &PoolFrame,
) -> Result<(image::RgbaImage, PoolReport), GpuError> {
    let format = renderer.colour_format;
    gpu.render_offscreen(frame.size, format, |view| renderer.render(gpu, view, frame))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_indices_cover_each_cell_with_two_triangles() {
        let idx = grid_indices(2);
        assert_eq!(idx.len(), 24);
        // Cell (1, 1) of a 2 × 2 grid: vertices 4, 5, 8, 7 of the 3 × 3.
        assert_eq!(&idx[18..24], &[4, 5, 8, 4, 8, 7]);
        assert!(idx.iter().all(|&i| i < 9));
    }

    #[test]
    fn half_floats_decode() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x3555), 0.333_251_95);
        assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(f16_to_f32(0x7c00), f32::INFINITY);
    }

    #[test]
    fn frame_carries_reduced_phases_and_ring_ages_only() {
        let scene = PoolScene::default();
        let view = PoolView::default_desktop([64, 48]);
        // Ten hours in: every phase is reduced to [0, 2π), every age is under the window.
        let t = 36_000.0 + 0.3;
        let f = PoolFrame::new(&scene, t, &view, &PoolSettings::default());
        assert_eq!(f.dropped, 0);
        assert_eq!(f.waves.len(), scene.water.waves.waves.len());
        for w in &f.waves {
            assert!((0.0..std::f32::consts::TAU).contains(&w.phase0));
        }
        let rings = scene.rings(t);
        assert_eq!(f.pool.counts[1] as usize, rings.len());
        let window = scene.water.ripples.window_decays * scene.water.ripples.decay_s;
        for (g, r) in f.pool.rings.iter().zip(&rings) {
            assert!(f64::from(g.center_age_amp[2]) <= window + 1e-6);
            assert!((f64::from(g.center_age_amp[2]) - r.age).abs() < 1e-6);
        }
        assert_eq!(
            f.pool.counts[0] as usize,
            scene.floaters.len() + scene.movers.len()
        );
    }

    #[test]
    fn tub_stands_on_the_table_point() {
        let scene = PoolScene::default();
        let settings = PoolSettings::default();
        let anchor = glam::DVec3::new(0.4, 0.75, -1.2);
        let table = DMat4::from_scale_rotation_translation(
            glam::DVec3::splat(0.2),
            glam::DQuat::from_rotation_y(1.1),
            anchor,
        );
        let model = PoolView::standing_on(table, &scene, &settings);
        // The centre of the tub's bottom lands on the tapped point; the water's rest level
        // 0.2 × (1 m + wall) above it.
        let bottom = glam::DVec3::new(0.0, scene.pool.floor_y - settings.wall, 0.0);
        assert!((model.transform_point3(bottom) - anchor).length() < 1e-12);
        let water = model.transform_point3(glam::DVec3::ZERO);
        assert!((water.y - anchor.y - 0.2 * (1.0 + settings.wall)).abs() < 1e-12);
    }

    #[test]
    fn model_transform_puts_eye_into_pool_space() {
        // A pool scaled to 0.2 and moved onto a table 0.8 m up at (1, 0.8, -2): the eye in pool
        // space is the world eye taken back through the inverse similarity.
        let scene = PoolScene::default();
        let mut view = PoolView::default_desktop([64, 64]);
        view.model = DMat4::from_scale_rotation_translation(
            glam::DVec3::splat(0.2),
            glam::DQuat::from_rotation_y(0.5),
            glam::DVec3::new(1.0, 0.8, -2.0),
        );
        view.camera.eye = glam::DVec3::new(1.0, 1.3, -1.4);
        let f = PoolFrame::new(&scene, 1.0, &view, &PoolSettings::default());
        let back = view.model.transform_point3(glam::DVec3::new(
            f64::from(f.frame.eye[0]),
            f64::from(f.frame.eye[1]),
            f64::from(f.frame.eye[2]),
        ));
        assert!((back - view.camera.eye).length() < 1e-5);
        // A pool-space point projects where the world point does through the camera alone.
        let p = glam::DVec3::new(0.3, 0.0, -0.2);
        let vp = glam::DMat4::from_cols_array_2d(&f.frame.view_proj.map(|c| c.map(f64::from)));
        let aspect = 1.0;
        let direct = view.camera.view_proj_local(DVec2::ZERO, aspect)
            * view.model.transform_point3(p).extend(1.0);
        let via = vp * p.extend(1.0);
        assert!((direct.truncate() / direct.w - via.truncate() / via.w).length() < 1e-4);
    }
}
