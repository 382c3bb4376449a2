//! What the renderer measures on the GPU when asked ([`crate::RenderOptions`]'s
//! `measure_gpu_time`): per-pass durations from timestamp queries ([`GpuTimer`], which owns
//! the slot arithmetic) and the primitives each pass submits from pipeline-statistics queries
//! ([`PassStats`]). Both resolve into the frame's encoder and read back after its submission.

use crate::frame::OffscreenTimestamps;
use crate::gpu::{Gpu, GpuError};

/// Passes a frame can time.
pub(crate) const TIMED_PASSES: u32 = 16;
/// Timestamp slots of pass k: 4k.. begin and end of its render pass and its compute stage.
/// The passes with offscreen work follow from OFFSCREEN_SLOTS, two each, in order: only
/// written slots are resolved (a query never written has no defined value), and a resolve
/// lands at a multiple of 256 bytes (wgpu::QUERY_RESOLVE_BUFFER_ALIGNMENT).
const OFFSCREEN_SLOTS: u32 = 4 * TIMED_PASSES;
// The last offscreen pair is inside the 6 × TIMED_PASSES queries, and a resolve at
// OFFSCREEN_SLOTS lands on the alignment wgpu asks for.
const _: () = assert!(OFFSCREEN_SLOTS + 2 * (TIMED_PASSES - 1) + 1 < 6 * TIMED_PASSES);
const _: () =
    assert!((OFFSCREEN_SLOTS as u64 * 8).is_multiple_of(wgpu::QUERY_RESOLVE_BUFFER_ALIGNMENT));

/// Timestamp queries of a frame's passes: where each pass writes, the resolve and read-back,
/// and the durations they give.
pub(crate) struct GpuTimer {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
}

/// Two query-sized buffers: one to resolve into, one to map.
fn resolve_and_read(device: &wgpu::Device, what: &str, size: u64) -> (wgpu::Buffer, wgpu::Buffer) {
    let buffer = |label: String, usage| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&label),
            size,
            usage,
            mapped_at_creation: false,
        })
    };
    (
        buffer(
            what.to_string(),
            wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
        ),
        buffer(
            format!("{what} read"),
            wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        ),
    )
}

impl GpuTimer {
    /// The timer, where the device has timestamp queries.
    pub(crate) fn new(gpu: &Gpu) -> Option<GpuTimer> {
        if !gpu.features.contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        // Per pass: begin and end of its render pass, its compute stage and its offscreen
        // passes (OFFSCREEN_SLOTS).
        let capacity = 6 * TIMED_PASSES;
        let (resolve, read) = resolve_and_read(&gpu.device, "timestamps", u64::from(capacity) * 8);
        Some(GpuTimer {
            queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: capacity,
            }),
            resolve,
            read,
        })
    }

    /// Can it time a frame of `passes` passes?
    pub(crate) fn fits(passes: usize) -> bool {
        passes <= TIMED_PASSES as usize
    }

    fn slot(k: usize, i: u32) -> u32 {
        4 * k as u32 + i
    }

    /// Where the `m`-th pass with offscreen work writes its offscreen timestamps.
    pub(crate) fn offscreen(&self, m: u32) -> OffscreenTimestamps<'_> {
        OffscreenTimestamps {
            queries: &self.queries,
            begin: OFFSCREEN_SLOTS + 2 * m,
            end: OFFSCREEN_SLOTS + 2 * m + 1,
        }
    }

    /// The timestamps of the `k`-th pass that runs: its compute stage.
    pub(crate) fn compute(&self, k: usize) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(Self::slot(k, 2)),
            end_of_pass_write_index: Some(Self::slot(k, 3)),
        }
    }

    /// The timestamps of the `k`-th pass that runs: its render pass.
    pub(crate) fn render(&self, k: usize) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(Self::slot(k, 0)),
            end_of_pass_write_index: Some(Self::slot(k, 1)),
        }
    }

    /// Resolve the slots `passes` passes and `offscreen` offscreen records wrote, and copy
    /// them for reading.
    pub(crate) fn resolve(&self, enc: &mut wgpu::CommandEncoder, passes: usize, offscreen: u32) {
        let n = 4 * passes as u32;
        enc.resolve_query_set(&self.queries, 0..n, &self.resolve, 0);
        let m = 2 * offscreen;
        let at = u64::from(OFFSCREEN_SLOTS) * 8;
        if m > 0 {
            enc.resolve_query_set(
                &self.queries,
                OFFSCREEN_SLOTS..OFFSCREEN_SLOTS + m,
                &self.resolve,
                at,
            );
        }
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, at + u64::from(m) * 8);
    }

    /// Read the submitted frame's timestamps back: per pass that ran, its milliseconds (render
    /// pass and compute stage) and those of its offscreen work (`offscreen[k]`: the index
    /// among the passes with offscreen work of the `k`-th pass, where it had any).
    pub(crate) fn read(
        &self,
        gpu: &Gpu,
        offscreen: &[Option<u32>],
    ) -> Result<Vec<(f64, Option<f64>)>, GpuError> {
        let bytes = gpu.read_buffer(&self.read)?;
        let ticks: &[u64] = bytemuck::cast_slice(&bytes);
        let period_ns = f64::from(gpu.queue.get_timestamp_period());
        Ok(Self::durations(ticks, period_ns, offscreen))
    }

    /// The slot arithmetic of [`GpuTimer::read`] on resolved `ticks` of `period_ns` each.
    fn durations(
        ticks: &[u64],
        period_ns: f64,
        offscreen: &[Option<u32>],
    ) -> Vec<(f64, Option<f64>)> {
        let ms = |ticks: u64| ticks as f64 * period_ns * 1e-6;
        offscreen
            .iter()
            .enumerate()
            .map(|(k, off)| {
                let q = &ticks[Self::slot(k, 0) as usize..Self::slot(k + 1, 0) as usize];
                let own = q[1].saturating_sub(q[0]) + q[3].saturating_sub(q[2]);
                let off = off.map(|m| {
                    let o = (OFFSCREEN_SLOTS + 2 * m) as usize;
                    ms(ticks[o + 1].saturating_sub(ticks[o]))
                });
                (ms(own), off)
            })
            .collect()
    }
}

/// Counters each pipeline-statistics query writes ([`PassStats`]).
const STATS_PER_QUERY: u64 = 3;

/// Pipeline-statistics queries, one per pass: vertex shader invocations, primitives entering
/// the clipper and fragment shader invocations, in that order (wgpu writes a query's counters
/// in the order of their bits).
pub(crate) struct PassStats {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    capacity: u32,
}

impl PassStats {
    /// The queries, where the device has pipeline statistics.
    pub(crate) fn new(gpu: &Gpu) -> Option<PassStats> {
        if !gpu
            .features
            .contains(wgpu::Features::PIPELINE_STATISTICS_QUERY)
        {
            return None;
        }
        let capacity = 16;
        let size = u64::from(capacity) * 8 * STATS_PER_QUERY;
        let (resolve, read) = resolve_and_read(&gpu.device, "primitives", size);
        Some(PassStats {
            queries: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass primitives"),
                ty: wgpu::QueryType::PipelineStatistics(
                    wgpu::PipelineStatisticsTypes::VERTEX_SHADER_INVOCATIONS
                        | wgpu::PipelineStatisticsTypes::CLIPPER_INVOCATIONS
                        | wgpu::PipelineStatisticsTypes::FRAGMENT_SHADER_INVOCATIONS,
                ),
                count: capacity,
            }),
            resolve,
            read,
            capacity,
        })
    }

    /// Can it count a frame of `passes` passes?
    pub(crate) fn fits(&self, passes: usize) -> bool {
        passes <= self.capacity as usize
    }

    /// Count what the `k`-th pass that runs draws in `pass` (until [`PassStats::end`]).
    pub(crate) fn begin(&self, pass: &mut wgpu::RenderPass<'_>, k: usize) {
        pass.begin_pipeline_statistics_query(&self.queries, k as u32);
    }

    pub(crate) fn end(pass: &mut wgpu::RenderPass<'_>) {
        pass.end_pipeline_statistics_query();
    }

    /// Resolve the counts of `passes` passes and copy them for reading.
    pub(crate) fn resolve(&self, enc: &mut wgpu::CommandEncoder, passes: usize) {
        let n = passes as u32;
        enc.resolve_query_set(&self.queries, 0..n, &self.resolve, 0);
        let bytes = u64::from(n) * 8 * STATS_PER_QUERY;
        enc.copy_buffer_to_buffer(&self.resolve, 0, &self.read, 0, bytes);
    }

    /// The submitted frame's counters, per pass that ran: vertex shader invocations,
    /// primitives, fragment shader invocations.
    pub(crate) fn read(&self, gpu: &Gpu, passes: usize) -> Result<Vec<[u64; 3]>, GpuError> {
        let bytes = gpu.read_buffer(&self.read)?;
        let counts: &[u64] = bytemuck::cast_slice(&bytes);
        Ok((0..passes)
            .map(|k| std::array::from_fn(|c| counts[3 * k + c]))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_pass_gets_its_render_and_compute_time_and_its_offscreen_time() {
        // Two passes; the second had offscreen work, the first offscreen record (m = 0).
        // Ticks of 2 ns: pass 0 renders 10..40 (30) and computes 5..9 (4); pass 1 renders
        // 50..150 (100) and computes 150..150 (0); its offscreen work runs 1000..1600 (600).
        let mut ticks = vec![0u64; (OFFSCREEN_SLOTS + 2) as usize];
        ticks[0..4].copy_from_slice(&[10, 40, 5, 9]);
        ticks[4..8].copy_from_slice(&[50, 150, 150, 150]);
        let o = OFFSCREEN_SLOTS as usize;
        ticks[o..o + 2].copy_from_slice(&[1000, 1600]);
        let d = GpuTimer::durations(&ticks, 2.0, &[None, Some(0)]);
        assert_eq!(d.len(), 2);
        assert!((d[0].0 - 34.0 * 2e-6).abs() < 1e-15, "{d:?}");
        assert_eq!(d[0].1, None);
        assert!((d[1].0 - 100.0 * 2e-6).abs() < 1e-15, "{d:?}");
        assert!((d[1].1.unwrap() - 600.0 * 2e-6).abs() < 1e-15, "{d:?}");
        // A timestamp that went backwards (no defined order between queues) counts as 0.
        ticks[1] = 5;
        assert!((GpuTimer::durations(&ticks, 2.0, &[None])[0].0 - 4.0 * 2e-6).abs() < 1e-15);
    }

    #[test]
    fn offscreen_slots_follow_every_pass_slot() {
        // The last timed pass's slots end where the offscreen ones begin.
        assert_eq!(GpuTimer::slot(TIMED_PASSES as usize, 0), OFFSCREEN_SLOTS);
        assert!(GpuTimer::fits(16) && !GpuTimer::fits(17));
    }
}
