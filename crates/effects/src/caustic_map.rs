//! The area-ratio caustic map on the GPU (`shaders/caustic_map.wgsl`): the surface grid of
//! [`super::caustics::area_ratio`] (the f64 reference), displaced by the frame's waves,
//! refracted onto the table and added up into a half-float map, once per frame that needs it:
//! by a compute pass with integer atomics ([`CausticMethod::Scatter`],
//! `shaders/caustic_scatter.wgsl`) or, without compute shaders, rasterised with additive
//! blending ([`CausticMethod::Raster`]). It replaces the f64 map computed on the CPU every
//! frame (1–2 ms, more than a whole frame on a fast GPU).

use glam::{DVec2, DVec3};

use super::caustics::{CausticRegion, MAX_INTENSITY};
use render::frame::{FrameContext, OffscreenTimestamps};
use render::gpu::Gpu;

/// The caustic map's surface grid, landed on the table (both methods).
pub const CAUSTIC_MAP: &str = include_str!("../../../shaders/effects/caustic_map.wgsl");
/// The compute method's scatter and resolve (with [`CAUSTIC_MAP`]).
pub const CAUSTIC_SCATTER: &str = include_str!("../../../shaders/effects/caustic_scatter.wgsl");
/// The caustic map's texel format: additive, filterable, values well above 1.
pub const CAUSTIC_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

/// `CausticGrid` of `shaders/caustic_map.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
struct CausticGrid {
    origin: [f32; 2],
    step: f32,
    side: u32,
    region: [f32; 4],
    light: [f32; 4],
    map: [f32; 4],
}

/// How the landed triangles are added up into the map (`shaders/caustic_map.wgsl`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CausticMethod {
    /// Rasterised with additive blending: for adapters without compute shaders.
    Raster,
    /// Each triangle finds its texel centres in a compute pass and adds to them with integer
    /// atomics; a small pass resolves the sums into the map. A rasteriser pays per triangle
    /// and the grid's triangles are about a texel each: on lavapipe 0.81 ms → see docs/effects.md.
    Scatter,
}

impl CausticMethod {
    /// Scatter where the adapter runs compute shaders with two storage buffers per stage.
    pub fn for_adapter(adapter: &wgpu::Adapter) -> CausticMethod {
        let compute = adapter
            .get_downlevel_capabilities()
            .flags
            .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
            && adapter.limits().max_storage_buffers_per_shader_stage >= 2;
        if compute {
            CausticMethod::Scatter
        } else {
            CausticMethod::Raster
        }
    }

    /// Render and compute passes it records per map.
    fn passes(self) -> usize {
        match self {
            CausticMethod::Raster => 1,
            CausticMethod::Scatter => 2,
        }
    }
}

/// The pass: its grid uniform (group 1) and the method's pipelines and buffers.
pub struct CausticMapPass {
    uniform: render::gpu::UniformGroup,
    method: Method,
    /// Grid points per side and texels per side of the prepared map.
    side: u32,
    map_side: u32,
}

enum Method {
    Raster {
        pipeline: wgpu::RenderPipeline,
        /// The grid's index buffer for `side` points per side, and its index count.
        indices: Option<(u32, wgpu::Buffer, u32)>,
    },
    Scatter(Box<Scatter>),
}

struct Scatter {
    points: wgpu::ComputePipeline,
    triangles: wgpu::ComputePipeline,
    resolve: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    resolve_layout: wgpu::BindGroupLayout,
    /// Buffers and groups for (grid side, map side).
    buffers: Option<ScatterBuffers>,
}

struct ScatterBuffers {
    sides: (u32, u32),
    light: wgpu::Buffer,
    group: wgpu::BindGroup,
    resolve_group: wgpu::BindGroup,
}

/// The surface grid of `area_ratio` for `region`: its first rest point (world), step and
/// points per side, with the same margin for light bent in from outside the square.
pub fn surface_grid(
    region: &CausticRegion,
    waves: &ocean::WaveSet,
    depth: f64,
    src_res: usize,
) -> (DVec2, f64, usize) {
    let src_res = src_res.max(1);
    let step = region.size / src_res as f64;
    let travel = depth.abs() * 1.5 + waves.waves.iter().map(|w| w.amplitude()).sum::<f64>();
    let margin = if region.periodic {
        0
    } else {
        (travel / step).ceil() as usize + 1
    };
    let origin = DVec2::from(region.min) - DVec2::splat(margin as f64 * step);
    (origin, step, src_res + 2 * margin + 1)
}

impl CausticMapPass {
    /// The pass with the method the adapter supports.
    pub fn new(gpu: &Gpu, frame_layout: &wgpu::BindGroupLayout) -> CausticMapPass {
        Self::with_method(gpu, frame_layout, CausticMethod::for_adapter(&gpu.adapter))
    }

    pub fn with_method(
        gpu: &Gpu,
        frame_layout: &wgpu::BindGroupLayout,
        method: CausticMethod,
    ) -> CausticMapPass {
        let device = &gpu.device;
        let uniform =
            render::gpu::UniformGroup::new(device, "caustic grid", size_of::<CausticGrid>() as u64);
        let method = match method {
            CausticMethod::Raster => {
                let module = crate::wgsl::module(device, "caustic map", &[CAUSTIC_MAP]);
                let pipeline = render::passes::bufferless_pipeline(
                    device,
                    render::passes::BufferlessPipeline {
                        label: "caustic map",
                        module: &module,
                        vertex: "vs_main",
                        fragment: "fs_main",
                        layouts: Some(&[Some(frame_layout), Some(&uniform.layout)]),
                        format: CAUSTIC_MAP_FORMAT,
                        blend: Some(render::passes::ADDITIVE),
                        depth: None,
                    },
                );
                Method::Raster {
                    pipeline,
                    indices: None,
                }
            }
            CausticMethod::Scatter => Method::Scatter(Box::new(Scatter::new(gpu, frame_layout))),
        };
        CausticMapPass {
            uniform,
            method,
            side: 0,
            map_side: 0,
        }
    }

    /// The method this pass draws with.
    pub fn method(&self) -> CausticMethod {
        match self.method {
            Method::Raster { .. } => CausticMethod::Raster,
            Method::Scatter(_) => CausticMethod::Scatter,
        }
    }

    /// Upload the grid that draws the caustics of `frame`'s sea on a table `depth` metres down
    /// over `region` (world metres) into a map `map_side` texels wide, from a `src_res`²
    /// surface grid.
    pub fn prepare(
        &mut self,
        gpu: &Gpu,
        frame: &FrameContext,
        region: &CausticRegion,
        depth: f64,
        src_res: usize,
        map_side: u32,
    ) {
        let s = frame.scene;
        let (origin, step, side) = surface_grid(region, &s.sea, depth, src_res);
        let o = frame.origin;
        let light = (-s.sun).normalize_or(DVec3::NEG_Y);
        let f = |v: f64| v as f32;
        let map_side = map_side.max(1);
        let grid = CausticGrid {
            origin: [f(origin.x - o.x), f(origin.y - o.y)],
            step: f(step),
            side: side as u32,
            region: [
                f(region.min[0] - o.x),
                f(region.min[1] - o.y),
                f(region.size),
                f(depth),
            ],
            light: [f(light.x), f(light.y), f(light.z), f(MAX_INTENSITY)],
            map: [
                f(region.size / f64::from(map_side)),
                map_side as f32,
                0.0,
                0.0,
            ],
        };
        gpu.queue
            .write_buffer(&self.uniform.buffer, 0, bytemuck::bytes_of(&grid));
        let side = side as u32;
        (self.side, self.map_side) = (side, map_side);
        match &mut self.method {
            Method::Raster { indices, .. } => {
                if indices.as_ref().is_none_or(|(n, _, _)| *n != side) {
                    *indices = Some(grid_indices(gpu, side));
                }
            }
            Method::Scatter(scatter) => scatter.fit(gpu, &self.uniform.buffer, side, map_side),
        }
    }

    /// Record the prepared grid's caustics into `target` (a [`CAUSTIC_MAP_FORMAT`] map of the
    /// prepared side). `frame_group` is bind group 0 with this frame's waves. `timestamps`
    /// are those of a run of `count` offscreen passes, this map's starting at `first`.
    pub fn record(
        &self,
        enc: &mut wgpu::CommandEncoder,
        frame_group: &wgpu::BindGroup,
        target: &wgpu::TextureView,
        timestamps: Option<OffscreenTimestamps<'_>>,
        first: usize,
        count: usize,
    ) {
        let writes = |index| OffscreenTimestamps::render(timestamps, index, count);
        match &self.method {
            Method::Raster { pipeline, indices } => {
                let mut pass = render::gpu::colour_pass(
                    enc,
                    "caustic map",
                    target,
                    wgpu::Color::TRANSPARENT,
                    writes(first),
                );
                if let Some((_, indices, n)) = indices {
                    pass.set_pipeline(pipeline);
                    pass.set_bind_group(0, frame_group, &[]);
                    pass.set_bind_group(1, &self.uniform.group, &[]);
                    pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..*n, 0, 0..1);
                }
            }
            Method::Scatter(scatter) => {
                let Some(b) = &scatter.buffers else {
                    render::gpu::colour_pass(
                        enc,
                        "caustic map",
                        target,
                        wgpu::Color::TRANSPARENT,
                        writes(first),
                    );
                    return;
                };
                enc.clear_buffer(&b.light, 0, None);
                {
                    let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: Some("caustic map scatter"),
                        timestamp_writes: OffscreenTimestamps::compute(timestamps, first, count),
                    });
                    pass.set_bind_group(0, frame_group, &[]);
                    pass.set_bind_group(1, &b.group, &[]);
                    pass.set_pipeline(&scatter.points);
                    pass.dispatch_workgroups(
                        (self.side * self.side).div_ceil(render::shader::WORKGROUP_SIZE),
                        1,
                        1,
                    );
                    let cells = self.side.saturating_sub(1);
                    pass.set_pipeline(&scatter.triangles);
                    pass.dispatch_workgroups(
                        (cells * cells).div_ceil(render::shader::WORKGROUP_SIZE),
                        1,
                        1,
                    );
                }
                let mut pass = render::gpu::colour_pass(
                    enc,
                    "caustic map",
                    target,
                    wgpu::Color::TRANSPARENT,
                    writes(first + 1),
                );
                pass.set_pipeline(&scatter.resolve);
                pass.set_bind_group(2, &b.resolve_group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
    }

    /// Offscreen passes [`Self::record`] makes.
    pub fn passes(&self) -> usize {
        self.method().passes()
    }
}

/// The grid's index buffer for `side` points per side: each cell as area_ratio splits it,
/// (k, k+1, k+side+1), (k, k+side+1, k+side).
fn grid_indices(gpu: &Gpu, side: u32) -> (u32, wgpu::Buffer, u32) {
    let mut idx = Vec::with_capacity(((side - 1) * (side - 1) * 6) as usize);
    for j in 0..side - 1 {
        for i in 0..side - 1 {
            let k = j * side + i;
            idx.extend_from_slice(&[k, k + 1, k + side + 1, k, k + side + 1, k + side]);
        }
    }
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("caustic grid indices"),
        size: (idx.len() * 4).max(4) as u64,
        usage: wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    gpu.queue
        .write_buffer(&buffer, 0, bytemuck::cast_slice(&idx));
    (side, buffer, idx.len() as u32)
}

impl Scatter {
    fn new(gpu: &Gpu, frame_layout: &wgpu::BindGroupLayout) -> Scatter {
        use render::gpu::layout;
        let device = &gpu.device;
        let compute = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("caustic scatter"),
            entries: &[
                layout::uniform(0, compute),
                layout::storage(1, compute, false),
                layout::storage(2, compute, false),
            ],
        });
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let resolve_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("caustic resolve"),
            entries: &[
                layout::storage(0, fragment, true),
                layout::uniform(1, fragment),
            ],
        });
        let module =
            crate::wgsl::module(device, "caustic scatter", &[CAUSTIC_MAP, CAUSTIC_SCATTER]);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("caustic scatter"),
            bind_group_layouts: &[Some(frame_layout), Some(&layout)],
            immediate_size: 0,
        });
        let compute_pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let resolve = render::passes::bufferless_pipeline(
            device,
            render::passes::BufferlessPipeline {
                label: "caustic resolve",
                module: &module,
                vertex: "vs_resolve",
                fragment: "fs_resolve",
                layouts: Some(&[None, None, Some(&resolve_layout)]),
                format: CAUSTIC_MAP_FORMAT,
                blend: None,
                depth: None,
            },
        );
        Scatter {
            points: compute_pipeline("cs_points"),
            triangles: compute_pipeline("cs_triangles"),
            resolve,
            layout,
            resolve_layout,
            buffers: None,
        }
    }

    /// Make the point and light buffers for `side` grid points and `map_side` texels per side
    /// unless they exist.
    fn fit(&mut self, gpu: &Gpu, uniform: &wgpu::Buffer, side: u32, map_side: u32) {
        if self
            .buffers
            .as_ref()
            .is_some_and(|b| b.sides == (side, map_side))
        {
            return;
        }
        let device = &gpu.device;
        let buffer = |label, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let points = buffer("caustic grid points", u64::from(side * side) * 16);
        let light = buffer("caustic light sums", u64::from(map_side * map_side) * 4);
        fn entry(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding,
                resource: b.as_entire_binding(),
            }
        }
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("caustic scatter"),
            layout: &self.layout,
            entries: &[entry(0, uniform), entry(1, &points), entry(2, &light)],
        });
        let resolve_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("caustic resolve"),
            layout: &self.resolve_layout,
            entries: &[entry(0, &light), entry(1, uniform)],
        });
        self.buffers = Some(ScatterBuffers {
            sides: (side, map_side),
            light,
            group,
            resolve_group,
        });
    }
}
