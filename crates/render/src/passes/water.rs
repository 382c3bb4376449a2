//! The water pass (`shaders/water.wgsl`): the clip-map displaced by the analytic sea and the
//! boats' wakes (`shaders/wake.wgsl`, sources from `ocean::wake`), with Fresnel-mixed sky
//! reflection, water-body light, Jacobian foam and wake foam.
//!
//! Where the adapter has compute shaders, a compute stage (`shaders/water_vertices.wgsl`)
//! displaces every clip-map vertex by the sea and the wakes once per frame into a vertex
//! buffer, and the vertex shader (`shaders/water_displaced.wgsl`) only projects it: a vertex
//! shader summing hundreds of wake sources starves a GPU's vertex pipeline (13× the water
//! pass on an H200) and runs on one thread in lavapipe. Without compute (OpenGL ES 3.0) the
//! vertex shader displaces by the sea alone (`shaders/water_no_wakes.wgsl`) and the report
//! says that wakes are skipped.

use crate::clipmap::ClipVertex;
use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::passes::{PipelineSpec, pipeline};
use crate::shader;

/// The water pass's compute stage: its pipeline and bind group 1.
struct VertexCompute {
    pipeline: wgpu::ComputePipeline,
    /// Wake sources, bins, indices, grid, the clip-map vertices and the displaced vertices.
    buffers: [Option<wgpu::Buffer>; 6],
    group: Option<wgpu::BindGroup>,
    /// Vertices to displace this frame.
    vertex_count: u32,
}

/// Bytes of one displaced vertex (`DisplacedVertex` of `shaders/water_vertices.wgsl`).
const DISPLACED_VERTEX_BYTES: u64 = 32;

/// `WakeGrid` of `shaders/water_vertices.wgsl` (32 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WakeGrid {
    pub origin: [f32; 2],
    pub inv_cell: f32,
    pub margin: f32,
    pub nx: u32,
    pub nz: u32,
    pub _pad: [u32; 2],
}

/// The wake sources binned on a grid: a point looks up its bin and sums only the sources
/// listed there. Every source whose cull circle, grown by `margin`, touches a bin is listed
/// in it, so a point within `margin` of a bin's points misses no source that reaches it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WakeBins {
    pub grid: WakeGrid,
    /// Per bin, row-major (x fastest): first index into `indices` and count.
    pub bins: Vec<[u32; 2]>,
    pub indices: Vec<u32>,
}

impl WakeBins {
    /// Bin `sources` over the rectangle their cull circles (grown by `margin`) cover, clipped
    /// to the square [−half, half]² (local metres).
    pub fn over_reach(
        sources: &[ocean::wake::GpuWakeSource],
        half: f32,
        max_bins: u32,
        margin: f32,
    ) -> WakeBins {
        let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
        for s in sources {
            let r = s.cull_r2.max(0.0).sqrt() + margin;
            for a in 0..2 {
                lo[a] = lo[a].min(s.pos[a] - r);
                hi[a] = hi[a].max(s.pos[a] + r);
            }
        }
        let (lo, hi) = (lo.map(|v| v.max(-half)), hi.map(|v| v.min(half)));
        if lo[0] >= hi[0] || lo[1] >= hi[1] {
            // Nothing reaches the square: one empty bin.
            return WakeBins::new(&[], [-half, -half], [half, half], 1, margin);
        }
        WakeBins::new(sources, lo, hi, max_bins, margin)
    }

    /// Bin `sources` over the local rectangle [lo, hi] with at most `max_bins` per side.
    pub fn new(
        sources: &[ocean::wake::GpuWakeSource],
        lo: [f32; 2],
        hi: [f32; 2],
        max_bins: u32,
        margin: f32,
    ) -> WakeBins {
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1.0);
        let cell = (size / max_bins as f32).max(2.0);
        let nx = (((hi[0] - lo[0]) / cell).ceil() as u32).clamp(1, max_bins);
        let nz = (((hi[1] - lo[1]) / cell).ceil() as u32).clamp(1, max_bins);
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); (nx * nz) as usize];
        let bin_of =
            |v: f32, o: f32, n: u32| ((v - o) / cell).floor().clamp(0.0, n as f32 - 1.0) as u32;
        for (k, s) in sources.iter().enumerate() {
            let r = s.cull_r2.max(0.0).sqrt() + margin;
            let (x0, x1) = (s.pos[0] - r, s.pos[0] + r);
            let (z0, z1) = (s.pos[1] - r, s.pos[1] + r);
            if x1 < lo[0]
                || z1 < lo[1]
                || x0 > lo[0] + nx as f32 * cell
                || z0 > lo[1] + nz as f32 * cell
            {
                continue;
            }
            for j in bin_of(z0, lo[1], nz)..=bin_of(z1, lo[1], nz) {
                for i in bin_of(x0, lo[0], nx)..=bin_of(x1, lo[0], nx) {
                    lists[(j * nx + i) as usize].push(k as u32);
                }
            }
        }
        let mut bins = Vec::with_capacity(lists.len());
        let mut indices = Vec::new();
        for l in &lists {
            bins.push([indices.len() as u32, l.len() as u32]);
            indices.extend_from_slice(l);
        }
        WakeBins {
            grid: WakeGrid {
                origin: lo,
                inv_cell: 1.0 / cell,
                margin,
                nx,
                nz,
                _pad: [0; 2],
            },
            bins,
            indices,
        }
    }
}

/// Bins per side of the wake grid, and how far (m) around a bin its list reaches: the
/// gradient is closed-form, so the margin only covers rounding of the bin lookup.
const WAKE_BINS: u32 = 128;
const WAKE_MARGIN_M: f32 = 0.5;

pub struct WaterPass {
    pipeline: wgpu::RenderPipeline,
    /// The clip-map vertices (drawn directly without the compute stage).
    vertices: Option<wgpu::Buffer>,
    indices: Option<wgpu::Buffer>,
    index_count: u32,
    compute: Option<VertexCompute>,
}

/// Can this adapter run the water's compute stage (sea and wakes per vertex)?
pub fn supports_wakes(adapter: &wgpu::Adapter) -> bool {
    adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        && adapter.limits().max_storage_buffers_per_shader_stage >= 5
}

/// The vertex stage of a pipeline that draws the water mesh: the WGSL file that defines
/// `vs_main` and its vertex buffer layout. `wakes`: the compute stage's displaced vertices.
pub fn vertex_stage(wakes: bool) -> (&'static str, wgpu::VertexBufferLayout<'static>) {
    if wakes {
        (
            shader::WATER_DISPLACED,
            wgpu::VertexBufferLayout {
                array_stride: DISPLACED_VERTEX_BYTES,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &DISPLACED_ATTRIBUTES,
            },
        )
    } else {
        (shader::WATER_NO_WAKES, vertex_layout())
    }
}

const DISPLACED_ATTRIBUTES: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4];

impl WaterPass {
    /// The water pass; `wakes` builds it with the wake hook (see [`supports_wakes`]).
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        t: Targets,
        wakes: bool,
    ) -> Self {
        let compute = wakes.then(|| {
            use crate::gpu::layout;
            let cs = wgpu::ShaderStages::COMPUTE;
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("water vertices"),
                entries: &[0, 1, 2, 3, 4, 5].map(|binding| match binding {
                    3 => layout::uniform(binding, cs),
                    _ => layout::storage(binding, cs, binding != 5),
                }),
            });
            let module = shader::module(
                device,
                "water vertices",
                &[shader::WAKE, shader::WATER_VERTICES],
            );
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("water vertices"),
                bind_group_layouts: &[Some(frame_layout), Some(&layout)],
                immediate_size: 0,
            });
            VertexCompute {
                pipeline: device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("water vertices"),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some("cs_displace"),
                    compilation_options: Default::default(),
                    cache: None,
                }),
                buffers: Default::default(),
                group: None,
                vertex_count: 0,
            }
        });
        let (stage, buffer) = vertex_stage(wakes);
        let module = shader::module(device, "water", &[stage, shader::WATER]);
        let spec = PipelineSpec {
            label: "water",
            module: &module,
            buffers: &[Some(buffer)],
            depth_write: true,
            depth_test: true,
            cull: None,
            extra_layouts: &[],
        };
        WaterPass {
            pipeline: pipeline(device, frame_layout, t, spec),
            vertices: None,
            indices: None,
            index_count: 0,
            compute,
        }
    }
}

/// The clip-map vertex attributes of `shaders/water.wgsl`'s `VertexIn`.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x2, 1 => Float32, 2 => Uint32];

/// The clip-map vertex buffer layout, for pipelines that draw the water mesh with another
/// fragment shader (the AR effects' `ArWaterPass`).
pub fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: size_of::<ClipVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

impl WaterPass {
    /// Draw this frame's mesh with `pipeline`, which shares the water's vertex stage
    /// ([`vertex_stage`]); returns the triangles drawn.
    pub fn draw_with(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        pipeline: &wgpu::RenderPipeline,
    ) -> u64 {
        let drawn = match &self.compute {
            Some(c) => c.buffers[5].as_ref(),
            None => self.vertices.as_ref(),
        };
        let (Some(v), Some(i)) = (drawn, &self.indices) else {
            return 0;
        };
        pass.set_pipeline(pipeline);
        pass.set_vertex_buffer(0, v.slice(..));
        pass.set_index_buffer(i.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
        u64::from(self.index_count / 3)
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
        *slot = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pass data"),
            size: need.next_power_of_two(),
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

impl Pass for WaterPass {
    fn name(&self) -> &'static str {
        "water"
    }
    fn condition(&self) -> &'static str {
        "some clip-map tile survives frustum and play-area culling"
    }
    fn plan(&self, frame: &FrameContext) -> Result<String, String> {
        let drawn: u32 = frame.mesh.levels.iter().map(|l| l.tiles_drawn).sum();
        let wakes = match (&self.compute, frame.wakes.sources.len()) {
            (None, n) if n > 0 => "; wakes skipped: the adapter has no compute shaders".into(),
            (_, 0) => String::new(),
            (_, n) => format!("; {n} wake sources ({} culled)", frame.wakes.culled),
        };
        if drawn > 0 {
            Ok(format!("{drawn} clip-map tiles in view{wakes}"))
        } else {
            Err("water off screen: every clip-map tile is outside the view or the play area".into())
        }
    }
    fn prepare(&mut self, gpu: &Gpu, frame: &FrameContext) {
        let vertex_bytes: &[u8] = bytemuck::cast_slice(&frame.mesh.vertices);
        upload(
            gpu,
            &mut self.indices,
            wgpu::BufferUsages::INDEX,
            bytemuck::cast_slice(&frame.mesh.indices),
        );
        self.index_count = frame.mesh.indices.len() as u32;
        let Some(c) = self.compute.as_mut() else {
            upload(
                gpu,
                &mut self.vertices,
                wgpu::BufferUsages::VERTEX,
                vertex_bytes,
            );
            return;
        };
        // Bin over where the sources reach, inside the clip-map's square around the local
        // origin: the bins are as small as the fleet's wake allows, not the whole sea's.
        let h = frame.clipmap.half_extent(frame.clipmap.levels() - 1) as f32 * 2.0;
        let bins = WakeBins::over_reach(&frame.wakes.sources, h, WAKE_BINS, WAKE_MARGIN_M);
        // Buffers are never empty (a zeroed entry is never read: counts say what is live).
        let zero = [ocean::wake::GpuWakeSource::default()];
        let sources: &[ocean::wake::GpuWakeSource] = if frame.wakes.sources.is_empty() {
            &zero
        } else {
            &frame.wakes.sources
        };
        let indices: &[u32] = if bins.indices.is_empty() {
            &[0]
        } else {
            &bins.indices
        };
        let n = frame.mesh.vertices.len();
        let storage = wgpu::BufferUsages::STORAGE;
        let data: [(&[u8], wgpu::BufferUsages); 5] = [
            (bytemuck::cast_slice(sources), storage),
            (bytemuck::cast_slice(&bins.bins), storage),
            (bytemuck::cast_slice(indices), storage),
            (bytemuck::bytes_of(&bins.grid), wgpu::BufferUsages::UNIFORM),
            (vertex_bytes, storage),
        ];
        for (slot, (bytes, usage)) in c.buffers.iter_mut().zip(data) {
            upload(gpu, slot, usage, bytes);
        }
        // The displaced vertices: written by the compute stage, drawn as a vertex buffer.
        let need = (n as u64 * DISPLACED_VERTEX_BYTES).max(DISPLACED_VERTEX_BYTES);
        if c.buffers[5].as_ref().is_none_or(|b| b.size() < need) {
            c.buffers[5] = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("displaced water vertices"),
                size: need.next_power_of_two(),
                usage: storage | wgpu::BufferUsages::VERTEX,
                mapped_at_creation: false,
            }));
        }
        // Made each frame: the vertex bindings are sized to this frame's mesh, so the
        // shader's arrayLength is the vertex count.
        let entries: Vec<wgpu::BindGroupEntry> = c
            .buffers
            .iter()
            .enumerate()
            .filter_map(|(i, b)| {
                let size = match i {
                    4 => std::num::NonZeroU64::new(vertex_bytes.len() as u64),
                    5 => std::num::NonZeroU64::new(n as u64 * DISPLACED_VERTEX_BYTES),
                    _ => None,
                };
                b.as_ref().map(|buffer| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer,
                        offset: 0,
                        size,
                    }),
                })
            })
            .collect();
        c.vertex_count = 0;
        if n == 0 {
            return;
        }
        c.group = Some(gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("water vertices"),
            layout: &c.pipeline.get_bind_group_layout(1),
            entries: &entries,
        }));
        c.vertex_count = n as u32;
    }
    fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>) {
        if let Some(c) = &self.compute
            && let Some(group) = &c.group
            && c.vertex_count > 0
        {
            pass.set_pipeline(&c.pipeline);
            pass.set_bind_group(1, group, &[]);
            pass.dispatch_workgroups(c.vertex_count.div_ceil(64), 1, 1);
        }
    }
    fn draw(&self, pass: &mut wgpu::RenderPass<'_>) -> u64 {
        self.draw_with(pass, &self.pipeline)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean::wake::GpuWakeSource;

    #[test]
    fn every_source_reaching_a_point_is_in_its_bin() {
        // Sources scattered over a square, each reaching a different radius.
        let sources: Vec<GpuWakeSource> = (0..300)
            .map(|k| {
                let f = k as f32;
                GpuWakeSource {
                    pos: [(f * 37.3) % 400.0 - 200.0, (f * 91.7) % 400.0 - 200.0],
                    cull_r2: (1.0 + (f * 13.1) % 30.0).powi(2),
                    ..Default::default()
                }
            })
            .collect();
        let bins = WakeBins::new(&sources, [-250.0, -250.0], [250.0, 250.0], 32, 2.0);
        let g = bins.grid;
        let mut listed = 0usize;
        for a in 0..97 {
            for b in 0..89 {
                let p = [-249.0 + a as f32 * 5.13, -249.0 + b as f32 * 5.59];
                let i = ((p[0] - g.origin[0]) * g.inv_cell) as u32;
                let j = ((p[1] - g.origin[1]) * g.inv_cell) as u32;
                let [first, count] = bins.bins[(j * g.nx + i) as usize];
                let list = &bins.indices[first as usize..(first + count) as usize];
                listed += list.len();
                // Any stencil point within the margin: every source whose cull circle holds
                // it is listed.
                for q in [p, [p[0] + 1.9, p[1]], [p[0], p[1] - 1.9]] {
                    for (k, s) in sources.iter().enumerate() {
                        let d2 = (q[0] - s.pos[0]).powi(2) + (q[1] - s.pos[1]).powi(2);
                        if d2 <= s.cull_r2 {
                            assert!(list.contains(&(k as u32)), "source {k} missing at {q:?}");
                        }
                    }
                }
            }
        }
        // And binning saves work: far fewer than all sources per point on average.
        assert!(listed < 97 * 89 * sources.len() / 5, "{listed}");
    }

    /// The sources a point sums: its bin's list, or none outside the grid (as `wake_bin`).
    fn listed_at(bins: &WakeBins, p: [f32; 2]) -> &[u32] {
        let g = bins.grid;
        let (x, z) = (
            (p[0] - g.origin[0]) * g.inv_cell,
            (p[1] - g.origin[1]) * g.inv_cell,
        );
        if x < 0.0 || z < 0.0 || x >= g.nx as f32 || z >= g.nz as f32 {
            return &[];
        }
        let [first, count] = bins.bins[(z as u32 * g.nx + x as u32) as usize];
        &bins.indices[first as usize..(first + count) as usize]
    }

    #[test]
    fn bins_cover_only_where_the_sources_reach() {
        // A fleet's wake 120 m across, 900 m from the origin of a 4 km clip-map.
        let sources: Vec<GpuWakeSource> = (0..200)
            .map(|k| {
                let f = k as f32;
                GpuWakeSource {
                    pos: [900.0 + (f * 37.3) % 120.0, -300.0 + (f * 91.7) % 80.0],
                    cull_r2: (2.0 + (f * 13.1) % 20.0).powi(2),
                    ..Default::default()
                }
            })
            .collect();
        let bins = WakeBins::over_reach(&sources, 2000.0, 128, 0.5);
        let whole = WakeBins::new(&sources, [-2000.0; 2], [2000.0; 2], 128, 0.5);
        // The grid spans the reach (≤ 164 m) in the smallest bins (2 m), not the whole
        // square's 31 m bins.
        let g = bins.grid;
        let cell = 1.0 / g.inv_cell;
        assert!(cell <= 2.0 + 1e-3, "{g:?}");
        assert!(
            g.nx as f32 * cell <= 166.0 && g.nz as f32 * cell <= 166.0,
            "{g:?}"
        );
        let (mut fine, mut coarse) = (0usize, 0usize);
        for a in 0..200 {
            for b in 0..150 {
                let p = [860.0 + a as f32 * 1.01, -340.0 + b as f32 * 1.07];
                let list = listed_at(&bins, p);
                for (k, s) in sources.iter().enumerate() {
                    let d2 = (p[0] - s.pos[0]).powi(2) + (p[1] - s.pos[1]).powi(2);
                    if d2 <= s.cull_r2 {
                        assert!(list.contains(&(k as u32)), "source {k} missing at {p:?}");
                    }
                }
                fine += list.len();
                coarse += listed_at(&whole, p).len();
            }
        }
        // Far fewer sources to loop over per point than with bins over the whole square.
        assert!(fine * 3 < coarse, "{fine} vs {coarse}");
        assert!(listed_at(&bins, [0.0, 0.0]).is_empty());
        // No source in reach: an empty grid.
        let none = WakeBins::over_reach(&sources, 100.0, 128, 0.5);
        assert!(none.indices.is_empty() && listed_at(&none, [0.0, 0.0]).is_empty());
    }
}
