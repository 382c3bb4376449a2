//! The water pass (`shaders/water.wgsl`): the clip-map displaced by the analytic sea and the
//! boats' wakes (`shaders/wake.wgsl`, sources from `ocean::wake`), with Fresnel-mixed sky
//! reflection, water-body light, Jacobian foam and wake foam.
//!
//! Wakes need storage buffers in vertex shaders; on an adapter without them (OpenGL ES 3.0)
//! the pass is built with the no-wake hook and the report says so.

use crate::clipmap::ClipVertex;
use crate::frame::{FrameContext, Pass, Targets};
use crate::gpu::Gpu;
use crate::passes::{PipelineSpec, pipeline};
use crate::shader;

/// The wake sources' bind group (group 1) of the water pass.
struct WakeBinding {
    layout: wgpu::BindGroupLayout,
    /// Sources, bins, indices, grid.
    buffers: [Option<wgpu::Buffer>; 4],
    group: Option<wgpu::BindGroup>,
}

/// `WakeGrid` of `shaders/water_wakes.wgsl` (32 bytes).
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
    vertices: Option<wgpu::Buffer>,
    indices: Option<wgpu::Buffer>,
    index_count: u32,
    wakes: Option<WakeBinding>,
}

/// Can this adapter read storage buffers in vertex shaders (what wakes need)?
pub fn supports_wakes(adapter: &wgpu::Adapter) -> bool {
    adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::VERTEX_STORAGE)
        && adapter.limits().max_storage_buffers_per_shader_stage >= 3
}

impl WaterPass {
    /// The water pass; `wakes` builds it with the wake hook (see [`supports_wakes`]).
    pub fn new(
        device: &wgpu::Device,
        frame_layout: &wgpu::BindGroupLayout,
        t: Targets,
        wakes: bool,
    ) -> Self {
        let wakes = wakes.then(|| WakeBinding {
            layout: device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("wake sources"),
                entries: &[0, 1, 2, 3].map(|binding| wgpu::BindGroupLayoutEntry {
                    binding,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: if binding == 3 {
                            wgpu::BufferBindingType::Uniform
                        } else {
                            wgpu::BufferBindingType::Storage { read_only: true }
                        },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                }),
            }),
            buffers: [None, None, None, None],
            group: None,
        });
        let module = match wakes {
            Some(_) => shader::module(
                device,
                "water",
                &[shader::WAKE, shader::WATER_WAKES, shader::WATER],
            ),
            None => shader::module(device, "water", &[shader::WATER_NO_WAKES, shader::WATER]),
        };
        let extra: Vec<&wgpu::BindGroupLayout> = wakes.iter().map(|w| &w.layout).collect();
        let spec = PipelineSpec {
            label: "water",
            module: &module,
            buffers: &[Some(vertex_layout())],
            depth_write: true,
            depth_test: true,
            cull: None,
            extra_layouts: &extra,
        };
        WaterPass {
            pipeline: pipeline(device, frame_layout, t, spec),
            vertices: None,
            indices: None,
            index_count: 0,
            wakes,
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
    /// The wake sources' bind group layout (group 1), when built with wakes.
    pub fn wake_layout(&self) -> Option<&wgpu::BindGroupLayout> {
        self.wakes.as_ref().map(|w| &w.layout)
    }

    /// Draw this frame's mesh (and wakes, group 1) with `pipeline`, which shares the water's
    /// vertex shader and layout; returns the triangles drawn.
    pub fn draw_with(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        pipeline: &wgpu::RenderPipeline,
    ) -> u64 {
        let (Some(v), Some(i)) = (&self.vertices, &self.indices) else {
            return 0;
        };
        pass.set_pipeline(pipeline);
        if let Some(g) = self.wakes.as_ref().and_then(|w| w.group.as_ref()) {
            pass.set_bind_group(1, g, &[]);
        }
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
        let wakes = match (&self.wakes, frame.wakes.sources.len()) {
            (None, n) if n > 0 => "; wakes skipped: no storage buffers in vertex shaders".into(),
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
        upload(
            gpu,
            &mut self.vertices,
            wgpu::BufferUsages::VERTEX,
            bytemuck::cast_slice(&frame.mesh.vertices),
        );
        upload(
            gpu,
            &mut self.indices,
            wgpu::BufferUsages::INDEX,
            bytemuck::cast_slice(&frame.mesh.indices),
        );
        self.index_count = frame.mesh.indices.len() as u32;
        if let Some(w) = self.wakes.as_mut() {
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
            let data: [(&[u8], wgpu::BufferUsages); 4] = [
                (bytemuck::cast_slice(sources), wgpu::BufferUsages::STORAGE),
                (
                    bytemuck::cast_slice(&bins.bins),
                    wgpu::BufferUsages::STORAGE,
                ),
                (bytemuck::cast_slice(indices), wgpu::BufferUsages::STORAGE),
                (bytemuck::bytes_of(&bins.grid), wgpu::BufferUsages::UNIFORM),
            ];
            let mut regrouped = w.group.is_none();
            for (slot, (bytes, usage)) in w.buffers.iter_mut().zip(data) {
                let old = slot.as_ref().map(|b| b.size());
                upload(gpu, slot, usage, bytes);
                regrouped |= slot.as_ref().map(|b| b.size()) != old;
            }
            if regrouped {
                let entries: Vec<wgpu::BindGroupEntry> = w
                    .buffers
                    .iter()
                    .enumerate()
                    .filter_map(|(i, b)| {
                        b.as_ref().map(|b| wgpu::BindGroupEntry {
                            binding: i as u32,
                            resource: b.as_entire_binding(),
                        })
                    })
                    .collect();
                w.group = Some(gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("wake sources"),
                    layout: &w.layout,
                    entries: &entries,
                }));
            }
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
